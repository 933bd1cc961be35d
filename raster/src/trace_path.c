/* The path tracer (cj_trace_options.integrator = CJ_INTEGRATOR_PATH; trace.h, docs/light.md):
 * the rendering equation by random walks from the camera, with next-event estimation to every
 * light, multiple importance sampling (power heuristic) between light and BRDF sampling for
 * area lights, and Russian roulette. Lights are read radiometrically (scene.h) whatever the
 * scene's light_model says: a path tracer has no other meaning for them.
 *
 * THE MATERIAL AS A BSDF (brdf.h), a mixture of three parts with weights that sum to <= 1:
 *   r_t                 a Fresnel dielectric of index ior (transmission)
 *   r_m                 a perfect mirror (mirror), tinted by c_p
 *   1 − r_t − r_m       r_d c_r / π + r_s c_p f_s (the radiometric local model) when > 0
 * One part is chosen per bounce with probability equal to its weight (the local part with the
 * rest), so the part's weight cancels. Emission (cj_material.emission, a radiance) is added
 * wherever a path meets it; emissive materials are not sampled as lights. Ambient light is
 * environment radiance: a path that leaves the scene gathers background + Σ I_a.
 *
 * RAYS: camera rays count as primary_rays, diffuse and glossy bounces as indirect_rays,
 * mirror and Fresnel reflections as reflection_rays, refractions as refraction_rays,
 * next-event rays as shadow_rays. Random numbers come from the per-sample counter-based generator,
 * so the image is bit-identical for any thread count. */
#include "trace_shade.h"

#include "brdf.h"

#include <math.h>

typedef struct pt_frame {
    cj_vec3 a, b, n;
} pt_frame;

static void to_local(const pt_frame *f, cj_vec3 v, double out[3]) {
    out[0] = cj_v3_dot(v, f->a);
    out[1] = cj_v3_dot(v, f->b);
    out[2] = cj_v3_dot(v, f->n);
}

static cj_vec3 to_world(const pt_frame *f, const double v[3]) {
    return cj_v3_add(cj_v3_add(cj_v3_scale(f->a, v[0]), cj_v3_scale(f->b, v[1])),
                     cj_v3_scale(f->n, v[2]));
}

/* The local part of a material: diffuse and glossy lobes, each chosen by its share. */
typedef struct pt_local {
    cj_rgb kd, ks; /* r_d c_r, r_s c_p */
    cj_brdf lobe;
    double p_diffuse; /* probability of sampling the diffuse lobe */
} pt_local;

static double lum(cj_rgb c) {
    return (c.r + c.g + c.b) / 3.0;
}

static cj_rgb local_f(const pt_local *l, const double wo[3], const double wi[3], double *pdf) {
    static const cj_brdf lambert = {CJ_BRDF_LAMBERT, 0.0, 1.0};
    double fd = cj_brdf_eval(&lambert, wo, wi), fs = cj_brdf_eval(&l->lobe, wo, wi);
    *pdf = l->p_diffuse * cj_brdf_pdf(&lambert, wo, wi) +
           (1.0 - l->p_diffuse) * cj_brdf_pdf(&l->lobe, wo, wi);
    return cj_rgb_make(l->kd.r * fd + l->ks.r * fs, l->kd.g * fd + l->ks.g * fs,
                       l->kd.b * fd + l->ks.b * fs);
}

static double power_heuristic(double a, double b) {
    return a * a / (a * a + b * b);
}

/* The first emitter (area, disc or sphere light) the ray meets before t_max: its index, distance
 * and the solid-angle pdf with which next-event estimation draws that direction; −1 when none. */
static int hit_emitter(const tr_lights *L, const cj_ray *ray, double t_max, double *t_out,
                       double *light_pdf) {
    int best = -1;
    for (int i = 0; i < L->count; ++i) {
        const cj_light *lt = L->light[i];
        double t, pdf;
        if (!tr_is_emitter(lt) || !tr_emitter_hit(lt, ray, t_max, &t, &pdf)) continue;
        t_max = t;
        best = i;
        *t_out = t;
        *light_pdf = pdf;
    }
    return best;
}

/* Two numbers in [0, 1)² for one of the first hit's samples: at the camera ray's first hit
 * (first) of a pixel with several stratified samples, the stratum of pixel sample s under a
 * keyed random permutation (one key per use, `salt`), offset by the pixel's random shift, as
 * the Whitted tracer stratifies its light samples (trace_shade.c: a fixed pairing with the
 * pixel strata would keep a variance more samples do not lower); elsewhere uniform. */
static void strat2(tr_shade *sh, int first, uint64_t salt, double *u, double *v) {
    const double a = tr_rand(&sh->rng), b = tr_rand(&sh->rng);
    if (!first || sh->spp < 2 || sh->random) {
        *u = a;
        *v = b;
        return;
    }
    const uint32_t ns = (uint32_t)sh->spp, k = (uint32_t)sh->strata;
    const uint32_t si = (cj_trace_permute(sh->sample, ns, sh->perm_key ^ salt) + sh->perm) % ns;
    if (k * k == ns) {
        *u = ((si % k) + a) / k;
        *v = ((si / k) + b) / k;
    } else {
        *u = (si + a) / ns;
        *v = b;
    }
}

/* Next-event estimation at a non-delta hit: Σ over the lights of f cos θ E, area lights by
 * one stratum-free area sample each, MIS-weighted against the BRDF's pdf. */
static cj_rgb next_event(tr_shade *sh, const cj_hit *h, const pt_frame *fr, const double wo[3],
                         const pt_local *loc, int receives, int first) {
    const tr_lights *L = sh->lights;
    cj_rgb sum = cj_rgb_make(0, 0, 0);
    for (int i = 0; i < L->count; ++i) {
        const cj_light *lt = L->light[i];
        cj_vec3 dir;
        double E = 1.0, tmax = INFINITY, light_pdf = 0.0;
        cj_vec3 target = lt->position;
        if (lt->kind == CJ_LIGHT_DIRECTIONAL) {
            dir = cj_v3_normalize(cj_v3_scale(lt->direction, -1.0));
        } else if (tr_is_emitter(lt)) { /* one sample (trace_lights.c), L_e E per unit */
            double u1, u2;
            strat2(sh, first, 0x6a09e667f3bcc909ull * (uint64_t)(i + 1), &u1, &u2);
            if (!tr_emitter_sample(lt, h->p, u1, u2, 0, &target, &E, &light_pdf)) continue;
            dir = cj_v3_normalize(cj_v3_sub(target, h->p));
            tmax = 1.0;
        } else {
            cj_vec3 to = cj_v3_sub(target, h->p);
            double r2 = cj_v3_dot(to, to);
            if (!(r2 > 0.0)) continue;
            dir = cj_v3_scale(to, 1.0 / sqrt(r2));
            E = 1.0 / r2;
            if (lt->kind == CJ_LIGHT_SPOT) {
                double ct = -cj_v3_dot(cj_v3_normalize(lt->direction), dir);
                E = ct >= cos(lt->spot_angle) ? E * pow(ct, lt->spot_exponent) : 0.0;
            }
            tmax = 1.0;
        }
        if (E == 0.0) continue;
        double wi[3];
        to_local(fr, dir, wi);
        if (!(wi[2] > 0.0)) continue;
        double bpdf;
        cj_rgb f = local_f(loc, wo, wi, &bpdf);
        if (f.r == 0.0 && f.g == 0.0 && f.b == 0.0) continue;
        if (lt->casts_shadows && receives) {
            cj_ray sr;
            sr.org = cj_ray_offset_origin(h, dir);
            sr.dir = tmax == 1.0 ? cj_v3_sub(target, sr.org) : dir;
            sr.tmin = 0.0;
            sr.tmax = tmax;
            if (tr_occluded(sh, &sr)) continue;
        }
        double w = light_pdf > 0.0 ? power_heuristic(light_pdf, bpdf) : 1.0;
        double s = lt->intensity * E * wi[2] * w;
        sum.r += f.r * lt->color.r * s;
        sum.g += f.g * lt->color.g * s;
        sum.b += f.b * lt->color.b * s;
    }
    if (sh->emit_nee) { /* one point of the emissive surfaces, picked by area (trace_emit.c) */
        const double u0 = tr_rand(&sh->rng);
        double u1, u2;
        strat2(sh, first, 0xbb67ae8584caa73bull, &u1, &u2);
        cj_vec3 target;
        cj_rgb le;
        double wgt, light_pdf;
        if (!tr_emit_sample(sh->s, h->p, u0, u1, u2, &target, &le, &wgt, &light_pdf)) return sum;
        const cj_vec3 dir = cj_v3_normalize(cj_v3_sub(target, h->p));
        double wi[3];
        to_local(fr, dir, wi);
        if (!(wi[2] > 0.0)) return sum;
        double bpdf;
        const cj_rgb f = local_f(loc, wo, wi, &bpdf);
        if (f.r == 0.0 && f.g == 0.0 && f.b == 0.0) return sum;
        if (receives) {
            /* stop just short of the target: it lies on the emitter's own surface */
            cj_ray sr;
            sr.org = cj_ray_offset_origin(h, dir);
            sr.dir = cj_v3_sub(target, sr.org);
            sr.tmin = 0.0;
            sr.tmax = 1.0 - 1e-6;
            if (tr_occluded(sh, &sr)) return sum;
        }
        const double s = wgt * wi[2] * power_heuristic(light_pdf, bpdf);
        sum.r += f.r * le.r * s;
        sum.g += f.g * le.g * s;
        sum.b += f.b * le.b * s;
    }
    return sum;
}

cj_rgb tr_path(tr_shade *sh, const cj_ray *camera_ray, int *hit_any) {
    const tr_lights *L = sh->lights;
    cj_rgb out = cj_rgb_make(0, 0, 0), T = cj_rgb_make(1, 1, 1);
    cj_ray ray = *camera_ray;
    double prev_pdf = 0.0;
    int prev_delta = 1, kind = TR_PRIMARY;
    for (int depth = 0;; ++depth) {
        cj_hit h;
        int got = tr_cast(sh, kind, &ray, &h);
        double tl = 0.0, lpdf = 0.0;
        int li = hit_emitter(L, &ray, got ? h.t : INFINITY, &tl, &lpdf);
        if (li >= 0) { /* an emitter seen directly or reached by a BRDF sample */
            const cj_light *lt = L->light[li];
            double w = 1.0;
            if (!prev_delta) w = power_heuristic(prev_pdf, lpdf);
            double s = lt->intensity * w;
            out.r += T.r * lt->color.r * s;
            out.g += T.g * lt->color.g * s;
            out.b += T.b * lt->color.b * s;
            if (depth == 0 && hit_any) *hit_any = 1;
            break;
        }
        if (!got) {
            out.r += T.r * (sh->background.r + L->ia.r);
            out.g += T.g * (sh->background.g + L->ia.g);
            out.b += T.b * (sh->background.b + L->ia.b);
            break;
        }
        if (depth == 0 && hit_any) *hit_any = 1;
        const tr_object *o = &sh->s->objs[h.obj];
        const cj_material *m = cj_scene_material(sh->s->scene, o->material);
        cj_vec3 d = cj_v3_normalize(ray.dir);
        const int front = cj_v3_dot(h.ng, d) < 0.0;
        cj_vec3 nf = front ? h.ng : cj_v3_scale(h.ng, -1.0), n = h.n;
        if (cj_v3_dot(n, nf) < 0.0) n = cj_v3_scale(n, -1.0);
        double we = 1.0; /* emission reached by a BRDF sample, MIS against sampling it as light */
        if (sh->emit_nee && !prev_delta && sh->s->emit_obj && sh->s->emit_obj[h.obj]) {
            const double dist = h.t * cj_v3_norm(ray.dir), cl = fabs(cj_v3_dot(h.ng, d));
            if (cl > 0.0) we = power_heuristic(prev_pdf, dist * dist / (sh->s->emit_area * cl));
        }
        out.r += T.r * m->emission.r * we;
        out.g += T.g * m->emission.g * we;
        out.b += T.b * m->emission.b * we;
        if (depth >= sh->max_depth) break;
        cj_rgb cr = m->color;
        if (m->texture >= 0 && m->texture < sh->s->ntex) {
            float tc[3];
            cj_tex_sample(&sh->s->tex[m->texture], h.u, h.v, 0.0, 0.0, 0.0, 0.0, tc);
            cr = cj_rgb_make(cr.r * tc[0], cr.g * tc[1], cr.b * tc[2]);
        }
        /* choose the part of the mixture */
        const double u = tr_rand(&sh->rng);
        const double rt = m->transmission, rm = m->mirror;
        pt_frame fr;
        cj_brdf_sample smp;
        cj_vec3 dir;
        if (u < rt) { /* dielectric: the geometric frame, wo on either side */
            fr.n = h.ng;
            cj_frame_from_axis(fr.n, &fr.a, &fr.b);
            double wo[3];
            to_local(&fr, cj_v3_scale(d, -1.0), wo);
            cj_brdf b = {CJ_BRDF_DIELECTRIC, 0.0, m->ior};
            if (!cj_brdf_sample_dir(&b, wo, 0.0, 0.0, tr_rand(&sh->rng), &smp)) break;
            dir = to_world(&fr, smp.wi);
            prev_delta = 1;
            kind = smp.wi[2] * wo[2] > 0.0 ? TR_REFLECT : TR_REFRACT;
        } else {
            fr.n = n;
            cj_frame_from_axis(fr.n, &fr.a, &fr.b);
            double wo[3];
            to_local(&fr, cj_v3_scale(d, -1.0), wo);
            if (!(wo[2] > 0.0)) break;
            if (u < rt + rm) { /* mirror, tinted by c_p */
                cj_brdf b = {CJ_BRDF_MIRROR, 0.0, 1.0};
                if (!cj_brdf_sample_dir(&b, wo, 0.0, 0.0, 0.0, &smp)) break;
                T = cj_rgb_make(T.r * m->specular.r, T.g * m->specular.g, T.b * m->specular.b);
                prev_delta = 1;
                kind = TR_REFLECT;
            } else {
                pt_local loc;
                loc.kd = cj_rgb_make(m->kd * cr.r, m->kd * cr.g, m->kd * cr.b);
                loc.ks = cj_rgb_make(m->ks * m->specular.r, m->ks * m->specular.g,
                                     m->ks * m->specular.b);
                loc.lobe.kind = m->specular_model == CJ_SPEC_PHONG ? CJ_BRDF_PHONG : CJ_BRDF_BLINN;
                loc.lobe.alpha = m->alpha;
                loc.lobe.ior = 1.0;
                double wd = lum(loc.kd), ws = lum(loc.ks);
                if (!(wd + ws > 0.0)) break;
                loc.p_diffuse = wd / (wd + ws);
                /* the local part's share of the mixture is 1 − r_t − r_m, chosen with that
                 * probability: the share cancels */
                cj_rgb ne = next_event(sh, &h, &fr, wo, &loc, m->receives_shadows, depth == 0);
                out.r += T.r * ne.r;
                out.g += T.g * ne.g;
                out.b += T.b * ne.b;
                static const cj_brdf lambert = {CJ_BRDF_LAMBERT, 0.0, 1.0};
                double u1, u2; /* the BRDF sample, stratified at the first hit */
                strat2(sh, depth == 0, 0x3c6ef372fe94f82bull, &u1, &u2);
                if (!cj_brdf_sample_dir(tr_rand(&sh->rng) < loc.p_diffuse ? &lambert : &loc.lobe,
                                        wo, u1, u2, 0.0, &smp))
                    break;
                double pdf;
                cj_rgb f = local_f(&loc, wo, smp.wi, &pdf);
                if (!(pdf > 0.0)) break;
                double c = smp.wi[2] / pdf;
                T = cj_rgb_make(T.r * f.r * c, T.g * f.g * c, T.b * f.b * c);
                prev_pdf = pdf;
                prev_delta = 0;
                kind = TR_INDIRECT;
            }
            dir = to_world(&fr, smp.wi);
        }
        dir = cj_v3_normalize(dir);
        ray.org = cj_ray_offset_origin(&h, dir);
        ray.dir = dir;
        ray.tmin = 0.0;
        ray.tmax = INFINITY;
        /* Russian roulette from the fourth bounce: survive with q, weight 1/q (unbiased) */
        if (depth >= 3) {
            double q = fmax(T.r, fmax(T.g, T.b));
            if (q < 0.95) {
                if (tr_rand(&sh->rng) >= q) break;
                T = cj_rgb_make(T.r / q, T.g / q, T.b / q);
            }
        }
    }
    return out;
}
