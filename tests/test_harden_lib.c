/* Library side of issue 14: overflow is CJ_ERR_RANGE (error bounds, spline control points,
 * interpolation intervals), contouring refuses tolerances doubles cannot resolve, the
 * tessellation size predictor (exact for uniform grids, close for adaptive ones), degenerate
 * patches refused instead of an empty mesh, plot titles capped, and plots of data spanning the
 * whole double range refused cleanly (a NaN tick count was converted to int before).
 * Issue 24: the one whole-file reader (devices, pipes and folders refused unread, its cap held to
 * the byte, inputs logged by inode), the one atomic writer (abandon, commit, a SIGTERM removes
 * the temporary) and particle emission bounded per step. */
#define _DEFAULT_SOURCE /* mkdtemp, mkfifo, link */
#include "casteljau/bezier.h"
#include "casteljau/catmull_rom.h"
#include "casteljau/implicit.h"
#include "casteljau/interp.h"
#include "casteljau/patchset.h"
#include "casteljau/plot.h"
#include "casteljau/particles.h"
#include "casteljau/tessellate.h"
#include "file_internal.h"

#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include <dirent.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

static void test_overflow_is_range(void **state) {
    (void)state;
    const double big[4] = {1.7e308, 1.7e308, 1.7e308, 1.7e308};
    cj_bezier c = cj_bezier_view(1, 2, big);
    double v[2], b[2];
    assert_int_equal(cj_bezier_eval(&c, CJ_EVAL_BERNSTEIN, 0.5, v), CJ_OK);
    assert_int_equal(cj_bezier_error_bound(&c, CJ_EVAL_BERNSTEIN, 0.5, b), CJ_ERR_RANGE);
    assert_non_null(strstr(cj_last_error(), "overflows"));

    const double far[8] = {-1e308, 0, 1e308, 0, -1e308, 1, 1e308, 1};
    double segs[3 * 8];
    assert_int_equal(cj_catmull_rom(far, 4, 2, NULL, segs, 3, NULL, NULL), CJ_ERR_RANGE);
    cj_spline_options o = cj_spline_defaults();
    o.kind = CJ_SPLINE_CENTRIPETAL;
    const double apart[6] = {-1e308, 0, 1e308, 0, 0, 1};
    assert_int_equal(cj_catmull_rom(apart, 3, 2, &o, segs, 2, NULL, NULL), CJ_ERR_RANGE);
    assert_null(strstr(cj_last_error(), "coincide"));

    const double ts[3] = {-1e308, 0, 1e308}, ys[3] = {0, 1, 2};
    double bez[3];
    assert_int_equal(cj_interp_points(ts, ys, 3, 1, -1e308, 1e308, bez, NULL, NULL), CJ_ERR_RANGE);
    assert_null(strstr(cj_last_error(), "LAPACK"));
    printf("test_harden_lib: bound, spline and interpolation overflow are CJ_ERR_RANGE with "
           "messages about the input\n");
}

static cj_status nop_emit(void *u, const double *xy, size_t n, int closed, double res) {
    (void)u, (void)xy, (void)n, (void)closed, (void)res;
    return CJ_OK;
}

static void test_contour_tolerance_floor(void **state) {
    (void)state;
    cj_implicit_shape s;
    cj_implicit f;
    assert_int_equal(cj_implicit_circle(0, 0, 1.9, &s, &f), CJ_OK);
    const double box[4] = {-2, -2, 2, 2};
    cj_contour_options o = {4096, 4096, 1e-300, NULL};
    assert_int_equal(cj_implicit_contour(&f, box, &o, nop_emit, NULL, NULL), CJ_ERR_RANGE);
    o.tol = 0.99 * CJ_CONTOUR_MIN_REL_TOL * 4.0;
    assert_int_equal(cj_implicit_contour(&f, box, &o, nop_emit, NULL, NULL), CJ_ERR_RANGE);
    o.nx = o.ny = 16;
    o.tol = 1e-6;
    assert_int_equal(cj_implicit_contour(&f, box, &o, nop_emit, NULL, NULL), CJ_OK);
    const double huge[4] = {-1e308, -1e308, 1e308, 1e308};
    o.tol = 1e300;
    assert_int_equal(cj_implicit_contour(&f, huge, &o, nop_emit, NULL, NULL), CJ_ERR_RANGE);
    assert_non_null(strstr(cj_last_error(), "box"));
    printf("test_harden_lib: contour tolerances below 2^-40 x scale and boxes wider than the "
           "double range refused before any work\n");
}

static void test_tessellation_prediction(void **state) {
    (void)state;
    cj_patchset *set = NULL;
    assert_int_equal(cj_patchset_load_bpt(CJ_TEAPOT_PATH, NULL, &set), CJ_OK);
    double lo[3], hi[3], size;
    assert_int_equal(cj_patchset_bbox(set, lo, hi, &size), CJ_OK);
    cj_tess_options u = {0.0, 7, 0, 0};
    double pred;
    assert_int_equal(cj_tessellate_predict(set->patches, set->count, &u, &pred), CJ_OK);
    assert_true(pred == 2.0 * 49.0 * (double)set->count);
    u.uniform = 4096; /* 1.07e9 triangles: predicted at once, nothing built */
    assert_int_equal(cj_tessellate_predict(set->patches, set->count, &u, &pred), CJ_OK);
    assert_true(pred > 1e9);
    for (int k = 2; k <= 4; ++k) {
        cj_tess_options a = {pow(10.0, -k) * size, 0, 0, 0};
        cj_mesh *m = NULL;
        cj_tess_report rep;
        assert_int_equal(cj_tessellate_predict(set->patches, set->count, &a, &pred), CJ_OK);
        assert_int_equal(cj_mesh_create(NULL, &m), CJ_OK);
        assert_int_equal(cj_tessellate_patches(set->patches, set->count, &a, m, &rep), CJ_OK);
        const double ratio = (double)rep.triangles / pred;
        printf("test_harden_lib: teapot at tol %.0e x size: predicted %.0f, made %zu (x%.2f)\n",
               pow(10.0, -k), pred, rep.triangles, ratio);
        assert_true(ratio >= 0.5 && ratio <= 2.0); /* the documented range, with margin */
        cj_mesh_destroy(m);
    }
    cj_patchset_destroy(set);
}

static void test_degenerate_patches(void **state) {
    (void)state;
    const double same[12] = {1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1};
    const cj_patch p11 = cj_patch_view(1, 1, same, NULL);
    const cj_patch p00 = cj_patch_view(0, 0, same, NULL);
    const cj_patch *cases[2] = {&p11, &p00};
    for (int c = 0; c < 2; ++c)
        for (int uniform = 0; uniform <= 3; uniform += 3) {
            cj_tess_options o = {1e-3, uniform, 0, 0};
            cj_mesh *m = NULL;
            assert_int_equal(cj_mesh_create(NULL, &m), CJ_OK);
            assert_int_equal(cj_tessellate_patches(cases[c], 1, &o, m, NULL), CJ_ERR_DEGENERATE);
            assert_int_equal(m->triangle_count, 0);
            cj_mesh_destroy(m);
        }
    printf("test_harden_lib: degenerate patches (all points equal, degree 0,0) are "
           "CJ_ERR_DEGENERATE in both modes, never an empty mesh called success\n");
}

static void test_plot_limits(void **state) {
    (void)state;
    cj_plot *p = NULL;
    assert_int_equal(cj_plot_create(NULL, &p), CJ_OK);
    char *title = malloc(CJ_PLOT_MAX_TITLE + 2);
    assert_non_null(title);
    memset(title, 'x', CJ_PLOT_MAX_TITLE + 1);
    title[CJ_PLOT_MAX_TITLE + 1] = '\0';
    assert_int_equal(cj_plot_set_title(p, title), CJ_ERR_RANGE);
    title[CJ_PLOT_MAX_TITLE] = '\0';
    assert_int_equal(cj_plot_set_title(p, title), CJ_OK);
    free(title);
    const double span[4] = {-1e308, -1e308, 1e308, 1e308};
    assert_int_equal(cj_plot_add_points(p, span, 2, cj_rgba_make(0, 0, 0, 255), 3), CJ_OK);
    cj_framebuffer *fb = NULL;
    assert_int_equal(cj_framebuffer_create(200, 150, 0, NULL, &fb), CJ_OK);
    /* the span overflows: refused with a status; with a font the layout computes ticks for it
     * (a NaN count converted to int: UB that clang's float-cast-overflow check reports) */
    cj_font *font = NULL;
    assert_int_equal(cj_font_open(NULL, &font), CJ_OK);
    assert_int_not_equal(cj_plot_render(p, fb, 0, 0, 200, 150, font), CJ_OK);
    assert_int_not_equal(cj_plot_render(p, fb, 0, 0, 200, 150, NULL), CJ_OK);
    cj_font_close(font);
    cj_framebuffer_destroy(fb);
    cj_plot_destroy(p);
    printf("test_harden_lib: titles above %d bytes refused; data spanning the double range "
           "refused cleanly\n",
           CJ_PLOT_MAX_TITLE);
}

/* ---- issue 24: the one reader, the one writer, bounded emission ---------------------------- */

static void write_text(const char *path, const char *text) {
    FILE *f = fopen(path, "wb");
    assert_non_null(f);
    fputs(text, f);
    assert_int_equal(fclose(f), 0);
}

static int temporaries_in(const char *dir) {
    DIR *d = opendir(dir);
    assert_non_null(d);
    int n = 0;
    for (struct dirent *e; (e = readdir(d));) n += strstr(e->d_name, ".tmp-") != NULL;
    closedir(d);
    return n;
}

static void test_file_reader(void **state) {
    (void)state;
    char dir[] = "/tmp/cj_test_reader_XXXXXX", path[128], link_path[128], fifo[128];
    assert_non_null(mkdtemp(dir));
    char *data = NULL;
    size_t n = 0;
    /* devices and pipes are refused before one byte is read (a FIFO without a writer would
     * block an ordinary open; /dev/zero would never end) */
    assert_int_equal(cj_file_read_all("/dev/zero", 1 << 20, "input", &data, &n), CJ_ERR_ARGUMENT);
    assert_non_null(strstr(cj_last_error(), "not a regular file"));
    snprintf(fifo, sizeof fifo, "%s/fifo", dir);
    assert_int_equal(mkfifo(fifo, 0600), 0);
    assert_int_equal(cj_file_read_all(fifo, 1 << 20, "input", &data, &n), CJ_ERR_ARGUMENT);
    assert_non_null(strstr(cj_last_error(), "a pipe"));
    assert_int_equal(cj_file_read_all(dir, 1 << 20, "input", &data, &n), CJ_ERR_ARGUMENT);
    /* the cap: exactly max_bytes is read, one more byte refused */
    snprintf(path, sizeof path, "%s/ten", dir);
    write_text(path, "0123456789");
    assert_int_equal(cj_file_read_all(path, 9, "input", &data, &n), CJ_ERR_RANGE);
    assert_int_equal(cj_file_read_all(path, 10, "input", &data, &n), CJ_OK);
    assert_int_equal(n, 10);
    assert_int_equal(data[10], '\0');
    free(data);
    /* the log of inputs knows the file under any name (a hard link) */
    snprintf(link_path, sizeof link_path, "%s/other_name", dir);
    assert_int_equal(link(path, link_path), 0);
    assert_non_null(cj_file_input_named(link_path));
    assert_string_equal(cj_file_input_named(link_path), path);
    assert_null(cj_file_input_named(fifo));
    unlink(link_path);
    unlink(path);
    unlink(fifo);
    rmdir(dir);
    printf("test_harden_lib: the whole-file reader refuses /dev/zero, a FIFO and a folder without "
           "reading, holds its cap to the byte, and logs inputs by device and inode\n");
}

static void test_atomic_writer(void **state) {
    (void)state;
    char dir[] = "/tmp/cj_test_atomic_XXXXXX", path[128];
    assert_non_null(mkdtemp(dir));
    snprintf(path, sizeof path, "%s/out.txt", dir);
    write_text(path, "old");
    cj_atomic_file f;
    assert_int_equal(cj_atomic_open(&f, path), CJ_OK);
    fputs("abandoned", f.fp);
    cj_atomic_abandon(&f);
    char *data = NULL;
    size_t n = 0;
    assert_int_equal(cj_file_read_all(path, 100, "output", &data, &n), CJ_OK);
    assert_string_equal(data, "old");
    free(data);
    assert_int_equal(temporaries_in(dir), 0);
    assert_int_equal(cj_atomic_open(&f, path), CJ_OK);
    fputs("new", f.fp);
    assert_int_equal(cj_atomic_commit(&f), CJ_OK);
    assert_int_equal(cj_file_read_all(path, 100, "output", &data, &n), CJ_OK);
    assert_string_equal(data, "new");
    free(data);
    /* SIGTERM while a temporary exists: the handler removes it, the process dies of the signal,
     * the destination keeps its content */
    const pid_t child = fork();
    assert_true(child >= 0);
    if (child == 0) {
        cj_temp_install_signal_cleanup();
        cj_atomic_file g;
        if (cj_atomic_open(&g, path)) _exit(3);
        fputs("half written", g.fp);
        fflush(g.fp);
        raise(SIGTERM);
        _exit(4);
    }
    int status = 0;
    assert_int_equal(waitpid(child, &status, 0), child);
    assert_true(WIFSIGNALED(status) && WTERMSIG(status) == SIGTERM);
    assert_int_equal(temporaries_in(dir), 0);
    assert_int_equal(cj_file_read_all(path, 100, "output", &data, &n), CJ_OK);
    assert_string_equal(data, "new");
    free(data);
    /* a destination in a missing folder is found by the up-front check */
    assert_int_equal(cj_file_check_output("/nonexistent-cj/x.gif", "GIF"), CJ_ERR_IO);
    assert_int_equal(cj_file_check_output(dir, "GIF"), CJ_ERR_ARGUMENT);
    unlink(path);
    rmdir(dir);
    printf("test_harden_lib: the atomic writer keeps the old file on abandon, replaces it on "
           "commit, and a SIGTERM removes its temporary\n");
}

static void test_emission_bounded(void **state) {
    (void)state;
    cj_emitter e = cj_emitter_defaults();
    e.rate = 1e18;
    cj_particles_desc d;
    memset(&d, 0, sizeof d);
    d.capacity = 10;
    d.emitter_count = 1;
    d.emitters = &e;
    cj_particles *p = NULL;
    assert_int_equal(cj_particles_create(&d, NULL, &p), CJ_OK);
    /* 1e16 particles in one step: refused at once, not spun through */
    assert_int_equal(cj_particles_step(p, 0.01, NULL), CJ_ERR_RANGE);
    assert_non_null(strstr(cj_last_error(), "emitter 0"));
    assert_int_equal(cj_particles_count(p), 0);
    cj_particles_destroy(p);
    e.rate = 100;
    assert_int_equal(cj_particles_create(&d, NULL, &p), CJ_OK);
    assert_int_equal(cj_particles_step(p, 0.05, NULL), CJ_OK);
    assert_int_equal(cj_particles_count(p), 5);
    cj_particles_destroy(p);
    printf("test_harden_lib: an emitter of 1e18 particles/s is refused per step (CJ_ERR_RANGE, "
           "nothing emitted); 100/s for 0.05 s emits 5\n");
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_overflow_is_range),
        cmocka_unit_test(test_contour_tolerance_floor),
        cmocka_unit_test(test_tessellation_prediction),
        cmocka_unit_test(test_degenerate_patches),
        cmocka_unit_test(test_plot_limits),
        cmocka_unit_test(test_file_reader),
        cmocka_unit_test(test_atomic_writer),
        cmocka_unit_test(test_emission_bounded),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
