/* casteljau eval --curve: the B-spline item of a JSON file, evaluated by de Boor. */
#include "eval_bspline.h"
#include "bspline_json.h"
#include "cli.h"
#include "file_internal.h"
#include "json_read_internal.h"

#include "casteljau/bspline.h"

#include <cJSON.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#define EVAL_MAX_BYTES ((size_t)256 << 20)

/* The curve document through the shared reader (file_internal.h: regular files only, at most
 * EVAL_MAX_BYTES, logged as an input). NULL with the reason in why; *nomem for memory. */
static char *slurp(const char *path, char *why, size_t n, int *nomem) {
    char *data = NULL;
    size_t size = 0;
    const cj_status st = cj_file_read_all(path, EVAL_MAX_BYTES, "--curve", &data, &size);
    *nomem = st == CJ_ERR_NOMEM;
    if (st) snprintf(why, n, "%s", cj_last_error());
    return st ? NULL : data;
}

int eval_bspline_run(const char *path, int derivative, int want_bound, char **targs, int ntargs) {
    if (derivative > CJ_BSPLINE_MAX_DERIV)
        return cli_fail("eval", "--derivative %d exceeds %d for a B-spline", derivative,
                        CJ_BSPLINE_MAX_DERIV);
    char why[512] = "";
    int nomem = 0;
    char *text = slurp(path, why, sizeof why, &nomem);
    if (!text) return nomem ? cli_error("eval", "%s", why) : cli_fail("eval", "%s", why);
    cJSON *doc = NULL;
    cj_status st = cj_json_parse(path, text, &doc);
    if (st) {
        free(text);
        return st == CJ_ERR_NOMEM ? cli_error("eval", "--curve: %s", cj_last_error())
                                  : cli_fail("eval", "--curve: %s", cj_last_error());
    }
    char ipath[96];
    const cJSON *item = cj_bsp_json_find(doc, ipath, sizeof ipath);
    cj_bsp_json b;
    int rc = 0;
    if (!item) {
        cJSON_Delete(doc);
        free(text);
        return cli_fail("eval", "--curve: '%s' has no item of type \"bspline\"", path);
    }
    cj_json_lines lines;
    cj_json_doc jdoc;
    cj_json_doc_init(&jdoc, &lines, path, text, doc);
    st = cj_bsp_json_parse(&jdoc, item, ipath, NULL, 50000000, &b);
    cj_json_doc_free(&jdoc);
    cJSON_Delete(doc);
    free(text);
    if (st)
        return st == CJ_ERR_NOMEM ? cli_error("eval", "--curve: %s", cj_last_error())
                                  : cli_fail("eval", "--curve: %s", cj_last_error());
    double *ts = NULL, *vals = NULL;
    size_t nt = 0;
    if (ntargs > 0) {
        nt = (size_t)ntargs;
        ts = malloc(sizeof(double) * nt);
        if (!ts) {
            rc = cli_error("eval", "out of memory");
            goto done;
        }
        for (size_t j = 0; j < nt; ++j)
            if (cli_parse_double(targs[j], &ts[j])) {
                char q[80];
                rc = cli_fail("eval", "parameter '%s' is not a finite number",
                              cli_quote(targs[j], q, sizeof q));
                goto done;
            }
    } else if (isatty(0)) {
        rc = cli_fail("eval", "no parameter T given (give them after the options, or pipe them "
                              "on standard input)");
        goto done;
    } else if (eval_read_params(stdin, &ts, &nt, &rc)) {
        goto done;
    }
    const cj_bspline c = cj_bsp_json_view(&b);
    const int dim = c.dim;
    vals = malloc(sizeof(double) * nt * (size_t)dim * 2);
    double *der = malloc(sizeof(double) * (size_t)(derivative + 1) * (size_t)dim);
    double *bnd = malloc(sizeof(double) * (size_t)(derivative + 1) * (size_t)dim);
    if (!vals || !der || !bnd) {
        free(der);
        free(bnd);
        rc = cli_error("eval", "out of memory");
        goto done;
    }
    for (size_t j = 0; j < nt && !rc; ++j) {
        double *v = vals + j * (size_t)dim * 2;
        st = cj_bspline_eval_derivs(&c, ts[j], derivative, der);
        if (!st) memcpy(v, der + (size_t)derivative * (size_t)dim, sizeof(double) * (size_t)dim);
        if (!st && want_bound && derivative == 0) st = cj_bspline_error_bound(&c, ts[j], v + dim);
        if (!st && want_bound && derivative > 0) {
            st = cj_bspline_derivs_error_bound(&c, ts[j], derivative, bnd);
            if (!st)
                memcpy(v + dim, bnd + (size_t)derivative * (size_t)dim,
                       sizeof(double) * (size_t)dim);
        }
        if (st) rc = cli_fail("eval", "%s", cj_last_error());
    }
    free(der);
    free(bnd);
    if (rc) goto done;
    for (size_t j = 0; j < nt; ++j) {
        const double *v = vals + j * (size_t)dim * 2;
        for (int k = 0; k < dim; ++k) {
            if (k) putchar(' ');
            cli_print_double(v[k]);
        }
        if (want_bound) {
            fputs(" |", stdout);
            for (int k = 0; k < dim; ++k) {
                putchar(' ');
                cli_print_double(v[dim + k]);
            }
        }
        putchar('\n');
    }
    if (fflush(stdout) != 0 || ferror(stdout)) rc = cli_error("eval", "cannot write the output");
done:
    free(ts);
    free(vals);
    cj_bsp_json_free(&b);
    return rc;
}
