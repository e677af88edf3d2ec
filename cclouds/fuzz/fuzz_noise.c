/* Fuzz harness: noise (cclouds/noise.h). Arbitrary float coordinates (NaN, Inf, huge, denormal), any seed, integer
 * parameters anywhere in their documented domains (period >= 0, cells >= 1, octaves in range: outside them the
 * library asserts, which this build keeps on). Contract: finite coordinates give finite values (Worley and its fBm
 * in [0, 1]); a non-finite coordinate gives NaN; curl vectors, gradients, divergences and rot are finite for every
 * finite input (up to FLT_MAX: README.md, finding 3); the seed and table forms agree bit for bit. */
#include "cclouds/noise.h"
#include "fuzz.h"

static int fin3(float x, float y, float z) { return isfinite(x) && isfinite(y) && isfinite(z); }

static int32_t fz_period(fz_reader *r) {
    int32_t p = fz_i32(r);
    return p < 0 ? (p == INT32_MIN ? 0 : -p) : p;
}

static int32_t fz_cells(fz_reader *r) {
    int32_t c = fz_period(r);
    return c < 1 ? 1 : c;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    fz_reader rd = fz_init(data, size);
    fz_reader *r = &rd;
    uint8_t which = fz_u8(r);
    float x = fz_float(r), y = fz_float(r), z = fz_float(r);
    uint32_t seed = fz_u32(r);
    int finite = fin3(x, y, z);
    uint8_t perm[CCL_NOISE_PERM_SIZE];
    FZ_CHECK(ccl_noise_perm_table(seed, perm) == CCL_OK, "perm table");
    FZ_CHECK(ccl_noise_perm_table(seed, NULL) == CCL_EINVAL, "NULL table accepted");
    switch (which % 8) {
    case 0: {
        int32_t period = fz_period(r);
        float v = ccl_noise_perlin3(x, y, z, seed, period);
        float w = ccl_noise_perlin3_perm(x, y, z, perm, period);
        FZ_CHECK(memcmp(&v, &w, sizeof v) == 0, "perlin3 seed/table forms differ");
        if (finite) FZ_CHECK(isfinite(v) && fabsf(v) <= 1.5f, "perlin3(%g, %g, %g; %u, %d) = %g", (double)x,
                             (double)y, (double)z, seed, period, (double)v);
        else FZ_CHECK(isnan(v), "perlin3 of a non-finite coordinate = %g", (double)v);
        if (period >= 1) {
            float t = ccl_noise_perlin3_tiled(x, y, z, period, seed);
            FZ_CHECK(memcmp(&v, &t, sizeof v) == 0, "perlin3_tiled != perlin3");
        }
        break;
    }
    case 1: {
        int32_t period = fz_period(r);
        ccl_noise_interp interp = (ccl_noise_interp)(fz_u8(r) % 4);
        float v = ccl_noise_perlin2(x, y, seed, period, interp);
        if (isfinite(x) && isfinite(y)) FZ_CHECK(isfinite(v) && fabsf(v) <= 1.5f, "perlin2 = %g", (double)v);
        else FZ_CHECK(isnan(v), "perlin2 of a non-finite coordinate = %g", (double)v);
        break;
    }
    case 2: {
        int32_t cells = fz_cells(r);
        ccl_worley_metric metric = (ccl_worley_metric)(fz_u8(r) % 2);
        int inverse = fz_bool(r);
        float v = ccl_noise_worley3(x, y, z, cells, seed, metric, inverse);
        if (finite) FZ_CHECK(v >= 0.0f && v <= 1.0f, "worley3(%g, %g, %g; cells %d) = %g", (double)x, (double)y,
                             (double)z, cells, (double)v);
        else FZ_CHECK(isnan(v), "worley3 of a non-finite coordinate = %g", (double)v);
        float c, f2, m;
        ccl_noise_worley3_variants(x, y, z, cells, seed, &c, &f2, &m);
        ccl_vec3 o = ccl_noise_worley_feature(fz_i32(r), fz_i32(r), fz_i32(r), cells, seed);
        FZ_CHECK(o.x >= 0.0f && o.x < 1.0f && o.y >= 0.0f && o.y < 1.0f && o.z >= 0.0f && o.z < 1.0f,
                 "feature offset outside [0, 1)");
        if (cells <= 4) {
            float b = ccl_noise_worley3_bruteforce(x, y, z, cells, seed, metric, inverse);
            if (finite) FZ_CHECK(b >= 0.0f && b <= 1.0f, "worley3_bruteforce = %g", (double)b);
        }
        break;
    }
    case 3: {
        int32_t octaves = fz_range(r, 1, 24);
        float frequency = fz_float(r);
        if (!(frequency > 0.0f)) frequency = 1.0f;
        /* the documented domain (asserted): frequency * 2^(octaves - 1) <= 2^24 (README.md, finding 6) */
        if (ldexpf(frequency, octaves - 1) > (float)CCL_NOISE_FBM_MAX_FREQUENCY)
            frequency = ldexpf((float)CCL_NOISE_FBM_MAX_FREQUENCY, 1 - octaves);
        int32_t period = fz_u8(r) < 128 ? 0 : fz_range(r, 1, (int32_t)(0x40000000 >> (octaves - 1)));
        float v = ccl_noise_fbm_perlin3(x, y, z, octaves, frequency, seed, period);
        float w = ccl_noise_fbm_perlin3_perm(x, y, z, octaves, frequency, perm, period);
        FZ_CHECK(memcmp(&v, &w, sizeof v) == 0 || (isnan(v) && isnan(w)), "fbm seed/table forms differ");
        double top = (double)frequency * ldexp(1.0, octaves - 1);
        /* finite wherever every octave's position p f_i is finite (perlin3 is finite for every finite coordinate) */
        if (finite && fabs((double)x) * top < 3.4e38 && fabs((double)y) * top < 3.4e38 && fabs((double)z) * top < 3.4e38)
            FZ_CHECK(isfinite(v) && fabsf(v) <= 1.5f, "fbm_perlin3(%.9g, %.9g, %.9g; octaves %d, frequency %.9g, seed %u, period %d) = %g", (double)x, (double)y, (double)z, octaves, (double)frequency, seed, period, (double)v);
        if (!finite) FZ_CHECK(isnan(v), "fbm_perlin3 of a non-finite coordinate = %g", (double)v);
        break;
    }
    case 4: {
        int32_t octaves = fz_range(r, 1, 16);
        int32_t cells = fz_range(r, 1, 65536 >> (octaves - 1));
        float v = ccl_noise_fbm_worley3(x, y, z, octaves, cells, seed, (ccl_worley_metric)(fz_u8(r) % 2), fz_bool(r));
        if (finite) FZ_CHECK(v >= 0.0f && v <= 1.0f, "fbm_worley3 = %g", (double)v);
        else FZ_CHECK(isnan(v), "fbm_worley3 of a non-finite coordinate = %g", (double)v);
        break;
    }
    case 5: {
        int32_t period = fz_period(r);
        float h = fz_float(r);
        if (!(h > 0.0f && h <= 0.25f)) h = 1.0f / CCL_NOISE_FD_STEP_INV;
        ccl_vec3 c = ccl_noise_curl3(x, y, z, seed, period, h);
        ccl_vec3 g = ccl_noise_gradient3(x, y, z, seed, period, h);
        float d = ccl_noise_divergence3(x, y, z, seed, period, h);
        float res = ccl_noise_curl_property(x, y, z, seed, period, h, fz_bool(r) ? CCL_VARIANT_THESIS
                                                                                 : CCL_VARIANT_CORRECTED);
        if (finite) {
            FZ_CHECK(isfinite(res), "curl_property(%g, %g, %g; h %g) not finite", (double)x, (double)y, (double)z,
                     (double)h);
            FZ_CHECK(fin3(c.x, c.y, c.z), "curl3(%g, %g, %g; h %g) not finite", (double)x, (double)y, (double)z,
                     (double)h);
            FZ_CHECK(fin3(g.x, g.y, g.z), "gradient3 not finite");
            FZ_CHECK(isfinite(d), "divergence3 not finite");
        }
        break;
    }
    case 6: {
        int32_t period = fz_period(r);
        float h = fz_float(r);
        if (!(h > 0.0f && h <= 0.25f)) h = 1.0f / CCL_NOISE_FD_STEP_INV;
        ccl_vec2 c = ccl_noise_curl2(x, y, seed, period, h);
        ccl_vec2 c2 = ccl_noise_curl2_perm(x, y, perm, period, h);
        FZ_CHECK(memcmp(&c, &c2, sizeof c) == 0 || (isnan(c.x) && isnan(c2.x)), "curl2 seed/table forms differ");
        float rot = ccl_noise_rot2(x, y, seed, period, h);
        if (isfinite(x) && isfinite(y)) {
            FZ_CHECK(isfinite(c.x) && isfinite(c.y), "curl2(%g, %g; h %g) not finite", (double)x, (double)y,
                     (double)h);
            FZ_CHECK(isfinite(rot), "rot2 not finite");
        }
        break;
    }
    default: {
        int32_t octaves = fz_range(r, 1, 24);
        ccl_vec2 p = {x, y};
        float amplitude = fz_float(r), frequency = fz_float(r), gain = fz_float(r), lacunarity = fz_float(r);
        float v = ccl_noise_fbm_perlin2(p, octaves, seed, amplitude, frequency, gain, lacunarity);
        (void)v; /* unnormalised: overflow to Inf/NaN is possible for huge amplitudes; no crash is the contract */
        float pw = ccl_noise_perlin_worley(fz_unit(r, 0.0f, 1.0f), fz_unit(r, 0.0f, 1.0f),
                                           (ccl_perlin_worley_mode)(fz_u8(r) % 5));
        FZ_CHECK(pw >= 0.0f && pw <= 1.0f, "perlin_worley = %g", (double)pw);
        break;
    }
    }
    return 0;
}
