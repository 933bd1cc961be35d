/* Private to the casteljau tool: `casteljau eval --curve`, B-spline/NURBS evaluation. */
#ifndef CASTELJAU_APP_EVAL_BSPLINE_H
#define CASTELJAU_APP_EVAL_BSPLINE_H

#include <stddef.h>
#include <stdio.h>

/* Evaluates the first bspline item of the JSON file at the parameters targs[ntargs] (or, if
 * there are none, those on standard input) and prints as `eval` does. Returns the exit status. */
int eval_bspline_run(const char *path, int derivative, int want_bound, char **targs, int ntargs);

/* White-space separated parameters from f (cmd_eval.c). 0, or -1 after a message (*rc). */
int eval_read_params(FILE *f, double **ts, size_t *nt, int *rc);

#endif
