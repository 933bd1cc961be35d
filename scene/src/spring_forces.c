/* The spring system's forces: gravity, drag and the damped springs. Shared by the explicit
 * integrators (spring_system.c) and the backward Euler (spring_implicit.c), which is why it
 * has its own file: both call it, it calls neither. */
#include "spring_internal.h"

#include <math.h>

/* Forces (not accelerations) at (x, v) into f. */
void cj_springs_forces_at(const cj_springs *s, const double *x, const double *v, double *f) {
    const size_t dim = (size_t)s->dim;
    for (size_t i = 0; i < s->count; ++i)
        for (size_t k = 0; k < dim; ++k)
            f[i * dim + k] = s->mass[i] * (s->gravity[k] - s->drag * v[i * dim + k]);
    for (size_t j = 0; j < s->nsprings; ++j) {
        const cj_spring *sp = &s->springs[j];
        const size_t a = (size_t)sp->a * dim, b = (size_t)sp->b * dim;
        double d[3], l2 = 0.0;
        for (size_t k = 0; k < dim; ++k) {
            d[k] = x[a + k] - x[b + k];
            l2 += d[k] * d[k];
        }
        const double l = sqrt(l2);
        if (!(l > 0.0)) continue;
        double vn = 0.0;
        for (size_t k = 0; k < dim; ++k) vn += (v[a + k] - v[b + k]) * d[k] / l;
        const double mag = sp->stiffness * (l - sp->rest) + sp->damping * vn;
        for (size_t k = 0; k < dim; ++k) {
            const double fk = -mag * d[k] / l;
            f[a + k] += fk;
            f[b + k] -= fk;
        }
    }
}
