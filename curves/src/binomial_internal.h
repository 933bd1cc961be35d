/* Private: exact binomial coefficients for the basis-based evaluation methods. */
#ifndef CASTELJAU_BINOMIAL_INTERNAL_H
#define CASTELJAU_BINOMIAL_INTERNAL_H

#include "casteljau/bezier.h"

#define CJ_BINOMIAL_TABLE_SIZE                                                                     \
    ((CJ_BEZIER_BINOMIAL_MAX_DEGREE + 1) * (CJ_BEZIER_BINOMIAL_MAX_DEGREE + 2) / 2)

extern const double cj_binomial_table[CJ_BINOMIAL_TABLE_SIZE];

/* Row n of Pascal's triangle (n <= CJ_BEZIER_BINOMIAL_MAX_DEGREE): row[i] = C(n,i). */
static inline const double *cj_binomial_row(int n) {
    return cj_binomial_table + n * (n + 1) / 2;
}

#endif
