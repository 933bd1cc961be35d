/* bench_scene: cost of reading scenes and meshes. Loads of the shipped scenes (median of 15),
 * then one grid mesh of 2·n² triangles saved as a JSON scene (inline mesh), OBJ, ASCII PLY and
 * binary PLY and read back: milliseconds, MB/s and triangles per second (thread CPU time, so
 * other processes on the machine do not count). */
#include "bench_clock.h"

#include "casteljau/mesh_read.h"
#include "casteljau/scene_json.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#define REPS 15

static double file_mb(const char *path) {
    struct stat st;
    return stat(path, &st) == 0 ? (double)st.st_size / 1e6 : 0.0;
}

static void load_scene(const char *name) {
    char path[512];
    snprintf(path, sizeof path, "%s/%s", CJ_SCENES_DIR, name);
    const cj_scene_json_options opt = {CJ_TEAPOT_PATH};
    double t[REPS];
    for (int r = 0; r < REPS; ++r) {
        cj_scene *s;
        double t0 = cj_bench_thread_cpu();
        if (cj_scene_load_json_with_options(path, &opt, NULL, &s)) {
            fprintf(stderr, "%s\n", cj_last_error());
            exit(1);
        }
        t[r] = cj_bench_thread_cpu() - t0;
        cj_scene_destroy(s);
    }
    printf("| %-18s | %8.3f ms |\n", name, 1e3 * cj_bench_median(t, REPS));
}

static cj_mesh *grid(int n) {
    cj_mesh *m;
    if (cj_mesh_create(NULL, &m)) exit(1);
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) {
            double u = (double)i / n, v = (double)j / n;
            double p[3] = {u, v, 0.1 * u * v}, q[3] = {-0.1 * v, -0.1 * u, 1}, uv[2] = {u, v};
            cj_mesh_add_vertex(m, p, q, uv, NULL);
        }
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            uint32_t a = (uint32_t)(j * (n + 1) + i), b = a + 1, c = a + (uint32_t)n + 1, d = c + 1;
            cj_mesh_add_triangle(m, a, b, d, 0);
            cj_mesh_add_triangle(m, a, d, c, 0);
        }
    return m;
}

static void time_mesh(const char *what, const char *path, size_t tris) {
    double t[5];
    for (int r = 0; r < 5; ++r) {
        cj_mesh *m;
        double t0 = cj_bench_thread_cpu();
        if (cj_mesh_read(path, NULL, &m)) {
            fprintf(stderr, "%s\n", cj_last_error());
            exit(1);
        }
        t[r] = cj_bench_thread_cpu() - t0;
        cj_mesh_destroy(m);
    }
    double s = cj_bench_median(t, 5), mb = file_mb(path);
    printf("| %-18s | %7.2f MB | %8.1f ms | %6.1f MB/s | %6.2f M tri/s |\n", what, mb, 1e3 * s,
           mb / s, tris / s / 1e6);
}

int main(int argc, char **argv) {
    int n = argc > 1 ? atoi(argv[1]) : 200;
    printf("bench_scene: scene loads (median of %d, thread CPU)\n\n", REPS);
    printf("| scene              | load        |\n|---|---|\n");
    const char *scenes[] = {"teapot.json", "quadrics.json", "revolution.json", "gallery.json"};
    for (int i = 0; i < 4; ++i) load_scene(scenes[i]);

    char dir[] = "/tmp/cj_bench_scene_XXXXXX";
    if (!mkdtemp(dir)) return 1;
    char pj[64], po[64], pa[64], pb[64];
    snprintf(pj, sizeof pj, "%s/m.json", dir);
    snprintf(po, sizeof po, "%s/m.obj", dir);
    snprintf(pa, sizeof pa, "%s/a.ply", dir);
    snprintf(pb, sizeof pb, "%s/b.ply", dir);
    cj_mesh *m = grid(n);
    size_t tris = m->triangle_count;
    cj_scene *s;
    cj_scene_create(NULL, &s);
    cj_geometry g;
    memset(&g, 0, sizeof g);
    g.kind = CJ_GEOM_MESH;
    g.u.mesh = m;
    cj_material mat = cj_material_defaults();
    int gi, mi;
    cj_scene_add_geometry(s, &g, &gi);
    cj_scene_add_material(s, &mat, &mi);
    cj_node node;
    memset(&node, 0, sizeof node);
    node.parent = -1, node.geometry = gi, node.material = mi, node.visible = 1;
    node.local = cj_transform_identity();
    cj_scene_add_node(s, &node, NULL);
    double t0 = cj_bench_thread_cpu();
    if (cj_scene_save_json(s, pj)) return 1;
    double tsave = cj_bench_thread_cpu() - t0;
    cj_mesh_write_obj(m, po);
    cj_mesh_write_ply(m, pa, 0);
    cj_mesh_write_ply(m, pb, 1);
    printf("\nbench_scene: a grid mesh of %zu triangles, %zu vertices (median of 5 reads)\n\n",
           tris, m->vertex_count);
    printf("| format             | size       | read        | rate        | triangles      |\n"
           "|---|---|---|---|---|\n");
    double t[5];
    for (int r = 0; r < 5; ++r) {
        cj_scene *b;
        double a0 = cj_bench_thread_cpu();
        if (cj_scene_load_json(pj, NULL, &b)) {
            fprintf(stderr, "%s\n", cj_last_error());
            return 1;
        }
        t[r] = cj_bench_thread_cpu() - a0;
        cj_scene_destroy(b);
    }
    double sj = cj_bench_median(t, 5), mbj = file_mb(pj);
    printf("| %-18s | %7.2f MB | %8.1f ms | %6.1f MB/s | %6.2f M tri/s |\n", "JSON (inline mesh)",
           mbj, 1e3 * sj, mbj / sj, tris / sj / 1e6);
    time_mesh("OBJ", po, tris);
    time_mesh("PLY ascii", pa, tris);
    time_mesh("PLY binary", pb, tris);
    printf("\nJSON save of that scene: %.1f ms (%.1f MB/s)\n", 1e3 * tsave, mbj / tsave);
    cj_scene_destroy(s);
    cj_mesh_destroy(m);
    unlink(pj);
    unlink(po);
    unlink(pa);
    unlink(pb);
    rmdir(dir);
    return 0;
}
