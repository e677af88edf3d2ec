/* C unit tests of cclouds/phase.h: closed forms, normalization (vc-2.8), mean cosine (vc-2.14), NaN propagation. */
#include "cclouds/phase.h"
#include "ccl_test.h"

#define PI_D 3.14159265358979323846

/* Integral over the sphere of p(cos theta): 2 pi * int_{-1}^{1} p(mu) dmu * mu^moment, composite Simpson in double. */
static double sphere_integral(float (*p)(float, float), float param, int moment)
{
    const int n = 20000; /* even */
    double h = 2.0 / n, sum = 0.0;
    int i;
    for (i = 0; i <= n; ++i) {
        double mu = -1.0 + i * h;
        double w = (i == 0 || i == n) ? 1.0 : (i % 2 ? 4.0 : 2.0);
        double f = (double)p((float)mu, param);
        if (moment) f *= mu;
        sum += w * f;
    }
    return 2.0 * PI_D * sum * h / 3.0;
}

static float hg(float mu, float g) { return ccl_phase_hg(mu, g); }
static float rayleigh(float mu, float unused) { (void)unused; return ccl_phase_rayleigh(mu); }
static float schlick(float mu, float k) { return ccl_phase_schlick(mu, k, CCL_VARIANT_CORRECTED); }
static float schlick_thesis(float mu, float k) { return ccl_phase_schlick(mu, k, CCL_VARIANT_THESIS); }

static void test_phase_isotropic_value(void)
{
    CCL_CHECK_REL(ccl_phase_isotropic(), 1.0 / (4.0 * PI_D), 1e-7);
}

static void test_phase_rayleigh_closed_form(void)
{
    CCL_CHECK_REL(ccl_phase_rayleigh(0.0f), 3.0 / (16.0 * PI_D), 1e-6);
    CCL_CHECK_REL(ccl_phase_rayleigh(1.0f), 3.0 / (8.0 * PI_D), 1e-6);
    CCL_CHECK_REL(ccl_phase_rayleigh(-1.0f), 3.0 / (8.0 * PI_D), 1e-6);
    CCL_CHECK_REL(sphere_integral(rayleigh, 0.0f, 0), 1.0, 1e-5);
    CCL_CHECK_CLOSE(sphere_integral(rayleigh, 0.0f, 1), 0.0, 1e-6);
}

static void test_phase_hg_normalized_and_mean_cosine(void)
{
    static const float gs[] = {-0.9f, -0.5f, 0.0f, 0.3f, 0.76f, 0.9f};
    size_t i;
    for (i = 0; i < sizeof gs / sizeof gs[0]; ++i) {
        CCL_CHECK_REL(sphere_integral(hg, gs[i], 0), 1.0, 1e-4);
        CCL_CHECK_CLOSE(sphere_integral(hg, gs[i], 1), gs[i], 1e-4);
    }
}

static void test_phase_hg_closed_form(void)
{
    /* forward peak (1+g)/(4 pi (1-g)^2), backward (1-g)/(4 pi (1+g)^2) */
    const double g = 0.6;
    CCL_CHECK_REL(ccl_phase_hg(1.0f, 0.6f), (1 + g) / (4 * PI_D * (1 - g) * (1 - g)), 1e-5);
    CCL_CHECK_REL(ccl_phase_hg(-1.0f, 0.6f), (1 - g) / (4 * PI_D * (1 + g) * (1 + g)), 1e-5);
    CCL_CHECK_REL(ccl_phase_hg(0.3f, 0.0f), 1.0 / (4 * PI_D), 1e-6);
}

static void test_phase_schlick_variants(void)
{
    CCL_CHECK_REL(sphere_integral(schlick, 0.7f, 0), 1.0, 1e-4);
    CCL_CHECK_REL(sphere_integral(schlick_thesis, 0.7f, 0), 1.0, 1e-4);
    /* corrected: k > 0 peaks forward; printed form peaks backward (spec error index item 2) */
    CCL_CHECK(ccl_phase_schlick(1.0f, 0.7f, CCL_VARIANT_CORRECTED) > ccl_phase_schlick(-1.0f, 0.7f, CCL_VARIANT_CORRECTED));
    CCL_CHECK(ccl_phase_schlick(1.0f, 0.7f, CCL_VARIANT_THESIS) < ccl_phase_schlick(-1.0f, 0.7f, CCL_VARIANT_THESIS));
    CCL_CHECK_REL(ccl_phase_schlick(0.25f, 0.5f, CCL_VARIANT_THESIS), ccl_phase_schlick(-0.25f, 0.5f, CCL_VARIANT_CORRECTED), 1e-7);
    CCL_CHECK(sphere_integral(schlick, 0.7f, 1) > 0.0);
}

static void test_schlick_k_values(void)
{
    CCL_CHECK_CLOSE(ccl_phase_schlick_k(0.0f), 0.0, 0.0);
    CCL_CHECK_REL(ccl_phase_schlick_k(1.0f), 1.0, 1e-6);
    CCL_CHECK_REL(ccl_phase_schlick_k(-1.0f), -1.0, 1e-6);
    CCL_CHECK_REL(ccl_phase_schlick_k(0.5f), 0.775 - 0.06875, 1e-6);
    CCL_CHECK(ccl_phase_schlick_k(0.9692f) > 1.0f); /* the overshoot noted in the spec for 2.16 */
}

static void test_phase_nan_propagates(void)
{
    float nan = (float)NAN;
    CCL_CHECK(isnan(ccl_phase_rayleigh(nan)));
    CCL_CHECK(isnan(ccl_phase_hg(nan, 0.5f)));
    CCL_CHECK(isnan(ccl_phase_schlick(nan, 0.5f, CCL_VARIANT_CORRECTED)));
    CCL_CHECK(isnan(ccl_phase_schlick_k(nan)));
}

int main(void)
{
    CCL_RUN(test_phase_isotropic_value);
    CCL_RUN(test_phase_rayleigh_closed_form);
    CCL_RUN(test_phase_hg_normalized_and_mean_cosine);
    CCL_RUN(test_phase_hg_closed_form);
    CCL_RUN(test_phase_schlick_variants);
    CCL_RUN(test_schlick_k_values);
    CCL_RUN(test_phase_nan_propagates);
    return ccl_test_report();
}
