/*
 * Issue 14 runtime setters from C: each setter against its getter and the physics it
 * changes (density doubles the mass, gravity scale 0 floats, a mass override gives dv = J/m,
 * type change and enable/disable), and each error: NULL world and outputs, stale ids, NaN,
 * negative and out-of-range numbers, unknown type codes, a plane body kept static; a failing
 * call changes nothing. Compiled as C11 and C++17, shared and static, and under valgrind in CI.
 */
#include "hearth.h"
#include "ensure.h"

#include <math.h>

static HearthShapeId make_box(HearthWorld *w, HearthBodyId b, HearthVec3 half) {
    HearthShapeDef def = hearth_shape_def_default();
    HearthBox box;
    box.center = v3(0, 0, 0);
    box.rotation.x = box.rotation.y = box.rotation.z = 0;
    box.rotation.w = 1;
    box.half_extents = half;
    HearthShapeId s;
    ENSURE_OK(hearth_shape_create_box(w, b, &def, &box, &s));
    return s;
}

static float body_y(HearthWorld *w, HearthBodyId b) {
    HearthTransform t;
    ENSURE_OK(hearth_body_get_transform(w, b, &t));
    return t.position.y;
}

static void test_shape_material(void) {
    HearthWorld *w = new_world();
    HearthBodyId b = new_body(w, HEARTH_BODY_DYNAMIC, v3(0, 5, 0), 0);
    HearthShapeId s = make_box(w, b, v3(0.5f, 0.25f, 1.0f));
    float m0, m1, x = -1, y = -1;
    ENSURE_OK(hearth_body_get_mass(w, b, &m0));
    ENSURE_OK(hearth_shape_set_density(w, s, 2000.0f));
    ENSURE_OK(hearth_shape_get_density(w, s, &x));
    ENSURE(x == 2000.0f);
    ENSURE_OK(hearth_body_get_mass(w, b, &m1));
    ENSURE(m1 == 2.0f * m0);

    ENSURE_OK(hearth_shape_set_friction(w, s, 0.8f, 0.3f));
    ENSURE_OK(hearth_shape_get_friction(w, s, &x, &y));
    ENSURE(x == 0.8f && y == 0.3f);
    ENSURE_OK(hearth_shape_set_restitution(w, s, 0.5f));
    ENSURE_OK(hearth_shape_get_restitution(w, s, &x));
    ENSURE(x == 0.5f);
    ENSURE_OK(hearth_shape_set_rolling_resistance(w, s, 0.2f));
    ENSURE_OK(hearth_shape_get_rolling_resistance(w, s, &x));
    ENSURE(x == 0.2f);
    ENSURE_OK(hearth_shape_set_torsional_friction(w, s, 0.1f));
    ENSURE_OK(hearth_shape_get_torsional_friction(w, s, &x));
    ENSURE(x == 0.1f);
    uint64_t u = 0;
    ENSURE_OK(hearth_shape_set_user_data(w, s, 0xABCDEF0123ull));
    ENSURE_OK(hearth_shape_get_user_data(w, s, &u));
    ENSURE(u == 0xABCDEF0123ull);

    /* Errors change nothing. */
    ENSURE_RESULT(hearth_shape_set_density(w, s, -1.0f), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE_RESULT(hearth_shape_set_density(w, s, NAN), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE_RESULT(hearth_shape_set_friction(w, s, -0.1f, 0.2f), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE_RESULT(hearth_shape_set_friction(w, s, 0.2f, NAN), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE_RESULT(hearth_shape_set_restitution(w, s, 1.5f), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE_RESULT(hearth_shape_set_rolling_resistance(w, s, INFINITY), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE_RESULT(hearth_shape_set_torsional_friction(w, s, -1.0f), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE_RESULT(hearth_shape_set_density(NULL, s, 1.0f), HEARTH_ERROR_NULL_POINTER);
    ENSURE_RESULT(hearth_shape_set_user_data(NULL, s, 1), HEARTH_ERROR_NULL_POINTER);
    ENSURE_RESULT(hearth_shape_get_density(w, s, NULL), HEARTH_ERROR_NULL_POINTER);
    ENSURE_RESULT(hearth_shape_get_friction(w, s, &x, NULL), HEARTH_ERROR_NULL_POINTER);
    ENSURE_RESULT(hearth_shape_get_restitution(NULL, s, &x), HEARTH_ERROR_NULL_POINTER);
    ENSURE_RESULT(hearth_shape_get_user_data(w, s, NULL), HEARTH_ERROR_NULL_POINTER);
    ENSURE_OK(hearth_shape_get_density(w, s, &x));
    ENSURE(x == 2000.0f);
    ENSURE_OK(hearth_shape_get_friction(w, s, &x, &y));
    ENSURE(x == 0.8f && y == 0.3f);
    ENSURE_OK(hearth_shape_get_restitution(w, s, &x));
    ENSURE(x == 0.5f);
    ENSURE_OK(hearth_shape_get_torsional_friction(w, s, &x));
    ENSURE(x == 0.1f);

    /* Stale ids; outputs untouched. */
    ENSURE_OK(hearth_body_destroy(w, b));
    x = 42.0f;
    ENSURE_RESULT(hearth_shape_get_density(w, s, &x), HEARTH_ERROR_INVALID_ID);
    ENSURE(x == 42.0f);
    ENSURE_RESULT(hearth_shape_set_density(w, s, 1.0f), HEARTH_ERROR_INVALID_ID);
    ENSURE_RESULT(hearth_shape_set_user_data(w, s, 1), HEARTH_ERROR_INVALID_ID);
    ENSURE_RESULT(hearth_shape_get_user_data(w, s, &u), HEARTH_ERROR_INVALID_ID);
    hearth_world_destroy(w);
}

static void test_gravity_scale_and_mass_data(void) {
    HearthWorld *w = new_world();
    HearthBodyId b = new_body(w, HEARTH_BODY_DYNAMIC, v3(0, 5, 0), 0);
    make_box(w, b, v3(0.5f, 0.5f, 0.5f));
    float g = -1;
    ENSURE_OK(hearth_body_get_gravity_scale(w, b, &g));
    ENSURE(g == 1.0f);
    ENSURE_OK(hearth_body_set_gravity_scale(w, b, 0.0f));
    ENSURE_OK(hearth_body_get_gravity_scale(w, b, &g));
    ENSURE(g == 0.0f);
    for (int i = 0; i < 60; i++) ENSURE_OK(hearth_world_step(w, 1.0f / 60.0f));
    ENSURE(body_y(w, b) == 5.0f);
    ENSURE_RESULT(hearth_body_set_gravity_scale(w, b, NAN), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE_RESULT(hearth_body_set_gravity_scale(w, b, 101.0f), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE_RESULT(hearth_body_set_gravity_scale(NULL, b, 1.0f), HEARTH_ERROR_NULL_POINTER);
    ENSURE_RESULT(hearth_body_get_gravity_scale(w, b, NULL), HEARTH_ERROR_NULL_POINTER);
    ENSURE_OK(hearth_body_get_gravity_scale(w, b, &g));
    ENSURE(g == 0.0f);

    HearthMassData d;
    d.mass = 4.0f;
    d.center = v3(0, 0, 0);
    d.inertia = v3(2, 4, 8);
    ENSURE_OK(hearth_body_set_mass_data(w, b, &d));
    HearthMassData r;
    ENSURE_OK(hearth_body_get_mass_data(w, b, &r));
    ENSURE(r.mass == 4.0f && r.inertia.x == 2.0f && r.inertia.y == 4.0f && r.inertia.z == 8.0f);
    ENSURE_OK(hearth_body_apply_linear_impulse(w, b, v3(2, 0, 0)));
    HearthVec3 v;
    ENSURE_OK(hearth_body_get_linear_velocity(w, b, &v));
    ENSURE(v.x == 0.5f);
    HearthMassData bad = d;
    bad.mass = 0.0f;
    ENSURE_RESULT(hearth_body_set_mass_data(w, b, &bad), HEARTH_ERROR_INVALID_ARGUMENT);
    bad.mass = -1.0f;
    ENSURE_RESULT(hearth_body_set_mass_data(w, b, &bad), HEARTH_ERROR_INVALID_ARGUMENT);
    bad = d;
    bad.inertia.y = NAN;
    ENSURE_RESULT(hearth_body_set_mass_data(w, b, &bad), HEARTH_ERROR_INVALID_ARGUMENT);
    bad = d;
    bad.center.x = INFINITY;
    ENSURE_RESULT(hearth_body_set_mass_data(w, b, &bad), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE_RESULT(hearth_body_set_mass_data(w, b, NULL), HEARTH_ERROR_NULL_POINTER);
    ENSURE_RESULT(hearth_body_set_mass_data(NULL, b, &d), HEARTH_ERROR_NULL_POINTER);
    ENSURE_RESULT(hearth_body_get_mass_data(w, b, NULL), HEARTH_ERROR_NULL_POINTER);
    ENSURE_OK(hearth_body_get_mass_data(w, b, &r));
    ENSURE(r.mass == 4.0f);
    ENSURE_OK(hearth_body_reset_mass_data(w, b));
    ENSURE_OK(hearth_body_get_mass_data(w, b, &r));
    ENSURE_NEAR(r.mass, 1000.0f, 1e-3f);
    ENSURE_RESULT(hearth_body_reset_mass_data(NULL, b), HEARTH_ERROR_NULL_POINTER);

    ENSURE_OK(hearth_body_destroy(w, b));
    ENSURE_RESULT(hearth_body_set_gravity_scale(w, b, 1.0f), HEARTH_ERROR_INVALID_ID);
    ENSURE_RESULT(hearth_body_get_gravity_scale(w, b, &g), HEARTH_ERROR_INVALID_ID);
    ENSURE_RESULT(hearth_body_set_mass_data(w, b, &d), HEARTH_ERROR_INVALID_ID);
    ENSURE_RESULT(hearth_body_get_mass_data(w, b, &r), HEARTH_ERROR_INVALID_ID);
    ENSURE_RESULT(hearth_body_reset_mass_data(w, b), HEARTH_ERROR_INVALID_ID);
    hearth_world_destroy(w);
}

static void test_locked_axes(void) {
    HearthWorld *w = new_world();
    HearthBodyId b = new_body(w, HEARTH_BODY_DYNAMIC, v3(0, 5, 0), 0);
    make_box(w, b, v3(0.5f, 0.5f, 0.5f));
    uint32_t bits = 99;
    ENSURE_OK(hearth_body_get_locked_axes(w, b, &bits));
    ENSURE(bits == 0);
    ENSURE_OK(hearth_body_set_linear_velocity(w, b, v3(1, 2, 3)));
    ENSURE_OK(hearth_body_set_angular_velocity(w, b, v3(4, 5, 6)));
    /* 2.5D: the XY plane, turning about Z only. The locked components are zero at once. */
    uint32_t planar = HEARTH_LOCK_LINEAR_Z | HEARTH_LOCK_ANGULAR_X | HEARTH_LOCK_ANGULAR_Y;
    ENSURE_OK(hearth_body_set_locked_axes(w, b, planar));
    ENSURE_OK(hearth_body_get_locked_axes(w, b, &bits));
    ENSURE(bits == planar);
    HearthVec3 v, av;
    ENSURE_OK(hearth_body_get_linear_velocity(w, b, &v));
    ENSURE_OK(hearth_body_get_angular_velocity(w, b, &av));
    ENSURE(v.x == 1.0f && v.y == 2.0f && v.z == 0.0f && av.x == 0.0f && av.y == 0.0f && av.z == 6.0f);
    /* Gravity and an off-centre impulse out of the plane leave the locked axes at exactly zero. */
    ENSURE_OK(hearth_body_apply_impulse_at_point(w, b, v3(100, 200, 3000), v3(0.3f, 5.4f, 0.2f)));
    HearthTransform t0;
    ENSURE_OK(hearth_body_get_transform(w, b, &t0));
    for (int i = 0; i < 60; i++) ENSURE_OK(hearth_world_step(w, 1.0f / 60.0f));
    HearthTransform t;
    ENSURE_OK(hearth_body_get_transform(w, b, &t));
    ENSURE_OK(hearth_body_get_linear_velocity(w, b, &v));
    ENSURE_OK(hearth_body_get_angular_velocity(w, b, &av));
    ENSURE(t.position.z == t0.position.z && v.z == 0.0f && av.x == 0.0f && av.y == 0.0f);
    ENSURE(t.position.y < 4.0f);
    /* Errors change nothing. */
    ENSURE_RESULT(hearth_body_set_locked_axes(w, b, 64), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE_RESULT(hearth_body_set_locked_axes(w, b, 0x80000000u | HEARTH_LOCK_LINEAR_X), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE_RESULT(hearth_body_set_locked_axes(NULL, b, 0), HEARTH_ERROR_NULL_POINTER);
    ENSURE_RESULT(hearth_body_get_locked_axes(NULL, b, &bits), HEARTH_ERROR_NULL_POINTER);
    ENSURE_RESULT(hearth_body_get_locked_axes(w, b, NULL), HEARTH_ERROR_NULL_POINTER);
    ENSURE_OK(hearth_body_get_locked_axes(w, b, &bits));
    ENSURE(bits == planar);
    /* In the def: unknown bits are refused there too. */
    HearthBodyDef d = hearth_body_def_default();
    d.type = HEARTH_BODY_DYNAMIC;
    d.locked_axes = HEARTH_LOCK_ANGULAR;
    HearthBodyId c;
    ENSURE_OK(hearth_body_create(w, &d, &c));
    ENSURE_OK(hearth_body_get_locked_axes(w, c, &bits));
    ENSURE(bits == (HEARTH_LOCK_ANGULAR_X | HEARTH_LOCK_ANGULAR_Y | HEARTH_LOCK_ANGULAR_Z));
    d.locked_axes = 1u << 6;
    ENSURE_RESULT(hearth_body_create(w, &d, &c), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE_OK(hearth_body_destroy(w, b));
    ENSURE_RESULT(hearth_body_set_locked_axes(w, b, 0), HEARTH_ERROR_INVALID_ID);
    ENSURE_RESULT(hearth_body_get_locked_axes(w, b, &bits), HEARTH_ERROR_INVALID_ID);
    hearth_world_destroy(w);
}

static void test_type_and_enable(void) {
    HearthWorld *w = new_world();
    HearthBodyId ground = new_body(w, HEARTH_BODY_STATIC, v3(0, 0, 0), 0);
    HearthShapeDef sd = hearth_shape_def_default();
    HearthPlane plane;
    plane.normal = v3(0, 1, 0);
    plane.offset = 0;
    HearthShapeId ps;
    ENSURE_OK(hearth_shape_create_plane(w, ground, &sd, &plane, &ps));
    HearthBodyId shelf = new_body(w, HEARTH_BODY_STATIC, v3(0, 3, 0), 0);
    make_box(w, shelf, v3(2, 0.25f, 2));
    HearthBodyId b = new_body(w, HEARTH_BODY_DYNAMIC, v3(0, 3.75f, 0), 0);
    make_box(w, b, v3(0.5f, 0.5f, 0.5f));
    for (int i = 0; i < 60; i++) ENSURE_OK(hearth_world_step(w, 1.0f / 60.0f));
    ENSURE_NEAR(body_y(w, b), 3.75f, 0.01f);

    /* Disable the shelf: the box falls to the ground. */
    bool on = false;
    ENSURE_OK(hearth_body_is_enabled(w, shelf, &on));
    ENSURE(on);
    ENSURE_OK(hearth_body_disable(w, shelf));
    ENSURE_OK(hearth_body_is_enabled(w, shelf, &on));
    ENSURE(!on);
    for (int i = 0; i < 120; i++) ENSURE_OK(hearth_world_step(w, 1.0f / 60.0f));
    ENSURE_NEAR(body_y(w, b), 0.5f, 0.01f);
    ENSURE_OK(hearth_body_enable(w, shelf));
    ENSURE_OK(hearth_body_is_enabled(w, shelf, &on));
    ENSURE(on);

    /* Type changes: the box made static stays put; made dynamic again, it is dynamic. */
    uint32_t t = 99;
    ENSURE_OK(hearth_body_set_type(w, b, HEARTH_BODY_STATIC));
    ENSURE_OK(hearth_body_get_type(w, b, &t));
    ENSURE(t == HEARTH_BODY_STATIC);
    float m = -1;
    ENSURE_OK(hearth_body_get_mass(w, b, &m));
    ENSURE(m == 0.0f);
    ENSURE_OK(hearth_body_set_type(w, b, HEARTH_BODY_DYNAMIC));
    ENSURE_OK(hearth_body_get_mass(w, b, &m));
    ENSURE_NEAR(m, 1000.0f, 1e-3f);
    ENSURE_OK(hearth_body_set_type(w, b, HEARTH_BODY_KINEMATIC));
    ENSURE_OK(hearth_body_get_type(w, b, &t));
    ENSURE(t == HEARTH_BODY_KINEMATIC);

    /* Errors. */
    ENSURE_RESULT(hearth_body_set_type(w, b, 3), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE_RESULT(hearth_body_set_type(w, ground, HEARTH_BODY_DYNAMIC), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE_OK(hearth_body_get_type(w, ground, &t));
    ENSURE(t == HEARTH_BODY_STATIC);
    ENSURE_RESULT(hearth_body_set_type(NULL, b, HEARTH_BODY_STATIC), HEARTH_ERROR_NULL_POINTER);
    ENSURE_RESULT(hearth_body_disable(NULL, b), HEARTH_ERROR_NULL_POINTER);
    ENSURE_RESULT(hearth_body_enable(NULL, b), HEARTH_ERROR_NULL_POINTER);
    ENSURE_RESULT(hearth_body_is_enabled(w, b, NULL), HEARTH_ERROR_NULL_POINTER);
    ENSURE_OK(hearth_body_destroy(w, b));
    ENSURE_RESULT(hearth_body_set_type(w, b, HEARTH_BODY_STATIC), HEARTH_ERROR_INVALID_ID);
    ENSURE_RESULT(hearth_body_disable(w, b), HEARTH_ERROR_INVALID_ID);
    ENSURE_RESULT(hearth_body_enable(w, b), HEARTH_ERROR_INVALID_ID);
    ENSURE_RESULT(hearth_body_is_enabled(w, b, &on), HEARTH_ERROR_INVALID_ID);
    hearth_world_destroy(w);
}

int main(void) {
    test_shape_material();
    test_gravity_scale_and_mass_data();
    test_locked_axes();
    test_type_and_enable();
    return ensure_report("test_setters");
}
