/*
 * draw_svg.c: debug draw into an SVG file. Builds a scene with every shape kind (a ground
 * plane, a heightfield, a triangle-mesh ramp, boxes, spheres, a capsule, a convex hull) and
 * a pendulum on a ball joint, steps it one second, and draws it with hearth_world_draw into
 * an orthographic front view (x to the right, y up; z dropped): shapes coloured by their
 * body's state, bounding boxes, contact points with normals and impulses, the joint, and
 * centres of mass. Open the file in a browser.
 *
 *   draw_svg [out.svg]      (default: scene.svg)
 *
 * It checks every result and that each primitive kind was drawn, and exits 1 otherwise.
 */
#include "hearth.h"

#include <stdio.h>
#include <stdlib.h>

#define CHECK(call)                                                                         \
    do {                                                                                    \
        HearthResult r_ = (call);                                                           \
        if (r_ != HEARTH_OK) {                                                              \
            char msg_[512];                                                                 \
            hearth_last_error_message(msg_, sizeof msg_);                                  \
            fprintf(stderr, "%s failed: %s (%s)\n", #call, hearth_result_name(r_), msg_); \
            exit(1);                                                                        \
        }                                                                                   \
    } while (0)

/* The view: world x in [-12, 12], y in [-3, 13], 40 pixels per metre. */
#define SCALE 40.0f
#define X0 -12.0f
#define Y1 13.0f
#define WIDTH 960
#define HEIGHT 640

typedef struct Svg {
    FILE *f;
    int counts[6]; /* segments, polygons, spheres, capsules, transforms, points */
} Svg;

static float px(const HearthVec3 *p) { return (p->x - X0) * SCALE; }
static float py(const HearthVec3 *p) { return (Y1 - p->y) * SCALE; }
static void rgb(uint32_t c, char out[8]) { snprintf(out, 8, "#%06x", (unsigned)(c >> 8)); }
static float alpha(uint32_t c) { return (float)(c & 0xFF) / 255.0f; }

static void segment(void *u, const HearthVec3 *a, const HearthVec3 *b, uint32_t color) {
    Svg *s = (Svg *)u;
    char c[8];
    rgb(color, c);
    fprintf(s->f, "<line x1='%.1f' y1='%.1f' x2='%.1f' y2='%.1f' stroke='%s' stroke-width='1.5'/>\n", px(a), py(a), px(b),
            py(b), c);
    s->counts[0]++;
}

static void polygon(void *u, const HearthVec3 *v, uint32_t n, uint32_t color) {
    Svg *s = (Svg *)u;
    char c[8];
    rgb(color, c);
    fprintf(s->f, "<polygon points='");
    for (uint32_t i = 0; i < n; i++) fprintf(s->f, "%.1f,%.1f ", px(&v[i]), py(&v[i]));
    fprintf(s->f, "' fill='%s' fill-opacity='%.2f' stroke='%s' stroke-width='0.8'/>\n", c, 0.25f * alpha(color), c);
    s->counts[1]++;
}

static void sphere(void *u, const HearthVec3 *p, float r, uint32_t color) {
    Svg *s = (Svg *)u;
    char c[8];
    rgb(color, c);
    fprintf(s->f, "<circle cx='%.1f' cy='%.1f' r='%.1f' fill='%s' fill-opacity='0.35' stroke='%s'/>\n", px(p), py(p),
            r * SCALE, c, c);
    s->counts[2]++;
}

static void capsule(void *u, const HearthVec3 *a, const HearthVec3 *b, float r, uint32_t color) {
    Svg *s = (Svg *)u;
    char c[8];
    rgb(color, c);
    /* A thick line with round caps is the capsule's outline seen from the front. */
    fprintf(s->f,
            "<line x1='%.1f' y1='%.1f' x2='%.1f' y2='%.1f' stroke='%s' stroke-opacity='0.5' stroke-width='%.1f' "
            "stroke-linecap='round'/>\n",
            px(a), py(a), px(b), py(b), c, 2.0f * r * SCALE);
    s->counts[3]++;
}

static void transform(void *u, const HearthTransform *t) {
    Svg *s = (Svg *)u;
    /* The body's x (red) and y (green) axes, 0.4 m long: rotate the unit axes by q. */
    const HearthQuat q = t->rotation;
    const float ax[2][3] = {{1 - 2 * (q.y * q.y + q.z * q.z), 2 * (q.x * q.y + q.w * q.z), 2 * (q.x * q.z - q.w * q.y)},
                            {2 * (q.x * q.y - q.w * q.z), 1 - 2 * (q.x * q.x + q.z * q.z), 2 * (q.y * q.z + q.w * q.x)}};
    const char *colors[2] = {"#e03030", "#30c030"};
    for (int k = 0; k < 2; k++) {
        HearthVec3 e = t->position;
        e.x += 0.4f * ax[k][0];
        e.y += 0.4f * ax[k][1];
        fprintf(s->f, "<line x1='%.1f' y1='%.1f' x2='%.1f' y2='%.1f' stroke='%s' stroke-width='2'/>\n", px(&t->position),
                py(&t->position), px(&e), py(&e), colors[k]);
    }
    s->counts[4]++;
}

static void point(void *u, const HearthVec3 *p, float size, uint32_t color) {
    Svg *s = (Svg *)u;
    char c[8];
    rgb(color, c);
    fprintf(s->f, "<circle cx='%.1f' cy='%.1f' r='%.1f' fill='%s'/>\n", px(p), py(p), size * SCALE, c);
    s->counts[5]++;
}

static HearthBodyId body(HearthWorld *w, uint32_t type, float x, float y, float z) {
    HearthBodyDef d = hearth_body_def_default();
    d.type = type;
    d.transform.position.x = x;
    d.transform.position.y = y;
    d.transform.position.z = z;
    HearthBodyId b;
    CHECK(hearth_body_create(w, &d, &b));
    return b;
}

static HearthTransform at(float x, float y, float z) {
    HearthTransform t = {{x, y, z}, {0, 0, 0, 1}};
    return t;
}

int main(int argc, char **argv) {
    const char *path = argc > 1 ? argv[1] : "scene.svg";
    HearthWorldDef wd = hearth_world_def_default();
    HearthWorld *w = NULL;
    CHECK(hearth_world_create(&wd, &w));
    HearthShapeDef sd = hearth_shape_def_default();
    HearthShapeId s;

    HearthPlane plane = {{0, 1, 0}, 0};
    CHECK(hearth_shape_create_plane(w, body(w, HEARTH_BODY_STATIC, 0, 0, 0), &sd, &plane, &s));

    /* A heightfield of gentle bumps on the right, a mesh ramp on the left. */
    float heights[7 * 7];
    for (int i = 0; i < 49; i++) heights[i] = 0.15f * (float)((i * 7) % 5);
    HearthHeightfieldId hf;
    CHECK(hearth_heightfield_create(w, 7, 7, heights, NULL, &hf));
    HearthHeightfieldShape hfs = {hf, at(0, 0, 0), {1, 1, 1}};
    CHECK(hearth_shape_create_heightfield(w, body(w, HEARTH_BODY_STATIC, 4, 0.01f, -3), &sd, &hfs, &s));
    HearthVec3 ramp[4] = {{-11, 0, -2}, {-5, 0, -2}, {-11, 3, -2}, {-11, 3, 2}};
    uint32_t tris[6] = {0, 2, 1, 1, 2, 3};
    HearthMeshId mesh;
    CHECK(hearth_mesh_create(w, ramp, 4, tris, 6, &mesh));
    HearthMeshShape ms = {mesh, at(0, 0, 0), {1, 1, 1}};
    CHECK(hearth_shape_create_mesh(w, body(w, HEARTH_BODY_STATIC, 0, 0.01f, 0), &sd, &ms, &s));

    /* A stack of boxes, spheres, a capsule and a hull falling onto them. */
    for (int i = 0; i < 4; i++) {
        HearthBox box = {{0, 0, 0}, {0, 0, 0, 1}, {0.5f, 0.5f, 0.5f}};
        CHECK(hearth_shape_create_box(w, body(w, HEARTH_BODY_DYNAMIC, -1.5f + 0.1f * (float)i, 0.5f + (float)i, 0), &sd, &box,
                                      &s));
    }
    for (int i = 0; i < 3; i++) {
        HearthSphere ball = {{0, 0, 0}, 0.4f};
        CHECK(hearth_shape_create_sphere(w, body(w, HEARTH_BODY_DYNAMIC, 1.5f + 1.2f * (float)i, 4 + (float)i, 0), &sd,
                                         &ball, &s));
    }
    HearthCapsule cap = {{-0.6f, 0, 0}, {0.6f, 0, 0}, 0.3f};
    CHECK(hearth_shape_create_capsule(w, body(w, HEARTH_BODY_DYNAMIC, -7, 6, 0), &sd, &cap, &s));
    HearthVec3 gem[6] = {{0.6f, 0, 0}, {-0.6f, 0, 0}, {0, 0.8f, 0}, {0, -0.8f, 0}, {0, 0, 0.6f}, {0, 0, -0.6f}};
    HearthHullDef hd = hearth_hull_def_default();
    HearthHullId hull;
    CHECK(hearth_hull_create(w, &hd, gem, 6, &hull));
    HearthHullShape hs = {hull, at(0, 0, 0), 1.0f};
    CHECK(hearth_shape_create_hull(w, body(w, HEARTH_BODY_DYNAMIC, 0, 8, 0), &sd, &hs, &s));

    /* A pendulum: a ball on a ball joint hanging from a world anchor. */
    HearthBodyId bob = body(w, HEARTH_BODY_DYNAMIC, 8, 10, 0);
    HearthSphere bob_shape = {{0, 0, 0}, 0.3f};
    CHECK(hearth_shape_create_sphere(w, bob, &sd, &bob_shape, &s));
    HearthBallJointDef jd = hearth_ball_joint_def_default();
    jd.base.body_a = bob;
    jd.base.frame_a = at(-2, 0, 0);
    jd.base.frame_b = at(6, 10, 0);
    HearthJointId joint;
    CHECK(hearth_joint_create_ball(w, &jd, &joint));

    for (int i = 0; i < 60; i++) CHECK(hearth_world_step(w, 1.0f / 60.0f));

    Svg svg = {fopen(path, "w"), {0, 0, 0, 0, 0, 0}};
    if (!svg.f) {
        perror(path);
        return 1;
    }
    fprintf(svg.f, "<svg xmlns='http://www.w3.org/2000/svg' width='%d' height='%d' viewBox='0 0 %d %d'>\n", WIDTH, HEIGHT,
            WIDTH, HEIGHT);
    fprintf(svg.f, "<rect width='100%%' height='100%%' fill='#20242a'/>\n");
    HearthDebugDraw d = hearth_debug_draw_default();
    d.draw_segment = segment;
    d.draw_polygon = polygon;
    d.draw_sphere = sphere;
    d.draw_capsule = capsule;
    d.draw_transform = transform;
    d.draw_point = point;
    d.user_data = &svg;
    d.draw_shapes = 1;
    d.draw_aabbs = 0;
    d.draw_contacts = 1;
    d.draw_joints = 1;
    d.draw_centers_of_mass = 1;
    CHECK(hearth_world_draw(w, &d));
    fprintf(svg.f, "</svg>\n");
    fclose(svg.f);
    hearth_world_destroy(w);

    printf("draw_svg: wrote %s: %d segments, %d polygons, %d spheres, %d capsules, %d frames, %d points\n", path,
           svg.counts[0], svg.counts[1], svg.counts[2], svg.counts[3], svg.counts[4], svg.counts[5]);
    for (int k = 0; k < 6; k++) {
        if (svg.counts[k] == 0) {
            fprintf(stderr, "draw_svg: primitive kind %d was never drawn\n", k);
            return 1;
        }
    }
    return 0;
}
