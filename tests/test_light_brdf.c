/* The BRDFs of raster/src/brdf.h (issue 21, docs/light.md):
 *  - Fresnel against its closed forms: ((η−1)/(η+1))² at normal incidence (η = 1.5, 1.33, from
 *    either side), Rp = 0 and Rs = ((η²−1)/(η²+1))² at Brewster's angle atan η, total internal
 *    reflection just past the critical angle asin(1/η) and not just before it;
 *  - energy conservation: for Lambert, Phong and Blinn at exponents 0 ... 5000 and views from
 *    0° to 89.5°, the directional albedo estimated by importance sampling (stratified, the
 *    weights f cos/pdf) is <= 1 within 4 standard errors; Lambert's is 1 and Phong's at normal
 *    incidence is 1 (closed forms);
 *  - the sampler draws what its pdf says: the albedo by importance sampling matches an
 *    independent midpoint quadrature of f cos θ over the hemisphere (exponents <= 30, within
 *    4 standard errors + the quadrature's error), ∫ pdf dω by quadrature is 1 for Lambert and
 *    <= 1 for the lobes, and every sample's weight equals f cos θi / pdf from eval and pdf;
 *  - the dielectric picks reflection with frequency F (binomial, 4σ), refracts by Snell's law
 *    (sin θt = sin θi / η, unit length, other side), and reflects everything beyond the
 *    critical angle. Seeded (tests/support/rng.h); the seed is printed. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "brdf.h"
#include "rng.h"

#include <math.h>
#include <stdio.h>

static const double PI = 3.14159265358979323846;

static void test_fresnel(void **state) {
    (void)state;
    const double etas[2] = {1.5, 1.33};
    for (int i = 0; i < 2; ++i) {
        double eta = etas[i], r0 = (eta - 1) / (eta + 1);
        r0 *= r0;
        double out = cj_fresnel_dielectric(1.0, eta, NULL, NULL);
        double in = cj_fresnel_dielectric(1.0, 1.0 / eta, NULL, NULL);
        double tb = atan(eta), rs, rp;
        cj_fresnel_dielectric(cos(tb), eta, &rs, &rp);
        double rs_ref = (eta * eta - 1) / (eta * eta + 1);
        rs_ref *= rs_ref;
        double crit = asin(1.0 / eta);
        double past = cj_fresnel_dielectric(cos(crit + 1e-6), 1.0 / eta, NULL, NULL);
        double before = cj_fresnel_dielectric(cos(crit - 1e-3), 1.0 / eta, NULL, NULL);
        printf("eta %.2f: F(0) %.17g outside, %.17g inside (closed form %.17g); Brewster %.4f "
               "rad: Rp %.3g, Rs %.17g (closed form %.17g); critical %.4f rad: F %.3f before, "
               "%.3f past\n",
               eta, out, in, r0, tb, rp, rs, rs_ref, crit, before, past);
        assert_true(fabs(out - r0) <= 1e-15);
        assert_true(fabs(in - r0) <= 1e-15);
        assert_true(rp <= 1e-30);
        assert_true(fabs(rs - rs_ref) <= 1e-15);
        assert_true(past == 1.0);
        assert_true(before < 1.0);
    }
}

/* Directional albedo by importance sampling: mean and standard error of the weights. */
static void albedo_is(const cj_brdf *b, const double wo[3], int strata, cj_rng *rng, double *mean,
                      double *se, double *worst_consistency) {
    double s = 0, s2 = 0;
    int n = strata * strata;
    for (int i = 0; i < strata; ++i)
        for (int j = 0; j < strata; ++j) {
            double u1 = (i + cj_rng_unit(rng)) / strata, u2 = (j + cj_rng_unit(rng)) / strata;
            cj_brdf_sample smp;
            double w = 0.0;
            if (cj_brdf_sample_dir(b, wo, u1, u2, 0.5, &smp)) {
                w = smp.weight;
                double f = cj_brdf_eval(b, wo, smp.wi), pdf = cj_brdf_pdf(b, wo, smp.wi);
                double e = fabs(w - f * smp.wi[2] / pdf) / (w > 1e-300 ? w : 1.0);
                if (pdf > 0 && e > *worst_consistency) *worst_consistency = e;
            }
            s += w;
            s2 += w * w;
        }
    *mean = s / n;
    double var = s2 / n - *mean * *mean;
    *se = sqrt(fmax(var, 0.0) / n); /* stratification only lowers the true error */
}

/* Midpoint quadrature over (θ, φ) of g(wi) dω, g = f cos θ (what = 0) or the pdf (what = 1). */
static double quad(const cj_brdf *b, const double wo[3], int nt, int what) {
    double sum = 0.0, dt = 0.5 * PI / nt, dp = 2 * PI / (2 * nt);
    for (int i = 0; i < nt; ++i) {
        double t = (i + 0.5) * dt, st = sin(t), ct = cos(t);
        for (int j = 0; j < 2 * nt; ++j) {
            double p = (j + 0.5) * dp, wi[3] = {st * cos(p), st * sin(p), ct};
            double g = what ? cj_brdf_pdf(b, wo, wi) : cj_brdf_eval(b, wo, wi) * ct;
            sum += g * st * dt * dp;
        }
    }
    return sum;
}

static void test_energy(void **state) {
    (void)state;
    const uint64_t seed = cj_test_seed("test_energy", 20261126);
    cj_rng rng;
    cj_rng_init(&rng, seed);
    const double alphas[] = {0, 0.5, 1, 3, 10, 30, 300, 5000};
    const double views[] = {0, 15, 30, 45, 60, 75, 85, 89.5};
    const cj_brdf_kind kinds[] = {CJ_BRDF_LAMBERT, CJ_BRDF_PHONG, CJ_BRDF_BLINN};
    const char *names[] = {"lambert", "phong", "blinn"};
    double worst_consistency = 0;
    for (int k = 0; k < 3; ++k) {
        double max_albedo = 0, worst_quad = 0, pdf_min = 2, pdf_max = 0;
        for (size_t a = 0; a < sizeof alphas / sizeof *alphas; ++a) {
            if (k == 0 && a > 0) break;
            cj_brdf b = {kinds[k], alphas[a], 1.0};
            for (size_t v = 0; v < sizeof views / sizeof *views; ++v) {
                double th = views[v] * PI / 180, wo[3] = {sin(th), 0, cos(th)};
                double m, se;
                albedo_is(&b, wo, 160, &rng, &m, &se, &worst_consistency);
                if (m > max_albedo) max_albedo = m;
                assert_true(m <= 1.0 + 4 * se + 1e-12);
                if (k == 0) assert_true(fabs(m - 1.0) < 1e-12);
                if (k == 1 && v == 0) assert_true(fabs(m - 1.0) <= 4 * se + 1e-9);
                if (alphas[a] <= 30) {
                    double q = quad(&b, wo, 400, 0), P = quad(&b, wo, 400, 1);
                    double e = fabs(q - m);
                    if (e > 4 * se + 2e-3)
                        printf("%s alpha %g view %g: importance %.6f +- %.1e, quadrature %.6f\n",
                               names[k], alphas[a], views[v], m, se, q);
                    /* the quadrature's own error: it resolves lobes up to α 30 to ~1e-3 */
                    assert_true(e <= 4 * se + 2e-3);
                    if (e > worst_quad) worst_quad = e;
                    if (P < pdf_min) pdf_min = P;
                    if (P > pdf_max) pdf_max = P;
                    assert_true(P <= 1.0 + 2e-3);
                    if (k == 0) assert_true(fabs(P - 1.0) <= 2e-3);
                }
            }
        }
        printf("%s: largest directional albedo %.5f over exponents 0..5000 and views 0..89.5 "
               "deg; |importance - quadrature| <= %.2e; quadrature of the pdf in [%.4f, %.4f]\n",
               names[k], max_albedo, worst_quad, pdf_min, pdf_max);
    }
    printf("weights against eval cos / pdf: worst relative difference %.2e\n", worst_consistency);
    assert_true(worst_consistency <= 1e-10);
}

static void test_dielectric(void **state) {
    (void)state;
    const uint64_t seed = cj_test_seed("test_dielectric", 77);
    cj_rng rng;
    cj_rng_init(&rng, seed);
    cj_brdf b = {CJ_BRDF_DIELECTRIC, 0, 1.5};
    const double views[] = {0, 30, 60, 80};
    for (int side = 0; side < 2; ++side)
        for (size_t v = 0; v < 4; ++v) {
            double th = views[v] * PI / 180, z = side ? -cos(th) : cos(th);
            double wo[3] = {sin(th), 0, z}, eta = side ? 1 / 1.5 : 1.5;
            double F = cj_fresnel_dielectric(cos(th), eta, NULL, NULL);
            int n = 100000, refl = 0;
            for (int i = 0; i < n; ++i) {
                cj_brdf_sample s;
                assert_true(cj_brdf_sample_dir(&b, wo, 0, 0, cj_rng_unit(&rng), &s));
                assert_true(s.delta && s.weight == 1.0);
                double len = sqrt(s.wi[0] * s.wi[0] + s.wi[1] * s.wi[1] + s.wi[2] * s.wi[2]);
                assert_true(fabs(len - 1.0) < 1e-12);
                if (s.wi[2] * z > 0) {
                    ++refl;
                    assert_true(fabs(s.wi[0] + wo[0]) < 1e-15 && fabs(s.wi[2] - z) < 1e-15);
                } else { /* Snell: sin θt = sin θi / η */
                    assert_true(fabs(fabs(s.wi[0]) - sin(th) / eta) < 1e-12);
                }
            }
            double freq = (double)refl / n, sd = sqrt(F * (1 - F) / n);
            printf("%s, %g deg: reflected %.4f of the draws, F %.4f\n", side ? "inside" : "outside",
                   views[v], freq, F);
            assert_true(fabs(freq - F) <= 4 * sd + 1e-12);
            if (side && th > asin(1 / 1.5)) assert_int_equal(refl, n);
        }
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_fresnel),
        cmocka_unit_test(test_energy),
        cmocka_unit_test(test_dielectric),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
