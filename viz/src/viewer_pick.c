/* Exact comparison of squared pixel distances for picking: no rounding may decide which of two
 * control points is nearer to the cursor, so ties are real ties and the tie rule (lowest index)
 * is the only thing that breaks them. Differences, squares and sums are expanded into
 * non-overlapping double components (error-free transformations, Shewchuk's expansions) and
 * only the sign of the exact total is looked at. */
#include "casteljau/viewer_model.h"
#include "viewer_internal.h"
#include "eft_internal.h"

#include <math.h>

/* a * b = p + e exactly (fma is exact in its last rounding). */
static void two_prod(double a, double b, double *p, double *e) {
    *p = a * b;
    *e = fma(a, b, -*p);
}

/* Adds x to the expansion e[0..n) (components in increasing magnitude); returns the new size. */
static int grow(double *e, int n, double x) {
    int m = 0;
    double q = x;
    for (int i = 0; i < n; ++i) {
        double s, err;
        cj_two_sum(q, e[i], &s, &err);
        if (err != 0.0) e[m++] = err;
        q = s;
    }
    if (q != 0.0 || m == 0) e[m++] = q;
    return m;
}

/* Appends ±(a − c)² as exact terms. */
static int add_square_of_difference(double *e, int n, double a, double c, double sign) {
    double h, l;
    cj_two_sum(a, -c, &h, &l);
    const double f[3][2] = {{h, h}, {2.0 * h, l}, {l, l}};
    for (int k = 0; k < 3; ++k) {
        double p, pe;
        two_prod(f[k][0], f[k][1], &p, &pe);
        n = grow(e, n, sign * p);
        n = grow(e, n, sign * pe);
    }
    return n;
}

static int sign_of(const double *e, int n) {
    for (int i = n - 1; i >= 0; --i)
        if (e[i] != 0.0) return e[i] > 0.0 ? 1 : -1;
    return 0;
}

int cj_vpick_closer(double ax, double ay, double bx, double by, double cx, double cy) {
    /* 24 terms at most; a growing expansion never has more components than terms added. */
    double e[32];
    int n = 0;
    n = add_square_of_difference(e, n, ax, cx, 1.0);
    n = add_square_of_difference(e, n, ay, cy, 1.0);
    n = add_square_of_difference(e, n, bx, cx, -1.0);
    n = add_square_of_difference(e, n, by, cy, -1.0);
    return sign_of(e, n);
}

int cj_vpick_within(double ax, double ay, double cx, double cy, double radius) {
    double e[32], p, pe;
    int n = 0;
    n = add_square_of_difference(e, n, ax, cx, 1.0);
    n = add_square_of_difference(e, n, ay, cy, 1.0);
    two_prod(radius, radius, &p, &pe);
    n = grow(e, n, -p);
    n = grow(e, n, -pe);
    return sign_of(e, n) <= 0;
}

int cj_vpick_compare(double ax, double ay, double bx, double by) {
    return cj_vpick_closer(ax, ay, bx, by, 0.0, 0.0);
}
