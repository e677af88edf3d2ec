/* The aircraft of oc §6: attitude from height points, flight model, procedural model. See cclouds/flight.h. */
#include "cclouds/flight.h"
#include "internal.h"

#include <stddef.h>

void ccl_flight_params_default(ccl_flight_params *out)
{
    if (out == NULL) return;
    /* The text gives none of these values (oc-6.1.1 "Not given"); the reasons: */
    out->length = 7.5f;       /* |AB| of the procedural model (nose z = -3.75, tail z = +3.75) */
    out->span = 12.0f;        /* |CD|: the model's wing span */
    out->point_rate = 1.0f;   /* 1 m/s: a 1 s press tilts the nose by atan(2/7.5) = 15 deg, the wings by 9.5 deg */
    out->max_pitch = 0.5f;    /* 29 deg: steep climbs and dives, never a loop (the model has no loop) */
    out->max_roll = 0.8f;     /* 46 deg: a steep bank, never a roll-over */
    out->level_rate = 0.0f;   /* the text does not level the plane by itself: it keeps its attitude */
    out->max_speed = 60.0f;   /* 60 m/s = 216 km/h: a light aircraft's cruise speed */
    out->acceleration = 8.0f; /* 0 -> 60 m/s in 7.5 s of W */
    out->turn_rate = 0.8f;    /* at 30 deg bank and full speed 0.4 rad/s: a full circle in 16 s */
    out->min_altitude = 5.0f; /* the ground (y = 0) plus the height of E above the wheels */
}

static int finite_f(float v) { return v == v && v - v == 0.0f; }

ccl_status ccl_flight_check(const ccl_flight_params *p, const char **out_field)
{
    const char *bad = NULL;
    const float half_pi = 1.5707964f;
    if (p == NULL) bad = "params";
    else if (!finite_f(p->length) || !(p->length > 0.0f)) bad = "length";
    else if (!finite_f(p->span) || !(p->span > 0.0f)) bad = "span";
    else if (!finite_f(p->point_rate) || !(p->point_rate >= 0.0f)) bad = "point_rate";
    else if (!finite_f(p->max_pitch) || !(p->max_pitch > 0.0f && p->max_pitch < half_pi)) bad = "max_pitch";
    else if (!finite_f(p->max_roll) || !(p->max_roll > 0.0f && p->max_roll < half_pi)) bad = "max_roll";
    else if (!finite_f(p->level_rate) || !(p->level_rate >= 0.0f)) bad = "level_rate";
    else if (!finite_f(p->max_speed) || !(p->max_speed > 0.0f)) bad = "max_speed";
    else if (!finite_f(p->acceleration) || !(p->acceleration >= 0.0f)) bad = "acceleration";
    else if (!finite_f(p->turn_rate) || !(p->turn_rate >= 0.0f)) bad = "turn_rate";
    else if (!finite_f(p->min_altitude)) bad = "min_altitude";
    if (out_field != NULL) *out_field = bad;
    return bad == NULL ? CCL_OK : CCL_EINVAL;
}

float ccl_flight_attitude(float h_a, float h_b, float h_c, float h_d, float length, float span, float *out_roll)
{
    CCL_REQUIRE(!(length <= 0.0f) && !(span <= 0.0f));
    /* oc-6.1.1: the tilt from the height differences of nose/tail and of the wing tips */
    if (out_roll != NULL) *out_roll = atan2f(h_c - h_d, span);
    return atan2f(h_a - h_b, length);
}

void ccl_flight_axes(float heading, float pitch, float roll, ccl_vec3 *out_forward, ccl_vec3 *out_right,
                     ccl_vec3 *out_up)
{
    float sh = sinf(heading), ch = cosf(heading), sp = sinf(pitch), cp = cosf(pitch);
    float sr = sinf(roll), cr = cosf(roll);
    ccl_vec3 f, r0, u0, r, u;
    f.x = sh * cp; f.y = sp; f.z = -(ch * cp);
    r0.x = ch; r0.y = 0.0f; r0.z = sh;      /* horizontal right wing of the level plane */
    u0 = ccl_vec3_cross(r0, f);             /* up of the unrolled plane */
    r = ccl_vec3_sub(ccl_vec3_scale(r0, cr), ccl_vec3_scale(u0, sr));
    u = ccl_vec3_add(ccl_vec3_scale(r0, sr), ccl_vec3_scale(u0, cr));
    if (out_forward != NULL) *out_forward = f;
    if (out_right != NULL) *out_right = r;
    if (out_up != NULL) *out_up = u;
}

/* Offset of a height point after one step: +-point_rate dt while a key of the axis is held, else the level drift;
 * clamped to the attitude limit. */
static float move_offset(float offset, int up_key, int down_key, float rate, float level, float dt, float limit)
{
    float o = offset;
    if (up_key && !down_key) {
        o = o + rate * dt;
    } else if (down_key && !up_key) {
        o = o - rate * dt;
    } else if (!up_key && !down_key && level > 0.0f) {
        float step = level * dt;
        if (o > step) o = o - step;
        else if (o < -step) o = o + step;
        else o = 0.0f;
    }
    if (o > limit) o = limit;
    if (o < -limit) o = -limit;
    return o;
}

void ccl_flight_step(const ccl_flight_params *p, const ccl_flight_state *in, int keys, float dt,
                     ccl_flight_state *out)
{
    ccl_flight_state s = *in;
    float pitch_limit, roll_limit, h_e, roll, pitch, turn;
    ccl_vec3 f;
    CCL_REQUIRE(dt > 0.0f);
    /* 1. height points; the limits are the offsets that give max_pitch / max_roll:
     *    atan2(2 o, length) = max_pitch  <=>  o = 0.5 length tan(max_pitch) */
    pitch_limit = 0.5f * p->length * tanf(p->max_pitch);
    roll_limit = 0.5f * p->span * tanf(p->max_roll);
    s.nose_offset = move_offset(s.nose_offset, keys & CCL_FLIGHT_KEY_DOWN, keys & CCL_FLIGHT_KEY_UP, p->point_rate,
                                p->level_rate, dt, pitch_limit);
    s.wing_offset = move_offset(s.wing_offset, keys & CCL_FLIGHT_KEY_RIGHT, keys & CCL_FLIGHT_KEY_LEFT,
                                p->point_rate, p->level_rate, dt, roll_limit);
    /* 2. speed */
    if ((keys & CCL_FLIGHT_KEY_W) && !(keys & CCL_FLIGHT_KEY_S)) s.speed = s.speed + p->acceleration * dt;
    if ((keys & CCL_FLIGHT_KEY_S) && !(keys & CCL_FLIGHT_KEY_W)) s.speed = s.speed - p->acceleration * dt;
    if (s.speed > p->max_speed) s.speed = p->max_speed;
    if (s.speed < 0.0f) s.speed = 0.0f;
    /* 3. attitude from the five heights (E = the altitude) */
    h_e = s.position.y;
    pitch = ccl_flight_attitude(h_e + s.nose_offset, h_e - s.nose_offset, h_e + s.wing_offset, h_e - s.wing_offset,
                                p->length, p->span, &roll);
    /* 4. the tilt gives the motion */
    turn = p->turn_rate * sinf(roll) * (s.speed / p->max_speed);
    s.heading = s.heading + turn * dt;
    f.x = sinf(s.heading) * cosf(pitch);
    f.y = sinf(pitch);
    f.z = -(cosf(s.heading) * cosf(pitch));
    s.position = ccl_vec3_add(s.position, ccl_vec3_scale(f, s.speed * dt));
    if (s.position.y < p->min_altitude) s.position.y = p->min_altitude;
    *out = s;
}

/* --- the procedural aircraft (oc-6.1 stand-in) ------------------------------------------------------------------- */

static float capsule(ccl_vec3 p, ccl_vec3 a, ccl_vec3 b, float r)
{
    ccl_vec3 pa = ccl_vec3_sub(p, a), ba = ccl_vec3_sub(b, a);
    float h = ccl_vec3_dot(pa, ba) / ccl_vec3_dot(ba, ba);
    if (h < 0.0f) h = 0.0f;
    if (h > 1.0f) h = 1.0f;
    return ccl_vec3_length(ccl_vec3_sub(pa, ccl_vec3_scale(ba, h))) - r;
}

/* rounded box: centre c, half extents e (the rounding r is inside e) */
static float round_box(ccl_vec3 p, ccl_vec3 c, ccl_vec3 e, float r)
{
    ccl_vec3 q, qp;
    float inner;
    q.x = fabsf(p.x - c.x) - e.x + r;
    q.y = fabsf(p.y - c.y) - e.y + r;
    q.z = fabsf(p.z - c.z) - e.z + r;
    qp.x = q.x > 0.0f ? q.x : 0.0f;
    qp.y = q.y > 0.0f ? q.y : 0.0f;
    qp.z = q.z > 0.0f ? q.z : 0.0f;
    inner = q.x > q.y ? q.x : q.y;
    inner = inner > q.z ? inner : q.z;
    if (inner > 0.0f) inner = 0.0f;
    return ccl_vec3_length(qp) + inner - r;
}

float ccl_flight_aircraft(ccl_vec3 p, int *out_part)
{
    float d, e;
    int part = 0;
    /* fuselage: cabin capsule and a thinner tail boom rising to the fin, spinner at the nose */
    d = capsule(p, v3(0.0f, 0.0f, -3.2f), v3(0.0f, 0.0f, 1.2f), 0.55f);
    e = capsule(p, v3(0.0f, 0.05f, 1.2f), v3(0.0f, 0.3f, 3.5f), 0.25f);
    if (e < d) d = e;
    e = capsule(p, v3(0.0f, 0.0f, -3.6f), v3(0.0f, 0.0f, -3.55f), 0.2f);
    if (e < d) d = e;
    /* wings: low wing, span 12, chord 1.6 */
    e = round_box(p, v3(0.0f, -0.25f, -0.9f), v3(6.0f, 0.07f, 0.8f), 0.06f);
    if (e < d) { d = e; part = 1; }
    /* tail surfaces: tailplane span 4 and the fin */
    e = round_box(p, v3(0.0f, 0.3f, 3.3f), v3(2.0f, 0.05f, 0.45f), 0.04f);
    if (e < d) { d = e; part = 2; }
    e = round_box(p, v3(0.0f, 0.95f, 3.35f), v3(0.06f, 0.7f, 0.45f), 0.05f);
    if (e < d) { d = e; part = 2; }
    /* canopy */
    e = capsule(p, v3(0.0f, 0.42f, -1.9f), v3(0.0f, 0.42f, -0.9f), 0.38f);
    if (e < d) { d = e; part = 3; }
    if (out_part != NULL) *out_part = part;
    return d;
}
