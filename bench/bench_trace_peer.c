/* bench_trace_peer: our BVH against Embree 3 (issue 20), one thread, single rays, the same
 * triangles (Embree gets them in float) and the same rays:
 *   - the teapot tessellated at 1e-3 (75 030 triangles) and at a tolerance giving >= 1e6;
 *   - closest hit, ns per ray: median and range of 11 rounds (thread CPU time);
 *   - build time of each (median of 3);
 *   - BENCH_ONLY=<what> runs one piece alone, for instruction counts under callgrind
 *     (valgrind --tool=callgrind --toggle-collect=bench_run_<what> ...): what is one of
 *     ours_rays, embree_rays, ours_build, embree_build; BENCH_MESH=1 takes the large mesh,
 *     BENCH_RAYS=<n> shoots n rays, BENCH_REPEAT=<k> shoots ours k times (for perf).
 * Rays: origins on a sphere of twice the mesh's box radius around its centre, aimed at uniform
 * points of the box (seeded). */
#define _POSIX_C_SOURCE 200809L
#include "bench_clock.h"
#include "casteljau/bvh.h"
#include "casteljau/patchset.h"
#include "casteljau/tessellate.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifdef CJ_HAVE_EMBREE
#include "embree_mesh.h"
#endif

#define NRAYS_DEFAULT 100000
/* Rays per round (BENCH_RAYS=<n> in the BENCH_ONLY mode, for shorter callgrind runs). */
static int g_nrays = NRAYS_DEFAULT;
#define ROUNDS 11

static uint64_t g_rng = 20261126;
static double urand(void) {
    g_rng = g_rng * 6364136223846793005ull + 1442695040888963407ull;
    return (double)(g_rng >> 11) * 0x1p-53;
}

static cj_ray *make_rays(const cj_mesh *m) {
    cj_aabb b = cj_aabb_empty();
    for (size_t i = 0; i < m->vertex_count; i++)
        cj_aabb_grow(&b,
                     cj_v3(m->positions[3 * i], m->positions[3 * i + 1], m->positions[3 * i + 2]));
    const cj_vec3 c =
        cj_v3(0.5 * (b.lo[0] + b.hi[0]), 0.5 * (b.lo[1] + b.hi[1]), 0.5 * (b.lo[2] + b.hi[2]));
    const cj_vec3 half = cj_v3(b.hi[0] - c.x, b.hi[1] - c.y, b.hi[2] - c.z);
    const double R = sqrt(cj_v3_dot(half, half));
    cj_ray *rays = malloc(g_nrays * sizeof *rays);
    if (!rays) abort();
    for (int i = 0; i < g_nrays; i++) {
        cj_vec3 u;
        do {
            u = cj_v3(2 * urand() - 1, 2 * urand() - 1, 2 * urand() - 1);
        } while (cj_v3_dot(u, u) > 1 || cj_v3_dot(u, u) < 1e-6);
        const cj_vec3 o = cj_v3_add(c, cj_v3_scale(cj_v3_normalize(u), 2 * R));
        const cj_vec3 t =
            cj_v3(b.lo[0] + urand() * (b.hi[0] - b.lo[0]), b.lo[1] + urand() * (b.hi[1] - b.lo[1]),
                  b.lo[2] + urand() * (b.hi[2] - b.lo[2]));
        rays[i].org = o;
        rays[i].dir = cj_v3_normalize(cj_v3_sub(t, o));
        rays[i].tmin = 0;
        rays[i].tmax = INFINITY;
    }
    return rays;
}

/* ---- the measured pieces (named for callgrind's --toggle-collect) -------------------------- */

__attribute__((noinline)) int bench_run_ours_rays(const cj_bvh *b, const cj_ray *rays);
__attribute__((noinline)) int bench_run_ours_rays(const cj_bvh *b, const cj_ray *rays) {
    int hits = 0;
    for (int i = 0; i < g_nrays; i++) {
        cj_hit h;
        hits += cj_bvh_mesh_closest(b, &rays[i], &h, NULL);
    }
    return hits;
}

__attribute__((noinline)) cj_bvh *bench_run_ours_build(const cj_mesh *m);
__attribute__((noinline)) cj_bvh *bench_run_ours_build(const cj_mesh *m) {
    cj_bvh *b = NULL;
    if (cj_bvh_mesh_build(m->positions, m->vertex_count, m->triangles, m->triangle_count, NULL, &b))
        abort();
    return b;
}

#ifdef CJ_HAVE_EMBREE
typedef cj_bench_embree emb;

__attribute__((noinline)) emb bench_run_embree_build(const cj_mesh *m);
__attribute__((noinline)) emb bench_run_embree_build(const cj_mesh *m) {
    return cj_bench_embree_build(m);
}

static void embree_free(emb e) {
    cj_bench_embree_free(e);
}

__attribute__((noinline)) int bench_run_embree_rays(RTCScene scene, const cj_ray *rays);
__attribute__((noinline)) int bench_run_embree_rays(RTCScene scene, const cj_ray *rays) {
    return cj_bench_embree_rays(scene, rays, g_nrays);
}
#endif

static void range(const double *v, int n, double *lo, double *hi) {
    *lo = *hi = v[0];
    for (int i = 1; i < n; i++) {
        if (v[i] < *lo) *lo = v[i];
        if (v[i] > *hi) *hi = v[i];
    }
}

static void measure(const char *name, const cj_mesh *m) {
    const cj_ray *rays = make_rays(m);
    double tb[2][3], tr[2][ROUNDS];
    int hits[2] = {0, 0};
    cj_bvh *b = NULL;
#ifdef CJ_HAVE_EMBREE
    emb e = {0};
#endif
    for (int r = 0; r < 3; r++) { /* builds, interleaved */
        double t0 = cj_bench_thread_cpu();
        cj_bvh *nb = bench_run_ours_build(m);
        tb[0][r] = cj_bench_thread_cpu() - t0;
        if (b) cj_bvh_destroy(b);
        b = nb;
#ifdef CJ_HAVE_EMBREE
        t0 = cj_bench_wall(); /* Embree builds on its own thread(s): wall time */
        emb ne = bench_run_embree_build(m);
        tb[1][r] = cj_bench_wall() - t0;
        if (e.dev) embree_free(e);
        e = ne;
#endif
    }
    for (int r = 0; r < ROUNDS; r++) { /* rays, interleaved */
        double t0 = cj_bench_thread_cpu();
        hits[0] = bench_run_ours_rays(b, rays);
        tr[0][r] = (cj_bench_thread_cpu() - t0) / g_nrays * 1e9;
#ifdef CJ_HAVE_EMBREE
        t0 = cj_bench_thread_cpu();
        hits[1] = bench_run_embree_rays(e.scene, rays);
        tr[1][r] = (cj_bench_thread_cpu() - t0) / g_nrays * 1e9;
#endif
    }
    cj_bvh_trav_stats st = {0};
    for (int i = 0; i < g_nrays; i++) {
        cj_hit h;
        cj_bvh_mesh_closest(b, &rays[i], &h, &st);
    }
    const int np = 1
#ifdef CJ_HAVE_EMBREE
                   + 1
#endif
        ;
    const char *who[2] = {"casteljau BVH (8-wide float boxes, exact double triangles)",
                          "Embree 3 rtcIntersect1 (float)"};
    double med[2], lo[2], hi[2], bmed[2];
    for (int p = 0; p < np; p++) {
        range(tr[p], ROUNDS, &lo[p], &hi[p]);
        med[p] = cj_bench_median(tr[p], ROUNDS);
        bmed[p] = cj_bench_median(tb[p], 3);
    }
    for (int p = 0; p < np; p++)
        printf("| %s (%zu tri) | %s | %.1f (%.1f-%.1f) | %.1f%% | %.1f ms |\n", name,
               m->triangle_count, who[p], med[p], lo[p], hi[p], 100.0 * hits[p] / g_nrays,
               1e3 * bmed[p]);
    printf("| | ours: box tests / triangles tested per ray | %.1f / %.1f | | |\n",
           (double)st.nodes / g_nrays, (double)st.prims / g_nrays);
    if (np == 2)
        printf("| | ratio ours / Embree | %.2f | | %.2f |\n", med[0] / med[1], bmed[0] / bmed[1]);
    cj_bvh_destroy(b);
#ifdef CJ_HAVE_EMBREE
    embree_free(e);
#endif
    free((void *)rays);
}

static cj_mesh *teapot(const cj_patchset *set, double tol) {
    cj_mesh *m;
    if (cj_mesh_create(NULL, &m)) abort();
    cj_tess_options o = {0};
    o.tol = tol;
    cj_tess_report rep;
    if (cj_tessellate_patches(set->patches, set->count, &o, m, &rep)) abort();
    return m;
}

int main(void) {
    cj_patchset *set;
    if (cj_patchset_load_bpt(CJ_TEAPOT_PATH, NULL, &set)) return 1;
    const char *only = getenv("BENCH_ONLY");
    const double tols[2] = {1e-3, 6e-5};
    const char *big = getenv("BENCH_MESH");
    if (only) { /* one piece, for callgrind */
        const char *nr = getenv("BENCH_RAYS");
        if (nr && atoi(nr) > 0 && atoi(nr) <= NRAYS_DEFAULT) g_nrays = atoi(nr);
        cj_mesh *m = teapot(set, tols[big ? 1 : 0]);
        const cj_ray *rays = make_rays(m);
        cj_bvh *b = NULL;
        if (!strcmp(only, "ours_build") || !strcmp(only, "ours_rays")) b = bench_run_ours_build(m);
        const char *rep = getenv("BENCH_REPEAT"); /* for perf: the rays again and again */
        const int nrep = rep && atoi(rep) > 0 ? atoi(rep) : 1;
        for (int k = 0; k < nrep; k++)
            if (!strcmp(only, "ours_rays")) printf("hits %d\n", bench_run_ours_rays(b, rays));
#ifdef CJ_HAVE_EMBREE
        if (!strcmp(only, "embree_build") || !strcmp(only, "embree_rays")) {
            emb e = bench_run_embree_build(m);
            if (!strcmp(only, "embree_rays"))
                printf("hits %d\n", bench_run_embree_rays(e.scene, rays));
            embree_free(e);
        }
#endif
        printf("%zu triangles, %d rays\n", m->triangle_count, g_nrays);
        if (b) cj_bvh_destroy(b);
        free((void *)rays);
        cj_mesh_destroy(m);
        cj_patchset_destroy(set);
        return 0;
    }
    printf("## bench_trace_peer: closest hit, one thread, %d rays, median (range) of %d "
           "interleaved rounds, thread CPU\n\n",
           g_nrays, ROUNDS);
    printf("| mesh | BVH | ns/ray | hit | build (ours: thread CPU; Embree: wall) |\n"
           "|---|---|---|---|---|\n");
    for (int k = 0; k < 2; k++) {
        cj_mesh *m = teapot(set, tols[k]);
        char name[64];
        snprintf(name, sizeof name, "teapot %.1e", tols[k]);
        measure(name, m);
        cj_mesh_destroy(m);
    }
    cj_patchset_destroy(set);
    return 0;
}
