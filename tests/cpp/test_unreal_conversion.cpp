// The engine-independent header of the Unreal plug-in
// (bindings/unreal/HearthPhysics/Source/HearthPhysics/Public/HearthConversion.h), tested with
// stand-ins for FVector and FQuat that do what Unreal's do (double members, the Hamilton
// product, FQuat::RotateVector's formula, FVector::CrossProduct's coordinate formula).
//
// Checks: round trips; that a rotation maps to the same physical rotation (rotate in Unreal
// then convert == convert then rotate in Hearth); handedness (cross products flip sign,
// v = ω × r and τ = r × F hold in both frames); named axes and gravity; quaternion
// normalisation; the fixed-step accumulator and interpolation.
//
// Built by tests/bindings_cpp.rs with -std=c++17 -Wall -Wextra -Wpedantic -Werror and linked
// with the library for one end-to-end check: a body placed and dropped in Unreal terms.
#include "HearthConversion.h"
#include "unreal_standins.h"

#include <cmath>
#include <cstdio>
#include <cstdint>

namespace HC = HearthConversion;

// ---- tests

static void test_named_axes_and_gravity() {
    // Unreal forward, right, up -> Hearth +x, +z, +y; 100 cm -> 1 m.
    CHECK(near3(HC::ToHearthVector(FVector(100, 0, 0)), HearthVec3{1, 0, 0}, 1e-7));
    CHECK(near3(HC::ToHearthVector(FVector(0, 100, 0)), HearthVec3{0, 0, 1}, 1e-7));
    CHECK(near3(HC::ToHearthVector(FVector(0, 0, 100)), HearthVec3{0, 1, 0}, 1e-7));
    // Unreal's default gravity is Hearth's, pointing down.
    const HearthVec3 g = HC::ToHearthVector(FVector(0, 0, -980));
    CHECK(near3(g, HearthVec3{0, -9.8f, 0}, 1e-6));
    const HearthWorldDef def = hearth_world_def_default();
    CHECK(def.gravity.y < 0 && def.gravity.x == 0 && def.gravity.z == 0);
    const FVector back = HC::ToUnrealVector<FVector>(def.gravity);
    CHECK(back.X == 0 && back.Y == 0 && back.Z < -980 && back.Z > -982); // -981 cm/s²
    // Units.
    CHECK(near3(HC::ToHearthForce(FVector(0, 0, 98100)), HearthVec3{0, 981, 0}, 1e-3)); // kg·cm/s² -> N
    CHECK_NEAR(HC::ToHearthDensity(1.0), 1000.0, 0.0);                                  // water
    CHECK(near3(HC::ToHearthDirection(FVector(0, 0, 1)), HearthVec3{0, 1, 0}, 0.0));
}

static void test_round_trips() {
    for (int i = 0; i < 200; i++) {
        const FVector v = rnd_vec(5000.0);
        CHECK(near3(HC::ToUnrealVector<FVector>(HC::ToHearthVector(v)), v, 1e-3));
        CHECK(near3(HC::ToUnrealDirection<FVector>(HC::ToHearthDirection(v)), v, 1e-3));
        CHECK(near3(HC::ToUnrealAngular<FVector>(HC::ToHearthAngular(v)), v, 1e-3));
        CHECK(near3(HC::ToUnrealForce<FVector>(HC::ToHearthForce(v)), v, 1e-3));
        CHECK(near3(HC::ToUnrealTorque<FVector>(HC::ToHearthTorque(v)), v, 1e-3));
        const FQuat q = rnd_quat();
        const FQuat r = HC::ToUnrealQuat<FQuat>(HC::ToHearthQuat(q));
        const double d = q.X * r.X + q.Y * r.Y + q.Z * r.Z + q.W * r.W;
        CHECK_NEAR(d, 1.0, 1e-6); // the same quaternion, not just the same rotation
    }
}

static void test_rotations_map_to_the_same_physical_rotation() {
    for (int i = 0; i < 500; i++) {
        const FQuat q = rnd_quat();
        const FVector v = rnd_vec(300.0);
        // Rotate in Unreal, then convert == convert, then rotate in Hearth.
        const HearthVec3 a = HC::ToHearthVector(q.RotateVector(v));
        const HearthVec3 b = HC::Rotate(HC::ToHearthQuat(q), HC::ToHearthVector(v));
        CHECK(near3(a, b, 2e-5 * 3.0));
        // Composition is kept: convert(q1 * q2) == convert(q1) * convert(q2) (as rotations).
        const FQuat q2 = rnd_quat();
        const HearthVec3 c = HC::ToHearthVector((q * q2).RotateVector(v));
        const HearthVec3 e = HC::Rotate(HC::ToHearthQuat(q), HC::Rotate(HC::ToHearthQuat(q2), HC::ToHearthVector(v)));
        CHECK(near3(c, e, 2e-5 * 3.0));
    }
    // A positive yaw in Unreal turns forward toward right (seen from above, clockwise);
    // physically the same turn in Hearth takes +x toward +z, a negative angle about +y.
    const FQuat yaw(FVector(0, 0, 1), 0.5 * M_PI);
    const FVector right = yaw.RotateVector(FVector(1, 0, 0));
    CHECK(near3(right, FVector(0, 1, 0), 1e-12));
    const HearthQuat h = HC::ToHearthQuat(yaw);
    CHECK(same_rotation(h, hq_axis_angle(HearthVec3{0, 1, 0}, -0.5 * M_PI), 1e-6));
    CHECK(near3(HC::Rotate(h, HearthVec3{1, 0, 0}), HearthVec3{0, 0, 1}, 1e-6));
}

static void test_handedness() {
    // Unreal is left-handed: forward × right = up by its coordinate formula.
    const FVector up = FVector::CrossProduct(FVector(1, 0, 0), FVector(0, 1, 0));
    CHECK(near3(up, FVector(0, 0, 1), 0.0));
    // Hearth is right-handed: the converted forward × right is down, and forward × up = right.
    const HearthVec3 f = HC::ToHearthDirection(FVector(1, 0, 0));
    const HearthVec3 r = HC::ToHearthDirection(FVector(0, 1, 0));
    const HearthVec3 u = HC::ToHearthDirection(FVector(0, 0, 1));
    CHECK(near3(HC::Cross(f, r), HearthVec3{-u.x, -u.y, -u.z}, 0.0));
    CHECK(near3(HC::Cross(f, u), r, 0.0));
    for (int i = 0; i < 200; i++) {
        const FVector a = rnd_vec(10.0), b = rnd_vec(10.0);
        // Cross products of vectors flip sign (det M = -1)...
        const HearthVec3 x = HC::ToHearthDirection(FVector::CrossProduct(a, b));
        const HearthVec3 y = HC::Cross(HC::ToHearthDirection(a), HC::ToHearthDirection(b));
        CHECK(near3(x, HearthVec3{-y.x, -y.y, -y.z}, 1e-4));
        // ...so pseudo-vectors map by -M and the physics laws read the same in both frames:
        // v = ω × r (velocity of a point on a spinning body) and τ = r × F.
        const FVector w = rnd_vec(3.0), rr = rnd_vec(200.0), F = rnd_vec(5000.0);
        const HearthVec3 v_h = HC::ToHearthVector(FVector::CrossProduct(w, rr));
        CHECK(near3(v_h, HC::Cross(HC::ToHearthAngular(w), HC::ToHearthVector(rr)), 1e-4));
        const HearthVec3 tau_h = HC::ToHearthTorque(FVector::CrossProduct(rr, F));
        CHECK(near3(tau_h, HC::Cross(HC::ToHearthVector(rr), HC::ToHearthForce(F)), 1e-3));
        // Angular velocity agrees with the rotation it produces over dt.
        const double n = std::sqrt(w.X * w.X + w.Y * w.Y + w.Z * w.Z);
        const double dt = 0.01;
        const FQuat turn(w * (1.0 / n), n * dt);
        const HearthVec3 wh = HC::ToHearthAngular(w);
        CHECK(same_rotation(HC::ToHearthQuat(turn), hq_axis_angle(wh, n * dt), 1e-6));
    }
}

static void test_quaternion_normalisation() {
    const HearthQuat q = HC::ToHearthQuat(FQuat(0, 0, 2, 2)); // not unit
    CHECK_NEAR(qlen(q), 1.0, 1e-6);
    const HearthQuat zero = HC::ToHearthQuat(FQuat(0, 0, 0, 0));
    CHECK(zero.x == 0 && zero.y == 0 && zero.z == 0 && zero.w == 1);
    const HearthQuat nan = HC::ToHearthQuat(FQuat(std::nan(""), 0, 0, 1));
    CHECK(nan.w == 1 && nan.x == 0);
    const FQuat back = HC::ToUnrealQuat<FQuat>(HearthQuat{0, 3, 0, 4});
    CHECK_NEAR(std::sqrt(back.X * back.X + back.Y * back.Y + back.Z * back.Z + back.W * back.W), 1.0, 1e-12);
    for (int i = 0; i < 100; i++) {
        const FQuat u = rnd_quat();
        const double s = rnd(0.01, 100.0);
        CHECK(same_rotation(HC::ToHearthQuat(FQuat(u.X * s, u.Y * s, u.Z * s, u.W * s)), HC::ToHearthQuat(u), 1e-6));
    }
    // Hearth accepts what the conversion makes.
    const HearthBodyDef def = hearth_body_def_default();
    CHECK(def.transform.rotation.w == 1.0f);
}

static void test_transforms() {
    // A local point placed by an Unreal transform, then converted, equals the point converted
    // and placed by the converted transform.
    for (int i = 0; i < 200; i++) {
        const FQuat q = rnd_quat();
        const FVector loc = rnd_vec(10000.0), local = rnd_vec(100.0);
        const FVector world = q.RotateVector(local) + loc;
        const HearthTransform t = HC::ToHearthTransform(loc, q);
        const HearthVec3 p = HC::Rotate(t.rotation, HC::ToHearthVector(local));
        const HearthVec3 placed{p.x + t.position.x, p.y + t.position.y, p.z + t.position.z};
        CHECK(near3(placed, HC::ToHearthVector(world), 1e-4 * 100.0 * 0.01 + 1e-4));
    }
}

static void test_accumulator() {
    HC::FixedStepAccumulator acc(1.0 / 60.0, 5);
    // 144 Hz frames: in 1 s exactly 60 steps, alpha always in [0, 1) and equal to leftover/step.
    int steps = 0;
    bool alpha_ok = true;
    for (int i = 0; i < 144; i++) {
        const int n = acc.Advance(1.0 / 144.0);
        alpha_ok = alpha_ok && n >= 0 && n <= 1 && acc.Alpha() >= 0.0 && acc.Alpha() < 1.0;
        alpha_ok = alpha_ok && std::fabs(acc.Alpha() - acc.GetAccumulated() * 60.0) < 1e-9;
        steps += n;
    }
    CHECK(alpha_ok);
    CHECK(steps == 60 || steps == 59); // 144 frames of 1/144 s is 1 s up to rounding
    CHECK(steps + acc.Alpha() > 59.999 && steps + acc.Alpha() < 60.001);
    // 30 Hz frames: exactly two steps each, alpha 0 (rounding does not lose a step).
    acc.Reset();
    bool two = true;
    for (int i = 0; i < 100; i++) {
        two = two && acc.Advance(1.0 / 30.0) == 2 && acc.Alpha() < 1e-6;
    }
    CHECK(two);
    // Half a step: no step, alpha 0.5; then another half: one step.
    acc.Reset();
    CHECK(acc.Advance(0.5 / 60.0) == 0);
    CHECK_NEAR(acc.Alpha(), 0.5, 1e-9);
    CHECK(acc.Advance(0.5 / 60.0) == 1);
    CHECK(acc.Alpha() < 1e-6);
    // A 1 s hitch: capped at 5 steps, the excess whole steps dropped, the fraction kept.
    acc.Reset();
    CHECK(acc.Advance(1.0 + 0.25 / 60.0) == 5);
    CHECK_NEAR(acc.Alpha(), 0.25, 1e-6);
    CHECK(acc.GetDroppedFrames() == 1);
    // The frame covered 5 steps and the kept fraction; the rest was dropped.
    CHECK_NEAR(acc.GetLastSimulatedSeconds(), 5.25 / 60.0, 1e-9);
    CHECK_NEAR(acc.GetLastDroppedSeconds(), 1.0 - 5.0 / 60.0, 1e-9);
    CHECK(acc.Advance(0.0) == 0); // nothing left over to catch up on
    CHECK(acc.GetLastSimulatedSeconds() == 0.0 && acc.GetLastDroppedSeconds() == 0.0);
    CHECK(acc.Advance(0.01) == 0);
    CHECK_NEAR(acc.GetLastSimulatedSeconds(), 0.01, 0.0); // not capped: all of the frame
    // Bad frame times count as zero.
    acc.Reset();
    CHECK(acc.Advance(-1.0) == 0 && acc.Advance(std::nan("")) == 0 && acc.Advance(INFINITY) == 0);
    CHECK(acc.Alpha() == 0.0);
    CHECK(acc.GetLastSimulatedSeconds() == 0.0);
    // Bad settings fall back to sane ones.
    HC::FixedStepAccumulator odd(0.0, 0);
    CHECK_NEAR(odd.GetStepSeconds(), 1.0 / 60.0, 0.0);
    CHECK(odd.GetMaxStepsPerFrame() == 1);
}

static void test_interpolation() {
    const HearthTransform a{HearthVec3{0, 0, 0}, HearthQuat{0, 0, 0, 1}};
    const HearthTransform b{HearthVec3{2, 4, -6}, hq_axis_angle(HearthVec3{0, 1, 0}, 0.5 * M_PI)};
    const HearthTransform at0 = HC::Interpolate(a, b, 0.0), at1 = HC::Interpolate(a, b, 1.0);
    CHECK(near3(at0.position, a.position, 0.0) && same_rotation(at0.rotation, a.rotation, 1e-7));
    CHECK(near3(at1.position, b.position, 1e-6) && same_rotation(at1.rotation, b.rotation, 1e-6));
    const HearthTransform mid = HC::Interpolate(a, b, 0.5);
    CHECK(near3(mid.position, HearthVec3{1, 2, -3}, 1e-6));
    CHECK(same_rotation(mid.rotation, hq_axis_angle(HearthVec3{0, 1, 0}, 0.25 * M_PI), 1e-6)); // 45°
    CHECK_NEAR(qlen(mid.rotation), 1.0, 1e-6);
    // The short way round: -b is the same rotation and gives the same halfway pose.
    HearthTransform nb = b;
    nb.rotation = HearthQuat{-b.rotation.x, -b.rotation.y, -b.rotation.z, -b.rotation.w};
    CHECK(same_rotation(HC::Interpolate(a, nb, 0.5).rotation, mid.rotation, 1e-6));
    // Nearly equal rotations (the nlerp branch) stay unit; alpha is clamped to [0, 1].
    const HearthTransform c{HearthVec3{0, 0, 0}, hq_axis_angle(HearthVec3{1, 0, 0}, 1e-3)};
    CHECK_NEAR(qlen(HC::Interpolate(a, c, 0.3).rotation), 1.0, 1e-6);
    CHECK(near3(HC::Interpolate(a, b, 7.0).position, b.position, 1e-6));
    // With the accumulator: render pose = Interpolate(previous state, current state, Alpha()).
    HC::FixedStepAccumulator acc(0.1, 8);
    acc.Advance(0.125);
    const HearthTransform shown = HC::Interpolate(a, b, acc.Alpha());
    CHECK(near3(shown.position, HearthVec3{0.5f, 1.0f, -1.5f}, 1e-5)); // alpha 0.25
}

// The whole round: an Unreal actor's pose and Unreal gravity go into a Hearth world, the
// world steps 1 s, and the pose read back is where Unreal physics would put it.
static void test_drop_in_a_real_world() {
    HearthWorldDef wd = hearth_world_def_default();
    wd.gravity = HC::ToHearthVector(FVector(0, 0, -980));
    HearthWorld *world = nullptr;
    CHECK(hearth_world_create(&wd, &world) == HEARTH_OK);
    const FQuat rot(FVector(0, 0, 1), 0.3);
    HearthBodyDef bd = hearth_body_def_default();
    bd.type = HEARTH_BODY_DYNAMIC;
    bd.transform = HC::ToHearthTransform(FVector(100, 200, 5000), rot);
    bd.linear_velocity = HC::ToHearthVector(FVector(0, 50, 0)); // 50 cm/s to the right
    HearthBodyId body{0, 0};
    CHECK(hearth_body_create(world, &bd, &body) == HEARTH_OK);
    for (int i = 0; i < 60; i++) {
        CHECK(hearth_world_step(world, 1.0f / 60.0f) == HEARTH_OK);
    }
    HearthTransform t{};
    CHECK(hearth_body_get_transform(world, body, &t) == HEARTH_OK);
    const FVector p = HC::ToUnrealVector<FVector>(t.position);
    CHECK_NEAR(p.X, 100.0, 0.01);
    CHECK_NEAR(p.Y, 250.0, 0.05);
    CHECK_NEAR(p.Z, 5000.0 - 490.0, 10.0); // ½ g t², up to the integrator's first-order error
    CHECK(p.Z < 5000.0 - 480.0);
    const FQuat r = HC::ToUnrealQuat<FQuat>(t.rotation);
    CHECK_NEAR(std::fabs(r.X * rot.X + r.Y * rot.Y + r.Z * rot.Z + r.W * rot.W), 1.0, 1e-6);
    hearth_world_destroy(world);
}

int main() {
    test_named_axes_and_gravity();
    test_round_trips();
    test_rotations_map_to_the_same_physical_rotation();
    test_handedness();
    test_quaternion_normalisation();
    test_transforms();
    test_accumulator();
    test_interpolation();
    test_drop_in_a_real_world();
    std::printf("test_unreal_conversion: %d passed, %d failed\n", g_passed, g_failed);
    return g_failed == 0 ? 0 : 1;
}
