/* C unit tests of the vector maths of cclouds/common.h: exact small-integer results, identities, the zero vector and
 * NaN; status strings and the version. */
#include "cclouds/common.h"
#include "ccl_test.h"

#include <string.h>

static int eq3(ccl_vec3 a, float x, float y, float z) { return a.x == x && a.y == y && a.z == z; }

static void test_vec3_arithmetic_exact(void)
{
    ccl_vec3 a = V(1, -2, 3), b = V(4, 5, -6);
    CCL_CHECK(eq3(ccl_vec3_add(a, b), 5, 3, -3));
    CCL_CHECK(eq3(ccl_vec3_sub(a, b), -3, -7, 9));
    CCL_CHECK(eq3(ccl_vec3_scale(a, -0.5f), -0.5f, 1, -1.5f));
    CCL_CHECK(ccl_vec3_dot(a, b) == 4.0f - 10.0f - 18.0f);
    CCL_CHECK(ccl_vec3_length(V(2, -3, 6)) == 7.0f); /* a Pythagorean quadruple: exact */
    CCL_CHECK(ccl_vec3_length(V(0, 0, 0)) == 0.0f);
}

static void test_vec3_cross_is_right_handed(void)
{
    ccl_vec3 a = V(1.5f, -2.0f, 0.25f), b = V(-3.0f, 0.5f, 4.0f), c;
    CCL_CHECK(eq3(ccl_vec3_cross(V(1, 0, 0), V(0, 1, 0)), 0, 0, 1)); /* x cross y = z */
    CCL_CHECK(eq3(ccl_vec3_cross(V(0, 1, 0), V(0, 0, 1)), 1, 0, 0));
    CCL_CHECK(eq3(ccl_vec3_cross(V(0, 0, 1), V(1, 0, 0)), 0, 1, 0));
    c = ccl_vec3_cross(a, b);
    /* orthogonal to both (exact here: the products are exact in float32), anti-commutative, a x a = 0 */
    CCL_CHECK_CLOSE(ccl_vec3_dot(c, a), 0.0, 1e-5);
    CCL_CHECK_CLOSE(ccl_vec3_dot(c, b), 0.0, 1e-5);
    {
        ccl_vec3 m = ccl_vec3_cross(b, a);
        CCL_CHECK(m.x == -c.x && m.y == -c.y && m.z == -c.z);
    }
    CCL_CHECK(eq3(ccl_vec3_cross(a, a), 0, 0, 0));
    /* |a x b|^2 = |a|^2 |b|^2 - (a.b)^2 (Lagrange) in double */
    {
        double ab = (double)a.x * (double)b.x + (double)a.y * (double)b.y + (double)a.z * (double)b.z;
        double aa = len3(a) * len3(a), bb = len3(b) * len3(b);
        CCL_CHECK_REL((double)ccl_vec3_length(c) * (double)ccl_vec3_length(c), aa * bb - ab * ab, 1e-6);
    }
}

static void test_vec3_normalize(void)
{
    ccl_vec3 n = ccl_vec3_normalize(V(0, 3, -4));
    float nan = (float)NAN;
    CCL_CHECK(eq3(n, 0.0f, 0.6f, -0.8f)); /* 3/5 and -4/5, each correctly rounded */
    n = ccl_vec3_normalize(V(1e-20f, -2e-20f, 2e-20f)); /* tiny: the squares underflow to denormals, still unit */
    CCL_CHECK_CLOSE(ccl_vec3_length(n), 1.0, 1e-3);
    n = ccl_vec3_normalize(V(3e18f, 4e18f, 0)); /* large: squares still in range */
    CCL_CHECK_CLOSE(n.x, 0.6, 1e-7);
    CCL_CHECK(eq3(ccl_vec3_normalize(V(0, 0, 0)), 0, 0, 0)); /* like wp.normalize */
    n = ccl_vec3_normalize(V(nan, 1, 0));
    CCL_CHECK(isnan(n.x) && isnan(n.y) && isnan(n.z)); /* NaN propagates */
    n = ccl_vec3_normalize(V(0.3f, -0.7f, 0.2f));
    CCL_CHECK_CLOSE(ccl_vec3_length(n), 1.0, 2e-7);
}

static void test_nan_propagates(void)
{
    float nan = (float)NAN;
    CCL_CHECK(isnan(ccl_vec3_add(V(nan, 0, 0), V(1, 1, 1)).x));
    CCL_CHECK(isnan(ccl_vec3_dot(V(0, nan, 0), V(1, 1, 1))));
    CCL_CHECK(isnan(ccl_vec3_length(V(0, 0, nan))));
    CCL_CHECK(isnan(ccl_vec3_cross(V(nan, 0, 0), V(0, 1, 0)).z));
}

static void test_status_and_version(void)
{
    CCL_CHECK(strcmp(ccl_status_str(CCL_OK), "ok") == 0);
    CCL_CHECK(strcmp(ccl_status_str(CCL_EINVAL), "invalid argument") == 0);
    CCL_CHECK(strcmp(ccl_status_str((ccl_status)99), "unknown status") == 0);
    CCL_CHECK(ccl_version() == CCL_VERSION_MAJOR * 10000 + CCL_VERSION_MINOR * 100 + CCL_VERSION_PATCH);
}

int main(void)
{
    CCL_RUN(test_vec3_arithmetic_exact);
    CCL_RUN(test_vec3_cross_is_right_handed);
    CCL_RUN(test_vec3_normalize);
    CCL_RUN(test_nan_propagates);
    CCL_RUN(test_status_and_version);
    return ccl_test_report();
}
