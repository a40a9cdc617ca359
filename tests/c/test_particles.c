/*
 * The particle world from C, using only include/hearth.h: every particle export and its
 * errors (NULL, garbage and zeroed defs, NaN, bad flags, stale and foreign ids), burst
 * emitters (exact counts, the cone, reproducible seeds, BUFFER_TOO_SMALL), bulk read-back,
 * the expired report, particles resting on the ground and hanging on rods. Compiled as C11
 * and C++17, shared and static, under valgrind.
 */
#include "hearth.h"
#include "ensure.h"

#include <stdlib.h>

static HearthWorld *make_world(void) {
    HearthWorldDef def = hearth_world_def_default();
    HearthWorld *w = NULL;
    ENSURE_OK(hearth_world_create(&def, &w));
    return w;
}

static HearthVec3 vec3(float x, float y, float z) {
    HearthVec3 v;
    v.x = x;
    v.y = y;
    v.z = z;
    return v;
}

static void add_ground(HearthWorld *w) {
    HearthBodyDef bd = hearth_body_def_default();
    HearthBodyId ground;
    ENSURE_OK(hearth_body_create(w, &bd, &ground));
    HearthShapeDef sd = hearth_shape_def_default();
    HearthPlane plane;
    plane.normal = vec3(0, 1, 0);
    plane.offset = 0.0f;
    HearthShapeId s;
    ENSURE_OK(hearth_shape_create_plane(w, ground, &sd, &plane, &s));
}

static void test_create_errors(void) {
    HearthWorld *w = make_world();
    HearthParticleDef def = hearth_particle_def_default();
    ENSURE(def.inverse_mass == 1.0f && def.radius > 0.0f && def.collide == 1 && def.allow_sleep == 1);
    ENSURE(isinf(def.lifetime));
    HearthParticleId p;
    memset(&p, 0, sizeof p);
    ENSURE_RESULT(hearth_particle_create(NULL, &def, &p), HEARTH_ERROR_NULL_POINTER);
    ENSURE_RESULT(hearth_particle_create(w, NULL, &p), HEARTH_ERROR_NULL_POINTER);
    ENSURE_RESULT(hearth_particle_create(w, &def, NULL), HEARTH_ERROR_NULL_POINTER);
    uint64_t garbage[16];
    memset(garbage, 0xAB, sizeof garbage);
    ENSURE_RESULT(hearth_particle_create(w, (const HearthParticleDef *)(const void *)garbage, &p),
                  HEARTH_ERROR_INVALID_ARGUMENT);
    memset(garbage, 0, sizeof garbage);
    ENSURE_RESULT(hearth_particle_create(w, (const HearthParticleDef *)(const void *)garbage, &p),
                  HEARTH_ERROR_INVALID_ARGUMENT);
    HearthParticleDef bad = def;
    bad.position.x = NAN;
    ENSURE_RESULT(hearth_particle_create(w, &bad, &p), HEARTH_ERROR_INVALID_ARGUMENT);
    bad = def;
    bad.velocity.z = INFINITY;
    ENSURE_RESULT(hearth_particle_create(w, &bad, &p), HEARTH_ERROR_INVALID_ARGUMENT);
    bad = def;
    bad.inverse_mass = -1.0f;
    ENSURE_RESULT(hearth_particle_create(w, &bad, &p), HEARTH_ERROR_INVALID_ARGUMENT);
    bad = def;
    bad.radius = -0.1f;
    ENSURE_RESULT(hearth_particle_create(w, &bad, &p), HEARTH_ERROR_INVALID_ARGUMENT);
    bad = def;
    bad.lifetime = 0.0f;
    ENSURE_RESULT(hearth_particle_create(w, &bad, &p), HEARTH_ERROR_INVALID_ARGUMENT);
    bad = def;
    bad.lifetime = NAN;
    ENSURE_RESULT(hearth_particle_create(w, &bad, &p), HEARTH_ERROR_INVALID_ARGUMENT);
    bad = def;
    bad.collide = 2;
    ENSURE_RESULT(hearth_particle_create(w, &bad, &p), HEARTH_ERROR_INVALID_ARGUMENT);
    bad = def;
    bad.allow_sleep = 255;
    ENSURE_RESULT(hearth_particle_create(w, &bad, &p), HEARTH_ERROR_INVALID_ARGUMENT);
    bad = def;
    bad.friction = -0.5f;
    ENSURE_RESULT(hearth_particle_create(w, &bad, &p), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE(p.index == 0 && p.generation == 0);
    size_t n = 99;
    ENSURE_OK(hearth_world_get_particle_count(w, &n));
    ENSURE(n == 0);
    ENSURE_RESULT(hearth_world_get_particle_count(w, NULL), HEARTH_ERROR_NULL_POINTER);
    ENSURE_RESULT(hearth_world_get_particle_count(NULL, &n), HEARTH_ERROR_NULL_POINTER);
    hearth_world_destroy(w);
}

static void test_state_and_ids(void) {
    HearthWorld *w = make_world();
    HearthWorld *other = make_world();
    HearthParticleDef def = hearth_particle_def_default();
    def.position = vec3(1, 2, 3);
    def.velocity = vec3(0, 1, 0);
    def.user_data = 0xBEEFu;
    HearthParticleId p;
    ENSURE_OK(hearth_particle_create(w, &def, &p));
    ENSURE(p.generation != 0);
    HearthVec3 v;
    ENSURE_OK(hearth_particle_get_position(w, p, &v));
    ENSURE(v.x == 1.0f && v.y == 2.0f && v.z == 3.0f);
    ENSURE_OK(hearth_particle_get_velocity(w, p, &v));
    ENSURE(v.y == 1.0f);
    uint64_t ud = 0;
    ENSURE_OK(hearth_particle_get_user_data(w, p, &ud));
    ENSURE(ud == 0xBEEFu);
    bool awake = false;
    ENSURE_OK(hearth_particle_is_awake(w, p, &awake));
    ENSURE(awake);
    ENSURE_RESULT(hearth_particle_get_position(w, p, NULL), HEARTH_ERROR_NULL_POINTER);
    ENSURE_RESULT(hearth_particle_get_position(NULL, p, &v), HEARTH_ERROR_NULL_POINTER);

    ENSURE_OK(hearth_particle_set_position(w, p, vec3(4, 5, 6)));
    ENSURE_OK(hearth_particle_set_velocity(w, p, vec3(1, 0, 0)));
    ENSURE_RESULT(hearth_particle_set_position(w, p, vec3(NAN, 0, 0)), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE_RESULT(hearth_particle_set_velocity(w, p, vec3(0, INFINITY, 0)), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE_OK(hearth_particle_get_position(w, p, &v));
    ENSURE(v.x == 4.0f && v.y == 5.0f && v.z == 6.0f);
    ENSURE_OK(hearth_particle_apply_impulse(w, p, vec3(0, 0, 2)));
    ENSURE_OK(hearth_particle_get_velocity(w, p, &v));
    ENSURE(v.x == 1.0f && v.z == 2.0f);
    ENSURE_RESULT(hearth_particle_apply_impulse(w, p, vec3(0, NAN, 0)), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE_RESULT(hearth_particle_apply_force(w, p, vec3(0, NAN, 0)), HEARTH_ERROR_INVALID_ARGUMENT);
    /* A force of m*g upward for one step cancels gravity: the velocity stays. */
    ENSURE_OK(hearth_particle_apply_force(w, p, vec3(0, 9.81f, 0)));
    ENSURE_OK(hearth_world_step(w, 1.0f / 60.0f));
    ENSURE_OK(hearth_particle_get_velocity(w, p, &v));
    ENSURE_NEAR(v.y, 0.0, 1e-5);
    ENSURE_OK(hearth_world_step(w, 1.0f / 60.0f));
    ENSURE_OK(hearth_particle_get_velocity(w, p, &v));
    ENSURE_NEAR(v.y, -9.81 / 60.0, 1e-4);

    ENSURE_OK(hearth_particle_set_awake(w, p, 0));
    ENSURE_OK(hearth_particle_is_awake(w, p, &awake));
    ENSURE(!awake);
    ENSURE_RESULT(hearth_particle_set_awake(w, p, 2), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE_OK(hearth_particle_set_awake(w, p, 1));
    ENSURE_OK(hearth_particle_is_awake(w, p, &awake));
    ENSURE(awake);

    /* Stale, null and foreign ids. */
    HearthParticleId null_id;
    memset(&null_id, 0, sizeof null_id);
    ENSURE_RESULT(hearth_particle_get_position(w, null_id, &v), HEARTH_ERROR_INVALID_ID);
    ENSURE_RESULT(hearth_particle_get_position(other, p, &v), HEARTH_ERROR_INVALID_ID);
    ENSURE_RESULT(hearth_particle_get_user_data(w, p, NULL), HEARTH_ERROR_NULL_POINTER);
    ENSURE_RESULT(hearth_particle_is_awake(w, p, NULL), HEARTH_ERROR_NULL_POINTER);
    ENSURE_RESULT(hearth_particle_get_velocity(NULL, p, &v), HEARTH_ERROR_NULL_POINTER);
    ENSURE_OK(hearth_particle_destroy(w, p));
    ENSURE_RESULT(hearth_particle_destroy(w, p), HEARTH_ERROR_INVALID_ID);
    ENSURE_RESULT(hearth_particle_get_user_data(w, p, &ud), HEARTH_ERROR_INVALID_ID);
    ENSURE_RESULT(hearth_particle_set_position(w, p, vec3(0, 0, 0)), HEARTH_ERROR_INVALID_ID);
    ENSURE_RESULT(hearth_particle_apply_impulse(w, p, vec3(0, 0, 0)), HEARTH_ERROR_INVALID_ID);
    ENSURE_RESULT(hearth_particle_set_awake(w, p, 1), HEARTH_ERROR_INVALID_ID);
    ENSURE_RESULT(hearth_particle_get_position(w, p, &v), HEARTH_ERROR_INVALID_ID);
    ENSURE_RESULT(hearth_particle_set_velocity(w, p, vec3(0, 0, 0)), HEARTH_ERROR_INVALID_ID);
    ENSURE_RESULT(hearth_particle_apply_force(w, p, vec3(0, 0, 0)), HEARTH_ERROR_INVALID_ID);
    ENSURE_RESULT(hearth_particle_is_awake(w, p, &awake), HEARTH_ERROR_INVALID_ID);
    HearthParticleId q;
    ENSURE_OK(hearth_particle_create(w, &def, &q));
    ENSURE(q.index == p.index && q.generation != p.generation);
    ENSURE_RESULT(hearth_particle_get_position(w, p, &v), HEARTH_ERROR_INVALID_ID);

    ENSURE_RESULT(hearth_world_set_particle_iterations(w, 0, 4), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE_RESULT(hearth_world_set_particle_iterations(w, 8, 65), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE_OK(hearth_world_set_particle_iterations(w, 12, 6));
    ENSURE_RESULT(hearth_world_set_particle_iterations(NULL, 12, 6), HEARTH_ERROR_NULL_POINTER);
    hearth_world_destroy(w);
    hearth_world_destroy(other);
}

static void test_bursts(void) {
    HearthWorld *w = make_world();
    HearthBurstDef def = hearth_burst_def_default();
    ENSURE(def.count > 0 && def.particle.internal_value != 0);
    def.position = vec3(0, 10, 0);
    def.direction = vec3(0, 0, 3); /* need not be unit length */
    def.cone_half_angle = 0.25f;
    def.count = 200;
    def.speed_min = 2.0f;
    def.speed_max = 4.0f;
    def.seed = 42;
    def.particle.gravity_scale = 0.0f;
    def.particle.collide = 0;
    HearthParticleId ids[256];
    size_t count = 0;
    /* Too small a buffer: nothing emitted. */
    ENSURE_RESULT(hearth_particle_emit_burst(w, &def, ids, 100, &count), HEARTH_ERROR_BUFFER_TOO_SMALL);
    size_t n = 1;
    ENSURE_OK(hearth_world_get_particle_count(w, &n));
    ENSURE(n == 0 && count == 0);
    ENSURE_OK(hearth_particle_emit_burst(w, &def, ids, 256, &count));
    ENSURE(count == 200);
    ENSURE_OK(hearth_world_get_particle_count(w, &n));
    ENSURE(n == 200);
    double worst = 0.0;
    for (size_t i = 0; i < count; i++) {
        HearthVec3 v;
        ENSURE_OK(hearth_particle_get_velocity(w, ids[i], &v));
        double s = sqrt((double)v.x * v.x + (double)v.y * v.y + (double)v.z * v.z);
        ENSURE(s >= 2.0 - 1e-5 && s <= 4.0 + 1e-5);
        double angle = acos(fmin(1.0, v.z / s));
        if (angle > worst) {
            worst = angle;
        }
    }
    ENSURE(worst <= 0.25 + 1e-4);
    ENSURE(worst > 0.2);
    /* Same seed, same burst; NULL outputs are fine. */
    HearthParticleId again[256];
    ENSURE_OK(hearth_particle_emit_burst(w, &def, again, 256, NULL));
    for (size_t i = 0; i < count; i++) {
        HearthVec3 a, b;
        ENSURE_OK(hearth_particle_get_velocity(w, ids[i], &a));
        ENSURE_OK(hearth_particle_get_velocity(w, again[i], &b));
        ENSURE(a.x == b.x && a.y == b.y && a.z == b.z);
    }
    ENSURE_OK(hearth_particle_emit_burst(w, &def, NULL, 0, &count));
    ENSURE(count == 200);
    ENSURE_OK(hearth_world_get_particle_count(w, &n));
    ENSURE(n == 600);
    /* Bad bursts. */
    ENSURE_RESULT(hearth_particle_emit_burst(NULL, &def, NULL, 0, NULL), HEARTH_ERROR_NULL_POINTER);
    ENSURE_RESULT(hearth_particle_emit_burst(w, NULL, NULL, 0, NULL), HEARTH_ERROR_NULL_POINTER);
    HearthBurstDef bad = def;
    bad.internal_value = 0;
    ENSURE_RESULT(hearth_particle_emit_burst(w, &bad, NULL, 0, NULL), HEARTH_ERROR_INVALID_ARGUMENT);
    bad = def;
    bad.particle.internal_value = 0;
    ENSURE_RESULT(hearth_particle_emit_burst(w, &bad, NULL, 0, NULL), HEARTH_ERROR_INVALID_ARGUMENT);
    bad = def;
    bad.direction = vec3(0, 0, 0);
    ENSURE_RESULT(hearth_particle_emit_burst(w, &bad, NULL, 0, NULL), HEARTH_ERROR_INVALID_ARGUMENT);
    bad = def;
    bad.cone_half_angle = 4.0f;
    ENSURE_RESULT(hearth_particle_emit_burst(w, &bad, NULL, 0, NULL), HEARTH_ERROR_INVALID_ARGUMENT);
    bad = def;
    bad.speed_min = 5.0f;
    ENSURE_RESULT(hearth_particle_emit_burst(w, &bad, NULL, 0, NULL), HEARTH_ERROR_INVALID_ARGUMENT);
    bad = def;
    bad.lifetime_min = -1.0f;
    ENSURE_RESULT(hearth_particle_emit_burst(w, &bad, NULL, 0, NULL), HEARTH_ERROR_INVALID_ARGUMENT);
    bad = def;
    bad.count = 2000000;
    ENSURE_RESULT(hearth_particle_emit_burst(w, &bad, NULL, 0, NULL), HEARTH_ERROR_INVALID_ARGUMENT);
    uint64_t garbage[32];
    memset(garbage, 0x5A, sizeof garbage);
    ENSURE_RESULT(hearth_particle_emit_burst(w, (const HearthBurstDef *)(const void *)garbage, NULL, 0, NULL),
                  HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE_OK(hearth_world_get_particle_count(w, &n));
    ENSURE(n == 600);
    hearth_world_destroy(w);
}

static void test_bulk_read_and_expiry(void) {
    HearthWorld *w = make_world();
    HearthBurstDef def = hearth_burst_def_default();
    def.count = 50;
    def.lifetime_min = 0.5f;
    def.lifetime_max = 1.0f;
    def.particle.user_data = 7;
    HearthParticleId ids[50];
    ENSURE_OK(hearth_particle_emit_burst(w, &def, ids, 50, NULL));
    HearthParticleDef pd = hearth_particle_def_default();
    pd.user_data = 8;
    HearthParticleId forever;
    ENSURE_OK(hearth_particle_create(w, &pd, &forever));
    ENSURE_OK(hearth_world_step(w, 1.0f / 60.0f));

    /* Everything at once. */
    HearthParticleId all_ids[64];
    HearthVec3 pos[64], vel[64];
    size_t n = 0;
    ENSURE_RESULT(hearth_world_get_particles(w, all_ids, pos, vel, 50, &n), HEARTH_ERROR_BUFFER_TOO_SMALL);
    ENSURE(n == 0);
    /* capacity 0: count only, like every bulk read */
    ENSURE_OK(hearth_world_get_particles(w, NULL, NULL, NULL, 0, &n));
    ENSURE(n == 51);
    ENSURE_RESULT(hearth_world_get_particles(w, all_ids, pos, vel, 64, NULL), HEARTH_ERROR_NULL_POINTER);
    ENSURE_RESULT(hearth_world_get_particles(NULL, all_ids, pos, vel, 64, &n), HEARTH_ERROR_NULL_POINTER);
    ENSURE_OK(hearth_world_get_particles(w, all_ids, pos, vel, 64, &n));
    ENSURE(n == 51);
    for (size_t i = 0; i < n; i++) {
        HearthVec3 p, v;
        ENSURE_OK(hearth_particle_get_position(w, all_ids[i], &p));
        ENSURE_OK(hearth_particle_get_velocity(w, all_ids[i], &v));
        ENSURE(p.x == pos[i].x && p.y == pos[i].y && p.z == pos[i].z);
        ENSURE(v.x == vel[i].x && v.y == vel[i].y && v.z == vel[i].z);
    }
    ENSURE_OK(hearth_world_get_particles(w, NULL, pos, NULL, 64, &n));
    ENSURE(n == 51);
    /* By id. */
    HearthVec3 some[3];
    HearthParticleId three[3] = {ids[0], forever, ids[49]};
    ENSURE_OK(hearth_world_get_particle_positions(w, three, 3, some));
    HearthVec3 check;
    ENSURE_OK(hearth_particle_get_position(w, forever, &check));
    ENSURE(some[1].x == check.x && some[1].y == check.y && some[1].z == check.z);
    ENSURE_OK(hearth_world_get_particle_positions(w, NULL, 0, NULL));
    ENSURE_RESULT(hearth_world_get_particle_positions(w, NULL, 3, some), HEARTH_ERROR_NULL_POINTER);
    ENSURE_RESULT(hearth_world_get_particle_positions(w, three, 3, NULL), HEARTH_ERROR_NULL_POINTER);

    /* Expiry: every burst particle expires once within 0.5..1 s, reported with its data. */
    const HearthExpiredParticle *expired = NULL;
    size_t expired_count = 99;
    ENSURE_OK(hearth_world_get_expired_particles(w, &expired, &expired_count));
    ENSURE(expired_count == 0);
    ENSURE_RESULT(hearth_world_get_expired_particles(w, NULL, &expired_count), HEARTH_ERROR_NULL_POINTER);
    ENSURE_RESULT(hearth_world_get_expired_particles(w, &expired, NULL), HEARTH_ERROR_NULL_POINTER);
    ENSURE_RESULT(hearth_world_get_expired_particles(NULL, &expired, &expired_count),
                  HEARTH_ERROR_NULL_POINTER);
    size_t total = 0;
    int step = 1;
    for (; step < 120; step++) {
        ENSURE_OK(hearth_world_step(w, 1.0f / 60.0f));
        ENSURE_OK(hearth_world_get_expired_particles(w, &expired, &expired_count));
        for (size_t i = 0; i < expired_count; i++) {
            ENSURE(expired[i].user_data == 7);
            HearthVec3 p;
            ENSURE_RESULT(hearth_particle_get_position(w, expired[i].id, &p), HEARTH_ERROR_INVALID_ID);
            double t = (step + 1) / 60.0;
            ENSURE(t >= 0.5 - 1e-6 && t <= 1.0 + 1.0 / 60.0);
        }
        total += expired_count;
    }
    ENSURE(total == 50);
    size_t n_left = 0;
    ENSURE_OK(hearth_world_get_particle_count(w, &n_left));
    ENSURE(n_left == 1);
    /* Positions by id refuse a stale id and write nothing. */
    some[0] = vec3(-1, -1, -1);
    ENSURE_RESULT(hearth_world_get_particle_positions(w, three, 3, some), HEARTH_ERROR_INVALID_ID);
    ENSURE(some[0].x == -1.0f);
    hearth_world_destroy(w);
}

static void test_particles_rest_and_hang(void) {
    HearthWorld *w = make_world();
    add_ground(w);
    HearthParticleDef pd = hearth_particle_def_default();
    pd.position = vec3(0, 2, 0);
    pd.radius = 0.1f;
    HearthParticleId resting;
    ENSURE_OK(hearth_particle_create(w, &pd, &resting));
    /* A particle on a rod from an anchor, and one more on a rod below it. */
    pd.position = vec3(1, 4, 0);
    pd.collide = 0;
    HearthParticleId a, b;
    ENSURE_OK(hearth_particle_create(w, &pd, &a));
    pd.position = vec3(1, 3, 0);
    pd.inverse_mass = 0.2f;
    ENSURE_OK(hearth_particle_create(w, &pd, &b));
    HearthRodGeneratorDef rd = hearth_rod_generator_def_default();
    rd.a.point = vec3(0, 5, 0);
    rd.b.particle = a;
    rd.length = sqrtf(2.0f);
    HearthGeneratorId r1, r2;
    ENSURE_OK(hearth_generator_create_rod(w, &rd, &r1));
    rd.a.particle = a;
    rd.a.point = vec3(0, 0, 0);
    rd.b.particle = b;
    rd.length = 1.0f;
    ENSURE_OK(hearth_generator_create_rod(w, &rd, &r2));
    double worst = 0.0;
    for (int i = 0; i < 240; i++) {
        ENSURE_OK(hearth_world_step(w, 1.0f / 60.0f));
        HearthVec3 pa, pb;
        ENSURE_OK(hearth_particle_get_position(w, a, &pa));
        ENSURE_OK(hearth_particle_get_position(w, b, &pb));
        double d1 = sqrt((double)pa.x * pa.x + (pa.y - 5.0) * (pa.y - 5.0) + (double)pa.z * pa.z);
        double dx = pb.x - pa.x, dy = pb.y - pa.y, dz = pb.z - pa.z;
        double d2 = sqrt(dx * dx + dy * dy + dz * dz);
        worst = fmax(worst, fmax(fabs(d1 - sqrt(2.0)), fabs(d2 - 1.0)));
    }
    ENSURE(worst < 1e-3);
    HearthVec3 p;
    ENSURE_OK(hearth_particle_get_position(w, resting, &p));
    ENSURE_NEAR(p.y, 0.1, 2e-3);
    /* Destroying a rod's particle: both rods stop and the other particle flies free
     * (v changes by g t exactly). */
    ENSURE_OK(hearth_particle_destroy(w, a));
    HearthVec3 before;
    ENSURE_OK(hearth_particle_get_velocity(w, b, &before));
    for (int i = 0; i < 30; i++) {
        ENSURE_OK(hearth_world_step(w, 1.0f / 60.0f));
    }
    HearthVec3 after;
    ENSURE_OK(hearth_particle_get_velocity(w, b, &after));
    ENSURE_NEAR(after.x, before.x, 1e-4);
    ENSURE_NEAR(after.y - before.y, -9.81 * 0.5, 1e-3);
    hearth_world_destroy(w);
}

int main(void) {
    test_create_errors();
    test_state_and_ids();
    test_bursts();
    test_bulk_read_and_expiry();
    test_particles_rest_and_hang();
    return ensure_report("test_particles");
}
