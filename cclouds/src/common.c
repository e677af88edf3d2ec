#include "cclouds/common.h"

#include <math.h>

const char *ccl_status_str(ccl_status status)
{
    switch (status) {
    case CCL_OK: return "ok";
    case CCL_EINVAL: return "invalid argument";
    case CCL_ENOMEM: return "out of memory";
    case CCL_EIO: return "input/output error";
    case CCL_ERANGE: return "size or index out of range";
    }
    return "unknown status";
}

int ccl_version(void)
{
    return CCL_VERSION_MAJOR * 10000 + CCL_VERSION_MINOR * 100 + CCL_VERSION_PATCH;
}

/* --- vector maths (see common.h; the operation order is the one Warp's builtins use) ----------------------------- */

ccl_vec3 ccl_vec3_add(ccl_vec3 a, ccl_vec3 b)
{
    ccl_vec3 r;
    r.x = a.x + b.x;
    r.y = a.y + b.y;
    r.z = a.z + b.z;
    return r;
}

ccl_vec3 ccl_vec3_sub(ccl_vec3 a, ccl_vec3 b)
{
    ccl_vec3 r;
    r.x = a.x - b.x;
    r.y = a.y - b.y;
    r.z = a.z - b.z;
    return r;
}

ccl_vec3 ccl_vec3_scale(ccl_vec3 a, float s)
{
    ccl_vec3 r;
    r.x = a.x * s;
    r.y = a.y * s;
    r.z = a.z * s;
    return r;
}

float ccl_vec3_dot(ccl_vec3 a, ccl_vec3 b)
{
    return a.x * b.x + a.y * b.y + a.z * b.z;
}

ccl_vec3 ccl_vec3_cross(ccl_vec3 a, ccl_vec3 b)
{
    ccl_vec3 r;
    r.x = a.y * b.z - a.z * b.y;
    r.y = a.z * b.x - a.x * b.z;
    r.z = a.x * b.y - a.y * b.x;
    return r;
}

float ccl_vec3_length(ccl_vec3 a)
{
    return sqrtf(a.x * a.x + a.y * a.y + a.z * a.z);
}

ccl_vec3 ccl_vec3_normalize(ccl_vec3 a)
{
    float l = sqrtf(a.x * a.x + a.y * a.y + a.z * a.z);
    ccl_vec3 r;
    if (l == 0.0f) { /* wp.normalize returns the zero vector; NaN (l != 0) propagates through the division */
        r.x = r.y = r.z = 0.0f;
        return r;
    }
    r.x = a.x / l;
    r.y = a.y / l;
    r.z = a.z / l;
    return r;
}
