/*
 * fireworks.c - chained particle bursts in plain C, written only against include/hearth.h.
 *
 * Rockets are one-particle bursts fired up a narrow cone. When a rocket's lifetime runs out
 * the world reports it (hearth_world_get_expired_particles) and this program bursts it into
 * sparks where it died; some sparks crackle into a last small burst of their own. Sparks
 * feel drag (a built-in force generator) and a gusting wind written in C (a user force
 * generator: a callback with user_data); they bounce on the ground until they burn out.
 * Every burst has its own seed, so the show is the same on every run.
 *
 * Every second it prints the number of live particles, bursts so far and the height of the
 * highest spark. It checks that every launched rocket burst, and that the show ends with no
 * particles left; on any failure it exits with status 1.
 *
 * Build and run from the repository root, after `cargo build --release`:
 *   cc -std=c11 -Wall -Wextra -O2 -Iinclude examples/c/fireworks.c -Ltarget/release -lhearth \
 *      -Wl,-rpath,$PWD/target/release -lm -o fireworks && ./fireworks
 */
#include "hearth.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

enum { ROCKET = 1, SPARK = 2, CRACKLE = 3 };

#define ROCKETS 6
#define SPARKS 80       /* per rocket */
#define CRACKLES 6      /* per crackling spark */
#define MAX_BURST 128

static const float DT = 1.0f / 60.0f;
static const int STEPS = 480; /* 8 s */

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

/* The wind: a user force generator. user_data points at this; the callback pushes every
 * attached particle with a gust that varies in time. */
typedef struct Wind {
    float time;
    float strength; /* N per particle at the peak of a gust */
    int calls;
} Wind;

static void wind_callback(void *user_data, HearthWorld *world, const HearthGeneratorContext *ctx) {
    Wind *wind = (Wind *)user_data;
    wind->calls++;
    wind->time += ctx->dt;
    float gust = wind->strength * (0.5f + 0.5f * sinf(1.3f * wind->time));
    for (size_t i = 0; i < ctx->particle_count; i++) {
        /* Applying forces is what a force generator may do during the step. */
        CHECK(hearth_particle_apply_force(world, ctx->particles[i], vec3(gust, 0.0f, 0.3f * gust)));
    }
}

static HearthGeneratorId g_drag;
static HearthGeneratorId g_wind;
static int g_bursts = 0;
static uint64_t g_seed = 1000;

/* A burst of `count` particles of kind `kind` at `p`, all feeling drag and wind. */
static void burst(HearthVec3 p, HearthVec3 direction, float cone, uint32_t count, float speed_min,
                  float speed_max, float life_min, float life_max, uint64_t kind) {
    HearthBurstDef def = hearth_burst_def_default(); /* always start from the defaults */
    def.position = p;
    def.direction = direction;
    def.cone_half_angle = cone;
    def.count = count;
    def.speed_min = speed_min;
    def.speed_max = speed_max;
    def.lifetime_min = life_min;
    def.lifetime_max = life_max;
    def.seed = g_seed++;
    def.particle.radius = 0.03f;
    def.particle.restitution = 0.4f;
    def.particle.user_data = kind;
    if (kind == ROCKET) {
        def.particle.collide = 0; /* rockets fly through whatever they meet */
    }
    HearthParticleId ids[MAX_BURST];
    size_t emitted = 0;
    CHECK(hearth_particle_emit_burst(g_world, &def, ids, MAX_BURST, &emitted));
    if (emitted != count) {
        fprintf(stderr, "error: a burst of %u emitted %zu particles\n", count, emitted);
        hearth_world_destroy(g_world);
        exit(1);
    }
    if (kind != ROCKET) {
        CHECK(hearth_generator_attach_particles(g_world, g_drag, ids, emitted));
        CHECK(hearth_generator_attach_particles(g_world, g_wind, ids, emitted));
    }
    g_bursts++;
}

int main(int argc, char **argv) {
    HearthWorldDef wd = hearth_world_def_default();
    CHECK(hearth_world_create(&wd, &g_world));

    /* The ground. */
    HearthBodyDef bd = hearth_body_def_default();
    HearthBodyId ground;
    CHECK(hearth_body_create(g_world, &bd, &ground));
    HearthShapeDef sd = hearth_shape_def_default();
    HearthPlane plane = {{0.0f, 1.0f, 0.0f}, 0.0f};
    HearthShapeId ground_shape;
    CHECK(hearth_shape_create_plane(g_world, ground, &sd, &plane, &ground_shape));

    /* Drag on sparks (a built-in) and a gusting wind (written here, in C). */
    HearthDragGeneratorDef drag = hearth_drag_generator_def_default();
    drag.k1 = 0.02f;
    drag.k2 = 0.05f;
    CHECK(hearth_generator_create_drag(g_world, &drag, &g_drag));
    Wind wind = {0.0f, 0.8f, 0};
    HearthUserForceGeneratorDef wdef = hearth_user_force_generator_def_default();
    wdef.callback = wind_callback;
    wdef.user_data = &wind;
    CHECK(hearth_generator_create_user_force(g_world, &wdef, &g_wind));

    int launched = 0, rockets_burst = 0;
    /* With a path argument, record the run for the browser viewer (viewer/index.html). */
    if (argc > 1) {
        HearthRecordDef record = hearth_record_def_default();
        record.record_contacts = 1;
        CHECK(hearth_world_record_start_file(g_world, argv[1], &record));
    }
    for (int step = 0; step < STEPS; step++) {
        /* A rocket every half second for the first three seconds, with a tiny mass so drag
         * does not matter for it. */
        if (step % 30 == 0 && launched < ROCKETS) {
            float x = -5.0f + 2.0f * (float)launched;
            burst(vec3(x, 0.1f, 0.0f), vec3(0.1f * (float)(launched % 3 - 1), 1.0f, 0.0f), 0.05f, 1, 16.0f,
                  18.0f, 1.2f, 1.5f, ROCKET);
            launched++;
        }
        CHECK(hearth_world_step(g_world, DT));

        /* Chain reactions: whatever expired in this step may burst. The array belongs to the
         * world and stays valid until the next step, so copy what we need first: bursting
         * does not change it, but it is good practice. */
        const HearthExpiredParticle *expired = NULL;
        size_t n = 0;
        CHECK(hearth_world_get_expired_particles(g_world, &expired, &n));
        for (size_t i = 0; i < n; i++) {
            HearthExpiredParticle e = expired[i];
            if (e.user_data == ROCKET) {
                rockets_burst++;
                burst(e.position, vec3(0, 1, 0), 3.14159265f, SPARKS, 4.0f, 7.0f, 1.0f, 2.0f, SPARK);
            } else if (e.user_data == SPARK && e.position.y > 4.0f && (g_seed % 5) == 0) {
                burst(e.position, e.velocity, 1.2f, CRACKLES, 1.0f, 2.5f, 0.3f, 0.6f, CRACKLE);
            } else if (e.user_data == SPARK) {
                g_seed++; /* keeps the crackle choice varied, and reproducible */
            }
        }

        if ((step + 1) % 60 == 0) {
            static HearthVec3 positions[8192];
            size_t live = 0;
            CHECK(hearth_world_get_particles(g_world, NULL, positions, NULL, 8192, &live));
            float top = 0.0f;
            for (size_t i = 0; i < live; i++) {
                top = positions[i].y > top ? positions[i].y : top;
            }
            printf("t = %4.1f s  live particles %4zu  bursts %3d  highest %5.2f m\n", (double)(step + 1) * DT,
                   live, g_bursts, (double)top);
        }
    }

    size_t left = 0;
    CHECK(hearth_world_get_particle_count(g_world, &left));
    int ok = launched == ROCKETS && rockets_burst == ROCKETS && left == 0 && wind.calls == STEPS;
    printf("%d rockets, %d bursts in all, %zu particles left, wind called %d times: %s\n", rockets_burst, g_bursts,
           left, wind.calls, ok ? "ok" : "FAILED");
    if (argc > 1) {
        CHECK(hearth_world_record_stop(g_world));
        fprintf(stderr, "recorded %s: open it with viewer/index.html\n", argv[1]);
    }
    hearth_world_destroy(g_world);
    return ok ? 0 : 1;
}
