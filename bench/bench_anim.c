/* bench_anim: accuracy costs time — each integrator (explicit Euler, symplectic Euler, RK4,
 * backward Euler) on a damped oscillator (exact solution in closed form) and a large-amplitude
 * pendulum (exact solution through Jacobi's elliptic sn, computed in long double by the AGM),
 * against the time step: maximum error over the run, time per step, and the step at which each
 * becomes unstable. Writes the table to stdout and a log-log plot (our own plot code) to the
 * PNG named by argv[1] (default docs/integrators.png). */
#include "bench_clock.h"

#include "casteljau/framebuffer.h"
#include "casteljau/image_io.h"
#include "casteljau/plot.h"
#include "casteljau/springs.h"
#include "casteljau/text.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#define PI 3.14159265358979323846
#define NH 13
#define NM 4

static const double steps_h[NH] = {0.3,  0.2,  0.1,  0.05, 0.02, 0.01, 0.005,
                                   2e-3, 1e-3, 5e-4, 2e-4, 1e-4, 5e-5};

/* ---- damped oscillator x'' + 2 ζ ω x' + ω² x = 0, x(0) = 1, x'(0) = 0 ------------------- */
static const double W = 2 * PI, ZETA = 0.05, T_END = 10.0;

static void osc_accel(void *u, double t, const double *x, const double *v, double *a) {
    (void)u;
    (void)t;
    a[0] = -2 * ZETA * W * v[0] - W * W * x[0];
}
static void osc_jac(void *u, double t, const double *x, const double *v, double *ax, double *av) {
    (void)u, (void)t, (void)x, (void)v;
    ax[0] = -W * W;
    av[0] = -2 * ZETA * W;
}
static double osc_exact(double t) {
    const double wd = W * sqrt(1 - ZETA * ZETA);
    return exp(-ZETA * W * t) * (cos(wd * t) + ZETA * W / wd * sin(wd * t));
}

/* ---- pendulum θ'' = −(g/L) sin θ, θ(0) = θ0, θ'(0) = 0 ------------------------------------ */
static const double G_L = 9.81, THETA0 = 1.0;

static void pen_accel(void *u, double t, const double *x, const double *v, double *a) {
    (void)u, (void)t, (void)v;
    a[0] = -G_L * sin(x[0]);
}
static void pen_jac(void *u, double t, const double *x, const double *v, double *ax, double *av) {
    (void)u, (void)t, (void)v;
    ax[0] = -G_L * cos(x[0]);
    av[0] = 0;
}

/* Jacobi sn(u, k) by the arithmetic-geometric mean (Abramowitz & Stegun 16.4), long double. */
static long double sn_agm(long double u, long double k) {
    long double a[40], c[40], b = sqrtl(1 - k * k);
    a[0] = 1;
    c[0] = k;
    int n = 0;
    while (fabsl(c[n]) > 1e-19L && n < 38) {
        a[n + 1] = (a[n] + b) / 2;
        c[n + 1] = (a[n] - b) / 2;
        b = sqrtl(a[n] * b);
        ++n;
    }
    long double phi = ldexpl(a[n] * u, n);
    for (int i = n; i > 0; --i) phi = (phi + asinl(c[i] / a[i] * sinl(phi))) / 2;
    return sinl(phi);
}
static long double ellK(long double k) {
    long double a = 1, b = sqrtl(1 - k * k);
    for (int i = 0; i < 40; ++i) {
        const long double an = (a + b) / 2;
        b = sqrtl(a * b);
        a = an;
    }
    return 3.14159265358979323846264338327950288L / (2 * a);
}
static double pen_exact(double t) {
    /* θ(t) = 2 asin(k sn(K − ω t, k)), k = sin(θ0/2), ω = sqrt(g/L) */
    const long double k = sinl(THETA0 / 2.0L), w = sqrtl(G_L);
    return (double)(2 * asinl(k * sn_agm(ellK(k) - w * t, k)));
}

typedef struct problem {
    const char *name;
    cj_ode2 sys;
    double (*exact)(double);
    double x0;
} problem;

/* Runs to T_END with step h: max |x − exact| over the steps (INFINITY if it blew up), and the
 * thread-CPU seconds per step of a second, untimed-free pass (the exact pendulum solution costs
 * more than a step, so errors are measured apart from the timing). */
static double run(const problem *p, cj_integrator m, double h, double *sec_per_step) {
    double work[64];
    int ipiv[4];
    const long n = lround(T_END / h);
    double x = p->x0, v = 0, err = 0;
    for (long i = 0; i < n; ++i) {
        if (cj_ode2_step(&p->sys, m, i * h, h, &x, &v, work, ipiv, NULL) != CJ_OK ||
            fabs(x) > 1e6) {
            err = INFINITY;
            break;
        }
        err = fmax(err, fabs(x - p->exact((double)(i + 1) * h)));
    }
    x = p->x0;
    v = 0;
    const double t0 = cj_bench_thread_cpu();
    long i = 0;
    for (; i < n; ++i)
        if (cj_ode2_step(&p->sys, m, i * h, h, &x, &v, work, ipiv, NULL) != CJ_OK) break;
    const double el = cj_bench_thread_cpu() - t0;
    if (sec_per_step) *sec_per_step = el / (double)(i > 0 ? i : 1);
    return err;
}

/* Unstable at h: the numerical solution of the (decaying) oscillator grows over 4000 steps. */
static int grows(const problem *p, cj_integrator m, double h) {
    double work[64];
    int ipiv[4];
    double x = 1, v = 0;
    for (int i = 0; i < 4000; ++i)
        if (cj_ode2_step(&p->sys, m, i * h, h, &x, &v, work, ipiv, NULL) != CJ_OK) return 1;
    return !(x * x + v * v / (W * W) <= 1.0);
}

static double unstable_step(const problem *p, cj_integrator m) {
    double lo = 1e-5, hi = 20.0;
    if (!grows(p, m, hi)) return INFINITY;
    if (grows(p, m, lo)) return 0;
    for (int i = 0; i < 60; ++i) {
        const double mid = sqrt(lo * hi);
        if (grows(p, m, mid))
            hi = mid;
        else
            lo = mid;
    }
    return sqrt(lo * hi);
}

static const cj_rgba COLORS[NM] = {
    {214, 39, 40, 255}, {31, 119, 180, 255}, {44, 160, 44, 255}, {148, 103, 189, 255}};

/* sps == NULL: error against the step; else against the CPU seconds per simulated second. */
static void plot_panel(cj_plot *pl, double err[NM][NH], double sps[NM][NH]) {
    for (int m = 0; m < NM; ++m) {
        double xy[2 * NH];
        size_t k = 0;
        for (int i = 0; i < NH; ++i)
            if (isfinite(err[m][i]) && err[m][i] > 0 && err[m][i] < 10) {
                /* plots have equal aspect: the horizontal decades are stretched */
                xy[2 * k] = sps ? 2.0 * log10(sps[m][i] / steps_h[i]) : 3.0 * log10(steps_h[i]);
                xy[2 * k + 1] = log10(err[m][i]);
                ++k;
            }
        if (k >= 2) cj_plot_add_polyline(pl, xy, k, 0, COLORS[m], 2.5, 1);
    }
}

int main(int argc, char **argv) {
    const char *png = argc > 1 ? argv[1] : "docs/integrators.png";
    problem probs[2] = {{"damped oscillator (w = 2 pi, zeta = 0.05, x0 = 1, 10 s)",
                         {1, NULL, osc_accel, osc_jac},
                         osc_exact,
                         1.0},
                        {"pendulum (g/L = 9.81, theta0 = 1 rad, exact via elliptic sn, 10 s)",
                         {1, NULL, pen_accel, pen_jac},
                         pen_exact,
                         THETA0}};
    static double err[2][NM][NH], sps[2][NM][NH];
    for (int pi = 0; pi < 2; ++pi) {
        printf("\n%s: max |x - exact| over the run, ns per step\n", probs[pi].name);
        printf("%-9s", "h");
        for (int m = 0; m < NM; ++m) printf(" | %-24s", cj_integrator_name((cj_integrator)m));
        printf("\n");
        for (int i = 0; i < NH; ++i) {
            printf("%-9.0e", steps_h[i]);
            for (int m = 0; m < NM; ++m) {
                err[pi][m][i] = run(&probs[pi], (cj_integrator)m, steps_h[i], &sps[pi][m][i]);
                if (isfinite(err[pi][m][i]))
                    printf(" | %10.3e %8.0f ns   ", err[pi][m][i], 1e9 * sps[pi][m][i]);
                else
                    printf(" | %-24s", "unstable (blew up)");
            }
            printf("\n");
        }
    }
    printf("\nstep at which each becomes unstable on the damped oscillator (solution grows over "
           "4000 steps; bisection):\n");
    const double theory[NM] = {2 * ZETA / W, NAN, 2.785293563 / W, INFINITY};
    for (int m = 0; m < NM; ++m) {
        const double hs = unstable_step(&probs[0], (cj_integrator)m);
        printf("  %-17s h* = %-10.4g (h* w = %-8.4g)", cj_integrator_name((cj_integrator)m), hs,
               hs * W);
        if (m == 0) printf("  theory 2 zeta / w = %.4g", theory[0]);
        if (m == 1) printf("  theory: symplectic Euler's stability edge near h w = 2");
        if (m == 2) printf("  theory (undamped) 2.785 / w = %.4g", theory[2]);
        if (m == 3) printf("  theory: A-stable, never (checked up to h = 20)");
        printf("\n");
    }
    /* plot: two panels, log10 error against log10 h */
    cj_framebuffer *fb = NULL;
    if (cj_framebuffer_create(2100, 620, 0, NULL, &fb) != CJ_OK) return 1;
    cj_framebuffer_clear(fb, cj_rgba_make(255, 255, 255, 255));
    cj_font *font = NULL;
    if (cj_font_open(NULL, &font) != CJ_OK) font = NULL;
    const char *titles[3] = {"damped oscillator: log10 max error (up) vs 3 log10 h (right)",
                             "pendulum, 1 rad: log10 max error (up) vs 3 log10 h (right)",
                             "oscillator: log10 error vs 2 log10 CPU s per simulated s"};
    for (int pi = 0; pi < 3; ++pi) {
        cj_plot *pl = NULL;
        if (cj_plot_create(NULL, &pl) != CJ_OK) return 1;
        cj_plot_set_title(pl, titles[pi]);
        if (pi < 2)
            cj_plot_set_view(pl, -13.5, -13.5, 0, 1);
        else
            cj_plot_set_view(pl, -15, -13.5, -1.5, 1);
        plot_panel(pl, err[pi < 2 ? pi : 0], pi < 2 ? NULL : sps[0]);
        if (cj_plot_render(pl, fb, pi * 700, 40, 700, 580, font) != CJ_OK)
            fprintf(stderr, "plot: %s\n", cj_last_error());
        cj_plot_destroy(pl);
    }
    if (font) {
        double x = 30;
        for (int m = 0; m < NM; ++m) {
            cj_font_draw(font, fb, x, 14, 16, COLORS[m], cj_integrator_name((cj_integrator)m));
            double adv = 0;
            cj_font_measure(font, 16, cj_integrator_name((cj_integrator)m), &adv, NULL, NULL);
            x += adv + 40;
        }
        cj_font_draw(font, fb, x + 20, 14, 14, cj_rgba_make(90, 90, 90, 255),
                     "left panels: x = 3 log10 h (-12 is h = 1e-4 s); right: x = 2 log10 (CPU s "
                     "per simulated "
                     "s), -8 is 1e-4 s; lines stop where the error exceeds 10");
        cj_font_close(font);
    }
    const cj_status st = cj_image_write(png, fb->width, fb->height, (const uint8_t *)fb->pixels,
                                        (size_t)fb->stride * 4);
    printf("\nplot: %s (%s)\n", png, st == CJ_OK ? "written" : cj_last_error());
    cj_framebuffer_destroy(fb);
    return st == CJ_OK ? 0 : 1;
}
