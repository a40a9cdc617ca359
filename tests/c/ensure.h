/* Minimal test macros for the Hearth C harness. Each program prints "N passed, M failed". */
#ifndef HEARTH_TEST_ENSURE_H
#define HEARTH_TEST_ENSURE_H

#include "hearth.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

static int g_passed = 0;
static int g_failed = 0;

#define ENSURE(cond)                                                                       \
    do {                                                                                   \
        if (cond) {                                                                        \
            g_passed++;                                                                    \
        } else {                                                                           \
            g_failed++;                                                                    \
            fprintf(stderr, "%s:%d: ENSURE(%s) failed\n", __FILE__, __LINE__, #cond);      \
        }                                                                                  \
    } while (0)

/* Expects a result code and, for failures, a non-empty thread-local message. */
#define ENSURE_RESULT(call, expected)                                                      \
    do {                                                                                   \
        HearthResult r_ = (call);                                                          \
        if (r_ == (expected)) {                                                            \
            g_passed++;                                                                    \
            if ((expected) != HEARTH_OK) {                                                 \
                char msg_[256];                                                            \
                size_t n_ = hearth_last_error_message(msg_, sizeof msg_);                  \
                ENSURE(n_ > 0 && strlen(msg_) > 0);                                        \
            }                                                                              \
        } else {                                                                           \
            char msg_[256];                                                                \
            hearth_last_error_message(msg_, sizeof msg_);                                  \
            g_failed++;                                                                    \
            fprintf(stderr, "%s:%d: %s returned %s, expected %s (last error: %s)\n",       \
                    __FILE__, __LINE__, #call, hearth_result_name(r_),                     \
                    hearth_result_name(expected), msg_);                                   \
        }                                                                                  \
    } while (0)

#define ENSURE_OK(call) ENSURE_RESULT(call, HEARTH_OK)

#define ENSURE_NEAR(a, b, tol)                                                             \
    do {                                                                                   \
        double a_ = (a), b_ = (b);                                                         \
        if (fabs(a_ - b_) <= (tol)) {                                                      \
            g_passed++;                                                                    \
        } else {                                                                           \
            g_failed++;                                                                    \
            fprintf(stderr, "%s:%d: |%s - %s| = |%g - %g| > %g\n", __FILE__, __LINE__, #a,  \
                    #b, a_, b_, (double)(tol));                                            \
        }                                                                                  \
    } while (0)

/* ----------------------------------------------------------------- shared set-up
 * Helpers several programs use; `static inline`, so a program that uses none of them still
 * compiles without warnings (-Wall -Wextra -Werror, C11 and C++17). */

/* Every byte of `p` is still the 0xA5 the caller filled it with: a failing call wrote
 * nothing. */
static inline int untouched(const void *p, size_t n) {
    const unsigned char *b = (const unsigned char *)p;
    for (size_t i = 0; i < n; i++)
        if (b[i] != 0xA5) return 0;
    return 1;
}

static inline HearthVec3 v3(float x, float y, float z) {
    HearthVec3 v;
    v.x = x;
    v.y = y;
    v.z = z;
    return v;
}

static inline int same_shape(HearthShapeId a, HearthShapeId b) {
    return a.index == b.index && a.generation == b.generation;
}

/* A world from the default def. */
static inline HearthWorld *new_world(void) {
    HearthWorldDef def = hearth_world_def_default();
    HearthWorld *w = NULL;
    ENSURE_OK(hearth_world_create(&def, &w));
    return w;
}

/* A body of `type` (HEARTH_BODY_*) at `p`, allowed to sleep or not. */
static inline HearthBodyId new_body(HearthWorld *w, uint32_t type, HearthVec3 p, int allow_sleep) {
    HearthBodyDef def = hearth_body_def_default();
    def.type = type;
    def.transform.position = p;
    def.allow_sleep = (uint8_t)(allow_sleep != 0);
    HearthBodyId b;
    memset(&b, 0, sizeof b);
    ENSURE_OK(hearth_body_create(w, &def, &b));
    return b;
}

/* A static body with a ground plane at y = 0 (the plane from the default shape def). */
static inline HearthBodyId new_ground(HearthWorld *w) {
    HearthBodyId g = new_body(w, HEARTH_BODY_STATIC, v3(0, 0, 0), 1);
    HearthShapeDef sd = hearth_shape_def_default();
    HearthPlane p = {{0, 1, 0}, 0};
    HearthShapeId sh = {0, 0};
    ENSURE_OK(hearth_shape_create_plane(w, g, &sd, &p, &sh));
    return g;
}

/* A default world with a ground plane at y = 0. */
static inline HearthWorld *new_world_on_ground(void) {
    HearthWorld *w = new_world();
    new_ground(w);
    return w;
}

/* A dynamic ball of radius 0.5 at (x, y, 0) carrying `user_data`. */
static inline HearthBodyId add_ball(HearthWorld *w, float x, float y, uint64_t user_data) {
    HearthBodyDef bd = hearth_body_def_default();
    bd.type = HEARTH_BODY_DYNAMIC;
    bd.transform.position = v3(x, y, 0);
    bd.user_data = user_data;
    HearthBodyId b = {0, 0};
    ENSURE_OK(hearth_body_create(w, &bd, &b));
    HearthShapeDef sd = hearth_shape_def_default();
    HearthSphere s = {{0, 0, 0}, 0.5f};
    HearthShapeId sh = {0, 0};
    ENSURE_OK(hearth_shape_create_sphere(w, b, &sd, &s, &sh));
    return b;
}

static int ensure_report(const char *name) {
    printf("%s: %d passed, %d failed\n", name, g_passed, g_failed);
    return g_failed == 0 ? 0 : 1;
}

#endif
