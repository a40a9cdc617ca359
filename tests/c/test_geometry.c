/*
 * Shared geometry from C, using only include/hearth.h: convex hulls, triangle meshes and
 * heightfields created, instanced by shapes with their own placement and scale, and
 * destroyed; every export and its errors (NULL, garbage defs, bad counts and indices,
 * NaN, out-of-range numbers, bad hole flags, stale, null and foreign ids, meshes and
 * heightfields on dynamic bodies, geometry destroyed while in use, WORLD_LOCKED from a
 * callback), outputs untouched on failure; exact hull mass (cube, rounded cube, scaled);
 * degenerate triangles skipped and counted; a box resting on a mesh floor and a hull cube
 * on a heightfield at their analytic heights; a sphere falling through a heightfield hole.
 * Compiled as C11 and C++17, shared and static, under valgrind.
 */
#include "hearth.h"
#include "ensure.h"

#include <stdlib.h>

static const float DT = 1.0f / 60.0f;

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

static HearthTransform identity(void) {
    HearthTransform t;
    memset(&t, 0, sizeof t);
    t.rotation.w = 1.0f;
    return t;
}

/* True when the calling thread's last error message contains `needle`. */
static int message_has(const char *needle) {
    char msg[512];
    hearth_last_error_message(msg, sizeof msg);
    if (strstr(msg, needle) == NULL) {
        fprintf(stderr, "message \"%s\" lacks \"%s\"\n", msg, needle);
        return 0;
    }
    return 1;
}

static HearthBodyId make_body(HearthWorld *w, uint32_t type, HearthVec3 p) {
    HearthBodyDef bd = hearth_body_def_default();
    bd.type = type;
    bd.transform.position = p;
    HearthBodyId b;
    memset(&b, 0, sizeof b);
    ENSURE_OK(hearth_body_create(w, &bd, &b));
    return b;
}

/* Corners of a cube of half size h, plus its centre (an interior point, dropped). */
static void cube_points(float h, HearthVec3 out[9]) {
    for (int i = 0; i < 8; i++) {
        out[i] = vec3(i & 1 ? h : -h, i & 2 ? h : -h, i & 4 ? h : -h);
    }
    out[8] = vec3(0, 0, 0);
}

static HearthHullId make_cube_hull(HearthWorld *w, float h, float radius) {
    HearthHullDef d = hearth_hull_def_default();
    d.convex_radius = radius;
    HearthVec3 p[9];
    cube_points(h, p);
    HearthHullId id;
    memset(&id, 0, sizeof id);
    ENSURE_OK(hearth_hull_create(w, &d, p, 9, &id));
    return id;
}

static HearthHullShape hull_shape(HearthHullId hull, float scale) {
    HearthHullShape s;
    s.hull = hull;
    s.local = identity();
    s.scale = scale;
    return s;
}

/* A flat n × n grid of unit cells in x–z at y = 0, facing +y. */
static void grid(int n, HearthVec3 *v, uint32_t *idx) {
    for (int r = 0; r <= n; r++) {
        for (int c = 0; c <= n; c++) {
            v[r * (n + 1) + c] = vec3((float)c - 0.5f * n, 0.0f, (float)r - 0.5f * n);
        }
    }
    int k = 0;
    for (int r = 0; r < n; r++) {
        for (int c = 0; c < n; c++) {
            uint32_t a = (uint32_t)(r * (n + 1) + c), b = a + 1, cc = a + (uint32_t)(n + 1), d = cc + 1;
            /* Counter-clockwise seen from +y. */
            idx[k++] = a;
            idx[k++] = cc;
            idx[k++] = d;
            idx[k++] = a;
            idx[k++] = d;
            idx[k++] = b;
        }
    }
}

static void test_hull_def_default(void) {
    HearthHullDef d = hearth_hull_def_default();
    ENSURE(d.convex_radius == 0.0f);
    ENSURE(d.weld_tolerance > 0.0f && d.weld_tolerance <= 0.1f);
}

static void test_hull_create_and_errors(void) {
    HearthWorld *w = make_world();
    HearthHullDef d = hearth_hull_def_default();
    HearthVec3 p[9];
    cube_points(0.5f, p);
    HearthHullId h, untouched;
    memset(&untouched, 0xAB, sizeof untouched);

    h = untouched;
    ENSURE_RESULT(hearth_hull_create(NULL, &d, p, 9, &h), HEARTH_ERROR_NULL_POINTER);
    ENSURE(message_has("world"));
    ENSURE_RESULT(hearth_hull_create(w, NULL, p, 9, &h), HEARTH_ERROR_NULL_POINTER);
    ENSURE(message_has("def"));
    ENSURE_RESULT(hearth_hull_create(w, &d, NULL, 9, &h), HEARTH_ERROR_NULL_POINTER);
    ENSURE(message_has("points"));
    ENSURE_RESULT(hearth_hull_create(w, &d, p, 9, NULL), HEARTH_ERROR_NULL_POINTER);
    ENSURE(message_has("out_hull"));
    HearthHullDef garbage;
    memset(&garbage, 0, sizeof garbage);
    ENSURE_RESULT(hearth_hull_create(w, &garbage, p, 9, &h), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE(message_has("hearth_hull_def_default"));
    ENSURE_RESULT(hearth_hull_create(w, &d, p, 0, &h), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE(message_has("point_count"));
    ENSURE_RESULT(hearth_hull_create(w, &d, p, 3, &h), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE(message_has("at least 4 points"));
    ENSURE_RESULT(hearth_hull_create(w, &d, p, (size_t)HEARTH_MAX_HULL_POINTS + 1, &h),
                  HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE(message_has("point_count"));
    HearthHullDef bad = d;
    bad.convex_radius = -0.1f;
    ENSURE_RESULT(hearth_hull_create(w, &bad, p, 9, &h), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE(message_has("convex_radius"));
    bad = d;
    bad.convex_radius = NAN;
    ENSURE_RESULT(hearth_hull_create(w, &bad, p, 9, &h), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE(message_has("convex_radius"));
    bad = d;
    bad.weld_tolerance = 0.5f;
    ENSURE_RESULT(hearth_hull_create(w, &bad, p, 9, &h), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE(message_has("weld_tolerance"));
    HearthVec3 q[9];
    memcpy(q, p, sizeof q);
    q[5].y = NAN;
    ENSURE_RESULT(hearth_hull_create(w, &d, q, 9, &h), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE(message_has("point 5"));
    q[5].y = INFINITY;
    ENSURE_RESULT(hearth_hull_create(w, &d, q, 9, &h), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE(message_has("point 5"));
    for (int i = 0; i < 9; i++) { /* all on y = 0: no volume */
        q[i] = p[i];
        q[i].y = 0.0f;
    }
    ENSURE_RESULT(hearth_hull_create(w, &d, q, 9, &h), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE(message_has("coplanar"));
    for (int i = 0; i < 9; i++) { /* 0.2 mm across */
        q[i] = vec3(p[i].x * 2e-4f, p[i].y * 2e-4f, p[i].z * 2e-4f);
    }
    ENSURE_RESULT(hearth_hull_create(w, &d, q, 9, &h), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE(message_has("at least 0.001 m"));
    ENSURE(memcmp(&h, &untouched, sizeof h) == 0); /* outputs written only on success */

    ENSURE_OK(hearth_hull_create(w, &d, p, 9, &h));
    ENSURE(h.generation != 0);
    uint32_t n = 12345;
    ENSURE_OK(hearth_hull_get_vertex_count(w, h, &n));
    ENSURE(n == 8); /* the centre is inside */
    n = 12345;
    ENSURE_RESULT(hearth_hull_get_vertex_count(NULL, h, &n), HEARTH_ERROR_NULL_POINTER);
    ENSURE_RESULT(hearth_hull_get_vertex_count(w, h, NULL), HEARTH_ERROR_NULL_POINTER);
    ENSURE(message_has("out_count"));
    HearthHullId null_id;
    memset(&null_id, 0, sizeof null_id);
    ENSURE_RESULT(hearth_hull_get_vertex_count(w, null_id, &n), HEARTH_ERROR_INVALID_ID);
    ENSURE(message_has("convex hull"));
    ENSURE(n == 12345);

    /* Foreign ids: the same slot in another world is not this hull. */
    HearthWorld *other = make_world();
    HearthHullId theirs = make_cube_hull(other, 0.5f, 0.0f);
    ENSURE_RESULT(hearth_hull_get_vertex_count(w, theirs, &n), HEARTH_ERROR_INVALID_ID);
    ENSURE_RESULT(hearth_hull_destroy(w, theirs), HEARTH_ERROR_INVALID_ID);
    ENSURE_RESULT(hearth_hull_get_vertex_count(other, h, &n), HEARTH_ERROR_INVALID_ID);
    hearth_world_destroy(other);

    ENSURE_RESULT(hearth_hull_destroy(NULL, h), HEARTH_ERROR_NULL_POINTER);
    ENSURE_RESULT(hearth_hull_destroy(w, null_id), HEARTH_ERROR_INVALID_ID);
    ENSURE_OK(hearth_hull_destroy(w, h));
    ENSURE_RESULT(hearth_hull_destroy(w, h), HEARTH_ERROR_INVALID_ID); /* stale */
    ENSURE_RESULT(hearth_hull_get_vertex_count(w, h, &n), HEARTH_ERROR_INVALID_ID);
    /* The slot is reused with a new generation; the old id stays dead. */
    HearthHullId h2 = make_cube_hull(w, 0.5f, 0.0f);
    ENSURE(h2.index == h.index && h2.generation != h.generation);
    ENSURE_RESULT(hearth_hull_get_vertex_count(w, h, &n), HEARTH_ERROR_INVALID_ID);
    hearth_world_destroy(w);
}

static void test_hull_shapes_mass_and_users(void) {
    HearthWorld *w = make_world();
    HearthShapeDef sd = hearth_shape_def_default();
    HearthHullId cube = make_cube_hull(w, 0.5f, 0.0f);
    HearthBodyId a = make_body(w, HEARTH_BODY_DYNAMIC, vec3(0, 5, 0));
    HearthBodyId b = make_body(w, HEARTH_BODY_DYNAMIC, vec3(3, 5, 0));
    HearthShapeId sa, sb, untouched;
    memset(&untouched, 0xCD, sizeof untouched);

    /* Unit cube, density 1000: 1000 kg exactly; scale 2 gives 8 m³. */
    HearthHullShape hs = hull_shape(cube, 1.0f);
    ENSURE_OK(hearth_shape_create_hull(w, a, &sd, &hs, &sa));
    float m = 0.0f;
    ENSURE_OK(hearth_body_get_mass(w, a, &m));
    ENSURE_NEAR(m, 1000.0, 0.01);
    hs.scale = 2.0f;
    hs.local.position = vec3(0.0f, 1.0f, 0.0f);
    ENSURE_OK(hearth_shape_create_hull(w, b, &sd, &hs, &sb));
    ENSURE_OK(hearth_body_get_mass(w, b, &m));
    ENSURE_NEAR(m, 8000.0, 0.1);
    HearthVec3 c;
    ENSURE_OK(hearth_body_get_center_of_mass(w, b, &c));
    ENSURE_NEAR(c.y, 6.0, 1e-4); /* body at y = 5, hull centred 1 m up */

    /* A rounded cube (side 1, radius 0.1): volume 1 + 6r + 3πr² + 4/3 πr³. */
    HearthHullId rounded = make_cube_hull(w, 0.5f, 0.1f);
    HearthBodyId r = make_body(w, HEARTH_BODY_DYNAMIC, vec3(6, 5, 0));
    HearthShapeId sr;
    HearthHullShape rs = hull_shape(rounded, 1.0f);
    ENSURE_OK(hearth_shape_create_hull(w, r, &sd, &rs, &sr));
    ENSURE_OK(hearth_body_get_mass(w, r, &m));
    const double pi = 3.14159265358979;
    ENSURE_NEAR(m, 1000.0 * (1.0 + 0.6 + 3.0 * pi * 0.01 + 4.0 / 3.0 * pi * 0.001), 0.5);

    /* Errors: nothing created, output untouched. */
    HearthShapeId s = untouched;
    HearthHullShape bad = hull_shape(cube, 0.0f);
    ENSURE_RESULT(hearth_shape_create_hull(w, a, &sd, &bad, &s), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE(message_has("scale"));
    bad.scale = -1.0f;
    ENSURE_RESULT(hearth_shape_create_hull(w, a, &sd, &bad, &s), HEARTH_ERROR_INVALID_ARGUMENT);
    bad.scale = NAN;
    ENSURE_RESULT(hearth_shape_create_hull(w, a, &sd, &bad, &s), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE(message_has("scale"));
    bad.scale = 1e-4f; /* 0.17 mm across */
    ENSURE_RESULT(hearth_shape_create_hull(w, a, &sd, &bad, &s), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE(message_has("at least 0.001 m"));
    bad = hull_shape(cube, 1.0f);
    bad.local.rotation.w = 0.0f;
    ENSURE_RESULT(hearth_shape_create_hull(w, a, &sd, &bad, &s), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE(message_has("rotation"));
    bad = hull_shape(cube, 1.0f);
    bad.local.position.x = INFINITY;
    ENSURE_RESULT(hearth_shape_create_hull(w, a, &sd, &bad, &s), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE(message_has("position"));
    ENSURE_RESULT(hearth_shape_create_hull(w, a, &sd, NULL, &s), HEARTH_ERROR_NULL_POINTER);
    ENSURE(message_has("geometry"));
    HearthHullShape none = hull_shape(cube, 1.0f);
    memset(&none.hull, 0, sizeof none.hull);
    ENSURE_RESULT(hearth_shape_create_hull(w, a, &sd, &none, &s), HEARTH_ERROR_INVALID_ID);
    ENSURE(message_has("convex hull"));
    ENSURE(memcmp(&s, &untouched, sizeof s) == 0);
    ENSURE_OK(hearth_body_get_mass(w, a, &m));
    ENSURE_NEAR(m, 1000.0, 0.01); /* the body is unchanged */

    /* In use by two shapes (on two bodies): refused, naming the count. */
    ENSURE_RESULT(hearth_hull_destroy(w, cube), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE(message_has("2 shapes"));
    ENSURE_OK(hearth_shape_destroy(w, sa));
    ENSURE_RESULT(hearth_hull_destroy(w, cube), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE(message_has("1 shape"));
    ENSURE_OK(hearth_body_destroy(w, b)); /* destroying the body releases its shapes */
    ENSURE_OK(hearth_hull_destroy(w, cube));
    /* A shape cannot be made from the freed hull. */
    hs = hull_shape(cube, 1.0f);
    ENSURE_RESULT(hearth_shape_create_hull(w, a, &sd, &hs, &s), HEARTH_ERROR_INVALID_ID);
    hearth_world_destroy(w);
}

static void test_mesh_create_and_errors(void) {
    HearthWorld *w = make_world();
    /* Two triangles of a unit square, then one repeating an index and one with no area. */
    HearthVec3 v[5] = {vec3(0, 0, 0), vec3(1, 0, 0), vec3(1, 0, 1), vec3(0, 0, 1), vec3(2, 0, 0)};
    uint32_t idx[12] = {0, 2, 1, 0, 3, 2, 0, 0, 1, 0, 1, 4};
    HearthMeshId m, untouched;
    memset(&untouched, 0xEF, sizeof untouched);
    m = untouched;
    ENSURE_RESULT(hearth_mesh_create(NULL, v, 5, idx, 12, &m), HEARTH_ERROR_NULL_POINTER);
    ENSURE_RESULT(hearth_mesh_create(w, NULL, 5, idx, 12, &m), HEARTH_ERROR_NULL_POINTER);
    ENSURE(message_has("vertices"));
    ENSURE_RESULT(hearth_mesh_create(w, v, 5, NULL, 12, &m), HEARTH_ERROR_NULL_POINTER);
    ENSURE(message_has("indices"));
    ENSURE_RESULT(hearth_mesh_create(w, v, 5, idx, 12, NULL), HEARTH_ERROR_NULL_POINTER);
    ENSURE(message_has("out_mesh"));
    ENSURE_RESULT(hearth_mesh_create(w, v, 0, idx, 12, &m), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE(message_has("vertex_count"));
    ENSURE_RESULT(hearth_mesh_create(w, v, 5, idx, 0, &m), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE(message_has("index_count"));
    ENSURE_RESULT(hearth_mesh_create(w, v, 5, idx, 4, &m), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE(message_has("multiple of 3"));
    ENSURE_RESULT(hearth_mesh_create(w, v, 4, idx, 12, &m), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE(message_has("triangle 3 index 2 is 4")); /* vertex 4 of only 4 */
    HearthVec3 nan_v[5];
    memcpy(nan_v, v, sizeof nan_v);
    nan_v[2].z = NAN;
    ENSURE_RESULT(hearth_mesh_create(w, nan_v, 5, idx, 12, &m), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE(message_has("vertex 2"));
    ENSURE_RESULT(hearth_mesh_create(w, v, 5, idx + 6, 6, &m), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE(message_has("degenerate"));
    ENSURE(memcmp(&m, &untouched, sizeof m) == 0);

    ENSURE_OK(hearth_mesh_create(w, v, 5, idx, 12, &m));
    uint32_t n = 99;
    ENSURE_OK(hearth_mesh_get_triangle_count(w, m, &n));
    ENSURE(n == 2);
    ENSURE_OK(hearth_mesh_get_degenerate_count(w, m, &n));
    ENSURE(n == 2);
    n = 99;
    ENSURE_RESULT(hearth_mesh_get_triangle_count(NULL, m, &n), HEARTH_ERROR_NULL_POINTER);
    ENSURE_RESULT(hearth_mesh_get_triangle_count(w, m, NULL), HEARTH_ERROR_NULL_POINTER);
    ENSURE_RESULT(hearth_mesh_get_degenerate_count(NULL, m, &n), HEARTH_ERROR_NULL_POINTER);
    ENSURE_RESULT(hearth_mesh_get_degenerate_count(w, m, NULL), HEARTH_ERROR_NULL_POINTER);
    ENSURE(message_has("out_count"));
    HearthMeshId null_id;
    memset(&null_id, 0, sizeof null_id);
    ENSURE_RESULT(hearth_mesh_get_triangle_count(w, null_id, &n), HEARTH_ERROR_INVALID_ID);
    ENSURE(message_has("triangle mesh"));
    ENSURE_RESULT(hearth_mesh_get_degenerate_count(w, null_id, &n), HEARTH_ERROR_INVALID_ID);
    ENSURE(n == 99);

    HearthWorld *other = make_world();
    HearthMeshId theirs;
    ENSURE_OK(hearth_mesh_create(other, v, 5, idx, 6, &theirs));
    ENSURE_RESULT(hearth_mesh_get_triangle_count(w, theirs, &n), HEARTH_ERROR_INVALID_ID);
    ENSURE_RESULT(hearth_mesh_destroy(w, theirs), HEARTH_ERROR_INVALID_ID);
    hearth_world_destroy(other);

    ENSURE_RESULT(hearth_mesh_destroy(NULL, m), HEARTH_ERROR_NULL_POINTER);
    ENSURE_OK(hearth_mesh_destroy(w, m));
    ENSURE_RESULT(hearth_mesh_destroy(w, m), HEARTH_ERROR_INVALID_ID);
    ENSURE_RESULT(hearth_mesh_get_degenerate_count(w, m, &n), HEARTH_ERROR_INVALID_ID);
    hearth_world_destroy(w);
}

/* A unit box dropped on a mesh floor comes to rest with its centre 0.5 m up. */
static void test_box_rests_on_mesh_floor(void) {
    HearthWorld *w = make_world();
    enum { N = 4 };
    HearthVec3 v[(N + 1) * (N + 1)];
    uint32_t idx[N * N * 6];
    grid(N, v, idx);
    HearthMeshId mesh;
    ENSURE_OK(hearth_mesh_create(w, v, (N + 1) * (N + 1), idx, N * N * 6, &mesh));
    HearthShapeDef sd = hearth_shape_def_default();
    HearthMeshShape ms;
    ms.mesh = mesh;
    ms.local = identity();
    ms.scale = vec3(2.0f, 1.0f, 2.0f); /* 8 m × 8 m */

    /* Not on a dynamic body: it has no volume. */
    HearthBodyId dyn = make_body(w, HEARTH_BODY_DYNAMIC, vec3(0, 3, 0));
    HearthShapeId s, untouched;
    memset(&untouched, 0x11, sizeof untouched);
    s = untouched;
    ENSURE_RESULT(hearth_shape_create_mesh(w, dyn, &sd, &ms, &s), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE(message_has("static or kinematic"));
    ENSURE(message_has("no mass"));
    HearthMeshShape bad = ms;
    bad.scale.y = 0.0f;
    HearthBodyId ground = make_body(w, HEARTH_BODY_STATIC, vec3(0, 0, 0));
    ENSURE_RESULT(hearth_shape_create_mesh(w, ground, &sd, &bad, &s), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE(message_has("mesh scale"));
    bad = ms;
    bad.scale.x = NAN;
    ENSURE_RESULT(hearth_shape_create_mesh(w, ground, &sd, &bad, &s), HEARTH_ERROR_INVALID_ARGUMENT);
    bad = ms;
    bad.local.rotation.w = 0.0f;
    ENSURE_RESULT(hearth_shape_create_mesh(w, ground, &sd, &bad, &s), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE(message_has("mesh rotation"));
    bad = ms;
    memset(&bad.mesh, 0, sizeof bad.mesh);
    ENSURE_RESULT(hearth_shape_create_mesh(w, ground, &sd, &bad, &s), HEARTH_ERROR_INVALID_ID);
    ENSURE_RESULT(hearth_shape_create_mesh(w, ground, &sd, NULL, &s), HEARTH_ERROR_NULL_POINTER);
    ENSURE(memcmp(&s, &untouched, sizeof s) == 0);

    /* Kinematic bodies take meshes too. */
    HearthBodyId kin = make_body(w, HEARTH_BODY_KINEMATIC, vec3(50, 0, 0));
    HearthShapeId sk;
    ENSURE_OK(hearth_shape_create_mesh(w, kin, &sd, &ms, &sk));
    ENSURE_OK(hearth_shape_create_mesh(w, ground, &sd, &ms, &s));
    ENSURE_RESULT(hearth_mesh_destroy(w, mesh), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE(message_has("2 shapes"));
    ENSURE_OK(hearth_body_destroy(w, kin));

    HearthBodyDef bd = hearth_body_def_default();
    bd.type = HEARTH_BODY_DYNAMIC;
    bd.transform.position = vec3(0.3f, 1.5f, -0.2f);
    HearthBodyId box;
    ENSURE_OK(hearth_body_create(w, &bd, &box));
    HearthBox bx;
    memset(&bx, 0, sizeof bx);
    bx.rotation.w = 1.0f;
    bx.half_extents = vec3(0.5f, 0.5f, 0.5f);
    HearthShapeId sb;
    ENSURE_OK(hearth_shape_create_box(w, box, &sd, &bx, &sb));
    for (int i = 0; i < 240; i++) {
        ENSURE_OK(hearth_world_step(w, DT));
    }
    HearthTransform t;
    ENSURE_OK(hearth_body_get_transform(w, box, &t));
    /* Rests at 0.5 m; penetration under the solver's slop, 5 mm allowed. */
    ENSURE_NEAR(t.position.y, 0.5, 5e-3);
    HearthVec3 vel;
    ENSURE_OK(hearth_body_get_linear_velocity(w, box, &vel));
    ENSURE(sqrtf(vel.x * vel.x + vel.y * vel.y + vel.z * vel.z) < 0.01f);
    ENSURE_RESULT(hearth_mesh_destroy(w, mesh), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE(message_has("1 shape"));
    ENSURE_OK(hearth_shape_destroy(w, s));
    ENSURE_OK(hearth_mesh_destroy(w, mesh));
    hearth_world_destroy(w);
}

static void test_heightfield(void) {
    HearthWorld *w = make_world();
    enum { R = 6, C = 5 };
    float heights[R * C];
    for (int i = 0; i < R * C; i++) {
        heights[i] = 0.25f;
    }
    uint8_t holes[(R - 1) * (C - 1)];
    memset(holes, 0, sizeof holes);
    holes[2 * (C - 1) + 1] = 1; /* cell (row 2, column 1) */
    HearthHeightfieldId hf, untouched;
    memset(&untouched, 0x22, sizeof untouched);
    hf = untouched;
    ENSURE_RESULT(hearth_heightfield_create(NULL, R, C, heights, holes, &hf), HEARTH_ERROR_NULL_POINTER);
    ENSURE_RESULT(hearth_heightfield_create(w, R, C, NULL, holes, &hf), HEARTH_ERROR_NULL_POINTER);
    ENSURE(message_has("heights"));
    ENSURE_RESULT(hearth_heightfield_create(w, R, C, heights, holes, NULL), HEARTH_ERROR_NULL_POINTER);
    ENSURE(message_has("out_heightfield"));
    ENSURE_RESULT(hearth_heightfield_create(w, 1, C, heights, holes, &hf), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE(message_has("rows"));
    ENSURE_RESULT(hearth_heightfield_create(w, R, HEARTH_MAX_HEIGHTFIELD_SAMPLES + 1, heights, holes, &hf),
                  HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE(message_has("columns"));
    heights[7] = NAN;
    ENSURE_RESULT(hearth_heightfield_create(w, R, C, heights, holes, &hf), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE(message_has("height 7"));
    heights[7] = 0.25f;
    holes[3] = 2;
    ENSURE_RESULT(hearth_heightfield_create(w, R, C, heights, holes, &hf), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE(message_has("holes[3]"));
    holes[3] = 0;
    ENSURE(memcmp(&hf, &untouched, sizeof hf) == 0);

    HearthHeightfieldId plain;
    ENSURE_OK(hearth_heightfield_create(w, R, C, heights, NULL, &plain));
    ENSURE_OK(hearth_heightfield_destroy(w, plain));
    ENSURE_RESULT(hearth_heightfield_destroy(w, plain), HEARTH_ERROR_INVALID_ID);
    ENSURE(message_has("heightfield"));
    ENSURE_RESULT(hearth_heightfield_destroy(NULL, plain), HEARTH_ERROR_NULL_POINTER);
    ENSURE_OK(hearth_heightfield_create(w, R, C, heights, holes, &hf));

    /* Spacing 2 m, heights doubled: the ground is at y = 0.5 over x 0..8, z 0..10. */
    HearthShapeDef sd = hearth_shape_def_default();
    HearthHeightfieldShape hs;
    hs.heightfield = hf;
    hs.local = identity();
    hs.scale = vec3(2.0f, 2.0f, 2.0f);
    HearthBodyId dyn = make_body(w, HEARTH_BODY_DYNAMIC, vec3(0, 3, 0));
    HearthShapeId s;
    ENSURE_RESULT(hearth_shape_create_heightfield(w, dyn, &sd, &hs, &s), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE(message_has("a heightfield can only be attached to a static or kinematic body"));
    HearthBodyId ground = make_body(w, HEARTH_BODY_STATIC, vec3(0, 0, 0));
    HearthHeightfieldShape bad = hs;
    bad.scale.z = -2.0f;
    ENSURE_RESULT(hearth_shape_create_heightfield(w, ground, &sd, &bad, &s), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE(message_has("heightfield scale"));
    bad = hs;
    bad.heightfield = plain; /* destroyed */
    ENSURE_RESULT(hearth_shape_create_heightfield(w, ground, &sd, &bad, &s), HEARTH_ERROR_INVALID_ID);
    ENSURE_RESULT(hearth_shape_create_heightfield(w, ground, &sd, NULL, &s), HEARTH_ERROR_NULL_POINTER);
    ENSURE_OK(hearth_shape_create_heightfield(w, ground, &sd, &hs, &s));

    /* A hull cube (side 1) rests 0.5 m above the ground: centre at y = 1.0. */
    HearthHullId cube = make_cube_hull(w, 0.5f, 0.0f);
    HearthBodyId a = make_body(w, HEARTH_BODY_DYNAMIC, vec3(5.1f, 2.0f, 7.1f));
    HearthShapeId sa;
    HearthHullShape cs = hull_shape(cube, 1.0f);
    ENSURE_OK(hearth_shape_create_hull(w, a, &sd, &cs, &sa));
    /* A sphere over the hole (x 2..4, z 4..6) falls through. */
    HearthBodyId ball = make_body(w, HEARTH_BODY_DYNAMIC, vec3(3.0f, 2.0f, 5.0f));
    HearthSphere sp;
    memset(&sp, 0, sizeof sp);
    sp.radius = 0.3f;
    HearthShapeId sball;
    ENSURE_OK(hearth_shape_create_sphere(w, ball, &sd, &sp, &sball));
    for (int i = 0; i < 240; i++) {
        ENSURE_OK(hearth_world_step(w, DT));
    }
    HearthTransform t;
    ENSURE_OK(hearth_body_get_transform(w, a, &t));
    ENSURE_NEAR(t.position.y, 1.0, 5e-3);
    ENSURE_OK(hearth_body_get_transform(w, ball, &t));
    ENSURE(t.position.y < -1.0f);

    ENSURE_RESULT(hearth_heightfield_destroy(w, hf), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE(message_has("1 shape"));
    ENSURE_OK(hearth_shape_destroy(w, s));
    ENSURE_OK(hearth_heightfield_destroy(w, hf));
    hearth_world_destroy(w);
}

/* WORLD_LOCKED: every geometry mutation from inside a force callback; reads work. */
typedef struct LockProbe {
    HearthHullId hull;
    HearthMeshId mesh;
    HearthHeightfieldId hf;
    HearthBodyId ground, dynamic;
    int calls;
    HearthResult hull_created, hull_destroyed, mesh_created, mesh_destroyed, hf_created, hf_destroyed;
    HearthResult hull_shape, mesh_shape, hf_shape, vertex_count, triangle_count, degenerate_count;
} LockProbe;

static void lock_callback(void *user_data, HearthWorld *world, const HearthGeneratorContext *context) {
    (void)context;
    LockProbe *p = (LockProbe *)user_data;
    p->calls++;
    HearthHullDef hd = hearth_hull_def_default();
    HearthVec3 pts[9];
    cube_points(0.5f, pts);
    HearthHullId h;
    p->hull_created = hearth_hull_create(world, &hd, pts, 9, &h);
    p->hull_destroyed = hearth_hull_destroy(world, p->hull);
    uint32_t idx[3] = {0, 2, 1};
    HearthMeshId m;
    p->mesh_created = hearth_mesh_create(world, pts, 9, idx, 3, &m);
    p->mesh_destroyed = hearth_mesh_destroy(world, p->mesh);
    float heights[4] = {0, 0, 0, 0};
    HearthHeightfieldId f;
    p->hf_created = hearth_heightfield_create(world, 2, 2, heights, NULL, &f);
    p->hf_destroyed = hearth_heightfield_destroy(world, p->hf);
    HearthShapeDef sd = hearth_shape_def_default();
    HearthShapeId s;
    HearthHullShape hs = hull_shape(p->hull, 1.0f);
    p->hull_shape = hearth_shape_create_hull(world, p->dynamic, &sd, &hs, &s);
    HearthMeshShape ms;
    ms.mesh = p->mesh;
    ms.local = identity();
    ms.scale = vec3(1, 1, 1);
    p->mesh_shape = hearth_shape_create_mesh(world, p->ground, &sd, &ms, &s);
    HearthHeightfieldShape fs;
    fs.heightfield = p->hf;
    fs.local = identity();
    fs.scale = vec3(1, 1, 1);
    p->hf_shape = hearth_shape_create_heightfield(world, p->ground, &sd, &fs, &s);
    uint32_t n;
    p->vertex_count = hearth_hull_get_vertex_count(world, p->hull, &n);
    p->triangle_count = hearth_mesh_get_triangle_count(world, p->mesh, &n);
    p->degenerate_count = hearth_mesh_get_degenerate_count(world, p->mesh, &n);
}

static void test_world_locked(void) {
    HearthWorld *w = make_world();
    LockProbe p;
    memset(&p, 0, sizeof p);
    p.hull = make_cube_hull(w, 0.5f, 0.0f);
    HearthVec3 pts[9];
    cube_points(0.5f, pts);
    uint32_t idx[3] = {0, 2, 1};
    ENSURE_OK(hearth_mesh_create(w, pts, 9, idx, 3, &p.mesh));
    float heights[4] = {0, 0, 0, 0};
    ENSURE_OK(hearth_heightfield_create(w, 2, 2, heights, NULL, &p.hf));
    p.ground = make_body(w, HEARTH_BODY_STATIC, vec3(0, 0, 0));
    p.dynamic = make_body(w, HEARTH_BODY_DYNAMIC, vec3(0, 5, 0));
    HearthUserForceGeneratorDef g = hearth_user_force_generator_def_default();
    g.callback = lock_callback;
    g.user_data = &p;
    HearthGeneratorId gen;
    ENSURE_OK(hearth_generator_create_user_force(w, &g, &gen));
    ENSURE_OK(hearth_world_step(w, DT));
    ENSURE(p.calls == 1);
    ENSURE(p.hull_created == HEARTH_ERROR_WORLD_LOCKED);
    ENSURE(p.hull_destroyed == HEARTH_ERROR_WORLD_LOCKED);
    ENSURE(p.mesh_created == HEARTH_ERROR_WORLD_LOCKED);
    ENSURE(p.mesh_destroyed == HEARTH_ERROR_WORLD_LOCKED);
    ENSURE(p.hf_created == HEARTH_ERROR_WORLD_LOCKED);
    ENSURE(p.hf_destroyed == HEARTH_ERROR_WORLD_LOCKED);
    ENSURE(p.hull_shape == HEARTH_ERROR_WORLD_LOCKED);
    ENSURE(p.mesh_shape == HEARTH_ERROR_WORLD_LOCKED);
    ENSURE(p.hf_shape == HEARTH_ERROR_WORLD_LOCKED);
    ENSURE(p.vertex_count == HEARTH_OK);
    ENSURE(p.triangle_count == HEARTH_OK);
    ENSURE(p.degenerate_count == HEARTH_OK);
    /* Nothing was created or destroyed: all three are free to go, and the body has no shape. */
    float m = -1.0f;
    ENSURE_OK(hearth_body_get_mass(w, p.dynamic, &m));
    ENSURE_OK(hearth_hull_destroy(w, p.hull));
    ENSURE_OK(hearth_mesh_destroy(w, p.mesh));
    ENSURE_OK(hearth_heightfield_destroy(w, p.hf));
    hearth_world_destroy(w);
}

int main(void) {
    test_hull_def_default();
    test_hull_create_and_errors();
    test_hull_shapes_mass_and_users();
    test_mesh_create_and_errors();
    test_box_rests_on_mesh_floor();
    test_heightfield();
    test_world_locked();
    return ensure_report("test_geometry");
}
