/*
 * Issue 14 debug draw from C: a counting drawer gets exactly the primitives each shape kind
 * promises (sphere, capsule, box faces, plane patch, hull faces, mesh and heightfield
 * triangles), each flag's primitives, the colours of sleeping and awake bodies; NULL
 * callbacks are skipped; the world is locked while callbacks run; and each error (NULL
 * world or draw, a def not from its default, a flag not 0/1) draws nothing. Compiled as C11
 * and C++17, shared and static, and under valgrind in CI.
 */
#include "hearth.h"
#include "ensure.h"

#include <string.h>

typedef struct Counts {
    int segments, polygons, polygon_vertices, spheres, capsules, transforms, points;
    uint32_t last_color;
    int locked_ok;
    HearthWorld *world;
} Counts;

static void on_segment(void *u, const HearthVec3 *a, const HearthVec3 *b, uint32_t color) {
    (void)a;
    (void)b;
    ((Counts *)u)->segments++;
    ((Counts *)u)->last_color = color;
}
static void on_polygon(void *u, const HearthVec3 *v, uint32_t n, uint32_t color) {
    (void)v;
    ((Counts *)u)->polygons++;
    ((Counts *)u)->polygon_vertices += (int)n;
    ((Counts *)u)->last_color = color;
}
static void on_sphere(void *u, const HearthVec3 *c, float r, uint32_t color) {
    (void)c;
    (void)r;
    Counts *k = (Counts *)u;
    k->spheres++;
    k->last_color = color;
    if (k->world) {
        /* The world is locked: reads work, changes and steps are refused. */
        HearthBodyDef bd = hearth_body_def_default();
        HearthBodyId b;
        HearthVec3 g;
        k->locked_ok = hearth_body_create(k->world, &bd, &b) == HEARTH_ERROR_WORLD_LOCKED &&
                       hearth_world_step(k->world, 1.0f / 60.0f) == HEARTH_ERROR_WORLD_LOCKED &&
                       hearth_world_get_gravity(k->world, &g) == HEARTH_OK;
        hearth_world_destroy(k->world); /* ignored while locked */
    }
}
static void on_capsule(void *u, const HearthVec3 *a, const HearthVec3 *b, float r, uint32_t color) {
    (void)a;
    (void)b;
    (void)r;
    ((Counts *)u)->capsules++;
    ((Counts *)u)->last_color = color;
}
static void on_transform(void *u, const HearthTransform *t) {
    (void)t;
    ((Counts *)u)->transforms++;
}
static void on_point(void *u, const HearthVec3 *p, float size, uint32_t color) {
    (void)p;
    (void)size;
    ((Counts *)u)->points++;
    ((Counts *)u)->last_color = color;
}

static HearthDebugDraw drawer(Counts *c) {
    HearthDebugDraw d = hearth_debug_draw_default();
    d.draw_segment = on_segment;
    d.draw_polygon = on_polygon;
    d.draw_sphere = on_sphere;
    d.draw_capsule = on_capsule;
    d.draw_transform = on_transform;
    d.draw_point = on_point;
    d.user_data = c;
    d.draw_shapes = 1;
    return d;
}

static Counts count(HearthWorld *w, HearthDebugDraw d) {
    Counts c;
    memset(&c, 0, sizeof c);
    d.user_data = &c;
    ENSURE_OK(hearth_world_draw(w, &d));
    return c;
}

static HearthVec3 vec(float x, float y, float z) {
    HearthVec3 v;
    v.x = x;
    v.y = y;
    v.z = z;
    return v;
}

static HearthTransform identity(void) {
    HearthTransform t;
    t.position = vec(0, 0, 0);
    t.rotation.x = t.rotation.y = t.rotation.z = 0;
    t.rotation.w = 1;
    return t;
}

static HearthBodyId make_body(HearthWorld *w, uint32_t type, HearthVec3 p) {
    HearthBodyDef def = hearth_body_def_default();
    def.type = type;
    def.transform.position = p;
    HearthBodyId b;
    ENSURE_OK(hearth_body_create(w, &def, &b));
    return b;
}

static void test_each_shape_kind(void) {
    HearthWorldDef wd = hearth_world_def_default();
    HearthWorld *w = NULL;
    ENSURE_OK(hearth_world_create(&wd, &w));
    HearthShapeDef sd = hearth_shape_def_default();
    HearthShapeId s;
    Counts dummy;
    HearthDebugDraw d = drawer(&dummy);

    HearthBodyId ground = make_body(w, HEARTH_BODY_STATIC, vec(0, 0, 0));
    HearthPlane plane;
    plane.normal = vec(0, 1, 0);
    plane.offset = 0;
    ENSURE_OK(hearth_shape_create_plane(w, ground, &sd, &plane, &s));
    Counts c = count(w, d);
    ENSURE(c.polygons == 1 && c.polygon_vertices == 4 && c.last_color == 0x8C8C8CFFu);

    HearthBodyId b = make_body(w, HEARTH_BODY_DYNAMIC, vec(0, 3, 0));
    HearthSphere sphere;
    sphere.center = vec(0, 0, 0);
    sphere.radius = 0.5f;
    ENSURE_OK(hearth_shape_create_sphere(w, b, &sd, &sphere, &s));
    HearthCapsule cap;
    cap.a = vec(0, 0, 0);
    cap.b = vec(1, 0, 0);
    cap.radius = 0.25f;
    ENSURE_OK(hearth_shape_create_capsule(w, b, &sd, &cap, &s));
    HearthBox box;
    box.center = vec(0, 1, 0);
    box.rotation = identity().rotation;
    box.half_extents = vec(0.5f, 0.5f, 0.5f);
    ENSURE_OK(hearth_shape_create_box(w, b, &sd, &box, &s));
    c = count(w, d);
    ENSURE(c.spheres == 1 && c.capsules == 1 && c.polygons == 7 && c.polygon_vertices == 28);

    /* A cube hull: six faces of four. */
    HearthVec3 cube[8];
    for (int i = 0; i < 8; i++) cube[i] = vec(i & 1 ? 0.5f : -0.5f, i & 2 ? 0.5f : -0.5f, i & 4 ? 0.5f : -0.5f);
    HearthHullDef hd = hearth_hull_def_default();
    HearthHullId hull;
    ENSURE_OK(hearth_hull_create(w, &hd, cube, 8, &hull));
    HearthHullShape hs;
    hs.hull = hull;
    hs.local = identity();
    hs.scale = 1.0f;
    HearthBodyId hb = make_body(w, HEARTH_BODY_DYNAMIC, vec(5, 3, 0));
    ENSURE_OK(hearth_shape_create_hull(w, hb, &sd, &hs, &s));
    c = count(w, d);
    ENSURE(c.polygons == 13 && c.polygon_vertices == 52);

    /* A mesh of two triangles. */
    HearthVec3 mv[4] = {vec(0, 0, 0), vec(1, 0, 0), vec(1, 0, 1), vec(0, 0, 1)};
    uint32_t mi[6] = {0, 2, 1, 0, 3, 2};
    HearthMeshId mesh;
    ENSURE_OK(hearth_mesh_create(w, mv, 4, mi, 6, &mesh));
    HearthMeshShape ms;
    ms.mesh = mesh;
    ms.local = identity();
    ms.scale = vec(1, 1, 1);
    HearthBodyId mb = make_body(w, HEARTH_BODY_STATIC, vec(-5, 0, 0));
    ENSURE_OK(hearth_shape_create_mesh(w, mb, &sd, &ms, &s));
    c = count(w, d);
    ENSURE(c.polygons == 15 && c.polygon_vertices == 58);

    /* A 3 x 3 heightfield with one hole: three solid cells, six triangles. */
    float heights[9] = {0, 0, 0, 0, 1, 0, 0, 0, 0};
    uint8_t holes[4] = {0, 1, 0, 0};
    HearthHeightfieldId hf;
    ENSURE_OK(hearth_heightfield_create(w, 3, 3, heights, holes, &hf));
    HearthHeightfieldShape hfs;
    hfs.heightfield = hf;
    hfs.local = identity();
    hfs.scale = vec(1, 1, 1);
    HearthBodyId fb = make_body(w, HEARTH_BODY_STATIC, vec(0, 0, -10));
    ENSURE_OK(hearth_shape_create_heightfield(w, fb, &sd, &hfs, &s));
    c = count(w, d);
    ENSURE(c.polygons == 21 && c.polygon_vertices == 76);

    /* NULL callbacks are skipped. */
    HearthDebugDraw only = hearth_debug_draw_default();
    only.draw_shapes = 1;
    only.draw_sphere = on_sphere;
    c = count(w, only);
    ENSURE(c.spheres == 1 && c.polygons == 0);
    hearth_world_destroy(w);
}

static void test_flags_colours_lock_and_errors(void) {
    HearthWorldDef wd = hearth_world_def_default();
    HearthWorld *w = NULL;
    ENSURE_OK(hearth_world_create(&wd, &w));
    HearthShapeDef sd = hearth_shape_def_default();
    HearthShapeId s;
    HearthBodyId ground = make_body(w, HEARTH_BODY_STATIC, vec(0, 0, 0));
    HearthPlane plane;
    plane.normal = vec(0, 1, 0);
    plane.offset = 0;
    ENSURE_OK(hearth_shape_create_plane(w, ground, &sd, &plane, &s));
    HearthBodyId b = make_body(w, HEARTH_BODY_DYNAMIC, vec(0, 0.5f, 0));
    HearthSphere sphere;
    sphere.center = vec(0, 0, 0);
    sphere.radius = 0.5f;
    ENSURE_OK(hearth_shape_create_sphere(w, b, &sd, &sphere, &s));
    Counts dummy;
    HearthDebugDraw d = drawer(&dummy);
    d.draw_shapes = 0;
    d.draw_sphere = NULL;
    Counts c = count(w, d);
    ENSURE(c.segments == 0 && c.polygons == 0 && c.points == 0);
    for (int i = 0; i < 30; i++) ENSURE_OK(hearth_world_step(w, 1.0f / 60.0f));
    d.draw_aabbs = 1;
    c = count(w, d);
    ENSURE(c.segments == 12);
    d.draw_aabbs = 0;
    d.draw_contacts = 1;
    c = count(w, d);
    ENSURE(c.points == 1 && c.segments == 2);
    d.draw_contacts = 0;
    d.draw_centers_of_mass = 1;
    c = count(w, d);
    ENSURE(c.transforms == 1);
    d.draw_centers_of_mass = 0;
    d.draw_joints = 1;
    HearthBallJointDef jd = hearth_ball_joint_def_default();
    jd.base.body_a = b;
    jd.base.frame_b.position = vec(0, 3, 0);
    HearthJointId j;
    ENSURE_OK(hearth_joint_create_ball(w, &jd, &j));
    c = count(w, d);
    ENSURE(c.segments == 2 && c.points == 2 && c.last_color == 0x33CCCCFFu);

    /* Colours: awake, then asleep. */
    Counts k;
    HearthDebugDraw shapes = drawer(&k);
    ENSURE_OK(hearth_body_set_awake(w, b, 1));
    c = count(w, shapes);
    ENSURE(c.spheres == 1 && c.last_color != 0x8C8C8CFFu);
    uint32_t awake_color = 0;
    {
        Counts z;
        memset(&z, 0, sizeof z);
        HearthDebugDraw only = hearth_debug_draw_default();
        only.draw_shapes = 1;
        only.draw_sphere = on_sphere;
        only.user_data = &z;
        ENSURE_OK(hearth_world_draw(w, &only));
        awake_color = z.last_color;
        ENSURE(awake_color == 0xE68C33FFu);
        ENSURE_OK(hearth_body_set_awake(w, b, 0));
        ENSURE_OK(hearth_world_draw(w, &only));
        ENSURE(z.last_color == 0x8C7359FFu);
        /* Inside a callback the world is locked. */
        z.world = w;
        ENSURE_OK(hearth_world_draw(w, &only));
        ENSURE(z.locked_ok);
        /* ... and unlocked after. */
        ENSURE_OK(hearth_world_step(w, 1.0f / 60.0f));
    }

    /* Errors draw nothing. */
    memset(&k, 0, sizeof k);
    shapes.user_data = &k;
    ENSURE_RESULT(hearth_world_draw(NULL, &shapes), HEARTH_ERROR_NULL_POINTER);
    ENSURE_RESULT(hearth_world_draw(w, NULL), HEARTH_ERROR_NULL_POINTER);
    HearthDebugDraw bad = shapes;
    bad.internal_value = 0;
    ENSURE_RESULT(hearth_world_draw(w, &bad), HEARTH_ERROR_INVALID_ARGUMENT);
    bad = shapes;
    bad.draw_contacts = 2;
    ENSURE_RESULT(hearth_world_draw(w, &bad), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE(k.spheres == 0 && k.polygons == 0 && k.segments == 0);
    hearth_world_destroy(w);
}

int main(void) {
    test_each_shape_kind();
    test_flags_colours_lock_and_errors();
    return ensure_report("test_draw");
}
