/* Deferred shading from the visibility buffer (seed 8-10): the Phong reflectance, flat /
 * Gouraud / Phong interpolation and textures, in one loop per kernel (render_pipe.h). */
#include "render_pipe.h"
#include "render_light8.h"
#include "render_pool.h"

#include "error_internal.h"

#include <math.h>
#include <sched.h>
#include <string.h>

#if defined(__GNUC__)
#define CJ_INLINE static inline __attribute__((always_inline))
#else
#define CJ_INLINE static inline
#endif

static inline float dot3f(const float a[3], const float b[3]) {
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static inline void normalize3f(float a[3]) {
    float l = sqrtf(dot3f(a, a));
    if (l > 0.0f) {
        float r = 1.0f / l;
        a[0] *= r;
        a[1] *= r;
        a[2] *= r;
    }
}

/* A = r_a I_a + r_d Σ I d,  S = c_p r_s Σ I s at the point pe (position − eye, float), with d
 * and s the diffuse and specular terms of the one reflection model (reflect_model.h) as the
 * lane lighting computes them (render_light8.h, one lane here): the scalar paths (flat,
 * Gouraud, transparent fragments) and the 8-wide Phong kernels give the same values. */
CJ_INLINE void light_eval(const cj_rctx *c, const cj_rmat *m, const float pe[3],
                          const float n_in[3], int flip, float A[3], float S[3]) {
    cj_lanes b;
    b.nx[0] = flip ? -n_in[0] : n_in[0];
    b.ny[0] = flip ? -n_in[1] : n_in[1];
    b.nz[0] = flip ? -n_in[2] : n_in[2];
    b.px[0] = pe[0];
    b.py[0] = pe[1];
    b.pz[0] = pe[2];
    b.alpha[0] = m->alpha;
    b.mirror[0] = m->spec_model == CJ_SPEC_PHONG;
    cj_lanes_light(c, 1, b.mirror[0], !b.mirror[0], &b);
    for (int k = 0; k < 3; ++k) {
        A[k] = m->amb[k] + m->kd * b.sd[k][0];
        S[k] = m->spec[k] * b.ss[k][0] + m->emit[k]; /* emission: added, not reflected */
    }
}

void cj_rlight_eval(const cj_rctx *c, const cj_rmat *m, const double p[3], const float n_in[3],
                    int flip, float A[3], float S[3]) {
    const float pe[3] = {(float)(p[0] - c->view->eye.x), (float)(p[1] - c->view->eye.y),
                         (float)(p[2] - c->view->eye.z)};
    light_eval(c, m, pe, n_in, flip, A, S);
}

cj_status cj_rshade_prepare_eye(cj_rctx *c, const cj_allocator *a) {
    const cj_vec3 e = c->view->eye;
    for (int i = 0; i < c->nlights; ++i) {
        cj_rlight *L = &c->lights[i];
        L->pe[0] = (float)(L->pos[0] - e.x);
        L->pe[1] = (float)(L->pos[1] - e.y);
        L->pe[2] = (float)(L->pos[2] - e.z);
    }
    const size_t nv = c->b->vertex_count;
    c->vrec = cj_ralloc(a, sizeof(float) * 8 * (nv ? nv : 1));
    if (!c->vrec) return cj_fail(CJ_ERR_NOMEM, "shading records of %zu vertices", nv);
    const double *p = c->b->pos;
    const float *nrm = c->b->nrm, *uv = c->b->uv;
    for (size_t v = 0; v < nv; ++v) {
        float *r = c->vrec + 8 * v;
        r[0] = nrm ? nrm[3 * v] : 0.0f;
        r[1] = nrm ? nrm[3 * v + 1] : 0.0f;
        r[2] = nrm ? nrm[3 * v + 2] : 0.0f;
        r[3] = (float)(p[3 * v] - e.x);
        r[4] = (float)(p[3 * v + 1] - e.y);
        r[5] = (float)(p[3 * v + 2] - e.z);
        r[6] = uv ? uv[2 * v] : 0.0f;
        r[7] = uv ? uv[2 * v + 1] : 0.0f;
    }
    return CJ_OK;
}

/* u, v and their screen derivatives from the triangle's (u,v) plane at pixel point (sx, sy). */
static inline void uv_derivs(const double *pl, double sx, double sy, double *dudx, double *dvdx,
                             double *dudy, double *dvdy) {
    const double *U = pl, *V = pl + 3, *Q = pl + 6;
    double s = Q[0] * sx + Q[1] * sy + Q[2];
    if (s == 0.0) {
        *dudx = *dvdx = *dudy = *dvdy = 0.0;
        return;
    }
    double u = (U[0] * sx + U[1] * sy + U[2]) / s, v = (V[0] * sx + V[1] * sy + V[2]) / s;
    *dudx = (U[0] - u * Q[0]) / s;
    *dudy = (U[1] - u * Q[1]) / s;
    *dvdx = (V[0] - v * Q[0]) / s;
    *dvdy = (V[1] - v * Q[1]) / s;
}

/* The texture's RGB at a sample of triangle tri of list L. */
void cj_rshade_tex(const cj_rctx *c, const cj_rlist *L, uint32_t tri, float b1, float b2, double sx,
                   double sy, float out[3]) {
    const uint32_t *tv = L->tris + 3 * (size_t)tri;
    const float b0 = 1.0f - b1 - b2;
    const cj_rmat *m = &c->mats[c->obj_mat[L->obj[tri]]];
    const float *t0 = c->b->uv + 2 * (size_t)tv[0], *t1 = c->b->uv + 2 * (size_t)tv[1],
                *t2 = c->b->uv + 2 * (size_t)tv[2];
    double u = (double)(b0 * t0[0] + b1 * t1[0] + b2 * t2[0]);
    double v = (double)(b0 * t0[1] + b1 * t1[1] + b2 * t2[1]);
    const cj_tex_sampler *smp = &c->samplers[m->tex];
    double dudx = 0, dvdx = 0, dudy = 0, dvdy = 0;
    if (smp->needs_deriv && L->uvplane)
        uv_derivs(cj_rshade_plane(c, L, tri), sx, sy, &dudx, &dvdx, &dudy, &dvdy);
    cj_tex_sample(smp, u, v, dudx, dvdx, dudy, dvdy, out);
}

/* The shading of one sample; model and tex are compile-time constants in every caller. */
CJ_INLINE void shade(const cj_rctx *c, const cj_rlist *L, uint32_t tri, float b1, float b2,
                     double sx, double sy, const int model, const int tex, float out[4]) {
    const uint32_t *tv = L->tris + 3 * (size_t)tri;
    const float b0 = 1.0f - b1 - b2;
    const cj_rmat *m = &c->mats[c->obj_mat[L->obj[tri]]];
    float cr[3] = {m->cr[0], m->cr[1], m->cr[2]};
    if (tex) {
        float t[3];
        cj_rshade_tex(c, L, tri, b1, b2, sx, sy, t);
        cr[0] *= t[0];
        cr[1] *= t[1];
        cr[2] *= t[2];
    }
    if (model == CJ_RM_UNLIT) {
        out[0] = cr[0] * m->amb[0];
        out[1] = cr[1] * m->amb[1];
        out[2] = cr[2] * m->amb[2];
    } else {
        float A[3], S[3];
        if (model == CJ_RM_FLAT) {
            const float *f = L->flat + 6 * (size_t)tri;
            A[0] = f[0], A[1] = f[1], A[2] = f[2], S[0] = f[3], S[1] = f[4], S[2] = f[5];
        } else if (model == CJ_RM_GOURAUD) {
            const size_t side = L->back && L->back[tri] ? 6 : 0, gs = (size_t)c->gstride;
            const float *g0 = c->gouraud + gs * tv[0] + side, *g1 = c->gouraud + gs * tv[1] + side,
                        *g2 = c->gouraud + gs * tv[2] + side;
            for (int k = 0; k < 3; ++k) {
                A[k] = b0 * g0[k] + b1 * g1[k] + b2 * g2[k];
                S[k] = b0 * g0[3 + k] + b1 * g1[3 + k] + b2 * g2[3 + k];
            }
        } else {
            const float *n0 = c->b->nrm + 3 * (size_t)tv[0], *n1 = c->b->nrm + 3 * (size_t)tv[1],
                        *n2 = c->b->nrm + 3 * (size_t)tv[2];
            const float *p0 = c->vrec + 8 * (size_t)tv[0] + 3,
                        *p1 = c->vrec + 8 * (size_t)tv[1] + 3,
                        *p2 = c->vrec + 8 * (size_t)tv[2] + 3;
            float n[3], p[3];
            for (int k = 0; k < 3; ++k) {
                n[k] = b0 * n0[k] + b1 * n1[k] + b2 * n2[k];
                p[k] = b0 * p0[k] + b1 * p1[k] + b2 * p2[k];
            }
            normalize3f(n);
            light_eval(c, m, p, n, L->back && L->back[tri], A, S);
        }
        out[0] = cr[0] * A[0] + S[0];
        out[1] = cr[1] * A[1] + S[1];
        out[2] = cr[2] * A[2] + S[2];
    }
    out[3] = m->opacity;
}

/* One fragment (the transparent pass). */
#define CJ_KERNEL_ONE(NAME, MODEL, TEX)                                                            \
    static void NAME##_one(const cj_rctx *c, const cj_rlist *L, uint32_t tri, float b1, float b2,  \
                           double sx, double sy, float out[4]) {                                   \
        shade(c, L, tri, b1, b2, sx, sy, MODEL, TEX, out);                                         \
    }

/* One loop per kernel over the tile's samples of that kernel. */
#define CJ_KERNEL_LOOP(NAME, MODEL, TEX)                                                           \
    static void NAME(const cj_rctx *c, const cj_tile *t, const uint32_t *idx, size_t n,            \
                     float *col) {                                                                 \
        const int tw = t->x1 - t->x0, spp = t->spp;                                                \
        for (size_t j = 0; j < n; ++j) {                                                           \
            uint32_t i = idx[j];                                                                   \
            const cj_vis_sample *s = &t->samples[i];                                               \
            double sx = 0.0, sy = 0.0;                                                             \
            if (TEX) {                                                                             \
                uint32_t px = i / (uint32_t)spp, si = i % (uint32_t)spp;                           \
                sx = t->x0 + (int)(px % (uint32_t)tw) + c->pattern[si][0];                         \
                sy = t->y0 + (int)(px / (uint32_t)tw) + c->pattern[si][1];                         \
            }                                                                                      \
            shade(c, &c->opaque, s->tri, s->b1, s->b2, sx, sy, MODEL, TEX, col + 4 * (size_t)i);   \
        }                                                                                          \
    }                                                                                              \
    CJ_KERNEL_ONE(NAME, MODEL, TEX)

CJ_KERNEL_LOOP(k_unlit, CJ_RM_UNLIT, 0)
CJ_KERNEL_LOOP(k_unlit_tex, CJ_RM_UNLIT, 1)
CJ_KERNEL_LOOP(k_flat, CJ_RM_FLAT, 0)
CJ_KERNEL_LOOP(k_flat_tex, CJ_RM_FLAT, 1)
CJ_KERNEL_LOOP(k_gouraud, CJ_RM_GOURAUD, 0)
CJ_KERNEL_LOOP(k_gouraud_tex, CJ_RM_GOURAUD, 1)
CJ_KERNEL_ONE(k_phong, CJ_RM_PHONG, 0)
CJ_KERNEL_ONE(k_phong_tex, CJ_RM_PHONG, 1)

typedef void (*kernel_fn)(const cj_rctx *, const cj_tile *, const uint32_t *, size_t, float *);
typedef void (*one_fn)(const cj_rctx *, const cj_rlist *, uint32_t, float, float, double, double,
                       float *);
/* Phong: the 8-wide kernels of render_shade8.c (the same values as k_phong_one). */
static const kernel_fn kernels[CJ_RK_COUNT] = {k_unlit,          k_unlit_tex,         k_flat,
                                               k_flat_tex,       k_gouraud,           k_gouraud_tex,
                                               cj_rshade_phong8, cj_rshade_phong8_tex};
static const one_fn ones[CJ_RK_COUNT] = {k_unlit_one,    k_unlit_tex_one, k_flat_one,
                                         k_flat_tex_one, k_gouraud_one,   k_gouraud_tex_one,
                                         k_phong_one,    k_phong_tex_one};

void cj_rshade_kernel(const cj_rctx *c, int k, const cj_tile *t, const uint32_t *idx, size_t n,
                      float *col) {
    kernels[k](c, t, idx, n, col);
}

void cj_rshade_one(const cj_rctx *c, const cj_rlist *L, uint32_t tri, float b1, float b2, double sx,
                   double sy, float out[4]) {
    ones[L->kernel[tri]](c, L, tri, b1, b2, sx, sy, out);
}

/* The (u,v) plane of a triangle in pixel coordinates: with M the 3x3 matrix of the vertices'
 * clip (x, y, w) as columns, q = M⁻¹ (X_ndc, Y_ndc, 1) are the perspective-correct barycentrics
 * up to a common factor (2D homogeneous rasterization), so u(x, y) = (U·(x,y,1)) / (Q·(x,y,1))
 * with U = Σ u_i A_i, Q = Σ A_i, A = M⁻¹ T and T the pixel -> NDC map. Works for vertices
 * behind the eye too (no division by w). Returns 0 for a singular M (the triangle is seen
 * edge-on and covers no sample). */
static int uv_plane(const cj_rctx *c, const uint32_t *tv, double out[9]) {
    double M[3][3];
    for (int i = 0; i < 3; ++i) {
        const double *cl = c->clip + 4 * (size_t)tv[i];
        M[0][i] = cl[0];
        M[1][i] = cl[1];
        M[2][i] = cl[3];
    }
    double inv[3][3];
    inv[0][0] = M[1][1] * M[2][2] - M[1][2] * M[2][1];
    inv[0][1] = M[0][2] * M[2][1] - M[0][1] * M[2][2];
    inv[0][2] = M[0][1] * M[1][2] - M[0][2] * M[1][1];
    inv[1][0] = M[1][2] * M[2][0] - M[1][0] * M[2][2];
    inv[1][1] = M[0][0] * M[2][2] - M[0][2] * M[2][0];
    inv[1][2] = M[0][2] * M[1][0] - M[0][0] * M[1][2];
    inv[2][0] = M[1][0] * M[2][1] - M[1][1] * M[2][0];
    inv[2][1] = M[0][1] * M[2][0] - M[0][0] * M[2][1];
    inv[2][2] = M[0][0] * M[1][1] - M[0][1] * M[1][0];
    double det = M[0][0] * inv[0][0] + M[0][1] * inv[1][0] + M[0][2] * inv[2][0];
    if (!(fabs(det) > 0.0)) return 0;
    /* the common factor 1/det cancels in the ratios: keep the adjugate */
    double sx = 2.0 / c->width, sy = 2.0 / c->height, A[3][3];
    for (int i = 0; i < 3; ++i) {
        A[i][0] = inv[i][0] * sx;
        A[i][1] = inv[i][1] * sy;
        A[i][2] = inv[i][2] - inv[i][0] - inv[i][1];
    }
    memset(out, 0, 9 * sizeof(double));
    for (int i = 0; i < 3; ++i) {
        const float *uv = c->b->uv + 2 * (size_t)tv[i];
        for (int k = 0; k < 3; ++k) {
            out[k] += uv[0] * A[i][k];
            out[3 + k] += uv[1] * A[i][k];
            out[6 + k] += A[i][k];
        }
    }
    return 1;
}

/* 1 if the viewer sees the back of triangle tv: (p̄ − ē)·n⃗ > 0 with n⃗ = (p1−p0)×(p2−p0) (seed
 * 7.2), or g⃗·n⃗ > 0 for an orthographic camera (every view ray is parallel to g⃗). */
static int shows_back(const cj_rctx *c, const uint32_t *tv) {
    const double *p0 = c->b->pos + 3 * (size_t)tv[0], *p1 = c->b->pos + 3 * (size_t)tv[1],
                 *p2 = c->b->pos + 3 * (size_t)tv[2];
    double e1[3], e2[3];
    for (int k = 0; k < 3; ++k) {
        e1[k] = p1[k] - p0[k];
        e2[k] = p2[k] - p0[k];
    }
    double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                   e1[0] * e2[1] - e1[1] * e2[0]};
    double d[3];
    if (c->view->cam.projection == CJ_PROJ_PERSPECTIVE) {
        d[0] = p0[0] - c->view->eye.x;
        d[1] = p0[1] - c->view->eye.y;
        d[2] = p0[2] - c->view->eye.z;
    } else {
        d[0] = c->view->gaze_unit.x;
        d[1] = c->view->gaze_unit.y;
        d[2] = c->view->gaze_unit.z;
    }
    return d[0] * n[0] + d[1] * n[1] + d[2] * n[2] > 0.0;
}

void cj_rshade_prepare_range(const cj_rctx *c, cj_rlist *L, size_t t0, size_t t1) {
    for (size_t t = t0; t < t1; ++t) {
        const cj_rmat *m = &c->mats[c->obj_mat[L->obj[t]]];
        const uint32_t *tv = L->tris + 3 * t;
        if (L->back) L->back[t] = m->two_sided && shows_back(c, tv);
        if (m->model == CJ_RM_FLAT) {
            const double *p0 = c->b->pos + 3 * (size_t)tv[0], *p1 = c->b->pos + 3 * (size_t)tv[1],
                         *p2 = c->b->pos + 3 * (size_t)tv[2];
            double e1[3], e2[3], p[3];
            for (int k = 0; k < 3; ++k) {
                e1[k] = p1[k] - p0[k];
                e2[k] = p2[k] - p0[k];
                p[k] = (p0[k] + p1[k] + p2[k]) / 3.0;
            }
            double nd[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                            e1[0] * e2[1] - e1[1] * e2[0]};
            double l = sqrt(nd[0] * nd[0] + nd[1] * nd[1] + nd[2] * nd[2]);
            float nf[3] = {0, 0, 0};
            if (l > 0.0)
                for (int k = 0; k < 3; ++k) nf[k] = (float)(nd[k] / l);
            cj_rlight_eval(c, m, p, nf, L->back && L->back[t], L->flat + 6 * t,
                           L->flat + 6 * t + 3);
        }
    }
}

const double *cj_rshade_plane_build(const cj_rctx *c, const cj_rlist *L, uint32_t tri) {
    _Atomic uint8_t *state = &L->plane_state[tri];
    double *plane = L->uvplane + 9 * (size_t)tri;
    uint8_t expect = 0;
    if (atomic_compare_exchange_strong_explicit(state, &expect, 1, memory_order_acquire,
                                                memory_order_acquire)) {
        if (!uv_plane(c, L->tris + 3 * (size_t)tri, plane)) memset(plane, 0, 9 * sizeof(double));
        atomic_store_explicit(state, 2, memory_order_release);
        return plane;
    }
    /* another worker is writing it (about a hundred instructions); yield now and then in case
     * that worker was descheduled mid-way */
    for (unsigned spin = 1; atomic_load_explicit(state, memory_order_acquire) != 2; ++spin)
        if (!(spin & 63)) sched_yield();
    return plane;
}

size_t cj_rshade_planes_built(const cj_rlist *L) {
    size_t n = 0;
    if (L->plane_state)
        for (size_t t = 0; t < L->count; ++t)
            n += atomic_load_explicit(&L->plane_state[t], memory_order_relaxed) == 2;
    return n;
}

typedef struct prepare_job {
    const cj_rctx *c;
    cj_rlist *L;
    size_t chunk;
} prepare_job;

static void prepare_task(void *user, int task, int worker) {
    (void)worker;
    const prepare_job *j = user;
    const size_t t0 = (size_t)task * j->chunk, t1 = t0 + j->chunk;
    cj_rshade_prepare_range(j->c, j->L, t0, t1 < j->L->count ? t1 : j->L->count);
}

cj_status cj_rshade_prepare_begin(cj_rctx *c, cj_rlist *L, const cj_allocator *a) {
    size_t n = L->count;
    L->kernel = cj_ralloc(a, n ? n : 1);
    if (!L->kernel) return cj_fail(CJ_ERR_NOMEM, "kernel table of %zu triangles", n);
    int any_flat = 0, any_plane = 0, any_two_sided = 0;
    for (size_t t = 0; t < n; ++t) {
        const cj_rmat *m = &c->mats[c->obj_mat[L->obj[t]]];
        int tex = m->tex >= 0;
        if (m->two_sided) any_two_sided = 1;
        L->kernel[t] = (uint8_t)(2 * m->model + tex);
        if (m->model == CJ_RM_FLAT) any_flat = 1;
        if (tex && c->samplers[m->tex].needs_deriv) any_plane = 1;
    }
    if (any_flat) {
        L->flat = cj_ralloc(a, sizeof(float) * 6 * (n ? n : 1));
        if (!L->flat) return cj_fail(CJ_ERR_NOMEM, "flat shading of %zu triangles", n);
    }
    if (any_plane) {
        L->uvplane = cj_ralloc(a, sizeof(double) * 9 * (n ? n : 1));
        L->plane_state = cj_ralloc(a, n ? n : 1);
        if (!L->uvplane || !L->plane_state)
            return cj_fail(CJ_ERR_NOMEM, "texture planes of %zu triangles", n);
        for (size_t t = 0; t < n; ++t) atomic_init(&L->plane_state[t], 0);
    }
    if (any_two_sided) {
        L->back = cj_ralloc(a, n ? n : 1);
        if (!L->back) return cj_fail(CJ_ERR_NOMEM, "facing flags of %zu triangles", n);
    }
    return CJ_OK;
}

cj_status cj_rshade_prepare_list(cj_rctx *c, cj_rlist *L, const cj_allocator *a, cj_rpool *pool,
                                 int workers) {
    cj_status st = cj_rshade_prepare_begin(c, L, a);
    if (st) return st;
    const size_t n = L->count;
    /* in ranges on the renderer's pool when it has one (a warm frame): the set-up is a serial
     * phase of the frame otherwise */
    const size_t chunk = 4096;
    if (pool && workers > 1 && n > chunk && n / chunk < 1000000) {
        prepare_job job = {c, L, chunk};
        cj_rpool_run(pool, (int)((n + chunk - 1) / chunk), workers, prepare_task, &job, NULL);
    } else {
        cj_rshade_prepare_range(c, L, 0, n);
    }
    return CJ_OK;
}

/* Per-vertex A, S of the vertices of Gouraud triangles (both lists: the transparent one may
 * hold vertices made by BSP splits). */
cj_status cj_rshade_prepare_gouraud(cj_rctx *c, const cj_allocator *a, size_t *vertices) {
    *vertices = 0;
    const cj_rbuild *b = c->b;
    int any = 0, two_sided = 0;
    for (size_t o = 0; o < b->object_count; ++o)
        if (c->mats[c->obj_mat[o]].model == CJ_RM_GOURAUD) {
            any = 1;
            if (c->mats[c->obj_mat[o]].two_sided) two_sided = 1;
        }
    if (!any) return CJ_OK;
    size_t nv = b->vertex_count ? b->vertex_count : 1;
    c->gstride = two_sided ? 12 : 6;
    c->gouraud = cj_ralloc(a, sizeof(float) * (size_t)c->gstride * nv);
    uint8_t *done = cj_ralloc(a, nv);
    if (!c->gouraud || !done) {
        cj_rfree(a, done);
        return cj_fail(CJ_ERR_NOMEM, "Gouraud vertices");
    }
    memset(done, 0, nv);
    const cj_rlist *lists[2] = {&c->opaque, &c->transp};
    for (int li = 0; li < 2; ++li) {
        const cj_rlist *L = lists[li];
        for (size_t t = 0; t < L->count; ++t) {
            const cj_rmat *m = &c->mats[c->obj_mat[L->obj[t]]];
            if (m->model != CJ_RM_GOURAUD) continue;
            for (int k = 0; k < 3; ++k) {
                uint32_t v = L->tris[3 * t + k];
                if (done[v]) continue;
                done[v] = 1;
                float *g = c->gouraud + (size_t)c->gstride * v;
                const double *p = b->pos + 3 * (size_t)v;
                const float *nv3 = b->nrm + 3 * (size_t)v;
                cj_rlight_eval(c, m, p, nv3, 0, g, g + 3);
                /* a vertex shared by front- and back-facing triangles is lit from both sides */
                if (m->two_sided) cj_rlight_eval(c, m, p, nv3, 1, g + 6, g + 9);
                ++*vertices;
            }
        }
    }
    cj_rfree(a, done);
    return CJ_OK;
}
