/* C unit tests of cclouds/optics.h: Snell round trip and TIR (rr-snell), Fresnel closed forms and the catalogue's
 * check values (rr-eq2, rr-eq3), the drop's field of view, both variants (rr-der-3.2.1). */
#include "cclouds/optics.h"
#include "ccl_test.h"

#define PI_D 3.14159265358979323846

static void test_optics_snell_angles_and_round_trip(void)
{
    /* incidence 40 deg onto the plane z = 0 (normal +z), air -> water */
    const double ti = 40.0 * PI_D / 180.0, tt = asin(sin(ti) / 1.33);
    ccl_vec3 d = V((float)sin(ti), 0.0f, (float)-cos(ti)), n = V(0.0f, 0.0f, 1.0f), r, t, back, r2;
    int tir;
    t = ccl_optics_snell(d, n, 1.0f, 1.33f, &r, &tir);
    CCL_CHECK(tir == 0);
    CCL_CHECK_CLOSE(t.x, sin(tt), 1e-6);
    CCL_CHECK_CLOSE(t.z, -cos(tt), 1e-6);
    CCL_CHECK_CLOSE(r.x, sin(ti), 1e-6); /* law of reflection */
    CCL_CHECK_CLOSE(r.z, cos(ti), 1e-6);
    /* reverse the refracted ray: it leaves along -d (the normal's side does not matter) */
    back = ccl_optics_snell(V(-t.x, -t.y, -t.z), n, 1.33f, 1.0f, &r2, &tir);
    CCL_CHECK(tir == 0);
    CCL_CHECK_CLOSE(back.x, -d.x, 1e-6);
    CCL_CHECK_CLOSE(back.z, -d.z, 1e-6);
}

static void test_optics_snell_total_internal_reflection(void)
{
    /* water -> air at 60 deg > critical 48.75 deg */
    const double ti = 60.0 * PI_D / 180.0;
    ccl_vec3 d = V((float)sin(ti), 0.0f, (float)cos(ti)), n = V(0.0f, 0.0f, 1.0f), r, t;
    int tir = 0;
    t = ccl_optics_snell(d, n, 1.33f, 1.0f, &r, &tir);
    CCL_CHECK(tir == 1);
    CCL_CHECK(t.x == 0.0f && t.y == 0.0f && t.z == 0.0f);
    CCL_CHECK_CLOSE(r.z, -cos(ti), 1e-6);
}

static void test_optics_fresnel_closed_forms(void)
{
    float rs, rp, r;
    const double n = 1.33, r0 = ((n - 1) / (n + 1)) * ((n - 1) / (n + 1));
    r = ccl_optics_fresnel(1.0f, 1.0f, 1.33f, &rs, &rp);
    CCL_CHECK_REL(r, r0, 1e-5);
    CCL_CHECK_REL(rs, r0, 1e-5);
    CCL_CHECK_REL(rp, r0, 1e-5);
    /* Brewster: tan theta_B = n2 / n1 */
    r = ccl_optics_fresnel((float)cos(atan(1.33)), 1.0f, 1.33f, &rs, &rp);
    CCL_CHECK_CLOSE(rp, 0.0, 1e-7);
    /* grazing -> 1 */
    r = ccl_optics_fresnel(0.0f, 1.0f, 1.33f, &rs, &rp);
    CCL_CHECK_CLOSE(r, 1.0, 1e-6);
    /* catalogue check values, air -> water */
    r = ccl_optics_fresnel((float)cos(60.0 * PI_D / 180.0), 1.0f, 1.33f, &rs, &rp);
    CCL_CHECK_CLOSE(rs, 0.1139, 5e-5);
    CCL_CHECK_CLOSE(rp, 0.0044, 5e-5);
    CCL_CHECK_CLOSE(r, 0.0591, 5e-5);
    r = ccl_optics_fresnel((float)cos(67.5 * PI_D / 180.0), 1.0f, 1.33f, &rs, &rp);
    CCL_CHECK_CLOSE(r, 0.1065, 5e-5);
    r = ccl_optics_fresnel((float)cos(80.0 * PI_D / 180.0), 1.0f, 1.33f, &rs, &rp);
    CCL_CHECK_CLOSE(r, 0.3469, 5e-5);
    /* water -> air beyond the critical angle: total internal reflection */
    r = ccl_optics_fresnel((float)cos(50.0 * PI_D / 180.0), 1.33f, 1.0f, &rs, &rp);
    CCL_CHECK(r == 1.0f && rs == 1.0f && rp == 1.0f);
    /* equal indices: nothing reflected, and the 0/0 at grazing incidence is its limit 1 */
    r = ccl_optics_fresnel(0.5f, 1.33f, 1.33f, &rs, &rp);
    CCL_CHECK_CLOSE(r, 0.0, 1e-12);
    r = ccl_optics_fresnel(0.0f, 1.33f, 1.33f, &rs, &rp);
    CCL_CHECK(r == 1.0f);
}

static void test_optics_drop_fov_variants(void)
{
    float tt, e, x, fov;
    fov = ccl_optics_drop_fov(1.33f, CCL_VARIANT_THESIS, &tt, &e, &x);
    CCL_CHECK(tt == 48.0f && e == 6.0f && x == 81.0f && fov == 150.0f);
    fov = ccl_optics_drop_fov(1.33f, CCL_VARIANT_CORRECTED, &tt, &e, &x);
    CCL_CHECK_CLOSE(tt, asin(1.0 / 1.33) * 180.0 / PI_D, 1e-4);
    CCL_CHECK_CLOSE(e, 7.51, 5e-3);
    CCL_CHECK_CLOSE(fov, 360.0 - 4.0 * asin(1.0 / 1.33) * 180.0 / PI_D, 1e-3);
    CCL_CHECK_CLOSE(fov, 165.0, 0.05);
}

int main(void)
{
    CCL_RUN(test_optics_snell_angles_and_round_trip);
    CCL_RUN(test_optics_snell_total_internal_reflection);
    CCL_RUN(test_optics_fresnel_closed_forms);
    CCL_RUN(test_optics_drop_fov_variants);
    return ccl_test_report();
}
