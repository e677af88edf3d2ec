/* C unit tests of cclouds/flight.h: attitude from the five height points (oc-6.1.1), the flight model's keys, speed
 * limits, climbing and turning only with speed, determinism, and the procedural aircraft (oc-6.1 stand-in). */
#include "cclouds/flight.h"
#include "ccl_test.h"

#define PI_D 3.14159265358979323846

static ccl_flight_state level(float altitude, float speed)
{
    ccl_flight_state s;
    s.position = V(0.0f, altitude, 0.0f);
    s.heading = 0.0f;
    s.speed = speed;
    s.nose_offset = 0.0f;
    s.wing_offset = 0.0f;
    return s;
}

static ccl_flight_state run(const ccl_flight_params *p, ccl_flight_state s, int keys, float seconds, float dt)
{
    int n = (int)(seconds / dt + 0.5f), i;
    for (i = 0; i < n; ++i) ccl_flight_step(p, &s, keys, dt, &s);
    return s;
}

static void test_flight_attitude_from_known_heights(void)
{
    float roll = 0.0f, pitch;
    /* nose 1 m above the tail over a length of 1 m: 45 deg nose up; wing tips level */
    pitch = ccl_flight_attitude(101.0f, 100.0f, 100.0f, 100.0f, 1.0f, 12.0f, &roll);
    CCL_CHECK_REL(pitch, PI_D / 4.0, 1e-6);
    CCL_CHECK_CLOSE(roll, 0.0, 0.0);
    /* left tip 6 m above the right over a 6 m span: 45 deg, right wing down */
    pitch = ccl_flight_attitude(0.0f, 0.0f, 3.0f, -3.0f, 7.5f, 6.0f, &roll);
    CCL_CHECK_CLOSE(pitch, 0.0, 0.0);
    CCL_CHECK_REL(roll, PI_D / 4.0, 1e-6);
    /* independent value: atan(0.5 / 7.5) */
    pitch = ccl_flight_attitude(0.25f, -0.25f, -1.0f, 1.0f, 7.5f, 12.0f, &roll);
    CCL_CHECK_REL(pitch, atan(0.5 / 7.5), 1e-6);
    CCL_CHECK_REL(roll, -atan(2.0 / 12.0), 1e-6);
    /* only differences count */
    CCL_CHECK(ccl_flight_attitude(1000.25f, 999.75f, 0.0f, 0.0f, 7.5f, 12.0f, NULL) ==
              ccl_flight_attitude(0.25f, -0.25f, 0.0f, 0.0f, 7.5f, 12.0f, NULL));
}

static void test_flight_axes_are_orthonormal(void)
{
    ccl_vec3 f, r, u;
    ccl_flight_axes(0.0f, 0.0f, 0.0f, &f, &r, &u);
    CCL_CHECK_CLOSE(f.z, -1.0, 1e-7);
    CCL_CHECK_CLOSE(r.x, 1.0, 1e-7);
    CCL_CHECK_CLOSE(u.y, 1.0, 1e-7);
    ccl_flight_axes(0.7f, 0.3f, 0.4f, &f, &r, &u);
    CCL_CHECK_CLOSE(ccl_vec3_dot(f, r), 0.0, 1e-6);
    CCL_CHECK_CLOSE(ccl_vec3_dot(f, u), 0.0, 1e-6);
    CCL_CHECK_CLOSE(ccl_vec3_dot(r, u), 0.0, 1e-6);
    CCL_CHECK_CLOSE(ccl_vec3_length(u), 1.0, 1e-6);
    /* right x up = -forward (x right, y up, z tail) */
    CCL_CHECK_CLOSE(ccl_vec3_dot(ccl_vec3_cross(r, u), f), -1.0, 1e-6);
    /* a positive roll lowers the right wing */
    ccl_flight_axes(0.0f, 0.0f, 0.3f, &f, &r, &u);
    CCL_CHECK_CLOSE(r.y, -sin(0.3), 1e-6);
}

static void test_flight_speed_limits(void)
{
    ccl_flight_params p;
    ccl_flight_state s;
    ccl_flight_params_default(&p);
    s = run(&p, level(500.0f, 0.0f), CCL_FLIGHT_KEY_W, 2.0f, 0.01f);
    CCL_CHECK_REL(s.speed, 2.0 * (double)p.acceleration, 1e-4);
    s = run(&p, s, CCL_FLIGHT_KEY_W, 60.0f, 0.01f);
    CCL_CHECK(s.speed == p.max_speed);
    s = run(&p, s, CCL_FLIGHT_KEY_S, 60.0f, 0.01f);
    CCL_CHECK(s.speed == 0.0f);
    /* W and S together: no change */
    s = run(&p, level(500.0f, 20.0f), CCL_FLIGHT_KEY_W | CCL_FLIGHT_KEY_S, 1.0f, 0.01f);
    CCL_CHECK(s.speed == 20.0f);
}

static void test_flight_climbing_needs_speed(void)
{
    ccl_flight_params p;
    ccl_flight_state s;
    ccl_flight_params_default(&p);
    /* at rest, the nose goes up but the plane stays where it is */
    s = run(&p, level(500.0f, 0.0f), CCL_FLIGHT_KEY_DOWN, 1.0f, 0.01f);
    CCL_CHECK(s.nose_offset > 0.0f);
    CCL_CHECK(s.position.y == 500.0f && s.position.x == 0.0f && s.position.z == 0.0f);
    /* with speed it climbs and moves forward (-z) */
    s = run(&p, s, 0, 1.0f, 0.01f);
    CCL_CHECK(s.position.y == 500.0f);
    s.speed = 30.0f;
    s = run(&p, s, 0, 1.0f, 0.01f);
    CCL_CHECK(s.position.y > 500.0f);
    CCL_CHECK(s.position.z < 0.0f);
    /* the climb rate is speed * sin(pitch) */
    {
        float pitch = ccl_flight_attitude(s.nose_offset, -s.nose_offset, 0.0f, 0.0f, p.length, p.span, NULL);
        CCL_CHECK_REL(s.position.y - 500.0f, 30.0 * sin((double)pitch) * 1.0, 1e-3);
    }
    /* the ground stops a dive */
    s = run(&p, level(10.0f, 60.0f), CCL_FLIGHT_KEY_UP, 10.0f, 0.01f);
    CCL_CHECK(s.position.y == p.min_altitude);
}

static void test_flight_attitude_grows_with_key_time(void)
{
    ccl_flight_params p;
    ccl_flight_state s1, s2, s3;
    ccl_flight_params_default(&p);
    s1 = run(&p, level(500.0f, 40.0f), CCL_FLIGHT_KEY_RIGHT, 0.5f, 0.01f);
    s2 = run(&p, level(500.0f, 40.0f), CCL_FLIGHT_KEY_RIGHT, 1.0f, 0.01f);
    CCL_CHECK_REL(s1.wing_offset, 0.5 * (double)p.point_rate, 1e-4);
    CCL_CHECK_REL(s2.wing_offset, 1.0 * (double)p.point_rate, 1e-4);
    /* clamped at max_roll */
    s3 = run(&p, level(500.0f, 40.0f), CCL_FLIGHT_KEY_RIGHT, 30.0f, 0.01f);
    CCL_CHECK_REL(atan2(2.0 * (double)s3.wing_offset, (double)p.span), p.max_roll, 1e-5);
    /* a right bank turns right (heading grows) only with speed */
    s1 = run(&p, s2, 0, 2.0f, 0.01f);
    CCL_CHECK(s1.heading > 0.0f && s1.position.x > 0.0f);
    s2.speed = 0.0f;
    s1 = run(&p, s2, 0, 2.0f, 0.01f);
    CCL_CHECK(s1.heading == s2.heading);
    /* left arrow lowers the left tip: negative wing offset, left turn */
    s1 = run(&p, level(500.0f, 40.0f), CCL_FLIGHT_KEY_LEFT, 3.0f, 0.01f);
    CCL_CHECK(s1.wing_offset < 0.0f && s1.heading < 0.0f);
    /* level_rate brings a released axis back */
    p.level_rate = 1.0f;
    s1 = run(&p, s2, 0, 5.0f, 0.01f);
    CCL_CHECK(s1.wing_offset == 0.0f);
}

static void test_flight_is_deterministic(void)
{
    ccl_flight_params p;
    ccl_flight_state a = level(300.0f, 10.0f), b = level(300.0f, 10.0f);
    int i;
    ccl_flight_params_default(&p);
    for (i = 0; i < 3000; ++i) {
        int keys = (i / 97) % 64;
        ccl_flight_step(&p, &a, keys, 1.0f / 60.0f, &a);
        ccl_flight_step(&p, &b, keys, 1.0f / 60.0f, &b);
    }
    CCL_CHECK(a.position.x == b.position.x && a.position.y == b.position.y && a.position.z == b.position.z);
    CCL_CHECK(a.heading == b.heading && a.speed == b.speed);
}

static void test_flight_check(void)
{
    ccl_flight_params p;
    const char *field = NULL;
    ccl_flight_params_default(&p);
    CCL_CHECK(ccl_flight_check(&p, &field) == CCL_OK && field == NULL);
    p.max_speed = 0.0f;
    CCL_CHECK(ccl_flight_check(&p, &field) == CCL_EINVAL && field != NULL && field[0] == 'm');
    ccl_flight_params_default(&p);
    p.max_roll = 1.6f;
    CCL_CHECK(ccl_flight_check(&p, &field) == CCL_EINVAL);
    CCL_CHECK(ccl_flight_check(NULL, &field) == CCL_EINVAL);
}

static void test_flight_aircraft_model(void)
{
    int part = -1;
    float d;
    /* inside the fuselage, the wing, the fin and the canopy */
    CCL_CHECK(ccl_flight_aircraft(V(0.0f, 0.0f, 0.0f), &part) < 0.0f && part == 0);
    CCL_CHECK(ccl_flight_aircraft(V(5.0f, -0.25f, -0.9f), &part) < 0.0f && part == 1);
    CCL_CHECK(ccl_flight_aircraft(V(0.0f, 1.2f, 3.35f), &part) < 0.0f && part == 2);
    CCL_CHECK(ccl_flight_aircraft(V(0.0f, 0.75f, -1.4f), &part) < 0.0f && part == 3);
    /* the nose and the tail at the height points A and B, the wing tips at C and D (within the skins) */
    CCL_CHECK(fabsf(ccl_flight_aircraft(V(0.0f, 0.0f, -3.8f), NULL)) < 0.06f);
    CCL_CHECK(fabsf(ccl_flight_aircraft(V(6.0f, -0.25f, -0.9f), NULL)) < 0.01f);
    /* far away: the distance to the model is within its bounding radius of the distance to the origin */
    d = ccl_flight_aircraft(V(0.0f, 100.0f, 0.0f), NULL);
    CCL_CHECK(d > 100.0f - 2.0f && d < 100.0f);
    /* a lower bound of the true distance: never more than the distance to a surface point (the spinner tip) */
    CCL_CHECK(ccl_flight_aircraft(V(0.0f, 0.0f, -10.0f), NULL) <= 10.0f - 3.8f + 1e-4f);
}

int main(void)
{
    CCL_RUN(test_flight_attitude_from_known_heights);
    CCL_RUN(test_flight_axes_are_orthonormal);
    CCL_RUN(test_flight_speed_limits);
    CCL_RUN(test_flight_climbing_needs_speed);
    CCL_RUN(test_flight_attitude_grows_with_key_time);
    CCL_RUN(test_flight_is_deterministic);
    CCL_RUN(test_flight_check);
    CCL_RUN(test_flight_aircraft_model);
    return ccl_test_report();
}
