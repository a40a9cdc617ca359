/*
 * pkgconfig_check.c - the smallest C program against an installed Hearth, built with the
 * flags pkg-config gives (tests/packaging.rs does this):
 *
 *   export PKG_CONFIG_PATH=PREFIX/lib/pkgconfig
 *   cc -std=c11 pkgconfig_check.c $(pkg-config --cflags --libs hearth) -Wl,-rpath,PREFIX/lib -o check
 *
 * A ball dropped from 2 m onto the ground plane rests at its radius. Prints "pkg-config: OK".
 */
#include <hearth.h>

#include <math.h>
#include <stdio.h>

int main(void) {
    if (hearth_version() != HEARTH_VERSION) {
        fprintf(stderr, "pkg-config: header and library versions differ\n");
        return 1;
    }
    HearthWorldDef wd = hearth_world_def_default();
    HearthWorld *world = NULL;
    if (hearth_world_create(&wd, &world) != HEARTH_OK) {
        return 1;
    }
    HearthBodyDef gd = hearth_body_def_default();
    HearthBodyId ground;
    HearthShapeDef sd = hearth_shape_def_default();
    HearthPlane plane = {{0.0f, 1.0f, 0.0f}, 0.0f};
    HearthShapeId shape;
    HearthBodyDef bd = hearth_body_def_default();
    bd.type = HEARTH_BODY_DYNAMIC;
    bd.transform.position.y = 2.0f;
    HearthBodyId ball;
    HearthSphere sphere = {{0.0f, 0.0f, 0.0f}, 0.25f};
    int ok = hearth_body_create(world, &gd, &ground) == HEARTH_OK &&
             hearth_shape_create_plane(world, ground, &sd, &plane, &shape) == HEARTH_OK &&
             hearth_body_create(world, &bd, &ball) == HEARTH_OK &&
             hearth_shape_create_sphere(world, ball, &sd, &sphere, &shape) == HEARTH_OK;
    for (int i = 0; ok && i < 120; i++) {
        ok = hearth_world_step(world, 1.0f / 60.0f) == HEARTH_OK;
    }
    HearthTransform t;
    ok = ok && hearth_body_get_transform(world, ball, &t) == HEARTH_OK && fabsf(t.position.y - 0.25f) < 0.01f;
    hearth_world_destroy(world);
    printf("pkg-config: %s\n", ok ? "OK" : "FAILED");
    return ok ? 0 : 1;
}
