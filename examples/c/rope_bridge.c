/*
 * rope_bridge.c - a rope bridge of particles and rods carrying a rigid box, in plain C,
 * written only against include/hearth.h.
 *
 * Two static posts stand 6 m apart. Between their tops hangs a 7 m rope of 28 particles
 * (0.5 kg each) joined by rods; its end rods are fixed to the posts at body-frame points.
 * A 40 kg box is dropped onto the middle. Particles and the box interact both ways: the
 * box presses the rope down, the rope holds the box up. After 6 s of settling, the program
 * watches the box for 6 s more and prints its height every second with the worst rod
 * error. It exits with status 1 unless the box rests on the bridge (height steady within
 * 5 mm) and every rod keeps its length within 1 mm.
 *
 * Build and run from the repository root, after `cargo build --release`:
 *   cc -std=c11 -Wall -Wextra -O2 -Iinclude examples/c/rope_bridge.c -Ltarget/release -lhearth \
 *      -Wl,-rpath,$PWD/target/release -lm -o rope_bridge && ./rope_bridge
 */
#include "hearth.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#define N 28 /* particles in the rope */

static const float DT = 1.0f / 60.0f;
static const float SPAN = 6.0f;  /* between the posts' tops (m) */
static const float ROPE = 7.0f;  /* length of the rope (m) */
static const float TOP = 5.0f;   /* height of the posts' tops (m) */

static HearthWorld *g_world = NULL;

static void check(HearthResult result, const char *what) {
    if (result == HEARTH_OK) {
        return;
    }
    char message[256];
    hearth_last_error_message(message, sizeof message);
    fprintf(stderr, "error: %s failed: %s (%s)\n", what, hearth_result_name(result), message);
    hearth_world_destroy(g_world);
    exit(1);
}
#define CHECK(call) check((call), #call)

static HearthVec3 vec3(float x, float y, float z) {
    HearthVec3 v = {x, y, z};
    return v;
}

static float distance(HearthVec3 a, HearthVec3 b) {
    float dx = a.x - b.x, dy = a.y - b.y, dz = a.z - b.z;
    return sqrtf(dx * dx + dy * dy + dz * dz);
}

/* A static post: a box from the ground to y = TOP, centred at x. */
static HearthBodyId post(float x) {
    HearthBodyDef bd = hearth_body_def_default(); /* static */
    bd.transform.position = vec3(x, 0.5f * TOP, 0.0f);
    HearthBodyId b;
    CHECK(hearth_body_create(g_world, &bd, &b));
    HearthShapeDef sd = hearth_shape_def_default();
    HearthBox box = {{0, 0, 0}, {0, 0, 0, 1}, {0.2f, 0.5f * TOP, 0.2f}};
    HearthShapeId s;
    CHECK(hearth_shape_create_box(g_world, b, &sd, &box, &s));
    return b;
}

int main(int argc, char **argv) {
    HearthWorldDef wd = hearth_world_def_default();
    CHECK(hearth_world_create(&wd, &g_world));

    /* Ground and posts. */
    HearthBodyDef gd = hearth_body_def_default();
    HearthBodyId ground;
    CHECK(hearth_body_create(g_world, &gd, &ground));
    HearthShapeDef sd = hearth_shape_def_default();
    HearthPlane plane = {{0.0f, 1.0f, 0.0f}, 0.0f};
    HearthShapeId ground_shape;
    CHECK(hearth_shape_create_plane(g_world, ground, &sd, &plane, &ground_shape));
    /* The rope hangs from points just inside the posts' tops, in each post's body frame. */
    float half = 0.5f * SPAN;
    HearthBodyId left = post(-half - 0.2f), right = post(half + 0.2f);
    HearthVec3 left_top = vec3(0.2f, 0.5f * TOP, 0.0f), right_top = vec3(-0.2f, 0.5f * TOP, 0.0f);

    /* The rope: particles on a parabola sagging 1.2 m, rods at the spacing they start at
     * (never shorter than the rope's even spacing). */
    HearthParticleId rope[N];
    HearthVec3 start[N + 2];
    float lengths[N + 1];
    start[0] = vec3(-half, TOP, 0.0f);
    start[N + 1] = vec3(half, TOP, 0.0f);
    for (int k = 1; k <= N; k++) {
        float t = (float)k / (float)(N + 1);
        float s = 2.0f * t - 1.0f;
        start[k] = vec3(-half + SPAN * t, TOP - 1.2f * (1.0f - s * s), 0.0f);
        HearthParticleDef pd = hearth_particle_def_default(); /* always start from the defaults */
        pd.position = start[k];
        pd.inverse_mass = 2.0f; /* 0.5 kg */
        pd.radius = 0.08f;
        pd.damping = 1.0f;      /* a rope loses energy as it sways */
        CHECK(hearth_particle_create(g_world, &pd, &rope[k - 1]));
    }
    for (int k = 0; k <= N; k++) {
        float spacing = ROPE / (float)(N + 1);
        float d = distance(start[k], start[k + 1]);
        lengths[k] = d > spacing ? d : spacing;
        HearthRodGeneratorDef rd = hearth_rod_generator_def_default();
        if (k == 0) {
            rd.a.body = left;
            rd.a.point = left_top;
        } else {
            rd.a.particle = rope[k - 1];
        }
        if (k == N) {
            rd.b.body = right;
            rd.b.point = right_top;
        } else {
            rd.b.particle = rope[k];
        }
        rd.length = lengths[k];
        HearthGeneratorId rod;
        CHECK(hearth_generator_create_rod(g_world, &rd, &rod));
    }

    /* The load: a 40 kg box dropped onto the middle. */
    HearthBodyDef bd = hearth_body_def_default();
    bd.type = HEARTH_BODY_DYNAMIC;
    bd.transform.position = vec3(0.0f, 4.5f, 0.0f);
    HearthBodyId crate;
    CHECK(hearth_body_create(g_world, &bd, &crate));
    HearthShapeDef cd = hearth_shape_def_default();
    cd.density = 40.0f / (0.8f * 0.4f * 0.6f);
    HearthBox box = {{0, 0, 0}, {0, 0, 0, 1}, {0.4f, 0.2f, 0.3f}};
    HearthShapeId crate_shape;
    CHECK(hearth_shape_create_box(g_world, crate, &cd, &box, &crate_shape));

    float low = 1e9f, high = -1e9f, worst = 0.0f;
    HearthVec3 positions[N];
    /* With a path argument, record the run for the browser viewer (viewer/index.html). */
    if (argc > 1) {
        HearthRecordDef record = hearth_record_def_default();
        record.record_contacts = 1;
        CHECK(hearth_world_record_start_file(g_world, argv[1], &record));
    }
    for (int step = 1; step <= 720; step++) {
        CHECK(hearth_world_step(g_world, DT));
        HearthTransform t;
        CHECK(hearth_body_get_transform(g_world, crate, &t));
        /* Bulk read-back of the rope, one call per frame. */
        CHECK(hearth_world_get_particle_positions(g_world, rope, N, positions));
        float err = 0.0f;
        for (int k = 0; k <= N; k++) {
            HearthVec3 a = k == 0 ? start[0] : positions[k - 1];
            HearthVec3 b = k == N ? start[N + 1] : positions[k];
            float e = fabsf(distance(a, b) - lengths[k]);
            err = e > err ? e : err;
        }
        worst = err > worst ? err : worst;
        if (step > 360) {
            low = t.position.y < low ? t.position.y : low;
            high = t.position.y > high ? t.position.y : high;
        }
        if (step % 60 == 0) {
            bool awake = false;
            CHECK(hearth_body_is_awake(g_world, crate, &awake));
            printf("t = %4.1f s  box at (%6.3f, %6.4f)  rope sag %6.3f m  worst rod error %.1e m  box %s\n",
                   (double)step * DT, (double)t.position.x, (double)t.position.y,
                   (double)(TOP - positions[N / 2].y), (double)err, awake ? "awake" : "asleep");
        }
    }
    int ok = high - low < 0.005f && low > 2.5f && worst < 1e-3f;
    printf("box rests between %.4f and %.4f m over the last 6 s (%.2f mm); worst rod error %.1e m: %s\n",
           (double)low, (double)high, 1000.0 * (double)(high - low), (double)worst, ok ? "ok" : "FAILED");
    if (argc > 1) {
        CHECK(hearth_world_record_stop(g_world));
        fprintf(stderr, "recorded %s: open it with viewer/index.html\n", argv[1]);
    }
    hearth_world_destroy(g_world);
    return ok ? 0 : 1;
}
