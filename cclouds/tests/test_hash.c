/* C unit tests of cclouds/hash.h: PCG hash values computed independently from the published formula (Python
 * integers), bijectivity on a range, avalanche on the low bits, and the [0, 1) mapping of ccl_hash_unit. */
#include "cclouds/hash.h"
#include "ccl_test.h"

#include <stdlib.h>

static void test_hash_pcg_values(void)
{
    /* Jarzynski & Olano 2020, pcg_hash(); values from the formula evaluated with Python integers mod 2^32 */
    CCL_CHECK(ccl_hash_pcg(0u) == 129708002u);
    CCL_CHECK(ccl_hash_pcg(1u) == 2831084092u);
    CCL_CHECK(ccl_hash_pcg(12345u) == 4099845390u);
    CCL_CHECK(ccl_hash_pcg(0xFFFFFFFFu) == 3861530882u);
}

static int cmp_u32(const void *a, const void *b)
{
    uint32_t x = *(const uint32_t *)a, y = *(const uint32_t *)b;
    return (x > y) - (x < y);
}

static void test_hash_pcg_injective_and_mixing(void)
{
    enum { N = 1 << 16 };
    static uint32_t h[N];
    uint32_t i;
    int dup = 0;
    double bits = 0.0;
    for (i = 0; i < N; ++i) h[i] = ccl_hash_pcg(i);
    /* consecutive inputs flip about half of the 32 output bits */
    for (i = 1; i < N; ++i) {
        uint32_t d = h[i] ^ h[i - 1];
        int c = 0;
        while (d) {
            c += (int)(d & 1u);
            d >>= 1;
        }
        bits += c;
    }
    bits /= (double)(N - 1);
    CCL_CHECK(bits > 15.0 && bits < 17.0);
    /* a bijection of uint32: no two of the first 2^16 inputs collide */
    qsort(h, N, sizeof h[0], cmp_u32);
    for (i = 1; i < N; ++i) dup += h[i] == h[i - 1];
    CCL_CHECK(dup == 0);
}

static void test_hash_unit(void)
{
    uint32_t i;
    double mean = 0.0;
    CCL_CHECK(ccl_hash_unit(0u) == 0.0f);
    CCL_CHECK(ccl_hash_unit(255u) == 0.0f); /* only the top 24 bits count */
    CCL_CHECK(ccl_hash_unit(256u) == 1.0f / 16777216.0f);
    CCL_CHECK(ccl_hash_unit(0x80000000u) == 0.5f);
    CCL_CHECK(ccl_hash_unit(0xFFFFFFFFu) == 1.0f - 1.0f / 16777216.0f); /* largest value, < 1 */
    for (i = 0; i < 100000u; ++i) {
        float u = ccl_hash_unit(ccl_hash_pcg(i));
        CCL_CHECK(u >= 0.0f && u < 1.0f);
        mean += (double)u;
    }
    /* uniform on [0, 1): mean 1/2, standard error 1 / sqrt(12 * 1e5) ~ 9e-4 */
    CCL_CHECK_CLOSE(mean / 100000.0, 0.5, 5e-3);
}

int main(void)
{
    CCL_RUN(test_hash_pcg_values);
    CCL_RUN(test_hash_pcg_injective_and_mixing);
    CCL_RUN(test_hash_unit);
    return ccl_test_report();
}
