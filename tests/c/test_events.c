/* Events, sensors and the step callbacks from C: a dropped box's contact begin, hit (speed
 * within 1 % of sqrt(2gh)) and end; a kinematic box through a sensor; move events; the
 * pair-filter and pre-solve callbacks (reads work, changes are locked); every error of the
 * new functions and the new def flags (each error changes nothing). */
#include "hearth.h"
#include "ensure.h"

#include <math.h>
#include <stdint.h>
#include <string.h>

static HearthWorld *make_world(HearthShapeId *out_ground) {
    HearthWorldDef wd = hearth_world_def_default();
    HearthWorld *w = NULL;
    ENSURE_OK(hearth_world_create(&wd, &w));
    HearthBodyDef gd = hearth_body_def_default();
    HearthBodyId g = {0, 0};
    ENSURE_OK(hearth_body_create(w, &gd, &g));
    HearthShapeDef sd = hearth_shape_def_default();
    HearthPlane p = {{0, 1, 0}, 0};
    ENSURE_OK(hearth_shape_create_plane(w, g, &sd, &p, out_ground));
    return w;
}

static HearthBodyId add_box(HearthWorld *w, uint32_t type, float x, float y, float h, const HearthShapeDef *sd,
                            HearthShapeId *out_shape) {
    HearthBodyDef bd = hearth_body_def_default();
    bd.type = type;
    bd.transform.position.x = x;
    bd.transform.position.y = y;
    bd.user_data = 7;
    HearthBodyId b = {0, 0};
    ENSURE_OK(hearth_body_create(w, &bd, &b));
    HearthBox box = {{0, 0, 0}, {0, 0, 0, 1}, {h, h, h}};
    ENSURE_OK(hearth_shape_create_box(w, b, sd, &box, out_shape));
    return b;
}

static void test_drop(void) {
    HearthShapeId ground;
    HearthWorld *w = make_world(&ground);
    HearthShapeDef sd = hearth_shape_def_default();
    ENSURE(sd.is_sensor == 0 && sd.enable_contact_events == 1 && sd.enable_hit_events == 0 && sd.enable_sensor_events == 1);
    sd.enable_hit_events = 1;
    const float h = 2.0f;
    HearthShapeId s;
    HearthBodyId b = add_box(w, HEARTH_BODY_DYNAMIC, 0, 0.5f + h, 0.5f, &sd, &s);
    int begins = 0, hits = 0, ends = 0, moves = 0;
    float speed = 0;
    for (int i = 0; i < 120; i++) {
        ENSURE_OK(hearth_world_step(w, 1.0f / 60.0f));
        HearthContactEvents ev;
        ENSURE_OK(hearth_world_get_contact_events(w, &ev));
        begins += (int)ev.begin_count;
        ends += (int)ev.end_count;
        for (size_t k = 0; k < ev.begin_count; k++) {
            int ours = (ev.begin[k].shape_a.index == s.index && ev.begin[k].shape_b.index == ground.index) ||
                       (ev.begin[k].shape_b.index == s.index && ev.begin[k].shape_a.index == ground.index);
            ENSURE(ours);
        }
        for (size_t k = 0; k < ev.hit_count; k++) {
            hits++;
            speed = ev.hit[k].approach_speed;
            ENSURE(fabsf(ev.hit[k].normal.y) > 0.999f);
        }
        HearthBodyEvents be;
        ENSURE_OK(hearth_world_get_body_events(w, &be));
        for (size_t k = 0; k < be.move_count; k++) {
            ENSURE(be.moves[k].body.index == b.index && be.moves[k].user_data == 7);
            moves++;
        }
    }
    ENSURE(begins == 1 && hits == 1 && ends == 0);
    ENSURE_NEAR(speed, sqrtf(2.0f * 9.81f * h), 0.01f * sqrtf(2.0f * 9.81f * h));
    ENSURE(moves > 30);
    /* Destroying the touching shape: an end with the next step. */
    ENSURE_OK(hearth_shape_destroy(w, s));
    ENSURE_OK(hearth_world_step(w, 1.0f / 60.0f));
    HearthContactEvents ev;
    ENSURE_OK(hearth_world_get_contact_events(w, &ev));
    ENSURE(ev.end_count == 1);
    hearth_world_destroy(w);
}

static void test_sensor(void) {
    HearthShapeId ground;
    HearthWorld *w = make_world(&ground);
    HearthShapeDef sensor = hearth_shape_def_default();
    sensor.is_sensor = 1;
    HearthShapeId zone, visitor;
    add_box(w, HEARTH_BODY_STATIC, 0, 3, 1.0f, &sensor, &zone);
    HearthShapeDef sd = hearth_shape_def_default();
    HearthBodyId k = add_box(w, HEARTH_BODY_KINEMATIC, -5, 3, 0.25f, &sd, &visitor);
    HearthVec3 v = {2, 0, 0};
    ENSURE_OK(hearth_body_set_linear_velocity(w, k, v));
    int begins = 0, ends = 0;
    for (int i = 0; i < 300; i++) {
        ENSURE_OK(hearth_world_step(w, 1.0f / 60.0f));
        HearthSensorEvents ev;
        ENSURE_OK(hearth_world_get_sensor_events(w, &ev));
        for (size_t j = 0; j < ev.begin_count; j++)
            ENSURE(ev.begin[j].sensor_shape.index == zone.index && ev.begin[j].visitor_shape.index == visitor.index);
        begins += (int)ev.begin_count;
        ends += (int)ev.end_count;
    }
    ENSURE(begins == 1 && ends == 1);
    /* A plane cannot be a sensor. */
    HearthBodyDef gd = hearth_body_def_default();
    HearthBodyId g;
    ENSURE_OK(hearth_body_create(w, &gd, &g));
    HearthPlane p = {{0, 1, 0}, -5};
    HearthShapeId out = {99, 99};
    ENSURE_RESULT(hearth_shape_create_plane(w, g, &sensor, &p, &out), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE(out.index == 99);
    hearth_world_destroy(w);
}

typedef struct {
    HearthShapeId platform;
    int filter_calls, pre_solve_calls, locked_ok;
} Hooks;

static uint8_t filter(void *user_data, HearthWorld *world, HearthShapeId a, HearthShapeId b) {
    Hooks *hk = (Hooks *)user_data;
    hk->filter_calls++;
    HearthVec3 g;
    if (hearth_world_get_gravity(world, &g) == HEARTH_OK &&
        hearth_world_set_gravity(world, g) == HEARTH_ERROR_WORLD_LOCKED)
        hk->locked_ok++;
    (void)a;
    (void)b;
    return 1;
}

/* The one-way platform: push only upwards, and only while the box is not part-way through. */
static uint8_t one_way(void *user_data, HearthWorld *world, const HearthPreSolveContact *c) {
    Hooks *hk = (Hooks *)user_data;
    hk->pre_solve_calls++;
    HearthBodyDef bd = hearth_body_def_default();
    HearthBodyId out;
    if (hearth_body_create(world, &bd, &out) == HEARTH_ERROR_WORLD_LOCKED) hk->locked_ok++;
    float up;
    if (c->shape_a.index == hk->platform.index) up = c->normal.y;
    else if (c->shape_b.index == hk->platform.index) up = -c->normal.y;
    else return 1;
    float deepest = 1e30f;
    for (uint32_t i = 0; i < c->point_count; i++)
        if (c->points[i].separation < deepest) deepest = c->points[i].separation;
    return up > 0.7f && deepest > -0.05f;
}

static void test_callbacks(void) {
    HearthShapeId ground;
    HearthWorld *w = make_world(&ground);
    Hooks hk;
    memset(&hk, 0, sizeof hk);
    HearthBodyDef pd = hearth_body_def_default();
    pd.transform.position.y = 3;
    HearthBodyId p;
    ENSURE_OK(hearth_body_create(w, &pd, &p));
    HearthShapeDef sd = hearth_shape_def_default();
    HearthBox slab = {{0, 0, 0}, {0, 0, 0, 1}, {2, 0.1f, 2}};
    ENSURE_OK(hearth_shape_create_box(w, p, &sd, &slab, &hk.platform));
    HearthShapeId s;
    HearthBodyId b = add_box(w, HEARTH_BODY_DYNAMIC, 0, 0.5f, 0.25f, &sd, &s);
    HearthVec3 up = {0, 10, 0};
    ENSURE_OK(hearth_body_set_linear_velocity(w, b, up));
    ENSURE_OK(hearth_world_set_pair_filter_callback(w, filter, &hk));
    ENSURE_OK(hearth_world_set_pre_solve_callback(w, one_way, &hk));
    for (int i = 0; i < 180; i++) ENSURE_OK(hearth_world_step(w, 1.0f / 60.0f));
    HearthTransform t;
    ENSURE_OK(hearth_body_get_transform(w, b, &t));
    ENSURE_NEAR(t.position.y, 3.35f, 0.005f);
    ENSURE(hk.filter_calls > 0 && hk.pre_solve_calls > 0);
    ENSURE(hk.locked_ok == hk.filter_calls + hk.pre_solve_calls);
    /* Cleared: no more calls. */
    ENSURE_OK(hearth_world_set_pair_filter_callback(w, NULL, NULL));
    ENSURE_OK(hearth_world_set_pre_solve_callback(w, NULL, NULL));
    int calls = hk.filter_calls + hk.pre_solve_calls;
    for (int i = 0; i < 10; i++) ENSURE_OK(hearth_world_step(w, 1.0f / 60.0f));
    ENSURE(hk.filter_calls + hk.pre_solve_calls == calls);
    hearth_world_destroy(w);
}

static void test_errors(void) {
    HearthShapeId ground;
    HearthWorld *w = make_world(&ground);
    char msg[256];
    HearthContactEvents ce;
    HearthSensorEvents se;
    HearthBodyEvents be;
    ENSURE_RESULT(hearth_world_get_contact_events(NULL, &ce), HEARTH_ERROR_NULL_POINTER);
    ENSURE_RESULT(hearth_world_get_contact_events(w, NULL), HEARTH_ERROR_NULL_POINTER);
    hearth_last_error_message(msg, sizeof msg);
    ENSURE(strstr(msg, "out_events") != NULL);
    ENSURE_RESULT(hearth_world_get_sensor_events(NULL, &se), HEARTH_ERROR_NULL_POINTER);
    ENSURE_RESULT(hearth_world_get_sensor_events(w, NULL), HEARTH_ERROR_NULL_POINTER);
    ENSURE_RESULT(hearth_world_get_body_events(NULL, &be), HEARTH_ERROR_NULL_POINTER);
    ENSURE_RESULT(hearth_world_get_body_events(w, NULL), HEARTH_ERROR_NULL_POINTER);
    ENSURE_RESULT(hearth_world_set_pair_filter_callback(NULL, filter, NULL), HEARTH_ERROR_NULL_POINTER);
    ENSURE_RESULT(hearth_world_set_pre_solve_callback(NULL, one_way, NULL), HEARTH_ERROR_NULL_POINTER);
    /* Before any step: empty. */
    ENSURE_OK(hearth_world_get_contact_events(w, &ce));
    ENSURE(ce.begin_count == 0 && ce.end_count == 0 && ce.hit_count == 0);
    ENSURE_OK(hearth_world_get_sensor_events(w, &se));
    ENSURE(se.begin_count == 0 && se.end_count == 0);
    ENSURE_OK(hearth_world_get_body_events(w, &be));
    ENSURE(be.move_count == 0);
    /* Flag bytes other than 0/1, each named. */
    HearthBodyDef bd = hearth_body_def_default();
    ENSURE(bd.enable_move_events == 1);
    bd.enable_move_events = 2;
    HearthBodyId b = {5, 5};
    ENSURE_RESULT(hearth_body_create(w, &bd, &b), HEARTH_ERROR_INVALID_ARGUMENT);
    hearth_last_error_message(msg, sizeof msg);
    ENSURE(strstr(msg, "enable_move_events") != NULL && b.index == 5);
    bd = hearth_body_def_default();
    bd.type = HEARTH_BODY_DYNAMIC;
    ENSURE_OK(hearth_body_create(w, &bd, &b));
    const char *names[] = {"is_sensor", "enable_contact_events", "enable_hit_events", "enable_sensor_events"};
    for (int k = 0; k < 4; k++) {
        HearthShapeDef sd = hearth_shape_def_default();
        uint8_t *field = k == 0 ? &sd.is_sensor : k == 1 ? &sd.enable_contact_events : k == 2 ? &sd.enable_hit_events : &sd.enable_sensor_events;
        *field = 3;
        HearthSphere sp = {{0, 0, 0}, 0.5f};
        HearthShapeId out = {9, 9};
        ENSURE_RESULT(hearth_shape_create_sphere(w, b, &sd, &sp, &out), HEARTH_ERROR_INVALID_ARGUMENT);
        hearth_last_error_message(msg, sizeof msg);
        ENSURE(strstr(msg, names[k]) != NULL && out.index == 9);
    }
    HearthWorldDef wd = hearth_world_def_default();
    ENSURE_NEAR(wd.hit_event_threshold, 1.0f, 0.0f);
    const float bad[] = {-1.0f, NAN, INFINITY, 2e4f};
    for (int k = 0; k < 4; k++) {
        wd.hit_event_threshold = bad[k];
        HearthWorld *w2 = NULL;
        ENSURE_RESULT(hearth_world_create(&wd, &w2), HEARTH_ERROR_INVALID_ARGUMENT);
        hearth_last_error_message(msg, sizeof msg);
        ENSURE(strstr(msg, "hit_event_threshold") != NULL && w2 == NULL);
    }
    hearth_world_destroy(w);
}

int main(void) {
    test_errors();
    test_drop();
    test_sensor();
    test_callbacks();
    return ensure_report("test_events");
}
