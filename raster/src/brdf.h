/* BRDFs as one small abstraction (issue 21, docs/light.md): each kind evaluates f, samples a
 * direction by importance and gives the pdf of what it samples. The glossy lobes are the ones
 * of the radiometric reflection model (reflect_model.h), so direct light computed from a
 * light's side and from the BRDF's side estimate the same integral.
 *
 * LOCAL FRAME: the shading normal is +z; wo points to the viewer (where the light leaves to),
 * wi to where the light comes from; both unit vectors; cos θ = z. Every BRDF here has unit
 * scale: the caller multiplies by its colour (ρ, c_p r_s, ...).
 *
 *   CJ_BRDF_LAMBERT     f = 1/π;  sampled ∝ cos θi (pdf cos θi / π), weight 1
 *   CJ_BRDF_PHONG       f = (α+2)/(2π) max(0, r·wi)^α, r = (−wo.x, −wo.y, wo.z) the mirror
 *                       direction; sampled ∝ (r·wi)^α about r (pdf (α+1)/(2π) (r·wi)^α),
 *                       weight (α+2)/(α+1) cos θi (0 below the horizon)
 *   CJ_BRDF_BLINN       f = (α+1)/(8π) (n·h)^α / ((wi·h) max(cos θi, cos θo)); h drawn with
 *                       density (α+1)/(2π) (n·h)^α, wi = wo reflected about h (pdf
 *                       (α+1)/(2π) (n·h)^α / (4 wo·h)), weight cos θi / max(cos θi, cos θo)
 *   CJ_BRDF_MIRROR      a delta: wi = r, weight 1
 *   CJ_BRDF_DIELECTRIC  a delta pair: reflection with the Fresnel reflectance F, refraction
 *                       (Snell) with 1 − F, chosen with those probabilities, so the weight is
 *                       1; total internal reflection sends everything to the reflection. ior
 *                       is the index inside (the side −z) over the index outside (+z); wo may
 *                       be on either side. Radiance is not scaled by η² across the interface
 *                       (the factors cancel on a path that enters and leaves the same medium).
 *
 * Weights are f cos θi / pdf: an estimator multiplies its throughput by the weight. The delta
 * kinds have eval = pdf = 0 (a light sample never hits a delta). Nothing allocates; every
 * function is pure. */
#ifndef CASTELJAU_BRDF_H
#define CASTELJAU_BRDF_H

typedef enum cj_brdf_kind {
    CJ_BRDF_LAMBERT = 0,
    CJ_BRDF_PHONG,
    CJ_BRDF_BLINN,
    CJ_BRDF_MIRROR,
    CJ_BRDF_DIELECTRIC
} cj_brdf_kind;

typedef struct cj_brdf {
    cj_brdf_kind kind;
    double alpha; /* PHONG, BLINN: exponent >= 0 */
    double ior;   /* DIELECTRIC: relative index (inside / outside) > 0 */
} cj_brdf;

typedef struct cj_brdf_sample {
    double wi[3];
    double
        weight; /* f cos θi / pdf (for a delta: the chosen branch's share over its probability) */
    double pdf; /* solid-angle pdf; 0 for a delta */
    int delta;  /* 1: a specular (delta) direction */
} cj_brdf_sample;

/* f(wo, wi); 0 for the delta kinds and where the lobe is empty. */
double cj_brdf_eval(const cj_brdf *b, const double wo[3], const double wi[3]);

/* The pdf with which cj_brdf_sample draws wi given wo (solid angle); 0 for the delta kinds. */
double cj_brdf_pdf(const cj_brdf *b, const double wo[3], const double wi[3]);

/* Draws wi from (u1, u2, u3) in [0, 1)³ (u3: the dielectric's branch). Returns 0 when the draw
 * gives no usable direction (below the horizon for the glossy lobes, wo on the horizon). */
int cj_brdf_sample_dir(const cj_brdf *b, const double wo[3], double u1, double u2, double u3,
                       cj_brdf_sample *out);

/* Fresnel reflectance of unpolarised light arriving with cos_i = cos θi > 0 at an interface
 * from index 1 into relative index eta: (Rs + Rp)/2 with Rs = ((cos_i − η cos_t)/(cos_i +
 * η cos_t))², Rp = ((η cos_i − cos_t)/(η cos_i + cos_t))², cos_t from Snell; 1 on total
 * internal reflection. rs, rp (may be NULL) receive the two polarisations. */
double cj_fresnel_dielectric(double cos_i, double eta, double *rs, double *rp);

#endif
