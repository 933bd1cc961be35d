/* One reflection model in both renderers (issue 21, docs/light.md), checked against the closed
 * form of that model on an exact unit sphere, never against the renderers' own code:
 *  - the scene (orthographic unit sphere, a directional light 80° from the view,
 *    ambient 0.3, kd 0.6, ks 0.5, α 3): at every pixel whose centre sees the sphere, the
 *    tracer (exact sphere) matches the closed form within 1e-6 and the rasterizer (tessellated
 *    sphere, float shading) within RASTER_TOL; beyond the terminator (n·l <= 0) both give the
 *    ambient term alone, c_r r_a I_a (the pixel of the issue, n·l = −0.02, among them);
 *  - the same for the Phong (mirror) lobe, and for a perspective view lit by a point and a
 *    spot light;
 *  - rasterizer and tracer differ per pixel by at most AGREE_TOL at every pixel whose 3 × 3
 *    neighbourhood is covered in both images (silhouette pixels are sampled differently: a
 *    tessellated outline against the exact one);
 *  - the same lamps in radiometric units (1/r², Lambert's 1/π, the normalised Phong lobe
 *    (α+2)/(2π) cos^α and the Blinn lobe (α+1)/(8π) cos^α θ_h / ((l·h) max(n·l, n·v)), each
 *    times n·l);
 *  - the JSON reader reads "specular_model" and the writer writes it back. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "casteljau/render.h"
#include "casteljau/scene.h"
#include "casteljau/scene_json.h"
#include "casteljau/trace.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#define W 96
#define H 96
/* Tolerances as fractions of the brightest closed-form pixel of the scene: */
#define RASTER_TOL 4e-3 /* the rasterizer against the closed form (tessellated normals, float) */
#define AGREE_TOL  4e-3 /* rasterizer against tracer, interior pixels */
#define TRACE_TOL  1e-6 /* the tracer against the closed form (exact sphere; a float image) */

static const double PI = 3.14159265358979323846;

typedef struct light_def {
    cj_light_kind kind;
    double I[3];
    double pos[3], dir[3]; /* dir: the way the light travels */
    double cut, expo;
} light_def;

typedef struct scene_def {
    int ortho;
    double ia[3]; /* ambient colour × intensity */
    double cr[3], cp[3], ka, kd, ks, alpha;
    cj_specular_model model;
    int radiometric; /* 1: 1/r², BRDF r_d c_r/π + r_s c_p N(α) s */
    int nlights;
    light_def lights[3];
} scene_def;

static cj_scene *build(const scene_def *d) {
    cj_scene *s;
    assert_int_equal(cj_scene_create(NULL, &s), CJ_OK);
    cj_camera cam = cj_camera_defaults();
    if (d->ortho) {
        cam.projection = CJ_PROJ_ORTHOGRAPHIC;
        cam.ortho_height = 2.4;
    } else {
        cam.fov_y = 30.0 * PI / 180.0;
    }
    assert_int_equal(cj_scene_set_camera(s, &cam), CJ_OK);
    cj_scene_settings st = cj_scene_settings_defaults();
    st.width = W;
    st.height = H;
    st.spp = 1;
    st.tol_px = 0.05;
    st.light_model = d->radiometric ? CJ_LIGHT_RADIOMETRIC : CJ_LIGHT_LEGACY;
    assert_int_equal(cj_scene_set_settings(s, &st), CJ_OK);
    cj_material m = cj_material_defaults();
    m.color = cj_rgb_make(d->cr[0], d->cr[1], d->cr[2]);
    m.specular = cj_rgb_make(d->cp[0], d->cp[1], d->cp[2]);
    m.ka = d->ka;
    m.kd = d->kd;
    m.ks = d->ks;
    m.alpha = d->alpha;
    m.specular_model = d->model;
    m.receives_shadows = 0;
    int mi, gi;
    assert_int_equal(cj_scene_add_material(s, &m, &mi), CJ_OK);
    cj_geometry g;
    memset(&g, 0, sizeof g);
    g.kind = CJ_GEOM_SPHERE;
    g.u.sphere.radius = 1.0;
    assert_int_equal(cj_scene_add_geometry(s, &g, &gi), CJ_OK);
    cj_node n = cj_node_defaults(gi, mi);
    assert_int_equal(cj_scene_add_node(s, &n, NULL), CJ_OK);
    cj_light a = cj_light_defaults(CJ_LIGHT_AMBIENT);
    a.color = cj_rgb_make(d->ia[0], d->ia[1], d->ia[2]);
    a.intensity = 1.0;
    assert_int_equal(cj_scene_add_light(s, &a, NULL), CJ_OK);
    for (int i = 0; i < d->nlights; ++i) {
        const light_def *ld = &d->lights[i];
        cj_light l = cj_light_defaults(ld->kind);
        l.color = cj_rgb_make(ld->I[0], ld->I[1], ld->I[2]);
        l.intensity = 1.0;
        l.position = cj_v3(ld->pos[0], ld->pos[1], ld->pos[2]);
        l.direction = cj_v3(ld->dir[0], ld->dir[1], ld->dir[2]);
        l.spot_angle = ld->cut;
        l.spot_exponent = ld->expo;
        l.casts_shadows = 0;
        assert_int_equal(cj_scene_add_light(s, &l, NULL), CJ_OK);
    }
    return s;
}

static void unit(double a[3]) {
    double l = sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    for (int k = 0; k < 3; ++k) a[k] /= l;
}

static double dot(const double a[3], const double b[3]) {
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* The closed form at the exact hit of the pixel centre's ray with the unit sphere: 1 and the
 * radiance in out, or 0 when the ray misses. nl_min receives the smallest n·l of its lights. */
static int closed_form(const scene_def *d, const cj_scene *s, int x, int y, double out[3],
                       double *nl_min) {
    cj_vec3 o, dir;
    assert_int_equal(cj_camera_ray(cj_scene_get_camera(s), W, H, x + 0.5, y + 0.5, &o, &dir),
                     CJ_OK);
    double O[3] = {o.x, o.y, o.z}, D[3] = {dir.x, dir.y, dir.z};
    double b = dot(O, D), c = dot(O, O) - 1.0, disc = b * b - c;
    if (disc <= 0.0) return 0;
    double t = -b - sqrt(disc), p[3], n[3], v[3];
    for (int k = 0; k < 3; ++k) {
        p[k] = O[k] + t * D[k];
        n[k] = p[k];
        v[k] = -D[k];
    }
    unit(n);
    for (int k = 0; k < 3; ++k) out[k] = d->cr[k] * d->ka * d->ia[k];
    *nl_min = 2.0;
    for (int i = 0; i < d->nlights; ++i) {
        const light_def *L = &d->lights[i];
        double l[3], f = 1.0;
        if (L->kind == CJ_LIGHT_DIRECTIONAL) {
            for (int k = 0; k < 3; ++k) l[k] = -L->dir[k];
        } else {
            for (int k = 0; k < 3; ++k) l[k] = L->pos[k] - p[k];
            if (d->radiometric) f = 1.0 / dot(l, l);
        }
        unit(l);
        if (L->kind == CJ_LIGHT_SPOT) {
            double a[3] = {L->dir[0], L->dir[1], L->dir[2]};
            unit(a);
            double ct = -dot(a, l);
            f = ct >= cos(L->cut) ? f * pow(ct, L->expo) : 0.0;
        }
        double nl = dot(n, l);
        if (nl < *nl_min) *nl_min = nl;
        if (nl <= 0.0) continue; /* the light is behind the surface: nothing at all */
        double c2, lh = 0.0;
        if (d->model == CJ_SPEC_PHONG) {
            double m[3];
            for (int k = 0; k < 3; ++k) m[k] = 2.0 * nl * n[k] - l[k];
            c2 = dot(m, v);
        } else {
            double h[3] = {l[0] + v[0], l[1] + v[1], l[2] + v[2]};
            unit(h);
            c2 = dot(n, h);
            lh = dot(l, h);
        }
        double sp = pow(c2 > 0.0 ? c2 : 0.0, d->alpha), df = nl;
        if (d->radiometric) { /* BRDF × n·l: Lambert 1/π, normalised Phong, Blinn (A-S) */
            df = nl / PI;
            double nv = dot(n, v);
            sp *= d->model == CJ_SPEC_PHONG
                      ? (d->alpha + 2) / (2 * PI) * nl
                      : (d->alpha + 1) / (8 * PI * lh * (nv > nl ? nv : nl)) * nl;
        }
        const double kd = d->kd, ks = d->ks;
        for (int k = 0; k < 3; ++k)
            out[k] += f * L->I[k] * (d->cr[k] * kd * df + d->cp[k] * ks * sp);
    }
    return 1;
}

static int covered(const cj_render_image *img, int x, int y) {
    for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
            int X = x + dx, Y = y + dy;
            if (X < 0 || Y < 0 || X >= W || Y >= H) return 0;
            if (img->ids[(size_t)Y * W + X] == 0) return 0;
        }
    return 1;
}

static void check_scene(const scene_def *d, const char *name) {
    cj_scene *s = build(d);
    cj_render_options o = cj_render_options_defaults();
    cj_render_image *ri = NULL, *ti = NULL;
    assert_int_equal(cj_render_raster(s, &o, CJ_IMAGE_IDS, NULL, &ri, NULL), CJ_OK);
    assert_int_equal(cj_render_trace(s, &o, CJ_IMAGE_IDS, NULL, &ti, NULL), CJ_OK);
    double worst_r = 0, worst_t = 0, worst_rt = 0, worst_dark = 0;
    double peak = 0;
    int hits = 0, dark = 0, interior = 0;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            double ref[3], nl_min;
            int hit = closed_form(d, s, x, y, ref, &nl_min);
            size_t i = (size_t)y * W + x;
            const float *rp = ri->rgba + 4 * i, *tp = ti->rgba + 4 * i;
            int inside = covered(ri, x, y) && covered(ti, x, y);
            if (hit) {
                ++hits;
                for (int k = 0; k < 3; ++k)
                    if (ref[k] > peak) peak = ref[k];
                assert_int_not_equal(ti->ids[i], 0);
                for (int k = 0; k < 3; ++k) {
                    double e = fabs(tp[k] - ref[k]);
                    if (e > worst_t) worst_t = e;
                }
                if (inside) {
                    for (int k = 0; k < 3; ++k) {
                        double e = fabs(rp[k] - ref[k]);
                        if (e > worst_r) worst_r = e;
                    }
                }
                if (nl_min <= 0.0 && d->nlights == 1) {
                    /* beyond the terminator: the ambient term alone in both */
                    ++dark;
                    for (int k = 0; k < 3; ++k) {
                        double a = d->cr[k] * d->ka * d->ia[k];
                        double e = fabs(tp[k] - a);
                        if (inside && fabs(rp[k] - a) > e) e = fabs(rp[k] - a);
                        if (e > worst_dark) worst_dark = e;
                    }
                }
            }
            if (inside) {
                ++interior;
                for (int k = 0; k < 3; ++k) {
                    double e = fabs(rp[k] - tp[k]);
                    if (e > worst_rt) worst_rt = e;
                }
            }
        }
    worst_r /= peak, worst_t /= peak, worst_rt /= peak, worst_dark /= peak;
    printf("%s: %d sphere pixels (%d interior, %d beyond the terminator), brightest %.4f; as "
           "fractions of it: |trace - closed form| <= %.2e (tol %.0e), |render - closed form| <= "
           "%.2e (tol %.0e), |render - trace| <= %.2e (tol %.0e), beyond the terminator |x - "
           "ambient| <= %.2e\n",
           name, hits, interior, dark, peak, worst_t, TRACE_TOL, worst_r, RASTER_TOL, worst_rt,
           AGREE_TOL, worst_dark);
    assert_true(hits > W * H / 3);
    assert_true(interior > hits / 2);
    assert_true(worst_t <= TRACE_TOL);
    assert_true(worst_r <= RASTER_TOL);
    assert_true(worst_rt <= AGREE_TOL);
    if (d->nlights == 1) {
        assert_true(dark > 100);
        assert_true(worst_dark <= RASTER_TOL);
    }
    cj_render_image_destroy(ri);
    cj_render_image_destroy(ti);
    cj_scene_destroy(s);
}

/* The scene: the view is +z, the light comes from 80° off it. */
static scene_def terminator_scene(cj_specular_model model) {
    scene_def d;
    memset(&d, 0, sizeof d);
    d.ortho = 1;
    d.ia[0] = d.ia[1] = d.ia[2] = 0.3;
    d.cr[0] = 0.0628, d.cr[1] = 0.15, d.cr[2] = 0.3333;
    d.cp[0] = d.cp[1] = d.cp[2] = 1.0;
    d.ka = 0.6;
    d.kd = 0.6;
    d.ks = 0.5;
    d.alpha = 3.0;
    d.model = model;
    d.nlights = 1;
    light_def *L = &d.lights[0];
    L->kind = CJ_LIGHT_DIRECTIONAL;
    L->I[0] = L->I[1] = L->I[2] = 1.0;
    double th = 80.0 * PI / 180.0;
    L->dir[0] = -sin(th);
    L->dir[2] = -cos(th);
    return d;
}

static void test_terminator_blinn(void **state) {
    (void)state;
    scene_def d = terminator_scene(CJ_SPEC_BLINN);
    check_scene(&d, "terminator, blinn");
}

static void test_terminator_phong(void **state) {
    (void)state;
    scene_def d = terminator_scene(CJ_SPEC_PHONG);
    check_scene(&d, "terminator, phong");
}

static scene_def lamps_scene(cj_specular_model model) {
    scene_def d;
    memset(&d, 0, sizeof d);
    d.ortho = 0;
    d.ia[0] = 0.1, d.ia[1] = 0.12, d.ia[2] = 0.15;
    d.cr[0] = 0.8, d.cr[1] = 0.5, d.cr[2] = 0.3;
    d.cp[0] = 1.0, d.cp[1] = 0.9, d.cp[2] = 0.8;
    d.ka = 1.0;
    d.kd = 0.7;
    d.ks = 0.4;
    d.alpha = 20.0;
    d.model = model;
    d.nlights = 2;
    light_def *P = &d.lights[0], *S = &d.lights[1];
    P->kind = CJ_LIGHT_POINT;
    P->I[0] = 0.7, P->I[1] = 0.6, P->I[2] = 0.5;
    P->pos[0] = 3, P->pos[1] = 4, P->pos[2] = 2;
    S->kind = CJ_LIGHT_SPOT;
    S->I[0] = 0.3, S->I[1] = 0.5, S->I[2] = 0.9;
    S->pos[0] = -3, S->pos[1] = -1, S->pos[2] = 3;
    S->dir[0] = 3, S->dir[1] = 1, S->dir[2] = -3;
    S->cut = 0.35;
    S->expo = 4.0;
    return d;
}

static void test_lamps_blinn(void **state) {
    (void)state;
    scene_def d = lamps_scene(CJ_SPEC_BLINN);
    check_scene(&d, "point + spot, perspective, blinn");
}

static void test_lamps_phong(void **state) {
    (void)state;
    scene_def d = lamps_scene(CJ_SPEC_PHONG);
    check_scene(&d, "point + spot, perspective, phong");
}

/* The material key reads, round-trips, and an unknown name is refused with the key named. */
static void test_json_specular_model(void **state) {
    (void)state;
    const char *doc = "{\"materials\": [{\"name\": \"a\", \"specular_model\": \"phong\"},"
                      " {\"name\": \"b\"}], \"objects\": []}";
    cj_scene *s = NULL;
    cj_status st = cj_scene_parse_json(doc, "doc", NULL, NULL, &s);
    if (st) printf("%s\n", cj_last_error());
    assert_int_equal(st, CJ_OK);
    assert_int_equal(cj_scene_material(s, 0)->specular_model, CJ_SPEC_PHONG);
    assert_int_equal(cj_scene_material(s, 1)->specular_model, CJ_SPEC_BLINN);
    char path[64];
    snprintf(path, sizeof path, "test_light_agree_%d.json", (int)getpid());
    assert_int_equal(cj_scene_save_json(s, path), CJ_OK);
    FILE *f = fopen(path, "rb");
    assert_non_null(f);
    char *text = calloc(1, 1 << 16);
    assert_non_null(text);
    size_t got = fread(text, 1, (1 << 16) - 1, f);
    fclose(f);
    remove(path);
    assert_true(got > 0);
    assert_non_null(strstr(text, "\"specular_model\":\t\"phong\""));
    assert_non_null(strstr(text, "\"specular_model\":\t\"blinn\""));
    free(text);
    cj_scene_destroy(s);
    const char *bad = "{\"materials\": [{\"name\": \"a\", \"specular_model\": \"cook\"}], "
                      "\"objects\": []}";
    assert_int_not_equal(cj_scene_parse_json(bad, "bad", NULL, NULL, &s), CJ_OK);
    printf("json: specular_model phong/blinn read and written; \"cook\" refused: %s\n",
           cj_last_error());
    assert_non_null(strstr(cj_last_error(), "specular_model"));
}

/* The lamps in radiometric units: intensities in W/sr at a few units, falling off as 1/r². */
static void test_lamps_radiometric(void **state) {
    (void)state;
    for (int model = 0; model < 2; ++model) {
        scene_def d = lamps_scene(model ? CJ_SPEC_PHONG : CJ_SPEC_BLINN);
        d.radiometric = 1;
        for (int k = 0; k < 3; ++k) {
            d.lights[0].I[k] *= 30.0;
            d.lights[1].I[k] *= 20.0;
        }
        check_scene(&d,
                    model ? "radiometric point + spot, phong" : "radiometric point + spot, blinn");
    }
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_terminator_blinn),  cmocka_unit_test(test_terminator_phong),
        cmocka_unit_test(test_lamps_blinn),       cmocka_unit_test(test_lamps_phong),
        cmocka_unit_test(test_lamps_radiometric), cmocka_unit_test(test_json_specular_model),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
