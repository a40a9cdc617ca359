/*
 * trajectory_hash.c - prints a fingerprint of a simulation, bit for bit, so that two builds
 * can be compared exactly: .ci/windows runs it on Linux and, built with MinGW-w64, under Wine,
 * and the outputs must be identical.
 *
 * The scene touches most of the engine: a pyramid of boxes on a ground plane hit by spheres,
 * capsules and boxes (broad and narrow phase, the SIMD contact solver, sleep), a chain of
 * capsules on ball joints from a world anchor, a hinge with a motor, and a drag generator.
 * Every 60 steps it prints an FNV-1a hash of the raw bytes of every body's transform, and
 * at the end the first bodies' positions as hexadecimal floats (%a), which show any last-bit
 * difference.
 */
#include "hearth.h"

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MAX_BODIES 256

static HearthWorld *g_world = NULL;
static HearthBodyId g_bodies[MAX_BODIES];
static size_t g_count = 0;

static void check(HearthResult result, const char *what) {
    if (result != HEARTH_OK) {
        char message[256];
        hearth_last_error_message(message, sizeof message);
        fprintf(stderr, "error: %s: %s (%s)\n", what, hearth_result_name(result), message);
        exit(1);
    }
}
#define CHECK(call) check((call), #call)

static HearthVec3 v3(float x, float y, float z) {
    HearthVec3 v = {x, y, z};
    return v;
}

static HearthBodyId body(uint32_t type, HearthVec3 p) {
    HearthBodyDef def = hearth_body_def_default();
    def.type = type;
    def.transform.position = p;
    HearthBodyId id = {0, 0};
    CHECK(hearth_body_create(g_world, &def, &id));
    if (type == HEARTH_BODY_DYNAMIC) {
        g_bodies[g_count++] = id;
    }
    return id;
}

static HearthBodyId box(HearthVec3 p, float half) {
    HearthBodyId id = body(HEARTH_BODY_DYNAMIC, p);
    HearthShapeDef sd = hearth_shape_def_default();
    HearthBox b = {v3(0, 0, 0), {0, 0, 0, 1}, v3(half, half, half)};
    HearthShapeId s;
    CHECK(hearth_shape_create_box(g_world, id, &sd, &b, &s));
    return id;
}

static HearthBodyId sphere(HearthVec3 p, float r) {
    HearthBodyId id = body(HEARTH_BODY_DYNAMIC, p);
    HearthShapeDef sd = hearth_shape_def_default();
    sd.restitution = 0.3f;
    HearthSphere b = {v3(0, 0, 0), r};
    HearthShapeId s;
    CHECK(hearth_shape_create_sphere(g_world, id, &sd, &b, &s));
    return id;
}

static HearthBodyId capsule(HearthVec3 p, float half_length, float r) {
    HearthBodyId id = body(HEARTH_BODY_DYNAMIC, p);
    HearthShapeDef sd = hearth_shape_def_default();
    HearthCapsule c = {v3(-half_length, 0, 0), v3(half_length, 0, 0), r};
    HearthShapeId s;
    CHECK(hearth_shape_create_capsule(g_world, id, &sd, &c, &s));
    return id;
}

static uint64_t fnv1a(const void *data, size_t n, uint64_t h) {
    const unsigned char *p = (const unsigned char *)data;
    for (size_t i = 0; i < n; i++) {
        h ^= p[i];
        h *= 1099511628211ull;
    }
    return h;
}

int main(void) {
    HearthWorldDef wd = hearth_world_def_default();
    CHECK(hearth_world_create(&wd, &g_world));
    HearthBodyId ground = body(HEARTH_BODY_STATIC, v3(0, 0, 0));
    HearthShapeDef sd = hearth_shape_def_default();
    HearthPlane plane = {v3(0, 1, 0), 0.0f};
    HearthShapeId s;
    CHECK(hearth_shape_create_plane(g_world, ground, &sd, &plane, &s));

    for (int layer = 0; layer < 4; layer++) { /* 16 + 9 + 4 + 1 boxes */
        int n = 4 - layer;
        for (int i = 0; i < n; i++) {
            for (int k = 0; k < n; k++) {
                box(v3(-0.5f * (float)(n - 1) + (float)i, 0.5f + (float)layer, -0.5f * (float)(n - 1) + (float)k), 0.5f);
            }
        }
    }
    for (int j = 0; j < 12; j++) {
        HearthVec3 p = v3(-1.5f + 0.9f * (float)(j % 4), 6.0f + 1.2f * (float)(j / 4), -0.4f + 0.3f * (float)(j % 3));
        if (j % 3 == 0) {
            sphere(p, 0.35f);
        } else if (j % 3 == 1) {
            capsule(p, 0.3f, 0.2f);
        } else {
            box(p, 0.3f);
        }
    }
    /* A chain of 6 capsules on ball joints, hanging from a world anchor at (6, 8, 0). */
    HearthBodyId previous = {0, 0};
    for (int i = 0; i < 6; i++) {
        HearthBodyId link = capsule(v3(6.0f + 0.5f * (float)i + 0.25f, 8.0f, 0.0f), 0.2f, 0.08f);
        HearthBallJointDef jd = hearth_ball_joint_def_default();
        jd.base.body_a = link;
        jd.base.body_b = previous; /* the null id is the world */
        jd.base.frame_a.position = v3(-0.25f, 0, 0);
        jd.base.frame_b.position = i == 0 ? v3(6.0f, 8.0f, 0.0f) : v3(0.25f, 0, 0);
        HearthJointId joint;
        CHECK(hearth_joint_create_ball(g_world, &jd, &joint));
        previous = link;
    }
    /* A door on a motorised hinge. */
    HearthBodyId door = box(v3(-6.0f, 1.5f, 0.0f), 0.5f);
    HearthHingeJointDef hd = hearth_hinge_joint_def_default();
    hd.base.body_a = door;
    hd.base.frame_a.position = v3(0.0f, 0.0f, 0.0f);
    hd.base.frame_b.position = v3(-6.0f, 1.5f, 0.0f);
    hd.enable_motor = 1;
    hd.motor_speed = 1.5f;
    hd.max_motor_torque = 50.0f;
    HearthJointId hinge;
    CHECK(hearth_joint_create_hinge(g_world, &hd, &hinge));
    /* Air drag on the falling bodies. */
    HearthDragGeneratorDef dd = hearth_drag_generator_def_default();
    HearthGeneratorId drag;
    CHECK(hearth_generator_create_drag(g_world, &dd, &drag));
    for (size_t i = 30; i < g_count; i++) {
        CHECK(hearth_generator_attach_body(g_world, drag, g_bodies[i]));
    }

    static HearthTransform xf[MAX_BODIES];
    for (int step = 1; step <= 360; step++) {
        CHECK(hearth_world_step(g_world, 1.0f / 60.0f));
        if (step % 60 == 0) {
            CHECK(hearth_world_get_transforms(g_world, g_bodies, g_count, xf));
            uint64_t h = fnv1a(xf, g_count * sizeof xf[0], 1469598103934665603ull);
            printf("step %3d: %zu bodies, hash %016llx\n", step, g_count, (unsigned long long)h);
        }
    }
    for (size_t i = 0; i < 4; i++) {
        printf("body %zu: %a %a %a\n", i, (double)xf[i].position.x, (double)xf[i].position.y, (double)xf[i].position.z);
    }
    hearth_world_destroy(g_world);
    return 0;
}
