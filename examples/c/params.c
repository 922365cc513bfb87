/* Every parameter given through the C API goes through the library's table of domains:
 * NaN, +inf, -inf, a negative value, zero and an absurd value are each refused with
 * HAPHE_STATUS_INVALID_ARGUMENT and a haphe_last_error() naming the parameter, or accepted
 * where the domain allows it. A value inside a texture or effect specification is refused
 * naming the parameter (`texture`, `effect`) and the specification; so is a malformed
 * specification. Prints one line per case; exits 1 on the first surprise.
 *
 *   cargo build -p haphe-c
 *   cc -std=c11 -Wall -Wextra -Werror examples/c/params.c -Icrates/haphe-c/include \
 *       -Ltarget/debug -lhaphe -lm -o params
 *   LD_LIBRARY_PATH=target/debug ./params */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "haphe.h"

/* A tetrahedron, 10 cm, counter-clockwise seen from outside. */
static const double VERTICES[] = {0, 0, 0, 0.1, 0, 0, 0, 0.1, 0, 0, 0, 0.1};
static const uint32_t FACES[] = {0, 2, 1, 0, 1, 3, 1, 2, 3, 0, 3, 2};

static HapheShape *shape;

/* The parameter a case gives a value to, and how. */
typedef enum {
    STIFFNESS,
    DAMPING,
    STATIC_FRICTION,
    DYNAMIC_FRICTION,
    POSITION,
    ROTATION,
    SET_POSITION,
    MAX_FORCE,
    PROXY_POSITION,
    TOOL_RADIUS,
    RATE_HZ,
    TEXTURE,
    EFFECT,
    EFFECT_RUN,
} Which;

/* The specification a TEXTURE, EFFECT or EFFECT_RUN case gives: its form with the
 * value. */
static char spec[96];

static HapheStatus give(Which which, const char *form, double v) {
    HapheScene *scene = NULL;
    HapheStatus status = haphe_scene_new(2, &scene);
    if (status != HAPHE_STATUS_OK) return status;
    HapheMaterial m = {800.0, 1.0, 0.5, 0.3};
    double x[3] = {v, 0.0, 0.0};
    double q[4] = {v, 0.0, 0.0, 0.0};
    uint32_t id = 0;
    HapheProxy *proxy = NULL;
    if (form != NULL) snprintf(spec, sizeof spec, form, v);
    switch (which) {
    case STIFFNESS: m.stiffness = v; break;
    case DAMPING: m.damping = v; break;
    case STATIC_FRICTION: m.static_friction = v; m.dynamic_friction = 0.0; break;
    case DYNAMIC_FRICTION: m.static_friction = 10.0; m.dynamic_friction = v; break;
    default: break;
    }
    switch (which) {
    case POSITION: status = haphe_scene_add(scene, shape, x, NULL, &m, &id); break;
    case ROTATION: status = haphe_scene_add(scene, shape, NULL, q, &m, &id); break;
    case SET_POSITION:
        status = haphe_scene_add(scene, shape, NULL, NULL, &m, &id);
        if (status == HAPHE_STATUS_OK) status = haphe_scene_set_pose(scene, id, x, NULL);
        break;
    case MAX_FORCE: status = haphe_proxy_new(NULL, v, 0.0, &proxy); break;
    case PROXY_POSITION: status = haphe_proxy_new(x, 3.3, 0.0, &proxy); break;
    case TOOL_RADIUS: status = haphe_proxy_new(NULL, 3.3, v, &proxy); break;
    case RATE_HZ:
        status = haphe_scene_add(scene, shape, NULL, NULL, &m, &id);
        if (status == HAPHE_STATUS_OK)
            status = haphe_run(scene, "hand", "press", 0.01, v, NULL, NULL, NULL);
        break;
    case TEXTURE:
        status = haphe_scene_add(scene, shape, NULL, NULL, &m, &id);
        if (status == HAPHE_STATUS_OK) status = haphe_scene_set_texture(scene, id, spec);
        break;
    case EFFECT: status = haphe_scene_add_effect(scene, spec); break;
    case EFFECT_RUN:
        /* Added, then run at 1000 Hz: a vibration above 500 Hz is refused there. */
        status = haphe_scene_add(scene, shape, NULL, NULL, &m, &id);
        if (status == HAPHE_STATUS_OK) status = haphe_scene_add_effect(scene, spec);
        if (status == HAPHE_STATUS_OK)
            status = haphe_run(scene, "hand", "press", 0.01, 1000.0, NULL, NULL, NULL);
        break;
    default: status = haphe_scene_add(scene, shape, NULL, NULL, &m, &id); break;
    }
    haphe_proxy_free(proxy);
    haphe_scene_free(scene);
    return status;
}

/* What each parameter must accept, stated here from the physics: whether 0 and -1 are
 * usable, and a value far beyond any device (0: none is absurd). A texture of no height is
 * none, a wavelength of nothing is no texture; an effect may be switched off by a zero
 * viscosity, stiffness or force, and a constant force points any way; a vibration of
 * 600 Hz is beyond a 1000 Hz servo. */
static const struct {
    Which which;
    const char *name;
    const char *form; /* NULL: the value is given as a number */
    double typical;
    int zero, negative;
    double absurd;
} CASES[] = {
    {STIFFNESS, "stiffness", NULL, 800.0, 0, 0, 1e7},
    {DAMPING, "damping", NULL, 1.0, 1, 0, 1e5},
    {STATIC_FRICTION, "static_friction", NULL, 0.5, 1, 0, 100.0},
    {DYNAMIC_FRICTION, "dynamic_friction", NULL, 0.3, 1, 0, 100.0},
    {POSITION, "position", NULL, 0.2, 1, 1, 1e12},
    {ROTATION, "rotation", NULL, 1.0, 0, 1, 0.0},
    {SET_POSITION, "position", NULL, 0.2, 1, 1, 1e12},
    {MAX_FORCE, "max_force", NULL, 3.3, 0, 0, 1e4},
    {PROXY_POSITION, "position", NULL, 0.2, 1, 1, 1e12},
    /* A tool of no size is the point; a tool of metres is a unit mixed up. */
    {TOOL_RADIUS, "tool_radius", NULL, 0.002, 1, 0, 10.0},
    {RATE_HZ, "rate_hz", NULL, 1000.0, 0, 0, 1e6},
    {TEXTURE, "texture", "sine:%g:0.002", 2e-4, 1, 0, 1.0},
    {TEXTURE, "texture", "noise:0.0001:%g", 2e-3, 0, 0, 100.0},
    {EFFECT, "effect", "viscosity:%g", 2.0, 1, 0, 1e5},
    {EFFECT, "effect", "viscosity:%g:box:0:0:0:1:1:1", 2.0, 1, 0, 1e5},
    {EFFECT, "effect", "spring:%g:0:0:0", 100.0, 1, 0, 1e7},
    {EFFECT, "effect", "magnet:%g:1", 0.01, 0, 0, 100.0},
    {EFFECT, "effect", "constant:%g:0:0", 0.3, 1, 1, 1e4},
    {EFFECT, "effect", "stick-slip:%g:0.5", 1000.0, 1, 0, 1e7},
    {EFFECT_RUN, "effect", "vibration:%g:0.3", 150.0, 0, 0, 600.0},
};

/* A texture or effect specification given whole (NULL: a null pointer). */
static HapheStatus give_text(Which which, const char *text) {
    HapheScene *scene = NULL;
    HapheStatus status = haphe_scene_new(1, &scene);
    uint32_t id = 0;
    if (status == HAPHE_STATUS_OK) status = haphe_scene_add(scene, shape, NULL, NULL, NULL, &id);
    if (status == HAPHE_STATUS_OK) {
        status = which == TEXTURE ? haphe_scene_set_texture(scene, id, text)
                                  : haphe_scene_add_effect(scene, text);
    }
    haphe_scene_free(scene);
    return status;
}

/* Malformed specifications, refused naming the parameter and the specification, and the
 * texture's null and "" (none). */
static const struct {
    Which which;
    const char *name;
    const char *spec;
    int accepted;
} TEXTS[] = {
    {TEXTURE, "texture", "bumps:1:2", 0},
    {TEXTURE, "texture", "sine:0.001", 0},
    {TEXTURE, "texture", "sine:x:0.002", 0},
    {TEXTURE, "texture", "sine:0.001:0.001", 0},
    {TEXTURE, "texture", "", 1},
    {TEXTURE, "texture", NULL, 1},
    {EFFECT, "effect", "wobble:1", 0},
    {EFFECT, "effect", "", 0},
    {EFFECT, "effect", NULL, 0},
    {EFFECT, "effect", "viscosity:2:inside:x", 0},
    {EFFECT, "effect", "spring:10:0:0", 0},
};

int main(void) {
    if (haphe_shape_from_arrays(VERTICES, 4, FACES, 4, &shape) != HAPHE_STATUS_OK) {
        fprintf(stderr, "shape: %s\n", haphe_last_error());
        return 1;
    }
    int cases = 0;
    for (size_t c = 0; c < sizeof CASES / sizeof CASES[0]; c++) {
        double values[8] = {CASES[c].typical, NAN, INFINITY, -INFINITY, -1.0, 0.0,
                            CASES[c].absurd, -CASES[c].absurd};
        int accepted[8] = {1, 0, 0, 0, CASES[c].negative, CASES[c].zero, 0, 0};
        size_t n = CASES[c].absurd != 0.0 ? 8 : 6;
        for (size_t i = 0; i < n; i++) {
            HapheStatus status = give(CASES[c].which, CASES[c].form, values[i]);
            const char *error = status == HAPHE_STATUS_OK ? "" : haphe_last_error();
            printf("%-16s %-8g -> %s\n", CASES[c].name, values[i],
                   status == HAPHE_STATUS_OK ? "accepted" : error);
            if (accepted[i]) {
                if (status != HAPHE_STATUS_OK) return 1;
            } else if (status != HAPHE_STATUS_INVALID_ARGUMENT ||
                       strncmp(error, CASES[c].name, strlen(CASES[c].name)) != 0 ||
                       strstr(error, " must be ") == NULL ||
                       (CASES[c].form != NULL && strstr(error, spec) == NULL)) {
                fprintf(stderr, "%s = %g: expected a refusal naming it\n", CASES[c].name,
                        values[i]);
                return 1;
            }
            cases++;
        }
    }
    for (size_t c = 0; c < sizeof TEXTS / sizeof TEXTS[0]; c++) {
        HapheStatus status = give_text(TEXTS[c].which, TEXTS[c].spec);
        const char *error = status == HAPHE_STATUS_OK ? "" : haphe_last_error();
        printf("%-16s %-8s -> %s\n", TEXTS[c].name, TEXTS[c].spec ? TEXTS[c].spec : "(null)",
               status == HAPHE_STATUS_OK ? "accepted" : error);
        if (TEXTS[c].accepted) {
            if (status != HAPHE_STATUS_OK) return 1;
        } else if (status != HAPHE_STATUS_INVALID_ARGUMENT ||
                   strncmp(error, TEXTS[c].name, strlen(TEXTS[c].name)) != 0 ||
                   (TEXTS[c].spec != NULL && strstr(error, TEXTS[c].spec) == NULL)) {
            fprintf(stderr, "%s = %s: expected a refusal naming it\n", TEXTS[c].name,
                    TEXTS[c].spec ? TEXTS[c].spec : "(null)");
            return 1;
        }
        cases++;
    }
    haphe_shape_free(shape);
    printf("%d cases: every refusal named its parameter\n", cases);
    return 0;
}
