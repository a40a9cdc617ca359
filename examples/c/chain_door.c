/*
 * chain_door.c: a swinging chain and a motorised door, using only include/hearth.h.
 *
 * The chain: 15 capsule links on ball joints, hung from a world anchor and released
 * horizontally; the last link carries a weight ten times a link's mass. The door: a box on a
 * vertical hinge with angle limits, driven by the hinge motor; when it reaches a limit the
 * program reverses the motor, so the door swings open and shut. Once per simulated second it
 * prints the chain's stretch, the door's angle and speed, and the force in the chain's top
 * joint. It checks that the chain stretches less than 1%, the door turns at the motor's speed
 * and stays within its limits, and exits 1 otherwise (or on any failed call).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hearth.h"

static void check(HearthResult r, const char *what) {
    if (r != HEARTH_OK) {
        char msg[256];
        hearth_last_error_message(msg, sizeof msg);
        fprintf(stderr, "%s failed: %s (%s)\n", what, hearth_result_name(r), msg);
        exit(1);
    }
}

static HearthVec3 vec3(float x, float y, float z) {
    HearthVec3 v;
    v.x = x;
    v.y = y;
    v.z = z;
    return v;
}

static HearthBodyId dynamic_body(HearthWorld *w, HearthVec3 position) {
    HearthBodyDef def = hearth_body_def_default();
    def.type = HEARTH_BODY_DYNAMIC;
    def.transform.position = position;
    def.allow_sleep = 0;
    HearthBodyId id;
    check(hearth_body_create(w, &def, &id), "hearth_body_create");
    return id;
}

enum { LINKS = 15 };
static const float LINK = 0.4f; /* joint to joint (m) */
static const float DOOR_OPEN = 1.5f; /* rad */
static const float DOOR_SPEED = 1.0f; /* rad/s */

int main(int argc, char **argv) {
    HearthWorldDef wd = hearth_world_def_default();
    wd.substeps = 12; /* joints sag as 1/substeps^2: 12 keep the heavy chain within 1% */
    HearthWorld *w = NULL;
    check(hearth_world_create(&wd, &w), "hearth_world_create");
    HearthShapeDef sd = hearth_shape_def_default();

    /* ---- The chain, laid out along +x from the anchor and let go. */
    HearthVec3 anchor = vec3(0.0f, 8.0f, 0.0f);
    HearthBodyId links[LINKS + 1];
    HearthJointId joints[LINKS + 1];
    for (int i = 0; i <= LINKS; i++) {
        int weight = i == LINKS;
        float x = anchor.x + (float)i * LINK + (weight ? 0.2f : 0.5f * LINK);
        links[i] = dynamic_body(w, vec3(x, anchor.y, 0.0f));
        HearthShapeId shape;
        if (weight) {
            HearthSphere s;
            memset(&s, 0, sizeof s);
            s.radius = 0.2f;
            HearthShapeDef heavy = sd;
            heavy.density = sd.density * 10.0f * 0.0029f / 0.0335f; /* ten links' worth */
            check(hearth_shape_create_sphere(w, links[i], &heavy, &s, &shape), "sphere");
        } else {
            HearthCapsule c;
            memset(&c, 0, sizeof c);
            c.a = vec3(-0.5f * LINK + 0.05f, 0, 0);
            c.b = vec3(0.5f * LINK - 0.05f, 0, 0);
            c.radius = 0.05f;
            check(hearth_shape_create_capsule(w, links[i], &sd, &c, &shape), "capsule");
        }
        HearthBallJointDef jd = hearth_ball_joint_def_default();
        jd.base.body_a = links[i];
        jd.base.frame_a.position = vec3(weight ? -0.2f : -0.5f * LINK, 0, 0);
        if (i == 0) {
            jd.base.frame_b.position = anchor; /* body_b null: the world */
        } else {
            jd.base.body_b = links[i - 1];
            jd.base.frame_b.position = vec3(0.5f * LINK, 0, 0);
        }
        check(hearth_joint_create_ball(w, &jd, &joints[i]), "hearth_joint_create_ball");
    }
    float rest = LINKS * LINK + 0.2f;

    /* ---- The door: 1 m wide, 2 m tall, hinged along its left edge to the world. */
    HearthVec3 hinge = vec3(-4.0f, 1.0f, 0.0f);
    HearthBodyId door = dynamic_body(w, vec3(hinge.x + 0.5f, hinge.y, 0.0f));
    HearthBox panel;
    memset(&panel, 0, sizeof panel);
    panel.rotation.w = 1.0f;
    panel.half_extents = vec3(0.5f, 1.0f, 0.03f);
    HearthShapeId panel_shape;
    check(hearth_shape_create_box(w, door, &sd, &panel, &panel_shape), "hearth_shape_create_box");
    HearthHingeJointDef hd = hearth_hinge_joint_def_default();
    /* The hinge axis is the frames' Z: turn it to world Y (-90 degrees about X). */
    HearthQuat z_to_y;
    z_to_y.x = -0.70710678f;
    z_to_y.y = 0.0f;
    z_to_y.z = 0.0f;
    z_to_y.w = 0.70710678f;
    hd.base.body_a = door;
    hd.base.frame_a.position = vec3(-0.5f, 0, 0);
    hd.base.frame_a.rotation = z_to_y;
    hd.base.frame_b.position = hinge;
    hd.base.frame_b.rotation = z_to_y;
    /* The hinge angle is the world's (B) turn relative to the door (A): opening the door by
     * +a about Y is an angle of -a, so the limits are [-DOOR_OPEN, 0]. */
    hd.enable_limit = 1;
    hd.lower = -DOOR_OPEN;
    hd.upper = 0.0f;
    hd.enable_motor = 1;
    hd.motor_speed = -DOOR_SPEED;
    hd.max_motor_torque = 200.0f;
    HearthJointId door_hinge;
    check(hearth_joint_create_hinge(w, &hd, &door_hinge), "hearth_joint_create_hinge");

    /* ---- Run 8 s. */
    const float dt = 1.0f / 60.0f;
    float worst_stretch = 0.0f, worst_door = 0.0f, mid_speed_error = 0.0f;
    int reversals = 0;
    /* With a path argument, record the run for the browser viewer (viewer/index.html). */
    if (argc > 1) {
        HearthRecordDef record = hearth_record_def_default();
        record.record_contacts = 1;
        check(hearth_world_record_start_file(w, argv[1], &record), "hearth_world_record_start_file");
    }
    for (int step = 1; step <= 480; step++) {
        check(hearth_world_step(w, dt), "hearth_world_step");
        HearthTransform end;
        check(hearth_body_get_transform(w, links[LINKS], &end), "get_transform");
        float dx = end.position.x - anchor.x, dy = end.position.y - anchor.y, dz = end.position.z - anchor.z;
        float stretch = sqrtf(dx * dx + dy * dy + dz * dz) / rest - 1.0f;
        if (stretch > worst_stretch) {
            worst_stretch = stretch;
        }

        HearthTransform xf;
        check(hearth_body_get_transform(w, door, &xf), "get_transform");
        float angle = 2.0f * atan2f(xf.rotation.y, xf.rotation.w);
        HearthVec3 spin;
        check(hearth_body_get_angular_velocity(w, door, &spin), "get_angular_velocity");
        if (angle > worst_door) {
            worst_door = angle;
        }
        bool on;
        float speed, max;
        check(hearth_joint_get_motor(w, door_hinge, &on, &speed, &max), "hearth_joint_get_motor");
        if (angle > 0.3f && angle < DOOR_OPEN - 0.3f) {
            float err = fabsf(fabsf(spin.y) - DOOR_SPEED);
            if (err > mid_speed_error) {
                mid_speed_error = err;
            }
        }
        /* Reverse the motor at the limits. */
        if ((speed < 0.0f && angle > DOOR_OPEN - 0.01f) || (speed > 0.0f && angle < 0.01f)) {
            check(hearth_joint_set_motor(w, door_hinge, 1, -speed, max), "hearth_joint_set_motor");
            reversals++;
        }
        if (step % 60 == 0) {
            HearthVec3 force, torque;
            check(hearth_joint_get_force(w, joints[0], &force, &torque), "hearth_joint_get_force");
            printf("t=%.0f s  chain: end (%.2f, %.2f) stretch %.3f%%, top joint %.0f N  |  door %.2f rad at %.2f rad/s\n",
                   step * dt, end.position.x, end.position.y, 100.0f * stretch,
                   sqrtf(force.x * force.x + force.y * force.y + force.z * force.z), angle, spin.y);
        }
    }
    printf("chain: largest stretch %.3f%%; door: widest %.3f rad (limit %.1f), speed error mid-swing %.3f rad/s, %d reversals\n",
           100.0f * worst_stretch, worst_door, DOOR_OPEN, mid_speed_error, reversals);
    if (argc > 1) {
        check(hearth_world_record_stop(w), "hearth_world_record_stop");
        fprintf(stderr, "recorded %s: open it with viewer/index.html\n", argv[1]);
    }
    hearth_world_destroy(w);
    if (worst_stretch > 0.01f || worst_door > DOOR_OPEN + 0.05f || mid_speed_error > 0.05f || reversals < 3) {
        fprintf(stderr, "chain_door: outcome out of tolerance\n");
        return 1;
    }
    return 0;
}
