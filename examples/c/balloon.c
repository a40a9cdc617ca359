/*
 * balloon.c - a Hearth example in plain C, written only against include/hearth.h.
 *
 * A pressurised balloon (a soft icosphere of 642 vertices, radius 0.5 m, 2 kg, gas
 * nRT = 400 J) is dropped from 3 m onto three dynamic wooden boxes lying on a ground plane.
 * It bounces, rolls off and settles; the boxes feel its weight and its push (soft-body
 * contacts are two-way, solved in the soft-body sub-steps). Every 30 steps the program prints the time, the balloon's centre
 * height and its volume, read back with the calls a host uses to rebuild its render mesh
 * each frame (positions and normals into caller-owned arrays, one call each). It checks
 * its own outcome: the balloon comes to rest above the ground and keeps its volume within
 * 5 % of its rest volume.
 *
 * Build and run from the repository root, after `cargo build --release`:
 *   cc -std=c11 -Wall -Wextra -O2 -Iinclude examples/c/balloon.c -Ltarget/release -lhearth \
 *      -Wl,-rpath,$PWD/target/release -lm -o balloon && ./balloon
 */
#include "hearth.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

static const float DT = 1.0f / 60.0f;
static const int STEPS = 600; /* 10 s */
static const int REPORT_EVERY = 30;

/* The world, so that a failure can still destroy it before exiting. */
static HearthWorld *g_world = NULL;
static HearthVec3 *g_positions = NULL;
static HearthVec3 *g_normals = NULL;

static void cleanup(void) {
    free(g_positions);
    free(g_normals);
    hearth_world_destroy(g_world); /* NULL is a no-op */
    g_positions = NULL;
    g_normals = NULL;
    g_world = NULL;
}

/* Every HearthResult goes through here: on failure, print the code's name and the
 * thread's detail message, clean up and exit with status 1. */
static void check(HearthResult result, const char *what) {
    if (result == HEARTH_OK) {
        return;
    }
    char message[256];
    hearth_last_error_message(message, sizeof message);
    fprintf(stderr, "error: %s failed: %s (%s)\n", what, hearth_result_name(result), message);
    cleanup();
    exit(1);
}
#define CHECK(call) check((call), #call)

static HearthVec3 vec3(float x, float y, float z) {
    HearthVec3 v = {x, y, z};
    return v;
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

/* A dynamic wooden box (density 500 kg/m^3) of the given half extents at `p`. */
static void add_box(HearthVec3 p, HearthVec3 half) {
    HearthBodyDef def = hearth_body_def_default();
    def.type = HEARTH_BODY_DYNAMIC;
    def.transform.position = p;
    HearthBodyId body = {0, 0};
    CHECK(hearth_body_create(g_world, &def, &body));
    HearthShapeDef sd = hearth_shape_def_default();
    sd.density = 500.0f;
    HearthBox box = {vec3(0.0f, 0.0f, 0.0f), {0.0f, 0.0f, 0.0f, 1.0f}, half};
    HearthShapeId shape = {0, 0};
    CHECK(hearth_shape_create_box(g_world, body, &sd, &box, &shape));
}

int main(int argc, char **argv) {
    if (hearth_version() != HEARTH_VERSION) {
        fprintf(stderr, "error: header version %u, library version %u\n", (unsigned)HEARTH_VERSION,
                (unsigned)hearth_version());
        return 1;
    }

    HearthWorldDef world_def = hearth_world_def_default();
    CHECK(hearth_world_create(&world_def, &g_world));
    add_ground();

    /* Three boxes side by side under the drop point, the middle one taller. */
    add_box(vec3(-0.9f, 0.25f, 0.0f), vec3(0.4f, 0.25f, 0.4f));
    add_box(vec3(0.0f, 0.4f, 0.1f), vec3(0.4f, 0.4f, 0.4f));
    add_box(vec3(0.9f, 0.25f, -0.1f), vec3(0.4f, 0.25f, 0.4f));

    /* The balloon: always start from the defaults, then edit. */
    HearthSoftBodyDef def = hearth_soft_body_def_default();
    def.transform.position = vec3(0.2f, 3.0f, 0.0f);
    def.mass = 2.0f;
    def.pressure = 400.0f; /* nRT (J): the gas pushes each face by nRT / V * area */
    def.friction = 0.6f;
    def.restitution = 0.2f; /* stiffness, damping and sub-steps: the defaults */
    HearthSoftBodyId balloon = {0, 0};
    CHECK(hearth_soft_body_create_icosphere(g_world, &def, 0.5f, 3, &balloon));

    size_t vertices = 0, triangles = 0;
    CHECK(hearth_soft_body_get_vertex_count(g_world, balloon, &vertices));
    CHECK(hearth_soft_body_get_triangle_count(g_world, balloon, &triangles));
    float rest_volume = 0.0f;
    CHECK(hearth_soft_body_get_rest_volume(g_world, balloon, &rest_volume));
    /* The host's render buffers: caller-owned, sized once, refilled every frame. */
    g_positions = (HearthVec3 *)malloc(vertices * sizeof(HearthVec3));
    g_normals = (HearthVec3 *)malloc(vertices * sizeof(HearthVec3));
    if (g_positions == NULL || g_normals == NULL) {
        fprintf(stderr, "error: out of memory\n");
        cleanup();
        return 1;
    }

    printf("Hearth %u.%u.%u C example: a balloon of %u vertices and %u triangles (rest volume %.4f m^3)\n",
           (unsigned)HEARTH_VERSION_MAJOR, (unsigned)HEARTH_VERSION_MINOR, (unsigned)HEARTH_VERSION_PATCH,
           (unsigned)vertices, (unsigned)triangles, (double)rest_volume);
    printf("%8s %16s %14s %10s\n", "t [s]", "centre y [m]", "volume [m^3]", "vs rest");

    float worst = 0.0f, lowest = 0.0f, last_y = 0.0f, second_ago = 0.0f;
    /* With a path argument, record the run for the browser viewer (viewer/index.html). */
    if (argc > 1) {
        HearthRecordDef record = hearth_record_def_default();
        record.record_contacts = 1;
        CHECK(hearth_world_record_start_file(g_world, argv[1], &record));
    }
    for (int step = 1; step <= STEPS; step++) {
        CHECK(hearth_world_step(g_world, DT));
        /* What a host does every frame: one call for positions, one for normals. */
        size_t n = 0;
        CHECK(hearth_soft_body_get_positions(g_world, balloon, g_positions, vertices, &n));
        CHECK(hearth_soft_body_get_normals(g_world, balloon, g_normals, vertices, &n));
        HearthVec3 centre;
        CHECK(hearth_soft_body_get_center(g_world, balloon, &centre));
        float volume = 0.0f;
        CHECK(hearth_soft_body_get_volume(g_world, balloon, &volume));
        float error = fabsf(volume / rest_volume - 1.0f);
        if (step > 30 && error > worst) {
            worst = error;
        }
        if (step == STEPS - 60) {
            second_ago = centre.y;
        }
        last_y = centre.y;
        if (step % REPORT_EVERY == 0) {
            printf("%8.2f %16.3f %14.4f %9.2f%%\n", (double)((float)step * DT), (double)centre.y, (double)volume,
                   100.0 * (double)(volume / rest_volume - 1.0f));
        }
    }
    lowest = g_positions[0].y;
    for (size_t i = 1; i < vertices; i++) {
        lowest = fminf(lowest, g_positions[i].y);
    }

    int ok = worst < 0.05f && fabsf(last_y - second_ago) < 0.01f && lowest > -0.02f;
    printf("worst volume change after the drop %.2f %%, lowest vertex %.3f m, moved %.4f m in the last second: %s\n",
           100.0 * (double)worst, (double)lowest, (double)fabsf(last_y - second_ago), ok ? "OK" : "FAILED");
    if (argc > 1) {
        CHECK(hearth_world_record_stop(g_world));
        fprintf(stderr, "recorded %s: open it with viewer/index.html\n", argv[1]);
    }
    cleanup();
    return ok ? 0 : 1;
}
