/*
 * Queries and collision filters from C, using only include/hearth.h: shape filters at
 * creation and at run time (a truth table through the broad phase), ray casts (closest,
 * callback with the -1/0/fraction/1 protocol, batch), shape casts, overlap queries by
 * shape, box and point with the count-then-fill protocol; analytic answers (a sphere hit
 * at d - r, a sphere cast onto a plane at (d - r)/|v|); every error (NULL, NaN, zero
 * translation, bad shape type, negative radius, stale ids, a too-small array, WORLD_LOCKED
 * from inside a ray callback) leaving outputs and the world untouched.
 * Compiled as C11 and C++17, shared and static, under valgrind.
 */
#include "hearth.h"
#include "ensure.h"

static const float DT = 1.0f / 60.0f;

static HearthShapeId add_sphere(HearthWorld *w, HearthBodyId b, float r, const HearthShapeDef *def) {
    HearthSphere s;
    s.center = v3(0, 0, 0);
    s.radius = r;
    HearthShapeId id;
    memset(&id, 0, sizeof id);
    ENSURE_OK(hearth_shape_create_sphere(w, b, def, &s, &id));
    return id;
}

static HearthShapeId add_plane(HearthWorld *w, HearthBodyId b, const HearthShapeDef *def) {
    HearthPlane p;
    p.normal = v3(0, 1, 0);
    p.offset = 0;
    HearthShapeId id;
    memset(&id, 0, sizeof id);
    ENSURE_OK(hearth_shape_create_plane(w, b, def, &p, &id));
    return id;
}

/* ------------------------------------------------------------------ filters */

static HearthShapeDef filtered(uint64_t category, uint64_t mask, int32_t group) {
    HearthShapeDef d = hearth_shape_def_default();
    d.filter.category_bits = category;
    d.filter.mask_bits = mask;
    d.filter.group_index = group;
    return d;
}

static void test_filter_truth_table(void) {
    HearthFilter def = hearth_filter_default();
    ENSURE(def.category_bits == 1 && def.mask_bits == ~0ull && def.group_index == 0);
    HearthShapeDef sd = hearth_shape_def_default();
    ENSURE(sd.filter.category_bits == def.category_bits && sd.filter.mask_bits == def.mask_bits &&
           sd.filter.group_index == def.group_index);
    struct {
        uint64_t ca, ma;
        int32_t ga;
        uint64_t cb, mb;
        int32_t gb;
        int collide;
    } rows[] = {
        {1, ~0ull, 0, 1, ~0ull, 0, 1}, {1, 2, 0, 2, 1, 0, 1},     {1, 2, 0, 2, 2, 0, 0},
        {1, 0, 5, 1, 0, 5, 1},         {1, ~0ull, -5, 1, ~0ull, -5, 0}, {1, ~0ull, -5, 1, ~0ull, -6, 1},
        {1ull << 63, 1ull << 63, 0, 1ull << 63, 1ull << 63, 0, 1},
    };
    for (size_t i = 0; i < sizeof rows / sizeof rows[0]; i++) {
        HearthWorld *w = new_world();
        HearthShapeDef a = filtered(rows[i].ca, rows[i].ma, rows[i].ga);
        HearthShapeDef b = filtered(rows[i].cb, rows[i].mb, rows[i].gb);
        HearthBodyId ground = new_body(w, HEARTH_BODY_STATIC, v3(0, 0, 0), 1);
        add_plane(w, ground, &b);
        HearthBodyId ball = new_body(w, HEARTH_BODY_DYNAMIC, v3(0, 0.45f, 0), 1);
        HearthShapeId s = add_sphere(w, ball, 0.5f, &a);
        HearthFilter got;
        ENSURE_OK(hearth_shape_get_filter(w, s, &got));
        ENSURE(got.category_bits == rows[i].ca && got.mask_bits == rows[i].ma && got.group_index == rows[i].ga);
        ENSURE_OK(hearth_world_step(w, DT));
        HearthWorldCounters c;
        ENSURE_OK(hearth_world_get_counters(w, &c));
        if (c.contact_count != (uint32_t)rows[i].collide) fprintf(stderr, "filter row %zu\n", i);
        ENSURE(c.contact_count == (uint32_t)rows[i].collide);
        hearth_world_destroy(w);
    }
}

static void test_set_filter(void) {
    HearthWorld *w = new_world();
    HearthShapeDef sd = hearth_shape_def_default();
    HearthBodyId ground = new_body(w, HEARTH_BODY_STATIC, v3(0, 0, 0), 1);
    add_plane(w, ground, &sd);
    HearthBodyId ball = new_body(w, HEARTH_BODY_DYNAMIC, v3(0, 0.5f, 0), 1);
    HearthShapeId s = add_sphere(w, ball, 0.5f, &sd);
    for (int i = 0; i < 30; i++) ENSURE_OK(hearth_world_step(w, DT));
    HearthWorldCounters c;
    ENSURE_OK(hearth_world_get_counters(w, &c));
    ENSURE(c.contact_count == 1);
    HearthFilter none = hearth_filter_default();
    none.mask_bits = 0;
    ENSURE_OK(hearth_shape_set_filter(w, s, none));
    ENSURE_OK(hearth_world_get_counters(w, &c));
    ENSURE(c.contact_count == 0);
    for (int i = 0; i < 30; i++) ENSURE_OK(hearth_world_step(w, DT));
    HearthTransform t;
    ENSURE_OK(hearth_body_get_transform(w, ball, &t));
    ENSURE(t.position.y < 0.0f); /* fell through the plane it no longer collides with */
    ENSURE_OK(hearth_shape_set_filter(w, s, hearth_filter_default()));
    ENSURE_OK(hearth_world_step(w, DT));
    ENSURE_OK(hearth_world_get_counters(w, &c));
    ENSURE(c.contact_count == 1);
    /* Errors. */
    HearthFilter out;
    memset(&out, 0xA5, sizeof out);
    HearthShapeId stale = s;
    ENSURE_OK(hearth_shape_destroy(w, s));
    ENSURE_RESULT(hearth_shape_set_filter(NULL, s, none), HEARTH_ERROR_NULL_POINTER);
    ENSURE_RESULT(hearth_shape_set_filter(w, stale, none), HEARTH_ERROR_INVALID_ID);
    ENSURE_RESULT(hearth_shape_get_filter(w, stale, &out), HEARTH_ERROR_INVALID_ID);
    ENSURE_RESULT(hearth_shape_get_filter(NULL, stale, &out), HEARTH_ERROR_NULL_POINTER);
    HearthBodyId other = new_body(w, HEARTH_BODY_DYNAMIC, v3(5, 5, 5), 1);
    HearthShapeId live = add_sphere(w, other, 0.5f, &sd);
    ENSURE_RESULT(hearth_shape_get_filter(w, live, NULL), HEARTH_ERROR_NULL_POINTER);
    ENSURE(untouched(&out, sizeof out));
    hearth_world_destroy(w);
}

/* ------------------------------------------------------------------ rays */

typedef struct {
    HearthWorld *world;
    int calls;
    float answer; /* what the callback returns; < -1.5: the hit's own fraction */
    HearthRayHit last;
    HearthResult mutation;
    HearthResult rebuild;
} RayLog;

static float on_hit(void *user_data, const HearthRayHit *hit) {
    RayLog *log = (RayLog *)user_data;
    log->calls++;
    log->last = *hit;
    /* Changing the world from inside a query callback is refused; reading works. */
    log->mutation = hearth_body_set_linear_velocity(log->world, hit->body, v3(0, 1, 0));
    log->rebuild = hearth_world_rebuild_broadphase(log->world);
    HearthTransform t;
    ENSURE_OK(hearth_body_get_transform(log->world, hit->body, &t));
    return log->answer < -1.5f ? hit->fraction : log->answer;
}

static void test_rays(void) {
    HearthWorld *w = new_world();
    HearthShapeDef sd = hearth_shape_def_default();
    HearthShapeId row[4];
    for (int i = 0; i < 4; i++) {
        HearthBodyId b = new_body(w, i % 2 ? HEARTH_BODY_DYNAMIC : HEARTH_BODY_STATIC, v3(3.0f * (float)i, 5, 0), 1);
        row[i] = add_sphere(w, b, 0.5f, &sd);
    }
    HearthQueryFilter all = hearth_query_filter_default();
    ENSURE(all.category_bits == 1 && all.mask_bits == ~0ull);
    /* Closest: a sphere at distance d = 4 of radius 0.5 is hit at 3.5 of a 10 m ray. */
    HearthRayHit hit;
    ENSURE_OK(hearth_world_cast_ray_closest(w, v3(-4, 5, 0), v3(10, 0, 0), &all, &hit));
    ENSURE(same_shape(hit.shape, row[0]));
    ENSURE_NEAR(hit.fraction, 0.35, 1e-5);
    ENSURE_NEAR(hit.point.x, -0.5, 1e-5);
    ENSURE_NEAR(hit.normal.x, -1.0, 1e-5);
    /* A miss: null ids, fraction 1, the ray's end. */
    ENSURE_OK(hearth_world_cast_ray_closest(w, v3(-4, 50, 0), v3(10, 0, 0), &all, &hit));
    ENSURE(hit.shape.index == 0 && hit.shape.generation == 0 && hit.fraction == 1.0f && hit.point.x == 6.0f);
    /* From inside a sphere: not hit (the next one is). */
    ENSURE_OK(hearth_world_cast_ray_closest(w, v3(0, 5, 0), v3(10, 0, 0), &all, &hit));
    ENSURE(same_shape(hit.shape, row[1]));
    ENSURE_NEAR(hit.fraction, 0.25, 1e-5);

    /* Callback: 1 continues through all four, 0 stops at the first, the hit's fraction ends
     * with the closest. */
    RayLog log;
    memset(&log, 0, sizeof log);
    log.world = w;
    log.answer = 1.0f;
    ENSURE_OK(hearth_world_cast_ray(w, v3(-4, 5, 0), v3(20, 0, 0), &all, on_hit, &log));
    ENSURE(log.calls == 4);
    ENSURE(log.mutation == HEARTH_ERROR_WORLD_LOCKED);
    ENSURE(log.rebuild == HEARTH_ERROR_WORLD_LOCKED);
    log.calls = 0;
    log.answer = 0.0f;
    ENSURE_OK(hearth_world_cast_ray(w, v3(-4, 5, 0), v3(20, 0, 0), &all, on_hit, &log));
    ENSURE(log.calls == 1);
    log.calls = 0;
    log.answer = -2.0f;
    ENSURE_OK(hearth_world_cast_ray(w, v3(-4, 5, 0), v3(20, 0, 0), &all, on_hit, &log));
    ENSURE(same_shape(log.last.shape, row[0]));
    log.calls = 0;
    log.answer = -1.0f;
    ENSURE_OK(hearth_world_cast_ray(w, v3(-4, 5, 0), v3(20, 0, 0), &all, on_hit, &log));
    ENSURE(log.calls == 4);
    /* After the query the world is unlocked again. */
    ENSURE_OK(hearth_world_step(w, DT));

    /* Batch: three rays, one a miss. */
    HearthRayInput rays[3];
    rays[0].origin = v3(-4, 5, 0);
    rays[0].translation = v3(10, 0, 0);
    rays[1].origin = v3(3, 10, 0);
    rays[1].translation = v3(0, -10, 0);
    rays[2].origin = v3(0, 50, 0);
    rays[2].translation = v3(1, 0, 0);
    HearthRayHit hits[3];
    ENSURE_OK(hearth_world_cast_rays(w, rays, 3, &all, hits));
    ENSURE(same_shape(hits[0].shape, row[0]) && hits[2].shape.index == 0);
    ENSURE(hits[1].fraction > 0.4f && hits[1].fraction < 0.46f); /* the ball at x = 3 is falling */
    ENSURE_OK(hearth_world_cast_rays(w, NULL, 0, &all, NULL));

    /* Query filter: leave out category 1 (every shape here). */
    HearthQueryFilter none = all;
    none.mask_bits = ~1ull;
    ENSURE_OK(hearth_world_cast_ray_closest(w, v3(-4, 5, 0), v3(10, 0, 0), &none, &hit));
    ENSURE(hit.shape.index == 0);

    /* Errors: nothing written. */
    HearthRayHit out;
    memset(&out, 0xA5, sizeof out);
    HearthVec3 nan3 = v3(NAN, 0, 0);
    ENSURE_RESULT(hearth_world_cast_ray_closest(NULL, v3(0, 0, 0), v3(1, 0, 0), &all, &out),
                  HEARTH_ERROR_NULL_POINTER);
    ENSURE_RESULT(hearth_world_cast_ray_closest(w, v3(0, 0, 0), v3(1, 0, 0), NULL, &out), HEARTH_ERROR_NULL_POINTER);
    ENSURE_RESULT(hearth_world_cast_ray_closest(w, v3(0, 0, 0), v3(1, 0, 0), &all, NULL), HEARTH_ERROR_NULL_POINTER);
    ENSURE_RESULT(hearth_world_cast_ray_closest(w, nan3, v3(1, 0, 0), &all, &out), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE_RESULT(hearth_world_cast_ray_closest(w, v3(0, 0, 0), nan3, &all, &out), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE_RESULT(hearth_world_cast_ray_closest(w, v3(0, 0, 0), v3(0, 0, 0), &all, &out),
                  HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE_RESULT(hearth_world_cast_ray_closest(w, v3(0, 0, 0), v3(INFINITY, 0, 0), &all, &out),
                  HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE(untouched(&out, sizeof out));
    log.calls = 0;
    ENSURE_RESULT(hearth_world_cast_ray(NULL, v3(0, 0, 0), v3(1, 0, 0), &all, on_hit, &log),
                  HEARTH_ERROR_NULL_POINTER);
    ENSURE_RESULT(hearth_world_cast_ray(w, v3(0, 0, 0), v3(1, 0, 0), NULL, on_hit, &log), HEARTH_ERROR_NULL_POINTER);
    ENSURE_RESULT(hearth_world_cast_ray(w, v3(0, 0, 0), v3(1, 0, 0), &all, NULL, &log), HEARTH_ERROR_NULL_POINTER);
    ENSURE_RESULT(hearth_world_cast_ray(w, v3(-4, 5, 0), v3(0, 0, 0), &all, on_hit, &log),
                  HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE(log.calls == 0);
    memset(hits, 0xA5, sizeof hits);
    rays[1].translation = v3(0, 0, 0);
    ENSURE_RESULT(hearth_world_cast_rays(w, rays, 3, &all, hits), HEARTH_ERROR_INVALID_ARGUMENT);
    char msg[256];
    hearth_last_error_message(msg, sizeof msg);
    ENSURE(strstr(msg, "rays[1]") != NULL);
    ENSURE_RESULT(hearth_world_cast_rays(w, NULL, 3, &all, hits), HEARTH_ERROR_NULL_POINTER);
    ENSURE_RESULT(hearth_world_cast_rays(w, rays, 3, &all, NULL), HEARTH_ERROR_NULL_POINTER);
    ENSURE_RESULT(hearth_world_cast_rays(w, rays, 3, NULL, hits), HEARTH_ERROR_NULL_POINTER);
    ENSURE_RESULT(hearth_world_cast_rays(NULL, rays, 3, &all, hits), HEARTH_ERROR_NULL_POINTER);
    ENSURE(untouched(hits, sizeof hits));
    hearth_world_destroy(w);
}

/* ------------------------------------------------------------------ broad-phase rebuild */

/* 300 spheres created one by one on a 3D grid, 64 seeded rays: a rebuild changes no hit and
 * no state, the tree is no taller, the world still steps; NULL is refused. */
static void test_rebuild_broadphase(void) {
    HearthWorld *w = new_world();
    HearthShapeDef sd = hearth_shape_def_default();
    for (int i = 0; i < 300; i++) {
        HearthVec3 p = v3((float)(i % 10) * 1.5f, 1.0f + (float)(i / 100) * 1.5f, (float)(i / 10 % 10) * 1.5f);
        add_sphere(w, new_body(w, HEARTH_BODY_DYNAMIC, p, 1), 0.5f, &sd);
    }
    HearthQueryFilter all = hearth_query_filter_default();
    HearthRayHit before[64], after[64];
    uint32_t seed = 12345;
    for (int pass = 0; pass < 2; pass++) {
        HearthRayHit *out = pass == 0 ? before : after;
        seed = 12345;
        for (int k = 0; k < 64; k++) {
            float r[6];
            for (int j = 0; j < 6; j++) {
                seed = seed * 1664525u + 1013904223u;
                r[j] = (float)(seed >> 8) / 16777216.0f;
            }
            HearthVec3 o = v3(-2.0f + 17.0f * r[0], -1.0f + 7.0f * r[1], -2.0f + 17.0f * r[2]);
            HearthVec3 d = v3(20.0f * r[3] - 10.0f, 20.0f * r[4] - 10.0f, 20.0f * r[5] - 10.0f);
            ENSURE_OK(hearth_world_cast_ray_closest(w, o, d, &all, &out[k]));
        }
        if (pass == 0) {
            HearthWorldCounters c0, c1;
            uint64_t h0, h1;
            ENSURE_OK(hearth_world_get_counters(w, &c0));
            ENSURE_OK(hearth_world_get_hash(w, &h0));
            ENSURE_OK(hearth_world_rebuild_broadphase(w));
            ENSURE_OK(hearth_world_get_counters(w, &c1));
            ENSURE_OK(hearth_world_get_hash(w, &h1));
            ENSURE(c1.tree_height <= c0.tree_height);
            ENSURE(c1.body_count == 300 && c1.contact_count == c0.contact_count);
            ENSURE(h0 == h1);
        }
    }
    int hits = 0;
    for (int k = 0; k < 64; k++) {
        ENSURE(same_shape(before[k].shape, after[k].shape));
        ENSURE(before[k].fraction == after[k].fraction);
        hits += before[k].shape.index != 0;
    }
    ENSURE(hits > 16);
    for (int i = 0; i < 30; i++) ENSURE_OK(hearth_world_step(w, DT));
    ENSURE_RESULT(hearth_world_rebuild_broadphase(NULL), HEARTH_ERROR_NULL_POINTER);
    char msg[256];
    hearth_last_error_message(msg, sizeof msg);
    ENSURE(strstr(msg, "world") != NULL);
    hearth_world_destroy(w);
}

/* ------------------------------------------------------------------ shape casts and overlaps */

static HearthQueryShape sphere_query(float r) {
    HearthQueryShape q;
    memset(&q, 0, sizeof q);
    q.type = HEARTH_QUERY_SHAPE_SPHERE;
    q.sphere.radius = r;
    return q;
}

static HearthTransform at(float x, float y, float z) {
    HearthTransform t;
    memset(&t, 0, sizeof t);
    t.position = v3(x, y, z);
    t.rotation.w = 1.0f;
    return t;
}

static void test_casts_and_overlaps(void) {
    HearthWorld *w = new_world();
    HearthShapeDef sd = hearth_shape_def_default();
    HearthBodyId ground = new_body(w, HEARTH_BODY_STATIC, v3(0, 0, 0), 1);
    HearthShapeId plane = add_plane(w, ground, &sd);
    HearthShapeId balls[3];
    for (int i = 0; i < 3; i++) {
        HearthBodyId b = new_body(w, HEARTH_BODY_STATIC, v3(2.0f * (float)i, 3, 0), 1);
        balls[i] = add_sphere(w, b, 0.5f, &sd);
    }
    HearthQueryFilter all = hearth_query_filter_default();
    /* A sphere of radius 0.5 cast from y = 5 at |v| = 10 onto the plane: (5 - 0.5)/10. */
    HearthQueryShape q = sphere_query(0.5f);
    HearthTransform from = at(-3, 5, 0);
    HearthRayHit hit;
    ENSURE_OK(hearth_world_cast_shape(w, &q, &from, v3(0, -10, 0), &all, &hit));
    ENSURE(same_shape(hit.shape, plane));
    ENSURE_NEAR(hit.fraction, 0.45, 1e-6);
    ENSURE_NEAR(hit.normal.y, 1.0, 1e-6);
    /* A box starting in overlap with ball 1: fraction 0. */
    HearthQueryShape box;
    memset(&box, 0, sizeof box);
    box.type = HEARTH_QUERY_SHAPE_BOX;
    box.box.rotation.w = 1.0f;
    box.box.half_extents = v3(0.3f, 0.3f, 0.3f);
    HearthTransform in_ball = at(2.2f, 3, 0);
    ENSURE_OK(hearth_world_cast_shape(w, &box, &in_ball, v3(0, 1, 0), &all, &hit));
    ENSURE(same_shape(hit.shape, balls[1]) && hit.fraction == 0.0f);

    /* Overlaps: a sphere of radius 1.2 at (1, 3, 0) touches balls 0 and 1 (1.7 apart). */
    HearthQueryShape big = sphere_query(1.2f);
    HearthTransform mid = at(1, 3, 0);
    size_t count = 99;
    ENSURE_OK(hearth_world_overlap_shape(w, &big, &mid, &all, NULL, 0, &count));
    ENSURE(count == 2);
    HearthShapeId ids[4];
    memset(ids, 0xA5, sizeof ids);
    size_t needed = 77;
    ENSURE_RESULT(hearth_world_overlap_shape(w, &big, &mid, &all, ids, 1, &needed), HEARTH_ERROR_BUFFER_TOO_SMALL);
    ENSURE(needed == 77 && untouched(ids, sizeof ids)); /* nothing written on failure */
    ENSURE_OK(hearth_world_overlap_shape(w, &big, &mid, &all, ids, 4, &count));
    ENSURE(count == 2);
    ENSURE((same_shape(ids[0], balls[0]) && same_shape(ids[1], balls[1])) ||
           (same_shape(ids[0], balls[1]) && same_shape(ids[1], balls[0])));
    /* A box query reaching into the plane and over ball 2's bounds. */
    ENSURE_OK(hearth_world_overlap_aabb(w, v3(3.6f, -1, -1), v3(5, 3, 1), &all, ids, 4, &count));
    ENSURE(count == 2 && same_shape(ids[0], plane) && same_shape(ids[1], balls[2]));
    ENSURE_OK(hearth_world_overlap_aabb(w, v3(3.6f, 1, -1), v3(5, 3, 1), &all, NULL, 0, &count));
    ENSURE(count == 1);
    /* Points: inside ball 0; under the plane; nowhere. */
    ENSURE_OK(hearth_world_overlap_point(w, v3(0.1f, 3.2f, 0), &all, ids, 4, &count));
    ENSURE(count == 1 && same_shape(ids[0], balls[0]));
    ENSURE_OK(hearth_world_overlap_point(w, v3(0, -1, 0), &all, ids, 4, &count));
    ENSURE(count == 1 && same_shape(ids[0], plane));
    ENSURE_OK(hearth_world_overlap_point(w, v3(0, 10, 0), &all, NULL, 0, &count));
    ENSURE(count == 0);

    /* Too small an array: as every bulk read (docs/API.md, the header preamble), all three
     * overlaps return BUFFER_TOO_SMALL, name the array, and write nothing: neither the ids nor
     * *out_count (the count comes from a capacity-0 call). */
    HearthShapeId one[1];
    char msg[256];
    for (int kind = 0; kind < 2; kind++) {
        memset(one, 0xA5, sizeof one);
        needed = 77;
        HearthResult r = kind == 0
            ? hearth_world_overlap_shape(w, &big, &mid, &all, one, 1, &needed)
            : hearth_world_overlap_aabb(w, v3(3.6f, -1, -1), v3(5, 3, 1), &all, one, 1, &needed);
        ENSURE(r == HEARTH_ERROR_BUFFER_TOO_SMALL);
        ENSURE(needed == 77 && untouched(one, sizeof one));
        ENSURE(hearth_last_error_message(msg, sizeof msg) > 0 && strstr(msg, "out_shapes") != NULL);
    }
    /* A point under the plane and inside a second ball: two hits need two slots. */
    HearthBodyId low = new_body(w, HEARTH_BODY_STATIC, v3(0, -0.2f, 0), 1);
    HearthShapeId under = add_sphere(w, low, 0.5f, &sd);
    memset(one, 0xA5, sizeof one);
    needed = 77;
    ENSURE_RESULT(hearth_world_overlap_point(w, v3(0, -0.1f, 0), &all, one, 1, &needed), HEARTH_ERROR_BUFFER_TOO_SMALL);
    ENSURE(needed == 77 && untouched(one, sizeof one));
    ENSURE(hearth_last_error_message(msg, sizeof msg) > 0 && strstr(msg, "out_shapes") != NULL);
    ENSURE_OK(hearth_world_overlap_point(w, v3(0, -0.1f, 0), &all, NULL, 0, &needed));
    ENSURE(needed == 2);
    ENSURE_OK(hearth_world_overlap_point(w, v3(0, -0.1f, 0), &all, ids, 2, &count));
    ENSURE(count == 2 && (same_shape(ids[0], under) || same_shape(ids[1], under)));
    ENSURE_OK(hearth_shape_destroy(w, under));
    ENSURE_OK(hearth_body_destroy(w, low));

    /* Errors: nothing written. */
    HearthRayHit out;
    memset(&out, 0xA5, sizeof out);
    HearthQueryShape bad = sphere_query(-1.0f);
    ENSURE_RESULT(hearth_world_cast_shape(w, &bad, &from, v3(0, -1, 0), &all, &out), HEARTH_ERROR_INVALID_ARGUMENT);
    bad = sphere_query(0.5f);
    bad.type = 9;
    ENSURE_RESULT(hearth_world_cast_shape(w, &bad, &from, v3(0, -1, 0), &all, &out), HEARTH_ERROR_INVALID_ARGUMENT);
    HearthQueryShape hull;
    memset(&hull, 0, sizeof hull);
    hull.type = HEARTH_QUERY_SHAPE_HULL;
    hull.hull.local.rotation.w = 1.0f;
    hull.hull.scale = 1.0f; /* a null hull id */
    ENSURE_RESULT(hearth_world_cast_shape(w, &hull, &from, v3(0, -1, 0), &all, &out), HEARTH_ERROR_INVALID_ID);
    ENSURE_RESULT(hearth_world_cast_shape(w, &q, &from, v3(0, 0, 0), &all, &out), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE_RESULT(hearth_world_cast_shape(w, &q, &from, v3(NAN, 0, 0), &all, &out), HEARTH_ERROR_INVALID_ARGUMENT);
    HearthTransform broken = from;
    broken.rotation.w = 0.0f;
    ENSURE_RESULT(hearth_world_cast_shape(w, &q, &broken, v3(0, -1, 0), &all, &out), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE_RESULT(hearth_world_cast_shape(NULL, &q, &from, v3(0, -1, 0), &all, &out), HEARTH_ERROR_NULL_POINTER);
    ENSURE_RESULT(hearth_world_cast_shape(w, NULL, &from, v3(0, -1, 0), &all, &out), HEARTH_ERROR_NULL_POINTER);
    ENSURE_RESULT(hearth_world_cast_shape(w, &q, NULL, v3(0, -1, 0), &all, &out), HEARTH_ERROR_NULL_POINTER);
    ENSURE_RESULT(hearth_world_cast_shape(w, &q, &from, v3(0, -1, 0), NULL, &out), HEARTH_ERROR_NULL_POINTER);
    ENSURE_RESULT(hearth_world_cast_shape(w, &q, &from, v3(0, -1, 0), &all, NULL), HEARTH_ERROR_NULL_POINTER);
    ENSURE(untouched(&out, sizeof out));
    memset(ids, 0xA5, sizeof ids);
    size_t n = 0xA5A5;
    ENSURE_RESULT(hearth_world_overlap_shape(w, &big, &mid, &all, NULL, 4, &n), HEARTH_ERROR_NULL_POINTER);
    ENSURE_RESULT(hearth_world_overlap_shape(w, &big, &mid, &all, ids, 4, NULL), HEARTH_ERROR_NULL_POINTER);
    ENSURE_RESULT(hearth_world_overlap_shape(w, &bad, &mid, &all, ids, 4, &n), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE_RESULT(hearth_world_overlap_shape(w, &big, &broken, &all, ids, 4, &n), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE_RESULT(hearth_world_overlap_shape(w, &hull, &mid, &all, ids, 4, &n), HEARTH_ERROR_INVALID_ID);
    ENSURE_RESULT(hearth_world_overlap_shape(NULL, &big, &mid, &all, ids, 4, &n), HEARTH_ERROR_NULL_POINTER);
    ENSURE_RESULT(hearth_world_overlap_shape(w, &big, &mid, NULL, ids, 4, &n), HEARTH_ERROR_NULL_POINTER);
    ENSURE_RESULT(hearth_world_overlap_aabb(w, v3(1, 1, 1), v3(0, 0, 0), &all, ids, 4, &n),
                  HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE_RESULT(hearth_world_overlap_aabb(w, v3(NAN, 1, 1), v3(2, 2, 2), &all, ids, 4, &n),
                  HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE_RESULT(hearth_world_overlap_aabb(w, v3(0, 0, 0), v3(1, 1, 1), NULL, ids, 4, &n),
                  HEARTH_ERROR_NULL_POINTER);
    ENSURE_RESULT(hearth_world_overlap_aabb(NULL, v3(0, 0, 0), v3(1, 1, 1), &all, ids, 4, &n),
                  HEARTH_ERROR_NULL_POINTER);
    ENSURE_RESULT(hearth_world_overlap_point(w, v3(INFINITY, 0, 0), &all, ids, 4, &n), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE_RESULT(hearth_world_overlap_point(w, v3(0, 0, 0), NULL, ids, 4, &n), HEARTH_ERROR_NULL_POINTER);
    ENSURE_RESULT(hearth_world_overlap_point(NULL, v3(0, 0, 0), &all, ids, 4, &n), HEARTH_ERROR_NULL_POINTER);
    ENSURE_RESULT(hearth_world_overlap_point(w, v3(0, -1, 0), &all, ids, 4, NULL), HEARTH_ERROR_NULL_POINTER);
    ENSURE(untouched(ids, sizeof ids) && n == 0xA5A5);
    hearth_world_destroy(w);
}

int main(void) {
    test_filter_truth_table();
    test_set_filter();
    test_rays();
    test_rebuild_broadphase();
    test_casts_and_overlaps();
    return ensure_report("test_query");
}
