/* Disc and sphere emitters (scene.h CJ_LIGHT_DISC, CJ_LIGHT_SPHERE; docs/light.md) against closed
 * forms, on a Lambertian floor z = 0 (albedo ρ, BRDF ρ/π) seen from above, radiometric model.
 *
 * DISC of radius R and radiance L parallel to the floor at height h, facing it. At a floor point
 * at horizontal distance a from the disc's axis,
 *   E = ∫ L cos θ cos θ′ / r² dA = (π L / 2) (1 − (h² + a² − R²) / √((h² + a² + R²)² − 4 a² R²))
 * (on the axis, a = 0: 2π L h² ∫₀^R ρ dρ / (h² + ρ²)² = π L R² / (h² + R²) = π L sin² θ, θ the
 * half-angle the disc subtends). The test checks this formula against a polar midpoint sum of
 * the integral before using it.
 * SPHERE of radius R and radiance L, centre at distance d: wherever the whole sphere is above
 * the horizon, E = π L (R/d)² cos θ (the projected solid angle of its cone, π sin² θ_max, times
 * the cosine of its axis).
 *
 * Renderers: the Whitted tracer with 256 stratified light samples per pixel and the path tracer
 * with 256 paths (next-event estimation by area for the disc and by solid angle for the sphere,
 * MIS with BRDF samples that hit them) must be within NOISE_TOL of the peak at every pixel and
 * their mean over the floor within BIAS_TOL of the oracle's; the Whitted tracer at 1 spp takes
 * the sphere's axis with weight π sin² θ_max, exact here; the rasterizer takes the disc as a
 * 32-gon of its area through Lambert's polygon formula (within RASTER_DISC_TOL of the closed
 * form; the far-field point it drew before, π R² L cos θ′ cos θ / r², was off by (R² + h²)/h²
 * on the axis) and the sphere as its far-field point (exact above the horizon); both where the
 * floor's horizon cuts them (test_horizons: a tilted disc through the floor, a sphere the floor
 * cuts, against midpoint sums; a disc at h = R/4) within HORIZON_TOL; one-sidedness of the disc;
 * a point inside a sphere light gets nothing from it; every renderer shows the emitters to
 * camera rays with their radiance. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "casteljau/render.h"
#include "casteljau/scene.h"
#include "casteljau/trace.h"
#include "light_floor.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define W         64
#define H         64
#define SPP       256
#define NOISE_TOL 0.03 /* one pixel, fraction of the peak radiance */
#define BIAS_TOL  3e-3 /* mean over the floor, fraction of the oracle's mean */

static const double PI = 3.14159265358979323846;
static const double RHO = 0.6, HALF = 2.0;
static const double DC[3] = {0.2, -0.1, 0.8}, DR = 0.6, DL = 3.0; /* disc: centre, radius, L */
static const double SC[3] = {-0.3, 0.2, 1.0}, SR = 0.3, SL = 2.0; /* sphere */
static const double EM = 1.25; /* radiance of an emissive surface */

static cj_scene *floor_scene(void) {
    cj_scene *s = cj_test_light_floor(W, H, HALF, 0.0, 10.0, RHO, CJ_LIGHT_RADIOMETRIC);
    assert_non_null(s);
    return s;
}

static void add_disc(cj_scene *s, double dir_z) {
    cj_light l = cj_light_defaults(CJ_LIGHT_DISC);
    l.position = cj_v3(DC[0], DC[1], DC[2]);
    l.direction = cj_v3(0, 0, dir_z);
    l.radius = DR;
    l.intensity = DL;
    assert_int_equal(cj_scene_add_light(s, &l, NULL), CJ_OK);
}

static void add_sphere(cj_scene *s) {
    cj_light l = cj_light_defaults(CJ_LIGHT_SPHERE);
    l.position = cj_v3(SC[0], SC[1], SC[2]);
    l.radius = SR;
    l.intensity = SL;
    assert_int_equal(cj_scene_add_light(s, &l, NULL), CJ_OK);
}

static void floor_point(int x, int y, double *px, double *py) {
    *px = -HALF + (x + 0.5) * (2 * HALF / W);
    *py = -HALF + (y + 0.5) * (2 * HALF / H);
}

/* The closed forms. */
static double disc_E(double a, double h, double R, double L) {
    const double s = h * h + a * a;
    return 0.5 * PI * L * (1.0 - (s - R * R) / sqrt((s + R * R) * (s + R * R) - 4 * a * a * R * R));
}

static double sphere_E(double px, double py) {
    const double dx = SC[0] - px, dy = SC[1] - py, dz = SC[2], d2 = dx * dx + dy * dy + dz * dz;
    return PI * SL * SR * SR / d2 * (dz / sqrt(d2));
}

/* kind 0 the rasterizer, 1 Whitted, 2 the path tracer */
static cj_render_image *draw(const cj_scene *s, int kind, int spp) {
    cj_render_options o = cj_render_options_defaults();
    o.spp = spp;
    cj_trace_options to;
    memset(&to, 0, sizeof to);
    to.integrator = kind == 2 ? CJ_INTEGRATOR_PATH : CJ_INTEGRATOR_WHITTED;
    cj_render_image *img = NULL;
    cj_status st = kind ? cj_render_trace_with_options(s, &o, &to, 0, NULL, &img, NULL)
                        : cj_render_raster(s, &o, 0, NULL, &img, NULL);
    if (st) printf("render failed: %s\n", cj_last_error());
    assert_int_equal(st, CJ_OK);
    return img;
}

typedef struct errs {
    double worst, rms, bias;
} errs;

/* Pixels with ref < 0 are left out (the emitter itself in front of the floor). */
static errs compare(const cj_render_image *img, const double *ref, double peak) {
    errs e = {0, 0, 0};
    double sum = 0, sum_ref = 0;
    int n = 0;
    for (int i = 0; i < W * H; ++i) {
        if (ref[i] < 0.0) continue;
        const double d = fabs(img->rgba[4 * i] - ref[i]) / peak;
        e.worst = fmax(e.worst, d);
        e.rms += d * d;
        sum += img->rgba[4 * i];
        sum_ref += ref[i];
        n++;
    }
    e.rms = sqrt(e.rms / n);
    e.bias = fabs(sum - sum_ref) / sum_ref;
    return e;
}

/* The path tracer, one unstratified light sample per bounce: per pixel looser than the Whitted
 * tracer's 256 strata; RMS over the floor and no bias. */
#define PATH_WORST_TOL 0.15
#define PATH_RMS_TOL   0.03
/* The rasterizer's disc (a 32-gon of the disc's area, reflect_model.h), fraction of the peak:
 * float shading on top of the polygon's ~2e-6 at h = 1.33 R */
#define RASTER_DISC_TOL 1e-5
/* the same where the floor's horizon cuts the emitter or the disc is R/4 above it */
#define HORIZON_TOL 1e-4

static const char *const NAMES[3] = {"render", "trace (whitted)", "trace (path)"};

static void test_disc(void **state) {
    (void)state;
    /* the oracle against a polar midpoint sum of cos θ cos θ′ / r² over the disc */
    const double as[3] = {0.0, 0.45, 1.7};
    for (int k = 0; k < 3; ++k) {
        const int NR = 1500, NP = 1500;
        double sum = 0.0;
        for (int i = 0; i < NR; ++i)
            for (int j = 0; j < NP; ++j) {
                const double r = (i + 0.5) * DR / NR, ph = (j + 0.5) * 2 * PI / NP;
                const double dx = r * cos(ph) - as[k], dy = r * sin(ph), h = DC[2];
                const double r2 = dx * dx + dy * dy + h * h;
                sum += DL * h * h / (r2 * r2) * r * (DR / NR) * (2 * PI / NP);
            }
        const double E = disc_E(as[k], DC[2], DR, DL);
        printf("oracle: disc irradiance at a = %.2f: closed form %.9f, midpoint sum %.9f\n", as[k],
               E, sum);
        assert_true(fabs(E - sum) < 2e-6 * E);
    }
    assert_true(fabs(disc_E(0, DC[2], DR, DL) - PI * DL * DR * DR / (DC[2] * DC[2] + DR * DR)) <
                1e-14);
    double *ref = malloc(sizeof(double) * W * H), *far = malloc(sizeof(double) * W * H), peak = 0;
    assert_true(ref && far);
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            double fx, fy;
            floor_point(x, y, &fx, &fy);
            const double dx = fx - DC[0], dy = fy - DC[1], h = DC[2];
            const double a = sqrt(dx * dx + dy * dy), r2 = a * a + h * h;
            ref[y * W + x] = RHO / PI * disc_E(a, h, DR, DL);
            far[y * W + x] = RHO / PI * PI * DR * DR * DL * (h * h) / (r2 * r2);
            peak = fmax(peak, ref[y * W + x]);
        }
    cj_render_image *raster = NULL;
    for (int kind = 0; kind < 3; ++kind) {
        cj_scene *s = floor_scene();
        add_disc(s, -1.0);
        cj_render_image *img = draw(s, kind, kind ? SPP : 1);
        errs e = compare(img, ref, peak);
        if (kind) {
            printf("disc (R %g at height %g, L %g), peak %.5f: %s %d spp, worst pixel %.2e of the "
                   "peak, RMS %.2e, mean off by %.2e (tol %.0e)\n",
                   DR, DC[2], DL, peak, NAMES[kind], SPP, e.worst, e.rms, e.bias, BIAS_TOL);
            assert_true(e.worst <= (kind == 2 ? PATH_WORST_TOL : NOISE_TOL));
            assert_true(e.rms <= (kind == 2 ? PATH_RMS_TOL : NOISE_TOL));
            assert_true(e.bias <= BIAS_TOL);
        } else {
            const errs x = compare(img, far, peak);
            printf("disc: render (the disc as a %d-gon of its area) off the exact irradiance by "
                   "%.2e of the peak, RMS %.2e (tol %.0e); the far-field point it replaced was "
                   "off by %.3f\n",
                   32, e.worst, e.rms, RASTER_DISC_TOL, x.worst);
            assert_true(e.worst <= RASTER_DISC_TOL);
            assert_true(x.worst > 0.3); /* the oracle tells the two apart */
            raster = img;
            cj_scene_destroy(s);
            continue;
        }
        /* render against trace directly: the tracer's noise is the whole difference */
        double worst = 0, rms = 0;
        for (int i = 0; i < W * H; ++i) {
            const double d = fabs(img->rgba[4 * i] - raster->rgba[4 * i]) / peak;
            worst = fmax(worst, d);
            rms += d * d;
        }
        rms = sqrt(rms / (W * H));
        printf("disc: render against %s %d spp: worst pixel %.2e of the peak, RMS %.2e\n",
               NAMES[kind], SPP, worst, rms);
        assert_true(worst <= (kind == 2 ? PATH_WORST_TOL : NOISE_TOL) + RASTER_DISC_TOL);
        assert_true(rms <= (kind == 2 ? PATH_RMS_TOL : NOISE_TOL) + RASTER_DISC_TOL);
        cj_render_image_destroy(img);
        cj_scene_destroy(s);
    }
    cj_render_image_destroy(raster);
    /* one-sided: facing up, the floor gets nothing (the disc itself faces the camera) */
    for (int kind = 0; kind < 3; ++kind) {
        cj_scene *s = floor_scene();
        add_disc(s, 1.0);
        cj_render_image *img = draw(s, kind, kind ? 16 : 1);
        float mx = 0;
        for (int y = 0; y < H; ++y)
            for (int x = 0; x < W; ++x) {
                double fx, fy;
                floor_point(x, y, &fx, &fy);
                if (hypot(fx - DC[0], fy - DC[1]) > DR + sqrt(2.0) * HALF / W)
                    mx = fmaxf(mx, img->rgba[4 * (y * W + x)]);
            }
        printf("%s: disc facing away, brightest floor pixel outside its outline %g\n", NAMES[kind],
               mx);
        assert_true(mx == 0.0f);
        cj_render_image_destroy(img);
        cj_scene_destroy(s);
    }
    free(ref);
    free(far);
}

static void test_sphere(void **state) {
    (void)state;
    double *ref = malloc(sizeof(double) * W * H), *seen = malloc(sizeof(double) * W * H), peak = 0;
    assert_true(ref && seen);
    const double half_diag = sqrt(2.0) * HALF / W;
    int inside = 0;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            double fx, fy;
            floor_point(x, y, &fx, &fy);
            const int i = y * W + x;
            ref[i] = RHO / PI * sphere_E(fx, fy);
            peak = fmax(peak, ref[i]);
            /* where camera rays meet the emitter: all of the pixel (L), part of it (left out) */
            const double c = hypot(fx - SC[0], fy - SC[1]);
            seen[i] = c < SR - half_diag ? SL : (c < SR + half_diag ? -1.0 : ref[i]);
            inside += c < SR - half_diag;
        }
    for (int kind = 0; kind < 3; ++kind) {
        for (int pass = 0; pass < (kind == 1 ? 2 : 1); ++pass) {
            const int spp = kind == 0 || pass == 1 ? 1 : SPP;
            cj_scene *s = floor_scene();
            add_sphere(s);
            cj_render_image *img = draw(s, kind, spp);
            /* every renderer shows the emitter to camera rays */
            const double *want = seen;
            for (int i = 0; i < W * H; ++i)
                if (want[i] == SL) assert_true(img->rgba[4 * i] == (float)SL);
            errs e = compare(img, want, peak);
            printf("sphere (R %g at height %g, L %g), peak %.5f: %s %d spp, worst pixel %.2e of "
                   "the peak, RMS %.2e, mean off by %.2e\n",
                   SR, SC[2], SL, peak, NAMES[kind], spp, e.worst, e.rms, e.bias);
            if (spp == 1) { /* the closed form itself, up to float pixels */
                assert_true(e.worst <= 1e-5);
            } else {
                assert_true(e.worst <= (kind == 2 ? PATH_WORST_TOL : NOISE_TOL));
                assert_true(e.rms <= (kind == 2 ? PATH_RMS_TOL : NOISE_TOL));
                assert_true(e.bias <= BIAS_TOL);
            }
            printf("  the %d pixels wholly inside the emitter's outline show its radiance %g "
                   "exactly\n",
                   inside, SL);
            cj_render_image_destroy(img);
            cj_scene_destroy(s);
        }
    }
    /* a scene inside a sphere light, camera included, gets nothing from it */
    for (int kind = 1; kind < 3; ++kind) {
        cj_scene *s = floor_scene();
        cj_light l = cj_light_defaults(CJ_LIGHT_SPHERE);
        l.position = cj_v3(0, 0, 0);
        l.radius = 100.0;
        assert_int_equal(cj_scene_add_light(s, &l, NULL), CJ_OK);
        cj_render_image *img = draw(s, kind, 16);
        float mx = 0;
        for (int i = 0; i < W * H; ++i) mx = fmaxf(mx, img->rgba[4 * i]);
        printf("%s: the scene inside a sphere light (it shines outwards): brightest pixel %g\n",
               NAMES[kind], mx);
        assert_true(mx == 0.0f);
        cj_render_image_destroy(img);
        cj_scene_destroy(s);
    }
    free(ref);
    free(seen);
}

/* Both renderers on one scene with emitters in view: a sphere light over the floor and a disc
 * facing the camera (away from the floor). At 1 sample per pixel both take the pixel centre's
 * ray: the emitters' pixels equal their radiance in both, and the floor (the sphere's exact
 * irradiance in both) agrees to float rounding. */
static void test_renderers_agree(void **state) {
    (void)state;
    cj_scene *s = floor_scene();
    cj_light sl = cj_light_defaults(CJ_LIGHT_SPHERE);
    sl.position = cj_v3(SC[0], SC[1], SC[2]);
    sl.radius = SR;
    sl.intensity = SL;
    sl.casts_shadows =
        0; /* the rasterizer has no shadows (the emissive patch below would cast one) */
    assert_int_equal(cj_scene_add_light(s, &sl, NULL), CJ_OK);
    add_disc(s, 1.0);
    /* and a surface whose material emits (reflecting nothing), seen by both */
    cj_material em = cj_material_defaults();
    em.color = cj_rgb_make(0, 0, 0);
    em.ka = em.kd = em.ks = 0.0;
    em.emission = cj_rgb_make(EM, EM, EM);
    int emi, gi;
    assert_int_equal(cj_scene_add_material(s, &em, &emi), CJ_OK);
    cj_geometry g;
    memset(&g, 0, sizeof g);
    g.kind = CJ_GEOM_PLANAR;
    assert_int_equal(cj_planar_patch_init(&g.u.planar, cj_v3(0.9, -1.6, 0.05), cj_v3(0.8, 0, 0),
                                          cj_v3(0, 0.5, 0)),
                     CJ_OK);
    assert_int_equal(cj_scene_add_geometry(s, &g, &gi), CJ_OK);
    cj_node n = cj_node_defaults(gi, emi);
    assert_int_equal(cj_scene_add_node(s, &n, NULL), CJ_OK);
    cj_render_image *r = draw(s, 0, 1), *t = draw(s, 1, 1);
    double worst = 0.0, peak = 0.0;
    int emitter_px = 0, emissive_px = 0;
    for (int i = 0; i < W * H; ++i) {
        const float a = r->rgba[4 * i], b = t->rgba[4 * i];
        if (a == (float)SL || a == (float)DL || b == (float)SL || b == (float)DL) {
            assert_true(a == b);
            emitter_px++;
            continue;
        }
        if (a == (float)EM || b == (float)EM) {
            assert_true(a == b);
            emissive_px++;
            continue;
        }
        peak = fmax(peak, b);
        worst = fmax(worst, fabs(a - b));
    }
    printf("render vs trace with emitters in view: %d emitter pixels and %d pixels of an emissive "
           "surface identical, floor within %.2e of its peak %.4f\n",
           emitter_px, emissive_px, worst / peak, peak);
    assert_true(emissive_px >= 90); /* 0.8 x 0.5 at 16 px per unit: 102 */
    assert_true(emitter_px > 300);  /* the disc (~290 px) and the sphere (~72 px), overlapping */
    assert_true(worst <= 1e-5 * peak);
    cj_render_image_destroy(r);
    cj_render_image_destroy(t);
    cj_scene_destroy(s);
}

static void test_refusals(void **state) {
    (void)state;
    cj_scene *s = floor_scene();
    cj_light l = cj_light_defaults(CJ_LIGHT_SPHERE);
    l.radius = 0.0;
    assert_int_equal(cj_scene_add_light(s, &l, NULL), CJ_ERR_RANGE);
    printf("radius 0: %s\n", cj_last_error());
    l = cj_light_defaults(CJ_LIGHT_DISC);
    l.direction = cj_v3(0, 0, 0);
    assert_int_not_equal(cj_scene_add_light(s, &l, NULL), CJ_OK);
    printf("disc without a normal: %s\n", cj_last_error());
    l = cj_light_defaults(CJ_LIGHT_DISC);
    l.radius = NAN;
    assert_int_equal(cj_scene_add_light(s, &l, NULL), CJ_ERR_NONFINITE);
    printf("NaN radius: %s\n", cj_last_error());
    cj_scene_destroy(s);
}

/* Oracles for emitters cut by the floor's horizon (floor normal +z), by midpoint sums over the
 * emitter. A disc (centre o, unit normal nl, radius R, radiance L) seen from floor point p:
 * ∫ L cos θ cos θ′ / r² dA over its points above the floor and facing p. */
static double disc_sum(const double p[2], const double o[3], const double nl[3], double R,
                       double L) {
    const int NR = 1000, NP = 1000;
    double e1[3] = {nl[1], -nl[0], 0.0};
    if (hypot(e1[0], e1[1]) < 1e-9) e1[0] = 1.0, e1[1] = 0.0;
    const double l1 = hypot(e1[0], e1[1]);
    e1[0] /= l1, e1[1] /= l1;
    const double e2[3] = {nl[1] * e1[2] - nl[2] * e1[1], nl[2] * e1[0] - nl[0] * e1[2],
                          nl[0] * e1[1] - nl[1] * e1[0]};
    double sum = 0.0;
    for (int i = 0; i < NR; ++i)
        for (int j = 0; j < NP; ++j) {
            const double r = (i + 0.5) * R / NR, ph = (j + 0.5) * 2 * PI / NP;
            const double c = r * cos(ph), sn = r * sin(ph);
            double w[3];
            for (int k = 0; k < 3; ++k) w[k] = o[k] + c * e1[k] + sn * e2[k];
            w[0] -= p[0], w[1] -= p[1];
            const double r2 = w[0] * w[0] + w[1] * w[1] + w[2] * w[2], rl = sqrt(r2);
            const double ct = w[2] / rl, ctl = -(w[0] * nl[0] + w[1] * nl[1] + w[2] * nl[2]) / rl;
            if (ct > 0 && ctl > 0) sum += L * ct * ctl / r2 * r * (R / NR) * (2 * PI / NP);
        }
    return sum;
}

/* A sphere (centre o, radius R, radiance L) from floor point p: L ∫ max(0, ω_z) dω over the cone
 * of directions that meet it, in polar coordinates about its axis. */
static double sphere_sum(const double p[2], const double o[3], double R, double L) {
    const int NA = 1000, NP = 1000;
    double u[3] = {o[0] - p[0], o[1] - p[1], o[2]};
    const double d = sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]), amax = asin(R / d);
    for (int k = 0; k < 3; ++k) u[k] /= d;
    double e1[3] = {-u[1], u[0], 0.0};
    const double l1 = hypot(e1[0], e1[1]);
    e1[0] /= l1, e1[1] /= l1;
    const double e2[3] = {u[1] * e1[2] - u[2] * e1[1], u[2] * e1[0] - u[0] * e1[2],
                          u[0] * e1[1] - u[1] * e1[0]};
    double sum = 0.0;
    for (int i = 0; i < NA; ++i)
        for (int j = 0; j < NP; ++j) {
            const double a = (i + 0.5) * amax / NA, ph = (j + 0.5) * 2 * PI / NP;
            const double wz = cos(a) * u[2] + sin(a) * (cos(ph) * e1[2] + sin(ph) * e2[2]);
            if (wz > 0) sum += L * wz * sin(a) * (amax / NA) * (2 * PI / NP);
        }
    return sum;
}

/* The rasterizer's disc and sphere where the floor's horizon cuts them (polygon path, the
 * horizon clip), and a disc close to the floor, against the oracles above at every 4th pixel
 * (pixels whose view the emitter hides left out), and against the Whitted tracer at 256 spp. */
static void test_horizons(void **state) {
    (void)state;
    /* the closed form still holds the disc at h = R/4 (the polygon's hardest regular case) */
    {
        const double h = 0.25 * DR, o[3] = {DC[0], DC[1], h}, nl[3] = {0, 0, -1};
        const double pt[2] = {DC[0] + 0.5, DC[1]};
        const double a = disc_E(0.5, h, DR, DL), b = disc_sum(pt, o, nl, DR, DL);
        printf("oracle: disc at h = R/4, a = 0.5: closed form %.9f, midpoint sum %.9f\n", a, b);
        assert_true(fabs(a - b) < 1e-5 * a);
    }
    for (int which = 0; which < 3; ++which) {
        cj_scene *s = floor_scene();
        cj_light l = cj_light_defaults(which == 2 ? CJ_LIGHT_SPHERE : CJ_LIGHT_DISC);
        double o[3] = {DC[0], DC[1], which == 0 ? 0.25 * DR : 0.25}, nl[3] = {0, 0, -1};
        const double R = which == 2 ? SR : DR, L = which == 2 ? SL : DL;
        if (which == 1) { /* tilted, its lower part below the floor */
            nl[0] = 2 / sqrt(5.0), nl[2] = -1 / sqrt(5.0);
        }
        if (which == 2) o[2] = 0.2; /* a sphere of radius 0.3 cut by the floor */
        l.position = cj_v3(o[0], o[1], o[2]);
        l.direction = cj_v3(nl[0], nl[1], nl[2]);
        l.radius = R;
        l.intensity = L;
        l.casts_shadows = 0;
        assert_int_equal(cj_scene_add_light(s, &l, NULL), CJ_OK);
        cj_render_image *r = draw(s, 0, 1), *t = draw(s, 1, SPP);
        double worst = 0, far_worst = 0, peak = 0, tworst = 0, trms = 0;
        int n = 0, nt = 0;
        for (int y = 0; y < H; ++y)
            for (int x = 0; x < W; ++x) {
                double p[2];
                floor_point(x, y, &p[0], &p[1]);
                const double dx = o[0] - p[0], dy = o[1] - p[1], dz = o[2];
                if (hypot(dx, dy) <= R + sqrt(2.0) * 2 * HALF / W) continue; /* hidden */
                const float rv = r->rgba[4 * (y * W + x)], tv = t->rgba[4 * (y * W + x)];
                tworst = fmax(tworst, fabs(rv - tv));
                trms += (rv - tv) * (rv - tv);
                nt++;
                if (x % 4 || y % 4) continue;
                double E;
                if (which == 0)
                    E = disc_E(hypot(dx, dy), o[2], R, L);
                else
                    E = which == 1 ? disc_sum(p, o, nl, R, L) : sphere_sum(p, o, R, L);
                /* the far-field point the rasterizer drew before */
                const double d2 = dx * dx + dy * dy + dz * dz, d = sqrt(d2);
                const double ctl = which == 2 ? 1 : (dx * nl[0] + dy * nl[1] + dz * nl[2]) / d;
                const double far = PI * R * R * L * fmax(0, ctl) * fmax(0, dz / d) / d2;
                peak = fmax(peak, RHO / PI * E);
                worst = fmax(worst, fabs(rv - RHO / PI * E));
                far_worst = fmax(far_worst, fabs(RHO / PI * (far - E)));
                n++;
            }
        const char *what[3] = {"disc parallel at h = R/4", "disc tilted through the floor",
                               "sphere cut by the floor"};
        printf("%s: render against the oracle at %d pixels: worst %.2e of the peak %.4f (tol "
               "%.0e); the far-field point was off by %.3f; against trace (whitted) %d spp at %d "
               "pixels: worst %.2e, RMS %.2e\n",
               what[which], n, worst / peak, peak, HORIZON_TOL, far_worst / peak, SPP, nt,
               tworst / peak, sqrt(trms / nt) / peak);
        assert_true(n > 100);
        assert_true(worst <= HORIZON_TOL * peak);
        assert_true(far_worst > 0.02 * peak); /* the oracle tells the two apart */
        assert_true(sqrt(trms / nt) <= NOISE_TOL * peak);
        cj_render_image_destroy(r);
        cj_render_image_destroy(t);
        cj_scene_destroy(s);
    }
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_disc),
        cmocka_unit_test(test_sphere),
        cmocka_unit_test(test_renderers_agree),
        cmocka_unit_test(test_horizons),
        cmocka_unit_test(test_refusals),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
