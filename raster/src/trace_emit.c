/* Emissive surfaces as lights (the path tracer's next-event estimation): the world triangles of
 * static emissive mesh and planar objects, picked by area, a point uniform on the one picked.
 * Other emissive objects (patches, quadrics, spheres, moving objects) are found only when a
 * path meets them. */
#include "trace_shade.h"

#include "error_internal.h"
#include "render_internal.h"

#include <math.h>
#include <string.h>

static int emits(const cj_material *m) {
    return m->emission.r > 0.0 || m->emission.g > 0.0 || m->emission.b > 0.0;
}

static cj_vec3 world_point(const tr_object *o, cj_vec3 p) {
    if (o->identity) return p;
    cj_vec3 w;
    cj_xform3_apply_point(&o->x.m, p, &w);
    return w;
}

static void add_tri(tr_scene *s, cj_vec3 a, cj_vec3 b, cj_vec3 c, cj_rgb e) {
    tr_emit_tri *t = &s->emit[s->nemit];
    t->p0 = a;
    t->e1 = cj_v3_sub(b, a);
    t->e2 = cj_v3_sub(c, a);
    const cj_vec3 n = cj_v3_cross(t->e1, t->e2);
    t->area = 0.5 * cj_v3_norm(n);
    if (!(t->area > 0.0)) return; /* degenerate: nothing to sample */
    t->n = cj_v3_scale(n, 0.5 / t->area);
    t->emission = e;
    s->nemit++;
}

cj_status tr_scene_emitters(tr_scene *s) {
    size_t count = 0;
    for (size_t i = 0; i < s->nobj; ++i) {
        const tr_object *o = &s->objs[i];
        if (o->motion || !emits(cj_scene_material(s->scene, o->material))) continue;
        if (o->kind == CJ_GEOM_MESH) count += o->g->u.mesh->triangle_count;
        if (o->kind == CJ_GEOM_PLANAR) count += 2;
    }
    if (!count) return CJ_OK;
    s->emit = cj_ralloc(&s->alloc, count * sizeof *s->emit);
    s->emit_cdf = cj_ralloc(&s->alloc, count * sizeof *s->emit_cdf);
    s->emit_obj = cj_ralloc(&s->alloc, s->nobj);
    if (!s->emit || !s->emit_cdf || !s->emit_obj)
        return cj_fail(CJ_ERR_NOMEM, "ray tracer: %zu emissive triangles", count);
    memset(s->emit_obj, 0, s->nobj);
    for (size_t i = 0; i < s->nobj; ++i) {
        const tr_object *o = &s->objs[i];
        const cj_material *m = cj_scene_material(s->scene, o->material);
        if (o->motion || !emits(m)) continue;
        if (o->kind == CJ_GEOM_MESH) {
            const cj_mesh *me = o->g->u.mesh;
            for (size_t k = 0; k < me->triangle_count; ++k) {
                cj_vec3 v[3];
                for (int j = 0; j < 3; ++j) {
                    const double *q = me->positions + 3 * (size_t)me->triangles[3 * k + (size_t)j];
                    v[j] = world_point(o, cj_v3(q[0], q[1], q[2]));
                }
                add_tri(s, v[0], v[1], v[2], m->emission);
            }
            s->emit_obj[i] = 1;
        } else if (o->kind == CJ_GEOM_PLANAR) {
            const cj_planar_patch *p = &o->g->u.planar;
            const cj_vec3 a = world_point(o, p->p), b = world_point(o, cj_v3_add(p->p, p->eu)),
                          c = world_point(o, cj_v3_add(cj_v3_add(p->p, p->eu), p->ev)),
                          d = world_point(o, cj_v3_add(p->p, p->ev));
            add_tri(s, a, b, c, m->emission);
            add_tri(s, a, c, d, m->emission);
            s->emit_obj[i] = 1;
        }
    }
    double acc = 0.0;
    for (size_t k = 0; k < s->nemit; ++k) {
        acc += s->emit[k].area;
        s->emit_cdf[k] = acc;
    }
    s->emit_area = acc;
    if (!(acc > 0.0)) s->nemit = 0;
    return CJ_OK;
}

int tr_emit_sample(const tr_scene *s, cj_vec3 p, double u0, double u1, double u2, cj_vec3 *target,
                   cj_rgb *emission, double *weight, double *pdf) {
    if (!s->nemit) return 0;
    /* the triangle whose CDF interval holds u0 · total area */
    const double x = u0 * s->emit_area;
    size_t lo = 0, hi = s->nemit - 1;
    while (lo < hi) {
        const size_t mid = lo + (hi - lo) / 2;
        if (s->emit_cdf[mid] > x)
            hi = mid;
        else
            lo = mid + 1;
    }
    const tr_emit_tri *t = &s->emit[lo];
    /* uniform on the triangle: (1 − √u1, √u1 (1 − u2), √u1 u2) */
    const double r = sqrt(u1), a = r * (1.0 - u2), b = r * u2;
    const cj_vec3 q = cj_v3_add(t->p0, cj_v3_add(cj_v3_scale(t->e1, a), cj_v3_scale(t->e2, b)));
    const cj_vec3 to = cj_v3_sub(q, p);
    const double r2 = cj_v3_dot(to, to);
    if (!(r2 > 0.0)) return 0;
    const double cl = fabs(cj_v3_dot(t->n, to)) / sqrt(r2);
    if (!(cl > 0.0)) return 0;
    *target = q;
    *emission = t->emission;
    *pdf = r2 / (s->emit_area * cl); /* area pdf 1/A_total to solid angle */
    *weight = 1.0 / *pdf;
    return 1;
}
