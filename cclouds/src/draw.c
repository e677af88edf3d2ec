/* Drawing with formulas, pt §3.3 - §3.5. See cclouds/draw.h. */
#include "cclouds/draw.h"
#include "cclouds/noise.h"
#include "internal.h"

#include <math.h>

/* fBm of pt-alg-3.2 with the printed coefficients (Kod 7.9). */
static float fbm(ccl_vec2 p, int32_t octaves, const uint8_t *perm)
{
    return ccl_noise_fbm_perlin2_perm(p, octaves, perm, 1.0f, 0.5f, 0.5f, 2.0f);
}

static ccl_vec2 v2(float x, float y)
{
    ccl_vec2 r;
    r.x = x;
    r.y = y;
    return r;
}

ccl_vec2 ccl_draw_coords(ccl_vec2 frag, ccl_vec2 resolution, int aspect, ccl_vec2 *out_p, ccl_vec2 *out_polar)
{
    ccl_vec2 uv = v2(frag.x / resolution.x, frag.y / resolution.y);
    ccl_vec2 p = v2(2.0f * uv.x - 1.0f, 2.0f * uv.y - 1.0f);
    CCL_REQUIRE(resolution.x >= 1.0f && resolution.y >= 1.0f);
    if (aspect == CCL_DRAW_ASPECT_X) p.x = p.x * (resolution.x / resolution.y);
    if (out_p) *out_p = p;
    if (out_polar) *out_polar = v2(sqrtf(p.x * p.x + p.y * p.y), atan2f(p.y, p.x));
    return uv;
}

int ccl_draw_curves(ccl_vec2 p, float threshold)
{
    int colour = CCL_DRAW_BACKGROUND;
    float f1 = 0.1f * expf(p.x);
    float f2 = (p.x + 0.9f) * (p.x + 0.9f) + p.y * p.y - 0.4f;
    float f3 = 0.2f * sinf(15.0f * p.y);
    CCL_REQUIRE(threshold > 0.0f);
    if (fabsf(p.y - f1) < threshold) colour = CCL_DRAW_RED;
    if (fabsf(f2) < threshold) colour = CCL_DRAW_BLUE;
    if (fabsf(p.x - f3) < threshold) colour = CCL_DRAW_YELLOW;
    return colour;
}

float ccl_draw_marble(ccl_vec2 p, int32_t octaves, uint32_t seed, float *out_fbm, float *out_combination)
{
    uint8_t perm[CCL_NOISE_PERM_SIZE];
    float f, sine, combination;
    CCL_REQUIRE(octaves >= 1 && octaves <= 12);
    ccl_noise_perm_table(seed, perm);
    f = fbm(v2(5.0f * p.x, 5.0f * p.y), octaves, perm);
    sine = (1.0f + sinf(50.0f * p.x)) / 2.0f;
    combination = (1.0f + sinf((p.x + f / 2.0f) * 50.0f)) / 2.0f;
    if (out_fbm) *out_fbm = f;
    if (out_combination) *out_combination = combination;
    return sine;
}

/* Quilez's offsets of the vector reading (Domain Warping, 2002/2012). */
static const float warp_offsets[4][2] = {{0.0f, 0.0f}, {5.2f, 1.3f}, {1.7f, 9.2f}, {8.3f, 2.8f}};

float ccl_draw_warp(ccl_vec2 p, int32_t depth, int32_t octaves, float strength, uint32_t seed, ccl_variant variant)
{
    uint8_t perm[CCL_NOISE_PERM_SIZE];
    float qx = 0.0f, qy = 0.0f;
    int32_t k;
    CCL_REQUIRE(depth >= 0 && depth <= 2);
    CCL_REQUIRE(octaves >= 1 && octaves <= 12);
    ccl_noise_perm_table(seed, perm);
    if (depth > 2) depth = 2;
    for (k = 0; k < depth; ++k) {
        float bx = p.x + strength * qx, by = p.y + strength * qy;
        if (variant == CCL_VARIANT_THESIS) {
            float q = fbm(v2(bx, by), octaves, perm); /* scalar offset added to both components */
            qx = q;
            qy = q;
        } else {
            float nx = fbm(v2(bx + warp_offsets[2 * k][0], by + warp_offsets[2 * k][1]), octaves, perm);
            float ny = fbm(v2(bx + warp_offsets[2 * k + 1][0], by + warp_offsets[2 * k + 1][1]), octaves, perm);
            qx = nx;
            qy = ny;
        }
    }
    return fbm(v2(p.x + strength * qx, p.y + strength * qy), octaves, perm);
}

/* ---- butterfly (pt-alg-3.5 stand-in) ------------------------------------------------------------------------------ */

#define BF_TWO_PI 6.28318530717958647692f

/* Wing texture at (s, v): s = distance from the hinge / span in [0, 1], v = position along the body / span.
 * Returns 1 and the colour inside the wing, 0 outside. */
static int wing(float s, float v, ccl_vec3 *colour)
{
    float ef = ((s - 0.5f) / 0.5f) * ((s - 0.5f) / 0.5f) + ((v - 0.22f) / 0.36f) * ((v - 0.22f) / 0.36f);
    float eh = ((s - 0.38f) / 0.38f) * ((s - 0.38f) / 0.38f) + ((v + 0.2f) / 0.3f) * ((v + 0.2f) / 0.3f);
    float e = fminf(ef, eh);
    float phi = atan2f(v, s);
    ccl_vec3 c = v3(0.98f, 0.55f, 0.1f);                       /* orange base */
    int body = s < 0.06f && fabsf(v) < 0.45f;
    if (!(s >= 0.0f) || (!(e < 1.0f) && !body)) return 0;
    if (fabsf(sinf(12.0f * phi)) < 0.07f) c = v3(0.15f, 0.08f, 0.02f); /* veins radiating from the hinge */
    if (e > 0.72f) c = v3(0.05f, 0.04f, 0.03f);                    /* black border */
    if (e > 0.8f && e < 0.93f && sinf(40.0f * phi) > 0.6f) c = v3(0.95f, 0.95f, 0.9f); /* white spots */
    if (body) c = v3(0.12f, 0.09f, 0.06f);                         /* body strip along the hinge */
    *colour = c;
    return 1;
}

ccl_vec3 ccl_draw_butterfly(ccl_vec2 p, float time)
{
    const ccl_vec3 cam = v3(0.0f, 2.0f, -3.0f), target = v3(0.0f, 0.0f, 0.0f), world_up = v3(0.0f, 1.0f, 0.0f);
    const float focal = 1.5f, span = 1.0f, half_length = 0.6f;
    const float omega = BF_TWO_PI / 4.0f, flap = BF_TWO_PI * 1.5f, theta_max = 1.0f;
    ccl_vec3 fwd = ccl_vec3_normalize(ccl_vec3_sub(target, cam));
    ccl_vec3 right = ccl_vec3_normalize(ccl_vec3_cross(fwd, world_up));
    ccl_vec3 up = ccl_vec3_normalize(ccl_vec3_cross(right, fwd));
    ccl_vec3 rd = ccl_vec3_normalize(ccl_vec3_add(ccl_vec3_add(ccl_vec3_scale(right, p.x), ccl_vec3_scale(up, p.y)),
                                                  ccl_vec3_scale(fwd, focal)));
    ccl_vec3 centre = v3(0.6f * sinf(omega * time), 0.25f * sinf(2.0f * omega * time), 0.0f);
    float theta = theta_max * sinf(flap * time);
    float ct = cosf(theta), st = sinf(theta);
    float yb = 0.5f + 0.5f * p.y;
    float best = INFINITY;
    ccl_vec3 colour;
    int side;
    yb = fminf(fmaxf(yb, 0.0f), 1.0f);
    colour = v3(0.55f + 0.25f * yb, 0.75f + 0.15f * yb, 0.95f); /* sky gradient */
    for (side = -1; side <= 1; side += 2) {
        float k = (float)side;
        ccl_vec3 d = v3(k * ct, st, 0.0f);        /* span direction of this wing */
        ccl_vec3 n = v3(st, -k * ct, 0.0f);       /* cross(d, z axis) */
        float denom = ccl_vec3_dot(rd, n), t, u, v;
        ccl_vec3 q, c;
        if (fabsf(denom) < 1e-6f) continue;
        t = ccl_vec3_dot(ccl_vec3_sub(centre, cam), n) / denom;
        if (!(t > 0.0f) || !(t < best)) continue;
        q = ccl_vec3_sub(ccl_vec3_add(cam, ccl_vec3_scale(rd, t)), centre);
        u = ccl_vec3_dot(q, d);
        v = q.z;
        if (!(u >= 0.0f && u <= span && fabsf(v) <= half_length)) continue;
        if (wing(u / span, v / span, &c)) {
            float shade = 0.55f + 0.45f * fabsf(denom);
            best = t;
            colour = ccl_vec3_scale(c, shade);
        }
    }
    return colour;
}
