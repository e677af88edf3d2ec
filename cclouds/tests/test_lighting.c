/* C unit tests of the cloudscape's sky lighting: the sun through the atmosphere (sky.h, Preetham et al. 1999
 * appendix A.1: ccl_sky_relative_air_mass, ccl_sky_sun_attenuation) against the closed forms evaluated in double. */
#include "cclouds/sky.h"
#include "ccl_test.h"

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

int main(void)
{
    CCL_RUN(test_air_mass_closed_form);
    CCL_RUN(test_sun_attenuation_closed_form);
    CCL_RUN(test_sun_reddens_towards_the_horizon);
    return ccl_test_report();
}
