/* A small C program over libhaphe: load a mesh, ask inside and first-crossing queries,
 * tick a proxy 100 000 times against a scene with a texture and force effects, then run
 * the servo loop with the simulated hand and a callback.
 *
 *   cargo build --release -p haphe-c
 *   cc -std=c11 -O2 examples/c/hello.c -Icrates/haphe-c/include -Ltarget/release -lhaphe -lm -o hello
 *   LD_LIBRARY_PATH=target/release ./hello meshes/models/spot.obj
 *
 * Built with -DHAPHE_COUNT_ALLOCATIONS against a library built with
 * `--features count-allocations`, it also checks that the tick loop and the servo's ticks
 * allocate nothing. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "haphe.h"

#define CHECK(call)                                                                    \
    do {                                                                               \
        HapheStatus status_ = (call);                                                  \
        if (status_ != HAPHE_STATUS_OK) {                                              \
            fprintf(stderr, "%s failed (%d): %s\n", #call, (int)status_, haphe_last_error()); \
            return 1;                                                                  \
        }                                                                              \
    } while (0)

/* What the servo's callback keeps: the largest force, and the library's allocation count
 * at the first and the last tick. */
typedef struct {
    double most;
    uint64_t first, last;
} Seen;

static void on_tick(const HapheTickRecord *record, void *user) {
    Seen *seen = (Seen *)user;
    double f = sqrt(record->force[0] * record->force[0] + record->force[1] * record->force[1] +
                    record->force[2] * record->force[2]);
    if (f > seen->most) seen->most = f;
#ifdef HAPHE_COUNT_ALLOCATIONS
    seen->last = haphe_allocations();
    if (record->tick == 0) seen->first = seen->last;
#endif
}

int main(int argc, char **argv) {
    if (argc < 2) {
        fprintf(stderr, "usage: %s MESH\n", argv[0]);
        return 2;
    }
    HapheShape *shape = NULL;
    CHECK(haphe_shape_from_file(argv[1], 1.0, &shape));
    printf("%s: %zu triangles\n", argv[1], haphe_shape_triangle_count(shape));

    /* A bad file: the status and the message naming it. */
    HapheShape *none = NULL;
    if (haphe_shape_from_file("no-such-file.obj", 1.0, &none) != HAPHE_STATUS_IO) return 1;
    printf("expected error: %s\n", haphe_last_error());

    /* Inside: the points of a line through the model's middle. */
    enum { N = 9 };
    double points[N][3], ends[N][3];
    uint8_t inside[N];
    HapheCrossing hits[N];
    for (int i = 0; i < N; i++) {
        points[i][0] = -1.0 + 2.0 * i / (N - 1);
        points[i][1] = 0.0;
        points[i][2] = 0.0;
        ends[i][0] = points[i][0];
        ends[i][1] = 5.0;
        ends[i][2] = 0.0;
    }
    CHECK(haphe_shape_inside(shape, &points[0][0], N, 0, inside));
    CHECK(haphe_shape_first_crossing(shape, &points[0][0], &ends[0][0], N, 0, hits));
    for (int i = 0; i < N; i++) {
        printf("x=%+.2f inside=%d crossing: triangle %lld at t=%.4f\n", points[i][0], inside[i],
               (long long)hits[i].triangle, hits[i].t);
    }

    /* A scene and a proxy pressed down onto the model from above, circling. */
    HapheScene *scene = NULL;
    CHECK(haphe_scene_new(4, &scene));
    HapheMaterial material = {800.0, 0.0, 0.3, 0.2};
    uint32_t id = 0;
    CHECK(haphe_scene_add(scene, shape, NULL, NULL, &material, &id));
    haphe_shape_free(shape); /* the scene keeps its own reference */
    /* Bumps 0.2 mm high every 2 mm on the surface; a drag of 2 N·s/m and a 150 Hz buzz in
     * contact, rendered by the servo loop (haphe_run). A bad specification is refused
     * naming it. */
    CHECK(haphe_scene_set_texture(scene, id, "sine:0.0002:0.002"));
    CHECK(haphe_scene_add_effect(scene, "viscosity:2"));
    CHECK(haphe_scene_add_effect(scene, "vibration:150:0.3"));
    if (haphe_scene_add_effect(scene, "viscosity:-2") != HAPHE_STATUS_INVALID_ARGUMENT) return 1;
    printf("expected error: %s\n", haphe_last_error());
    double top[3] = {0.0, 2.0, 0.0};
    HapheProxy *proxy = NULL;
    /* A point tool (radius 0); a radius in metres makes it a sphere. */
    CHECK(haphe_proxy_new(top, haphe_default_max_force(), 0.0, &proxy));
    HapheTick tick;
    CHECK(haphe_proxy_tick(proxy, scene, top, NULL, &tick));
#ifdef HAPHE_COUNT_ALLOCATIONS
    uint64_t before = haphe_allocations();
#endif
    long touching = 0;
    for (int k = 0; k < 100000; k++) {
        double a = k * 1e-3;
        double hip[3] = {0.2 * cos(a), 0.3 * sin(3 * a), 0.2 * sin(a)};
        CHECK(haphe_proxy_tick(proxy, scene, hip, NULL, &tick));
        touching += tick.in_contact;
    }
#ifdef HAPHE_COUNT_ALLOCATIONS
    uint64_t allocations = haphe_allocations() - before;
    printf("allocations in 100000 ticks: %llu\n", (unsigned long long)allocations);
    if (allocations != 0) return 1;
#endif
    printf("100000 ticks, %ld in contact, last force (%.3f, %.3f, %.3f) N\n", touching,
           tick.force[0], tick.force[1], tick.force[2]);
    if (touching == 0) return 1;

    /* The servo loop with the simulated hand, 1 s at 1 kHz. */
    Seen seen = {0.0, 0, 0};
    uint64_t ticks = 0;
    CHECK(haphe_run(scene, "hand", "press", 1.0, 1000.0, on_tick, &seen, &ticks));
    printf("servo: %llu ticks, largest force %.3f N\n", (unsigned long long)ticks, seen.most);
    if (ticks != 1000 || seen.most <= 0.0 || seen.most > haphe_default_max_force() + 1e-9)
        return 1;
#ifdef HAPHE_COUNT_ALLOCATIONS
    printf("allocations in the servo's ticks 1 to 999: %llu\n",
           (unsigned long long)(seen.last - seen.first));
    if (seen.last - seen.first != 0) return 1;
#endif

    haphe_proxy_free(proxy);
    haphe_scene_free(scene);
    return 0;
}
