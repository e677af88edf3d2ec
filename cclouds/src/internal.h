/* Private helpers shared by the cclouds sources (not installed). */
#ifndef CCLOUDS_INTERNAL_H
#define CCLOUDS_INTERNAL_H

#include <assert.h>
#include <math.h>

#include "cclouds/common.h"

#define CCL_PI_F 3.14159265358979323846f
#define CCL_INV_4PI_F 0.0795774715459476679f /* 1 / (4 pi) */

/* Precondition check: active in debug builds, compiled out with NDEBUG. NaN arguments pass (they propagate). */
#define CCL_REQUIRE(cond) assert(cond)

/* Small vector helpers used across sources (Warp: wp.vec3 and pywarp/kernels/common.py). static inline: each source
 * gets its own copy, no exported symbol; an unused one draws no warning. */

static inline ccl_vec3 v3(float x, float y, float z)
{
    ccl_vec3 r;
    r.x = x;
    r.y = y;
    r.z = z;
    return r;
}

/* x clamped to [0, 1]; NaN passes through (both comparisons are false). */
static inline float clamp01(float x)
{
    return x < 0.0f ? 0.0f : (x > 1.0f ? 1.0f : x);
}

/* a + (b - a) f, component-wise (GLSL mix) */
static inline ccl_vec3 mix3(ccl_vec3 a, ccl_vec3 b, float f)
{
    return v3(a.x + (b.x - a.x) * f, a.y + (b.y - a.y) * f, a.z + (b.z - a.z) * f);
}

/* A cell coordinate x (voxel, texel) bounded to [-1, n] before any floor and cast: below -1 or above n every read
 * clamps to the same edge cell, so a trilinear or bilinear fetch is unchanged, and the cast stays within int for any
 * float (+-Inf and |x| >= 2^31 included). x must not be NaN (the callers return NaN before). */
static inline float bound_cell(float x, int n)
{
    return x < -1.0f ? -1.0f : (x > (float)n ? (float)n : x);
}

#endif /* CCLOUDS_INTERNAL_H */
