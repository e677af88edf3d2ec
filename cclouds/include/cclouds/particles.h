/*
 * cclouds/particles.h -- the rain particle system and the per-pixel drop/streak compositing of the rr text
 * (Rejdova 2009 after Rousseau, Jolivet & Ghazanfarpour 2006): drops spawned in a box around the camera, falling at
 * their terminal speed (rr-code-5.2.2), retinal-persistence streaks (rr-alg-3.2.3), the wide-angle scene capture's
 * projection (rr-alg-3.1.2) and the refraction fragment shaders (rr-code-5.2.3, rr-code-5.2.4).
 *
 * Conventions:
 *   - Scene units: metres_per_unit metres (default 1). Particle positions are relative to the camera position
 *     (translation only: world axes, y up), so the rain surrounds the viewer wherever it goes (rr-code-5.2.2 does not
 *     say whether its box is world- or camera-fixed; spec erratum 17).
 *   - Randomness: the PCG hash of hash.h, keyed by (seed, particle index, generation, draw): a particle's state
 *     depends on nothing else, so the system is deterministic per seed whatever the thread count.
 *   - Images: row-major float32 RGB, (y, x) with y = 0 the top row; the mask is float32 RGBA (x, y, z refraction
 *     vector, a inside flag), mask row 0 the TOP of the drop; the capture is RGB.
 *   - Pixel coordinates are continuous: pixel (x, y) covers [x, x + 1) x [y, y + 1), its centre is (x + 0.5, y + 0.5).
 */
#ifndef CCLOUDS_PARTICLES_H
#define CCLOUDS_PARTICLES_H

#include "cclouds/common.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Upper bound of the uniform draws averaged by the Gaussian size of ccl_particles_gauss (the loop bound). */
#define CCL_PARTICLES_MAX_SIZE_SAMPLES 64
/* Taps of the retinal-persistence shader rr-code-5.2.4 (i = -3 .. 3). */
#define CCL_PARTICLES_STREAK_TAPS 7
/* Colour samples of a physical streak pixel: the drop's mask column across the chord the pixel sees (8: the chord of a
 * streak is at most the drop's diameter, ~13 px at the nearest drops, so the samples are <= 2 px apart there and the
 * mean colour of the column changes by a few percent from 8 to 64 samples; the positions are fixed in the drop, so
 * they leave no pattern along the streak). */
#define CCL_PARTICLES_STREAK_SAMPLES 8
/* Shortest physical streak [pixels] (1/64): a drop that moves less during the exposure is drawn as a streak this long
 * (its coverage integral divides by the length; a still drop is then the drop itself, antialiased). */
#define CCL_PARTICLES_MIN_STREAK_PX 0.015625f
/* Largest particle count of one system (the loop bound of ccl_particles_simulate and the shaders). */
#define CCL_PARTICLES_MAX_COUNT 1000000
/* Narrowest capture FOV [rad] (1/64: about 0.9 deg): below it tan(fov_capture/2) underflows towards 0 and the capture
 * coordinates overflow (NaN at the view's centre, 0 x Inf). */
#define CCL_PARTICLES_MIN_FOV_CAPTURE 0.015625f
/* Largest |coordinate| of the spawn box and the respawn level [scene units] (2^20): box widths (max - min, up to
 * 2^21) and the positions spawned and stepped in the box stay finite (a box of +-3e38 made max - min Inf, NaN
 * particles). */
#define CCL_PARTICLES_MAX_EXTENT 1048576.0f
/* Smallest scene unit [m] (1/1024, about a millimetre): the fall speed v_t / metres_per_unit stays below ~6e5 units/s
 * (v_t <= ~600 m/s at slowdown 1/64), so a step of dt <= 1 s stays finite (1e-45 made the speed Inf, y NaN). */
#define CCL_PARTICLES_MIN_METRES_PER_UNIT 0.0009765625f

/* What the compositing pass draws for a sprite (its `streaks` argument). DROPS: rr-code-5.2.3, the drop's refraction.
 * STREAKS_THESIS: rr-code-5.2.4 as the text has it, 7 mask taps stretched over a rectangle. STREAKS_PHYSICAL: the
 * drop's disc integrated over the exposure (ccl_particles_streak_cover): thin, tapered, faint. */
typedef enum ccl_particles_streaks {
    CCL_PARTICLES_DROPS = 0,
    CCL_PARTICLES_STREAKS_THESIS = 1,
    CCL_PARTICLES_STREAKS_PHYSICAL = 2
} ccl_particles_streaks;

/* Capture filtering (rr-alg-3.1.2 says nearest suffices; rr-code-5.2.1-c sets GL_LINEAR). */
typedef enum ccl_particles_filter {
    CCL_PARTICLES_NEAREST = 0,
    CCL_PARTICLES_LINEAR = 1
} ccl_particles_filter;

/* Parameters of the particle system (rr-code-5.2.2). Defaults: ccl_particles_params_default. */
typedef struct {
    ccl_vec3 box_min;        /* spawn box, camera-relative scene units: (-1, 1, -1.5) */
    ccl_vec3 box_max;        /* (1, 1.25, 1.5) */
    float respawn_y;         /* a particle below this y is regenerated: -1 (< box_min.y) */
    float size_mean_mm;      /* Gauss(1, 1.3, 8): mean radius 1.3 mm */
    float size_spread_mm;    /* Gauss(1, 1.3, 8): the 1 -- width of the averaged uniforms, radius in mean +- spread/2 */
    int size_samples;        /* Gauss(1, 1.3, 8): the 8 -- uniforms averaged, [1, CCL_PARTICLES_MAX_SIZE_SAMPLES] */
    float slowdown;          /* speeds divided by this: 4 */
    float metres_per_unit;   /* scene unit in metres: 1 */
    ccl_vec3 wind;           /* horizontal drift (x, z used; y must be 0) in scene units per second: 0 */
    uint32_t seed;           /* seed of every draw */
} ccl_particles_params;

/* The text's parameters (rr-code-5.2.2; see the header comment of each field). */
CCL_API void ccl_particles_params_default(ccl_particles_params *out);

/* Check the parameters: box_min < box_max per axis, respawn_y < box_min.y, size_mean_mm - size_spread_mm / 2 >= 0.1
 * and size_mean_mm + size_spread_mm / 2 <= 4.5 (the radii of Tables 2.1/2.2), size_spread_mm >= 0, size_samples in
 * [1, 64], slowdown in [1/64, 1000] (the domain of ccl_rain_terminal_speed), metres_per_unit >=
 * CCL_PARTICLES_MIN_METRES_PER_UNIT, |box_min|, |box_max| per component and -respawn_y <= CCL_PARTICLES_MAX_EXTENT,
 * wind.y == 0, every value finite. Returns CCL_EINVAL and the name of the
 * first bad field in *field (may be NULL), else CCL_OK. */
CCL_API ccl_status ccl_particles_params_check(const ccl_particles_params *p, const char **field);

/* Uniform draw k of particle `index` in its `generation`: ccl_hash_unit(ccl_hash_pcg(key + k)) with
 * key = ccl_hash_pcg(ccl_hash_pcg(ccl_hash_pcg(seed) ^ index) ^ generation). Ref: rr-code-5.2.2
 * (RandomFromInterval). Output in [0, 1). */
CCL_API float ccl_particles_uniform(uint32_t seed, uint32_t index, uint32_t generation, uint32_t k);

/* The particle size Gauss(1, 1.3, 8) of rr-code-5.2.2, in our reading Gauss(spread, mean, samples): the mean of
 * `samples` uniform draws (draws 3 .. 3 + samples - 1 of the particle) on [mean - spread/2, mean + spread/2]
 * (Irwin-Hall: bell-shaped, bounded, standard deviation spread / sqrt(12 samples) = 0.102 mm for (1, 1.3, 8)).
 * Radius in mm. Domain: samples in [1, CCL_PARTICLES_MAX_SIZE_SAMPLES]; output in [mean - spread/2, mean + spread/2). */
CCL_API float ccl_particles_gauss(uint32_t seed, uint32_t index, uint32_t generation, float mean, float spread,
                                  int samples);

/* GenerateNewParticle (rr-code-5.2.2, its stray brace and argument fixed): position uniform in the box (draws 0, 1,
 * 2 for x, y, z) -- with warm != 0, y uniform in [respawn_y, box_max.y] instead (a system that has been falling for
 * a while; ours, not the text's) --, radius from ccl_particles_gauss, speed = v_t(radius) / slowdown /
 * metres_per_unit (scene units per second) with v_t the terminal speed of Table 2.2 (ccl_rain_terminal_speed).
 * p must pass ccl_particles_params_check. */
CCL_API void ccl_particles_spawn(const ccl_particles_params *p, uint32_t index, uint32_t generation, int warm,
                                 ccl_vec3 *out_pos, float *out_radius_mm, float *out_speed);

/* One frame of one particle (the loop body of SimulateParticleSystem, rr-code-5.2.2), in the printed order: if
 * pos.y < respawn_y the particle is regenerated (generation + 1, not warm); then pos.y -= dt speed (frame-rate
 * independent: dt is the frame time in seconds); the wind moves x and z by dt wind, wrapped into the box (periodic).
 * dt in [0, 1] s with |wind.x| dt <= box width x and |wind.z| dt <= box width z. In/out: pos, radius, speed,
 * generation. */
CCL_API void ccl_particles_step(const ccl_particles_params *p, uint32_t index, float dt, ccl_vec3 *pos,
                                float *radius_mm, float *speed, uint32_t *generation);

/* SimulateParticleSystem (rr-code-5.2.2) for `frames` frames of dt seconds on a system of *count particles (arrays of
 * `capacity` entries; *count is the state, in and out). Each frame: while corrected (variant CCL_VARIANT_CORRECTED),
 * a system above `requested` loses its highest-index particles (the text has no removal) and one below it gains one
 * particle (index *count, generation 0, not warm) and *count += 1; with CCL_VARIANT_THESIS the printed decrement
 * *count -= 1 runs instead (the new particle is never counted: no particle is ever simulated -- pinned by the tests);
 * then every particle i < *count takes ccl_particles_step. With warm != 0 and *count == 0 on entry (corrected only),
 * the system starts full: `requested` particles spawned warm.
 * Domain: requested in [0, capacity], capacity in [0, CCL_PARTICLES_MAX_COUNT], frames >= 0, dt as in
 * ccl_particles_step, *count in [min(-frames... , 0) .. capacity]. Returns CCL_EINVAL for bad parameters. */
CCL_API ccl_status ccl_particles_simulate(const ccl_particles_params *p, int requested, float dt, int frames, int warm,
                                          ccl_variant variant, int capacity, ccl_vec3 *pos, float *radius_mm,
                                          float *speed, uint32_t *generation, int *count);

/* Retinal persistence -> streak geometry. Ref: rr-alg-3.2.3, rr-code-5.2.4 (texelOffset). speed: fall speed (scene
 * units per second, >= 0); persistence_s: fade time of the retinal image (s; the text: 60 - 90 ms); radius: the
 * drop's billboard radius (scene units, > 0). The particle is reshaped into a vertical streak billboard 2 radius wide
 * and 2 radius + L tall, the mask stretched over it (the listing's gl_TexCoord[1] spans the quad). Returns the streak
 * length L = speed persistence_s (the fall while the retinal image fades) and *out_tap_offset = (L / 6) /
 * (2 radius + L): the fall between two of the 7 taps in units of the streak's height (mask units), so that taps
 * -3 .. 3 span the fall. Output: L >= 0, tap offset in [0, 1/6). */
CCL_API float ccl_particles_streak(float speed, float persistence_s, float radius, float *out_tap_offset);

/* The capture lookup P_o (rr-alg-3.1.2, rr-alg-3.1.3): the texture coordinate in the wide-angle capture of the
 * direction seen through a point of the view image. The capture camera sits at the viewer's position with its
 * orientation, vertical FOV fov_capture and a square image; the view camera has vertical FOV fov_view and aspect
 * `aspect` (width / height). ndc = the point's normalised device coordinates in the view, (-1, -1) bottom-left.
 * Returns (u, v) in capture texture units, v = 0 the TOP row: u = 0.5 + 0.5 ndc.x aspect tan(fov_view/2) /
 * tan(fov_capture/2), v = 0.5 - 0.5 ndc.y tan(fov_view/2) / tan(fov_capture/2). fov_view in (0, pi) rad,
 * fov_capture in [CCL_PARTICLES_MIN_FOV_CAPTURE, pi) rad, aspect > 0. */
CCL_API ccl_vec2 ccl_particles_capture_uv(ccl_vec2 ndc, float aspect, float fov_view, float fov_capture);

/* A drop or streak on screen (what the vertex stage of rr-code-5.2.3/5.2.4 produces), in view pixels. */
typedef struct {
    float cx, cy;        /* centre of the billboard (pixels, continuous; y down) */
    float radius;        /* half width = the drop's radius on screen (pixels, > 0) */
    float half_height;   /* half height: radius for a drop, radius + L/2 for a streak (pixels) */
    float tap_offset;    /* streak tap step in mask units (ccl_particles_streak); 0 for drops */
    float depth;         /* distance along the view axis (sorting: far first) */
} ccl_particles_sprite;

/* The refraction colour of one drop tap (rr-code-5.2.3's body, its defects fixed): mask texel (nearest) at
 * (mask_u, mask_v) in [0, 1) (outside: no drop); if inside (a > 0) and the ray exists (z > 0, x / z and y / z
 * not NaN: a texel with a NaN exit direction has no ray), P_c = P_o + scale
 * (x, y) / z with scale = 0.5 / tan(fov_capture/2) (so that a drop in the centre of the view samples its refracted
 * direction exactly; the mask's y points up, capture v down), the capture fetched at P_c (nearest or bilinear,
 * clamped to the edge: any finite or infinite P_c beyond the capture reads its edge texels; a NaN P_c gives NaN
 * rgb). Returns 1 and writes rgb when the tap hits, else 0. */
CCL_API int ccl_particles_tap(const float *mask, int mask_size, const float *capture, int capture_size,
                              float mask_u, float mask_v, ccl_vec2 p_o, float scale, int filter, ccl_vec3 *out_rgb);

/* The exposure of pixel (px, py) (its centre; the pixel is the unit square around it) to the physical streak of a
 * sprite: the drop's disc of radius `radius` px falls during the exposure T from its centre at cy + L/2 - L
 * (L = 2 (half_height - radius), at least CCL_PARTICLES_MIN_STREAK_PX) to cy + L/2, the head. Model (Garg & Nayar,
 * "Detection and removal of rain from videos", CVPR 2004: a pixel records the time average of what it sees during
 * the exposure; a drop covers a pixel for tau < 1.2 ms of a 1/30 s frame, so a streak's opacity is about tau / T =
 * D / L): alpha = (1/T) int w(t) cov(t) dt, cov = the share of the pixel the disc covers, w(t) = 1 - cos(2 pi t/T)
 * (mean 1, so the total exposure of the model is kept: the alphas of a streak sum to pi radius^2) -- the retinal
 * image building up and fading within the persistence time, so both ends taper smoothly instead of the hard cut of a
 * box exposure. Integrated in closed form: the pixel's width against the disc's chord (exact), its height against
 * the motion (exact for the chord's mean half-length *out_half_chord over the pixel's columns). Returns alpha in
 * [0, 1] (0 outside the streak) and *out_mask_u, the mask column of the pixel's share of the disc. */
CCL_API float ccl_particles_streak_cover(const ccl_particles_sprite *sprite, float px, float py, float *out_mask_u,
                                         float *out_half_chord);

/* One pixel of the rain frame: the background colour bg, then every sprite (in the array's order: far first) that
 * covers the pixel centre (x + 0.5, y + 0.5) composited over it. Billboard -> mask coordinates: mask u = dx /
 * (2 radius) + 1/2, v = dy / (2 half_height) + 1/2 (the mask stretched over a streak's quad). Ref: rr-code-5.2.3 (drops: one tap, alpha =
 * opacity), rr-code-5.2.4 (streaks = CCL_PARTICLES_STREAKS_THESIS: 7 taps i = -3 .. 3 at mask v shifted by i
 * tap_offset, colour = the mean of the taps that hit, alpha = opacity * hits / 7 -- the share of the persistence time
 * the drop covers the pixel: the text's "reduced alpha", amount not given). streaks = CCL_PARTICLES_STREAKS_PHYSICAL:
 * alpha = opacity * ccl_particles_streak_cover (every pixel the disc's streak touches, not only those whose centre
 * lies in the box), colour = the mean of CCL_PARTICLES_STREAK_SAMPLES taps down the mask column it returns, evenly
 * across the chord (mask v = 1/2 + dy / (2 radius), dy in (-half chord, half chord)); a pixel whose samples all miss
 * keeps its colour. p_o: the pixel's capture coordinate (ccl_particles_capture_uv); scale as in ccl_particles_tap.
 * n in [0, CCL_PARTICLES_MAX_COUNT]. */
CCL_API ccl_vec3 ccl_particles_shade_pixel(const ccl_particles_sprite *sprites, int n, const float *mask,
                                           int mask_size, const float *capture, int capture_size, int x, int y,
                                           ccl_vec2 p_o, float scale, int filter, int streaks, float opacity,
                                           ccl_vec3 bg);

/* Point lights of the light-drop model (rr-A1, rr-A2, rr-A3, rr-CF; described by the text, never implemented in it)
 * as the compositing pass applies it to every refraction tap. Positions are camera-relative scene units (world axes,
 * y up, the eye at the origin -- the frame of the particles); a light of colour (0, 0, 0) is off. The mask normals
 * (mask frame: x right, y up, z away from the viewer) are turned into this frame by the view basis right, up,
 * forward. Defaults (the scene's): lights off, ambient (1, 1, 1), r_half 1 unit, variant corrected. */
typedef struct {
    ccl_vec3 l1, c_l1;       /* light 1: position, colour C_L (RGB >= 0) */
    ccl_vec3 l2, c_l2;       /* light 2 */
    ccl_vec3 ambient;        /* C_amb of rr-CF (RGB >= 0) */
    float r_half;            /* DistFact = 1 / (1 + (d / r_half)^2): half-intensity distance (scene units, > 0) */
    ccl_variant variant;     /* rr-A1: CORRECTED clamps V_PE . V_N at 0, THESIS as printed */
    ccl_vec3 right, up, forward; /* view basis (unit, scene frame): mask normal (x, y, z) -> x right + y up + z forward */
} ccl_particles_lights;
/* ccl_particles_shade_pixel with the light-drop model: every tap that hits (rr-code-5.2.3/5.2.4) has its refracted
 * colour C_O replaced by C_F = ccl_rain_light_colour(C_O, ambient, p, n, eye = (0, 0, 0), l1, c_l1, l2, c_l2, r_half,
 * variant) before the averaging and compositing, with p = positions[j] (the drop's centre; at scene scale the drop is
 * a point next to lights metres away -- also for a streak's earlier taps) and n = the entry normal of the tap's mask
 * texel (`normals`: mask_size^2 x 3 floats, the mask frame, as ccl_rain_mask writes them) in the scene frame.
 * Ref: rr-CF, rr-A1, rr-A2, rr-A3, rr-code-5.2.3, rr-code-5.2.4. lights = NULL (or positions or normals NULL):
 * exactly ccl_particles_shade_pixel.
 * Other parameters as ccl_particles_shade_pixel; positions: n entries parallel to sprites. */
CCL_API ccl_vec3 ccl_particles_shade_pixel_lit(const ccl_particles_sprite *sprites, const ccl_vec3 *positions, int n,
                                               const float *mask, const float *normals, int mask_size,
                                               const float *capture, int capture_size, int x, int y, ccl_vec2 p_o,
                                               float scale, int filter, int streaks, float opacity,
                                               const ccl_particles_lights *lights, ccl_vec3 bg);
/* The whole rain frame: every pixel of the width x height background (RGB floats, rows from the top) shaded by
 * ccl_particles_shade_pixel with P_o = ccl_particles_capture_uv of its centre's NDC (aspect width/height) and
 * scale = 0.5 / tan(fov_capture/2). Ref: rr-code-5.2.3, rr-code-5.2.4 (the C reference of the Warp kernel, which
 * tests only the sprites of each pixel's screen tile). sprites: n sprites, far first; mask: mask_size^2 x 4 floats;
 * capture: capture_size^2 x 3 floats; opacity in [0, 1]; out: width x height x 3 floats (may not alias the inputs).
 * Returns CCL_EINVAL (nothing written) for a bad size, fov (fov_view in (0, pi), fov_capture in
 * [CCL_PARTICLES_MIN_FOV_CAPTURE, pi)), filter, streaks (a ccl_particles_streaks), opacity or a sprite with
 * radius <= 0 or half_height < radius. */
CCL_API ccl_status ccl_particles_composite(const float *background, int width, int height,
                                           const ccl_particles_sprite *sprites, int n, const float *mask,
                                           int mask_size, const float *capture, int capture_size, float fov_view,
                                           float fov_capture, int filter, int streaks, float opacity, float *out);

#ifdef __cplusplus
}
#endif

#endif /* CCLOUDS_PARTICLES_H */
