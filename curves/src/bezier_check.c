#include "bezier_internal.h"
#include "eval_internal.h"

#include <assert.h>
#include <math.h>

double cj_gamma(int k) {
    double ku = (double)k * CJ_UNIT_ROUNDOFF;
    return ku / (1.0 - ku);
}

cj_status cj_check_param(double t, const char *what) {
    if (!isfinite(t))
        return cj_fail(CJ_ERR_NONFINITE, "%s is %s", what, isnan(t) ? "NaN" : "infinite");
    return CJ_OK;
}

cj_status cj_bezier_check(const cj_bezier *c, int max_degree) {
    assert(c != NULL);
    if (c->degree < 0)
        return cj_fail(CJ_ERR_EMPTY, "curve has no control points (degree %d)", c->degree);
    if (c->degree > max_degree)
        return cj_fail(CJ_ERR_DEGREE, "degree %d exceeds this method's limit of %d", c->degree,
                       max_degree);
    if (c->dim < 1 || c->dim > CJ_MAX_DIM)
        return cj_fail(CJ_ERR_DIMENSION, "dimension %d is outside 1..%d", c->dim, CJ_MAX_DIM);
    assert(c->pts != NULL);
    const size_t count = (size_t)c->degree + 1;
    if (cj_all_finite(c->pts, count * (size_t)c->dim)) return CJ_OK;
    /* Slow path only to name the offending point and coordinate. */
    return cj_check_points(c->pts, count, c->dim, "control point");
}

cj_status cj_check_value(const double *v, int dim, double t) {
    if (cj_all_finite(v, (size_t)dim)) return CJ_OK;
    return cj_fail(CJ_ERR_RANGE,
                   "the value at t = %.17g overflows the double range (extrapolating too far?)", t);
}
