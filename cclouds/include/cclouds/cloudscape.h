/*
 * cclouds/cloudscape.h -- the scalar C reference of the whole cloudscape pixel (vc chapter 4): sky background,
 * cloud-layer raymarch with cone light sampling, compositing and sRGB encoding. pywarp/kernels/cloudscape.py mirrors
 * it operation by operation; the tests compare the two at sampled pixels.
 *
 * One pixel (vc-A25 -> A14/A24 -> A18 -> A17 -> A19/A20/2.31 -> A21 -> 4.8):
 *   d      = camera ray through the pixel centre (ccl_camera_ray), optionally tilted by the ray jitter (vc-A23)
 *   B      = ground_colour if the ray hits the Earth sphere ahead, else the sky colour of d (gradient or Preetham,
 *            display-linear: the Preetham sky is already tone mapped). The thesis draws no ground (the Earth sphere
 *            only stops the clouds below the horizon); a flat ground colour keeps the view from above readable.
 *   [t0,t1]= the part of the ray inside the cloud layer (ccl_raymarch_layer_segment: camera below, inside or above
 *            the layer)
 *   n      = ccl_raymarch_view_sample_count(d.y, samples_min, samples_max) when adaptive_samples, else samples_max
 *   for i < n: p = ccl_raymarch_point(eye, d, t0, dt, i, offset);  rho = density(p) (vc-A17)
 *       if rho > 0: d_light = sigma_light * sum_j w_j density(q_j)  over the 6 cone samples q_j (vc-A19),
 *                   w_j = light_step (near samples) and (far_factor - 1) * 5 light_step (the far one);
 *                   a = absorption_base + absorption_precip * precipitation;
 *                   L = sun_colour * E(d_light, a, dot(d, to_sun), g) + ambient(h)   (vc-2.31, vc-A20;
 *                       the beer / powder flags replace a term of E by 1, to show what each contributes)
 *                   ccl_raymarch_accumulate(colour, T, sigma, rho, dt, L, exit_eps)     (vc-A21)
 *                   stop when early_exit and the accumulation says so (then, with exit_fill, C += T L, T = 0)
 *            -- this loop is ccl_cloudscape_march_textbook (march = CCL_CLOUDSCAPE_MARCH_TEXTBOOK); the default
 *            march (CCL_CLOUDSCAPE_MARCH_FAST) computes it with refinement, grouping, light interpolation and
 *            level of detail (see ccl_cloudscape_march)
 *   C_f    = B (1 - O_D) + C_clouds with O_D = 1 - T (vc-4.8), then sRGB encoding.
 * density(p) (vc-A17): h = relative height (vc-A15); weather map at (p.x, p.z) + wind -> coverage D_h (R),
 *   precipitation (G), cloud type (B); D_v = height gradient (vc-4.7, A16); base texture at p -> B (vc-2.28);
 *   B_D = coverage(B, D_v, D_h, C) (vc-2.29) with C = 1 - D_h or D_h (coverage_threshold); curl texture at (p.x,
 *   p.z) displaces the detail lookup;
 *   density = detail erosion (vc-2.30) with the detail texture. Densities are clamped at 0 (required here: a
 *   negative extinction would amplify light). The early outs (h outside [0, 1], D_h = 0, D_v <= 0, B_D <= 0) return
 *   exactly what the full pipeline returns for those inputs; they only skip texture fetches.
 *
 *
 * Lighting (p->lighting; not in the thesis, which gives no light colours, vc-A36):
 *   CCL_LIGHTING_THESIS: sun_colour, ambient_bottom / _top are the constants of ccl_cloudscape_params_default and B is
 *     ground_colour on the Earth -- the thesis's images with one octave (ms_octaves 1), one HG lobe (silver_weight 0)
 *     and the sky lighting's further terms off (ms_depth, ms_view, ms_slab, ambient_aniso, ambient_ground_weight,
 *     mie_delta 0; the defaults turn them on), which the caller sets (pywarp: THESIS_LIGHTING).
 *   CCL_LIGHTING_SKY (default): ccl_cloudscape_light, called once per frame (per settings change) before the pixels,
 *     replaces the constants by values of the sky model (gradient or Preetham, whichever the scene uses):
 *       sun_colour     = sun_intensity * ccl_sky_sun_attenuation(theta_s, turbidity)  (Preetham et al. 1999 A.1:
 *                        Rayleigh and aerosol extinction along the air mass towards the sun: white at noon, orange
 *                        at sunset); with the sky CCL_SKY_PREETHAM_RADIANCE (physical units) k x
 *                        CCL_CLOUDSCAPE_SUN_KLX_X10 / 10 instead of sun_intensity, k = the sky's exposure;
 *       ambient_top    = the mean sky radiance over the upper hemisphere (solid-angle weighted; with
 *                        ambient_ground_weight w > 0 blended with the lit ground's radiance), ambient_bottom =
 *                        ambient_bottom_ratio x ambient_top, ambient_ground = the cosine-weighted mean (E_sky / pi),
 *                        by the midpoint rule on CCL_CLOUDSCAPE_SKY_THETA_CELLS x _PHI_CELLS cells of equal
 *                        (zenith angle, azimuth) size, each weighted by sin(theta) (x cos(theta)), normalised by the
 *                        quadrature's own weight sum (a constant sky gives exactly its value); sky values are the
 *                        display-linear colours the background shows (Preetham: tone mapped, or k C_HDR in physical
 *                        units), negative ones as 0.
 *     and the pixel changes in three places:
 *       ground   G = ground_albedo (sun_colour max(n . s, 0) T_shadow / pi + ambient_ground) at the point P where the
 *                  ray meets the Earth (n its normal, s towards the sun): Lambertian, lit by the sun through the
 *                  clouds and by the sky; T_shadow = exp(-sigma_light sum_k rho(q_k) dt) over
 *                  CCL_CLOUDSCAPE_GROUND_SHADOW_SAMPLES midpoints q_k of the ray from P towards the sun through the
 *                  layer (between the far roots of the inner and outer spheres), rho the base-shape density (no
 *                  detail: the shadow is soft at the ground anyway; at the footprint dt's mip level with p->lod):
 *                  the clouds cast their shadows on the ground (ccl_cloudscape_ground);
 *       haze     H = the sky model's colour in the ray's direction lifted to the horizon, (d.x, max(d.y, 0), d.z)
 *                  normalised ((0, 0, -1) for the nadir itself): the colour of the air towards the horizon in that
 *                  azimuth, where the sky is the in-scattered light of a long path through the air;
 *       aerial perspective (aerial_km > 0): with f(t) = exp(-t_air(t) / aerial_km) (a fog of extinction
 *                  1 / aerial_km at the ground, in-scattering H): B = G f(t_ground) + H (1 - f(t_ground)) on the
 *                  Earth, B = H in the sky; the clouds C_clouds f(t_c) + H O_D (1 - f(t_c)) with t_c the
 *                  transmittance-weighted mean distance of the view samples, sum_i (T_i-1 - T_i) t_i /
 *                  sum_i (T_i-1 - T_i). t_air(t) is the length of ground-level air with the optical depth of the
 *                  path, the fog's density falling as exp(-y / aerial_height_km) with the altitude y (flat-Earth
 *                  heights y = y_eye + u s along the ray, u = the ray's vertical component at the camera):
 *                    t_air = H / u (exp(-y_eye / H) - exp(-(y_eye + u t) / H)), at most t (the air is nowhere
 *                  denser than at the ground; t exp(-y_eye / H) (1 - x / 2) for |x| = |u t / H| < 1e-3);
 *                  aerial_height_km = 0: t_air = t, the homogeneous fog C exp(-t / aerial_km) + H (1 - exp(..)).
 *       horizon  anti-aliased: B = H + (B_ground - H) c with c the pixel's coverage by the Earth, clamp(0.5 - a /
 *                  pixel_angle, 0, 1), a = asin(d . up) + acos(r_earth / |eye - centre|) the ray's elevation above
 *                  the horizon (a box filter one pixel high); a ray above the Earth with c > 0 takes the ground at
 *                  the horizon's distance sqrt(|eye - centre|^2 - r_earth^2).
 *   In both modes the sun energy E of each sample is ccl_cloudscape_energy: the multiple-scattering octaves of
 *   Wrenninge et al. 2013 (as Hillaire 2016, "Physically based sky, atmosphere and cloud rendering in Frostbite"),
 *   E = sum_{i < ms_octaves} ms_b^i E_2.31(ms_a^i d, a, cos_theta, phase with eccentricities x ms_c^i), with the
 *   dual-lobe phase (1 - w) HG(g) + w HG(silver_g) (w = silver_weight); ms_octaves = 1 and w = 0 is vc-2.31 exactly.
 *
 * Textures are float32 RGBA, power-of-two sizes, indexed [z][y][x][c] (3-D) or [y][x][c] (2-D) and sampled with
 * wrap-around (they tile): base and detail with ccl_texgen_sample_trilinear_wrap, weather and curl with
 * ccl_cloudscape_sample_bilinear_wrap. World units are kilometres, y is up (see cclouds/raymarch.h).
 */
#ifndef CCLOUDS_CLOUDSCAPE_H
#define CCLOUDS_CLOUDSCAPE_H

#include "cclouds/camera.h"
#include "cclouds/common.h"
#include "cclouds/raymarch.h"
#include "cclouds/sky.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Limits of ccl_cloudscape_check. Every texture coordinate the density computes, in texels ((world position within
 * the outer sphere + wind offset + curl displacement) / scale * size, per axis), must stay below
 * CCL_CLOUDSCAPE_MAX_TEXCOORD = 2^23, where float32 keeps no fraction to interpolate with (the samplers return NaN
 * from there on). The curl texture's vectors are assumed to be at most CCL_CLOUDSCAPE_MAX_CURL long (the generated
 * texture's are below 2.5 lattice units, vc-A11). */
#define CCL_CLOUDSCAPE_MAX_TEXCOORD 8388608
#define CCL_CLOUDSCAPE_MAX_CURL 16
/* Largest distance of the far light sample, light_far_factor x 5 x light_step_km, that ccl_cloudscape_check accepts
 * (km): its weight times a density, six of them summed and times sigma_light, and the cone's radius there stay
 * finite (each factor alone can be finite while their product overflows: inf x 0 = NaN). The layer is a few km
 * thick; 10^6 km is far beyond any useful value. */
#define CCL_CLOUDSCAPE_MAX_LIGHT_KM 1.0e6
/* Largest light_far_factor that ccl_cloudscape_check accepts: the far sample's weight is
 * (light_far_factor - 1) x 5 x light_step_km, and its first product overflowed to inf for a factor near FLT_MAX
 * while the whole product stayed small (a step of 1e-39 km: inf x a density of 0 = a NaN pixel, found by fuzzing).
 * The thesis's factor is 3; 10^6 is far beyond any useful value. */
#define CCL_CLOUDSCAPE_MAX_LIGHT_FAR_FACTOR 1.0e6f
/* Largest exposure of a Preetham sky of the thesis variant that ccl_cloudscape_check accepts. The printed tone map
 * 1 - exp(+k C) (vc-4.5) grows without bound in k C: at exposure 5 the default sky reached -inf and the composite
 * made NaN pixels of it (-inf x 0, inf - inf). The brightest HDR channel of the model is below 140 (every
 * direction, T in [2, 10], the sun above the horizon), so at k <= 0.25 the sky stays above -e^35 (~ -1.6e15),
 * finite through every sum and product of the render. The thesis's own k is 0.03; the variant's sky is <= 0
 * (black on screen) at every k anyway. */
#define CCL_CLOUDSCAPE_MAX_THESIS_EXPOSURE 0.25f

/* The four textures of the cloudscape (not owned). */
typedef struct ccl_cloud_textures {
    const float *base;     /* base_size^3 RGBA: R Perlin-Worley, G B A inverse-Worley fBm (vc-A9) */
    int base_size;
    const float *detail;   /* detail_size^3 RGBA: RGB inverse-Worley fBm (vc-A10), A unused */
    int detail_size;
    const float *curl;     /* curl_size^2 RGBA: RG = 2-D curl-noise vector (vc-A11), BA unused */
    int curl_size;
    const float *weather;  /* weather_size^2 RGBA: R coverage, G precipitation, B cloud type (vc-A12) */
    int weather_size;
    /* Optional mip chains for the level of detail (params.lod): levels 1 .. log2(size) of base / detail, each level
     * right after the previous one, texel [z][y][x] of the (size >> k)^3 level k, built by ccl_cloudscape_mip3.
     * NULL: level 0 only (no level of detail). */
    const float *base_mips;
    const float *detail_mips;
} ccl_cloud_textures;

/* Every parameter of the cloud pass. ccl_cloudscape_params_default documents the defaults and their reasons. */
typedef struct ccl_cloudscape_params {
    ccl_cloud_layer layer;      /* Earth and layer spheres (vc-A14); default 6371 km, base 1.5 km, top 4 km */
    float base_scale_km;        /* world size of one tile of the base texture (default 6 km) */
    float detail_scale_km;      /* world size of one tile of the detail texture (default 0.8 km) */
    float weather_scale_km;     /* world size of one tile of the weather map, planar projection (default 32 km) */
    float curl_scale_km;        /* world size of one tile of the curl texture (default 8 km) */
    float curl_strength_km;     /* displacement of the detail lookup per unit curl vector (default 0.2 km) */
    float weather_offset[2];    /* wind: (x, z) offset of the weather-map lookup, km */
    float detail_offset[3];     /* wind: offset of the detail lookup, km */
    float sigma;                /* extinction per unit density along the view ray, 1/km (default 30) */
    float sigma_light;          /* extinction per unit density towards the sun, 1/km (default 30) */
    float absorption_base;      /* a of vc-2.31 = absorption_base + absorption_precip * precipitation (1) */
    float absorption_precip;    /* (default 2) */
    float g;                    /* Henyey-Greenstein asymmetry of vc-2.31 (default 0.2) */
    float sun_colour[3];        /* sun radiance per channel, display-linear units (default 12 * (1, 0.96, 0.88)) */
    float ambient_bottom[3];    /* ambient radiance at the layer base (vc-A20; default (0.12, 0.14, 0.18)) */
    float ambient_top[3];       /* ambient radiance at the layer top (default (0.30, 0.34, 0.42)) */
    int samples_min;            /* view samples at the zenith (vc-A18; 64) */
    int samples_max;            /* view samples at the horizon (128) */
    int adaptive_samples;       /* 1: n from the ray's y (vc-A18); 0: always samples_max */
    int early_exit;             /* 1: stop when the accumulation reaches full opacity (vc-A21) */
    float exit_eps;             /* early-exit threshold: stop once 1 - T >= 1 - exit_eps (1/64, see the .c) */
    int exit_fill;              /* 1: at the early exit the remaining transmittance T takes the light of the last
                                   sample (C += T L, T = 0), an estimate of the rest of the ray; 0: T stays and
                                   the background shows through it (default 1, see the .c) */
    float light_interp;         /* light interpolation, >= 0 (display-linear radiance; default 1/256, see the .c): a
                                   lit sample between two consecutive lit samples whose optical depths towards the
                                   sun were computed takes the mean of theirs where its weight in the pixel times
                                   the largest channel difference of their lights is at most this (a sample that
                                   ends the ray computes its own); 0: every lit sample computes its own (vc-A19 as
                                   the thesis has it) */
    float light_step_km;        /* axial step of the light cone (vc-A19; 0.1 km) */
    float light_cone_angle;     /* half-angle of the light cone, rad (15 degrees) */
    float light_far_factor;     /* distance of the far light sample relative to the near cone (3), in
                                   [1, CCL_CLOUDSCAPE_MAX_LIGHT_FAR_FACTOR]; the far sample's distance
                                   light_far_factor x 5 x light_step_km is at most CCL_CLOUDSCAPE_MAX_LIGHT_KM */
    int light_detail;           /* 1: light samples use the full density with detail erosion; 0: base shape only */
    int jitter_mode;            /* ccl_jitter_mode (vc-A23): CCL_JITTER_TILT (default), _OFFSET, _NONE */
    float jitter_amount;        /* tilt scale, rad (0.002) */
    int gradient_clamp;         /* clamp the remaps of the height gradients (vc-4.7); default 1, see the .c */
    int detail_direction;       /* ccl_detail_direction of vc-2.30 (default CCL_DETAIL_FORMULA) */
    float ground_colour[3];     /* background where the view ray hits the Earth sphere (default (0.09, 0.10, 0.08)) */
    int coverage_threshold;     /* reading of the undefined C of vc-2.29: CCL_COVERAGE_ONE_MINUS (default) or
                                   CCL_COVERAGE_SAME (C := D_h, the spec's literal reading) -- see the .c */
    int beer;                   /* 1: Beer's term exp(-d a) of vc-2.31 on (default); 0: replaced by 1 */
    int powder;                 /* 1: the powder term 1 - exp(-2 d) of vc-2.31 on (the thesis); 0: replaced by 1
                                   (default, chosen by measurement: see the .c) */
    int lod;                    /* 1: level of detail (default): base and detail sampled at the mip level of the
                                   sample's footprint, see ccl_cloudscape_lod; 0: full resolution everywhere (thesis) */
    float lod_bias;             /* added to every mip level (default 0; > 0 blurs, < 0 sharpens), in [-4, 4] */
    float refine_step_km;       /* refinement: a view step longer than this is split into sub-steps of at most this
                                   length where the coarse test of the step, of the previous or of the next step
                                   finds cloud (a step's samples lie between the previous and the next step's coarse
                                   points); where the view steps are already this
                                   short, those within CCL_CLOUDSCAPE_GROUP_SPAN x this are grouped and skipped
                                   together where the coarse tests at both ends of the group find no cloud (default
                                   0.1 km; 0 = off, the thesis) */
    int refine_max;             /* most sub-steps per view step, and view steps per group, in [1, 64] (default 8) */
    int weather_detile;         /* 1: the weather map does not tile visibly (ccl_cloudscape_weather; default);
                                   0: one periodic lookup, the thesis */
    /* Lighting (see "Lighting" above; defaults and their reasons in cloudscape.c). */
    int lighting;               /* ccl_lighting: CCL_LIGHTING_SKY (default) or CCL_LIGHTING_THESIS */
    float sun_intensity;        /* sky mode: sun_colour = sun_intensity * ccl_sky_sun_attenuation (default 16) */
    float turbidity;            /* sky mode: turbidity T of the sun's attenuation, in [2, 10] (default 2.5) */
    float ambient_bottom_ratio; /* sky mode: ambient_bottom = ratio * ambient_top, in [0, 1] (default 0.4) */
    float ambient_ground[3];    /* sky mode: the sky light on the ground, the cosine-weighted mean sky radiance over
                                   the upper hemisphere (E_sky / pi); written by ccl_cloudscape_light */
    float ground_albedo[3];     /* sky mode: Lambertian albedo of the ground, in [0, 1] (default (0.04, 0.05, 0.03)) */
    float ground_variation;     /* sky mode: relative albedo variation of the ground, in [0, 1]: the albedo times
                                   1 + v (2 n - 1), n in [0, 1) the patches of ccl_cloudscape_ground (default 0: a
                                   uniform ground, as the thesis's) */
    float aerial_km;            /* sky mode: aerial-perspective e-folding distance at the ground, km; 0 = off
                                   (default 30) */
    float aerial_height_km;     /* sky mode: scale height of the haze, km; 0 = homogeneous (default 2) */
    int ms_octaves;             /* multiple-scattering octaves, 1 = single scattering, <= 8 (default 4, measured) */
    float ms_a;                 /* octave i: optical depth towards the sun x ms_a^i, in [0, 1] (default 0.5) */
    float ms_b;                 /* octave i: contribution x ms_b^i, in [0, 1] (default 0.5) */
    float ms_c;                 /* octave i: phase eccentricities x ms_c^i, in [0, 1] (default 0.5) */
    float silver_g;             /* second HG lobe: phase = (1 - w) HG(g) + w HG(silver_g), in (-1, 1) (default 0.8) */
    float silver_weight;        /* w of the second lobe, in [0, 1]; 0 = the thesis's single HG (default 0: chosen
                                   by measurement, see the .c) */
    int phase;                  /* ccl_cloudscape_phase of the sun energy: CCL_CLOUDSCAPE_PHASE_THESIS (default: HG(g)
                                   and the silver lobe) or CCL_CLOUDSCAPE_PHASE_MIE (ccl_phase_mie of droplet_um) */
    float droplet_um;           /* droplet diameter of the Mie phase, um, in [CCL_PHASE_MIE_D_MIN, _MAX] (default 15) */
    float ambient_ground_weight; /* sky mode: ambient_top = (1 - w) x the sky's mean over the upper hemisphere + w x
                                    the unshadowed ground's radiance ground_albedo (sun_colour cos theta_s / pi +
                                    ambient_ground), w in [0, 1] (default 0; 0.5: the mean over the whole sphere) */
    float ms_depth;             /* octaves i >= 1 x ccl_cloudscape_ms_gain(d, ms_depth, ms_thin): the multiple
                                   scattering grows with the optical depth d towards the sun, km-free scale > 0;
                                   0 = off, gain 1 (default 0) */
    float ms_thin;              /* the gain at d = 0, in [0, 1] (default 0) */
    float ms_view;              /* octaves i >= 1 x ccl_cloudscape_ms_view(T, ms_view, ms_view_trans), T the view
                                   transmittance in front of the sample, in [0, 1000] (default 0: off) */
    float ms_view_trans;        /* T0 of ccl_cloudscape_ms_view, in [0.001, 1] (default 1) */
    float ms_slab;              /* octaves i >= 1 x ccl_cloudscape_ms_slab(mu0, d, T, ms_slab, ms_slab_mu,
                                   ms_slab_far): gain k in [0, 1000] (default 0: off, weight 1) */
    float ms_slab_mu;           /* exponent p of the sun's cosine mu0 in ccl_cloudscape_ms_slab, in [0, 4]
                                   (default 1) */
    float ms_slab_far;          /* share s of the octaves lost on the side away from the sun in
                                   ccl_cloudscape_ms_slab, in [0, 1] (default 0) */
    float ambient_aniso;        /* the ambient x ccl_cloudscape_ambient_aniso(mu, T, ambient_aniso), mu the cosine of
                                   the view direction with the local up, in [0, 1] (default 0: off) */
    float mie_delta;            /* sky mode with the Mie phase: the share f in [0, 1] of the forward HG lobe that
                                   the lighting treats as unscattered (delta scaling, ccl_cloudscape_mie_delta_scale /
                                   _phase; default 0: off) */
    int march;                  /* ccl_cloudscape_march_kind: CCL_CLOUDSCAPE_MARCH_FAST (default) or
                                   CCL_CLOUDSCAPE_MARCH_TEXTBOOK (the thesis's loop, see ccl_cloudscape_march) */
} ccl_cloudscape_params;

/* The loop of ccl_cloudscape_march. */
typedef enum ccl_cloudscape_march_kind {
    CCL_CLOUDSCAPE_MARCH_FAST = 0,     /* refinement, grouping, light interpolation, level of detail (default) */
    CCL_CLOUDSCAPE_MARCH_TEXTBOOK = 1  /* vc-A18..A21 as the thesis prints them: ccl_cloudscape_march_textbook */
} ccl_cloudscape_march_kind;

/* Where the light of the cloud pass comes from. */
typedef enum ccl_lighting {
    CCL_LIGHTING_THESIS = 0,  /* the constants sun_colour, ambient_bottom / _top and a flat ground_colour */
    CCL_LIGHTING_SKY = 1      /* sun, ambient, lit ground and aerial perspective from the sky model (default) */
} ccl_lighting;

/* The phase function of the sun energy (ccl_cloudscape_energy). */
typedef enum ccl_cloudscape_phase {
    CCL_CLOUDSCAPE_PHASE_THESIS = 0,  /* HG(g) of vc-2.31, with the silver lobe where silver_weight > 0 (default) */
    CCL_CLOUDSCAPE_PHASE_MIE = 1      /* the approximate Mie phase of cloud droplets, ccl_phase_mie(droplet_um) */
} ccl_cloudscape_phase;

/* The sun's illuminance above the atmosphere at normal incidence, klx x 10 (an integer for the cffi-parsable
 * header): 127.5 klx, the extraterrestrial solar illuminance of the IES Lighting Handbook (Darula et al. 2005 give
 * 133.8 klx; the 5 % between them is the uncertainty of this constant). Its colour is taken as the white of linear
 * sRGB (a 5800 K sun outside the atmosphere is within a few per cent of D65 per channel); the atmosphere's
 * transmittance per channel (ccl_sky_sun_attenuation) colours it. In the units of CCL_SKY_PREETHAM_RADIANCE:
 * kcd/m^2 x sr = klx. */
#define CCL_CLOUDSCAPE_SUN_KLX_X10 1275
/* Most multiple-scattering octaves ccl_cloudscape_check accepts (the octave loop runs per light evaluation). */
#define CCL_CLOUDSCAPE_MAX_MS_OCTAVES 8
/* Base-shape density samples along the ray from a ground point towards the sun (the clouds' shadow on the ground):
 * 12 spaces them 0.2 km apart through the default 2.5 km layer under a high sun, finer than the cloud cells, and
 * costs 12 texture fetches per ground pixel (the clouds take up to 7 x 128). */
#define CCL_CLOUDSCAPE_GROUND_SHADOW_SAMPLES 12
/* With refinement on, a view step is at most refine_step_km x refine_max long (0.8 km by default): the coarse test
 * that decides where to refine is one point per view step, and with longer steps it misses whole clouds between two
 * points -- from inside or above the layer, rays near the horizon cross up to 357 km of the default layer, and with
 * samples_max = 128 steps of 2.8 km each pixel's coarse points land on different clouds: a speckled row (fig 4.13 a).
 * A longer segment takes more view steps, at most CCL_CLOUDSCAPE_COARSE_MAX_FACTOR x samples_max (4 x 128 steps
 * of 0.8 km cover those 357 km; the factor bounds the work per ray for any layer). A step is refined where the
 * coarse test of the previous, its own or the next step finds cloud: without the next step's, a cloud that begins
 * after the step's own coarse point was entered up to a step late, past its lit surface, by some pixels and not by
 * their neighbours -- dark speckles across the clouds at eye level from inside the layer, and frame-to-frame
 * flicker near the horizon (tests/clouds/test_artefacts.py). The next step's test is kept for it: no extra work. */
#define CCL_CLOUDSCAPE_COARSE_MAX_FACTOR 4
/* Grouping of short view steps (refinement on, view steps <= refine_step_km: the steep rays, most of a view from
 * below or above the layer): consecutive view steps spanning at most CCL_CLOUDSCAPE_GROUP_SPAN x refine_step_km
 * (and at most refine_max of them) share one coarse test (base shape, no detail, at the mip level of a view sample)
 * at each end; the group is marched where either end finds cloud, else skipped. The detail only erodes, so a sample
 * whose coarse test is 0 has density 0: a group is skipped wrongly only where cloud lies wholly between its two
 * ends. 2 (0.2 km by default) was measured on the thinnest clouds, stratus (type 0, coverage 0.9, oc fig 2.8),
 * against the march without groups: 0.003 % of the pixels change, by at most 2 levels of 8 bits. Spans of 0.3 km
 * and 0.8 km left speckles along thin cloud edges there (0.04 % and 0.8 % of the pixels off by more than 8
 * levels, up to 36 and 92). Each group costs one test (its end is the next group's start). */
#define CCL_CLOUDSCAPE_GROUP_SPAN 2.0f
/* Quadrature of the sky means of ccl_cloudscape_light: zenith-angle x azimuth cells over the upper hemisphere. 8 x 16
 * cells of 11.25 x 22.5 degrees: the Preetham and gradient skies vary slowly except within ~10 degrees of the sun,
 * which one cell averages; for a sky linear in d.y the means are off by 0.24 % (mean) and 0.11 % (cosine-weighted)
 * of the zenith-horizon difference (cclouds/tests/test_lighting.c). 128 sky evaluations, once per frame. */
#define CCL_CLOUDSCAPE_SKY_THETA_CELLS 8
#define CCL_CLOUDSCAPE_SKY_PHI_CELLS 16

/* Readings of the threshold C of vc-2.29 in the renderer. */
typedef enum ccl_coverage_threshold {
    CCL_COVERAGE_SAME = 0,      /* C := D_h: remap(B D_v, D_h, 1, 0, 1) D_h (the spec's most plausible literal reading) */
    CCL_COVERAGE_ONE_MINUS = 1  /* C := 1 - D_h: remap(B D_v, 1 - D_h, 1, 0, 1) D_h (common implementations) */
} ccl_coverage_threshold;

/* Sky background of the cloudscape. */
typedef enum ccl_sky_kind {
    CCL_SKY_GRADIENT = 0,          /* vc-A28 */
    CCL_SKY_PREETHAM = 1,          /* vc-A29 (default): tone mapped, 1 - exp(-k C_HDR) (vc-4.5) */
    CCL_SKY_PREETHAM_RADIANCE = 2  /* vc-A29 in physical units: k C_HDR, the radiance (C_HDR: linear sRGB whose Y is
                                      the luminance in kcd/m^2, vc-2.39) times the one exposure k = preetham.exposure
                                      (the tone map's slope at 0); with sky lighting the sun is then
                                      k CCL_CLOUDSCAPE_SUN_KLX x ccl_sky_sun_attenuation (ccl_cloudscape_light) */
} ccl_sky_kind;

typedef struct ccl_cloudscape_sky {
    int kind;                   /* ccl_sky_kind */
    float sun[3];               /* unit direction towards the sun (ccl_sky_sun_direction) */
    ccl_preetham preetham;      /* filled by ccl_sky_preetham_init when kind == CCL_SKY_PREETHAM */
    ccl_sky_gradient gradient;  /* filled by ccl_sky_gradient_defaults / _init when kind == CCL_SKY_GRADIENT */
} ccl_cloudscape_sky;

/* The documented defaults (see the field comments; reasons in cloudscape.c). */
CCL_API void ccl_cloudscape_params_default(ccl_cloudscape_params *out);

/* Validate parameters, textures and sky. Returns CCL_OK, or CCL_EINVAL and *out_field = the name of the first bad
 * field (a static string; out_field may be NULL). Besides each field's own range: the layer centre finite; the
 * texture-coordinate bound CCL_CLOUDSCAPE_MAX_TEXCOORD for every texture at its size (reported as base_scale_km,
 * curl_scale_km, weather_scale_km, weather_offset, detail_scale_km, curl_strength_km or detail_offset);
 * | |sky.sun| - 1 | <= 1e-3; a gradient sky's colours in [0, CCL_SKY_GRADIENT_MAX_COLOUR] (sky.gradient, as
 * ccl_sky_gradient_init; any exponent keeps the glow in [0, sun] since its cosine is clamped); a Preetham sky of the thesis variant with exposure in
 * (0, CCL_CLOUDSCAPE_MAX_THESIS_EXPOSURE] (sky.preetham.exposure). */
CCL_API ccl_status ccl_cloudscape_check(const ccl_cloudscape_params *p, const ccl_cloud_textures *t,
                                        const ccl_cloudscape_sky *sky, const char **out_field);

/* Bilinear sample of a periodic 2-D RGBA texture tex[y][x][4] of edge size_mask + 1 (a power of two) at texture
 * coordinates (u, v) (1 = one period, texel centres at (i + 0.5) / size), indices wrapped with & size_mask.
 * Domain |u * size|, |v * size| < 2^23; outside it (or for NaN) the four outputs are NaN. */
CCL_API void ccl_cloudscape_sample_bilinear_wrap(const float *tex, int size_mask, float u, float v, float *out_rgba);

/* Cloud density at a world position (vc-A17, see above); *out_precipitation = weather-map G at the position.
 * detail = 0 skips the detail erosion (returns B_D). Inputs must have passed ccl_cloudscape_check. */
CCL_API float ccl_cloudscape_density(const ccl_cloudscape_params *p, const ccl_cloud_textures *t, ccl_vec3 pos,
                                     int detail, float *out_precipitation);

/* The de-tiling of the weather map (ccl_cloudscape_weather): a 32 km map repeats visibly from a few km up. The map
 * is sampled a second time rotated by 37 degrees, scaled by 1 / 1.37 and shifted (an irrational-looking rotation and
 * scale, so the two lattices of repeats do not align), and a third time, 5.3 times larger and rotated the other way,
 * whose coverage (R) selects between the two through smoothstep(0.35, 0.65, R): large patches of one or the other,
 * with short transitions, so that the blend seldom averages two coverages (which would thin the gaps between cloud
 * fields). */
#define CCL_WEATHER_DETILE_COS 0.79863551f  /* cos 37 deg */
#define CCL_WEATHER_DETILE_SIN 0.60181502f  /* sin 37 deg */
#define CCL_WEATHER_DETILE_SCALE_B 1.37f
#define CCL_WEATHER_DETILE_SCALE_M 5.3f
#define CCL_WEATHER_DETILE_SHIFT_U 0.31f
#define CCL_WEATHER_DETILE_SHIFT_V 0.57f
#define CCL_WEATHER_DETILE_EDGE0 0.35f
#define CCL_WEATHER_DETILE_EDGE1 0.65f

/* The weather map (RGBA: coverage, precipitation, cloud type, -) at world (x, z) km with the wind offset: one
 * periodic bilinear lookup at ((x, z) + weather_offset) / weather_scale_km, and with p->weather_detile the blend
 * described above. out_rgba[4]. */
CCL_API void ccl_cloudscape_weather(const ccl_cloudscape_params *p, const ccl_cloud_textures *t, float x_km,
                                    float z_km, float *out_rgba);

/* Density with a level of detail: base and detail textures sampled at mip levels lod_base / lod_detail (<= 0: full
 * resolution; fractional levels blend the two nearest levels; the last level is the texture's mean, and at the
 * detail's last level the curl lookup is skipped). Without mips (t->base_mips / detail_mips NULL) level 0. */
CCL_API float ccl_cloudscape_density_lod(const ccl_cloudscape_params *p, const ccl_cloud_textures *t, ccl_vec3 pos,
                                         int detail, float lod_base, float lod_detail, float *out_precipitation);

/* The mip level of a sample of footprint footprint_km on a texture of texel size texel_km:
 * log2(footprint / texel) + bias; 0 for a footprint <= 0 or NaN. The march takes as footprint the pixel's width at
 * the sample's distance (distance x pixel_angle: ~0.4 km near the horizon against 47 m base and 25 m detail
 * texels), the coarse test of the refinement the larger of that and the view step, and the light samples at least
 * the light step. */
CCL_API float ccl_cloudscape_lod(float footprint_km, float texel_km, float bias);

/* The mip levels 1 .. log2(size) of a periodic RGBA volume tex (size^3 texels [z][y][x][4], size a power of two):
 * each texel the mean of its 8 children, summed x fastest, then y, then z. out gets the levels one after another;
 * out_len must be the number of floats: 4 * sum_{k>=1} (size >> k)^3. CCL_EINVAL otherwise. */
CCL_API ccl_status ccl_cloudscape_mip3(const float *tex, int size, float *out, size_t out_len);

/* The out_len ccl_cloudscape_mip3 needs for an edge size (floats): 4 * sum_{k>=1} (size >> k)^3; 0 for a size that
 * is not a power of two in [1, 4096]. */
CCL_API size_t ccl_cloudscape_mip3_len(int size);

/* The sun energy of one sample (see "Lighting" above): sum over i < p->ms_octaves of
 *   ms_b^i * beer(ms_a^i d) * phase_i(cos_theta) * powder(ms_a^i d),
 *   beer(x) = exp(-x a), powder(x) = 1 - exp(-2 x) (each replaced by 1 when p->beer / p->powder is 0),
 *   phase_i = (1 - w) HG(cos_theta, ms_c^i g) + w HG(cos_theta, ms_c^i silver_g), w = p->silver_weight (HG(g) alone
 *   when w = 0).
 * Ref: vc-2.31 (the i = 0 term; with ms_octaves = 1 and w = 0 the result equals ccl_clouds_energy bit for bit),
 * Wrenninge, Kulla & Lundqvist 2013 "Oz: the great and volumetric" (octaves), Hillaire 2016. d -> optical depth
 * towards the sun (>= 0), a -> absorption factor of vc-2.31 (>= 0), cos_theta in [-1, 1] (view . sun). Output >= 0
 * [1/sr]. p must have passed ccl_cloudscape_check. */
CCL_API float ccl_cloudscape_energy(const ccl_cloudscape_params *p, float d, float a, float cos_theta);

/* Delta scaling of the approximate Mie phase (vc-x-mie-delta; beyond the text): the forward HG lobe of ccl_phase_mie
 * (weight 1 - w_D, g_HG = 0.99 at 15 um: its light stays within a degree or two of the direction of travel -- the
 * diffraction peak of the droplets) is, for the lighting, light that was not scattered at all. A share f of it is
 * moved from the scattered to the transmitted light:
 *   extinction  sigma' = sigma s,  s = ccl_cloudscape_mie_delta_scale(d, f) = 1 - f (1 - w_D),
 *   phase       p'(cos) = ccl_cloudscape_mie_delta_phase(cos, d, f)
 *                       = ((1 - f) (1 - w_D) HG(cos, g_HG) + w_D Draine(cos, g_D, alpha)) / s,
 * which keeps sigma p everywhere but in the peak: sigma' p' = sigma p - sigma f (1 - w_D) HG(g_HG), and p' integrates
 * to 1. f = 0: sigma and ccl_phase_mie unchanged; f = 1: Draine's lobe alone, with w_D of the extinction.
 * Ref: Joseph, Wiscombe & Weinman 1976 (the delta-Eddington approximation), Wiscombe 1977 (delta-M), here with the
 * peak of Jendersie & d'Eon 2023 as the delta. diameter_um in [CCL_PHASE_MIE_D_MIN, _MAX], f in [0, 1], cos_theta in
 * [-1, 1]. ccl_cloudscape_light applies the scale to sigma and sigma_light (sky lighting, phase MIE, mie_delta > 0)
 * and ccl_cloudscape_energy uses p'. Why: a path tracer sees the peak's light go on almost undeviated, which the
 * octaves cannot represent: thin cloud then lets the sky behind through and a thick cloud's base receives more sun. */
/* The weight of the multiple-scattering octaves (i >= 1) of ccl_cloudscape_energy by the optical depth d towards the
 * sun (vc-x-ms-gain; beyond the text):
 *   gain = t + (1 - t) (1 - exp(-d / D)),  D = depth > 0, t = thin in [0, 1];  depth = 0: gain = 1 (the octaves as
 *   Wrenninge et al. 2013 and Hillaire 2016 have them).
 * Why: the octaves stand for light scattered more than once, which needs cloud around the sample; a thin wisp (small
 * d) scatters the sun once, and the octaves then add light the path-traced reference does not have (thin cloud at
 * 1.2-2.2 times the reference's energy). d >= 0, output in [t, 1]. */
CCL_API float ccl_cloudscape_ms_gain(float d, float depth, float thin);
/* The weight of the multiple-scattering octaves (i >= 1) by the depth into the cloud along the view (vc-x-ms-view;
 * beyond the text):  weight = 1 + k max(1 - T / T0, 0),  T in [0, 1] the view transmittance in front of the sample,
 * k >= 0, T0 in (0, 1]; k = 0: 1. Why: light that has gone deep into a thick cloud is trapped there and scattered
 * many times; the octaves, functions of the optical depth towards the sun only, leave thick cloud at 0.7-0.9 of the
 * path-traced energy. A thin cloud (tau < 3, with delta scaling T > 0.2 along its whole ray) keeps T above T0 and is
 * left as it is. Output in [1, 1 + k]. */
CCL_API float ccl_cloudscape_ms_view(float trans, float k, float t0);
/* The weight of the multiple-scattering octaves (i >= 1) by the sun's elevation and the sample's place between the
 * sun and the viewer (vc-x-ms-slab; beyond the text):
 *   weight = k max(mu0, 0)^p (1 - s r),  r = d / (d + tau_v),  tau_v = -ln max(T, 1e-30)
 * mu0 in [-1, 1] the cosine of the direction to the sun with the local up, d >= 0 the optical depth towards the sun,
 * T in [0, 1] the view transmittance in front of the sample (tau_v: the optical depth from the sample back to the
 * eye), k in [0, 1000], p in [0, 4], s in [0, 1]; r = 0 where d + tau_v = 0; k = 0: 1 (off).
 * Why: light scattered many times has forgotten the sun's direction (diffusion, the two-stream slab): what reaches
 * the inside of a cloud is the sun's flux through its top, which falls with mu0, not with the optical depth along
 * the slant path of the octaves; and the diffuse light falls from the cloud's lit side to its far side, so light
 * leaving on the side away from the sun (seen from below: the base, r near 1) is weaker than light leaving towards
 * it (the sunlit tops, r near 0). Without it thick cloud seen from below goes from 0.88 of the path-traced energy at
 * a high sun to 1.14-1.31 at a low one, while the tops seen from above at 35 deg are about right. Output in
 * [k (1 - s) max(mu0, 0)^p, k max(mu0, 0)^p]. */
CCL_API float ccl_cloudscape_ms_slab(float mu0, float d, float trans, float k, float p, float s);
/* The weight of the ambient by the view direction (vc-x-ambient-aniso; beyond the text):
 *   weight = 1 + alpha mu T,  mu in [-1, 1] the cosine of the view direction with the local up, T in [0, 1] the view
 *   transmittance in front of the sample, alpha in [0, 1]; alpha = 0: 1.
 * Why: the ambient is the sky's light from above (mostly), and a forward-scattering cloud sends it on downwards: seen
 * from below (mu > 0) a thin cloud shows more of it, seen from above (mu < 0) less (thin cloud from above at 1.2-1.5
 * of the reference's energy with an isotropic ambient). Deeper in the cloud (T small) the light has been scattered
 * many times and is isotropic. Output in [1 - alpha, 1 + alpha]. */
CCL_API float ccl_cloudscape_ambient_aniso(float mu, float trans, float alpha);
CCL_API float ccl_cloudscape_mie_delta_scale(float diameter_um, float f);
CCL_API float ccl_cloudscape_mie_delta_phase(float cos_theta, float diameter_um, float f);

/* Size of the ground's albedo patches (ground_variation) [km]: 0.125, fields and woods of a hundred metres or so seen
 * from a low camera (the rain scene's 50 m), with a second octave 4 times smaller inside them. */
#define CCL_CLOUDSCAPE_GROUND_PATCH_KM 0.125f
/* Radiance of the ground at a point on (or near) the Earth sphere, sky lighting (see "Lighting" above): ground_albedo
 * (sun_colour max(n . to_sun, 0) T_shadow / pi + ambient_ground), n = the sphere's normal at point, T_shadow from
 * CCL_CLOUDSCAPE_GROUND_SHADOW_SAMPLES base-shape density samples towards the sun. With ground_variation v > 0 the
 * albedo is times 1 + v (2 n - 1), n = 2/3 N(x / P, z / P) + 1/3 N(4 x / P, 4 z / P) at the point's (x, z) in km,
 * P = CCL_CLOUDSCAPE_GROUND_PATCH_KM, N the smoothstep-interpolated value noise of ccl_hash_pcg lattice values.
 * *out_shadow (may be NULL) gets T_shadow in [0, 1]. out_rgb[3] >= 0. Inputs must have passed ccl_cloudscape_check;
 * point below the inner sphere. */
CCL_API void ccl_cloudscape_ground(const ccl_cloudscape_params *p, const ccl_cloud_textures *t, ccl_vec3 point,
                                   ccl_vec3 to_sun, float *out_rgb, float *out_shadow);

/* The per-frame lighting setup (see "Lighting" above): *out = *p, and for p->lighting == CCL_LIGHTING_SKY with
 * sun_colour, ambient_top, ambient_bottom and ambient_ground computed from the sky model and sky->sun (theta_s =
 * acos(clamp(sun.y, 0, 1))); CCL_LIGHTING_THESIS: an unchanged copy. out may equal p. Call it once before
 * ccl_cloudscape_pixel (ccl_cloudscape_render does); p and sky must have passed ccl_cloudscape_check. */
CCL_API void ccl_cloudscape_light(const ccl_cloudscape_params *p, const ccl_cloudscape_sky *sky,
                                  ccl_cloudscape_params *out);

/* March one view ray through the layer: cloud colour (premultiplied, display-linear), view transmittance T and the
 * number of view samples taken. offset in [0, 1): sample position within each step (0.5 = midpoints).
 * pixel_angle: the angle between neighbouring pixels' rays (rad), for the level of detail (p->lod).
 * *out_depth_km (may be NULL): the transmittance-weighted mean distance of the samples (0 where nothing was
 * accumulated), the distance of the aerial perspective.
 * p->march selects the loop: CCL_CLOUDSCAPE_MARCH_FAST, the loop above with refinement, grouping, light
 * interpolation and level of detail (each documented at its parameter); CCL_CLOUDSCAPE_MARCH_TEXTBOOK,
 * ccl_cloudscape_march_textbook. */
CCL_API void ccl_cloudscape_march(const ccl_cloudscape_params *p, const ccl_cloud_textures *t, ccl_vec3 eye,
                                  ccl_vec3 dir, ccl_vec3 to_sun, float offset, float pixel_angle, float *out_rgb,
                                  float *out_transmittance, int *out_samples, float *out_depth_km);

/* The thesis's loop (vc-A18..A21, §4.3.2), for reading beside the text: n uniform view samples (vc-A18: adaptive
 * or samples_max) through the layer segment; at each, the full-resolution density (vc-A17); where it is non-zero,
 * the optical depth towards the sun from the 6 cone samples (vc-A19), the light E + ambient (vc-2.31, vc-A20) and
 * the front-to-back accumulation with the early termination (vc-A21). No refinement, grouping, light interpolation
 * or level of detail (refine_step_km, refine_max, light_interp, lod and lod_bias are not read); every other
 * parameter means what it means in the fast march, which with lod = 0, refine_step_km = 0 and light_interp = 0
 * gives the same result bit for bit. Outputs as ccl_cloudscape_march (out_samples: the view samples taken). */
CCL_API void ccl_cloudscape_march_textbook(const ccl_cloudscape_params *p, const ccl_cloud_textures *t, ccl_vec3 eye,
                                           ccl_vec3 dir, ccl_vec3 to_sun, float offset, float *out_rgb,
                                           float *out_transmittance, int *out_samples, float *out_depth_km);

/* The display-linear colour (before sRGB encoding) of pixel (x, y) of a width x height frame: sky, clouds,
 * composite. frame seeds the ray jitter. out_rgb[3]. With sky lighting, p must come from ccl_cloudscape_light (it
 * reads sun_colour and the ambients as they are). */
CCL_API void ccl_cloudscape_pixel(const ccl_cloudscape_params *p, const ccl_cloud_textures *t,
                                  const ccl_cloudscape_sky *sky, const ccl_camera *cam, int x, int y, int width,
                                  int height, int frame, float *out_rgb);

/* Render a whole frame on one thread (ccl_cloudscape_light once, then ccl_cloudscape_pixel per pixel): out_rgb
 * (height x width x 3, row 0 at the top) gets sRGB-encoded values in [0, 1]. Returns CCL_EINVAL for bad parameters
 * (see ccl_cloudscape_check), sizes < 1, frame < 0, NULL pointers or out_len != width * height * 3. */
CCL_API ccl_status ccl_cloudscape_render(const ccl_cloudscape_params *p, const ccl_cloud_textures *t,
                                         const ccl_cloudscape_sky *sky, const ccl_camera *cam, int width, int height,
                                         int frame, float *out_rgb, size_t out_len);

#ifdef __cplusplus
}
#endif

#endif /* CCLOUDS_CLOUDSCAPE_H */
