/* Cutting through the C API: a block of 24³ voxels of 1 mm built here is drilled by a
 * tool of 2 mm that the hand pushes straight down at 10 mm/s for a second (every tick the
 * cutter is pressed with the contact force, every 10 ticks refreshed and its shape given
 * to the object): voxels are removed and the tool goes more than 2 mm below the top face,
 * the force finite and within its maximum. The cut volume is saved as NIfTI-1 (.nii and
 * .nii.gz) in DIR and read back equal; bad input is refused naming the argument (NaN
 * value, bad affine, tool radius, cut force, voxel size, centre, a shape that is not a
 * version of the object's, a missing file, NIfTI-2). Prints one summary line; exits 1 on
 * the first surprise.
 *
 *   cc -std=c11 -Wall -Wextra -Werror crates/haphe-c/check/cut.c \
 *       -Icrates/haphe-c/include -Ltarget/debug -lhaphe -lm -o cut
 *   LD_LIBRARY_PATH=target/debug ./cut meshes/models/sphere.ply target/c-examples */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "haphe.h"

enum { N = 24, MARGIN = 4 };
static const double VOXEL = 1e-3;
static const double TOOL = 2e-3;

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

/* A refused call: the status and a message containing `part`. */
static void refused(HapheStatus status, HapheStatus expected, const char *part) {
    CHECK(status == expected, "status %d, expected %d, for \"%s\"", (int)status,
          (int)expected, part);
    CHECK(strstr(haphe_last_error(), part) != NULL, "message \"%s\", expected \"...%s...\"",
          haphe_last_error(), part);
}

/* The block: material (1) from voxel MARGIN to N-1-MARGIN on each axis, air (0) around,
 * the grid centred on the origin; `affine` receives its 4×4 affine (row by row). */
static HapheVolume *block(double affine[16], float *values) {
    const double half = 0.5 * (N - 1) * VOXEL;
    for (int k = 0; k < N; k++)
        for (int j = 0; j < N; j++)
            for (int i = 0; i < N; i++) {
                int in = i >= MARGIN && i < N - MARGIN && j >= MARGIN && j < N - MARGIN &&
                         k >= MARGIN && k < N - MARGIN;
                values[i + N * (j + N * k)] = in ? 1.0f : 0.0f;
            }
    memset(affine, 0, 16 * sizeof affine[0]);
    for (int r = 0; r < 3; r++) {
        affine[5 * r] = VOXEL;
        affine[4 * r + 3] = -half;
    }
    affine[15] = 1.0;
    const size_t dims[3] = {N, N, N};
    HapheVolume *volume = NULL;
    OK(haphe_volume_new(dims, values, (size_t)N * N * N, affine, 0.5f, &volume));
    return volume;
}

/* Drills the block; returns how far below the top face the tool's centre went (m). */
static double drill(HapheCutter *cutter, double top, size_t *versions) {
    HapheShape *shape = NULL;
    HapheScene *scene = NULL;
    HapheProxy *proxy = NULL;
    uint32_t id = 0;
    OK(haphe_cutter_shape(cutter, &shape));
    OK(haphe_scene_new(4, &scene));
    /* The grid's centre at the origin, where the block's affine already puts it. */
    OK(haphe_scene_add_volume(scene, cutter, NULL, NULL, NULL, &id));
    haphe_shape_free(shape);
    const double max_force = haphe_default_max_force();
    double start[3] = {0.0, 0.0, top + TOOL + 3e-3}, deepest = INFINITY;
    OK(haphe_proxy_new(start, max_force, TOOL, &proxy));
    for (size_t tick = 0; tick < 1000; tick++) {
        double hip[3] = {0.0, 0.0, start[2] - 0.01 * (double)tick * 1e-3};
        HapheTick out;
        OK(haphe_proxy_tick(proxy, scene, hip, NULL, &out));
        double f = sqrt(out.force[0] * out.force[0] + out.force[1] * out.force[1] +
                        out.force[2] * out.force[2]);
        CHECK(isfinite(f) && f <= max_force * (1 + 1e-12), "tick %zu: force %g", tick, f);
        if (out.in_contact) {
            /* The block is placed at the origin: the world frame is the volume's. */
            OK(haphe_cutter_press(cutter, out.proxy, f, 1e-3, NULL));
        }
        if (tick % 10 == 9) {
            HapheShape *next = NULL;
            OK(haphe_cutter_refresh(cutter, &next));
            if (next) {
                OK(haphe_scene_replace(scene, id, next));
                haphe_shape_free(next);
                *versions += 1;
            }
        }
        if (out.proxy[2] < deepest) deepest = out.proxy[2];
    }
    haphe_proxy_free(proxy);
    haphe_scene_free(scene);
    return top - deepest;
}

/* The cutter's shape placed with its grid's centre at `at`: a point proxy coming down
 * 5 mm beside the drilled hole rests on the top face there. */
static void placed(HapheCutter *cutter, double top) {
    const double at[3] = {0.05, -0.02, 0.1};
    HapheScene *scene = NULL;
    HapheProxy *proxy = NULL;
    OK(haphe_scene_new(2, &scene));
    OK(haphe_scene_add_volume(scene, cutter, at, NULL, NULL, NULL));
    double hip[3] = {at[0], at[1] + 5e-3, at[2] + top + 5e-3};
    OK(haphe_proxy_new(hip, haphe_default_max_force(), 0.0, &proxy));
    HapheTick out;
    for (int tick = 0; tick < 100; tick++) {
        hip[2] -= 1e-4; /* down 10 mm: 5 mm into the block */
        OK(haphe_proxy_tick(proxy, scene, hip, NULL, &out));
    }
    CHECK(out.in_contact && fabs(out.proxy[2] - (at[2] + top)) < 2e-4,
          "placed at (%g, %g, %g): the proxy rests at z %g, the top face at %g", at[0], at[1],
          at[2], out.proxy[2], at[2] + top);
    refused(haphe_scene_add_volume(scene, NULL, at, NULL, NULL, NULL),
            HAPHE_STATUS_INVALID_ARGUMENT, "cutter");
    haphe_proxy_free(proxy);
    haphe_scene_free(scene);
}

/* The volume saved at `path` reads back with the same dims, values and affine. */
static void round_trip(const HapheVolume *volume, const char *path) {
    HapheVolume *back = NULL;
    OK(haphe_volume_save(volume, path));
    OK(haphe_volume_read_nifti(path, 0.5f, 1, &back));
    size_t d0[3], d1[3], n0, n1;
    const float *v0, *v1;
    double a0[16], a1[16];
    float iso = 0.0f;
    OK(haphe_volume_dims(volume, d0));
    OK(haphe_volume_dims(back, d1));
    CHECK(memcmp(d0, d1, sizeof d0) == 0, "%s: other dims", path);
    OK(haphe_volume_values(volume, &v0, &n0));
    OK(haphe_volume_values(back, &v1, &n1));
    CHECK(n0 == n1 && memcmp(v0, v1, n0 * sizeof *v0) == 0, "%s: other values", path);
    OK(haphe_volume_affine(volume, a0, NULL));
    OK(haphe_volume_affine(back, a1, &iso));
    for (int i = 0; i < 16; i++)
        CHECK(fabs(a0[i] - a1[i]) <= 1e-12, "%s: affine[%d] %g, was %g", path, i, a1[i], a0[i]);
    CHECK(iso == 0.5f, "%s: iso %g", path, iso);
    haphe_volume_free(back);
}

/* Bad input refused, naming the argument. */
static void refusals(const HapheShape *sphere, const HapheVolume *volume, const char *dir) {
    double affine[16];
    float *values = malloc(sizeof(float) * N * N * N);
    CHECK(values != NULL, "out of memory");
    HapheVolume *good = block(affine, values), *none = NULL;
    const size_t dims[3] = {N, N, N};
    values[3 + N * (2 + N * 1)] = NAN;
    refused(haphe_volume_new(dims, values, (size_t)N * N * N, affine, 0.5f, &none),
            HAPHE_STATUS_INVALID_ARGUMENT, "values: voxel [3, 2, 1] is NaN");
    values[3 + N * (2 + N * 1)] = 0.0f;
    affine[15] = 2.0;
    refused(haphe_volume_new(dims, values, (size_t)N * N * N, affine, 0.5f, &none),
            HAPHE_STATUS_INVALID_ARGUMENT, "affine");
    affine[15] = 1.0;
    affine[5] = 0.0;
    refused(haphe_volume_new(dims, values, (size_t)N * N * N, affine, 0.5f, &none),
            HAPHE_STATUS_INVALID_ARGUMENT, "affine");
    refused(haphe_volume_new(dims, values, 5, affine, 0.5f, &none),
            HAPHE_STATUS_INVALID_ARGUMENT, "values");
    HapheCutter *cutter = NULL;
    refused(haphe_cutter_new(volume, -1e-3, 0.5, &cutter), HAPHE_STATUS_INVALID_ARGUMENT,
            "tool_radius");
    refused(haphe_cutter_new(volume, TOOL, NAN, &cutter), HAPHE_STATUS_INVALID_ARGUMENT,
            "cut_force");
    const double voxels[] = {0.0, -1e-3, NAN, 2.0, 1e-7};
    for (size_t i = 0; i < sizeof voxels / sizeof voxels[0]; i++)
        refused(haphe_volume_from_shape(sphere, voxels[i], &none),
                HAPHE_STATUS_INVALID_ARGUMENT, "voxel");
    OK(haphe_cutter_new(good, TOOL, 0.5, &cutter));
    /* A shape that is not a version of the object's, and an unknown object. */
    HapheShape *first = NULL;
    HapheScene *scene = NULL;
    uint32_t id = 0;
    OK(haphe_cutter_shape(cutter, &first));
    OK(haphe_scene_new(2, &scene));
    OK(haphe_scene_add(scene, first, NULL, NULL, NULL, &id));
    refused(haphe_scene_replace(scene, id, sphere), HAPHE_STATUS_INVALID_ARGUMENT,
            "shape: the shape is not a new version");
    refused(haphe_scene_replace(scene, id + 7, first), HAPHE_STATUS_INVALID_ARGUMENT,
            "no object");
    haphe_scene_free(scene);
    haphe_shape_free(first);
    const double nan_centre[3] = {0.0, NAN, 0.0};
    refused(haphe_cutter_press(cutter, nan_centre, 1.0, 1e-3, NULL),
            HAPHE_STATUS_INVALID_ARGUMENT, "centre");
    char path[4096];
    snprintf(path, sizeof path, "%s/missing.nii", dir);
    refused(haphe_volume_read_nifti(path, 0.0f, 0, &none), HAPHE_STATUS_IO, "missing.nii");
    snprintf(path, sizeof path, "%s/two.nii", dir);
    FILE *f = fopen(path, "wb");
    CHECK(f != NULL, "cannot write %s", path);
    unsigned char header[1024] = {0x1c, 0x02, 0, 0, 'n', '+', '2', 0}; /* sizeof_hdr 540 */
    fwrite(header, 1, sizeof header, f);
    fclose(f);
    refused(haphe_volume_read_nifti(path, 0.0f, 0, &none), HAPHE_STATUS_FORMAT, "NIfTI-2");
    CHECK(none == NULL, "a refused call gave a volume");
    remove(path);
    haphe_cutter_free(cutter);
    haphe_volume_free(good);
    free(values);
}

int main(int argc, char **argv) {
    CHECK(argc == 3, "usage: %s SPHERE.ply DIR", argv[0]);
    double affine[16];
    float *values = malloc(sizeof(float) * N * N * N);
    CHECK(values != NULL, "out of memory");
    HapheVolume *volume = block(affine, values);
    const double top = (N - MARGIN - 0.5) * VOXEL - 0.5 * (N - 1) * VOXEL;

    HapheCutter *cutter = NULL;
    OK(haphe_cutter_new(volume, TOOL, 0.5, &cutter));
    size_t versions = 0;
    double depth = drill(cutter, top, &versions);
    uint64_t removed = haphe_cutter_removed(cutter);
    CHECK(removed > 0 && versions >= 3, "%llu voxels removed, %zu versions",
          (unsigned long long)removed, versions);
    CHECK(depth > 2e-3, "the tool's centre went %.2f mm below the top face only", depth * 1e3);
    placed(cutter, top);

    /* A harder material, cut ten times slower: the same drilling goes less deep. */
    HapheCutter *hard = NULL;
    OK(haphe_cutter_new(volume, TOOL, 0.5, &hard));
    const char *bone[] = {"bone:1:0.002:900:0.2"};
    OK(haphe_cutter_set_layers(hard, bone, 1));
    const char *bad[] = {"bone:1:0.002:900:0.2", "enamel:2"};
    refused(haphe_cutter_set_layers(hard, bad, 2), HAPHE_STATUS_INVALID_ARGUMENT,
            "layers: `enamel:2`");
    size_t hard_versions = 0;
    double hard_depth = drill(hard, top, &hard_versions);
    CHECK(hard_depth < depth - 1e-3, "the harder layer was drilled %.2f mm deep, the default %.2f",
          hard_depth * 1e3, depth * 1e3);
    haphe_cutter_free(hard);

    HapheVolume *cut = NULL;
    OK(haphe_cutter_volume(cutter, &cut));
    char path[4096];
    snprintf(path, sizeof path, "%s/cut.nii", argv[2]);
    round_trip(cut, path);
    remove(path);
    snprintf(path, sizeof path, "%s/cut.nii.gz", argv[2]);
    round_trip(cut, path);
    remove(path);

    HapheShape *sphere = NULL;
    HapheVolume *voxelised = NULL;
    OK(haphe_shape_from_file(argv[1], 0.05, &sphere));
    OK(haphe_volume_from_shape(sphere, 0.002, &voxelised));
    refusals(sphere, volume, argv[2]);

    haphe_volume_free(voxelised);
    haphe_shape_free(sphere);
    haphe_volume_free(cut);
    haphe_cutter_free(cutter);
    haphe_volume_free(volume);
    free(values);
    printf("cut: %llu voxels removed in %zu versions, the tool %.2f mm below the top face "
           "(%.2f mm in a layer cut ten times slower); NIfTI round trips equal; all refusals "
           "named\n",
           (unsigned long long)removed, versions, depth * 1e3, hard_depth * 1e3);
    return 0;
}
