/* Whitted shading with distribution extensions (trace.h): local Phong with shadow rays,
 * mirror reflection, refraction with the medium's ior tracked, straight-through transparency,
 * area-light and glossy samples from a counter-based generator. */
#define _POSIX_C_SOURCE 200809L
#include "trace_shade.h"

#include "brdf.h"
#include "clock_internal.h"
#include "reflect_model.h"

#include <math.h>
#include <string.h>

static const double PI = 3.14159265358979323846;

uint64_t cj_trace_mix(uint64_t z) {
    z += 0x9e3779b97f4a7c15ull;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

double tr_rand(tr_rng *r) {
    uint64_t v = cj_trace_mix(r->key ^ cj_trace_mix(r->n++));
    return (double)(v >> 11) * 0x1p-53;
}

uint32_t cj_trace_permute(uint32_t i, uint32_t n, uint64_t key) {
    /* Each step is a bijection of the b-bit integers (xor, add, odd multiply, xor-shift), so
     * their composition permutes [0, 2^b); walking the cycle until the value falls below n
     * restricts it to a permutation of [0, n). */
    uint32_t mask = n - 1;
    mask |= mask >> 1;
    mask |= mask >> 2;
    mask |= mask >> 4;
    mask |= mask >> 8;
    mask |= mask >> 16;
    uint32_t k0 = (uint32_t)key, k1 = (uint32_t)(key >> 32);
    do {
        i = (i ^ k0) & mask;
        i = (i * 0x9e3779b1u) & mask;
        i ^= i >> 3;
        i = (i + k1) & mask;
        i = (i * 0x85ebca6bu) & mask;
        i ^= i >> 5;
        i = (i ^ (k0 >> 7)) & mask;
        i = (i * 0xc2b2ae35u) & mask;
        i ^= i >> 2;
    } while (i >= n);
    return i;
}

int cj_trace_refract(cj_vec3 d, cj_vec3 n, double n1, double n2, cj_vec3 *t) {
    double eta = n1 / n2, ci = -cj_v3_dot(d, n);
    double k = 1.0 - eta * eta * (1.0 - ci * ci);
    if (k < 0.0) return 0;
    *t = cj_v3_normalize(cj_v3_add(cj_v3_scale(d, eta), cj_v3_scale(n, eta * ci - sqrt(k))));
    return 1;
}

int tr_cast(tr_shade *sh, int kind, const cj_ray *ray, cj_hit *hit) {
    double t0 = cj_clock_seconds();
    int got = tr_closest(sh->s, ray, sh->time, hit, sh->c);
    sh->c->seconds[kind] += cj_clock_seconds() - t0;
    sh->c->cast[kind]++;
    if (got) sh->c->hit[kind]++;
    return got;
}

int tr_occluded(tr_shade *sh, const cj_ray *ray) {
    double t0 = cj_clock_seconds();
    int got = tr_any(sh->s, ray, sh->time, sh->c);
    sh->c->seconds[TR_SHADOW] += cj_clock_seconds() - t0;
    sh->c->cast[TR_SHADOW]++;
    if (got) sh->c->hit[TR_SHADOW]++;
    return got;
}

cj_vec3 cj_trace_cosine_sample(cj_vec3 n, double u1, double u2) {
    /* Malley: uniform on the disk, lifted; the projected solid angle makes the pdf cos θ / π */
    double r = sqrt(u1), ph = 2.0 * PI * u2, z = sqrt(fmax(0.0, 1.0 - u1));
    cj_vec3 a, b;
    cj_frame_from_axis(n, &a, &b);
    return cj_v3_normalize(cj_v3_add(
        cj_v3_scale(n, z), cj_v3_add(cj_v3_scale(a, r * cos(ph)), cj_v3_scale(b, r * sin(ph)))));
}

/* One-bounce diffuse interreflection (trace.h): N cosine-weighted rays about the shading normal
 * n, u1 stratified over the N. The Lambert term kd c_r L cos θ / π divided by the pdf cos θ / π
 * leaves kd c_r L per ray: no cosine, no π. Rays below the geometric surface nf add nothing. */
static cj_rgb indirect_light(tr_shade *sh, const cj_hit *h, cj_vec3 n, cj_vec3 nf,
                             const cj_material *m, cj_rgb cr, int depth, tr_medium med) {
    int N = sh->indirect;
    double acc[3] = {0, 0, 0};
    sh->in_indirect = 1;
    for (int i = 0; i < N; i++) {
        double u1 = (i + tr_rand(&sh->rng)) / N, u2 = tr_rand(&sh->rng);
        cj_vec3 dir = cj_trace_cosine_sample(n, u1, u2);
        if (!(cj_v3_dot(dir, nf) > 0.0)) continue;
        cj_ray r = {cj_ray_offset_origin(h, dir), dir, 0.0, INFINITY};
        cj_rgb L = tr_trace(sh, &r, TR_INDIRECT, depth + 1, med, NULL);
        acc[0] += L.r;
        acc[1] += L.g;
        acc[2] += L.b;
    }
    sh->in_indirect = 0;
    double w = m->kd / N;
    return cj_rgb_make(cr.r * acc[0] * w, cr.g * acc[1] * w, cr.b * acc[2] * w);
}

/* A direction of the local frame (a, b, n) in world space. */
static cj_vec3 to_world3(cj_vec3 a, cj_vec3 b, cj_vec3 n, const double v[3]) {
    return cj_v3_add(cj_v3_add(cj_v3_scale(a, v[0]), cj_v3_scale(b, v[1])), cj_v3_scale(n, v[2]));
}

/* The local reflection model (reflect_model.h, the rasterizer's too) at the hit with shadow
 * rays; n faces the viewer (against d). */
static cj_rgb local_light(tr_shade *sh, const cj_material *m, const cj_hit *h, cj_vec3 n, cj_vec3 d,
                          cj_rgb cr, int depth) {
    const tr_lights *L = sh->lights;
    if (L->unlit) return cr;
    cj_rgb out =
        cj_rgb_make(cr.r * m->ka * L->ia.r, cr.g * m->ka * L->ia.g, cr.b * m->ka * L->ia.b);
    cj_vec3 v = cj_v3_scale(d, -1.0);
    const double kdn = m->kd, ksn = m->ks;
    for (int i = 0; i < L->count; i++) {
        const cj_light *lt = L->light[i];
        cj_vec3 lp = lt->position;
        const int extended = tr_is_emitter(lt);
        double s = 0.5, t = 0.5;
        if (extended && sh->spp > 1) {
            /* Stratified over the samples of the pixel at the first hit, random deeper.
             * The light stratum of pixel sample s is a keyed random permutation of s:
             * a fixed pairing (such as a cyclic shift) ties each light stratum to one
             * part of the pixel, and the pixel's estimate then keeps a variance that
             * more samples do not reduce. The random offset makes every sample's
             * stratum uniform over the pixels, so the estimate stays unbiased. */
            if (depth == 0 && !sh->random) {
                uint32_t ns = (uint32_t)sh->spp;
                uint32_t si = (cj_trace_permute(sh->sample, ns, sh->perm_key) + sh->perm) % ns;
                uint32_t k = (uint32_t)sh->strata;
                if (k * k == ns) {
                    s = ((si % k) + tr_rand(&sh->rng)) / k;
                    t = ((si / k) + tr_rand(&sh->rng)) / k;
                } else { /* spp strata across the light's first edge */
                    s = (si + tr_rand(&sh->rng)) / ns;
                    t = tr_rand(&sh->rng);
                }
            } else {
                s = tr_rand(&sh->rng);
                t = tr_rand(&sh->rng);
            }
        }
        cj_vec3 l;
        double f = 1.0;
        if (lt->kind == CJ_LIGHT_DIRECTIONAL) {
            l = cj_v3_normalize(cj_v3_scale(lt->direction, -1.0));
        } else if (extended && L->radiometric) {
            /* a sample of ∫ L_e cos θ dω over the emitter (trace_lights.c): by area for a
             * parallelogram or disc (L_e A cos θ′ / r²), by the cone's solid angle for a
             * sphere; one-sided emitters */
            double pdf;
            if (!tr_emitter_sample(lt, h->p, s, t, sh->spp == 1, &lp, &f, &pdf)) continue;
            l = cj_v3_normalize(cj_v3_sub(lp, h->p));
        } else {
            if (extended) lp = tr_emitter_point(lt, s, t); /* legacy: a point light on it */
            cj_vec3 to = cj_v3_sub(lp, h->p);
            double r2 = cj_v3_dot(to, to);
            l = cj_v3_normalize(to);
            if (L->radiometric) f = 1.0 / r2; /* point and spot: an intensity, 1/r² */
            if (lt->kind == CJ_LIGHT_SPOT) {
                double ct = -cj_v3_dot(cj_v3_normalize(lt->direction), l);
                f = ct >= cos(lt->spot_angle) ? f * pow(ct, lt->spot_exponent) : 0.0;
            }
        }
        double nl = cj_v3_dot(n, l);
        if (!(nl > 0.0) || f == 0.0) continue; /* behind the surface: its own shadow */
        if (lt->casts_shadows && m->receives_shadows) {
            cj_ray sr;
            sr.org = cj_ray_offset_origin(h, l);
            if (lt->kind == CJ_LIGHT_DIRECTIONAL) {
                sr.dir = l;
                sr.tmax = INFINITY;
            } else {
                sr.dir = cj_v3_sub(lp, sr.org);
                sr.tmax = 1.0;
            }
            sr.tmin = 0.0;
            if (tr_occluded(sh, &sr)) continue;
        }
        double I[3] = {lt->color.r * lt->intensity * f, lt->color.g * lt->intensity * f,
                       lt->color.b * lt->intensity * f};
        const double na[3] = {n.x, n.y, n.z}, la[3] = {l.x, l.y, l.z}, va[3] = {v.x, v.y, v.z};
        double dt, sp;
        cj_reflect_terms_d(na, la, va, m->alpha, (int)m->specular_model, L->radiometric, &dt, &sp);
        dt *= kdn;
        sp *= ksn;
        out.r += cr.r * I[0] * dt + m->specular.r * I[0] * sp;
        out.g += cr.g * I[1] * dt + m->specular.g * I[1] * sp;
        out.b += cr.b * I[2] * dt + m->specular.b * I[2] * sp;
    }
    return out;
}

static cj_rgb add_scaled(cj_rgb a, cj_rgb b, double s) {
    return cj_rgb_make(a.r + s * b.r, a.g + s * b.g, a.b + s * b.b);
}

/* The radiometric emitter a ray meets before t_max, or NULL. Not for indirect rays: their
 * light is the direct term's already (the local model samples every light). */
static const cj_light *seen_emitter(const tr_shade *sh, const cj_ray *ray, int kind, double t_max) {
    const tr_lights *L = sh->lights;
    if (!L->radiometric || kind == TR_INDIRECT) return NULL;
    const cj_light *best = NULL;
    for (int i = 0; i < L->count; ++i) {
        double t, pdf;
        if (tr_is_emitter(L->light[i]) && tr_emitter_hit(L->light[i], ray, t_max, &t, &pdf)) {
            t_max = t;
            best = L->light[i];
        }
    }
    return best;
}

cj_rgb tr_trace(tr_shade *sh, const cj_ray *ray, int kind, int depth, tr_medium med, int *hit_any) {
    cj_hit h;
    const int got = tr_cast(sh, kind, ray, &h);
    const cj_light *em = seen_emitter(sh, ray, kind, got ? h.t : INFINITY);
    if (em) { /* an emitter in front: its radiance */
        if (hit_any) *hit_any = 1;
        return cj_rgb_make(em->color.r * em->intensity, em->color.g * em->intensity,
                           em->color.b * em->intensity);
    }
    if (!got) return sh->background;
    if (hit_any) *hit_any = 1;
    const tr_object *o = &sh->s->objs[h.obj];
    const cj_material *m = cj_scene_material(sh->s->scene, o->material);
    cj_vec3 d = cj_v3_normalize(ray->dir);
    int front = cj_v3_dot(h.ng, d) < 0.0;
    cj_vec3 n = h.n, nf = front ? h.ng : cj_v3_scale(h.ng, -1.0);
    if (cj_v3_dot(n, nf) < 0.0) n = cj_v3_scale(n, -1.0); /* shading normal on the ray's side */
    cj_rgb cr = m->color;
    if (m->texture >= 0 && m->texture < sh->s->ntex) {
        float tc[3];
        cj_tex_sample(&sh->s->tex[m->texture], h.u, h.v, 0.0, 0.0, 0.0, 0.0, tc);
        cr = cj_rgb_make(cr.r * tc[0], cr.g * tc[1], cr.b * tc[2]);
    }
    double rt = m->transmission, rm = m->mirror, op = m->opacity;
    cj_rgb out = cj_rgb_make(0, 0, 0);
    if (rt < 1.0) {
        cj_rgb loc = local_light(sh, m, &h, n, d, cr, depth);
        loc = add_scaled(loc, m->emission, 1.0);
        if (sh->indirect > 0 && !sh->in_indirect && m->kd > 0.0 && depth < sh->max_depth &&
            !sh->lights->unlit)
            loc = add_scaled(loc, indirect_light(sh, &h, n, nf, m, cr, depth, med), 1.0);
        out = add_scaled(out, loc, (1.0 - rt) * op);
        if (op < 1.0 && depth < sh->max_depth) {
            cj_ray tr = {cj_ray_offset_origin(&h, d), d, 0.0, INFINITY};
            out = add_scaled(out, tr_trace(sh, &tr, TR_THROUGH, depth + 1, med, NULL),
                             (1.0 - rt) * (1.0 - op));
        }
    }
    if (depth >= sh->max_depth) return out;
    /* The secondary rays through the BRDFs of brdf.h, in the frame of the normal facing the
     * ray (wo = −d is +z). Legacy: the weights of the original Whitted tracer (mirror r_m,
     * refraction r_t, no Fresnel, the glossy lobe as a blurred mirror of weight 1). Radiometric:
     * the path tracer's BSDF, traced on both branches (Fresnel F to the reflection, 1 − F to
     * the refraction), the mirror tinted by c_p, the glossy lobe weighted f cos θ / pdf. */
    const int radiometric = sh->lights->radiometric;
    cj_vec3 fa, fb;
    cj_frame_from_axis(nf, &fa, &fb);
    const double wo[3] = {-cj_v3_dot(d, fa), -cj_v3_dot(d, fb), -cj_v3_dot(d, nf)};
    double reflect_w = rm;
    if (rt > 0.0) {
        /* entering: from the current medium into the material; leaving: back to the outer one */
        double n1, n2;
        tr_medium inner = med;
        if (front) {
            n1 = med.ior[med.top];
            n2 = m->ior;
            if (inner.top + 1 < TR_MAX_MEDIA) inner.ior[++inner.top] = m->ior;
        } else {
            n1 = med.ior[med.top];
            if (inner.top > 0) inner.top--;
            n2 = inner.ior[inner.top];
        }
        const cj_brdf glass = {CJ_BRDF_DIELECTRIC, 0.0, n2 / n1};
        const double F = cj_fresnel_dielectric(wo[2], n2 / n1, NULL, NULL);
        cj_brdf_sample smp;
        /* u3 = 1: the refraction branch (taken whenever F < 1) */
        if (F < 1.0 && cj_brdf_sample_dir(&glass, wo, 0.0, 0.0, 1.0, &smp)) {
            const cj_vec3 t = to_world3(fa, fb, nf, smp.wi);
            cj_ray rr = {cj_ray_offset_origin(&h, t), t, 0.0, INFINITY};
            out = add_scaled(out, tr_trace(sh, &rr, TR_REFRACT, depth + 1, inner, NULL),
                             radiometric ? rt * (1.0 - F) : rt);
            if (radiometric) reflect_w += rt * F;
        } else {
            reflect_w += rt; /* total internal reflection */
        }
    }
    if (reflect_w > 0.0) {
        static const cj_brdf mirror = {CJ_BRDF_MIRROR, 0.0, 1.0};
        cj_brdf_sample smp;
        cj_brdf_sample_dir(&mirror, wo, 0.0, 0.0, 0.0, &smp);
        double w = reflect_w;
        if (m->glossiness > 0.0 && sh->spp > 1) {
            const cj_brdf lobe = {CJ_BRDF_PHONG, m->glossiness, 1.0};
            cj_brdf_sample g;
            const double u1 = tr_rand(&sh->rng), u2 = tr_rand(&sh->rng);
            if (cj_brdf_sample_dir(&lobe, wo, u1, u2, 0.0, &g)) { /* else the mirror direction */
                smp = g;
                if (radiometric) w *= g.weight;
            }
        }
        const cj_vec3 r = cj_v3_normalize(to_world3(fa, fb, nf, smp.wi));
        cj_ray rr = {cj_ray_offset_origin(&h, r), r, 0.0, INFINITY};
        const cj_rgb L = tr_trace(sh, &rr, TR_REFLECT, depth + 1, med, NULL);
        if (radiometric) /* tinted by c_p, as in the path tracer */
            out = cj_rgb_make(out.r + w * m->specular.r * L.r, out.g + w * m->specular.g * L.g,
                              out.b + w * m->specular.b * L.b);
        else
            out = add_scaled(out, L, w);
    }
    return out;
}
