/*
 * Joints from C, using only include/hearth.h: every joint export and its errors (NULL,
 * garbage and zeroed defs, bad flags, NaN, out-of-range limits, stale and foreign ids, the
 * wrong joint type), the defaults, the get/set pairs, applied force, breaking and the broken
 * report (a broken joint reports zero force), body destruction destroying joints, the world's
 * angular speed limit, and joints doing physics (a pendulum, a motor).
 * Compiled as C11 and C++17, shared and static, under valgrind.
 */
#include "hearth.h"
#include "ensure.h"

static HearthWorld *make_world(void) {
    HearthWorldDef def = hearth_world_def_default();
    def.enable_sleep = 0;
    HearthWorld *w = NULL;
    ENSURE_OK(hearth_world_create(&def, &w));
    return w;
}

static HearthBodyId make_ball(HearthWorld *w, float x, float y, float z) {
    HearthBodyDef bd = hearth_body_def_default();
    bd.type = HEARTH_BODY_DYNAMIC;
    bd.transform.position.x = x;
    bd.transform.position.y = y;
    bd.transform.position.z = z;
    HearthBodyId b;
    memset(&b, 0, sizeof b);
    ENSURE_OK(hearth_body_create(w, &bd, &b));
    HearthShapeDef sd = hearth_shape_def_default();
    HearthSphere s;
    memset(&s, 0, sizeof s);
    s.radius = 0.2f;
    HearthShapeId sh;
    ENSURE_OK(hearth_shape_create_sphere(w, b, &sd, &s, &sh));
    return b;
}

static HearthVec3 vec3(float x, float y, float z) {
    HearthVec3 v;
    v.x = x;
    v.y = y;
    v.z = z;
    return v;
}

static int is_null_joint(HearthJointId j) { return j.index == 0 && j.generation == 0; }

static void test_defaults(void) {
    HearthBallJointDef b = hearth_ball_joint_def_default();
    ENSURE(b.enable_swing_limit == 0 && b.enable_twist_limit == 0);
    ENSURE(b.base.collide_connected == 0);
    ENSURE(b.base.frame_a.rotation.w == 1.0f && b.base.frame_b.rotation.w == 1.0f);
    ENSURE(b.base.break_force > 1e30f && b.base.break_torque > 1e30f);
    HearthHingeJointDef h = hearth_hinge_joint_def_default();
    ENSURE(h.enable_limit == 0 && h.enable_motor == 0 && h.enable_spring == 0);
    ENSURE(h.lower < 0.0f && h.upper > 0.0f);
    HearthFixedJointDef f = hearth_fixed_joint_def_default();
    ENSURE(f.base.body_a.generation == 0);
    HearthDistanceJointDef d = hearth_distance_joint_def_default();
    ENSURE(d.length == 1.0f && d.enable_spring == 0 && d.min_length == 0.0f);
    HearthSliderJointDef s = hearth_slider_joint_def_default();
    ENSURE(s.enable_limit == 0 && s.enable_motor == 0 && s.lower < s.upper);
}

static void test_create_errors(void) {
    HearthWorld *w = make_world();
    HearthBodyId a = make_ball(w, 0, 5, 0);
    HearthJointId j;
    memset(&j, 0, sizeof j);

    HearthHingeJointDef h = hearth_hinge_joint_def_default();
    h.base.body_a = a;
    ENSURE_RESULT(hearth_joint_create_hinge(NULL, &h, &j), HEARTH_ERROR_NULL_POINTER);
    ENSURE_RESULT(hearth_joint_create_hinge(w, NULL, &j), HEARTH_ERROR_NULL_POINTER);
    ENSURE_RESULT(hearth_joint_create_hinge(w, &h, NULL), HEARTH_ERROR_NULL_POINTER);

    /* Garbage and zeroed defs. */
    HearthHingeJointDef garbage;
    memset(&garbage, 0xAB, sizeof garbage);
    ENSURE_RESULT(hearth_joint_create_hinge(w, &garbage, &j), HEARTH_ERROR_INVALID_ARGUMENT);
    HearthBallJointDef zero_ball;
    memset(&zero_ball, 0, sizeof zero_ball);
    ENSURE_RESULT(hearth_joint_create_ball(w, &zero_ball, &j), HEARTH_ERROR_INVALID_ARGUMENT);
    HearthFixedJointDef zero_fixed;
    memset(&zero_fixed, 0, sizeof zero_fixed);
    ENSURE_RESULT(hearth_joint_create_fixed(w, &zero_fixed, &j), HEARTH_ERROR_INVALID_ARGUMENT);
    HearthDistanceJointDef zero_dist;
    memset(&zero_dist, 0, sizeof zero_dist);
    ENSURE_RESULT(hearth_joint_create_distance(w, &zero_dist, &j), HEARTH_ERROR_INVALID_ARGUMENT);
    HearthSliderJointDef zero_slider;
    memset(&zero_slider, 0, sizeof zero_slider);
    ENSURE_RESULT(hearth_joint_create_slider(w, &zero_slider, &j), HEARTH_ERROR_INVALID_ARGUMENT);

    /* Bad numbers and flags. */
    HearthHingeJointDef bad = h;
    bad.base.frame_a.position.x = NAN;
    ENSURE_RESULT(hearth_joint_create_hinge(w, &bad, &j), HEARTH_ERROR_INVALID_ARGUMENT);
    bad = h;
    bad.base.frame_b.rotation.w = 0.0f;
    ENSURE_RESULT(hearth_joint_create_hinge(w, &bad, &j), HEARTH_ERROR_INVALID_ARGUMENT);
    bad = h;
    bad.enable_limit = 2;
    ENSURE_RESULT(hearth_joint_create_hinge(w, &bad, &j), HEARTH_ERROR_INVALID_ARGUMENT);
    bad = h;
    bad.base.collide_connected = 7;
    ENSURE_RESULT(hearth_joint_create_hinge(w, &bad, &j), HEARTH_ERROR_INVALID_ARGUMENT);
    bad = h;
    bad.lower = 1.0f;
    bad.upper = -1.0f;
    ENSURE_RESULT(hearth_joint_create_hinge(w, &bad, &j), HEARTH_ERROR_INVALID_ARGUMENT);
    bad = h;
    bad.max_motor_torque = -1.0f;
    ENSURE_RESULT(hearth_joint_create_hinge(w, &bad, &j), HEARTH_ERROR_INVALID_ARGUMENT);
    bad = h;
    bad.base.break_force = INFINITY;
    ENSURE_RESULT(hearth_joint_create_hinge(w, &bad, &j), HEARTH_ERROR_INVALID_ARGUMENT);
    HearthBallJointDef ball = hearth_ball_joint_def_default();
    ball.base.body_a = a;
    ball.swing_limit = -0.5f;
    ENSURE_RESULT(hearth_joint_create_ball(w, &ball, &j), HEARTH_ERROR_INVALID_ARGUMENT);
    HearthDistanceJointDef dist = hearth_distance_joint_def_default();
    dist.base.body_a = a;
    dist.length = -1.0f;
    ENSURE_RESULT(hearth_joint_create_distance(w, &dist, &j), HEARTH_ERROR_INVALID_ARGUMENT);
    HearthSliderJointDef slider = hearth_slider_joint_def_default();
    slider.base.body_a = a;
    slider.enable_motor = 9;
    ENSURE_RESULT(hearth_joint_create_slider(w, &slider, &j), HEARTH_ERROR_INVALID_ARGUMENT);

    /* Bodies: null A, A == B, both static, stale, foreign. */
    HearthFixedJointDef fixed = hearth_fixed_joint_def_default();
    ENSURE_RESULT(hearth_joint_create_fixed(w, &fixed, &j), HEARTH_ERROR_INVALID_ID);
    fixed.base.body_a = a;
    fixed.base.body_b = a;
    ENSURE_RESULT(hearth_joint_create_fixed(w, &fixed, &j), HEARTH_ERROR_INVALID_ARGUMENT);
    HearthBodyDef sbd = hearth_body_def_default();
    HearthBodyId ground;
    ENSURE_OK(hearth_body_create(w, &sbd, &ground));
    fixed.base.body_a = ground;
    memset(&fixed.base.body_b, 0, sizeof fixed.base.body_b);
    ENSURE_RESULT(hearth_joint_create_fixed(w, &fixed, &j), HEARTH_ERROR_INVALID_ARGUMENT);
    HearthBodyId gone = make_ball(w, 3, 5, 0);
    ENSURE_OK(hearth_body_destroy(w, gone));
    fixed.base.body_a = gone;
    ENSURE_RESULT(hearth_joint_create_fixed(w, &fixed, &j), HEARTH_ERROR_INVALID_ID);
    HearthWorld *other = make_world();
    HearthBodyId foreign = make_ball(other, 0, 0, 0);
    fixed.base.body_a = a;
    fixed.base.body_b = foreign;
    ENSURE_RESULT(hearth_joint_create_fixed(w, &fixed, &j), HEARTH_ERROR_INVALID_ID);
    ENSURE(is_null_joint(j)); /* failing calls wrote nothing */
    hearth_world_destroy(other);
    hearth_world_destroy(w);
}

static void test_every_type_and_accessors(void) {
    HearthWorld *w = make_world();
    HearthBodyId a = make_ball(w, 0, 5, 0);
    HearthBodyId b = make_ball(w, 1, 5, 0);
    HearthJointId ball, hinge, fixed, dist, slider;
    uint32_t type = 99;

    HearthBallJointDef bd = hearth_ball_joint_def_default();
    bd.base.body_a = a;
    bd.base.body_b = b;
    bd.base.frame_a.position = vec3(0.5f, 0, 0);
    bd.base.frame_b.position = vec3(-0.5f, 0, 0);
    bd.enable_swing_limit = 1;
    bd.swing_limit = 0.7f;
    ENSURE_OK(hearth_joint_create_ball(w, &bd, &ball));
    ENSURE_OK(hearth_joint_get_type(w, ball, &type));
    ENSURE(type == HEARTH_JOINT_BALL);

    HearthHingeJointDef hd = hearth_hinge_joint_def_default();
    hd.base.body_a = a;
    hd.base.frame_b.position = vec3(0, 6, 0);
    ENSURE_OK(hearth_joint_create_hinge(w, &hd, &hinge));
    ENSURE_OK(hearth_joint_get_type(w, hinge, &type));
    ENSURE(type == HEARTH_JOINT_HINGE);

    HearthFixedJointDef fd = hearth_fixed_joint_def_default();
    fd.base.body_a = b;
    fd.base.body_b = a;
    ENSURE_OK(hearth_joint_create_fixed(w, &fd, &fixed));
    ENSURE_OK(hearth_joint_get_type(w, fixed, &type));
    ENSURE(type == HEARTH_JOINT_FIXED);

    HearthDistanceJointDef dd = hearth_distance_joint_def_default();
    dd.base.body_a = a;
    dd.base.body_b = b;
    ENSURE_OK(hearth_joint_create_distance(w, &dd, &dist));
    ENSURE_OK(hearth_joint_get_type(w, dist, &type));
    ENSURE(type == HEARTH_JOINT_DISTANCE);

    HearthSliderJointDef sd = hearth_slider_joint_def_default();
    sd.base.body_a = b;
    ENSURE_OK(hearth_joint_create_slider(w, &sd, &slider));
    ENSURE_OK(hearth_joint_get_type(w, slider, &type));
    ENSURE(type == HEARTH_JOINT_SLIDER);
    ENSURE_RESULT(hearth_joint_get_type(w, slider, NULL), HEARTH_ERROR_NULL_POINTER);
    ENSURE_RESULT(hearth_joint_get_type(NULL, slider, &type), HEARTH_ERROR_NULL_POINTER);

    /* Bodies. */
    HearthBodyId ra, rb;
    ENSURE_OK(hearth_joint_get_bodies(w, ball, &ra, &rb));
    ENSURE(ra.index == a.index && ra.generation == a.generation && rb.index == b.index);
    ENSURE_OK(hearth_joint_get_bodies(w, hinge, &ra, &rb));
    ENSURE(rb.index == 0 && rb.generation == 0);
    ENSURE_RESULT(hearth_joint_get_bodies(w, hinge, NULL, &rb), HEARTH_ERROR_NULL_POINTER);
    ENSURE_RESULT(hearth_joint_get_bodies(w, hinge, &ra, NULL), HEARTH_ERROR_NULL_POINTER);

    /* Motor: hinge and slider only. */
    bool enabled = false;
    float speed = 0, max = 0, lower = 0, upper = 0, angle = 0, hz = 0, ratio = 0;
    ENSURE_OK(hearth_joint_set_motor(w, hinge, 1, 2.5f, 40.0f));
    ENSURE_OK(hearth_joint_get_motor(w, hinge, &enabled, &speed, &max));
    ENSURE(enabled && speed == 2.5f && max == 40.0f);
    ENSURE_OK(hearth_joint_set_motor(w, slider, 1, -1.0f, 100.0f));
    ENSURE_OK(hearth_joint_get_motor(w, slider, &enabled, &speed, &max));
    ENSURE(enabled && speed == -1.0f && max == 100.0f);
    ENSURE_RESULT(hearth_joint_set_motor(w, ball, 1, 1.0f, 1.0f), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE_RESULT(hearth_joint_get_motor(w, fixed, &enabled, &speed, &max), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE_RESULT(hearth_joint_set_motor(w, hinge, 2, 1.0f, 1.0f), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE_RESULT(hearth_joint_set_motor(w, hinge, 1, NAN, 1.0f), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE_RESULT(hearth_joint_set_motor(w, hinge, 1, 1.0f, -1.0f), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE_OK(hearth_joint_get_motor(w, hinge, &enabled, &speed, &max));
    ENSURE(speed == 2.5f); /* failures changed nothing */
    ENSURE_RESULT(hearth_joint_get_motor(w, hinge, NULL, &speed, &max), HEARTH_ERROR_NULL_POINTER);
    ENSURE_RESULT(hearth_joint_set_motor(NULL, hinge, 1, 1.0f, 1.0f), HEARTH_ERROR_NULL_POINTER);

    /* Limits: hinge, slider, distance, ball twist; not fixed. */
    ENSURE_OK(hearth_joint_set_limits(w, hinge, 1, -0.5f, 0.25f));
    ENSURE_OK(hearth_joint_get_limits(w, hinge, &enabled, &lower, &upper));
    ENSURE(enabled && lower == -0.5f && upper == 0.25f);
    ENSURE_OK(hearth_joint_set_limits(w, slider, 1, -2.0f, 3.0f));
    ENSURE_OK(hearth_joint_get_limits(w, slider, &enabled, &lower, &upper));
    ENSURE(lower == -2.0f && upper == 3.0f);
    ENSURE_OK(hearth_joint_set_limits(w, dist, 0, 0.5f, 1.5f));
    ENSURE_OK(hearth_joint_get_limits(w, dist, &enabled, &lower, &upper));
    ENSURE(!enabled && lower == 0.5f && upper == 1.5f);
    ENSURE_OK(hearth_joint_set_limits(w, ball, 1, -0.1f, 0.1f));
    ENSURE_OK(hearth_joint_get_limits(w, ball, &enabled, &lower, &upper));
    ENSURE(enabled && upper == 0.1f);
    ENSURE_RESULT(hearth_joint_set_limits(w, fixed, 1, -1.0f, 1.0f), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE_RESULT(hearth_joint_get_limits(w, fixed, &enabled, &lower, &upper), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE_RESULT(hearth_joint_set_limits(w, hinge, 1, 1.0f, -1.0f), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE_RESULT(hearth_joint_set_limits(w, hinge, 1, -4.0f, 0.0f), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE_RESULT(hearth_joint_set_limits(w, dist, 1, -1.0f, 1.0f), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE_RESULT(hearth_joint_set_limits(w, hinge, 3, -1.0f, 1.0f), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE_RESULT(hearth_joint_get_limits(w, hinge, &enabled, NULL, &upper), HEARTH_ERROR_NULL_POINTER);

    /* Cone: ball only. */
    ENSURE_OK(hearth_joint_get_cone_limit(w, ball, &enabled, &angle));
    ENSURE(enabled && angle == 0.7f);
    ENSURE_OK(hearth_joint_set_cone_limit(w, ball, 0, 1.0f));
    ENSURE_OK(hearth_joint_get_cone_limit(w, ball, &enabled, &angle));
    ENSURE(!enabled && angle == 1.0f);
    ENSURE_RESULT(hearth_joint_set_cone_limit(w, ball, 1, 4.0f), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE_RESULT(hearth_joint_set_cone_limit(w, hinge, 1, 1.0f), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE_RESULT(hearth_joint_get_cone_limit(w, hinge, &enabled, &angle), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE_RESULT(hearth_joint_get_cone_limit(w, ball, &enabled, NULL), HEARTH_ERROR_NULL_POINTER);

    /* Spring: hinge and distance. */
    ENSURE_OK(hearth_joint_set_spring(w, dist, 1, 4.0f, 0.5f));
    ENSURE_OK(hearth_joint_get_spring(w, dist, &enabled, &hz, &ratio));
    ENSURE(enabled && hz == 4.0f && ratio == 0.5f);
    ENSURE_OK(hearth_joint_set_spring(w, hinge, 0, 1.0f, 0.0f));
    ENSURE_OK(hearth_joint_get_spring(w, hinge, &enabled, &hz, &ratio));
    ENSURE(!enabled && hz == 1.0f);
    ENSURE_RESULT(hearth_joint_set_spring(w, slider, 1, 1.0f, 1.0f), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE_RESULT(hearth_joint_get_spring(w, ball, &enabled, &hz, &ratio), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE_RESULT(hearth_joint_set_spring(w, dist, 1, -1.0f, 1.0f), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE_RESULT(hearth_joint_get_spring(w, dist, &enabled, &hz, NULL), HEARTH_ERROR_NULL_POINTER);

    /* Force, broken flag. */
    HearthVec3 force, torque;
    bool broken = true;
    ENSURE_OK(hearth_joint_get_force(w, fixed, &force, &torque));
    ENSURE(force.x == 0.0f && force.y == 0.0f && torque.z == 0.0f);
    ENSURE_RESULT(hearth_joint_get_force(w, fixed, NULL, &torque), HEARTH_ERROR_NULL_POINTER);
    ENSURE_RESULT(hearth_joint_get_force(w, fixed, &force, NULL), HEARTH_ERROR_NULL_POINTER);
    ENSURE_OK(hearth_joint_is_broken(w, fixed, &broken));
    ENSURE(!broken);
    ENSURE_RESULT(hearth_joint_is_broken(w, fixed, NULL), HEARTH_ERROR_NULL_POINTER);
    for (int i = 0; i < 30; i++) {
        ENSURE_OK(hearth_world_step(w, 1.0f / 60.0f));
    }

    /* Destroy; stale and foreign ids everywhere. */
    ENSURE_OK(hearth_joint_destroy(w, ball));
    ENSURE_RESULT(hearth_joint_destroy(w, ball), HEARTH_ERROR_INVALID_ID);
    ENSURE_RESULT(hearth_joint_destroy(NULL, ball), HEARTH_ERROR_NULL_POINTER);
    HearthJointId null_id;
    memset(&null_id, 0, sizeof null_id);
    ENSURE_RESULT(hearth_joint_destroy(w, null_id), HEARTH_ERROR_INVALID_ID);
    ENSURE_RESULT(hearth_joint_get_type(w, ball, &type), HEARTH_ERROR_INVALID_ID);
    ENSURE_RESULT(hearth_joint_get_bodies(w, ball, &ra, &rb), HEARTH_ERROR_INVALID_ID);
    ENSURE_RESULT(hearth_joint_set_motor(w, ball, 0, 0, 0), HEARTH_ERROR_INVALID_ID);
    ENSURE_RESULT(hearth_joint_get_motor(w, ball, &enabled, &speed, &max), HEARTH_ERROR_INVALID_ID);
    ENSURE_RESULT(hearth_joint_set_limits(w, ball, 0, 0, 0), HEARTH_ERROR_INVALID_ID);
    ENSURE_RESULT(hearth_joint_get_limits(w, ball, &enabled, &lower, &upper), HEARTH_ERROR_INVALID_ID);
    ENSURE_RESULT(hearth_joint_set_cone_limit(w, ball, 0, 0), HEARTH_ERROR_INVALID_ID);
    ENSURE_RESULT(hearth_joint_get_cone_limit(w, ball, &enabled, &angle), HEARTH_ERROR_INVALID_ID);
    ENSURE_RESULT(hearth_joint_set_spring(w, ball, 0, 0, 0), HEARTH_ERROR_INVALID_ID);
    ENSURE_RESULT(hearth_joint_get_spring(w, ball, &enabled, &hz, &ratio), HEARTH_ERROR_INVALID_ID);
    ENSURE_RESULT(hearth_joint_get_force(w, ball, &force, &torque), HEARTH_ERROR_INVALID_ID);
    ENSURE_RESULT(hearth_joint_is_broken(w, ball, &broken), HEARTH_ERROR_INVALID_ID);
    HearthWorld *other = make_world();
    ENSURE_RESULT(hearth_joint_is_broken(other, hinge, &broken), HEARTH_ERROR_INVALID_ID);
    ENSURE_RESULT(hearth_joint_destroy(other, hinge), HEARTH_ERROR_INVALID_ID);
    hearth_world_destroy(other);

    /* Destroying a body destroys its joints (the hinge, distance and fixed on a). */
    ENSURE_OK(hearth_body_destroy(w, a));
    ENSURE_RESULT(hearth_joint_get_type(w, hinge, &type), HEARTH_ERROR_INVALID_ID);
    ENSURE_RESULT(hearth_joint_get_type(w, dist, &type), HEARTH_ERROR_INVALID_ID);
    ENSURE_RESULT(hearth_joint_get_type(w, fixed, &type), HEARTH_ERROR_INVALID_ID);
    ENSURE_OK(hearth_joint_get_type(w, slider, &type));
    hearth_world_destroy(w);
}

static void test_breaking_and_report(void) {
    HearthWorld *w = make_world();
    HearthBodyId b = make_ball(w, 0, 4, 0);
    HearthFixedJointDef fd = hearth_fixed_joint_def_default();
    fd.base.body_a = b;
    fd.base.frame_b.position = vec3(0, 4, 0);
    fd.base.break_force = 2000.0f;
    HearthJointId j;
    ENSURE_OK(hearth_joint_create_fixed(w, &fd, &j));
    size_t count = 99;
    ENSURE_OK(hearth_world_get_broken_joints(w, NULL, 0, &count));
    ENSURE(count == 0);
    ENSURE_OK(hearth_world_step(w, 1.0f / 60.0f));
    HearthVec3 force, torque;
    ENSURE_OK(hearth_joint_get_force(w, j, &force, &torque));
    /* Holds the ball's weight: m = 1000 * 4/3 pi 0.2^3 = 33.5 kg. */
    ENSURE_NEAR(force.y, -33.51f * 9.81f, 5.0);
    ENSURE_OK(hearth_body_apply_force(w, b, vec3(0, -5000.0f, 0)));
    ENSURE_OK(hearth_world_step(w, 1.0f / 60.0f));
    bool broken = false;
    ENSURE_OK(hearth_joint_is_broken(w, j, &broken));
    ENSURE(broken);
    ENSURE_OK(hearth_world_get_broken_joints(w, NULL, 0, &count));
    ENSURE(count == 1);
    HearthJointId list[4];
    ENSURE_RESULT(hearth_world_get_broken_joints(w, list, 4, NULL), HEARTH_ERROR_NULL_POINTER);
    ENSURE_RESULT(hearth_world_get_broken_joints(w, NULL, 4, &count), HEARTH_ERROR_NULL_POINTER);
    ENSURE_RESULT(hearth_world_get_broken_joints(NULL, list, 4, &count), HEARTH_ERROR_NULL_POINTER);
    count = 0;
    ENSURE_OK(hearth_world_get_broken_joints(w, list, 4, &count));
    ENSURE(count == 1 && list[0].index == j.index && list[0].generation == j.generation);
    ENSURE_OK(hearth_world_step(w, 1.0f / 60.0f));
    ENSURE_OK(hearth_world_get_broken_joints(w, list, 4, &count));
    ENSURE(count == 0);
    /* A broken joint applies nothing and reports zero, for good. */
    int nonzero = 0;
    for (int i = 0; i < 120; i++) {
        ENSURE_OK(hearth_joint_get_force(w, j, &force, &torque));
        nonzero += force.x != 0.0f || force.y != 0.0f || force.z != 0.0f || torque.x != 0.0f ||
                   torque.y != 0.0f || torque.z != 0.0f;
        ENSURE_OK(hearth_world_step(w, 1.0f / 60.0f));
    }
    ENSURE(nonzero == 0);
    ENSURE_OK(hearth_joint_destroy(w, j));
    hearth_world_destroy(w);
}

/* The angular speed limit of the world def (appended after internal_value): its default,
 * its validation, and that it holds for a body a hinge motor and a huge torque spin. */
static void test_angular_speed_limit(void) {
    HearthWorldDef def = hearth_world_def_default();
    ENSURE_NEAR(def.max_angular_speed, 314.159265, 1e-3);
    HearthWorld *w = NULL;
    const float bad[] = {0.0f, -1.0f, NAN, INFINITY};
    for (int i = 0; i < 4; i++) {
        HearthWorldDef d = def;
        d.max_angular_speed = bad[i];
        ENSURE_RESULT(hearth_world_create(&d, &w), HEARTH_ERROR_INVALID_ARGUMENT);
        char msg[256];
        hearth_last_error_message(msg, sizeof msg);
        ENSURE(strstr(msg, "max_angular_speed") != NULL);
        ENSURE(w == NULL);
    }
    def.max_angular_speed = 20.0f;
    def.enable_sleep = 0;
    def.gravity = vec3(0, 0, 0);
    ENSURE_OK(hearth_world_create(&def, &w));
    HearthBodyId b = make_ball(w, 0, 0, 0);
    /* Set above the limit: refused with a message naming the limit, nothing changes. */
    HearthVec3 av;
    ENSURE_RESULT(hearth_body_set_angular_velocity(w, b, vec3(0, 0, 20.5f)), HEARTH_ERROR_INVALID_ARGUMENT);
    char msg[256];
    hearth_last_error_message(msg, sizeof msg);
    ENSURE(strstr(msg, "max_angular_speed") != NULL);
    ENSURE_OK(hearth_body_get_angular_velocity(w, b, &av));
    ENSURE(av.x == 0.0f && av.y == 0.0f && av.z == 0.0f);
    /* An impulse that would spin it faster: capped, axis kept. */
    ENSURE_OK(hearth_body_apply_angular_impulse(w, b, vec3(0, 0, 1.0e6f)));
    ENSURE_OK(hearth_body_get_angular_velocity(w, b, &av));
    ENSURE_NEAR(av.z, 20.0, 1e-3);
    ENSURE(av.x == 0.0f && av.y == 0.0f);
    /* The largest torques: finite and within the limit. */
    for (int i = 0; i < 60; i++) {
        ENSURE_OK(hearth_body_apply_torque(w, b, vec3(5.0e11f, -5.0e11f, 5.0e11f)));
        ENSURE_OK(hearth_world_step(w, 1.0f / 60.0f));
    }
    ENSURE_OK(hearth_body_get_angular_velocity(w, b, &av));
    float spin = sqrtf(av.x * av.x + av.y * av.y + av.z * av.z);
    ENSURE(isfinite(spin) && spin <= 20.0f * 1.0001f);
    ENSURE_NEAR(spin, 20.0, 1e-3);
    hearth_world_destroy(w);
}

static void test_too_small_buffer(void) {
    HearthWorld *w = make_world();
    HearthJointId ids[3];
    for (int i = 0; i < 3; i++) {
        HearthBodyId b = make_ball(w, (float)i * 2.0f, 4, 0);
        HearthBallJointDef bd = hearth_ball_joint_def_default();
        bd.base.body_a = b;
        bd.base.frame_b.position = vec3((float)i * 2.0f, 4, 0);
        bd.base.break_force = 10.0f;
        ENSURE_OK(hearth_joint_create_ball(w, &bd, &ids[i]));
    }
    ENSURE_OK(hearth_world_step(w, 1.0f / 60.0f));
    size_t count = 0;
    ENSURE_OK(hearth_world_get_broken_joints(w, NULL, 0, &count));
    ENSURE(count == 3);
    HearthJointId two[2];
    count = 77;
    ENSURE_RESULT(hearth_world_get_broken_joints(w, two, 2, &count), HEARTH_ERROR_BUFFER_TOO_SMALL);
    ENSURE(count == 77); /* nothing written */
    hearth_world_destroy(w);
}

static void test_physics(void) {
    /* A motorised hinge reaches its speed; a pendulum on a hinge swings under the pivot. */
    HearthWorld *w = make_world();
    HearthBodyId wheel = make_ball(w, 0, 5, 0);
    HearthHingeJointDef hd = hearth_hinge_joint_def_default();
    hd.base.body_a = wheel;
    hd.base.frame_b.position = vec3(0, 5, 0);
    hd.enable_motor = 1;
    hd.motor_speed = -2.0f; /* B (the world) relative to A: the wheel turns at +2 rad/s */
    hd.max_motor_torque = 100.0f;
    HearthJointId motor;
    ENSURE_OK(hearth_joint_create_hinge(w, &hd, &motor));

    HearthBodyId bob = make_ball(w, 5, 4, 0);
    HearthHingeJointDef pd = hearth_hinge_joint_def_default();
    pd.base.body_a = bob;
    pd.base.frame_a.position = vec3(-1, 0, 0); /* the pivot, 1 m to the bob's left */
    pd.base.frame_b.position = vec3(4, 4, 0);
    HearthJointId pendulum;
    ENSURE_OK(hearth_joint_create_hinge(w, &pd, &pendulum));
    for (int i = 0; i < 120; i++) {
        ENSURE_OK(hearth_world_step(w, 1.0f / 60.0f));
    }
    HearthVec3 av, p;
    ENSURE_OK(hearth_body_get_angular_velocity(w, wheel, &av));
    ENSURE_NEAR(av.z, 2.0, 0.01);
    HearthTransform xf;
    ENSURE_OK(hearth_body_get_transform(w, bob, &xf));
    p = xf.position;
    float dx = p.x - 4.0f, dy = p.y - 4.0f;
    ENSURE_NEAR(sqrtf(dx * dx + dy * dy), 1.0, 0.005);
    hearth_world_destroy(w);
}

static void test_locked_from_callback_is_not_needed(void) {
    /* Joint mutations are structural: they go through the world lock like every other
     * create/destroy/set (tested generically in test_generators.c). Here only a NULL world. */
    HearthJointId j;
    memset(&j, 0, sizeof j);
    HearthBallJointDef bd = hearth_ball_joint_def_default();
    ENSURE_RESULT(hearth_joint_create_ball(NULL, &bd, &j), HEARTH_ERROR_NULL_POINTER);
    HearthDistanceJointDef dd = hearth_distance_joint_def_default();
    ENSURE_RESULT(hearth_joint_create_distance(NULL, &dd, &j), HEARTH_ERROR_NULL_POINTER);
    HearthSliderJointDef sd = hearth_slider_joint_def_default();
    ENSURE_RESULT(hearth_joint_create_slider(NULL, &sd, &j), HEARTH_ERROR_NULL_POINTER);
    HearthFixedJointDef fd = hearth_fixed_joint_def_default();
    ENSURE_RESULT(hearth_joint_create_fixed(NULL, &fd, &j), HEARTH_ERROR_NULL_POINTER);
}

int main(void) {
    test_defaults();
    test_create_errors();
    test_every_type_and_accessors();
    test_breaking_and_report();
    test_angular_speed_limit();
    test_too_small_buffer();
    test_physics();
    test_locked_from_callback_is_not_needed();
    return ensure_report("test_joints");
}
