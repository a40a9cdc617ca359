/*
 * pyramid.cpp - the scene of examples/c/pyramid.c written with the C++ wrapper
 * (bindings/cpp/hearth.hpp), printing the same text (only the language name differs).
 *
 * Builds a pyramid of unit boxes on a ground plane, drops a "pile" of 60 alternating spheres
 * and boxes onto it from a grid above, and steps 30 s at 60 Hz. Every three seconds it prints
 * the time, the height of the pyramid's top box and how many bodies are awake. By the end
 * every body sleeps; it exits with status 1 if one does not.
 *
 * Build and run from the repository root, after `cargo build --release`:
 *   c++ -std=c++17 -Wall -Wextra -O2 -Iinclude -Ibindings/cpp examples/cpp/pyramid.cpp \
 *       -Ltarget/release -lhearth -Wl,-rpath,$PWD/target/release -o pyramid_cpp && ./pyramid_cpp
 */
#include "hearth.hpp"

#include <cinttypes>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <vector>

namespace {

const int BASE = 5;           // boxes per side in the bottom layer: 25+16+9+4+1 = 55 boxes
const int PYRAMID_BOXES = 55;
const int PILE_BODIES = 60;   // alternating spheres (r = 0.5) and unit boxes
const int PILE_ROW = 8;       // the pile starts as an 8 x 8 grid (60 of its 64 cells used)
const float DT = 1.0f / 60.0f;
const int STEPS = 1800;       // 30 s
const int REPORT_EVERY = 180;

hearth::Body add_box(hearth::World &world, hearth::Vec3 p) {
    hearth::Body body = world.create_body(hearth::BodyType::Dynamic, p);
    body.add(hearth::box(hearth::vec3(0.5f, 0.5f, 0.5f)));
    return body;
}

// FNV-1a over the bits of every body's position, rotation, linear and angular velocity (13
// floats), folded into `h`: the "state hash" column, as in pyramid.c.
std::uint64_t hash_state(std::uint64_t h, hearth::World &world, const std::vector<hearth::BodyId> &bodies,
                         std::vector<hearth::Transform> &transforms) {
    world.transforms(bodies, transforms);
    for (std::size_t b = 0; b < bodies.size(); b++) {
        const auto body = world.body(bodies[b]);
        const hearth::Transform &x = transforms[b];
        const hearth::Vec3 v = body.linear_velocity(), w = body.angular_velocity();
        for (float f : {x.position.x, x.position.y, x.position.z, x.rotation.x, x.rotation.y, x.rotation.z,
                        x.rotation.w, v.x, v.y, v.z, w.x, w.y, w.z}) {
            std::uint32_t bits;
            std::memcpy(&bits, &f, sizeof bits);
            h = (h ^ bits) * 0x100000001b3ull;
        }
    }
    return h;
}

hearth::Body add_sphere(hearth::World &world, hearth::Vec3 p) {
    hearth::Body body = world.create_body(hearth::BodyType::Dynamic, p);
    body.add(hearth::sphere(0.5f));
    return body;
}

/// Runs the scene; returns how many bodies are awake at the end.
int run() {
    if (!hearth::version_matches()) {
        throw std::runtime_error("the library's version is not the header's");
    }
    hearth::World world(hearth::world_def()); // destroyed with everything in it, also on errors
    world.create_body(hearth::BodyType::Static).add(hearth::plane(hearth::vec3(0, 1, 0), 0.0f));

    std::vector<hearth::BodyId> bodies; // ids, for the one-call bulk read
    // Pyramid: layer L has (BASE - L)^2 boxes, centred on the y axis; the last is the top.
    for (int layer = 0; layer < BASE; layer++) {
        const int n = BASE - layer;
        const float offset = -0.5f * (float)(n - 1);
        for (int i = 0; i < n; i++) {
            for (int k = 0; k < n; k++) {
                bodies.push_back(add_box(world, hearth::vec3(offset + (float)i, 0.5f + (float)layer, offset + (float)k)).id());
            }
        }
    }
    const size_t top = bodies.size() - 1;
    // Pile: a grid 1.5 m apart, 10 m up, centred over the pyramid.
    for (int j = 0; j < PILE_BODIES; j++) {
        const hearth::Vec3 p = hearth::vec3(-5.25f + 1.5f * (float)(j % PILE_ROW), 10.0f,
                                            -5.25f + 1.5f * (float)(j / PILE_ROW));
        bodies.push_back((j % 2 == 0 ? add_sphere(world, p) : add_box(world, p)).id());
    }

    std::printf("Hearth %u.%u.%u C++ example: pyramid of %d boxes (base %d) + pile of %d spheres/boxes\n",
                (unsigned)HEARTH_VERSION_MAJOR, (unsigned)HEARTH_VERSION_MINOR, (unsigned)HEARTH_VERSION_PATCH,
                PYRAMID_BOXES, BASE, PILE_BODIES);
    std::printf("%8s %14s %16s %8s\n", "t [s]", "top box y [m]", "state hash", "awake");
    std::uint64_t hash = 0xcbf29ce484222325ull;

    std::vector<hearth::Transform> transforms(bodies.size()); // filled in one call per report
    int awake = (int)bodies.size();
    for (int step = 1; step <= STEPS; step++) {
        world.step(DT);
        hash = hash_state(hash, world, bodies, transforms); // after every step
        if (step % REPORT_EVERY != 0) {
            continue;
        }
        world.transforms(bodies, transforms);
        awake = 0;
        for (const hearth::BodyId id : bodies) {
            awake += world.body(id).is_awake() ? 1 : 0;
        }
        const double t = (double)((float)step * DT);
        std::printf("%8.2f %14.3f %016" PRIx64 " %4d/%d\n", t, (double)transforms[top].position.y, hash, awake,
                    (int)bodies.size());
    }
    return awake;
}

} // namespace

int main() {
    int awake = 0;
    try {
        awake = run();
    } catch (const hearth::Error &e) {
        std::fprintf(stderr, "error: %s\n", e.what()); // "HEARTH_ERROR_...: message"
        return 1;
    } catch (const std::exception &e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 1;
    }
    if (awake != 0) {
        std::fprintf(stderr, "error: %d bodies still awake after %d steps\n", awake, STEPS);
        return 1;
    }
    std::printf("done\n");
    return 0;
}
