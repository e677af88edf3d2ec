/* Private helpers shared by the cclouds sources (not installed). */
#ifndef CCLOUDS_INTERNAL_H
#define CCLOUDS_INTERNAL_H

#include <assert.h>
#include <math.h>

#define CCL_PI_F 3.14159265358979323846f
#define CCL_INV_4PI_F 0.0795774715459476679f /* 1 / (4 pi) */

/* Precondition check: active in debug builds, compiled out with NDEBUG. NaN arguments pass (they propagate). */
#define CCL_REQUIRE(cond) assert(cond)

#endif /* CCLOUDS_INTERNAL_H */
