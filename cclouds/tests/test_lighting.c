/* C unit tests of the cloudscape's sky lighting: the sun through the atmosphere (sky.h, Preetham et al. 1999
 * appendix A.1: ccl_sky_relative_air_mass, ccl_sky_sun_attenuation) against the closed forms evaluated in double;
 * cloudscape.h: the multiple-scattering / dual-lobe energy (ccl_cloudscape_energy) against vc-2.31 and its sum, the
 * per-frame light setup (ccl_cloudscape_light) against the hemispherical means of a gradient sky, the lit ground
 * (ccl_cloudscape_ground) in clear air and under an opaque layer, and the check of the new parameters. */
#include "cclouds/clouds.h"
#include "cclouds/cloudscape.h"
#include "cclouds/phase.h"
#include "cclouds/sky.h"
#include "ccl_test.h"

#include <string.h>

#define PI_D 3.14159265358979323846

static double air_mass_d(double theta_s)
{
    return 1.0 / (cos(theta_s) + 0.15 * pow(93.885 - theta_s * 180.0 / PI_D, -1.253));
}

static double attenuation_d(double theta_s, double T, double lambda_um)
{
    const double m = air_mass_d(theta_s), beta = 0.04608365822050 * T - 0.04586025928522;
    return exp(-0.008735 * pow(lambda_um, -4.08) * m) * exp(-beta * pow(lambda_um, -1.3) * m);
}

static void test_air_mass_closed_form(void)
{
    static const double deg[] = {0.0, 30.0, 60.0, 80.0, 86.0, 89.0};
    size_t i;
    for (i = 0; i < sizeof deg / sizeof deg[0]; ++i) {
        const float th = (float)(deg[i] * PI_D / 180.0);
        /* float32 cos, pow and one division: a few ulp, x 8 for the sensitivity near the horizon */
        CCL_CHECK_REL(ccl_sky_relative_air_mass(th), air_mass_d((double)th), 1e-5);
    }
    /* the zenith and horizon values of Kasten's formula */
    CCL_CHECK_CLOSE(ccl_sky_relative_air_mass(0.0f), 0.99949, 1e-5);
    CCL_CHECK_CLOSE(ccl_sky_relative_air_mass(1.5707964f), 36.51, 0.01);
}

static void test_sun_attenuation_closed_form(void)
{
    static const double deg[] = {0.0, 30.0, 55.0, 70.0, 86.0, 90.0};
    static const double turb[] = {2.0, 2.5, 6.0, 10.0};
    size_t i, j;
    for (i = 0; i < sizeof deg / sizeof deg[0]; ++i)
        for (j = 0; j < sizeof turb / sizeof turb[0]; ++j) {
            const float th = i + 1 == sizeof deg / sizeof deg[0] ? 1.5707964f : (float)(deg[i] * PI_D / 180.0);
            const ccl_vec3 t = ccl_sky_sun_attenuation(th, (float)turb[j]);
            /* exp(-x), x = (Rayleigh + aerosol) m <= 54 (T = 10, B channel at the horizon): the relative error of
             * exp(-x) is x times that of x. m's is at most ~3e-6: near the horizon 93.885 - theta_deg cancels (the
             * float32 theta_deg ~ 90 is exact to 4e-6 deg, 1e-6 of 3.885, times the exponent 1.253), plus a few ulp
             * of cos, pow and the products. Hence 2e-5 + 3e-6 x. */
            const double r = attenuation_d((double)th, turb[j], 0.68), g = attenuation_d((double)th, turb[j], 0.55),
                         b = attenuation_d((double)th, turb[j], 0.44);
            CCL_CHECK_REL(t.x, r, 2e-5 - 3e-6 * log(r));
            CCL_CHECK_REL(t.y, g, 2e-5 - 3e-6 * log(g));
            CCL_CHECK_REL(t.z, b, 2e-5 - 3e-6 * log(b));
        }
}

static void test_sun_reddens_towards_the_horizon(void)
{
    float prev_rb = 0.0f;
    int k;
    for (k = 0; k <= 18; ++k) {
        const float th = (float)k * 0.0872665f; /* 0 .. 90 deg in 5 deg steps */
        const ccl_vec3 t = ccl_sky_sun_attenuation(th < 1.5707964f ? th : 1.5707964f, 2.5f);
        CCL_CHECK(t.x >= t.y && t.y >= t.z && t.z > 0.0f && t.x <= 1.0f);
        CCL_CHECK(t.x / t.z >= prev_rb); /* red over blue grows as the sun sinks */
        prev_rb = t.x / t.z;
    }
    /* more haze, less light */
    CCL_CHECK(ccl_sky_sun_attenuation(0.5f, 5.0f).y < ccl_sky_sun_attenuation(0.5f, 2.0f).y);
}

static void test_energy_one_octave_one_lobe_is_vc_2_31(void)
{
    ccl_cloudscape_params p;
    int i, j, k;
    ccl_cloudscape_params_default(&p);
    p.ms_octaves = 1;
    p.silver_weight = 0.0f;
    p.powder = 1; /* vc-2.31 as printed (the default is off) */
    for (i = 0; i <= 20; ++i)
        for (j = 0; j <= 10; ++j)
            for (k = 0; k < 3; ++k) {
                const float d = (float)i * 0.25f, c = -1.0f + 0.2f * (float)j, a = 1.0f + (float)k;
                p.g = -0.3f + 0.3f * (float)k;
                CCL_CHECK(ccl_cloudscape_energy(&p, d, a, c) == ccl_clouds_energy(d, a, c, p.g)); /* bit for bit */
            }
}

static double hg_d(double c, double g) { return (1.0 - g * g) / (4.0 * PI_D * pow(1.0 + g * g - 2.0 * g * c, 1.5)); }

static void test_energy_octave_sum_closed_form(void)
{
    ccl_cloudscape_params p;
    int n, j;
    ccl_cloudscape_params_default(&p);
    p.powder = 1; /* the closed form below has the powder term */
    p.g = 0.3f;
    p.silver_g = 0.85f;
    p.silver_weight = 0.25f;
    p.ms_a = 0.6f;
    p.ms_b = 0.45f;
    p.ms_c = 0.7f;
    p.ms_depth = 0.0f; /* the octave sum alone: no weight by the optical depth towards the sun */
    for (n = 1; n <= CCL_CLOUDSCAPE_MAX_MS_OCTAVES; ++n)
        for (j = 0; j <= 8; ++j) {
            const double c = -1.0 + 0.25 * j, d = 1.3, a = 1.4;
            double e = 0.0;
            int i;
            p.ms_octaves = n;
            for (i = 0; i < n; ++i) {
                const double ai = pow(0.6, i), bi = pow(0.45, i), ci = pow(0.7, i);
                const double phase = 0.75 * hg_d(c, 0.3 * ci) + 0.25 * hg_d(c, 0.85 * ci);
                e += bi * exp(-d * ai * a) * phase * (1.0 - exp(-2.0 * d * ai));
            }
            /* float32 terms of a few ulp each, the HG peak of g = 0.85 amplifying its argument's rounding ~10x */
            CCL_CHECK_REL(ccl_cloudscape_energy(&p, 1.3f, 1.4f, (float)c), e, 1e-5);
        }
}

static void test_energy_octaves_brighten_thick_clouds_most(void)
{
    /* each octave adds light, and relatively more where the optical depth towards the sun is large */
    ccl_cloudscape_params p1, p3;
    float prev = 0.0f;
    int i;
    ccl_cloudscape_params_default(&p1);
    p1.ms_octaves = 1;
    p3 = p1;
    p3.ms_octaves = 3;
    for (i = 1; i <= 40; ++i) {
        const float d = 0.25f * (float)i, e1 = ccl_cloudscape_energy(&p1, d, 1.4f, 0.3f),
                    e3 = ccl_cloudscape_energy(&p3, d, 1.4f, 0.3f);
        CCL_CHECK(e3 > e1);
        CCL_CHECK(e3 / e1 >= prev);
        prev = e3 / e1;
    }
    CCL_CHECK(prev > 10.0f); /* deep inside, the halved extinction of the octaves dominates */
}

static void test_light_thesis_is_an_unchanged_copy(void)
{
    ccl_cloudscape_params p, out;
    ccl_cloudscape_sky sky;
    memset(&sky, 0, sizeof sky);
    sky.kind = CCL_SKY_GRADIENT;
    ccl_sky_gradient_defaults(&sky.gradient);
    sky.sun[1] = 1.0f;
    ccl_cloudscape_params_default(&p);
    p.lighting = CCL_LIGHTING_THESIS;
    memset(&out, 0xab, sizeof out);
    ccl_cloudscape_light(&p, &sky, &out);
    CCL_CHECK(memcmp(&p, &out, sizeof p) == 0);
}

static void test_light_hemisphere_means_of_a_gradient_sky(void)
{
    /* gradient sky without its sun term: L(d) = h + (z - h) d.y; over the upper hemisphere the solid-angle mean of
     * d.y is 1/2 and the cosine-weighted mean 2/3 */
    static const float h[3] = {0.6f, 0.7f, 0.9f}, z[3] = {0.1f, 0.3f, 0.7f};
    ccl_cloudscape_params p, out;
    ccl_cloudscape_sky sky;
    ccl_vec3 hv, zv, sun0, att;
    int c;
    memset(&sky, 0, sizeof sky);
    hv.x = h[0]; hv.y = h[1]; hv.z = h[2];
    zv.x = z[0]; zv.y = z[1]; zv.z = z[2];
    sun0.x = sun0.y = sun0.z = 0.0f;
    CCL_CHECK(ccl_sky_gradient_init(hv, zv, sun0, 64.0f, &sky.gradient) == CCL_OK);
    sky.kind = CCL_SKY_GRADIENT;
    sky.sun[0] = 0.0f;
    sky.sun[1] = 0.5f; /* 30 degrees up */
    sky.sun[2] = -0.8660254f;
    ccl_cloudscape_params_default(&p);
    p.ambient_ground_weight = 0.0f; /* the sky's means alone, without the lit ground's share */
    ccl_cloudscape_light(&p, &sky, &out);
    att = ccl_sky_sun_attenuation(acosf(0.5f), p.turbidity);
    CCL_CHECK(out.sun_colour[0] == p.sun_intensity * att.x);
    CCL_CHECK(out.sun_colour[1] == p.sun_intensity * att.y);
    CCL_CHECK(out.sun_colour[2] == p.sun_intensity * att.z);
    {
        /* the documented quadrature in double: midpoints of 8 zenith-angle cells, weights sin and sin cos (the
         * azimuth cells drop out of a sky that depends on d.y only) */
        double sw = 0.0, swc = 0.0, swcc = 0.0, m1, m2;
        int i;
        for (i = 0; i < CCL_CLOUDSCAPE_SKY_THETA_CELLS; ++i) {
            const double th = (i + 0.5) * (PI_D / 2.0) / CCL_CLOUDSCAPE_SKY_THETA_CELLS;
            sw += sin(th);
            swc += sin(th) * cos(th);
            swcc += sin(th) * cos(th) * cos(th);
        }
        m1 = swc / sw;   /* mean of d.y over the hemisphere: 1/2 exactly, 0.50242 by the quadrature */
        m2 = swcc / swc; /* cosine-weighted mean: 2/3 exactly, 0.66561 by the quadrature */
        CCL_CHECK(fabs(m1 - 0.5) < 2.5e-3 && fabs(m2 - 2.0 / 3.0) < 1.1e-3);
        for (c = 0; c < 3; ++c) {
            /* float32 sums of 128 terms: a few 1e-7 relative */
            CCL_CHECK_REL(out.ambient_top[c], (double)h[c] + (double)(z[c] - h[c]) * m1, 2e-6);
            CCL_CHECK_REL(out.ambient_ground[c], (double)h[c] + (double)(z[c] - h[c]) * m2, 2e-6);
            CCL_CHECK(out.ambient_bottom[c] == p.ambient_bottom_ratio * out.ambient_top[c]);
        }
    }
    /* nothing else changes */
    memcpy(out.sun_colour, p.sun_colour, sizeof p.sun_colour);
    memcpy(out.ambient_top, p.ambient_top, sizeof p.ambient_top);
    memcpy(out.ambient_bottom, p.ambient_bottom, sizeof p.ambient_bottom);
    memcpy(out.ambient_ground, p.ambient_ground, sizeof p.ambient_ground);
    CCL_CHECK(memcmp(&p, &out, sizeof p) == 0);
    /* a constant sky gives its value (to rounding) */
    CCL_CHECK(ccl_sky_gradient_init(hv, hv, sun0, 64.0f, &sky.gradient) == CCL_OK);
    ccl_cloudscape_light(&p, &sky, &p); /* out may alias p */
    for (c = 0; c < 3; ++c) {
        CCL_CHECK_REL(p.ambient_top[c], h[c], 1e-6);
        CCL_CHECK_REL(p.ambient_ground[c], h[c], 1e-6);
    }
}

/* Textures of one constant texel value each (4^3 / 4^2 RGBA). */
static float base_tex[4 * 4 * 4 * 4], detail_tex[4 * 4 * 4 * 4], curl_tex[4 * 4 * 4], weather_tex[4 * 4 * 4];

static ccl_cloud_textures constant_textures(float coverage)
{
    ccl_cloud_textures t;
    int i;
    for (i = 0; i < 4 * 4 * 4 * 4; ++i) {
        base_tex[i] = 1.0f;
        detail_tex[i] = 0.0f;
    }
    for (i = 0; i < 4 * 4 * 4; ++i) {
        curl_tex[i] = 0.0f;
        weather_tex[i] = (i % 4 == 0) ? coverage : (i % 4 == 2 ? 1.0f : 0.0f); /* R coverage, B type cumulus */
    }
    memset(&t, 0, sizeof t);
    t.base = base_tex;
    t.base_size = 4;
    t.detail = detail_tex;
    t.detail_size = 4;
    t.curl = curl_tex;
    t.curl_size = 4;
    t.weather = weather_tex;
    t.weather_size = 4;
    return t;
}

static void test_ground_clear_and_under_an_opaque_layer(void)
{
    ccl_cloudscape_params p;
    ccl_cloud_textures t;
    ccl_vec3 point, sun;
    float rgb[3], shadow;
    int c;
    ccl_cloudscape_params_default(&p);
    p.sun_colour[0] = 10.0f;
    p.sun_colour[1] = 8.0f;
    p.sun_colour[2] = 6.0f;
    p.ambient_ground[0] = 0.3f;
    p.ambient_ground[1] = 0.4f;
    p.ambient_ground[2] = 0.5f;
    point = p.layer.centre;
    point.y += p.layer.r_earth; /* on the ground under the centre's zenith */
    sun.x = 0.6f;
    sun.y = 0.8f;
    sun.z = 0.0f;
    /* clear air: sun x cos / pi + sky, times the albedo */
    t = constant_textures(0.0f);
    ccl_cloudscape_ground(&p, &t, point, sun, rgb, &shadow);
    CCL_CHECK(shadow == 1.0f);
    for (c = 0; c < 3; ++c)
        CCL_CHECK_REL(rgb[c], (double)p.ground_albedo[c] * ((double)p.sun_colour[c] * 0.8 / PI_D +
                                                            (double)p.ambient_ground[c]), 1e-6);
    /* a layer covered everywhere: the sun is blocked, the sky light remains */
    t = constant_textures(1.0f);
    ccl_cloudscape_ground(&p, &t, point, sun, rgb, &shadow);
    CCL_CHECK(shadow < 1e-6f);
    for (c = 0; c < 3; ++c) CCL_CHECK_REL(rgb[c], p.ground_albedo[c] * p.ambient_ground[c], 1e-5);
    /* the sun below the ground's horizon: no sun, no shadow ray */
    sun.x = 0.0f;
    sun.y = -1.0f;
    ccl_cloudscape_ground(&p, &t, point, sun, rgb, &shadow);
    CCL_CHECK(shadow == 1.0f);
    for (c = 0; c < 3; ++c) CCL_CHECK(rgb[c] == p.ground_albedo[c] * (p.sun_colour[c] * 0.0f + p.ambient_ground[c]));
}

static void test_check_names_the_lighting_fields(void)
{
    ccl_cloudscape_params p;
    ccl_cloud_textures t = constant_textures(0.5f);
    ccl_cloudscape_sky sky;
    const char *field = NULL;
    memset(&sky, 0, sizeof sky);
    sky.kind = CCL_SKY_GRADIENT;
    ccl_sky_gradient_defaults(&sky.gradient);
    sky.sun[1] = 1.0f;
    ccl_cloudscape_params_default(&p);
    CCL_CHECK(ccl_cloudscape_check(&p, &t, &sky, &field) == CCL_OK);
#define BAD(stmt, name) \
    do { \
        ccl_cloudscape_params q = p; \
        stmt; \
        CCL_CHECK(ccl_cloudscape_check(&q, &t, &sky, &field) == CCL_EINVAL && field && strcmp(field, name) == 0); \
    } while (0)
    BAD(q.lighting = 2, "lighting");
    BAD(q.sun_intensity = -1.0f, "sun_intensity");
    BAD(q.sun_intensity = NAN, "sun_intensity");
    BAD(q.turbidity = 1.5f, "turbidity");
    BAD(q.ambient_bottom_ratio = 1.5f, "ambient_bottom_ratio");
    BAD(q.ambient_ground[1] = -0.1f, "ambient_ground");
    BAD(q.ground_albedo[2] = 1.1f, "ground_albedo");
    BAD(q.aerial_km = INFINITY, "aerial_km");
    BAD(q.aerial_height_km = -1.0f, "aerial_height_km");
    BAD(q.ms_octaves = 0, "ms_octaves");
    BAD(q.ms_octaves = CCL_CLOUDSCAPE_MAX_MS_OCTAVES + 1, "ms_octaves");
    BAD(q.ms_a = 1.5f, "ms_a");
    BAD(q.ms_b = -0.5f, "ms_b");
    BAD(q.ms_c = NAN, "ms_c");
    BAD(q.silver_g = 1.0f, "silver_g");
    BAD(q.silver_weight = 1.01f, "silver_weight");
    BAD(q.ms_view = -1.0f, "ms_view");
    BAD(q.ms_view = NAN, "ms_view");
    BAD(q.ms_view_trans = 0.0f, "ms_view_trans");
    BAD(q.ambient_aniso = 1.5f, "ambient_aniso");
    BAD(q.ms_slab = -1.0f, "ms_slab");
    BAD(q.ms_slab = NAN, "ms_slab");
    BAD(q.ms_slab_mu = 4.5f, "ms_slab_mu");
    BAD(q.ms_slab_far = 1.5f, "ms_slab_far");
    /* the march's parameters of this renderer: the exit's fill, the light interpolation, the far light sample's
     * distance (each factor finite, their product too large: its weight x 0 was a NaN pixel, found by fuzzing) */
    BAD(q.exit_fill = 2, "exit_fill");
    BAD(q.light_interp = -1.0f, "light_interp");
    BAD(q.light_interp = INFINITY, "light_interp");
    BAD((q.light_step_km = 2.0e34f, q.light_far_factor = 1.7e7f), "light_far_factor");
    BAD(q.light_far_factor = 2.1e6f, "light_far_factor"); /* 2.1e6 x 5 x 0.1 km > 10^6 km */
    /* the product small, the factor near FLT_MAX: (factor - 1) x 5 overflowed (found by fuzzing) */
    BAD((q.light_step_km = 1.0e-39f, q.light_far_factor = 3.0e38f), "light_far_factor");
    BAD(q.light_far_factor = 1.01e6f, "light_far_factor");
#undef BAD
}

/* vc-x-ms-view and vc-x-ambient-aniso against their closed forms in double, and their limits (their defaults:
 * tests/clouds/test_default_lighting.py) */
static void test_view_weights_closed_form(void)
{
    int i;
    for (i = 0; i <= 20; ++i) {
        const double T = i / 20.0, mu = -1.0 + i / 10.0;
        const double wv = 1.0 + 3.0 * fmax(1.0 - T / 0.3, 0.0);
        CCL_CHECK(fabs((double)ccl_cloudscape_ms_view((float)T, 3.0f, 0.3f) - wv) <= 1e-6 * wv);
        CCL_CHECK(ccl_cloudscape_ms_view((float)T, 0.0f, 0.3f) == 1.0f);
        CCL_CHECK(fabs((double)ccl_cloudscape_ambient_aniso((float)mu, 0.8f, 0.5f) - (1.0 + 0.5 * mu * 0.8)) <= 1e-6);
        CCL_CHECK(ccl_cloudscape_ambient_aniso((float)mu, 0.8f, 0.0f) == 1.0f);
    }
    CCL_CHECK(ccl_cloudscape_ms_view(0.0f, 3.0f, 0.3f) == 4.0f && ccl_cloudscape_ms_view(0.3f, 3.0f, 0.3f) == 1.0f);
    CCL_CHECK(ccl_cloudscape_ambient_aniso(-1.0f, 1.0f, 0.4f) == 0.6f);
    CCL_CHECK(ccl_cloudscape_ambient_aniso(0.7f, 0.0f, 1.0f) == 1.0f);
}

/* vc-x-ms-slab against its closed form in double, and its limits (its defaults: tests/clouds/test_default_lighting.py) */
static void test_ms_slab_closed_form(void)
{
    int i, j;
    for (i = 0; i <= 20; ++i) {
        const double mu0 = -0.5 + i / 13.0 > 1.0 ? 1.0 : -0.5 + i / 13.0;
        for (j = 0; j <= 10; ++j) {
            const double d = 0.7 * j, T = exp(-0.4 * (10 - j) * (i % 3));
            const double tv = -log(T), r = d + tv > 0.0 ? d / (d + tv) : 0.0;
            const double w = 1.8 * pow(fmax(mu0, 0.0), 0.5) * (1.0 - 0.67 * r);
            const float got = ccl_cloudscape_ms_slab((float)mu0, (float)d, (float)T, 1.8f, 0.5f, 0.67f);
            CCL_CHECK(fabs((double)got - w) <= 1e-5 * (1.0 + w));
            CCL_CHECK(ccl_cloudscape_ms_slab((float)mu0, (float)d, (float)T, 0.0f, 0.5f, 0.67f) == 1.0f);
        }
    }
    /* the sun at the zenith, no weight by place: k; the sun at or below the horizon: 0; p = 0: no elevation term */
    CCL_CHECK(ccl_cloudscape_ms_slab(1.0f, 3.0f, 0.5f, 2.0f, 1.0f, 0.0f) == 2.0f);
    CCL_CHECK(ccl_cloudscape_ms_slab(0.0f, 3.0f, 0.5f, 2.0f, 0.5f, 0.5f) == 0.0f);
    CCL_CHECK(ccl_cloudscape_ms_slab(-0.3f, 3.0f, 0.5f, 2.0f, 0.5f, 0.5f) == 0.0f);
    CCL_CHECK(ccl_cloudscape_ms_slab(0.2f, 3.0f, 0.5f, 2.0f, 0.0f, 0.0f) == 2.0f);
    /* nothing towards the sun (the lit side, r = 0): k mu0^p; nothing back to the eye (r = 1): k mu0^p (1 - s);
     * neither (r = 0 by definition) and an opaque view in front (tau_v = -ln 1e-30) stay finite */
    CCL_CHECK(ccl_cloudscape_ms_slab(0.25f, 0.0f, 0.3f, 1.0f, 0.5f, 0.6f) == 0.5f);
    CCL_CHECK(fabsf(ccl_cloudscape_ms_slab(0.25f, 5.0f, 1.0f, 1.0f, 0.5f, 0.6f) - 0.2f) <= 1e-6f);
    CCL_CHECK(ccl_cloudscape_ms_slab(0.25f, 0.0f, 1.0f, 1.0f, 0.5f, 0.6f) == 0.5f);
    CCL_CHECK(isfinite(ccl_cloudscape_ms_slab(0.5f, 1.0e6f, 0.0f, 1000.0f, 4.0f, 1.0f)));
}

int main(void)
{
    CCL_RUN(test_air_mass_closed_form);
    CCL_RUN(test_ms_slab_closed_form);
    CCL_RUN(test_sun_attenuation_closed_form);
    CCL_RUN(test_sun_reddens_towards_the_horizon);
    CCL_RUN(test_energy_one_octave_one_lobe_is_vc_2_31);
    CCL_RUN(test_energy_octave_sum_closed_form);
    CCL_RUN(test_energy_octaves_brighten_thick_clouds_most);
    CCL_RUN(test_light_thesis_is_an_unchanged_copy);
    CCL_RUN(test_light_hemisphere_means_of_a_gradient_sky);
    CCL_RUN(test_ground_clear_and_under_an_opaque_layer);
    CCL_RUN(test_check_names_the_lighting_fields);
    CCL_RUN(test_view_weights_closed_form);
    return ccl_test_report();
}
