/* Channels on scene paths: parsed and resolved once into pointers, posed in place. */
#include "casteljau/anim_scene.h"

#include "error_internal.h"
#include "clock_internal.h"

#include <assert.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef enum {
    B_NONE = 0,
    B_VEC3,   /* cj_vec3 */
    B_RGB,    /* cj_rgb */
    B_SCALAR, /* double */
    B_QUAT,   /* double[4] */
    B_POINT,  /* 3 consecutive doubles of a control-point array */
    B_CAM_EYE,
    B_CAM_GAZE,
    B_CAM_UP,
    B_CAM_LOOKAT,
    B_CAM_FOV
} bind_kind;

typedef struct binding {
    bind_kind kind;
    void *ptr;
} binding;

typedef struct entry {
    cj_channel *ch;  /* a keyframe channel, or NULL for motion along a path */
    cj_path *motion; /* owned */
    double start, dur, param;
    cj_ease ease;
    char *path;
    binding bind;
} entry;

struct cj_anim {
    cj_allocator alloc;
    int has_alloc;
    size_t count, cap;
    entry *e;
    cj_scene *scene;    /* bound scene, or NULL */
    size_t bind_failed; /* the channel the last failed bind stopped at */
};

static void *a_alloc(const cj_anim *a, size_t n) {
    return a->has_alloc ? a->alloc.alloc(a->alloc.user, n) : malloc(n);
}
static void a_free(const cj_anim *a, void *p) {
    if (a->has_alloc)
        a->alloc.free(a->alloc.user, p);
    else
        free(p);
}

cj_status cj_anim_create(const cj_allocator *alloc, cj_anim **out) {
    assert(out);
    cj_anim *a = alloc ? alloc->alloc(alloc->user, sizeof *a) : malloc(sizeof *a);
    if (!a) return cj_fail(CJ_ERR_NOMEM, "animation: no memory");
    memset(a, 0, sizeof *a);
    if (alloc) {
        a->alloc = *alloc;
        a->has_alloc = 1;
    }
    *out = a;
    return CJ_OK;
}

void cj_anim_destroy(cj_anim *a) {
    if (!a) return;
    for (size_t i = 0; i < a->count; ++i) {
        cj_channel_destroy(a->e[i].ch);
        cj_path_destroy(a->e[i].motion);
        a_free(a, a->e[i].path);
    }
    a_free(a, a->e);
    a_free(a, a);
}

/* Room for one more entry and a copy of the path; the entry is zeroed. */
static cj_status new_entry(cj_anim *a, const char *path, entry **out) {
    if (a->count == a->cap) {
        const size_t nc = a->cap ? 2 * a->cap : 8;
        entry *e = a_alloc(a, sizeof *e * nc);
        if (!e) return cj_fail(CJ_ERR_NOMEM, "animation: no memory for %zu channels", nc);
        if (a->count) memcpy(e, a->e, sizeof *e * a->count);
        a_free(a, a->e);
        a->e = e;
        a->cap = nc;
    }
    const size_t len = strlen(path);
    char *p = a_alloc(a, len + 1);
    if (!p) return cj_fail(CJ_ERR_NOMEM, "animation: no memory for a path");
    memcpy(p, path, len + 1);
    entry *e = &a->e[a->count];
    memset(e, 0, sizeof *e);
    e->path = p;
    *out = e;
    return CJ_OK;
}

cj_status cj_anim_add(cj_anim *a, const char *path, const cj_channel_desc *desc) {
    assert(a && path && desc);
    entry *e;
    cj_status st = new_entry(a, path, &e);
    if (st != CJ_OK) return st;
    st = cj_channel_create(desc, a->has_alloc ? &a->alloc : NULL, &e->ch);
    if (st != CJ_OK) {
        a_free(a, e->path);
        char msg[256];
        snprintf(msg, sizeof msg, "%s", cj_last_error());
        return cj_fail(st, "channel %zu (%s): %s", a->count, path, msg);
    }
    ++a->count;
    a->scene = NULL; /* a new channel needs binding */
    return CJ_OK;
}

cj_status cj_anim_add_path(cj_anim *a, const char *path, cj_path *motion, double start,
                           double duration, cj_ease ease, double ease_param) {
    assert(a && path && motion);
    if (!isfinite(start) || !isfinite(duration) || !isfinite(ease_param))
        return cj_fail(CJ_ERR_NONFINITE, "channel %zu (%s): start, duration or ease parameter",
                       a->count, path);
    if (start < 0.0 || !(duration > 0.0))
        return cj_fail(CJ_ERR_RANGE, "channel %zu (%s): start %g must be >= 0, duration %g > 0",
                       a->count, path, start, duration);
    double sigma;
    cj_status st = cj_ease_eval(ease, ease_param, 0.5, &sigma);
    if (st != CJ_OK) return st;
    entry *e;
    st = new_entry(a, path, &e);
    if (st != CJ_OK) return st;
    e->motion = motion;
    e->start = start;
    e->dur = duration;
    e->ease = ease;
    e->param = ease_param;
    ++a->count;
    a->scene = NULL;
    return CJ_OK;
}

size_t cj_anim_channel_count(const cj_anim *a) {
    return a->count;
}
const char *cj_anim_channel_path(const cj_anim *a, size_t i) {
    return i < a->count ? a->e[i].path : NULL;
}
const cj_channel *cj_anim_channel(const cj_anim *a, size_t i) {
    return i < a->count ? a->e[i].ch : NULL;
}

void cj_anim_range(const cj_anim *a, double *t0, double *t1) {
    double lo = 0.0, hi = 0.0;
    for (size_t i = 0; i < a->count; ++i) {
        double c0 = a->e[i].start, c1 = a->e[i].start + a->e[i].dur;
        if (a->e[i].ch) cj_channel_range(a->e[i].ch, &c0, &c1);
        lo = i ? fmin(lo, c0) : c0;
        hi = i ? fmax(hi, c1) : c1;
    }
    if (t0) *t0 = lo;
    if (t1) *t1 = hi;
}

int cj_anim_animates_control_points(const cj_anim *a) {
    for (size_t i = 0; i < a->count; ++i)
        if (strstr(a->e[i].path, ".points[")) return 1;
    return 0;
}

/* ---- path parsing ---------------------------------------------------------------------- */

typedef struct cursor {
    const char *s;
    size_t ch;        /* channel number, for messages */
    const char *path; /* the whole path, for messages */
} cursor;

static int eat(cursor *c, const char *lit) {
    const size_t n = strlen(lit);
    if (strncmp(c->s, lit, n)) return 0;
    c->s += n;
    return 1;
}

static cj_status bad(const cursor *c, const char *what) {
    return cj_fail(CJ_ERR_ARGUMENT, "channel %zu: %s: %s", c->ch, c->path, what);
}

/* "[123]" into *idx, or "[\"name\"]" looked up among the nodes. */
static cj_status index_of(cursor *c, const cj_scene *scene, int nodes, size_t count, int *idx) {
    if (!eat(c, "[")) return bad(c, "expected '['");
    if (*c->s == '"' && nodes) {
        const char *q = strchr(c->s + 1, '"');
        if (!q) return bad(c, "unterminated node name");
        const size_t n = (size_t)(q - c->s - 1);
        for (size_t i = 0; i < count; ++i) {
            const char *nm = cj_scene_node(scene, (int)i)->name;
            if (nm && strlen(nm) == n && !strncmp(nm, c->s + 1, n)) {
                *idx = (int)i;
                c->s = q + 1;
                return eat(c, "]") ? CJ_OK : bad(c, "expected ']'");
            }
        }
        return bad(c, "no node has that name");
    }
    char *end;
    const long v = strtol(c->s, &end, 10);
    if (end == c->s || v < 0) return bad(c, "expected a non-negative index");
    c->s = end;
    if (!eat(c, "]")) return bad(c, "expected ']'");
    if ((size_t)v >= count) {
        char msg[96];
        snprintf(msg, sizeof msg, "index %ld does not exist (%zu there)", v, count);
        return bad(c, msg);
    }
    *idx = (int)v;
    return CJ_OK;
}

static cj_status resolve(cj_scene *scene, cursor *c, binding *b) {
    int i = 0, is_curve = 0;
    cj_status st;
    if (eat(c, "camera.")) {
        if (eat(c, "eye"))
            b->kind = B_CAM_EYE;
        else if (eat(c, "gaze"))
            b->kind = B_CAM_GAZE;
        else if (eat(c, "up"))
            b->kind = B_CAM_UP;
        else if (eat(c, "look_at"))
            b->kind = B_CAM_LOOKAT;
        else if (eat(c, "fov_y"))
            b->kind = B_CAM_FOV;
        else
            return bad(c, "camera has eye, gaze, up, look_at, fov_y");
    } else if (eat(c, "lights")) {
        if ((st = index_of(c, scene, 0, cj_scene_light_count(scene), &i))) return st;
        cj_light *l = cj_scene_light_mut(scene, i);
        if (eat(c, ".position"))
            *b = (binding){B_VEC3, &l->position};
        else if (eat(c, ".direction"))
            *b = (binding){B_VEC3, &l->direction};
        else if (eat(c, ".color"))
            *b = (binding){B_RGB, &l->color};
        else if (eat(c, ".intensity"))
            *b = (binding){B_SCALAR, &l->intensity};
        else
            return bad(c, "a light has position, direction, color, intensity");
    } else if (eat(c, "materials")) {
        if ((st = index_of(c, scene, 0, cj_scene_material_count(scene), &i))) return st;
        cj_material *m = cj_scene_material_mut(scene, i);
        if (eat(c, ".color"))
            *b = (binding){B_RGB, &m->color};
        else if (eat(c, ".specular"))
            *b = (binding){B_RGB, &m->specular};
        else if (eat(c, ".ka"))
            *b = (binding){B_SCALAR, &m->ka};
        else if (eat(c, ".kd"))
            *b = (binding){B_SCALAR, &m->kd};
        else if (eat(c, ".ks"))
            *b = (binding){B_SCALAR, &m->ks};
        else if (eat(c, ".alpha"))
            *b = (binding){B_SCALAR, &m->alpha};
        else if (eat(c, ".opacity"))
            *b = (binding){B_SCALAR, &m->opacity};
        else if (eat(c, ".mirror"))
            *b = (binding){B_SCALAR, &m->mirror};
        else if (eat(c, ".transmission"))
            *b = (binding){B_SCALAR, &m->transmission};
        else
            return bad(c, "a material has color, specular, ka, kd, ks, alpha, opacity, mirror, "
                          "transmission");
    } else if (eat(c, "nodes")) {
        if ((st = index_of(c, scene, 1, cj_scene_node_count(scene), &i))) return st;
        cj_node *n = cj_scene_node_mut(scene, i);
        if (eat(c, ".translate"))
            *b = (binding){B_VEC3, &n->local.translate};
        else if (eat(c, ".scale"))
            *b = (binding){B_VEC3, &n->local.scale};
        else if (eat(c, ".rotation"))
            *b = (binding){B_QUAT, n->local.rotation};
        else if (eat(c, ".patches") || (eat(c, ".curve.points") && (is_curve = 1))) {
            cj_geometry *g = n->geometry >= 0 ? cj_scene_geometry_mut(scene, n->geometry) : NULL;
            int pi = 0, j = 0;
            if (!is_curve) {
                if (!g || g->kind != CJ_GEOM_PATCHES) return bad(c, "the node has no patches");
                if ((st = index_of(c, scene, 0, g->u.patches.count, &pi))) return st;
                if (!eat(c, ".points")) return bad(c, "expected .points[J]");
                const cj_patch *pt = &g->u.patches.patches[pi];
                const size_t np = (size_t)(pt->deg_u + 1) * (size_t)(pt->deg_v + 1);
                if ((st = index_of(c, scene, 0, np, &j))) return st;
                /* the scene owns (allocated) these arrays; const only in the view type */
                *b = (binding){B_POINT, (double *)(uintptr_t)(pt->pts + 3 * (size_t)j)};
            } else {
                if (!g || g->kind != CJ_GEOM_CURVE) return bad(c, "the node has no curve");
                if ((st = index_of(c, scene, 0, g->u.curve.count, &j))) return st;
                *b = (binding){B_POINT, (double *)(uintptr_t)(g->u.curve.pts + 3 * (size_t)j)};
            }
        } else
            return bad(c, "a node has translate, scale, rotation, patches[P].points[J], "
                          "curve.points[J]");
    } else {
        return bad(c, "a path starts with nodes, camera, lights or materials");
    }
    if (*c->s) return bad(c, "unexpected text after the field");
    return CJ_OK;
}

size_t cj_anim_bind_failed(const cj_anim *a) {
    assert(a);
    return a->bind_failed;
}

cj_status cj_anim_bind(cj_anim *a, cj_scene *scene) {
    assert(a && scene);
    binding *tmp = a_alloc(a, sizeof *tmp * (a->count ? a->count : 1));
    if (!tmp) return cj_fail(CJ_ERR_NOMEM, "animation: no memory to bind");
    for (size_t i = 0; i < a->count; ++i) {
        const entry *en = &a->e[i];
        cursor c = {en->path, i, en->path};
        binding b = {B_NONE, NULL};
        cj_status st = resolve(scene, &c, &b);
        if (st == CJ_OK) {
            const cj_channel_kind k = en->ch ? cj_channel_kind_of(en->ch) : CJ_CHANNEL_VECTOR;
            const int dim = en->ch ? cj_channel_dim(en->ch) : cj_path_dim(en->motion);
            const int want = b.kind == B_SCALAR || b.kind == B_CAM_FOV ? 1 : 3;
            if (b.kind == B_QUAT) {
                if (k == CJ_CHANNEL_VECTOR)
                    st =
                        cj_fail(CJ_ERR_DIMENSION,
                                "channel %zu: %s needs a quaternion or Euler channel", i, en->path);
            } else if (k != CJ_CHANNEL_VECTOR || dim != want) {
                st =
                    cj_fail(CJ_ERR_DIMENSION,
                            "channel %zu: %s takes a vector channel of dimension %d (this one: "
                            "%s, dimension %d)",
                            i, en->path, want, k == CJ_CHANNEL_VECTOR ? "vector" : "rotation", dim);
            }
        }
        if (st != CJ_OK) {
            a_free(a, tmp);
            a->bind_failed = i;
            return st;
        }
        tmp[i] = b;
    }
    for (size_t i = 0; i < a->count; ++i) a->e[i].bind = tmp[i];
    a_free(a, tmp);
    a->scene = scene;
    return CJ_OK;
}

cj_status cj_anim_pose(cj_scene *scene, const cj_anim *a, double t, cj_anim_pose_info *info) {
    assert(scene && a);
    if (a->scene != scene)
        return cj_fail(CJ_ERR_ARGUMENT, "animation is not bound to this scene (cj_anim_bind)");
    if (!isfinite(t)) return cj_fail(CJ_ERR_NONFINITE, "pose time %g", t);
    const double t0 = cj_clock_seconds();
    cj_anim_pose_info inf;
    memset(&inf, 0, sizeof inf);
    cj_camera cam = *cj_scene_get_camera(scene);
    int have_look = 0;
    double look[3] = {0, 0, 0};
    for (size_t i = 0; i < a->count; ++i) {
        const entry *en = &a->e[i];
        const binding *b = &en->bind;
        double v[CJ_MAX_DIM];
        cj_status st;
        if (en->motion)
            st =
                cj_path_motion(en->motion, en->ease, en->param, (t - en->start) / en->dur, v, NULL);
        else if (b->kind == B_QUAT)
            st = cj_channel_eval_quat(en->ch, t, v);
        else
            st = cj_channel_eval(en->ch, t, v);
        if (st != CJ_OK) return st;
        switch (b->kind) {
        case B_VEC3:
            *(cj_vec3 *)b->ptr = cj_v3(v[0], v[1], v[2]);
            break;
        case B_RGB:
            *(cj_rgb *)b->ptr = cj_rgb_make(v[0], v[1], v[2]);
            break;
        case B_SCALAR:
            *(double *)b->ptr = v[0];
            break;
        case B_QUAT:
            memcpy(b->ptr, v, sizeof(double) * 4);
            break;
        case B_POINT:
            memcpy(b->ptr, v, sizeof(double) * 3);
            inf.control_points = 1;
            break;
        case B_CAM_EYE:
            cam.eye = cj_v3(v[0], v[1], v[2]);
            inf.camera = 1;
            break;
        case B_CAM_GAZE:
            cam.gaze = cj_v3(v[0], v[1], v[2]);
            inf.camera = 1;
            break;
        case B_CAM_UP:
            cam.up = cj_v3(v[0], v[1], v[2]);
            inf.camera = 1;
            break;
        case B_CAM_LOOKAT:
            memcpy(look, v, sizeof look);
            have_look = 1;
            inf.camera = 1;
            break;
        case B_CAM_FOV:
            cam.fov_y = v[0];
            inf.camera = 1;
            break;
        default:
            return cj_fail(CJ_ERR_ARGUMENT, "channel %zu is not bound", i);
        }
        ++inf.channels;
    }
    if (have_look) cam.gaze = cj_v3_sub(cj_v3(look[0], look[1], look[2]), cam.eye);
    if (inf.camera) {
        cj_status st = cj_scene_set_camera(scene, &cam);
        if (st != CJ_OK) {
            char msg[200];
            snprintf(msg, sizeof msg, "%s", cj_last_error());
            return cj_fail(st, "camera posed at t = %g: %s", t, msg);
        }
    }
    inf.seconds = cj_clock_seconds() - t0;
    if (info) *info = inf;
    return CJ_OK;
}
