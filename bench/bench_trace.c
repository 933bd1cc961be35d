/* bench_trace: the ray tracer's costs (issue 9).
 *  1. intersection cost per primitive kind (ns per ray, the same random rays aimed at the
 *     primitive's box): triangle, sphere, the quadrics, cylinder, torus, planar, bicubic patch
 *     directly vs its tessellation under a BVH; the teapot's 32 patches directly vs meshes;
 *  2. BVH scaling: closest hit on 1e3..1e6 triangles (constant total area: the same mean free
 *     path), ns and box tests per ray;
 *  3. Embree (if built with it) on the same teapot triangles and the same rays, one thread,
 *     single rays (rtcIntersect1);
 *  4. the tracer on the demo scene (patches direct) and with the teapot as a mesh: rays per
 *     second of each kind (primary, shadow, secondary) from the stage report, on 1 and 2
 *     threads, and ms per frame. */
#define _POSIX_C_SOURCE 200809L
#include "bench_clock.h"
#include "bench_trace_more.h"
#include "casteljau/bvh.h"
#include "casteljau/patchset.h"
#include "casteljau/ray.h"
#include "casteljau/render.h"
#include "casteljau/tessellate.h"
#include "casteljau/trace.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifdef CJ_HAVE_EMBREE
#include "embree_mesh.h"
#endif

static uint64_t rng_state = 88172645463325252ull;
static double urand(void) {
    rng_state ^= rng_state << 13;
    rng_state ^= rng_state >> 7;
    rng_state ^= rng_state << 17;
    return (double)(rng_state >> 11) * 0x1p-53;
}

static cj_vec3 runit(void) {
    for (;;) {
        cj_vec3 p = cj_v3(2 * urand() - 1, 2 * urand() - 1, 2 * urand() - 1);
        double n = cj_v3_norm(p);
        if (n > 0.1 && n <= 1) return cj_v3_scale(p, 1 / n);
    }
}

#define NRAYS 20000
static cj_ray rays[NRAYS];

/* Rays from a sphere of radius 3 R around c towards random points of the box [c ± R]. */
static void make_rays(cj_vec3 c, double R) {
    for (int i = 0; i < NRAYS; i++) {
        cj_vec3 o = cj_v3_add(c, cj_v3_scale(runit(), 3 * R));
        cj_vec3 t = cj_v3_add(
            c, cj_v3(R * (2 * urand() - 1), R * (2 * urand() - 1), R * (2 * urand() - 1)));
        rays[i].org = o;
        rays[i].dir = cj_v3_sub(t, o);
        rays[i].tmin = 0;
        rays[i].tmax = INFINITY;
    }
}

typedef int (*prim_fn)(const void *data, const cj_ray *r, cj_hit *h);

static void time_kind(const char *name, prim_fn fn, const void *data) {
    cj_hit h;
    int hits = 0;
    double best = 1e30;
    for (int rep = 0; rep < 3; rep++) {
        double t0 = cj_bench_wall();
        hits = 0;
        for (int i = 0; i < NRAYS; i++) hits += fn(data, &rays[i], &h);
        double dt = cj_bench_wall() - t0;
        if (dt < best) best = dt;
    }
    printf("  %-34s %9.1f ns/ray  (%5.1f%% hit)\n", name, 1e9 * best / NRAYS, 100.0 * hits / NRAYS);
}

static int f_tri(const void *d, const cj_ray *r, cj_hit *h) {
    const cj_vec3 *v = d;
    return cj_ray_triangle(r, v[0], v[1], v[2], h);
}
static int f_sphere(const void *d, const cj_ray *r, cj_hit *h) {
    (void)d;
    return cj_ray_sphere(r, cj_v3(0, 0, 0), 1.0, h);
}
static int f_quadric(const void *d, const cj_ray *r, cj_hit *h) {
    return cj_ray_quadric(r, d, h);
}
static int f_cyl(const void *d, const cj_ray *r, cj_hit *h) {
    return cj_ray_cylinder(r, d, h);
}
static int f_torus(const void *d, const cj_ray *r, cj_hit *h) {
    return cj_ray_torus(r, d, h);
}
static int f_planar(const void *d, const cj_ray *r, cj_hit *h) {
    return cj_ray_planar(r, d, h);
}
typedef struct patch_data {
    const cj_patch *p;
    double tol;
} patch_data;
static int f_patch(const void *d, const cj_ray *r, cj_hit *h) {
    const patch_data *pd = d;
    return cj_ray_patch(r, pd->p, pd->tol, h, NULL);
}
static int f_mesh(const void *d, const cj_ray *r, cj_hit *h) {
    return cj_bvh_mesh_closest(d, r, h, NULL);
}
typedef struct set_data {
    const cj_patchset *set;
    cj_bvh *bvh;
    double tol;
} set_data;
static int set_cb(void *user, uint32_t prim, const cj_ray *r, cj_hit *h) {
    const set_data *sd = user;
    return cj_ray_patch(r, &sd->set->patches[prim], sd->tol, h, NULL);
}
static int f_set(const void *d, const cj_ray *r, cj_hit *h) {
    const set_data *sd = d;
    return cj_bvh_closest(sd->bvh, r, set_cb, (void *)sd, h, NULL);
}

static cj_mesh *tess(const cj_patch *p, size_t n, double tol, cj_bvh **bvh) {
    cj_mesh *m;
    cj_mesh_create(NULL, &m);
    cj_tess_options o = {0};
    o.tol = tol;
    cj_tess_report rep;
    cj_tessellate_patches(p, n, &o, m, &rep);
    cj_bvh_mesh_build(m->positions, m->vertex_count, m->triangles, m->triangle_count, NULL, bvh);
    return m;
}

#ifdef CJ_HAVE_EMBREE
static void embree_teapot(const cj_mesh *m, cj_bvh *ours) {
    cj_bench_embree e = cj_bench_embree_build(m);
    double best = 1e30;
    int hits = 0;
    for (int rep = 0; rep < 3; rep++) {
        double t0 = cj_bench_wall();
        hits = cj_bench_embree_rays(e.scene, rays, NRAYS);
        double dt = cj_bench_wall() - t0;
        if (dt < best) best = dt;
    }
    printf("  %-34s %9.1f ns/ray  (%5.1f%% hit)  [Embree 3, float, 1 thread]\n",
           "teapot mesh, Embree rtcIntersect1", 1e9 * best / NRAYS, 100.0 * hits / NRAYS);
    (void)ours;
    cj_bench_embree_free(e);
}
#endif

static void tracer_run(const char *name, cj_scene *sc, int w, int h) {
    for (int th = 1; th <= 2; th++) {
        cj_render_options o = cj_render_options_defaults();
        o.width = w;
        o.height = h;
        o.threads = th;
        cj_render_image *img;
        cj_stage_report rep;
        double t0 = cj_bench_wall();
        if (cj_render_trace(sc, &o, 0, NULL, &img, &rep)) {
            printf("trace failed: %s\n", cj_last_error());
            return;
        }
        double wall = cj_bench_wall() - t0;
        cj_render_image_destroy(img);
        const char *kinds[4] = {"primary_rays", "shadow_rays", "reflection_rays",
                                "refraction_rays"};
        printf("  %-22s %d thread%s: %7.0f ms/frame;", name, th, th > 1 ? "s" : " ", 1e3 * wall);
        for (int k = 0; k < 4; k++) {
            const cj_stage *s = cj_stage_report_find(&rep, kinds[k]);
            if (!s || !s->in) continue;
            /* seconds are summed over threads: per-thread rate x threads = throughput */
            printf(" %s %.2f M/s",
                   k == 0   ? "primary"
                   : k == 1 ? "shadow"
                   : k == 2 ? "reflect"
                            : "refract",
                   1e-6 * (double)s->in / s->seconds * th);
        }
        printf("\n");
    }
}

/* Soft shadows: a sphere on a floor under an area light; RMSE against a 1024-spp reference
 * for 1..256 spp (stratified samples: pixel positions and light points) and ms per frame. */
static void rmse_vs_spp(void) {
    cj_scene *sc;
    if (cj_scene_create(NULL, &sc)) return;
    cj_camera cam = cj_camera_defaults();
    cam.eye = cj_v3(0, 3, 6);
    cam.gaze = cj_v3(0, -2.5, -6);
    cj_scene_set_camera(sc, &cam);
    cj_scene_settings set = cj_scene_settings_defaults();
    set.width = 64;
    set.height = 48;
    cj_scene_set_settings(sc, &set);
    cj_light amb = cj_light_defaults(CJ_LIGHT_AMBIENT), area = cj_light_defaults(CJ_LIGHT_AREA);
    amb.intensity = 0.2;
    area.position = cj_v3(-1.5, 4, -1.5);
    area.edge_u = cj_v3(3, 0, 0);
    area.edge_v = cj_v3(0, 0, 3);
    cj_scene_add_light(sc, &amb, NULL);
    cj_scene_add_light(sc, &area, NULL);
    cj_material m = cj_material_defaults();
    int im, g1, g2;
    cj_scene_add_material(sc, &m, &im);
    cj_geometry g;
    memset(&g, 0, sizeof g);
    g.kind = CJ_GEOM_PLANAR;
    cj_planar_patch_init(&g.u.planar, cj_v3(-10, 0, 10), cj_v3(20, 0, 0), cj_v3(0, 0, -20));
    cj_scene_add_geometry(sc, &g, &g1);
    memset(&g, 0, sizeof g);
    g.kind = CJ_GEOM_SPHERE;
    g.u.sphere.center = cj_v3(0, 1, 0);
    g.u.sphere.radius = 1;
    cj_scene_add_geometry(sc, &g, &g2);
    cj_node n;
    memset(&n, 0, sizeof n);
    n.parent = -1;
    n.local = cj_transform_identity();
    n.visible = 1;
    n.overlay.iso_count = 1;
    n.overlay.normal_length = 0.1;
    n.material = im;
    n.geometry = g1;
    cj_scene_add_node(sc, &n, NULL);
    n.geometry = g2;
    cj_scene_add_node(sc, &n, NULL);
    cj_render_options o = cj_render_options_defaults();
    o.threads = 2;
    o.spp = 1024;
    cj_render_image *ref;
    if (cj_render_trace(sc, &o, 0, NULL, &ref, NULL)) return;
    printf("\nsoft shadow (area light), 64x48, RMSE against 1024 spp (stratified), 2 threads\n");
    for (int mode = 0; mode < 2; mode++) {
        cj_trace_options to = {mode, 0, 0, 0, 0};
        printf("  %s sampling (pixel positions and light points)\n",
               mode ? "plain random" : "stratified");
        double prev = 0;
        for (int spp = 1; spp <= 256; spp *= 4) {
            o.spp = spp;
            o.use_seed = 1;
            o.seed = 777;
            cj_render_image *img;
            double t0 = cj_bench_wall();
            if (cj_render_trace_with_options(sc, &o, &to, 0, NULL, &img, NULL)) break;
            double dt = cj_bench_wall() - t0, e = 0;
            size_t np = 64 * 48;
            for (size_t i = 0; i < np; i++)
                for (int k = 0; k < 3; k++) {
                    double d = img->rgba[4 * i + k] - ref->rgba[4 * i + k];
                    e += d * d;
                }
            e = sqrt(e / (3.0 * np));
            printf("    spp %4d: RMSE %.5f  %8.1f ms/frame", spp, e, 1e3 * dt);
            if (prev > 0) printf("  ratio to 1/4 the samples %.2f (1/sqrt(n): 0.50)", e / prev);
            printf("\n");
            prev = e;
            cj_render_image_destroy(img);
        }
    }
    cj_render_image_destroy(ref);
    cj_scene_destroy(sc);
}

int main(int argc, char **argv) {
    if (argc > 1 && strcmp(argv[1], "--sampling") == 0) { /* only the noise against spp */
        rmse_vs_spp();
        bench_trace_rmse_shipped(CJ_SCENES_DIR "/raytrace.json", CJ_TEAPOT_PATH);
        return 0;
    }
    if (argc > 1) {
        fprintf(stderr, "usage: bench_trace [--sampling]\n");
        return 2;
    }
    printf("bench_trace: intersection cost per primitive kind (%d rays at the primitive's box)\n",
           NRAYS);
    make_rays(cj_v3(0, 0, 0), 1.0);
    cj_vec3 tri[3] = {cj_v3(-1, -1, 0.1), cj_v3(1, -0.8, -0.2), cj_v3(0.1, 1, 0)};
    time_kind("triangle (watertight)", f_tri, tri);
    time_kind("sphere", f_sphere, NULL);
    cj_quadric q[6];
    cj_quadric_ellipsoid(&q[0], 1, 0.8, 0.6);
    cj_quadric_hyperboloid1(&q[1], 0.5, 0.5, 0.5, -1, 1);
    cj_quadric_hyperboloid2(&q[2], 0.5, 0.5, 0.5, 0, 1);
    cj_quadric_cone(&q[3], 0.5, 0.5, 1, -1, 1);
    cj_quadric_paraboloid(&q[4], 0.7, 0.7, 1);
    cj_quadric_hyperbolic_paraboloid(&q[5], 1, 1, -1, 1, -1, 1);
    const char *qn[6] = {"ellipsoid",  "hyperboloid (1 sheet)", "hyperboloid (2 sheets)", "cone",
                         "paraboloid", "hyperbolic paraboloid"};
    for (int i = 0; i < 6; i++) time_kind(qn[i], f_quadric, &q[i]);
    cj_cylinder cy;
    cj_cylinder_init(&cy, cj_v3(0, 0, -1), cj_v3(0.2, 0.1, 1), 0.6, 0, 2);
    time_kind("cylinder", f_cyl, &cy);
    cj_torus to;
    cj_torus_init(&to, cj_v3(0, 0, 0), cj_v3(0.3, 0.2, 1), 0.7, 0.25);
    time_kind("torus (quartic, isolated roots)", f_torus, &to);
    cj_planar_patch pp;
    cj_planar_patch_init(&pp, cj_v3(-1, -1, 0), cj_v3(2, 0, 0.3), cj_v3(0, 2, 0));
    time_kind("planar patch", f_planar, &pp);
    /* a bicubic bump */
    double pts[48];
    for (int j = 0; j < 4; j++)
        for (int i = 0; i < 4; i++) {
            pts[3 * (4 * j + i)] = -1 + 2 * i / 3.0;
            pts[3 * (4 * j + i) + 1] = -1 + 2 * j / 3.0;
            pts[3 * (4 * j + i) + 2] = ((i == 1 || i == 2) && (j == 1 || j == 2)) ? 0.8 : -0.2;
        }
    cj_patch P = cj_patch_view(3, 3, pts, NULL);
    const double tols[3] = {1e-4, 1e-7, 1e-10};
    for (int k = 0; k < 3; k++) {
        patch_data pd = {&P, tols[k]};
        char name[64];
        snprintf(name, sizeof name, "bicubic patch direct, tol %.0e", tols[k]);
        time_kind(name, f_patch, &pd);
    }
    for (int k = 0; k < 2; k++) {
        cj_bvh *b;
        double tt = k ? 1e-4 : 1e-3;
        cj_mesh *m = tess(&P, 1, tt, &b);
        char name[64];
        snprintf(name, sizeof name, "bicubic tessellated %.0e (%zu tri)", tt, m->triangle_count);
        time_kind(name, f_mesh, b);
        cj_bvh_destroy(b);
        cj_mesh_destroy(m);
    }

    printf("\nthe teapot (32 bicubic patches, box diagonal %.2f)\n", 8.3);
    cj_patchset *set;
    if (cj_patchset_load_bpt(CJ_TEAPOT_PATH, NULL, &set)) return 1;
    make_rays(cj_v3(0.25, 0, 1.5), 2.0);
    set_data sd;
    sd.set = set;
    cj_aabb boxes[64];
    for (size_t i = 0; i < set->count; i++) boxes[i] = cj_aabb_patch(&set->patches[i]);
    cj_bvh_build(boxes, set->count, NULL, &sd.bvh);
    for (int k = 0; k < 2; k++) {
        sd.tol = k ? 1e-9 : 1e-6;
        char name[64];
        snprintf(name, sizeof name, "teapot patches direct, tol %.0e", sd.tol);
        time_kind(name, f_set, &sd);
    }
    cj_mesh *tm = NULL;
    cj_bvh *tb = NULL;
    cj_mesh *fine = NULL;
    for (int k = 0; k < 3; k++) {
        const double tt[3] = {1e-2, 1e-3, 1e-4};
        cj_bvh *b;
        cj_mesh *m = tess(set->patches, set->count, tt[k], &b);
        char name[64];
        snprintf(name, sizeof name, "teapot mesh %.0e (%zu tri)", tt[k], m->triangle_count);
        time_kind(name, f_mesh, b);
        if (k == 1) {
            tm = m;
            tb = b;
        } else if (k == 2) {
            fine = m; /* the reference of the patch-tolerance section */
            cj_bvh_destroy(b);
        } else {
            cj_bvh_destroy(b);
            cj_mesh_destroy(m);
        }
    }
#ifdef CJ_HAVE_EMBREE
    embree_teapot(tm, tb);
#else
    printf("  (built without Embree)\n");
#endif

    printf("\nBVH scaling (random triangles in a fixed cube, constant total area)\n");
    for (size_t n = 1000; n <= 1000000; n *= 10) {
        double *pos = malloc(9 * n * sizeof *pos);
        uint32_t *ix = malloc(3 * n * sizeof *ix);
        double sz = 4.0 * sqrt(100.0 / (double)n);
        for (size_t t = 0; t < n; t++) {
            cj_vec3 c = cj_v3(10 * urand(), 10 * urand(), 10 * urand());
            for (int k = 0; k < 3; k++) {
                cj_vec3 v = cj_v3_add(c, cj_v3_scale(runit(), sz));
                pos[9 * t + 3 * k] = v.x;
                pos[9 * t + 3 * k + 1] = v.y;
                pos[9 * t + 3 * k + 2] = v.z;
                ix[3 * t + k] = (uint32_t)(3 * t + k);
            }
        }
        double t0 = cj_bench_wall();
        cj_bvh *b;
        cj_bvh_mesh_build(pos, 3 * n, ix, n, NULL, &b);
        double tb_s = cj_bench_wall() - t0;
        for (int i = 0; i < NRAYS; i++) {
            rays[i].org = cj_v3(10 * urand(), 10 * urand(), 10 * urand());
            rays[i].dir = runit();
            rays[i].tmin = 0;
            rays[i].tmax = INFINITY;
        }
        cj_bvh_trav_stats st = {0};
        cj_hit h;
        t0 = cj_bench_wall();
        for (int i = 0; i < NRAYS; i++) cj_bvh_mesh_closest(b, &rays[i], &h, &st);
        double dt = cj_bench_wall() - t0;
        printf("  %8zu triangles: build %7.1f ms, depth %2d, %6.1f ns/ray, %5.1f boxes + %4.1f "
               "triangles per ray\n",
               n, 1e3 * tb_s, b->depth, 1e9 * dt / NRAYS, (double)st.nodes / NRAYS,
               (double)st.prims / NRAYS);
        cj_bvh_destroy(b);
        free(pos);
        free(ix);
    }

    printf("\nthe tracer, demo scene 320x240, spp 1, max depth 6 (rays/s per thread x threads)\n");
    cj_scene *sc;
    if (cj_trace_demo_scene(CJ_TEAPOT_PATH, NULL, &sc)) return 1;
    tracer_run("teapot as patches", sc, 320, 240);
    /* the same scene with the teapot as a mesh (tessellated at 1e-3) */
    cj_geometry *g = cj_scene_geometry_mut(sc, 0);
    cj_geometry gm;
    memset(&gm, 0, sizeof gm);
    gm.kind = CJ_GEOM_MESH;
    gm.u.mesh = tm;
    int gi;
    (void)g;
    if (cj_scene_add_geometry(sc, &gm, &gi) == CJ_OK) {
        cj_node *nd = cj_scene_node_mut(sc, 0);
        nd->geometry = gi;
        tracer_run("teapot as mesh 1e-3", sc, 320, 240);
    }
    cj_scene_destroy(sc);
    cj_bvh_destroy(tb);
    cj_mesh_destroy(tm);
    cj_bvh_destroy(sd.bvh);
    cj_patchset_destroy(set);
    bench_trace_tolerance(CJ_TEAPOT_PATH, fine, 1e-4);
    cj_mesh_destroy(fine);
    rmse_vs_spp();
    bench_trace_rmse_shipped(CJ_SCENES_DIR "/raytrace.json", CJ_TEAPOT_PATH);
    bench_trace_povray();
    return 0;
}
