// A small consumer of an installed Hearth: a sphere and a box dropped on the ground must come
// to rest at their analytic heights. Exits 0 and prints "consumer: OK ..." when they do.
#include <hearth.hpp>

#include <cmath>
#include <cstdio>

int main() {
    try {
        if (!hearth::version_matches()) {
            std::fprintf(stderr, "consumer: header %u and library %u differ\n", (unsigned)HEARTH_VERSION,
                         (unsigned)hearth::version());
            return 1;
        }
        hearth::World world(hearth::world_def());
        world.create_body(hearth::BodyType::Static).add(hearth::plane(hearth::vec3(0, 1, 0), 0.0f));
        hearth::Body ball = world.create_body(hearth::BodyType::Dynamic, hearth::vec3(-1, 3, 0));
        ball.add(hearth::sphere(0.4f));
        hearth::Body box = world.create_body(hearth::BodyType::Dynamic, hearth::vec3(1, 2, 0));
        box.add(hearth::box(hearth::vec3(0.3f, 0.3f, 0.3f)));
        for (int i = 0; i < 180; i++) {
            world.step(1.0f / 60.0f);
        }
        const float yb = ball.position().y, yx = box.position().y;
        std::printf("consumer: Hearth %u.%u.%u, sphere at y = %.3f m (0.4), box at y = %.3f m (0.3)\n",
                    (unsigned)HEARTH_VERSION_MAJOR, (unsigned)HEARTH_VERSION_MINOR,
                    (unsigned)HEARTH_VERSION_PATCH, (double)yb, (double)yx);
        if (std::fabs(yb - 0.4f) > 0.01f || std::fabs(yx - 0.3f) > 0.01f) {
            std::fprintf(stderr, "consumer: FAILED, bodies not at rest heights\n");
            return 1;
        }
    } catch (const hearth::Error &e) {
        std::fprintf(stderr, "consumer: %s\n", e.what());
        return 1;
    }
    std::printf("consumer: OK\n");
    return 0;
}
