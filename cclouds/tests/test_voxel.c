/* C unit tests of cclouds/voxel.h: the settings check, the exponential filter (oc-5.2.2: range, monotonicity in
 * cover and sharpness), the SIN window (oc-5.2.3.1), the cloud array (oc-5.2.1) with the border problem reproduced
 * (oc-5.2.3) and removed by the zero-border larger array (oc-5.2.3.2), determinism, per-axis scaling
 * (oc-5.2.3-scale), and the falloff envelope (beyond the text). */
#include "cclouds/voxel.h"
#include "cclouds/valuenoise.h"
#include "ccl_test.h"

#include <stdlib.h>
#include <string.h>

static void test_settings(void)
{
    ccl_voxel_settings s = ccl_voxel_settings_default(), t;
    const char *field = "x";
    CCL_CHECK(ccl_voxel_settings_check(&s, &field) == CCL_OK && field == NULL);
    CCL_CHECK(s.size == 64 && s.levels == 4 && s.border == CCL_VOXEL_BORDER_ZERO);
    t = s; t.sharpness = 1.0f;
    CCL_CHECK(ccl_voxel_settings_check(&t, &field) == CCL_EINVAL && strcmp(field, "sharpness") == 0);
    t = s; t.sharpness = 0.0f;
    CCL_CHECK(ccl_voxel_settings_check(&t, &field) == CCL_EINVAL && strcmp(field, "sharpness") == 0);
    t = s; t.sharpness = 1.5f;
    CCL_CHECK(ccl_voxel_settings_check(&t, &field) == CCL_EINVAL && strcmp(field, "sharpness") == 0);
    t = s; t.cover = 256.0f;
    CCL_CHECK(ccl_voxel_settings_check(&t, &field) == CCL_EINVAL && strcmp(field, "cover") == 0);
    t = s; t.size = 60; /* not a multiple of 8 */
    CCL_CHECK(ccl_voxel_settings_check(&t, &field) == CCL_EINVAL && strcmp(field, "size") == 0);
    t = s; t.size = 24; /* base 3 < 4 */
    CCL_CHECK(ccl_voxel_settings_check(&t, &field) == CCL_EINVAL && strcmp(field, "size") == 0);
    t = s; t.persistence = 0.0f;
    CCL_CHECK(ccl_voxel_settings_check(&t, &field) == CCL_EINVAL && strcmp(field, "persistence") == 0);
    CCL_CHECK(ccl_voxel_settings_check(NULL, &field) == CCL_EINVAL && strcmp(field, "s") == 0);
    CCL_CHECK(s.envelope == 0.0f && s.envelope_base == 0.35f); /* the text's array by default */
    t = s; t.envelope = 1.5f;
    CCL_CHECK(ccl_voxel_settings_check(&t, &field) == CCL_EINVAL && strcmp(field, "envelope") == 0);
    t = s; t.envelope_base = 0.0f;
    CCL_CHECK(ccl_voxel_settings_check(&t, &field) == CCL_EINVAL && strcmp(field, "envelope_base") == 0);
}

/* The envelope's squared radius: 0 at the (lowered) centre, 1 at the centres of the faces, 3 in the corners; with
 * the base below the centre at 1/3 of the edge (base 0.5), equal distances fall off twice as fast below. The
 * envelope lowers the noise by envelope * q: 0.5 at the inscribed ellipsoid. */
static void test_envelope(void)
{
    ccl_voxel_settings s = ccl_voxel_settings_default();
    float *plain = (float *)malloc(32 * 32 * 32 * sizeof(float)), *env = (float *)malloc(32 * 32 * 32 * sizeof(float));
    size_t k;
    CCL_CHECK_CLOSE(ccl_voxel_envelope(0, 16, 16, 33, 1.0f), 1.0, 1e-6);
    CCL_CHECK_CLOSE(ccl_voxel_envelope(16, 16, 16, 33, 1.0f), 0.0, 1e-6);
    CCL_CHECK_CLOSE(ccl_voxel_envelope(32, 32, 0, 33, 1.0f), 3.0, 1e-6);
    CCL_CHECK_CLOSE(ccl_voxel_envelope(16, 0, 16, 33, 0.5f), 1.0, 1e-6);   /* the bottom face centre */
    CCL_CHECK_CLOSE(ccl_voxel_envelope(16, 32, 16, 33, 0.5f), 1.0, 1e-6);  /* the top face centre */
    /* edge 25, base 0.5: the centre at y = 8; 2 voxels below it (of 8) and 4 above it (of 16) give the same q */
    CCL_CHECK_CLOSE(ccl_voxel_envelope(12, 6, 12, 25, 0.5f), 0.0625, 1e-6);
    CCL_CHECK_CLOSE(ccl_voxel_envelope(12, 12, 12, 25, 0.5f), 0.0625, 1e-6);
    s.size = 32;
    s.seed = 3;
    CCL_CHECK(ccl_voxel_noise(&s, plain, 32 * 32 * 32) == CCL_OK);
    s.envelope = 0.5f;
    CCL_CHECK(ccl_voxel_noise(&s, env, 32 * 32 * 32) == CCL_OK);
    for (k = 0; k < 32 * 32 * 32; ++k) {
        int x = (int)(k % 32), y = (int)(k / 32 % 32), z = (int)(k / 1024);
        double ref = (double)plain[k] - 0.5 * (double)ccl_voxel_envelope(x, y, z, 32, s.envelope_base);
        CCL_CHECK_CLOSE(env[k], ref < 0.0 ? 0.0 : ref, 1e-6);
    }
    free(plain);
    free(env);
}

static void test_filter(void)
{
    float n, c, s;
    CCL_CHECK(ccl_voxel_filter(0.3f, 100.0f, 0.9f) == 0.0f);                  /* 76.5 - 100 < 0 -> 0 */
    CCL_CHECK_CLOSE(ccl_voxel_filter(0.6f, 100.0f, 0.9f), 255.0 * (1.0 - pow(0.9, 0.6 * 255.0 - 100.0)), 1e-3);
    for (n = 0.0f; n <= 1.0f; n += 0.0625f) {
        float prev_c = 1e9f, prev_s = 1e9f;
        for (c = 0.0f; c <= 255.0f; c += 15.0f) {
            float d = ccl_voxel_filter(n, c, 0.95f);
            CCL_CHECK(d >= 0.0f && d <= 255.0f);
            CCL_CHECK(d <= prev_c); /* more cover -> less cloud */
            prev_c = d;
        }
        for (s = 0.05f; s < 1.0f; s += 0.1f) {
            float d = ccl_voxel_filter(n, 50.0f, s);
            CCL_CHECK(d <= prev_s); /* sharper (smaller s) -> denser */
            prev_s = d;
        }
    }
}

static void test_sin_window(void)
{
    CCL_CHECK(ccl_voxel_sin_window(0, 8.0f) == 0.0f);
    CCL_CHECK(ccl_voxel_sin_window(8, 8.0f) == 1.0f && ccl_voxel_sin_window(100, 8.0f) == 1.0f);
    CCL_CHECK_CLOSE(ccl_voxel_sin_window(4, 8.0f), sin(3.14159265358979 / 4.0), 1e-7);
}

static int faces_nonzero(const uint8_t *v, int32_t n)
{
    int32_t x, y, z, count = 0;
    for (z = 0; z < n; ++z)
        for (y = 0; y < n; ++y)
            for (x = 0; x < n; ++x)
                if ((x == 0 || y == 0 || z == 0 || x == n - 1 || y == n - 1 || z == n - 1)
                    && v[((size_t)z * (size_t)n + (size_t)y) * (size_t)n + (size_t)x] != 0)
                    ++count;
    return count;
}

static void test_cloud_borders(void)
{
    ccl_voxel_settings s = ccl_voxel_settings_default();
    size_t total;
    uint8_t *a, *b;
    float *noise;
    int k;
    s.size = 32;
    total = (size_t)32 * 32 * 32;
    a = (uint8_t *)malloc(total);
    b = (uint8_t *)malloc(total);
    noise = (float *)malloc(total * sizeof(float));
    for (k = 0; k < 3; ++k) {
        s.interpolation = k;
        s.cover = 100.0f;
        s.border = CCL_VOXEL_BORDER_ZERO;
        CCL_CHECK(ccl_voxel_cloud(&s, a, total) == CCL_OK);
        CCL_CHECK(faces_nonzero(a, 32) == 0);   /* the larger array: no voxel on the faces */
        s.border = CCL_VOXEL_BORDER_SIN;
        CCL_CHECK(ccl_voxel_cloud(&s, b, total) == CCL_OK);
        CCL_CHECK(faces_nonzero(b, 32) == 0);
        s.border = CCL_VOXEL_BORDER_NONE;
        CCL_CHECK(ccl_voxel_cloud(&s, b, total) == CCL_OK);
        CCL_CHECK(faces_nonzero(b, 32) > 0);    /* the border problem, reproduced */
    }
    /* same seed, same volume; another seed, another volume */
    s = ccl_voxel_settings_default();
    s.size = 32;
    CCL_CHECK(ccl_voxel_cloud(&s, a, total) == CCL_OK);
    CCL_CHECK(ccl_voxel_cloud(&s, b, total) == CCL_OK);
    CCL_CHECK(memcmp(a, b, total) == 0);
    s.seed = 1u;
    CCL_CHECK(ccl_voxel_cloud(&s, b, total) == CCL_OK);
    CCL_CHECK(memcmp(a, b, total) != 0);
    /* noise in [0, 1]; errors */
    CCL_CHECK(ccl_voxel_noise(&s, noise, total) == CCL_OK);
    for (k = 0; k < (int)total; k += 97) CCL_CHECK(noise[k] >= 0.0f && noise[k] <= 1.0f);
    CCL_CHECK(ccl_voxel_noise(&s, noise, total - 1) == CCL_ERANGE);
    s.sharpness = 1.0f;
    CCL_CHECK(ccl_voxel_cloud(&s, a, total) == CCL_EINVAL);
    free(a);
    free(b);
    free(noise);
}

static void test_scale(void)
{
    ccl_voxel_settings s = ccl_voxel_settings_default();
    size_t total = (size_t)32 * 32 * 32;
    uint8_t *a = (uint8_t *)malloc(total), *b = (uint8_t *)malloc(total), *c = (uint8_t *)malloc(48 * 40 * 16);
    int32_t x, y, z, nonzero = 0;
    s.size = 32;
    CCL_CHECK(ccl_voxel_cloud(&s, a, total) == CCL_OK);
    CCL_CHECK(ccl_voxel_scale(a, 32, 32, 32, b, 32, 32, 32) == CCL_OK);
    CCL_CHECK(memcmp(a, b, total) == 0); /* scale 1 is the identity */
    CCL_CHECK(ccl_voxel_scale(a, 32, 32, 32, c, 48, 40, 16) == CCL_OK);
    for (z = 0; z < 16; ++z)
        for (y = 0; y < 40; ++y)
            for (x = 0; x < 48; ++x) {
                uint8_t v = c[((size_t)z * 40 + (size_t)y) * 48 + (size_t)x];
                if (x == 0 || y == 0 || z == 0 || x == 47 || y == 39 || z == 15) CCL_CHECK(v == 0);
                nonzero += v != 0;
            }
    CCL_CHECK(nonzero > 0);
    CCL_CHECK(ccl_voxel_scale(a, 32, 32, 32, c, 1, 40, 16) == CCL_EINVAL);
    free(a);
    free(b);
    free(c);
}

int main(void)
{
    CCL_RUN(test_settings);
    CCL_RUN(test_filter);
    CCL_RUN(test_sin_window);
    CCL_RUN(test_cloud_borders);
    CCL_RUN(test_scale);
    CCL_RUN(test_envelope);
    return ccl_test_report();
}
