/* casteljau tessellate: Bézier patches (the Utah teapot, a .bpt file, or one patch from the
 * command line) to a triangle mesh file, with the proven error bound and the measured
 * deviation. The mesh size is predicted before any work and refused above --max-triangles. */
#define _DEFAULT_SOURCE /* readlink */
#include "cli.h"
#include "cli_guard.h"
#include "cli_progress.h"

#include "mesh_vtu.h"
#include "weights.h"

#include "casteljau/patchset.h"
#include "surface_load.h"
#include "casteljau/tessellate.h"

#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#define TESS_DEFAULT_MAX_TRIANGLES 1000000L
#define TESS_MAX_MAX_TRIANGLES     200000000L

static const char tess_usage[] =
    "usage: casteljau tessellate (--teapot | --bpt FILE | --surface FILE.json |\n"
    "                            --patch \"x,y,z;...\" --degree M,N\n"
    "                            [--weights \"w;...\"]) [--tol T | --uniform K]\n"
    "                            [--max-triangles N] -o OUT.obj|OUT.ply|OUT.vtu\n"
    "  --teapot  the Utah teapot (32 bicubic patches, teapot.bpt of the installation)\n"
    "  --surface a B-spline or NURBS surface (JSON: type bspline_surface | nurbs_surface, degree,\n"
    "            size, points, knots_u/knots_v, weights; what 'casteljau fit --grid' writes),\n"
    "            tessellated as its Bezier patches\n"
    "  --bpt     patches from a .bpt file (Newell's format: a count, then per patch 'M N' and\n"
    "            (M+1)(N+1) points 'x y z')\n"
    "  --patch   (M+1)(N+1) control points, row by row with u fastest (index j*(M+1)+i)\n"
    "  --weights one weight > 0 per control point, same order: a rational patch (scaled so the\n"
    "            largest is in [1,2), which changes nothing; proven bound\n"
    "            too; its measured deviation is the smaller of |S - L| and |S - Q|, L the linear\n"
    "            and Q the homogeneous linear interpolant of the triangle)\n"
    "  --tol     bound on the distance from surface to mesh (model units; default 1e-3 of the\n"
    "            model's bounding-box diagonal); --uniform K: K x K segments per patch\n"
    "  --max-triangles  refuse (exit 2, before the work) a mesh predicted or found to need more\n"
    "            triangles (default 1000000); the prediction is printed when it is refused\n"
    "Options may come in any order, as --opt value or --opt=value.\n"
    "Output: the mesh file, by extension: .obj (welded vertices, vt, vn, a group per patch),\n"
    ".ply (binary little-endian: position, normal, uv), .vtu (VTK XML, ASCII triangles with\n"
    "normals, uv and the patch index). Written atomically: complete or not at all. Stdout:\n"
    "'patches N', 'triangles N', 'vertices N', 'bound B' (proven) and 'measured D', one per\n"
    "line. Exit status 0; 2 for a bad argument or input (a degenerate patch, too many\n"
    "triangles); 1 when the file cannot be written or memory runs out.\n";

/* The teapot of this installation (cli_teapot_path: beside the executable first). */
static cj_status load_teapot(cj_patchset **set) {
    return cj_patchset_load_bpt(cli_teapot_path(), NULL, set);
}

int cmd_tessellate(int argc, char **argv) {
    const char *cmd = "tessellate";
    int teapot = 0, have_tol = 0, uniform = 0;
    long max_triangles = TESS_DEFAULT_MAX_TRIANGLES;
    const char *patch_text = NULL, *degree_text = NULL, *weights_text = NULL, *out = NULL,
               *bpt = NULL, *surface = NULL;
    double tol = 0.0;
    enum {
        O_TEAPOT,
        O_BPT,
        O_PATCH,
        O_DEGREE,
        O_WEIGHTS,
        O_OUT,
        O_TOL,
        O_UNIFORM,
        O_MAXTRI,
        O_SURFACE
    };
    static const cli_opt opts[] = {{"--teapot", NULL, 0},        {"--bpt", NULL, 1},
                                   {"--patch", NULL, 1},         {"--degree", NULL, 1},
                                   {"--weights", NULL, 1},       {"--output", "-o", 1},
                                   {"--tol", NULL, 1},           {"--uniform", NULL, 1},
                                   {"--max-triangles", NULL, 1}, {"--surface", NULL, 1}};
    cli_parser ps;
    cli_parser_init(&ps, cmd, tess_usage, argc, argv, opts, sizeof opts / sizeof opts[0]);
    for (;;) {
        const char *v;
        char q[160];
        const int k = cli_next(&ps, &v);
        if (k == CLI_END) break;
        if (k == CLI_EXIT_OK) return 0;
        if (k == CLI_BAD) return CLI_EXIT_USAGE;
        if (k == CLI_POSITIONAL)
            return cli_fail(cmd, "unexpected argument '%s' (try 'casteljau tessellate --help')",
                            cli_quote(v, q, sizeof q));
        long x;
        switch (k) {
        case O_TEAPOT:
            teapot = 1;
            break;
        case O_BPT:
            bpt = v;
            break;
        case O_SURFACE:
            surface = v;
            break;
        case O_PATCH:
            patch_text = v;
            break;
        case O_DEGREE:
            degree_text = v;
            break;
        case O_WEIGHTS:
            weights_text = v;
            break;
        case O_OUT:
            out = v;
            break;
        case O_TOL:
            if (cli_parse_double(v, &tol) != 0 || !(tol > 0.0))
                return cli_fail(cmd, "--tol '%s' is not a positive finite number",
                                cli_quote(v, q, sizeof q));
            have_tol = 1;
            break;
        case O_UNIFORM:
            if (cli_parse_int(v, 1, CJ_TESS_DEFAULT_MAX_SEGMENTS, &x) != 0)
                return cli_fail(cmd, "--uniform '%s' is not an integer in 1..%d",
                                cli_quote(v, q, sizeof q), CJ_TESS_DEFAULT_MAX_SEGMENTS);
            uniform = (int)x;
            break;
        default:
            if (cli_parse_int(v, 1, TESS_MAX_MAX_TRIANGLES, &x) != 0)
                return cli_fail(cmd, "--max-triangles '%s' is not an integer in 1..%ld",
                                cli_quote(v, q, sizeof q), TESS_MAX_MAX_TRIANGLES);
            max_triangles = x;
            break;
        }
    }
    const int models = (teapot != 0) + (patch_text != NULL) + (bpt != NULL) + (surface != NULL);
    if (models > 1) return cli_fail(cmd, "give one of --teapot, --bpt, --surface or --patch");
    if (models == 0)
        return cli_fail(cmd, "no model: give --teapot, --bpt FILE, --surface FILE or --patch");
    if (patch_text && !degree_text) return cli_fail(cmd, "--patch needs --degree M,N");
    if (!patch_text && degree_text) return cli_fail(cmd, "--degree is only for --patch");
    if (!patch_text && weights_text) return cli_fail(cmd, "--weights is only for --patch");
    if (have_tol && uniform) return cli_fail(cmd, "give either --tol or --uniform, not both");
    if (!out) return cli_fail(cmd, "no output file: give -o OUT.obj, OUT.ply or OUT.vtu");
    const int vtu = cli_has_ext(out, ".vtu");
    if (!cli_has_ext(out, ".obj") && !cli_has_ext(out, ".ply") && !vtu)
        return cli_fail(cmd, "output '%s' must end in .obj, .ply or .vtu", out);

    cj_patchset *set = NULL;
    surface_patches sp = {0, NULL, NULL, NULL};
    cj_patch single;
    double *pts = NULL, *weights = NULL;
    const cj_patch *patches;
    size_t count;
    double size = 0.0;
    int rc = 0;
    if ((rc = cli_check_output(cmd, "output", out))) return rc;
    if (teapot || bpt) {
        cj_status st = teapot ? load_teapot(&set) : cj_patchset_load_bpt(bpt, NULL, &set);
        if (st)
            return st == CJ_ERR_NOMEM
                       ? cli_error(cmd, "%s", cj_last_error())
                       : cli_fail(cmd, "%s: %s", teapot ? "teapot data" : "--bpt", cj_last_error());
        if ((rc = cli_guard_output(cmd, "-o", out))) goto done;
        patches = set->patches;
        count = set->count;
        double lo[3], hi[3];
        if ((st = cj_patchset_bbox(set, lo, hi, &size))) {
            rc = cli_fail(cmd, "%s", cj_last_error());
            goto done;
        }
    } else if (surface) {
        char why[400];
        int nomem = 0;
        if (surface_load(surface, &sp, why, sizeof why, &nomem))
            return nomem ? cli_error(cmd, "--surface: %s", why)
                         : cli_fail(cmd, "--surface: %s", why);
        patches = sp.patches;
        count = sp.count;
        cj_patchset view;
        memset(&view, 0, sizeof view);
        view.count = sp.count;
        view.patches = sp.patches;
        view.points = sp.pts;
        double lo[3], hi[3];
        if (cj_patchset_bbox(&view, lo, hi, &size)) {
            rc = cli_fail(cmd, "%s", cj_last_error());
            goto done;
        }
    } else {
        int m, n;
        if (cli_parse_degree(degree_text, &m, &n))
            return cli_fail(cmd, "--degree '%s': M and N must be integers in 0..%d", degree_text,
                            CJ_PATCH_MAX_DEGREE);
        size_t npts;
        int dim;
        char why[256];
        if (cli_parse_points(patch_text, &pts, &npts, &dim, why, sizeof why) != 0)
            return cli_fail(cmd, "--patch: %s", why);
        const size_t need = (size_t)(m + 1) * (size_t)(n + 1);
        if (dim != 3) {
            rc = cli_fail(cmd, "--patch: points have %d coordinates, patches need 3", dim);
            goto done;
        }
        if (npts != need) {
            rc = cli_fail(cmd, "--patch has %zu points but degree %d,%d needs (M+1)(N+1) = %zu",
                          npts, m, n, need);
            goto done;
        }
        if (weights_text) {
            size_t nw;
            if (cli_parse_list(weights_text, &weights, &nw, why, sizeof why) != 0) {
                rc = cli_fail(cmd, "--weights: %s", why);
                goto done;
            }
            if (nw != need) {
                rc = cli_fail(cmd, "--weights has %zu values but --patch has %zu points", nw, need);
                goto done;
            }
            for (size_t i = 0; i < nw; ++i)
                if (!(weights[i] > 0.0)) {
                    rc = cli_fail(cmd, "--weights: weight %zu is %g, weights must be > 0", i,
                                  weights[i]);
                    goto done;
                }
            if (weights_normalize(weights, nw)) {
                rc = cli_fail(cmd, "--weights span more than the double range");
                goto done;
            }
        }
        single = cj_patch_view(m, n, pts, weights);
        cj_status st = cj_patch_size(&single, &size);
        if (st) {
            rc = cli_fail(cmd, "--patch: %s", cj_last_error());
            goto done;
        }
        patches = &single;
        count = 1;
    }
    if (!have_tol && !uniform) tol = 1e-3 * (size > 0.0 ? size : 1.0);

    cj_mesh *mesh = NULL;
    /* Each patch is also capped per direction, so that no trial build of the adaptive search
     * can outgrow --max-triangles either. */
    const double seg_cap = floor(sqrt((double)max_triangles / 2.0));
    cj_tess_options opt = {tol, uniform, 4,
                           seg_cap < CJ_TESS_DEFAULT_MAX_SEGMENTS ? (int)fmax(seg_cap, 2.0) : 0};
    cj_tess_report rep;
    double predicted = 0.0;
    cj_status st = cj_tessellate_predict(patches, count, &opt, &predicted);
    if (st) {
        rc = cli_fail(cmd, "%s", cj_last_error());
        goto done;
    }
    if (predicted > (double)max_triangles) {
        rc = cli_fail(cmd,
                      "the mesh is predicted to need about %.3g triangles, above --max-triangles "
                      "%ld: give a larger --tol (or smaller --uniform), or raise "
                      "--max-triangles",
                      predicted, max_triangles);
        goto done;
    }
    if (opt.uniform > 0 && opt.max_segments && opt.uniform > opt.max_segments)
        opt.max_segments = 0; /* the prediction for uniform is exact: it fits */
    if ((st = cj_mesh_create(NULL, &mesh))) {
        rc = cli_error(cmd, "%s", cj_last_error());
        goto done;
    }
    st = cj_tessellate_patches(patches, count, &opt, mesh, &rep);
    if (st == CJ_ERR_CAP && opt.max_segments)
        rc = cli_fail(cmd,
                      "%s: the mesh would exceed --max-triangles %ld (predicted about %.3g "
                      "triangles); give a larger --tol or raise --max-triangles",
                      cj_last_error(), max_triangles, predicted);
    else if (st) /* name where the patches came from: a degenerate patch is in that file */
        rc = st == CJ_ERR_NOMEM ? cli_error(cmd, "%s", cj_last_error())
                                : cli_fail(cmd, "%s: %s",
                                           teapot ? "teapot data"
                                           : bpt  ? bpt
                                                  : "--patch",
                                           cj_last_error());
    else if (rep.triangles > (size_t)max_triangles)
        rc = cli_fail(cmd,
                      "the mesh has %zu triangles, above --max-triangles %ld (predicted %.3g): "
                      "nothing written",
                      rep.triangles, max_triangles, predicted);
    if (!rc) {
        char why[512];
        if (vtu ? mesh_write_vtu(mesh, out, why, sizeof why) : (cj_mesh_write(mesh, out) != 0)) {
            rc = cli_error(cmd, "%s", vtu ? why : cj_last_error());
        } else {
            printf("patches %zu\n", count);
            printf("triangles %zu\n", rep.triangles);
            printf("vertices %zu\n", rep.vertices);
            printf("bound ");
            cli_print_double(rep.bound);
            printf("\nmeasured ");
            cli_print_double(rep.measured);
            printf("\n");
            char detail[64];
            snprintf(detail, sizeof detail, "%zu triangles", rep.triangles);
            cli_summary(cmd, out, out, detail, -1.0);
        }
    }
    cj_mesh_destroy(mesh);
done:
    cj_patchset_destroy(set);
    surface_patches_free(&sp);
    free(pts);
    free(weights);
    return rc;
}
