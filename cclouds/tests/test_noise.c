/* C unit tests of cclouds/noise.h: permutation tables, Perlin noise against Ken Perlin's published value and its
 * lattice zeros (vc-A1), exact periodicity (vc-A2, vc-A5), Worley properties (vc-A3..A5), fBm (vc-2.21, A6),
 * curl-noise identities (vc-2.22..2.26, vc-A7), Perlin-Worley (vc-A8), NaN propagation. (The fades and remap are
 * tested in test_interp.c, the hash in test_hash.c.) */
#include "cclouds/noise.h"
#include "ccl_test.h"

#include <float.h>
#include <string.h>

static void test_perm_tables(void)
{
    uint8_t t0[CCL_NOISE_PERM_SIZE], t1[CCL_NOISE_PERM_SIZE], t2[CCL_NOISE_PERM_SIZE];
    int seen[256], i;
    CCL_CHECK(ccl_noise_perm_table(0u, NULL) == CCL_EINVAL);
    CCL_CHECK(ccl_noise_perm_table(0u, t0) == CCL_OK);
    /* Perlin's table starts 151, 160, 137, 91 and ends 156, 180 */
    CCL_CHECK(t0[0] == 151 && t0[1] == 160 && t0[2] == 137 && t0[3] == 91 && t0[254] == 156 && t0[255] == 180);
    CCL_CHECK(ccl_noise_perm_table(7u, t1) == CCL_OK);
    CCL_CHECK(ccl_noise_perm_table(8u, t2) == CCL_OK);
    CCL_CHECK(memcmp(t1, t2, 256) != 0);
    CCL_CHECK(memcmp(t0, t1, 256) != 0);
    memset(seen, 0, sizeof seen);
    for (i = 0; i < 256; ++i) {
        seen[t1[i]]++;
        CCL_CHECK(t1[256 + i] == t1[i] && t0[256 + i] == t0[i]);
    }
    for (i = 0; i < 256; ++i) CCL_CHECK(seen[i] == 1);
}

static void test_perlin_reference_value_and_lattice_zeros(void)
{
    int i, j, k;
    /* Ken Perlin's page: noise(3.14, 42, 7) = 0.13691995878400012 (double); float32 input 3.14f differs by 1e-7 */
    CCL_CHECK_CLOSE(ccl_noise_perlin3(3.14f, 42.0f, 7.0f, 0u, 0), 0.13691995878400012, 2e-6);
    for (k = -3; k <= 3; ++k)
        for (j = -3; j <= 3; ++j)
            for (i = -3; i <= 3; ++i) {
                CCL_CHECK(ccl_noise_perlin3((float)i * 7.0f, (float)j, (float)k * 3.0f, 0u, 0) == 0.0f);
                CCL_CHECK(ccl_noise_perlin3((float)i, (float)j, (float)k, 99u, 5) == 0.0f);
            }
    /* 2-D = the z = 0 slice, bit for bit */
    for (i = 0; i < 50; ++i) {
        float x = -7.3f + 0.61f * (float)i, y = 3.1f - 0.37f * (float)i;
        CCL_CHECK(ccl_noise_perlin2(x, y, 0u, 0, CCL_INTERP_QUINTIC) == ccl_noise_perlin3(x, y, 0.0f, 0u, 0));
        CCL_CHECK(ccl_noise_perlin2(x, y, 3u, 4, CCL_INTERP_QUINTIC) == ccl_noise_perlin3(x, y, 0.0f, 3u, 4));
    }
}

static void test_perlin_periodic_exact(void)
{
    int i;
    for (i = 0; i < 400; ++i) {
        /* points on a 1/64 grid: p + period is exact */
        float x = (float)((i * 37) % 997) / 64.0f - 7.0f, y = (float)((i * 53) % 991) / 64.0f - 3.0f;
        float z = (float)((i * 71) % 983) / 64.0f - 5.0f;
        float a = ccl_noise_perlin3(x, y, z, 0u, 5);
        CCL_CHECK(a == ccl_noise_perlin3(x + 5.0f, y, z, 0u, 5));
        CCL_CHECK(a == ccl_noise_perlin3(x, y - 5.0f, z, 0u, 5));
        CCL_CHECK(a == ccl_noise_perlin3(x, y, z + 10.0f, 0u, 5));
        CCL_CHECK(a == ccl_noise_perlin3_tiled(x, y, z, 5, 0u));
        CCL_CHECK(ccl_noise_perlin3(x, y, z, 0u, 0) == ccl_noise_perlin3(x + 256.0f, y, z, 0u, 0)); /* Perlin's 256 */
        CCL_CHECK(ccl_noise_perlin3(x, y, z, 11u, 300) == ccl_noise_perlin3(x, y + 300.0f, z, 11u, 300));
    }
    /* period 256 is Perlin's own wrap */
    CCL_CHECK(ccl_noise_perlin3(1.3f, 2.7f, -0.4f, 0u, 256) == ccl_noise_perlin3(1.3f, 2.7f, -0.4f, 0u, 0));
}

static void test_worley_properties(void)
{
    int i, c;
    float ox, oy, oz;
    for (c = 1; c <= 8; c *= 2) {
        /* value 0 at the feature point of cell (1, 0, 1): (1 + ox) / c is exact for c a power of two */
        ccl_vec3 o = ccl_noise_worley_feature(1, 0, 1, c, 42u);
        ox = o.x;
        oy = o.y;
        oz = o.z;
        CCL_CHECK(ox >= 0.0f && ox < 1.0f && oy >= 0.0f && oy < 1.0f && oz >= 0.0f && oz < 1.0f);
        CCL_CHECK(ccl_noise_worley3((1.0f + ox) / (float)c, oy / (float)c, (1.0f + oz) / (float)c, c, 42u,
                                    CCL_WORLEY_EUCLIDEAN, 0) == 0.0f);
        CCL_CHECK(ccl_noise_worley3((1.0f + ox) / (float)c, oy / (float)c, (1.0f + oz) / (float)c, c, 42u,
                                    CCL_WORLEY_MANHATTAN, 1) == 1.0f);
    }
    /* wrapped cell indices give the same feature point */
    {
        ccl_vec3 a = ccl_noise_worley_feature(-1, 5, 2, 4, 3u), b = ccl_noise_worley_feature(3, 1, 6, 4, 3u);
        CCL_CHECK(a.x == b.x && a.y == b.y && a.z == b.z);
    }
    for (i = 0; i < 300; ++i) {
        float x = (float)((i * 37) % 256) / 256.0f, y = (float)((i * 91) % 256) / 256.0f;
        float z = (float)((i * 13) % 256) / 256.0f;
        float e = ccl_noise_worley3(x, y, z, 5, 9u, CCL_WORLEY_EUCLIDEAN, 0);
        float m = ccl_noise_worley3(x, y, z, 5, 9u, CCL_WORLEY_MANHATTAN, 0);
        float cl, mh, inv;
        CCL_CHECK(e >= 0.0f && e <= 1.0f && m >= 0.0f && m <= 1.0f);
        CCL_CHECK(m >= e); /* L1 >= L2 for every point, hence for the minimum */
        CCL_CHECK(ccl_noise_worley3(x, y, z, 5, 9u, CCL_WORLEY_EUCLIDEAN, 1) == 1.0f - e);
        /* periodic with period 1, exactly */
        CCL_CHECK(e == ccl_noise_worley3(x + 1.0f, y, z, 5, 9u, CCL_WORLEY_EUCLIDEAN, 0));
        CCL_CHECK(e == ccl_noise_worley3(x, y - 1.0f, z + 2.0f, 5, 9u, CCL_WORLEY_EUCLIDEAN, 0));
        CCL_CHECK(m == ccl_noise_worley3(x - 3.0f, y, z, 5, 9u, CCL_WORLEY_MANHATTAN, 0));
        /* vc-A4 variants and the literal vc-A5 construction */
        ccl_noise_worley3_variants(x, y, z, 5, 9u, &cl, &mh, &inv);
        CCL_CHECK(cl == e && mh == m && inv == 1.0f - e);
        CCL_CHECK_CLOSE(ccl_noise_worley3_bruteforce(x, y, z, 5, 9u, CCL_WORLEY_EUCLIDEAN, 0), e, 2e-6);
        CCL_CHECK_CLOSE(ccl_noise_worley3_bruteforce(x, y, z, 5, 9u, CCL_WORLEY_MANHATTAN, 0), m, 2e-6);
    }
}

static void test_fbm(void)
{
    int i;
    for (i = 0; i < 100; ++i) {
        float x = (float)((i * 37) % 128) / 128.0f, y = (float)((i * 91) % 128) / 128.0f;
        float z = (float)((i * 13) % 128) / 128.0f;
        float n0 = ccl_noise_perlin3(x * 4.0f, y * 4.0f, z * 4.0f, 0u, 4);
        float n1 = ccl_noise_perlin3(x * 8.0f, y * 8.0f, z * 8.0f, 0u, 8);
        float n2 = ccl_noise_perlin3(x * 16.0f, y * 16.0f, z * 16.0f, 0u, 16);
        float f = ccl_noise_fbm_perlin3(x, y, z, 3, 4.0f, 0u, 4);
        CCL_CHECK(ccl_noise_fbm_perlin3(x, y, z, 1, 4.0f, 0u, 4) == n0);
        CCL_CHECK_CLOSE(f, ((double)n0 + 0.5 * (double)n1 + 0.25 * (double)n2) / 1.75, 3e-7);
        /* frequency 4, period 4: period 1 in x */
        CCL_CHECK(f == ccl_noise_fbm_perlin3(x + 1.0f, y, z - 1.0f, 3, 4.0f, 0u, 4));
        {
            float w0 = ccl_noise_worley3(x, y, z, 2, 5u, CCL_WORLEY_EUCLIDEAN, 1);
            float w1 = ccl_noise_worley3(x, y, z, 4, 6u, CCL_WORLEY_EUCLIDEAN, 1);
            float w = ccl_noise_fbm_worley3(x, y, z, 2, 2, 5u, CCL_WORLEY_EUCLIDEAN, 1);
            CCL_CHECK_CLOSE(w, ((double)w0 + 0.5 * (double)w1) / 1.5, 2e-7);
            CCL_CHECK(w == ccl_noise_fbm_worley3(x, y + 1.0f, z, 2, 2, 5u, CCL_WORLEY_EUCLIDEAN, 1));
        }
    }
}

static void test_curl_identities(void)
{
    int i;
    const float h = 1.0f / CCL_NOISE_FD_STEP_INV;
    double max_div = 0.0, max_curlcurl = 0.0;
    for (i = 0; i < 40; ++i) {
        float x = -3.1f + 0.173f * (float)i, y = 1.7f - 0.291f * (float)i, z = 0.37f * (float)i;
        ccl_vec3 v, g;
        ccl_vec2 c;
        float div = ccl_noise_curl_property(x, y, z, 0u, 0, h, CCL_VARIANT_CORRECTED);
        float cc = ccl_noise_curl_property(x, y, z, 0u, 0, h, CCL_VARIANT_THESIS);
        if (fabs((double)div) > max_div) max_div = fabs((double)div);
        if ((double)cc > max_curlcurl) max_curlcurl = (double)cc;
        /* 2.24 = z component of 2.23 at z = 0 */
        v = ccl_noise_curl3(x, y, 0.0f, 0u, 0, h);
        CCL_CHECK(ccl_noise_rot2(x, y, 0u, 0, h) == v.z);
        /* 2-D curl noise is perpendicular to the gradient of its stream function */
        c = ccl_noise_curl2(x, y, 0u, 0, h);
        g = ccl_noise_gradient3(x, y, 0.0f, 0u, 0, h);
        CCL_CHECK(c.x == g.y && c.y == -g.x);
    }
    /* div(curl psi) is round-off (< 1e-3; the curl components are O(1), their derivatives O(10));
     * the printed reading curl(curl psi) = 0 fails by orders of magnitude */
    CCL_CHECK(max_div < 1e-3);
    CCL_CHECK(max_curlcurl > 1.0);
}

static void test_perlin_worley(void)
{
    CCL_CHECK_CLOSE(ccl_noise_perlin_worley(0.5f, 0.2f, CCL_PW_THESIS), 0.36, 1e-7);     /* (0.2 + 0.5*0.8)^2 */
    CCL_CHECK_CLOSE(ccl_noise_perlin_worley(0.5f, 0.2f, CCL_PW_HILLAIRE), 0.6, 1e-7);
    CCL_CHECK_CLOSE(ccl_noise_perlin_worley(0.6f, 0.2f, CCL_PW_GPU_PRO_7), 0.5, 1e-7);  /* (0.6-0.2)/0.8 */
    CCL_CHECK(ccl_noise_perlin_worley(0.1f, 0.2f, CCL_PW_GPU_PRO_7) == 0.0f);            /* clamped */
    CCL_CHECK(ccl_noise_perlin_worley(0.7f, 1.0f, CCL_PW_GPU_PRO_7) == 0.0f);            /* W = 1 */
    CCL_CHECK_CLOSE(ccl_noise_perlin_worley(0.5f, 0.2f, CCL_PW_PRODUCT), 0.1, 1e-8);
    CCL_CHECK_CLOSE(ccl_noise_perlin_worley(0.5f, 0.2f, CCL_PW_AVERAGE), 0.35, 1e-8);
}

static void test_noise_nan_propagates(void)
{
    float nan = (float)NAN;
    ccl_vec3 v;
    CCL_CHECK(isnan(ccl_noise_perlin3(nan, 0.5f, 0.5f, 0u, 0)));
    CCL_CHECK(isnan(ccl_noise_perlin3(0.5f, (float)INFINITY, 0.5f, 3u, 4)));
    CCL_CHECK(isnan(ccl_noise_perlin2(nan, 0.5f, 0u, 0, CCL_INTERP_LINEAR)));
    CCL_CHECK(isnan(ccl_noise_worley3(0.5f, nan, 0.5f, 4, 0u, CCL_WORLEY_EUCLIDEAN, 0)));
    CCL_CHECK(isnan(ccl_noise_worley3_bruteforce(0.5f, nan, 0.5f, 4, 0u, CCL_WORLEY_EUCLIDEAN, 0)));
    CCL_CHECK(isnan(ccl_noise_fbm_perlin3(nan, 0.5f, 0.5f, 3, 2.0f, 0u, 0)));
    CCL_CHECK(isnan(ccl_noise_fbm_worley3(nan, 0.5f, 0.5f, 3, 2, 0u, CCL_WORLEY_EUCLIDEAN, 1)));
    v = ccl_noise_curl3(nan, 0.0f, 0.0f, 0u, 0, 0.01f);
    CCL_CHECK(isnan(v.x) && isnan(v.y) && isnan(v.z));
    CCL_CHECK(isnan(ccl_noise_gradient3(0.5f, nan, 0.0f, 0u, 0, 0.01f).y));
    CCL_CHECK(isnan(ccl_noise_curl2(nan, 0.5f, 0u, 0, 0.01f).x));
    CCL_CHECK(isnan(ccl_noise_perlin_worley(nan, 0.5f, CCL_PW_THESIS)));
    CCL_CHECK(isnan(ccl_noise_perlin_worley(0.5f, nan, CCL_PW_GPU_PRO_7)));
}

int main(void)
{
    CCL_RUN(test_perm_tables);
    CCL_RUN(test_perlin_reference_value_and_lattice_zeros);
    CCL_RUN(test_perlin_periodic_exact);
    CCL_RUN(test_worley_properties);
    CCL_RUN(test_fbm);
    CCL_RUN(test_curl_identities);
    CCL_RUN(test_perlin_worley);
    CCL_RUN(test_noise_nan_propagates);
    return ccl_test_report();
}
