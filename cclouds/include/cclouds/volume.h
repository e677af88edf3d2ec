/*
 * cclouds/volume.h -- volume rendering of uint8 cloud volumes in a sky: the stand-in for SimVoleon, the Coin3D
 * extension the oc text displays its cloud arrays with (§1, §5.2.1), plus the two survey methods the text describes
 * without formulas, in kind: metaballs (oc-4.2) and textured ellipsoids (oc-4.3). pywarp/kernels/volume.py mirrors
 * every function operation by operation; the tests compare the two at sampled pixels.
 *
 * A scene is a sky, a flat ground, up to CCL_VOLUME_MAX_GRIDS cloud boxes and optionally the aircraft of
 * cclouds/flight.h. World units are metres, y up.
 *
 * A grid (ccl_volume_grid) is an nx x ny x nz uint8 array, index (z * ny + y) * nx + x ([z][y][x], NumPy's C order of
 * an array of shape (nz, ny, nx)); 0 = invisible ... 255 = opaque (oc-5.2.1), placed in an axis-aligned box from
 * origin to origin + extent: the per-axis extents are the scaling of oc-5.2.3-scale. The march works in VOXEL space
 * (v = (x - origin) * n / extent per axis, voxel centres at i + 0.5), so a stretched cloud keeps its optical depth
 * across (its matter is spread, not multiplied).
 *
 * One pixel (ccl_volume_pixel):
 *   d      = ccl_camera_ray(pixel); jitter j = ccl_hash_unit(ccl_hash_pcg(x + 65536 y)) when p->jitter, else 0.5
 *   t_hit  = the aircraft's distance along d (sphere tracing of ccl_flight_aircraft, <= CCL_VOLUME_AIRCRAFT_STEPS
 *            steps inside its bounding sphere), +inf if missed
 *   B      = background: the shaded aircraft at t_hit, else the ground where d.y < 0 (fogged), else the sky
 *   grids  = visited in the order of their entry distance along d (ties: lower index first); each one marched alone
 *            from max(t_enter, 0) to min(t_exit, t_hit) with step dt = step_voxels / |d_v| (d_v = d in voxel space),
 *            at most max_steps samples, sample k at t_enter + (k + j) dt; a sample in an empty brick of skip
 *            distance m >= 1 (ccl_volume_skip: every brick within m - 1 bricks of it is empty too) jumps to the first
 *            sample k' > k at or after the exit of that empty cube of (2 m - 1)^3 bricks -- the skipped samples are
 *            exactly 0, so the image is the one without skipping (a skip map of zeros), at a few jumps per empty
 *            stretch instead of one per brick or per voxel:
 *              rho   = trilinear density / 255;  skip when 0
 *              alpha = 1 - exp(-tau_per_voxel * rho * step_voxels)
 *              L     = sun_colour * T_sun * 4 pi HG(dot(d, sun), g) + mix(ambient_bottom, ambient_top, v.y / ny)
 *                      with T_sun the trilinear sample of the grid's precomputed light volume (ccl_volume_light)
 *              C    += T alpha L;  T *= 1 - alpha;  stop when T < exit_transmittance
 *            then aerial fog on the grid's part: f = exp(-max(t_enter, 0) / fog_distance);
 *            C_total += T_total (f C + (1 - f)(1 - T) sky_horizon),  T_total *= T
 *   colour = C_total + T_total B (display-linear; the image kernels clamp to [0, 1] and encode sRGB).
 * Boxes that overlap are composited one after the other (not interleaved): place clouds in separate boxes.
 * Simple sun lighting, documented: single scattering of the sun attenuated inside the cloud's own box only (no
 * cloud shadows on other clouds, the ground or the aircraft), a Henyey-Greenstein phase, a height-graded ambient
 * term standing in for the sky light; the ground and the aircraft are Lambertian.
 */
#ifndef CCLOUDS_VOLUME_H
#define CCLOUDS_VOLUME_H

#include "cclouds/camera.h"
#include "cclouds/common.h"

#ifdef __cplusplus
extern "C" {
#endif

#define CCL_VOLUME_MAX_GRIDS 16
/* The generated ground (ccl_volume_ground): 5 octaves (a field's edge down to 1/16 of it: 11 m at the defaults, the
 * pixel size at 2 km); a period of 256 lattice cells, so that u 2^(octaves - 1) <= 4096 (CCL_VALUENOISE_MAX_COORD);
 * the seed of its three noise fields (any: fixed, the ground is the same in every flight). */
#define CCL_VOLUME_GROUND_OCTAVES 5
#define CCL_VOLUME_GROUND_PERIOD 256
#define CCL_VOLUME_GROUND_SEED 7u
/* Largest colour component (and sun_glow) ccl_volume_check accepts: 10^6, far above display-linear use (<= a few),
 * low enough that colour x phase x glow stays finite (with FLT_MAX the aircraft's Inf x 0 was a NaN pixel). */
#define CCL_VOLUME_MAX_COLOUR 1000000
/* Box extents per axis must lie in [1 / R, R] metres, R = 10^6 (1 um .. 1000 km): the voxel scale n / extent and
 * the light ray's voxel-space direction stay finite and non-zero (a denormal extent made them Inf, a huge one
 * underflowed the direction's length to 0: NaN light). */
#define CCL_VOLUME_LENGTH_RANGE 1000000
/* Largest optical depth per voxel (tau_per_voxel, light_tau_per_voxel) and largest step in voxels (step_voxels,
 * light_step_voxels) ccl_volume_check accepts: 10^6 each, so the optical depth of a step, their product, stays
 * finite (with 1.6e32 x 8.4e6 it was Inf, and Inf x a density of 0 made the light volume NaN). A voxel of optical
 * depth 10^6 is opaque many times over; a step of 10^6 voxels is beyond any grid's diagonal. */
#define CCL_VOLUME_MAX_TAU 1000000
#define CCL_VOLUME_MAX_STEP 1000000
#define CCL_VOLUME_AIRCRAFT_STEPS 64
#define CCL_VOLUME_BRICK 2 /* edge of the empty-space-skipping bricks, voxels (2: measured faster than 4 on the
                                flight scene's soft clouds, whose 4^3 bricks are 40 % occupied) */

/* One cloud volume placed in the world (not owned). */
typedef struct ccl_volume_grid {
    const unsigned char *density; /* nx * ny * nz voxels [z][y][x]: 0 invisible ... 255 opaque */
    const float *light;           /* the same layout: transmittance towards the sun in [0, 1] (ccl_volume_light) */
    const unsigned char *skip;    /* bricks of CCL_VOLUME_BRICK^3 voxels, ceil(n / B) per axis (B = CCL_VOLUME_BRICK), [bz][by][bx]:
                                     ccl_volume_skip (0 = occupied; m >= 1: empty, and so is every brick within
                                     Chebyshev distance m - 1); all zeros = no skipping */
    int nx, ny, nz;               /* >= 1 */
    ccl_vec3 origin;              /* world position of the box's minimum corner [m] */
    ccl_vec3 extent;              /* world size of the box per axis [m], in [1e-6, 1e6] (CCL_VOLUME_LENGTH_RANGE) */
} ccl_volume_grid;

/* Everything else of a frame (defaults and reasons: ccl_volume_params_default, volume.c). */
typedef struct ccl_volume_params {
    ccl_vec3 sun;               /* unit vector towards the sun */
    ccl_vec3 sun_colour;        /* direct sunlight, display-linear */
    ccl_vec3 ambient_top;       /* ambient light at the top of a cloud box (and on the aircraft from above) */
    ccl_vec3 ambient_bottom;    /* ambient light at the bottom of a cloud box */
    ccl_vec3 sky_zenith;        /* sky colour straight up */
    ccl_vec3 sky_horizon;       /* sky colour at the horizon; also the colour of the aerial fog */
    ccl_vec3 ground_a;          /* the two colours the ground's albedo noise mixes (ccl_volume_ground) */
    ccl_vec3 ground_b;
    float sun_glow;             /* strength of the glow around the sun in the sky */
    float sun_glow_power;       /* its falloff: glow * max(dot(d, sun), 0)^power */
    float field_size;           /* edge of one lattice cell of the ground's value noise at its first octave [m] */
    float fog_distance;         /* e-folding distance of the aerial fog [m] */
    float tau_per_voxel;        /* optical depth of one voxel length at density 255, view rays */
    float light_tau_per_voxel;  /* the same towards the sun (ccl_volume_light) */
    float step_voxels;          /* view-ray step in voxel lengths */
    float light_step_voxels;    /* light-ray step in voxel lengths (ccl_volume_light) */
    float exit_transmittance;   /* early ray termination below this transmittance */
    int max_steps;              /* most samples per grid and ray */
    float g;                    /* Henyey-Greenstein asymmetry of the cloud phase function, (-1, 1) */
    int jitter;                 /* 1: per-pixel hashed start offset (no slicing artefacts); 0: midpoints */
    int aircraft;               /* 1: draw the aircraft of ccl_flight_aircraft */
    ccl_vec3 aircraft_position; /* its centre of gravity E [m] */
    ccl_vec3 aircraft_forward;  /* body axes (ccl_flight_axes), orthonormal */
    ccl_vec3 aircraft_right;
    ccl_vec3 aircraft_up;
    float aircraft_scale;       /* world metres per model metre, > 0 */
} ccl_volume_params;

/* The documented defaults (reasons in volume.c). */
CCL_API void ccl_volume_params_default(ccl_volume_params *out);

/* Validate parameters and grids (count in [0, CCL_VOLUME_MAX_GRIDS], sizes >= 1, extents in [1e-6, 1e6] m
 * (CCL_VOLUME_LENGTH_RANGE), non-NULL arrays, unit sun and axes, finite values, colour components and sun_glow in
 * [0, CCL_VOLUME_MAX_COLOUR], optical depths per voxel in [0, CCL_VOLUME_MAX_TAU], steps in
 * [0.05, CCL_VOLUME_MAX_STEP] voxels, max_steps in [1, 100000], g in (-1, 1)). Returns CCL_OK or CCL_EINVAL
 * with *out_field = the first bad field (static string; out_field may be NULL). */
CCL_API ccl_status ccl_volume_check(const ccl_volume_params *p, const ccl_volume_grid *grids, int count,
                                    const char **out_field);

/* Trilinear sample of a uint8 grid at a voxel-space position v (voxel centres at i + 0.5, indices clamped to the
 * grid), divided by 255: in [0, 1]. Any finite or infinite v is accepted (beyond the grid: the edge voxels); a NaN
 * component gives NaN. */
CCL_API float ccl_volume_sample(const unsigned char *density, int nx, int ny, int nz, ccl_vec3 v);

/* The same for a float grid (the light volume). */
CCL_API float ccl_volume_sample_float(const float *values, int nx, int ny, int nz, ccl_vec3 v);

/* Entry and exit of the ray eye + t dir through the grid's box (slab test in voxel space; t in world units along
 * dir, which need not be unit). Returns 1 and *out_t0 <= *out_t1 when the line meets the box with t1 > 0, else 0. */
CCL_API int ccl_volume_box(const ccl_volume_grid *grid, ccl_vec3 eye, ccl_vec3 dir, float *out_t0, float *out_t1);

/* Light volume of one grid: for every voxel centre, exp(-light_tau_per_voxel * sum rho * light_step_voxels) over
 * samples k = 1, 2, ... at (k) light_step_voxels towards the sun in voxel space until the box is left (the
 * precomputation the text proposes as a speed-up, §7: the lighting does not change while the sun and the cloud do
 * not). grid->light is ignored; out_light holds nx * ny * nz floats. Returns CCL_EINVAL for a bad grid or
 * parameters, CCL_OK otherwise. */
CCL_API ccl_status ccl_volume_light(const ccl_volume_params *p, const ccl_volume_grid *grid, float *out_light,
                                    size_t out_len);

/* Brick occupancy of a grid for empty-space skipping: brick (bx, by, bz) covers voxel-space positions
 * [B b, B b + B) per axis (B = CCL_VOLUME_BRICK); it is 1 when any voxel of indices B b - 1 .. B b + B (clamped to
 * the grid: every voxel a trilinear sample inside the brick can touch) is > 0, else 0.
 * out_len = ceil(nx/B) ceil(ny/B) ceil(nz/B).
 * grid->skip and grid->light are ignored. CCL_EINVAL for a bad grid or length. */
CCL_API ccl_status ccl_volume_occupancy(const ccl_volume_grid *grid, unsigned char *out, size_t out_len);

/* Skip distances of a grid for empty-space skipping (Ref: none; a rendering speed-up, the same pixels): from the
 * brick occupancy of ccl_volume_occupancy, out[b] = 0 for an occupied brick, else min(255, the Chebyshev distance in
 * bricks from b to the nearest occupied brick) (255 when no brick is occupied): every brick within distance
 * out[b] - 1 of b is empty, so a ray in b may jump to the exit of that cube. Computed by repeated 26-neighbour
 * dilation. out_len = ceil(nx/B) ceil(ny/B) ceil(nz/B); grid->skip and grid->light are ignored. CCL_EINVAL for a bad
 * grid or length. */
CCL_API ccl_status ccl_volume_skip(const ccl_volume_grid *grid, unsigned char *out, size_t out_len);

/* The sky colour in direction d (unit): sky_horizon + (sky_zenith - sky_horizon) sqrt(max(d.y, 0)) + sun_colour
 * sun_glow clamp(dot(d, sun), 0, 1)^sun_glow_power (clamped at 1: the dot of unit vectors may round above it).
 * Display-linear. */
CCL_API ccl_vec3 ccl_volume_sky(const ccl_volume_params *p, ccl_vec3 d);

/* Albedo of the generated ground at (gx, gz) [m], made with the text's own tools: 2-D value-noise octave sums
 * (ccl_valuenoise_fbm, CCL_VOLUME_GROUND_OCTAVES octaves, persistence 0.5, raw lattice, cosine interpolation) at
 * lattice coordinates u = (g / field_size + CCL_VOLUME_GROUND_PERIOD / 2) wrapped into [0, CCL_VOLUME_GROUND_PERIOD)
 * (the noise repeats every PERIOD field sizes, 46 km at the defaults: far in the fog). Three fields, octave seeds
 * CCL_VOLUME_GROUND_SEED + 0, 1, 2:
 *   meadows and fields  a = fbm(u), albedo = mix(ground_a, ground_b, clamp(2.5 (a - 0.5) + 0.5, 0, 1))
 *   forest              b = fbm(u), albedo = mix(albedo, 0.45 ground_a, clamp(12 (b - 0.56), 0, 1))
 *   a river             r = fbm(u / 4) (its slow octaves meander), albedo = mix(albedo, water,
 *                       clamp((0.012 - |r - 0.5|) / 0.004, 0, 1)): the level line r = 0.5, ~ a field wide;
 *                       water = (0.06, 0.09, 0.12), a dark blue-grey river seen from above.
 * Beyond the text (it shows no ground); the contrast 2.5, the forest threshold 0.56 (about a fifth of the land) and
 * ramp 12, and the river's half-width 0.012 and ramp 0.004 were chosen by eye from the air at 500 m.
 * Display-linear reflectances. */
CCL_API ccl_vec3 ccl_volume_ground(const ccl_volume_params *p, float gx, float gz);

/* The background of a ray without clouds: the aircraft (when hit), else the ground (d.y < 0 and eye.y > 0:
 * ccl_volume_ground at the hit, Lambertian under the sun and the sky: albedo (sun_colour max(sun.y, 0) +
 * ambient_top), fogged towards sky_horizon by exp(-t / fog_distance)), else ccl_volume_sky. *out_t: the distance of
 * the aircraft hit (the clouds are marched up to it) or +inf. Display-linear. */
CCL_API ccl_vec3 ccl_volume_background(const ccl_volume_params *p, ccl_vec3 eye, ccl_vec3 d, float *out_t);

/* The display-linear colour of pixel (x, y) of a width x height frame (see the top of this header). grids[count]
 * with their light volumes; inputs must have passed ccl_volume_check. out_rgb[3]. */
CCL_API void ccl_volume_pixel(const ccl_volume_params *p, const ccl_volume_grid *grids, int count,
                              const ccl_camera *cam, int x, int y, int width, int height, float *out_rgb);

/* Metaball field contribution of one source (Ref: oc-4.2: sources with a centre, a radius and a strength; the text
 * gives no field function: Wyvill's soft-object kernel is used, strength (1 - r^2/R^2)^3 for r < R, else 0).
 * distance r >= 0 from the source's centre, radius R > 0 (any, infinite included), strength any finite; returns the
 * contribution, between 0 and strength (0 for r >= R; NaN for a NaN r). A cloud base is the sum over the sources,
 * thresholded. */
CCL_API float ccl_volume_metaball(float distance, float radius, float strength);

/* Opacity of a textured ellipsoid (Ref: oc-4.3, Gardner 1985's translucency; the text gives no formulas). p: the
 * point relative to the ellipsoid's centre [m]; radii > 0 its semi-axes; texture in [0, 1] the texturing function
 * at p (Perlin/value-noise fBm standing in for Gardner's sum of sines, as the text suggests); threshold t1 and ramp
 * d > 0: with q = |p / radii|^2 and g = 1 - q (1 at the centre, 0 on the surface), opacity =
 * clamp((texture - t1 - d (1 - g)) / d, 0, 1): the texture decides the inside, and the edge is eaten away towards
 * the surface. Returns the opacity in [0, 1]. */
CCL_API float ccl_volume_ellipsoid(ccl_vec3 p, ccl_vec3 radii, float texture, float threshold, float ramp);

#ifdef __cplusplus
}
#endif

#endif /* CCLOUDS_VOLUME_H */
