/*
 * A seeded fuzzer of the whole C API: random sequences of calls over worlds, bodies, shapes,
 * joints, generators (with user callbacks), particles, emitters, soft bodies and steps, each
 * call with well-formed arguments or with one hostile one (NULL, a stale, foreign, null or
 * garbage id, a def not from its default, NaN, infinities, negative or out-of-range numbers,
 * unknown codes, flag bytes other than 0/1, buffers too small).
 *
 * For every call it checks the result code against what include/hearth.h promises for that
 * input; for a failing call, a non-empty message (naming the parameter for a bad number),
 * outputs left unwritten and the observable state of every world unchanged (counts,
 * transforms, velocities, sleep flags, particles, soft-body vertices, attachments, joints);
 * HEARTH_ERROR_PANIC never; and after every call that can move things, every body, particle
 * and soft-body vertex finite and no faster than the world's max_linear_speed.
 *
 * Reproducible: the sequence depends only on the seed. A failure prints the seed, the call
 * number and the function, and `fuzz_api SEED CALLS` replays it.
 *   fuzz_api                      the CI run: seeds 1..4, 1500 calls each
 *   fuzz_api SEED [CALLS]         one seed
 *   HEARTH_FUZZ_SEED=7 HEARTH_FUZZ_ITERATIONS=1000000 fuzz_api   a long run
 * Compiled as C11 and as C++17, linked shared and static, and run under valgrind in CI.
 */
#include "hearth.h"
#include "ensure.h"

#include <float.h>
#include <stdint.h>
#include <stdlib.h>

/* ------------------------------------------------------------------ the documented ranges */
/* README "Supported ranges" (asserted against the library by tests/ranges.rs). */
#define MIN_TIME_STEP 1e-3f
#define MAX_TIME_STEP 0.1f
#define MIN_LENGTH 1e-3f
#define MAX_LENGTH 1e4f
#define MAX_COORDINATE 1e5f
#define MAX_SPEED 1e4f
#define MAX_ANGULAR_SPEED 1e4f /* the largest max_angular_speed a world accepts */
#define MAX_ACCELERATION 1e4f
#define MAX_GRAVITY_SCALE 100.0f
#define MAX_FORCE 1e12f
#define MAX_IMPULSE 1e10f
#define MIN_DENSITY 1e-3f
#define MAX_DENSITY 1e5f
#define MAX_INVERSE_MASS 1e9f
#define MAX_DAMPING 1e3f

/* ------------------------------------------------------------------------------ random */
static uint64_t g_rng;

static uint64_t next_u64(void) {
    /* splitmix64 */
    uint64_t z = (g_rng += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}
static uint32_t rnd(uint32_t n) { return n ? (uint32_t)(next_u64() % n) : 0; }
static int chance(uint32_t percent) { return rnd(100) < percent; }
static float unit(void) { return (float)(next_u64() >> 40) * (1.0f / 16777216.0f); }
static float frange(float lo, float hi) { return lo + (hi - lo) * unit(); }
/* Log-uniform in [lo, hi] (both > 0). */
static float flog(float lo, float hi) { return lo * powf(hi / lo, unit()); }

static HearthVec3 vec(float x, float y, float z) {
    HearthVec3 v;
    v.x = x;
    v.y = y;
    v.z = z;
    return v;
}
static float len3(HearthVec3 v) { return sqrtf(v.x * v.x + v.y * v.y + v.z * v.z); }
static HearthVec3 scale3(HearthVec3 v, float s) { return vec(v.x * s, v.y * s, v.z * s); }
/* A random direction. */
static HearthVec3 dir3(void) {
    for (;;) {
        HearthVec3 v = vec(frange(-1, 1), frange(-1, 1), frange(-1, 1));
        float l = len3(v);
        if (l > 0.1f && l <= 1.0f) return scale3(v, 1.0f / l);
    }
}
/* A vector of length up to `max`: often small, sometimes exactly at the limit. */
static HearthVec3 vec_up_to(float max, float typical) {
    switch (rnd(6)) {
    case 0: return vec(0, 0, 0);
    case 1: return scale3(dir3(), max * 0.999f);
    case 2: return scale3(dir3(), flog(1e-6f, 1.0f) * max);
    default: return scale3(dir3(), frange(0, typical < max ? typical : max));
    }
}
static HearthQuat quat_any(void) {
    HearthQuat q;
    q.x = frange(-1, 1);
    q.y = frange(-1, 1);
    q.z = frange(-1, 1);
    q.w = frange(-1, 1);
    if (fabsf(q.x) + fabsf(q.y) + fabsf(q.z) + fabsf(q.w) < 0.1f) q.w = 1;
    if (chance(30)) { q.x = q.y = q.z = 0; q.w = 1; }
    return q;
}
static HearthTransform xf(HearthVec3 p, HearthQuat q) {
    HearthTransform t;
    t.position = p;
    t.rotation = q;
    return t;
}

/* A number that is never valid where a finite number in a range is asked for. */
static float nonfinite(void) {
    switch (rnd(3)) {
    case 0: return NAN;
    case 1: return INFINITY;
    default: return -INFINITY;
    }
}
/* Bad values for a field documented as [lo, hi] (lo may be 0 or negative). */
static float outside(float lo, float hi) {
    switch (rnd(6)) {
    case 0: return nonfinite();
    case 1: return hi * 1.01f + 1e-3f;
    case 2: return FLT_MAX;
    case 3: return lo >= 0 ? -1e-3f - lo : lo * 1.01f - 1e-3f;
    case 4: return lo > 0 ? lo * 0.5f : -FLT_MAX;
    default: return hi * 1e4f + 1.0f;
    }
}
/* Replaces one component of `v` by a bad value (NaN, infinite, huge). */
static HearthVec3 spoil3(HearthVec3 v, float bad) {
    switch (rnd(3)) {
    case 0: v.x = bad; break;
    case 1: v.y = bad; break;
    default: v.z = bad; break;
    }
    return v;
}
static uint8_t bad_flag(void) { return (uint8_t)(2 + rnd(254)); }
static uint8_t flag01(void) { return (uint8_t)rnd(2); }

/* ----------------------------------------------------------------------------------- ids */
typedef struct {
    uint32_t index, generation;
} Id;

#define ID_CONVERSIONS(T, name)                                                               \
    static T name(Id x) {                                                                     \
        T r;                                                                                  \
        r.index = x.index;                                                                    \
        r.generation = x.generation;                                                          \
        return r;                                                                             \
    }
ID_CONVERSIONS(HearthBodyId, body_id)
ID_CONVERSIONS(HearthShapeId, shape_id)
ID_CONVERSIONS(HearthJointId, joint_id)
ID_CONVERSIONS(HearthGeneratorId, gen_id)
ID_CONVERSIONS(HearthParticleId, particle_id)
ID_CONVERSIONS(HearthSoftBodyId, soft_id)
ID_CONVERSIONS(HearthHullId, hull_id)
ID_CONVERSIONS(HearthMeshId, mesh_id)
ID_CONVERSIONS(HearthHeightfieldId, hf_id)
#define TO_ID(x) id_of((x).index, (x).generation)
static Id id_of(uint32_t index, uint32_t generation) {
    Id r;
    r.index = index;
    r.generation = generation;
    return r;
}
static int id_eq(Id a, Id b) { return a.index == b.index && a.generation == b.generation; }
static const Id NULL_ID = {0, 0};

enum { K_BODY, K_SHAPE, K_JOINT, K_GEN, K_PARTICLE, K_SOFT, K_HULL, K_MESH, K_HF, K_COUNT };
static const int KIND_MAX[K_COUNT] = {40, 60, 24, 24, 300, 3, 4, 3, 3};
#define MAX_LIVE 300
#define DEAD_RING 64
#define MAX_ATTACH 16

typedef struct {
    Id id;
    uint32_t meta;   /* body and joint and generator type; soft body vertex count; a shape's
                      * geometry kind (0 primitive, else K_HULL, K_MESH, K_HF); a mesh's
                      * triangle count */
    Id a, b;         /* a shape's body and geometry; a joint's bodies (b null: the world) */
    Id att_bodies[MAX_ATTACH];
    int n_att_bodies;
    Id att_particles[MAX_ATTACH];
    int n_att_particles;
    Id dead_attached; /* the last attached particle that died (a stale id to detach) */
} Obj;

#define NWORLDS 3
typedef struct {
    HearthWorld *w;
    HearthWorldDef def;
    Obj live[K_COUNT][MAX_LIVE];
    int n[K_COUNT];
    int recording; /* a recording into fuzz_sink is running */
} FWorld;

static FWorld g_worlds[NWORLDS];
/* Ids of destroyed objects and of objects of destroyed worlds, by kind (a ring). */
static Id g_dead[K_COUNT][DEAD_RING];
static int g_ndead[K_COUNT];

static void bury(int kind, Id id) { g_dead[kind][g_ndead[kind]++ % DEAD_RING] = id; }

static int find(FWorld *fw, int kind, Id id) {
    for (int i = 0; i < fw->n[kind]; i++)
        if (id_eq(fw->live[kind][i].id, id)) return i;
    return -1;
}
static Obj *add(FWorld *fw, int kind, Id id) {
    Obj *o = &fw->live[kind][fw->n[kind]++];
    memset(o, 0, sizeof *o);
    o->id = id;
    return o;
}
static void drop_at(FWorld *fw, int kind, int i) {
    fw->live[kind][i] = fw->live[kind][--fw->n[kind]];
}
static int full(FWorld *fw, int kind) { return fw->n[kind] >= KIND_MAX[kind]; }
static Obj *pick(FWorld *fw, int kind) { return fw->n[kind] ? &fw->live[kind][rnd((uint32_t)fw->n[kind])] : NULL; }

static FWorld *live_world(void) {
    FWorld *c[NWORLDS];
    int n = 0;
    for (int i = 0; i < NWORLDS; i++)
        if (g_worlds[i].w) c[n++] = &g_worlds[i];
    return n ? c[rnd((uint32_t)n)] : NULL;
}

/* An id that must be refused with HEARTH_ERROR_INVALID_ID in `fw` (never one of its live
 * objects of that kind): null, destroyed, from another live or a destroyed world, garbage. */
static Id bad_id_any(FWorld *fw, int kind, int *which) {
    for (int tries = 0; tries < 8; tries++) {
        *which = (int)rnd(5);
        switch (*which) {
        case 0: return NULL_ID;
        case 1:
            if (g_ndead[kind]) {
                int n = g_ndead[kind] < DEAD_RING ? g_ndead[kind] : DEAD_RING;
                return g_dead[kind][rnd((uint32_t)n)];
            }
            break;
        case 2:
            for (int i = 0; i < NWORLDS; i++) {
                FWorld *o = &g_worlds[(i + rnd(NWORLDS)) % NWORLDS];
                if (o != fw && o->w && o->n[kind]) return o->live[kind][rnd((uint32_t)o->n[kind])].id;
            }
            break;
        case 3:
            /* An index of a live object with a generation no world hands out (tag 0). */
            if (fw->n[kind]) {
                Id x = fw->live[kind][rnd((uint32_t)fw->n[kind])].id;
                x.generation &= 0xFFFFFu;
                if (x.generation == 0) x.generation = 1;
                return x;
            }
            break;
        default: return id_of(rnd(1000), 1 + rnd(0xFFFFF));
        }
    }
    *which = 0;
    return NULL_ID;
}

static void fail(const char *what, const char *detail);
/* Set where a null id means something else (the world as a joint's body B). */
static int g_nonnull;

/* An id that must be refused with HEARTH_ERROR_INVALID_ID in `fw` (never one of its live
 * objects of that kind): null, destroyed, from another live or a destroyed world, garbage. */
static Id bad_id(FWorld *fw, int kind) {
    int which;
    Id x = bad_id_any(fw, kind, &which);
    if (g_nonnull && x.index == 0 && x.generation == 0) x = id_of(1 + rnd(100), 1 + rnd(0xFFFFF));
    if (find(fw, kind, x) >= 0) {
        char detail[128];
        snprintf(detail, sizeof detail, "a \"bad\" id {%u, %#x} (source %d) is live", x.index, x.generation, which);
        fail("fuzzer", detail);
        return NULL_ID;
    }
    return x;
}

/* ----------------------------------------------------------------- failures and context */
static uint64_t g_seed;
static long g_call;               /* calls made with this seed */
static const char *g_op = "";     /* the operation being fuzzed */
static int g_quiet_fail_budget = 40; /* stop printing after this many failures */

static void fail(const char *what, const char *detail) {
    g_failed++;
    if (g_quiet_fail_budget-- > 0) {
        char msg[4096];
        hearth_last_error_message(msg, sizeof msg);
        fprintf(stderr, "fuzz_api: FAILED seed %llu call %ld (%s): %s%s%s [last error: %s]\n",
                (unsigned long long)g_seed, g_call, g_op, what, detail[0] ? ": " : "", detail, msg);
    }
}
static void pass(void) { g_passed++; }

/* ------------------------------------------------------------- snapshots of every world */
typedef struct {
    unsigned char *data;
    size_t len, cap;
} Snap;

static void put(Snap *s, const void *p, size_t n) {
    if (s->len + n > s->cap) {
        size_t cap = s->cap ? s->cap * 2 : 4096;
        while (cap < s->len + n) cap *= 2;
        s->data = (unsigned char *)realloc(s->data, cap);
        s->cap = cap;
    }
    memcpy(s->data + s->len, p, n);
    s->len += n;
}

static HearthTransform g_xf_buf[MAX_LIVE];
static HearthBodyId g_body_buf[MAX_LIVE];
static HearthParticleId g_pid_buf[MAX_LIVE + 1];
static HearthVec3 g_pos_buf[MAX_LIVE + 1], g_vel_buf[MAX_LIVE + 1];
static HearthVec3 g_vert_buf[65 * 65 * 2];
/* Output buffers of the fuzzed calls (the snapshot buffers above are overwritten between a
 * call and the check of its outputs). */
static HearthTransform g_out_xf[MAX_LIVE + 1];
static HearthVec3 g_out_vec[65 * 65 * 2];
static HearthParticleId g_out_pid[MAX_LIVE + 1];

/* Everything a host can observe that a failing call must leave alone. Reads only; each read
 * must succeed (a failed read is itself a failure). */
static void snapshot(Snap *s) {
    s->len = 0;
    for (int wi = 0; wi < NWORLDS; wi++) {
        FWorld *fw = &g_worlds[wi];
        if (!fw->w) continue;
        HearthWorldCounters c;
        memset(&c, 0, sizeof c);
        if (hearth_world_get_counters(fw->w, &c) != HEARTH_OK) fail("snapshot", "get_counters");
        c.tree_height = 0; /* not state a call promises to keep */
        put(s, &c, sizeof c);
        HearthVec3 g;
        if (hearth_world_get_gravity(fw->w, &g) != HEARTH_OK) fail("snapshot", "get_gravity");
        put(s, &g, sizeof g);
        int nb = fw->n[K_BODY];
        for (int i = 0; i < nb; i++) g_body_buf[i] = body_id(fw->live[K_BODY][i].id);
        if (hearth_world_get_transforms(fw->w, g_body_buf, (size_t)nb, g_xf_buf) != HEARTH_OK)
            fail("snapshot", "get_transforms");
        put(s, g_xf_buf, sizeof(HearthTransform) * (size_t)nb);
        for (int i = 0; i < nb; i++) {
            HearthVec3 v, w;
            bool awake = false;
            float mass = 0;
            if (hearth_body_get_linear_velocity(fw->w, g_body_buf[i], &v) != HEARTH_OK ||
                hearth_body_get_angular_velocity(fw->w, g_body_buf[i], &w) != HEARTH_OK ||
                hearth_body_is_awake(fw->w, g_body_buf[i], &awake) != HEARTH_OK ||
                hearth_body_get_mass(fw->w, g_body_buf[i], &mass) != HEARTH_OK)
                fail("snapshot", "body getters");
            put(s, &v, sizeof v);
            put(s, &w, sizeof w);
            put(s, &awake, sizeof awake);
            put(s, &mass, sizeof mass);
        }
        size_t np = 0;
        if (hearth_world_get_particles(fw->w, g_pid_buf, g_pos_buf, g_vel_buf, MAX_LIVE + 1, &np) != HEARTH_OK)
            fail("snapshot", "get_particles");
        put(s, &np, sizeof np);
        put(s, g_pid_buf, sizeof(HearthParticleId) * np);
        put(s, g_pos_buf, sizeof(HearthVec3) * np);
        put(s, g_vel_buf, sizeof(HearthVec3) * np);
        size_t nsoft = 0;
        if (hearth_world_get_soft_body_count(fw->w, &nsoft) != HEARTH_OK) fail("snapshot", "soft count");
        put(s, &nsoft, sizeof nsoft);
        for (int i = 0; i < fw->n[K_SOFT]; i++) {
            HearthSoftBodyId sb = soft_id(fw->live[K_SOFT][i].id);
            size_t n = 0;
            HearthSoftBodySettings st;
            memset(&st, 0, sizeof st); /* padding bytes are compared too */
            float pressure = 0;
            if (hearth_soft_body_get_positions(fw->w, sb, g_vert_buf, sizeof g_vert_buf / sizeof g_vert_buf[0], &n) !=
                    HEARTH_OK ||
                hearth_soft_body_get_settings(fw->w, sb, &st) != HEARTH_OK ||
                hearth_soft_body_get_pressure(fw->w, sb, &pressure) != HEARTH_OK)
                fail("snapshot", "soft body getters");
            put(s, g_vert_buf, sizeof(HearthVec3) * n);
            put(s, &st, sizeof st);
            put(s, &pressure, sizeof pressure);
        }
        for (int i = 0; i < fw->n[K_GEN]; i++) {
            uint32_t b = 0, p = 0;
            if (hearth_generator_get_attachment_count(fw->w, gen_id(fw->live[K_GEN][i].id), &b, &p) != HEARTH_OK)
                fail("snapshot", "attachment count");
            put(s, &b, sizeof b);
            put(s, &p, sizeof p);
        }
        for (int i = 0; i < fw->n[K_JOINT]; i++) {
            HearthJointId j = joint_id(fw->live[K_JOINT][i].id);
            bool broken = false, en = false;
            float lo = 0, hi = 0;
            if (hearth_joint_is_broken(fw->w, j, &broken) != HEARTH_OK) fail("snapshot", "joint is_broken");
            put(s, &broken, sizeof broken);
            if (fw->live[K_JOINT][i].meta != HEARTH_JOINT_FIXED) {
                if (hearth_joint_get_limits(fw->w, j, &en, &lo, &hi) != HEARTH_OK) fail("snapshot", "joint limits");
                put(s, &en, sizeof en);
                put(s, &lo, sizeof lo);
                put(s, &hi, sizeof hi);
            }
        }
    }
}

static Snap g_before, g_after;

/* --------------------------------------------------------------------- the call checker */
/* Output sentinels: every output is filled with this byte before a call; a failing call
 * must leave it so. */
#define SENTINEL 0xA5 /* as `untouched` (ensure.h) checks */

static int g_locked; /* inside a callback: no snapshots, the world is mid-step */
static int g_trace;  /* HEARTH_FUZZ_TRACE=1: every call on stderr */

/* Takes the "before" snapshot when the call is expected to fail. */
static void pre(HearthResult expected) {
    if (expected != HEARTH_OK && !g_locked) snapshot(&g_before);
}

/* Checks a call's result against the expected one. `field`: for a bad number, a word the
 * message must contain. `out`/`out_len`: an output that must be unwritten on failure. */
static void mark(const char *call);
static void post(const char *call, HearthResult got, HearthResult expected, const char *field, const void *out,
                 size_t out_len) {
    g_call++;
    mark(call);
    if (g_trace) fprintf(stderr, "%ld %s -> %s\n", g_call, call, hearth_result_name(got));
    char detail[600];
    if (got == HEARTH_ERROR_PANIC) {
        snprintf(detail, sizeof detail, "%s returned HEARTH_ERROR_PANIC (expected %s)", call,
                 hearth_result_name(expected));
        fail("panic", detail);
        return;
    }
    if (got != expected) {
        snprintf(detail, sizeof detail, "%s returned %s, expected %s", call, hearth_result_name(got),
                 hearth_result_name(expected));
        fail("result", detail);
        return;
    }
    pass();
    if (got == HEARTH_OK) return;
    char msg[512];
    size_t n = hearth_last_error_message(msg, sizeof msg);
    if (n == 0 || msg[0] == 0) fail("message", call);
    if (field && got == HEARTH_ERROR_INVALID_ARGUMENT && !strstr(msg, field)) {
        snprintf(detail, sizeof detail, "%.200s: the message \"%.250s\" does not name %s", call, msg, field);
        fail("message names the parameter", detail);
    }
    if (out && !untouched(out, out_len)) {
        snprintf(detail, sizeof detail, "%s wrote its output although it failed", call);
        fail("outputs", detail);
    }
    if (!g_locked) {
        snapshot(&g_after);
        if (g_after.len != g_before.len || memcmp(g_after.data, g_before.data, g_before.len) != 0) {
            size_t at = 0;
            while (at < g_before.len && at < g_after.len && g_before.data[at] == g_after.data[at]) at++;
            snprintf(detail, sizeof detail, "%s failed (%s) but changed the state of a world (snapshot byte %zu of %zu)",
                     call, hearth_result_name(got), at, g_before.len);
            fail("failing call changed nothing", detail);
        }
    }
}

/* CALL(expr, expected, field, out, out_len): runs one checked call; `r` holds its result. */
#define CALL(expr, expected, field, out, out_len)                                           \
    HearthResult exp_ = (expected);                                                         \
    pre(exp_);                                                                              \
    HearthResult r = (expr);                                                                \
    post(#expr, r, exp_, field, out, out_len)

/* ------------------------------------------------------------- finiteness and the limits */
static int finite3(HearthVec3 v) { return isfinite(v.x) && isfinite(v.y) && isfinite(v.z); }

/* The world's speed limit for bodies, particles and soft-body vertices (the solver caps
 * speeds at it; rounding may put a capped speed a few ulps above). */
static float speed_limit(const FWorld *fw) { return fw->def.max_linear_speed * 1.0001f + 1e-4f; }
/* The world's angular speed limit: what a host may set and what the solver caps at. */
static float angular_limit(const FWorld *fw) { return fw->def.max_angular_speed * 1.0001f + 1e-4f; }

/* What a world holds, printed with the first failure of its state. */
static void dump_world(FWorld *fw) {
    const HearthWorldDef *d = &fw->def;
    fprintf(stderr, "  world: gravity (%g %g %g) substeps %u integrator %u sleep %u max speed %g hertz %g zeta %g push %g\n",
            d->gravity.x, d->gravity.y, d->gravity.z, d->substeps, d->integrator, d->enable_sleep, d->max_linear_speed,
            d->contact_hertz, d->contact_damping_ratio, d->contact_push_max_velocity);
    fprintf(stderr, "  %d bodies, %d shapes, %d joints, %d generators, %d particles, %d soft bodies\n", fw->n[K_BODY],
            fw->n[K_SHAPE], fw->n[K_JOINT], fw->n[K_GEN], fw->n[K_PARTICLE], fw->n[K_SOFT]);
    for (int i = 0; i < fw->n[K_BODY]; i++) {
        HearthBodyId b = body_id(fw->live[K_BODY][i].id);
        HearthTransform t;
        HearthVec3 v, w;
        float m = 0;
        int ns = 0, nj = 0;
        hearth_body_get_transform(fw->w, b, &t);
        hearth_body_get_linear_velocity(fw->w, b, &v);
        hearth_body_get_angular_velocity(fw->w, b, &w);
        hearth_body_get_mass(fw->w, b, &m);
        for (int k = 0; k < fw->n[K_SHAPE]; k++) ns += id_eq(fw->live[K_SHAPE][k].a, TO_ID(b));
        for (int k = 0; k < fw->n[K_JOINT]; k++) nj += id_eq(fw->live[K_JOINT][k].a, TO_ID(b)) || id_eq(fw->live[K_JOINT][k].b, TO_ID(b));
        fprintf(stderr, "  body %u type %u mass %g shapes %d joints %d p (%g %g %g) v (%g %g %g) w (%g %g %g)\n", b.index,
                fw->live[K_BODY][i].meta, m, ns, nj, t.position.x, t.position.y, t.position.z, v.x, v.y, v.z, w.x, w.y, w.z);
    }
    for (int k = 0; k < fw->n[K_JOINT]; k++)
        fprintf(stderr, "  joint type %u bodies %u %u\n", fw->live[K_JOINT][k].meta, fw->live[K_JOINT][k].a.index,
                fw->live[K_JOINT][k].b.generation ? fw->live[K_JOINT][k].b.index : 9999);
    for (int k = 0; k < fw->n[K_GEN]; k++)
        fprintf(stderr, "  generator type %u bodies %d particles %d\n", fw->live[K_GEN][k].meta,
                fw->live[K_GEN][k].n_att_bodies, fw->live[K_GEN][k].n_att_particles);
}

/* Set when a world's state broke (reported once); the run replaces the world. */
static FWorld *g_broken;

static void check_state(FWorld *fw, const char *when) {
    char detail[256];
    int before = g_failed;
    for (int i = 0; i < fw->n[K_BODY]; i++) {
        HearthBodyId b = body_id(fw->live[K_BODY][i].id);
        HearthTransform t;
        HearthVec3 v, w;
        if (hearth_body_get_transform(fw->w, b, &t) != HEARTH_OK ||
            hearth_body_get_linear_velocity(fw->w, b, &v) != HEARTH_OK ||
            hearth_body_get_angular_velocity(fw->w, b, &w) != HEARTH_OK) {
            fail("state", "a live body cannot be read");
            continue;
        }
        HearthQuat q = t.rotation;
        float qn = sqrtf(q.x * q.x + q.y * q.y + q.z * q.z + q.w * q.w);
        if (!finite3(t.position) || !isfinite(qn) || fabsf(qn - 1) > 1e-3f || !finite3(v) || !finite3(w)) {
            snprintf(detail, sizeof detail, "%s: body %u: position (%g %g %g) |q| %g v (%g %g %g) w (%g %g %g)", when,
                     b.index, t.position.x, t.position.y, t.position.z, qn, v.x, v.y, v.z, w.x, w.y, w.z);
            fail("a body state is not finite", detail);
        } else if (len3(v) > speed_limit(fw) || len3(w) > angular_limit(fw)) {
            uint32_t type = fw->live[K_BODY][i].meta;
            snprintf(detail, sizeof detail, "%s: body %u (type %u): |v| %g (limit %g), |w| %g", when, b.index, type,
                     len3(v), fw->def.max_linear_speed, len3(w));
            fail("a body is faster than the limit", detail);
        } else {
            pass();
        }
    }
    size_t np = 0;
    if (hearth_world_get_particles(fw->w, g_pid_buf, g_pos_buf, g_vel_buf, MAX_LIVE + 1, &np) != HEARTH_OK) {
        fail("state", "particles cannot be read");
        np = 0;
    }
    for (size_t i = 0; i < np; i++) {
        if (!finite3(g_pos_buf[i]) || !finite3(g_vel_buf[i]) || len3(g_vel_buf[i]) > speed_limit(fw)) {
            snprintf(detail, sizeof detail, "%s: particle %u: p (%g %g %g) v (%g %g %g)", when, g_pid_buf[i].index,
                     g_pos_buf[i].x, g_pos_buf[i].y, g_pos_buf[i].z, g_vel_buf[i].x, g_vel_buf[i].y, g_vel_buf[i].z);
            fail("a particle is not finite or too fast", detail);
            break;
        }
    }
    for (int i = 0; i < fw->n[K_SOFT]; i++) {
        HearthSoftBodyId sb = soft_id(fw->live[K_SOFT][i].id);
        size_t n = 0;
        if (hearth_soft_body_get_positions(fw->w, sb, g_vert_buf, sizeof g_vert_buf / sizeof g_vert_buf[0], &n) !=
            HEARTH_OK) {
            fail("state", "soft body positions cannot be read");
            continue;
        }
        for (size_t k = 0; k < n; k++) {
            HearthVec3 v = vec(0, 0, 0);
            int bad = !finite3(g_vert_buf[k]);
            if (!bad && k % 7 == 0) {
                if (hearth_soft_body_get_vertex_velocity(fw->w, sb, (uint32_t)k, &v) != HEARTH_OK) bad = 1;
                else bad = !finite3(v) || len3(v) > speed_limit(fw);
            }
            if (bad) {
                snprintf(detail, sizeof detail, "%s: soft body %u vertex %u at (%g %g %g) speed %g", when, sb.index,
                         (unsigned)k, g_vert_buf[k].x, g_vert_buf[k].y, g_vert_buf[k].z, k % 7 == 0 ? len3(v) : -1.0f);
                fail("a soft-body vertex is not finite or too fast", detail);
                break;
            }
        }
    }
    if (g_failed != before) {
        if (g_broken != fw && g_quiet_fail_budget > 0) dump_world(fw);
        g_broken = fw;
    }
}

/* ---------------------------------------------------------------------------- worlds */
typedef enum { F_NONE, F_NULL_WORLD, F_NULL_IN, F_NULL_OUT, F_COOKIE, F_ID, F_NUMBER, F_FLAG, F_CODE } Fault;

/* No fault most of the time; otherwise one of the listed kinds. */
static Fault fault_of(int n, const Fault *kinds) {
    if (chance(55) || n == 0) return F_NONE;
    return kinds[rnd((uint32_t)n)];
}
#define FAULTS(...)                                                                         \
    const Fault kinds_[] = {__VA_ARGS__};                                                   \
    Fault f = fault_of((int)(sizeof kinds_ / sizeof kinds_[0]), kinds_)

/* Forgets a world's objects: their ids become ids of a destroyed world. */
static void forget_world(FWorld *fw) {
    for (int k = 0; k < K_COUNT; k++) {
        for (int i = 0; i < fw->n[k]; i++) bury(k, fw->live[k][i].id);
        fw->n[k] = 0;
    }
    fw->w = NULL;
}

/* A job system that runs a task at once, in two ranges, the second first (enqueue returns
 * NULL: done), or defers it to finish (enqueue returns a handle). */
typedef struct { HearthTaskFn task; uint32_t count; void *ctx; } FuzzTask;
static FuzzTask g_fuzz_task;
static void *fuzz_enqueue(HearthTaskFn task, uint32_t count, uint32_t min_range, void *ctx, void *user) {
    (void)min_range;
    if (user) {
        g_fuzz_task.task = task; g_fuzz_task.count = count; g_fuzz_task.ctx = ctx;
        return &g_fuzz_task;
    }
    uint32_t half = count / 2;
    if (half < count) task(half, count, 1, ctx);
    if (half > 0) task(0, half, 0, ctx);
    return NULL;
}
static void fuzz_finish(void *user_task, void *user) {
    (void)user;
    FuzzTask *t = (FuzzTask *)user_task;
    t->task(0, t->count, 0, t->ctx);
}

static HearthWorldDef good_world_def(void) {
    HearthWorldDef d = hearth_world_def_default();
    if (chance(50)) return d;
    switch (rnd(4)) {
    case 0: d.gravity = vec_up_to(MAX_ACCELERATION, 30); break;
    case 1: d.gravity = vec(0, -9.81f, 0); break;
    default: break;
    }
    if (chance(30)) d.substeps = 1 + rnd(64);
    if (chance(20)) d.integrator = HEARTH_INTEGRATOR_RK4;
    if (chance(20)) d.enable_sleep = 0;
    if (chance(20)) d.max_linear_speed = chance(50) ? MAX_SPEED : flog(1.0f, MAX_SPEED);
    if (chance(20)) d.max_angular_speed = chance(50) ? MAX_ANGULAR_SPEED : flog(1e-3f, MAX_ANGULAR_SPEED);
    if (chance(10)) d.velocity_iterations = 1 + rnd(8);
    if (chance(10)) d.sleep_threshold = frange(0, 1);
    if (chance(10)) d.contact_hertz = flog(1.0f, 1e4f);
    if (chance(10)) d.contact_damping_ratio = frange(0, 100);
    if (chance(10)) d.contact_push_max_velocity = flog(0.01f, 100);
    if (chance(10)) d.restitution_threshold = frange(0, 10);
    if (chance(10)) d.time_to_sleep = frange(0, 5);
    if (chance(10)) d.worker_count = 1 + rnd(3);
    if (chance(10)) {
        d.worker_count = 2;
        d.enqueue_task = fuzz_enqueue;
        d.finish_task = fuzz_finish;
        d.user_task_context = chance(50) ? &g_fuzz_task : NULL;
    }
    return d;
}

/* One bad field of a world def; returns the name the message must contain. */
static const char *spoil_world_def(HearthWorldDef *d, Fault f) {
    if (f == F_FLAG) { d->enable_sleep = bad_flag(); return "enable_sleep"; }
    if (f == F_CODE) { d->integrator = 2 + rnd(1000); return "integrator"; }
    switch (rnd(13)) {
    case 10: d->worker_count = chance(50) ? 0 : 65 + rnd(1000); return "worker_count";
    case 11:
        if (chance(50)) { d->enqueue_task = fuzz_enqueue; d->finish_task = NULL; return "finish_task"; }
        d->enqueue_task = NULL; d->finish_task = fuzz_finish; return "enqueue_task";
    case 9: d->max_angular_speed = outside(1e-3f, MAX_ANGULAR_SPEED); return "max_angular_speed";
    case 0: d->gravity = chance(50) ? spoil3(d->gravity, nonfinite()) : scale3(dir3(), MAX_ACCELERATION * (1.01f + unit())); return "gravity";
    case 1: d->substeps = chance(50) ? 0 : 65 + rnd(1000); return "substeps";
    case 2: d->velocity_iterations = chance(50) ? 0 : 65 + rnd(100); return "velocity_iterations";
    case 3: d->sleep_threshold = outside(0, MAX_SPEED); return "sleep_threshold";
    case 4: d->time_to_sleep = chance(50) ? -1.0f : nonfinite(); if (d->time_to_sleep == INFINITY) d->time_to_sleep = NAN; return "time_to_sleep";
    case 5: d->contact_hertz = outside(1e-3f, 1e6f); return "contact_hertz";
    case 6: d->contact_damping_ratio = outside(0, 1e3f); return "contact_damping_ratio";
    case 7: d->contact_push_max_velocity = outside(1e-6f, MAX_SPEED); return "contact_push_max_velocity";
    case 8: d->restitution_threshold = outside(0, MAX_SPEED); return "restitution_threshold";
    default: d->max_linear_speed = outside(1e-3f, MAX_SPEED); return "max_linear_speed";
    }
}

static void op_world_create(void) {
    FWorld *fw = NULL;
    for (int i = 0; i < NWORLDS; i++)
        if (!g_worlds[i].w) fw = &g_worlds[i];
    if (!fw) return;
    FAULTS(F_NULL_IN, F_NULL_OUT, F_COOKIE, F_NUMBER, F_FLAG, F_CODE);
    HearthWorldDef d = good_world_def();
    const char *field = NULL;
    if (f == F_COOKIE) d.internal_value ^= 1u + rnd(0xFFFF);
    if (f == F_NUMBER || f == F_FLAG || f == F_CODE) field = spoil_world_def(&d, f);
    HearthWorld *w;
    memset(&w, SENTINEL, sizeof w);
    HearthResult expected = f == F_NONE ? HEARTH_OK
                            : (f == F_NULL_IN || f == F_NULL_OUT) ? HEARTH_ERROR_NULL_POINTER
                                                                  : HEARTH_ERROR_INVALID_ARGUMENT;
    {
        CALL(hearth_world_create(f == F_NULL_IN ? NULL : &d, f == F_NULL_OUT ? NULL : &w), expected, field, &w,
             sizeof w);
        if (r == HEARTH_OK) {
            memset(fw, 0, sizeof *fw);
            fw->w = w;
            fw->def = d;
        }
    }
}

static void op_world_destroy(void) {
    if (chance(20)) {
        hearth_world_destroy(NULL); /* a no-op */
        pass();
        return;
    }
    FWorld *fw = live_world();
    if (!fw) return;
    mark("hearth_world_destroy");
    hearth_world_destroy(fw->w);
    forget_world(fw);
    pass();
}

static void after_step(FWorld *fw, size_t before_count, const HearthParticleId *before_ids);

static float good_dt(void) {
    switch (rnd(10)) {
    case 0: return MIN_TIME_STEP;
    case 1: return MAX_TIME_STEP;
    case 2: return 0.0f;
    case 3: return flog(MIN_TIME_STEP, MAX_TIME_STEP);
    default: return 1.0f / 60.0f;
    }
}
static float bad_dt(void) {
    switch (rnd(8)) {
    case 0: return 1e-20f;
    case 1: return 1e-40f; /* denormal */
    case 2: return MIN_TIME_STEP * 0.9f;
    case 3: return MAX_TIME_STEP * 1.5f;
    case 4: return 1e6f;
    case 5: return -1.0f / 60.0f;
    case 6: return -MIN_TIME_STEP;
    default: return nonfinite();
    }
}

static HearthParticleId g_step_ids[MAX_LIVE + 1];

static void op_world_step(void) {
    FWorld *fw = live_world();
    if (!fw) return;
    FAULTS(F_NULL_WORLD, F_NUMBER);
    float dt = f == F_NUMBER ? bad_dt() : good_dt();
    size_t np = (size_t)fw->n[K_PARTICLE];
    for (size_t i = 0; i < np; i++) g_step_ids[i] = particle_id(fw->live[K_PARTICLE][i].id);
    HearthResult expected = f == F_NULL_WORLD ? HEARTH_ERROR_NULL_POINTER
                            : f == F_NUMBER   ? HEARTH_ERROR_INVALID_ARGUMENT
                                              : HEARTH_OK;
    {
        CALL(hearth_world_step(f == F_NULL_WORLD ? NULL : fw->w, dt), expected, "dt", NULL, 0);
        if (r == HEARTH_OK) after_step(fw, np, g_step_ids);
        if (r == HEARTH_ERROR_PANIC) g_broken = fw; /* reported; the world refuses to step again */
    }
}

static void forget_particle_everywhere(FWorld *fw, Id p) {
    for (int g = 0; g < fw->n[K_GEN]; g++) {
        Obj *o = &fw->live[K_GEN][g];
        for (int k = 0; k < o->n_att_particles; k++)
            if (id_eq(o->att_particles[k], p)) {
                o->dead_attached = p;
                o->att_particles[k--] = o->att_particles[--o->n_att_particles];
            }
    }
}

/* After a successful step: the particles that vanished are exactly the expired ones. */
static void after_step(FWorld *fw, size_t before_count, const HearthParticleId *before_ids) {
    const HearthExpiredParticle *expired = NULL;
    size_t nexp = 0;
    if (hearth_world_get_expired_particles(fw->w, &expired, &nexp) != HEARTH_OK) fail("step", "expired report");
    size_t np = 0;
    if (hearth_world_get_particles(fw->w, g_pid_buf, NULL, NULL, MAX_LIVE + 1, &np) != HEARTH_OK)
        fail("step", "get_particles");
    for (size_t i = 0; i < before_count; i++) {
        Id p = TO_ID(before_ids[i]);
        int alive = 0, reported = 0;
        for (size_t k = 0; k < np; k++) alive |= id_eq(TO_ID(g_pid_buf[k]), p);
        for (size_t k = 0; k < nexp; k++) reported |= id_eq(TO_ID(expired[k].id), p);
        if (!alive && !reported) fail("step", "a particle vanished without being reported as expired");
        if (alive && reported) fail("step", "a particle was reported expired but is alive");
        if (!alive) {
            int j = find(fw, K_PARTICLE, p);
            if (j >= 0) drop_at(fw, K_PARTICLE, j);
            forget_particle_everywhere(fw, p);
            bury(K_PARTICLE, p);
        }
    }
    if ((size_t)fw->n[K_PARTICLE] != np) fail("step", "particles appeared during the step");
    size_t nbroken = 0;
    if (hearth_world_get_broken_joints(fw->w, NULL, 0, &nbroken) != HEARTH_OK) fail("step", "broken joints count");
    check_state(fw, "after a step");
}

/* ------------------------------------------------------------------------- callbacks */
static FWorld *world_of(HearthWorld *w) {
    for (int i = 0; i < NWORLDS; i++)
        if (g_worlds[i].w == w) return &g_worlds[i];
    return NULL;
}

static void force_callback(void *user_data, HearthWorld *world, const HearthGeneratorContext *ctx) {
    FWorld *fw = (FWorld *)user_data;
    const char *saved = g_op;
    g_op = "user force callback";
    g_locked = 1;
    if (world_of(world) != fw || !ctx) fail("callback", "wrong world or context");
    for (int k = 0; k < 2; k++) {
        HearthBodyId b = ctx->body_count ? ctx->bodies[rnd((uint32_t)ctx->body_count)] : body_id(bad_id(fw, K_BODY));
        HearthResult valid_body = ctx->body_count ? HEARTH_OK : HEARTH_ERROR_INVALID_ID;
        switch (rnd(9)) {
        case 0: { CALL(hearth_body_apply_force(world, b, vec_up_to(MAX_FORCE, 100)), valid_body, NULL, NULL, 0); break; }
        case 1: { CALL(hearth_body_apply_torque(world, b, vec_up_to(MAX_FORCE, 10)), valid_body, NULL, NULL, 0); break; }
        case 2: { CALL(hearth_body_apply_force_at_point(world, b, vec_up_to(MAX_FORCE, 100), vec(frange(-5, 5), frange(-5, 5), frange(-5, 5))), valid_body, NULL, NULL, 0); break; }
        case 3: {
            HearthVec3 bad = spoil3(vec(0, 0, 0), nonfinite());
            /* The number is checked first. */
            CALL(hearth_body_apply_force(world, b, bad), HEARTH_ERROR_INVALID_ARGUMENT, "force", NULL, 0);
            break;
        }
        case 4: {
            if (!ctx->particle_count) break;
            HearthParticleId p = ctx->particles[rnd((uint32_t)ctx->particle_count)];
            CALL(hearth_particle_apply_force(world, p, vec_up_to(MAX_FORCE, 10)), HEARTH_OK, NULL, NULL, 0);
            break;
        }
        case 5: {
            HearthBodyDef d = hearth_body_def_default();
            HearthBodyId out;
            memset(&out, SENTINEL, sizeof out);
            CALL(hearth_body_create(world, &d, &out), HEARTH_ERROR_WORLD_LOCKED, NULL, &out, sizeof out);
            break;
        }
        case 6: { CALL(hearth_world_step(world, 1.0f / 60.0f), HEARTH_ERROR_WORLD_LOCKED, NULL, NULL, 0); break; }
        case 7: { CALL(hearth_body_apply_linear_impulse(world, b, vec(0, 1, 0)), HEARTH_ERROR_WORLD_LOCKED, NULL, NULL, 0); break; }
        default: {
            hearth_world_destroy(world); /* ignored inside a callback */
            HearthTransform t;
            memset(&t, SENTINEL, sizeof t);
            CALL(hearth_body_get_transform(world, b, &t), valid_body, NULL, &t, sizeof t);
            break;
        }
        }
    }
    g_locked = 0;
    g_op = saved;
}

/* A contact between live objects of the world (at least one body or particle). */
static HearthGeneratedContact good_contact(FWorld *fw) {
    HearthGeneratedContact c;
    memset(&c, 0, sizeof c);
    Obj *b1 = pick(fw, K_BODY), *b2 = pick(fw, K_BODY);
    Obj *p1 = pick(fw, K_PARTICLE), *p2 = pick(fw, K_PARTICLE);
    if (p1 && (chance(40) || !b1)) c.particle_a = particle_id(p1->id);
    else if (b1) c.body_a = body_id(b1->id);
    switch (rnd(3)) {
    case 0: break; /* the world */
    case 1:
        if (b2 && !(b1 && id_eq(b2->id, TO_ID(c.body_a)))) c.body_b = body_id(b2->id);
        break;
    default:
        if (p2 && !id_eq(p2->id, TO_ID(c.particle_a))) c.particle_b = particle_id(p2->id);
        break;
    }
    c.point = vec(frange(-5, 5), frange(-1, 5), frange(-5, 5));
    c.normal = scale3(dir3(), frange(0.5f, 2));
    c.penetration = frange(-0.05f, 0.05f);
    c.restitution = frange(0, 1);
    c.friction = frange(0, 1);
    return c;
}

static void contact_callback(void *user_data, HearthWorld *world, const HearthGeneratorContext *ctx,
                             HearthContactSink *sink) {
    FWorld *fw = (FWorld *)user_data;
    const char *saved = g_op;
    g_op = "user contact callback";
    g_locked = 1;
    if (world_of(world) != fw || !ctx || !sink) fail("callback", "wrong world, context or sink");
    int tries = (int)rnd(4);
    for (int k = 0; k < tries; k++) {
        uint32_t count = 0, capacity = 0;
        {
            CALL(hearth_contact_sink_get_count(sink, &count, &capacity), HEARTH_OK, NULL, NULL, 0);
        }
        HearthGeneratedContact c = good_contact(fw);
        int has_object = c.body_a.generation || c.particle_a.generation;
        if (!has_object) break;
        HearthResult expected = count < capacity ? HEARTH_OK : HEARTH_ERROR_BUFFER_TOO_SMALL;
        const char *field = NULL;
        switch (rnd(8)) {
        case 0: c.normal = chance(50) ? vec(0, 0, 0) : spoil3(c.normal, nonfinite()); expected = HEARTH_ERROR_INVALID_ARGUMENT; field = "normal"; break;
        case 1: c.penetration = nonfinite(); expected = HEARTH_ERROR_INVALID_ARGUMENT; field = "penetration"; break;
        case 2: c.restitution = -1.0f; expected = HEARTH_ERROR_INVALID_ARGUMENT; field = "restitution"; break;
        case 3: c.body_a = body_id(bad_id(fw, K_BODY)); c.particle_a = particle_id(NULL_ID);
            expected = c.body_a.generation ? HEARTH_ERROR_INVALID_ID : (c.body_b.generation || c.particle_b.generation) ? expected : HEARTH_ERROR_INVALID_ARGUMENT;
            break;
        case 4: {
            Obj *b = pick(fw, K_BODY);
            if (b) { CALL(hearth_body_apply_force(world, body_id(b->id), vec(0, 1, 0)), HEARTH_ERROR_WORLD_LOCKED, NULL, NULL, 0); }
            continue;
        }
        default: break;
        }
        {
            int null_sink = chance(5);
            if (null_sink) expected = HEARTH_ERROR_NULL_POINTER;
            CALL(hearth_contact_sink_add(null_sink ? NULL : sink, &c), expected, field, NULL, 0);
            (void)r;
        }
    }
    g_locked = 0;
    g_op = saved;
}

/* ---------------------------------------------------------------------------- bodies */
static HearthVec3 good_position(void) {
    switch (rnd(8)) {
    case 0: return vec(frange(-MAX_COORDINATE, MAX_COORDINATE), frange(-MAX_COORDINATE, MAX_COORDINATE), frange(-MAX_COORDINATE, MAX_COORDINATE));
    case 1: return vec(MAX_COORDINATE, -MAX_COORDINATE, 0);
    default: return vec(frange(-10, 10), frange(0, 10), frange(-10, 10));
    }
}
static HearthVec3 bad_position(void) {
    HearthVec3 p = good_position();
    return spoil3(p, chance(50) ? nonfinite() : (chance(50) ? 1.01f : -1.01f) * MAX_COORDINATE);
}
static HearthQuat bad_quat(void) {
    HearthQuat q = quat_any();
    switch (rnd(3)) {
    case 0: q.x = q.y = q.z = q.w = 0; break;
    case 1: q.y = nonfinite(); break;
    default: q.x = q.y = q.z = q.w = 1e-9f; break;
    }
    return q;
}

static void destroyed_body(FWorld *fw, Id b) {
    int i = find(fw, K_BODY, b);
    if (i >= 0) drop_at(fw, K_BODY, i);
    bury(K_BODY, b);
    for (int s = 0; s < fw->n[K_SHAPE]; s++)
        if (id_eq(fw->live[K_SHAPE][s].a, b)) { bury(K_SHAPE, fw->live[K_SHAPE][s].id); drop_at(fw, K_SHAPE, s--); }
    for (int j = 0; j < fw->n[K_JOINT]; j++)
        if (id_eq(fw->live[K_JOINT][j].a, b) || id_eq(fw->live[K_JOINT][j].b, b)) { bury(K_JOINT, fw->live[K_JOINT][j].id); drop_at(fw, K_JOINT, j--); }
    for (int g = 0; g < fw->n[K_GEN]; g++) {
        Obj *o = &fw->live[K_GEN][g];
        for (int k = 0; k < o->n_att_bodies; k++)
            if (id_eq(o->att_bodies[k], b)) o->att_bodies[k--] = o->att_bodies[--o->n_att_bodies];
    }
}

static void op_body_create(FWorld *fw) {
    if (full(fw, K_BODY)) return;
    FAULTS(F_NULL_WORLD, F_NULL_IN, F_NULL_OUT, F_COOKIE, F_NUMBER, F_FLAG, F_CODE);
    HearthBodyDef d = hearth_body_def_default();
    d.type = rnd(5) == 0 ? HEARTH_BODY_STATIC : rnd(6) == 0 ? HEARTH_BODY_KINEMATIC : HEARTH_BODY_DYNAMIC;
    d.transform = xf(good_position(), quat_any());
    if (chance(30)) d.linear_velocity = vec_up_to(fw->def.max_linear_speed, 5);
    if (chance(30)) d.angular_velocity = vec_up_to(fw->def.max_angular_speed, 5);
    if (chance(20)) d.linear_damping = chance(50) ? MAX_DAMPING : frange(0, 2);
    if (chance(20)) d.angular_damping = chance(50) ? MAX_DAMPING : frange(0, 2);
    if (chance(20)) d.gravity_scale = frange(-MAX_GRAVITY_SCALE, MAX_GRAVITY_SCALE);
    if (chance(20)) d.allow_sleep = 0;
    if (chance(10)) d.is_awake = 0;
    if (chance(10)) d.locked_axes = rnd(64);
    d.user_data = next_u64();
    const char *field = NULL;
    switch (f) {
    case F_COOKIE: d.internal_value = rnd(2) ? 0 : (uint32_t)next_u64(); if (d.internal_value == hearth_body_def_default().internal_value) d.internal_value++; break;
    case F_FLAG: if (chance(50)) { d.allow_sleep = bad_flag(); field = "allow_sleep"; } else { d.is_awake = bad_flag(); field = "is_awake"; } break;
    case F_CODE: if (chance(50)) { d.type = 3 + rnd(100000); field = "type"; } else { d.locked_axes = (64u << rnd(26)) | rnd(64); field = "locked_axes"; } break;
    case F_NUMBER:
        switch (rnd(7)) {
        case 0: d.transform.position = bad_position(); field = "position"; break;
        case 1: d.transform.rotation = bad_quat(); field = "rotation"; break;
        case 2: d.linear_velocity = chance(50) ? spoil3(d.linear_velocity, nonfinite()) : scale3(dir3(), fw->def.max_linear_speed * 1.01f); field = "linear_velocity"; break;
        case 3: d.angular_velocity = chance(50) ? spoil3(d.angular_velocity, nonfinite()) : scale3(dir3(), fw->def.max_angular_speed * 1.01f + 1e-3f); field = "angular_velocity"; break;
        case 4: d.linear_damping = outside(0, MAX_DAMPING); field = "linear_damping"; break;
        case 5: d.angular_damping = outside(0, MAX_DAMPING); field = "angular_damping"; break;
        default: d.gravity_scale = outside(-MAX_GRAVITY_SCALE, MAX_GRAVITY_SCALE); field = "gravity_scale"; break;
        }
        break;
    default: break;
    }
    HearthBodyId out;
    memset(&out, SENTINEL, sizeof out);
    HearthResult expected = f == F_NONE ? HEARTH_OK
                            : (f == F_NULL_WORLD || f == F_NULL_IN || f == F_NULL_OUT) ? HEARTH_ERROR_NULL_POINTER
                                                                                      : HEARTH_ERROR_INVALID_ARGUMENT;
    CALL(hearth_body_create(f == F_NULL_WORLD ? NULL : fw->w, f == F_NULL_IN ? NULL : &d, f == F_NULL_OUT ? NULL : &out),
         expected, field, &out, sizeof out);
    if (r == HEARTH_OK) add(fw, K_BODY, TO_ID(out))->meta = d.type;
}

/* A live body of `fw`, or (fault F_ID) a bad id; NULL world for F_NULL_WORLD. Returns the
 * result the id alone leads to. */
static HearthResult target_body(FWorld *fw, Fault f, HearthBodyId *out, Obj **obj) {
    *obj = NULL;
    if (f == F_NULL_WORLD) {
        *out = fw->n[K_BODY] ? body_id(pick(fw, K_BODY)->id) : body_id(NULL_ID);
        return HEARTH_ERROR_NULL_POINTER;
    }
    if (f == F_ID || fw->n[K_BODY] == 0) {
        *out = body_id(bad_id(fw, K_BODY));
        return HEARTH_ERROR_INVALID_ID;
    }
    *obj = pick(fw, K_BODY);
    *out = body_id((*obj)->id);
    return HEARTH_OK;
}
#define W(fw, f) ((f) == F_NULL_WORLD ? NULL : (fw)->w)

static void op_body_destroy(FWorld *fw) {
    FAULTS(F_NULL_WORLD, F_ID);
    HearthBodyId b;
    Obj *o;
    HearthResult expected = target_body(fw, f, &b, &o);
    CALL(hearth_body_destroy(W(fw, f), b), expected, NULL, NULL, 0);
    if (r == HEARTH_OK) destroyed_body(fw, TO_ID(b));
}

/* The getters: one output each. */
static void op_body_get(FWorld *fw) {
    FAULTS(F_NULL_WORLD, F_ID, F_NULL_OUT);
    HearthBodyId b;
    Obj *o;
    HearthResult expected = target_body(fw, f, &b, &o);
    if (f == F_NULL_OUT) expected = HEARTH_ERROR_NULL_POINTER;
    int nul = f == F_NULL_OUT;
    HearthWorld *w = W(fw, f);
    union {
        HearthTransform t;
        HearthVec3 v;
        bool flag;
        float x;
        uint64_t u64;
        uint32_t u32;
    } out;
    memset(&out, SENTINEL, sizeof out);
    switch (rnd(9)) {
    case 0: { CALL(hearth_body_get_transform(w, b, nul ? NULL : &out.t), expected, NULL, &out, sizeof out); break; }
    case 1: { CALL(hearth_body_get_linear_velocity(w, b, nul ? NULL : &out.v), expected, NULL, &out, sizeof out); break; }
    case 2: { CALL(hearth_body_get_angular_velocity(w, b, nul ? NULL : &out.v), expected, NULL, &out, sizeof out); break; }
    case 3: { CALL(hearth_body_is_awake(w, b, nul ? NULL : &out.flag), expected, NULL, &out, sizeof out); break; }
    case 4: { CALL(hearth_body_get_center_of_mass(w, b, nul ? NULL : &out.v), expected, NULL, &out, sizeof out); break; }
    case 5: { CALL(hearth_body_get_mass(w, b, nul ? NULL : &out.x), expected, NULL, &out, sizeof out);
        if (r == HEARTH_OK && (!isfinite(out.x) || out.x < 0)) fail("body mass", "not finite or negative");
        break; }
    case 6: { CALL(hearth_body_get_user_data(w, b, nul ? NULL : &out.u64), expected, NULL, &out, sizeof out); break; }
    case 7: {
        CALL(hearth_body_get_type(w, b, nul ? NULL : &out.u32), expected, NULL, &out, sizeof out);
        if (r == HEARTH_OK && out.u32 != o->meta) fail("body type", "differs from the def's");
        break;
    }
    default: {
        /* The bulk read, with one bad id among good ones. */
        size_t n = (size_t)fw->n[K_BODY];
        HearthBodyId ids[MAX_LIVE + 1];
        for (size_t i = 0; i < n; i++) ids[i] = body_id(fw->live[K_BODY][i].id);
        HearthResult e = f == F_NULL_WORLD ? HEARTH_ERROR_NULL_POINTER : HEARTH_OK;
        if (f == F_ID) { ids[n++] = body_id(bad_id(fw, K_BODY)); e = HEARTH_ERROR_INVALID_ID; }
        if (f == F_NULL_OUT && n > 0) e = HEARTH_ERROR_NULL_POINTER;
        memset(g_out_xf, SENTINEL, sizeof g_out_xf);
        CALL(hearth_world_get_transforms(w, n || chance(50) ? ids : NULL, n, nul ? NULL : g_out_xf), e, NULL, g_out_xf, sizeof(HearthTransform) * n);
        break;
    }
    }
}

static void op_body_set(FWorld *fw) {
    FAULTS(F_NULL_WORLD, F_ID, F_NUMBER, F_NULL_IN, F_FLAG);
    HearthBodyId b;
    Obj *o;
    HearthResult expected = target_body(fw, f == F_NULL_IN || f == F_FLAG || f == F_NUMBER ? F_NONE : f, &b, &o);
    if (f == F_NULL_WORLD) expected = HEARTH_ERROR_NULL_POINTER;
    int bad_arg = expected == HEARTH_OK && f == F_NUMBER;
    HearthResult arg_result = bad_arg ? HEARTH_ERROR_INVALID_ARGUMENT : expected;
    HearthWorld *w = W(fw, f);
    float vmax = fw->def.max_linear_speed;
    switch (rnd(6)) {
    case 0: {
        HearthTransform t = xf(good_position(), quat_any());
        const char *field = NULL;
        if (f == F_NUMBER) { if (chance(50)) { t.position = bad_position(); field = "position"; } else { t.rotation = bad_quat(); field = "rotation"; } }
        HearthResult e = f == F_NULL_IN && expected == HEARTH_OK ? HEARTH_ERROR_NULL_POINTER : arg_result;
        if (f == F_NULL_IN && expected == HEARTH_ERROR_INVALID_ID) e = HEARTH_ERROR_NULL_POINTER;
        CALL(hearth_body_set_transform(w, b, f == F_NULL_IN ? NULL : &t), e, field, NULL, 0);
        break;
    }
    case 1: {
        HearthTransform t = xf(good_position(), quat_any());
        const char *field = NULL;
        if (f == F_NUMBER) { if (chance(50)) { t.position = bad_position(); field = "position"; } else { t.rotation = bad_quat(); field = "rotation"; } }
        HearthResult e = arg_result;
        if (f == F_NULL_IN) e = f == F_NULL_WORLD ? e : HEARTH_ERROR_NULL_POINTER;
        else if (e == HEARTH_OK && o->meta != HEARTH_BODY_KINEMATIC) e = HEARTH_ERROR_INVALID_ARGUMENT;
        else if (e == HEARTH_ERROR_INVALID_ARGUMENT && o->meta != HEARTH_BODY_KINEMATIC) field = NULL;
        CALL(hearth_body_set_target_transform(w, b, f == F_NULL_IN ? NULL : &t), e, field, NULL, 0);
        break;
    }
    case 2: {
        HearthVec3 v = vec_up_to(vmax, 20);
        if (f == F_NUMBER) v = chance(50) ? spoil3(v, nonfinite()) : scale3(dir3(), vmax * 1.01f + 1e-3f);
        CALL(hearth_body_set_linear_velocity(w, b, v), f == F_NULL_IN || f == F_FLAG ? expected : arg_result, "velocity", NULL, 0);
        break;
    }
    case 3: {
        HearthVec3 v = vec_up_to(fw->def.max_angular_speed, 20);
        if (f == F_NUMBER) v = chance(50) ? spoil3(v, nonfinite()) : scale3(dir3(), fw->def.max_angular_speed * 1.01f + 1e-3f);
        CALL(hearth_body_set_angular_velocity(w, b, v), f == F_NULL_IN || f == F_FLAG ? expected : arg_result, "velocity", NULL, 0);
        break;
    }
    case 4: {
        uint8_t a = f == F_FLAG ? bad_flag() : flag01();
        HearthResult e = f == F_FLAG && expected == HEARTH_OK ? HEARTH_ERROR_INVALID_ARGUMENT : expected;
        if (f == F_FLAG && expected == HEARTH_ERROR_INVALID_ID) e = HEARTH_ERROR_INVALID_ARGUMENT; /* the flag is checked first */
        CALL(hearth_body_set_awake(w, b, a), e, "awake", NULL, 0);
        break;
    }
    default: {
        float l = chance(50) ? frange(0, 5) : MAX_DAMPING, a = frange(0, 5);
        const char *field = NULL;
        if (f == F_NUMBER) { if (chance(50)) { l = outside(0, MAX_DAMPING); field = "linear damping"; } else { a = outside(0, MAX_DAMPING); field = "angular damping"; } }
        CALL(hearth_body_set_damping(w, b, l, a), f == F_NULL_IN || f == F_FLAG ? expected : arg_result, field, NULL, 0);
        break;
    }
    }
    if (expected == HEARTH_OK) check_state(fw, "after a body setter");
}

static void op_body_forces(FWorld *fw) {
    FAULTS(F_NULL_WORLD, F_ID, F_NUMBER);
    /* Forces check the number before the id, impulses at the centre the id first: with a bad
     * number and no live body either code is right, so that case is left out. */
    if (f == F_NUMBER && fw->n[K_BODY] == 0) return;
    HearthBodyId b;
    Obj *o;
    HearthResult expected = target_body(fw, f == F_NUMBER ? F_NONE : f, &b, &o);
    HearthResult e = f == F_NUMBER && expected == HEARTH_OK ? HEARTH_ERROR_INVALID_ARGUMENT : expected;
    HearthWorld *w = W(fw, f);
    HearthVec3 pt = chance(70) ? vec(frange(-10, 10), frange(-10, 10), frange(-10, 10)) : good_position();
    switch (rnd(6)) {
    case 0: {
        HearthVec3 v = f == F_NUMBER ? (chance(50) ? spoil3(vec(1, 2, 3), nonfinite()) : scale3(dir3(), MAX_FORCE * 1.01f)) : vec_up_to(MAX_FORCE, 100);
        CALL(hearth_body_apply_force(w, b, v), e, "force", NULL, 0);
        break;
    }
    case 1: {
        HearthVec3 v = f == F_NUMBER ? (chance(50) ? spoil3(vec(1, 2, 3), nonfinite()) : scale3(dir3(), MAX_FORCE * 1.01f)) : vec_up_to(MAX_FORCE, 10);
        CALL(hearth_body_apply_torque(w, b, v), e, "torque", NULL, 0);
        break;
    }
    case 2: {
        HearthVec3 v = f == F_NUMBER ? (chance(50) ? spoil3(vec(1, 2, 3), nonfinite()) : scale3(dir3(), MAX_IMPULSE * 1.01f)) : vec_up_to(MAX_IMPULSE, 10);
        CALL(hearth_body_apply_linear_impulse(w, b, v), e, "impulse", NULL, 0);
        break;
    }
    case 3: {
        HearthVec3 v = f == F_NUMBER ? (chance(50) ? spoil3(vec(1, 2, 3), nonfinite()) : scale3(dir3(), MAX_IMPULSE * 1.01f)) : vec_up_to(MAX_IMPULSE, 10);
        CALL(hearth_body_apply_angular_impulse(w, b, v), e, "impulse", NULL, 0);
        break;
    }
    case 4: {
        HearthVec3 v = vec_up_to(MAX_FORCE, 100);
        const char *field = NULL;
        if (f == F_NUMBER) { if (chance(50)) { v = spoil3(v, nonfinite()); field = "force"; } else { pt = bad_position(); field = "point"; } }
        CALL(hearth_body_apply_force_at_point(w, b, v, pt), e, field, NULL, 0);
        break;
    }
    default: {
        HearthVec3 v = vec_up_to(MAX_IMPULSE, 10);
        const char *field = NULL;
        if (f == F_NUMBER) { if (chance(50)) { v = scale3(dir3(), outside(0, MAX_IMPULSE)); if (!(len3(v) > MAX_IMPULSE)) v = spoil3(v, NAN); field = "impulse"; } else { pt = bad_position(); field = "point"; } }
        CALL(hearth_body_apply_impulse_at_point(w, b, v, pt), e, field, NULL, 0);
        break;
    }
    }
    if (expected == HEARTH_OK) check_state(fw, "after a force or impulse");
}

/* ---------------------------------------------------------------------------- shapes */
static float good_length(void) {
    switch (rnd(10)) {
    case 0: return MIN_LENGTH;
    case 1: return chance(20) ? MAX_LENGTH : flog(MIN_LENGTH, MAX_LENGTH);
    default: return frange(0.05f, 1.0f);
    }
}
static float good_density(void) {
    switch (rnd(8)) {
    case 0: return 0;
    case 1: return MIN_DENSITY;
    case 2: return MAX_DENSITY;
    case 3: return flog(MIN_DENSITY, MAX_DENSITY);
    default: return 1000;
    }
}

static void op_shape_create(FWorld *fw) {
    if (full(fw, K_SHAPE)) return;
    FAULTS(F_NULL_WORLD, F_ID, F_NULL_IN, F_NULL_OUT, F_COOKIE, F_NUMBER);
    /* The def is checked before the body, the numbers after it: without a live body only
     * the id itself is fuzzed. */
    if (fw->n[K_BODY] == 0 && f != F_ID && f != F_NULL_WORLD) return;
    HearthBodyId b;
    Obj *o;
    HearthResult expected = target_body(fw, f == F_ID || f == F_NULL_WORLD ? f : F_NONE, &b, &o);
    HearthShapeDef sd = hearth_shape_def_default();
    sd.density = good_density();
    if (chance(30)) { sd.static_friction = frange(0, 2); sd.dynamic_friction = frange(0, 2); }
    if (chance(30)) sd.restitution = frange(0, 1);
    const char *field = NULL;
    int kind = (int)rnd(4);
    /* Sensors and event flags (a plane cannot be a sensor). */
    if (kind != 3 && chance(15)) sd.is_sensor = 1;
    if (chance(30)) sd.enable_hit_events = 1;
    if (chance(20)) sd.enable_contact_events = 0;
    if (chance(20)) sd.enable_sensor_events = 0;
    int null_def = f == F_NULL_IN && chance(50), null_geom = f == F_NULL_IN && !null_def;
    if (f == F_COOKIE) sd.internal_value = 0;
    if (f == F_NUMBER && chance(30)) {
        switch (rnd(3)) {
        case 0: sd.density = chance(50) ? outside(MIN_DENSITY, MAX_DENSITY) : MIN_DENSITY * 0.5f; field = "density"; break;
        case 1: sd.restitution = outside(0, 1); field = "restitution"; break;
        default: sd.static_friction = chance(50) ? -1.0f : nonfinite(); field = "static_friction"; break;
        }
    }
    int bad_geom = f == F_NUMBER && !field;
    if (expected == HEARTH_OK) {
        if (f == F_NULL_IN || f == F_NULL_OUT) expected = HEARTH_ERROR_NULL_POINTER;
        else if (f == F_COOKIE || f == F_NUMBER) expected = HEARTH_ERROR_INVALID_ARGUMENT;
        else if (kind == 3 && o->meta != HEARTH_BODY_STATIC) expected = HEARTH_ERROR_INVALID_ARGUMENT;
    } else if (expected == HEARTH_ERROR_INVALID_ID && (f == F_NULL_IN || f == F_NULL_OUT)) {
        expected = HEARTH_ERROR_NULL_POINTER; /* pointers are checked before the id */
    }
    HearthShapeId out;
    memset(&out, SENTINEL, sizeof out);
    HearthWorld *w = W(fw, f);
    HearthShapeDef *pd = null_def ? NULL : &sd;
    HearthShapeId *po = f == F_NULL_OUT ? NULL : &out;
    HearthVec3 c = chance(60) ? vec(0, 0, 0) : chance(80) ? vec(frange(-1, 1), frange(-1, 1), frange(-1, 1)) : good_position();
    if (kind == 0) {
        HearthSphere s;
        s.center = c;
        s.radius = good_length();
        if (bad_geom) { if (chance(50)) { s.radius = outside(MIN_LENGTH, MAX_LENGTH); field = "radius"; } else { s.center = bad_position(); field = "center"; } }
        CALL(hearth_shape_create_sphere(w, b, pd, null_geom ? NULL : &s, po), expected, field, &out, sizeof out);
        if (r == HEARTH_OK) add(fw, K_SHAPE, TO_ID(out))->a = TO_ID(b);
    } else if (kind == 1) {
        HearthBox bx;
        bx.center = c;
        bx.rotation = quat_any();
        bx.half_extents = vec(good_length(), good_length(), good_length());
        if (bad_geom) {
            switch (rnd(3)) {
            case 0: bx.half_extents = spoil3(bx.half_extents, outside(MIN_LENGTH, MAX_LENGTH)); field = "half_extents"; break;
            case 1: bx.rotation = bad_quat(); field = "rotation"; break;
            default: bx.center = bad_position(); field = "center"; break;
            }
        }
        CALL(hearth_shape_create_box(w, b, pd, null_geom ? NULL : &bx, po), expected, field, &out, sizeof out);
        if (r == HEARTH_OK) add(fw, K_SHAPE, TO_ID(out))->a = TO_ID(b);
    } else if (kind == 2) {
        HearthCapsule cp;
        float half = chance(20) ? 0 : chance(10) ? MAX_LENGTH * 0.4999f : frange(0, 1);
        HearthVec3 axis = dir3();
        c = vec(frange(-1, 1), frange(-1, 1), frange(-1, 1));
        cp.a = vec(c.x - axis.x * half, c.y - axis.y * half, c.z - axis.z * half);
        cp.b = vec(c.x + axis.x * half, c.y + axis.y * half, c.z + axis.z * half);
        cp.radius = good_length();
        if (bad_geom) {
            switch (rnd(3)) {
            case 0: cp.radius = outside(MIN_LENGTH, MAX_LENGTH); field = "radius"; break;
            case 1: cp.a = bad_position(); field = "capsule a"; break;
            default: cp.a = vec(-MAX_LENGTH, 0, 0); cp.b = vec(MAX_LENGTH * 0.02f, 0, 0); field = "segment"; break;
            }
        }
        CALL(hearth_shape_create_capsule(w, b, pd, null_geom ? NULL : &cp, po), expected, field, &out, sizeof out);
        if (r == HEARTH_OK) add(fw, K_SHAPE, TO_ID(out))->a = TO_ID(b);
    } else {
        HearthPlane p;
        p.normal = chance(70) ? vec(0, 1, 0) : scale3(dir3(), flog(1e-3f, 1e3f));
        p.offset = chance(70) ? 0 : frange(-5, 5) * len3(p.normal);
        if (bad_geom) {
            switch (rnd(3)) {
            case 0: p.normal = chance(50) ? vec(0, 0, 0) : spoil3(p.normal, nonfinite()); field = "normal"; break;
            case 1: p.offset = chance(50) ? nonfinite() : MAX_COORDINATE * 1.01f * len3(p.normal); field = "offset"; break;
            default: p.normal = vec(1e-30f, 0, 0); field = "normal"; break;
            }
        }
        CALL(hearth_shape_create_plane(w, b, pd, null_geom ? NULL : &p, po), expected, field, &out, sizeof out);
        if (r == HEARTH_OK) add(fw, K_SHAPE, TO_ID(out))->a = TO_ID(b);
    }
    if (expected == HEARTH_OK) check_state(fw, "after a shape was added");
}

static void op_shape_other(FWorld *fw) {
    FAULTS(F_NULL_WORLD, F_ID, F_NULL_OUT);
    Obj *o = f == F_ID ? NULL : pick(fw, K_SHAPE);
    HearthShapeId s = o ? shape_id(o->id) : shape_id(bad_id(fw, K_SHAPE));
    HearthResult expected = f == F_NULL_WORLD ? HEARTH_ERROR_NULL_POINTER : o ? HEARTH_OK : HEARTH_ERROR_INVALID_ID;
    if (chance(50)) {
        if (f == F_NULL_OUT) return;
        CALL(hearth_shape_destroy(W(fw, f), s), expected, NULL, NULL, 0);
        if (r == HEARTH_OK) { bury(K_SHAPE, o->id); drop_at(fw, K_SHAPE, (int)(o - fw->live[K_SHAPE])); }
    } else {
        HearthBodyId b;
        memset(&b, SENTINEL, sizeof b);
        if (f == F_NULL_OUT && expected == HEARTH_OK) expected = HEARTH_ERROR_NULL_POINTER;
        CALL(hearth_shape_get_body(W(fw, f), s, f == F_NULL_OUT ? NULL : &b), expected, NULL, &b, sizeof b);
        if (r == HEARTH_OK && !id_eq(TO_ID(b), o->a)) fail("shape_get_body", "not the body it was added to");
    }
}

/* ------------------------------------------------------------------------- particles */
static HearthParticleDef good_particle_def(FWorld *fw) {
    HearthParticleDef d = hearth_particle_def_default();
    d.position = chance(80) ? vec(frange(-5, 5), frange(0, 5), frange(-5, 5)) : good_position();
    if (chance(40)) d.velocity = vec_up_to(fw->def.max_linear_speed, 10);
    if (chance(20)) d.acceleration = vec_up_to(MAX_ACCELERATION, 10);
    if (chance(30)) d.inverse_mass = chance(30) ? 0 : chance(30) ? MAX_INVERSE_MASS : flog(1e-3f, 1e3f);
    if (chance(30)) d.radius = chance(30) ? 0 : good_length();
    if (chance(20)) d.damping = frange(0, MAX_DAMPING);
    if (chance(20)) d.gravity_scale = frange(-MAX_GRAVITY_SCALE, MAX_GRAVITY_SCALE);
    if (chance(20)) d.restitution = frange(0, 1);
    if (chance(20)) d.friction = frange(0, 2);
    if (chance(30)) d.lifetime = flog(1e-3f, 10);
    if (chance(10)) d.collide = 0;
    if (chance(10)) d.allow_sleep = 0;
    d.user_data = next_u64();
    return d;
}

static const char *spoil_particle_def(FWorld *fw, HearthParticleDef *d, Fault f) {
    if (f == F_COOKIE) { d->internal_value = 0; return NULL; }
    if (f == F_FLAG) { if (chance(50)) { d->collide = bad_flag(); return "collide"; } d->allow_sleep = bad_flag(); return "allow_sleep"; }
    switch (rnd(10)) {
    case 0: d->position = bad_position(); return "position";
    case 1: d->velocity = chance(50) ? spoil3(d->velocity, nonfinite()) : scale3(dir3(), fw->def.max_linear_speed * 1.01f + 1e-3f); return "velocity";
    case 2: d->acceleration = chance(50) ? spoil3(d->acceleration, nonfinite()) : scale3(dir3(), MAX_ACCELERATION * 1.01f); return "acceleration";
    case 3: d->inverse_mass = outside(0, MAX_INVERSE_MASS); return "inverse_mass";
    case 4: d->radius = chance(50) ? 1e-4f : outside(MIN_LENGTH, MAX_LENGTH); if (d->radius == 0) d->radius = -1; return "radius";
    case 5: d->damping = outside(0, MAX_DAMPING); return "damping";
    case 6: d->gravity_scale = outside(-MAX_GRAVITY_SCALE, MAX_GRAVITY_SCALE); return "gravity_scale";
    case 7: d->restitution = outside(0, 1); return "restitution";
    case 8: d->friction = chance(50) ? -0.5f : nonfinite(); return "friction";
    default: d->lifetime = chance(50) ? 0.0f : chance(50) ? -1.0f : NAN; return "lifetime";
    }
}

static void op_particle_create(FWorld *fw) {
    if (full(fw, K_PARTICLE)) return;
    FAULTS(F_NULL_WORLD, F_NULL_IN, F_NULL_OUT, F_COOKIE, F_NUMBER, F_FLAG);
    HearthParticleDef d = good_particle_def(fw);
    const char *field = f == F_COOKIE || f == F_NUMBER || f == F_FLAG ? spoil_particle_def(fw, &d, f) : NULL;
    HearthParticleId out;
    memset(&out, SENTINEL, sizeof out);
    HearthResult expected = f == F_NONE ? HEARTH_OK
                            : (f == F_NULL_WORLD || f == F_NULL_IN || f == F_NULL_OUT) ? HEARTH_ERROR_NULL_POINTER
                                                                                      : HEARTH_ERROR_INVALID_ARGUMENT;
    CALL(hearth_particle_create(W(fw, f), f == F_NULL_IN ? NULL : &d, f == F_NULL_OUT ? NULL : &out), expected, field,
         &out, sizeof out);
    if (r == HEARTH_OK) add(fw, K_PARTICLE, TO_ID(out));
}

static void op_particle_emit(FWorld *fw) {
    if (fw->n[K_PARTICLE] + 64 > KIND_MAX[K_PARTICLE]) return;
    FAULTS(F_NULL_WORLD, F_NULL_IN, F_COOKIE, F_NUMBER, F_FLAG);
    HearthBurstDef d = hearth_burst_def_default();
    float vmax = fw->def.max_linear_speed;
    d.particle = good_particle_def(fw);
    d.particle.velocity = vec_up_to(vmax * 0.5f, 2);
    d.position = chance(80) ? vec(frange(-5, 5), frange(0, 5), frange(-5, 5)) : good_position();
    d.direction = scale3(dir3(), flog(1e-3f, 1e3f));
    d.cone_half_angle = frange(0, 3.14159f);
    d.count = rnd(33);
    d.speed_max = chance(20) ? vmax * 0.5f : frange(0, vmax * 0.5f < 20 ? vmax * 0.5f : 20);
    d.speed_min = frange(0, d.speed_max);
    d.lifetime_min = flog(1e-3f, 5);
    d.lifetime_max = chance(20) ? INFINITY : d.lifetime_min * frange(1, 3);
    d.seed = next_u64();
    const char *field = NULL;
    if (f == F_COOKIE) { if (chance(50)) d.internal_value = 0; else d.particle.internal_value = 0; }
    if (f == F_FLAG) { d.particle.collide = bad_flag(); field = "collide"; }
    if (f == F_NUMBER) {
        switch (rnd(9)) {
        case 0: d.direction = chance(50) ? vec(0, 0, 0) : spoil3(d.direction, nonfinite()); field = "direction"; break;
        case 1: d.cone_half_angle = chance(50) ? -0.1f : chance(50) ? 3.2f : NAN; field = "cone_half_angle"; break;
        case 2: d.count = 1048577 + rnd(1000); field = "count"; break;
        case 3: d.speed_min = d.speed_max + 1; field = "speed_min"; break;
        case 4: d.speed_max = vmax * 1.01f + 1e-3f; d.speed_min = 0; field = "speed_max"; break;
        case 5: d.lifetime_min = chance(50) ? 0.0f : -1.0f; field = "lifetime_min"; break;
        case 6: d.lifetime_max = d.lifetime_min * 0.5f; field = "lifetime_min"; break;
        case 7: d.position = bad_position(); field = "position"; break;
        default: d.particle.damping = -1; field = "damping"; break;
        }
    }
    HearthParticleId ids[40];
    memset(ids, SENTINEL, sizeof ids);
    size_t count;
    memset(&count, SENTINEL, sizeof count);
    int want_ids = chance(70);
    int small = f == F_NONE && want_ids && d.count > 0 && chance(10);
    size_t capacity = small ? d.count - 1 : 40;
    HearthResult expected = f == F_NONE ? (small ? HEARTH_ERROR_BUFFER_TOO_SMALL : HEARTH_OK)
                            : (f == F_NULL_WORLD || f == F_NULL_IN) ? HEARTH_ERROR_NULL_POINTER
                                                                    : HEARTH_ERROR_INVALID_ARGUMENT;
    CALL(hearth_particle_emit_burst(W(fw, f), f == F_NULL_IN ? NULL : &d, want_ids ? ids : NULL, capacity,
                                    chance(80) ? &count : NULL),
         expected, field, ids, sizeof ids);
    if (r == HEARTH_OK) {
        /* The ids are in the bulk list; read them all back. */
        size_t np = 0;
        hearth_world_get_particles(fw->w, g_pid_buf, NULL, NULL, MAX_LIVE + 1, &np);
        for (size_t i = 0; i < np; i++)
            if (find(fw, K_PARTICLE, TO_ID(g_pid_buf[i])) < 0) add(fw, K_PARTICLE, TO_ID(g_pid_buf[i]));
        if ((size_t)fw->n[K_PARTICLE] != np) fail("emit", "particle count differs from the tracked one");
        if (want_ids)
            for (uint32_t i = 0; i < d.count; i++)
                if (find(fw, K_PARTICLE, TO_ID(ids[i])) < 0) fail("emit", "an emitted id is not live");
        check_state(fw, "after a burst");
    }
    if (r != HEARTH_OK && !untouched(&count, sizeof count)) fail("emit", "out_count written on failure");
}

static void op_particle_other(FWorld *fw) {
    FAULTS(F_NULL_WORLD, F_ID, F_NUMBER, F_NULL_OUT, F_FLAG);
    Obj *o = f == F_ID ? NULL : pick(fw, K_PARTICLE);
    if (!o && f != F_ID && f != F_NULL_WORLD) return;
    HearthParticleId p = o ? particle_id(o->id) : particle_id(bad_id(fw, K_PARTICLE));
    HearthResult idr = f == F_NULL_WORLD ? HEARTH_ERROR_NULL_POINTER : o ? HEARTH_OK : HEARTH_ERROR_INVALID_ID;
    HearthWorld *w = W(fw, f);
    float vmax = fw->def.max_linear_speed;
    union {
        HearthVec3 v;
        bool flag;
        uint64_t u64;
    } out;
    memset(&out, SENTINEL, sizeof out);
    int nul = f == F_NULL_OUT;
    HearthResult getr = nul && idr != HEARTH_ERROR_NULL_POINTER ? HEARTH_ERROR_NULL_POINTER : idr;
    HearthResult numr = f == F_NUMBER && idr == HEARTH_OK ? HEARTH_ERROR_INVALID_ARGUMENT : idr;
    switch (rnd(11)) {
    case 0: { CALL(hearth_particle_get_position(w, p, nul ? NULL : &out.v), getr, NULL, &out, sizeof out); break; }
    case 1: { CALL(hearth_particle_get_velocity(w, p, nul ? NULL : &out.v), getr, NULL, &out, sizeof out); break; }
    case 2: { CALL(hearth_particle_is_awake(w, p, nul ? NULL : &out.flag), getr, NULL, &out, sizeof out); break; }
    case 3: { CALL(hearth_particle_get_user_data(w, p, nul ? NULL : &out.u64), getr, NULL, &out, sizeof out); break; }
    case 4: {
        HearthVec3 v = f == F_NUMBER ? bad_position() : good_position();
        CALL(hearth_particle_set_position(w, p, v), numr, "position", NULL, 0);
        break;
    }
    case 5: {
        HearthVec3 v = f == F_NUMBER ? (chance(50) ? spoil3(vec(0, 0, 0), nonfinite()) : scale3(dir3(), vmax * 1.01f + 1e-3f)) : vec_up_to(vmax, 10);
        CALL(hearth_particle_set_velocity(w, p, v), numr, "velocity", NULL, 0);
        break;
    }
    case 6: {
        HearthVec3 v = f == F_NUMBER ? (chance(50) ? spoil3(vec(0, 0, 0), nonfinite()) : scale3(dir3(), MAX_FORCE * 1.01f)) : vec_up_to(MAX_FORCE, 10);
        CALL(hearth_particle_apply_force(w, p, v), numr, "force", NULL, 0);
        break;
    }
    case 7: {
        HearthVec3 v = f == F_NUMBER ? (chance(50) ? spoil3(vec(0, 0, 0), nonfinite()) : scale3(dir3(), MAX_IMPULSE * 1.01f)) : vec_up_to(MAX_IMPULSE, 10);
        CALL(hearth_particle_apply_impulse(w, p, v), numr, "impulse", NULL, 0);
        break;
    }
    case 8: {
        uint8_t a = f == F_FLAG ? bad_flag() : flag01();
        HearthResult e = f == F_FLAG && idr != HEARTH_ERROR_NULL_POINTER ? HEARTH_ERROR_INVALID_ARGUMENT : idr;
        CALL(hearth_particle_set_awake(w, p, a), e, "awake", NULL, 0);
        break;
    }
    case 9: {
        if (f == F_ID && chance(50)) break;
        CALL(hearth_particle_destroy(w, p), idr, NULL, NULL, 0);
        if (r == HEARTH_OK) { forget_particle_everywhere(fw, o->id); bury(K_PARTICLE, o->id); drop_at(fw, K_PARTICLE, (int)(o - fw->live[K_PARTICLE])); }
        break;
    }
    default: {
        /* Bulk reads of particles. */
        size_t n = (size_t)fw->n[K_PARTICLE], count;
        HearthParticleId ids[MAX_LIVE + 1];
        for (size_t i = 0; i < n; i++) ids[i] = particle_id(fw->live[K_PARTICLE][i].id);
        memset(g_out_vec, SENTINEL, sizeof g_out_vec);
        memset(&count, SENTINEL, sizeof count);
        switch (rnd(4)) {
        case 0: {
            HearthResult e = f == F_NULL_WORLD ? HEARTH_ERROR_NULL_POINTER : HEARTH_OK;
            if (f == F_ID) { ids[n++] = p; e = HEARTH_ERROR_INVALID_ID; }
            if (nul && n) e = HEARTH_ERROR_NULL_POINTER;
            CALL(hearth_world_get_particle_positions(w, ids, n, nul ? NULL : g_out_vec), e, NULL, g_out_vec, sizeof(HearthVec3) * n);
            break;
        }
        case 1: {
            HearthResult e = f == F_NULL_WORLD || nul ? HEARTH_ERROR_NULL_POINTER : HEARTH_OK;
            size_t cap = n > 0 && chance(30) ? n - 1 : chance(20) ? 0 : MAX_LIVE + 1;
            if (e == HEARTH_OK && cap > 0 && cap < n) e = HEARTH_ERROR_BUFFER_TOO_SMALL;
            CALL(hearth_world_get_particles(w, chance(50) ? g_out_pid : NULL, g_out_vec, NULL, cap, nul ? NULL : &count), e, NULL, g_out_vec, sizeof(HearthVec3) * (MAX_LIVE + 1));
            if (r == HEARTH_OK && count != n) fail("get_particles", "count differs from the tracked one");
            break;
        }
        case 2: {
            HearthResult e = f == F_NULL_WORLD || nul ? HEARTH_ERROR_NULL_POINTER : HEARTH_OK;
            CALL(hearth_world_get_particle_count(w, nul ? NULL : &count), e, NULL, &count, sizeof count);
            if (r == HEARTH_OK && count != n) fail("get_particle_count", "differs from the tracked one");
            break;
        }
        default: {
            const HearthExpiredParticle *arr;
            memset(&arr, SENTINEL, sizeof arr);
            HearthResult e = f == F_NULL_WORLD || nul ? HEARTH_ERROR_NULL_POINTER : HEARTH_OK;
            CALL(hearth_world_get_expired_particles(w, nul && chance(50) ? NULL : &arr, nul ? NULL : &count), e, NULL, &arr, sizeof arr);
            break;
        }
        }
        break;
    }
    }
    if (idr == HEARTH_OK) check_state(fw, "after a particle call");
}

/* ------------------------------------------------------------------------ generators */
/* A link end: a live body point, a live particle, or a world point. */
static HearthLinkEnd good_end(FWorld *fw) {
    HearthLinkEnd e;
    memset(&e, 0, sizeof e);
    e.point = vec(frange(-2, 2), frange(0, 4), frange(-2, 2));
    Obj *b = pick(fw, K_BODY), *p = pick(fw, K_PARTICLE);
    switch (rnd(3)) {
    case 0: if (b) e.body = body_id(b->id); break;
    case 1: if (p) e.particle = particle_id(p->id); break;
    default: break;
    }
    return e;
}
static int is_world_end(const HearthLinkEnd *e) { return !e->body.generation && !e->particle.generation && !e->body.index && !e->particle.index; }
static int same_end(const HearthLinkEnd *a, const HearthLinkEnd *b) {
    if (a->particle.generation || b->particle.generation) return id_eq(TO_ID(a->particle), TO_ID(b->particle)) && !a->body.generation && !b->body.generation;
    return id_eq(TO_ID(a->body), TO_ID(b->body)) && memcmp(&a->point, &b->point, sizeof a->point) == 0;
}

static void op_generator_create(FWorld *fw) {
    if (full(fw, K_GEN)) return;
    FAULTS(F_NULL_WORLD, F_NULL_IN, F_NULL_OUT, F_COOKIE, F_NUMBER, F_ID, F_FLAG);
    HearthGeneratorId out;
    memset(&out, SENTINEL, sizeof out);
    HearthGeneratorId *po = f == F_NULL_OUT ? NULL : &out;
    HearthWorld *w = W(fw, f);
    int nul = f == F_NULL_IN;
    HearthResult expected = f == F_NULL_WORLD || f == F_NULL_IN || f == F_NULL_OUT ? HEARTH_ERROR_NULL_POINTER
                            : f == F_COOKIE || f == F_NUMBER || f == F_FLAG    ? HEARTH_ERROR_INVALID_ARGUMENT
                                                                                : HEARTH_OK;
    const char *field = NULL;
    uint32_t type = rnd(11);
    int r_ok = 0;
    /* Faults a kind cannot have become "no fault". */
#define NO_FAULT_HERE(cond)                                                                  \
    if (cond) { f = F_NONE; expected = HEARTH_OK; }
    switch (type) {
    case HEARTH_GENERATOR_GRAVITY: {
        NO_FAULT_HERE(f == F_ID || f == F_FLAG);
        HearthGravityGeneratorDef d = hearth_gravity_generator_def_default();
        d.acceleration = vec_up_to(50, 20);
        if (f == F_COOKIE) d.internal_value = 0;
        if (f == F_NUMBER) { d.acceleration = spoil3(d.acceleration, nonfinite()); field = "acceleration"; }
        CALL(hearth_generator_create_gravity(w, nul ? NULL : &d, po), expected, field, &out, sizeof out);
        r_ok = r == HEARTH_OK;
        break;
    }
    case HEARTH_GENERATOR_DRAG: {
        NO_FAULT_HERE(f == F_ID || f == F_FLAG);
        HearthDragGeneratorDef d = hearth_drag_generator_def_default();
        d.k1 = frange(0, 1);
        d.k2 = frange(0, 0.1f);
        if (f == F_COOKIE) d.internal_value = 0;
        if (f == F_NUMBER) { if (chance(50)) { d.k1 = chance(50) ? -1.0f : NAN; field = "k1"; } else { d.k2 = chance(50) ? -1.0f : NAN; field = "k2"; } }
        CALL(hearth_generator_create_drag(w, nul ? NULL : &d, po), expected, field, &out, sizeof out);
        r_ok = r == HEARTH_OK;
        break;
    }
    case HEARTH_GENERATOR_SPRING:
    case HEARTH_GENERATOR_BUNGEE: {
        NO_FAULT_HERE(f == F_FLAG);
        HearthSpringGeneratorDef d = hearth_spring_generator_def_default();
        d.other = good_end(fw);
        d.local_point = vec(frange(-1, 1), frange(-1, 1), frange(-1, 1));
        d.rest_length = frange(0, 3);
        d.stiffness = frange(0, 500);
        d.damping = frange(0, 10);
        if (f == F_COOKIE) d.internal_value = 0;
        if (f == F_ID) { d.other.body = body_id(bad_id(fw, K_BODY)); d.other.particle = particle_id(NULL_ID); if (!d.other.body.generation && !d.other.body.index) { f = F_NONE; expected = HEARTH_OK; } else expected = HEARTH_ERROR_INVALID_ID; }
        if (f == F_NUMBER) {
            switch (rnd(4)) {
            case 0: d.rest_length = chance(50) ? -1.0f : NAN; field = "rest_length"; break;
            case 1: d.stiffness = chance(50) ? -1.0f : NAN; field = "stiffness"; break;
            case 2: d.damping = chance(50) ? -1.0f : NAN; field = "damping"; break;
            default:
                if (chance(50) || d.other.particle.generation) { d.other.body = body_id(id_of(1, 1)); d.other.particle = particle_id(id_of(1, 1)); field = "not both"; }
                else { d.other.point = spoil3(d.other.point, nonfinite()); field = "other"; } /* a particle end has no point */
                break;
            }
        }
        if (type == HEARTH_GENERATOR_SPRING) {
            CALL(hearth_generator_create_spring(w, nul ? NULL : &d, po), expected, field, &out, sizeof out);
            r_ok = r == HEARTH_OK;
        } else {
            CALL(hearth_generator_create_bungee(w, nul ? NULL : &d, po), expected, field, &out, sizeof out);
            r_ok = r == HEARTH_OK;
        }
        break;
    }
    case HEARTH_GENERATOR_STIFF_SPRING: {
        NO_FAULT_HERE(f == F_FLAG || f == F_ID);
        HearthStiffSpringGeneratorDef d = hearth_stiff_spring_generator_def_default();
        d.anchor = good_end(fw);
        d.stiffness = flog(1, 1e4f);
        d.damping = frange(0, 50);
        if (f == F_COOKIE) d.internal_value = 0;
        if (f == F_NUMBER) { if (chance(50)) { d.stiffness = chance(50) ? 0.0f : NAN; field = "stiffness"; } else { d.damping = -1; field = "damping"; } }
        CALL(hearth_generator_create_stiff_spring(w, nul ? NULL : &d, po), expected, field, &out, sizeof out);
        r_ok = r == HEARTH_OK;
        break;
    }
    case HEARTH_GENERATOR_BUOYANCY: {
        NO_FAULT_HERE(f == F_FLAG || f == F_ID);
        HearthBuoyancyGeneratorDef d = hearth_buoyancy_generator_def_default();
        d.surface_normal = scale3(dir3(), frange(0.5f, 2));
        d.surface_offset = frange(-2, 2);
        d.max_depth = frange(0.1f, 2);
        d.volume = frange(0, 0.5f);
        d.liquid_density = frange(0, 2000);
        if (f == F_COOKIE) d.internal_value = 0;
        if (f == F_NUMBER) {
            switch (rnd(3)) {
            case 0: d.surface_normal = vec(0, 0, 0); field = "surface_normal"; break;
            case 1: d.max_depth = chance(50) ? 0.0f : NAN; field = "max_depth"; break;
            default: d.volume = -1; field = "volume"; break;
            }
        }
        CALL(hearth_generator_create_buoyancy(w, nul ? NULL : &d, po), expected, field, &out, sizeof out);
        r_ok = r == HEARTH_OK;
        break;
    }
    case HEARTH_GENERATOR_EXPLOSION: {
        NO_FAULT_HERE(f == F_ID);
        HearthExplosionGeneratorDef d = hearth_explosion_generator_def_default();
        d.center = chance(80) ? vec(frange(-5, 5), frange(-2, 5), frange(-5, 5)) : good_position();
        d.blast_radius = chance(20) ? MAX_LENGTH : frange(0, 10);
        d.blast_impulse = chance(20) ? MAX_IMPULSE : frange(0, 200);
        d.shock_speed = chance(20) ? MAX_SPEED : frange(0, 50);
        d.shock_thickness = chance(20) ? 0 : chance(20) ? MAX_LENGTH : frange(0, 3);
        d.shock_force = chance(20) ? MAX_FORCE : frange(0, 1000);
        d.max_radius = chance(20) ? MAX_LENGTH : frange(0, 30);
        d.affect_all = flag01();
        if (f == F_COOKIE) d.internal_value = 0;
        if (f == F_FLAG) { d.affect_all = bad_flag(); field = "affect_all"; }
        if (f == F_NUMBER) {
            switch (rnd(7)) {
            case 0: d.center = bad_position(); field = "center"; break;
            case 1: d.blast_radius = outside(0, MAX_LENGTH); field = "blast_radius"; break;
            case 2: d.blast_impulse = outside(0, MAX_IMPULSE); field = "blast_impulse"; break;
            case 3: d.shock_speed = outside(0, MAX_SPEED); field = "shock_speed"; break;
            case 4: d.shock_thickness = outside(0, MAX_LENGTH); field = "shock_thickness"; break;
            case 5: d.shock_force = outside(0, MAX_FORCE); field = "shock_force"; break;
            default: d.max_radius = outside(0, MAX_LENGTH); field = "max_radius"; break;
            }
        }
        CALL(hearth_generator_create_explosion(w, nul ? NULL : &d, po), expected, field, &out, sizeof out);
        r_ok = r == HEARTH_OK;
        break;
    }
    case HEARTH_GENERATOR_ROD:
    case HEARTH_GENERATOR_CABLE: {
        NO_FAULT_HERE(f == F_FLAG);
        HearthLinkEnd a = good_end(fw), b = good_end(fw);
        for (int t = 0; t < 4 && ((is_world_end(&a) && is_world_end(&b)) || same_end(&a, &b)); t++) b = good_end(fw);
        if (f == F_NONE && ((is_world_end(&a) && is_world_end(&b)) || same_end(&a, &b))) expected = HEARTH_ERROR_INVALID_ARGUMENT;
        if (f == F_ID) {
            a.body = body_id(bad_id(fw, K_BODY));
            a.particle = particle_id(NULL_ID);
            if (!a.body.generation && !a.body.index) { f = F_NONE; expected = (is_world_end(&b) || same_end(&a, &b)) ? HEARTH_ERROR_INVALID_ARGUMENT : HEARTH_OK; }
            else expected = HEARTH_ERROR_INVALID_ID;
        }
        if (f == F_NUMBER) {
            /* The same end twice, or two world ends; or a bad length (the ends are checked
             * first: with bad ends too the message is about them). */
            if (chance(50)) { a = good_end(fw); b = a; if (is_world_end(&a)) b.point.x += 1; }
            else if (!(is_world_end(&a) && is_world_end(&b)) && !same_end(&a, &b)) field = type == HEARTH_GENERATOR_ROD ? "length" : "max_length";
            else { a = good_end(fw); b = a; if (is_world_end(&a)) b.point.x += 1; }
        }
        if (type == HEARTH_GENERATOR_ROD) {
            HearthRodGeneratorDef d = hearth_rod_generator_def_default();
            d.a = a;
            d.b = b;
            d.length = frange(0, 3);
            if (f == F_COOKIE) d.internal_value = 0;
            if (field) d.length = chance(50) ? -1.0f : NAN;
            CALL(hearth_generator_create_rod(w, nul ? NULL : &d, po), expected, field, &out, sizeof out);
            r_ok = r == HEARTH_OK;
        } else {
            HearthCableGeneratorDef d = hearth_cable_generator_def_default();
            d.a = a;
            d.b = b;
            d.max_length = frange(0, 3);
            d.restitution = frange(0, 1);
            if (f == F_COOKIE) d.internal_value = 0;
            if (field) d.max_length = chance(50) ? -1.0f : NAN;
            CALL(hearth_generator_create_cable(w, nul ? NULL : &d, po), expected, field, &out, sizeof out);
            r_ok = r == HEARTH_OK;
        }
        break;
    }
    case HEARTH_GENERATOR_USER_FORCE: {
        NO_FAULT_HERE(f == F_ID || f == F_FLAG || f == F_NUMBER);
        HearthUserForceGeneratorDef d = hearth_user_force_generator_def_default();
        d.callback = force_callback;
        d.user_data = fw;
        if (f == F_COOKIE) d.internal_value = 0;
        if (f == F_NONE && chance(10)) { d.callback = NULL; expected = HEARTH_ERROR_NULL_POINTER; }
        CALL(hearth_generator_create_user_force(w, nul ? NULL : &d, po), expected, field, &out, sizeof out);
        r_ok = r == HEARTH_OK;
        break;
    }
    default: {
        NO_FAULT_HERE(f == F_ID || f == F_FLAG);
        HearthUserContactGeneratorDef d = hearth_user_contact_generator_def_default();
        d.callback = contact_callback;
        d.user_data = fw;
        d.capacity = rnd(4);
        if (f == F_COOKIE) d.internal_value = 0;
        if (f == F_NUMBER) { d.capacity = 1048577 + rnd(100); field = "capacity"; }
        if (f == F_NONE && chance(10)) { d.callback = NULL; expected = HEARTH_ERROR_NULL_POINTER; }
        CALL(hearth_generator_create_user_contact(w, nul ? NULL : &d, po), expected, field, &out, sizeof out);
        r_ok = r == HEARTH_OK;
        break;
    }
    }
#undef NO_FAULT_HERE
    if (r_ok) add(fw, K_GEN, TO_ID(out))->meta = type;
}

static int attached(const Id *list, int n, Id x) {
    for (int i = 0; i < n; i++)
        if (id_eq(list[i], x)) return 1;
    return 0;
}

static void op_generator_other(FWorld *fw) {
    FAULTS(F_NULL_WORLD, F_ID, F_NULL_OUT, F_NULL_IN);
    Obj *g = f == F_ID && chance(50) ? NULL : pick(fw, K_GEN);
    HearthGeneratorId gid = g ? gen_id(g->id) : gen_id(bad_id(fw, K_GEN));
    HearthResult gr = f == F_NULL_WORLD ? HEARTH_ERROR_NULL_POINTER : g ? HEARTH_OK : HEARTH_ERROR_INVALID_ID;
    int link = g && (g->meta == HEARTH_GENERATOR_ROD || g->meta == HEARTH_GENERATOR_CABLE);
    HearthWorld *w = W(fw, f);
    int bad_other = f == F_ID && g != NULL;
    switch (rnd(8)) {
    case 0: {
        if (f == F_ID && g) break;
        CALL(hearth_generator_destroy(w, gid), gr, NULL, NULL, 0);
        if (r == HEARTH_OK) { bury(K_GEN, g->id); drop_at(fw, K_GEN, (int)(g - fw->live[K_GEN])); }
        break;
    }
    case 1:
    case 2: {
        /* attach / detach a body */
        Obj *b = bad_other ? NULL : (g && g->n_att_bodies && chance(50)) ? NULL : pick(fw, K_BODY);
        Id bid = b ? b->id : (g && g->n_att_bodies && !bad_other) ? g->att_bodies[rnd((uint32_t)g->n_att_bodies)] : bad_id(fw, K_BODY);
        int is_att = g && attached(g->att_bodies, g->n_att_bodies, bid);
        int live_body = find(fw, K_BODY, bid) >= 0;
        if (rnd(2) == 0) {
            HearthResult e = gr != HEARTH_OK ? gr : link ? HEARTH_ERROR_INVALID_ARGUMENT : !live_body ? HEARTH_ERROR_INVALID_ID : is_att ? HEARTH_ERROR_INVALID_ARGUMENT : HEARTH_OK;
            if (e == HEARTH_OK && g->n_att_bodies >= MAX_ATTACH) break;
            CALL(hearth_generator_attach_body(w, gid, body_id(bid)), e, NULL, NULL, 0);
            if (r == HEARTH_OK) g->att_bodies[g->n_att_bodies++] = bid;
        } else {
            HearthResult e = gr != HEARTH_OK ? gr : link ? HEARTH_ERROR_INVALID_ARGUMENT : !is_att ? HEARTH_ERROR_INVALID_ID : HEARTH_OK;
            CALL(hearth_generator_detach_body(w, gid, body_id(bid)), e, NULL, NULL, 0);
            if (r == HEARTH_OK) for (int k = 0; k < g->n_att_bodies; k++) if (id_eq(g->att_bodies[k], bid)) g->att_bodies[k--] = g->att_bodies[--g->n_att_bodies];
        }
        break;
    }
    case 3:
    case 4: {
        /* attach / detach a particle */
        Obj *p = bad_other ? NULL : (g && g->n_att_particles && chance(50)) ? NULL : pick(fw, K_PARTICLE);
        Id pid = p ? p->id : (g && g->n_att_particles && !bad_other) ? g->att_particles[rnd((uint32_t)g->n_att_particles)] : bad_id(fw, K_PARTICLE);
        if (g && g->dead_attached.generation && chance(20)) pid = g->dead_attached; /* destroyed while attached */
        int is_att = g && attached(g->att_particles, g->n_att_particles, pid);
        int live = find(fw, K_PARTICLE, pid) >= 0;
        if (rnd(2) == 0) {
            HearthResult e = gr != HEARTH_OK ? gr : link ? HEARTH_ERROR_INVALID_ARGUMENT : !live ? HEARTH_ERROR_INVALID_ID : is_att ? HEARTH_ERROR_INVALID_ARGUMENT : HEARTH_OK;
            if (e == HEARTH_OK && g->n_att_particles >= MAX_ATTACH) break;
            CALL(hearth_generator_attach_particle(w, gid, particle_id(pid)), e, NULL, NULL, 0);
            if (r == HEARTH_OK) g->att_particles[g->n_att_particles++] = pid;
        } else {
            HearthResult e = gr != HEARTH_OK ? gr : link ? HEARTH_ERROR_INVALID_ARGUMENT : !is_att ? HEARTH_ERROR_INVALID_ID : HEARTH_OK;
            CALL(hearth_generator_detach_particle(w, gid, particle_id(pid)), e, NULL, NULL, 0);
            if (r == HEARTH_OK) for (int k = 0; k < g->n_att_particles; k++) if (id_eq(g->att_particles[k], pid)) g->att_particles[k--] = g->att_particles[--g->n_att_particles];
        }
        break;
    }
    case 5: {
        /* attach many particles: all or nothing */
        HearthParticleId ids[8];
        int n = (int)rnd(5);
        HearthResult e = gr;
        if (f == F_NULL_IN && n == 0) n = 1;
        /* Checked in order: each id live, then not attached yet; then no id twice. */
        HearthResult first_bad = HEARTH_OK;
        int dup = 0;
        for (int i = 0; i < n; i++) {
            Obj *p = pick(fw, K_PARTICLE);
            Id pid = p && !(bad_other && i == n - 1) ? p->id : bad_id(fw, K_PARTICLE);
            ids[i] = particle_id(pid);
            if (first_bad == HEARTH_OK) {
                if (find(fw, K_PARTICLE, pid) < 0) first_bad = HEARTH_ERROR_INVALID_ID;
                else if (g && attached(g->att_particles, g->n_att_particles, pid)) first_bad = HEARTH_ERROR_INVALID_ARGUMENT;
            }
            for (int k = 0; k < i; k++) dup |= id_eq(TO_ID(ids[k]), pid);
        }
        if (f == F_NULL_IN && e != HEARTH_ERROR_NULL_POINTER) e = HEARTH_ERROR_NULL_POINTER;
        else if (e == HEARTH_OK && n > 0) {
            if (link) e = HEARTH_ERROR_INVALID_ARGUMENT;
            else if (first_bad != HEARTH_OK) e = first_bad;
            else if (dup) e = HEARTH_ERROR_INVALID_ARGUMENT;
        }
        if (e == HEARTH_OK && g->n_att_particles + n > MAX_ATTACH) break;
        CALL(hearth_generator_attach_particles(w, gid, f == F_NULL_IN ? NULL : ids, (size_t)n), e, NULL, NULL, 0);
        if (r == HEARTH_OK) for (int i = 0; i < n; i++) g->att_particles[g->n_att_particles++] = TO_ID(ids[i]);
        break;
    }
    case 6: {
        uint32_t nb, np;
        memset(&nb, SENTINEL, sizeof nb);
        memset(&np, SENTINEL, sizeof np);
        int nul = f == F_NULL_OUT;
        HearthResult e = gr == HEARTH_ERROR_NULL_POINTER ? gr : nul ? HEARTH_ERROR_NULL_POINTER : gr;
        CALL(hearth_generator_get_attachment_count(w, gid, nul && chance(50) ? NULL : &nb, nul ? NULL : &np), e, NULL, &nb, sizeof nb);
        if (r == HEARTH_OK && (nb != (uint32_t)g->n_att_bodies || np != (uint32_t)g->n_att_particles)) fail("attachment count", "differs from the tracked one");
        break;
    }
    default: {
        uint32_t t;
        memset(&t, SENTINEL, sizeof t);
        int nul = f == F_NULL_OUT;
        HearthResult e = gr == HEARTH_ERROR_NULL_POINTER ? gr : nul ? HEARTH_ERROR_NULL_POINTER : gr;
        CALL(hearth_generator_get_type(w, gid, nul ? NULL : &t), e, NULL, &t, sizeof t);
        if (r == HEARTH_OK && t != g->meta) fail("generator type", "differs from the created one");
        break;
    }
    }
}

/* ---------------------------------------------------------------------------- joints */
static HearthJointBase good_base(FWorld *fw, HearthResult *expected) {
    HearthJointBase b;
    memset(&b, 0, sizeof b);
    Obj *a = pick(fw, K_BODY), *o = pick(fw, K_BODY);
    b.frame_a = xf(vec(frange(-1, 1), frange(-1, 1), frange(-1, 1)), quat_any());
    b.frame_b = xf(vec(frange(-1, 1), frange(-1, 1), frange(-1, 1)), quat_any());
    b.collide_connected = flag01();
    b.break_force = chance(70) ? FLT_MAX : flog(1, 1e6f);
    b.break_torque = chance(70) ? FLT_MAX : flog(1, 1e6f);
    *expected = HEARTH_OK;
    if (!a) {
        *expected = HEARTH_ERROR_INVALID_ID; /* body_a null */
        return b;
    }
    b.body_a = body_id(a->id);
    int b_static = 1;
    if (o && !id_eq(o->id, a->id) && chance(70)) {
        b.body_b = body_id(o->id);
        b_static = o->meta == HEARTH_BODY_STATIC;
    }
    if (a->meta == HEARTH_BODY_STATIC && b_static) *expected = HEARTH_ERROR_INVALID_ARGUMENT;
    return b;
}

static void op_joint_create(FWorld *fw) {
    if (full(fw, K_JOINT)) return;
    FAULTS(F_NULL_WORLD, F_NULL_IN, F_NULL_OUT, F_COOKIE, F_NUMBER, F_ID, F_FLAG);
    HearthResult base_result;
    HearthJointBase base = good_base(fw, &base_result);
    const char *field = NULL;
    if (f == F_ID) {
        if (chance(50) || !base.body_b.generation) base.body_a = body_id(bad_id(fw, K_BODY));
        else { g_nonnull = 1; base.body_b = body_id(bad_id(fw, K_BODY)); g_nonnull = 0; }
        if (!base.body_b.generation && !base.body_b.index && !base.body_a.generation && !base.body_a.index) base_result = HEARTH_ERROR_INVALID_ID;
    }
    uint32_t type = rnd(5);
    int spoil_kind = f == F_NUMBER && type != HEARTH_JOINT_FIXED && chance(40);
    if (f == F_NUMBER && !spoil_kind) {
        switch (rnd(4)) {
        case 0: base.frame_a.position = spoil3(base.frame_a.position, nonfinite()); field = "frame_a"; break;
        case 1: base.frame_b.rotation = bad_quat(); field = "frame_b"; break;
        case 2: base.break_force = chance(50) ? 0.0f : chance(50) ? -1.0f : NAN; field = "break_force"; break;
        default: base.break_torque = chance(50) ? 0.0f : NAN; field = "break_torque"; break;
        }
    }
    if (f == F_FLAG) { base.collide_connected = bad_flag(); field = "collide_connected"; }
    HearthResult expected;
    switch (f) {
    case F_NONE: expected = base_result; break;
    case F_NULL_WORLD: case F_NULL_IN: case F_NULL_OUT: expected = HEARTH_ERROR_NULL_POINTER; break;
    case F_ID: expected = HEARTH_ERROR_INVALID_ID; break;
    default: expected = HEARTH_ERROR_INVALID_ARGUMENT; break;
    }
    /* body_b equal to body_a through a bad id cannot happen (bad ids are never live). */
    HearthJointId out;
    memset(&out, SENTINEL, sizeof out);
    HearthJointId *po = f == F_NULL_OUT ? NULL : &out;
    HearthWorld *w = W(fw, f);
    int nul = f == F_NULL_IN, cookie = f == F_COOKIE;
    switch (type) {
    case HEARTH_JOINT_BALL: {
        HearthBallJointDef d = hearth_ball_joint_def_default();
        d.base = base;
        d.enable_swing_limit = flag01();
        d.swing_limit = frange(0, 3.14f);
        d.enable_twist_limit = flag01();
        d.lower_twist = frange(-3.14f, 0);
        d.upper_twist = frange(0, 3.14f);
        if (cookie) d.internal_value = 0;
        if (spoil_kind) { d.swing_limit = chance(50) ? -0.5f : 4.0f; field = "swing_limit"; }
        CALL(hearth_joint_create_ball(w, nul ? NULL : &d, po), expected, field, &out, sizeof out);
        if (r == HEARTH_OK) { Obj *o = add(fw, K_JOINT, TO_ID(out)); o->meta = type; o->a = TO_ID(base.body_a); o->b = TO_ID(base.body_b); }
        break;
    }
    case HEARTH_JOINT_HINGE: {
        HearthHingeJointDef d = hearth_hinge_joint_def_default();
        d.base = base;
        d.enable_limit = flag01();
        d.lower = frange(-3.14f, 0);
        d.upper = frange(0, 3.14f);
        d.enable_motor = flag01();
        d.motor_speed = frange(-10, 10);
        d.max_motor_torque = frange(0, 1000);
        d.enable_spring = flag01();
        d.spring_hertz = frange(0, 10);
        d.spring_damping_ratio = frange(0, 2);
        if (cookie) d.internal_value = 0;
        if (spoil_kind) { if (chance(50)) { d.lower = 1; d.upper = -1; field = "lower"; } else { d.max_motor_torque = -1; field = "max"; } }
        CALL(hearth_joint_create_hinge(w, nul ? NULL : &d, po), expected, field, &out, sizeof out);
        if (r == HEARTH_OK) { Obj *o = add(fw, K_JOINT, TO_ID(out)); o->meta = type; o->a = TO_ID(base.body_a); o->b = TO_ID(base.body_b); }
        break;
    }
    case HEARTH_JOINT_FIXED: {
        HearthFixedJointDef d = hearth_fixed_joint_def_default();
        d.base = base;
        if (cookie) d.internal_value = 0;
        CALL(hearth_joint_create_fixed(w, nul ? NULL : &d, po), expected, field, &out, sizeof out);
        if (r == HEARTH_OK) { Obj *o = add(fw, K_JOINT, TO_ID(out)); o->meta = type; o->a = TO_ID(base.body_a); o->b = TO_ID(base.body_b); }
        break;
    }
    case HEARTH_JOINT_DISTANCE: {
        HearthDistanceJointDef d = hearth_distance_joint_def_default();
        d.base = base;
        d.length = frange(0, 3);
        d.enable_limit = flag01();
        d.min_length = frange(0, 1);
        d.max_length = d.min_length + frange(0, 2);
        d.enable_spring = flag01();
        d.spring_hertz = frange(0, 10);
        d.spring_damping_ratio = frange(0, 2);
        if (cookie) d.internal_value = 0;
        if (spoil_kind) { if (chance(50)) { d.length = chance(50) ? -1.0f : NAN; field = "length"; } else { d.spring_hertz = -1; field = "spring_hertz"; } }
        CALL(hearth_joint_create_distance(w, nul ? NULL : &d, po), expected, field, &out, sizeof out);
        if (r == HEARTH_OK) { Obj *o = add(fw, K_JOINT, TO_ID(out)); o->meta = type; o->a = TO_ID(base.body_a); o->b = TO_ID(base.body_b); }
        break;
    }
    default: {
        HearthSliderJointDef d = hearth_slider_joint_def_default();
        d.base = base;
        d.enable_limit = flag01();
        d.lower = frange(-2, 0);
        d.upper = frange(0, 2);
        d.enable_motor = flag01();
        d.motor_speed = frange(-5, 5);
        d.max_motor_force = frange(0, 1000);
        if (cookie) d.internal_value = 0;
        if (spoil_kind) { d.lower = NAN; field = "lower"; }
        CALL(hearth_joint_create_slider(w, nul ? NULL : &d, po), expected, field, &out, sizeof out);
        if (r == HEARTH_OK) { Obj *o = add(fw, K_JOINT, TO_ID(out)); o->meta = type; o->a = TO_ID(base.body_a); o->b = TO_ID(base.body_b); }
        break;
    }
    }
    if (expected == HEARTH_OK) check_state(fw, "after a joint was created");
}

static void op_joint_other(FWorld *fw) {
    FAULTS(F_NULL_WORLD, F_ID, F_NULL_OUT, F_NUMBER, F_FLAG);
    Obj *j = f == F_ID ? NULL : pick(fw, K_JOINT);
    if (!j && f != F_ID && f != F_NULL_WORLD) return;
    HearthJointId jid = j ? joint_id(j->id) : joint_id(bad_id(fw, K_JOINT));
    HearthResult jr = f == F_NULL_WORLD ? HEARTH_ERROR_NULL_POINTER : j ? HEARTH_OK : HEARTH_ERROR_INVALID_ID;
    uint32_t t = j ? j->meta : 99;
    HearthWorld *w = W(fw, f);
    int nul = f == F_NULL_OUT;
    /* Getters check their outputs before the id. */
    HearthResult gr = jr == HEARTH_ERROR_NULL_POINTER || nul ? HEARTH_ERROR_NULL_POINTER : jr;
    bool e_out;
    float a_out, b_out;
    HearthVec3 v1, v2;
    memset(&e_out, SENTINEL, sizeof e_out);
    memset(&a_out, SENTINEL, sizeof a_out);
    memset(&b_out, SENTINEL, sizeof b_out);
    memset(&v1, SENTINEL, sizeof v1);
    memset(&v2, SENTINEL, sizeof v2);
    int has_motor = t == HEARTH_JOINT_HINGE || t == HEARTH_JOINT_SLIDER;
    int has_limits = t != HEARTH_JOINT_FIXED;
    int has_cone = t == HEARTH_JOINT_BALL;
    int has_spring = t == HEARTH_JOINT_HINGE || t == HEARTH_JOINT_DISTANCE;
    /* A setter: world, then the flag, then the id, then the kind, then the numbers. */
#define SETTER_RESULT(has)                                                                   \
    (jr == HEARTH_ERROR_NULL_POINTER ? jr                                                     \
     : f == F_FLAG                   ? HEARTH_ERROR_INVALID_ARGUMENT                          \
     : jr != HEARTH_OK               ? jr                                                     \
     : !(has) || f == F_NUMBER       ? HEARTH_ERROR_INVALID_ARGUMENT                          \
                                     : HEARTH_OK)
#define GETTER_RESULT(has) (gr != HEARTH_OK ? gr : !(has) ? HEARTH_ERROR_INVALID_ARGUMENT : HEARTH_OK)
    uint8_t en = f == F_FLAG ? bad_flag() : flag01();
    switch (rnd(14)) {
    case 0: {
        if (f == F_ID && chance(50)) break;
        CALL(hearth_joint_destroy(w, jid), jr, NULL, NULL, 0);
        if (r == HEARTH_OK) { bury(K_JOINT, j->id); drop_at(fw, K_JOINT, (int)(j - fw->live[K_JOINT])); }
        break;
    }
    case 1: {
        uint32_t type;
        memset(&type, SENTINEL, sizeof type);
        CALL(hearth_joint_get_type(w, jid, nul ? NULL : &type), gr, NULL, &type, sizeof type);
        if (r == HEARTH_OK && type != t) fail("joint type", "differs from the created one");
        break;
    }
    case 2: {
        HearthBodyId a, b;
        memset(&a, SENTINEL, sizeof a);
        memset(&b, SENTINEL, sizeof b);
        CALL(hearth_joint_get_bodies(w, jid, nul && chance(50) ? NULL : &a, nul ? NULL : &b), gr, NULL, &a, sizeof a);
        if (r == HEARTH_OK && (!id_eq(TO_ID(a), j->a) || !id_eq(TO_ID(b), j->b))) fail("joint bodies", "differ from the def's");
        break;
    }
    case 3: {
        float speed = t == HEARTH_JOINT_HINGE ? frange(-20, 20) : frange(-5, 5), max = frange(0, 500);
        if (f == F_NUMBER) { if (chance(50)) speed = NAN; else max = -1; }
        CALL(hearth_joint_set_motor(w, jid, en, speed, max), SETTER_RESULT(has_motor), NULL, NULL, 0);
        break;
    }
    case 4: { CALL(hearth_joint_get_motor(w, jid, nul ? NULL : &e_out, &a_out, &b_out), GETTER_RESULT(has_motor), NULL, &e_out, sizeof e_out); break; }
    case 5: {
        float lo, hi;
        if (t == HEARTH_JOINT_DISTANCE) { lo = frange(0, 1); hi = lo + frange(0, 2); }
        else if (t == HEARTH_JOINT_SLIDER) { lo = frange(-2, 0); hi = frange(0, 2); }
        else { lo = frange(-3.1f, 0); hi = frange(0, 3.1f); }
        if (f == F_NUMBER) { if (chance(50)) { float x = lo; lo = hi + 0.5f; hi = x; } else lo = NAN; }
        CALL(hearth_joint_set_limits(w, jid, en, lo, hi), SETTER_RESULT(has_limits), NULL, NULL, 0);
        break;
    }
    case 6: { CALL(hearth_joint_get_limits(w, jid, &e_out, nul ? NULL : &a_out, &b_out), GETTER_RESULT(has_limits), NULL, &a_out, sizeof a_out); break; }
    case 7: {
        float angle = f == F_NUMBER ? (chance(50) ? -0.1f : 3.5f) : frange(0, 3.14f);
        CALL(hearth_joint_set_cone_limit(w, jid, en, angle), SETTER_RESULT(has_cone), NULL, NULL, 0);
        break;
    }
    case 8: { CALL(hearth_joint_get_cone_limit(w, jid, &e_out, nul ? NULL : &a_out), GETTER_RESULT(has_cone), NULL, &a_out, sizeof a_out); break; }
    case 9: {
        float hz = frange(0, 10), z = frange(0, 2);
        if (f == F_NUMBER) { if (chance(50)) hz = -1; else z = NAN; }
        CALL(hearth_joint_set_spring(w, jid, en, hz, z), SETTER_RESULT(has_spring), NULL, NULL, 0);
        break;
    }
    case 10: { CALL(hearth_joint_get_spring(w, jid, &e_out, &a_out, nul ? NULL : &b_out), GETTER_RESULT(has_spring), NULL, &b_out, sizeof b_out); break; }
    case 11: {
        CALL(hearth_joint_get_force(w, jid, &v1, nul ? NULL : &v2), gr, NULL, &v1, sizeof v1);
        if (r == HEARTH_OK && (!finite3(v1) || !finite3(v2))) fail("joint force", "not finite");
        break;
    }
    case 12: { CALL(hearth_joint_is_broken(w, jid, nul ? NULL : &e_out), gr, NULL, &e_out, sizeof e_out); break; }
    default: {
        HearthJointId ids[MAX_LIVE];
        size_t count;
        memset(ids, SENTINEL, sizeof ids);
        memset(&count, SENTINEL, sizeof count);
        size_t cap = chance(50) ? 0 : chance(50) ? 1 : MAX_LIVE;
        int null_arr = cap > 0 && chance(10);
        HearthResult e = jr == HEARTH_ERROR_NULL_POINTER || nul || null_arr ? HEARTH_ERROR_NULL_POINTER : HEARTH_OK;
        size_t nb = 0;
        if (e == HEARTH_OK) hearth_world_get_broken_joints(fw->w, NULL, 0, &nb);
        if (e == HEARTH_OK && cap > 0 && cap < nb) e = HEARTH_ERROR_BUFFER_TOO_SMALL;
        CALL(hearth_world_get_broken_joints(w, null_arr ? NULL : ids, cap, nul ? NULL : &count), e, NULL, ids, sizeof ids);
        break;
    }
    }
#undef SETTER_RESULT
#undef GETTER_RESULT
}

/* ----------------------------------------------------------------------- soft bodies */
static HearthSoftBodyDef good_soft_def(FWorld *fw) {
    HearthSoftBodyDef d = hearth_soft_body_def_default();
    d.transform = xf(vec(frange(-3, 3), frange(0.5f, 4), frange(-3, 3)), quat_any());
    if (chance(30)) d.velocity = vec_up_to(fw->def.max_linear_speed < 5 ? fw->def.max_linear_speed : 5, 5);
    d.mass = frange(0.1f, 10);
    if (chance(30)) d.edge_compliance = frange(0, 0.01f);
    if (chance(30)) d.bend_compliance = chance(30) ? INFINITY : frange(0, 1);
    d.preserve_volume = flag01();
    if (chance(30)) d.pressure = frange(0, 500);
    if (chance(30)) d.damping = frange(0, 5);
    if (chance(30)) d.deformation_damping = frange(0, 5);
    if (chance(30)) d.restitution = frange(0, 1);
    if (chance(30)) d.vertex_radius = frange(0, 0.05f);
    if (chance(30)) d.gravity_scale = frange(-2, 2);
    d.substeps = 1 + rnd(10);
    d.iterations = 1 + rnd(3);
    if (chance(10)) d.collide = 0;
    return d;
}

static void op_soft_create(FWorld *fw) {
    if (full(fw, K_SOFT)) return;
    FAULTS(F_NULL_WORLD, F_NULL_IN, F_NULL_OUT, F_COOKIE, F_NUMBER, F_FLAG);
    HearthSoftBodyDef d = good_soft_def(fw);
    const char *field = NULL;
    int geom_fault = f == F_NUMBER && chance(50);
    if (f == F_COOKIE) d.internal_value = 0;
    if (f == F_FLAG) { if (chance(50)) { d.collide = bad_flag(); field = "collide"; } else { d.preserve_volume = bad_flag(); field = "preserve_volume"; } }
    if (f == F_NUMBER && !geom_fault) {
        switch (rnd(6)) {
        case 0: d.mass = chance(50) ? 0.0f : NAN; field = "mass"; break;
        case 1: d.edge_compliance = -1; field = "edge_compliance"; break;
        case 2: d.transform.position = spoil3(d.transform.position, nonfinite()); field = "position"; break;
        case 3: d.damping = NAN; field = "damping"; break;
        case 4: d.substeps = chance(50) ? 0 : 65; field = "substeps"; break;
        default: d.transform.rotation = bad_quat(); field = "rotation"; break;
        }
    }
    HearthResult expected = f == F_NONE ? HEARTH_OK
                            : (f == F_NULL_WORLD || f == F_NULL_IN || f == F_NULL_OUT) ? HEARTH_ERROR_NULL_POINTER
                                                                                      : HEARTH_ERROR_INVALID_ARGUMENT;
    HearthSoftBodyId out;
    memset(&out, SENTINEL, sizeof out);
    HearthSoftBodyId *po = f == F_NULL_OUT ? NULL : &out;
    HearthWorld *w = W(fw, f);
    HearthSoftBodyDef *pd = f == F_NULL_IN ? NULL : &d;
    int r_ok = 0;
    switch (rnd(4)) {
    case 0: {
        float radius = frange(0.2f, 1);
        uint32_t sub = rnd(3);
        if (geom_fault) { if (chance(50)) { radius = chance(50) ? 0.0f : nonfinite(); field = "radius"; } else { sub = 7 + rnd(10); field = "subdivisions"; } }
        CALL(hearth_soft_body_create_icosphere(w, pd, radius, sub, po), expected, field, &out, sizeof out);
        r_ok = r == HEARTH_OK;
        break;
    }
    case 1: {
        HearthVec3 h = vec(frange(0.1f, 1), frange(0.1f, 1), frange(0.1f, 1));
        uint32_t c = 1 + rnd(3);
        if (geom_fault) { if (chance(50)) { h = spoil3(h, chance(50) ? -1.0f : nonfinite()); field = "half_extents"; } else { c = chance(50) ? 0 : 65; field = "cells"; } }
        CALL(hearth_soft_body_create_box(w, pd, h, c, 1 + rnd(3), 1 + rnd(2), po), expected, field, &out, sizeof out);
        r_ok = r == HEARTH_OK;
        break;
    }
    case 2: {
        float wd = frange(0.5f, 2), ht = frange(0.5f, 2);
        uint32_t cols = 1 + rnd(8), rows = 1 + rnd(8);
        if (geom_fault) { if (chance(50)) { wd = chance(50) ? 0.0f : NAN; field = "width"; } else { rows = chance(50) ? 0 : 1025; field = "rows"; } }
        CALL(hearth_soft_body_create_cloth(w, pd, wd, ht, cols, rows, po), expected, field, &out, sizeof out);
        r_ok = r == HEARTH_OK;
        break;
    }
    default: {
        /* A tetrahedron, wound outwards. */
        HearthVec3 v[4];
        v[0] = vec(0, 0, 0);
        v[1] = vec(1, 0, 0);
        v[2] = vec(0, 1, 0);
        v[3] = vec(0, 0, 1);
        uint32_t idx[12] = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3};
        float masses[4] = {0.25f, 0.5f, 0.25f, 1.0f};
        size_t nv = 4, ni = 12;
        int use_masses = chance(50);
        int null_verts = 0;
        if (geom_fault) {
            switch (rnd(5)) {
            case 0: v[2] = spoil3(v[2], nonfinite()); field = "vert"; break;
            case 1: idx[4] = 7; field = "index"; break;
            case 2: ni = 11; field = "index_count"; break;
            case 3: masses[1] = chance(50) ? 0.0f : NAN; use_masses = 1; field = "mass"; break;
            default: idx[1] = idx[0]; field = "triangle"; break;
            }
        }
        if (f == F_NULL_IN && chance(50)) { null_verts = 1; pd = &d; }
        CALL(hearth_soft_body_create_mesh(w, pd, null_verts ? NULL : v, nv, idx, ni, use_masses ? masses : NULL, po),
             expected, field, &out, sizeof out);
        r_ok = r == HEARTH_OK;
        break;
    }
    }
    if (r_ok) {
        size_t n = 0;
        hearth_soft_body_get_vertex_count(fw->w, out, &n);
        add(fw, K_SOFT, TO_ID(out))->meta = (uint32_t)n;
        check_state(fw, "after a soft body was created");
    }
}

static void op_soft_other(FWorld *fw) {
    FAULTS(F_NULL_WORLD, F_ID, F_NULL_OUT, F_NUMBER, F_NULL_IN, F_FLAG);
    Obj *s = f == F_ID ? NULL : pick(fw, K_SOFT);
    if (!s && f != F_ID && f != F_NULL_WORLD) return;
    HearthSoftBodyId sid = s ? soft_id(s->id) : soft_id(bad_id(fw, K_SOFT));
    HearthResult sr = f == F_NULL_WORLD ? HEARTH_ERROR_NULL_POINTER : s ? HEARTH_OK : HEARTH_ERROR_INVALID_ID;
    HearthWorld *w = W(fw, f);
    int nul = f == F_NULL_OUT;
    HearthResult gr = sr == HEARTH_ERROR_NULL_POINTER || nul ? HEARTH_ERROR_NULL_POINTER : sr;
    uint32_t nv = s ? s->meta : 4;
    uint32_t vertex = f == F_NUMBER && chance(50) ? nv + rnd(10) : rnd(nv ? nv : 1);
    int bad_vertex = vertex >= nv;
    HearthResult vr = sr != HEARTH_OK ? sr : bad_vertex ? HEARTH_ERROR_INVALID_ARGUMENT : HEARTH_OK;
    union {
        HearthVec3 v;
        float x;
        size_t n;
        uint64_t u64;
        bool flag;
        HearthSoftBodySettings st;
    } out;
    memset(&out, SENTINEL, sizeof out);
    switch (rnd(20)) {
    case 0: {
        if (f == F_ID && chance(50)) break;
        CALL(hearth_soft_body_destroy(w, sid), sr, NULL, NULL, 0);
        if (r == HEARTH_OK) { bury(K_SOFT, s->id); drop_at(fw, K_SOFT, (int)(s - fw->live[K_SOFT])); }
        break;
    }
    case 1: { CALL(hearth_soft_body_get_vertex_count(w, sid, nul ? NULL : &out.n), gr, NULL, &out, sizeof out); break; }
    case 2: { CALL(hearth_soft_body_get_triangle_count(w, sid, nul ? NULL : &out.n), gr, NULL, &out, sizeof out); break; }
    case 3:
    case 4:
    case 5: {
        /* Bulk reads: count only, enough room, too little room. */
        size_t count;
        memset(&count, SENTINEL, sizeof count);
        memset(g_out_vec, SENTINEL, sizeof g_out_vec);
        size_t need = nv;
        uint32_t tri[3 * 4 * 64];
        memset(tri, SENTINEL, sizeof tri);
        size_t cap = chance(30) ? 0 : chance(30) ? (need ? need - 1 : 0) : sizeof g_out_vec / sizeof g_out_vec[0];
        int null_arr = cap > 0 && chance(10);
        HearthResult e = sr == HEARTH_ERROR_NULL_POINTER || nul ? HEARTH_ERROR_NULL_POINTER : sr;
        if (e == HEARTH_OK && null_arr) e = HEARTH_ERROR_NULL_POINTER;
        if (e == HEARTH_OK && cap > 0 && cap < need) e = HEARTH_ERROR_BUFFER_TOO_SMALL;
        int which = (int)rnd(3);
        if (which == 0) {
            CALL(hearth_soft_body_get_positions(w, sid, null_arr ? NULL : g_out_vec, cap, nul ? NULL : &count), e, NULL, g_out_vec, sizeof(HearthVec3) * 4);
        } else if (which == 1) {
            CALL(hearth_soft_body_get_normals(w, sid, null_arr ? NULL : g_out_vec, cap, nul ? NULL : &count), e, NULL, g_out_vec, sizeof(HearthVec3) * 4);
            if (r == HEARTH_OK && cap) for (size_t k = 0; k < count; k++) if (!finite3(g_out_vec[k])) { fail("soft normals", "not finite"); break; }
        } else {
            size_t ntri = 0;
            if (s) hearth_soft_body_get_triangle_count(fw->w, sid, &ntri);
            size_t icap = cap == 0 ? 0 : cap < need ? (ntri > 0 ? 3 * ntri - 1 : 0) : sizeof tri / sizeof tri[0];
            HearthResult ei = sr == HEARTH_ERROR_NULL_POINTER || nul ? HEARTH_ERROR_NULL_POINTER : sr;
            if (ei == HEARTH_OK && null_arr && icap > 0) ei = HEARTH_ERROR_NULL_POINTER;
            if (ei == HEARTH_OK && icap > 0 && icap < 3 * ntri) ei = HEARTH_ERROR_BUFFER_TOO_SMALL;
            if (3 * ntri > sizeof tri / sizeof tri[0]) break;
            CALL(hearth_soft_body_get_indices(w, sid, null_arr ? NULL : tri, icap, nul ? NULL : &count), ei, NULL, tri, sizeof tri);
        }
        break;
    }
    case 6: {
        HearthResult e = gr != HEARTH_OK ? gr : vr;
        CALL(hearth_soft_body_get_vertex_position(w, sid, vertex, nul ? NULL : &out.v), e, NULL, &out, sizeof out);
        break;
    }
    case 7: {
        HearthResult e = gr != HEARTH_OK ? gr : vr;
        CALL(hearth_soft_body_get_vertex_velocity(w, sid, vertex, nul ? NULL : &out.v), e, NULL, &out, sizeof out);
        break;
    }
    case 8: { CALL(hearth_soft_body_get_center(w, sid, nul ? NULL : &out.v), gr, NULL, &out, sizeof out); break; }
    case 9: {
        /* All five scalar getters, so that the default run reaches each of them. */
        float *p = nul ? NULL : &out.x;
        { CALL(hearth_soft_body_get_mass(w, sid, p), gr, NULL, &out, sizeof out); }
        memset(&out, SENTINEL, sizeof out);
        { CALL(hearth_soft_body_get_volume(w, sid, p), gr, NULL, &out, sizeof out); }
        memset(&out, SENTINEL, sizeof out);
        { CALL(hearth_soft_body_get_rest_volume(w, sid, p), gr, NULL, &out, sizeof out); }
        memset(&out, SENTINEL, sizeof out);
        { CALL(hearth_soft_body_get_pressure(w, sid, p), gr, NULL, &out, sizeof out); }
        memset(&out, SENTINEL, sizeof out);
        { CALL(hearth_soft_body_get_user_data(w, sid, nul ? NULL : &out.u64), gr, NULL, &out, sizeof out); }
        break;
    }
    case 10: {
        float p = f == F_NUMBER ? (chance(50) ? -1.0f : nonfinite()) : frange(0, 500);
        HearthResult e = sr != HEARTH_OK ? sr : f == F_NUMBER ? HEARTH_ERROR_INVALID_ARGUMENT : HEARTH_OK;
        CALL(hearth_soft_body_set_pressure(w, sid, p), e, "pressure", NULL, 0);
        break;
    }
    case 11: {
        /* pin to the world, or to a body (live or, with F_ID on the body, bad) */
        Obj *b = pick(fw, K_BODY);
        HearthBodyId body = b && chance(50) ? body_id(b->id) : body_id(NULL_ID);
        HearthResult e = vr;
        if (f == F_NUMBER && !bad_vertex) e = sr; /* no bad number here */
        CALL(hearth_soft_body_pin_vertex(w, sid, vertex, body), e, NULL, NULL, 0);
        break;
    }
    case 12: {
        if (!s || f == F_ID) break;
        HearthBodyId body = body_id(bad_id(fw, K_BODY));
        int is_null = !body.index && !body.generation;
        HearthResult e = sr != HEARTH_OK ? sr : is_null ? vr : bad_vertex ? HEARTH_ERROR_INVALID_ARGUMENT : HEARTH_ERROR_INVALID_ID;
        if (!is_null && bad_vertex) break; /* either code */
        CALL(hearth_soft_body_pin_vertex(w, sid, vertex, body), e, NULL, NULL, 0);
        break;
    }
    case 13: { CALL(hearth_soft_body_unpin_vertex(w, sid, vertex), vr, NULL, NULL, 0); break; }
    case 14: {
        HearthResult e = gr != HEARTH_OK ? gr : vr;
        CALL(hearth_soft_body_is_vertex_pinned(w, sid, vertex, nul ? NULL : &out.flag), e, NULL, &out, sizeof out);
        break;
    }
    case 15: {
        HearthVec3 j = vec_up_to(10, 5);
        HearthResult e = vr;
        if (f == F_NUMBER && !bad_vertex) {
            j = chance(50) ? spoil3(j, nonfinite()) : scale3(dir3(), chance(50) ? MAX_IMPULSE * 1.01f : FLT_MAX);
            e = sr != HEARTH_OK ? sr : HEARTH_ERROR_INVALID_ARGUMENT;
        }
        CALL(hearth_soft_body_apply_impulse(w, sid, vertex, j), e, NULL, NULL, 0);
        break;
    }
    case 16: {
        HearthVec3 j = vec_up_to(20, 10);
        HearthResult e = sr;
        if (f == F_NUMBER) {
            j = chance(50) ? spoil3(j, nonfinite()) : scale3(dir3(), chance(50) ? MAX_IMPULSE * 1.01f : FLT_MAX);
            e = sr != HEARTH_OK ? sr : HEARTH_ERROR_INVALID_ARGUMENT;
        }
        CALL(hearth_soft_body_apply_impulse_all(w, sid, j), e, NULL, NULL, 0);
        break;
    }
    case 17: { CALL(hearth_soft_body_get_settings(w, sid, nul ? NULL : &out.st), gr, NULL, &out, sizeof out); break; }
    case 18: {
        HearthSoftBodySettings st;
        HearthSoftBodyDef d = good_soft_def(fw);
        st.edge_compliance = d.edge_compliance;
        st.bend_compliance = d.bend_compliance;
        st.preserve_volume = d.preserve_volume;
        st.volume_compliance = d.volume_compliance;
        st.pressure = d.pressure;
        st.damping = d.damping;
        st.deformation_damping = d.deformation_damping;
        st.friction = d.friction;
        st.restitution = d.restitution;
        st.vertex_radius = d.vertex_radius;
        st.gravity_scale = d.gravity_scale;
        st.substeps = d.substeps;
        st.iterations = d.iterations;
        st.collide = d.collide;
        const char *field = NULL;
        HearthResult e = sr;
        if (f == F_FLAG) { st.collide = bad_flag(); field = "collide"; if (e != HEARTH_ERROR_NULL_POINTER) e = HEARTH_ERROR_INVALID_ARGUMENT; }
        if (f == F_NUMBER) {
            switch (rnd(3)) {
            case 0: st.damping = -1; field = "damping"; break;
            case 1: st.iterations = 17; field = "iterations"; break;
            default: st.vertex_radius = NAN; field = "vertex_radius"; break;
            }
            if (e == HEARTH_OK) e = HEARTH_ERROR_INVALID_ARGUMENT;
        }
        if (f == F_NULL_IN && e != HEARTH_ERROR_NULL_POINTER) e = HEARTH_ERROR_NULL_POINTER;
        CALL(hearth_soft_body_set_settings(w, sid, f == F_NULL_IN ? NULL : &st), e, field, NULL, 0);
        break;
    }
    default: {
        float edge = frange(0, 0.01f), bend = chance(30) ? INFINITY : frange(0, 1), vol = frange(0, 0.01f);
        HearthResult e = sr;
        const char *field = NULL;
        if (f == F_NUMBER) { if (chance(50)) { edge = chance(50) ? INFINITY : -1.0f; field = "edge"; } else { bend = NAN; field = "bend"; } if (e == HEARTH_OK) e = HEARTH_ERROR_INVALID_ARGUMENT; }
        CALL(hearth_soft_body_set_compliance(w, sid, edge, bend, vol), e, field, NULL, 0);
        break;
    }
    }
    if (s) check_state(fw, "after a soft-body call");
}

/* ------------------------------------------------------------- world-level odds and ends */
static void op_misc(FWorld *fw) {
    FAULTS(F_NULL_WORLD, F_NULL_OUT, F_NUMBER);
    HearthWorld *w = W(fw, f);
    int nul = f == F_NULL_OUT;
    switch (rnd(9)) {
    case 0: {
        mark("hearth_version");
        mark("hearth_result_name");
        if (hearth_version() != HEARTH_VERSION) fail("version", "differs from the header's");
        const char *name = hearth_result_name((int32_t)next_u64());
        if (!name || !name[0]) fail("result_name", "empty");
        pass();
        break;
    }
    case 1: {
        char buf[8];
        memset(buf, SENTINEL, sizeof buf);
        mark("hearth_last_error_message");
        size_t full_len = hearth_last_error_message(NULL, 0);
        size_t n = hearth_last_error_message(buf, rnd(9));
        if (n != full_len) fail("last_error_message", "length differs between calls");
        pass();
        break;
    }
    case 2: {
        HearthVec3 g = vec_up_to(MAX_ACCELERATION, 20);
        if (f == F_NUMBER) g = chance(50) ? spoil3(g, nonfinite()) : scale3(dir3(), MAX_ACCELERATION * 1.01f);
        HearthResult e = f == F_NULL_WORLD ? HEARTH_ERROR_NULL_POINTER : f == F_NUMBER ? HEARTH_ERROR_INVALID_ARGUMENT : HEARTH_OK;
        CALL(hearth_world_set_gravity(w, g), e, "gravity", NULL, 0);
        break;
    }
    case 3: {
        HearthVec3 g;
        memset(&g, SENTINEL, sizeof g);
        CALL(hearth_world_get_gravity(w, nul ? NULL : &g), f == F_NULL_WORLD || nul ? HEARTH_ERROR_NULL_POINTER : HEARTH_OK, NULL, &g, sizeof g);
        break;
    }
    case 4: {
        HearthWorldCounters c;
        memset(&c, SENTINEL, sizeof c);
        CALL(hearth_world_get_counters(w, nul ? NULL : &c), f == F_NULL_WORLD || nul ? HEARTH_ERROR_NULL_POINTER : HEARTH_OK, NULL, &c, sizeof c);
        if (r == HEARTH_OK && c.body_count != (uint32_t)fw->n[K_BODY]) fail("counters", "body count differs from the tracked one");
        uint64_t hash;
        memset(&hash, SENTINEL, sizeof hash);
        {
            CALL(hearth_world_get_hash(w, nul ? NULL : &hash), f == F_NULL_WORLD || nul ? HEARTH_ERROR_NULL_POINTER : HEARTH_OK, NULL, &hash, sizeof hash);
        }
        {
            /* (No random draw: the default run's sequence, which reaches every export, stays.) */
            CALL(hearth_world_rebuild_broadphase(w), f == F_NULL_WORLD ? HEARTH_ERROR_NULL_POINTER : HEARTH_OK, NULL, NULL, 0);
        }
        break;
    }
    case 5: {
        uint32_t v = 1 + rnd(64), p = 1 + rnd(64);
        if (f == F_NUMBER) { if (chance(50)) v = chance(50) ? 0 : 65; else p = chance(50) ? 0 : 1000; }
        HearthResult e = f == F_NULL_WORLD ? HEARTH_ERROR_NULL_POINTER : f == F_NUMBER ? HEARTH_ERROR_INVALID_ARGUMENT : HEARTH_OK;
        CALL(hearth_world_set_particle_iterations(w, v, p), e, "iterations", NULL, 0);
        break;
    }
    case 6: {
        size_t n;
        memset(&n, SENTINEL, sizeof n);
        CALL(hearth_world_get_soft_body_count(w, nul ? NULL : &n), f == F_NULL_WORLD || nul ? HEARTH_ERROR_NULL_POINTER : HEARTH_OK, NULL, &n, sizeof n);
        if (r == HEARTH_OK && n != (size_t)fw->n[K_SOFT]) fail("soft body count", "differs from the tracked one");
        break;
    }
    default: {
        /* Every def default carries its cookie (a def from one is accepted: covered above). */
        HearthWorldDef wd = hearth_world_def_default();
        HearthBodyDef bd = hearth_body_def_default();
        HearthShapeDef sd = hearth_shape_def_default();
        HearthParticleDef pd = hearth_particle_def_default();
        HearthBurstDef bu = hearth_burst_def_default();
        HearthSoftBodyDef so = hearth_soft_body_def_default();
        HearthBallJointDef j1 = hearth_ball_joint_def_default();
        HearthHingeJointDef j2 = hearth_hinge_joint_def_default();
        HearthFixedJointDef j3 = hearth_fixed_joint_def_default();
        HearthDistanceJointDef j4 = hearth_distance_joint_def_default();
        HearthSliderJointDef j5 = hearth_slider_joint_def_default();
        HearthGravityGeneratorDef g1 = hearth_gravity_generator_def_default();
        HearthDragGeneratorDef g2 = hearth_drag_generator_def_default();
        HearthSpringGeneratorDef g3 = hearth_spring_generator_def_default();
        HearthStiffSpringGeneratorDef g4 = hearth_stiff_spring_generator_def_default();
        HearthBuoyancyGeneratorDef g5 = hearth_buoyancy_generator_def_default();
        HearthExplosionGeneratorDef g6 = hearth_explosion_generator_def_default();
        HearthRodGeneratorDef g7 = hearth_rod_generator_def_default();
        HearthCableGeneratorDef g8 = hearth_cable_generator_def_default();
        HearthUserForceGeneratorDef g9 = hearth_user_force_generator_def_default();
        HearthUserContactGeneratorDef g10 = hearth_user_contact_generator_def_default();
        const char *names[] = {"hearth_world_def_default", "hearth_body_def_default", "hearth_shape_def_default",
                               "hearth_particle_def_default", "hearth_burst_def_default", "hearth_soft_body_def_default",
                               "hearth_ball_joint_def_default", "hearth_hinge_joint_def_default",
                               "hearth_fixed_joint_def_default", "hearth_distance_joint_def_default",
                               "hearth_slider_joint_def_default", "hearth_gravity_generator_def_default",
                               "hearth_drag_generator_def_default", "hearth_spring_generator_def_default",
                               "hearth_stiff_spring_generator_def_default", "hearth_buoyancy_generator_def_default",
                               "hearth_explosion_generator_def_default", "hearth_rod_generator_def_default",
                               "hearth_cable_generator_def_default", "hearth_user_force_generator_def_default",
                               "hearth_user_contact_generator_def_default"};
        for (size_t i = 0; i < sizeof names / sizeof names[0]; i++) mark(names[i]);
        uint32_t c = wd.internal_value;
        if (bd.internal_value != c || sd.internal_value != c || pd.internal_value != c || bu.internal_value != c ||
            so.internal_value != c || j1.internal_value != c || j2.internal_value != c || j3.internal_value != c ||
            j4.internal_value != c || j5.internal_value != c || g1.internal_value != c || g2.internal_value != c ||
            g3.internal_value != c || g4.internal_value != c || g5.internal_value != c || g6.internal_value != c ||
            g7.internal_value != c || g8.internal_value != c || g9.internal_value != c || g10.internal_value != c)
            fail("defaults", "a def default without the cookie");
        pass();
        break;
    }
    }
}

/* ----------------------------------------------------------------- coverage of the API */
#define MAX_NAMES 256
static char g_names[MAX_NAMES][64];
static int g_nnames;

static void mark(const char *call) {
    char name[64];
    size_t n = 0;
    while (call[n] && call[n] != '(' && call[n] != ' ' && n < sizeof name - 1) n++;
    memcpy(name, call, n);
    name[n] = 0;
    for (int i = 0; i < g_nnames; i++)
        if (strcmp(g_names[i], name) == 0) return;
    if (g_nnames < MAX_NAMES) memcpy(g_names[g_nnames++], name, n + 1);
}

static int cmp_names(const void *a, const void *b) { return strcmp((const char *)a, (const char *)b); }

/* ---------------------------------------------------------------------------- the run */
typedef void (*WorldOp)(FWorld *);
typedef struct {
    const char *name;
    WorldOp fn;
    int weight;
} Op;

/* ---------------------------------------------------------------------------- recording */
/* A sink that counts the bytes: recording runs through every step without touching disk. */
static size_t g_recorded_bytes;
static int32_t fuzz_sink(void *user_data, const uint8_t *bytes, size_t len) {
    (void)bytes;
    *(size_t *)user_data += len;
    return 0;
}

static void op_record(FWorld *fw) {
    FAULTS(F_NULL_WORLD, F_NULL_IN, F_COOKIE, F_FLAG);
    HearthWorld *w = W(fw, f);
    mark("hearth_record_def_default");
    HearthRecordDef d = hearth_record_def_default();
    d.record_contacts = flag01();
    const char *field = NULL;
    if (f == F_COOKIE) d.internal_value ^= 1u + rnd(0xFFFF);
    if (f == F_FLAG) { d.record_contacts = bad_flag(); field = "record_contacts"; }
    HearthResult def_fault = f == F_COOKIE || f == F_FLAG ? HEARTH_ERROR_INVALID_ARGUMENT : HEARTH_OK;
    HearthResult null_fault = f == F_NULL_WORLD || f == F_NULL_IN ? HEARTH_ERROR_NULL_POINTER : HEARTH_OK;
    switch (rnd(4)) {
    case 0:
    case 1: {
        d.write = fuzz_sink;
        d.user_data = &g_recorded_bytes;
        HearthResult e = null_fault ? null_fault : def_fault ? def_fault : fw->recording ? HEARTH_ERROR_INVALID_ARGUMENT : HEARTH_OK;
        CALL(hearth_world_record_start_callback(w, f == F_NULL_IN ? NULL : &d), e, field, NULL, 0);
        if (r == HEARTH_OK) fw->recording = 1;
        break;
    }
    case 2: {
        /* A file that cannot be created: an I/O error naming the path, nothing started. */
        const char *path = "/nonexistent-hearth-fuzz-dir/recording.hrec";
        HearthResult e = null_fault ? null_fault
                         : def_fault ? def_fault
                         : fw->recording ? HEARTH_ERROR_INVALID_ARGUMENT
                                         : HEARTH_ERROR_IO;
        CALL(hearth_world_record_start_file(w, f == F_NULL_IN ? NULL : path, &d), e, field, NULL, 0);
        break;
    }
    default: {
        HearthResult e = f == F_NULL_WORLD ? HEARTH_ERROR_NULL_POINTER : fw->recording ? HEARTH_OK : HEARTH_ERROR_INVALID_ARGUMENT;
        CALL(hearth_world_record_stop(w), e, NULL, NULL, 0);
        if (r == HEARTH_OK) fw->recording = 0;
        break;
    }
    }
}

/* ------------------------------------------------------------------------ shared geometry */
/* Shapes using geometry `id` of kind `kind` (tracked: a body's destruction drops its shapes). */
static int geometry_users(FWorld *fw, int kind, Id id) {
    int n = 0;
    for (int i = 0; i < fw->n[K_SHAPE]; i++)
        n += fw->live[K_SHAPE][i].meta == (uint32_t)kind && id_eq(fw->live[K_SHAPE][i].b, id);
    return n;
}

static HearthVec3 g_geo_points[9 * 9]; /* a mesh grid of 8 × 8 cells, or a hull cloud of up to 47 */
static uint32_t g_geo_indices[6 * 8 * 8 + 3];
static float g_geo_heights[9 * 9];
static uint8_t g_geo_holes[8 * 8];

static void op_geometry_create(FWorld *fw) {
    FAULTS(F_NULL_WORLD, F_NULL_IN, F_NULL_OUT, F_COOKIE, F_NUMBER);
    HearthWorld *w = W(fw, f);
    HearthResult e = f == F_NULL_WORLD || f == F_NULL_IN || f == F_NULL_OUT ? HEARTH_ERROR_NULL_POINTER
                     : f == F_NUMBER || f == F_COOKIE                       ? HEARTH_ERROR_INVALID_ARGUMENT
                                                                            : HEARTH_OK;
    const char *field = NULL;
    switch (rnd(3)) {
    case 0: {
        if (full(fw, K_HULL)) return;
        /* A box's corners (never degenerate) and points inside and on it. */
        HearthVec3 half = vec(flog(0.01f, 5), flog(0.01f, 5), flog(0.01f, 5));
        size_t n = 8 + rnd(40);
        for (size_t i = 0; i < n; i++) {
            float sx = i < 8 ? ((i & 1) ? 1.0f : -1.0f) : frange(-1, 1);
            float sy = i < 8 ? ((i & 2) ? 1.0f : -1.0f) : frange(-1, 1);
            float sz = i < 8 ? ((i & 4) ? 1.0f : -1.0f) : frange(-1, 1);
            g_geo_points[i] = vec(sx * half.x, sy * half.y, sz * half.z);
        }
        mark("hearth_hull_def_default");
        HearthHullDef d = hearth_hull_def_default();
        if (chance(30)) d.convex_radius = frange(0, 0.05f);
        if (f == F_COOKIE) d.internal_value ^= 1u + rnd(0xFFFF);
        if (f == F_NUMBER) {
            switch (rnd(4)) {
            case 0: g_geo_points[rnd((uint32_t)n)].y = nonfinite(); break;
            case 1: n = 3; break;
            case 2: for (size_t i = 0; i < n; i++) g_geo_points[i].z = 0.0f; break; /* coplanar */
            default: d.convex_radius = chance(50) ? -0.1f : nonfinite(); field = "convex_radius"; break;
            }
        }
        HearthHullId out;
        memset(&out, SENTINEL, sizeof out);
        int null_def = f == F_NULL_IN && chance(50);
        CALL(hearth_hull_create(w, null_def ? NULL : &d, f == F_NULL_IN && !null_def ? NULL : g_geo_points, n,
                                f == F_NULL_OUT ? NULL : &out),
             e, field, &out, sizeof out);
        if (r == HEARTH_OK) add(fw, K_HULL, TO_ID(out));
        break;
    }
    case 1: {
        if (full(fw, K_MESH)) return;
        /* A bumpy grid of c × c cells, two triangles each, maybe one degenerate triangle. */
        uint32_t c = 1 + rnd(8);
        float cell = flog(0.1f, 10);
        size_t nv = (size_t)(c + 1) * (c + 1), ni = 0;
        for (uint32_t i = 0; i <= c; i++)
            for (uint32_t k = 0; k <= c; k++) g_geo_points[i * (c + 1) + k] = vec(k * cell, frange(-0.2f, 0.2f) * cell, i * cell);
        for (uint32_t i = 0; i < c; i++)
            for (uint32_t k = 0; k < c; k++) {
                uint32_t a = i * (c + 1) + k, b = a + 1, cc = a + c + 1, dd = cc + 1;
                uint32_t t[6] = {a, cc, dd, a, dd, b};
                for (int j = 0; j < 6; j++) g_geo_indices[ni++] = t[j];
            }
        int degenerate = chance(30);
        if (degenerate) { g_geo_indices[ni++] = 0; g_geo_indices[ni++] = 0; g_geo_indices[ni++] = 1; }
        if (f == F_NUMBER) {
            switch (rnd(3)) {
            case 0: g_geo_points[rnd((uint32_t)nv)].x = nonfinite(); break;
            case 1: g_geo_indices[rnd((uint32_t)ni)] = (uint32_t)nv + rnd(5); break;
            default: ni -= 1 + rnd(2); field = "index_count"; break;
            }
        }
        if (f == F_COOKIE) e = HEARTH_OK; /* no def */
        HearthMeshId out;
        memset(&out, SENTINEL, sizeof out);
        int null_v = f == F_NULL_IN && chance(50);
        CALL(hearth_mesh_create(w, null_v ? NULL : g_geo_points, nv, f == F_NULL_IN && !null_v ? NULL : g_geo_indices, ni,
                                f == F_NULL_OUT ? NULL : &out),
             e, field, &out, sizeof out);
        if (r == HEARTH_OK) {
            Obj *o = add(fw, K_MESH, TO_ID(out));
            o->meta = 2 * c * c;
            o->n_att_bodies = degenerate;
        }
        break;
    }
    default: {
        if (full(fw, K_HF)) return;
        uint32_t rows = 2 + rnd(8), cols = 2 + rnd(8);
        for (uint32_t i = 0; i < rows * cols; i++) g_geo_heights[i] = frange(-1, 1);
        int holes = chance(30);
        for (uint32_t i = 0; i < (rows - 1) * (cols - 1); i++) g_geo_holes[i] = (uint8_t)chance(20);
        if (f == F_NUMBER) {
            switch (rnd(3)) {
            case 0: g_geo_heights[rnd(rows * cols)] = nonfinite(); break;
            case 1: rows = chance(50) ? 1 : 40000; field = "rows"; break;
            default: holes = 1; g_geo_holes[rnd((rows - 1) * (cols - 1))] = 2 + (uint8_t)rnd(200); field = "holes"; break;
            }
        }
        if (f == F_COOKIE) e = HEARTH_OK;
        if (f == F_NULL_IN && chance(50)) { f = F_NONE; holes = 0; e = HEARTH_OK; } /* NULL holes: none */
        HearthHeightfieldId out;
        memset(&out, SENTINEL, sizeof out);
        CALL(hearth_heightfield_create(w, rows, cols, f == F_NULL_IN ? NULL : g_geo_heights, holes ? g_geo_holes : NULL,
                                       f == F_NULL_OUT ? NULL : &out),
             e, field, &out, sizeof out);
        if (r == HEARTH_OK) add(fw, K_HF, TO_ID(out));
        break;
    }
    }
}

static void op_geometry_other(FWorld *fw) {
    FAULTS(F_NULL_WORLD, F_ID, F_NULL_OUT);
    int kind = K_HULL + (int)rnd(3);
    Obj *o = pick(fw, kind);
    if (!o && f != F_ID) return;
    Id id = f == F_ID ? bad_id(fw, kind) : o->id;
    HearthWorld *w = W(fw, f);
    HearthResult e = f == F_NULL_WORLD ? HEARTH_ERROR_NULL_POINTER : f == F_ID ? HEARTH_ERROR_INVALID_ID : HEARTH_OK;
    uint32_t count;
    memset(&count, SENTINEL, sizeof count);
    uint32_t *po = f == F_NULL_OUT ? NULL : &count;
    HearthResult read_e = f == F_NULL_OUT ? HEARTH_ERROR_NULL_POINTER : e;
    if (chance(50)) {
        /* Reads. */
        if (kind == K_HULL) {
            CALL(hearth_hull_get_vertex_count(w, hull_id(id), po), read_e, NULL, &count, sizeof count);
            if (r == HEARTH_OK && (count < 4 || count > 255)) fail("hull", "vertex count outside 4..=255");
        } else if (kind == K_MESH) {
            if (chance(50)) {
                CALL(hearth_mesh_get_triangle_count(w, mesh_id(id), po), read_e, NULL, &count, sizeof count);
                if (r == HEARTH_OK && count != o->meta) fail("mesh", "triangle count differs from the grid's");
            } else {
                CALL(hearth_mesh_get_degenerate_count(w, mesh_id(id), po), read_e, NULL, &count, sizeof count);
                if (r == HEARTH_OK && count != (uint32_t)o->n_att_bodies) fail("mesh", "degenerate count differs");
            }
        } else {
            /* A heightfield has no reads: destroy a stale one instead. */
            if (f == F_NULL_OUT) return;
            if (f == F_NONE) return;
            CALL(hearth_heightfield_destroy(w, hf_id(id)), e, NULL, NULL, 0);
        }
        return;
    }
    if (f == F_NULL_OUT) return;
    /* Destroy: refused while shapes use it. */
    if (f == F_NONE && geometry_users(fw, kind, id) > 0) e = HEARTH_ERROR_INVALID_ARGUMENT;
    HearthResult res;
    if (kind == K_HULL) {
        CALL(hearth_hull_destroy(w, hull_id(id)), e, NULL, NULL, 0);
        res = r;
    } else if (kind == K_MESH) {
        CALL(hearth_mesh_destroy(w, mesh_id(id)), e, NULL, NULL, 0);
        res = r;
    } else {
        CALL(hearth_heightfield_destroy(w, hf_id(id)), e, NULL, NULL, 0);
        res = r;
    }
    if (res == HEARTH_OK) {
        bury(kind, id);
        drop_at(fw, kind, (int)(o - fw->live[kind]));
    }
}

static void op_geometry_shape(FWorld *fw) {
    if (full(fw, K_SHAPE) || fw->n[K_BODY] == 0) return;
    FAULTS(F_ID, F_NUMBER);
    int kind = K_HULL + (int)rnd(3);
    Obj *g = pick(fw, kind);
    if (!g && f != F_ID) return;
    Obj *body = pick(fw, K_BODY);
    if (f == F_ID && kind != K_HULL && body->meta == HEARTH_BODY_DYNAMIC) return; /* two faults */
    HearthBodyId b = body_id(body->id);
    Id gid = f == F_ID ? bad_id(fw, kind) : g->id;
    mark("hearth_shape_def_default");
    HearthShapeDef sd = hearth_shape_def_default();
    sd.density = good_density();
    const char *field = NULL;
    HearthResult e = HEARTH_OK;
    if (f == F_ID) e = HEARTH_ERROR_INVALID_ID;
    else if (kind != K_HULL && body->meta == HEARTH_BODY_DYNAMIC) e = HEARTH_ERROR_INVALID_ARGUMENT;
    else if (f == F_NUMBER) { e = HEARTH_ERROR_INVALID_ARGUMENT; field = "scale"; }
    HearthTransform local = xf(chance(60) ? vec(0, 0, 0) : vec(frange(-1, 1), frange(-1, 1), frange(-1, 1)), quat_any());
    HearthShapeId out;
    memset(&out, SENTINEL, sizeof out);
    HearthResult res;
    if (kind == K_HULL) {
        HearthHullShape h;
        h.hull = hull_id(gid);
        h.local = local;
        h.scale = f == F_NUMBER ? (chance(50) ? -flog(0.1f, 2) : chance(50) ? 0.0f : nonfinite()) : flog(0.5f, 2);
        CALL(hearth_shape_create_hull(fw->w, b, &sd, &h, &out), e, field, &out, sizeof out);
        res = r;
    } else {
        HearthVec3 scale = vec(flog(0.5f, 2), flog(0.5f, 2), flog(0.5f, 2));
        if (f == F_NUMBER) scale = spoil3(scale, chance(50) ? -1.0f : nonfinite());
        if (kind == K_MESH) {
            HearthMeshShape m;
            m.mesh = mesh_id(gid);
            m.local = local;
            m.scale = scale;
            CALL(hearth_shape_create_mesh(fw->w, b, &sd, &m, &out), e, field, &out, sizeof out);
            res = r;
        } else {
            HearthHeightfieldShape hs;
            hs.heightfield = hf_id(gid);
            hs.local = local;
            hs.scale = scale;
            CALL(hearth_shape_create_heightfield(fw->w, b, &sd, &hs, &out), e, field, &out, sizeof out);
            res = r;
        }
    }
    if (res == HEARTH_OK) {
        Obj *o = add(fw, K_SHAPE, TO_ID(out));
        o->a = TO_ID(b);
        o->meta = (uint32_t)kind;
        o->b = gid;
        check_state(fw, "after a shape of shared geometry was added");
    }
}

/* --------------------------------------------------------------------------- queries */
static HearthQueryFilter any_query_filter(void) {
    mark("hearth_query_filter_default");
    HearthQueryFilter q = hearth_query_filter_default();
    if (chance(30)) {
        q.category_bits = next_u64();
        q.mask_bits = next_u64();
    }
    return q;
}

static HearthRayHit g_query_hits[8];
static HearthShapeId g_query_ids[16];

static float query_callback(void *user_data, const HearthRayHit *hit) {
    int *calls = (int *)user_data;
    (*calls)++;
    if (!(hit->fraction >= 0.0f && hit->fraction <= 1.0f)) fail("cast_ray", "fraction outside [0, 1]");
    switch (rnd(4)) {
    case 0: return -1.0f;
    case 1: return 0.0f;
    case 2: return hit->fraction;
    default: return 1.0f;
    }
}

/* A query shape of every kind; `bad` spoils a size (returns the word the message names) or
 * the type code. */
static const char *query_shape(FWorld *fw, HearthQueryShape *s, Fault f, int *hull_ok) {
    memset(s, 0, sizeof *s);
    *hull_ok = 1;
    s->type = rnd(4);
    s->sphere.radius = flog(0.01f, 3);
    s->capsule.a = vec(0, -0.5f, 0);
    s->capsule.b = vec(0, 0.5f, 0);
    s->capsule.radius = flog(0.01f, 1);
    s->box.rotation = quat_any();
    s->box.half_extents = vec(flog(0.01f, 2), flog(0.01f, 2), flog(0.01f, 2));
    s->hull.local = xf(vec(0, 0, 0), quat_any());
    s->hull.scale = frange(0.5f, 2);
    if (s->type == HEARTH_QUERY_SHAPE_HULL) {
        Obj *h = f == F_ID ? NULL : pick(fw, K_HULL);
        if (h) s->hull.hull = hull_id(h->id);
        else {
            s->hull.hull = hull_id(bad_id(fw, K_HULL));
            *hull_ok = 0;
        }
    }
    if (f == F_CODE) { s->type = 4 + rnd(100); return NULL; }
    if (f == F_NUMBER) {
        switch (s->type) {
        case HEARTH_QUERY_SHAPE_SPHERE: s->sphere.radius = chance(50) ? -1.0f : nonfinite(); return "radius";
        case HEARTH_QUERY_SHAPE_CAPSULE: s->capsule.radius = chance(50) ? 0.0f : nonfinite(); return "radius";
        case HEARTH_QUERY_SHAPE_BOX: s->box.half_extents.y = chance(50) ? -0.5f : nonfinite(); return "half_extents";
        default: s->hull.scale = chance(50) ? -1.0f : nonfinite(); return "scale";
        }
    }
    return NULL;
}

static void op_query(FWorld *fw) {
    FAULTS(F_NONE, F_NULL_WORLD, F_NULL_IN, F_NULL_OUT, F_NUMBER, F_CODE, F_ID);
    HearthQueryFilter qf = any_query_filter();
    const HearthQueryFilter *pf = f == F_NULL_IN ? NULL : &qf;
    HearthVec3 o = chance(70) ? vec(frange(-10, 10), frange(-2, 10), frange(-10, 10)) : good_position();
    HearthVec3 t = scale3(dir3(), flog(1e-3f, 100));
    const char *field = NULL;
    int which = (int)rnd(9);
    /* Faults a call cannot have are no faults. */
    if ((f == F_CODE || f == F_ID) && which != 3 && which != 4 && which != 7 && which != 8) f = F_NONE;
    if (f == F_NUMBER && (which == 7 || which == 8)) f = F_NONE;
    if (f == F_NUMBER && which != 3 && which != 4) {
        if (which == 5) { o = bad_position(); field = "aabb min"; }
        else if (which == 6) { o = bad_position(); field = "point"; }
        else if (chance(50)) { o = bad_position(); field = "origin"; }
        else { t = chance(50) ? vec(0, 0, 0) : spoil3(t, nonfinite()); field = "translation"; }
    }
    HearthResult expected = f == F_NULL_WORLD || f == F_NULL_IN || f == F_NULL_OUT ? HEARTH_ERROR_NULL_POINTER
                          : f == F_NUMBER || f == F_CODE                         ? HEARTH_ERROR_INVALID_ARGUMENT
                                                                                 : HEARTH_OK;
    switch (which) {
    case 0: {
        HearthRayHit h;
        memset(&h, SENTINEL, sizeof h);
        CALL(hearth_world_cast_ray_closest(W(fw, f), o, t, pf, f == F_NULL_OUT ? NULL : &h), expected, field, &h,
             sizeof h);
        if (r == HEARTH_OK && !(h.fraction >= 0.0f && h.fraction <= 1.0f && finite3(h.point)))
            fail("cast_ray_closest", "a hit outside [0, 1] or not finite");
        break;
    }
    case 1: {
        int calls = 0;
        CALL(hearth_world_cast_ray(W(fw, f), o, t, pf, f == F_NULL_OUT ? NULL : query_callback, &calls), expected,
             field, NULL, 0);
        if (r != HEARTH_OK && calls) fail("cast_ray", "called back although it failed");
        break;
    }
    case 2: {
        HearthRayInput rays[8];
        size_t n = 1 + rnd(8);
        for (size_t i = 0; i < n; i++) {
            rays[i].origin = vec(frange(-10, 10), frange(-2, 10), frange(-10, 10));
            rays[i].translation = scale3(dir3(), flog(1e-3f, 100));
        }
        if (f == F_NUMBER) {
            size_t k = rnd((uint32_t)n);
            rays[k].origin = o;
            rays[k].translation = t;
            field = "rays[";
        }
        memset(g_query_hits, SENTINEL, sizeof g_query_hits);
        CALL(hearth_world_cast_rays(W(fw, f), f == F_NULL_IN && chance(50) ? NULL : rays, n,
                                    f == F_NULL_IN ? (pf ? pf : NULL) : pf, f == F_NULL_OUT ? NULL : g_query_hits),
             expected, field, g_query_hits, sizeof g_query_hits);
        if (r == HEARTH_OK)
            for (size_t i = 0; i < n; i++)
                if (!(g_query_hits[i].fraction >= 0.0f && g_query_hits[i].fraction <= 1.0f))
                    fail("cast_rays", "a fraction outside [0, 1]");
        break;
    }
    case 3:
    case 4: {
        HearthQueryShape s;
        int hull_ok;
        const char *sfield = query_shape(fw, &s, f, &hull_ok);
        if (f == F_NUMBER) field = sfield;
        if (expected == HEARTH_OK && !hull_ok) expected = HEARTH_ERROR_INVALID_ID;
        if (f == F_ID && hull_ok) expected = HEARTH_OK;
        HearthTransform x = xf(o, quat_any());
        if (which == 3) {
            HearthRayHit h;
            memset(&h, SENTINEL, sizeof h);
            CALL(hearth_world_cast_shape(W(fw, f), f == F_NULL_IN && chance(50) ? NULL : &s, &x, t,
                                         f == F_NULL_IN ? NULL : pf, f == F_NULL_OUT ? NULL : &h),
                 expected, field, &h, sizeof h);
            if (r == HEARTH_OK && !(h.fraction >= 0.0f && h.fraction <= 1.0f)) fail("cast_shape", "fraction");
        } else {
            size_t count = 0;
            size_t cap = chance(30) ? 0 : rnd(16);
            memset(g_query_ids, SENTINEL, sizeof g_query_ids);
            {
                /* The count first, without the pointer faults: a bad number or code still
                 * fails, and so does a hull id that is not live. */
                HearthResult e1 = f == F_NUMBER || f == F_CODE ? expected
                                : !hull_ok                    ? HEARTH_ERROR_INVALID_ID
                                                              : HEARTH_OK;
                CALL(hearth_world_overlap_shape(fw->w, &s, &x, &qf, NULL, 0, &count), e1, field, NULL, 0);
                if (r != HEARTH_OK) break;
            }
            HearthResult e2 = expected != HEARTH_OK ? expected : cap > 0 && cap < count ? HEARTH_ERROR_BUFFER_TOO_SMALL : HEARTH_OK;
            size_t got = 0;
            CALL(hearth_world_overlap_shape(W(fw, f), f == F_NULL_IN && chance(50) ? NULL : &s, &x,
                                            f == F_NULL_IN ? NULL : pf, cap ? g_query_ids : NULL, cap,
                                            f == F_NULL_OUT ? NULL : &got),
                 e2, field, g_query_ids, sizeof g_query_ids);
            if (r == HEARTH_OK && got != count) fail("overlap_shape", "a different count the second time");
        }
        break;
    }
    case 5:
    case 6: {
        size_t count = 0, got = 0;
        size_t cap = chance(30) ? 0 : rnd(16);
        /* The upper corner within the range too (a corner past it is a bad number). */
        HearthVec3 hi = vec(fminf(o.x + flog(0.01f, 10), MAX_COORDINATE), fminf(o.y + flog(0.01f, 10), MAX_COORDINATE),
                            fminf(o.z + flog(0.01f, 10), MAX_COORDINATE));
        if (f == F_NUMBER || f == F_NULL_IN) { /* the counting call would fail the same way */
            memset(g_query_ids, SENTINEL, sizeof g_query_ids);
            if (which == 5) {
                CALL(hearth_world_overlap_aabb(W(fw, f), o, hi, pf, cap ? g_query_ids : NULL, cap, &got), expected,
                     field, g_query_ids, sizeof g_query_ids);
            } else {
                CALL(hearth_world_overlap_point(W(fw, f), o, pf, cap ? g_query_ids : NULL, cap, &got), expected,
                     field, g_query_ids, sizeof g_query_ids);
            }
            break;
        }
        if (which == 5) {
            CALL(hearth_world_overlap_aabb(fw->w, o, hi, &qf, NULL, 0, &count), HEARTH_OK, NULL, NULL, 0);
        } else {
            CALL(hearth_world_overlap_point(fw->w, o, &qf, NULL, 0, &count), HEARTH_OK, NULL, NULL, 0);
        }
        HearthResult e2 = expected != HEARTH_OK ? expected : cap > 0 && cap < count ? HEARTH_ERROR_BUFFER_TOO_SMALL : HEARTH_OK;
        memset(g_query_ids, SENTINEL, sizeof g_query_ids);
        if (which == 5) {
            CALL(hearth_world_overlap_aabb(W(fw, f), o, hi, pf, cap ? g_query_ids : NULL, cap,
                                           f == F_NULL_OUT ? NULL : &got),
                 e2, field, g_query_ids, sizeof g_query_ids);
            (void)r;
        } else {
            CALL(hearth_world_overlap_point(W(fw, f), o, pf, cap ? g_query_ids : NULL, cap,
                                            f == F_NULL_OUT ? NULL : &got),
                 e2, field, g_query_ids, sizeof g_query_ids);
            (void)r;
        }
        break;
    }
    case 7: {
        Obj *s = f == F_ID ? NULL : pick(fw, K_SHAPE);
        if (f == F_NULL_IN || f == F_NULL_OUT) f = F_NONE;
        HearthShapeId id = s ? shape_id(s->id) : shape_id(bad_id(fw, K_SHAPE));
        mark("hearth_filter_default");
        HearthFilter flt = hearth_filter_default();
        flt.category_bits = chance(50) ? 1ull << rnd(64) : next_u64();
        flt.mask_bits = chance(30) ? ~0ull : next_u64();
        flt.group_index = (int32_t)rnd(7) - 3;
        HearthResult e = f == F_NULL_WORLD ? HEARTH_ERROR_NULL_POINTER : s ? HEARTH_OK : HEARTH_ERROR_INVALID_ID;
        CALL(hearth_shape_set_filter(W(fw, f), id, flt), e, NULL, NULL, 0);
        (void)r;
        break;
    }
    default: {
        Obj *s = f == F_ID ? NULL : pick(fw, K_SHAPE);
        if (f == F_NULL_IN) f = F_NONE;
        HearthShapeId id = s ? shape_id(s->id) : shape_id(bad_id(fw, K_SHAPE));
        HearthFilter out;
        memset(&out, SENTINEL, sizeof out);
        HearthResult e = f == F_NULL_WORLD || f == F_NULL_OUT ? HEARTH_ERROR_NULL_POINTER : s ? HEARTH_OK : HEARTH_ERROR_INVALID_ID;
        CALL(hearth_shape_get_filter(W(fw, f), id, f == F_NULL_OUT ? NULL : &out), e, NULL, &out, sizeof out);
        (void)r;
        break;
    }
    }
}

/* ------------------------------------------------------------------ events and filters */
/* The pair filter and pre-solve callbacks: they read (an event read and gravity), try a
 * mutation (locked) and keep or drop by a hash of the ids (reproducible). */
static uint8_t pair_filter_callback(void *user_data, HearthWorld *world, HearthShapeId a, HearthShapeId b) {
    FWorld *fw = (FWorld *)user_data;
    const char *saved = g_op;
    g_op = "pair filter callback";
    g_locked = 1;
    if (world_of(world) != fw) fail("pair filter", "wrong world");
    HearthVec3 g;
    { CALL(hearth_world_get_gravity(world, &g), HEARTH_OK, NULL, NULL, 0); }
    { CALL(hearth_world_set_gravity(world, g), HEARTH_ERROR_WORLD_LOCKED, NULL, NULL, 0); }
    { CALL(hearth_world_set_pair_filter_callback(world, NULL, NULL), HEARTH_ERROR_WORLD_LOCKED, NULL, NULL, 0); }
    g_locked = 0;
    g_op = saved;
    return (uint8_t)(((a.index * 31u + b.index * 17u) % 5u) != 0u);
}

static uint8_t pre_solve_callback(void *user_data, HearthWorld *world, const HearthPreSolveContact *c) {
    FWorld *fw = (FWorld *)user_data;
    const char *saved = g_op;
    g_op = "pre-solve callback";
    g_locked = 1;
    if (world_of(world) != fw || !c) fail("pre-solve", "wrong world or contact");
    if (c->point_count < 1 || c->point_count > 4) fail("pre-solve", "point count outside 1..4");
    for (uint32_t i = 0; i < c->point_count; i++)
        if (!finite3(c->points[i].point) || !isfinite(c->points[i].separation)) fail("pre-solve", "non-finite point");
    if (fabsf(len3(c->normal) - 1.0f) > 1e-3f) fail("pre-solve", "normal not unit");
    HearthContactEvents ev;
    { CALL(hearth_world_get_contact_events(world, &ev), HEARTH_OK, NULL, NULL, 0); }
    { CALL(hearth_world_set_pre_solve_callback(world, NULL, NULL), HEARTH_ERROR_WORLD_LOCKED, NULL, NULL, 0); }
    g_locked = 0;
    g_op = saved;
    return (uint8_t)(c->normal.y > -0.5f);
}

static void op_events(FWorld *fw) {
    FAULTS(F_NULL_WORLD, F_NULL_OUT);
    HearthWorld *w = W(fw, f);
    int nul = f == F_NULL_OUT;
    HearthResult e = f == F_NULL_WORLD || nul ? HEARTH_ERROR_NULL_POINTER : HEARTH_OK;
    switch (rnd(5)) {
    case 0: {
        HearthContactEvents ev;
        memset(&ev, SENTINEL, sizeof ev);
        CALL(hearth_world_get_contact_events(w, nul ? NULL : &ev), e, NULL, &ev, sizeof ev);
        if (r == HEARTH_OK) {
            for (size_t i = 0; i < ev.begin_count; i++)
                if (ev.begin[i].shape_a.generation == 0 || ev.begin[i].body_b.generation == 0) fail("contact events", "null id");
            for (size_t i = 0; i < ev.hit_count; i++)
                if (!(ev.hit[i].approach_speed > 0.0f) || !finite3(ev.hit[i].point)) fail("contact events", "bad hit");
        }
        break;
    }
    case 1: {
        HearthSensorEvents ev;
        memset(&ev, SENTINEL, sizeof ev);
        CALL(hearth_world_get_sensor_events(w, nul ? NULL : &ev), e, NULL, &ev, sizeof ev);
        if (r == HEARTH_OK && (ev.begin_count > 0 && !ev.begin)) fail("sensor events", "NULL array");
        break;
    }
    case 2: {
        HearthBodyEvents ev;
        memset(&ev, SENTINEL, sizeof ev);
        CALL(hearth_world_get_body_events(w, nul ? NULL : &ev), e, NULL, &ev, sizeof ev);
        if (r == HEARTH_OK)
            for (size_t i = 0; i < ev.move_count; i++)
                if (!finite3(ev.moves[i].transform.position) || ev.moves[i].fell_asleep > 1) fail("body events", "bad move");
        break;
    }
    case 3: {
        HearthResult e2 = f == F_NULL_WORLD ? HEARTH_ERROR_NULL_POINTER : HEARTH_OK;
        CALL(hearth_world_set_pair_filter_callback(w, chance(70) ? pair_filter_callback : NULL, fw), e2, NULL, NULL, 0);
        break;
    }
    default: {
        HearthResult e2 = f == F_NULL_WORLD ? HEARTH_ERROR_NULL_POINTER : HEARTH_OK;
        CALL(hearth_world_set_pre_solve_callback(w, chance(70) ? pre_solve_callback : NULL, fw), e2, NULL, NULL, 0);
        break;
    }
    }
}

/* ------------------------------------------------------------------------------ snapshots */
/* Save, then restore the same bytes into the world (its tracked objects stay as they are) and
 * into a fresh world, each saving the same bytes again; or a failing call: NULLs, a buffer too
 * small (the size needed still reported), the snapshot cut short or with a bit flipped. */
static uint8_t *g_snap_buf;
static size_t g_snap_cap;

static void op_snapshot(FWorld *fw) {
    FAULTS(F_NULL_WORLD, F_NULL_IN, F_NULL_OUT, F_NUMBER);
    HearthWorld *w = W(fw, f);
    size_t size = 0;
    {
        HearthResult e = f == F_NULL_WORLD || f == F_NULL_OUT ? HEARTH_ERROR_NULL_POINTER : HEARTH_OK;
        CALL(hearth_world_snapshot_size(w, f == F_NULL_OUT ? NULL : &size), e, NULL, NULL, 0);
        if (r != HEARTH_OK) return;
    }
    if (size > g_snap_cap) {
        g_snap_cap = size * 2;
        g_snap_buf = (uint8_t *)realloc(g_snap_buf, g_snap_cap);
    }
    if (f == F_NUMBER && size > 0) {
        /* Too small: BUFFER_TOO_SMALL with the size needed in out_written, the buffer untouched. */
        size_t written = 0;
        size_t cap = rnd((uint32_t)size);
        memset(g_snap_buf, SENTINEL, size);
        CALL(hearth_world_snapshot_save(fw->w, g_snap_buf, cap, &written), HEARTH_ERROR_BUFFER_TOO_SMALL, NULL,
             g_snap_buf, size);
        if (written != size) fail("snapshot", "a too-small save did not report the size needed");
        return;
    }
    size_t written = 0;
    {
        HearthResult e = f == F_NULL_IN ? HEARTH_ERROR_NULL_POINTER : HEARTH_OK;
        CALL(hearth_world_snapshot_save(fw->w, f == F_NULL_IN ? NULL : g_snap_buf, size, &written), e, NULL, NULL, 0);
        if (r != HEARTH_OK) return;
    }
    if (written != size) fail("snapshot", "save wrote another size than snapshot_size said");
    switch (rnd(4)) {
    case 0: { /* cut short */
        size_t len = rnd((uint32_t)size);
        CALL(hearth_world_snapshot_restore(fw->w, len == 0 && chance(50) ? NULL : g_snap_buf, len),
             HEARTH_ERROR_INVALID_ARGUMENT, NULL, NULL, 0);
        break;
    }
    case 1: { /* a bit flipped */
        size_t bit = (size_t)rnd((uint32_t)(size * 8));
        g_snap_buf[bit / 8] ^= (uint8_t)(1u << (bit % 8));
        CALL(hearth_world_snapshot_restore(fw->w, g_snap_buf, size), HEARTH_ERROR_INVALID_ARGUMENT, NULL, NULL, 0);
        break;
    }
    case 2: { /* into a fresh world, which then saves the same bytes */
        HearthWorldDef wd = hearth_world_def_default();
        HearthWorld *fresh = NULL;
        if (hearth_world_create(&wd, &fresh) != HEARTH_OK) return; /* the world limit */
        {
            CALL(hearth_world_snapshot_restore(fresh, g_snap_buf, size), HEARTH_OK, NULL, NULL, 0);
        }
        uint8_t *again = (uint8_t *)malloc(size);
        size_t n = 0;
        mark("hearth_world_snapshot_save");
        if (hearth_world_snapshot_save(fresh, again, size, &n) != HEARTH_OK || n != size ||
            memcmp(again, g_snap_buf, size) != 0)
            fail("snapshot", "a fresh world restored from a snapshot saves other bytes");
        free(again);
        /* The fresh world holds the particles the snapshot's world held. */
        size_t np_fresh = 0, np_world = 0;
        { CALL(hearth_world_get_particle_count(fresh, &np_fresh), HEARTH_OK, NULL, NULL, 0); }
        { CALL(hearth_world_get_particle_count(fw->w, &np_world), HEARTH_OK, NULL, NULL, 0); }
        if (np_fresh != np_world) fail("snapshot", "a fresh world restored from a snapshot has other particles");
        /* Its user generators lost their callbacks: list them and set them again. */
        size_t missing = 0;
        {
            CALL(hearth_world_get_user_generators_missing_callback(fresh, NULL, 0, &missing), HEARTH_OK, NULL, NULL, 0);
        }
        if (missing > 0) {
            HearthGeneratorId *ids = (HearthGeneratorId *)malloc(missing * sizeof *ids);
            size_t got = 0;
            if (missing > 1) {
                CALL(hearth_world_get_user_generators_missing_callback(fresh, ids, missing - 1, &got),
                     HEARTH_ERROR_BUFFER_TOO_SMALL, NULL, NULL, 0);
            }
            {
                CALL(hearth_world_get_user_generators_missing_callback(fresh, ids, missing, &got), HEARTH_OK, NULL, NULL, 0);
            }
            for (size_t i = 0; i < got; i++) {
                uint32_t type = 0;
                mark("hearth_generator_get_type");
                if (hearth_generator_get_type(fresh, ids[i], &type) != HEARTH_OK) fail("snapshot", "generator type");
                HearthUserForceGeneratorDef fd = hearth_user_force_generator_def_default();
                fd.callback = force_callback;
                HearthUserContactGeneratorDef cd = hearth_user_contact_generator_def_default();
                cd.callback = contact_callback;
                int is_force = type == HEARTH_GENERATOR_USER_FORCE;
                if (is_force) { /* the other kind's setter is refused */
                    { CALL(hearth_generator_set_user_contact_callback(fresh, ids[i], &cd), HEARTH_ERROR_INVALID_ARGUMENT, "generator", NULL, 0); }
                    { CALL(hearth_generator_set_user_force_callback(fresh, ids[i], &fd), HEARTH_OK, NULL, NULL, 0); }
                } else {
                    { CALL(hearth_generator_set_user_force_callback(fresh, ids[i], &fd), HEARTH_ERROR_INVALID_ARGUMENT, "generator", NULL, 0); }
                    { CALL(hearth_generator_set_user_contact_callback(fresh, ids[i], &cd), HEARTH_OK, NULL, NULL, 0); }
                }
            }
            free(ids);
            {
                CALL(hearth_world_get_user_generators_missing_callback(fresh, NULL, 0, &missing), HEARTH_OK, NULL, NULL, 0);
            }
            if (missing != 0) fail("snapshot", "user generators still miss callbacks after setting them");
        }
        hearth_world_destroy(fresh);
        break;
    }
    default: { /* into the same world: nothing changes, so saving again gives the same bytes */
        {
            HearthResult e = f == F_NULL_WORLD ? HEARTH_ERROR_NULL_POINTER : HEARTH_OK;
            CALL(hearth_world_snapshot_restore(w, g_snap_buf, size), e, NULL, NULL, 0);
        }
        size_t missing = 1;
        {
            HearthResult e = f == F_NULL_OUT ? HEARTH_ERROR_NULL_POINTER : HEARTH_OK;
            CALL(hearth_world_get_user_generators_missing_callback(fw->w, NULL, 0, f == F_NULL_OUT ? NULL : &missing), e,
                 NULL, NULL, 0);
            if (r == HEARTH_OK && missing != 0) fail("snapshot", "a same-world restore dropped a callback");
        }
        uint8_t *again = (uint8_t *)malloc(size);
        size_t n = 0;
        if (hearth_world_snapshot_save(fw->w, again, size, &n) != HEARTH_OK || n != size ||
            memcmp(again, g_snap_buf, size) != 0)
            fail("snapshot", "save, restore, save changed the bytes");
        free(again);
        /* Set each user generator's callback again (a contact generator's capacity may change). */
        for (int i = 0; i < fw->n[K_GEN]; i++) {
            const uint32_t type = fw->live[K_GEN][i].meta;
            if (type != HEARTH_GENERATOR_USER_FORCE && type != HEARTH_GENERATOR_USER_CONTACT) continue;
            HearthGeneratorId g = gen_id(fw->live[K_GEN][i].id);
            HearthUserForceGeneratorDef fd = hearth_user_force_generator_def_default();
            fd.callback = force_callback;
            fd.user_data = fw;
            HearthUserContactGeneratorDef cd = hearth_user_contact_generator_def_default();
            cd.callback = contact_callback;
            cd.user_data = fw;
            cd.capacity = rnd(4);
            const int is_force = type == HEARTH_GENERATOR_USER_FORCE;
            if (is_force) {
                { CALL(hearth_generator_set_user_contact_callback(fw->w, g, &cd), HEARTH_ERROR_INVALID_ARGUMENT, "generator", NULL, 0); }
                { CALL(hearth_generator_set_user_force_callback(fw->w, g, &fd), HEARTH_OK, NULL, NULL, 0); }
            } else {
                { CALL(hearth_generator_set_user_force_callback(fw->w, g, &fd), HEARTH_ERROR_INVALID_ARGUMENT, "generator", NULL, 0); }
                { CALL(hearth_generator_set_user_contact_callback(fw->w, g, &cd), HEARTH_OK, NULL, NULL, 0); }
            }
        }
        if (fw->n[K_GEN] > 0) {
            /* a stale generator id */
            HearthUserForceGeneratorDef fd = hearth_user_force_generator_def_default();
            fd.callback = force_callback;
            CALL(hearth_generator_set_user_force_callback(fw->w, gen_id(bad_id(fw, K_GEN)), &fd), HEARTH_ERROR_INVALID_ID,
                 NULL, NULL, 0);
        }
        break;
    }
    }
}

static void op_step(FWorld *fw) { (void)fw; op_world_step(); }
/* Issue 14's runtime setters and getters. Successful calls keep the model true: a body's
 * type is set to the one it has (the code checked), a disable is followed by an enable. */
static void op_setters(FWorld *fw) {
    FAULTS(F_NULL_WORLD, F_ID, F_NUMBER, F_NULL_OUT, F_NULL_IN, F_CODE);
    HearthWorld *w = W(fw, f);
    union {
        HearthMassData m;
        float x[2];
        uint64_t u64;
        uint32_t u32;
        bool flag;
    } out;
    memset(&out, SENTINEL, sizeof out);
    if (chance(50)) {
        Obj *o = f == F_ID || fw->n[K_SHAPE] == 0 ? NULL : pick(fw, K_SHAPE);
        HearthShapeId s = o ? shape_id(o->id) : shape_id(bad_id(fw, K_SHAPE));
        HearthResult id_r = f == F_NULL_WORLD ? HEARTH_ERROR_NULL_POINTER : o ? HEARTH_OK : HEARTH_ERROR_INVALID_ID;
        HearthResult get_r = f == F_NULL_OUT && id_r != HEARTH_ERROR_NULL_POINTER ? HEARTH_ERROR_NULL_POINTER : id_r;
        HearthResult set_r = f == F_NUMBER && id_r == HEARTH_OK ? HEARTH_ERROR_INVALID_ARGUMENT : id_r;
        int nul = f == F_NULL_OUT;
        switch (rnd(12)) {
        case 0: {
            float a = frange(0, 1), b = frange(0, 1);
            const char *field = NULL;
            if (f == F_NUMBER) { if (chance(50)) { a = outside(0, 1e30f); field = "static_friction"; } else { b = outside(0, 1e30f); field = "dynamic_friction"; } }
            if (f == F_NUMBER && (isfinite(a) && a >= 0) && (isfinite(b) && b >= 0)) set_r = id_r;
            CALL(hearth_shape_set_friction(w, s, a, b), set_r, set_r == HEARTH_ERROR_INVALID_ARGUMENT ? field : NULL, NULL, 0);
            break;
        }
        case 1: { CALL(hearth_shape_get_friction(w, s, nul ? NULL : &out.x[0], &out.x[1]), get_r, NULL, &out, sizeof out); break; }
        case 2: {
            float x = f == F_NUMBER ? outside(0, 1) : frange(0, 1);
            CALL(hearth_shape_set_restitution(w, s, x), set_r, "restitution", NULL, 0);
            break;
        }
        case 3: { CALL(hearth_shape_get_restitution(w, s, nul ? NULL : &out.x[0]), get_r, NULL, &out, sizeof out); break; }
        case 4: {
            float x = f == F_NUMBER ? outside(0, 1) : frange(0, 1);
            CALL(hearth_shape_set_rolling_resistance(w, s, x), set_r, "rolling_resistance", NULL, 0);
            break;
        }
        case 5: { CALL(hearth_shape_get_rolling_resistance(w, s, nul ? NULL : &out.x[0]), get_r, NULL, &out, sizeof out); break; }
        case 6: {
            float x = f == F_NUMBER ? outside(0, 1) : frange(0, 1);
            CALL(hearth_shape_set_torsional_friction(w, s, x), set_r, "torsional_friction", NULL, 0);
            break;
        }
        case 7: { CALL(hearth_shape_get_torsional_friction(w, s, nul ? NULL : &out.x[0]), get_r, NULL, &out, sizeof out); break; }
        case 8: {
            float x = f == F_NUMBER ? (chance(50) ? nonfinite() : (chance(50) ? -1.0f : MAX_DENSITY * 1.01f)) : frange(MIN_DENSITY, 3000.0f);
            CALL(hearth_shape_set_density(w, s, x), set_r, "density", NULL, 0);
            break;
        }
        case 9: { CALL(hearth_shape_get_density(w, s, nul ? NULL : &out.x[0]), get_r, NULL, &out, sizeof out);
            if (r == HEARTH_OK && !(out.x[0] >= 0)) fail("shape density", "negative or NaN");
            break; }
        case 10: { if (f == F_NUMBER) return; CALL(hearth_shape_set_user_data(w, s, next_u64()), id_r, NULL, NULL, 0); break; }
        default: { CALL(hearth_shape_get_user_data(w, s, nul ? NULL : &out.u64), get_r, NULL, &out, sizeof out); break; }
        }
    } else {
        HearthBodyId b;
        Obj *o;
        HearthResult id_r = target_body(fw, f == F_NULL_WORLD || f == F_ID ? f : F_NONE, &b, &o);
        HearthResult get_r = f == F_NULL_OUT && id_r != HEARTH_ERROR_NULL_POINTER ? HEARTH_ERROR_NULL_POINTER : id_r;
        HearthResult set_r = f == F_NUMBER && id_r == HEARTH_OK ? HEARTH_ERROR_INVALID_ARGUMENT : id_r;
        int nul = f == F_NULL_OUT;
        switch (rnd(11)) {
        case 0: {
            float x = f == F_NUMBER ? outside(-MAX_GRAVITY_SCALE, MAX_GRAVITY_SCALE) : frange(-2, 2);
            CALL(hearth_body_set_gravity_scale(w, b, x), set_r, "gravity_scale", NULL, 0);
            break;
        }
        case 1: { CALL(hearth_body_get_gravity_scale(w, b, nul ? NULL : &out.x[0]), get_r, NULL, &out, sizeof out); break; }
        case 2: {
            HearthMassData d;
            d.mass = frange(0.1f, 100.0f);
            d.center = vec(frange(-1, 1), frange(-1, 1), frange(-1, 1));
            d.inertia = vec(frange(0.01f, 10), frange(0.01f, 10), frange(0.01f, 10));
            const char *field = NULL;
            if (f == F_NUMBER) {
                switch (rnd(3)) {
                case 0: d.mass = chance(50) ? nonfinite() : (chance(50) ? 0.0f : -1.0f); field = "mass"; break;
                case 1: d.center = bad_position(); field = "center"; break;
                default: d.inertia.y = chance(50) ? nonfinite() : 0.0f; field = "inertia.y"; break;
                }
            }
            HearthResult e = f == F_NULL_IN && id_r != HEARTH_ERROR_NULL_POINTER ? HEARTH_ERROR_NULL_POINTER : set_r;
            CALL(hearth_body_set_mass_data(w, b, f == F_NULL_IN ? NULL : &d), e, field, NULL, 0);
            break;
        }
        case 3: { CALL(hearth_body_get_mass_data(w, b, nul ? NULL : &out.m), get_r, NULL, &out, sizeof out);
            if (r == HEARTH_OK && !(out.m.mass >= 0 && finite3(out.m.center) && finite3(out.m.inertia))) fail("mass data", "not finite");
            break; }
        case 4: { if (f == F_NUMBER) return; CALL(hearth_body_reset_mass_data(w, b), id_r, NULL, NULL, 0); break; }
        case 5: {
            uint32_t t = o ? o->meta : HEARTH_BODY_DYNAMIC;
            HearthResult e = id_r;
            /* The code is checked before the id. */
            if (f == F_CODE) { t = 3 + rnd(1000); e = HEARTH_ERROR_INVALID_ARGUMENT; }
            CALL(hearth_body_set_type(w, b, t), e, f == F_CODE ? "type" : NULL, NULL, 0);
            break;
        }
        case 6: {
            if (f == F_NUMBER) return;
            CALL(hearth_body_disable(w, b), id_r, NULL, NULL, 0);
            if (r == HEARTH_OK) {
                bool on = true;
                ENSURE_OK(hearth_body_is_enabled(w, b, &on));
                if (on) fail("body_disable", "still enabled");
            }
            { CALL(hearth_body_enable(w, b), id_r, NULL, NULL, 0); }
            break;
        }
        case 7: { if (f == F_NUMBER) return; CALL(hearth_body_enable(w, b), id_r, NULL, NULL, 0); break; }
        case 8: {
            /* Unknown lock bits are refused; valid masks lock (mostly nothing, so bodies keep moving). */
            uint32_t bits = f == F_NUMBER ? (64u << rnd(26)) | rnd(64) : (chance(70) ? 0 : rnd(64));
            CALL(hearth_body_set_locked_axes(w, b, bits), set_r, "locked_axes", NULL, 0);
            break;
        }
        case 9: { CALL(hearth_body_get_locked_axes(w, b, nul ? NULL : &out.u32), get_r, NULL, &out, sizeof out);
            if (r == HEARTH_OK && out.u32 > 63) fail("body locked axes", "unknown bits read back");
            break; }
        default: {
            CALL(hearth_body_is_enabled(w, b, nul ? NULL : &out.flag), get_r, NULL, &out, sizeof out);
            if (r == HEARTH_OK && !out.flag) fail("body_is_enabled", "a body is disabled outside op_setters");
            break;
        }
        }
        if (id_r == HEARTH_OK && f == F_NONE) check_state(fw, "after a runtime setter");
    }
}

/* Debug draw: every callback counts; a draw with a fault draws nothing. */
static long g_drawn;
static void fz_segment(void *u, const HearthVec3 *a, const HearthVec3 *b, uint32_t c) { (void)u; (void)c; if (!finite3(*a) || !finite3(*b)) fail("draw", "segment not finite"); g_drawn++; }
static void fz_polygon(void *u, const HearthVec3 *v, uint32_t n, uint32_t c) { (void)u; (void)c; for (uint32_t i = 0; i < n; i++) if (!finite3(v[i])) fail("draw", "polygon not finite"); if (n < 3) fail("draw", "polygon of fewer than 3 vertices"); g_drawn++; }
static void fz_sphere(void *u, const HearthVec3 *p, float r, uint32_t c) { (void)u; (void)c; if (!finite3(*p) || !(r > 0)) fail("draw", "sphere"); g_drawn++; }
static void fz_capsule(void *u, const HearthVec3 *a, const HearthVec3 *b, float r, uint32_t c) { (void)u; (void)c; (void)r; if (!finite3(*a) || !finite3(*b)) fail("draw", "capsule"); g_drawn++; }
static void fz_transform(void *u, const HearthTransform *t) { (void)u; if (!finite3(t->position)) fail("draw", "transform"); g_drawn++; }
static void fz_point(void *u, const HearthVec3 *p, float s, uint32_t c) { (void)u; (void)c; (void)s; if (!finite3(*p)) fail("draw", "point"); g_drawn++; }

static void op_draw(FWorld *fw) {
    FAULTS(F_NULL_WORLD, F_NULL_IN, F_COOKIE, F_FLAG);
    HearthDebugDraw d = hearth_debug_draw_default();
    mark("hearth_debug_draw_default");
    if (chance(80)) d.draw_segment = fz_segment;
    if (chance(80)) d.draw_polygon = fz_polygon;
    if (chance(80)) d.draw_sphere = fz_sphere;
    if (chance(80)) d.draw_capsule = fz_capsule;
    if (chance(80)) d.draw_transform = fz_transform;
    if (chance(80)) d.draw_point = fz_point;
    d.draw_shapes = flag01();
    d.draw_aabbs = flag01();
    d.draw_contacts = flag01();
    d.draw_joints = flag01();
    d.draw_centers_of_mass = flag01();
    const char *field = NULL;
    HearthResult expected = HEARTH_OK;
    switch (f) {
    case F_NULL_WORLD: case F_NULL_IN: expected = HEARTH_ERROR_NULL_POINTER; break;
    case F_COOKIE: d.internal_value = (uint32_t)next_u64(); if (d.internal_value == hearth_debug_draw_default().internal_value) d.internal_value ^= 1; expected = HEARTH_ERROR_INVALID_ARGUMENT; break;
    case F_FLAG:
        expected = HEARTH_ERROR_INVALID_ARGUMENT;
        switch (rnd(5)) {
        case 0: d.draw_shapes = bad_flag(); field = "draw_shapes"; break;
        case 1: d.draw_aabbs = bad_flag(); field = "draw_aabbs"; break;
        case 2: d.draw_contacts = bad_flag(); field = "draw_contacts"; break;
        case 3: d.draw_joints = bad_flag(); field = "draw_joints"; break;
        default: d.draw_centers_of_mass = bad_flag(); field = "draw_centers_of_mass"; break;
        }
        break;
    default: break;
    }
    g_drawn = 0;
    CALL(hearth_world_draw(W(fw, f), f == F_NULL_IN ? NULL : &d), expected, field, NULL, 0);
    if (r != HEARTH_OK && g_drawn != 0) fail("hearth_world_draw", "a failing draw called a callback");
}

static void op_create_world(FWorld *fw) { (void)fw; op_world_create(); }
static void op_destroy_world(FWorld *fw) { (void)fw; if (chance(30)) op_world_destroy(); }

static const Op OPS[] = {
    {"world_create", op_create_world, 2},
    {"world_destroy", op_destroy_world, 1},
    {"world_step", op_step, 10},
    {"misc", op_misc, 4},
    {"body_create", op_body_create, 8},
    {"body_destroy", op_body_destroy, 2},
    {"body_get", op_body_get, 5},
    {"body_set", op_body_set, 6},
    {"body_forces", op_body_forces, 6},
    {"shape_create", op_shape_create, 7},
    {"shape_other", op_shape_other, 2},
    {"particle_create", op_particle_create, 4},
    {"particle_emit", op_particle_emit, 2},
    {"particle_other", op_particle_other, 5},
    {"generator_create", op_generator_create, 4},
    {"generator_other", op_generator_other, 5},
    {"joint_create", op_joint_create, 4},
    {"joint_other", op_joint_other, 5},
    {"soft_create", op_soft_create, 1},
    {"soft_other", op_soft_other, 4},
    {"record", op_record, 1},
    {"snapshot", op_snapshot, 2},
    {"geometry_create", op_geometry_create, 2},
    {"geometry_other", op_geometry_other, 2},
    {"geometry_shape", op_geometry_shape, 2},
    {"query", op_query, 4},
    {"events", op_events, 2},
    {"setters", op_setters, 4},
    {"draw", op_draw, 2},
};
#define NOPS ((int)(sizeof OPS / sizeof OPS[0]))

/* HEARTH_FUZZ_SKIP=joint,soft: leaves out the operations whose names start so (to tell
 * which area a failure comes from). */
static int skipped(const char *name) {
    const char *list = getenv("HEARTH_FUZZ_SKIP");
    if (!list) return 0;
    while (*list) {
        size_t n = strcspn(list, ",");
        if (n && strncmp(name, list, n) == 0) return 1;
        list += n + (list[n] == ',');
    }
    return 0;
}

static void run_seed(uint64_t seed, long calls) {
    g_seed = seed;
    g_rng = seed * 0x2545F4914F6CDD1Dull + 1;
    g_call = 0;
    memset(g_worlds, 0, sizeof g_worlds);
    memset(g_ndead, 0, sizeof g_ndead);
    int total = 0, weight[NOPS];
    for (int i = 0; i < NOPS; i++) total += weight[i] = skipped(OPS[i].name) ? 0 : OPS[i].weight;
    long iteration = 0;
    while (g_call < calls && iteration < calls * 4) {
        iteration++;
        FWorld *fw = live_world();
        if (!fw) {
            g_op = "world_create";
            op_world_create();
            continue;
        }
        int k = (int)rnd((uint32_t)total), i = 0;
        while (k >= weight[i]) k -= weight[i++];
        g_op = OPS[i].name;
        if (g_trace) fprintf(stderr, "-- %ld %s world %d\n", g_call, g_op, (int)(fw - g_worlds));
        OPS[i].fn(fw);
        if (g_broken) {
            /* Reported; go on with a fresh world. */
            if (g_broken->w) {
                hearth_world_destroy(g_broken->w);
                forget_world(g_broken);
            }
            g_broken = NULL;
        }
    }
    for (int i = 0; i < NWORLDS; i++)
        if (g_worlds[i].w) {
            hearth_world_destroy(g_worlds[i].w);
            forget_world(&g_worlds[i]);
        }
}

static uint64_t env_u64(const char *name, uint64_t fallback) {
    const char *s = getenv(name);
    return s && *s ? strtoull(s, NULL, 10) : fallback;
}

int main(int argc, char **argv) {
    uint64_t first = 1, seeds = 4;
    long calls = 1500;
    if (getenv("HEARTH_FUZZ_SEED")) { first = env_u64("HEARTH_FUZZ_SEED", 1); seeds = 1; }
    calls = (long)env_u64("HEARTH_FUZZ_ITERATIONS", (uint64_t)calls);
    if (argc > 1) { first = strtoull(argv[1], NULL, 10); seeds = 1; }
    if (argc > 2) calls = strtol(argv[2], NULL, 10);
    g_trace = getenv("HEARTH_FUZZ_TRACE") != NULL;
    for (uint64_t s = first; s < first + seeds; s++) {
        int before = g_failed;
        run_seed(s, calls);
        if (g_failed != before)
            fprintf(stderr, "fuzz_api: seed %llu failed; replay with: fuzz_api %llu %ld\n", (unsigned long long)s,
                    (unsigned long long)s, calls);
    }
    /* Which functions the run called (tests/c_harness.rs checks every export is here). */
    qsort(g_names, (size_t)g_nnames, sizeof g_names[0], cmp_names);
    printf("fuzz_api: called %d functions:", g_nnames);
    for (int i = 0; i < g_nnames; i++) printf(" %s", g_names[i]);
    printf("\n");
    free(g_before.data);
    free(g_after.data);
    free(g_snap_buf);
    return ensure_report("fuzz_api");
}
