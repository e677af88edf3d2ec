/* Escape-time fractals, pt §3.6. See cclouds/fractal.h. */
#include "cclouds/fractal.h"
#include "internal.h"

#include <math.h>

static ccl_vec2 complex_mul(ccl_vec2 a, ccl_vec2 b)
{
    ccl_vec2 r;
    r.x = a.x * b.x - a.y * b.y;
    r.y = a.x * b.y + a.y * b.x;
    return r;
}

/* z^d by d - 1 complex multiplications (d small, bounded by the caller). */
static ccl_vec2 complex_pow(ccl_vec2 z, int32_t d)
{
    ccl_vec2 r = z;
    int32_t i;
    for (i = 1; i < d; ++i) r = complex_mul(r, z);
    return r;
}

/* ln|z| without overflow of |z|^2: ln(max) + ln(1 + (min/max)^2) / 2. */
static float log_abs(ccl_vec2 z)
{
    float a = fmaxf(fabsf(z.x), fabsf(z.y));
    float b = fminf(fabsf(z.x), fabsf(z.y));
    float q = b / a;
    return logf(a) + 0.5f * logf(1.0f + q * q);
}

static int32_t julia_iter(ccl_vec2 z, ccl_vec2 c, int32_t power, int32_t max_iter, float escape, int map,
                          float *out_smooth)
{
    int32_t n;
    float smooth;
    for (n = 0; n < max_iter; ++n) {
        if (map == CCL_FRACTAL_EXP) {
            float e, nx;
            if (z.x > escape) break;
            e = expf(z.x); /* e^z = e^x (cos y + i sin y) */
            nx = e * cosf(z.y) + c.x;
            z.y = e * sinf(z.y) + c.y;
            z.x = nx;
        } else {
            ccl_vec2 w;
            if (z.x * z.x + z.y * z.y > escape * escape) break;
            w = complex_pow(z, power);
            z.x = w.x + c.x;
            z.y = w.y + c.y;
        }
    }
    if (n >= max_iter) {
        smooth = (float)max_iter;
    } else if (map == CCL_FRACTAL_EXP) {
        float s = logf(z.x) / escape;
        s = fminf(fmaxf(s, 0.0f), 1.0f);
        smooth = (float)n + 1.0f - s;
    } else {
        smooth = (float)n + 1.0f - logf(log_abs(z) / logf(escape)) / logf((float)power);
    }
    if (out_smooth) *out_smooth = smooth;
    return n;
}

int32_t ccl_fractal_julia(ccl_vec2 z0, ccl_vec2 c, int32_t power, int32_t max_iter, float escape, int map,
                          float *out_smooth)
{
    CCL_REQUIRE(power >= 2 && power <= 12);
    CCL_REQUIRE(max_iter >= 1);
    CCL_REQUIRE(escape > 1.0f && escape <= 64.0f);
    return julia_iter(z0, c, power, max_iter, escape, map, out_smooth);
}

int32_t ccl_fractal_julia_example(ccl_vec2 z0, int32_t max_iter, int example, float *out_smooth)
{
    ccl_vec2 c;
    CCL_REQUIRE(max_iter >= 1);
    if (example == CCL_JULIA_X5) {
        c.x = 0.544f;
        c.y = 0.0f;
        return julia_iter(z0, c, 5, max_iter, 16.0f, CCL_FRACTAL_POLY, out_smooth);
    }
    if (example == CCL_JULIA_X2) {
        c.x = 0.285f;
        c.y = 0.01f;
        return julia_iter(z0, c, 2, max_iter, 16.0f, CCL_FRACTAL_POLY, out_smooth);
    }
    c.x = -0.65f;
    c.y = 0.0f;
    return julia_iter(z0, c, 1, max_iter, 50.0f, CCL_FRACTAL_EXP, out_smooth);
}

ccl_vec2 ccl_fractal_quadratic(ccl_vec2 z, ccl_vec2 mu, ccl_variant variant)
{
    ccl_vec2 r = complex_mul(z, z);
    if (variant == CCL_VARIANT_THESIS) {
        r.x = r.x - mu.x;
        r.y = r.y - mu.y;
    } else {
        r.x = r.x + mu.x;
        r.y = r.y + mu.y;
    }
    return r;
}

int32_t ccl_fractal_mandelbrot(ccl_vec2 mu, int32_t max_iter, float escape, ccl_variant variant, float *out_smooth)
{
    ccl_vec2 a;
    int32_t n;
    float smooth;
    CCL_REQUIRE(max_iter >= 1);
    CCL_REQUIRE(escape >= 2.0f);
    a.x = 0.0f;
    a.y = 0.0f;
    for (n = 0; n < max_iter; ++n) {
        if (a.x * a.x + a.y * a.y > escape * escape) break;
        a = ccl_fractal_quadratic(a, mu, variant);
    }
    if (n >= max_iter) smooth = (float)max_iter;
    else smooth = (float)n + 1.0f - logf(log_abs(a) / logf(escape)) / logf(2.0f);
    if (out_smooth) *out_smooth = smooth;
    return n;
}
