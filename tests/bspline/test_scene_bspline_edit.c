/* B-spline / NURBS surfaces kept in the scene model (casteljau/scene_bspline.h): the patches the
 * renderers draw are the library's conversion bit for bit; load -> save -> load rebuilds the same
 * surface bit for bit and the second save is byte-identical to the first; moving a control point
 * or its weight re-derives exactly the patches a fresh conversion changes, all within the point's
 * support of at most (p+1)(q+1) patches; a direct patch edit makes the save fall back to
 * "patches"; bad edits are refused by name. */
#include "casteljau/bspline_surface.h"
#include "casteljau/patch.h"
#include "casteljau/scene.h"
#include "casteljau/scene_bspline.h"
#include "casteljau/scene_json.h"
#include "casteljau/status.h"
#include "rng.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int failures;
#define CHECK(cond, ...)                                                                           \
    do {                                                                                           \
        if (!(cond)) {                                                                             \
            ++failures;                                                                            \
            printf("FAIL line %d: ", __LINE__);                                                    \
            printf(__VA_ARGS__);                                                                   \
            printf("\n");                                                                          \
        }                                                                                          \
    } while (0)

/* Whether geometry `gi` holds exactly cj_bspline_surface_to_patches of `s`, bit for bit. */
static int patches_match(const cj_geometry *g, const cj_bspline_surface *s) {
    int np = 0;
    if (cj_bspline_surface_patch_count(s, &np) || (size_t)np != g->u.patches.count) return 0;
    const size_t per = (size_t)(s->deg_u + 1) * (size_t)(s->deg_v + 1);
    double *pts = malloc(sizeof(double) * 3 * per * (size_t)np);
    double *w = s->weights ? malloc(sizeof(double) * per * (size_t)np) : NULL;
    int same = pts && (!s->weights || w) &&
               !cj_bspline_surface_to_patches(s, pts, w, NULL, NULL, np, NULL);
    for (int k = 0; same && k < np; ++k) {
        const cj_patch *p = &g->u.patches.patches[k];
        same = p->deg_u == s->deg_u && p->deg_v == s->deg_v && !p->weights == !w &&
               !memcmp(p->pts, pts + 3 * per * (size_t)k, 3 * per * sizeof(double)) &&
               (!w || !memcmp(p->weights, w + per * (size_t)k, per * sizeof(double)));
    }
    free(pts);
    free(w);
    return same;
}

static int same_surface(const cj_bspline_surface *a, const cj_bspline_surface *b) {
    if (a->deg_u != b->deg_u || a->deg_v != b->deg_v || a->npts_u != b->npts_u ||
        a->npts_v != b->npts_v || !a->weights != !b->weights)
        return 0;
    const size_t n = (size_t)a->npts_u * (size_t)a->npts_v;
    return !memcmp(a->pts, b->pts, 3 * n * sizeof(double)) &&
           (!a->weights || !memcmp(a->weights, b->weights, n * sizeof(double))) &&
           !memcmp(a->knots_u, b->knots_u, (size_t)(a->npts_u + a->deg_u + 1) * sizeof(double)) &&
           !memcmp(a->knots_v, b->knots_v, (size_t)(a->npts_v + a->deg_v + 1) * sizeof(double));
}

static char *slurp(const char *path) {
    FILE *f = fopen(path, "rb");
    if (!f) return NULL;
    fseek(f, 0, SEEK_END);
    long n = ftell(f);
    fseek(f, 0, SEEK_SET);
    char *t = malloc((size_t)n + 1);
    if (t && fread(t, 1, (size_t)n, f) != (size_t)n) {
        free(t);
        t = NULL;
    }
    if (t) t[n] = 0;
    fclose(f);
    return t;
}

static void test_round_trip(void) {
    cj_scene *a = NULL, *b = NULL;
    cj_status st = cj_scene_load_json(CJ_SCENE_FILE, NULL, &a);
    CHECK(st == CJ_OK, "load %s: %s", CJ_SCENE_FILE, cj_last_error());
    if (st) return;
    int kept = 0, nurbs = 0;
    for (size_t i = 0; i < cj_scene_geometry_count(a); ++i) {
        const cj_bspline_surface *s = cj_scene_geometry_bspline(a, (int)i);
        if (!s) continue;
        ++kept;
        nurbs += s->weights != NULL;
        CHECK(patches_match(cj_scene_geometry(a, (int)i), s),
              "geometry %zu: patches differ from cj_bspline_surface_to_patches", i);
    }
    CHECK(kept == 2 && nurbs == 1, "%d kept B-spline surfaces (%d NURBS), wanted 2 (1)", kept,
          nurbs);
    const char *f1 = "test_scene_bspline_edit_1.json", *f2 = "test_scene_bspline_edit_2.json";
    st = cj_scene_save_json(a, f1);
    CHECK(st == CJ_OK, "save: %s", cj_last_error());
    if (!st) st = cj_scene_load_json(f1, NULL, &b);
    CHECK(st == CJ_OK, "reload: %s", cj_last_error());
    if (!st) {
        CHECK(cj_scene_geometry_count(a) == cj_scene_geometry_count(b), "geometry counts");
        for (size_t i = 0; i < cj_scene_geometry_count(a) && i < cj_scene_geometry_count(b); ++i) {
            const cj_bspline_surface *sa = cj_scene_geometry_bspline(a, (int)i);
            const cj_bspline_surface *sb = cj_scene_geometry_bspline(b, (int)i);
            CHECK(!sa == !sb && (!sa || (same_surface(sa, sb) &&
                                         patches_match(cj_scene_geometry(b, (int)i), sb))),
                  "geometry %zu: the reloaded B-spline form or its patches differ", i);
        }
        st = cj_scene_save_json(b, f2);
        CHECK(st == CJ_OK, "second save: %s", cj_last_error());
        char *t1 = slurp(f1), *t2 = slurp(f2);
        CHECK(t1 && t2 && !strcmp(t1, t2), "the second save differs from the first");
        CHECK(t1 && strstr(t1, "\"nurbs_surface\"") && strstr(t1, "\"bspline_surface\""),
              "the save does not write the surfaces as B-splines");
        free(t1);
        free(t2);
        cj_scene_destroy(b);
    }
    /* A direct edit of a patch detaches the B-spline form: the save writes patches. */
    for (size_t i = 0; i < cj_scene_geometry_count(a); ++i)
        if (cj_scene_geometry_bspline(a, (int)i)) {
            cj_geometry *g = cj_scene_geometry_mut(a, (int)i);
            ((double *)g->u.patches.patches[0].pts)[0] += 0.125;
        }
    st = cj_scene_save_json(a, f2);
    char *t = slurp(f2);
    CHECK(!st && t && !strstr(t, "_surface\"") && strstr(t, "\"patches\""),
          "after a direct patch edit the save still writes B-spline surfaces");
    free(t);
    cj_scene_destroy(a);
    remove(f1);
    remove(f2);
    printf("round trip: %s keeps its 2 B-spline surfaces (1 NURBS) with patches equal to the "
           "conversion bit for bit; load -> save -> load rebuilds them bit for bit and the second "
           "save is byte-identical; a direct patch edit saves as patches\n",
           CJ_SCENE_FILE);
}

/* A clamped knot vector on [0, 1] for n points of degree p with random interior knots, some
 * repeated up to multiplicity p (tiny and repeated spans). */
static void random_knots(cj_rng *r, int n, int p, double *k) {
    for (int i = 0; i <= p; ++i) {
        k[i] = 0.0;
        k[n + i] = 1.0;
    }
    int i = p + 1;
    while (i < n) {
        const double x = cj_rng_range(r, 0.05, 0.95);
        int mult = cj_rng_int(r, 1, p);
        if (mult > n - i) mult = n - i;
        for (int m = 0; m < mult; ++m) k[i++] = x;
    }
    /* sort the interior */
    for (int a = p + 1; a < n; ++a)
        for (int b = a; b > p + 1 && k[b - 1] > k[b]; --b) {
            const double t = k[b];
            k[b] = k[b - 1];
            k[b - 1] = t;
        }
}

static void test_edits(uint64_t seed) {
    cj_rng r;
    cj_rng_init(&r, seed);
    int edits = 0, worst = 0, full = 0;
    long changed_total = 0;
    for (int trial = 0; trial < 40; ++trial) {
        const int p = cj_rng_int(&r, 1, 3), q = cj_rng_int(&r, 1, 3);
        const int nu = p + 1 + cj_rng_int(&r, 0, 6), nv = q + 1 + cj_rng_int(&r, 0, 6);
        const int rational = trial % 2;
        const size_t n = (size_t)nu * (size_t)nv;
        double *pts = malloc(3 * n * sizeof(double)), *w = malloc(n * sizeof(double));
        double ku[32], kv[32];
        random_knots(&r, nu, p, ku);
        random_knots(&r, nv, q, kv);
        for (int j = 0; j < nv; ++j)
            for (int i = 0; i < nu; ++i) {
                double *x = pts + 3 * ((size_t)j * (size_t)nu + (size_t)i);
                x[0] = i + cj_rng_range(&r, -0.3, 0.3);
                x[1] = j + cj_rng_range(&r, -0.3, 0.3);
                x[2] = cj_rng_range(&r, -1.0, 1.0);
                w[(size_t)j * (size_t)nu + (size_t)i] = cj_rng_range(&r, 0.5, 2.0);
            }
        const cj_bspline_surface s0 = {p, q, nu, nv, pts, rational ? w : NULL, ku, kv};
        cj_scene *scene = NULL;
        int gi = -1;
        cj_status st = cj_scene_create(NULL, &scene);
        if (!st) st = cj_scene_add_bspline_surface(scene, &s0, &gi);
        CHECK(st == CJ_OK, "trial %d: add: %s", trial, cj_last_error());
        if (st) {
            cj_scene_destroy(scene);
            free(pts);
            free(w);
            continue;
        }
        const cj_bspline_surface *s = cj_scene_geometry_bspline(scene, gi);
        const cj_geometry *g = cj_scene_geometry(scene, gi);
        const size_t per = (size_t)(p + 1) * (size_t)(q + 1), np = g->u.patches.count;
        double *before = malloc(3 * per * np * sizeof(double));
        for (int e = 0; e < 6; ++e) {
            const int i = cj_rng_int(&r, 0, nu - 1), j = cj_rng_int(&r, 0, nv - 1);
            for (size_t k = 0; k < np; ++k)
                memcpy(before + 3 * per * k, g->u.patches.patches[k].pts, 3 * per * sizeof(double));
            const double *old = s->pts + 3 * ((size_t)j * (size_t)nu + (size_t)i);
            const double xyz[3] = {old[0] + cj_rng_range(&r, -0.5, 0.5), old[1], old[2] + 0.25};
            const double weight = rational ? cj_rng_range(&r, 0.5, 2.0) : 1.0;
            int support[16], changed[16], nchanged = -1;
            const int ns = cj_scene_bspline_support(scene, gi, i, j, support, 16);
            st = cj_scene_bspline_set_point(scene, gi, i, j, xyz, weight, changed, 16, &nchanged);
            CHECK(st == CJ_OK, "trial %d edit %d: %s", trial, e, cj_last_error());
            if (st) continue;
            ++edits;
            changed_total += nchanged;
            if (nchanged > worst) worst = nchanged;
            full += nchanged == (p + 1) * (q + 1);
            CHECK(ns >= 1 && ns <= (p + 1) * (q + 1), "trial %d: support of (%d,%d) is %d patches",
                  trial, i, j, ns);
            CHECK(nchanged >= 1 && nchanged <= ns,
                  "trial %d: moving (%d,%d) changed %d patches (support %d)", trial, i, j, nchanged,
                  ns);
            /* every changed patch is in the support, and no other patch's bits moved */
            int inside = 1;
            for (int c = 0; c < nchanged; ++c) {
                int found = 0;
                for (int m = 0; m < ns; ++m) found |= support[m] == changed[c];
                inside &= found;
            }
            CHECK(inside, "trial %d: a changed patch lies outside the support", trial);
            int others = 1;
            for (size_t k = 0; k < np; ++k) {
                int listed = 0;
                for (int c = 0; c < nchanged; ++c) listed |= (size_t)changed[c] == k;
                if (!listed)
                    others &= !memcmp(before + 3 * per * k, g->u.patches.patches[k].pts,
                                      3 * per * sizeof(double));
            }
            CHECK(others, "trial %d: a patch not listed as changed moved", trial);
            CHECK(patches_match(g, s), "trial %d edit %d: patches differ from a fresh conversion",
                  trial, e);
        }
        /* bad edits: refused by name, nothing changes */
        const double nan3[3] = {NAN, 0, 0}, ok3[3] = {0, 0, 0}, far3[3] = {0, 2e9, 0};
        CHECK(cj_scene_bspline_set_point(scene, gi, 0, 0, nan3, 1.0, NULL, 0, NULL) ==
                      CJ_ERR_NONFINITE &&
                  strstr(cj_last_error(), "(0, 0)"),
              "NaN point: %s", cj_last_error());
        CHECK(cj_scene_bspline_set_point(scene, gi, 0, 0, far3, 1.0, NULL, 0, NULL) == CJ_ERR_RANGE,
              "far point: %s", cj_last_error());
        CHECK(cj_scene_bspline_set_point(scene, gi, nu, 0, ok3, 1.0, NULL, 0, NULL) ==
                  CJ_ERR_ARGUMENT,
              "point out of the net: %s", cj_last_error());
        CHECK(cj_scene_bspline_set_point(scene, gi, 0, 0, ok3, rational ? 0.0 : 2.0, NULL, 0,
                                         NULL) == CJ_ERR_ARGUMENT &&
                  strstr(cj_last_error(), "weight"),
              "bad weight: %s", cj_last_error());
        CHECK(patches_match(g, s), "trial %d: a refused edit changed the patches", trial);
        free(before);
        cj_scene_destroy(scene);
        free(pts);
        free(w);
    }
    printf("edits: %d control point moves (half with a new weight) on 40 random surfaces of "
           "degrees 1..3 with repeated knots: each changed only patches of the point's support "
           "(at most (p+1)(q+1); worst %d, mean %.2f, %d edits changed the full (p+1)(q+1)), the "
           "rest kept their bits, and the result equals a fresh conversion bit for bit; NaN, "
           "far, out-of-net points and bad weights refused\n",
           edits, worst, edits ? (double)changed_total / edits : 0.0, full);
}

/* A bicubic on 7 x 7 points with simple uniform knots: an interior point moves all 16 patches of
 * its support, a corner point one patch. */
static void test_uniform(void) {
    double pts[3 * 49], k[11];
    CHECK(!cj_bspline_uniform_knots(7, 3, 0.0, 1.0, 1, k), "knots: %s", cj_last_error());
    for (int j = 0; j < 7; ++j)
        for (int i = 0; i < 7; ++i) {
            pts[3 * (7 * j + i)] = i;
            pts[3 * (7 * j + i) + 1] = j;
            pts[3 * (7 * j + i) + 2] = (i * j) % 3;
        }
    const cj_bspline_surface s = {3, 3, 7, 7, pts, NULL, k, k};
    cj_scene *scene = NULL;
    int gi = -1, centre = -1, corner = -1;
    cj_status st = cj_scene_create(NULL, &scene);
    if (!st) st = cj_scene_add_bspline_surface(scene, &s, &gi);
    CHECK(st == CJ_OK, "add: %s", cj_last_error());
    if (!st) {
        const double up[3] = {3, 3, 2}, low[3] = {0, 0, -1};
        st = cj_scene_bspline_set_point(scene, gi, 3, 3, up, 1.0, NULL, 0, &centre);
        if (!st) st = cj_scene_bspline_set_point(scene, gi, 0, 0, low, 1.0, NULL, 0, &corner);
        CHECK(st == CJ_OK, "edit: %s", cj_last_error());
    }
    CHECK(scene && cj_scene_geometry(scene, gi)->u.patches.count == 16 && centre == 16 &&
              corner == 1,
          "bicubic 7 x 7: the centre point changed %d patches (want 16 of 16), the corner %d "
          "(want 1)",
          centre, corner);
    cj_scene_destroy(scene);
    printf("uniform bicubic 7 x 7 (16 patches): the centre point changes all (p+1)(q+1) = 16, a "
           "corner point 1\n");
}

int main(void) {
    const uint64_t seed = cj_test_seed("test_scene_bspline_edit", 22);
    test_round_trip();
    test_uniform();
    test_edits(seed);
    if (failures) {
        printf("%d failure(s)\n", failures);
        return 1;
    }
    printf("test_scene_bspline_edit: all checks passed\n");
    return 0;
}
