/* bench_surfaces: cost of evaluating the analytic surfaces of surfaces/ through the common
 * cj_param_surface interface (point + partials, unit normal, implicit f + gradient) and of the
 * taper/twist deformations per vertex. Prints a table; nothing is asserted. */
#define _POSIX_C_SOURCE 200809L /* clock_gettime */
#include "casteljau/analytic.h"
#include "casteljau/bezier.h"
#include "casteljau/deform.h"
#include "casteljau/quadric.h"
#include "casteljau/surface.h"

#include <stdio.h>
#include <stdlib.h>
#include <time.h>
#include "bench_clock.h"

static volatile double sink;

enum { N = 200000 };

static void bench(const char *name, const cj_param_surface *s, const cj_implicit_surface *is) {
    double acc = 0.0, t0 = cj_bench_wall();
    for (int i = 0; i < N; ++i) {
        double u = s->u0 + (s->u1 - s->u0) * (((long long)i * 7919) % N) / (double)N;
        double v = s->v0 + (s->v1 - s->v0) * (((long long)i * 104729) % N) / (double)N;
        cj_vec3 p, su, sv;
        if (cj_surface_eval(s, u, v, &p, &su, &sv) != CJ_OK) abort();
        acc += p.x + su.y + sv.z;
    }
    double t1 = cj_bench_wall();
    for (int i = 0; i < N; ++i) {
        double u = s->u0 + (s->u1 - s->u0) * (((long long)i * 7919) % N) / (double)N;
        double v = s->v0 + (s->v1 - s->v0) * (((long long)i * 104729) % N) / (double)N;
        cj_vec3 n;
        if (cj_surface_normal(s, u, v, &n) != CJ_OK) abort();
        acc += n.x;
    }
    double t2 = cj_bench_wall(), t3 = t2;
    if (is) {
        for (int i = 0; i < N; ++i) {
            double f;
            cj_vec3 g, x = cj_v3(0.001 * (i % 1000), 0.5, 0.002 * (i % 500));
            if (cj_implicit_eval(is, x, &f, &g) != CJ_OK) abort();
            acc += f + g.x;
        }
        t3 = cj_bench_wall();
    }
    sink = acc;
    if (is)
        printf("| %-28s | %8.1f | %8.1f | %8.1f |\n", name, 1e9 * (t1 - t0) / N,
               1e9 * (t2 - t1) / N, 1e9 * (t3 - t2) / N);
    else
        printf("| %-28s | %8.1f | %8.1f | %8s |\n", name, 1e9 * (t1 - t0) / N, 1e9 * (t2 - t1) / N,
               "-");
}

int main(void) {
    cj_vec3 o = cj_v3(0, 0, 0), z = cj_v3(0, 0, 1);
    cj_quadric q[6];
    cj_quadric_ellipsoid(&q[0], 2, 1, 0.5);
    cj_quadric_hyperboloid1(&q[1], 1, 2, 0.7, -1.5, 1.2);
    cj_quadric_hyperboloid2(&q[2], 1, 0.5, 2, 0, 1.5);
    cj_quadric_cone(&q[3], 1, 2, 1.5, 0, 2);
    cj_quadric_paraboloid(&q[4], 1, 3, 1.5);
    cj_quadric_hyperbolic_paraboloid(&q[5], 2, 1, -1, 1.5, -2, 1);
    const char *qn[6] = {"ellipsoid",     "hyperboloid, one sheet", "hyperboloid, two sheets",
                         "elliptic cone", "elliptic paraboloid",    "hyperbolic paraboloid"};
    printf("ns per call, %d calls each (u,v scattered over the domain)\n\n", N);
    printf("| %-28s | %8s | %8s | %8s |\n", "surface", "S,Su,Sv", "normal", "f, grad");
    printf("|------------------------------|----------|----------|----------|\n");
    cj_param_surface s;
    cj_implicit_surface is;
    for (int k = 0; k < 6; ++k) {
        cj_quadric_surface(&q[k], &s);
        cj_quadric_implicit(&q[k], &is);
        bench(qn[k], &s, &is);
    }
    cj_torus t;
    cj_torus_init(&t, o, cj_v3(0.2, 0.1, 1), 3, 1);
    cj_torus_surface(&t, &s);
    cj_torus_implicit(&t, &is);
    bench("torus", &s, &is);
    cj_cylinder c;
    cj_cylinder_init(&c, o, z, 1, 0, 2);
    cj_cylinder_surface(&c, &s);
    cj_cylinder_implicit(&c, &is);
    bench("right circular cylinder", &s, &is);
    cj_bilinear b;
    cj_bilinear_init(&b, o, cj_v3(2, 0, 1), cj_v3(0, 1, 1), cj_v3(2, 2, -1));
    cj_bilinear_surface(&b, &s);
    bench("bilinear patch", &s, NULL);
    static const double prof[] = {0, -1, 1.3, -1, 1.3, 1, 0, 1};
    cj_bezier pb = cj_bezier_view(3, 2, prof);
    cj_curve2 pc;
    cj_curve2_from_bezier(&pb, &pc);
    cj_revolution rv;
    cj_revolution_init(&rv, &pc, o, z);
    cj_revolution_surface(&rv, &s);
    bench("revolution, cubic profile", &s, NULL);
    cj_gen_cylinder gc;
    cj_gen_cylinder_init(&gc, &pc, o, cj_v3(1, 0, 0), cj_v3(0, 1, 0), cj_v3(0.2, 0, 1), 0, 1);
    cj_gen_cylinder_surface(&gc, &s);
    bench("general cylinder, cubic", &s, NULL);
    cj_deform d;
    cj_deformed_surface ds;
    cj_param_surface es;
    cj_quadric_surface(&q[0], &es);
    cj_deform_twist(&d, o, z, 1.0);
    cj_deform_surface(&d, &es, &ds, &s);
    bench("twisted ellipsoid", &s, NULL);
    cj_deform_taper(&d, o, z, 1.0, 0.2, 0.05);
    cj_deform_surface(&d, &es, &ds, &s);
    bench("tapered ellipsoid", &s, NULL);

    /* Deforming vertex arrays. */
    enum { V = 100000 };
    double *pos = malloc(3 * V * sizeof(double)), *nrm = malloc(3 * V * sizeof(double));
    if (!pos || !nrm) return 1;
    printf("\n| %-28s | %12s |\n", "deform_vertices", "ns / vertex");
    printf("|------------------------------|--------------|\n");
    for (int kind = 0; kind < 2; ++kind) {
        if (kind == 0)
            cj_deform_twist(&d, o, z, 1.0);
        else
            cj_deform_taper(&d, o, z, 1.0, 0.2, 0.05);
        for (int i = 0; i < V; ++i) {
            pos[3 * i] = 0.001 * (i % 1000), pos[3 * i + 1] = 0.5, pos[3 * i + 2] = 1e-5 * i;
            nrm[3 * i] = 0, nrm[3 * i + 1] = 0.6, nrm[3 * i + 2] = 0.8;
        }
        double t0 = cj_bench_wall();
        if (cj_deform_vertices(&d, pos, nrm, V) != CJ_OK) abort();
        double t1 = cj_bench_wall();
        printf("| %-28s | %12.1f |\n",
               kind ? "taper (positions+normals)" : "twist (positions+normals)",
               1e9 * (t1 - t0) / V);
    }
    free(pos);
    free(nrm);
    return 0;
}
