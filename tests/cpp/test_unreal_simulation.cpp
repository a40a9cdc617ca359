// The engine-independent core of the Unreal plug-in
// (bindings/unreal/HearthPhysics/Source/HearthPhysics/Public/HearthSimulation.h and
// HearthShapes.h) against a real Hearth world, driven the way UHearthWorldSubsystem drives it:
// frames of varying length, actors stood in for by poses in Unreal units (cm, FQuat), every
// pose converted with HearthConversion.h both ways.
//
// Checks, each analytic case beside a seeded randomized one:
// * forces act for their frame's duration, whatever the frame rate (1 N on 1 kg for a 1/30 s
//   frame that runs two steps gives 1/30 m/s; for three 1/180 s frames before one step,
//   1/60 m/s), torques and forces at points likewise, time dropped at the cap excluded;
// * impulses act once, at once; velocity changes ignore the mass;
// * rendered poses are interpolated: a body moving steadily is shown exactly one step behind
//   the game clock, at any frame rate;
// * kinematic bodies reach their actor's pose by the end of each frame's steps, carry a box
//   standing on them (it slips v²/(2μg) at the start, as the analytic answer says), and stop
//   when the actor stops;
// * gameplay moves of dynamic and static actors teleport their bodies (no snapping back);
//   round trips through Unreal units never do;
// * gravity followed from the host; repeated errors throttled;
// * simple-collision elements (spheres, boxes, capsules, scaled and rotated) become the
//   shapes Unreal describes (corners, end points, masses from g/cm³);
// * shared geometry: a convex element becomes a hull (a 1 m cube of 1 g/cm³ weighs 1000 kg,
//   scaled uniformly or not; it rests on the ground at 0.5 m), complex collision a mesh (a box
//   rests on a converted floor at its analytic height; Unreal's winding faces up after the
//   handedness flip, the reversed winding down, mirrored scales flip it back), a landscape a
//   heightfield (a box rests on a converted sloped landscape at its analytic distance, axes
//   and spacing as Unreal's, and falls off past its edge); the cache shares one geometry
//   between components of one asset and destroys it after its last user; bad input is
//   reported through the error callback with nothing cached; a seeded randomized pile of
//   converted hulls on a converted bumpy landscape stays finite, bounded and on it.
//
// Built by tests/bindings_cpp.rs with -std=c++17 -Wall -Wextra -Wpedantic -Wshadow -Werror
// (Unreal builds treat shadowing as an error) and run under valgrind with HEARTH_VALGRIND=1.
#include "HearthConversion.h"
#include "HearthShapes.h"
#include "HearthSimulation.h"
#include "unreal_standins.h"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

namespace HC = HearthConversion;
namespace Core = HearthCore;

static const double H = 1.0 / 60.0; // the simulation's fixed step

// ---- helpers

static HearthWorldDef world_def(HearthVec3 gravity) {
    HearthWorldDef d = hearth_world_def_default();
    d.gravity = gravity;
    return d;
}

static const HearthVec3 ZERO_G{0.0f, 0.0f, 0.0f};
static const HearthVec3 EARTH_G{0.0f, -9.81f, 0.0f};

static HearthTransform at(double x, double y, double z) {
    return HearthTransform{HearthVec3{(float)x, (float)y, (float)z}, HearthQuat{0, 0, 0, 1}};
}

/** A dynamic box of the given half extents and mass (density chosen to match), awake for
 * good so that tests on still bodies are not about sleep. */
static HearthBodyId add_box(Core::FSimulation &sim, HearthTransform pose, HearthVec3 half, double mass,
                            bool allow_sleep = false) {
    HearthBodyDef bd = hearth_body_def_default();
    bd.type = HEARTH_BODY_DYNAMIC;
    bd.transform = pose;
    bd.allow_sleep = allow_sleep ? 1 : 0;
    const HearthBodyId id = sim.AddBody(bd);
    HearthShapeDef sd = hearth_shape_def_default();
    sd.density = (float)(mass / (8.0 * half.x * half.y * half.z));
    const HearthBox box{HearthVec3{0, 0, 0}, HearthQuat{0, 0, 0, 1}, half};
    CHECK(sim.AddBox(id, sd, box));
    return id;
}

static HearthBodyId add_kinematic_box(Core::FSimulation &sim, HearthTransform pose, HearthVec3 half) {
    HearthBodyDef bd = hearth_body_def_default();
    bd.type = HEARTH_BODY_KINEMATIC;
    bd.transform = pose;
    const HearthBodyId id = sim.AddBody(bd);
    const HearthShapeDef sd = hearth_shape_def_default();
    const HearthBox box{HearthVec3{0, 0, 0}, HearthQuat{0, 0, 0, 1}, half};
    CHECK(sim.AddBox(id, sd, box));
    return id;
}

static void add_ground(Core::FSimulation &sim) {
    const HearthBodyDef bd = hearth_body_def_default(); // static
    const HearthBodyId ground = sim.AddBody(bd);
    const HearthShapeDef sd = hearth_shape_def_default();
    HearthShapeId shape{0, 0};
    const HearthPlane plane{HearthVec3{0, 1, 0}, 0.0f};
    CHECK(hearth_shape_create_plane(sim.GetWorld(), ground, &sd, &plane, &shape) == HEARTH_OK);
}

static HearthVec3 velocity(Core::FSimulation &sim, HearthBodyId b) {
    HearthVec3 v{0, 0, 0};
    CHECK(sim.GetLinearVelocity(b, v));
    return v;
}
static HearthVec3 spin(Core::FSimulation &sim, HearthBodyId b) {
    HearthVec3 w{0, 0, 0};
    CHECK(sim.GetAngularVelocity(b, w));
    return w;
}
static HearthTransform stepped(Core::FSimulation &sim, HearthBodyId b) {
    HearthTransform t{};
    CHECK(sim.GetSteppedPose(b, t));
    return t;
}

/** Collects the simulation's error messages. */
struct ErrorLog {
    std::vector<std::string> messages;
    static void Receive(void *user_data, const char *message) {
        static_cast<ErrorLog *>(user_data)->messages.push_back(message);
    }
};

static bool finite3(const HearthVec3 &v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// ---- forces

static void test_force_lasts_for_its_frame() {
    // The cases the issue measured with hearth_body_apply_force called once per frame.
    {
        Core::FSimulation sim;
        CHECK(sim.Create(world_def(ZERO_G)));
        const HearthBodyId b = add_box(sim, at(0, 0, 0), HearthVec3{0.05f, 0.05f, 0.05f}, 1.0);
        float mass = 0;
        CHECK(sim.GetMass(b, mass));
        CHECK_NEAR(mass, 1.0, 1e-5);
        CHECK(sim.AddForce(b, HearthVec3{1, 0, 0}));
        CHECK(sim.Advance(1.0 / 30.0) == 2);
        CHECK_NEAR(velocity(sim, b).x, 1.0 / 30.0, 1e-6); // was 1/60: the force counted for one step
    }
    {
        Core::FSimulation sim;
        CHECK(sim.Create(world_def(ZERO_G)));
        const HearthBodyId b = add_box(sim, at(0, 0, 0), HearthVec3{0.05f, 0.05f, 0.05f}, 1.0);
        int steps = 0;
        for (int frame = 0; frame < 3; frame++) {
            CHECK(sim.AddForce(b, HearthVec3{1, 0, 0}));
            steps += sim.Advance(1.0 / 180.0);
        }
        CHECK(steps == 1);
        CHECK_NEAR(velocity(sim, b).x, 1.0 / 60.0, 1e-6); // was 0.05: three frames' forces in one step
        // No force in the next frame: nothing more is delivered.
        CHECK(sim.Advance(1.0 / 60.0) == 1);
        CHECK_NEAR(velocity(sim, b).x, 1.0 / 60.0, 1e-6);
    }
    // A hitch: 0.5 s at a cap of 8 steps simulates 8/60 s; the force acts for that long.
    {
        Core::FSimulation sim;
        CHECK(sim.Create(world_def(ZERO_G)));
        const HearthBodyId b = add_box(sim, at(0, 0, 0), HearthVec3{0.05f, 0.05f, 0.05f}, 1.0);
        CHECK(sim.AddForce(b, HearthVec3{0, 0, 2}));
        CHECK(sim.Advance(0.5) == 8);
        CHECK_NEAR(velocity(sim, b).z, 2.0 * 8.0 / 60.0, 1e-6);
    }
    // Torque: a 1 kg cube of 0.1 m edges has I = m·a²/6 = 1/600 kg·m² about any axis.
    {
        Core::FSimulation sim;
        CHECK(sim.Create(world_def(ZERO_G)));
        const HearthBodyId b = add_box(sim, at(0, 0, 0), HearthVec3{0.05f, 0.05f, 0.05f}, 1.0);
        CHECK(sim.AddTorque(b, HearthVec3{0, 0.001f, 0}));
        CHECK(sim.Advance(1.0 / 30.0) == 2);
        CHECK_NEAR(spin(sim, b).y, 0.001 / 30.0 * 600.0, 1e-5); // 0.02 rad/s
        // A force at a point: the force at the centre plus r × F.
        CHECK(sim.AddForceAtPoint(b, HearthVec3{0, 0, 1}, HearthVec3{0.05f, 0, 0}));
        CHECK(sim.Advance(1.0 / 60.0) == 1);
        CHECK_NEAR(velocity(sim, b).z, 1.0 / 60.0, 1e-5);
        CHECK_NEAR(spin(sim, b).y, 0.02 - 0.05 / 60.0 * 600.0, 2e-4); // (0.05,0,0) × (0,0,1) = (0,-0.05,0)
    }
    // Forces on bodies that forces do not move are refused; so are NaN forces, with an error.
    {
        Core::FSimulation sim;
        ErrorLog log;
        sim.SetErrorCallback(&ErrorLog::Receive, &log);
        CHECK(sim.Create(world_def(ZERO_G)));
        const HearthBodyId k = add_kinematic_box(sim, at(0, 0, 0), HearthVec3{1, 1, 1});
        CHECK(!sim.AddForce(k, HearthVec3{1, 0, 0}));
        const HearthBodyId b = add_box(sim, at(5, 0, 0), HearthVec3{0.05f, 0.05f, 0.05f}, 1.0);
        CHECK(!sim.AddForce(b, HearthVec3{NAN, 0, 0}));
        CHECK(log.messages.size() == 1 && log.messages[0].find("AddForce: the force (nan, 0, 0) is not finite") == 0);
        CHECK(!sim.AddTorque(b, HearthVec3{0, INFINITY, 0}));
        CHECK(!sim.AddForceAtPoint(b, HearthVec3{1, 0, 0}, HearthVec3{0, 0, NAN}));
        CHECK(log.messages.size() == 3);
        CHECK(!sim.AddForce(HearthBodyId{0, 0}, HearthVec3{1, 0, 0}));
        CHECK(sim.Advance(H) == 1);
        CHECK(velocity(sim, b).x == 0.0f && spin(sim, b).y == 0.0f);
    }
}

// Randomized: frames between 1/300 and 1/8 s with a constant force. Whatever the frames, the
// velocity after each frame is F/m times the physics clock (steps × h): every step received
// exactly F·h.
static void test_force_at_random_frame_rates() {
    for (int seed = 0; seed < 12; seed++) {
        g_seed = 0x1234567ull + (uint64_t)seed * 7919ull;
        Core::FSimulation sim;
        CHECK(sim.Create(world_def(ZERO_G)));
        const double mass = rnd(0.5, 20.0);
        const HearthBodyId b = add_box(sim, at(0, 0, 0), HearthVec3{0.2f, 0.1f, 0.3f}, mass);
        const HearthVec3 f{(float)rnd(-50, 50), (float)rnd(-50, 50), (float)rnd(-50, 50)};
        long steps = 0;
        bool per_frame_ok = true;
        double worst = 0.0;
        for (double t = 0.0; t < 2.0;) {
            const double dt = rnd(0.0, 1.0) < 0.1 ? rnd(1.0 / 12.0, 1.0 / 8.0) : rnd(1.0 / 300.0, 1.0 / 30.0);
            t += dt;
            sim.AddForce(b, f);
            steps += sim.Advance(dt);
            const HearthVec3 v = velocity(sim, b);
            const double clock = (double)steps * H;
            const double ex = f.x / mass * clock, ey = f.y / mass * clock, ez = f.z / mass * clock;
            const double err = std::fmax(std::fabs(v.x - ex), std::fmax(std::fabs(v.y - ey), std::fabs(v.z - ez)));
            worst = std::fmax(worst, err / (1.0 + std::fabs(ex) + std::fabs(ey) + std::fabs(ez)));
            per_frame_ok = per_frame_ok && err <= 2e-5 * (1.0 + std::fabs(ex) + std::fabs(ey) + std::fabs(ez));
        }
        if (!per_frame_ok) {
            std::printf("seed %d: worst relative velocity error %g\n", seed, worst);
        }
        CHECK(per_frame_ok);
        CHECK(steps >= 119); // 2 s and a little more, no hitch above the cap of 8 steps
    }
}

// ---- impulses

static void test_impulses_act_once() {
    Core::FSimulation sim;
    CHECK(sim.Create(world_def(ZERO_G)));
    const HearthBodyId b = add_box(sim, at(0, 0, 0), HearthVec3{0.05f, 0.05f, 0.05f}, 2.0);
    CHECK(sim.AddImpulse(b, HearthVec3{3, 0, 0}, false));
    CHECK_NEAR(velocity(sim, b).x, 1.5, 1e-6); // at once
    CHECK(sim.Advance(1.0 / 240.0) == 0);
    CHECK(sim.Advance(1.0 / 20.0) == 3);
    CHECK_NEAR(velocity(sim, b).x, 1.5, 1e-6); // and only once
    CHECK(sim.AddImpulse(b, HearthVec3{0, 0, 0.5f}, true)); // a velocity change: 0.5 m/s whatever the mass
    CHECK_NEAR(velocity(sim, b).z, 0.5, 1e-6);
    // At a point: r × J over I = m·a²/6 = 2/600.
    CHECK(sim.AddImpulseAtPoint(b, HearthVec3{0, 0.01f, 0}, stepped(sim, b).position));
    CHECK_NEAR(spin(sim, b).x, 0.0, 1e-6);
    CHECK(sim.AddAngularImpulse(b, HearthVec3{0.002f, 0, 0}));
    CHECK_NEAR(spin(sim, b).x, 0.002 * 300.0, 1e-4);
    // Randomized: random impulses in random frame patterns change v by ΣJ/m.
    for (int seed = 0; seed < 8; seed++) {
        g_seed = 0xBADC0FFEEull + (uint64_t)seed;
        Core::FSimulation s2;
        CHECK(s2.Create(world_def(ZERO_G)));
        const double mass = rnd(0.3, 30.0);
        const HearthBodyId c = add_box(s2, at(0, 0, 0), HearthVec3{0.1f, 0.2f, 0.3f}, mass);
        double jx = 0.0;
        for (int frame = 0; frame < 100; frame++) {
            if (rnd(0, 1) < 0.3) {
                const float j = (float)rnd(-5, 5);
                CHECK(s2.AddImpulse(c, HearthVec3{j, 0, 0}, false));
                jx += j;
            }
            s2.Advance(rnd(0.0, 0.06));
        }
        CHECK_NEAR(velocity(s2, c).x, jx / mass, 1e-4 * (1.0 + std::fabs(jx / mass)));
    }
}

// ---- interpolation

static void test_rendered_motion_is_smooth() {
    for (int seed = 0; seed < 6; seed++) {
        g_seed = 0xF00Dull + (uint64_t)seed * 31ull;
        Core::FSimulation sim;
        CHECK(sim.Create(world_def(ZERO_G)));
        HearthBodyDef bd = hearth_body_def_default();
        bd.type = HEARTH_BODY_DYNAMIC;
        bd.allow_sleep = 0;
        bd.linear_velocity = HearthVec3{3.0f, 0, 0};
        const HearthBodyId b = sim.AddBody(bd);
        const HearthSphere ball{HearthVec3{0, 0, 0}, 0.25f};
        CHECK(sim.AddSphere(b, hearth_shape_def_default(), ball));
        // Rendered at the game clock minus one step: x = 3 (t - h) once a step has run.
        double t = 0.0;
        long steps = 0;
        bool on_line = true;
        const double hz = rnd(25.0, 250.0);
        for (int frame = 0; frame < 200; frame++) {
            const double dt = (1.0 / hz) * rnd(0.8, 1.2);
            t += dt;
            steps += sim.Advance(dt);
            HearthTransform shown{};
            CHECK(sim.GetRenderPose(b, shown));
            if (steps >= 1) {
                on_line = on_line && std::fabs(shown.position.x - 3.0 * (t - H)) < 2e-4;
            }
        }
        CHECK(on_line);
    }
}

// ---- kinematic bodies

static HearthTransform platform_pose(double x, double y, double yaw) {
    const double s = std::sin(0.5 * yaw), c = std::cos(0.5 * yaw);
    return HearthTransform{HearthVec3{(float)x, (float)y, 0.0f}, HearthQuat{0.0f, (float)s, 0.0f, (float)c}};
}

static void test_kinematic_platform_carries_a_box() {
    Core::FSimulation sim;
    CHECK(sim.Create(world_def(EARTH_G)));
    add_ground(sim);
    const HearthBodyId platform = add_kinematic_box(sim, platform_pose(0, 1, 0), HearthVec3{3, 0.1f, 3});
    const HearthBodyId box = add_box(sim, at(0, 1.35, 0), HearthVec3{0.25f, 0.25f, 0.25f}, 10.0);
    for (int i = 0; i < 60; i++) { // settle on the still platform
        sim.SyncFromHost(platform, platform_pose(0, 1, 0));
        sim.Advance(H);
    }
    const HearthTransform start = stepped(sim, box);
    CHECK_NEAR(start.position.y, 1.35, 0.01);
    // The actor moves at 1 m/s along x for 2 s, rendered at an uneven 40-200 Hz.
    // The platform's physics clock runs behind the game clock by the accumulator's leftover;
    // after every frame that steps it is where the actor was at that moment.
    g_seed = 0xC0FFEEull;
    double t = 0.0;
    bool followed = true, steady = true;
    while (t < 2.0 - 1e-9) {
        const double dt = std::fmin(rnd(1.0 / 200.0, 1.0 / 40.0), 2.0 - t);
        t += dt;
        sim.SyncFromHost(platform, platform_pose(t, 1, 0));
        if (sim.Advance(dt) > 0) {
            const double physics_t = t - sim.GetAccumulator().GetAccumulated();
            followed = followed && Core::SamePose(stepped(sim, platform), platform_pose(physics_t, 1, 0));

            steady = steady && std::fabs(velocity(sim, platform).x - 1.0) < 1e-3; // the actor's speed, every step
        }
    }
    CHECK(followed);
    CHECK(steady);
    // Friction carries the box: it slips while friction brings it to 1 m/s, v²/(2 μ g) with
    // μ = 0.6 (both materials) = 8.5 cm, then rides along.
    const double slip = 1.0 / (2.0 * 0.6 * 9.81);
    const double platform_moved = stepped(sim, platform).position.x; // 2 m less the physics lag
    const double moved = stepped(sim, box).position.x - start.position.x;
    std::printf("platform: box carried %.4f m while the platform moved %.4f m (analytic %.4f)\n", moved,
                platform_moved, platform_moved - slip);
    CHECK_NEAR(moved, platform_moved - slip, 0.005); // measured 1.4 mm off
    CHECK_NEAR(velocity(sim, box).x, 1.0, 0.02);
    // The actor stops at 2 m: the physics catches up with it in the next step and holds still
    // from the one after.
    const HearthTransform stop = platform_pose(2.0, 1, 0);
    for (int i = 0; i < 2; i++) {
        sim.SyncFromHost(platform, stop);
        CHECK(sim.Advance(H) == 1);
    }
    CHECK(Core::SamePose(stepped(sim, platform), stop));
    CHECK_NEAR(velocity(sim, platform).x, 0.0, 1e-6);
    for (int i = 0; i < 60; i++) {
        sim.SyncFromHost(platform, stop);
        sim.Advance(H);
    }
    CHECK(Core::SamePose(stepped(sim, platform), stop));
    CHECK_NEAR(velocity(sim, platform).x, 0.0, 1e-6);
    CHECK_NEAR(velocity(sim, box).x, 0.0, 0.01);
    // An elevator: up 1 m in 2 s, the box stays on top (0.35 m above the platform's centre).
    t = 0.0;
    bool on_top = true;
    const double x_stop = stop.position.x;
    while (t < 2.0 - 1e-9) {
        t += 1.0 / 75.0;
        sim.SyncFromHost(platform, platform_pose(x_stop, 1.0 + 0.5 * t, 0));
        sim.Advance(1.0 / 75.0);
        const double gap = stepped(sim, box).position.y - stepped(sim, platform).position.y;
        on_top = on_top && std::fabs(gap - 0.35) < 0.01;
    }
    CHECK(on_top);
    // Teleport stops a kinematic body where it is put.
    CHECK(sim.Teleport(platform, platform_pose(x_stop, 5.0, 0)));
    CHECK(sim.Advance(H) == 1);
    CHECK(Core::SamePose(stepped(sim, platform), platform_pose(x_stop, 5.0, 0)));
    CHECK_NEAR(velocity(sim, platform).y, 0.0, 1e-6);
    // A target on a body that is not kinematic is refused.
    CHECK(!sim.SetKinematicTarget(box, at(0, 0, 0)));
}

// Randomized: paths of random sums of sines (position and yaw), random frame rates; the
// platform is at its actor's pose after every frame that steps.
static void test_kinematic_random_paths() {
    for (int seed = 0; seed < 6; seed++) {
        g_seed = 0xABCDEFull * (uint64_t)(seed + 1);
        Core::FSimulation sim;
        CHECK(sim.Create(world_def(EARTH_G)));
        const HearthBodyId platform = add_kinematic_box(sim, platform_pose(0, 0, 0), HearthVec3{1, 0.1f, 1});
        const double ax = rnd(0.5, 3), wx = rnd(0.5, 4), ay = rnd(0.1, 1), wy = rnd(0.5, 3), wyaw = rnd(-2, 2);
        double t = 0.0;
        bool followed = true, finite = true;
        HearthTransform before = platform_pose(0, 0, 0);
        for (int frame = 0; frame < 300; frame++) {
            const double dt = rnd(0.0, 0.05);
            t += dt;
            const HearthTransform host = platform_pose(ax * std::sin(wx * t), ay * std::sin(wy * t), wyaw * t);
            sim.SyncFromHost(platform, host);
            if (sim.Advance(dt) > 0) {
                // Where the actor's path through this frame was when the last step ended.
                const double along = 1.0 - sim.GetAccumulator().GetAccumulated() / dt;
                followed = followed && Core::SamePose(stepped(sim, platform), HC::Interpolate(before, host, along));
            }
            finite = finite && finite3(velocity(sim, platform));
            before = host;
        }
        CHECK(followed);
        CHECK(finite);
    }
}

// ---- gameplay moves, teleports, round trips through Unreal units

/** An actor as Unreal holds it. */
struct Actor {
    FVector location{0, 0, 0};
    FQuat rotation{0, 0, 0, 1};
    HearthTransform pose() const { return HC::ToHearthTransform(location, rotation); }
    void show(const HearthTransform &t) {
        location = HC::ToUnrealVector<FVector>(t.position);
        rotation = HC::ToUnrealQuat<FQuat>(t.rotation);
    }
};

// The threshold of a gameplay move (README: more than 0.1 mm or 0.002°).
static void test_same_pose_threshold() {
    const HearthTransform a = at(3, 4, 5);
    HearthTransform b = a;
    b.position.x += 0.00009f;
    CHECK(Core::SamePose(a, b));
    b.position.x = a.position.x + 0.00012f;
    CHECK(!Core::SamePose(a, b));
    const auto turned = [&](double degrees) {
        HearthTransform t = a;
        t.rotation = hq_axis_angle(HearthVec3{0.3f, 1.0f, -0.2f}, degrees * M_PI / 180.0);
        return t;
    };
    CHECK(Core::SamePose(a, turned(0.001)));
    CHECK(!Core::SamePose(a, turned(0.003)));
    CHECK(Core::SamePose(a, turned(360.0))); // q and -q
}

static void test_gameplay_moves_teleport() {
    Core::FSimulation sim;
    CHECK(sim.Create(world_def(EARTH_G)));
    add_ground(sim);
    // A tumbling box falling from 20 m, its actor updated every frame through Unreal units.
    Actor actor;
    actor.location = FVector(0, 0, 2000);
    actor.rotation = FQuat(FVector(0.6, 0.0, 0.8), 0.7);
    HearthBodyDef bd = hearth_body_def_default();
    bd.type = HEARTH_BODY_DYNAMIC;
    bd.transform = actor.pose();
    bd.angular_velocity = HearthVec3{1.0f, 2.0f, -0.5f};
    const HearthBodyId b = sim.AddBody(bd);
    const HearthBox shape{HearthVec3{0, 0, 0}, HearthQuat{0, 0, 0, 1}, HearthVec3{0.3f, 0.2f, 0.1f}};
    CHECK(sim.AddBox(b, hearth_shape_def_default(), shape));
    g_seed = 0x5EEDull;
    for (int frame = 0; frame < 60; frame++) {
        sim.SyncFromHost(b, actor.pose()); // unchanged by gameplay: no teleport
        sim.Advance(rnd(1.0 / 144.0, 1.0 / 30.0));
        HearthTransform shown{};
        CHECK(sim.GetRenderPose(b, shown));
        actor.show(shown);
    }
    CHECK(sim.GetTeleportCount() == 0);
    const double vy = velocity(sim, b).y;
    CHECK(vy < -3.0); // falling
    // Gameplay moves the actor 5 m forward and to 10 m up: the body goes there and keeps falling.
    actor.location = FVector(500, 0, 1000);
    sim.SyncFromHost(b, actor.pose());
    CHECK(sim.GetTeleportCount() == 1);
    CHECK(sim.Advance(H) == 1);
    HearthTransform shown{};
    CHECK(sim.GetRenderPose(b, shown));
    CHECK_NEAR(shown.position.x, 5.0, 0.05);
    CHECK_NEAR(shown.position.y, 10.0, 0.2); // one step of fall from 10 m, not back at the old height
    CHECK_NEAR(velocity(sim, b).y, vy - 9.81 * H, 0.01); // velocity kept
    actor.show(shown);
    // A static floor moved by gameplay: the box lands on it at its new height.
    HearthBodyDef fd = hearth_body_def_default(); // static
    fd.transform = at(5, 2, 0);
    const HearthBodyId shelf = sim.AddBody(fd);
    const HearthBox slab{HearthVec3{0, 0, 0}, HearthQuat{0, 0, 0, 1}, HearthVec3{2, 0.5f, 2}};
    CHECK(sim.AddBox(shelf, hearth_shape_def_default(), slab));
    sim.SyncFromHost(shelf, at(5, 4, 0)); // gameplay raised it by 2 m
    CHECK(sim.GetTeleportCount() == 2);
    for (int frame = 0; frame < 300; frame++) {
        sim.SyncFromHost(b, actor.pose());
        sim.SyncFromHost(shelf, at(5, 4, 0));
        sim.Advance(H);
        CHECK(sim.GetRenderPose(b, shown));
        actor.show(shown);
    }
    CHECK(sim.GetTeleportCount() == 2);
    CHECK(shown.position.y > 4.5 && shown.position.y < 4.9); // resting on the slab's top at 4.5 m
    // Removing a body forgets it; its id is refused afterwards.
    CHECK(sim.RemoveBody(b));
    CHECK(!sim.HasBody(b));
    CHECK(!sim.GetRenderPose(b, shown));
    CHECK(sim.GetReportedErrorCount() == 0);
}

// Randomized sessions: boxes, balls and capsules on a ground with a moving kinematic paddle;
// random frame times (zero, normal, hitches), random forces, impulses and teleports; every
// dynamic actor round-trips through Unreal units each frame. Teleports happen exactly when
// the test moves an actor; state stays finite and speeds bounded; once the input stops, the
// kinetic energy does not grow and every body ends above the ground.
static void test_random_sessions() {
    for (int seed = 0; seed < 4; seed++) {
        g_seed = 0x777ull + (uint64_t)seed * 104729ull;
        Core::FSimulation sim;
        CHECK(sim.Create(world_def(EARTH_G)));
        add_ground(sim);
        const HearthBodyId paddle = add_kinematic_box(sim, platform_pose(0, 0.5, 0), HearthVec3{2, 0.2f, 0.2f});
        std::vector<HearthBodyId> bodies;
        std::vector<Actor> actors;
        std::vector<double> masses;
        std::vector<HearthVec3> inertia; // principal moments in the body frame (kg·m²)
        const HearthShapeDef material = hearth_shape_def_default();
        for (int i = 0; i < 12; i++) {
            Actor a;
            a.location = FVector(rnd(-300, 300), rnd(-300, 300), rnd(100, 800));
            a.rotation = rnd_quat();
            HearthBodyDef bd = hearth_body_def_default();
            bd.type = HEARTH_BODY_DYNAMIC;
            bd.transform = a.pose();
            const HearthBodyId id = sim.AddBody(bd);
            const FVector one(1, 1, 1);
            const FQuat none(0, 0, 0, 1);
            bool made = false;
            float m = 0;
            HearthVec3 moments{0, 0, 0};
            if (i % 3 == 0) {
                HearthSphere s{};
                made = HearthShapes::MakeSphere(FVector(0, 0, 0), rnd(10, 40), one, s) && sim.AddSphere(id, material, s);
                made = made && sim.GetMass(id, m);
                const float k = 0.4f * m * s.radius * s.radius;
                moments = HearthVec3{k, k, k};
            } else if (i % 3 == 1) {
                HearthBox bx{};
                made = HearthShapes::MakeBox(FVector(0, 0, 0), none, rnd(20, 80), rnd(20, 80), rnd(20, 80), one, bx) &&
                       sim.AddBox(id, material, bx);
                made = made && sim.GetMass(id, m);
                const HearthVec3 e = bx.half_extents; // I = m (b² + c²) / 3 with half extents
                moments = HearthVec3{m * (e.y * e.y + e.z * e.z) / 3, m * (e.x * e.x + e.z * e.z) / 3,
                                     m * (e.x * e.x + e.y * e.y) / 3};
            } else {
                HearthCapsule c{};
                made = HearthShapes::MakeCapsule(FVector(0, 0, 0), none, rnd(10, 30), rnd(0, 60), one, c) &&
                       sim.AddCapsule(id, material, c); // along the body's y
                made = made && sim.GetMass(id, m);
                const double r = c.radius, len = c.b.y - c.a.y;
                const double cyl = M_PI * r * r * len, ball = 4.0 / 3.0 * M_PI * r * r * r;
                const double mc = m * cyl / (cyl + ball), ms = m * ball / (cyl + ball);
                const double axial = mc * r * r / 2 + ms * 0.4 * r * r;
                const double across = mc * (len * len / 12 + r * r / 4) + ms * (0.4 * r * r + len * len / 4 + 3 * len * r / 8);
                moments = HearthVec3{(float)across, (float)axial, (float)across};
            }
            CHECK(made);
            bodies.push_back(id);
            actors.push_back(a);
            masses.push_back(m);
            inertia.push_back(moments);
        }
        int moved_by_test = 0;
        double t = 0.0;
        bool finite = true, bounded = true;
        for (int frame = 0; frame < 400; frame++) {
            const double r = rnd(0, 1);
            const double dt = r < 0.05 ? 0.0 : (r < 0.08 ? rnd(0.1, 0.4) : rnd(1.0 / 200.0, 1.0 / 25.0));
            t += dt;
            sim.SyncFromHost(paddle, platform_pose(1.5 * std::sin(2.0 * t), 0.5, 3.0 * t));
            for (size_t i = 0; i < bodies.size(); i++) {
                if (rnd(0, 1) < 0.01) { // gameplay moves this actor
                    actors[i].location = FVector(rnd(-300, 300), rnd(-300, 300), rnd(200, 600));
                    moved_by_test++;
                }
                sim.SyncFromHost(bodies[i], actors[i].pose());
                const double k = rnd(0, 1);
                if (k < 0.2) {
                    sim.AddForce(bodies[i], HearthVec3{(float)rnd(-200, 200), (float)rnd(0, 400), (float)rnd(-200, 200)});
                } else if (k < 0.25) {
                    sim.AddImpulse(bodies[i], HearthVec3{(float)rnd(-2, 2), (float)rnd(0, 4), (float)rnd(-2, 2)}, true);
                } else if (k < 0.3) {
                    sim.AddTorque(bodies[i], HearthVec3{(float)rnd(-20, 20), (float)rnd(-20, 20), (float)rnd(-20, 20)});
                }
            }
            sim.Advance(dt);
            for (size_t i = 0; i < bodies.size(); i++) {
                HearthTransform shown{};
                CHECK(sim.GetRenderPose(bodies[i], shown));
                finite = finite && finite3(shown.position);
                actors[i].show(shown);
                const HearthVec3 v = velocity(sim, bodies[i]);
                bounded = bounded && finite3(v) && std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z) < 100.0;
            }
        }
        CHECK(finite);
        CHECK(bounded);
        CHECK(sim.GetTeleportCount() == moved_by_test);
        // Quiet: no more input, the paddle still; 2 s to settle, then 6 s in 1/60 s frames.
        // Mechanical energy: translation, rotation (ω in the body frame against the principal
        // moments) and potential m g y (the shapes are centred on their bodies' origins, so
        // the origin is the centre of mass).
        const auto energy = [&]() {
            double e = 0.0;
            for (size_t i = 0; i < bodies.size(); i++) {
                const HearthVec3 v = velocity(sim, bodies[i]);
                const HearthTransform pose = stepped(sim, bodies[i]);
                const HearthQuat q = pose.rotation, inverse{-q.x, -q.y, -q.z, q.w};
                const HearthVec3 w = HC::Rotate(inverse, spin(sim, bodies[i]));
                const HearthVec3 I = inertia[i];
                e += 0.5 * masses[i] * (v.x * v.x + v.y * v.y + v.z * v.z);
                e += 0.5 * (I.x * w.x * w.x + I.y * w.y * w.y + I.z * w.z * w.z);
                e += masses[i] * 9.81 * pose.position.y;
            }
            return e;
        };
        for (int frame = 0; frame < 120; frame++) { // spins and overlaps from the input play out
            sim.Advance(H);
        }
        CHECK(near3(velocity(sim, paddle), ZERO_G, 1e-5) && near3(spin(sim, paddle), ZERO_G, 1e-5)); // stopped
        const double e0 = energy();
        double peak = e0;
        for (int frame = 0; frame < 360; frame++) {
            sim.Advance(H);
            peak = std::fmax(peak, energy());
        }
        // Nothing drives the bodies now: their energy only falls (1 J of slack for rounding
        // and the rotational energy left out, compared with totals of 10^3 to 10^4 J).
        if (peak > e0 + 1.0) {
            std::printf("seed %d: energy rose from %.3f J to %.3f J\n", seed, e0, peak);
        }
        CHECK(peak <= e0 + 1.0);
        bool above = true;
        for (const HearthBodyId id : bodies) {
            above = above && stepped(sim, id).position.y > -0.05f;
        }
        CHECK(above);
        CHECK(sim.GetReportedErrorCount() == 0);
    }
}

// ---- gravity and errors

/** A level streamed in body by body: once 256 bodies were added, the next Advance rebuilds the
 * broad-phase tree (once), and a ray hits what it hit before; fewer bodies do not rebuild. */
static void test_broadphase_rebuilt_after_a_level_load() {
    Core::FSimulation sim;
    CHECK(sim.Create(world_def(EARTH_G)));
    add_ground(sim);
    for (int i = 0; i < 299; i++) {
        add_box(sim, at((i % 10) * 1.0, 0.25 + (i / 100) * 0.5, (i / 10 % 10) * 1.0), HearthVec3{0.25f, 0.25f, 0.25f}, 1.0, true);
    }
    const HearthQueryFilter all = hearth_query_filter_default();
    HearthRayHit before{}, after{};
    CHECK(hearth_world_cast_ray_closest(sim.GetWorld(), HearthVec3{4.1f, 10, 4.2f}, HearthVec3{0, -20, 0}, &all, &before) == HEARTH_OK);
    HearthWorldCounters c0{}, c1{};
    CHECK(hearth_world_get_counters(sim.GetWorld(), &c0) == HEARTH_OK);
    CHECK(sim.Advance(0.0) == 0 && sim.GetBroadphaseRebuildCount() == 0); // no step, no rebuild
    CHECK(sim.Advance(H) == 1);
    CHECK(sim.GetBroadphaseRebuildCount() == 1);
    CHECK(hearth_world_get_counters(sim.GetWorld(), &c1) == HEARTH_OK);
    CHECK(c1.tree_height <= c0.tree_height);
    CHECK(hearth_world_cast_ray_closest(sim.GetWorld(), HearthVec3{4.1f, 10, 4.2f}, HearthVec3{0, -20, 0}, &all, &after) == HEARTH_OK);
    CHECK(before.shape.index != 0 && before.shape.index == after.shape.index);
    add_box(sim, at(20, 1, 0), HearthVec3{0.25f, 0.25f, 0.25f}, 1.0);
    sim.Advance(H);
    CHECK(sim.GetBroadphaseRebuildCount() == 1 && sim.GetReportedErrorCount() == 0);
    // Switched off.
    Core::FSimulation off;
    Core::FSimulationSettings settings;
    settings.RebuildBroadphaseAfterBodies = 0;
    CHECK(off.Create(world_def(EARTH_G), settings));
    for (int i = 0; i < 300; i++) {
        add_box(off, at(i * 1.0, 1, 0), HearthVec3{0.25f, 0.25f, 0.25f}, 1.0);
    }
    off.Advance(H);
    CHECK(off.GetBroadphaseRebuildCount() == 0);
}

static void test_gravity_followed() {
    Core::FSimulation sim;
    CHECK(sim.Create(world_def(EARTH_G)));
    const HearthBodyId b = add_box(sim, at(0, 100, 0), HearthVec3{0.1f, 0.1f, 0.1f}, 1.0);
    for (int i = 0; i < 30; i++) {
        CHECK(sim.SetGravity(HC::ToHearthVector(FVector(0, 0, -981)))); // unchanged: no call
        sim.Advance(H);
    }
    CHECK_NEAR(velocity(sim, b).y, -9.81 * 0.5, 1e-4);
    // The level's gravity changes to the Moon's (-162 cm/s²) mid-flight.
    for (int i = 0; i < 30; i++) {
        CHECK(sim.SetGravity(HC::ToHearthVector(FVector(0, 0, -162))));
        sim.Advance(H);
    }
    CHECK_NEAR(velocity(sim, b).y, -9.81 * 0.5 - 1.62 * 0.5, 1e-4);
    HearthVec3 g{0, 0, 0};
    CHECK(hearth_world_get_gravity(sim.GetWorld(), &g) == HEARTH_OK);
    CHECK_NEAR(g.y, -1.62, 1e-6);
    CHECK(!sim.SetGravity(HearthVec3{0, NAN, 0})); // refused by Hearth, reported
    CHECK(sim.GetReportedErrorCount() == 1);
    CHECK_NEAR(sim.GetGravity().y, -1.62, 1e-6);
}

static void test_version_compatibility() {
    const auto v = [](uint32_t major, uint32_t minor, uint32_t patch) { return (major << 16) | (minor << 8) | patch; };
    CHECK(Core::IsCompatibleVersion(hearth_version(), HEARTH_VERSION)); // this build
    // 0.x: the minor is the ABI.
    CHECK(Core::IsCompatibleVersion(v(0, 1, 0), v(0, 1, 0)));
    CHECK(Core::IsCompatibleVersion(v(0, 1, 7), v(0, 1, 2)));
    CHECK(Core::IsCompatibleVersion(v(0, 1, 2), v(0, 1, 7)));
    CHECK(!Core::IsCompatibleVersion(v(0, 2, 0), v(0, 1, 0)));
    CHECK(!Core::IsCompatibleVersion(v(0, 0, 9), v(0, 1, 0)));
    CHECK(!Core::IsCompatibleVersion(v(1, 1, 0), v(0, 1, 0)));
    // From 1.0: the major, and a library at least as new as the header's minor.
    CHECK(Core::IsCompatibleVersion(v(1, 3, 0), v(1, 2, 5)));
    CHECK(!Core::IsCompatibleVersion(v(1, 1, 9), v(1, 2, 0)));
    CHECK(!Core::IsCompatibleVersion(v(2, 0, 0), v(1, 0, 0)));
}

static void test_errors_are_throttled() {
    Core::FErrorThrottle throttle(5.0);
    int held = -1;
    CHECK(throttle.Admit("a", 0.0, held) && held == 0);
    CHECK(!throttle.Admit("a", 1.0, held));
    CHECK(!throttle.Admit("a", 4.9, held));
    CHECK(throttle.Admit("b", 4.9, held) && held == 0); // another key is not held back
    CHECK(throttle.Admit("a", 5.0, held) && held == 2);
    CHECK(!throttle.Admit("a", 9.9, held));
    CHECK(throttle.Admit("a", 10.0, held) && held == 1);
    CHECK(throttle.GetHeldBackTotal() == 3);

    // The same call failing every frame for 20 s at 60 Hz (a host pushing a broken gravity):
    // 1200 failures give one message at once and one every 5 s after, with the count.
    Core::FSimulation sim;
    ErrorLog log;
    sim.SetErrorCallback(&ErrorLog::Receive, &log);
    CHECK(sim.Create(world_def(ZERO_G)));
    const HearthBodyId b = add_box(sim, at(0, 0, 0), HearthVec3{0.1f, 0.1f, 0.1f}, 1.0);
    for (int frame = 0; frame < 1200; frame++) {
        CHECK(!sim.SetGravity(HearthVec3{0, INFINITY, 0}));
        sim.Advance(H);
    }
    for (const std::string &m : log.messages) {
        std::printf("  logged: %s\n", m.c_str());
    }
    CHECK(log.messages.size() == 4 || log.messages.size() == 5);
    CHECK(!log.messages.empty() &&
          log.messages[0].find("hearth_world_set_gravity failed: HEARTH_ERROR_INVALID_ARGUMENT") == 0);
    CHECK(log.messages.size() > 1 && (log.messages[1].find("(and 299 more like it in the last 5 s)") != std::string::npos ||
                                      log.messages[1].find("(and 300 more like it in the last 5 s)") != std::string::npos));
    CHECK((size_t)sim.GetReportedErrorCount() == log.messages.size());
    CHECK(sim.GetReportedErrorCount() + sim.GetHeldBackErrorCount() == 1200);
    // A body destroyed behind the simulation's back is reported once and dropped; the others
    // keep moving.
    log.messages.clear();
    const HearthBodyId c = add_box(sim, at(1, 0, 0), HearthVec3{0.1f, 0.1f, 0.1f}, 1.0);
    CHECK(sim.SetLinearVelocity(c, HearthVec3{1, 0, 0}));
    CHECK(hearth_body_destroy(sim.GetWorld(), b) == HEARTH_OK);
    for (int frame = 0; frame < 60; frame++) {
        sim.Advance(H);
    }
    CHECK(!sim.HasBody(b) && sim.HasBody(c));
    CHECK(log.messages.size() == 1 && log.messages[0].find("was destroyed outside FSimulation::RemoveBody") != std::string::npos);
    CHECK_NEAR(stepped(sim, c).position.x, 2.0, 1e-4);
    // A world that failed to be created is reported and steps nothing.
    Core::FSimulation broken;
    broken.SetErrorCallback(&ErrorLog::Receive, &log);
    HearthWorldDef bad = hearth_world_def_default();
    bad.gravity.x = NAN;
    CHECK(!broken.Create(bad));
    CHECK(!broken.IsRunning() && broken.Advance(1.0) == 0);
    CHECK(log.messages.back().find("hearth_world_create failed: HEARTH_ERROR_INVALID_ARGUMENT") == 0);
    // A fixed step outside Hearth's time-step range would fail every step: refused at once.
    for (double step : {0.0, 0.0005, 0.2, -1.0 / 60.0, (double)NAN}) {
        Core::FSimulationSettings settings;
        settings.StepSeconds = step;
        Core::FSimulation odd;
        odd.SetErrorCallback(&ErrorLog::Receive, &log);
        CHECK(!odd.Create(hearth_world_def_default(), settings));
        CHECK(!odd.IsRunning() && odd.Advance(1.0) == 0);
        CHECK(log.messages.back().find("StepSeconds must be within 0.001 to 0.1 s") != std::string::npos);
    }
    Core::FSimulationSettings slow;
    slow.StepSeconds = 0.1; // both ends of the range are accepted
    Core::FSimulation ok;
    CHECK(ok.Create(hearth_world_def_default(), slow) && ok.Advance(0.1) == 1);
}

// ---- shapes from simple-collision elements

/** The corners of an Unreal box element (world = component, cm) in Hearth coordinates. */
static HearthVec3 unreal_box_corner(const FVector &c, const FQuat &q, const FVector &half, int sx, int sy, int sz) {
    return HC::ToHearthVector(c + q.RotateVector(FVector(sx * half.X, sy * half.Y, sz * half.Z)));
}
static HearthVec3 hearth_box_corner(const HearthBox &b, int sx, int sy, int sz) {
    // Unreal's local (X, Y, Z) signs are Hearth's local (x, z, y).
    const HearthVec3 local{(float)sx * b.half_extents.x, (float)sz * b.half_extents.y, (float)sy * b.half_extents.z};
    const HearthVec3 r = HC::Rotate(b.rotation, local);
    return HearthVec3{r.x + b.center.x, r.y + b.center.y, r.z + b.center.z};
}

static void test_shapes_from_elements() {
    const FVector one(1, 1, 1);
    const FQuat none(0, 0, 0, 1);
    // Sphere: the centre scales componentwise, the radius by the smallest |scale|.
    HearthSphere s{};
    CHECK(HearthShapes::MakeSphere(FVector(10, 20, 30), 50.0, FVector(2, 3, -4), s));
    CHECK(near3(s.center, HC::ToHearthVector(FVector(20, 60, -120)), 1e-6));
    CHECK_NEAR(s.radius, 1.0, 1e-6);
    CHECK(!HearthShapes::MakeSphere(FVector(0, 0, 0), 0.0, one, s));
    CHECK(!HearthShapes::MakeSphere(FVector(0, 0, 0), 10.0, FVector(1, 0, 1), s));
    CHECK(!HearthShapes::MakeSphere(FVector(NAN, 0, 0), 10.0, one, s));
    // Box: edges X = 200, Y = 100, Z = 50 cm are half extents (1, 0.25, 0.5) m in Hearth's
    // (x, y, z) = Unreal's (X, Z, Y).
    HearthBox b{};
    CHECK(HearthShapes::MakeBox(FVector(0, 0, 0), none, 200, 100, 50, one, b));
    CHECK(near3(b.half_extents, HearthVec3{1.0f, 0.25f, 0.5f}, 1e-7));
    CHECK(!HearthShapes::MakeBox(FVector(0, 0, 0), none, 200, -1, 50, one, b));
    // Rotated, scaled, off-centre boxes: every corner where Unreal puts it.
    g_seed = 0xB0ABull;
    bool corners = true;
    for (int i = 0; i < 300; i++) {
        const FVector c = rnd_vec(300.0), scale(rnd(0.2, 3), rnd(0.2, 3), rnd(0.2, 3));
        const FQuat q = rnd_quat();
        const double ex = rnd(1, 400), ey = rnd(1, 400), ez = rnd(1, 400);
        CHECK(HearthShapes::MakeBox(c, q, ex, ey, ez, scale, b));
        const FVector sc(c.X * scale.X, c.Y * scale.Y, c.Z * scale.Z);
        const FVector half(0.5 * ex * scale.X, 0.5 * ey * scale.Y, 0.5 * ez * scale.Z);
        for (int k = 0; k < 8; k++) {
            const int sx = (k & 1) ? 1 : -1, sy = (k & 2) ? 1 : -1, sz = (k & 4) ? 1 : -1;
            corners = corners && near3(hearth_box_corner(b, sx, sy, sz), unreal_box_corner(sc, q, half, sx, sy, sz), 2e-5);
        }
    }
    CHECK(corners);
    // Capsule along local Z: centre (0, 0, 100) cm, radius 30, length 100 -> segment from
    // y = 0.5 to 1.5 m, radius 0.3 m.
    HearthCapsule cap{};
    CHECK(HearthShapes::MakeCapsule(FVector(0, 0, 100), none, 30, 100, one, cap));
    CHECK(near3(cap.a, HearthVec3{0, 0.5f, 0}, 1e-6) && near3(cap.b, HearthVec3{0, 1.5f, 0}, 1e-6));
    CHECK_NEAR(cap.radius, 0.3, 1e-7);
    // Lying along Unreal's Y (right, Hearth z) after a 90° roll about X.
    CHECK(HearthShapes::MakeCapsule(FVector(0, 0, 0), FQuat(FVector(1, 0, 0), -0.5 * M_PI), 30, 100, one, cap));
    CHECK(near3(cap.b, HC::ToHearthVector(FVector(0, 50, 0)), 1e-6) || near3(cap.a, HC::ToHearthVector(FVector(0, 50, 0)), 1e-6));
    // Scale: radius by max(|X|, |Y|), total length by |Z|; squashed below its diameter it
    // is a ball (zero segment, radius the half length).
    CHECK(HearthShapes::MakeCapsule(FVector(0, 0, 0), none, 30, 100, FVector(2, 1, 1), cap));
    CHECK_NEAR(cap.radius, 0.6, 1e-7);
    CHECK_NEAR(cap.b.y - cap.a.y, 2.0 * (0.8 - 0.6), 1e-6);
    CHECK(HearthShapes::MakeCapsule(FVector(0, 0, 0), none, 30, 100, FVector(2, 2, 0.5), cap));
    CHECK_NEAR(cap.radius, 0.4, 1e-7);
    CHECK(near3(cap.a, cap.b, 0.0));
    CHECK(!HearthShapes::MakeCapsule(FVector(0, 0, 0), none, 0, 100, one, cap));
    CHECK(!HearthShapes::MakeCapsule(FVector(0, 0, 0), none, 10, -1, one, cap));
    // Randomized capsules: both end points at ±(L/2)·scale along the rotated axis.
    bool ends = true;
    for (int i = 0; i < 200; i++) {
        const FVector c = rnd_vec(200.0);
        const FQuat q = rnd_quat();
        const double r = rnd(1, 50), len = rnd(0, 200);
        CHECK(HearthShapes::MakeCapsule(c, q, r, len, one, cap));
        const HearthVec3 tip = HC::ToHearthVector(c + q.RotateVector(FVector(0, 0, 0.5 * len)));
        const HearthVec3 tail = HC::ToHearthVector(c + q.RotateVector(FVector(0, 0, -0.5 * len)));
        ends = ends && near3(cap.b, tip, 1e-5) && near3(cap.a, tail, 1e-5);
    }
    CHECK(ends);

    // In a real world: masses from Unreal densities (g/cm³) and the element volumes.
    Core::FSimulation sim;
    CHECK(sim.Create(world_def(ZERO_G)));
    HearthShapeDef water = hearth_shape_def_default();
    water.density = HC::ToHearthDensity(1.0); // 1 g/cm³
    HearthBodyDef bd = hearth_body_def_default();
    bd.type = HEARTH_BODY_DYNAMIC;
    const HearthBodyId cube = sim.AddBody(bd);
    CHECK(HearthShapes::MakeBox(FVector(0, 0, 0), none, 100, 100, 100, one, b) && sim.AddBox(cube, water, b));
    float m = 0;
    CHECK(sim.GetMass(cube, m));
    CHECK_NEAR(m, 1000.0, 0.01); // 1 m³ of water
    const HearthBodyId pill = sim.AddBody(bd);
    CHECK(HearthShapes::MakeCapsule(FVector(0, 0, 0), rnd_quat(), 20, 60, one, cap) && sim.AddCapsule(pill, water, cap));
    CHECK(sim.GetMass(pill, m));
    CHECK_NEAR(m, 1000.0 * (M_PI * 0.04 * 0.6 + 4.0 / 3.0 * M_PI * 0.008), 0.05);
    // Compound: two spheres of one body add up.
    const HearthBodyId pair = sim.AddBody(bd);
    CHECK(HearthShapes::MakeSphere(FVector(-100, 0, 0), 25, one, s) && sim.AddSphere(pair, water, s));
    CHECK(HearthShapes::MakeSphere(FVector(100, 0, 0), 25, one, s) && sim.AddSphere(pair, water, s));
    CHECK(sim.GetMass(pair, m));
    CHECK_NEAR(m, 2.0 * 1000.0 * 4.0 / 3.0 * M_PI * 0.25 * 0.25 * 0.25, 0.05);
}

// ---- shared geometry: hulls, meshes, heightfields

/** Settings that report every error (no throttling), to count them. */
static Core::FSimulationSettings every_error() {
    Core::FSimulationSettings s;
    s.ErrorIntervalSeconds = 0.0;
    return s;
}

/** The eight corners of an axis-aligned box of half extents (cm) about c (Unreal). */
static std::vector<FVector> corners_cm(FVector c, double hx, double hy, double hz) {
    std::vector<FVector> v;
    for (int i = 0; i < 8; i++) {
        v.push_back(FVector(c.X + ((i & 1) ? hx : -hx), c.Y + ((i & 2) ? hy : -hy), c.Z + ((i & 4) ? hz : -hz)));
    }
    return v;
}

static HearthBodyId add_static(Core::FSimulation &sim, HearthTransform pose = at(0, 0, 0)) {
    HearthBodyDef bd = hearth_body_def_default();
    bd.transform = pose;
    return sim.AddBody(bd);
}
static HearthBodyId add_dynamic(Core::FSimulation &sim, HearthTransform pose) {
    HearthBodyDef bd = hearth_body_def_default();
    bd.type = HEARTH_BODY_DYNAMIC;
    bd.transform = pose;
    return sim.AddBody(bd);
}
static void run(Core::FSimulation &sim, double seconds) {
    for (int i = 0; i < (int)std::lround(seconds / H); i++) {
        sim.Advance(H);
    }
}
static uint32_t hull_vertices(Core::FSimulation &sim, const void *asset, int32_t element, HearthResult &result) {
    uint32_t index = 0, generation = 0, count = 0;
    if (!sim.GetGeometryId(asset, element, Core::FSimulation::EGeometry::Hull, index, generation)) {
        result = HEARTH_ERROR_INVALID_ID;
        return 0;
    }
    result = hearth_hull_get_vertex_count(sim.GetWorld(), HearthHullId{index, generation}, &count);
    return count;
}

static void test_convex_elements_become_hulls() {
    const FVector one(1, 1, 1);
    const std::vector<FVector> cube = corners_cm(FVector(0, 0, 0), 50, 50, 50); // 1 m cube
    HearthShapeDef water = hearth_shape_def_default();
    water.density = HC::ToHearthDensity(1.0); // 1000 kg/m³

    // Points: Unreal cm, component space, scale baked only when not uniform.
    HearthShapes::FGeometryScale g;
    CHECK(HearthShapes::ConvexScale(FVector(2, 2, 2), g) && g.Scale.x == 2.0f && g.BakeX == 1.0 && g.BakeZ == 1.0);
    CHECK(HearthShapes::ConvexScale(FVector(-2, 2, 2), g) && g.Scale.x == 2.0f && g.BakeX == -1.0);
    CHECK(HearthShapes::ConvexScale(FVector(1, 2, 3), g) && g.Scale.x == 1.0f && g.BakeY == 2.0 && g.BakeZ == 3.0);
    CHECK(!HearthShapes::ConvexScale(FVector(1, 0, 1), g) && !HearthShapes::ConvexScale(FVector(1, NAN, 1), g));
    std::vector<HearthVec3> pts;
    CHECK(HearthShapes::ConvexScale(FVector(1, 2, 3), g));
    const FVector p(10, 20, 30);
    HearthShapes::ConvertPoints(&p, 1, g, pts);
    CHECK(pts.size() == 1 && std::fabs(pts[0].x - 0.1f) < 1e-7f && std::fabs(pts[0].y - 0.9f) < 1e-6f &&
          std::fabs(pts[0].z - 0.4f) < 1e-7f); // (X, Z, Y) · scale / 100

    Core::FSimulation sim;
    ErrorLog log;
    sim.SetErrorCallback(&ErrorLog::Receive, &log);
    CHECK(sim.Create(world_def(EARTH_G), every_error()));
    int asset_a = 0, asset_b = 0; // stand-ins for two UStaticMesh assets
    // Mass: 1 m³ at 1000 kg/m³, uniform scale 2 (8000 kg), non-uniform (2, 1, 1) baked (2000 kg).
    const struct {
        FVector scale;
        double mass;
    } cases[] = {{one, 1000.0}, {FVector(2, 2, 2), 8000.0}, {FVector(2, 1, 1), 2000.0}, {FVector(-1, 1, 1), 1000.0}};
    for (const auto &c : cases) {
        const HearthBodyId b = add_dynamic(sim, at(0, 50, 0));
        CHECK(sim.AddHull(b, water, &asset_a, 0, cube.data(), cube.size(), c.scale));
        float m = 0;
        CHECK(sim.GetMass(b, m));
        CHECK(std::fabs(m - c.mass) <= 1e-3 * c.mass);
    }
    // (1,1,1) and (2,2,2) share the unbaked hull; (2,1,1) and (-1,1,1) bake their own.
    CHECK(sim.GetGeometryCount() == 3);
    CHECK(sim.GetGeometryUsers(&asset_a, 0, Core::FSimulation::EGeometry::Hull) == 4);
    CHECK(log.messages.empty());

    // Bad input through the error path, nothing cached: three points, a NaN, a zero scale.
    const HearthBodyId bad = add_dynamic(sim, at(0, 60, 0));
    CHECK(!sim.AddHull(bad, water, &asset_b, 0, cube.data(), 3, one));
    CHECK(log.messages.size() == 1 && log.messages[0].find("hearth_hull_create failed: HEARTH_ERROR_INVALID_ARGUMENT") == 0);
    std::vector<FVector> nan_cube = cube;
    nan_cube[3].Y = NAN;
    CHECK(!sim.AddHull(bad, water, &asset_b, 1, nan_cube.data(), nan_cube.size(), one));
    CHECK(log.messages.size() == 2);
    CHECK(!sim.AddHull(bad, water, &asset_b, 0, cube.data(), cube.size(), FVector(1, 0, 1)));
    CHECK(log.messages.size() == 3 && log.messages[2].find("AddHull: every component of the scale") == 0);
    CHECK(sim.GetGeometryCount() == 3);
    // A shape that fails after its hull was built releases it: a bad shape def.
    HearthShapeDef broken = water;
    broken.density = -1.0f;
    CHECK(!sim.AddHull(bad, broken, &asset_b, 0, cube.data(), cube.size(), one));
    CHECK(log.messages.size() == 4 && log.messages[3].find("hearth_shape_create_hull failed") == 0);
    CHECK(sim.GetGeometryCount() == 3);
    sim.Destroy();
    CHECK(sim.GetGeometryCount() == 0);
    log.messages.clear();

    // Rest: a converted 1 m cube falls onto the ground and rests at 0.5 m (± 5 mm).
    CHECK(sim.Create(world_def(EARTH_G), every_error()));
    add_ground(sim);
    const HearthBodyId die = add_dynamic(sim, at(0, 1.2, 0));
    CHECK(sim.AddHull(die, water, &asset_a, 0, cube.data(), cube.size(), one));
    run(sim, 3.0);
    CHECK_NEAR(stepped(sim, die).position.y, 0.5, 0.005);
    CHECK(log.messages.empty());
}

static void test_cache_shares_and_releases() {
    const FVector one(1, 1, 1);
    const std::vector<FVector> cube = corners_cm(FVector(0, 0, 0), 50, 50, 50);
    const std::vector<FVector> wedge = {FVector(0, 0, 0), FVector(100, 0, 0), FVector(0, 100, 0), FVector(0, 0, 100)};
    Core::FSimulation sim;
    ErrorLog log;
    sim.SetErrorCallback(&ErrorLog::Receive, &log);
    CHECK(sim.Create(world_def(ZERO_G), every_error()));
    const HearthShapeDef sd = hearth_shape_def_default();
    int mesh_asset = 0;
    // Two components of one static mesh with two convex elements: two hulls, two users each.
    const HearthBodyId a = add_dynamic(sim, at(0, 0, 0));
    const HearthBodyId b = add_dynamic(sim, at(5, 0, 0));
    for (HearthBodyId body : {a, b}) {
        CHECK(sim.AddHull(body, sd, &mesh_asset, 0, cube.data(), cube.size(), one));
        CHECK(sim.AddHull(body, sd, &mesh_asset, 1, wedge.data(), wedge.size(), one));
    }
    CHECK(sim.GetGeometryCount() == 2);
    uint32_t ia = 0, ga = 0;
    CHECK(sim.GetGeometryId(&mesh_asset, 0, Core::FSimulation::EGeometry::Hull, ia, ga));
    CHECK(sim.GetGeometryUsers(&mesh_asset, 0, Core::FSimulation::EGeometry::Hull) == 2);
    HearthResult r = HEARTH_OK;
    CHECK(hull_vertices(sim, &mesh_asset, 0, r) == 8 && r == HEARTH_OK);
    CHECK(hull_vertices(sim, &mesh_asset, 1, r) == 4 && r == HEARTH_OK);
    // Hearth refuses to destroy a hull in use: the cache must not try before the last user goes.
    CHECK(hearth_hull_destroy(sim.GetWorld(), HearthHullId{ia, ga}) == HEARTH_ERROR_INVALID_ARGUMENT);
    // The first component goes: the hulls stay for the second.
    CHECK(sim.RemoveBody(a));
    CHECK(sim.GetGeometryCount() == 2);
    CHECK(sim.GetGeometryUsers(&mesh_asset, 0, Core::FSimulation::EGeometry::Hull) == 1);
    uint32_t count = 0;
    CHECK(hearth_hull_get_vertex_count(sim.GetWorld(), HearthHullId{ia, ga}, &count) == HEARTH_OK && count == 8);
    // The last goes: both hulls are destroyed in Hearth too.
    CHECK(sim.RemoveBody(b));
    CHECK(sim.GetGeometryCount() == 0);
    CHECK(hearth_hull_get_vertex_count(sim.GetWorld(), HearthHullId{ia, ga}, &count) == HEARTH_ERROR_INVALID_ID);
    // A body destroyed behind the simulation's back releases its uses when it is dropped.
    const HearthBodyId c = add_dynamic(sim, at(0, 0, 0));
    CHECK(sim.AddHull(c, sd, &mesh_asset, 0, cube.data(), cube.size(), one));
    CHECK(hearth_body_destroy(sim.GetWorld(), c) == HEARTH_OK);
    CHECK(sim.Advance(H) == 1);
    CHECK(!sim.HasBody(c) && sim.GetGeometryCount() == 0);
    // Geometry used by a shape made outside the cache: the cache's release is refused by
    // Hearth, reported, and the entry kept (retried later) rather than leaking a stale id.
    const HearthBodyId d = add_dynamic(sim, at(0, 0, 0));
    CHECK(sim.AddHull(d, sd, &mesh_asset, 0, cube.data(), cube.size(), one));
    CHECK(sim.GetGeometryId(&mesh_asset, 0, Core::FSimulation::EGeometry::Hull, ia, ga));
    const HearthBodyId outside = add_dynamic(sim, at(3, 0, 0));
    const HearthHullShape foreign{HearthHullId{ia, ga}, at(0, 0, 0), 1.0f};
    HearthShapeId foreign_shape{0, 0};
    CHECK(hearth_shape_create_hull(sim.GetWorld(), outside, &sd, &foreign, &foreign_shape) == HEARTH_OK);
    const size_t before = log.messages.size();
    CHECK(sim.RemoveBody(d));
    CHECK(log.messages.size() == before + 1 && log.messages.back().find("hearth_hull_destroy failed") == 0);
    CHECK(sim.GetGeometryCount() == 1);
    CHECK(hearth_shape_destroy(sim.GetWorld(), foreign_shape) == HEARTH_OK);
    const HearthBodyId e = add_dynamic(sim, at(0, 0, 0));
    CHECK(sim.AddHull(e, sd, &mesh_asset, 0, cube.data(), cube.size(), one)); // reuses the kept hull
    CHECK(sim.GetGeometryCount() == 1);
    CHECK(sim.RemoveBody(e) && sim.GetGeometryCount() == 0);
}

/** A floor quad at height z (cm), ±half (cm), wound as Unreal winds a face seen from +Z:
 * front normal (C − A) × (B − A) up. */
static void floor_quad(double z, double half, std::vector<FVector> &v, std::vector<uint32_t> &idx, bool face_up) {
    v = {FVector(-half, -half, z), FVector(half, -half, z), FVector(half, half, z), FVector(-half, half, z)};
    idx = face_up ? std::vector<uint32_t>{0, 2, 1, 0, 3, 2} : std::vector<uint32_t>{0, 1, 2, 0, 2, 3};
}

static void test_complex_collision_becomes_a_mesh() {
    // Unreal's front: (C − A) × (B − A) points up for the face-up quad.
    std::vector<FVector> v;
    std::vector<uint32_t> idx;
    floor_quad(20, 200, v, idx, true);
    for (size_t t = 0; t < idx.size(); t += 3) {
        const FVector n = FVector::CrossProduct(v[idx[t + 2]] - v[idx[t]], v[idx[t + 1]] - v[idx[t]]);
        CHECK(n.Z > 0);
    }
    // After conversion, Hearth's front (B − A) × (C − A) points up (+y), as it must.
    HearthShapes::FGeometryScale g;
    std::vector<HearthVec3> pts;
    std::vector<uint32_t> hidx;
    const FVector mirrors[] = {FVector(1, 1, 1), FVector(-1, 1, 1), FVector(-1, -1, 1), FVector(2, -3, 0.5)};
    for (const FVector &m : mirrors) {
        CHECK(HearthShapes::MeshScale(m, g));
        HearthShapes::ConvertPoints(v.data(), v.size(), g, pts);
        HearthShapes::ConvertIndices(idx.data(), idx.size(), g, hidx);
        for (size_t t = 0; t < hidx.size(); t += 3) {
            const HearthVec3 &A = pts[hidx[t]], &B = pts[hidx[t + 1]], &C = pts[hidx[t + 2]];
            const HearthVec3 n = HC::Cross(HearthVec3{B.x - A.x, B.y - A.y, B.z - A.z},
                                           HearthVec3{C.x - A.x, C.y - A.y, C.z - A.z});
            CHECK(n.y > 0); // still facing up, mirrored or not
        }
    }
    CHECK(HearthShapes::MeshScale(FVector(2, -3, 0.5), g) && g.Scale.x == 2.0f && g.Scale.y == 0.5f &&
          g.Scale.z == 3.0f);

    // Physics: a 0.4 m box dropped on each converted floor. The floor's height is 20 cm times
    // the Z scale, on a static body at the origin; the box rests with its centre 0.2 m above.
    const struct {
        FVector scale;
        bool face_up;
        double floor; // m, or NAN when the box must fall through (floor facing down)
    } cases[] = {{FVector(1, 1, 1), true, 0.2},   {FVector(1, 1, 2), true, 0.4},  {FVector(-1, 1, 1), true, 0.2},
                 {FVector(1, -2, 0.5), true, 0.1}, {FVector(1, 1, 1), false, NAN}};
    for (const auto &c : cases) {
        Core::FSimulation sim;
        ErrorLog log;
        sim.SetErrorCallback(&ErrorLog::Receive, &log);
        CHECK(sim.Create(world_def(EARTH_G), every_error()));
        floor_quad(20, 200, v, idx, c.face_up);
        int asset = 0;
        const HearthBodyId ground = add_static(sim);
        CHECK(sim.AddMesh(ground, hearth_shape_def_default(), &asset, v.data(), v.size(), idx.data(), idx.size(),
                          c.scale));
        const HearthBodyId box = add_box(sim, at(0.3, 1.2, -0.4), HearthVec3{0.2f, 0.2f, 0.2f}, 10.0, true);
        run(sim, 3.0);
        const double y = stepped(sim, box).position.y;
        if (std::isnan(c.floor)) {
            CHECK(y < -1.0); // a floor facing down does not hold it: this is what a winding error does
        } else {
            CHECK_NEAR(y, c.floor + 0.2, 0.005);
        }
        CHECK(log.messages.empty());
    }

    // Sharing and errors: one mesh for two floors of one asset; refused on a dynamic body
    // (reported, nothing cached); a bad index reported.
    Core::FSimulation sim;
    ErrorLog log;
    sim.SetErrorCallback(&ErrorLog::Receive, &log);
    CHECK(sim.Create(world_def(EARTH_G), every_error()));
    floor_quad(0, 200, v, idx, true);
    int asset = 0, other = 0;
    const HearthBodyId f1 = add_static(sim), f2 = add_static(sim, at(10, 0, 0));
    CHECK(sim.AddMesh(f1, hearth_shape_def_default(), &asset, v.data(), v.size(), idx.data(), idx.size(), FVector(1, 1, 1)));
    CHECK(sim.AddMesh(f2, hearth_shape_def_default(), &asset, v.data(), v.size(), idx.data(), idx.size(), FVector(3, 3, 3)));
    CHECK(sim.GetGeometryCount() == 1 && sim.GetGeometryUsers(&asset, -1, Core::FSimulation::EGeometry::Mesh) == 2);
    const HearthBodyId dyn = add_dynamic(sim, at(0, 5, 0));
    CHECK(!sim.AddMesh(dyn, hearth_shape_def_default(), &other, v.data(), v.size(), idx.data(), idx.size(), FVector(1, 1, 1)));
    CHECK(log.messages.size() == 1 && log.messages[0].find("hearth_shape_create_mesh failed: HEARTH_ERROR_INVALID_ARGUMENT") == 0);
    CHECK(sim.GetGeometryCount() == 1);
    idx[4] = 9;
    CHECK(!sim.AddMesh(f1, hearth_shape_def_default(), &other, v.data(), v.size(), idx.data(), idx.size(), FVector(1, 1, 1)));
    CHECK(log.messages.size() == 2 && log.messages[1].find("hearth_mesh_create failed") == 0);
    CHECK(sim.GetGeometryCount() == 1);
    CHECK(sim.RemoveBody(f1) && sim.GetGeometryCount() == 1);
    CHECK(sim.RemoveBody(f2) && sim.GetGeometryCount() == 0);
}

static void test_landscape_becomes_a_heightfield() {
    // A plane landscape h = 0.1·X + 0.05·Y (cm), 9 × 7 samples 100 cm apart, scaled (1, 1, 1):
    // Hearth's plane y = 0.1·x + 0.05·z. A box dropped at (3, ·, 2) m rests with its centre
    // one half extent from the plane along its normal.
    const uint32_t sx = 9, sy = 7;
    std::vector<float> h(sx * sy);
    for (uint32_t y = 0; y < sy; y++) {
        for (uint32_t x = 0; x < sx; x++) {
            h[y * sx + x] = (float)(0.1 * (x * 100.0) + 0.05 * (y * 100.0));
        }
    }
    std::vector<float> out;
    HearthVec3 scale{0, 0, 0};
    CHECK(HearthShapes::MakeHeightfield(sx, sy, h.data(), 100.0, 100.0, FVector(2, 3, 4), out, scale));
    CHECK(scale.x == 2.0f && scale.y == 4.0f && scale.z == 3.0f);
    CHECK(std::fabs(out[2 * sx + 3] - 0.4f) < 1e-6f); // sample (x 3, y 2): 30 + 10 cm
    CHECK(!HearthShapes::MakeHeightfield(1, sy, h.data(), 100.0, 100.0, FVector(1, 1, 1), out, scale));
    CHECK(!HearthShapes::MakeHeightfield(sx, sy, h.data(), 0.0, 100.0, FVector(1, 1, 1), out, scale));
    CHECK(!HearthShapes::MakeHeightfield(sx, sy, h.data(), 100.0, 100.0, FVector(-1, 1, 1), out, scale));
    {
        Core::FSimulation sim;
        ErrorLog log;
        sim.SetErrorCallback(&ErrorLog::Receive, &log);
        CHECK(sim.Create(world_def(EARTH_G), every_error()));
        int landscape = 0;
        const HearthBodyId ground = add_static(sim);
        CHECK(sim.AddHeightfield(ground, hearth_shape_def_default(), &landscape, sx, sy, h.data(), nullptr, 100.0,
                                 100.0, FVector(1, 1, 1)));
        const HearthBodyId box = add_box(sim, at(3.0, 1.5, 2.0), HearthVec3{0.2f, 0.2f, 0.2f}, 10.0, true);
        run(sim, 3.0);
        const HearthVec3 p = stepped(sim, box).position;
        const double n = std::sqrt(1.0 + 0.01 + 0.0025);
        CHECK_NEAR((p.y - 0.1 * p.x - 0.05 * p.z) / n, 0.2, 0.005);
        // With X and Y swapped the plane would be y = 0.05·x + 0.1·z: 0.05 m off here.
        CHECK(std::fabs((p.y - 0.05 * p.x - 0.1 * p.z) / n - 0.2) > 0.02);
        CHECK(log.messages.empty());
    }
    // Flat at 50 cm, 5 × 5 samples 100 cm apart, component scale (2, 1, 2), placed 0.5 m up:
    // 8 m by 4 m at 1.5 m high. A box inside rests at 1.7 m; one past the X edge (x = 9 m) falls off.
    {
        const uint32_t n = 5;
        std::vector<float> flat(n * n, 50.0f);
        Core::FSimulation sim;
        ErrorLog log;
        sim.SetErrorCallback(&ErrorLog::Receive, &log);
        CHECK(sim.Create(world_def(EARTH_G), every_error()));
        int landscape = 0;
        const HearthBodyId ground = add_static(sim);
        // Placed 0.5 m up in the body's frame (Local), as a landscape's collision component
        // sits at its offset in the actor's frame.
        CHECK(sim.AddHeightfield(ground, hearth_shape_def_default(), &landscape, n, n, flat.data(), nullptr, 100.0,
                                 100.0, FVector(2, 1, 2), at(0, 0.5, 0)));
        const HearthBodyId in = add_box(sim, at(7.5, 2.0, 3.5), HearthVec3{0.2f, 0.2f, 0.2f}, 10.0, true);
        const HearthBodyId off = add_box(sim, at(9.0, 2.0, 2.0), HearthVec3{0.2f, 0.2f, 0.2f}, 10.0, true);
        const HearthBodyId off_z = add_box(sim, at(2.0, 2.0, 4.5), HearthVec3{0.2f, 0.2f, 0.2f}, 10.0, true);
        run(sim, 3.0);
        CHECK_NEAR(stepped(sim, in).position.y, 1.7, 0.005);
        CHECK(stepped(sim, off).position.y < -1.0);
        CHECK(stepped(sim, off_z).position.y < -1.0); // Unreal Y spans 4 m: Hearth z past 4 m is off
        // Errors: NaN height (Hearth), a hole flag of 2 (Hearth), a mirrored scale (the core).
        flat[7] = NAN;
        int other = 0;
        CHECK(!sim.AddHeightfield(ground, hearth_shape_def_default(), &other, n, n, flat.data(), nullptr, 100.0, 100.0,
                                  FVector(1, 1, 1)));
        CHECK(log.messages.size() == 1 && log.messages[0].find("hearth_heightfield_create failed") == 0);
        flat[7] = 0.0f;
        std::vector<uint8_t> holes((n - 1) * (n - 1), 0);
        holes[3] = 2;
        CHECK(!sim.AddHeightfield(ground, hearth_shape_def_default(), &other, n, n, flat.data(), holes.data(), 100.0,
                                  100.0, FVector(1, 1, 1)));
        CHECK(log.messages.size() == 2);
        CHECK(!sim.AddHeightfield(ground, hearth_shape_def_default(), &other, n, n, flat.data(), nullptr, 100.0, 100.0,
                                  FVector(1, -1, 1)));
        CHECK(log.messages.size() == 3 && log.messages[2].find("AddHeightfield: a landscape needs") == 0);
        CHECK(sim.GetGeometryCount() == 1);
        CHECK(sim.RemoveBody(ground) && sim.GetGeometryCount() == 0);
    }
}

/** Seeded randomized: random convex elements (8–20 points in a random box), random uniform
 * and non-uniform scales, dropped on a converted bumpy landscape: everything stays finite,
 * slower than free fall from the drop height, and above the lowest ground. */
static void test_random_hulls_on_landscape() {
    const uint32_t n = 17;
    std::vector<float> h(n * n);
    for (uint32_t y = 0; y < n; y++) {
        for (uint32_t x = 0; x < n; x++) {
            h[y * n + x] = (float)(30.0 * std::sin(0.7 * x) * std::cos(0.5 * y)); // ±30 cm
        }
    }
    Core::FSimulation sim;
    ErrorLog log;
    sim.SetErrorCallback(&ErrorLog::Receive, &log);
    CHECK(sim.Create(world_def(EARTH_G), every_error()));
    const HearthBodyId ground = add_static(sim);
    int landscape = 0;
    CHECK(sim.AddHeightfield(ground, hearth_shape_def_default(), &landscape, n, n, h.data(), nullptr, 100.0, 100.0,
                             FVector(1, 1, 1)));
    int assets[4] = {0, 0, 0, 0};
    std::vector<std::vector<FVector>> clouds(4);
    for (auto &cloud : clouds) {
        const double ex = rnd(15, 40), ey = rnd(15, 40), ez = rnd(15, 40);
        const int count = 8 + (int)rnd(0, 12.99);
        for (int i = 0; i < count; i++) {
            cloud.push_back(FVector(rnd(-ex, ex), rnd(-ey, ey), rnd(-ez, ez)));
        }
        for (const FVector &c : corners_cm(FVector(0, 0, 0), ex, ey, ez)) { // never flat
            cloud.push_back(c * 0.9);
        }
    }
    std::vector<HearthBodyId> bodies;
    for (int i = 0; i < 30; i++) {
        const int a = (int)rnd(0, 3.99);
        const double u = rnd(0.5, 1.5);
        const FVector s = (i % 2) ? FVector(u, u, u) : FVector(rnd(0.5, 1.5), rnd(0.5, 1.5), rnd(0.5, 1.5));
        const HearthBodyId b = add_dynamic(sim, HearthTransform{HearthVec3{(float)rnd(3, 13), (float)rnd(1.5, 4),
                                                                           (float)rnd(3, 13)},
                                                                HC::ToHearthQuat(rnd_quat())});
        CHECK(sim.AddHull(b, hearth_shape_def_default(), &assets[a], 0, clouds[a].data(), clouds[a].size(), s));
        bodies.push_back(b);
    }
    CHECK(sim.GetGeometryCount() <= 1 + 4 + 15); // uniform scales share their asset's hull
    bool finite = true, bounded = true, above = true;
    for (int frame = 0; frame < 240; frame++) {
        sim.Advance(H);
        for (HearthBodyId b : bodies) {
            const HearthTransform t = stepped(sim, b);
            const HearthVec3 v = velocity(sim, b);
            finite = finite && finite3(t.position) && finite3(v);
            bounded = bounded && std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z) < std::sqrt(2.0 * 9.81 * 4.5) + 1.0;
            const bool inside = t.position.x > 0.5 && t.position.x < 15.5 && t.position.z > 0.5 && t.position.z < 15.5;
            above = above && (!inside || t.position.y > -0.35);
        }
    }
    CHECK(finite && bounded && above);
    CHECK(log.messages.empty());
    for (HearthBodyId b : bodies) {
        CHECK(sim.RemoveBody(b));
    }
    CHECK(sim.GetGeometryCount() == 1); // only the landscape's heightfield is left
}

int main() {
    test_force_lasts_for_its_frame();
    test_force_at_random_frame_rates();
    test_impulses_act_once();
    test_rendered_motion_is_smooth();
    test_kinematic_platform_carries_a_box();
    test_kinematic_random_paths();
    test_same_pose_threshold();
    test_gameplay_moves_teleport();
    test_random_sessions();
    test_gravity_followed();
    test_broadphase_rebuilt_after_a_level_load();
    test_errors_are_throttled();
    test_version_compatibility();
    test_shapes_from_elements();
    test_convex_elements_become_hulls();
    test_cache_shares_and_releases();
    test_complex_collision_becomes_a_mesh();
    test_landscape_becomes_a_heightfield();
    test_random_hulls_on_landscape();
    std::printf("test_unreal_simulation: %d passed, %d failed\n", g_passed, g_failed);
    return g_failed == 0 ? 0 : 1;
}
