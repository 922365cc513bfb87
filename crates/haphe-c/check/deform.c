/* Deformation through the C API: a sphere read from MESH (the repository's unit sphere,
 * scaled to 5 cm) is placed twice in a scene sharing one shape; its arrays come out in the
 * surface's order, a grown copy of them deforms the first object (a point between the two
 * radii is then inside it, the other object and the caller's shape unchanged), a subset
 * moves only the vertices named, a proxy pressing on the sphere while it breathes every
 * tick is never inside the current surface, and bad input is refused naming the row
 * (NaN, wrong count, index out of range, unknown object) with the scene unchanged. Prints
 * what it checked; exits 1 on the first surprise.
 *
 *   cc -std=c11 -Wall -Wextra -Werror crates/haphe-c/check/deform.c \
 *       -Icrates/haphe-c/include -Ltarget/debug -lhaphe -lm -o deform
 *   LD_LIBRARY_PATH=target/debug ./deform meshes/models/sphere.ply */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "haphe.h"

static const double RADIUS = 0.05;
static const double PI = 3.14159265358979323846;

#define CHECK(cond, ...)                                                                   \
    do {                                                                                   \
        if (!(cond)) {                                                                     \
            fprintf(stderr, "%s:%d: ", __FILE__, __LINE__);                                \
            fprintf(stderr, __VA_ARGS__);                                                  \
            fprintf(stderr, "\n");                                                         \
            exit(1);                                                                       \
        }                                                                                  \
    } while (0)

#define OK(call) CHECK((call) == HAPHE_STATUS_OK, "%s: %s", #call, haphe_last_error())

/* The version of object `id`'s shape now. */
static uint64_t version_of(HapheScene *scene, uint32_t id) {
    HapheShape *now = NULL;
    OK(haphe_scene_shape(scene, id, &now));
    uint64_t v = haphe_shape_version(now);
    haphe_shape_free(now);
    return v;
}

/* Whether `p` is inside object `id`'s shape now. */
static int inside_now(HapheScene *scene, uint32_t id, const double p[3]) {
    HapheShape *now = NULL;
    uint8_t in = 2;
    OK(haphe_scene_shape(scene, id, &now));
    OK(haphe_shape_inside(now, p, 1, 0, &in));
    haphe_shape_free(now);
    return in;
}

/* A refused call: the status, a message starting with `prefix`, the scene unchanged. */
static void refused(HapheStatus status, const char *prefix, HapheScene *scene, uint32_t id,
                    uint64_t version) {
    CHECK(status == HAPHE_STATUS_INVALID_ARGUMENT, "status %d for \"%s\"", (int)status, prefix);
    CHECK(strncmp(haphe_last_error(), prefix, strlen(prefix)) == 0,
          "message \"%s\", expected \"%s...\"", haphe_last_error(), prefix);
    CHECK(version_of(scene, id) == version, "a refused deformation changed the scene");
    printf("refused: %s\n", haphe_last_error());
}

int main(int argc, char **argv) {
    if (argc != 2) {
        fprintf(stderr, "usage: %s MESH\n", argv[0]);
        return 2;
    }
    HapheShape *shape = NULL;
    OK(haphe_shape_from_file(argv[1], RADIUS, &shape));
    size_t n = haphe_shape_vertex_count(shape), m = haphe_shape_triangle_count(shape);
    CHECK(n > 100 && m > 100, "%zu vertices, %zu triangles", n, m);
    double *rest = malloc(3 * n * sizeof(double)), *xyz = malloc(3 * n * sizeof(double));
    uint32_t *faces = malloc(3 * m * sizeof(uint32_t));
    CHECK(rest && xyz && faces, "out of memory");
    CHECK(haphe_shape_arrays(shape, rest, n - 1, faces, m) == HAPHE_STATUS_INVALID_ARGUMENT &&
              strstr(haphe_last_error(), "vertex_count") != NULL,
          "a wrong vertex count accepted: %s", haphe_last_error());
    OK(haphe_shape_arrays(shape, rest, n, faces, m));
    for (size_t i = 0; i < n; i++) {
        double r = sqrt(rest[3 * i] * rest[3 * i] + rest[3 * i + 1] * rest[3 * i + 1] +
                        rest[3 * i + 2] * rest[3 * i + 2]);
        CHECK(fabs(r - RADIUS) < 1e-6, "vertex %zu at radius %g", i, r);
    }
    for (size_t i = 0; i < 3 * m; i++) CHECK(faces[i] < n, "face index %u", faces[i]);

    HapheScene *scene = NULL;
    uint32_t a = 0, b = 0;
    OK(haphe_scene_new(4, &scene));
    OK(haphe_scene_add(scene, shape, NULL, NULL, NULL, &a));
    double far[3] = {1.0, 0.0, 0.0};
    OK(haphe_scene_add(scene, shape, far, NULL, NULL, &b));

    /* Grown by 10 %: a point between the two radii is inside the deformed object only. */
    const double between[3] = {0.0, 0.0, 1.05 * RADIUS};
    CHECK(!inside_now(scene, a, between), "inside before the deformation");
    for (size_t i = 0; i < 3 * n; i++) xyz[i] = 1.1 * rest[i];
    OK(haphe_scene_deform(scene, a, xyz, n));
    CHECK(version_of(scene, a) == 1 && version_of(scene, b) == 0, "versions");
    CHECK(inside_now(scene, a, between), "not inside the grown sphere");
    CHECK(!inside_now(scene, b, between), "the other object changed");
    uint8_t in = 2;
    OK(haphe_shape_inside(shape, between, 1, 0, &in));
    CHECK(in == 0 && haphe_shape_version(shape) == 0, "the caller's shape changed");
    printf("deformed: version 1, the point at 1.05 r inside; the shared shape unchanged\n");

    /* A subset: vertices 0 and 5 to half their rest position, the others as they were. */
    uint32_t two[2] = {0, 5};
    double half[6];
    for (int k = 0; k < 3; k++) {
        half[k] = 0.5 * rest[k];
        half[3 + k] = 0.5 * rest[15 + k];
    }
    OK(haphe_scene_deform_at(scene, a, two, half, 2));
    HapheShape *now = NULL;
    OK(haphe_scene_shape(scene, a, &now));
    OK(haphe_shape_arrays(now, xyz, n, NULL, 0));
    haphe_shape_free(now);
    for (size_t i = 0; i < n; i++)
        for (int k = 0; k < 3; k++) {
            double expected = (i == 0 || i == 5) ? 0.5 * rest[3 * i + k] : 1.1 * rest[3 * i + k];
            CHECK(xyz[3 * i + k] == expected, "vertex %zu: %g, expected %g", i, xyz[3 * i + k],
                  expected);
        }
    printf("subset: only vertices 0 and 5 moved\n");

    /* Bad input, each refused naming the argument and the row, the scene unchanged. */
    for (size_t i = 0; i < 3 * n; i++) xyz[i] = rest[i];
    xyz[3 * 17 + 1] = NAN;
    refused(haphe_scene_deform(scene, a, xyz, n), "xyz: row 17: a coordinate", scene, a, 2);
    xyz[3 * 17 + 1] = rest[3 * 17 + 1];
    xyz[3 * (n - 1)] = INFINITY;
    char message[128];
    snprintf(message, sizeof message, "xyz: row %zu: a coordinate", n - 1);
    refused(haphe_scene_deform(scene, a, xyz, n), message, scene, a, 2);
    xyz[3 * (n - 1)] = rest[3 * (n - 1)];
    snprintf(message, sizeof message, "xyz: %zu vertex positions given, but the shape has %zu",
             n - 1, n);
    refused(haphe_scene_deform(scene, a, xyz, n - 1), message, scene, a, 2);
    uint32_t out_of_range[2] = {3, (uint32_t)n + 5};
    snprintf(message, sizeof message,
             "indices: row 1: vertex index %zu is out of range (the shape has %zu vertices)",
             n + 5, n);
    refused(haphe_scene_deform_at(scene, a, out_of_range, half, 2), message, scene, a, 2);
    refused(haphe_scene_deform(scene, 9, xyz, n), "no object 9 in the scene", scene, a, 2);
    refused(haphe_scene_deform_at(scene, 9, two, half, 2), "no object 9 in the scene", scene, a,
            2);
    refused(haphe_scene_deform(scene, a, NULL, n), "xyz is null", scene, a, 2);
    refused(haphe_scene_deform_at(scene, a, NULL, half, 2), "indices is null", scene, a, 2);
    HapheShape *none = NULL;
    CHECK(haphe_scene_shape(scene, 9, &none) == HAPHE_STATUS_INVALID_ARGUMENT && none == NULL,
          "an unknown object's shape");

    /* The sphere breathes (radius x0.85 to x1.15 at 2 Hz) every tick while the hand presses
     * from 3 mm outside its radius to 11 mm inside, 1.7 times a second: the proxy is never
     * inside the current surface and the force is finite and within its maximum. */
    HapheProxy *proxy = NULL;
    const double max_force = haphe_default_max_force();
    const double dir[3] = {0.6, 0.0, 0.8};
    double start[3];
    for (int k = 0; k < 3; k++) start[k] = dir[k] * (RADIUS + 0.003);
    OK(haphe_proxy_new(start, max_force, 0.0, &proxy));
    size_t ticks = 500, contact = 0, hand_inside = 0;
    for (size_t tick = 0; tick < ticks; tick++) {
        double t = (double)tick / 1000.0, scale = 1.0 + 0.15 * sin(2 * PI * 2.0 * t);
        for (size_t i = 0; i < 3 * n; i++) xyz[i] = scale * rest[i];
        OK(haphe_scene_deform(scene, a, xyz, n));
        double depth = -0.004 + 0.007 * cos(2 * PI * 1.7 * t), hip[3];
        for (int k = 0; k < 3; k++) hip[k] = dir[k] * (scale * RADIUS + depth);
        HapheTick out;
        OK(haphe_proxy_tick(proxy, scene, hip, NULL, &out));
        double f = sqrt(out.force[0] * out.force[0] + out.force[1] * out.force[1] +
                        out.force[2] * out.force[2]);
        CHECK(isfinite(f) && f <= max_force * (1 + 1e-12), "tick %zu: force %g", tick, f);
        CHECK(!inside_now(scene, a, out.proxy), "tick %zu: the proxy is inside the surface",
              tick);
        hand_inside += inside_now(scene, a, hip);
        contact += out.in_contact;
    }
    /* Guard: the hand, a path of the scene, is inside the surface on many ticks. */
    CHECK(hand_inside > ticks / 4, "the hand was inside on %zu ticks only", hand_inside);
    CHECK(contact >= hand_inside * 9 / 10, "%zu contact ticks for %zu with the hand inside",
          contact, hand_inside);
    CHECK(version_of(scene, a) == 2 + ticks, "one deformation a tick");
    printf("breathing: %zu ticks, %zu in contact (the hand inside on %zu), never inside\n", ticks,
           contact, hand_inside);

    haphe_proxy_free(proxy);
    haphe_scene_free(scene);
    haphe_shape_free(shape);
    free(rest);
    free(xyz);
    free(faces);
    printf("deform: all checks passed\n");
    return 0;
}
