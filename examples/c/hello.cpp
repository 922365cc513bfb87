// The C API from C++: RAII handles over libhaphe, one inside query and a short tick loop.
//
//   c++ -std=c++17 -O2 examples/c/hello.cpp -Icrates/haphe-c/include -Ltarget/release -lhaphe -o hello-cpp
//   LD_LIBRARY_PATH=target/release ./hello-cpp meshes/models/spot.obj
#include <cstdio>
#include <memory>
#include <stdexcept>
#include <string>

#include "haphe.h"

namespace {

void check(HapheStatus status, const char *what) {
    if (status != HAPHE_STATUS_OK) {
        throw std::runtime_error(std::string(what) + ": " + haphe_last_error());
    }
}

struct ShapeFree { void operator()(HapheShape *s) const { haphe_shape_free(s); } };
struct SceneFree { void operator()(HapheScene *s) const { haphe_scene_free(s); } };
struct ProxyFree { void operator()(HapheProxy *p) const { haphe_proxy_free(p); } };

}  // namespace

int main(int argc, char **argv) try {
    if (argc < 2) {
        std::fprintf(stderr, "usage: %s MESH\n", argv[0]);
        return 2;
    }
    HapheShape *raw_shape = nullptr;
    check(haphe_shape_from_file(argv[1], 1.0, &raw_shape), "load");
    std::unique_ptr<HapheShape, ShapeFree> shape(raw_shape);

    const double centre[3] = {0.0, 0.0, 0.0};
    uint8_t inside = 0;
    check(haphe_shape_inside(shape.get(), centre, 1, 0, &inside), "inside");
    std::printf("origin inside: %d\n", inside);

    HapheScene *raw_scene = nullptr;
    check(haphe_scene_new(1, &raw_scene), "scene");
    std::unique_ptr<HapheScene, SceneFree> scene(raw_scene);
    check(haphe_scene_add(scene.get(), shape.get(), nullptr, nullptr, nullptr, nullptr), "add");

    const double start[3] = {0.0, 2.0, 0.0};
    HapheProxy *raw_proxy = nullptr;
    // The tool: a ball of 2 cm radius, its centre the proxy (0 would be a point).
    const double tool_radius = 0.02;
    check(haphe_proxy_new(start, haphe_default_max_force(), tool_radius, &raw_proxy), "proxy");
    std::unique_ptr<HapheProxy, ProxyFree> proxy(raw_proxy);
    HapheTick tick{};
    int touching = 0;
    for (int k = 0; k <= 2000; k++) {
        const double hip[3] = {0.0, 2.0 - 2.0 * k / 2000.0, 0.0};
        check(haphe_proxy_tick(proxy.get(), scene.get(), hip, nullptr, &tick), "tick");
        touching += tick.in_contact;
    }
    std::printf("pressed down a %.0f mm ball: %d ticks in contact, force (%.3f, %.3f, %.3f) N, proxy y %.4f m\n",
                tool_radius * 1e3, touching, tick.force[0], tick.force[1], tick.force[2], tick.proxy[1]);
    return touching > 0 ? 0 : 1;
} catch (const std::exception &e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 1;
}
