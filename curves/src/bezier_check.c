#include "bezier_internal.h"

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
    return cj_check_points(c->pts, (size_t)c->degree + 1, c->dim, "control point");
}
