/*
 * cclouds/fuzz/fuzz_vec.h -- the small vector helpers the geometric harnesses share (fuzz_optics, fuzz_sdf,
 * fuzz_terrain_parts) and the float epsilon every harness states its bounds in.
 */
#ifndef CCLOUDS_FUZZ_VEC_H
#define CCLOUDS_FUZZ_VEC_H

#include <math.h>

#include "cclouds/common.h"

/* FLT_EPSILON written out (2^-23): the relative bound the harnesses' checks are stated in */
#define EPS 1.1920929e-7f

static inline ccl_vec3 v3(float x, float y, float z) {
    ccl_vec3 v;
    v.x = x;
    v.y = y;
    v.z = z;
    return v;
}

static inline float len3(ccl_vec3 a) { return sqrtf(a.x * a.x + a.y * a.y + a.z * a.z); }

#endif
