/*
 * cclouds/flight.h -- the aircraft of the oc text's flight simulator "Aeropláne" (§6): a small procedural model that
 * stands in for the 3DS model the text imports (oc-6.1), its attitude from five height points (oc-6.1.1) and the
 * flight model driven by the six keys of the text's control table (§6.1.2). pywarp/kernels/flight.py mirrors every
 * function operation by operation.
 *
 * Frames and units (shared with cclouds/volume.h):
 *   - World: y up, metres. Heading psi: 0 = flying towards -z, positive towards +x (a right turn), as the camera yaw
 *     of the cloudscape. Pitch theta > 0: nose up. Roll phi > 0: right wing down (banked to the right).
 *   - Model (local) frame of the aircraft: x = right wing, y = up, z = TAIL (the nose points to -z, like a camera).
 *     forward f = (sin psi cos theta, sin theta, -cos psi cos theta); right r and up u follow from the roll
 *     (ccl_flight_axes). A local point p is at world position + p.x r + p.y u - p.z f.
 *   - Height points (oc-6.1.1, Obrázek 6.1; the text does not place A-D, this is the reading of the catalogue):
 *     A = nose (0, 0, -length/2), B = tail (0, 0, +length/2), C = left wing tip (-span/2, 0, 0),
 *     D = right wing tip (+span/2, 0, 0), E = centre of gravity (0, 0, 0): its height is the altitude.
 *
 * The flight model (the text gives no rates, limits or formulas; every value is a named parameter of
 * ccl_flight_params with its reason in flight.c):
 *   1. keys move the height points: Down arrow (climb) raises A and lowers B, Up arrow (descend) the reverse; Left
 *      arrow lowers C and raises D, Right arrow the reverse. Each moves at point_rate [m/s] while its key is held, so
 *      the attitude change grows with how long the key is held (oc-6.1.1); the offsets are clamped to the attitude
 *      limits max_pitch / max_roll. With level_rate > 0 an axis whose keys are released drifts back to level (the
 *      text says nothing about it: default 0, the plane keeps its attitude).
 *   2. W / S change the speed by +- acceleration * dt, clamped to [0, max_speed] (§6.1.2).
 *   3. attitude from the heights (ccl_flight_attitude): pitch = atan2(h_A - h_B, length),
 *      roll = atan2(h_C - h_D, span).
 *   4. the tilt gives the direction of motion: heading += turn_rate * sin(roll) * (speed / max_speed) * dt (the bank
 *      turns the plane, only when it moves), then position += speed * dt * forward(heading, pitch). A plane without
 *      speed neither climbs nor turns (§6.1.2: "the plane needs speed to climb"); there is no gravity or lift model in
 *      the text and none here. The altitude is clamped at min_altitude (the ground).
 */
#ifndef CCLOUDS_FLIGHT_H
#define CCLOUDS_FLIGHT_H

#include "cclouds/common.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Key bits of one simulation step (the control table of §6.1.2). */
#define CCL_FLIGHT_KEY_UP 1     /* up arrow: descend (nose point A sinks, tail B rises) */
#define CCL_FLIGHT_KEY_DOWN 2   /* down arrow: climb (A rises, B sinks) */
#define CCL_FLIGHT_KEY_LEFT 4   /* left arrow: turn left (left tip C sinks, D rises) */
#define CCL_FLIGHT_KEY_RIGHT 8  /* right arrow: turn right (C rises, D sinks) */
#define CCL_FLIGHT_KEY_W 16     /* W: faster, up to max_speed */
#define CCL_FLIGHT_KEY_S 32     /* S: slower, down to 0 */
#define CCL_FLIGHT_KEY_ALL 63

/* Parameters of the flight model (defaults and reasons: ccl_flight_params_default, flight.c). */
typedef struct ccl_flight_params {
    float length;        /* distance nose A - tail B [m] (7.5: the model of ccl_flight_aircraft) */
    float span;          /* distance of the wing tips C - D [m] (12) */
    float point_rate;    /* rise/sink speed of a height point while its key is held [m/s] (1) */
    float max_pitch;     /* attitude limit |pitch| [rad] (0.5) */
    float max_roll;      /* attitude limit |roll| [rad] (0.8) */
    float level_rate;    /* return of released axes towards level [m/s of point offset] (0) */
    float max_speed;     /* [m/s] (60) */
    float acceleration;  /* speed change while W or S is held [m/s^2] (8) */
    float turn_rate;     /* heading rate at roll pi/2 and full speed [rad/s] (0.8) */
    float min_altitude;  /* lowest altitude of E [m] (5: the ground plus half the wheels) */
} ccl_flight_params;

/* State of the aircraft. The heights of A-D are the altitude position.y plus or minus the two offsets. */
typedef struct ccl_flight_state {
    ccl_vec3 position;   /* centre of gravity E, world [m] */
    float heading;       /* psi [rad], 0 = towards -z, positive towards +x */
    float speed;         /* [m/s], in [0, max_speed] */
    float nose_offset;   /* h_A - h_E = h_E - h_B [m] */
    float wing_offset;   /* h_C - h_E = h_E - h_D [m] */
} ccl_flight_state;

/* The documented defaults (reasons in flight.c). */
CCL_API void ccl_flight_params_default(ccl_flight_params *out);

/* Validate parameters: every field finite; length, span, max_speed > 0; point_rate, acceleration, turn_rate,
 * level_rate >= 0; 0 < max_pitch < pi/2, 0 < max_roll < pi/2. Returns CCL_OK or CCL_EINVAL with *out_field = the
 * name of the first bad field (static string; out_field may be NULL). */
CCL_API ccl_status ccl_flight_check(const ccl_flight_params *p, const char **out_field);

/* Attitude from the five height points. Ref: oc-6.1.1 (the tilt "computed from the height differences between the
 * points"; the formula is the catalogue's reading): pitch = atan2(h_a - h_b, length), roll = atan2(h_c - h_d, span).
 * h_a nose, h_b tail, h_c left wing tip, h_d right wing tip [m, any finite]; h_e (the centre of gravity, the
 * altitude) does not enter the tilt and is therefore not a parameter. length = |AB| > 0, span = |CD| > 0 [m].
 * Returns pitch in (-pi/2, pi/2) [rad] (> 0 nose up); *out_roll in (-pi/2, pi/2) [rad] (> 0 right wing down). */
CCL_API float ccl_flight_attitude(float h_a, float h_b, float h_c, float h_d, float length, float span,
                                  float *out_roll);

/* Body axes from heading, pitch and roll [rad] (see the frames above): *out_forward (nose direction), *out_right
 * (right wing), *out_up; an orthonormal right-handed set (right x up = -forward). */
CCL_API void ccl_flight_axes(float heading, float pitch, float roll, ccl_vec3 *out_forward, ccl_vec3 *out_right,
                             ccl_vec3 *out_up);

/* One step of the flight model (steps 1-4 above) with the keys held during it. p: checked parameters; in: state;
 * keys: OR of CCL_FLIGHT_KEY_* (other bits ignored); dt > 0 [s]. in and out may alias. Pure: the same inputs give
 * the same state, so a script of timed key presses stepped with a fixed dt gives the same trajectory. */
CCL_API void ccl_flight_step(const ccl_flight_params *p, const ccl_flight_state *in, int keys, float dt,
                             ccl_flight_state *out);

/* Signed distance from a point of the model frame to the procedural aircraft that stands in for the text's 3DS
 * model (oc-6.1: the model was exported from 3DS to Open Inventor with 3DS2IV; no model ships with the text).
 * Ref: oc-6.1. A low-wing light aircraft: fuselage (capsules, nose at z = -3.75, tail at +3.75), wings (span 12,
 * chord 1.6), tailplane (span 4), fin and canopy, as rounded boxes and capsules joined by min(). p [m], model frame;
 * returns the distance [m] (< 0 inside; exact outside the parts' overlaps, a lower bound elsewhere, so sphere tracing
 * is safe) and *out_part: 0 fuselage, 1 wings, 2 tail surfaces, 3 canopy (the nearest part). */
CCL_API float ccl_flight_aircraft(ccl_vec3 p, int *out_part);

#ifdef __cplusplus
}
#endif

#endif /* CCLOUDS_FLIGHT_H */
