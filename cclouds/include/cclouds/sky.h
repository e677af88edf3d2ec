/*
 * cclouds/sky.h -- sky models (vc §2.5, §4.2): turbidity, the CIE clear sky, the Perez all-weather model, the
 * Preetham, Shirley & Smits 1999 daylight model, and the two sky models of the thesis (gradient vc-A28 and
 * Preetham vc-A29) as per-direction functions over precomputed per-frame constants.
 *
 * Angles (radians unless the name ends in _deg):
 *   theta   -- zenith angle of the view direction, 0 = zenith, pi/2 = horizon;
 *   gamma   -- angle between the view direction and the direction towards the sun;
 *   theta_s -- zenith angle of the sun (the Preetham model needs 0 <= theta_s <= pi/2, sun above the horizon).
 * Directions are unit vectors in a right-handed, Y-up world (OpenGL, as the thesis: "the ray's Y component" is the
 * height). The sun direction points from the observer towards the sun and is built from an elevation e (degrees
 * above the horizon) and an azimuth a (degrees, 0 = -Z, the look direction of a default OpenGL camera, 90 = +X):
 *   sun = (cos e sin a, sin e, -cos e cos a), so theta_s = pi/2 - e.
 *
 * Horizon and below-horizon view directions (not specified by the thesis, vc-2.36 note): every Perez-type function
 * here evaluates cos(theta) as max(cos(theta), 0.01). The value 0.01 is the one Radiance's perezlum.cal and
 * skybright.cal use (G. Ward); for the Preetham coefficients (B < 0 for T >= 1.21) exp(B / 0.01) < 2e-6, so rays at
 * and below the horizon get the horizon limit of the formula, continuously, and B / cos(theta) never divides by 0.
 *
 * Units: the Preetham zenith luminance Y_Z is in kcd/m^2 (Preetham et al. 1999); chromaticities are CIE 1931 x, y.
 */
#ifndef CCLOUDS_SKY_H
#define CCLOUDS_SKY_H

#include "cclouds/common.h"
#include "cclouds/colour.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Valid turbidity range of the Preetham fits, enforced by ccl_sky_preetham_init and the Python boundary: 2 <= T <= 10
 * (Preetham et al. 1999 fitted roughly this range; Zotti, Wilkie & Purgathofer 2007 document the model's failures
 * outside it -- e.g. B_Y > 0 for T < 1.21 makes the luminance grow towards the horizon without bound). */
#define CCL_PREETHAM_TURBIDITY_MIN 2
#define CCL_PREETHAM_TURBIDITY_MAX 10

/* Per-frame constants of the Preetham sky (vc-A29, "PreethamSkyModel::update"), filled by ccl_sky_preetham_init. */
typedef struct ccl_preetham {
    float perez_Y[5];  /* Perez A..E of the luminance Y (vc-2.42) */
    float perez_x[5];  /* Perez A..E of the chromaticity x (vc-2.43) */
    float perez_y[5];  /* Perez A..E of the chromaticity y (vc-2.44) */
    float zenith_Y;    /* Y_Z [kcd/m^2] (vc-2.39) */
    float zenith_x;    /* x_z (vc-2.40) */
    float zenith_y;    /* y_z (vc-2.41) */
    float factor_Y;    /* Y_Z / F_Y(0, theta_s) (vc-4.2): Y(theta, gamma) = factor_Y * F_Y(theta, gamma) (vc-2.38) */
    float factor_x;    /* x_z / F_x(0, theta_s) */
    float factor_y;    /* y_z / F_y(0, theta_s) */
    float turbidity;   /* T */
    float theta_s;     /* sun zenith angle [rad] */
    float exposure;    /* tone-map exposure k of vc-4.5 */
    int variant;       /* ccl_variant applied to all three errata of the chain: vc-2.39, vc-4.4 and vc-4.5 */
} ccl_preetham;

/* Largest colour component of the gradient sky that ccl_sky_gradient_init accepts (linear RGB). The cloudscape's sky
 * lighting sums the sky over a hemisphere of cells (ccl_cloudscape_light): a horizon of 1e37 overflowed those sums
 * and made NaN pixels; at 10^6 every sum and the colour itself (horizon + zenith + sun <= 3e6) stay finite. The
 * defaults are below 1 (display-linear colours); the volume sky's colours have the same bound
 * (CCL_VOLUME_MAX_COLOUR). */
#define CCL_SKY_GRADIENT_MAX_COLOUR 1.0e6f

/* Per-frame constants of the gradient sky (vc-A28). All colours are linear RGB; see ccl_sky_gradient_defaults. */
typedef struct ccl_sky_gradient {
    float horizon[3];   /* light blue at the horizon (view y <= 0) */
    float zenith[3];    /* dark blue at the zenith (view y = 1) */
    float sun[3];       /* colour added at the sun */
    float sun_exponent; /* n of the sun term max(cos gamma, 0)^n, > 0 */
} ccl_sky_gradient;

/* Turbidity T = (t_m + t_h) / t_m.
 * Ref: vc-2.33 (Preetham et al. 1999, after McCartney 1976). t_m -> optical thickness of the purely molecular
 * atmosphere, > 0; t_h -> optical thickness of the haze, >= 0. Output T >= 1 (T = 1: pure air). */
CCL_API float ccl_sky_turbidity(float t_m, float t_h);

/* CIE clear-sky luminance Y = Y_z * f(gamma) phi(theta) / (f(theta_s) phi(0)) with
 * f(g) = 0.91 + 10 exp(-3 g) + 0.45 cos^2 g and phi(t) = 1 - exp(-0.32 / cos t).
 * Ref: vc-2.35 (CIE 1973 clear sky; Kittler). theta in [0, pi] (cos theta clamped to >= 0.01, see the file comment),
 * gamma in [0, pi], theta_s in [0, pi/2], Y_z -> zenith luminance (any unit, output has the same). At theta = 0,
 * gamma = theta_s the output is Y_z. Equal to Y_z F(theta, gamma) / F(0, theta_s) with the Perez function 2.36 and
 * A = -1, B = -0.32, C = 10/0.91, D = -3, E = 0.45/0.91 (the spec's derivation; the text's C = 10, E = 0.45 are off
 * by the factor 0.91). */
CCL_API float ccl_sky_cie_clear(float theta, float gamma, float theta_s, float Y_z);

/* Bound of the Perez coefficients of ccl_sky_perez and the functions that take A..E: A, C, E in [-M, M], B and D in
 * [-M, 0] with M = 10^6. B, D <= 0 (the luminance falls towards the horizon and away from the sun) keeps both
 * exponentials <= 1, so |F| <= (1 + M)(1 + 2M): finite, where finite coefficients such as (-1, 0, -3.4e38, 0,
 * -3.4e38) gave 0 x -inf = NaN. Preetham's coefficients for 2 <= T <= 10 and the CIE standard skies lie inside. */
#define CCL_SKY_PEREZ_MAX_COEFFICIENT 1.0e6f

/* Perez all-weather relative luminance F = (1 + A exp(B / cos theta)) (1 + C exp(D gamma) + E cos^2 gamma).
 * Ref: vc-2.36 (Perez, Seals & Michalsky 1993). theta in [0, pi] (cos theta clamped to >= 0.01, see the file
 * comment), gamma in [0, pi]; A..E within CCL_SKY_PEREZ_MAX_COEFFICIENT (B, D <= 0). Output: relative luminance
 * (dimensionless), finite; > 0 for the Preetham coefficients of 2 <= T <= 10. NaN propagates. */
CCL_API float ccl_sky_perez(float theta, float gamma, float A, float B, float C, float D, float E);

/* CIE-adopted modified Perez function (CIE standard general sky, CIE S 011/E:2003):
 * F = (1 + A exp(B / cos theta)) (1 + C (exp(D gamma) - exp(D pi/2)) + E cos^2 gamma).
 * Ref: vc-2.37. Arguments as ccl_sky_perez. variant CCL_VARIANT_CORRECTED: the subtracted term is the constant
 * exp(D pi/2), so the indicatrix is exactly 1 at gamma = pi/2. variant CCL_VARIANT_THESIS: exp(D gamma pi/2) as
 * printed (spec error index item 8). */
CCL_API float ccl_sky_perez_cie(float theta, float gamma, float A, float B, float C, float D, float E,
                                ccl_variant variant);

/* Zenith normalisation factor Y_z / F(0, theta_s) of one channel.
 * Ref: vc-4.2 (applied to Y, x and y alike, each with its own A..E: spec error index item 21). theta_s in [0, pi/2];
 * Y_z -> the channel's zenith value (Y_Z, x_z or y_z); A..E -> that channel's Perez coefficients. */
CCL_API float ccl_sky_perez_zenith_factor(float theta_s, float Y_z, float A, float B, float C, float D, float E);

/* Normalised Perez distribution Y = F(theta, gamma) / F(0, theta_s) * Y_z (evaluated in this order, so the zenith
 * theta = 0, gamma = theta_s returns Y_z exactly).
 * Ref: vc-2.38. theta, gamma in [0, pi]; theta_s in [0, pi/2]; Y_z -> zenith value of the channel; A..E -> Perez
 * coefficients. */
CCL_API float ccl_sky_perez_normalized(float theta, float gamma, float theta_s, float Y_z, float A, float B, float C,
                                       float D, float E);

/* Preetham zenith colour in xyY: chromaticity x_z, y_z and luminance Y_Z [kcd/m^2].
 * Y_Z = (4.0453 T - 4.9710) tan chi - 0.2155 T + 2.4192, chi = (4/9 - T/120)(pi - 2 theta_s); x_z, y_z as
 * ccl_sky_preetham_zenith_x / _y. Ref: vc-2.39, 2.40, 2.41 (Preetham, Shirley & Smits 1999, appendix A.2).
 * turbidity -> T in [2, 10]; theta_s -> sun zenith angle in [0, pi/2].
 * variant CCL_VARIANT_CORRECTED: Preetham's 4.0453 T; CCL_VARIANT_THESIS: 6.0453 T as printed (spec error index
 * item 9). Check values of Y_Z (corrected / thesis): T = 2, theta_s = 0 -> 15.5007 / 32.8266; T = 2, 30 deg ->
 * 5.8867 / 10.8855; T = 3, 60 deg -> 5.1392 / 7.9583. Output (x_z, y_z, Y_Z), the xyY of ccl_colour_xyY_to_XYZ. */
CCL_API ccl_vec3 ccl_sky_preetham_zenith(float turbidity, float theta_s, ccl_variant variant);

/* Preetham zenith chromaticity x_z = [T^2 T 1] M_x [theta_s^3 theta_s^2 theta_s 1]^T.
 * Ref: vc-2.40 (Preetham et al. 1999). turbidity in [2, 10], theta_s in [0, pi/2]. T = 2, theta_s = 0 -> 0.26674. */
CCL_API float ccl_sky_preetham_zenith_x(float turbidity, float theta_s);

/* Preetham zenith chromaticity y_z = [T^2 T 1] M_y [theta_s^3 theta_s^2 theta_s 1]^T.
 * Ref: vc-2.41 (Preetham et al. 1999). turbidity in [2, 10], theta_s in [0, pi/2]. T = 2, theta_s = 0 -> 0.27720. */
CCL_API float ccl_sky_preetham_zenith_y(float turbidity, float theta_s);

/* Perez coefficients of the luminance Y from the turbidity: A_Y = 0.1787 T - 1.4630, B_Y = -0.3554 T + 0.4275,
 * C_Y = -0.0227 T + 5.3251, D_Y = 0.1206 T - 2.5771, E_Y = -0.0670 T + 0.3703.
 * Ref: vc-2.42 (Preetham et al. 1999). turbidity in [2, 10]. Outputs through out_A .. out_E. */
CCL_API void ccl_sky_preetham_perez_Y(float turbidity, float *out_A, float *out_B, float *out_C, float *out_D,
                                      float *out_E);

/* Perez coefficients of the chromaticity x: A_x = -0.0193 T - 0.2592, B_x = -0.0665 T + 0.0008,
 * C_x = -0.0004 T + 0.2125, D_x = -0.0641 T - 0.8989, E_x = -0.0033 T + 0.0452.
 * Ref: vc-2.43 (Preetham et al. 1999). turbidity in [2, 10]. */
CCL_API void ccl_sky_preetham_perez_x(float turbidity, float *out_A, float *out_B, float *out_C, float *out_D,
                                      float *out_E);

/* Perez coefficients of the chromaticity y: A_y = -0.0167 T - 0.2608, B_y = -0.0950 T + 0.0092,
 * C_y = -0.0079 T + 0.2102, D_y = -0.0441 T - 1.6537, E_y = -0.0109 T + 0.0529.
 * Ref: vc-2.44 (Preetham et al. 1999). turbidity in [2, 10]. */
CCL_API void ccl_sky_preetham_perez_y(float turbidity, float *out_A, float *out_B, float *out_C, float *out_D,
                                      float *out_E);

/* Unit direction towards the sun from its elevation and azimuth in degrees (the thesis' "two angles in degrees"):
 * (cos e sin a, sin e, -cos e cos a), Y up, azimuth 0 = -Z, 90 = +X (see the file comment).
 * Ref: vc-A28, vc-A29. elevation_deg in [-90, 90], azimuth_deg any finite value. Output: the unit vector. */
CCL_API ccl_vec3 ccl_sky_sun_direction(float elevation_deg, float azimuth_deg);

/* Per-frame constants of the Preetham sky: Perez coefficients (2.42-2.44), zenith values (2.39-2.41) and their
 * normalisation factors (4.2) for turbidity T and sun zenith angle theta_s; exposure is the tone-map k of 4.5.
 * Ref: vc-A29 (PreethamSkyModel::update). Validates: returns CCL_EINVAL (and leaves *out untouched) unless
 * 2 <= turbidity <= 10, 0 <= theta_s <= pi/2 (sun above the horizon), 0 < exposure < inf, variant is a ccl_variant,
 * out != NULL; NaN is invalid. variant: CCL_VARIANT_CORRECTED (Preetham's 4.0453, Lindbloom's -0.9692660,
 * 1 - exp(-k C)) or CCL_VARIANT_THESIS (6.0453, -0.9392660, 1 - exp(+k C), all as printed). */
CCL_API ccl_status ccl_sky_preetham_init(float turbidity, float theta_s, float exposure, ccl_variant variant,
                                         ccl_preetham *out);

/* Preetham sky in CIE xyY for one unit view direction d and the unit direction s towards the sun (whose zenith
 * angle must be p->theta_s): theta = acos(d_y), gamma = acos(clamp(d . s, -1, 1)); each channel is
 * factor * F(theta, gamma) (2.36 x 4.2 = 2.38). Output (x, y, Y): chromaticity and luminance [kcd/m^2].
 * Ref: vc-A29 (GPU part up to xyY). Directions below the horizon use the horizon limit (file comment). */
CCL_API ccl_vec3 ccl_sky_preetham_xyY(ccl_vec3 dir, ccl_vec3 sun, const ccl_preetham *p);

/* Preetham sky as linear sRGB before the tone map: xyY (above) -> XYZ (4.3) -> RGB (4.4, matrix of p->variant).
 * Ref: vc-A29. Output in kcd/m^2-scaled linear RGB (HDR). */
CCL_API ccl_vec3 ccl_sky_preetham_hdr(ccl_vec3 dir, ccl_vec3 sun, const ccl_preetham *p);

/* Preetham sky colour as written by the thesis to the frame buffer: ccl_sky_preetham_hdr, then the tone map 4.5
 * per channel with p->exposure and p->variant. Linear, not sRGB-encoded (apply ccl_colour_srgb_encode for display);
 * not clamped (out-of-gamut colours can be slightly negative; the thesis variant is <= 0 everywhere).
 * Ref: vc-A29. Allocation-free; the per-pixel function of the renderer. */
CCL_API ccl_vec3 ccl_sky_preetham_rgb(ccl_vec3 dir, ccl_vec3 sun, const ccl_preetham *p);

/* What ccl_sky_preetham_colour returns. */
typedef enum ccl_sky_preetham_output {
    CCL_SKY_PREETHAM_TONEMAPPED = 0, /* ccl_sky_preetham_rgb: linear RGB after the tone map 4.5 (the thesis) */
    CCL_SKY_PREETHAM_HDR = 1,        /* ccl_sky_preetham_hdr: linear sRGB before the tone map */
    CCL_SKY_PREETHAM_XYY = 2,        /* ccl_sky_preetham_xyY: (x, y, Y) */
    CCL_SKY_PREETHAM_SRGB = 3        /* tonemapped, then ccl_colour_srgb_encode per channel (for display) */
} ccl_sky_preetham_output;

/* Preetham sky of one view direction from the sky parameters themselves (the element-wise form of vc-A29; a
 * renderer calls ccl_sky_sun_direction and ccl_sky_preetham_init once per frame and ccl_sky_preetham_rgb per pixel,
 * which this function does in one call): theta_s = (90 - sun_elevation_deg) in radians,
 * s = ccl_sky_sun_direction(sun_elevation_deg, sun_azimuth_deg), d = direction / |direction|.
 * Ref: vc-A29 (vc-2.36, 2.38-2.44, 4.2-4.5). direction -> any non-zero view vector (Y up), normalised here;
 * turbidity in [2, 10]; sun_elevation_deg in [0, 90] (the model needs the sun above the horizon); sun_azimuth_deg
 * any finite value; exposure > 0; variant applies to all three errata (2.39, 4.4, 4.5); output: see
 * ccl_sky_preetham_output. Parameters are not validated here (ccl_sky_preetham_init validates them). */
CCL_API ccl_vec3 ccl_sky_preetham_colour(ccl_vec3 direction, float turbidity, float sun_elevation_deg,
                                         float sun_azimuth_deg, float exposure, ccl_variant variant,
                                         ccl_sky_preetham_output output);

/* The documented default parameters of the gradient sky (the thesis gives no values; see the Python docstring of
 * sky_gradient for the reasons): horizon (0.66, 0.78, 0.94), zenith (0.16, 0.34, 0.72), sun (1.0, 0.9, 0.7),
 * sun_exponent 64. */
CCL_API void ccl_sky_gradient_defaults(ccl_sky_gradient *out);

/* Fill a gradient sky from its colours (linear RGB, each component in [0, CCL_SKY_GRADIENT_MAX_COLOUR]) and the sun
 * exponent (> 0,
 * finite). Ref: vc-A28. Returns CCL_EINVAL (leaving *out untouched) for any invalid value or out == NULL. */
CCL_API ccl_status ccl_sky_gradient_init(ccl_vec3 horizon, ccl_vec3 zenith, ccl_vec3 sun, float sun_exponent,
                                         ccl_sky_gradient *out);

/* Gradient sky colour of a unit view direction d with unit sun direction s:
 * t = clamp(d_y, 0, 1); rgb = horizon + t (zenith - horizon) + sun * clamp(d . s, 0, 1)^sun_exponent (the
 * clamp at 1 keeps the result finite for any finite exponent when d . s rounds above 1).
 * Ref: vc-A28 (linear interpolation between a light and a dark blue by the ray's Y component plus a sun colour by
 * the angle to the sun). Output linear RGB >= 0 for non-negative colours. Allocation-free. */
CCL_API ccl_vec3 ccl_sky_gradient_rgb(ccl_vec3 dir, ccl_vec3 sun, const ccl_sky_gradient *g);

/* What ccl_sky_gradient_colour returns. */
typedef enum ccl_sky_gradient_output {
    CCL_SKY_GRADIENT_LINEAR = 0, /* ccl_sky_gradient_rgb: the colour as the thesis writes it */
    CCL_SKY_GRADIENT_SRGB = 1    /* then ccl_colour_srgb_encode per channel (for display) */
} ccl_sky_gradient_output;

/* Gradient sky of one view direction from the sky parameters themselves (the element-wise form of vc-A28):
 * s = ccl_sky_sun_direction(sun_elevation_deg, sun_azimuth_deg), d = direction / |direction|, then
 * ccl_sky_gradient_rgb with the given colours and exponent.
 * Ref: vc-A28. direction -> any non-zero view vector (Y up), normalised here; sun_elevation_deg in [-90, 90];
 * sun_azimuth_deg any finite value; horizon_colour, zenith_colour, sun_colour -> linear RGB, components in
 * [0, CCL_SKY_GRADIENT_MAX_COLOUR]; sun_exponent > 0; output: see ccl_sky_gradient_output. Not validated here (ccl_sky_gradient_init validates). */
CCL_API ccl_vec3 ccl_sky_gradient_colour(ccl_vec3 direction, float sun_elevation_deg, float sun_azimuth_deg,
                                         ccl_vec3 horizon_colour, ccl_vec3 zenith_colour, ccl_vec3 sun_colour,
                                         float sun_exponent, ccl_sky_gradient_output output);

/* --- the sun through the atmosphere (the light of the cloudscape's sky lighting) ------------------------------------
 * Not in the thesis: Preetham, Shirley & Smits 1999, appendix A.1 ("sun attenuation"), reduced to its Rayleigh and
 * Angstrom aerosol terms at three wavelengths for R, G, B. The ozone, water-vapour and mixed-gas absorption bands of
 * the appendix are omitted: they carve narrow bands out of the spectrum and, sampled at three wavelengths, would
 * only add a near-constant factor per channel (ozone's Chappuis band dims G and R by a few per cent). */

/* Wavelengths [micrometres] at which ccl_sky_sun_attenuation evaluates R, G, B: near the peaks of the sRGB / CIE
 * colour-matching functions (red 0.60-0.70, green 0.55, blue 0.44-0.45). */
#define CCL_SKY_SUN_LAMBDA_R_UM 0.680f
#define CCL_SKY_SUN_LAMBDA_G_UM 0.550f
#define CCL_SKY_SUN_LAMBDA_B_UM 0.440f

/* Relative optical air mass of the path towards the sun, Kasten's formula as Preetham et al. 1999 (appendix A.1) use
 * it: m = 1 / (cos theta_s + 0.15 (93.885 - theta_s_deg)^-1.253), theta_s_deg = theta_s in degrees.
 * theta_s -> sun zenith angle [rad] in [0, pi/2]. Output m: 0.9995 at the zenith, ~1.74 at 55 deg, ~12.3 at 86 deg,
 * ~36.5 at the horizon (finite there, unlike the flat-Earth 1 / cos theta_s). */
CCL_API float ccl_sky_relative_air_mass(float theta_s);

/* Transmittance of the atmosphere towards the sun per channel (R, G, B at CCL_SKY_SUN_LAMBDA_*_UM):
 *   t(lambda) = exp(-0.008735 lambda^-4.08 m) exp(-beta lambda^-alpha m)
 * (Rayleigh, Angstrom aerosol), m = ccl_sky_relative_air_mass(theta_s), alpha = 1.3,
 * beta = 0.04608365822050 T - 0.04586025928522 (Preetham et al. 1999 appendix A.1; lambda in micrometres).
 * theta_s -> sun zenith angle [rad] in [0, pi/2]; turbidity -> T in [2, 10]. Output in (0, 1]^3, R >= G >= B (the
 * sun reddens as it sets): T = 2.5 at the zenith (0.855, 0.778, 0.637), at 86 deg (0.145, 0.045, 0.0039). */
CCL_API ccl_vec3 ccl_sky_sun_attenuation(float theta_s, float turbidity);

#ifdef __cplusplus
}
#endif

#endif /* CCLOUDS_SKY_H */
