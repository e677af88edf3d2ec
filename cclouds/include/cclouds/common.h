/*
 * cclouds/common.h -- types shared by every cclouds header.
 *
 * Header conventions (the Python binding parses the public headers with cffi, so they stay in a plain C subset):
 *   - declarations only: no inline functions, no function-like macros, no conditional declarations;
 *   - every public function is declared on lines starting with `CCL_API`;
 *   - constants are either enum values or `#define CCL_NAME <integer>`.
 */
#ifndef CCLOUDS_COMMON_H
#define CCLOUDS_COMMON_H

#include <stdint.h>
#include <stddef.h>

#if defined(_WIN32) && defined(CCLOUDS_SHARED)
#  if defined(CCLOUDS_BUILDING)
#    define CCL_API __declspec(dllexport)
#  else
#    define CCL_API __declspec(dllimport)
#  endif
#elif defined(__GNUC__) && defined(CCLOUDS_BUILDING)
#  define CCL_API __attribute__((visibility("default")))
#else
#  define CCL_API
#endif

#ifdef __cplusplus
extern "C" {
#endif

#define CCL_VERSION_MAJOR 0
#define CCL_VERSION_MINOR 1
#define CCL_VERSION_PATCH 0

/* Result of every function that validates input, allocates or does I/O. Pure math functions return their value. */
typedef enum ccl_status {
    CCL_OK = 0,       /* success */
    CCL_EINVAL = 1,   /* an argument is outside its documented domain (NaN included) */
    CCL_ENOMEM = 2,   /* allocation failed */
    CCL_EIO = 3,      /* reading or writing a file failed */
    CCL_ERANGE = 4    /* a size or index is out of range */
} ccl_status;

/* Where a source text prints a formula that is wrong, the function takes a variant:
 * CCL_VARIANT_CORRECTED (default, the formula of the original paper / the physically right form) or
 * CCL_VARIANT_THESIS (the formula exactly as printed, kept for reproducing the text). */
typedef enum ccl_variant {
    CCL_VARIANT_CORRECTED = 0,
    CCL_VARIANT_THESIS = 1
} ccl_variant;

/* Vectors of float32 (positions in km, directions, colours), passed and returned by value. */
typedef struct {
    float x, y;
} ccl_vec2;

typedef struct {
    float x, y, z;
} ccl_vec3;

/* --- vector maths ---------------------------------------------------------------------------------------------------
 * Shared by every cclouds source (no private copies). float32 operations in the order written below, so that the
 * Warp code that mirrors a C function computes the same bits. Their Warp twins are Warp's own builtins, not catalogue
 * entries (not registered): a + b, a - b, a * s, wp.dot, wp.cross, wp.length, wp.normalize.
 * Total: NaN and Inf propagate by IEEE rules; no precondition. */

/* a + b, component-wise. Warp: a + b. */
CCL_API ccl_vec3 ccl_vec3_add(ccl_vec3 a, ccl_vec3 b);

/* a - b, component-wise. Warp: a - b. */
CCL_API ccl_vec3 ccl_vec3_sub(ccl_vec3 a, ccl_vec3 b);

/* a s, every component times the scalar s. Warp: a * s. */
CCL_API ccl_vec3 ccl_vec3_scale(ccl_vec3 a, float s);

/* Dot product a.x b.x + a.y b.y + a.z b.z (summed left to right). Warp: wp.dot(a, b). */
CCL_API float ccl_vec3_dot(ccl_vec3 a, ccl_vec3 b);

/* Cross product a x b = (a.y b.z - a.z b.y, a.z b.x - a.x b.z, a.x b.y - a.y b.x) (right-handed). Warp: wp.cross. */
CCL_API ccl_vec3 ccl_vec3_cross(ccl_vec3 a, ccl_vec3 b);

/* Euclidean length sqrt(a.x^2 + a.y^2 + a.z^2) (>= 0; no scaling against overflow, like Warp). Warp: wp.length. */
CCL_API float ccl_vec3_length(ccl_vec3 a);

/* Unit vector a / |a| (each component divided by the length). The zero vector gives the zero vector, as Warp's
 * wp.normalize does; a NaN component gives NaN components here, where wp.normalize returns the zero vector (the
 * only difference between the twins). Warp: wp.normalize. */
CCL_API ccl_vec3 ccl_vec3_normalize(ccl_vec3 a);

/* Short human-readable name of a status code ("ok", "invalid argument", ...); never NULL. */
CCL_API const char *ccl_status_str(ccl_status status);

/* Library version as MAJOR*10000 + MINOR*100 + PATCH. */
CCL_API int ccl_version(void);

#ifdef __cplusplus
}
#endif

#endif /* CCLOUDS_COMMON_H */
