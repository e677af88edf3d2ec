/* The rain particle system and the drop/streak compositing of the rr text. See cclouds/particles.h. */
#include "cclouds/particles.h"

#include <math.h>
#include <stddef.h>

#include "cclouds/hash.h"
#include "cclouds/rain.h"
#include "internal.h"

void ccl_particles_params_default(ccl_particles_params *out)
{
    ccl_vec3 lo = {-1.0f, 1.0f, -1.5f}, hi = {1.0f, 1.25f, 1.5f}, zero = {0.0f, 0.0f, 0.0f};
    out->box_min = lo;             /* rr-code-5.2.2: X in [-1, 1], Y in [1, 1.25], Z in [-1.5, 1.5] */
    out->box_max = hi;
    out->respawn_y = -1.0f;        /* rr-code-5.2.2: regenerated when Y < -1.0 */
    out->size_mean_mm = 1.3f;      /* Gauss(1, 1.3, 8) */
    out->size_spread_mm = 1.0f;
    out->size_samples = 8;
    out->slowdown = 4.0f;          /* "slowed down four times" */
    out->metres_per_unit = 1.0f;   /* not given (erratum 17): a scene unit is a metre */
    out->wind = zero;              /* our extension */
    out->seed = 0u;
}

static int within3(ccl_vec3 v)
{
    return fabsf(v.x) <= CCL_PARTICLES_MAX_EXTENT && fabsf(v.y) <= CCL_PARTICLES_MAX_EXTENT
           && fabsf(v.z) <= CCL_PARTICLES_MAX_EXTENT;
}

static int finite3(ccl_vec3 v) { return isfinite(v.x) && isfinite(v.y) && isfinite(v.z); }

ccl_status ccl_particles_params_check(const ccl_particles_params *p, const char **field)
{
    const char *bad = NULL;
    if (!p) bad = "params";
    else if (!within3(p->box_min)) bad = "box_min";
    else if (!within3(p->box_max) || !(p->box_min.x < p->box_max.x) || !(p->box_min.y < p->box_max.y)
             || !(p->box_min.z < p->box_max.z)) bad = "box_max";
    else if (!(p->respawn_y >= -CCL_PARTICLES_MAX_EXTENT && p->respawn_y < p->box_min.y)) bad = "respawn_y";
    else if (!isfinite(p->size_spread_mm) || !(p->size_spread_mm >= 0.0f)) bad = "size_spread_mm";
    else if (!isfinite(p->size_mean_mm) || !(p->size_mean_mm - 0.5f * p->size_spread_mm >= 0.1f)
             || !(p->size_mean_mm + 0.5f * p->size_spread_mm <= 4.5f)) bad = "size_mean_mm";
    else if (p->size_samples < 1 || p->size_samples > CCL_PARTICLES_MAX_SIZE_SAMPLES) bad = "size_samples";
    else if (!isfinite(p->slowdown) || !(p->slowdown >= 0.015625f && p->slowdown <= 1000.0f)) bad = "slowdown";
    else if (!isfinite(p->metres_per_unit) || !(p->metres_per_unit >= CCL_PARTICLES_MIN_METRES_PER_UNIT)) bad = "metres_per_unit";
    else if (!finite3(p->wind) || p->wind.y != 0.0f) bad = "wind";
    if (field) *field = bad;
    return bad ? CCL_EINVAL : CCL_OK;
}

float ccl_particles_uniform(uint32_t seed, uint32_t index, uint32_t generation, uint32_t k)
{
    uint32_t key = ccl_hash_pcg(ccl_hash_pcg(ccl_hash_pcg(seed) ^ index) ^ generation);
    return ccl_hash_unit(ccl_hash_pcg(key + k));
}

float ccl_particles_gauss(uint32_t seed, uint32_t index, uint32_t generation, float mean, float spread, int samples)
{
    float sum = 0.0f;
    int k;
    CCL_REQUIRE(samples >= 1 && samples <= CCL_PARTICLES_MAX_SIZE_SAMPLES);
    if (samples < 1) samples = 1;
    if (samples > CCL_PARTICLES_MAX_SIZE_SAMPLES) samples = CCL_PARTICLES_MAX_SIZE_SAMPLES;
    for (k = 0; k < samples; ++k) sum += ccl_particles_uniform(seed, index, generation, 3u + (uint32_t)k);
    return mean + spread * (sum / (float)samples - 0.5f);
}

void ccl_particles_spawn(const ccl_particles_params *p, uint32_t index, uint32_t generation, int warm,
                         ccl_vec3 *out_pos, float *out_radius_mm, float *out_speed)
{
    float ux = ccl_particles_uniform(p->seed, index, generation, 0u);
    float uy = ccl_particles_uniform(p->seed, index, generation, 1u);
    float uz = ccl_particles_uniform(p->seed, index, generation, 2u);
    float y0 = warm ? p->respawn_y : p->box_min.y;
    float r = ccl_particles_gauss(p->seed, index, generation, p->size_mean_mm, p->size_spread_mm, p->size_samples);
    out_pos->x = p->box_min.x + (p->box_max.x - p->box_min.x) * ux;
    out_pos->y = y0 + (p->box_max.y - y0) * uy;
    out_pos->z = p->box_min.z + (p->box_max.z - p->box_min.z) * uz;
    *out_radius_mm = r;
    *out_speed = ccl_rain_terminal_speed(r, p->slowdown) / p->metres_per_unit;
}

static float wrap(float v, float lo, float hi)
{
    float w = hi - lo;
    if (v < lo) v = v + w;
    if (v >= hi) v = v - w;
    return v;
}

void ccl_particles_step(const ccl_particles_params *p, uint32_t index, float dt, ccl_vec3 *pos, float *radius_mm,
                        float *speed, uint32_t *generation)
{
    if (pos->y < p->respawn_y) {
        *generation = *generation + 1u;
        ccl_particles_spawn(p, index, *generation, 0, pos, radius_mm, speed);
    }
    pos->y = pos->y - dt * *speed;
    pos->x = wrap(pos->x + dt * p->wind.x, p->box_min.x, p->box_max.x);
    pos->z = wrap(pos->z + dt * p->wind.z, p->box_min.z, p->box_max.z);
}

ccl_status ccl_particles_simulate(const ccl_particles_params *p, int requested, float dt, int frames, int warm,
                                  ccl_variant variant, int capacity, ccl_vec3 *pos, float *radius_mm, float *speed,
                                  uint32_t *generation, int *count)
{
    int f, i;
    if (ccl_particles_params_check(p, NULL) != CCL_OK || !count) return CCL_EINVAL;
    if (capacity < 0 || capacity > CCL_PARTICLES_MAX_COUNT || requested < 0 || requested > capacity || frames < 0)
        return CCL_EINVAL;
    if (!(dt >= 0.0f && dt <= 1.0f) || fabsf(p->wind.x) * dt > p->box_max.x - p->box_min.x
        || fabsf(p->wind.z) * dt > p->box_max.z - p->box_min.z)
        return CCL_EINVAL;
    if (variant != CCL_VARIANT_CORRECTED && variant != CCL_VARIANT_THESIS) return CCL_EINVAL;
    if (*count > capacity) return CCL_EINVAL;
    if (capacity > 0 && (!pos || !radius_mm || !speed || !generation)) return CCL_EINVAL;
    if (warm && variant == CCL_VARIANT_CORRECTED && *count == 0) {
        for (i = 0; i < requested; ++i) {
            generation[i] = 0u;
            ccl_particles_spawn(p, (uint32_t)i, 0u, 1, &pos[i], &radius_mm[i], &speed[i]);
        }
        *count = requested;
    }
    for (f = 0; f < frames; ++f) {
        int n;
        if (variant == CCL_VARIANT_CORRECTED) {
            if (*count > requested) *count = requested;  /* removal when the count is lowered (not in the text) */
            if (*count < requested) {
                i = *count;
                generation[i] = 0u;
                ccl_particles_spawn(p, (uint32_t)i, 0u, 0, &pos[i], &radius_mm[i], &speed[i]);
                *count = *count + 1;
            }
        } else if (*count < requested) {
            /* as printed: GenerateNewParticle() then numberOfGeneratedParticles - 1; a slot below 0 does not exist,
             * so the new particle is written nowhere and never simulated */
            if (*count >= 0 && *count < capacity) {
                i = *count;
                generation[i] = 0u;
                ccl_particles_spawn(p, (uint32_t)i, 0u, 0, &pos[i], &radius_mm[i], &speed[i]);
            }
            if (*count > -CCL_PARTICLES_MAX_COUNT) *count = *count - 1;
        }
        n = *count < 0 ? 0 : *count;
        for (i = 0; i < n; ++i) ccl_particles_step(p, (uint32_t)i, dt, &pos[i], &radius_mm[i], &speed[i], &generation[i]);
    }
    return CCL_OK;
}

float ccl_particles_streak(float speed, float persistence_s, float radius, float *out_tap_offset)
{
    float length = speed * persistence_s;
    CCL_REQUIRE(!(speed < 0.0f) && !(persistence_s < 0.0f) && !(radius <= 0.0f));
    *out_tap_offset = (length / 6.0f) / (2.0f * radius + length);
    return length;
}

ccl_vec2 ccl_particles_capture_uv(ccl_vec2 ndc, float aspect, float fov_view, float fov_capture)
{
    ccl_vec2 uv;
    float ratio = tanf(0.5f * fov_view) / tanf(0.5f * fov_capture);
    CCL_REQUIRE(!(aspect <= 0.0f) && !(fov_capture < CCL_PARTICLES_MIN_FOV_CAPTURE));
    uv.x = 0.5f + 0.5f * (ndc.x * aspect * ratio);
    uv.y = 0.5f - 0.5f * (ndc.y * ratio);
    return uv;
}

static int clampi(int v, int lo, int hi) { return v < lo ? lo : (v > hi ? hi : v); }

static ccl_vec3 texel(const float *img, int size, int x, int y)
{
    const float *t = img + 3 * ((size_t)clampi(y, 0, size - 1) * (size_t)size + (size_t)clampi(x, 0, size - 1));
    ccl_vec3 c;
    c.x = t[0];
    c.y = t[1];
    c.z = t[2];
    return c;
}

static ccl_vec3 fetch(const float *img, int size, float u, float v, int filter)
{
    if (!(u == u && v == v)) { /* NaN propagates */
        ccl_vec3 nan3;
        nan3.x = nan3.y = nan3.z = u + v;
        return nan3;
    }
    if (filter == CCL_PARTICLES_LINEAR) {
        float fx = bound_cell(u * (float)size - 0.5f, size), fy = bound_cell(v * (float)size - 0.5f, size);
        float x0f = floorf(fx), y0f = floorf(fy);
        float ax = fx - x0f, ay = fy - y0f;
        int x0 = (int)x0f, y0 = (int)y0f;
        ccl_vec3 a = texel(img, size, x0, y0), b = texel(img, size, x0 + 1, y0);
        ccl_vec3 c = texel(img, size, x0, y0 + 1), d = texel(img, size, x0 + 1, y0 + 1);
        ccl_vec3 top, bot, out;
        top.x = a.x + (b.x - a.x) * ax;
        top.y = a.y + (b.y - a.y) * ax;
        top.z = a.z + (b.z - a.z) * ax;
        bot.x = c.x + (d.x - c.x) * ax;
        bot.y = c.y + (d.y - c.y) * ax;
        bot.z = c.z + (d.z - c.z) * ax;
        out.x = top.x + (bot.x - top.x) * ay;
        out.y = top.y + (bot.y - top.y) * ay;
        out.z = top.z + (bot.z - top.z) * ay;
        return out;
    }
    return texel(img, size, (int)floorf(bound_cell(u * (float)size, size)),
                 (int)floorf(bound_cell(v * (float)size, size)));
}

int ccl_particles_tap(const float *mask, int mask_size, const float *capture, int capture_size, float mask_u,
                      float mask_v, ccl_vec2 p_o, float scale, int filter, ccl_vec3 *out_rgb)
{
    const float *m;
    int mx, my;
    float uc, vc, qx, qy;
    if (!(mask_u >= 0.0f && mask_u < 1.0f && mask_v >= 0.0f && mask_v < 1.0f)) return 0;
    mx = clampi((int)(mask_u * (float)mask_size), 0, mask_size - 1);
    my = clampi((int)(mask_v * (float)mask_size), 0, mask_size - 1);
    m = mask + 4 * ((size_t)my * (size_t)mask_size + (size_t)mx);
    if (!(m[3] > 0.0f && m[2] > 0.0f)) return 0;
    qx = m[0] / m[2];
    qy = m[1] / m[2];
    if (qx != qx || qy != qy) return 0; /* a NaN exit direction (or 0/0, Inf/Inf): the texel has no ray */
    uc = p_o.x + scale * qx;
    vc = p_o.y - scale * qy;
    *out_rgb = fetch(capture, capture_size, uc, vc, filter);
    return 1;
}

static ccl_vec3 light_tap(const ccl_particles_lights *L, ccl_vec3 p, const float *nt, ccl_vec3 c_o)
{
    ccl_vec3 n, eye = {0.0f, 0.0f, 0.0f};
    n.x = nt[0] * L->right.x + nt[1] * L->up.x + nt[2] * L->forward.x;
    n.y = nt[0] * L->right.y + nt[1] * L->up.y + nt[2] * L->forward.y;
    n.z = nt[0] * L->right.z + nt[1] * L->up.z + nt[2] * L->forward.z;
    return ccl_rain_light_colour(c_o, L->ambient, p, n, eye, L->l1, L->c_l1, L->l2, L->c_l2, L->r_half, L->variant);
}

/* The second integral of the exposure weight w(s) = 1 - cos(2 pi s) on [0, 1] (0 before, 1 after): s^2/2 +
 * (cos 2 pi s - 1) / (2 pi)^2 inside, s - 1/2 after. */
static float exposure_w2(float s)
{
    const float k = 2.0f * CCL_PI_F;
    if (s <= 0.0f) return 0.0f;
    if (s >= 1.0f) return s - 0.5f;
    return 0.5f * s * s + (cosf(k * s) - 1.0f) / (k * k);
}

/* exposure_w2(s) - (s - 1/2): 0 after the exposure, so that differences near its end do not cancel. */
static float exposure_w2_end(float s)
{
    const float k = 2.0f * CCL_PI_F;
    float t = 1.0f - s;
    if (s >= 1.0f) return 0.0f;
    return 0.5f * t * t + (cosf(k * t) - 1.0f) / (k * k);
}

static float sinc(float x) { return fabsf(x) < 1e-4f ? 1.0f : sinf(x) / x; }

/* int_0^u 2 sqrt(r^2 - t^2) dt for u in [-r, r]: the area of the disc left of u, less half the disc */
static float chord_integral(float u, float r)
{
    float q = u / r;
    if (q > 1.0f) q = 1.0f;
    if (q < -1.0f) q = -1.0f;
    return r * r * (q * sqrtf(fmaxf(1.0f - q * q, 0.0f)) + asinf(q));
}

float ccl_particles_streak_cover(const ccl_particles_sprite *sprite, float px, float py, float *out_mask_u,
                                 float *out_half_chord)
{
    const float k = 2.0f * CCL_PI_F;
    float r = sprite->radius, travel = 2.0f * (sprite->half_height - sprite->radius);
    float len = fmaxf(travel, CCL_PARTICLES_MIN_STREAK_PX);
    float head = sprite->cy + 0.5f * travel;
    float dx = px - sprite->cx, lo = fmaxf(dx - 0.5f, -r), hi = fminf(dx + 0.5f, r);
    float cover, h, a, e, d, alpha;
    *out_mask_u = 0.5f;
    *out_half_chord = 0.0f;
    if (!(hi > lo)) return 0.0f;
    cover = hi - lo;
    h = 0.5f * (chord_integral(hi, r) - chord_integral(lo, r)) / cover;
    *out_mask_u = 0.5f * (lo + hi) / (2.0f * r) + 0.5f;
    *out_half_chord = h;
    /* the pixel row [py - 1/2, py + 1/2] sees the chord [y - h, y + h] around the centre y = head - len (1 - s) at
     * exposure time s in [0, 1] when s is within d = h / len of a = 1 + (py - head) / len, over the row's e = 1/(2 len):
     * alpha = cover len (W2(a+e+d) - W2(a-e+d) - W2(a+e-d) + W2(a-e-d)), W2 = exposure_w2 */
    a = 1.0f + (py - head) / len;
    e = 0.5f / len;
    d = h / len;
    if (a + e + d <= 0.0f || a - e - d >= 1.0f) return 0.0f;
    if (a - e - d >= 0.0f && a + e + d <= 1.0f) /* inside the exposure: the same sum in closed form */
        alpha = cover * (2.0f * h / len) * (1.0f - sinc(k * e) * sinc(k * d) * cosf(k * a));
    else if (a - e - d >= 0.0f)
        alpha = cover * len * (exposure_w2_end(a + e + d) - exposure_w2_end(a - e + d) - exposure_w2_end(a + e - d)
                               + exposure_w2_end(a - e - d));
    else
        alpha = cover * len * (exposure_w2(a + e + d) - exposure_w2(a - e + d) - exposure_w2(a + e - d)
                               + exposure_w2(a - e - d));
    return fminf(fmaxf(alpha, 0.0f), 1.0f);
}

static ccl_vec3 shade(const ccl_particles_sprite *sprites, const ccl_vec3 *positions, int n, const float *mask,
                      const float *normals, int mask_size, const float *capture, int capture_size, int x, int y,
                      ccl_vec2 p_o, float scale, int filter, int streaks, float opacity,
                      const ccl_particles_lights *lights, ccl_vec3 bg)
{
    float px = (float)x + 0.5f, py = (float)y + 0.5f;
    ccl_vec3 c = bg;
    int j;
    if (n > CCL_PARTICLES_MAX_COUNT) n = CCL_PARTICLES_MAX_COUNT;
    for (j = 0; j < n; ++j) {
        const ccl_particles_sprite *s = &sprites[j];
        float dx = px - s->cx, dy = py - s->cy, mu, mv;
        ccl_vec3 sum = {0.0f, 0.0f, 0.0f}, rgb;
        int hits = 0, i, lo = 0, hi = 0;
        float alpha;
        if (streaks == CCL_PARTICLES_STREAKS_PHYSICAL) {
            float h, cover;
            if (!(fabsf(dx) < s->radius + 0.5f && fabsf(dy) < s->half_height + 0.5f)) continue;
            cover = ccl_particles_streak_cover(s, px, py, &mu, &h);
            if (!(cover > 0.0f)) continue;
            for (i = 0; i < CCL_PARTICLES_STREAK_SAMPLES; ++i) {
                float tv = 0.5f + h * ((2.0f * (float)i + 1.0f) / (float)CCL_PARTICLES_STREAK_SAMPLES - 1.0f)
                                      / (2.0f * s->radius);
                if (ccl_particles_tap(mask, mask_size, capture, capture_size, mu, tv, p_o, scale, filter, &rgb)) {
                    if (lights) {
                        int mx = clampi((int)(mu * (float)mask_size), 0, mask_size - 1);
                        int my = clampi((int)(tv * (float)mask_size), 0, mask_size - 1);
                        rgb = light_tap(lights, positions[j],
                                        normals + 3 * ((size_t)my * (size_t)mask_size + (size_t)mx), rgb);
                    }
                    sum.x += rgb.x;
                    sum.y += rgb.y;
                    sum.z += rgb.z;
                    ++hits;
                }
            }
            if (hits == 0) continue;
            alpha = opacity * cover;
            c.x = c.x + (sum.x / (float)hits - c.x) * alpha;
            c.y = c.y + (sum.y / (float)hits - c.y) * alpha;
            c.z = c.z + (sum.z / (float)hits - c.z) * alpha;
            continue;
        }
        if (!(fabsf(dx) < s->radius && fabsf(dy) < s->half_height)) continue;
        mu = dx / (2.0f * s->radius) + 0.5f;
        mv = dy / (2.0f * s->half_height) + 0.5f;
        if (streaks) {
            lo = -(CCL_PARTICLES_STREAK_TAPS / 2);
            hi = CCL_PARTICLES_STREAK_TAPS / 2;
        }
        for (i = lo; i <= hi; ++i) {
            float tv = mv - (float)i * s->tap_offset;
            if (ccl_particles_tap(mask, mask_size, capture, capture_size, mu, tv, p_o, scale, filter, &rgb)) {
                if (lights) {
                    /* the texel ccl_particles_tap read (it hit, so mu and tv are in [0, 1)) */
                    int mx = clampi((int)(mu * (float)mask_size), 0, mask_size - 1);
                    int my = clampi((int)(tv * (float)mask_size), 0, mask_size - 1);
                    rgb = light_tap(lights, positions[j], normals + 3 * ((size_t)my * (size_t)mask_size + (size_t)mx),
                                    rgb);
                }
                sum.x += rgb.x;
                sum.y += rgb.y;
                sum.z += rgb.z;
                ++hits;
            }
        }
        if (hits == 0) continue;
        alpha = streaks ? opacity * ((float)hits / (float)CCL_PARTICLES_STREAK_TAPS) : opacity;
        c.x = c.x + (sum.x / (float)hits - c.x) * alpha;
        c.y = c.y + (sum.y / (float)hits - c.y) * alpha;
        c.z = c.z + (sum.z / (float)hits - c.z) * alpha;
    }
    return c;
}

ccl_vec3 ccl_particles_shade_pixel(const ccl_particles_sprite *sprites, int n, const float *mask, int mask_size,
                                   const float *capture, int capture_size, int x, int y, ccl_vec2 p_o, float scale,
                                   int filter, int streaks, float opacity, ccl_vec3 bg)
{
    return shade(sprites, NULL, n, mask, NULL, mask_size, capture, capture_size, x, y, p_o, scale, filter, streaks,
                 opacity, NULL, bg);
}

ccl_vec3 ccl_particles_shade_pixel_lit(const ccl_particles_sprite *sprites, const ccl_vec3 *positions, int n,
                                       const float *mask, const float *normals, int mask_size, const float *capture,
                                       int capture_size, int x, int y, ccl_vec2 p_o, float scale, int filter,
                                       int streaks, float opacity, const ccl_particles_lights *lights, ccl_vec3 bg)
{
    if (lights && (!positions || !normals)) lights = NULL;
    return shade(sprites, positions, n, mask, normals, mask_size, capture, capture_size, x, y, p_o, scale, filter,
                 streaks, opacity, lights, bg);
}

ccl_status ccl_particles_composite(const float *background, int width, int height, const ccl_particles_sprite *sprites,
                                   int n, const float *mask, int mask_size, const float *capture, int capture_size,
                                   float fov_view, float fov_capture, int filter, int streaks, float opacity,
                                   float *out)
{
    int x, y, j;
    float scale, aspect;
    if (!background || !mask || !capture || !out || width < 1 || height < 1 || mask_size < 1 || capture_size < 1)
        return CCL_EINVAL;
    if (n < 0 || n > CCL_PARTICLES_MAX_COUNT || (n > 0 && !sprites)) return CCL_EINVAL;
    if (!(fov_view > 0.0f && fov_view < CCL_PI_F)) return CCL_EINVAL;
    if (!(fov_capture >= CCL_PARTICLES_MIN_FOV_CAPTURE && fov_capture < CCL_PI_F)) return CCL_EINVAL;
    if (filter != CCL_PARTICLES_NEAREST && filter != CCL_PARTICLES_LINEAR) return CCL_EINVAL;
    if (streaks != CCL_PARTICLES_DROPS && streaks != CCL_PARTICLES_STREAKS_THESIS
        && streaks != CCL_PARTICLES_STREAKS_PHYSICAL)
        return CCL_EINVAL;
    if (!(opacity >= 0.0f && opacity <= 1.0f)) return CCL_EINVAL;
    for (j = 0; j < n; ++j)
        if (!(sprites[j].radius > 0.0f) || !(sprites[j].half_height >= sprites[j].radius)) return CCL_EINVAL;
    scale = 0.5f / tanf(0.5f * fov_capture);
    aspect = (float)width / (float)height;
    for (y = 0; y < height; ++y) {
        for (x = 0; x < width; ++x) {
            size_t k = 3 * ((size_t)y * (size_t)width + (size_t)x);
            ccl_vec2 ndc, p_o;
            ccl_vec3 bg, c;
            ndc.x = 2.0f * (((float)x + 0.5f) / (float)width) - 1.0f;
            ndc.y = 1.0f - 2.0f * (((float)y + 0.5f) / (float)height);
            p_o = ccl_particles_capture_uv(ndc, aspect, fov_view, fov_capture);
            bg.x = background[k];
            bg.y = background[k + 1];
            bg.z = background[k + 2];
            c = ccl_particles_shade_pixel(sprites, n, mask, mask_size, capture, capture_size, x, y, p_o, scale, filter,
                                          streaks, opacity, bg);
            out[k] = c.x;
            out[k + 1] = c.y;
            out[k + 2] = c.z;
        }
    }
    return CCL_OK;
}
