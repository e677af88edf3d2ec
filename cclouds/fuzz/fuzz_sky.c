/* Fuzz harness: sky setup (cclouds/sky.h): ccl_sky_preetham_init and ccl_sky_gradient_init with arbitrary floats
 * (NaN, Inf, huge) and any variant value. Contract: CCL_OK exactly for the documented domain (2 <= T <= 10,
 * 0 <= theta_s <= pi/2, 0 < exposure < inf, variant 0 or 1; gradient colours finite and >= 0, exponent finite and
 * > 0); CCL_EINVAL leaves *out untouched; after CCL_OK the per-pixel colour of any unit view direction is finite. */
#include "cclouds/sky.h"
#include "fuzz.h"

static ccl_vec3 fz_dir(fz_reader *r) {
    ccl_vec3 d = {fz_unit(r, -1.0f, 1.0f), fz_unit(r, -1.0f, 1.0f), fz_unit(r, -1.0f, 1.0f)};
    if (fz_u8(r) < 32) { /* axis directions and the horizon exactly */
        static const ccl_vec3 axes[] = {{0, 1, 0}, {0, -1, 0}, {1, 0, 0}, {0, 0, -1}, {0.70710678f, 0, 0.70710678f}};
        return axes[fz_u8(r) % 5];
    }
    if (ccl_vec3_length(d) < 1e-3f) d.y = 1.0f;
    return ccl_vec3_normalize(d);
}

static ccl_vec3 fz_colour(fz_reader *r) {
    ccl_vec3 c;
    c.x = fz_u8(r) < 128 ? fz_unit(r, 0.0f, 2.0f) : (fz_u8(r) < 64 ? CCL_SKY_GRADIENT_MAX_COLOUR : fz_float(r));
    c.y = fz_u8(r) < 128 ? fz_unit(r, 0.0f, 2.0f) : (fz_u8(r) < 64 ? CCL_SKY_GRADIENT_MAX_COLOUR : fz_float(r));
    c.z = fz_u8(r) < 128 ? fz_unit(r, 0.0f, 2.0f) : (fz_u8(r) < 64 ? CCL_SKY_GRADIENT_MAX_COLOUR : fz_float(r));
    return c;
}

/* the documented colour domain of the gradient sky: [0, CCL_SKY_GRADIENT_MAX_COLOUR] per component (finding N2) */
static int colour_ok(ccl_vec3 c) {
    return c.x >= 0.0f && c.y >= 0.0f && c.z >= 0.0f && c.x <= CCL_SKY_GRADIENT_MAX_COLOUR &&
           c.y <= CCL_SKY_GRADIENT_MAX_COLOUR && c.z <= CCL_SKY_GRADIENT_MAX_COLOUR;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    fz_reader rd = fz_init(data, size);
    fz_reader *r = &rd;
    if (fz_bool(r)) {
        float turbidity = fz_u8(r) < 128 ? fz_unit(r, 1.5f, 10.5f) : fz_float(r);
        float theta_s = fz_u8(r) < 128 ? fz_unit(r, -0.1f, 1.7f) : fz_float(r);
        float exposure = fz_u8(r) < 128 ? fz_unit(r, 0.0f, 1.0f) : fz_float(r);
        int32_t variant = fz_u8(r) < 200 ? (int32_t)(fz_u8(r) % 2) : fz_i32(r);
        ccl_preetham p, before;
        memset(&p, 0xA5, sizeof p);
        before = p;
        ccl_status st = ccl_sky_preetham_init(turbidity, theta_s, exposure, (ccl_variant)variant, &p);
        int valid = turbidity >= 2.0f && turbidity <= 10.0f && theta_s >= 0.0f && theta_s <= 1.57079637f &&
                    exposure > 0.0f && exposure < INFINITY && (variant == 0 || variant == 1);
        FZ_CHECK((st == CCL_OK) == valid, "preetham_init(T %g, theta_s %.9g, k %g, variant %d) = %d", (double)turbidity,
                 (double)theta_s, (double)exposure, variant, (int)st);
        FZ_CHECK(ccl_sky_preetham_init(turbidity, theta_s, exposure, (ccl_variant)variant, NULL) == CCL_EINVAL,
                 "NULL out accepted");
        if (st != CCL_OK) {
            FZ_CHECK(memcmp(&p, &before, sizeof p) == 0, "*out written on CCL_EINVAL");
            return 0;
        }
        /* sun with zenith angle theta_s, any azimuth */
        float az = fz_unit(r, 0.0f, 6.2831853f);
        ccl_vec3 sun = {sinf(theta_s) * cosf(az), cosf(theta_s), sinf(theta_s) * sinf(az)};
        for (int i = 0; i < 4; ++i) {
            ccl_vec3 d = fz_dir(r);
            ccl_vec3 c = ccl_sky_preetham_rgb(d, sun, &p);
            ccl_vec3 h = ccl_sky_preetham_hdr(d, sun, &p);
            ccl_vec3 x = ccl_sky_preetham_xyY(d, sun, &p);
            /* the thesis variant's tone map 1 - exp(+k C) is <= 0 and reaches -Inf for k C > 88 (documented) where
             * the HDR colour C is >= 0; a channel of a colour outside the sRGB gamut (the xyY -> RGB matrix: e.g. the
             * blue of the horizon under a sun on the horizon at T = 2) is negative, and there 1 - exp(k C) is in [0, 1]
             * (0 or 1 where k C rounds to 0 or exp underflows) */
            if (variant == CCL_VARIANT_THESIS)
                FZ_CHECK((h.x >= 0.0f ? c.x <= 0.0f : c.x >= 0.0f && c.x <= 1.0f) &&
                         (h.y >= 0.0f ? c.y <= 0.0f : c.y >= 0.0f && c.y <= 1.0f) &&
                         (h.z >= 0.0f ? c.z <= 0.0f : c.z >= 0.0f && c.z <= 1.0f),
                         "thesis preetham_rgb not 1 - exp(k C) in sign (c %g %g %g, hdr %g %g %g)", (double)c.x,
                         (double)c.y, (double)c.z, (double)h.x, (double)h.y, (double)h.z);
            else
            FZ_CHECK(isfinite(c.x) && isfinite(c.y) && isfinite(c.z), "preetham_rgb not finite (T %g, theta_s %.9g, "
                     "k %g, variant %d, d %g %g %g)", (double)turbidity, (double)theta_s, (double)exposure, variant,
                     (double)d.x, (double)d.y, (double)d.z);
            FZ_CHECK(isfinite(h.x) && isfinite(h.y) && isfinite(h.z), "preetham_hdr not finite");
            FZ_CHECK(isfinite(x.x) && isfinite(x.y) && isfinite(x.z), "preetham_xyY not finite");
        }
    } else {
        ccl_vec3 hz = fz_colour(r), zn = fz_colour(r), sn = fz_colour(r);
        float e = fz_u8(r) < 128 ? fz_unit(r, 0.0f, 256.0f) : fz_float(r);
        ccl_sky_gradient g, before;
        memset(&g, 0x5A, sizeof g);
        before = g;
        ccl_status st = ccl_sky_gradient_init(hz, zn, sn, e, &g);
        int valid = colour_ok(hz) && colour_ok(zn) && colour_ok(sn) && isfinite(e) && e > 0.0f;
        FZ_CHECK((st == CCL_OK) == valid, "gradient_init status %d, expected valid %d", (int)st, valid);
        FZ_CHECK(ccl_sky_gradient_init(hz, zn, sn, e, NULL) == CCL_EINVAL, "NULL out accepted");
        if (st != CCL_OK) {
            FZ_CHECK(memcmp(&g, &before, sizeof g) == 0, "*out written on CCL_EINVAL");
            return 0;
        }
        ccl_vec3 sun = fz_dir(r);
        for (int i = 0; i < 4; ++i) {
            ccl_vec3 d = fz_dir(r);
            ccl_vec3 c = ccl_sky_gradient_rgb(d, sun, &g);
            /* accepted colours are at most 1e6: finite and non-negative for any exponent (the cosine is clamped
             * to [0, 1], README.md, finding 4) */
            FZ_CHECK(!isnan(c.x) && !isnan(c.y) && !isnan(c.z) && c.x >= 0.0f && c.y >= 0.0f && c.z >= 0.0f,
                     "gradient_rgb = (%g, %g, %g)", (double)c.x, (double)c.y, (double)c.z);
            FZ_CHECK(isfinite(c.x) && isfinite(c.y) && isfinite(c.z), "gradient_rgb not finite: h %g %g %g z %g %g %g s %g %g %g e %g d %g %g %g sun %g %g %g -> %g %g %g", (double)hz.x, (double)hz.y, (double)hz.z, (double)zn.x, (double)zn.y, (double)zn.z, (double)sn.x, (double)sn.y, (double)sn.z, (double)e, (double)d.x, (double)d.y, (double)d.z, (double)sun.x, (double)sun.y, (double)sun.z, (double)c.x, (double)c.y, (double)c.z);
        }
    }
    return 0;
}
