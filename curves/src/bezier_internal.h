/* Private helpers shared by the Bézier sources. */
#ifndef CASTELJAU_BEZIER_INTERNAL_H
#define CASTELJAU_BEZIER_INTERNAL_H

#include "casteljau/bezier.h"
#include "error_internal.h"

/* Validates a parameter: finite, else CJ_ERR_NONFINITE naming `what`. */
cj_status cj_check_param(double t, const char *what);

/* Work space for one de Casteljau triangle row of the largest curve. */
#define CJ_BEZIER_WORK ((CJ_BEZIER_MAX_DEGREE + 1) * CJ_MAX_DIM)

#endif
