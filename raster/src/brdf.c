/* BRDFs with importance sampling and pdfs (brdf.h). The glossy lobes are evaluated by the
 * reflection model both renderers use (reflect_model.h), written there once. */
#include "brdf.h"

#include "reflect_model.h"

#include <math.h>

static const double PI = 3.14159265358979323846;

static double dot3(const double a[3], const double b[3]) {
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* A unit vector at angle acos(ct) from the unit axis a, azimuth phi about it. */
static void around(const double a[3], double ct, double phi, double out[3]) {
    /* an orthonormal frame about a (Duff et al.'s branchless construction) */
    const double sign = a[2] >= 0.0 ? 1.0 : -1.0;
    const double p = -1.0 / (sign + a[2]), q = a[0] * a[1] * p;
    const double t[3] = {1.0 + sign * a[0] * a[0] * p, sign * q, -sign * a[0]};
    const double s[3] = {q, sign + a[1] * a[1] * p, -a[1]};
    const double st = sqrt(fmax(0.0, 1.0 - ct * ct)), c = cos(phi) * st, d = sin(phi) * st;
    for (int k = 0; k < 3; ++k) out[k] = ct * a[k] + c * t[k] + d * s[k];
}

static double glossy_f(const cj_brdf *b, const double wo[3], const double wi[3]) {
    if (!(wi[2] > 0.0) || !(wo[2] > 0.0)) return 0.0;
    static const double n[3] = {0.0, 0.0, 1.0};
    double d, s;
    cj_reflect_terms_d(n, wi, wo, b->alpha,
                       b->kind == CJ_BRDF_PHONG ? CJ_SPEC_PHONG : CJ_SPEC_BLINN, 1, &d, &s);
    return s / wi[2]; /* the model returns f_s cos θi */
}

double cj_brdf_eval(const cj_brdf *b, const double wo[3], const double wi[3]) {
    switch (b->kind) {
    case CJ_BRDF_LAMBERT:
        return wi[2] > 0.0 && wo[2] > 0.0 ? 1.0 / PI : 0.0;
    case CJ_BRDF_PHONG:
    case CJ_BRDF_BLINN:
        return glossy_f(b, wo, wi);
    default:
        return 0.0;
    }
}

double cj_brdf_pdf(const cj_brdf *b, const double wo[3], const double wi[3]) {
    if (!(wi[2] > 0.0) || !(wo[2] > 0.0)) return 0.0;
    switch (b->kind) {
    case CJ_BRDF_LAMBERT:
        return wi[2] / PI;
    case CJ_BRDF_PHONG: {
        const double r[3] = {-wo[0], -wo[1], wo[2]};
        const double c = dot3(r, wi);
        if (!(c > 0.0)) return 0.0;
        return (b->alpha + 1.0) / (2.0 * PI) * pow(c, b->alpha);
    }
    case CJ_BRDF_BLINN: {
        double h[3] = {wo[0] + wi[0], wo[1] + wi[1], wo[2] + wi[2]};
        const double l = sqrt(dot3(h, h));
        if (!(l > 0.0)) return 0.0;
        for (int k = 0; k < 3; ++k) h[k] /= l;
        const double oh = dot3(wo, h);
        if (!(oh > 0.0)) return 0.0;
        return (b->alpha + 1.0) / (2.0 * PI) * pow(h[2], b->alpha) / (4.0 * oh);
    }
    default:
        return 0.0;
    }
}

double cj_fresnel_dielectric(double cos_i, double eta, double *rs, double *rp) {
    const double s2 = (1.0 - cos_i * cos_i) / (eta * eta); /* sin² θt by Snell */
    if (s2 >= 1.0) {
        if (rs) *rs = 1.0;
        if (rp) *rp = 1.0;
        return 1.0;
    }
    const double ct = sqrt(1.0 - s2);
    const double a = (cos_i - eta * ct) / (cos_i + eta * ct);
    const double p = (eta * cos_i - ct) / (eta * cos_i + ct);
    if (rs) *rs = a * a;
    if (rp) *rp = p * p;
    return 0.5 * (a * a + p * p);
}

int cj_brdf_sample_dir(const cj_brdf *b, const double wo[3], double u1, double u2, double u3,
                       cj_brdf_sample *out) {
    out->pdf = 0.0;
    out->delta = 0;
    out->weight = 0.0;
    switch (b->kind) {
    case CJ_BRDF_LAMBERT: {
        if (!(wo[2] > 0.0)) return 0;
        /* Malley: uniform on the disk, lifted (pdf cos θ / π) */
        const double r = sqrt(u1), ph = 2.0 * PI * u2;
        out->wi[0] = r * cos(ph);
        out->wi[1] = r * sin(ph);
        out->wi[2] = sqrt(fmax(0.0, 1.0 - u1));
        out->pdf = out->wi[2] / PI;
        out->weight = 1.0;
        return out->wi[2] > 0.0;
    }
    case CJ_BRDF_PHONG: {
        if (!(wo[2] > 0.0)) return 0;
        const double r[3] = {-wo[0], -wo[1], wo[2]};
        around(r, pow(u1, 1.0 / (b->alpha + 1.0)), 2.0 * PI * u2, out->wi);
        if (!(out->wi[2] > 0.0)) return 0;
        out->pdf = cj_brdf_pdf(b, wo, out->wi);
        out->weight = (b->alpha + 2.0) / (b->alpha + 1.0) * out->wi[2];
        return out->pdf > 0.0;
    }
    case CJ_BRDF_BLINN: {
        if (!(wo[2] > 0.0)) return 0;
        static const double n[3] = {0.0, 0.0, 1.0};
        double h[3];
        around(n, pow(u1, 1.0 / (b->alpha + 1.0)), 2.0 * PI * u2, h);
        const double oh = dot3(wo, h);
        if (!(oh > 0.0)) return 0;
        for (int k = 0; k < 3; ++k) out->wi[k] = 2.0 * oh * h[k] - wo[k];
        if (!(out->wi[2] > 0.0)) return 0;
        out->pdf = cj_brdf_pdf(b, wo, out->wi);
        out->weight = out->wi[2] / fmax(out->wi[2], wo[2]);
        return out->pdf > 0.0;
    }
    case CJ_BRDF_MIRROR:
        if (!(wo[2] > 0.0)) return 0;
        out->wi[0] = -wo[0];
        out->wi[1] = -wo[1];
        out->wi[2] = wo[2];
        out->delta = 1;
        out->weight = 1.0;
        return 1;
    case CJ_BRDF_DIELECTRIC: {
        if (wo[2] == 0.0) return 0;
        const int outside = wo[2] > 0.0;
        const double eta = outside ? b->ior : 1.0 / b->ior, ci = fabs(wo[2]);
        const double F = cj_fresnel_dielectric(ci, eta, NULL, NULL);
        out->delta = 1;
        out->weight = 1.0;
        if (u3 < F) {
            out->wi[0] = -wo[0];
            out->wi[1] = -wo[1];
            out->wi[2] = wo[2];
            return 1;
        }
        /* refraction: wi = −wo/η + (cos_i/η − cos_t) n on the other side */
        const double ct = sqrt(fmax(0.0, 1.0 - (1.0 - ci * ci) / (eta * eta)));
        const double sgn = outside ? 1.0 : -1.0;
        out->wi[0] = -wo[0] / eta;
        out->wi[1] = -wo[1] / eta;
        out->wi[2] = -sgn * ct;
        return 1;
    }
    }
    return 0;
}
