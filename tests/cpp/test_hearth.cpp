// The C++ wrapper (bindings/cpp/hearth.hpp) tested on real behaviour: a box resting on a plane
// at its analytic height, every error kind as an exception with its code and message (and as
// a Result in the nothrow API) leaving the world unchanged, move-only RAII ownership, lambdas
// as force and contact generators (a hovering body, a lambda floor, exceptions and failed
// Statuses reported by step(), boxes released), bulk read-back equal to single reads, joints,
// particles, soft bodies (and their settings read back and changed), built-in generators and
// shared geometry (a box resting on a mesh floor and a hull cube on a heightfield).
//
// Compiled by tests/bindings_cpp.rs with -std=c++17 -Wall -Wextra -Wpedantic -Werror, linked
// shared and static, and once more with -fno-exceptions (only the nothrow half is built then);
// run under valgrind when HEARTH_VALGRIND=1. Prints "N passed, M failed".
#include "hearth.hpp"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <algorithm>
#include <memory>
#include <stdexcept>
#include <string>
#include <thread>
#include <type_traits>
#include <vector>

static std::string g_program; // argv[0]: test files go next to the program

static int g_passed = 0;
static int g_failed = 0;

#define CHECK(cond)                                                                             \
    do {                                                                                        \
        if (cond) {                                                                             \
            g_passed++;                                                                         \
        } else {                                                                                \
            g_failed++;                                                                         \
            std::fprintf(stderr, "%s:%d: CHECK(%s) failed\n", __FILE__, __LINE__, #cond);       \
        }                                                                                       \
    } while (0)

#define CHECK_NEAR(a, b, tol)                                                                   \
    do {                                                                                        \
        const double a_ = (a), b_ = (b);                                                        \
        if (std::fabs(a_ - b_) <= (tol)) {                                                      \
            g_passed++;                                                                         \
        } else {                                                                                \
            g_failed++;                                                                         \
            std::fprintf(stderr, "%s:%d: |%s - %s| = |%g - %g| > %g\n", __FILE__, __LINE__, #a, \
                         #b, a_, b_, (double)(tol));                                            \
        }                                                                                       \
    } while (0)

// A Result that must have succeeded.
#define CHECK_OK(result)                                                                        \
    do {                                                                                        \
        const auto &r_ = (result);                                                              \
        if (r_.ok()) {                                                                          \
            g_passed++;                                                                         \
        } else {                                                                                \
            g_failed++;                                                                         \
            std::fprintf(stderr, "%s:%d: %s failed: %s: %s\n", __FILE__, __LINE__, #result,     \
                         hearth::code_name(r_.code()), r_.message().c_str());                   \
        }                                                                                       \
    } while (0)

// A Result that must have failed with `code` and a message.
#define CHECK_CODE(result, expected)                                                            \
    do {                                                                                        \
        const auto &r_ = (result);                                                              \
        if (r_.code() == (expected) && !r_.message().empty() && !r_.ok()) {                     \
            g_passed++;                                                                         \
        } else {                                                                                \
            g_failed++;                                                                         \
            std::fprintf(stderr, "%s:%d: %s gave %s (\"%s\"), expected %s\n", __FILE__,         \
                         __LINE__, #result, hearth::code_name(r_.code()), r_.message().c_str(), \
                         hearth::code_name(expected));                                          \
        }                                                                                       \
    } while (0)

#if HEARTH_CPP_EXCEPTIONS
// A statement that must throw hearth::Error with `code` and a message naming it.
#define CHECK_THROWS(stmt, expected)                                                            \
    do {                                                                                        \
        bool thrown_ = false;                                                                   \
        try {                                                                                   \
            stmt;                                                                               \
        } catch (const hearth::Error &e_) {                                                     \
            thrown_ = e_.code() == (expected) && !e_.message().empty() &&                       \
                      std::string(e_.what()).find(hearth::code_name(expected)) == 0;            \
            if (!thrown_) {                                                                     \
                std::fprintf(stderr, "%s:%d: threw %s\n", __FILE__, __LINE__, e_.what());       \
            }                                                                                   \
        }                                                                                       \
        if (thrown_) {                                                                          \
            g_passed++;                                                                         \
        } else {                                                                                \
            g_failed++;                                                                         \
            std::fprintf(stderr, "%s:%d: %s did not throw %s\n", __FILE__, __LINE__, #stmt,     \
                         hearth::code_name(expected));                                          \
        }                                                                                       \
    } while (0)
#endif

static const float DT = 1.0f / 60.0f;
static const float NaN = std::nanf("");

static bool same_transform(const hearth::Transform &a, const hearth::Transform &b) {
    return std::memcmp(&a, &b, sizeof a) == 0;
}

// Field by field (the structs have padding, which memcmp would compare too).
static bool same_settings(const hearth::SoftBodySettings &a, const hearth::SoftBodySettings &b) {
    return a.edge_compliance == b.edge_compliance && a.bend_compliance == b.bend_compliance &&
           a.preserve_volume == b.preserve_volume && a.volume_compliance == b.volume_compliance &&
           a.pressure == b.pressure && a.damping == b.damping && a.deformation_damping == b.deformation_damping &&
           a.friction == b.friction && a.restitution == b.restitution && a.vertex_radius == b.vertex_radius &&
           a.gravity_scale == b.gravity_scale && a.substeps == b.substeps && a.iterations == b.iterations &&
           a.collide == b.collide;
}

// The settings part of a def (the like-named fields).
static hearth::SoftBodySettings settings_of(const hearth::SoftBodyDef &d) {
    hearth::SoftBodySettings s{};
    s.edge_compliance = d.edge_compliance;
    s.bend_compliance = d.bend_compliance;
    s.preserve_volume = d.preserve_volume;
    s.volume_compliance = d.volume_compliance;
    s.pressure = d.pressure;
    s.damping = d.damping;
    s.deformation_damping = d.deformation_damping;
    s.friction = d.friction;
    s.restitution = d.restitution;
    s.vertex_radius = d.vertex_radius;
    s.gravity_scale = d.gravity_scale;
    s.substeps = d.substeps;
    s.iterations = d.iterations;
    s.collide = d.collide;
    return s;
}

// ============================================================== the throwing API (default)
#if HEARTH_CPP_EXCEPTIONS

static hearth::World make_world(bool sleep = false) {
    hearth::WorldDef def = hearth::world_def();
    def.enable_sleep = sleep ? 1 : 0;
    return hearth::World(def);
}

static hearth::Body add_ground(hearth::World &w) {
    hearth::Body ground = w.create_body(hearth::BodyType::Static);
    ground.add(hearth::plane(hearth::vec3(0, 1, 0), 0.0f));
    return ground;
}

static hearth::Body add_ball(hearth::World &w, hearth::Vec3 p, float radius = 0.25f) {
    hearth::Body b = w.create_body(hearth::BodyType::Dynamic, p);
    b.add(hearth::sphere(radius));
    return b;
}

static void test_box_rests_on_plane() {
    hearth::World w = make_world(true);
    add_ground(w);
    hearth::Body box = w.create_body(hearth::BodyType::Dynamic, hearth::vec3(0.3f, 2.0f, -0.2f));
    hearth::Shape s = box.add(hearth::box(hearth::vec3(0.5f, 0.25f, 0.75f)));
    CHECK(s.body() == box);
    CHECK(box.type() == hearth::BodyType::Dynamic);
    // 1 x 0.5 x 1.5 m of water density: 750 kg.
    CHECK_NEAR(box.mass(), 750.0, 0.01);
    for (int i = 0; i < 360; i++) { // it settles in 1 s and falls asleep by 4.5 s
        w.step(DT);
    }
    const hearth::Transform t = box.transform();
    CHECK_NEAR(t.position.y, 0.25, 0.005); // rests on its face: half height above the plane
    CHECK_NEAR(t.position.x, 0.3, 0.005);
    CHECK_NEAR(t.position.z, -0.2, 0.005);
    CHECK_NEAR(std::fabs(t.rotation.w), 1.0, 1e-4);
    CHECK(!box.is_awake()); // it fell asleep
    const hearth::WorldCounters c = w.counters();
    CHECK(c.body_count == 2 && c.awake_body_count == 0);
}

static void test_errors_as_exceptions() {
    hearth::World w = make_world();
    hearth::Body b = add_ball(w, hearth::vec3(0, 5, 0));
    hearth::Body doomed = add_ball(w, hearth::vec3(3, 5, 0));
    const hearth::Transform before = b.transform();
    doomed.destroy();

    // Stale id: INVALID_ID with the C layer's message; the exception is a runtime_error.
    CHECK_THROWS(doomed.transform(), hearth::Code::InvalidId);
    CHECK_THROWS(doomed.destroy(), hearth::Code::InvalidId);
    CHECK_THROWS(hearth::Body().mass(), hearth::Code::NullPointer); // default handle: no world
    try {
        doomed.set_linear_velocity(hearth::vec3(1, 0, 0));
        CHECK(false);
    } catch (const std::runtime_error &e) {
        CHECK(std::string(e.what()).find("HEARTH_ERROR_INVALID_ID: ") == 0);
        CHECK(std::strlen(e.what()) > std::strlen("HEARTH_ERROR_INVALID_ID: "));
    }
    // NaN and other bad numbers: INVALID_ARGUMENT, and the world is unchanged.
    hearth::Transform bad = before;
    bad.position.y = NaN;
    CHECK_THROWS(b.set_transform(bad), hearth::Code::InvalidArgument);
    CHECK_THROWS(b.set_linear_velocity(hearth::vec3(NaN, 0, 0)), hearth::Code::InvalidArgument);
    CHECK_THROWS(w.step(NaN), hearth::Code::InvalidArgument);
    CHECK_THROWS(w.step(-1.0f), hearth::Code::InvalidArgument);
    CHECK_THROWS(b.add(hearth::sphere(-1.0f)), hearth::Code::InvalidArgument);
    CHECK_THROWS(b.add(hearth::plane(hearth::vec3(0, 1, 0), 0)), hearth::Code::InvalidArgument);
    hearth::BodyDef garbage;
    std::memset(&garbage, 0, sizeof garbage); // not from body_def(): cookie missing
    CHECK_THROWS(w.create_body(garbage), hearth::Code::InvalidArgument);
    CHECK(same_transform(b.transform(), before));
    CHECK(w.counters().body_count == 1);
    CHECK_NEAR(b.linear_velocity().y, 0.0, 0.0);
    // A world def with bad numbers: no world is made.
    hearth::WorldDef wd = hearth::world_def();
    wd.substeps = 0;
    CHECK_THROWS(hearth::World bad_world(wd), hearth::Code::InvalidArgument);
    // The angular speed limit (appended to the def): default 100 pi, validated, applied.
    wd = hearth::world_def();
    CHECK_NEAR(wd.max_angular_speed, 314.159265, 1e-3);
    wd.max_angular_speed = -1.0f;
    CHECK_THROWS(hearth::World bad_world(wd), hearth::Code::InvalidArgument);
    wd.max_angular_speed = 5.0f;
    {
        hearth::World limited(wd);
        hearth::Body spun = limited.create_body(hearth::BodyType::Dynamic);
        spun.add(hearth::sphere(0.5f));
        CHECK_THROWS(spun.set_angular_velocity(hearth::vec3(0, 6.0f, 0)), hearth::Code::InvalidArgument);
        spun.apply_angular_impulse(hearth::vec3(0, 1.0e6f, 0)); // capped at the limit
        CHECK_NEAR(spun.angular_velocity().y, 5.0, 1e-4);
    }
    // Buffers too small (checked by the wrapper before the C call).
    std::vector<hearth::BodyId> ids{b.id(), b.id()};
    std::vector<hearth::Transform> one(1);
    CHECK_THROWS(w.transforms(ids, one), hearth::Code::BufferTooSmall);
    // Structural change from inside a lambda: WORLD_LOCKED, rethrown by step().
    int calls = 0;
    hearth::Generator g = w.add_force_generator([&](hearth::ForceContext &ctx) {
        calls++;
        ctx.world().create_body(hearth::BodyType::Dynamic);
    });
    CHECK_THROWS(w.step(DT), hearth::Code::WorldLocked);
    CHECK(calls == 1);
    CHECK(w.counters().body_count == 1);
    w.destroy_generator(g);
    CHECK_THROWS(w.destroy_generator(g), hearth::Code::InvalidId); // stale now
    CHECK(hearth::code_name(hearth::Code::Panic) == std::string("HEARTH_ERROR_PANIC"));
    CHECK(hearth::code_name(hearth::Code::LimitReached) == std::string("HEARTH_ERROR_LIMIT_REACHED"));
}

// Rolling resistance and torsional friction, the shape def's last fields: defaults, range
// errors, and a ball that rolls and one that spins to rest on the closed forms
// (7v²/(10cg) and 2rω/(5tg), within 5 %).
static void test_rolling_resistance_and_torsional_friction() {
    hearth::World w = make_world(true);
    const hearth::ShapeDef defaults = hearth::shape_def();
    CHECK_NEAR(defaults.rolling_resistance, 0.05, 1e-7);
    CHECK_NEAR(defaults.torsional_friction, 0.05, 1e-7);
    hearth::Body probe = w.create_body(hearth::BodyType::Dynamic, hearth::vec3(0, 5, 0));
    for (float bad : {-0.1f, 1.5f, NaN, INFINITY}) {
        hearth::ShapeDef def = hearth::shape_def();
        def.rolling_resistance = bad;
        CHECK_THROWS(probe.add(hearth::sphere(0.3f), def), hearth::Code::InvalidArgument);
        def = hearth::shape_def();
        def.torsional_friction = bad;
        CHECK_THROWS(probe.add(hearth::sphere(0.3f), def), hearth::Code::InvalidArgument);
    }
    probe.destroy();

    add_ground(w);
    const float r = 0.3f, v = 2.0f, c = 0.2f, t = 0.3f, spin = 6.0f, g = 9.81f;
    hearth::ShapeDef ball = hearth::shape_def();
    ball.rolling_resistance = c;
    ball.torsional_friction = t;
    hearth::Body rolling = w.create_body(hearth::BodyType::Dynamic, hearth::vec3(0, r, 0));
    rolling.add(hearth::sphere(r), ball);
    rolling.set_linear_velocity(hearth::vec3(v, 0, 0));
    rolling.set_angular_velocity(hearth::vec3(0, 0, -v / r));
    hearth::Body spinning = w.create_body(hearth::BodyType::Dynamic, hearth::vec3(5, r, 0));
    spinning.add(hearth::sphere(r), ball);
    spinning.set_angular_velocity(hearth::vec3(0, spin, 0));
    int stopped = -1;
    for (int i = 1; i <= 600; i++) {
        w.step(DT);
        if (stopped < 0 && spinning.angular_velocity().y <= 1e-3f) {
            stopped = i;
        }
    }
    const double distance = 7.0 * v * v / (10.0 * c * g), time = 2.0 * r * spin / (5.0 * t * g);
    CHECK_NEAR(rolling.transform().position.x, distance, 0.05 * distance);
    CHECK_NEAR(stopped * DT, time, 0.05 * time + DT);
    CHECK(!rolling.is_awake() && !spinning.is_awake());
}

static void test_move_semantics() {
    static_assert(!std::is_copy_constructible<hearth::World>::value, "World is move-only");
    static_assert(!std::is_copy_assignable<hearth::World>::value, "World is move-only");
    static_assert(std::is_nothrow_move_constructible<hearth::World>::value, "World moves");
    static_assert(std::is_nothrow_move_assignable<hearth::World>::value, "World moves");
    static_assert(std::is_trivially_copyable<hearth::Body>::value, "handles are values");

    auto counter = std::make_shared<int>(0);
    hearth::World a = make_world();
    hearth::Body ball = add_ball(a, hearth::vec3(0, 10, 0));
    hearth::Generator g = a.add_force_generator([counter](hearth::ForceContext &) { (*counter)++; });
    HearthWorld *raw = a.get();

    hearth::World b(std::move(a)); // move construction: the C world and its lambdas move along
    CHECK(!a && a.get() == nullptr && b.get() == raw);
    CHECK(a.lambda_count() == 0 && b.lambda_count() == 1);
    CHECK_THROWS(a.step(DT), hearth::Code::NullPointer); // the moved-from World is empty
    CHECK_THROWS(a.create_body(hearth::body_def()), hearth::Code::NullPointer);
    b.step(DT);
    CHECK(*counter == 1);
    CHECK(ball.position().y < 10.0f); // handles stay valid across the move

    hearth::World c = make_world();
    add_ball(c, hearth::vec3(0, 1, 0));
    c = std::move(b); // move assignment destroys c's old world
    CHECK(c.get() == raw && c.counters().body_count == 1);
    c.step(DT);
    CHECK(*counter == 2);
    CHECK(c.generator(g.id()).type() == hearth::GeneratorType::UserForce);

    // The lambda (and its captures) is released by destroy_generator and with the World.
    CHECK(counter.use_count() == 2);
    c.destroy_generator(g);
    CHECK(counter.use_count() == 1 && c.lambda_count() == 0);
    c.step(DT);
    CHECK(*counter == 2);
    {
        hearth::World d = make_world();
        d.add_force_generator([counter](hearth::ForceContext &) {});
        d.add_contact_generator([counter](hearth::ContactContext &) {});
        CHECK(counter.use_count() == 3 && d.lambda_count() == 2);
    }
    CHECK(counter.use_count() == 1);
    // A generator that fails to be made keeps nothing.
    hearth::World e;
    CHECK_THROWS(e.add_force_generator([counter](hearth::ForceContext &) {}), hearth::Code::NullPointer);
    CHECK(counter.use_count() == 1);
}

static void test_lambda_force_hovers() {
    hearth::World w = make_world();
    hearth::Body hover = add_ball(w, hearth::vec3(0, 5, 0));
    hearth::Body falls = add_ball(w, hearth::vec3(2, 5, 0));
    hearth::Particle p = w.create_particle([] {
        hearth::ParticleDef d = hearth::particle_def();
        d.position = hearth::vec3(-2, 5, 0);
        return d;
    }());
    int calls = 0;
    float seen_dt = 0.0f;
    size_t seen_bodies = 0, seen_particles = 0;
    hearth::Generator lift = w.add_force_generator([&](hearth::ForceContext &ctx) {
        calls++;
        seen_dt = ctx.dt();
        seen_bodies = ctx.bodies().size();
        seen_particles = ctx.particles().size();
        const hearth::Vec3 g = ctx.world().gravity();
        for (hearth::Body b : ctx.bodies()) {
            const float m = b.mass();
            b.apply_force(hearth::vec3(-g.x * m, -g.y * m, -g.z * m));
        }
        for (hearth::Particle q : ctx.particles()) {
            q.apply_force(hearth::vec3(0, 9.81f, 0)); // 1 kg
        }
    });
    lift.attach(hover);
    lift.attach(p);
    CHECK(lift.type() == hearth::GeneratorType::UserForce);
    const hearth::Attachments a = lift.attachments();
    CHECK(a.bodies == 1 && a.particles == 1);
    for (int i = 0; i < 60; i++) {
        w.step(DT);
    }
    CHECK(calls == 60 && seen_bodies == 1 && seen_particles == 1);
    CHECK_NEAR(seen_dt, DT, 1e-7);
    CHECK_NEAR(hover.position().y, 5.0, 1e-3);
    CHECK_NEAR(p.position().y, 5.0, 1e-3);
    CHECK_NEAR(falls.position().y, 5.0 - 0.5 * 9.81, 0.1); // free fall for 1 s
    lift.detach(hover);
    CHECK(lift.attachments().bodies == 0);
    w.step(DT);
    CHECK(hover.linear_velocity().y < 0.0f);
}

static void test_lambda_exception_rethrown_by_step() {
    hearth::World w = make_world();
    hearth::Body b = add_ball(w, hearth::vec3(0, 5, 0));
    int first = 0, second = 0;
    bool explode = true;
    w.add_force_generator([&](hearth::ForceContext &) {
        first++;
        if (explode) {
            throw std::runtime_error("boom from a lambda");
        }
    });
    w.add_force_generator([&](hearth::ForceContext &) { second++; });
    bool caught = false;
    try {
        w.step(DT);
    } catch (const std::runtime_error &e) {
        caught = std::string(e.what()) == "boom from a lambda"; // the original exception
    }
    CHECK(caught);
    CHECK(first == 1 && second == 0); // the rest of that step's lambdas were skipped
    CHECK(b.position().y < 5.0f);     // the step itself ran
    explode = false;
    w.step(DT); // the failure was reported once; the next step is clean
    CHECK(first == 2 && second == 1);
    // A non-standard exception type comes back as itself too.
    w.add_force_generator([](hearth::ForceContext &) { throw 42; });
    int thrown = 0;
    try {
        w.step(DT);
    } catch (int v) {
        thrown = v;
    }
    CHECK(thrown == 42);
    // A lambda returning a failed Status: step() throws hearth::Error with its code.
    hearth::World w2 = make_world();
    w2.add_force_generator([](hearth::ForceContext &) -> hearth::Status {
        return hearth::Status(hearth::Code::InvalidArgument, "rejected by the lambda");
    });
    CHECK_THROWS(w2.step(DT), hearth::Code::InvalidArgument);
}

static void test_lambda_contact_floor() {
    // No plane: a contact lambda is the floor, at y = 0, for one ball and one particle.
    hearth::World w = make_world();
    hearth::Body ball = add_ball(w, hearth::vec3(0, 1, 0));
    hearth::ParticleDef pd = hearth::particle_def();
    pd.position = hearth::vec3(2, 1, 0);
    hearth::Particle p = w.create_particle(pd);
    uint32_t seen_capacity = 0;
    bool refused = false;
    hearth::Generator floor = w.add_contact_generator(
        [&](hearth::ContactContext &ctx) {
            const hearth::Vec3 bp = ball.position();
            hearth::GeneratedContact c{};
            c.body_b = ball.id();
            c.point = hearth::vec3(bp.x, 0, bp.z);
            c.normal = hearth::vec3(0, 1, 0);
            c.penetration = 0.25f - bp.y;
            c.friction = 0.5f;
            ctx.add(c);
            const hearth::Vec3 pp = p.position();
            hearth::GeneratedContact pc{};
            pc.particle_b = p.id();
            pc.point = hearth::vec3(pp.x, 0, pp.z);
            pc.normal = hearth::vec3(0, 1, 0);
            pc.penetration = 0.05f - pp.y;
            ctx.add(pc);
            seen_capacity = ctx.capacity();
            try {
                ctx.add(c); // capacity 2: the third is refused
            } catch (const hearth::Error &e) {
                refused = e.code() == hearth::Code::BufferTooSmall;
            }
        },
        2);
    CHECK(floor.type() == hearth::GeneratorType::UserContact);
    for (int i = 0; i < 180; i++) {
        w.step(DT);
    }
    CHECK(seen_capacity == 2 && refused);
    CHECK_NEAR(ball.position().y, 0.25, 0.01);
    CHECK_NEAR(p.position().y, 0.05, 0.01);
}

static void test_bulk_equals_single_reads() {
    hearth::World w = make_world();
    add_ground(w);
    std::vector<hearth::Body> bodies;
    for (int i = 0; i < 12; i++) {
        hearth::Body b = w.create_body(hearth::BodyType::Dynamic,
                                       hearth::vec3(0.3f * (float)(i % 3), 1.0f + 1.1f * (float)i, 0.1f * (float)i));
        if (i % 2 == 0) {
            b.add(hearth::box(hearth::vec3(0.5f, 0.5f, 0.5f)));
        } else {
            b.add(hearth::capsule(hearth::vec3(0, -0.3f, 0), hearth::vec3(0, 0.3f, 0), 0.2f));
        }
        b.set_angular_velocity(hearth::vec3(0.1f * (float)i, 0.2f, 0.0f));
        bodies.push_back(b);
    }
    for (int i = 0; i < 90; i++) {
        w.step(DT);
    }
    std::vector<hearth::BodyId> ids;
    for (const hearth::Body &b : bodies) {
        ids.push_back(b.id());
    }
    std::vector<hearth::Transform> span_out(ids.size());
    w.transforms(ids, span_out);
    const std::vector<hearth::Transform> vec_out = w.transforms(bodies);
    bool all_equal = vec_out.size() == bodies.size();
    for (size_t i = 0; i < bodies.size() && all_equal; i++) {
        const hearth::Transform single = bodies[i].transform();
        all_equal = same_transform(single, span_out[i]) && same_transform(single, vec_out[i]);
    }
    CHECK(all_equal);
    // A stale id anywhere: nothing written, INVALID_ID.
    bodies[5].destroy();
    std::vector<hearth::Transform> untouched(ids.size(), hearth::transform(hearth::vec3(7, 7, 7)));
    CHECK_THROWS(w.transforms(ids, untouched), hearth::Code::InvalidId);
    CHECK(untouched[0].position.x == 7.0f && untouched[11].position.x == 7.0f);
}

static void test_joints() {
    hearth::World w = make_world();
    // A 1 m pendulum on a distance joint to a world anchor at (0, 3, 0).
    hearth::Body bob = add_ball(w, hearth::vec3(1, 3, 0), 0.1f);
    hearth::DistanceJointDef dd = hearth::distance_joint_def();
    dd.base.body_a = bob.id();
    dd.base.frame_b = hearth::transform(hearth::vec3(0, 3, 0));
    dd.length = 1.0f;
    hearth::Joint rope = w.create_joint(dd);
    CHECK(rope.type() == hearth::JointType::Distance);
    const auto pair = rope.bodies();
    CHECK(pair.first == bob && pair.second.is_null());
    float worst = 0.0f;
    for (int i = 0; i < 120; i++) {
        w.step(DT);
        const hearth::Vec3 p = bob.position();
        const float len = std::sqrt(p.x * p.x + (p.y - 3) * (p.y - 3) + p.z * p.z);
        worst = std::fmax(worst, std::fabs(len - 1.0f));
    }
    CHECK(worst < 0.01f);
    CHECK(bob.position().y < 2.5f); // it swung down
    // The rope pulls its world end (body B) toward the bob: along anchor -> bob.
    const hearth::Vec3 f = rope.force().force, bp = bob.position();
    CHECK(f.x * bp.x + f.y * (bp.y - 3.0f) + f.z * bp.z > 0.0f);
    CHECK(!rope.is_broken());
    CHECK(w.broken_joints().empty());
    // A motorised hinge: set and read back, limits round trip, a wrong-type call throws.
    hearth::Body door = w.create_body(hearth::BodyType::Dynamic, hearth::vec3(5, 1, 0));
    door.add(hearth::box(hearth::vec3(0.5f, 1.0f, 0.05f)));
    hearth::HingeJointDef hd = hearth::hinge_joint_def();
    hd.base.body_a = door.id();
    hd.base.frame_b = hearth::transform(hearth::vec3(5, 1, 0));
    hearth::Joint hinge = w.create_joint(hd);
    hinge.set_motor(true, 1.5f, 100.0f);
    const hearth::Motor m = hinge.motor();
    CHECK(m.enabled && m.speed == 1.5f && m.max == 100.0f);
    hinge.set_limits(true, -0.5f, 0.75f);
    const hearth::Limits l = hinge.limits();
    CHECK(l.enabled && l.lower == -0.5f && l.upper == 0.75f);
    CHECK_THROWS(hinge.set_cone_limit(true, 0.3f), hearth::Code::InvalidArgument);
    CHECK_THROWS(hinge.set_limits(true, 1.0f, -1.0f), hearth::Code::InvalidArgument);
    CHECK(hinge.limits().upper == 0.75f); // unchanged by the failed call
    hinge.destroy();
    CHECK_THROWS(hinge.type(), hearth::Code::InvalidId);
    // Destroying a body destroys its joints.
    bob.destroy();
    CHECK_THROWS(rope.type(), hearth::Code::InvalidId);
}

static void test_particles() {
    hearth::World w = make_world();
    hearth::ParticleDef pd = hearth::particle_def();
    pd.position = hearth::vec3(0, 20, 0);
    pd.collide = 0;
    pd.user_data = 77;
    hearth::Particle p = w.create_particle(pd);
    CHECK(p.user_data() == 77);
    for (int i = 0; i < 60; i++) {
        w.step(DT);
    }
    CHECK_NEAR(p.position().y, 20.0 - 0.5 * 9.81, 0.1);
    CHECK_NEAR(p.velocity().y, -9.81, 0.01);
    hearth::BurstDef bd = hearth::burst_def();
    bd.position = hearth::vec3(0, 5, 0);
    bd.count = 10;
    bd.lifetime_min = 0.5f;
    bd.lifetime_max = 0.5f;
    const std::vector<hearth::Particle> burst = w.emit_burst(bd);
    CHECK(burst.size() == 10 && w.particle_count() == 11);
    w.step(DT);
    // Bulk reads equal single reads.
    std::vector<hearth::ParticleId> ids(11);
    std::vector<hearth::Vec3> pos(11), vel(11);
    CHECK(w.particles(ids, pos, vel) == 11);
    bool equal = true;
    for (size_t i = 0; i < ids.size(); i++) {
        const hearth::Particle q = w.particle(ids[i]);
        const hearth::Vec3 sp = q.position(), sv = q.velocity();
        equal = equal && std::memcmp(&sp, &pos[i], sizeof sp) == 0 && std::memcmp(&sv, &vel[i], sizeof sv) == 0;
    }
    CHECK(equal);
    std::vector<hearth::Vec3> by_id(ids.size());
    w.particle_positions(ids, by_id);
    CHECK(std::memcmp(by_id.data(), pos.data(), sizeof(hearth::Vec3) * pos.size()) == 0);
    std::vector<hearth::Vec3> short_buffer(3);
    CHECK_THROWS(w.particles({}, short_buffer, {}), hearth::Code::BufferTooSmall);
    // The burst expires after 0.5 s and is reported for one step.
    size_t expired = 0;
    for (int i = 0; i < 40; i++) {
        w.step(DT);
        expired += w.expired_particles().size();
    }
    CHECK(expired == 10 && w.particle_count() == 1);
    CHECK_THROWS(burst[0].position(), hearth::Code::InvalidId);
    p.destroy();
    CHECK(w.particle_count() == 0);
}

static void test_soft_bodies() {
    hearth::World w = make_world();
    add_ground(w);
    hearth::SoftBodyDef sd = hearth::soft_body_def();
    sd.transform.position = hearth::vec3(0, 2, 0);
    sd.pressure = 50.0f;
    hearth::SoftBody ball = w.create_soft_icosphere(sd, 0.5f, 2);
    CHECK(ball.vertex_count() == 162);
    CHECK(ball.indices().size() == 3 * ball.triangle_count());
    CHECK_NEAR(ball.mass(), 1.0, 1e-5);
    for (int i = 0; i < 30; i++) {
        w.step(DT);
    }
    const std::vector<hearth::Vec3> pos = ball.positions();
    bool equal = pos.size() == 162;
    for (uint32_t v = 0; v < pos.size() && equal; v++) {
        const hearth::Vec3 single = ball.vertex_position(v);
        equal = std::memcmp(&single, &pos[v], sizeof single) == 0;
    }
    CHECK(equal);
    std::vector<hearth::Vec3> normals(162);
    CHECK(ball.normals(normals) == 162);
    CHECK_NEAR(std::sqrt(normals[0].x * normals[0].x + normals[0].y * normals[0].y + normals[0].z * normals[0].z),
               1.0, 1e-4);
    CHECK(ball.center().y < 2.0f);
    CHECK_THROWS(ball.vertex_position(162), hearth::Code::InvalidArgument);
    std::vector<hearth::Vec3> tiny(5);
    CHECK_THROWS(ball.positions(tiny), hearth::Code::BufferTooSmall);
    // A tetrahedron from a mesh, a pinned cloth.
    const hearth::Vec3 tet_v[4] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    const uint32_t tet_i[12] = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3};
    hearth::SoftBodyDef td = hearth::soft_body_def();
    td.transform.position = hearth::vec3(5, 5, 0);
    hearth::SoftBody tet = w.create_soft_body(td, tet_v, tet_i);
    CHECK_NEAR(tet.rest_volume(), 1.0 / 6.0, 1e-5);
    const uint32_t bad_i[3] = {0, 1, 9};
    CHECK_THROWS(w.create_soft_body(td, tet_v, bad_i), hearth::Code::InvalidArgument);
    hearth::SoftBody cloth = w.create_cloth(td, 1.0f, 1.0f, 4, 4);
    cloth.pin_vertex(0);
    CHECK(cloth.is_vertex_pinned(0) && !cloth.is_vertex_pinned(1));
    cloth.unpin_vertex(0);
    CHECK(!cloth.is_vertex_pinned(0));
    CHECK(w.soft_body_count() == 3);
    tet.destroy();
    CHECK_THROWS(tet.volume(), hearth::Code::InvalidId);
    CHECK(w.soft_body_count() == 2);
}

static void test_soft_body_settings() {
    hearth::World w = make_world();
    const hearth::SoftBodyDef defaults = hearth::soft_body_def();
    CHECK(defaults.deformation_damping == 2.0f && defaults.iterations == 2 && defaults.substeps == 20);
    hearth::SoftBodyDef sd = hearth::soft_body_def();
    sd.transform.position = hearth::vec3(0, 2, 0);
    sd.edge_compliance = 1e-4f;
    sd.bend_compliance = INFINITY;
    sd.preserve_volume = 1;
    sd.volume_compliance = 0.01f;
    sd.pressure = 30.0f;
    sd.damping = 0.25f;
    sd.deformation_damping = 3.5f;
    sd.friction = 0.8f;
    sd.restitution = 0.1f;
    sd.vertex_radius = 0.02f;
    sd.gravity_scale = 0.5f;
    sd.substeps = 12;
    sd.iterations = 4;
    sd.collide = 0;
    hearth::SoftBody ball = w.create_soft_icosphere(sd, 0.5f, 1);
    hearth::SoftBodySettings s = ball.settings();
    CHECK(same_settings(s, settings_of(sd))); // the def given at creation
    CHECK(same_settings(w.create_cloth(defaults, 1.0f, 1.0f, 2, 2).settings(), settings_of(defaults)));

    // Set, then get returns them.
    s.edge_compliance = 0.001f;
    s.bend_compliance = 0.5f;
    s.preserve_volume = 0;
    s.pressure = 12.0f;
    s.deformation_damping = 0.0f;
    s.gravity_scale = -1.0f;
    s.substeps = 64;
    s.iterations = 16;
    s.collide = 1;
    ball.set_settings(s);
    CHECK(same_settings(ball.settings(), s));
    CHECK(ball.pressure() == 12.0f);

    // set_compliance changes those three and nothing else.
    ball.set_compliance(0.002f, INFINITY, 0.25f);
    hearth::SoftBodySettings c = ball.settings();
    CHECK(c.edge_compliance == 0.002f && std::isinf(c.bend_compliance) && c.volume_compliance == 0.25f);
    c.edge_compliance = s.edge_compliance;
    c.bend_compliance = s.bend_compliance;
    c.volume_compliance = s.volume_compliance;
    CHECK(same_settings(c, s));
    s = ball.settings();

    // Bad values throw InvalidArgument and change nothing.
    hearth::SoftBodySettings bad = s;
    bad.damping = NaN;
    CHECK_THROWS(ball.set_settings(bad), hearth::Code::InvalidArgument);
    bad = s;
    bad.deformation_damping = -1.0f;
    CHECK_THROWS(ball.set_settings(bad), hearth::Code::InvalidArgument);
    bad = s;
    bad.iterations = 0;
    CHECK_THROWS(ball.set_settings(bad), hearth::Code::InvalidArgument);
    bad.iterations = 17;
    CHECK_THROWS(ball.set_settings(bad), hearth::Code::InvalidArgument);
    bad = s;
    bad.substeps = 65;
    CHECK_THROWS(ball.set_settings(bad), hearth::Code::InvalidArgument);
    bad = s;
    bad.collide = 2;
    CHECK_THROWS(ball.set_settings(bad), hearth::Code::InvalidArgument);
    CHECK_THROWS(ball.set_settings(hearth::SoftBodySettings{}), hearth::Code::InvalidArgument); // 0 sub-steps
    CHECK_THROWS(ball.set_compliance(NaN, 0.0f, 0.0f), hearth::Code::InvalidArgument);
    CHECK_THROWS(ball.set_compliance(0.0f, -1.0f, 0.0f), hearth::Code::InvalidArgument);
    CHECK_THROWS(ball.set_compliance(INFINITY, 0.0f, 0.0f), hearth::Code::InvalidArgument);
    CHECK(same_settings(ball.settings(), s));

    // The new settings run: gravity scale -1 lifts it.
    const float y = ball.center().y;
    w.step(DT);
    CHECK(ball.center().y > y);

    ball.destroy();
    CHECK_THROWS(ball.settings(), hearth::Code::InvalidId);
    CHECK_THROWS(ball.set_settings(s), hearth::Code::InvalidId);
    CHECK_THROWS(ball.set_compliance(0.0f, 0.01f, 0.0f), hearth::Code::InvalidId);
}

static void test_builtin_generators() {
    hearth::World w = make_world();
    hearth::Body b = add_ball(w, hearth::vec3(0, 10, 0));
    hearth::GravityGeneratorDef gd = hearth::gravity_generator_def();
    gd.acceleration = hearth::vec3(0, 9.81f, 0); // cancels world gravity
    hearth::Generator anti = w.create_gravity_generator(gd);
    anti.attach(b);
    CHECK_THROWS(anti.attach(b), hearth::Code::InvalidArgument); // already attached
    CHECK(anti.type() == hearth::GeneratorType::Gravity);
    for (int i = 0; i < 30; i++) {
        w.step(DT);
    }
    CHECK_NEAR(b.position().y, 10.0, 1e-3);
    w.destroy_generator(anti);
    hearth::RodGeneratorDef rd = hearth::rod_generator_def();
    rd.a = hearth::link_body(b.id());
    rd.b = hearth::link_world(hearth::vec3(0, 11, 0));
    rd.length = 1.0f;
    hearth::Generator rod = w.create_rod(rd);
    CHECK(rod.type() == hearth::GeneratorType::Rod);
    CHECK_THROWS(rod.attach(b), hearth::Code::InvalidArgument);
    for (int i = 0; i < 60; i++) {
        w.step(DT);
    }
    CHECK_NEAR(b.position().y, 10.0, 0.01); // hangs on the rod
}

static void test_recording() {
    hearth::World w = make_world();
    hearth::Body b = add_ball(w, hearth::vec3(0, 5, 0));
    // Into a file next to this program (each build variant has its own).
    const std::string path = g_program + ".hrec";
    w.record_to_file(path, true);
    CHECK_THROWS(w.record_to_file(path), hearth::Code::InvalidArgument); // already recording
    for (int i = 0; i < 10; i++) {
        w.step(DT);
    }
    w.stop_recording();
    CHECK_THROWS(w.stop_recording(), hearth::Code::InvalidArgument); // not recording
    std::FILE *f = std::fopen(path.c_str(), "rb");
    char head[8] = {0};
    CHECK(f != nullptr && std::fread(head, 1, 8, f) == 8 && std::memcmp(head, "HEARTHRC", 8) == 0);
    if (f != nullptr) {
        std::fseek(f, 0, SEEK_END);
        CHECK(std::ftell(f) > 16 + 10 * 31); // a falling ball: its 31-byte record every step
        std::fclose(f);
    }
    std::remove(path.c_str());
    CHECK_THROWS(w.record_to_file("/nonexistent-dir/x.hrec"), hearth::Code::Io);
    // Through a lambda.
    std::vector<uint8_t> bytes;
    int calls = 0;
    w.record_to([&](const uint8_t *data, size_t len) {
        calls++;
        bytes.insert(bytes.end(), data, data + len);
        return true;
    });
    CHECK(calls == 1 && bytes.size() > 16 && std::memcmp(bytes.data(), "HEARTHRC", 8) == 0);
    w.step(DT);
    CHECK(calls == 2);
    w.stop_recording();
    // A lambda that throws: the step it throws in rethrows it; the next step reports Io and
    // does not run; then the world steps without recording.
    int writes = 0;
    w.record_to([&](const uint8_t *, size_t) -> bool {
        if (++writes == 2) {
            throw std::runtime_error("disk full");
        }
        return true;
    });
    try {
        w.step(DT);
        CHECK(false);
    } catch (const std::runtime_error &e) {
        CHECK(std::string(e.what()) == "disk full");
    }
    const float y = b.position().y;
    CHECK_THROWS(w.step(DT), hearth::Code::Io);
    CHECK(b.position().y == y);
    w.step(DT);
    CHECK(writes == 2 && b.position().y < y);
}

static void test_recording_start_failure() {
    hearth::World w = make_world();
    CHECK_THROWS(w.record_to([](const uint8_t *, size_t) { return false; }), hearth::Code::Io);
    CHECK_THROWS(w.stop_recording(), hearth::Code::InvalidArgument);
}

// Shared geometry: a box dropped on a mesh floor rests at the analytic height (0.5 m), a hull
// cube on a heightfield at 1.0 m; counts, the refusal to free geometry in use, a mesh refused
// on a dynamic body.
static int g_snapshot_force_calls = 0;
static void snapshot_force(void *, HearthWorld *, const HearthGeneratorContext *) { g_snapshot_force_calls++; }

static void test_snapshots() {
    hearth::World w = make_world();
    add_ground(w);
    hearth::Body ball = add_ball(w, hearth::vec3(0, 3, 0));
    int lambda_calls = 0;
    w.add_force_generator([&](hearth::ForceContext &) { lambda_calls++; });
    for (int i = 0; i < 10; i++) {
        w.step(DT);
    }
    const std::vector<uint8_t> snap = w.save_snapshot();
    CHECK(snap.size() == w.snapshot_size());
    for (int i = 0; i < 20; i++) {
        w.step(DT);
    }
    const hearth::Transform first = ball.transform();
    const std::vector<uint8_t> after = w.save_snapshot();
    w.restore_snapshot(snap);
    CHECK(w.save_snapshot() == snap);
    for (int i = 0; i < 20; i++) {
        w.step(DT);
    }
    const hearth::Transform again = ball.transform();
    CHECK(std::memcmp(&first, &again, sizeof first) == 0); // bit for bit, the same handle
    CHECK(w.save_snapshot() == after);
    CHECK(lambda_calls == 50); // the lambda kept in the same world
    CHECK(w.user_generators_missing_callback().empty());
    std::vector<uint8_t> bad = snap;
    bad[bad.size() / 2] ^= 1;
    CHECK_THROWS(w.restore_snapshot(bad), hearth::Code::InvalidArgument);
    CHECK_THROWS(w.restore_snapshot(snap.data(), snap.size() - 1), hearth::Code::InvalidArgument);
    CHECK(w.save_snapshot() == after); // unchanged

    hearth::World fresh = make_world();
    fresh.restore_snapshot(snap);
    const std::vector<hearth::Generator> missing = fresh.user_generators_missing_callback();
    CHECK(missing.size() == 1 && missing[0].type() == hearth::GeneratorType::UserForce);
    hearth::UserForceGeneratorDef def = hearth::user_force_generator_def();
    def.callback = &snapshot_force;
    fresh.set_user_force_callback(missing[0], def);
    CHECK_THROWS(fresh.set_user_contact_callback(missing[0], hearth::user_contact_generator_def()),
                 hearth::Code::NullPointer);
    CHECK(fresh.user_generators_missing_callback().empty());
    fresh.step(DT);
    CHECK(g_snapshot_force_calls == 1);
}

static void test_geometry() {
    hearth::World w = make_world();
    std::vector<hearth::Vec3> v;
    std::vector<uint32_t> idx;
    const int n = 4;
    for (int r = 0; r <= n; r++) {
        for (int c = 0; c <= n; c++) {
            v.push_back(hearth::vec3(float(c) - 2.0f, 0.0f, float(r) - 2.0f));
        }
    }
    for (int r = 0; r < n; r++) {
        for (int c = 0; c < n; c++) {
            const uint32_t a = uint32_t(r * (n + 1) + c), b = a + 1, cc = a + uint32_t(n + 1), d = cc + 1;
            for (uint32_t i : {a, cc, d, a, d, b}) {
                idx.push_back(i);
            }
        }
    }
    idx.insert(idx.end(), {0, 0, 1}); // degenerate: skipped and counted
    hearth::Mesh mesh = w.create_mesh(v, idx);
    CHECK(mesh.triangle_count() == 32);
    CHECK(mesh.degenerate_count() == 1);
    hearth::Body ground = w.create_body(hearth::BodyType::Static);
    ground.add(mesh.shape(hearth::vec3(2, 1, 2)));
    hearth::Body dyn = w.create_body(hearth::BodyType::Dynamic, hearth::vec3(0, 3, 0));
    CHECK_THROWS(dyn.add(mesh.shape()), hearth::Code::InvalidArgument);
    CHECK_THROWS(mesh.destroy(), hearth::Code::InvalidArgument);

    hearth::Body box = w.create_body(hearth::BodyType::Dynamic, hearth::vec3(0.3f, 1.5f, -0.2f));
    box.add(hearth::box(hearth::vec3(0.5f, 0.5f, 0.5f)));

    const std::vector<hearth::Vec3> cube = {
        hearth::vec3(-0.5f, -0.5f, -0.5f), hearth::vec3(0.5f, -0.5f, -0.5f), hearth::vec3(-0.5f, 0.5f, -0.5f),
        hearth::vec3(0.5f, 0.5f, -0.5f),   hearth::vec3(-0.5f, -0.5f, 0.5f), hearth::vec3(0.5f, -0.5f, 0.5f),
        hearth::vec3(-0.5f, 0.5f, 0.5f),   hearth::vec3(0.5f, 0.5f, 0.5f),
    };
    hearth::Hull hull = w.create_hull(cube);
    CHECK(hull.vertex_count() == 8);
    CHECK_THROWS(w.create_hull(hearth::Span<const hearth::Vec3>(cube.data(), 3)), hearth::Code::InvalidArgument);
    const std::vector<float> heights(6 * 5, 0.25f);
    hearth::Heightfield hf = w.create_heightfield(6, 5, heights);
    CHECK_THROWS(w.create_heightfield(5, 5, heights), hearth::Code::InvalidArgument);
    hearth::Body terrain = w.create_body(hearth::BodyType::Static, hearth::vec3(20, 0, 0));
    terrain.add(hf.shape(hearth::vec3(2, 2, 2))); // ground at y = 0.5
    hearth::Body a = w.create_body(hearth::BodyType::Dynamic, hearth::vec3(25.1f, 2.0f, 5.1f));
    a.add(hull.shape());
    CHECK_NEAR(a.mass(), 1000.0, 0.01);
    for (int i = 0; i < 240; i++) {
        w.step(DT);
    }
    CHECK_NEAR(box.position().y, 0.5, 5e-3);
    CHECK_NEAR(a.position().y, 1.0, 5e-3);
    CHECK_THROWS(hull.destroy(), hearth::Code::InvalidArgument);
    a.destroy();
    hull.destroy();
    CHECK_THROWS(hull.vertex_count(), hearth::Code::InvalidId);
    terrain.destroy();
    hf.destroy();
    ground.destroy();
    mesh.destroy();
    CHECK_THROWS(mesh.triangle_count(), hearth::Code::InvalidId);
}

// Queries and filters: a ray hits a sphere at d - r, a sphere cast onto the plane stops at
// (d - r)/|v|, overlaps, the callback protocol and an exception from the callback, filters.
static void test_queries_and_filters() {
    hearth::World w = make_world(true);
    add_ground(w);
    hearth::Body ball = w.create_body(hearth::BodyType::Static, hearth::vec3(0, 2, 0));
    hearth::Shape s = ball.add(hearth::sphere(0.5f));
    hearth::RayHit h = w.cast_ray_closest(hearth::vec3(-4, 2, 0), hearth::vec3(10, 0, 0));
    CHECK(hearth::is_hit(h) && hearth::same_id(h.shape, s.id()));
    CHECK_NEAR(h.fraction, 0.35, 1e-5);
    CHECK(!hearth::is_hit(w.cast_ray_closest(hearth::vec3(-4, 9, 0), hearth::vec3(10, 0, 0))));
    // A rebuilt broad-phase tree answers the same.
    w.rebuild_broadphase();
    hearth::RayHit again = w.cast_ray_closest(hearth::vec3(-4, 2, 0), hearth::vec3(10, 0, 0));
    CHECK(hearth::same_id(again.shape, s.id()) && again.fraction == h.fraction);
    int calls = 0;
    w.cast_ray(hearth::vec3(-4, 2, 0), hearth::vec3(0, -10, 0), [&](const hearth::RayHit &) {
        calls++;
        return 1.0f;
    });
    w.cast_ray(hearth::vec3(-4, 2, 0), hearth::vec3(10, -10, 0), [&](const hearth::RayHit &) {
        calls++;
        return 1.0f;
    });
    CHECK(calls == 2); // the plane, once per ray
    bool thrown = false;
    try {
        w.cast_ray(hearth::vec3(-4, 2, 0), hearth::vec3(10, 0, 0),
                   [](const hearth::RayHit &) -> float { throw std::runtime_error("from the callback"); });
    } catch (const std::runtime_error &e) {
        thrown = std::string(e.what()) == "from the callback";
    }
    CHECK(thrown);
    hearth::RayInput rays[2] = {{hearth::vec3(-4, 2, 0), hearth::vec3(10, 0, 0)}, {hearth::vec3(9, 9, 9), hearth::vec3(1, 0, 0)}};
    hearth::RayHit hits[2];
    w.cast_rays(rays, hits);
    CHECK(hearth::is_hit(hits[0]) && !hearth::is_hit(hits[1]));
    hearth::RayHit c = w.cast_shape(hearth::query_shape(hearth::sphere(0.5f)), hearth::transform(hearth::vec3(5, 5, 0)),
                                    hearth::vec3(0, -10, 0));
    CHECK_NEAR(c.fraction, 0.45, 1e-6); // (5 - 0.5) / 10
    CHECK(w.overlap_shape(hearth::query_shape(hearth::box(hearth::vec3(0.3f, 0.3f, 0.3f))),
                          hearth::transform(hearth::vec3(0.5f, 2.5f, 0))).size() == 1);
    CHECK(w.overlap_aabb(hearth::vec3(-1, -1, -1), hearth::vec3(1, 3, 1)).size() == 2); // plane and ball
    CHECK(w.overlap_point(hearth::vec3(0, 2.2f, 0)).size() == 1);
    hearth::Filter f = s.filter();
    CHECK(f.category_bits == 1 && f.mask_bits == ~0ull && f.group_index == 0);
    s.set_filter(hearth::filter(4));
    CHECK(s.filter().category_bits == 4);
    CHECK(!hearth::is_hit(w.cast_ray_closest(hearth::vec3(-4, 2, 0), hearth::vec3(10, 0, 0), hearth::query_filter(1, 3))));
    bool invalid = false;
    try {
        w.cast_ray_closest(hearth::vec3(0, 0, 0), hearth::vec3(0, 0, 0));
    } catch (const hearth::Error &e) {
        invalid = e.code() == hearth::Code::InvalidArgument;
    }
    CHECK(invalid);
}

static void test_events_and_step_callbacks() {
    hearth::World w = make_world(true);
    add_ground(w);
    // A dropped box: one begin, one hit at sqrt(2gh) within 1 %, move events.
    const float h = 2.0f;
    hearth::ShapeDef hits = hearth::shape_def();
    hits.enable_hit_events = 1;
    hearth::Body box = w.create_body(hearth::BodyType::Dynamic, hearth::vec3(0, 0.5f + h, 0));
    box.add(hearth::box(hearth::vec3(0.5f, 0.5f, 0.5f)), hits);
    size_t begins = 0, nhits = 0, moves = 0;
    float speed = 0;
    for (int i = 0; i < 120; i++) {
        w.step(DT);
        hearth::ContactEvents ev = w.contact_events();
        begins += ev.begin_count;
        nhits += ev.hit_count;
        if (ev.hit_count) speed = ev.hit[0].approach_speed;
        moves += hearth::BodyEvents(w.body_events()).move_count;
    }
    CHECK(begins == 1 && nhits == 1 && moves > 30);
    CHECK_NEAR(speed, std::sqrt(2.0f * 9.81f * h), 0.01f * std::sqrt(2.0f * 9.81f * h));
    // A sensor and a kinematic visitor.
    hearth::ShapeDef sensor = hearth::shape_def();
    sensor.is_sensor = 1;
    hearth::Body zone = w.create_body(hearth::BodyType::Static, hearth::vec3(10, 3, 0));
    zone.add(hearth::box(hearth::vec3(1, 1, 1)), sensor);
    CHECK_THROWS(zone.add(hearth::plane(hearth::vec3(0, 1, 0), -10), sensor), hearth::Code::InvalidArgument);
    hearth::Body mover = w.create_body(hearth::BodyType::Kinematic, hearth::vec3(5, 3, 0));
    mover.add(hearth::box(hearth::vec3(0.25f, 0.25f, 0.25f)));
    mover.set_linear_velocity(hearth::vec3(2, 0, 0));
    size_t sb = 0, se = 0;
    for (int i = 0; i < 300; i++) {
        w.step(DT);
        hearth::SensorEvents ev = w.sensor_events();
        sb += ev.begin_count;
        se += ev.end_count;
    }
    CHECK(sb == 1 && se == 1);
    // A one-way platform through the pre-solve lambda, and a pair filter.
    hearth::World p = make_world(true);
    add_ground(p);
    hearth::Body slab = p.create_body(hearth::BodyType::Static, hearth::vec3(0, 3, 0));
    const hearth::ShapeId platform = hearth::Shape(slab.add(hearth::box(hearth::vec3(2, 0.1f, 2)))).id();
    hearth::Body thrown = p.create_body(hearth::BodyType::Dynamic, hearth::vec3(0, 0.5f, 0));
    thrown.add(hearth::box(hearth::vec3(0.25f, 0.25f, 0.25f)));
    thrown.set_linear_velocity(hearth::vec3(0, 10, 0));
    int asked = 0;
    p.set_pair_filter([&](hearth::ShapeId, hearth::ShapeId) {
        asked++;
        return true;
    });
    p.set_pre_solve([&](const hearth::PreSolveContact &c) {
        float up;
        if (c.shape_a.index == platform.index) up = c.normal.y;
        else if (c.shape_b.index == platform.index) up = -c.normal.y;
        else return true;
        float deepest = 1e30f;
        for (uint32_t i = 0; i < c.point_count; i++) deepest = std::fmin(deepest, c.points[i].separation);
        return up > 0.7f && deepest > -0.05f;
    });
    for (int i = 0; i < 180; i++) p.step(DT);
    CHECK_NEAR(hearth::Transform(thrown.transform()).position.y, 3.35f, 0.005f);
    CHECK(asked > 0);
    // A throwing lambda is reported by the step (the box fell asleep on the platform: woken,
    // its contact is solved and the lambda asked).
    thrown.set_awake(true);
    p.set_pre_solve([](const hearth::PreSolveContact &) -> bool { throw std::runtime_error("boom"); });
    bool caught = false;
    try {
        p.step(DT);
    } catch (const std::runtime_error &e) {
        caught = std::string(e.what()) == "boom"; // the original exception, after the step
    }
    CHECK(caught);
    p.clear_pre_solve();
    p.clear_pair_filter();
    p.step(DT);
}

static void test_runtime_setters() {
    hearth::World w = make_world(true);
    add_ground(w);
    hearth::Body b = w.create_body(hearth::BodyType::Dynamic, hearth::vec3(0, 5, 0));
    hearth::Shape s = b.add(hearth::box(hearth::vec3(0.5f, 0.25f, 1.0f)), hearth::shape_def());
    const float m0 = b.mass();
    s.set_density(2000.0f);
    CHECK(s.density() == 2000.0f);
    CHECK(b.mass() == 2.0f * m0);
    s.set_friction(0.75f, 0.25f);
    CHECK(s.friction().first == 0.75f && s.friction().second == 0.25f);
    s.set_restitution(0.5f);
    s.set_rolling_resistance(0.25f);
    s.set_torsional_friction(0.125f);
    CHECK(s.restitution() == 0.5f && s.rolling_resistance() == 0.25f && s.torsional_friction() == 0.125f);
    s.set_user_data(99);
    CHECK(s.user_data() == 99);
    CHECK_THROWS(s.set_density(-1.0f), hearth::Code::InvalidArgument);
    CHECK_THROWS(s.set_friction(NaN, 0.1f), hearth::Code::InvalidArgument);
    CHECK(s.density() == 2000.0f);

    b.set_gravity_scale(0.0f);
    CHECK(b.gravity_scale() == 0.0f);
    for (int i = 0; i < 30; i++) w.step(DT);
    CHECK(b.transform().position.y == 5.0f);
    CHECK_THROWS(b.set_gravity_scale(INFINITY), hearth::Code::InvalidArgument);
    hearth::MassData d{};
    d.mass = 4.0f;
    d.inertia = hearth::vec3(2, 4, 8);
    b.set_mass_data(d);
    CHECK(b.mass_data().mass == 4.0f && b.mass_data().inertia.z == 8.0f);
    b.apply_linear_impulse(hearth::vec3(2, 0, 0));
    CHECK(b.linear_velocity().x == 0.5f);
    d.mass = 0.0f;
    CHECK_THROWS(b.set_mass_data(d), hearth::Code::InvalidArgument);
    b.reset_mass_data();
    CHECK_NEAR(b.mass(), 2000.0, 1e-2);

    b.set_type(hearth::BodyType::Static);
    CHECK(b.type() == hearth::BodyType::Static && b.mass() == 0.0f);
    CHECK_THROWS(b.set_type(static_cast<hearth::BodyType>(9)), hearth::Code::InvalidArgument);
    b.set_type(hearth::BodyType::Dynamic);
    b.set_gravity_scale(1.0f);
    CHECK(b.is_enabled());
    b.disable();
    CHECK(!b.is_enabled());
    for (int i = 0; i < 30; i++) w.step(DT);
    CHECK(b.transform().position.y == 5.0f);
    b.enable();
    for (int i = 0; i < 240; i++) w.step(DT);
    CHECK_NEAR(b.transform().position.y, 0.25, 0.01);
}

struct DrawCounts {
    int polygons = 0, spheres = 0, segments = 0;
    uint32_t sphere_color = 0;
};

static void test_debug_draw() {
    hearth::World w = make_world(true);
    add_ground(w);
    hearth::Body b = w.create_body(hearth::BodyType::Dynamic, hearth::vec3(0, 3, 0));
    b.add(hearth::sphere(0.5f), hearth::shape_def());
    hearth::Body c = w.create_body(hearth::BodyType::Dynamic, hearth::vec3(3, 3, 0));
    c.add(hearth::box(hearth::vec3(0.5f, 0.5f, 0.5f)), hearth::shape_def());
    DrawCounts n;
    hearth::DebugDraw d = hearth::debug_draw();
    d.user_data = &n;
    d.draw_shapes = 1;
    d.draw_polygon = [](void *u, const HearthVec3 *, uint32_t, uint32_t) { static_cast<DrawCounts *>(u)->polygons++; };
    d.draw_sphere = [](void *u, const HearthVec3 *, float, uint32_t color) {
        static_cast<DrawCounts *>(u)->spheres++;
        static_cast<DrawCounts *>(u)->sphere_color = color;
    };
    d.draw_segment = [](void *u, const HearthVec3 *, const HearthVec3 *, uint32_t) {
        static_cast<DrawCounts *>(u)->segments++;
    };
    w.draw(d);
    CHECK(n.polygons == 7 && n.spheres == 1 && n.segments == 0); // plane patch + six box faces
    CHECK(n.sphere_color == 0xE68C33FFu);
    n = DrawCounts();
    d.draw_shapes = 0;
    d.draw_aabbs = 1;
    w.draw(d);
    CHECK(n.segments == 24 && n.polygons == 0);
    d.draw_aabbs = 3;
    CHECK_THROWS(w.draw(d), hearth::Code::InvalidArgument);
}

// A job system of plain function pointers: each task's ranges are dealt to two std::threads
// (odd and even chunks, last first); finish joins them.
struct ThreadJob {
    hearth::TaskFn task;
    uint32_t count, chunk;
    void *context;
    std::thread threads[2];
};

static void *thread_enqueue(hearth::TaskFn task, uint32_t count, uint32_t min_range, void *context, void *user) {
    ++*static_cast<int *>(user);
    ThreadJob *job = new ThreadJob{task, count, min_range > 0 ? min_range : 1, context, {}};
    for (uint32_t t = 0; t < 2; t++) {
        job->threads[t] = std::thread([job, t] {
            const uint32_t chunks = (job->count + job->chunk - 1) / job->chunk;
            for (uint32_t k = chunks; k-- > 0;) {
                if (k % 2 != t) continue;
                const uint32_t start = k * job->chunk;
                job->task(start, std::min(start + job->chunk, job->count), t, job->context);
            }
        });
    }
    return job;
}

static void thread_finish(void *user_task, void *) {
    ThreadJob *job = static_cast<ThreadJob *>(user_task);
    for (std::thread &t : job->threads) t.join();
    delete job;
}

static uint64_t pile_hash(const hearth::WorldDef &def) {
    hearth::World w(def);
    add_ground(w);
    for (int i = 0; i < 200; i++) {
        const hearth::Vec3 p = hearth::vec3((i % 10) * 1.05f - 5.0f, 0.5f + (i / 10 % 4) * 1.1f, (i / 40) * 1.05f);
        hearth::Body b = w.create_body(hearth::BodyType::Dynamic, p);
        if (i % 2 == 0) b.add(hearth::sphere(0.5f)); else b.add(hearth::box(hearth::vec3(0.5f, 0.5f, 0.5f)));
    }
    const uint64_t before = w.state_hash();
    for (int i = 0; i < 30; i++) w.step(DT);
    CHECK(w.state_hash() != before);
    return w.state_hash();
}

static void test_threads_give_the_same_hash() {
    const uint64_t one = pile_hash(hearth::world_def());
    CHECK(pile_hash(hearth::threaded_world_def(3)) == one);
    int enqueued = 0;
    CHECK(pile_hash(hearth::threaded_world_def(2, thread_enqueue, thread_finish, &enqueued)) == one);
    CHECK(enqueued > 0);
    bool threw = false;
    try {
        hearth::World bad(hearth::threaded_world_def(0));
    } catch (const hearth::Error &e) {
        threw = e.code() == hearth::Code::InvalidArgument && e.message().find("worker_count") != std::string::npos;
    }
    CHECK(threw);
}

static void test_locked_axes() {
    hearth::World w = make_world(false);
    hearth::Body b = w.create_body(hearth::BodyType::Dynamic, hearth::vec3(0, 5, 0));
    b.add(hearth::box(hearth::vec3(0.5f, 0.5f, 0.5f)), hearth::shape_def());
    CHECK(b.locked_axes() == 0u);
    b.set_linear_velocity(hearth::vec3(1, 2, 3));
    b.set_locked_axes(HEARTH_LOCK_LINEAR_Y | HEARTH_LOCK_ANGULAR);
    CHECK(b.locked_axes() == (HEARTH_LOCK_LINEAR_Y | HEARTH_LOCK_ANGULAR));
    CHECK(b.linear_velocity().y == 0.0f && b.linear_velocity().x == 1.0f);
    b.apply_angular_impulse(hearth::vec3(5, 5, 5));
    for (int i = 0; i < 30; i++) w.step(DT);
    // Locked in y: it floats; locked in rotation: it never turns.
    CHECK(b.transform().position.y == 5.0f);
    CHECK(b.angular_velocity().x == 0.0f && b.angular_velocity().y == 0.0f && b.angular_velocity().z == 0.0f);
    CHECK_THROWS(b.set_locked_axes(64u), hearth::Code::InvalidArgument);
    CHECK(b.locked_axes() == (HEARTH_LOCK_LINEAR_Y | HEARTH_LOCK_ANGULAR));
}

static void run_throwing_tests() {
    test_events_and_step_callbacks();
    test_box_rests_on_plane();
    test_errors_as_exceptions();
    test_rolling_resistance_and_torsional_friction();
    test_runtime_setters();
    test_locked_axes();
    test_debug_draw();
    test_move_semantics();
    test_lambda_force_hovers();
    test_lambda_exception_rethrown_by_step();
    test_lambda_contact_floor();
    test_bulk_equals_single_reads();
    test_joints();
    test_particles();
    test_soft_bodies();
    test_soft_body_settings();
    test_builtin_generators();
    test_recording();
    test_recording_start_failure();
    test_snapshots();
    test_geometry();
    test_queries_and_filters();
    test_threads_give_the_same_hash();
}
#endif // HEARTH_CPP_EXCEPTIONS

// ======================================================================= the nothrow API

namespace nt = hearth::nothrow;

static void test_nothrow_results() {
    static_assert(std::is_same<decltype(std::declval<nt::Body>().mass()), hearth::Result<float>>::value,
                  "nothrow calls return Result");
    hearth::WorldDef def = hearth::world_def();
    def.enable_sleep = 1;
    hearth::Result<nt::World> created = nt::World::create(def);
    CHECK_OK(created);
    nt::World w = std::move(created).value();
    CHECK(static_cast<bool>(w));

    def.substeps = 1000;
    CHECK_CODE(nt::World::create(def), hearth::Code::InvalidArgument);

    nt::Body ground = w.create_body(hearth::BodyType::Static).value();
    CHECK_OK(ground.add(hearth::plane(hearth::vec3(0, 1, 0), 0.0f)));
    hearth::Result<nt::Body> made = w.create_body(hearth::BodyType::Dynamic, hearth::vec3(0, 2, 0));
    CHECK_OK(made);
    nt::Body box = *made;
    CHECK_OK(box.add(hearth::box(hearth::vec3(0.5f, 0.5f, 0.5f))));
    for (int i = 0; i < 240; i++) {
        if (!w.step(DT)) {
            CHECK(false);
            break;
        }
    }
    CHECK_NEAR(box.position().value().y, 0.5, 0.005);

    // Every error kind as a Result, the world unchanged.
    const hearth::Transform before = box.transform().value();
    hearth::Transform bad = before;
    bad.rotation = hearth::Quat{0, 0, 0, 0};
    CHECK_CODE(box.set_transform(bad), hearth::Code::InvalidArgument);
    CHECK_CODE(box.apply_force(hearth::vec3(0, NaN, 0)), hearth::Code::InvalidArgument);
    CHECK_CODE(w.step(NaN), hearth::Code::InvalidArgument);
    CHECK(same_transform(box.transform().value(), before));
    nt::Body gone = w.create_body(hearth::BodyType::Dynamic).value();
    CHECK_OK(gone.destroy());
    CHECK_CODE(gone.transform(), hearth::Code::InvalidId);
    CHECK(gone.mass().value_or(-1.0f) == -1.0f);
    CHECK_CODE(nt::Body().mass(), hearth::Code::NullPointer);
    std::vector<hearth::BodyId> ids{box.id(), gone.id()};
    std::vector<hearth::Transform> out(2);
    CHECK_CODE(w.transforms(ids, out), hearth::Code::InvalidId);
    CHECK(w.counters().value().body_count == 2);

    // Move: the moved-from world is empty and says so.
    nt::World moved(std::move(w));
    CHECK_CODE(w.step(DT), hearth::Code::NullPointer);
    CHECK_OK(moved.step(DT));
    nt::World empty;
    CHECK_CODE(empty.add_force_generator([](nt::ForceContext &) {}), hearth::Code::NullPointer);
}

static void test_nothrow_recording() {
    nt::World w = nt::World::create().value();
    size_t total = 0;
    CHECK_OK(w.record_to([&](const uint8_t *, size_t len) {
        total += len;
        return true;
    }));
    CHECK(total > 16);
    CHECK_OK(w.step(DT));
    CHECK(w.record_to_file("x.hrec").code() == hearth::Code::InvalidArgument); // already recording
    CHECK_OK(w.stop_recording());
    CHECK(w.stop_recording().code() == hearth::Code::InvalidArgument);
    CHECK(w.record_to([](const uint8_t *, size_t) { return false; }).code() == hearth::Code::Io);
    nt::World empty;
    CHECK(empty.record_to([](const uint8_t *, size_t) { return true; }).code() == hearth::Code::NullPointer);
    CHECK(empty.record_to_file("x.hrec").code() == hearth::Code::NullPointer);
}

static void test_nothrow_lambdas() {
    hearth::WorldDef def = hearth::world_def();
    def.enable_sleep = 0;
    nt::World w = nt::World::create(def).value();
    nt::Body b = w.create_body(hearth::BodyType::Dynamic, hearth::vec3(0, 5, 0)).value();
    CHECK_OK(b.add(hearth::sphere(0.25f)));
    // A hovering body: the lambda reads and applies through Results and returns a Status.
    hearth::Result<nt::Generator> lift = w.add_force_generator([](nt::ForceContext &ctx) -> hearth::Status {
        for (nt::Body body : ctx.bodies()) {
            const hearth::Result<float> m = body.mass();
            if (!m) {
                return hearth::Status(m.code(), m.message());
            }
            hearth::Status s = body.apply_force(hearth::vec3(0, 9.81f * *m, 0));
            if (!s) {
                return s;
            }
        }
        return hearth::Status();
    });
    CHECK_OK(lift);
    CHECK_OK(lift->attach(b));
    for (int i = 0; i < 60; i++) {
        CHECK_OK(w.step(DT));
    }
    CHECK_NEAR(b.position().value().y, 5.0, 1e-3);
    // A structural change from the lambda fails with WORLD_LOCKED; the lambda passes the
    // Status on and step() returns it (once).
    int calls = 0;
    hearth::Result<nt::Generator> bad = w.add_force_generator([&](nt::ForceContext &ctx) -> hearth::Status {
        calls++;
        hearth::Result<nt::Body> nb = ctx.world().create_body(hearth::body_def());
        return nb ? hearth::Status() : hearth::Status(nb.code(), nb.message());
    });
    CHECK_OK(bad);
    CHECK_CODE(w.step(DT), hearth::Code::WorldLocked);
    CHECK(calls == 1);
    CHECK_OK(w.destroy_generator(*bad));
    CHECK_OK(w.step(DT));
    CHECK(w.lambda_count() == 1);
    // Contact lambda in the nothrow API: a floor at y = 1.
    nt::Body ball = w.create_body(hearth::BodyType::Dynamic, hearth::vec3(3, 3, 0)).value();
    CHECK_OK(ball.add(hearth::sphere(0.25f)));
    hearth::Result<nt::Generator> floor = w.add_contact_generator([ball](nt::ContactContext &ctx) {
        const hearth::Vec3 p = ball.position().value_or(hearth::vec3(0, 0, 0));
        hearth::GeneratedContact c{};
        c.body_b = ball.id();
        c.point = hearth::vec3(p.x, 1, p.z);
        c.normal = hearth::vec3(0, 1, 0);
        c.penetration = 1.25f - p.y;
        return ctx.add(c);
    });
    CHECK_OK(floor);
    for (int i = 0; i < 120; i++) {
        CHECK_OK(w.step(DT));
    }
    CHECK_NEAR(ball.position().value().y, 1.25, 0.01);
#if HEARTH_CPP_EXCEPTIONS
    // With exceptions compiled in, a throwing lambda in the nothrow API becomes a Status.
    w.add_force_generator([](nt::ForceContext &) { throw std::runtime_error("nothrow boom"); }).value();
    const hearth::Status s = w.step(DT);
    CHECK(s.code() == hearth::Code::CallbackException && s.message() == "nothrow boom");
#endif
}

static void test_nothrow_handles() {
    nt::World w = nt::World::create().value();
    nt::Body a = w.create_body(hearth::BodyType::Dynamic, hearth::vec3(0, 5, 0)).value();
    CHECK_OK(a.add(hearth::sphere(0.2f)));
    hearth::BallJointDef bd = hearth::ball_joint_def();
    bd.base.body_a = a.id();
    bd.base.frame_b = hearth::transform(hearth::vec3(0, 6, 0));
    bd.base.frame_a = hearth::transform(hearth::vec3(0, 1, 0));
    hearth::Result<nt::Joint> j = w.create_joint(bd);
    CHECK_OK(j);
    CHECK_OK(j->set_cone_limit(true, 0.5f));
    CHECK(j->cone_limit().value().enabled && j->cone_limit().value().angle == 0.5f);
    CHECK_CODE(j->motor(), hearth::Code::InvalidArgument); // a ball joint has no motor
    hearth::ParticleDef pd = hearth::particle_def();
    pd.position = hearth::vec3(1, 1, 1);
    hearth::Result<nt::Particle> p = w.create_particle(pd);
    CHECK_OK(p);
    pd.radius = -1.0f;
    CHECK_CODE(w.create_particle(pd), hearth::Code::InvalidArgument);
    CHECK(w.particle_count().value() == 1);
    // Shared geometry as Results.
    const hearth::Vec3 tet[4] = {hearth::vec3(0, 0, 0), hearth::vec3(1, 0, 0), hearth::vec3(0, 1, 0),
                                 hearth::vec3(0, 0, 1)};
    hearth::Result<nt::Hull> hull = w.create_hull(tet);
    CHECK_OK(hull);
    CHECK(hull->vertex_count().value() == 4);
    CHECK_OK(a.add(hull->shape(0.5f)));
    CHECK_CODE(hull->destroy(), hearth::Code::InvalidArgument);
    const uint32_t tri[3] = {0, 2, 1};
    hearth::Result<nt::Mesh> mesh = w.create_mesh(tet, tri);
    CHECK_OK(mesh);
    CHECK(mesh->degenerate_count().value() == 0);
    CHECK_CODE(a.add(mesh->shape()), hearth::Code::InvalidArgument); // a dynamic body
    CHECK_OK(mesh->destroy());
    CHECK_CODE(mesh->triangle_count(), hearth::Code::InvalidId);
    const float h4[4] = {0, 0, 0, 0};
    const uint8_t bad_hole[1] = {2};
    CHECK_CODE(w.create_heightfield(2, 2, h4, bad_hole), hearth::Code::InvalidArgument);
    hearth::Result<nt::Heightfield> hf = w.create_heightfield(2, 2, h4);
    CHECK_OK(hf);
    CHECK_OK(hf->destroy());
    CHECK_CODE(hf->destroy(), hearth::Code::InvalidId);
    hearth::Result<nt::SoftBody> s = w.create_soft_box(hearth::soft_body_def(), hearth::vec3(0.5f, 0.5f, 0.5f), 2, 2, 2);
    CHECK_OK(s);
    CHECK(s->vertex_count().value() == 27);
    CHECK_CODE(w.create_soft_icosphere(hearth::soft_body_def(), 1.0f, 7), hearth::Code::InvalidArgument);
    // Soft-body settings as Results.
    hearth::SoftBodyDef sd = hearth::soft_body_def();
    sd.deformation_damping = 0.5f;
    sd.iterations = 3;
    CHECK_OK(s->set_pressure(5.0f));
    hearth::Result<hearth::SoftBodySettings> got = s->settings();
    CHECK_OK(got);
    hearth::SoftBodySettings expected = settings_of(hearth::soft_body_def());
    expected.pressure = 5.0f;
    CHECK(got.ok() && same_settings(*got, expected));
    hearth::SoftBodySettings want = settings_of(sd);
    CHECK_OK(s->set_settings(want));
    CHECK(same_settings(s->settings().value(), want));
    CHECK_OK(s->set_compliance(0.01f, 0.02f, 0.03f));
    const hearth::SoftBodySettings after = s->settings().value();
    CHECK(after.edge_compliance == 0.01f && after.bend_compliance == 0.02f && after.volume_compliance == 0.03f);
    hearth::SoftBodySettings bad = after;
    bad.iterations = 17;
    CHECK_CODE(s->set_settings(bad), hearth::Code::InvalidArgument);
    bad = after;
    bad.friction = NaN;
    CHECK_CODE(s->set_settings(bad), hearth::Code::InvalidArgument);
    CHECK_CODE(s->set_compliance(0.0f, NaN, 0.0f), hearth::Code::InvalidArgument);
    CHECK_CODE(s->set_compliance(0.0f, 0.0f, -1.0f), hearth::Code::InvalidArgument);
    CHECK(same_settings(s->settings().value(), after));
    CHECK_OK(s->destroy());
    CHECK_CODE(s->settings(), hearth::Code::InvalidId);
    CHECK_CODE(s->set_settings(after), hearth::Code::InvalidId);
    CHECK_CODE(s->set_compliance(0.0f, 0.0f, 0.0f), hearth::Code::InvalidId);
    CHECK(hearth::version_matches());
    CHECK(hearth::version() == HEARTH_VERSION);
}

int main(int argc, char **argv) {
    g_program = argc > 0 ? argv[0] : "test_hearth";
#if HEARTH_CPP_EXCEPTIONS
    run_throwing_tests();
    const char *mode = "exceptions";
#else
    const char *mode = "no exceptions";
#endif
    test_nothrow_results();
    test_nothrow_lambdas();
    test_nothrow_handles();
    test_nothrow_recording();
    std::printf("test_hearth (%s): %d passed, %d failed\n", mode, g_passed, g_failed);
    return g_failed == 0 ? 0 : 1;
}
