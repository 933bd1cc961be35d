/* Cloth: a grid of particles with structural, shear and bend springs, built on
 * cj_springs_create (spring_system.c). */
#include "casteljau/springs.h"

#include "error_internal.h"
#include "particle_internal.h"
#include "spring_internal.h"

#include <assert.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

cj_status cj_springs_create_cloth(int nu, int nv, const double corner[3], const double eu[3],
                                  const double ev[3], double mass, double k_struct, double k_shear,
                                  double k_bend, double c, const int *pinned, size_t pinned_count,
                                  const cj_springs_desc *extra, const cj_allocator *alloc,
                                  cj_springs **out) {
    if (nu < 2 || nv < 2 || nu > 4096 || nv > 4096)
        return cj_fail(CJ_ERR_RANGE, "cloth grid %d x %d: each side must be in 2..4096", nu, nv);
    if (extra && extra->dim != 3)
        return cj_fail(CJ_ERR_DIMENSION, "cloth: extra description must be 3D");
    if (!(mass > 0.0) || !isfinite(mass))
        return cj_fail(CJ_ERR_RANGE, "cloth mass %g must be finite and > 0", mass);
    const size_t np = (size_t)nu * (size_t)nv;
    const size_t maxspr = 8 * np;
    double *x = malloc(sizeof(double) * 3 * np), *m = malloc(sizeof(double) * np);
    unsigned char *fixed = calloc(np, 1);
    cj_spring *spr = malloc(sizeof(cj_spring) * maxspr);
    cj_status st = CJ_OK;
    if (!x || !m || !fixed || !spr) {
        st = cj_fail(CJ_ERR_NOMEM, "cloth: no memory for %zu particles", np);
        goto done;
    }
    for (int j = 0; j < nv; ++j)
        for (int i = 0; i < nu; ++i) {
            const size_t id = (size_t)j * (size_t)nu + (size_t)i;
            const double a = (double)i / (nu - 1), b = (double)j / (nv - 1);
            for (int k = 0; k < 3; ++k) x[3 * id + k] = corner[k] + a * eu[k] + b * ev[k];
            m[id] = mass / (double)np;
        }
    for (size_t q = 0; q < pinned_count; ++q) {
        if (pinned[q] < 0 || (size_t)pinned[q] >= np) {
            st = cj_fail(CJ_ERR_ARGUMENT, "cloth: pinned particle %d of %zu", pinned[q], np);
            goto done;
        }
        fixed[pinned[q]] = 1;
    }
    size_t ns = 0;
    static const int offs[6][3] = {{1, 0, 0},  {0, 1, 0}, {1, 1, 1},
                                   {-1, 1, 1}, {2, 0, 2}, {0, 2, 2}};
    for (int j = 0; j < nv; ++j)
        for (int i = 0; i < nu; ++i)
            for (int o = 0; o < 6; ++o) {
                const int i2 = i + offs[o][0], j2 = j + offs[o][1], kind = offs[o][2];
                const double k = kind == 0 ? k_struct : kind == 1 ? k_shear : k_bend;
                if (i2 < 0 || i2 >= nu || j2 >= nv || k == 0.0) continue;
                cj_spring *sp = &spr[ns++];
                sp->a = j * nu + i;
                sp->b = j2 * nu + i2;
                double l2 = 0.0;
                for (int kk = 0; kk < 3; ++kk) {
                    const double d = x[3 * (size_t)sp->a + kk] - x[3 * (size_t)sp->b + kk];
                    l2 += d * d;
                }
                sp->rest = sqrt(l2);
                sp->stiffness = k;
                sp->damping = c;
            }
    cj_springs_desc d;
    memset(&d, 0, sizeof d);
    if (extra) d = *extra;
    d.dim = 3;
    d.count = np;
    d.x = x;
    d.v = NULL;
    d.mass = m;
    d.fixed = fixed;
    d.spring_count = ns;
    d.springs = spr;
    st = cj_springs_create(&d, alloc, out);
done:
    free(x);
    free(m);
    free(fixed);
    free(spr);
    return st;
}
