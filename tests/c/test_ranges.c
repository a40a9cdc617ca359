/*
 * Issue 12 from C: ids never cross worlds however many worlds come and go, the 4,096th live
 * world is refused, and the supported ranges (README "Supported ranges"): time steps at
 * both ends in every subsystem, the accepted extremes leave the world finite, the values
 * outside are refused with HEARTH_ERROR_INVALID_ARGUMENT, a message naming the parameter,
 * and no change. Compiled as C11 and C++17, shared and static, and under valgrind in CI.
 */
#include "hearth.h"
#include "ensure.h"

#include <float.h>
#include <stdlib.h>

/* The documented limits (tests/ranges.rs checks them against the library). */
#define MIN_TIME_STEP 1e-3f
#define MAX_TIME_STEP 0.1f
#define MIN_LENGTH 1e-3f
#define MAX_LENGTH 1e4f
#define MAX_ACCELERATION 1e4f
#define MAX_FORCE 1e12f
#define MAX_IMPULSE 1e10f

static HearthVec3 vec(float x, float y, float z) {
    HearthVec3 v;
    v.x = x;
    v.y = y;
    v.z = z;
    return v;
}

static HearthWorld *make_world(void) {
    HearthWorldDef def = hearth_world_def_default();
    HearthWorld *w = NULL;
    ENSURE_OK(hearth_world_create(&def, &w));
    return w;
}

static HearthBodyId make_body(HearthWorld *w, uint32_t type, HearthVec3 p) {
    HearthBodyDef def = hearth_body_def_default();
    def.type = type;
    def.transform.position = p;
    HearthBodyId id;
    memset(&id, 0, sizeof id);
    ENSURE_OK(hearth_body_create(w, &def, &id));
    return id;
}

static void add_sphere(HearthWorld *w, HearthBodyId b, float radius, float density) {
    HearthShapeDef sd = hearth_shape_def_default();
    sd.density = density;
    HearthSphere s;
    s.center = vec(0, 0, 0);
    s.radius = radius;
    HearthShapeId id;
    ENSURE_OK(hearth_shape_create_sphere(w, b, &sd, &s, &id));
}

static void add_ground(HearthWorld *w) {
    HearthBodyId g = make_body(w, HEARTH_BODY_STATIC, vec(0, 0, 0));
    HearthShapeDef sd = hearth_shape_def_default();
    HearthPlane p;
    p.normal = vec(0, 1, 0);
    p.offset = 0;
    HearthShapeId id;
    ENSURE_OK(hearth_shape_create_plane(w, g, &sd, &p, &id));
}

static uint32_t body_count(const HearthWorld *w) {
    HearthWorldCounters c;
    ENSURE_OK(hearth_world_get_counters(w, &c));
    return c.body_count;
}

static int finite3(HearthVec3 v) { return isfinite(v.x) && isfinite(v.y) && isfinite(v.z); }

/* Every body, particle and soft-body vertex finite. */
static int world_is_finite(const HearthWorld *w, const HearthBodyId *bodies, size_t nb) {
    for (size_t i = 0; i < nb; i++) {
        HearthTransform t;
        HearthVec3 v, a;
        if (hearth_body_get_transform(w, bodies[i], &t) != HEARTH_OK || !finite3(t.position)) return 0;
        if (hearth_body_get_linear_velocity(w, bodies[i], &v) != HEARTH_OK || !finite3(v)) return 0;
        if (hearth_body_get_angular_velocity(w, bodies[i], &a) != HEARTH_OK || !finite3(a)) return 0;
        if (!isfinite(t.rotation.x + t.rotation.y + t.rotation.z + t.rotation.w)) return 0;
    }
    static HearthVec3 pos[1024];
    size_t n = 0;
    if (hearth_world_get_particles(w, NULL, pos, NULL, 1024, &n) != HEARTH_OK) return 0;
    for (size_t i = 0; i < n; i++)
        if (!finite3(pos[i])) return 0;
    return 1;
}

/* Expects INVALID_ARGUMENT with `name` in the message. */
#define ENSURE_REFUSED(call, name)                                                          \
    do {                                                                                    \
        ENSURE_RESULT(call, HEARTH_ERROR_INVALID_ARGUMENT);                                 \
        char m_[256];                                                                       \
        hearth_last_error_message(m_, sizeof m_);                                           \
        if (!strstr(m_, name)) {                                                            \
            g_failed++;                                                                     \
            fprintf(stderr, "%s:%d: the message \"%s\" does not name %s\n", __FILE__,      \
                    __LINE__, m_, name);                                                    \
        }                                                                                   \
    } while (0)

/* ------------------------------------------------------------------------------- ids */

/* 4,200 worlds (more than the 4,095 tags) come and go while one lives: none of their ids
 * is ever accepted by the live world, nor the live world's by them. */
static void test_ids_never_cross_worlds_over_many_world_generations(void) {
    HearthWorld *keeper = make_world();
    HearthBodyId mine = make_body(keeper, HEARTH_BODY_DYNAMIC, vec(0, 1, 0));
    int crossed = 0;
    for (int round = 0; round < 4200; round++) {
        HearthWorld *other = make_world();
        HearthBodyId theirs = make_body(other, HEARTH_BODY_DYNAMIC, vec(0, 2, 0));
        /* Same slot index in both worlds: only the tag tells them apart. */
        if (theirs.index != mine.index) crossed++;
        HearthTransform t;
        if (hearth_body_destroy(keeper, theirs) != HEARTH_ERROR_INVALID_ID) crossed++;
        if (hearth_body_get_transform(other, mine, &t) != HEARTH_ERROR_INVALID_ID) crossed++;
        if (hearth_body_destroy(other, mine) != HEARTH_ERROR_INVALID_ID) crossed++;
        hearth_world_destroy(other);
    }
    ENSURE(crossed == 0);
    ENSURE(body_count(keeper) == 1);
    HearthTransform t;
    ENSURE_OK(hearth_body_get_transform(keeper, mine, &t));
    ENSURE_NEAR(t.position.y, 1.0, 0.0);
    hearth_world_destroy(keeper);
}

/* A particle destroyed while attached to a generator: detaching its stale id is refused
 * (it used to be accepted until the next step pruned the list). */
static void test_a_destroyed_particle_cannot_be_detached(void) {
    HearthWorld *w = make_world();
    HearthParticleDef pd = hearth_particle_def_default();
    HearthParticleId p;
    ENSURE_OK(hearth_particle_create(w, &pd, &p));
    HearthGravityGeneratorDef gd = hearth_gravity_generator_def_default();
    HearthGeneratorId g;
    ENSURE_OK(hearth_generator_create_gravity(w, &gd, &g));
    ENSURE_OK(hearth_generator_attach_particle(w, g, p));
    ENSURE_OK(hearth_particle_destroy(w, p));
    ENSURE_RESULT(hearth_generator_detach_particle(w, g, p), HEARTH_ERROR_INVALID_ID);
    uint32_t nb = 9, np = 9;
    ENSURE_OK(hearth_generator_get_attachment_count(w, g, &nb, &np));
    ENSURE(nb == 0 && np == 0);
    hearth_world_destroy(w);
}

/* 4,095 worlds may be alive at once; the next is refused with HEARTH_ERROR_LIMIT_REACHED
 * (nothing written), and destroying one makes room again. */
static void test_the_4096th_live_world_is_refused(void) {
    enum { MAX_LIVE = 4095 };
    HearthWorld **worlds = (HearthWorld **)calloc(MAX_LIVE, sizeof *worlds);
    HearthWorldDef def = hearth_world_def_default();
    int made = 0;
    while (made < MAX_LIVE && hearth_world_create(&def, &worlds[made]) == HEARTH_OK) made++;
    ENSURE(made == MAX_LIVE);
    HearthWorld *extra = (HearthWorld *)&def; /* a sentinel: must stay unwritten */
    ENSURE_RESULT(hearth_world_create(&def, &extra), HEARTH_ERROR_LIMIT_REACHED);
    ENSURE(extra == (HearthWorld *)&def);
    char msg[256];
    hearth_last_error_message(msg, sizeof msg);
    ENSURE(strstr(msg, "4095 worlds") != NULL);
    ENSURE(strcmp(hearth_result_name(HEARTH_ERROR_LIMIT_REACHED), "HEARTH_ERROR_LIMIT_REACHED") == 0);
    hearth_world_destroy(worlds[made / 2]);
    ENSURE_OK(hearth_world_create(&def, &worlds[made / 2]));
    for (int i = 0; i < made; i++) hearth_world_destroy(worlds[i]);
    free(worlds);
}

/* ----------------------------------------------------------------------- time steps */

/* One world with every subsystem: a box on the ground, a hinge pendulum, particles on a rod
 * and a burst, a soft ball. */
typedef struct {
    HearthWorld *w;
    HearthBodyId bodies[4];
    HearthSoftBodyId ball;
} Scene;

static Scene make_scene(void) {
    Scene s;
    s.w = make_world();
    add_ground(s.w);
    s.bodies[0] = make_body(s.w, HEARTH_BODY_DYNAMIC, vec(0, 0.5f, 0));
    add_sphere(s.w, s.bodies[0], 0.5f, 1000);
    s.bodies[1] = make_body(s.w, HEARTH_BODY_DYNAMIC, vec(3, 3, 0));
    add_sphere(s.w, s.bodies[1], 0.2f, 1000);
    HearthHingeJointDef hd = hearth_hinge_joint_def_default();
    hd.base.body_a = s.bodies[1];
    hd.base.frame_a.position = vec(-1, 0, 0);
    hd.base.frame_b.position = vec(2, 3, 0);
    HearthJointId j;
    ENSURE_OK(hearth_joint_create_hinge(s.w, &hd, &j));
    s.bodies[2] = make_body(s.w, HEARTH_BODY_DYNAMIC, vec(-3, 2, 0));
    add_sphere(s.w, s.bodies[2], 0.1f, 1000);
    s.bodies[3] = make_body(s.w, HEARTH_BODY_KINEMATIC, vec(0, 5, 5));
    ENSURE_OK(hearth_body_set_linear_velocity(s.w, s.bodies[3], vec(1, 0, 0)));

    HearthParticleDef pd = hearth_particle_def_default();
    pd.position = vec(-2, 2, -2);
    HearthParticleId p;
    ENSURE_OK(hearth_particle_create(s.w, &pd, &p));
    HearthRodGeneratorDef rd = hearth_rod_generator_def_default();
    rd.a.particle = p;
    rd.b.point = vec(-2, 3, -2);
    HearthGeneratorId g;
    ENSURE_OK(hearth_generator_create_rod(s.w, &rd, &g));
    HearthBurstDef bd = hearth_burst_def_default();
    bd.position = vec(2, 1, 2);
    bd.lifetime_max = INFINITY;
    ENSURE_OK(hearth_particle_emit_burst(s.w, &bd, NULL, 0, NULL));

    HearthSoftBodyDef sd = hearth_soft_body_def_default();
    sd.transform.position = vec(-4, 1, 3);
    sd.pressure = 200;
    ENSURE_OK(hearth_soft_body_create_icosphere(s.w, &sd, 0.5f, 1, &s.ball));
    return s;
}

static int soft_is_finite(const HearthWorld *w, HearthSoftBodyId ball) {
    HearthVec3 p[64];
    size_t n = 0;
    if (hearth_soft_body_get_positions(w, ball, p, 64, &n) != HEARTH_OK || n != 42) return 0;
    for (size_t i = 0; i < n; i++)
        if (!finite3(p[i])) return 0;
    return 1;
}

static void test_time_steps_at_both_ends_in_every_subsystem(void) {
    const float ends[2] = {MIN_TIME_STEP, MAX_TIME_STEP};
    for (int e = 0; e < 2; e++) {
        Scene s = make_scene();
        int ok = 1;
        for (int i = 0; i < 100 && ok; i++) {
            ok = hearth_world_step(s.w, ends[e]) == HEARTH_OK && world_is_finite(s.w, s.bodies, 4) &&
                 soft_is_finite(s.w, s.ball);
        }
        ENSURE(ok);
        hearth_world_destroy(s.w);
    }
}

static void test_time_steps_outside_the_range_are_refused_and_change_nothing(void) {
    Scene s = make_scene();
    ENSURE_OK(hearth_world_step(s.w, 1.0f / 60.0f));
    HearthTransform before[4], after[4];
    ENSURE_OK(hearth_world_get_transforms(s.w, s.bodies, 4, before));
    const float bad[] = {1e-20f, 1e-40f /* denormal */, MIN_TIME_STEP * 0.99f, MAX_TIME_STEP * 1.01f, 1e6f,
                         -1.0f / 60.0f, NAN, INFINITY};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) ENSURE_REFUSED(hearth_world_step(s.w, bad[i]), "dt");
    /* 0 is a step that does nothing. */
    ENSURE_OK(hearth_world_step(s.w, 0.0f));
    ENSURE_OK(hearth_world_get_transforms(s.w, s.bodies, 4, after));
    ENSURE(memcmp(before, after, sizeof before) == 0);
    hearth_world_destroy(s.w);
}

/* ----------------------------------------------------------- item 10's extreme values */

static void test_extreme_values(void) {
    HearthWorld *w = make_world();
    add_ground(w);
    HearthBodyId b[3];
    b[0] = make_body(w, HEARTH_BODY_DYNAMIC, vec(0, 1, 0));
    add_sphere(w, b[0], 0.1f, 1000);
    b[1] = make_body(w, HEARTH_BODY_DYNAMIC, vec(50, MAX_LENGTH + 1, 0));
    add_sphere(w, b[1], MAX_LENGTH, 1000); /* the largest sphere */
    b[2] = make_body(w, HEARTH_BODY_DYNAMIC, vec(-50, 1, 0));
    add_sphere(w, b[2], MIN_LENGTH, 1000); /* the smallest */

    /* Refused, naming the parameter, changing nothing. */
    HearthTransform before[3], after[3];
    ENSURE_OK(hearth_world_get_transforms(w, b, 3, before));
    ENSURE_REFUSED(hearth_world_step(w, 1e6f), "dt");
    ENSURE_REFUSED(hearth_world_set_gravity(w, vec(0, -1e30f, 0)), "gravity");
    ENSURE_REFUSED(hearth_body_apply_torque(w, b[0], vec(3e38f, 0, 0)), "torque");
    ENSURE_REFUSED(hearth_body_apply_force(w, b[0], vec(0, 2 * MAX_FORCE, 0)), "force");
    ENSURE_REFUSED(hearth_body_apply_linear_impulse(w, b[0], vec(0, 2 * MAX_IMPULSE, 0)), "impulse");
    HearthShapeDef sd = hearth_shape_def_default();
    HearthSphere huge;
    huge.center = vec(0, 0, 0);
    huge.radius = 1e30f;
    HearthShapeId sid;
    ENSURE_REFUSED(hearth_shape_create_sphere(w, b[0], &sd, &huge, &sid), "radius");
    huge.radius = MIN_LENGTH * 0.5f;
    ENSURE_REFUSED(hearth_shape_create_sphere(w, b[0], &sd, &huge, &sid), "radius");
    HearthExplosionGeneratorDef ed = hearth_explosion_generator_def_default();
    ed.blast_impulse = 3e38f;
    HearthGeneratorId g;
    ENSURE_REFUSED(hearth_generator_create_explosion(w, &ed, &g), "blast_impulse");
    HearthVec3 gravity;
    ENSURE_OK(hearth_world_get_gravity(w, &gravity));
    ENSURE_NEAR(gravity.y, -9.81, 1e-6);
    ENSURE_OK(hearth_world_get_transforms(w, b, 3, after));
    ENSURE(memcmp(before, after, sizeof before) == 0);
    ENSURE(body_count(w) == 4);

    /* Accepted at the limit, and the world stays finite. */
    ENSURE_OK(hearth_world_set_gravity(w, vec(0, -MAX_ACCELERATION, 0)));
    ENSURE_OK(hearth_body_apply_force(w, b[2], vec(MAX_FORCE, 0, 0)));
    /* (The largest torque on the 1 mm sphere needs the solver's angular speed cap: tested in
     * tests/ranges.rs.) */
    ENSURE_OK(hearth_body_apply_torque(w, b[0], vec(0, 0, MAX_FORCE)));
    ENSURE_OK(hearth_body_apply_impulse_at_point(w, b[0], vec(0, MAX_IMPULSE, 0), vec(1e5f, 0, 0)));
    ed.blast_impulse = MAX_IMPULSE;
    ed.shock_force = MAX_FORCE;
    ENSURE_OK(hearth_generator_create_explosion(w, &ed, &g));
    int ok = 1;
    for (int i = 0; i < 60 && ok; i++) ok = hearth_world_step(w, 1.0f / 60.0f) == HEARTH_OK && world_is_finite(w, b, 3);
    ENSURE(ok);
    ENSURE_OK(hearth_world_step(w, MIN_TIME_STEP));
    ENSURE(world_is_finite(w, b, 3));
    hearth_world_destroy(w);
}

int main(void) {
    test_ids_never_cross_worlds_over_many_world_generations();
    test_the_4096th_live_world_is_refused();
    test_a_destroyed_particle_cannot_be_detached();
    test_time_steps_at_both_ends_in_every_subsystem();
    test_time_steps_outside_the_range_are_refused_and_change_nothing();
    test_extreme_values();
    return ensure_report("test_ranges");
}
