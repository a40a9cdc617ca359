/*
 * one_way_platform.c: a platform you can jump up through and stand on, made with the
 * pre-solve callback, using only include/hearth.h.
 *
 * A thin static slab hangs 3 m above the ground (its top at 3.1 m). A 0.5 m box is thrown
 * straight up from the ground at 10 m/s: it would rise 5.1 m. The pre-solve callback keeps
 * a contact with the slab only when it pushes the box up and the box is not already part-way
 * through, so the box passes the slab on the way up and lands on top on the way down. The
 * program also reads the contact events (contact begin and end follow the shapes, so the box
 * begins touching the slab twice: passing up through it, and landing) and prints the hit
 * event of the landing (its approach speed is the fall's sqrt(2gh)). Every 20 steps it prints the time and the box's height.
 * It checks that the box rose above the slab and rests on top at 3.35 m (within 5 mm), and
 * exits 1 otherwise (or on any failed call).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "hearth.h"

static void check(HearthResult r, const char *what) {
    if (r != HEARTH_OK) {
        char msg[256];
        hearth_last_error_message(msg, sizeof msg);
        fprintf(stderr, "%s failed: %s (%s)\n", what, hearth_result_name(r), msg);
        exit(1);
    }
}

/* What the callback needs: the slab's shape id. */
typedef struct {
    HearthShapeId platform;
} Platform;

static int same(HearthShapeId a, HearthShapeId b) { return a.index == b.index && a.generation == b.generation; }

/* Keep a contact with the slab only when it pushes the other shape up (the normal from the
 * slab towards it points up) and the other shape is not already 5 cm or more into it. */
static uint8_t one_way(void *user_data, HearthWorld *world, const HearthPreSolveContact *c) {
    const Platform *p = (const Platform *)user_data;
    (void)world;
    float up;
    if (same(c->shape_a, p->platform)) up = c->normal.y;
    else if (same(c->shape_b, p->platform)) up = -c->normal.y;
    else return 1;
    float deepest = INFINITY;
    for (uint32_t i = 0; i < c->point_count; i++)
        if (c->points[i].separation < deepest) deepest = c->points[i].separation;
    return up > 0.7f && deepest > -0.05f;
}

int main(void) {
    HearthWorldDef wd = hearth_world_def_default();
    HearthWorld *w = NULL;
    check(hearth_world_create(&wd, &w), "hearth_world_create");

    HearthBodyDef gd = hearth_body_def_default();
    HearthBodyId ground;
    check(hearth_body_create(w, &gd, &ground), "hearth_body_create");
    HearthShapeDef sd = hearth_shape_def_default();
    HearthPlane floor_plane = {{0, 1, 0}, 0};
    HearthShapeId floor_shape;
    check(hearth_shape_create_plane(w, ground, &sd, &floor_plane, &floor_shape), "hearth_shape_create_plane");

    Platform platform;
    HearthBodyDef pd = hearth_body_def_default();
    pd.transform.position.y = 3.0f;
    HearthBodyId slab;
    check(hearth_body_create(w, &pd, &slab), "hearth_body_create");
    HearthBox slab_box = {{0, 0, 0}, {0, 0, 0, 1}, {2.0f, 0.1f, 2.0f}};
    check(hearth_shape_create_box(w, slab, &sd, &slab_box, &platform.platform), "hearth_shape_create_box");

    HearthBodyDef bd = hearth_body_def_default();
    bd.type = HEARTH_BODY_DYNAMIC;
    bd.transform.position.y = 0.5f;
    bd.linear_velocity.y = 10.0f;
    HearthBodyId box;
    check(hearth_body_create(w, &bd, &box), "hearth_body_create");
    HearthShapeDef box_def = hearth_shape_def_default();
    box_def.enable_hit_events = 1;
    HearthBox cube = {{0, 0, 0}, {0, 0, 0, 1}, {0.25f, 0.25f, 0.25f}};
    HearthShapeId box_shape;
    check(hearth_shape_create_box(w, box, &box_def, &cube, &box_shape), "hearth_shape_create_box");

    check(hearth_world_set_pre_solve_callback(w, one_way, &platform), "hearth_world_set_pre_solve_callback");

    float top = 0.0f;
    int landings = 0;
    HearthTransform t;
    for (int step = 1; step <= 180; step++) {
        check(hearth_world_step(w, 1.0f / 60.0f), "hearth_world_step");
        check(hearth_body_get_transform(w, box, &t), "hearth_body_get_transform");
        if (t.position.y > top) top = t.position.y;
        HearthContactEvents ev;
        check(hearth_world_get_contact_events(w, &ev), "hearth_world_get_contact_events");
        for (size_t i = 0; i < ev.hit_count; i++)
            printf("t = %.2f s: hit at %.2f m/s, height %.3f m\n", step / 60.0, ev.hit[i].approach_speed,
                   ev.hit[i].point.y);
        for (size_t i = 0; i < ev.begin_count; i++)
            if (same(ev.begin[i].shape_a, platform.platform) || same(ev.begin[i].shape_b, platform.platform)) landings++;
        if (step % 20 == 0) printf("t = %.2f s: box at %.3f m\n", step / 60.0, t.position.y);
    }
    hearth_world_destroy(w);

    int ok = top > 4.0f && fabsf(t.position.y - 3.35f) < 0.005f;
    printf("rose to %.2f m, rests at %.4f m (expected 3.35 m), %d begin event(s) with the slab: %s\n", top,
           t.position.y, landings, ok ? "OK" : "FAILED");
    return ok ? 0 : 1;
}
