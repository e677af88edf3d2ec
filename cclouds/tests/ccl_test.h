/*
 * ccl_test.h -- the tiny unit-test harness of cclouds (no dependencies).
 *
 *   static void test_something(void) { CCL_CHECK(x == 1); CCL_CHECK_CLOSE(a, b, 1e-6); }
 *   int main(void) { CCL_RUN(test_something); return ccl_test_report(); }
 *
 * Each test executable is one ctest test; it prints every failed check with file and line and exits non-zero if any
 * check failed.
 */
#ifndef CCLOUDS_TEST_H
#define CCLOUDS_TEST_H

#include "cclouds/common.h"

#include <math.h>
#include <stdio.h>

static int ccl_test_checks = 0;
static int ccl_test_failures = 0;

static void ccl_test_fail(const char *file, int line, const char *what)
{
    ++ccl_test_failures;
    fprintf(stderr, "%s:%d: check failed: %s\n", file, line, what);
}

/* |a - b| <= tol_abs + tol_rel * |b|; NaN never passes unless both are NaN. */
static int ccl_test_close(double a, double b, double tol_abs, double tol_rel)
{
    if (isnan(a) || isnan(b)) return isnan(a) && isnan(b);
    return fabs(a - b) <= tol_abs + tol_rel * fabs(b);
}

/* Vector literals and the float64 length of a vector, shared by the tests (static inline: no warning where unused). */
static inline ccl_vec2 V2(float x, float y)
{
    ccl_vec2 v;
    v.x = x;
    v.y = y;
    return v;
}

static inline ccl_vec3 V(float x, float y, float z)
{
    ccl_vec3 v;
    v.x = x;
    v.y = y;
    v.z = z;
    return v;
}

static inline double len3(ccl_vec3 a)
{
    return sqrt((double)a.x * (double)a.x + (double)a.y * (double)a.y + (double)a.z * (double)a.z);
}

#define CCL_CHECK(cond) \
    do { ++ccl_test_checks; if (!(cond)) ccl_test_fail(__FILE__, __LINE__, #cond); } while (0)

#define CCL_CHECK_CLOSE(a, b, tol_abs) \
    do { \
        double ccl_a_ = (double)(a), ccl_b_ = (double)(b); \
        ++ccl_test_checks; \
        if (!ccl_test_close(ccl_a_, ccl_b_, (tol_abs), 0.0)) { \
            char ccl_msg_[256]; \
            snprintf(ccl_msg_, sizeof ccl_msg_, "%s = %.9g, expected %s = %.9g (tol %g)", #a, ccl_a_, #b, ccl_b_, \
                     (double)(tol_abs)); \
            ccl_test_fail(__FILE__, __LINE__, ccl_msg_); \
        } \
    } while (0)

#define CCL_CHECK_REL(a, b, tol_rel) \
    do { \
        double ccl_a_ = (double)(a), ccl_b_ = (double)(b); \
        ++ccl_test_checks; \
        if (!ccl_test_close(ccl_a_, ccl_b_, 0.0, (tol_rel))) { \
            char ccl_msg_[256]; \
            snprintf(ccl_msg_, sizeof ccl_msg_, "%s = %.9g, expected %s = %.9g (rel tol %g)", #a, ccl_a_, #b, \
                     ccl_b_, (double)(tol_rel)); \
            ccl_test_fail(__FILE__, __LINE__, ccl_msg_); \
        } \
    } while (0)

#define CCL_RUN(fn) \
    do { int ccl_before_ = ccl_test_failures; fn(); \
         printf("%-50s %s\n", #fn, ccl_test_failures == ccl_before_ ? "ok" : "FAILED"); } while (0)

static int ccl_test_report(void)
{
    printf("%d checks, %d failed\n", ccl_test_checks, ccl_test_failures);
    return ccl_test_failures == 0 ? 0 : 1;
}

#endif /* CCLOUDS_TEST_H */
