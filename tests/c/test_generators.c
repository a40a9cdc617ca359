/*
 * Force and contact generators from C, using only include/hearth.h: every generator export
 * and its errors (NULL, garbage and zeroed defs, NaN, stale and foreign ids), attachments,
 * user force and contact generators through callbacks (user_data, exact call counts, what a
 * callback may and may not do: reads and its phase's own operation work, re-entry and
 * structural changes get HEARTH_ERROR_WORLD_LOCKED), the contact sink's rules, and built-in
 * generators doing physics. Compiled as C11 and C++17, shared and static, under valgrind.
 */
#include "hearth.h"
#include "ensure.h"

static HearthWorld *make_world(float gravity_y) {
    HearthWorldDef def = hearth_world_def_default();
    def.gravity.y = gravity_y;
    def.enable_sleep = 0;
    HearthWorld *w = NULL;
    ENSURE_OK(hearth_world_create(&def, &w));
    return w;
}

static HearthBodyId make_ball(HearthWorld *w, float x, float y, float z) {
    HearthBodyDef bd = hearth_body_def_default();
    bd.type = HEARTH_BODY_DYNAMIC;
    bd.transform.position.x = x;
    bd.transform.position.y = y;
    bd.transform.position.z = z;
    HearthBodyId b;
    memset(&b, 0, sizeof b);
    ENSURE_OK(hearth_body_create(w, &bd, &b));
    HearthShapeDef sd = hearth_shape_def_default();
    HearthSphere s;
    memset(&s, 0, sizeof s);
    s.radius = 0.25f;
    HearthShapeId sh;
    ENSURE_OK(hearth_shape_create_sphere(w, b, &sd, &s, &sh));
    return b;
}

static HearthParticleId make_particle(HearthWorld *w, float x, float y, float z) {
    HearthParticleDef pd = hearth_particle_def_default();
    pd.position.x = x;
    pd.position.y = y;
    pd.position.z = z;
    HearthParticleId p;
    memset(&p, 0, sizeof p);
    ENSURE_OK(hearth_particle_create(w, &pd, &p));
    return p;
}

static HearthVec3 vec3(float x, float y, float z) {
    HearthVec3 v;
    v.x = x;
    v.y = y;
    v.z = z;
    return v;
}

static void test_defaults_and_def_errors(void) {
    HearthWorld *w = make_world(-9.81f);
    HearthGeneratorId g;
    memset(&g, 0, sizeof g);

    HearthGravityGeneratorDef gd = hearth_gravity_generator_def_default();
    ENSURE_NEAR(gd.acceleration.y, -9.81, 1e-6);
    HearthDragGeneratorDef dd = hearth_drag_generator_def_default();
    ENSURE(dd.k1 >= 0.0f && dd.k2 >= 0.0f);
    HearthSpringGeneratorDef sd = hearth_spring_generator_def_default();
    ENSURE(sd.stiffness > 0.0f && sd.rest_length >= 0.0f);
    HearthStiffSpringGeneratorDef ssd = hearth_stiff_spring_generator_def_default();
    ENSURE(ssd.stiffness > 0.0f);
    HearthBuoyancyGeneratorDef bd = hearth_buoyancy_generator_def_default();
    ENSURE(bd.surface_normal.y == 1.0f && bd.liquid_density == 1000.0f);
    HearthExplosionGeneratorDef ed = hearth_explosion_generator_def_default();
    ENSURE(ed.affect_all == 1);
    HearthRodGeneratorDef rd = hearth_rod_generator_def_default();
    HearthCableGeneratorDef cd = hearth_cable_generator_def_default();
    HearthUserForceGeneratorDef ufd = hearth_user_force_generator_def_default();
    ENSURE(ufd.callback == NULL && ufd.user_data == NULL);
    HearthUserContactGeneratorDef ucd = hearth_user_contact_generator_def_default();
    ENSURE(ucd.capacity > 0);

    /* NULL world, def, output. */
    ENSURE_RESULT(hearth_generator_create_gravity(NULL, &gd, &g), HEARTH_ERROR_NULL_POINTER);
    ENSURE_RESULT(hearth_generator_create_gravity(w, NULL, &g), HEARTH_ERROR_NULL_POINTER);
    ENSURE_RESULT(hearth_generator_create_gravity(w, &gd, NULL), HEARTH_ERROR_NULL_POINTER);
    ENSURE_RESULT(hearth_generator_create_drag(w, NULL, &g), HEARTH_ERROR_NULL_POINTER);
    ENSURE_RESULT(hearth_generator_create_spring(w, NULL, &g), HEARTH_ERROR_NULL_POINTER);
    ENSURE_RESULT(hearth_generator_create_bungee(w, NULL, &g), HEARTH_ERROR_NULL_POINTER);
    ENSURE_RESULT(hearth_generator_create_stiff_spring(w, NULL, &g), HEARTH_ERROR_NULL_POINTER);
    ENSURE_RESULT(hearth_generator_create_buoyancy(w, NULL, &g), HEARTH_ERROR_NULL_POINTER);
    ENSURE_RESULT(hearth_generator_create_explosion(w, NULL, &g), HEARTH_ERROR_NULL_POINTER);
    ENSURE_RESULT(hearth_generator_create_rod(w, NULL, &g), HEARTH_ERROR_NULL_POINTER);
    ENSURE_RESULT(hearth_generator_create_cable(w, NULL, &g), HEARTH_ERROR_NULL_POINTER);
    ENSURE_RESULT(hearth_generator_create_user_force(w, NULL, &g), HEARTH_ERROR_NULL_POINTER);
    ENSURE_RESULT(hearth_generator_create_user_contact(w, NULL, &g), HEARTH_ERROR_NULL_POINTER);

    /* Garbage and zeroed defs: every create rejects them. */
    unsigned char garbage[256];
    memset(garbage, 0xAB, sizeof garbage);
    unsigned char zeroed[256];
    memset(zeroed, 0, sizeof zeroed);
    const unsigned char *bad[2] = {garbage, zeroed};
    for (int k = 0; k < 2; k++) {
        const void *b = bad[k];
        ENSURE_RESULT(hearth_generator_create_gravity(w, (const HearthGravityGeneratorDef *)b, &g),
                      HEARTH_ERROR_INVALID_ARGUMENT);
        ENSURE_RESULT(hearth_generator_create_drag(w, (const HearthDragGeneratorDef *)b, &g),
                      HEARTH_ERROR_INVALID_ARGUMENT);
        ENSURE_RESULT(hearth_generator_create_spring(w, (const HearthSpringGeneratorDef *)b, &g),
                      HEARTH_ERROR_INVALID_ARGUMENT);
        ENSURE_RESULT(hearth_generator_create_bungee(w, (const HearthSpringGeneratorDef *)b, &g),
                      HEARTH_ERROR_INVALID_ARGUMENT);
        ENSURE_RESULT(
            hearth_generator_create_stiff_spring(w, (const HearthStiffSpringGeneratorDef *)b, &g),
            HEARTH_ERROR_INVALID_ARGUMENT);
        ENSURE_RESULT(hearth_generator_create_buoyancy(w, (const HearthBuoyancyGeneratorDef *)b, &g),
                      HEARTH_ERROR_INVALID_ARGUMENT);
        ENSURE_RESULT(
            hearth_generator_create_explosion(w, (const HearthExplosionGeneratorDef *)b, &g),
            HEARTH_ERROR_INVALID_ARGUMENT);
        ENSURE_RESULT(hearth_generator_create_rod(w, (const HearthRodGeneratorDef *)b, &g),
                      HEARTH_ERROR_INVALID_ARGUMENT);
        ENSURE_RESULT(hearth_generator_create_cable(w, (const HearthCableGeneratorDef *)b, &g),
                      HEARTH_ERROR_INVALID_ARGUMENT);
    }
    /* Out-of-range numbers. */
    HearthGravityGeneratorDef gbad = gd;
    gbad.acceleration.x = NAN;
    ENSURE_RESULT(hearth_generator_create_gravity(w, &gbad, &g), HEARTH_ERROR_INVALID_ARGUMENT);
    HearthDragGeneratorDef dbad = dd;
    dbad.k2 = -1.0f;
    ENSURE_RESULT(hearth_generator_create_drag(w, &dbad, &g), HEARTH_ERROR_INVALID_ARGUMENT);
    HearthSpringGeneratorDef sbad = sd;
    sbad.stiffness = INFINITY;
    ENSURE_RESULT(hearth_generator_create_spring(w, &sbad, &g), HEARTH_ERROR_INVALID_ARGUMENT);
    sbad = sd;
    sbad.rest_length = -1.0f;
    ENSURE_RESULT(hearth_generator_create_bungee(w, &sbad, &g), HEARTH_ERROR_INVALID_ARGUMENT);
    HearthStiffSpringGeneratorDef ssbad = ssd;
    ssbad.stiffness = 0.0f;
    ENSURE_RESULT(hearth_generator_create_stiff_spring(w, &ssbad, &g), HEARTH_ERROR_INVALID_ARGUMENT);
    HearthBuoyancyGeneratorDef bbad = bd;
    bbad.surface_normal = vec3(0, 0, 0);
    ENSURE_RESULT(hearth_generator_create_buoyancy(w, &bbad, &g), HEARTH_ERROR_INVALID_ARGUMENT);
    bbad = bd;
    bbad.max_depth = 0.0f;
    ENSURE_RESULT(hearth_generator_create_buoyancy(w, &bbad, &g), HEARTH_ERROR_INVALID_ARGUMENT);
    HearthExplosionGeneratorDef ebad = ed;
    ebad.affect_all = 2;
    ENSURE_RESULT(hearth_generator_create_explosion(w, &ebad, &g), HEARTH_ERROR_INVALID_ARGUMENT);
    ebad = ed;
    ebad.shock_speed = NAN;
    ENSURE_RESULT(hearth_generator_create_explosion(w, &ebad, &g), HEARTH_ERROR_INVALID_ARGUMENT);
    /* Rods and cables: two world ends, the same end twice, both ids in an end, dead ids. */
    ENSURE_RESULT(hearth_generator_create_rod(w, &rd, &g), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE_RESULT(hearth_generator_create_cable(w, &cd, &g), HEARTH_ERROR_INVALID_ARGUMENT);
    HearthBodyId b = make_ball(w, 0, 5, 0);
    HearthParticleId p = make_particle(w, 1, 5, 0);
    HearthRodGeneratorDef rbad = rd;
    rbad.a.body = b;
    rbad.b.body = b;
    ENSURE_RESULT(hearth_generator_create_rod(w, &rbad, &g), HEARTH_ERROR_INVALID_ARGUMENT);
    rbad = rd;
    rbad.a.body = b;
    rbad.a.particle = p;
    ENSURE_RESULT(hearth_generator_create_rod(w, &rbad, &g), HEARTH_ERROR_INVALID_ARGUMENT);
    rbad = rd;
    rbad.a.body = b;
    rbad.length = NAN;
    ENSURE_RESULT(hearth_generator_create_rod(w, &rbad, &g), HEARTH_ERROR_INVALID_ARGUMENT);
    HearthCableGeneratorDef cbad = cd;
    cbad.a.particle = p;
    cbad.restitution = -0.5f;
    ENSURE_RESULT(hearth_generator_create_cable(w, &cbad, &g), HEARTH_ERROR_INVALID_ARGUMENT);
    HearthBodyId dead_body = make_ball(w, 9, 9, 9);
    ENSURE_OK(hearth_body_destroy(w, dead_body));
    rbad = rd;
    rbad.a.body = dead_body;
    ENSURE_RESULT(hearth_generator_create_rod(w, &rbad, &g), HEARTH_ERROR_INVALID_ID);
    sbad = sd;
    sbad.other.body = dead_body;
    ENSURE_RESULT(hearth_generator_create_spring(w, &sbad, &g), HEARTH_ERROR_INVALID_ID);
    HearthParticleId garbage_particle;
    garbage_particle.index = 77;
    garbage_particle.generation = 0;
    ssbad = ssd;
    ssbad.anchor.particle = garbage_particle;
    ENSURE_RESULT(hearth_generator_create_stiff_spring(w, &ssbad, &g), HEARTH_ERROR_INVALID_ID);
    /* User generators need a callback. */
    ENSURE_RESULT(hearth_generator_create_user_force(w, &ufd, &g), HEARTH_ERROR_NULL_POINTER);
    ENSURE_RESULT(hearth_generator_create_user_contact(w, &ucd, &g), HEARTH_ERROR_NULL_POINTER);
    HearthUserForceGeneratorDef ufbad = ufd;
    ufbad.internal_value = 0;
    ENSURE_RESULT(hearth_generator_create_user_force(w, &ufbad, &g), HEARTH_ERROR_INVALID_ARGUMENT);
    /* Failures wrote nothing. */
    ENSURE(g.index == 0 && g.generation == 0);
    hearth_world_destroy(w);
}

static void test_ids_and_attachments(void) {
    HearthWorld *w = make_world(-9.81f);
    HearthWorld *other = make_world(-9.81f);
    HearthBodyId b1 = make_ball(w, 0, 5, 0);
    HearthBodyId b2 = make_ball(w, 2, 5, 0);
    HearthParticleId p1 = make_particle(w, 0, 8, 0);
    HearthParticleId p2 = make_particle(w, 1, 8, 0);
    HearthDragGeneratorDef dd = hearth_drag_generator_def_default();
    HearthGeneratorId drag;
    ENSURE_OK(hearth_generator_create_drag(w, &dd, &drag));
    ENSURE(drag.generation != 0);
    uint32_t type = 99;
    ENSURE_OK(hearth_generator_get_type(w, drag, &type));
    ENSURE(type == HEARTH_GENERATOR_DRAG);
    ENSURE_RESULT(hearth_generator_get_type(w, drag, NULL), HEARTH_ERROR_NULL_POINTER);
    ENSURE_RESULT(hearth_generator_get_type(NULL, drag, &type), HEARTH_ERROR_NULL_POINTER);

    ENSURE_OK(hearth_generator_attach_body(w, drag, b1));
    ENSURE_OK(hearth_generator_attach_body(w, drag, b2));
    ENSURE_OK(hearth_generator_attach_particle(w, drag, p1));
    ENSURE_RESULT(hearth_generator_attach_body(w, drag, b1), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE_RESULT(hearth_generator_attach_particle(w, drag, p1), HEARTH_ERROR_INVALID_ARGUMENT);
    uint32_t nb = 0, np = 0;
    ENSURE_OK(hearth_generator_get_attachment_count(w, drag, &nb, &np));
    ENSURE(nb == 2 && np == 1);
    ENSURE_RESULT(hearth_generator_get_attachment_count(w, drag, NULL, &np), HEARTH_ERROR_NULL_POINTER);

    /* Detach: attached ones only. */
    ENSURE_OK(hearth_generator_detach_body(w, drag, b2));
    ENSURE_RESULT(hearth_generator_detach_body(w, drag, b2), HEARTH_ERROR_INVALID_ID);
    ENSURE_RESULT(hearth_generator_detach_particle(w, drag, p2), HEARTH_ERROR_INVALID_ID);
    ENSURE_OK(hearth_generator_detach_particle(w, drag, p1));
    ENSURE_OK(hearth_generator_get_attachment_count(w, drag, &nb, &np));
    ENSURE(nb == 1 && np == 0);

    /* Bulk attach: all or nothing. */
    HearthParticleId batch[3] = {p1, p2, p1};
    ENSURE_RESULT(hearth_generator_attach_particles(w, drag, batch, 3), HEARTH_ERROR_INVALID_ARGUMENT);
    HearthParticleId dead = make_particle(w, 5, 5, 5);
    ENSURE_OK(hearth_particle_destroy(w, dead));
    HearthParticleId batch2[3] = {p1, p2, dead};
    ENSURE_RESULT(hearth_generator_attach_particles(w, drag, batch2, 3), HEARTH_ERROR_INVALID_ID);
    ENSURE_OK(hearth_generator_get_attachment_count(w, drag, &nb, &np));
    ENSURE(np == 0);
    ENSURE_OK(hearth_generator_attach_particles(w, drag, batch2, 2));
    ENSURE_OK(hearth_generator_attach_particles(w, drag, NULL, 0));
    ENSURE_RESULT(hearth_generator_attach_particles(w, drag, NULL, 2), HEARTH_ERROR_NULL_POINTER);
    ENSURE_OK(hearth_generator_get_attachment_count(w, drag, &nb, &np));
    ENSURE(np == 2);

    /* Destroying a body or particle detaches it everywhere. */
    ENSURE_OK(hearth_body_destroy(w, b1));
    ENSURE_OK(hearth_particle_destroy(w, p2));
    ENSURE_OK(hearth_generator_get_attachment_count(w, drag, &nb, &np));
    ENSURE(nb == 0 && np == 1);
    ENSURE_RESULT(hearth_generator_attach_body(w, drag, b1), HEARTH_ERROR_INVALID_ID);
    ENSURE_RESULT(hearth_generator_attach_particle(w, drag, p2), HEARTH_ERROR_INVALID_ID);
    ENSURE_OK(hearth_world_step(w, 1.0f / 60.0f));

    /* Rods take no attachments. */
    HearthRodGeneratorDef rd = hearth_rod_generator_def_default();
    rd.a.body = b2;
    rd.b.point = vec3(2, 7, 0);
    rd.length = 2.0f;
    HearthGeneratorId rod;
    ENSURE_OK(hearth_generator_create_rod(w, &rd, &rod));
    ENSURE_RESULT(hearth_generator_attach_body(w, rod, b2), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE_RESULT(hearth_generator_attach_particle(w, rod, p1), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE_OK(hearth_generator_get_type(w, rod, &type));
    ENSURE(type == HEARTH_GENERATOR_ROD);

    /* Stale, null and foreign generator ids. */
    ENSURE_OK(hearth_generator_destroy(w, drag));
    ENSURE_RESULT(hearth_generator_destroy(w, drag), HEARTH_ERROR_INVALID_ID);
    ENSURE_RESULT(hearth_generator_attach_body(w, drag, b2), HEARTH_ERROR_INVALID_ID);
    ENSURE_RESULT(hearth_generator_get_type(w, drag, &type), HEARTH_ERROR_INVALID_ID);
    HearthGeneratorId null_id;
    memset(&null_id, 0, sizeof null_id);
    ENSURE_RESULT(hearth_generator_destroy(w, null_id), HEARTH_ERROR_INVALID_ID);
    ENSURE_RESULT(hearth_generator_destroy(other, rod), HEARTH_ERROR_INVALID_ID);
    ENSURE_RESULT(hearth_generator_destroy(NULL, rod), HEARTH_ERROR_NULL_POINTER);
    HearthGeneratorId again;
    ENSURE_OK(hearth_generator_create_drag(w, &dd, &again));
    ENSURE(again.index == drag.index && again.generation != drag.generation);
    ENSURE_RESULT(hearth_generator_attach_body(w, drag, b2), HEARTH_ERROR_INVALID_ID);
    /* A body of another world. */
    HearthBodyId foreign = make_ball(other, 0, 0, 0);
    ENSURE_RESULT(hearth_generator_attach_body(w, again, foreign), HEARTH_ERROR_INVALID_ID);
    hearth_world_destroy(w);
    hearth_world_destroy(other);
}

/* ------------------------------------------------------------------ user force generators */

typedef struct ForceProbe {
    int calls;
    int saw_bodies;
    int saw_particles;
    float dt;
    HearthGeneratorId generator;
    HearthBodyId body;
    HearthResult read;
    HearthResult applied;
    HearthResult applied_particle;
    HearthResult created;
    HearthResult destroyed;
    HearthResult stepped;
    HearthResult set_transform;
    HearthResult attached;
    HearthResult particle_created;
    HearthResult impulse;
    HearthResult sink_add;
    HearthResult particle_destroyed;
    HearthResult generator_destroyed;
    HearthResult burst;
    HearthResult particle_moved;
    float read_y;
} ForceProbe;

/* Reads the body's transform and lifts it with exactly its weight, then tries what a force
 * generator must not do. */
static void lift_callback(void *user_data, HearthWorld *world, const HearthGeneratorContext *ctx) {
    ForceProbe *probe = (ForceProbe *)user_data;
    probe->calls++;
    probe->dt = ctx->dt;
    probe->generator = ctx->generator;
    probe->saw_bodies = (int)ctx->body_count;
    probe->saw_particles = (int)ctx->particle_count;
    for (size_t i = 0; i < ctx->body_count; i++) {
        HearthTransform t;
        probe->read = hearth_body_get_transform(world, ctx->bodies[i], &t);
        probe->read_y = t.position.y;
        float mass = 0.0f;
        hearth_body_get_mass(world, ctx->bodies[i], &mass);
        probe->applied = hearth_body_apply_force(world, ctx->bodies[i], vec3(0, 9.81f * mass, 0));
    }
    for (size_t i = 0; i < ctx->particle_count; i++) {
        probe->applied_particle = hearth_particle_apply_force(world, ctx->particles[i], vec3(0, 9.81f, 0));
    }
    HearthBodyDef bd = hearth_body_def_default();
    HearthBodyId nb;
    probe->created = hearth_body_create(world, &bd, &nb);
    probe->destroyed = hearth_body_destroy(world, probe->body);
    probe->stepped = hearth_world_step(world, 1.0f / 60.0f);
    HearthTransform t;
    memset(&t, 0, sizeof t);
    t.rotation.w = 1.0f;
    probe->set_transform = hearth_body_set_transform(world, probe->body, &t);
    probe->attached = hearth_generator_attach_body(world, ctx->generator, probe->body);
    HearthParticleDef pd = hearth_particle_def_default();
    HearthParticleId np;
    probe->particle_created = hearth_particle_create(world, &pd, &np);
    probe->impulse = hearth_body_apply_linear_impulse(world, probe->body, vec3(0, 1, 0));
    probe->sink_add = hearth_contact_sink_add(NULL, NULL);
    if (ctx->particle_count > 0) {
        probe->particle_destroyed = hearth_particle_destroy(world, ctx->particles[0]);
        probe->particle_moved = hearth_particle_set_position(world, ctx->particles[0], vec3(0, 0, 0));
    }
    probe->generator_destroyed = hearth_generator_destroy(world, ctx->generator);
    HearthBurstDef burst = hearth_burst_def_default();
    probe->burst = hearth_particle_emit_burst(world, &burst, NULL, 0, NULL);
    hearth_world_destroy(world); /* ignored while stepping */
}

static void test_user_force_generator(void) {
    HearthWorld *w = make_world(-9.81f);
    HearthBodyId b = make_ball(w, 0, 10, 0);
    HearthParticleId p = make_particle(w, 3, 10, 0);
    ForceProbe probe;
    memset(&probe, 0, sizeof probe);
    probe.body = b;
    HearthUserForceGeneratorDef def = hearth_user_force_generator_def_default();
    def.callback = lift_callback;
    def.user_data = &probe;
    HearthGeneratorId g;
    ENSURE_OK(hearth_generator_create_user_force(w, &def, &g));
    uint32_t type = 0;
    ENSURE_OK(hearth_generator_get_type(w, g, &type));
    ENSURE(type == HEARTH_GENERATOR_USER_FORCE);
    ENSURE_OK(hearth_generator_attach_body(w, g, b));
    ENSURE_OK(hearth_generator_attach_particle(w, g, p));

    /* Not called before a step, nor by a zero step. */
    ENSURE(probe.calls == 0);
    ENSURE_OK(hearth_world_step(w, 0.0f));
    ENSURE(probe.calls == 0);
    for (int i = 0; i < 30; i++) {
        ENSURE_OK(hearth_world_step(w, 1.0f / 60.0f));
    }
    ENSURE(probe.calls == 30);
    ENSURE(probe.saw_bodies == 1 && probe.saw_particles == 1);
    ENSURE_NEAR(probe.dt, 1.0 / 60.0, 1e-7);
    ENSURE(probe.generator.index == g.index && probe.generator.generation == g.generation);
    /* Reads and forces worked; everything structural was refused. */
    ENSURE(probe.read == HEARTH_OK);
    ENSURE_NEAR(probe.read_y, 10.0, 1e-3);
    ENSURE(probe.applied == HEARTH_OK);
    ENSURE(probe.applied_particle == HEARTH_OK);
    ENSURE(probe.created == HEARTH_ERROR_WORLD_LOCKED);
    ENSURE(probe.destroyed == HEARTH_ERROR_WORLD_LOCKED);
    ENSURE(probe.stepped == HEARTH_ERROR_WORLD_LOCKED);
    ENSURE(probe.set_transform == HEARTH_ERROR_WORLD_LOCKED);
    ENSURE(probe.attached == HEARTH_ERROR_WORLD_LOCKED);
    ENSURE(probe.particle_created == HEARTH_ERROR_WORLD_LOCKED);
    ENSURE(probe.impulse == HEARTH_ERROR_WORLD_LOCKED);
    ENSURE(probe.sink_add == HEARTH_ERROR_NULL_POINTER);
    ENSURE(probe.particle_destroyed == HEARTH_ERROR_WORLD_LOCKED);
    ENSURE(probe.particle_moved == HEARTH_ERROR_WORLD_LOCKED);
    ENSURE(probe.generator_destroyed == HEARTH_ERROR_WORLD_LOCKED);
    ENSURE(probe.burst == HEARTH_ERROR_WORLD_LOCKED);
    /* The lift cancelled gravity: both float where they were. */
    HearthTransform t;
    ENSURE_OK(hearth_body_get_transform(w, b, &t));
    ENSURE_NEAR(t.position.y, 10.0, 1e-3);
    HearthVec3 pp;
    ENSURE_OK(hearth_particle_get_position(w, p, &pp));
    ENSURE_NEAR(pp.y, 10.0, 1e-3);
    HearthWorldCounters c;
    ENSURE_OK(hearth_world_get_counters(w, &c));
    ENSURE(c.body_count == 1);
    /* Outside a step the same calls work again. */
    HearthBodyDef bd = hearth_body_def_default();
    HearthBodyId nb;
    ENSURE_OK(hearth_body_create(w, &bd, &nb));
    /* Two generators: each called once per step, in creation order. */
    ForceProbe second;
    memset(&second, 0, sizeof second);
    second.body = nb;
    def.user_data = &second;
    HearthGeneratorId g2;
    ENSURE_OK(hearth_generator_create_user_force(w, &def, &g2));
    for (int i = 0; i < 5; i++) {
        ENSURE_OK(hearth_world_step(w, 1.0f / 60.0f));
    }
    ENSURE(probe.calls == 35 && second.calls == 5);
    ENSURE(second.saw_bodies == 0 && second.saw_particles == 0);
    /* Destroyed: no more calls. */
    ENSURE_OK(hearth_generator_destroy(w, g));
    ENSURE_OK(hearth_world_step(w, 1.0f / 60.0f));
    ENSURE(probe.calls == 35 && second.calls == 6);
    hearth_world_destroy(w);
}

/* ----------------------------------------------------------------- user contact generators */

typedef struct ContactProbe {
    int calls;
    HearthBodyId body;
    HearthParticleId particle;
    HearthResult ok_body;
    HearthResult ok_particle;
    HearthResult over_capacity;
    HearthResult nan_normal;
    HearthResult zero_normal;
    HearthResult both_ids;
    HearthResult no_object;
    HearthResult same_object;
    HearthResult negative_friction;
    HearthResult stale;
    HearthResult null_contact;
    HearthResult force;
    HearthResult created;
    HearthResult read;
    uint32_t count;
    uint32_t capacity;
    HearthContactSink *kept_sink;
    HearthBodyId stale_body;
} ContactProbe;

/* A floor at y = 0 for one body (radius 0.25) and one particle (radius 0.05), written by
 * hand: body or particle against the world, normal from the world to the object. */
static void floor_callback(void *user_data, HearthWorld *world, const HearthGeneratorContext *ctx,
                           HearthContactSink *sink) {
    (void)ctx;
    ContactProbe *probe = (ContactProbe *)user_data;
    probe->calls++;
    probe->kept_sink = sink;
    HearthTransform t;
    probe->read = hearth_body_get_transform(world, probe->body, &t);
    HearthGeneratedContact c;
    memset(&c, 0, sizeof c);
    c.body_b = probe->body;
    c.point = vec3(t.position.x, 0, t.position.z);
    c.normal = vec3(0, 1, 0);
    c.penetration = 0.25f - t.position.y;
    c.friction = 0.5f;
    probe->ok_body = hearth_contact_sink_add(sink, &c);

    HearthVec3 pp;
    hearth_particle_get_position(world, probe->particle, &pp);
    HearthGeneratedContact pc;
    memset(&pc, 0, sizeof pc);
    pc.particle_b = probe->particle;
    pc.point = vec3(pp.x, 0, pp.z);
    pc.normal = vec3(0, 2, 0); /* need not be unit length */
    pc.penetration = 0.05f - pp.y;
    probe->ok_particle = hearth_contact_sink_add(sink, &pc);

    /* Capacity 2: a third is refused. */
    probe->over_capacity = hearth_contact_sink_add(sink, &c);
    hearth_contact_sink_get_count(sink, &probe->count, &probe->capacity);

    HearthGeneratedContact bad = c;
    bad.normal.y = NAN;
    probe->nan_normal = hearth_contact_sink_add(sink, &bad);
    bad = c;
    bad.normal = vec3(0, 0, 0);
    probe->zero_normal = hearth_contact_sink_add(sink, &bad);
    bad = c;
    bad.particle_b = probe->particle;
    probe->both_ids = hearth_contact_sink_add(sink, &bad);
    memset(&bad, 0, sizeof bad);
    bad.normal = vec3(0, 1, 0);
    probe->no_object = hearth_contact_sink_add(sink, &bad);
    bad = c;
    bad.body_a = probe->body;
    probe->same_object = hearth_contact_sink_add(sink, &bad);
    bad = c;
    bad.friction = -1.0f;
    probe->negative_friction = hearth_contact_sink_add(sink, &bad);
    bad = c;
    bad.body_b = probe->stale_body;
    probe->stale = hearth_contact_sink_add(sink, &bad);
    probe->null_contact = hearth_contact_sink_add(sink, NULL);
    probe->force = hearth_body_apply_force(world, probe->body, vec3(0, 1, 0));
    HearthParticleDef pd = hearth_particle_def_default();
    HearthParticleId np;
    probe->created = hearth_particle_create(world, &pd, &np);
}

static void test_user_contact_generator(void) {
    HearthWorld *w = make_world(-9.81f);
    HearthBodyId b = make_ball(w, 0, 1, 0);
    HearthParticleId p = make_particle(w, 2, 1, 0);
    ContactProbe probe;
    memset(&probe, 0, sizeof probe);
    probe.body = b;
    probe.particle = p;
    probe.stale_body = make_ball(w, 5, 5, 5);
    ENSURE_OK(hearth_body_destroy(w, probe.stale_body));
    HearthUserContactGeneratorDef def = hearth_user_contact_generator_def_default();
    def.callback = floor_callback;
    def.user_data = &probe;
    def.capacity = 2;
    HearthGeneratorId g;
    ENSURE_OK(hearth_generator_create_user_contact(w, &def, &g));
    for (int i = 0; i < 180; i++) {
        ENSURE_OK(hearth_world_step(w, 1.0f / 60.0f));
    }
    ENSURE(probe.calls == 180);
    ENSURE(probe.read == HEARTH_OK);
    ENSURE(probe.ok_body == HEARTH_OK);
    ENSURE(probe.ok_particle == HEARTH_OK);
    ENSURE(probe.over_capacity == HEARTH_ERROR_BUFFER_TOO_SMALL);
    ENSURE(probe.count == 2 && probe.capacity == 2);
    ENSURE(probe.nan_normal == HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE(probe.zero_normal == HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE(probe.both_ids == HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE(probe.no_object == HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE(probe.same_object == HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE(probe.negative_friction == HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE(probe.stale == HEARTH_ERROR_INVALID_ID);
    ENSURE(probe.null_contact == HEARTH_ERROR_NULL_POINTER);
    ENSURE(probe.force == HEARTH_ERROR_WORLD_LOCKED);
    ENSURE(probe.created == HEARTH_ERROR_WORLD_LOCKED);
    /* The hand-written floor holds both: the ball rests with its bottom at y = 0. */
    HearthTransform t;
    ENSURE_OK(hearth_body_get_transform(w, b, &t));
    ENSURE_NEAR(t.position.y, 0.25, 5e-3);
    HearthVec3 v;
    ENSURE_OK(hearth_body_get_linear_velocity(w, b, &v));
    ENSURE_NEAR(v.y, 0.0, 1e-2);
    HearthVec3 pp;
    ENSURE_OK(hearth_particle_get_position(w, p, &pp));
    ENSURE_NEAR(pp.y, 0.05, 5e-3);
    /* The sink is refused outside its callback. */
    HearthGeneratedContact c;
    memset(&c, 0, sizeof c);
    c.body_b = b;
    c.normal = vec3(0, 1, 0);
    ENSURE_RESULT(hearth_contact_sink_add(probe.kept_sink, &c), HEARTH_ERROR_INVALID_ARGUMENT);
    uint32_t count = 0, capacity = 0;
    ENSURE_RESULT(hearth_contact_sink_get_count(NULL, &count, &capacity), HEARTH_ERROR_NULL_POINTER);
    ENSURE_OK(hearth_generator_destroy(w, g));
    ENSURE_OK(hearth_world_step(w, 1.0f / 60.0f));
    ENSURE(probe.calls == 180);
    hearth_world_destroy(w);
}

/* -------------------------------------------------------------------- built-ins in action */

static void test_builtins_do_physics(void) {
    /* Spring: a 2 kg particle on an anchored spring of 50 N/m oscillates with period
     * 2 pi sqrt(m/k); a quarter period after release from 0.2 m it passes the rest length. */
    HearthWorld *w = make_world(0.0f);
    HearthParticleDef pd = hearth_particle_def_default();
    pd.position = vec3(1.2f, 0, 0);
    pd.inverse_mass = 0.5f;
    pd.collide = 0;
    HearthParticleId p;
    ENSURE_OK(hearth_particle_create(w, &pd, &p));
    HearthSpringGeneratorDef sd = hearth_spring_generator_def_default();
    sd.rest_length = 1.0f;
    sd.stiffness = 50.0f;
    HearthGeneratorId spring;
    ENSURE_OK(hearth_generator_create_spring(w, &sd, &spring));
    ENSURE_OK(hearth_generator_attach_particle(w, spring, p));
    const double period = 2.0 * 3.14159265358979 * sqrt(2.0 / 50.0);
    int quarter = (int)(period / 4.0 * 60.0 + 0.5);
    for (int i = 0; i < quarter; i++) {
        ENSURE_OK(hearth_world_step(w, 1.0f / 60.0f));
    }
    HearthVec3 x;
    ENSURE_OK(hearth_particle_get_position(w, p, &x));
    ENSURE_NEAR(x.x, 1.0, 0.02);
    hearth_world_destroy(w);

    /* Rod between two bodies: holds its length while they fall and swing. */
    w = make_world(-9.81f);
    HearthBodyId a = make_ball(w, 0, 5, 0);
    HearthBodyId b = make_ball(w, 1, 5, 0);
    HearthRodGeneratorDef rd = hearth_rod_generator_def_default();
    rd.a.point = vec3(0, 8, 0);
    rd.b.body = a;
    rd.length = 3.0f;
    HearthGeneratorId rod1, rod2;
    ENSURE_OK(hearth_generator_create_rod(w, &rd, &rod1));
    rd.a.body = a;
    rd.a.point = vec3(0, 0, 0); /* now a body-frame attachment: the centre */
    rd.b.body = b;
    rd.length = 1.0f;
    ENSURE_OK(hearth_generator_create_rod(w, &rd, &rod2));
    double worst = 0.0;
    for (int i = 0; i < 240; i++) {
        ENSURE_OK(hearth_world_step(w, 1.0f / 60.0f));
        HearthTransform ta, tb;
        ENSURE_OK(hearth_body_get_transform(w, a, &ta));
        ENSURE_OK(hearth_body_get_transform(w, b, &tb));
        double dx = tb.position.x - ta.position.x, dy = tb.position.y - ta.position.y,
               dz = tb.position.z - ta.position.z;
        double err = fabs(sqrt(dx * dx + dy * dy + dz * dz) - 1.0);
        if (err > worst) {
            worst = err;
        }
    }
    printf("rods between bodies: worst length error %.5f m\n", worst);
    ENSURE(worst < 0.02);
    /* A rod whose body is destroyed stops; its id stays valid. */
    ENSURE_OK(hearth_body_destroy(w, b));
    ENSURE_OK(hearth_world_step(w, 1.0f / 60.0f));
    uint32_t type = 0;
    ENSURE_OK(hearth_generator_get_type(w, rod2, &type));
    ENSURE(type == HEARTH_GENERATOR_ROD);

    /* Explosion: pushes a particle away. */
    HearthParticleId q = make_particle(w, 0, 20, 3);
    HearthExplosionGeneratorDef ed = hearth_explosion_generator_def_default();
    ed.center = vec3(0, 20, 0);
    HearthGeneratorId boom;
    ENSURE_OK(hearth_generator_create_explosion(w, &ed, &boom));
    ENSURE_OK(hearth_world_step(w, 1.0f / 60.0f));
    HearthVec3 v;
    ENSURE_OK(hearth_particle_get_velocity(w, q, &v));
    ENSURE(v.z > 5.0f);
    ENSURE_OK(hearth_generator_destroy(w, boom));

    /* Buoyancy holds a particle afloat; a bungee, a stiff spring and extra gravity run. */
    HearthBuoyancyGeneratorDef bd = hearth_buoyancy_generator_def_default();
    bd.volume = 0.002f; /* 1 kg in water: half submerged at rest */
    HearthGeneratorId buoy;
    ENSURE_OK(hearth_generator_create_buoyancy(w, &bd, &buoy));
    HearthDragGeneratorDef dd = hearth_drag_generator_def_default();
    dd.k1 = 2.0f;
    HearthGeneratorId drag;
    ENSURE_OK(hearth_generator_create_drag(w, &dd, &drag));
    HearthParticleId floater = make_particle(w, 10, 1, 0);
    ENSURE_OK(hearth_generator_attach_particle(w, buoy, floater));
    ENSURE_OK(hearth_generator_attach_particle(w, drag, floater));
    HearthSpringGeneratorDef bgd = hearth_spring_generator_def_default();
    HearthGeneratorId bungee;
    ENSURE_OK(hearth_generator_create_bungee(w, &bgd, &bungee));
    HearthStiffSpringGeneratorDef ssd = hearth_stiff_spring_generator_def_default();
    HearthGeneratorId stiff;
    ENSURE_OK(hearth_generator_create_stiff_spring(w, &ssd, &stiff));
    HearthGravityGeneratorDef gd = hearth_gravity_generator_def_default();
    HearthGeneratorId grav;
    ENSURE_OK(hearth_generator_create_gravity(w, &gd, &grav));
    HearthCableGeneratorDef cd = hearth_cable_generator_def_default();
    cd.a.point = vec3(-5, 3, 0);
    cd.b.particle = make_particle(w, -5, 2, 0);
    HearthGeneratorId cable;
    ENSURE_OK(hearth_generator_create_cable(w, &cd, &cable));
    for (int i = 0; i < 600; i++) {
        ENSURE_OK(hearth_world_step(w, 1.0f / 60.0f));
    }
    HearthVec3 f;
    ENSURE_OK(hearth_particle_get_position(w, floater, &f));
    ENSURE_NEAR(f.y, 0.0, 0.02);
    HearthVec3 hang;
    ENSURE_OK(hearth_particle_get_position(w, cd.b.particle, &hang));
    ENSURE_NEAR(hang.y, 2.0, 5e-3);
    hearth_world_destroy(w);
}

int main(void) {
    test_defaults_and_def_errors();
    test_ids_and_attachments();
    test_user_force_generator();
    test_user_contact_generator();
    test_builtins_do_physics();
    return ensure_report("test_generators");
}
