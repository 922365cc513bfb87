/* The C API's answers against the Rust library's: reads a mesh and the answers file
 * written by `cargo run -p haphe-c --example c_answers -- MESH`, asks
 * haphe_shape_inside and haphe_shape_first_crossing the same questions, and fails
 * (exit 1) on any answer that differs, bit for bit, or on a file that checks nothing
 * (no point inside or none outside, no segment that crosses or none that misses).
 *
 *   cc -std=c11 -Wall -Wextra -Werror crates/haphe-c/check/answers.c \
 *       -Icrates/haphe-c/include -Ltarget/debug -lhaphe -o answers
 *   LD_LIBRARY_PATH=target/debug ./answers MESH ANSWERS */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "haphe.h"

enum { SHOWN = 5 };

static int read3(FILE *f, double v[3]) {
    return fscanf(f, "%lf %lf %lf", &v[0], &v[1], &v[2]) == 3;
}

/* Whether two doubles are the same number, NaN equal to NaN. */
static int same(double a, double b) {
    return (a != a && b != b) || memcmp(&a, &b, sizeof a) == 0;
}

static int same3(const double a[3], const double b[3]) {
    return same(a[0], b[0]) && same(a[1], b[1]) && same(a[2], b[2]);
}

int main(int argc, char **argv) {
    if (argc != 3) {
        fprintf(stderr, "usage: %s MESH ANSWERS\n", argv[0]);
        return 2;
    }
    FILE *f = fopen(argv[2], "r");
    if (!f) {
        fprintf(stderr, "cannot open %s\n", argv[2]);
        return 2;
    }
    HapheShape *shape = NULL;
    if (haphe_shape_from_file(argv[1], 1.0, &shape) != HAPHE_STATUS_OK) {
        fprintf(stderr, "%s: %s\n", argv[1], haphe_last_error());
        return 2;
    }
    int version = 0;
    size_t n = 0, n_inside = 0;
    if (fscanf(f, "haphe-c-answers %d inside %zu %zu", &version, &n, &n_inside) != 3 ||
        version != 1) {
        fprintf(stderr, "%s: not an answers file of version 1\n", argv[2]);
        return 2;
    }
    /* All points in one call, as an application asks them. */
    double *points = malloc(3 * (n + 1) * sizeof(double));
    uint8_t *expected = malloc(n + 1), *got = malloc(n + 1);
    if (!points || !expected || !got) return 2;
    for (size_t i = 0; i < n; i++) {
        unsigned e = 0;
        if (!read3(f, &points[3 * i]) || fscanf(f, "%u", &e) != 1) {
            fprintf(stderr, "%s: point %zu unreadable\n", argv[2], i);
            return 2;
        }
        expected[i] = (uint8_t)e;
        got[i] = 2;
    }
    if (haphe_shape_inside(shape, points, n, 0, got) != HAPHE_STATUS_OK) {
        fprintf(stderr, "haphe_shape_inside: %s\n", haphe_last_error());
        return 1;
    }
    size_t wrong = 0, examined = 0, seen_inside = 0;
    for (size_t i = 0; i < n; i++) {
        const double *p = &points[3 * i];
        examined++;
        seen_inside += expected[i];
        if (got[i] != expected[i] && wrong++ < SHOWN)
            fprintf(stderr, "inside (%.17g, %.17g, %.17g): C says %u, Rust %u\n", p[0], p[1],
                    p[2], (unsigned)got[i], (unsigned)expected[i]);
    }
    size_t m = 0, m_hits = 0;
    if (fscanf(f, " crossing %zu %zu", &m, &m_hits) != 2) {
        fprintf(stderr, "%s: no crossing section\n", argv[2]);
        return 2;
    }
    double *p0 = malloc(3 * (m + 1) * sizeof(double)), *p1 = malloc(3 * (m + 1) * sizeof(double));
    HapheCrossing *want = malloc((m + 1) * sizeof(HapheCrossing));
    HapheCrossing *hits = malloc((m + 1) * sizeof(HapheCrossing));
    if (!p0 || !p1 || !want || !hits) return 2;
    size_t seen_hits = 0;
    for (size_t i = 0; i < m; i++) {
        char word[32];
        if (!read3(f, &p0[3 * i]) || !read3(f, &p1[3 * i]) || fscanf(f, "%31s", word) != 1) {
            fprintf(stderr, "%s: segment %zu unreadable\n", argv[2], i);
            return 2;
        }
        HapheCrossing *w = &want[i];
        w->t = NAN;
        w->triangle = -1;
        w->entering = 0;
        for (int k = 0; k < 3; k++) w->point[k] = w->normal[k] = NAN;
        if (strcmp(word, "none") != 0) {
            long long triangle = 0;
            unsigned entering = 0;
            w->t = strtod(word, NULL);
            if (fscanf(f, "%lld %u", &triangle, &entering) != 2 || !read3(f, w->point) ||
                !read3(f, w->normal)) {
                fprintf(stderr, "%s: crossing %zu unreadable\n", argv[2], i);
                return 2;
            }
            w->triangle = triangle;
            w->entering = (uint8_t)entering;
            seen_hits++;
        }
    }
    if (haphe_shape_first_crossing(shape, p0, p1, m, 0, hits) != HAPHE_STATUS_OK) {
        fprintf(stderr, "haphe_shape_first_crossing: %s\n", haphe_last_error());
        return 1;
    }
    size_t crossed = 0, wrong_crossings = 0;
    for (size_t i = 0; i < m; i++) {
        const HapheCrossing *g = &hits[i], *w = &want[i];
        crossed++;
        if (!(same(g->t, w->t) && g->triangle == w->triangle && g->entering == w->entering &&
              same3(g->point, w->point) && same3(g->normal, w->normal)) &&
            wrong_crossings++ < SHOWN)
            fprintf(stderr,
                    "segment %zu: C says t %.17g triangle %lld entering %u, Rust t %.17g "
                    "triangle %lld entering %u\n",
                    i, g->t, (long long)g->triangle, (unsigned)g->entering, w->t,
                    (long long)w->triangle, (unsigned)w->entering);
    }
    fclose(f);
    haphe_shape_free(shape);
    free(points);
    free(expected);
    free(got);
    free(p0);
    free(p1);
    free(want);
    free(hits);
    printf("%s: %zu points (%zu inside), %zu differ; %zu segments (%zu crossing), %zu differ\n",
           argv[1], examined, seen_inside, wrong, crossed, seen_hits, wrong_crossings);
    /* The counts examined are the file's, and both answers of each query occur. */
    if (examined != n || seen_inside != n_inside || crossed != m || seen_hits != m_hits ||
        seen_inside == 0 || seen_inside == n || seen_hits == 0 || seen_hits == m) {
        fprintf(stderr, "the answers file checks too little or does not match its counts\n");
        return 1;
    }
    return wrong == 0 && wrong_crossings == 0 ? 0 : 1;
}
