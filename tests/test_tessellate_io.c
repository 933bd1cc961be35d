/* Tessellation output and input (split from test_tessellate.c): OBJ/PLY export of the
 * teapot mesh, the .bpt loader's messages on bad files, and the caller's allocator and the mesh
 * errors. */
#define _POSIX_C_SOURCE 200809L
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "casteljau/analytic.h"
#include "casteljau/patchset.h"
#include "casteljau/quadric.h"
#include "casteljau/tessellate.h"
#include "rng.h"
#include "tessellate_test.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#ifndef CJ_TEAPOT_PATH
#define CJ_TEAPOT_PATH "data/teapot.bpt"
#endif

static void slurp(const char *path, char **buf, size_t *len) {
    FILE *f = fopen(path, "rb");
    assert_non_null(f);
    fseek(f, 0, SEEK_END);
    long n = ftell(f);
    fseek(f, 0, SEEK_SET);
    *buf = malloc((size_t)n + 1);
    assert_true(fread(*buf, 1, (size_t)n, f) == (size_t)n);
    (*buf)[n] = '\0';
    *len = (size_t)n;
    fclose(f);
}

static void test_export(void **state) {
    (void)state;
    cj_patchset *set;
    assert_int_equal(cj_patchset_load_bpt(CJ_TEAPOT_PATH, NULL, &set), CJ_OK);
    cj_mesh *mesh;
    assert_int_equal(cj_mesh_create(NULL, &mesh), CJ_OK);
    cj_tess_options opt = {0.0, 3, 0, 0};
    assert_int_equal(cj_tessellate_patches(set->patches, set->count, &opt, mesh, NULL), CJ_OK);
    char dir[] = "/tmp/cj_tess_XXXXXX";
    assert_non_null(mkdtemp(dir));
    char obj[256], ply[256], bad[256], plya[256];
    snprintf(obj, sizeof obj, "%s/t.obj", dir);
    snprintf(ply, sizeof ply, "%s/t.ply", dir);
    snprintf(plya, sizeof plya, "%s/ta.ply", dir);
    snprintf(bad, sizeof bad, "%s/missing/t.obj", dir);
    assert_int_equal(cj_mesh_write(mesh, obj), CJ_OK);
    assert_int_equal(cj_mesh_write(mesh, ply), CJ_OK);
    assert_int_equal(cj_mesh_write_ply(mesh, plya, 0), CJ_OK);
    assert_int_equal(cj_mesh_write(mesh, bad), CJ_ERR_IO);
    assert_int_equal(access(bad, F_OK), -1);
    assert_int_equal(cj_mesh_write(mesh, "x.stl"), CJ_ERR_ARGUMENT);
    /* OBJ: one v per distinct position, vt/vn per vertex, a g per patch, faces p/t/n */
    cj_mesh_topology topo;
    cj_mesh_topology_compute(mesh, &topo);
    char *text;
    size_t len;
    slurp(obj, &text, &len);
    size_t nv = 0, nvt = 0, nvn = 0, nf = 0, ng = 0;
    for (char *line = strtok(text, "\n"); line; line = strtok(NULL, "\n")) {
        if (!strncmp(line, "v ", 2)) ++nv;
        if (!strncmp(line, "vt ", 3)) ++nvt;
        if (!strncmp(line, "vn ", 3)) ++nvn;
        if (!strncmp(line, "g patch_", 8)) ++ng;
        if (!strncmp(line, "f ", 2)) {
            unsigned a[9];
            assert_int_equal(sscanf(line, "f %u/%u/%u %u/%u/%u %u/%u/%u", &a[0], &a[1], &a[2],
                                    &a[3], &a[4], &a[5], &a[6], &a[7], &a[8]),
                             9);
            ++nf;
        }
    }
    free(text);
    assert_int_equal(nvt, mesh->vertex_count);
    assert_int_equal(nvn, mesh->vertex_count);
    assert_int_equal(nf, mesh->triangle_count);
    assert_int_equal(ng, 32);
    assert_true(nv < mesh->vertex_count); /* welded: seam vertices written once */
    /* PLY binary: header + 8 doubles per vertex + (1 + 3*4) bytes per face */
    slurp(ply, &text, &len);
    char *end = strstr(text, "end_header\n");
    assert_non_null(end);
    assert_non_null(strstr(text, "binary_little_endian"));
    const size_t header = (size_t)(end - text) + strlen("end_header\n");
    assert_int_equal(len, header + 64 * mesh->vertex_count + 13 * mesh->triangle_count);
    double x0;
    memcpy(&x0, text + header, 8);
    assert_true(x0 == mesh->positions[0]);
    free(text);
    slurp(plya, &text, &len);
    assert_non_null(strstr(text, "format ascii 1.0"));
    free(text);
    unlink(obj);
    unlink(ply);
    unlink(plya);
    rmdir(dir);
    cj_mesh_destroy(mesh);
    cj_patchset_destroy(set);
    printf("export: OBJ (welded v, per-vertex vt/vn, 32 g groups, p/t/n faces), binary and ascii "
           "PLY layout, unwritable path -> CJ_ERR_IO and no file, unknown extension\n");
}

static void test_bpt_errors(void **state) {
    (void)state;
    cj_patchset *set = NULL;
    assert_int_equal(
        cj_patchset_parse_bpt("1\n1 1\n0 0 0\n1 0 0\n0 x 0\n1 1 1\n", "a.bpt", NULL, &set),
        CJ_ERR_PARSE);
    assert_non_null(strstr(cj_last_error(), "a.bpt:5:"));
    assert_non_null(strstr(cj_last_error(), "'x'"));
    assert_int_equal(cj_patchset_parse_bpt("1\n1 1\n0 0 0\n1 0 0\n", "b.bpt", NULL, &set),
                     CJ_ERR_PARSE);
    assert_non_null(strstr(cj_last_error(), "end of file"));
    assert_int_equal(cj_patchset_parse_bpt("1\n40 1\n", "c.bpt", NULL, &set), CJ_ERR_DEGREE);
    assert_non_null(strstr(cj_last_error(), "c.bpt:2:"));
    assert_int_equal(cj_patchset_parse_bpt("1 # one patch\n0 0\n1 2 3\n7\n", "d.bpt", NULL, &set),
                     CJ_ERR_PARSE);
    assert_non_null(strstr(cj_last_error(), "d.bpt:4:"));
    assert_int_equal(
        cj_patchset_parse_bpt("1 # one patch\n0 0\n1 2 3 # a point\n", "e.bpt", NULL, &set), CJ_OK);
    assert_true(set->count == 1 && set->patches[0].pts[2] == 3.0);
    cj_patchset_destroy(set);
    assert_int_equal(cj_patchset_load_bpt("/nonexistent/x.bpt", NULL, &set), CJ_ERR_IO);
    assert_non_null(strstr(cj_last_error(), "/nonexistent/x.bpt"));
    printf(".bpt loader: line-numbered messages for a bad number, end of file, a degree over the "
           "limit, trailing data; comments; missing file names the path\n");
}

typedef struct counting {
    size_t allocs, frees;
} counting;

static void *count_alloc(void *user, size_t bytes) {
    ++((counting *)user)->allocs;
    return malloc(bytes);
}
static void count_free(void *user, void *ptr) {
    if (ptr) ++((counting *)user)->frees;
    free(ptr);
}

static void test_allocator_and_mesh_errors(void **state) {
    (void)state;
    counting c = {0, 0};
    const cj_allocator a = {count_alloc, count_free, &c};
    cj_patchset *set;
    assert_int_equal(cj_patchset_load_bpt(CJ_TEAPOT_PATH, &a, &set), CJ_OK);
    cj_mesh *mesh;
    assert_int_equal(cj_mesh_create(&a, &mesh), CJ_OK);
    cj_tess_options opt = {1e-2, 0, 0, 0};
    assert_int_equal(cj_tessellate_patches(set->patches, set->count, &opt, mesh, NULL), CJ_OK);
    assert_true(c.allocs > 10);
    const double p[3] = {0, 0, 0}, bad[3] = {0, NAN, 0};
    uint32_t idx;
    assert_int_equal(cj_mesh_add_vertex(mesh, bad, NULL, NULL, &idx), CJ_ERR_NONFINITE);
    assert_int_equal(cj_mesh_add_vertex(mesh, p, NULL, NULL, &idx), CJ_OK);
    assert_int_equal(cj_mesh_add_triangle(mesh, idx, idx + 1, 0, 0), CJ_ERR_RANGE);
    assert_non_null(strstr(cj_last_error(), "vertex index"));
    cj_mesh_destroy(mesh);
    cj_patchset_destroy(set);
    assert_int_equal(c.allocs, c.frees);
    printf("allocator: %zu allocations of the teapot set, mesh and tessellation temporaries all "
           "through the caller's allocator and all released; NaN vertex and bad index rejected\n",
           c.allocs);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_export),
        cmocka_unit_test(test_bpt_errors),
        cmocka_unit_test(test_allocator_and_mesh_errors),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
