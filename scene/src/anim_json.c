/* Animation documents: channels, paths, gravity, colliders and a cloth read from JSON, every
 * key checked, errors as "file:line: path message". */
#include "casteljau/anim_json.h"

#include "casteljau/catmull_rom.h"
#include "anim_json_internal.h"
#include "error_internal.h"
#include "file_internal.h"

#include <cjson/cJSON.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define PI_ 3.14159265358979323846

/* ---- channels ----------------------------------------------------------------------------- */

static const char *const INTERP[] = {
    "step",    "linear",      "catmull_rom", "centripetal", "kochanek_bartels",
    "hermite", "bezier_auto", "gltf_cubic",  "squad",       NULL};
static const char *const KINDS[] = {"vector", "quaternion", "euler", NULL};
static const char *const ORDERS[] = {"xyz", "xzy", "yxz", "yzx", "zxy", "zyx", NULL};
static const char *const EASES[] = {"linear", "smoothstep", "sine", "trapezoid", NULL};

static cj_status read_path_channel(actx *c, cj_anim *anim, const cJSON *ch, const char *path,
                                   const char *target) {
    static const char *const PK[] = {"points", "closed", "spline", "tension", NULL};
    const cJSON *pj = cJSON_GetObjectItemCaseSensitive(ch, "path");
    char pp[300];
    snprintf(pp, sizeof pp, "%s.path", path);
    cj_status st = cj_json_object(&c->json, pj, pp, PK);
    if (st) return st;
    const cJSON *pts = cJSON_GetObjectItemCaseSensitive(pj, "points");
    if (!pts) return cj_json_fail(&c->json, pj, 0, CJ_ERR_PARSE, "%s needs \"points\"", pp);
    int dim = 3, spline = 0;
    double *p = NULL, tension = 0.5;
    snprintf(pp, sizeof pp, "%s.path.points", path);
    if ((st = aj_key_values(c, pts, pp, &dim, 0, &p))) return st;
    const size_t n = (size_t)cJSON_GetArraySize(pts);
    const cJSON *cl = cJSON_GetObjectItemCaseSensitive(pj, "closed");
    if (cl && !cJSON_IsBool(cl))
        st = cj_json_fail(&c->json, cl, 0, CJ_ERR_PARSE, "%s.path.closed must be true or false",
                          path);
    static const char *const SPL[] = {"catmull_rom", "centripetal", NULL};
    snprintf(pp, sizeof pp, "%s.path", path);
    if (!st) st = aj_pick(c, pj, pp, "spline", SPL, &spline);
    if (!st) st = cj_json_num(&c->json, pj, pp, "tension", CJ_JSON_GE, -1e300, 0, &tension);
    double start = 0, dur = 0, accel = 0.25;
    int ease = 0;
    if (!st) st = cj_json_num(&c->json, ch, path, "start", CJ_JSON_GE, 0, 0, &start);
    if (!st) st = cj_json_num(&c->json, ch, path, "duration", CJ_JSON_GE, 0, 0, &dur);
    if (!st && !(dur > 0))
        st = cj_json_fail(&c->json, ch, 0, CJ_ERR_RANGE, "%s.duration must be given and > 0", path);
    if (!st) st = aj_pick(c, ch, path, "ease", EASES, &ease);
    if (!st) st = cj_json_num(&c->json, ch, path, "accel", CJ_JSON_GE, 0, 0, &accel);
    double *segs = NULL;
    cj_path *motion = NULL;
    if (!st) {
        cj_spline_options o = cj_spline_defaults();
        o.kind = spline ? CJ_SPLINE_CENTRIPETAL : CJ_SPLINE_CATMULL_ROM;
        o.tension = tension;
        o.closed = cl && cJSON_IsTrue(cl);
        const size_t ns = cj_spline_segment_count(n, o.closed);
        segs = malloc(sizeof(double) * 4 * 3 * (ns ? ns : 1));
        if (!segs) st = cj_fail(CJ_ERR_NOMEM, "no memory for a path");
        if (!st) st = cj_catmull_rom(p, n, dim, &o, segs, ns, NULL, NULL);
        if (!st) st = cj_path_create(segs, ns, dim, 1e-10, NULL, &motion);
        if (!st) st = cj_anim_add_path(anim, target, motion, start, dur, (cj_ease)ease, accel);
        if (!st) st = aj_channel_line(c, ch);
        if (st) {
            cj_path_destroy(motion);
            char msg[300];
            snprintf(msg, sizeof msg, "%s", cj_last_error());
            st = cj_json_fail(&c->json, pj, 0, st, "%s.path: %s", path, msg);
        }
    }
    free(segs);
    free(p);
    return st;
}

static cj_status read_channel(actx *c, cj_anim *anim, const cJSON *ch, const char *path) {
    static const char *const CK[] = {
        "target",  "type",       "interpolation", "times",       "values",  "tangents",
        "tension", "continuity", "bias",          "euler_order", "degrees", "path",
        "start",   "duration",   "ease",          "accel",       NULL};
    cj_status st = cj_json_object(&c->json, ch, path, CK);
    if (st) return st;
    const cJSON *tg = cJSON_GetObjectItemCaseSensitive(ch, "target");
    if (!cJSON_IsString(tg))
        return cj_json_fail(&c->json, tg ? tg : ch, 0, CJ_ERR_PARSE, "%s.target must be a string",
                            path);
    if (cJSON_GetObjectItemCaseSensitive(ch, "path"))
        return read_path_channel(c, anim, ch, path, tg->valuestring);
    int kind = 0, interp = 1, order = 0;
    if ((st = aj_pick(c, ch, path, "type", KINDS, &kind))) return st;
    if ((st = aj_pick(c, ch, path, "interpolation", INTERP, &interp))) return st;
    if ((st = aj_pick(c, ch, path, "euler_order", ORDERS, &order))) return st;
    const cJSON *tj = cJSON_GetObjectItemCaseSensitive(ch, "times");
    const cJSON *vj = cJSON_GetObjectItemCaseSensitive(ch, "values");
    if (!tj || !vj)
        return cj_json_fail(&c->json, ch, 0, CJ_ERR_PARSE, "%s needs \"times\" and \"values\"",
                            path);
    char pp[300];
    snprintf(pp, sizeof pp, "%s.times", path);
    int one = 1;
    double *t = NULL, *v = NULL, *tan = NULL;
    if ((st = aj_key_values(c, tj, pp, &one, 0, &t))) return st;
    const size_t n = (size_t)cJSON_GetArraySize(tj);
    int dim = kind == 1 ? 4 : kind == 2 ? 3 : 0;
    snprintf(pp, sizeof pp, "%s.values", path);
    st = aj_key_values(c, vj, pp, &dim, n, &v);
    cj_channel_desc d = cj_channel_desc_make((cj_channel_kind)kind, (cj_interp)interp, dim);
    if (!st) st = cj_json_num(&c->json, ch, path, "tension", CJ_JSON_GE, -1e300, 0, &d.tension);
    if (!st)
        st = cj_json_num(&c->json, ch, path, "continuity", CJ_JSON_GE, -1e300, 0, &d.continuity);
    if (!st) st = cj_json_num(&c->json, ch, path, "bias", CJ_JSON_GE, -1e300, 0, &d.bias);
    const cJSON *deg = cJSON_GetObjectItemCaseSensitive(ch, "degrees");
    if (!st && deg && !cJSON_IsBool(deg))
        st = cj_json_fail(&c->json, deg, 0, CJ_ERR_PARSE, "%s.degrees must be true or false", path);
    if (!st && kind == 2 && deg && cJSON_IsTrue(deg))
        for (size_t i = 0; i < 3 * n; ++i) v[i] *= PI_ / 180.0;
    const cJSON *tn = cJSON_GetObjectItemCaseSensitive(ch, "tangents");
    if (!st && tn) {
        snprintf(pp, sizeof pp, "%s.tangents", path);
        if (interp == CJ_INTERP_GLTF_CUBIC) {
            /* [in, out] per key: flatten the pairs */
            int d2 = 0;
            tan = malloc(sizeof(double) * 2 * n * (size_t)(dim ? dim : 1));
            if (!tan) st = cj_fail(CJ_ERR_NOMEM, "no memory for tangents");
            size_t i = 0;
            if (!st && (!cJSON_IsArray(tn) || (size_t)cJSON_GetArraySize(tn) != n))
                st = cj_json_fail(&c->json, tn, 0, CJ_ERR_PARSE, "%s must hold [in, out] per key",
                                  pp);
            for (const cJSON *e = tn ? tn->child : NULL; !st && e; e = e->next, ++i) {
                double *pair_v = NULL;
                char pe[320];
                snprintf(pe, sizeof pe, "%s[%zu]", pp, i);
                d2 = dim;
                st = aj_key_values(c, e, pe, &d2, 2, &pair_v);
                if (!st)
                    memcpy(tan + 2 * i * (size_t)dim, pair_v, sizeof(double) * 2 * (size_t)dim);
                free(pair_v);
            }
        } else {
            int d2 = dim;
            st = aj_key_values(c, tn, pp, &d2, n, &tan);
        }
    }
    if (!st) {
        d.count = n;
        d.times = t;
        d.values = v;
        d.tangents = tan;
        d.euler_order = (cj_euler_order)order;
        st = cj_anim_add(anim, tg->valuestring, &d);
        if (!st) st = aj_channel_line(c, ch);
        if (st) {
            char msg[400];
            snprintf(msg, sizeof msg, "%s", cj_last_error());
            st = cj_json_fail(&c->json, ch, 0, st, "%s: %s", path, msg);
        }
    }
    free(t);
    free(v);
    free(tan);
    return st;
}

/* ---- the document ------------------------------------------------------------------------- */

static const char *const INTEGRATORS[] = {"explicit_euler", "symplectic_euler", "rk4",
                                          "implicit_euler", NULL};

static cj_status read_colliders(actx *c, const cJSON *cj, cj_sphere_collider *sph, size_t *nsph,
                                cj_plane_collider *pl, size_t *npl) {
    static const char *const K[] = {"spheres", "planes", NULL};
    static const char *const SK[] = {"center", "radius", "friction", NULL};
    static const char *const PK[] = {"normal", "offset", "friction", NULL};
    cj_status st = cj_json_object(&c->json, cj, "colliders", K);
    if (st) return st;
    const cJSON *s = cJSON_GetObjectItemCaseSensitive(cj, "spheres");
    const cJSON *p = cJSON_GetObjectItemCaseSensitive(cj, "planes");
    size_t i = 0;
    for (const cJSON *e = s ? s->child : NULL; e; e = e->next, ++i) {
        char path[64];
        snprintf(path, sizeof path, "colliders.spheres[%zu]", i);
        if (i >= 8) return cj_json_fail(&c->json, e, 0, CJ_ERR_PARSE, "at most 8 spheres");
        sph[i] = (cj_sphere_collider){{0, 0, 0}, 1, 0};
        if ((st = cj_json_object(&c->json, e, path, SK)) ||
            (st = aj_vec3(c, e, path, "center", sph[i].center)) ||
            (st = cj_json_num(&c->json, e, path, "radius", CJ_JSON_GE, 0, 0, &sph[i].radius)) ||
            (st = cj_json_num(&c->json, e, path, "friction", CJ_JSON_GE, 0, 0, &sph[i].friction)))
            return st;
    }
    *nsph = i;
    i = 0;
    for (const cJSON *e = p ? p->child : NULL; e; e = e->next, ++i) {
        char path[64];
        snprintf(path, sizeof path, "colliders.planes[%zu]", i);
        if (i >= 8) return cj_json_fail(&c->json, e, 0, CJ_ERR_PARSE, "at most 8 planes");
        pl[i] = (cj_plane_collider){{0, 1, 0}, 0, 0};
        if ((st = cj_json_object(&c->json, e, path, PK)) ||
            (st = aj_vec3(c, e, path, "normal", pl[i].normal)) ||
            (st = cj_json_num(&c->json, e, path, "offset", CJ_JSON_GE, -1e300, 0, &pl[i].offset)) ||
            (st = cj_json_num(&c->json, e, path, "friction", CJ_JSON_GE, 0, 0, &pl[i].friction)))
            return st;
    }
    *npl = i;
    return CJ_OK;
}

static cj_status read_cloth(actx *c, cj_anim_doc *doc, const cJSON *cj,
                            const cj_springs_desc *extra) {
    static const char *const K[] = {
        "grid",   "corner",     "edge_u",          "edge_v", "mass", "stiffness",    "damping",
        "pinned", "integrator", "steps_per_frame", "color",  "name", "collide_with", NULL};
    cj_status st = cj_json_object(&c->json, cj, "cloth", K);
    if (st) return st;
    double grid[2] = {16, 16}, corner[3] = {-1, 1, -1}, eu[3] = {2, 0, 0}, ev[3] = {0, 0, 2};
    double mass = 1, k[3] = {2000, 500, 50}, damping = 0.5, spf = 4, col[3] = {0.8, 0.2, 0.2};
    int integ = CJ_INTEGRATE_IMPLICIT_EULER;
    const cJSON *g = cJSON_GetObjectItemCaseSensitive(cj, "grid");
    if (g && (st = aj_nums(c, g, "cloth.grid", 2, grid, 2, NULL))) return st;
    if (grid[0] < 2 || grid[1] < 2 || grid[0] > 256 || grid[1] > 256 || grid[0] != floor(grid[0]) ||
        grid[1] != floor(grid[1]))
        return cj_json_fail(&c->json, g, 0, CJ_ERR_RANGE,
                            "cloth.grid must be two integers in 2..256");
    const cJSON *kj = cJSON_GetObjectItemCaseSensitive(cj, "stiffness");
    if (kj && (st = aj_nums(c, kj, "cloth.stiffness", 3, k, 3, NULL))) return st;
    const cJSON *cc = cJSON_GetObjectItemCaseSensitive(cj, "color");
    if (cc && (st = aj_nums(c, cc, "cloth.color", 3, col, 3, NULL))) return st;
    if ((st = aj_vec3_in(c, cj, "cloth", "corner", CJ_ANIM_MAX_COORD, corner)) ||
        (st = aj_vec3_in(c, cj, "cloth", "edge_u", CJ_ANIM_MAX_COORD, eu)) ||
        (st = aj_vec3_in(c, cj, "cloth", "edge_v", CJ_ANIM_MAX_COORD, ev)) ||
        (st = cj_json_num(&c->json, cj, "cloth", "mass", CJ_JSON_GE, 0, 0, &mass)) ||
        (st = cj_json_num(&c->json, cj, "cloth", "damping", CJ_JSON_GE, 0, 0, &damping)) ||
        (st = aj_num_in(c, cj, "cloth", "steps_per_frame", 1, CJ_ANIM_MAX_STEPS_PER_FRAME, 1,
                        &spf)) ||
        (st = aj_pick(c, cj, "cloth", "integrator", INTEGRATORS, &integ)))
        return st;
    const cJSON *nm = cJSON_GetObjectItemCaseSensitive(cj, "name");
    if (nm && !cJSON_IsString(nm))
        return cj_json_fail(&c->json, nm, 0, CJ_ERR_PARSE, "cloth.name must be a string");
    snprintf(doc->cloth_name, sizeof doc->cloth_name, "%s", nm ? nm->valuestring : "cloth");
    double pins[64];
    size_t npins = 0;
    const cJSON *pj = cJSON_GetObjectItemCaseSensitive(cj, "pinned");
    if (pj && (st = aj_nums(c, pj, "cloth.pinned", 0, pins, 64, &npins))) return st;
    int ipins[64];
    for (size_t i = 0; i < npins; ++i) {
        if (!(pins[i] >= 0 && pins[i] < grid[0] * grid[1]) || pins[i] != floor(pins[i]))
            return cj_json_fail(&c->json, pj, 0, CJ_ERR_RANGE,
                                "cloth.pinned[%zu] = %g is not a vertex index in 0..%g", i, pins[i],
                                grid[0] * grid[1] - 1);
        ipins[i] = (int)pins[i];
    }
    st = cj_springs_create_cloth((int)grid[0], (int)grid[1], corner, eu, ev, mass, k[0], k[1], k[2],
                                 damping, ipins, npins, extra, NULL, &doc->cloth);
    if (st) {
        char msg[300];
        snprintf(msg, sizeof msg, "%s", cj_last_error());
        return cj_json_fail(&c->json, cj, 0, st, "cloth: %s", msg);
    }
    const cJSON *cw = cJSON_GetObjectItemCaseSensitive(cj, "collide_with");
    size_t ncw = 0;
    if (cw && !cJSON_IsArray(cw))
        return cj_json_fail(&c->json, cw, 0, CJ_ERR_PARSE,
                            "cloth.collide_with must be a list of names");
    for (const cJSON *e = cw ? cw->child : NULL; e; e = e->next, ++ncw) {
        if (ncw >= 4 || !cJSON_IsString(e))
            return cj_json_fail(&c->json, e, 0, CJ_ERR_PARSE,
                                "cloth.collide_with[%zu] must be an object's name (at most 4)",
                                ncw);
        snprintf(doc->cloth_collide_with[ncw], sizeof doc->cloth_collide_with[ncw], "%s",
                 e->valuestring);
    }
    doc->cloth_collide_count = (int)ncw;
    /* kept to rebuild the cloth with its patch colliders at attach */
    doc->cloth_grid[0] = (int)grid[0];
    doc->cloth_grid[1] = (int)grid[1];
    memcpy(doc->cloth_corner, corner, sizeof corner);
    memcpy(doc->cloth_eu, eu, sizeof eu);
    memcpy(doc->cloth_ev, ev, sizeof ev);
    memcpy(doc->cloth_k, k, sizeof k);
    doc->cloth_mass = mass;
    doc->cloth_damping = damping;
    memcpy(doc->cloth_pins, ipins, sizeof(int) * npins);
    doc->cloth_pin_count = npins;
    doc->cloth_nu = (int)grid[0];
    doc->cloth_nv = (int)grid[1];
    doc->cloth_integrator = (cj_integrator)integ;
    doc->steps_per_frame = (int)spf;
    doc->cloth_color = cj_rgb_make(col[0], col[1], col[2]);
    return CJ_OK;
}

static cj_status read_emitter(actx *c, const cJSON *e, const char *path, cj_emitter *out) {
    static const char *const K[] = {"position",      "direction", "spread",   "speed",
                                    "speed_jitter",  "rate",      "lifetime", "lifetime_jitter",
                                    "jitter_radius", "start",     "stop",     NULL};
    *out = cj_emitter_defaults();
    cj_status st;
    if ((st = cj_json_object(&c->json, e, path, K)) ||
        (st = aj_vec3_in(c, e, path, "position", CJ_ANIM_MAX_COORD, out->position)) ||
        (st = aj_vec3_in(c, e, path, "direction", CJ_ANIM_MAX_COORD, out->direction)) ||
        (st = cj_json_num(&c->json, e, path, "spread", CJ_JSON_GE, 0, 0, &out->spread)) ||
        (st = aj_num_in(c, e, path, "speed", 0, CJ_ANIM_MAX_SPEED, 0, &out->speed)) ||
        (st = cj_json_num(&c->json, e, path, "speed_jitter", CJ_JSON_GE, 0, 0,
                          &out->speed_jitter)) ||
        (st = aj_num_in(c, e, path, "rate", 0, CJ_ANIM_MAX_EMIT_RATE, 0, &out->rate)) ||
        (st = aj_num_in(c, e, path, "lifetime", 0, CJ_ANIM_MAX_LIFETIME, 0, &out->lifetime)) ||
        (st = cj_json_num(&c->json, e, path, "lifetime_jitter", CJ_JSON_GE, 0, 0,
                          &out->lifetime_jitter)) ||
        (st = aj_num_in(c, e, path, "jitter_radius", 0, CJ_ANIM_MAX_COORD, 0,
                        &out->jitter_radius)) ||
        (st = cj_json_num(&c->json, e, path, "start", CJ_JSON_GE, 0, 0, &out->start)) ||
        (st = cj_json_num(&c->json, e, path, "stop", CJ_JSON_GE, 0, 0, &out->stop)))
        return st;
    return CJ_OK;
}

static cj_status read_particles(actx *c, cj_anim_doc *doc, const cJSON *pj) {
    static const char *const K[] = {"capacity",        "seed",     "restitution", "wind",
                                    "steps_per_frame", "radius",   "color",       "collide_with",
                                    "flocking",        "emitters", NULL};
    static const char *const FK[] = {"radius",   "separation", "alignment",
                                     "cohesion", "max_speed",  NULL};
    cj_status st = cj_json_object(&c->json, pj, "particles", K);
    if (st) return st;
    cj_particles_desc *d = &doc->pdesc;
    double cap = 200, seed = 1, spf = 1, col[3] = {1, 0.8, 0.2};
    doc->particle_radius = 0.04;
    if ((st = cj_json_num(&c->json, pj, "particles", "capacity", CJ_JSON_GE, 1, 0, &cap)) ||
        (st = aj_num_in(c, pj, "particles", "seed", 0, 9007199254740992.0, 1, &seed)) ||
        (st = cj_json_num(&c->json, pj, "particles", "restitution", CJ_JSON_GE, 0, 0,
                          &d->restitution)) ||
        (st = aj_vec3_in(c, pj, "particles", "wind", CJ_ANIM_MAX_SPEED, d->wind)) ||
        (st = aj_num_in(c, pj, "particles", "steps_per_frame", 1, CJ_ANIM_MAX_STEPS_PER_FRAME, 1,
                        &spf)) ||
        (st = aj_num_in(c, pj, "particles", "radius", 0, CJ_ANIM_MAX_COORD, 0,
                        &doc->particle_radius)))
        return st;
    if (cap > 5000 || cap != floor(cap))
        return cj_json_fail(&c->json, cJSON_GetObjectItemCaseSensitive(pj, "capacity"), 0,
                            CJ_ERR_RANGE, "particles.capacity must be an integer in 1..5000");
    const cJSON *cc = cJSON_GetObjectItemCaseSensitive(pj, "color");
    if (cc && (st = aj_nums(c, cc, "particles.color", 3, col, 3, NULL))) return st;
    const cJSON *fl = cJSON_GetObjectItemCaseSensitive(pj, "flocking");
    if (fl) {
        cj_flocking *f = &d->flocking;
        if ((st = cj_json_object(&c->json, fl, "particles.flocking", FK)) ||
            (st = cj_json_num(&c->json, fl, "particles.flocking", "radius", CJ_JSON_GE, 0, 0,
                              &f->radius)) ||
            (st = cj_json_num(&c->json, fl, "particles.flocking", "separation", CJ_JSON_GE, -1e300,
                              0, &f->separation)) ||
            (st = cj_json_num(&c->json, fl, "particles.flocking", "alignment", CJ_JSON_GE, -1e300,
                              0, &f->alignment)) ||
            (st = cj_json_num(&c->json, fl, "particles.flocking", "cohesion", CJ_JSON_GE, -1e300, 0,
                              &f->cohesion)) ||
            (st = cj_json_num(&c->json, fl, "particles.flocking", "max_speed", CJ_JSON_GE, 0, 0,
                              &f->max_speed)))
            return st;
    }
    const cJSON *cw = cJSON_GetObjectItemCaseSensitive(pj, "collide_with");
    size_t i = 0;
    if (cw && !cJSON_IsArray(cw))
        return cj_json_fail(&c->json, cw, 0, CJ_ERR_PARSE,
                            "particles.collide_with must be a list of names");
    for (const cJSON *e = cw ? cw->child : NULL; e; e = e->next, ++i) {
        if (i >= 8 || !cJSON_IsString(e))
            return cj_json_fail(&c->json, e, 0, CJ_ERR_PARSE,
                                "particles.collide_with[%zu] must be an object's "
                                "name (at most 8)",
                                i);
        snprintf(doc->collide_with[i], sizeof doc->collide_with[i], "%s", e->valuestring);
    }
    doc->collide_count = (int)i;
    const cJSON *em = cJSON_GetObjectItemCaseSensitive(pj, "emitters");
    if (em && !cJSON_IsArray(em))
        return cj_json_fail(&c->json, em, 0, CJ_ERR_PARSE, "particles.emitters must be a list");
    i = 0;
    for (const cJSON *e = em ? em->child : NULL; e; e = e->next, ++i) {
        char path[48];
        snprintf(path, sizeof path, "particles.emitters[%zu]", i);
        if (i >= 16) return cj_json_fail(&c->json, e, 0, CJ_ERR_PARSE, "at most 16 emitters");
        if ((st = read_emitter(c, e, path, &doc->emitters[i]))) return st;
        doc->emitter_lines[i] = cj_json_line(&c->json, e);
    }
    d->capacity = (size_t)cap;
    d->seed = (uint64_t)seed;
    d->emitter_count = i;
    d->emitters = doc->emitters;
    doc->particle_steps = (int)spf;
    doc->particle_color = cj_rgb_make(col[0], col[1], col[2]);
    doc->has_particles = 1;
    /* validate now (the patch colliders come at attach): errors point at the section */
    cj_particles *probe = NULL;
    st = cj_particles_create(d, NULL, &probe);
    cj_particles_destroy(probe);
    if (st) {
        char msg[300];
        snprintf(msg, sizeof msg, "%s", cj_last_error());
        return cj_json_fail(&c->json, pj, 0, st, "particles: %s", msg);
    }
    return CJ_OK;
}

static cj_status read_doc(actx *c, const cJSON *root, cj_anim_doc *doc) {
    static const char *const TOP[] = {"scene",     "fps",     "frames",        "channels",
                                      "gravity",   "drag",    "colliders",     "cloth",
                                      "particles", "shutter", "shutter_poses", NULL};
    cj_status st = cj_json_object(&c->json, root, "document", TOP);
    if (st) return st;
    const cJSON *sc = cJSON_GetObjectItemCaseSensitive(root, "scene");
    if (sc) {
        if (!cJSON_IsString(sc))
            return cj_json_fail(&c->json, sc, 0, CJ_ERR_PARSE, "scene must be a file name");
        st = cj_json_resolve(&c->json, c->base_dir, sc, "scene", sc->valuestring, doc->scene_path,
                             sizeof doc->scene_path);
        if (st) return st;
    }
    if ((st =
             aj_num_in(c, root, "document", "fps", CJ_ANIM_MIN_FPS, CJ_ANIM_MAX_FPS, 0, &doc->fps)))
        return st;
    doc->fps_line = cj_json_line(&c->json, cJSON_GetObjectItemCaseSensitive(root, "fps"));
    const cJSON *fr = cJSON_GetObjectItemCaseSensitive(root, "frames");
    if (fr) {
        double f[2];
        if ((st = aj_nums(c, fr, "frames", 2, f, 2, NULL))) return st;
        if (f[0] < 0 || f[1] < f[0] || f[1] > 1e7 || f[0] != floor(f[0]) || f[1] != floor(f[1]))
            return cj_json_fail(&c->json, fr, 0, CJ_ERR_RANGE,
                                "frames must be [first, last], 0 <= first <= last");
        doc->frame_first = (int)f[0];
        doc->frame_last = (int)f[1];
    }
    const cJSON *sh = cJSON_GetObjectItemCaseSensitive(root, "shutter");
    if (sh) {
        if ((st = aj_nums(c, sh, "shutter", 2, doc->shutter, 2, NULL))) return st;
        if (!(doc->shutter[0] >= -1.0 && doc->shutter[0] < doc->shutter[1] &&
              doc->shutter[1] <= 1.0))
            return cj_json_fail(&c->json, sh, 0, CJ_ERR_RANGE,
                                "shutter must be [open, close] in frames, -1 <= open < close <= 1");
        doc->has_shutter = 1;
    }
    double poses = 16;
    if ((st = aj_num_in(c, root, "document", "shutter_poses", 2, CJ_ANIM_MAX_SHUTTER_POSES, 1,
                        &poses)))
        return st;
    doc->shutter_poses = (int)poses;
    const cJSON *chs = cJSON_GetObjectItemCaseSensitive(root, "channels");
    if (chs && !cJSON_IsArray(chs))
        return cj_json_fail(&c->json, chs, 0, CJ_ERR_PARSE, "channels must be an array");
    size_t i = 0;
    for (const cJSON *e = chs ? chs->child : NULL; e; e = e->next, ++i) {
        char path[48];
        snprintf(path, sizeof path, "channels[%zu]", i);
        if ((st = read_channel(c, doc->anim, e, path))) return st;
    }
    cj_springs_desc extra;
    memset(&extra, 0, sizeof extra);
    extra.dim = 3;
    cj_sphere_collider sph[8];
    cj_plane_collider pl[8];
    memset(sph, 0, sizeof sph);
    memset(pl, 0, sizeof pl);
    if ((st = aj_vec3_in(c, root, "document", "gravity", CJ_ANIM_MAX_GRAVITY, extra.gravity)) ||
        (st = aj_num_in(c, root, "document", "drag", 0, 1e6, 0, &extra.drag)))
        return st;
    const cJSON *co = cJSON_GetObjectItemCaseSensitive(root, "colliders");
    if (co && (st = read_colliders(c, co, sph, &extra.sphere_count, pl, &extra.plane_count)))
        return st;
    extra.spheres = sph;
    extra.planes = pl;
    const cJSON *cl = cJSON_GetObjectItemCaseSensitive(root, "cloth");
    if (cl && (st = read_cloth(c, doc, cl, &extra))) return st;
    /* particles share gravity, drag and the colliders */
    memcpy(doc->spheres, sph, sizeof sph);
    memcpy(doc->planes, pl, sizeof pl);
    memcpy(doc->pdesc.gravity, extra.gravity, sizeof extra.gravity);
    doc->pdesc.drag = extra.drag;
    doc->pdesc.spheres = doc->spheres;
    doc->pdesc.sphere_count = extra.sphere_count;
    doc->pdesc.planes = doc->planes;
    doc->pdesc.plane_count = extra.plane_count;
    const cJSON *pj = cJSON_GetObjectItemCaseSensitive(root, "particles");
    if (pj && (st = read_particles(c, doc, pj))) return st;
    return cj_anim_doc_set_fps(doc, doc->fps, NULL);
}

cj_status cj_anim_doc_set_fps(cj_anim_doc *doc, double fps, const char *origin) {
    if (!(fps >= CJ_ANIM_MIN_FPS && fps <= CJ_ANIM_MAX_FPS))
        return cj_fail(CJ_ERR_RANGE, "%s %g must be in [%g, %g]", origin ? origin : "fps", fps,
                       CJ_ANIM_MIN_FPS, CJ_ANIM_MAX_FPS);
    const int spf = doc->particle_steps > 0 ? doc->particle_steps : 1;
    for (size_t i = 0; doc->has_particles && i < doc->pdesc.emitter_count; ++i) {
        const double per_step = doc->emitters[i].rate / (fps * spf);
        if (per_step > CJ_ANIM_MAX_EMIT_PER_STEP)
            return cj_fail(CJ_ERR_RANGE,
                           "%s:%d: particles.emitters[%zu].rate %g at %s %g and "
                           "particles.steps_per_frame %d emits %g particles per step (at most "
                           "%g: lower the rate, raise fps or steps_per_frame)",
                           doc->source, doc->emitter_lines[i], i, doc->emitters[i].rate,
                           origin ? origin : "fps", fps, spf, per_step, CJ_ANIM_MAX_EMIT_PER_STEP);
    }
    doc->fps = fps;
    return CJ_OK;
}

cj_status cj_anim_doc_parse(const char *text, const char *name, const char *base_dir,
                            cj_anim_doc **out) {
    actx c;
    memset(&c, 0, sizeof c);
    c.name = name ? name : "animation";
    c.base_dir = base_dir ? base_dir : "";
    cJSON *root = NULL;
    CJ_JSON_TRY(cj_json_parse(c.name, text, &root));
    cj_json_doc_init(&c.json, &c.lines, c.name, text, root);
    cj_anim_doc *doc = calloc(1, sizeof *doc);
    cj_status st = doc ? CJ_OK : cj_fail(CJ_ERR_NOMEM, "no memory for the animation");
    if (!st) {
        doc->fps = 24;
        doc->cloth_node = doc->cloth_geometry = -1;
        doc->particle_node0 = -1;
        doc->steps_per_frame = 1;
        st = cj_anim_create(NULL, &doc->anim);
    }
    if (!st) {
        snprintf(doc->source, sizeof doc->source, "%s", c.name);
        c.doc = doc;
        st = read_doc(&c, root, doc);
    }
    cJSON_Delete(root);
    cj_json_doc_free(&c.json);
    if (st) {
        cj_anim_doc_destroy(doc);
        return st;
    }
    *out = doc;
    return CJ_OK;
}

cj_status cj_anim_doc_load(const char *path, cj_anim_doc **out) {
    char *buf = NULL;
    size_t n = 0;
    cj_status rs = cj_file_read_all(path, CJ_FILE_MAX_BYTES, "animation document", &buf, &n);
    if (rs) return rs;
    if (strlen(buf) != n) {
        free(buf);
        return cj_fail(CJ_ERR_PARSE, "%s: the file contains a NUL byte (not JSON text)", path);
    }
    char dir[1024];
    snprintf(dir, sizeof dir, "%s", path);
    char *slash = strrchr(dir, '/');
    if (slash)
        *slash = 0;
    else
        dir[0] = 0;
    const char *base = strrchr(path, '/');
    cj_status st = cj_anim_doc_parse(buf, base ? base + 1 : path, dir, out);
    free(buf);
    return st;
}

void cj_anim_doc_destroy(cj_anim_doc *doc) {
    if (!doc) return;
    cj_anim_destroy(doc->anim);
    free(doc->channel_lines);
    cj_springs_destroy(doc->cloth);
    cj_particles_destroy(doc->particles);
    for (int i = 0; i < 8; ++i) cj_patch_collider_destroy(doc->patch_colliders[i]);
    for (int i = 0; i < 4; ++i) cj_patch_collider_destroy(doc->cloth_colliders[i]);
    free(doc);
}
