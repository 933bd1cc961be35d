/* casteljau tessellate: Bézier patches (the Utah teapot or one patch from the command line)
 * to a triangle mesh file, with the proven error bound and the measured deviation. */
#include "cli.h"

#include "casteljau/patchset.h"
#include "casteljau/tessellate.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char tess_usage[] =
    "usage: casteljau tessellate (--teapot | --patch \"x,y,z;...\" --degree M,N [--weights "
    "\"w;...\"])\n"
    "                            [--tol T | --uniform K] -o OUT.obj|OUT.ply\n"
    "  --patch   (M+1)(N+1) control points, row by row with u fastest (index j*(M+1)+i)\n"
    "  --weights one weight > 0 per control point, same order: a rational patch (proven bound\n"
    "            too; its measured deviation is the smaller of |S - L| and |S - Q|, L the linear\n"
    "            and Q the homogeneous linear interpolant of the triangle)\n"
    "  --tol     bound on the distance from surface to mesh (model units; default 1e-3 of the\n"
    "            model's bounding-box diagonal); --uniform K: K x K segments per patch\n"
    "  prints: patches, triangles, the proven bound and the measured deviation\n";

#ifndef CJ_TEAPOT_SOURCE
#define CJ_TEAPOT_SOURCE "data/teapot.bpt"
#endif
#ifndef CJ_TEAPOT_INSTALLED
#define CJ_TEAPOT_INSTALLED "/usr/local/share/casteljau/teapot.bpt"
#endif

static int has_ext(const char *path, const char *ext) {
    size_t a = strlen(path), b = strlen(ext);
    if (a <= b) return 0;
    for (size_t i = 0; i < b; ++i) {
        char c = path[a - b + i];
        if (c >= 'A' && c <= 'Z') c = (char)(c - 'A' + 'a');
        if (c != ext[i]) return 0;
    }
    return 1;
}

static int parse_int(const char *s, int lo, int hi, int *out) {
    char *end;
    long v = strtol(s, &end, 10);
    if (end == s || *end || v < lo || v > hi) return -1;
    *out = (int)v;
    return 0;
}

int cmd_tessellate(int argc, char **argv) {
    const char *cmd = "tessellate";
    int teapot = 0, have_tol = 0, uniform = 0;
    const char *patch_text = NULL, *degree_text = NULL, *weights_text = NULL, *out = NULL;
    double tol = 0.0;
    for (int i = 1; i < argc; ++i) {
        const char *a = argv[i];
        if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
            fputs(tess_usage, stdout);
            return 0;
        }
        if (!strcmp(a, "--teapot")) {
            teapot = 1;
            continue;
        }
        if (i + 1 >= argc) return cli_fail(cmd, "option '%s' needs a value (or is unknown)", a);
        const char *v = argv[++i];
        if (!strcmp(a, "--patch"))
            patch_text = v;
        else if (!strcmp(a, "--degree"))
            degree_text = v;
        else if (!strcmp(a, "--weights"))
            weights_text = v;
        else if (!strcmp(a, "-o"))
            out = v;
        else if (!strcmp(a, "--tol")) {
            if (cli_parse_double(v, &tol) != 0 || !(tol > 0.0))
                return cli_fail(cmd, "--tol '%s' is not a positive finite number", v);
            have_tol = 1;
        } else if (!strcmp(a, "--uniform")) {
            if (parse_int(v, 1, CJ_TESS_DEFAULT_MAX_SEGMENTS, &uniform) != 0)
                return cli_fail(cmd, "--uniform '%s' is not an integer in 1..%d", v,
                                CJ_TESS_DEFAULT_MAX_SEGMENTS);
        } else
            return cli_fail(cmd, "unknown option '%s' (try --help)", a);
    }
    if (teapot && patch_text) return cli_fail(cmd, "give either --teapot or --patch, not both");
    if (!teapot && !patch_text) return cli_fail(cmd, "no model: give --teapot or --patch");
    if (patch_text && !degree_text) return cli_fail(cmd, "--patch needs --degree M,N");
    if (!patch_text && degree_text) return cli_fail(cmd, "--degree is only for --patch");
    if (!patch_text && weights_text) return cli_fail(cmd, "--weights is only for --patch");
    if (have_tol && uniform) return cli_fail(cmd, "give either --tol or --uniform, not both");
    if (!out) return cli_fail(cmd, "no output file: give -o OUT.obj or -o OUT.ply");
    if (!has_ext(out, ".obj") && !has_ext(out, ".ply"))
        return cli_fail(cmd, "output '%s' must end in .obj or .ply", out);

    cj_patchset *set = NULL;
    cj_patch single;
    double *pts = NULL, *weights = NULL;
    const cj_patch *patches;
    size_t count;
    double size = 0.0;
    if (teapot) {
        cj_status st = cj_patchset_load_bpt(CJ_TEAPOT_SOURCE, NULL, &set);
        if (st == CJ_ERR_IO) st = cj_patchset_load_bpt(CJ_TEAPOT_INSTALLED, NULL, &set);
        if (st) return cli_fail(cmd, "teapot data: %s", cj_last_error());
        patches = set->patches;
        count = set->count;
        double lo[3], hi[3];
        cj_patchset_bbox(set, lo, hi, &size);
    } else {
        int m, n;
        char *comma = strchr(degree_text, ',');
        char tmp[64];
        if (!comma || strlen(degree_text) >= sizeof tmp)
            return cli_fail(cmd, "--degree '%s' must be M,N", degree_text);
        memcpy(tmp, degree_text, (size_t)(comma - degree_text));
        tmp[comma - degree_text] = '\0';
        if (parse_int(tmp, 0, CJ_PATCH_MAX_DEGREE, &m) != 0 ||
            parse_int(comma + 1, 0, CJ_PATCH_MAX_DEGREE, &n) != 0)
            return cli_fail(cmd, "--degree '%s': M and N must be integers in 0..%d", degree_text,
                            CJ_PATCH_MAX_DEGREE);
        size_t npts;
        int dim;
        char why[256];
        if (cli_parse_points(patch_text, &pts, &npts, &dim, why, sizeof why) != 0)
            return cli_fail(cmd, "--patch: %s", why);
        if (dim != 3) {
            free(pts);
            return cli_fail(cmd, "--patch: points have %d coordinates, patches need 3", dim);
        }
        const size_t need = (size_t)(m + 1) * (size_t)(n + 1);
        if (npts != need) {
            free(pts);
            return cli_fail(cmd, "--patch has %zu points but degree %d,%d needs (M+1)(N+1) = %zu",
                            npts, m, n, need);
        }
        if (weights_text) {
            size_t nw;
            if (cli_parse_list(weights_text, &weights, &nw, why, sizeof why) != 0) {
                free(pts);
                return cli_fail(cmd, "--weights: %s", why);
            }
            if (nw != need) {
                free(pts);
                free(weights);
                return cli_fail(cmd, "--weights has %zu values but --patch has %zu points", nw,
                                need);
            }
            for (size_t q = 0; q < nw; ++q)
                if (!(weights[q] > 0.0)) {
                    const double bad = weights[q];
                    free(pts);
                    free(weights);
                    return cli_fail(cmd, "--weights: weight %zu is %g, weights must be > 0", q,
                                    bad);
                }
        }
        single = cj_patch_view(m, n, pts, weights);
        cj_status st = cj_patch_size(&single, &size);
        if (st) {
            free(pts);
            free(weights);
            return cli_fail(cmd, "--patch: %s", cj_last_error());
        }
        patches = &single;
        count = 1;
    }
    if (!have_tol && !uniform) tol = 1e-3 * (size > 0.0 ? size : 1.0);

    int rc = 0;
    cj_mesh *mesh = NULL;
    cj_tess_options opt = {tol, uniform, 4, 0};
    cj_tess_report rep;
    cj_status st = cj_mesh_create(NULL, &mesh);
    if (!st) st = cj_tessellate_patches(patches, count, &opt, mesh, &rep);
    if (st) {
        rc = cli_fail(cmd, "%s", cj_last_error());
    } else if ((st = cj_mesh_write(mesh, out))) {
        fprintf(stderr, "casteljau %s: %s\n", cmd, cj_last_error());
        rc = 1;
    } else {
        printf("patches %zu\n", count);
        printf("triangles %zu\n", rep.triangles);
        printf("vertices %zu\n", rep.vertices);
        printf("bound ");
        cli_print_double(rep.bound);
        printf("\nmeasured ");
        cli_print_double(rep.measured);
        printf("\n");
    }
    cj_mesh_destroy(mesh);
    cj_patchset_destroy(set);
    free(pts);
    free(weights);
    return rc;
}
