/* Geometric optics of a water drop, rr §2.2 and §3.2.1. See cclouds/optics.h for the conventions. */
#include "cclouds/optics.h"
#include "internal.h"

#define CCL_DEG_PER_RAD_F 57.2957795130823208768f /* 180 / pi */
#define CCL_RAD_PER_DEG_F 0.0174532925199432957692f /* pi / 180 */

ccl_vec3 ccl_optics_snell(ccl_vec3 d, ccl_vec3 n, float n1, float n2, ccl_vec3 *out_r, int *out_tir)
{
    float cos_i, eta, k;
    ccl_vec3 nn, t;
    CCL_REQUIRE(!(n1 <= 0.0f || n2 <= 0.0f));
    /* orient the normal against the incident direction */
    nn = n;
    if (ccl_vec3_dot(n, d) > 0.0f) nn = ccl_vec3_scale(n, -1.0f);
    cos_i = -ccl_vec3_dot(nn, d);
    /* law of reflection: r = d + 2 cos_i n' */
    *out_r = ccl_vec3_add(d, ccl_vec3_scale(nn, 2.0f * cos_i));
    /* Snell: t = eta d + (eta cos_i - sqrt(k)) n' */
    eta = n1 / n2;
    if (isinf(eta * eta)) {
        /* eta^2 overflows (n2 below ~5e-20 n1; Inf x 0 at normal incidence): every oblique ray is totally reflected
         * (eta^2 sin^2 > 1 for the smallest sin^2 > 0, 2^-24), a ray along the normal goes straight on */
        if (!(1.0f - cos_i * cos_i > 0.0f)) {
            *out_tir = 0;
            return d;
        }
        k = -1.0f;
    } else {
        k = 1.0f - eta * eta * (1.0f - cos_i * cos_i);
    }
    if (k < 0.0f) {
        t.x = 0.0f;
        t.y = 0.0f;
        t.z = 0.0f;
        *out_tir = 1;
        return t;
    }
    *out_tir = 0;
    return ccl_vec3_add(ccl_vec3_scale(d, eta), ccl_vec3_scale(nn, eta * cos_i - sqrtf(k)));
}

float ccl_optics_fresnel(float cos_i, float n1, float n2, float *out_rs, float *out_rp)
{
    float eta, k, cos_t, a, b, rs, rp;
    CCL_REQUIRE(!(cos_i < 0.0f || cos_i > 1.0f));
    CCL_REQUIRE(!(n1 <= 0.0f || n2 <= 0.0f));
    eta = n1 / n2;
    k = 1.0f - eta * eta * (1.0f - cos_i * cos_i);
    if (k < 0.0f) { /* beyond the critical angle: total internal reflection */
        *out_rs = 1.0f;
        *out_rp = 1.0f;
        return 1.0f;
    }
    cos_t = sqrtf(k);
    /* rr-eq2, cosine form */
    a = n1 * cos_i - n2 * cos_t;
    b = n1 * cos_i + n2 * cos_t;
    rs = (b > 0.0f) ? (a / b) * (a / b) : 1.0f; /* b = 0 only at cos_i = cos_t = 0: the grazing limit 1 */
    /* rr-eq3, cosine form */
    a = n1 * cos_t - n2 * cos_i;
    b = n1 * cos_t + n2 * cos_i;
    rp = (b > 0.0f) ? (a / b) * (a / b) : 1.0f;
    *out_rs = rs;
    *out_rp = rp;
    return 0.5f * (rs + rp);
}

float ccl_optics_drop_fov(float n, ccl_variant variant, float *out_theta_t, float *out_exit_normal, float *out_exit)
{
    float theta_t, e, x;
    CCL_REQUIRE(!(n < 1.0f || n > 2.0f));
    theta_t = asinf(1.0f / n) * CCL_DEG_PER_RAD_F;
    if (variant == CCL_VARIANT_THESIS) {
        /* the printed chain: each angle truncated to whole degrees (48.75 -> 48, 81.26 -> 81) */
        theta_t = floorf(theta_t);
        e = 2.0f * theta_t - 90.0f;
        x = floorf(asinf(fminf(n * sinf(theta_t * CCL_RAD_PER_DEG_F), 1.0f)) * CCL_DEG_PER_RAD_F);
    } else {
        /* exact: the internal angle at the exit equals theta_t, so the ray leaves tangentially */
        e = 2.0f * theta_t - 90.0f;
        x = 90.0f;
    }
    *out_theta_t = theta_t;
    *out_exit_normal = e;
    *out_exit = x;
    return 2.0f * (x - e);
}
