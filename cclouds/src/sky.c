/* Sky models, vc §2.5 and §4.2. See cclouds/sky.h for the angle conventions, units and the horizon clamp. */
#include "cclouds/sky.h"
#include "internal.h"

#define SKY_HALF_PI_F 1.57079632679489662f  /* pi / 2 */
#define SKY_DEG2RAD_F 0.0174532925199432958f /* pi / 180 */
#define SKY_COS_THETA_MIN 0.01f              /* horizon clamp of cos(theta) (Radiance perezlum.cal), sky.h */

/* max(cos_theta, 0.01), keeping NaN */
static float clamp_cos_theta(float cos_theta)
{
    return (cos_theta < SKY_COS_THETA_MIN) ? SKY_COS_THETA_MIN : cos_theta;
}

/* Perez 2.36 from cos(theta), gamma and cos(gamma): the form every caller shares (the sky kernel has the cosines
 * from dot products and must not recompute them from the angles). */
static float perez_cg(float cos_theta, float gamma, float cos_gamma, float A, float B, float C, float D, float E)
{
    const float ct = clamp_cos_theta(cos_theta);
    return (1.0f + A * expf(B / ct)) * (1.0f + C * expf(D * gamma) + E * cos_gamma * cos_gamma);
}

static float perez_arr(float cos_theta, float gamma, float cos_gamma, const float c[5])
{
    return perez_cg(cos_theta, gamma, cos_gamma, c[0], c[1], c[2], c[3], c[4]);
}

float ccl_sky_turbidity(float t_m, float t_h)
{
    CCL_REQUIRE(!(t_m <= 0.0f) && !(t_h < 0.0f));
    /* vc-2.33 */
    return (t_m + t_h) / t_m;
}

/* the CIE clear-sky scattering indicatrix 0.91 + 10 exp(-3 g) + 0.45 cos^2 g */
static float cie_indicatrix(float g)
{
    const float c = cosf(g);
    return 0.91f + 10.0f * expf(-3.0f * g) + 0.45f * c * c;
}

float ccl_sky_cie_clear(float theta, float gamma, float theta_s, float Y_z)
{
    float num, den;
    CCL_REQUIRE(!(theta < 0.0f || theta > CCL_PI_F) && !(gamma < 0.0f || gamma > CCL_PI_F));
    CCL_REQUIRE(!(theta_s < 0.0f || theta_s > SKY_HALF_PI_F));
    /* vc-2.35: gradation 1 - exp(-0.32 / cos theta), 1 - exp(-0.32) at the zenith */
    num = cie_indicatrix(gamma) * (1.0f - expf(-0.32f / clamp_cos_theta(cosf(theta))));
    den = cie_indicatrix(theta_s) * (1.0f - expf(-0.32f));
    return (num / den) * Y_z;
}

float ccl_sky_perez(float theta, float gamma, float A, float B, float C, float D, float E)
{
    CCL_REQUIRE(!(theta < 0.0f || theta > CCL_PI_F) && !(gamma < 0.0f || gamma > CCL_PI_F));
    /* vc-2.36 */
    return perez_cg(cosf(theta), gamma, cosf(gamma), A, B, C, D, E);
}

float ccl_sky_perez_cie(float theta, float gamma, float A, float B, float C, float D, float E, ccl_variant variant)
{
    float ct, cg, sub;
    CCL_REQUIRE(!(theta < 0.0f || theta > CCL_PI_F) && !(gamma < 0.0f || gamma > CCL_PI_F));
    /* vc-2.37: corrected subtracts the constant exp(D pi/2); as printed exp(D gamma pi/2) */
    ct = clamp_cos_theta(cosf(theta));
    cg = cosf(gamma);
    sub = (variant == CCL_VARIANT_THESIS) ? expf(D * gamma * SKY_HALF_PI_F) : expf(D * SKY_HALF_PI_F);
    return (1.0f + A * expf(B / ct)) * (1.0f + C * (expf(D * gamma) - sub) + E * cg * cg);
}

float ccl_sky_perez_zenith_factor(float theta_s, float Y_z, float A, float B, float C, float D, float E)
{
    CCL_REQUIRE(!(theta_s < 0.0f || theta_s > SKY_HALF_PI_F));
    /* vc-4.2: Y_z / F(0, theta_s); at the zenith cos theta = 1 and gamma = theta_s */
    return Y_z / perez_cg(1.0f, theta_s, cosf(theta_s), A, B, C, D, E);
}

float ccl_sky_perez_normalized(float theta, float gamma, float theta_s, float Y_z, float A, float B, float C, float D,
                           float E)
{
    float f, f0;
    CCL_REQUIRE(!(theta < 0.0f || theta > CCL_PI_F) && !(gamma < 0.0f || gamma > CCL_PI_F));
    CCL_REQUIRE(!(theta_s < 0.0f || theta_s > SKY_HALF_PI_F));
    /* vc-2.38: F(theta, gamma) / F(0, theta_s) * Y_z */
    f = perez_cg(cosf(theta), gamma, cosf(gamma), A, B, C, D, E);
    f0 = perez_cg(1.0f, theta_s, cosf(theta_s), A, B, C, D, E);
    return (f / f0) * Y_z;
}

static float zenith_Y(float T, float theta_s, ccl_variant variant)
{
    /* vc-2.39: Preetham 4.0453 (corrected) or 6.0453 (as printed) */
    const float k = (variant == CCL_VARIANT_THESIS) ? 6.0453f : 4.0453f;
    const float chi = (4.0f / 9.0f - T / 120.0f) * (CCL_PI_F - 2.0f * theta_s);
    return (k * T - 4.9710f) * tanf(chi) - 0.2155f * T + 2.4192f;
}

float ccl_sky_preetham_zenith_x(float turbidity, float theta_s)
{
    const float T = turbidity, t = theta_s;
    float t2, t3, r0, r1, r2;
    CCL_REQUIRE(!(theta_s < 0.0f || theta_s > SKY_HALF_PI_F));
    /* vc-2.40: rows of M_x times [t^3 t^2 t 1], then [T^2 T 1] */
    t2 = t * t;
    t3 = t2 * t;
    r0 = 0.00166f * t3 - 0.00375f * t2 + 0.00209f * t;
    r1 = -0.02903f * t3 + 0.06377f * t2 - 0.03202f * t + 0.00394f;
    r2 = 0.11693f * t3 - 0.21196f * t2 + 0.06052f * t + 0.25886f;
    return T * T * r0 + T * r1 + r2;
}

float ccl_sky_preetham_zenith_y(float turbidity, float theta_s)
{
    const float T = turbidity, t = theta_s;
    float t2, t3, r0, r1, r2;
    CCL_REQUIRE(!(theta_s < 0.0f || theta_s > SKY_HALF_PI_F));
    /* vc-2.41 */
    t2 = t * t;
    t3 = t2 * t;
    r0 = 0.00275f * t3 - 0.00610f * t2 + 0.00317f * t;
    r1 = -0.04214f * t3 + 0.08970f * t2 - 0.04153f * t + 0.00516f;
    r2 = 0.15346f * t3 - 0.26756f * t2 + 0.06670f * t + 0.26688f;
    return T * T * r0 + T * r1 + r2;
}

ccl_vec3 ccl_sky_preetham_zenith(float turbidity, float theta_s, ccl_variant variant)
{
    ccl_vec3 xyY;
    CCL_REQUIRE(!(theta_s < 0.0f || theta_s > SKY_HALF_PI_F));
    xyY.x = ccl_sky_preetham_zenith_x(turbidity, theta_s);
    xyY.y = ccl_sky_preetham_zenith_y(turbidity, theta_s);
    xyY.z = zenith_Y(turbidity, theta_s, variant);
    return xyY;
}

void ccl_sky_preetham_perez_Y(float turbidity, float *out_A, float *out_B, float *out_C, float *out_D, float *out_E)
{
    const float T = turbidity;
    CCL_REQUIRE(out_A != NULL && out_B != NULL && out_C != NULL && out_D != NULL && out_E != NULL);
    /* vc-2.42 */
    *out_A = 0.1787f * T - 1.4630f;
    *out_B = -0.3554f * T + 0.4275f;
    *out_C = -0.0227f * T + 5.3251f;
    *out_D = 0.1206f * T - 2.5771f;
    *out_E = -0.0670f * T + 0.3703f;
}

void ccl_sky_preetham_perez_x(float turbidity, float *out_A, float *out_B, float *out_C, float *out_D, float *out_E)
{
    const float T = turbidity;
    CCL_REQUIRE(out_A != NULL && out_B != NULL && out_C != NULL && out_D != NULL && out_E != NULL);
    /* vc-2.43 */
    *out_A = -0.0193f * T - 0.2592f;
    *out_B = -0.0665f * T + 0.0008f;
    *out_C = -0.0004f * T + 0.2125f;
    *out_D = -0.0641f * T - 0.8989f;
    *out_E = -0.0033f * T + 0.0452f;
}

void ccl_sky_preetham_perez_y(float turbidity, float *out_A, float *out_B, float *out_C, float *out_D, float *out_E)
{
    const float T = turbidity;
    CCL_REQUIRE(out_A != NULL && out_B != NULL && out_C != NULL && out_D != NULL && out_E != NULL);
    /* vc-2.44 */
    *out_A = -0.0167f * T - 0.2608f;
    *out_B = -0.0950f * T + 0.0092f;
    *out_C = -0.0079f * T + 0.2102f;
    *out_D = -0.0441f * T - 1.6537f;
    *out_E = -0.0109f * T + 0.0529f;
}

ccl_vec3 ccl_sky_sun_direction(float elevation_deg, float azimuth_deg)
{
    ccl_vec3 s;
    float e, a, ce;
    CCL_REQUIRE(!(elevation_deg < -90.0f || elevation_deg > 90.0f));
    e = elevation_deg * SKY_DEG2RAD_F;
    a = azimuth_deg * SKY_DEG2RAD_F;
    ce = cosf(e);
    s.x = ce * sinf(a);
    s.y = sinf(e);
    s.z = -ce * cosf(a);
    return s;
}

/* The per-frame constants without validation: 2.42-2.44 -> 2.39-2.41 -> 4.2 (the order of
 * PreethamSkyModel::update). Shared by ccl_sky_preetham_init and ccl_sky_preetham. */
static ccl_preetham preetham_fill(float turbidity, float theta_s, float exposure, ccl_variant variant)
{
    ccl_preetham p;
    ccl_vec3 z;
    float zY, zx, zy;
    ccl_sky_preetham_perez_Y(turbidity, &p.perez_Y[0], &p.perez_Y[1], &p.perez_Y[2], &p.perez_Y[3], &p.perez_Y[4]);
    ccl_sky_preetham_perez_x(turbidity, &p.perez_x[0], &p.perez_x[1], &p.perez_x[2], &p.perez_x[3], &p.perez_x[4]);
    ccl_sky_preetham_perez_y(turbidity, &p.perez_y[0], &p.perez_y[1], &p.perez_y[2], &p.perez_y[3], &p.perez_y[4]);
    z = ccl_sky_preetham_zenith(turbidity, theta_s, variant);
    zx = z.x;
    zy = z.y;
    zY = z.z;
    p.zenith_Y = zY;
    p.zenith_x = zx;
    p.zenith_y = zy;
    p.factor_Y = ccl_sky_perez_zenith_factor(theta_s, zY, p.perez_Y[0], p.perez_Y[1], p.perez_Y[2], p.perez_Y[3],
                                         p.perez_Y[4]);
    p.factor_x = ccl_sky_perez_zenith_factor(theta_s, zx, p.perez_x[0], p.perez_x[1], p.perez_x[2], p.perez_x[3],
                                         p.perez_x[4]);
    p.factor_y = ccl_sky_perez_zenith_factor(theta_s, zy, p.perez_y[0], p.perez_y[1], p.perez_y[2], p.perez_y[3],
                                         p.perez_y[4]);
    p.turbidity = turbidity;
    p.theta_s = theta_s;
    p.exposure = exposure;
    p.variant = (int)variant;
    return p;
}

ccl_status ccl_sky_preetham_init(float turbidity, float theta_s, float exposure, ccl_variant variant, ccl_preetham *out)
{
    if (out == NULL) return CCL_EINVAL;
    if (!(turbidity >= (float)CCL_PREETHAM_TURBIDITY_MIN && turbidity <= (float)CCL_PREETHAM_TURBIDITY_MAX))
        return CCL_EINVAL;
    if (!(theta_s >= 0.0f && theta_s <= SKY_HALF_PI_F)) return CCL_EINVAL; /* sun below the horizon */
    if (!(exposure > 0.0f && isfinite(exposure))) return CCL_EINVAL;
    if (variant != CCL_VARIANT_CORRECTED && variant != CCL_VARIANT_THESIS) return CCL_EINVAL;
    *out = preetham_fill(turbidity, theta_s, exposure, variant);
    return CCL_OK;
}

ccl_vec3 ccl_sky_preetham_xyY(ccl_vec3 dir, ccl_vec3 sun, const ccl_preetham *p)
{
    ccl_vec3 c;
    float cos_g, gamma;
    CCL_REQUIRE(p != NULL);
    /* theta from cos theta = d_y (Y up), gamma = angle(d, s) */
    cos_g = dir.x * sun.x + dir.y * sun.y + dir.z * sun.z;
    if (cos_g > 1.0f) cos_g = 1.0f;
    if (cos_g < -1.0f) cos_g = -1.0f;
    gamma = acosf(cos_g);
    /* 2.36 x 4.2 = 2.38, per channel */
    c.x = p->factor_x * perez_arr(dir.y, gamma, cos_g, p->perez_x);
    c.y = p->factor_y * perez_arr(dir.y, gamma, cos_g, p->perez_y);
    c.z = p->factor_Y * perez_arr(dir.y, gamma, cos_g, p->perez_Y);
    return c;
}

ccl_vec3 ccl_sky_preetham_hdr(ccl_vec3 dir, ccl_vec3 sun, const ccl_preetham *p)
{
    CCL_REQUIRE(p != NULL);
    /* xyY -> XYZ (4.3) -> linear sRGB (4.4) */
    return ccl_colour_XYZ_to_linear_srgb(ccl_colour_xyY_to_XYZ(ccl_sky_preetham_xyY(dir, sun, p)),
                                         (ccl_variant)p->variant);
}

ccl_vec3 ccl_sky_preetham_rgb(ccl_vec3 dir, ccl_vec3 sun, const ccl_preetham *p)
{
    ccl_vec3 c;
    CCL_REQUIRE(p != NULL);
    c = ccl_sky_preetham_hdr(dir, sun, p);
    /* corrected: a channel outside the sRGB gamut (negative: e.g. the horizon's blue under a setting sun) is clipped
     * to 0, as 1 - exp(-k C) of a negative C is negative and reaches -Inf for a large exposure k */
    if (p->variant == CCL_VARIANT_CORRECTED) {
        c.x = c.x < 0.0f ? 0.0f : c.x; /* (a NaN stays NaN) */
        c.y = c.y < 0.0f ? 0.0f : c.y;
        c.z = c.z < 0.0f ? 0.0f : c.z;
    }
    /* 4.5 per channel */
    c.x = ccl_colour_tonemap_exp(c.x, p->exposure, (ccl_variant)p->variant);
    c.y = ccl_colour_tonemap_exp(c.y, p->exposure, (ccl_variant)p->variant);
    c.z = ccl_colour_tonemap_exp(c.z, p->exposure, (ccl_variant)p->variant);
    return c;
}

/* d / |d| in float, the same operations as the Warp twin */
static ccl_vec3 normalize3(ccl_vec3 d)
{
    const float l = sqrtf(d.x * d.x + d.y * d.y + d.z * d.z);
    d.x = d.x / l;
    d.y = d.y / l;
    d.z = d.z / l;
    return d;
}

static ccl_vec3 srgb_encode3(ccl_vec3 c)
{
    c.x = ccl_colour_srgb_encode(c.x);
    c.y = ccl_colour_srgb_encode(c.y);
    c.z = ccl_colour_srgb_encode(c.z);
    return c;
}

ccl_vec3 ccl_sky_preetham_colour(ccl_vec3 direction, float turbidity, float sun_elevation_deg,
                                 float sun_azimuth_deg, float exposure, ccl_variant variant,
                                 ccl_sky_preetham_output output)
{
    const float theta_s = (90.0f - sun_elevation_deg) * SKY_DEG2RAD_F;
    const ccl_preetham p = preetham_fill(turbidity, theta_s, exposure, variant);
    const ccl_vec3 sun = ccl_sky_sun_direction(sun_elevation_deg, sun_azimuth_deg);
    const ccl_vec3 d = normalize3(direction);
    if (output == CCL_SKY_PREETHAM_XYY) return ccl_sky_preetham_xyY(d, sun, &p);
    if (output == CCL_SKY_PREETHAM_HDR) return ccl_sky_preetham_hdr(d, sun, &p);
    if (output == CCL_SKY_PREETHAM_SRGB) return srgb_encode3(ccl_sky_preetham_rgb(d, sun, &p));
    return ccl_sky_preetham_rgb(d, sun, &p);
}

void ccl_sky_gradient_defaults(ccl_sky_gradient *out)
{
    CCL_REQUIRE(out != NULL);
    out->horizon[0] = 0.66f;
    out->horizon[1] = 0.78f;
    out->horizon[2] = 0.94f;
    out->zenith[0] = 0.16f;
    out->zenith[1] = 0.34f;
    out->zenith[2] = 0.72f;
    out->sun[0] = 1.0f;
    out->sun[1] = 0.9f;
    out->sun[2] = 0.7f;
    out->sun_exponent = 64.0f;
}

static int valid_colour(float v)
{
    return v >= 0.0f && v <= CCL_SKY_GRADIENT_MAX_COLOUR;
}

static int valid_colour3(ccl_vec3 c)
{
    return valid_colour(c.x) && valid_colour(c.y) && valid_colour(c.z);
}

ccl_status ccl_sky_gradient_init(ccl_vec3 horizon, ccl_vec3 zenith, ccl_vec3 sun, float sun_exponent,
                                 ccl_sky_gradient *out)
{
    if (out == NULL) return CCL_EINVAL;
    if (!(valid_colour3(horizon) && valid_colour3(zenith) && valid_colour3(sun))) return CCL_EINVAL;
    if (!(sun_exponent > 0.0f && isfinite(sun_exponent))) return CCL_EINVAL;
    out->horizon[0] = horizon.x;
    out->horizon[1] = horizon.y;
    out->horizon[2] = horizon.z;
    out->zenith[0] = zenith.x;
    out->zenith[1] = zenith.y;
    out->zenith[2] = zenith.z;
    out->sun[0] = sun.x;
    out->sun[1] = sun.y;
    out->sun[2] = sun.z;
    out->sun_exponent = sun_exponent;
    return CCL_OK;
}

ccl_vec3 ccl_sky_gradient_rgb(ccl_vec3 dir, ccl_vec3 sun, const ccl_sky_gradient *g)
{
    ccl_vec3 r;
    float t, c, s;
    CCL_REQUIRE(g != NULL);
    /* vc-A28: lerp(horizon, zenith, clamp(d_y, 0, 1)) + sun * max(d . s, 0)^n */
    t = dir.y;
    if (t < 0.0f) t = 0.0f;
    if (t > 1.0f) t = 1.0f;
    c = dir.x * sun.x + dir.y * sun.y + dir.z * sun.z;
    /* The dot of two unit vectors can round to 1 + 2^-23; c^n then overflows for n above ~7e8: clamp to [0, 1]. */
    if (c < 0.0f) c = 0.0f;
    if (c > 1.0f) c = 1.0f;
    s = powf(c, g->sun_exponent);
    r.x = g->horizon[0] + t * (g->zenith[0] - g->horizon[0]) + g->sun[0] * s;
    r.y = g->horizon[1] + t * (g->zenith[1] - g->horizon[1]) + g->sun[1] * s;
    r.z = g->horizon[2] + t * (g->zenith[2] - g->horizon[2]) + g->sun[2] * s;
    return r;
}

ccl_vec3 ccl_sky_gradient_colour(ccl_vec3 direction, float sun_elevation_deg, float sun_azimuth_deg,
                                 ccl_vec3 horizon_colour, ccl_vec3 zenith_colour, ccl_vec3 sun_colour,
                                 float sun_exponent, ccl_sky_gradient_output output)
{
    ccl_sky_gradient g;
    ccl_vec3 c;
    g.horizon[0] = horizon_colour.x;
    g.horizon[1] = horizon_colour.y;
    g.horizon[2] = horizon_colour.z;
    g.zenith[0] = zenith_colour.x;
    g.zenith[1] = zenith_colour.y;
    g.zenith[2] = zenith_colour.z;
    g.sun[0] = sun_colour.x;
    g.sun[1] = sun_colour.y;
    g.sun[2] = sun_colour.z;
    g.sun_exponent = sun_exponent;
    c = ccl_sky_gradient_rgb(normalize3(direction), ccl_sky_sun_direction(sun_elevation_deg, sun_azimuth_deg), &g);
    return output == CCL_SKY_GRADIENT_SRGB ? srgb_encode3(c) : c;
}

/* --- the sun through the atmosphere (Preetham et al. 1999, appendix A.1) ------------------------------------------- */

float ccl_sky_relative_air_mass(float theta_s)
{
    CCL_REQUIRE(!(theta_s < 0.0f || theta_s > 1.5707964f));
    /* Kasten's formula with theta_s in degrees, as Preetham's appendix A.1 */
    return 1.0f / (cosf(theta_s) + 0.15f * powf(93.885f - theta_s * 57.2957795f, -1.253f));
}

/* exp(-0.008735 lambda^-4.08 m) exp(-beta lambda^-alpha m): Rayleigh and Angstrom terms of one wavelength */
static float sun_transmittance(float lambda_um, float m, float beta)
{
    const float rayleigh = expf(-(0.008735f * powf(lambda_um, -4.08f)) * m);
    const float aerosol = expf(-(beta * powf(lambda_um, -1.3f)) * m);
    return rayleigh * aerosol;
}

ccl_vec3 ccl_sky_sun_attenuation(float theta_s, float turbidity)
{
    const float m = ccl_sky_relative_air_mass(theta_s);
    const float beta = 0.04608365822050f * turbidity - 0.04586025928522f; /* Angstrom turbidity, alpha = 1.3 */
    ccl_vec3 t;
    t.x = sun_transmittance(CCL_SKY_SUN_LAMBDA_R_UM, m, beta);
    t.y = sun_transmittance(CCL_SKY_SUN_LAMBDA_G_UM, m, beta);
    t.z = sun_transmittance(CCL_SKY_SUN_LAMBDA_B_UM, m, beta);
    return t;
}
