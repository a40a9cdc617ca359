/*
 * pyramid.c - a Hearth example in plain C, written only against include/hearth.h.
 *
 * Builds a pyramid of unit boxes on a ground plane, drops a "pile" of 60 alternating
 * spheres and boxes onto it from a grid above, and steps 30 s at 60 Hz. Every three seconds
 * it prints the time, the height of the pyramid's top box and how many bodies are awake.
 * The spheres roll off and slow down by their rolling resistance; by the end every body
 * sleeps, and the program exits with status 1 if one does not.
 *
 * Build and run from the repository root, after `cargo build --release`:
 *   cc -std=c11 -Wall -Wextra -O2 -Iinclude examples/c/pyramid.c -Ltarget/release -lhearth \
 *      -Wl,-rpath,$PWD/target/release -lm -o pyramid && ./pyramid
 */
#include "hearth.h"

#include <inttypes.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define BASE 5           /* boxes per side in the bottom layer: 25+16+9+4+1 = 55 boxes */
#define PYRAMID_BOXES 55
#define PILE_BODIES 60   /* alternating spheres (r = 0.5) and unit boxes */
#define PILE_ROW 8       /* the pile starts as an 8 x 8 grid (60 of its 64 cells used) */
#define MAX_BODIES (PYRAMID_BOXES + PILE_BODIES)

static const float DT = 1.0f / 60.0f;
static const int STEPS = 1800; /* 30 s */
static const int REPORT_EVERY = 180;

/* The world, so that a failure can still destroy it before exiting. */
static HearthWorld *g_world = NULL;

/* Every HearthResult goes through here: on failure, print the code's name and the
 * thread's detail message, clean up and exit with status 1. */
static void check(HearthResult result, const char *what) {
    if (result == HEARTH_OK) {
        return;
    }
    char message[256];
    hearth_last_error_message(message, sizeof message);
    fprintf(stderr, "error: %s failed: %s (%s)\n", what, hearth_result_name(result), message);
    hearth_world_destroy(g_world); /* NULL is a no-op */
    exit(1);
}
#define CHECK(call) check((call), #call)

static HearthVec3 vec3(float x, float y, float z) {
    HearthVec3 v = {x, y, z};
    return v;
}

/* A dynamic body at `p` with no shapes yet. */
static HearthBodyId dynamic_body(HearthVec3 p) {
    HearthBodyDef def = hearth_body_def_default(); /* always start from the defaults */
    def.type = HEARTH_BODY_DYNAMIC;
    def.transform.position = p;
    HearthBodyId body = {0, 0};
    CHECK(hearth_body_create(g_world, &def, &body));
    return body;
}

static HearthBodyId add_box(HearthVec3 p) {
    HearthBodyId body = dynamic_body(p);
    HearthShapeDef sd = hearth_shape_def_default();
    HearthBox box = {vec3(0.0f, 0.0f, 0.0f), {0.0f, 0.0f, 0.0f, 1.0f}, vec3(0.5f, 0.5f, 0.5f)};
    HearthShapeId shape = {0, 0};
    CHECK(hearth_shape_create_box(g_world, body, &sd, &box, &shape));
    return body;
}

static HearthBodyId add_sphere(HearthVec3 p) {
    HearthBodyId body = dynamic_body(p);
    HearthShapeDef sd = hearth_shape_def_default();
    HearthSphere sphere = {vec3(0.0f, 0.0f, 0.0f), 0.5f};
    HearthShapeId shape = {0, 0};
    CHECK(hearth_shape_create_sphere(g_world, body, &sd, &sphere, &shape));
    return body;
}

/* The static ground: the half-space y <= 0, a plane on a static body. */
static void add_ground(void) {
    HearthBodyDef def = hearth_body_def_default(); /* static by default */
    HearthBodyId ground = {0, 0};
    CHECK(hearth_body_create(g_world, &def, &ground));
    HearthShapeDef sd = hearth_shape_def_default();
    HearthPlane plane = {vec3(0.0f, 1.0f, 0.0f), 0.0f};
    HearthShapeId shape = {0, 0};
    CHECK(hearth_shape_create_plane(g_world, ground, &sd, &plane, &shape));
}

/* FNV-1a over the bits of every body's position, rotation, linear and angular velocity (13
 * floats), folded into `h`: the "state hash" column. The C, C++, Python and C# examples must
 * print the same hashes, so they agree to the last bit on every body after every step. */
static uint64_t hash_state(uint64_t h, const HearthBodyId *bodies, size_t count,
                           HearthTransform *transforms) {
    CHECK(hearth_world_get_transforms(g_world, bodies, count, transforms));
    for (size_t b = 0; b < count; b++) {
        HearthVec3 v, w;
        CHECK(hearth_body_get_linear_velocity(g_world, bodies[b], &v));
        CHECK(hearth_body_get_angular_velocity(g_world, bodies[b], &w));
        const HearthTransform *x = &transforms[b];
        const float state[13] = {x->position.x, x->position.y, x->position.z, x->rotation.x,
                                 x->rotation.y, x->rotation.z, x->rotation.w, v.x, v.y, v.z,
                                 w.x, w.y, w.z};
        for (size_t i = 0; i < 13; i++) {
            uint32_t bits;
            memcpy(&bits, &state[i], sizeof bits);
            h = (h ^ bits) * UINT64_C(0x100000001b3);
        }
    }
    return h;
}

int main(int argc, char **argv) {
    if (hearth_version() != HEARTH_VERSION) {
        fprintf(stderr, "error: header version %u, library version %u\n", (unsigned)HEARTH_VERSION,
                (unsigned)hearth_version());
        return 1;
    }

    HearthWorldDef world_def = hearth_world_def_default(); /* gravity -9.81 y, 6 sub-steps */
    CHECK(hearth_world_create(&world_def, &g_world));
    add_ground();

    HearthBodyId bodies[MAX_BODIES];
    size_t count = 0;

    /* Pyramid: layer L has (BASE - L)^2 boxes, centred on the y axis; the last is the top. */
    for (int layer = 0; layer < BASE; layer++) {
        int n = BASE - layer;
        float offset = -0.5f * (float)(n - 1);
        for (int i = 0; i < n; i++) {
            for (int k = 0; k < n; k++) {
                HearthVec3 p = vec3(offset + (float)i, 0.5f + (float)layer, offset + (float)k);
                bodies[count++] = add_box(p);
            }
        }
    }
    const size_t top = count - 1;

    /* Pile: a grid 1.5 m apart, 10 m up, centred over the pyramid. */
    for (int j = 0; j < PILE_BODIES; j++) {
        float x = -5.25f + 1.5f * (float)(j % PILE_ROW);
        float z = -5.25f + 1.5f * (float)(j / PILE_ROW);
        HearthVec3 p = vec3(x, 10.0f, z);
        bodies[count++] = (j % 2 == 0) ? add_sphere(p) : add_box(p);
    }

    printf("Hearth %u.%u.%u C example: pyramid of %d boxes (base %d) + pile of %d spheres/boxes\n",
           (unsigned)HEARTH_VERSION_MAJOR, (unsigned)HEARTH_VERSION_MINOR,
           (unsigned)HEARTH_VERSION_PATCH, PYRAMID_BOXES, BASE, PILE_BODIES);
    printf("%8s %14s %16s %8s\n", "t [s]", "top box y [m]", "state hash", "awake");
    uint64_t hash = UINT64_C(0xcbf29ce484222325);

    HearthTransform transforms[MAX_BODIES]; /* caller-owned, filled in one call per report */
    /* With a path argument, record the run for the browser viewer (viewer/index.html). */
    if (argc > 1) {
        HearthRecordDef record = hearth_record_def_default();
        record.record_contacts = 1;
        CHECK(hearth_world_record_start_file(g_world, argv[1], &record));
    }
    int awake = (int)count;
    for (int step = 1; step <= STEPS; step++) {
        CHECK(hearth_world_step(g_world, DT));
        hash = hash_state(hash, bodies, count, transforms); /* after every step */
        if (step % REPORT_EVERY != 0) {
            continue;
        }
        CHECK(hearth_world_get_transforms(g_world, bodies, count, transforms));
        awake = 0;
        for (size_t b = 0; b < count; b++) {
            bool is_awake = false;
            CHECK(hearth_body_is_awake(g_world, bodies[b], &is_awake));
            awake += is_awake ? 1 : 0;
        }
        double t = (double)((float)step * DT);
        printf("%8.2f %14.3f %016" PRIx64 " %4d/%d\n", t, (double)transforms[top].position.y, hash,
               awake, (int)count);
    }

    if (argc > 1) {
        CHECK(hearth_world_record_stop(g_world));
        fprintf(stderr, "recorded %s: open it with viewer/index.html\n", argv[1]);
    }
    hearth_world_destroy(g_world);
    g_world = NULL;
    if (awake != 0) {
        fprintf(stderr, "error: %d bodies still awake after %d steps\n", awake, STEPS);
        return 1;
    }
    printf("done\n");
    return 0;
}
