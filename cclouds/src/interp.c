/* Interpolants and remap. See cclouds/interp.h. */
#include "cclouds/interp.h"
#include "internal.h"

float ccl_interp_fade_cubic(float t)
{
    /* vc-2.19: 3t^2 - 2t^3 */
    return t * t * (3.0f - 2.0f * t);
}

float ccl_interp_fade_quintic(float t)
{
    /* vc-2.20: 6t^5 - 15t^4 + 10t^3, Perlin's Horner form; it rounds to 1 + 2^-23 for 22,237 floats in
     * [0.99536, 1) (fuzz finding Q), so 1 there (a NaN t stays NaN) */
    const float f = t * t * t * (t * (t * 6.0f - 15.0f) + 10.0f);
    return f > 1.0f ? 1.0f : f;
}

float ccl_interp_lerp(float t, float a, float b)
{
    return a + t * (b - a);
}

float ccl_interp_cosine(float t, float a, float b)
{
    float s = (1.0f - cosf(CCL_PI_F * t)) * 0.5f;
    return a + s * (b - a);
}

float ccl_interp_remap(float v, float o_min, float o_max, float n_min, float n_max)
{
    CCL_REQUIRE(o_max != o_min);
    /* vc-2.27 */
    return n_min + (v - o_min) / (o_max - o_min) * (n_max - n_min);
}
