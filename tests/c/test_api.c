/*
 * The C ABI contract, exercised from C using only include/hearth.h: every Core function,
 * each documented misuse and its result code, id rules, bulk read-back, churn, and a
 * falling box that comes to rest. Compiled as C11 and as C++17, linked against the shared
 * and the static library, and run under valgrind in CI.
 */
#include "hearth.h"
#include "ensure.h"

#include <stdlib.h>

static HearthWorld *make_world(void) {
    HearthWorldDef def = hearth_world_def_default();
    HearthWorld *w = NULL;
    ENSURE_OK(hearth_world_create(&def, &w));
    ENSURE(w != NULL);
    return w;
}

static HearthBodyId make_body(HearthWorld *w, uint32_t type, float x, float y, float z) {
    HearthBodyDef def = hearth_body_def_default();
    def.type = type;
    def.transform.position.x = x;
    def.transform.position.y = y;
    def.transform.position.z = z;
    HearthBodyId id;
    memset(&id, 0, sizeof id);
    ENSURE_OK(hearth_body_create(w, &def, &id));
    return id;
}

static HearthShapeId add_box(HearthWorld *w, HearthBodyId b, float hx, float hy, float hz) {
    HearthShapeDef sd = hearth_shape_def_default();
    HearthBox box;
    memset(&box, 0, sizeof box);
    box.rotation.w = 1.0f;
    box.half_extents.x = hx;
    box.half_extents.y = hy;
    box.half_extents.z = hz;
    HearthShapeId s;
    memset(&s, 0, sizeof s);
    ENSURE_OK(hearth_shape_create_box(w, b, &sd, &box, &s));
    return s;
}

static HearthShapeId add_ground_plane(HearthWorld *w, HearthBodyId ground) {
    HearthShapeDef sd = hearth_shape_def_default();
    HearthPlane plane;
    plane.normal.x = 0.0f;
    plane.normal.y = 1.0f;
    plane.normal.z = 0.0f;
    plane.offset = 0.0f;
    HearthShapeId s;
    memset(&s, 0, sizeof s);
    ENSURE_OK(hearth_shape_create_plane(w, ground, &sd, &plane, &s));
    return s;
}

static uint32_t body_count(const HearthWorld *w) {
    HearthWorldCounters c;
    ENSURE_OK(hearth_world_get_counters(w, &c));
    return c.body_count;
}

static void test_version_and_names(void) {
    ENSURE(hearth_version() == HEARTH_VERSION);
    ENSURE(strcmp(hearth_result_name(HEARTH_OK), "HEARTH_OK") == 0);
    ENSURE(strcmp(hearth_result_name(HEARTH_ERROR_NULL_POINTER), "HEARTH_ERROR_NULL_POINTER") == 0);
    ENSURE(strcmp(hearth_result_name(HEARTH_ERROR_INVALID_ID), "HEARTH_ERROR_INVALID_ID") == 0);
    ENSURE(strcmp(hearth_result_name(HEARTH_ERROR_INVALID_ARGUMENT), "HEARTH_ERROR_INVALID_ARGUMENT") == 0);
    ENSURE(strcmp(hearth_result_name(HEARTH_ERROR_WORLD_LOCKED), "HEARTH_ERROR_WORLD_LOCKED") == 0);
    ENSURE(strcmp(hearth_result_name(HEARTH_ERROR_BUFFER_TOO_SMALL), "HEARTH_ERROR_BUFFER_TOO_SMALL") == 0);
    ENSURE(strcmp(hearth_result_name(HEARTH_ERROR_PANIC), "HEARTH_ERROR_PANIC") == 0);
    ENSURE(strcmp(hearth_result_name(-1), "HEARTH_ERROR_UNKNOWN") == 0);
    ENSURE(strcmp(hearth_result_name(12345), "HEARTH_ERROR_UNKNOWN") == 0);
}

static void test_last_error_message(void) {
    ENSURE_RESULT(hearth_world_create(NULL, NULL), HEARTH_ERROR_NULL_POINTER);
    size_t full = hearth_last_error_message(NULL, 0);
    ENSURE(full > 0);
    char big[512];
    ENSURE(hearth_last_error_message(big, sizeof big) == full);
    ENSURE(strlen(big) == full);
    char small[5];
    memset(small, 'x', sizeof small);
    ENSURE(hearth_last_error_message(small, sizeof small) == full);
    ENSURE(small[4] == '\0' && strlen(small) == 4 && strncmp(small, big, 4) == 0);
    char one = 'x';
    ENSURE(hearth_last_error_message(&one, 1) == full);
    ENSURE(one == '\0');
}

static void test_world_create_errors(void) {
    HearthWorldDef def = hearth_world_def_default();
    ENSURE_NEAR(def.gravity.y, -9.81, 1e-6);
    ENSURE(def.gravity.x == 0.0f && def.gravity.z == 0.0f);
    ENSURE(def.substeps >= 1);
    ENSURE(def.enable_sleep == 1);

    HearthWorld *sentinel = (HearthWorld *)(uintptr_t)0x1234;
    HearthWorld *w = sentinel;
    ENSURE_RESULT(hearth_world_create(NULL, &w), HEARTH_ERROR_NULL_POINTER);
    ENSURE(w == sentinel);
    ENSURE_RESULT(hearth_world_create(&def, NULL), HEARTH_ERROR_NULL_POINTER);

    HearthWorldDef garbage;
    memset(&garbage, 0xAB, sizeof garbage);
    ENSURE_RESULT(hearth_world_create(&garbage, &w), HEARTH_ERROR_INVALID_ARGUMENT);
    HearthWorldDef zeroed;
    memset(&zeroed, 0, sizeof zeroed);
    ENSURE_RESULT(hearth_world_create(&zeroed, &w), HEARTH_ERROR_INVALID_ARGUMENT);

    HearthWorldDef bad = def;
    bad.substeps = 0;
    ENSURE_RESULT(hearth_world_create(&bad, &w), HEARTH_ERROR_INVALID_ARGUMENT);
    bad = def;
    bad.gravity.y = NAN;
    ENSURE_RESULT(hearth_world_create(&bad, &w), HEARTH_ERROR_INVALID_ARGUMENT);
    bad = def;
    bad.gravity.x = INFINITY;
    ENSURE_RESULT(hearth_world_create(&bad, &w), HEARTH_ERROR_INVALID_ARGUMENT);
    bad = def;
    bad.enable_sleep = 2;
    ENSURE_RESULT(hearth_world_create(&bad, &w), HEARTH_ERROR_INVALID_ARGUMENT);
    bad = def;
    bad.integrator = 77;
    ENSURE_RESULT(hearth_world_create(&bad, &w), HEARTH_ERROR_INVALID_ARGUMENT);
    bad = def;
    bad.sleep_threshold = -1.0f;
    ENSURE_RESULT(hearth_world_create(&bad, &w), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE(w == sentinel);

    hearth_world_destroy(NULL); /* a no-op */

    w = make_world();
    ENSURE_RESULT(hearth_world_step(NULL, 1.0f / 60.0f), HEARTH_ERROR_NULL_POINTER);
    ENSURE_RESULT(hearth_world_step(w, NAN), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE_RESULT(hearth_world_step(w, -0.01f), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE_RESULT(hearth_world_step(w, INFINITY), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE_OK(hearth_world_step(w, 0.0f));
    ENSURE_OK(hearth_world_step(w, 1.0f / 60.0f));

    HearthVec3 g;
    ENSURE_OK(hearth_world_get_gravity(w, &g));
    ENSURE_NEAR(g.y, -9.81, 1e-6);
    HearthVec3 nan_g = {0.0f, NAN, 0.0f};
    ENSURE_RESULT(hearth_world_set_gravity(w, nan_g), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE_OK(hearth_world_get_gravity(w, &g));
    ENSURE_NEAR(g.y, -9.81, 1e-6);
    ENSURE_RESULT(hearth_world_get_gravity(w, NULL), HEARTH_ERROR_NULL_POINTER);
    ENSURE_RESULT(hearth_world_get_counters(NULL, NULL), HEARTH_ERROR_NULL_POINTER);
    hearth_world_destroy(w);
}

static void test_body_create_errors(void) {
    HearthWorld *w = make_world();
    HearthBodyDef def = hearth_body_def_default();
    ENSURE(def.type == HEARTH_BODY_STATIC);
    ENSURE(def.transform.rotation.w == 1.0f);
    ENSURE(def.allow_sleep == 1);
    ENSURE(def.user_data == 0);

    HearthBodyId id = {77u, 88u};
    ENSURE_RESULT(hearth_body_create(NULL, &def, &id), HEARTH_ERROR_NULL_POINTER);
    ENSURE_RESULT(hearth_body_create(w, NULL, &id), HEARTH_ERROR_NULL_POINTER);
    ENSURE_RESULT(hearth_body_create(w, &def, NULL), HEARTH_ERROR_NULL_POINTER);

    HearthBodyDef garbage;
    memset(&garbage, 0x5C, sizeof garbage);
    ENSURE_RESULT(hearth_body_create(w, &garbage, &id), HEARTH_ERROR_INVALID_ARGUMENT);

    HearthBodyDef bad = def;
    bad.type = 9;
    ENSURE_RESULT(hearth_body_create(w, &bad, &id), HEARTH_ERROR_INVALID_ARGUMENT);
    bad = def;
    bad.transform.position.x = NAN;
    ENSURE_RESULT(hearth_body_create(w, &bad, &id), HEARTH_ERROR_INVALID_ARGUMENT);
    bad = def;
    bad.transform.rotation.w = 0.0f;
    ENSURE_RESULT(hearth_body_create(w, &bad, &id), HEARTH_ERROR_INVALID_ARGUMENT);
    bad = def;
    bad.linear_velocity.z = INFINITY;
    ENSURE_RESULT(hearth_body_create(w, &bad, &id), HEARTH_ERROR_INVALID_ARGUMENT);
    bad = def;
    bad.angular_velocity.y = -INFINITY;
    ENSURE_RESULT(hearth_body_create(w, &bad, &id), HEARTH_ERROR_INVALID_ARGUMENT);
    bad = def;
    bad.linear_damping = -1.0f;
    ENSURE_RESULT(hearth_body_create(w, &bad, &id), HEARTH_ERROR_INVALID_ARGUMENT);
    bad = def;
    bad.angular_damping = NAN;
    ENSURE_RESULT(hearth_body_create(w, &bad, &id), HEARTH_ERROR_INVALID_ARGUMENT);
    bad = def;
    bad.allow_sleep = 2;
    ENSURE_RESULT(hearth_body_create(w, &bad, &id), HEARTH_ERROR_INVALID_ARGUMENT);
    bad = def;
    bad.is_awake = 255;
    ENSURE_RESULT(hearth_body_create(w, &bad, &id), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE(id.index == 77u && id.generation == 88u); /* untouched */
    ENSURE(body_count(w) == 0);

    /* A non-normalised rotation is accepted and normalised. */
    bad = def;
    bad.type = HEARTH_BODY_DYNAMIC;
    bad.transform.rotation.w = 2.0f;
    bad.user_data = 0xDEADBEEFCAFEull;
    ENSURE_OK(hearth_body_create(w, &bad, &id));
    HearthTransform t;
    ENSURE_OK(hearth_body_get_transform(w, id, &t));
    ENSURE_NEAR(t.rotation.w, 1.0, 1e-6);
    uint64_t ud = 0;
    ENSURE_OK(hearth_body_get_user_data(w, id, &ud));
    ENSURE(ud == 0xDEADBEEFCAFEull);
    ENSURE(body_count(w) == 1);
    hearth_world_destroy(w);
}

static void test_ids(void) {
    HearthWorld *w1 = make_world();
    HearthWorld *w2 = make_world();
    HearthBodyId a = make_body(w1, HEARTH_BODY_DYNAMIC, 0, 0, 0);
    HearthBodyId null_id;
    memset(&null_id, 0, sizeof null_id);
    HearthTransform t;
    HearthVec3 v;
    bool awake;
    ENSURE_RESULT(hearth_body_get_transform(w1, null_id, &t), HEARTH_ERROR_INVALID_ID);
    ENSURE_RESULT(hearth_body_get_linear_velocity(w1, null_id, &v), HEARTH_ERROR_INVALID_ID);
    ENSURE_RESULT(hearth_body_destroy(w1, null_id), HEARTH_ERROR_INVALID_ID);

    /* An id of another world is foreign there, even when the index exists. */
    HearthBodyId b = make_body(w2, HEARTH_BODY_DYNAMIC, 0, 0, 0);
    ENSURE(a.index == b.index);
    ENSURE_RESULT(hearth_body_get_transform(w2, a, &t), HEARTH_ERROR_INVALID_ID);
    ENSURE_RESULT(hearth_body_destroy(w2, a), HEARTH_ERROR_INVALID_ID);
    ENSURE(body_count(w2) == 1);

    /* Never-existing index. */
    HearthBodyId bogus = a;
    bogus.index = 100000;
    ENSURE_RESULT(hearth_body_is_awake(w1, bogus, &awake), HEARTH_ERROR_INVALID_ID);

    /* A destroyed id is stale, and a reused slot never revives it. */
    ENSURE_OK(hearth_body_destroy(w1, a));
    ENSURE_RESULT(hearth_body_destroy(w1, a), HEARTH_ERROR_INVALID_ID);
    ENSURE_RESULT(hearth_body_get_transform(w1, a, &t), HEARTH_ERROR_INVALID_ID);
    HearthBodyId c = make_body(w1, HEARTH_BODY_DYNAMIC, 1, 2, 3);
    ENSURE(c.index == a.index && c.generation != a.generation);
    ENSURE_RESULT(hearth_body_get_transform(w1, a, &t), HEARTH_ERROR_INVALID_ID);
    ENSURE_RESULT(hearth_body_set_linear_velocity(w1, a, v), HEARTH_ERROR_INVALID_ID);
    ENSURE_OK(hearth_body_get_transform(w1, c, &t));
    ENSURE_NEAR(t.position.y, 2.0, 1e-6);

    /* Every body function rejects a stale id. */
    HearthVec3 zero = {0, 0, 0};
    ENSURE_RESULT(hearth_body_set_transform(w1, a, &t), HEARTH_ERROR_INVALID_ID);
    ENSURE_RESULT(hearth_body_get_angular_velocity(w1, a, &v), HEARTH_ERROR_INVALID_ID);
    ENSURE_RESULT(hearth_body_set_angular_velocity(w1, a, zero), HEARTH_ERROR_INVALID_ID);
    ENSURE_RESULT(hearth_body_is_awake(w1, a, &awake), HEARTH_ERROR_INVALID_ID);
    ENSURE_RESULT(hearth_body_apply_force(w1, a, zero), HEARTH_ERROR_INVALID_ID);
    HearthShapeId s;
    HearthShapeDef sd = hearth_shape_def_default();
    HearthSphere sphere = {{0, 0, 0}, 0.5f};
    ENSURE_RESULT(hearth_shape_create_sphere(w1, a, &sd, &sphere, &s), HEARTH_ERROR_INVALID_ID);

    /* Shape ids follow the same rules. */
    ENSURE_OK(hearth_shape_create_sphere(w1, c, &sd, &sphere, &s));
    HearthBodyId owner;
    ENSURE_OK(hearth_shape_get_body(w1, s, &owner));
    ENSURE(owner.index == c.index && owner.generation == c.generation);
    ENSURE_RESULT(hearth_shape_get_body(w2, s, &owner), HEARTH_ERROR_INVALID_ID);
    ENSURE_OK(hearth_shape_destroy(w1, s));
    ENSURE_RESULT(hearth_shape_destroy(w1, s), HEARTH_ERROR_INVALID_ID);
    ENSURE_RESULT(hearth_shape_get_body(w1, s, &owner), HEARTH_ERROR_INVALID_ID);

    hearth_world_destroy(w1);
    hearth_world_destroy(w2);
}

static void test_shape_errors(void) {
    HearthWorld *w = make_world();
    HearthBodyId body = make_body(w, HEARTH_BODY_DYNAMIC, 0, 5, 0);
    HearthBodyId ground = make_body(w, HEARTH_BODY_STATIC, 0, 0, 0);
    HearthShapeDef sd = hearth_shape_def_default();
    ENSURE_NEAR(sd.density, 1000.0, 1e-3);
    ENSURE(sd.static_friction >= sd.dynamic_friction);
    HearthShapeId s = {5u, 6u};

    HearthSphere sphere = {{0, 0, 0}, 0.5f};
    ENSURE_RESULT(hearth_shape_create_sphere(NULL, body, &sd, &sphere, &s), HEARTH_ERROR_NULL_POINTER);
    ENSURE_RESULT(hearth_shape_create_sphere(w, body, NULL, &sphere, &s), HEARTH_ERROR_NULL_POINTER);
    ENSURE_RESULT(hearth_shape_create_sphere(w, body, &sd, NULL, &s), HEARTH_ERROR_NULL_POINTER);
    ENSURE_RESULT(hearth_shape_create_sphere(w, body, &sd, &sphere, NULL), HEARTH_ERROR_NULL_POINTER);
    HearthShapeDef garbage;
    memset(&garbage, 0xFF, sizeof garbage);
    ENSURE_RESULT(hearth_shape_create_sphere(w, body, &garbage, &sphere, &s), HEARTH_ERROR_INVALID_ARGUMENT);
    HearthShapeDef bad = sd;
    bad.density = -1.0f;
    ENSURE_RESULT(hearth_shape_create_sphere(w, body, &bad, &sphere, &s), HEARTH_ERROR_INVALID_ARGUMENT);
    bad = sd;
    bad.static_friction = NAN;
    ENSURE_RESULT(hearth_shape_create_sphere(w, body, &bad, &sphere, &s), HEARTH_ERROR_INVALID_ARGUMENT);
    bad = sd;
    bad.restitution = -0.5f;
    ENSURE_RESULT(hearth_shape_create_sphere(w, body, &bad, &sphere, &s), HEARTH_ERROR_INVALID_ARGUMENT);

    /* Rolling resistance and torsional friction: defaults, and 0..=1, finite. */
    ENSURE_NEAR(sd.rolling_resistance, 0.05, 1e-7);
    ENSURE_NEAR(sd.torsional_friction, 0.05, 1e-7);
    const float bad_coefficients[] = {NAN, INFINITY, -0.01f, 1.01f};
    HearthCapsule capsule = {{0, 0, 0}, {0, 1, 0}, 0.2f};
    for (size_t k = 0; k < sizeof bad_coefficients / sizeof bad_coefficients[0]; k++) {
        char msg[256];
        bad = sd;
        bad.rolling_resistance = bad_coefficients[k];
        ENSURE_RESULT(hearth_shape_create_sphere(w, body, &bad, &sphere, &s), HEARTH_ERROR_INVALID_ARGUMENT);
        hearth_last_error_message(msg, sizeof msg);
        ENSURE(strstr(msg, "rolling_resistance") != NULL);
        bad = sd;
        bad.torsional_friction = bad_coefficients[k];
        ENSURE_RESULT(hearth_shape_create_capsule(w, body, &bad, &capsule, &s), HEARTH_ERROR_INVALID_ARGUMENT);
        hearth_last_error_message(msg, sizeof msg);
        ENSURE(strstr(msg, "torsional_friction") != NULL);
    }
    /* Failures wrote nothing. */
    ENSURE(s.index == 5u && s.generation == 6u);
    bad = sd;
    bad.rolling_resistance = 1.0f;
    bad.torsional_friction = 0.0f;
    ENSURE_OK(hearth_shape_create_sphere(w, body, &bad, &sphere, &s));
    ENSURE_OK(hearth_shape_destroy(w, s));
    s.index = 5u;
    s.generation = 6u;
    HearthSphere bad_sphere = {{0, 0, 0}, -0.5f};
    ENSURE_RESULT(hearth_shape_create_sphere(w, body, &sd, &bad_sphere, &s), HEARTH_ERROR_INVALID_ARGUMENT);
    bad_sphere.radius = 0.0f;
    ENSURE_RESULT(hearth_shape_create_sphere(w, body, &sd, &bad_sphere, &s), HEARTH_ERROR_INVALID_ARGUMENT);
    bad_sphere.radius = 1.0f;
    bad_sphere.center.y = INFINITY;
    ENSURE_RESULT(hearth_shape_create_sphere(w, body, &sd, &bad_sphere, &s), HEARTH_ERROR_INVALID_ARGUMENT);

    HearthBox box;
    memset(&box, 0, sizeof box);
    box.rotation.w = 1.0f;
    box.half_extents.x = 0.5f;
    box.half_extents.y = -0.5f;
    box.half_extents.z = 0.5f;
    ENSURE_RESULT(hearth_shape_create_box(w, body, &sd, &box, &s), HEARTH_ERROR_INVALID_ARGUMENT);
    box.half_extents.y = 0.5f;
    box.rotation.w = 0.0f;
    ENSURE_RESULT(hearth_shape_create_box(w, body, &sd, &box, &s), HEARTH_ERROR_INVALID_ARGUMENT);
    box.rotation.w = 1.0f;
    box.center.x = NAN;
    ENSURE_RESULT(hearth_shape_create_box(w, body, &sd, &box, &s), HEARTH_ERROR_INVALID_ARGUMENT);

    HearthCapsule cap = {{0, -0.5f, 0}, {0, 0.5f, 0}, -0.1f};
    ENSURE_RESULT(hearth_shape_create_capsule(w, body, &sd, &cap, &s), HEARTH_ERROR_INVALID_ARGUMENT);
    cap.radius = 0.25f;
    cap.b.z = NAN;
    ENSURE_RESULT(hearth_shape_create_capsule(w, body, &sd, &cap, &s), HEARTH_ERROR_INVALID_ARGUMENT);

    HearthPlane plane = {{0, 0, 0}, 0.0f};
    ENSURE_RESULT(hearth_shape_create_plane(w, ground, &sd, &plane, &s), HEARTH_ERROR_INVALID_ARGUMENT);
    plane.normal.y = 1.0f;
    plane.offset = NAN;
    ENSURE_RESULT(hearth_shape_create_plane(w, ground, &sd, &plane, &s), HEARTH_ERROR_INVALID_ARGUMENT);
    plane.offset = 0.0f;
    ENSURE_RESULT(hearth_shape_create_plane(w, body, &sd, &plane, &s), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE(s.index == 5u && s.generation == 6u); /* untouched by every failure */

    float mass = -1.0f;
    ENSURE_OK(hearth_body_get_mass(w, body, &mass));
    ENSURE_NEAR(mass, 1.0, 1e-6); /* a dynamic body without shapes moves as 1 kg */

    /* Mass from density: a 0.5 m sphere of water plus a 1x1x1 box of water. */
    ENSURE_OK(hearth_shape_create_sphere(w, body, &sd, &sphere, &s));
    ENSURE_OK(hearth_body_get_mass(w, body, &mass));
    ENSURE_NEAR(mass, 1000.0 * 4.0 / 3.0 * 3.14159265 * 0.125, 0.05);
    box.center.x = 2.0f;
    ENSURE_OK(hearth_shape_create_box(w, body, &sd, &box, &s));
    ENSURE_OK(hearth_body_get_mass(w, body, &mass));
    ENSURE_NEAR(mass, 523.599 + 1000.0, 0.1);
    HearthVec3 com;
    ENSURE_OK(hearth_body_get_center_of_mass(w, body, &com));
    ENSURE_NEAR(com.x, 2.0 * 1000.0 / 1523.599, 1e-3);
    cap.b.z = 0.0f;
    ENSURE_OK(hearth_shape_create_capsule(w, body, &sd, &cap, &s));
    ENSURE_OK(hearth_shape_create_plane(w, ground, &sd, &plane, &s));
    hearth_world_destroy(w);
}

static void test_state_roundtrip(void) {
    HearthWorld *w = make_world();
    HearthBodyId b = make_body(w, HEARTH_BODY_DYNAMIC, 0, 10, 0);
    add_box(w, b, 0.5f, 0.5f, 0.5f);

    HearthTransform t;
    t.position.x = 1.0f;
    t.position.y = 2.0f;
    t.position.z = 3.0f;
    t.rotation.x = 0.0f;
    t.rotation.y = 0.70710678f;
    t.rotation.z = 0.0f;
    t.rotation.w = 0.70710678f;
    ENSURE_OK(hearth_body_set_transform(w, b, &t));
    HearthTransform r;
    ENSURE_OK(hearth_body_get_transform(w, b, &r));
    ENSURE_NEAR(r.position.x, 1.0, 1e-6);
    ENSURE_NEAR(r.position.z, 3.0, 1e-6);
    ENSURE_NEAR(r.rotation.y, 0.70710678, 1e-6);

    HearthTransform bad = t;
    bad.position.y = NAN;
    ENSURE_RESULT(hearth_body_set_transform(w, b, &bad), HEARTH_ERROR_INVALID_ARGUMENT);
    bad = t;
    bad.rotation.y = 0.0f;
    bad.rotation.w = 0.0f;
    ENSURE_RESULT(hearth_body_set_transform(w, b, &bad), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE_RESULT(hearth_body_set_transform(w, b, NULL), HEARTH_ERROR_NULL_POINTER);
    ENSURE_RESULT(hearth_body_get_transform(w, b, NULL), HEARTH_ERROR_NULL_POINTER);
    ENSURE_RESULT(hearth_body_get_transform(NULL, b, &r), HEARTH_ERROR_NULL_POINTER);
    ENSURE_OK(hearth_body_get_transform(w, b, &r));
    ENSURE_NEAR(r.position.y, 2.0, 1e-6); /* unchanged by the failures */

    HearthVec3 v = {1.5f, -2.0f, 0.25f};
    HearthVec3 o;
    ENSURE_OK(hearth_body_set_linear_velocity(w, b, v));
    ENSURE_OK(hearth_body_get_linear_velocity(w, b, &o));
    ENSURE(o.x == 1.5f && o.y == -2.0f && o.z == 0.25f);
    HearthVec3 nan_v = {NAN, 0, 0};
    ENSURE_RESULT(hearth_body_set_linear_velocity(w, b, nan_v), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE_RESULT(hearth_body_set_angular_velocity(w, b, nan_v), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE_OK(hearth_body_get_linear_velocity(w, b, &o));
    ENSURE(o.x == 1.5f);
    HearthVec3 wv = {0.0f, 3.0f, 0.0f};
    ENSURE_OK(hearth_body_set_angular_velocity(w, b, wv));
    ENSURE_OK(hearth_body_get_angular_velocity(w, b, &o));
    ENSURE(o.y == 3.0f);
    ENSURE_RESULT(hearth_body_get_angular_velocity(w, b, NULL), HEARTH_ERROR_NULL_POINTER);

    bool awake = false;
    ENSURE_OK(hearth_body_is_awake(w, b, &awake));
    ENSURE(awake);
    ENSURE_RESULT(hearth_body_is_awake(w, b, NULL), HEARTH_ERROR_NULL_POINTER);
    uint32_t type = 99;
    ENSURE_OK(hearth_body_get_type(w, b, &type));
    ENSURE(type == HEARTH_BODY_DYNAMIC);

    /* Free flight for one second matches the kinematics of gravity exactly enough. */
    HearthVec3 zero = {0, 0, 0};
    ENSURE_OK(hearth_body_set_angular_velocity(w, b, zero));
    ENSURE_OK(hearth_body_set_linear_velocity(w, b, zero));
    for (int i = 0; i < 60; i++) ENSURE_OK(hearth_world_step(w, 1.0f / 60.0f));
    ENSURE_OK(hearth_body_get_linear_velocity(w, b, &o));
    ENSURE_NEAR(o.y, -9.81, 1e-3);
    ENSURE_OK(hearth_body_get_transform(w, b, &r));
    ENSURE_NEAR(r.position.y, 2.0 - 0.5 * 9.81, 0.05);

    /* Forces and impulses. */
    float mass;
    ENSURE_OK(hearth_body_get_mass(w, b, &mass));
    HearthVec3 impulse = {mass * 2.0f, 0, 0};
    ENSURE_OK(hearth_body_apply_linear_impulse(w, b, impulse));
    ENSURE_OK(hearth_body_get_linear_velocity(w, b, &o));
    ENSURE_NEAR(o.x, 2.0, 1e-4);
    HearthVec3 inf_f = {INFINITY, 0, 0};
    ENSURE_RESULT(hearth_body_apply_force(w, b, inf_f), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE_RESULT(hearth_body_apply_force_at_point(w, b, zero, inf_f), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE_RESULT(hearth_body_apply_torque(w, b, inf_f), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE_RESULT(hearth_body_apply_impulse_at_point(w, b, inf_f, zero), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE_RESULT(hearth_body_apply_angular_impulse(w, b, inf_f), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE_RESULT(hearth_body_set_damping(w, b, -1.0f, 0.0f), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE_RESULT(hearth_body_set_awake(w, b, 3), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE_OK(hearth_body_get_linear_velocity(w, b, &o));
    ENSURE_NEAR(o.x, 2.0, 1e-4);
    hearth_world_destroy(w);
}

static void test_bulk_read(void) {
    HearthWorld *w = make_world();
    enum { N = 50 };
    HearthBodyId ids[N];
    for (int i = 0; i < N; i++) {
        ids[i] = make_body(w, i % 3 == 0 ? HEARTH_BODY_STATIC : HEARTH_BODY_DYNAMIC, (float)i, (float)(i * 2), 0);
        if (i % 3 != 0) add_box(w, ids[i], 0.25f, 0.25f, 0.25f);
    }
    for (int i = 0; i < 10; i++) ENSURE_OK(hearth_world_step(w, 1.0f / 60.0f));
    HearthTransform bulk[N];
    ENSURE_OK(hearth_world_get_transforms(w, ids, N, bulk));
    int same = 1;
    for (int i = 0; i < N; i++) {
        HearthTransform one;
        ENSURE_OK(hearth_body_get_transform(w, ids[i], &one));
        same &= memcmp(&one, &bulk[i], sizeof one) == 0;
    }
    ENSURE(same);
    ENSURE_OK(hearth_world_get_transforms(w, NULL, 0, NULL));
    ENSURE_RESULT(hearth_world_get_transforms(w, NULL, 3, bulk), HEARTH_ERROR_NULL_POINTER);
    ENSURE_RESULT(hearth_world_get_transforms(w, ids, 3, NULL), HEARTH_ERROR_NULL_POINTER);
    ENSURE_RESULT(hearth_world_get_transforms(NULL, ids, 3, bulk), HEARTH_ERROR_NULL_POINTER);

    /* A stale id anywhere: error, and nothing written. */
    ENSURE_OK(hearth_body_destroy(w, ids[7]));
    HearthTransform marker[N];
    memset(marker, 0x7F, sizeof marker);
    HearthTransform copy[N];
    memcpy(copy, marker, sizeof marker);
    ENSURE_RESULT(hearth_world_get_transforms(w, ids, N, marker), HEARTH_ERROR_INVALID_ID);
    ENSURE(memcmp(copy, marker, sizeof marker) == 0);
    hearth_world_destroy(w);
}

static unsigned rng_state = 12345u;
static unsigned rng(void) {
    rng_state = rng_state * 1664525u + 1013904223u;
    return rng_state >> 8;
}

static void test_churn(void) {
    HearthWorld *w = make_world();
    HearthBodyId ground = make_body(w, HEARTH_BODY_STATIC, 0, 0, 0);
    add_ground_plane(w, ground);
    enum { SLOTS = 200 };
    HearthBodyId live[SLOTS];
    HearthBodyId dead[SLOTS];
    int have[SLOTS];
    int ndead = 0;
    memset(have, 0, sizeof have);
    uint32_t expected = 1;
    for (int round = 0; round < 3000; round++) {
        int k = (int)(rng() % SLOTS);
        if (have[k]) {
            ENSURE_OK(hearth_body_destroy(w, live[k]));
            if (ndead < SLOTS) dead[ndead++] = live[k];
            have[k] = 0;
            expected--;
        } else {
            live[k] = make_body(w, HEARTH_BODY_DYNAMIC, (float)(k % 20) * 1.1f, 0.6f + (float)(k / 20) * 1.1f, 0);
            if (rng() % 2) {
                add_box(w, live[k], 0.5f, 0.5f, 0.5f);
            } else {
                HearthShapeDef sd = hearth_shape_def_default();
                HearthSphere s = {{0, 0, 0}, 0.5f};
                HearthShapeId sid;
                ENSURE_OK(hearth_shape_create_sphere(w, live[k], &sd, &s, &sid));
            }
            have[k] = 1;
            expected++;
        }
        if (round % 10 == 0) ENSURE_OK(hearth_world_step(w, 1.0f / 60.0f));
    }
    ENSURE(body_count(w) == expected);
    int stale_rejected = 1;
    for (int i = 0; i < ndead; i++) {
        HearthTransform t;
        stale_rejected &= hearth_body_get_transform(w, dead[i], &t) == HEARTH_ERROR_INVALID_ID;
    }
    ENSURE(stale_rejected);
    hearth_world_destroy(w);
}

static void test_box_comes_to_rest(void) {
    HearthWorld *w = make_world();
    HearthBodyId ground = make_body(w, HEARTH_BODY_STATIC, 0, 0, 0);
    add_ground_plane(w, ground);
    HearthBodyId box = make_body(w, HEARTH_BODY_DYNAMIC, 0, 3, 0);
    add_box(w, box, 0.5f, 0.5f, 0.5f);
    bool awake = true;
    int steps = 0;
    for (; steps < 600 && awake; steps++) {
        ENSURE_OK(hearth_world_step(w, 1.0f / 60.0f));
        ENSURE_OK(hearth_body_is_awake(w, box, &awake));
    }
    HearthTransform t;
    ENSURE_OK(hearth_body_get_transform(w, box, &t));
    ENSURE_NEAR(t.position.y, 0.5, 0.01);
    ENSURE_NEAR(t.position.x, 0.0, 1e-3);
    ENSURE_NEAR(t.rotation.w, 1.0, 1e-4);
    ENSURE(!awake); /* it fell asleep within 10 s */
    HearthVec3 v;
    ENSURE_OK(hearth_body_get_linear_velocity(w, box, &v));
    ENSURE_NEAR(v.y, 0.0, 1e-3);

    /* Sphere on a static box floor rests at floor top + radius. */
    HearthBodyId floor_body = make_body(w, HEARTH_BODY_STATIC, 10, -1, 0);
    add_box(w, floor_body, 2.0f, 1.0f, 2.0f);
    HearthBodyId ball = make_body(w, HEARTH_BODY_DYNAMIC, 10, 2, 0);
    HearthShapeDef sd = hearth_shape_def_default();
    HearthSphere s = {{0, 0, 0}, 0.25f};
    HearthShapeId sid;
    ENSURE_OK(hearth_shape_create_sphere(w, ball, &sd, &s, &sid));
    for (int i = 0; i < 180; i++) ENSURE_OK(hearth_world_step(w, 1.0f / 60.0f));
    ENSURE_OK(hearth_body_get_transform(w, ball, &t));
    ENSURE_NEAR(t.position.y, 0.25, 0.01);
    hearth_world_destroy(w);
}

/* A ball rolling on a level plane with rolling resistance c (the pair's larger value) slows
 * at 5/7·c·g and stops after 7v²/(10·c·g); then it sleeps. Spinning in place with torsional
 * friction t it stops after 2·r·ω/(5·t·g). */
static void test_rolling_ball_stops(void) {
    HearthWorld *w = make_world();
    HearthBodyId ground = make_body(w, HEARTH_BODY_STATIC, 0, 0, 0);
    add_ground_plane(w, ground); /* default material: 0.05 */
    const float r = 0.3f, v0 = 2.0f, c = 0.2f, t = 0.3f, spin = 6.0f, g = 9.81f;
    HearthShapeDef sd = hearth_shape_def_default();
    sd.rolling_resistance = c;
    sd.torsional_friction = t;
    HearthSphere sphere = {{0, 0, 0}, r};
    HearthShapeId sid;
    HearthBodyId ball = make_body(w, HEARTH_BODY_DYNAMIC, 0, r, 0);
    ENSURE_OK(hearth_shape_create_sphere(w, ball, &sd, &sphere, &sid));
    HearthBodyId top = make_body(w, HEARTH_BODY_DYNAMIC, 5, r, 0);
    ENSURE_OK(hearth_shape_create_sphere(w, top, &sd, &sphere, &sid));
    HearthVec3 v = {v0, 0, 0}, omega = {0, 0, -v0 / r}, spin_up = {0, spin, 0};
    ENSURE_OK(hearth_body_set_linear_velocity(w, ball, v));
    ENSURE_OK(hearth_body_set_angular_velocity(w, ball, omega));
    ENSURE_OK(hearth_body_set_angular_velocity(w, top, spin_up));
    int rolled = -1, spun = -1;
    for (int i = 1; i <= 600; i++) {
        ENSURE_OK(hearth_world_step(w, 1.0f / 60.0f));
        HearthVec3 u;
        ENSURE_OK(hearth_body_get_linear_velocity(w, ball, &u));
        if (rolled < 0 && u.x <= 1e-3f) rolled = i;
        ENSURE_OK(hearth_body_get_angular_velocity(w, top, &u));
        if (spun < 0 && u.y <= 1e-3f) spun = i;
    }
    HearthTransform tf;
    ENSURE_OK(hearth_body_get_transform(w, ball, &tf));
    double distance = 7.0 * v0 * v0 / (10.0 * c * g), stop_time = 2.0 * r * spin / (5.0 * t * g);
    ENSURE_NEAR(tf.position.x, distance, 0.05 * distance);
    ENSURE(spun > 0);
    ENSURE_NEAR(spun / 60.0, stop_time, 0.05 * stop_time + 1.0 / 60.0);
    ENSURE(rolled > 0);
    bool awake = true;
    ENSURE_OK(hearth_body_is_awake(w, ball, &awake));
    ENSURE(!awake);
    ENSURE_OK(hearth_body_is_awake(w, top, &awake));
    ENSURE(!awake);
    hearth_world_destroy(w);
}

int main(void) {
    test_version_and_names();
    test_last_error_message();
    test_world_create_errors();
    test_body_create_errors();
    test_ids();
    test_shape_errors();
    test_state_roundtrip();
    test_bulk_read();
    test_churn();
    test_box_comes_to_rest();
    test_rolling_ball_stops();
    return ensure_report("test_api");
}
