/* Tessellation of Bézier patches (uniform / adaptive with a proven bound, watertight) and of
 * parametric surfaces. See tessellate.h for the rules and the proof of the bound. */
#include "casteljau/tessellate.h"
#include "alloc_internal.h"
#include "error_internal.h"
#include "patch_internal.h"

#include <assert.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#define U_ROUND CJ_UNIT_ROUNDOFF

/* Bounds on |S_uu|, |S_uv|, |S_vv| over a region, in the patch's own parameters. */
typedef struct dbounds {
    double uu, uv, vv;
} dbounds;

/* Norm of a difference vector (dimension d) inflated by 8u times the magnitude of its terms
 * (covers the rounding of the difference and of the norm). */
static double diff_norm(const double *d, const double *mag, int dim) {
    double e2 = 0.0;
    for (int k = 0; k < dim; ++k) {
        const double e = fabs(d[k]) + 8.0 * U_ROUND * mag[k];
        e2 += e * e;
    }
    return sqrt(e2) * (1.0 + 4.0 * U_ROUND);
}

/* Second-derivative bounds of a polynomial net of dimension dim (1..3) and degree (m,n) over
 * [0,1]^2. */
static dbounds net_bounds(const double *h, int dim, int m, int n) {
    dbounds b = {0.0, 0.0, 0.0};
    const int m1 = m + 1;
#define P(i, j) (h + dim * ((j)*m1 + (i)))
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= m; ++i) {
            double d[3], mag[3];
            if (i + 2 <= m) {
                for (int k = 0; k < dim; ++k) {
                    d[k] = (P(i + 2, j)[k] - 2.0 * P(i + 1, j)[k]) + P(i, j)[k];
                    mag[k] = fabs(P(i + 2, j)[k]) + 2.0 * fabs(P(i + 1, j)[k]) + fabs(P(i, j)[k]);
                }
                const double x = diff_norm(d, mag, dim);
                if (x > b.uu) b.uu = x;
            }
            if (j + 2 <= n) {
                for (int k = 0; k < dim; ++k) {
                    d[k] = (P(i, j + 2)[k] - 2.0 * P(i, j + 1)[k]) + P(i, j)[k];
                    mag[k] = fabs(P(i, j + 2)[k]) + 2.0 * fabs(P(i, j + 1)[k]) + fabs(P(i, j)[k]);
                }
                const double x = diff_norm(d, mag, dim);
                if (x > b.vv) b.vv = x;
            }
            if (i + 1 <= m && j + 1 <= n) {
                for (int k = 0; k < dim; ++k) {
                    d[k] = (P(i + 1, j + 1)[k] - P(i + 1, j)[k]) - (P(i, j + 1)[k] - P(i, j)[k]);
                    mag[k] = fabs(P(i + 1, j + 1)[k]) + fabs(P(i + 1, j)[k]) +
                             fabs(P(i, j + 1)[k]) + fabs(P(i, j)[k]);
                }
                const double x = diff_norm(d, mag, dim);
                if (x > b.uv) b.uv = x;
            }
        }
#undef P
    b.uu *= (double)m * (double)(m - 1);
    b.vv *= (double)n * (double)(n - 1);
    b.uv *= (double)m * (double)n;
    return b;
}

int cj_tess_edge_segments(const double *pts, int degree, double tol, int cap) {
    assert(pts != NULL);
    if (degree < 2) return 1;
    double mx = 0.0;
    for (int a = 0; a + 2 <= degree; ++a) {
        double d[3], mag[3];
        for (int k = 0; k < 3; ++k) {
            d[k] = (pts[3 * (a + 2) + k] - 2.0 * pts[3 * (a + 1) + k]) + pts[3 * a + k];
            mag[k] = fabs(pts[3 * (a + 2) + k]) + 2.0 * fabs(pts[3 * (a + 1) + k]) +
                     fabs(pts[3 * a + k]);
        }
        const double x = diff_norm(d, mag, 3);
        if (x > mx) mx = x;
    }
    const double m2 = mx * (double)degree * (double)(degree - 1);
    if (m2 == 0.0) return 1;
    const double k = ceil(sqrt(m2 / (8.0 * tol)));
    if (!(k <= (double)cap)) return cap + 1;
    return k < 1.0 ? 1 : (int)k;
}

/* Temporaries go through the mesh's allocator (a mesh always has one). */
static void *t_alloc(const cj_mesh *mesh, size_t bytes) {
    return cj_allocator_alloc(&mesh->alloc_, bytes);
}
static void t_free(const cj_mesh *mesh, void *ptr) {
    cj_allocator_free(&mesh->alloc_, ptr);
}

/* ---- per-patch state ----------------------------------------------------------------- */

typedef struct edge_info {
    int degree, collapsed, reversed;
    double pts[(CJ_PATCH_MAX_DEGREE + 1) * 3]; /* canonical order */
    double w[CJ_PATCH_MAX_DEGREE + 1];
} edge_info;

typedef struct ptess {
    const cj_patch *p;
    int32_t id;
    double h[CJ_PATCH_NET_MAX];
    int hd, m, n;
    int rational;
    double evalerr;
    /* rational patches (see rational_tri_bound) */
    double suberr_x, suberr_w; /* rounding of a sub-net coefficient */
    double verterr;            /* rounding of a vertex (3D norm) */
    double cellbox[4];         /* the grid cell whose sub-net is in cellnet */
    double cellq[4];           /* homog_bounds of that cell */
    double cellnet[CJ_PATCH_NET_MAX], trinet[CJ_PATCH_NET_MAX];
    double fnet[(CJ_PATCH_MAX_DEGREE + 2) * (CJ_PATCH_MAX_DEGREE + 2) * 3]; /* F's net */
    edge_info e[4];
    cj_mesh *mesh;
    int measure;
    int planning;      /* builds only for their bound and size: no normals */
    double abort_over; /* > 0: stop a build as soon as its bound exceeds this (it fails) */
    int aborted;       /* the last build stopped early */
    /* results of one build */
    double bound, measured;
    double worst_terms[3]; /* uu, uv, vv contributions of the worst triangle */
    size_t dropped;
} ptess;

static int cmp_point(const double *a, double wa, const double *b, double wb) {
    for (int k = 0; k < 3; ++k)
        if (a[k] != b[k]) return a[k] < b[k] ? -1 : 1;
    if (wa != wb) return wa < wb ? -1 : 1;
    return 0;
}

static void edge_setup(const cj_patch *p, int side, edge_info *e) {
    int first, step, count;
    cj_patch_edge_indices(p->deg_u, p->deg_v, side, &first, &step, &count);
    double g[(CJ_PATCH_MAX_DEGREE + 1) * 3], gw[CJ_PATCH_MAX_DEGREE + 1];
    for (int a = 0; a < count; ++a) {
        memcpy(g + 3 * a, p->pts + 3 * (first + a * step), 3 * sizeof(double));
        gw[a] = p->weights ? p->weights[first + a * step] : 1.0;
    }
    e->degree = count - 1;
    e->collapsed = 1;
    for (int a = 1; a < count && e->collapsed; ++a)
        if (cmp_point(g + 3 * a, gw[a], g, gw[0]) != 0) e->collapsed = 0;
    e->reversed = 0;
    for (int a = 0; a < count; ++a) {
        const int c = cmp_point(g + 3 * a, gw[a], g + 3 * (count - 1 - a), gw[count - 1 - a]);
        if (c != 0) {
            e->reversed = c > 0;
            break;
        }
    }
    for (int a = 0; a < count; ++a) {
        const int src = e->reversed ? count - 1 - a : a;
        memcpy(e->pts + 3 * a, g + 3 * src, 3 * sizeof(double));
        e->w[a] = gw[src];
    }
}

/* Point a of k along the patch side (side parameter a/k), evaluated canonically. */
static void edge_point(const edge_info *e, int rational, int a, int k, double out[3]) {
    const int ac = e->reversed ? k - a : a;
    const int d = e->degree;
    if (e->collapsed || ac == 0) {
        memcpy(out, e->pts, 3 * sizeof(double));
        return;
    }
    if (ac == k) {
        memcpy(out, e->pts + 3 * d, 3 * sizeof(double));
        return;
    }
    const double t = (double)ac / (double)k, s = 1.0 - t;
    double w[(CJ_PATCH_MAX_DEGREE + 1) * 4];
    const int hd = rational ? 4 : 3;
    for (int i = 0; i <= d; ++i) {
        const double wi = rational ? e->w[i] : 1.0;
        for (int c = 0; c < 3; ++c)
            w[i * hd + c] = rational ? wi * e->pts[3 * i + c] : e->pts[3 * i + c];
        if (rational) w[i * hd + 3] = wi;
    }
    for (int r = d; r > 0; --r)
        for (int i = 0; i < r * hd; ++i) w[i] = s * w[i] + t * w[i + hd];
    for (int c = 0; c < 3; ++c) out[c] = rational ? w[c] / w[3] : w[c];
}

static void eval_point(const ptess *P, double u, double v, double out[3]) {
    double r[4];
    cj_patch_eval_h(P->h, P->hd, P->m, P->n, u, v, r);
    if (P->hd == 4)
        for (int c = 0; c < 3; ++c) out[c] = r[c] / r[3];
    else
        memcpy(out, r, 3 * sizeof(double));
}

static cj_status add_vertex(ptess *P, const double pos[3], double u, double v, uint32_t *idx) {
    double nrm[3] = {0.0, 0.0, 0.0};
    const double uv[2] = {u, v};
    if (!P->planning && cj_patch_normal_unchecked(P->p, P->h, P->hd, u, v, nrm, NULL) != CJ_OK)
        nrm[0] = nrm[1] = nrm[2] = 0.0; /* a patch collapsed to a curve: no normal */
    return cj_mesh_add_vertex(P->mesh, pos, nrm, uv, idx);
}

static int same_pos(const double *a, const double *b) {
    return a[0] == b[0] && a[1] == b[1] && a[2] == b[2];
}

static dbounds strip_bounds(const ptess *P, double u0, double u1, double v0, double v1);
static double rational_tri_bound(ptess *P, const double *ua, const double *ub, const double *uc,
                                 const double *pa, const double *pb, const double *pc, int in_cell,
                                 double floor);

/* Adds triangle (a,b,c) (reordered CCW in (u,v)), accounting its bound with strip bounds
 * `db` and its measured deviation; degenerate triangles are counted and not added. */
static cj_status add_tri(ptess *P, uint32_t a, uint32_t b, uint32_t c, const dbounds *db) {
    cj_mesh *M = P->mesh;
    const double *ua = M->uvs + 2 * (size_t)a, *ub = M->uvs + 2 * (size_t)b,
                 *uc = M->uvs + 2 * (size_t)c;
    const double area = (ub[0] - ua[0]) * (uc[1] - ua[1]) - (ub[1] - ua[1]) * (uc[0] - ua[0]);
    if (area < 0.0) {
        uint32_t t = b;
        b = c;
        c = t;
        const double *tu = ub;
        ub = uc;
        uc = tu;
    }
    if (P->rational) {
        double bnd = rational_tri_bound(P, ua, ub, uc, M->positions + 3 * (size_t)a,
                                        M->positions + 3 * (size_t)b, M->positions + 3 * (size_t)c,
                                        db != NULL, P->bound);
        if (!(bnd >= 0.0)) bnd = INFINITY;
        if (bnd > P->bound) P->bound = bnd;
        if (P->abort_over > 0.0 && P->bound > P->abort_over) P->aborted = 1;
    } else {
        const double u0 = fmin(fmin(ua[0], ub[0]), uc[0]), u1 = fmax(fmax(ua[0], ub[0]), uc[0]);
        const double v0 = fmin(fmin(ua[1], ub[1]), uc[1]), v1 = fmax(fmax(ua[1], ub[1]), uc[1]);
        const double du = u1 - u0, dv = v1 - v0;
        dbounds local;
        if (!db) { /* bounds over the triangle's own (u,v) box */
            local = (du > 0.0 && dv > 0.0) ? strip_bounds(P, u0, u1, v0, v1)
                                           : strip_bounds(P, 0.0, 1.0, 0.0, 1.0);
            db = &local;
        }
        const double t0 = db->uu * du * du, t1 = 2.0 * db->uv * du * dv, t2 = db->vv * dv * dv;
        const double bnd = (t0 + t1 + t2) * 0.125 * (1.0 + 8.0 * U_ROUND) + P->evalerr;
        if (bnd > P->bound) {
            P->bound = bnd;
            P->worst_terms[0] = t0;
            P->worst_terms[1] = t1;
            P->worst_terms[2] = t2;
        }
        if (P->abort_over > 0.0 && P->bound > P->abort_over) P->aborted = 1;
    }
    const double *pa = M->positions + 3 * (size_t)a, *pb = M->positions + 3 * (size_t)b,
                 *pc = M->positions + 3 * (size_t)c;
    if (P->measure > 0) {
        const int L = P->measure;
        /* rational: min(|S - L|, |S - Q|), Q(x) = Σ λ_i w_i V_i / Σ λ_i w_i (both points of
         * the triangle; the bound is the smaller of one for each: rational_tri_bound) */
        double wa = 1.0, wb = 1.0, wc = 1.0;
        if (P->rational) {
            double r[4];
            cj_patch_eval_h(P->h, 4, P->m, P->n, ua[0], ua[1], r);
            wa = r[3];
            cj_patch_eval_h(P->h, 4, P->m, P->n, ub[0], ub[1], r);
            wb = r[3];
            cj_patch_eval_h(P->h, 4, P->m, P->n, uc[0], uc[1], r);
            wc = r[3];
        }
        for (int i = 0; i <= L; ++i)
            for (int j = 0; i + j <= L; ++j) {
                const double la = (double)i / L, lb = (double)j / L, lc = 1.0 - la - lb;
                const double u = la * ua[0] + lb * ub[0] + lc * uc[0];
                const double v = la * ua[1] + lb * ub[1] + lc * uc[1];
                double s[3], d2 = 0.0;
                eval_point(P, u, v, s);
                for (int k = 0; k < 3; ++k) {
                    const double x = s[k] - (la * pa[k] + lb * pb[k] + lc * pc[k]);
                    d2 += x * x;
                }
                double dev = sqrt(d2);
                if (P->rational) {
                    const double sw = la * wa + lb * wb + lc * wc;
                    double q2 = 0.0;
                    for (int k = 0; k < 3; ++k) {
                        const double x =
                            s[k] - (la * wa * pa[k] + lb * wb * pb[k] + lc * wc * pc[k]) / sw;
                        q2 += x * x;
                    }
                    dev = fmin(dev, sqrt(q2));
                }
                if (dev > P->measured) P->measured = dev;
            }
    }
    if (same_pos(pa, pb) || same_pos(pb, pc) || same_pos(pa, pc)) {
        ++P->dropped;
        return CJ_OK;
    }
    return cj_mesh_add_triangle(M, a, b, c, P->id);
}

/* Sub-net bounds over [u0,u1]x[v0,v1], rescaled to the patch's parameters (polynomial
 * patches; rational ones: rational_tri_bound). */
static dbounds strip_bounds(const ptess *P, double u0, double u1, double v0, double v1) {
    assert(!P->rational);
    double sub[CJ_PATCH_NET_MAX];
    cj_patch_sub_h(P->h, P->hd, P->m, P->n, u0, u1, v0, v1, sub);
    dbounds b = net_bounds(sub, 3, P->m, P->n);
    const double wu = u1 - u0, wv = v1 - v0;
    b.uu /= wu * wu;
    b.uv /= wu * wv;
    b.vv /= wv * wv;
    /* the divisions round: inflate */
    b.uu *= 1.0 + 4.0 * U_ROUND;
    b.uv *= 1.0 + 4.0 * U_ROUND;
    b.vv *= 1.0 + 4.0 * U_ROUND;
    return b;
}

/* Homogeneous rational bound (see RATIONAL BOUND, (Q)) of a box from its homogeneous sub-net:
 * out[0..2] = effective second-derivative bounds (M_Y + R M_w) / wlo in the box's local
 * coordinates, out[3] = the constant rounding term 2 (sqrt(3) eY + R ew) / wlo. */
static void homog_bounds(const ptess *P, const double *sub, double out[4]) {
    const int m = P->m, n = P->n;
    const int count = (m + 1) * (n + 1);
    double wmin = INFINITY, lo[3] = {INFINITY, INFINITY, INFINITY},
           hi[3] = {-INFINITY, -INFINITY, -INFINITY}, pmax = 0.0;
    for (int q = 0; q < count; ++q) {
        const double w = sub[4 * q + 3];
        wmin = fmin(wmin, w);
        for (int k = 0; k < 3; ++k) {
            const double x = sub[4 * q + k] / w;
            lo[k] = fmin(lo[k], x);
            hi[k] = fmax(hi[k], x);
            pmax = fmax(pmax, fabs(x));
        }
    }
    const double ew = P->suberr_w;
    const double wlow = (wmin - ew) * (1.0 - 4.0 * U_ROUND);
    if (!(wlow > 0.0)) {
        out[0] = out[1] = out[2] = out[3] = INFINITY;
        return;
    }
    double c[3], cmax = 0.0;
    for (int k = 0; k < 3; ++k) {
        c[k] = 0.5 * (lo[k] + hi[k]);
        cmax = fmax(cmax, fabs(c[k]));
    }
    double Y[(CJ_PATCH_MAX_DEGREE + 1) * (CJ_PATCH_MAX_DEGREE + 1) * 3],
        W[(CJ_PATCH_MAX_DEGREE + 1) * (CJ_PATCH_MAX_DEGREE + 1)];
    double r2 = 0.0, ymag = 0.0;
    for (int q = 0; q < count; ++q) {
        const double w = sub[4 * q + 3];
        double d2 = 0.0;
        for (int k = 0; k < 3; ++k) {
            Y[3 * q + k] = sub[4 * q + k] - c[k] * w;
            ymag = fmax(ymag, fabs(sub[4 * q + k]) + fabs(c[k]) * w);
            const double x = sub[4 * q + k] / w - c[k];
            d2 += x * x;
        }
        r2 = fmax(r2, d2);
        W[q] = w;
    }
    /* R: the computed distances round (a few ulps), the computed points b'_ij are off the
     * exact ones by <= (suberr_x + |b'| suberr_w) / w per coordinate */
    const double R = (sqrt(r2) * (1.0 + 8.0 * U_ROUND) +
                      sqrt(3.0) * (P->suberr_x + pmax * ew) / wlow + 4.0 * U_ROUND * pmax) *
                     (1.0 + 4.0 * U_ROUND);
    const double eY = P->suberr_x + cmax * ew + cj_gamma(3) * ymag;
    const dbounds by = net_bounds(Y, 3, m, n), bw = net_bounds(W, 1, m, n);
    const double inf = 1.0 + 16.0 * U_ROUND;
    out[0] = (by.uu + R * bw.uu) / wlow * inf;
    out[1] = (by.uv + R * bw.uv) / wlow * inf;
    out[2] = (by.vv + R * bw.vv) / wlow * inf;
    out[3] = 2.0 * (sqrt(3.0) * eY + R * ew) / wlow * inf;
}

/* RATIONAL BOUND. The patch is S = X / w with X (3D) and w > 0 polynomial patches: the
 * numerator and denominator of the homogeneous net (w_ij b_ij, w_ij). Take a triangle T with
 * parameter vertices p_i inside a box B (its grid cell, or its own (u,v) box), local
 * coordinates (s,t) in [0,1]^2 on B, barycentric coordinates λ_i(x), mesh vertices V_i, and
 * wlo <= w <= whi on B (the smallest and largest coefficient of B's weight sub-net: Bernstein
 * coefficients, all > 0). Two bounds, each on the distance from S(x) to a point of the mesh
 * triangle; the smaller is kept (bF when it is needed at all: see floor below).
 *
 * (L) bF, on |S(x) - Lm(x)|, Lm the mesh's linear interpolant of the V_i. Take the affine map
 * L(s,t) = A + Bs + Ct (3D coefficients) computed from the V_i. Then
 *     S - L = (X - w L) / w = F / w,    F = X - w L,
 * and F is a POLYNOMIAL patch of degree (m+1, n+1): writing L in bilinear Bernstein form
 * (its corner values L_ab, a, b in {0,1}) and using B_i^m B_a^1 = c(i,a) B_{i+a}^{m+1} with
 * c(i,0) = (m+1-i)/(m+1), c(i,1) = (i+1)/(m+1), its Bernstein coefficients are
 *     F_kl = Σ_{a,b} cu(k,a) cv(l,b) (X_{k-a,l-b} - w_{k-a,l-b} L_ab),
 * cu(k,0) = (m+1-k)/(m+1), cu(k,1) = k/(m+1) (terms with k-a or l-b out of range absent), X, w
 * the coefficients of B's homogeneous sub-net. For x in T,
 *     |F(x)| <= |F(x) - Σ λ_i F(p_i)| + max_i |F(p_i)|,
 * the first term bounded by the polynomial case's interpolation bound IB(F) = (Fuu ds^2 +
 * 2 Fuv ds dt + Fvv dt^2) / 8 with the second differences of F's net (degree m+1, n+1) and the
 * triangle's extents ds, dt in local coordinates; and F(p_i) = w(p_i) (S(p_i) - L(p_i)), where
 * |S(p_i) - L(p_i)| <= |S(p_i) - V_i| + |V_i - L(p_i)| <= verterr + e, verterr the rounding of
 * a vertex and e >= max_i |V_i - L(p_i)| (computed, plus its rounding). Since L and Lm are both
 * affine, |L - Lm| <= e on T (its max is at a vertex). So
 *     |S(x) - Lm(x)| <= [ IB(F) + whi (verterr + e) ] / wlo + e.
 * F's second derivatives are w S_uu + 2 w_u (S_u - L_u) + w_uu (S - L) etc., so the weight's
 * variation enters only through S_u - L_u and S - L, which vanish as the triangle shrinks: as
 * tight as the polynomial bound (and 0 along a cylinder's straight direction).
 *
 * (Q) bQ, on |S(x) - Q(x)|, Q(x) = Xl / wl = Σ μ_i V_i with Xl = Σ λ_i X(p_i), wl = Σ λ_i w(p_i),
 * μ_i = λ_i w(p_i) / wl >= 0 summing to 1: a point of the triangle (the homogeneous linear
 * interpolant, projected). For any point c, with Y = X - c w (net w_ij (b_ij - c)) and
 * Yl = Xl - c wl its interpolant:
 *     S - Q = Y/w - Yl/wl = (Y - Yl)/w + (Yl/wl)(wl - w)/w = [(Y - Yl) - (Q - c)(w - wl)] / w,
 * so |S - Q| <= (|Y - Yl| + R |w - wl|) / wlo with R >= |Q - c|: both are interpolation errors
 * of polynomial patches, bounded from the second differences of B's sub-nets of Y (3D) and w
 * (scalar): the polynomial formula with M = (M_Y + R M_w) / wlo (homog_bounds). c is the
 * centre of the box of B's Euclidean sub-net points b'_ij and R = max |b'_ij - c| (the exact
 * vertices lie on the patch over B, in the hull of the b'_ij, and Q is in their triangle), so
 * Y = w (b - c) is small on B and R M_w is of third order. The mesh's vertices are off the
 * exact ones by <= verterr, which moves Q by as much. Exact for a rational-linear
 * parametrisation (a segment with unequal end weights), where (L) pays for the uneven speed;
 * (L) is better where the weight varies across a straight direction.
 *
 * Both are distances from S(x) to a point of the mesh triangle, so min(bF, bQ) bounds the
 * distance surface -> mesh; as x -> Lm(x) and x -> Q(x) both map T onto the mesh triangle, it
 * also bounds mesh -> surface. Rounding: the sub-net is exact up to suberr_x (numerator
 * coordinates) and suberr_w (weights) per coefficient (at most 2(m+n) levels of s a + t b);
 * forming F_kl (Y) adds gamma(8) (gamma(3)) of its terms' magnitudes; a polynomial whose
 * coefficients move by eps per coordinate moves by <= eps everywhere (partition of unity), so
 * its interpolation error by <= 2 sqrt(3) eps (3D norm) (2 eps for w), which is added. The
 * rounding of the split parameters (moving B by a few ulps) is ignored, as in the polynomial
 * case. A triangle degenerate in (u,v) gets bQ only; wlo <= 0 gives +INF.
 * in_cell: B is the grid cell loaded in P->cellnet (load_cell); otherwise the triangle's own
 * (u,v) box (the whole square for a triangle without area in u or v). Returns min(bF, bQ), or
 * just bQ when bQ <= floor (the largest bound so far: the triangle cannot raise it). */
static double rational_tri_bound(ptess *P, const double *ua, const double *ub, const double *uc,
                                 const double *pa, const double *pb, const double *pc, int in_cell,
                                 double floor) {
    const int m = P->m, n = P->n, m1 = m + 1, n1 = n + 1;
    const double *uv[3] = {ua, ub, uc}, *V[3] = {pa, pb, pc};
    double box[4];
    const double *net;
    double qb[4];
    if (in_cell) {
        memcpy(box, P->cellbox, sizeof box);
        memcpy(qb, P->cellq, sizeof qb);
        net = P->cellnet;
    } else {
        box[0] = fmin(fmin(ua[0], ub[0]), uc[0]);
        box[1] = fmax(fmax(ua[0], ub[0]), uc[0]);
        box[2] = fmin(fmin(ua[1], ub[1]), uc[1]);
        box[3] = fmax(fmax(ua[1], ub[1]), uc[1]);
        if (!(box[1] > box[0] && box[3] > box[2])) {
            box[0] = box[2] = 0.0;
            box[1] = box[3] = 1.0;
        }
        cj_patch_sub_h(P->h, 4, m, n, box[0], box[1], box[2], box[3], P->trinet);
        net = P->trinet;
        homog_bounds(P, net, qb);
    }
    const double wu = box[1] - box[0], wv = box[3] - box[2];
    double st[3][2];
    for (int i = 0; i < 3; ++i) {
        st[i][0] = (uv[i][0] - box[0]) / wu;
        st[i][1] = (uv[i][1] - box[2]) / wv;
    }
    const double ds = (fmax(fmax(ua[0], ub[0]), uc[0]) - fmin(fmin(ua[0], ub[0]), uc[0])) / wu *
                      (1.0 + 4.0 * U_ROUND);
    const double dt = (fmax(fmax(ua[1], ub[1]), uc[1]) - fmin(fmin(ua[1], ub[1]), uc[1])) / wv *
                      (1.0 + 4.0 * U_ROUND);
    const double bq = ((qb[0] * ds * ds + 2.0 * qb[1] * ds * dt + qb[2] * dt * dt) * 0.125 *
                           (1.0 + 8.0 * U_ROUND) +
                       qb[3] + P->verterr) *
                      (1.0 + 8.0 * U_ROUND);
    if (!(bq > floor)) return bq; /* cannot raise the patch's bound: bF is not needed */
    /* L through the three vertices in local coordinates */
    const double d1s = st[1][0] - st[0][0], d1t = st[1][1] - st[0][1];
    const double d2s = st[2][0] - st[0][0], d2t = st[2][1] - st[0][1];
    const double det = d1s * d2t - d1t * d2s;
    if (!(det != 0.0) || !isfinite(det)) return bq; /* no triangle in (u,v): no L */
    double A[3], Bc[3], C[3];
    for (int k = 0; k < 3; ++k) {
        const double e1 = V[1][k] - V[0][k], e2 = V[2][k] - V[0][k];
        Bc[k] = (e1 * d2t - e2 * d1t) / det;
        C[k] = (e2 * d1s - e1 * d2s) / det;
        A[k] = V[0][k] - Bc[k] * st[0][0] - C[k] * st[0][1];
    }
    /* e >= max_i |V_i - L(p_i)|: the computed residual plus its rounding (and that of s_i,
     * t_i, a few ulps of the coordinates in [0,1]) */
    double e = 0.0;
    for (int i = 0; i < 3; ++i) {
        double e2 = 0.0;
        for (int k = 0; k < 3; ++k) {
            const double r = (A[k] + Bc[k] * st[i][0] + C[k] * st[i][1]) - V[i][k];
            const double mag = fabs(A[k]) + 2.0 * (fabs(Bc[k]) + fabs(C[k])) + fabs(V[i][k]);
            const double x = fabs(r) + 8.0 * U_ROUND * mag;
            e2 += x * x;
        }
        e = fmax(e, sqrt(e2) * (1.0 + 4.0 * U_ROUND));
    }
    double Lc[2][2][3], lmax = 0.0; /* corner values L_ab */
    for (int a = 0; a < 2; ++a)
        for (int b = 0; b < 2; ++b)
            for (int k = 0; k < 3; ++k) {
                Lc[a][b][k] = A[k] + Bc[k] * a + C[k] * b;
                lmax = fmax(lmax, fabs(Lc[a][b][k]));
            }
    /* F's net, degree (m+1, n+1), stride 3 */
    double wlo = INFINITY, whi = 0.0, fmag = 0.0;
    for (int q = 0; q < m1 * n1; ++q) {
        wlo = fmin(wlo, net[4 * q + 3]);
        whi = fmax(whi, net[4 * q + 3]);
    }
    double *F = P->fnet;
    for (int l = 0; l <= n1; ++l)
        for (int k = 0; k <= m1; ++k) {
            double f[3] = {0.0, 0.0, 0.0}, mag = 0.0;
            for (int a = 0; a < 2; ++a) {
                const int i = k - a;
                if (i < 0 || i > m) continue;
                const double cu = a ? (double)k / m1 : (double)(m1 - k) / m1;
                for (int b = 0; b < 2; ++b) {
                    const int j = l - b;
                    if (j < 0 || j > n) continue;
                    const double cv = b ? (double)l / n1 : (double)(n1 - l) / n1;
                    const double *h = net + 4 * (j * m1 + i);
                    const double c = cu * cv;
                    for (int d = 0; d < 3; ++d) {
                        f[d] += c * (h[d] - h[3] * Lc[a][b][d]);
                        mag = fmax(mag, fabs(h[d]) + h[3] * lmax);
                    }
                }
            }
            memcpy(F + 3 * (l * (m1 + 1) + k), f, sizeof f);
            fmag = fmax(fmag, mag);
        }
    wlo = (wlo - P->suberr_w) * (1.0 - 4.0 * U_ROUND);
    whi = (whi + P->suberr_w) * (1.0 + 4.0 * U_ROUND);
    if (!(wlo > 0.0)) return INFINITY;
    const double eF = P->suberr_x + P->suberr_w * lmax + cj_gamma(8) * fmag;
    const dbounds fb = net_bounds(F, 3, m1, n1);
    const double ib = (fb.uu * ds * ds + 2.0 * fb.uv * ds * dt + fb.vv * dt * dt) * 0.125 *
                          (1.0 + 8.0 * U_ROUND) +
                      2.0 * sqrt(3.0) * eF;
    const double bf = ((ib + whi * (P->verterr + e)) / wlo + e) * (1.0 + 8.0 * U_ROUND);
    return fmin(bf, bq);
}

/* Loads the homogeneous sub-net of the grid cell [u0,u1]x[v0,v1] for rational_tri_bound. */
static void load_cell(ptess *P, double u0, double u1, double v0, double v1) {
    cj_patch_sub_h(P->h, 4, P->m, P->n, u0, u1, v0, v1, P->cellnet);
    P->cellbox[0] = u0;
    P->cellbox[1] = u1;
    P->cellbox[2] = v0;
    P->cellbox[3] = v1;
    homog_bounds(P, P->cellnet, P->cellq);
}

/* Zipper between outer points o[0..k] with side parameters tout[0..k] and inner points
 * in[0..L] with side parameters tin[0..L]: advances the row whose next segment's midpoint
 * comes first. */
static cj_status zipper(ptess *P, const uint32_t *o, const double *tout, int k, const uint32_t *in,
                        const double *tin, int L, const dbounds *db) {
    int a = 0, b = 0;
    while (a < k || b < L) {
        int adv_outer;
        if (a == k)
            adv_outer = 0;
        else if (b == L)
            adv_outer = 1;
        else
            adv_outer = tout[a] + tout[a + 1] < tin[b] + tin[b + 1];
        cj_status st;
        if (adv_outer) {
            st = add_tri(P, o[a], o[a + 1], in[b], db);
            ++a;
        } else {
            st = add_tri(P, o[a], in[b + 1], in[b], db);
            ++b;
        }
        if (st || P->aborted) return st;
    }
    return CJ_OK;
}

/* One build of a patch: interior breakpoints ub[0..nu] (ub[0] = 0, ub[nu] = 1) and
 * vb[0..nv]; k[s] segments on side s (a collapsed side uses the interior breakpoints of its
 * direction, k[s] = nu or nv). */
static cj_status build_patch(ptess *P, int nu, const double *ub, int nv, const double *vb,
                             const int k[4]) {
    const int m = P->m, n = P->n;
    cj_status st = CJ_OK;
    P->bound = 0.0;
    P->measured = 0.0;
    P->dropped = 0;
    P->aborted = 0;
    P->worst_terms[0] = P->worst_terms[1] = P->worst_terms[2] = 0.0;
    const size_t nouter = (size_t)(k[0] + k[1] + k[2] + k[3] + 4);
    const size_t ngrid = (size_t)(nu + 1) * (size_t)(nv + 1);
    const size_t nmax = (size_t)(nu > nv ? nu : nv) + 1;
    uint32_t *buf = t_alloc(P->mesh, sizeof(uint32_t) * (nouter + ngrid + nmax));
    double *tbuf = t_alloc(P->mesh, sizeof(double) * (nouter + nmax));
    if (!buf || !tbuf) {
        st = cj_fail(CJ_ERR_NOMEM, "out of memory tessellating patch %d", (int)P->id);
        goto done;
    }
    uint32_t *o[4];
    double *tout[4];
    o[0] = buf;
    tout[0] = tbuf;
    for (int s = 1; s < 4; ++s) {
        o[s] = o[s - 1] + k[s - 1] + 1;
        tout[s] = tout[s - 1] + k[s - 1] + 1;
    }
    uint32_t *g = buf + nouter; /* grid indices, (j*(nu+1)+i) */
    uint32_t *inner = g + ngrid;
    double *tin = tbuf + nouter;
    int regular = 1;
    for (int s = 0; s < 4; ++s) {
        const int along_u = !(s & 1);
        const double *br = along_u ? ub : vb;
        const int nb = along_u ? nu : nv;
        for (int a = 0; a <= k[s]; ++a)
            tout[s][a] = P->e[s].collapsed ? br[a] : (double)a / (double)k[s];
        if (k[s] != nb)
            regular = 0;
        else
            for (int a = 0; a <= k[s] && regular; ++a)
                if (tout[s][a] != br[a]) regular = 0;
    }
    /* corners: the control points themselves */
    const int m1 = m + 1;
    uint32_t c00, c10, c11, c01;
    if ((st = add_vertex(P, P->p->pts, 0.0, 0.0, &c00))) goto done;
    if ((st = add_vertex(P, P->p->pts + 3 * m, 1.0, 0.0, &c10))) goto done;
    if ((st = add_vertex(P, P->p->pts + 3 * (n * m1 + m), 1.0, 1.0, &c11))) goto done;
    if ((st = add_vertex(P, P->p->pts + 3 * (n * m1), 0.0, 1.0, &c01))) goto done;
    const uint32_t first[4] = {c00, c10, c01, c00}, last[4] = {c10, c11, c11, c01};
    for (int s = 0; s < 4; ++s) {
        o[s][0] = first[s];
        o[s][k[s]] = last[s];
        for (int a = 1; a < k[s]; ++a) {
            double pos[3];
            edge_point(&P->e[s], P->rational, a, k[s], pos);
            const double t = tout[s][a];
            double u, v;
            switch (s) {
            case 0:
                u = t, v = 0.0;
                break;
            case 1:
                u = 1.0, v = t;
                break;
            case 2:
                u = t, v = 1.0;
                break;
            default:
                u = 0.0, v = t;
                break;
            }
            if ((st = add_vertex(P, pos, u, v, &o[s][a]))) goto done;
        }
    }
    for (int j = 1; j < nv; ++j)
        for (int i = 1; i < nu; ++i) {
            double pos[3];
            eval_point(P, ub[i], vb[j], pos);
            if ((st = add_vertex(P, pos, ub[i], vb[j], &g[j * (nu + 1) + i]))) goto done;
        }
    int j0 = 0, j1 = nv, i0 = 0, i1 = nu; /* the block of regular cells */
    if (regular) {
        for (int i = 0; i <= nu; ++i) {
            g[i] = o[0][i];
            g[nv * (nu + 1) + i] = o[2][i];
        }
        for (int j = 0; j <= nv; ++j) {
            g[j * (nu + 1)] = o[3][j];
            g[j * (nu + 1) + nu] = o[1][j];
        }
    } else {
        assert(nu >= 2 && nv >= 2);
        int L = nu - 2;
        for (int i = 1; i < nu; ++i) {
            inner[i - 1] = g[1 * (nu + 1) + i];
            tin[i - 1] = ub[i];
        }
        if ((st = zipper(P, o[0], tout[0], k[0], inner, tin, L, NULL)) || P->aborted) goto done;
        for (int i = 1; i < nu; ++i) inner[i - 1] = g[(nv - 1) * (nu + 1) + i];
        if ((st = zipper(P, o[2], tout[2], k[2], inner, tin, L, NULL)) || P->aborted) goto done;
        L = nv - 2;
        for (int j = 1; j < nv; ++j) {
            inner[j - 1] = g[j * (nu + 1) + 1];
            tin[j - 1] = vb[j];
        }
        if ((st = zipper(P, o[3], tout[3], k[3], inner, tin, L, NULL)) || P->aborted) goto done;
        for (int j = 1; j < nv; ++j) inner[j - 1] = g[j * (nu + 1) + nu - 1];
        if ((st = zipper(P, o[1], tout[1], k[1], inner, tin, L, NULL)) || P->aborted) goto done;
        j0 = i0 = 1;
        j1 = nv - 1;
        i1 = nu - 1;
    }
    for (int j = j0; j < j1; ++j)
        for (int i = i0; i < i1; ++i) {
            dbounds cb = {0.0, 0.0, 0.0};
            if (P->rational)
                load_cell(P, ub[i], ub[i + 1], vb[j], vb[j + 1]);
            else
                cb = strip_bounds(P, ub[i], ub[i + 1], vb[j], vb[j + 1]);
            const uint32_t A = g[j * (nu + 1) + i], B = g[j * (nu + 1) + i + 1],
                           C = g[(j + 1) * (nu + 1) + i + 1], D = g[(j + 1) * (nu + 1) + i];
            if ((st = add_tri(P, A, B, C, &cb))) goto done;
            if ((st = add_tri(P, A, C, D, &cb)) || P->aborted) goto done;
        }
done:
    t_free(P->mesh, buf);
    t_free(P->mesh, tbuf);
    return st;
}

/* Breakpoints 0 = b[0] < ... < b[cnt] = 1 equidistributing the piecewise constant density
 * rho[0..S-1] on S equal slabs (uniform where the density vanishes everywhere). */
static void equidistribute(const double *rho, int S, int cnt, double *b) {
    double total = 0.0;
    for (int a = 0; a < S; ++a) total += rho[a] / S;
    b[0] = 0.0;
    b[cnt] = 1.0;
    if (!(total > 0.0)) {
        for (int i = 1; i < cnt; ++i) b[i] = (double)i / cnt;
        return;
    }
    int a = 0;
    double acc = 0.0;
    for (int i = 1; i < cnt; ++i) {
        const double target = total * i / cnt;
        while (a < S - 1 && acc + rho[a] / S < target) {
            acc += rho[a] / S;
            ++a;
        }
        double x = rho[a] > 0.0 ? (double)a / S + (target - acc) / rho[a] : (double)(a + 1) / S;
        if (x > (double)(a + 1) / S) x = (double)(a + 1) / S;
        b[i] = x;
    }
    for (int i = 1; i < cnt; ++i) /* strictly increasing */
        if (!(b[i] > b[i - 1]) || !(b[i] < 1.0)) b[i] = b[i - 1] + (1.0 - b[i - 1]) / (cnt - i + 1);
}

#define SLABS 16

/* Side counts of one build: a collapsed side follows the grid of its direction; otherwise the
 * fixed count kfix[e] or, when planning (kfix NULL), the larger of the edge-flatness count
 * ke[e] and the grid count along that side, so that the zipper triangles next to the side are
 * no wider than the grid cells there (a straight edge across which the patch twists needs as
 * many segments as the interior, or its slivers force the whole interior finer). */
static void side_counts(const ptess *P, const int ke[4], const int *kfix, int nu, int nv,
                        int k[4]) {
    for (int e = 0; e < 4; ++e) {
        const int ng = (e & 1) ? nv : nu;
        if (P->e[e].collapsed)
            k[e] = ng;
        else if (kfix)
            k[e] = kfix[e];
        else
            k[e] = ke[e] > ng ? ke[e] : ng;
    }
}

/* A candidate grid: nu x nv cells, lines equidistributing the slab densities or (uni)
 * uniform. */
typedef struct grid {
    int nu, nv, uni;
} grid;

/* Builds grid g with side counts k; *pass receives whether the proven bound is <= tol. The
 * build stays in the mesh (replacing whatever was there after vs, ts). */
static cj_status try_grid(ptess *P, const double *rho_u, const double *rho_v, grid g,
                          const int k[4], double tol, size_t q, size_t vs, size_t ts, int *pass) {
    static const double flat[SLABS]; /* zero density: uniform lines */
    const int nu = g.nu, nv = g.nv;
    double *ub = t_alloc(P->mesh, sizeof(double) * (size_t)(nu + 1));
    double *vb = t_alloc(P->mesh, sizeof(double) * (size_t)(nv + 1));
    cj_status st = CJ_OK;
    if (!ub || !vb) {
        st = cj_fail(CJ_ERR_NOMEM, "out of memory tessellating patch %zu", q);
    } else {
        equidistribute(g.uni ? flat : rho_u, SLABS, nu, ub);
        equidistribute(g.uni ? flat : rho_v, SLABS, nv, vb);
        cj_mesh_truncate(P->mesh, vs, ts);
        P->abort_over = tol; /* a failing build is never kept: stop it early */
        st = build_patch(P, nu, ub, nv, vb, k);
        P->abort_over = 0.0;
        *pass = !st && !P->aborted && P->bound <= tol;
    }
    t_free(P->mesh, ub);
    t_free(P->mesh, vb);
    return st;
}

/* Adaptive choice for one patch. Interior: a grid of nu x nv cells whose lines equidistribute
 * the slab densities, nu = ceil(s base_u), nv = ceil(s base_v), with the scale s the smallest
 * (found by growing, then bisection) for which the per-triangle bound is <= tol; then uniform
 * K x K grids with fewer triangles than that build are tried (smallest passing K by
 * bisection), so a patch never gets more triangles than the uniform grid its sides allow.
 * Sides: when planning (kfix NULL) each build uses side_counts() and kout receives the counts
 * of the kept build; otherwise the counts kfix are imposed and the grid *hint (nu >= 2) is
 * tried first. The mesh then holds the passing build with the fewest triangles (when planning:
 * some build, to be truncated); *out is that grid. */
/* Grid densities of the set-up patch: sqrt of the second-derivative bound on SLABS slabs per
 * direction (the mixed term counts in both, so a straight direction is still refined where it
 * twists), and the cell counts of the search's starting grid for tol (base_u, base_v). */
static void patch_densities(ptess *P, double tol, double *rho_u, double *rho_v, double *base_u,
                            double *base_v) {
    {
        double su = 0.0, sv = 0.0;
        if (P->rational) {
            /* densities only shape the grid (the bound is checked per triangle): per cell of
             * SLABS x SLABS, the smaller of the largest |S_uu|, |S_uv|, |S_vv| sampled at its
             * corners and centre and of the homogeneous bound's M's */
            for (int a = 0; a < SLABS; ++a) rho_u[a] = rho_v[a] = 0.0;
            for (int a = 0; a < SLABS; ++a)
                for (int b = 0; b < SLABS; ++b) {
                    static const double off[5][2] = {{0, 0}, {1, 0}, {0, 1}, {1, 1}, {0.5, 0.5}};
                    double fu = 0.0, fv = 0.0, qb[4];
                    cj_patch_sub_h(P->h, 4, P->m, P->n, (double)a / SLABS, (double)(a + 1) / SLABS,
                                   (double)b / SLABS, (double)(b + 1) / SLABS, P->trinet);
                    homog_bounds(P, P->trinet, qb);
                    for (int o = 0; o < 5; ++o) {
                        double d[27];
                        cj_patch_derivs_unchecked(P->p, P->h, 4, (a + off[o][0]) / SLABS,
                                                  (b + off[o][1]) / SLABS, 2, 2, d);
                        const double suu = sqrt(d[18] * d[18] + d[19] * d[19] + d[20] * d[20]);
                        const double suv = sqrt(d[12] * d[12] + d[13] * d[13] + d[14] * d[14]);
                        const double svv = sqrt(d[6] * d[6] + d[7] * d[7] + d[8] * d[8]);
                        fu = fmax(fu, sqrt(fmax(suu, suv)));
                        fv = fmax(fv, sqrt(fmax(svv, suv)));
                    }
                    /* the bound kept is the smaller of the two (rational_tri_bound) */
                    rho_u[a] = fmax(rho_u[a], fmin(fu, SLABS * sqrt(fmax(qb[0], qb[1]))));
                    rho_v[b] = fmax(rho_v[b], fmin(fv, SLABS * sqrt(fmax(qb[2], qb[1]))));
                }
        } else {
            for (int a = 0; a < SLABS; ++a) {
                const dbounds bu =
                    strip_bounds(P, (double)a / SLABS, (double)(a + 1) / SLABS, 0.0, 1.0);
                const dbounds bv =
                    strip_bounds(P, 0.0, 1.0, (double)a / SLABS, (double)(a + 1) / SLABS);
                rho_u[a] = sqrt(fmax(bu.uu, bu.uv));
                rho_v[a] = sqrt(fmax(bv.vv, bv.uv));
            }
        }
        for (int a = 0; a < SLABS; ++a) {
            su += rho_u[a] / SLABS;
            sv += rho_v[a] / SLABS;
        }
        *base_u = su / sqrt(4.0 * tol);
        *base_v = sv / sqrt(4.0 * tol);
    }
}

static cj_status adaptive_patch(ptess *P, double tol, int cap, size_t q, const int *kfix,
                                const grid *hint, int kout[4], grid *out) {
    int ke[4];
    for (int s = 0; s < 4; ++s) {
        ke[s] = P->e[s].collapsed
                    ? 0
                    : cj_tess_edge_segments(P->e[s].pts, P->e[s].degree, 0.25 * tol, cap);
        if (ke[s] > cap)
            return cj_fail(CJ_ERR_CAP,
                           "patch %zu, edge %d needs more than %d segments for tolerance %.3g", q,
                           s, cap, tol);
    }
    /* grid densities: see patch_densities */
    double base_u, base_v;
    double rho_u[SLABS], rho_v[SLABS];
    patch_densities(P, tol, rho_u, rho_v, &base_u, &base_v);
    const size_t vs = P->mesh->vertex_count, ts = P->mesh->triangle_count;
    cj_status st = CJ_OK;
    int k[4];
    if (kfix && hint && hint->nu >= 2 && hint->nv >= 2) {
        int pass = 0;
        side_counts(P, ke, kfix, hint->nu, hint->nv, k);
        if ((st = try_grid(P, rho_u, rho_v, *hint, k, tol, q, vs, ts, &pass))) return st;
        if (pass) {
            *out = *hint;
            memcpy(kout, k, sizeof k);
            return CJ_OK;
        }
    }
    double lo = 0.0, hi = 0.0, s = 1.0;
    grid best = {0, 0, 0}, last = {-1, -1, 0};
    size_t best_tris = (size_t)-1;
    int last_pass = 0;
    for (int iter = 0; iter < 60; ++iter) {
        int nu = (int)fmin(ceil(s * base_u), (double)cap + 1.0);
        int nv = (int)fmin(ceil(s * base_v), (double)cap + 1.0);
        if (nu < 2) nu = 2;
        if (nv < 2) nv = 2;
        if (nu > cap || nv > cap) {
            if (best.nu) break; /* a finer passing build exists */
            st = cj_fail(CJ_ERR_CAP,
                         "patch %zu needs more than %d segments per direction for tolerance %.3g",
                         q, cap, tol);
            break;
        }
        int pass;
        if (nu == last.nu && nv == last.nv) {
            pass = last_pass;
        } else {
            const grid g = {nu, nv, 0};
            side_counts(P, ke, kfix, nu, nv, k);
            if ((st = try_grid(P, rho_u, rho_v, g, k, tol, q, vs, ts, &pass))) break;
            const size_t tris = P->mesh->triangle_count - ts;
            if (pass && tris < best_tris) {
                best_tris = tris;
                best = g;
            }
            last = g;
            last_pass = pass;
        }
        if (pass)
            hi = s;
        else
            lo = s;
        if (hi == 0.0)
            s *= 1.5; /* no passing scale yet */
        else if (lo == 0.0 && iter < 8)
            s *= 0.6; /* passing: look for a smaller scale */
        else if (hi - lo > 0.03 * hi)
            s = 0.5 * (lo + hi);
        else
            break;
        if (lo == 0.0 && iter >= 8) lo = s; /* stop shrinking */
    }
    if (!st && best.nu == 0)
        st = cj_fail(CJ_ERR_CAP, "patch %zu: no grid met tolerance %.3g", q, tol);
    if (!st && best_tris == 0) /* every triangle collapsed: nothing to search for */
        st = cj_fail(CJ_ERR_DEGENERATE,
                     "patch %zu is degenerate: its surface has no area (every triangle "
                     "collapses to a point or a curve)",
                     q);
    if (!st) {
        /* uniform K x K grids with fewer than best_tris triangles: the largest such K first;
         * if it passes, bisect for the smallest passing K (the bound decreases with K) */
        int khi = (int)floor(sqrt((double)(best_tris - 1) / 2.0));
        if (khi > cap) khi = cap;
        int klo = 1; /* klo fails (or is below the minimum 2), khi passes */
        int probe = khi;
        while (probe >= 2 && probe > klo) {
            const grid g = {probe, probe, 1};
            int pass;
            side_counts(P, ke, kfix, probe, probe, k);
            if ((st = try_grid(P, rho_u, rho_v, g, k, tol, q, vs, ts, &pass))) break;
            const size_t tris = P->mesh->triangle_count - ts;
            last = g;
            if (pass && tris < best_tris) {
                best_tris = tris;
                best = g;
            }
            if (!pass) {
                if (probe == khi) break; /* no uniform grid that small passes */
                klo = probe;
            } else {
                khi = probe;
            }
            probe = (klo + khi) / 2;
            if (probe == klo) break;
        }
    }
    side_counts(P, ke, kfix, best.nu, best.nv, k);
    /* rebuild the best grid unless it is the last build or only planning (kfix NULL) */
    if (!st && kfix && (best.nu != last.nu || best.nv != last.nv || best.uni != last.uni)) {
        int pass; /* deterministic: it passes again */
        st = try_grid(P, rho_u, rho_v, best, k, tol, q, vs, ts, &pass);
    }
    *out = best;
    memcpy(kout, k, sizeof k);
    return st;
}

/* A patch side for finding shared edges: its control points in canonical order. */
typedef struct side_ref {
    const cj_patch *p;
    int first, step, count, reversed;
    size_t slot; /* 4 * patch + side */
} side_ref;

static const double *side_point(const side_ref *r, int a, double *w) {
    const int i = r->first + r->step * (r->reversed ? r->count - 1 - a : a);
    *w = r->p->weights ? r->p->weights[i] : 1.0;
    return r->p->pts + 3 * i;
}

/* Same comparison as edge_setup's canonical order: equal iff the two sides would evaluate
 * their points from identical control sequences. */
static int cmp_side_points(const side_ref *a, const side_ref *b) {
    if (a->count != b->count) return a->count < b->count ? -1 : 1;
    for (int i = 0; i < a->count; ++i) {
        double wa, wb;
        const double *pa = side_point(a, i, &wa), *pb = side_point(b, i, &wb);
        const int c = cmp_point(pa, wa, pb, wb);
        if (c) return c;
    }
    return 0;
}

static int cmp_side_ref(const void *x, const void *y) {
    const side_ref *a = x, *b = y;
    const int c = cmp_side_points(a, b);
    if (c) return c;
    return a->slot < b->slot ? -1 : (a->slot > b->slot ? 1 : 0);
}

/* Per-patch state for one patch (everything but the results of a build). */
static void ptess_setup(ptess *P, const cj_patch *p, size_t q, cj_mesh *mesh, int measure) {
    memset(P, 0, sizeof *P);
    P->p = p;
    P->id = (int32_t)q;
    P->m = p->deg_u;
    P->n = p->deg_v;
    P->hd = cj_patch_load_h(p, P->h);
    P->rational = p->weights != NULL;
    P->mesh = mesh;
    P->measure = measure;
    double mx = 0.0;
    for (size_t i = 0; i < 3 * cj_patch_point_count(p); ++i) mx = fmax(mx, fabs(p->pts[i]));
    /* vertex rounding (de Casteljau) plus the sample's own rounding, in 3D norm */
    P->evalerr = 2.0 * cj_gamma(3 * (P->m + P->n) + 4) * mx * sqrt(3.0);
    if (P->rational) {
        /* homogeneous de Casteljau: numerator off by <= g w max|b|, weight by <= g w (weights
         * > 0), g = gamma(3(m+n)+4); the quotient by <= (2g + u) max|b| / (1 - g) per
         * coordinate */
        const double g0 = cj_gamma(3 * (P->m + P->n) + 4);
        P->verterr = (2.0 * g0 + U_ROUND) / (1.0 - g0) * mx * sqrt(3.0) * (1.0 + 8.0 * U_ROUND);
        /* sub-net coefficients (rational_tri_bound): <= 2(m+n) levels of s a + t b (and the
         * rounding of s = 1 - t), relative to the largest coefficient */
        double hx = 0.0, hw = 0.0;
        for (size_t i = 0; i < cj_patch_point_count(p); ++i) {
            for (int k = 0; k < 3; ++k) hx = fmax(hx, fabs(P->h[4 * i + (size_t)k]));
            hw = fmax(hw, P->h[4 * i + 3]);
        }
        const double g = cj_gamma(6 * (P->m + P->n) + 8);
        P->suberr_x = g * hx;
        P->suberr_w = g * hw;
    }
    for (int s = 0; s < 4; ++s) edge_setup(p, s, &P->e[s]);
}

typedef struct patch_plan {
    int k[4];
    grid g;
} patch_plan;

/* Adaptive planning pass over patches [0, count): each patch's side counts (side_counts of
 * its best build) and grid; then every side shared by several patches (identical canonical
 * control points) gets the largest count any of them asked for. Returns the number of
 * patches planned (< count when patch *planned failed with the returned status). The mesh is
 * left as it was. */
static cj_status plan_patches(const cj_patch *patches, size_t count, double tol, int cap, ptess *P,
                              cj_mesh *mesh, patch_plan *plan, side_ref *refs, size_t *planned) {
    const size_t vs = mesh->vertex_count, ts = mesh->triangle_count;
    cj_status st = CJ_OK;
    size_t q = 0;
    for (; q < count; ++q) {
        ptess_setup(P, &patches[q], q, mesh, 0);
        P->planning = 1;
        st = adaptive_patch(P, tol, cap, q, NULL, NULL, plan[q].k, &plan[q].g);
        cj_mesh_truncate(mesh, vs, ts);
        if (st) break;
    }
    *planned = q;
    size_t nr = 0;
    for (size_t i = 0; i < q; ++i)
        for (int s = 0; s < 4; ++s) {
            edge_info e;
            edge_setup(&patches[i], s, &e);
            if (e.collapsed) continue;
            side_ref *r = &refs[nr++];
            r->p = &patches[i];
            cj_patch_edge_indices(patches[i].deg_u, patches[i].deg_v, s, &r->first, &r->step,
                                  &r->count);
            r->reversed = e.reversed;
            r->slot = 4 * i + (size_t)s;
        }
    qsort(refs, nr, sizeof *refs, cmp_side_ref);
    for (size_t a = 0; a < nr;) {
        size_t b = a + 1;
        int kmax = plan[refs[a].slot / 4].k[refs[a].slot % 4];
        while (b < nr && cmp_side_points(&refs[a], &refs[b]) == 0) {
            const int kb = plan[refs[b].slot / 4].k[refs[b].slot % 4];
            if (kb > kmax) kmax = kb;
            ++b;
        }
        for (size_t c = a; c < b; ++c) plan[refs[c].slot / 4].k[refs[c].slot % 4] = kmax;
        a = b;
    }
    return st;
}

cj_status cj_tessellate_patches(const cj_patch *patches, size_t count, const cj_tess_options *opt,
                                cj_mesh *mesh, cj_tess_report *report) {
    assert(opt != NULL && mesh != NULL);
    assert(patches != NULL || count == 0);
    cj_tess_report rep;
    memset(&rep, 0, sizeof rep);
    rep.measured = opt->measure > 0 ? 0.0 : -1.0;
    if (opt->uniform < 0)
        return cj_fail(CJ_ERR_ARGUMENT, "uniform segment count %d is negative", opt->uniform);
    if (opt->measure < 0)
        return cj_fail(CJ_ERR_ARGUMENT, "measure lattice %d is negative", opt->measure);
    if (opt->max_segments < 0)
        return cj_fail(CJ_ERR_ARGUMENT, "max_segments %d is negative", opt->max_segments);
    const int cap = opt->max_segments ? opt->max_segments : CJ_TESS_DEFAULT_MAX_SEGMENTS;
    if (opt->uniform == 0) {
        if (!isfinite(opt->tol)) return cj_fail(CJ_ERR_NONFINITE, "tolerance is not finite");
        if (!(opt->tol > 0.0))
            return cj_fail(CJ_ERR_ARGUMENT, "tolerance %.17g must be > 0", opt->tol);
    } else if (opt->uniform > cap) {
        return cj_fail(CJ_ERR_CAP, "uniform count %d exceeds the cap of %d segments", opt->uniform,
                       cap);
    }
    for (size_t q = 0; q < count; ++q) {
        cj_status st = cj_patch_check(&patches[q]);
        if (st) return cj_fail(st, "patch %zu: %s", q, cj_last_error());
    }
    const int adaptive = opt->uniform == 0;
    ptess *P = t_alloc(mesh, sizeof *P);
    double *br = adaptive ? NULL : t_alloc(mesh, sizeof(double) * (size_t)(opt->uniform + 1));
    const int fits = count <= SIZE_MAX / (4 * sizeof(side_ref)); /* sizes below cannot wrap */
    patch_plan *plan = adaptive && count && fits ? t_alloc(mesh, sizeof *plan * count) : NULL;
    side_ref *refs = adaptive && count && fits ? t_alloc(mesh, sizeof *refs * 4 * count) : NULL;
    if (!P || (!adaptive && !br) || (adaptive && count && (!plan || !refs))) {
        t_free(mesh, P);
        t_free(mesh, br);
        t_free(mesh, plan);
        t_free(mesh, refs);
        return cj_fail(CJ_ERR_NOMEM, "out of memory");
    }
    if (br)
        for (int i = 0; i <= opt->uniform; ++i) br[i] = (double)i / (double)opt->uniform;
    const size_t v_start = mesh->vertex_count, t_start = mesh->triangle_count;
    cj_status st = CJ_OK, plan_st = CJ_OK;
    size_t todo = count;
    if (adaptive) /* patches after a planning failure are not built */
        plan_st = plan_patches(patches, count, opt->tol, cap, P, mesh, plan, refs, &todo);
    if (plan_st == CJ_ERR_NOMEM) todo = 0;
    for (size_t q = 0; q < todo && !st; ++q) {
        ptess_setup(P, &patches[q], q, mesh, opt->measure);
        const size_t vq = mesh->vertex_count, tq = mesh->triangle_count;
        int nu = 0, nv = 0;
        if (!adaptive) {
            const int k[4] = {opt->uniform, opt->uniform, opt->uniform, opt->uniform};
            nu = nv = opt->uniform;
            st = build_patch(P, nu, br, nv, br, k);
        } else {
            int kused[4];
            grid g = {0, 0, 0};
            st = adaptive_patch(P, opt->tol, cap, q, plan[q].k, &plan[q].g, kused, &g);
            nu = g.nu;
            nv = g.nv;
        }
        if (!st && mesh->triangle_count == tq)
            st = cj_fail(CJ_ERR_DEGENERATE,
                         "patch %zu is degenerate: its surface has no area (every triangle "
                         "collapses to a point or a curve)",
                         q);
        if (st) { /* no partial or failing build of this patch stays */
            cj_mesh_truncate(mesh, vq, tq);
            break;
        }
        rep.bound = fmax(rep.bound, P->bound);
        if (opt->measure > 0 && P->measured > rep.measured) rep.measured = P->measured;
        rep.dropped += P->dropped;
        if (nu > rep.max_nu) rep.max_nu = nu;
        if (nv > rep.max_nv) rep.max_nv = nv;
    }
    if (!st) st = plan_st;
    t_free(mesh, P);
    t_free(mesh, br);
    t_free(mesh, plan);
    t_free(mesh, refs);
    rep.vertices = mesh->vertex_count - v_start;
    rep.triangles = mesh->triangle_count - t_start;
    if (report) *report = rep;
    return st;
}

cj_status cj_tessellate_predict(const cj_patch *patches, size_t count, const cj_tess_options *opt,
                                double *triangles) {
    assert(opt != NULL && triangles != NULL);
    assert(patches != NULL || count == 0);
    if (opt->uniform < 0)
        return cj_fail(CJ_ERR_ARGUMENT, "uniform segment count %d is negative", opt->uniform);
    for (size_t q = 0; q < count; ++q) {
        cj_status st = cj_patch_check(&patches[q]);
        if (st) return cj_fail(st, "patch %zu: %s", q, cj_last_error());
    }
    if (opt->uniform > 0) {
        *triangles = 2.0 * (double)opt->uniform * (double)opt->uniform * (double)count;
        return CJ_OK;
    }
    if (!isfinite(opt->tol)) return cj_fail(CJ_ERR_NONFINITE, "tolerance is not finite");
    if (!(opt->tol > 0.0)) return cj_fail(CJ_ERR_ARGUMENT, "tolerance %.17g must be > 0", opt->tol);
    cj_mesh *scratch = NULL;
    cj_status st = cj_mesh_create(NULL, &scratch);
    ptess *P = st ? NULL : malloc(sizeof *P);
    if (!P) {
        cj_mesh_destroy(scratch);
        return cj_fail(CJ_ERR_NOMEM, "out of memory");
    }
    double total = 0.0;
    for (size_t q = 0; q < count; ++q) {
        double rho_u[SLABS], rho_v[SLABS], bu, bv;
        ptess_setup(P, &patches[q], q, scratch, 0);
        patch_densities(P, opt->tol, rho_u, rho_v, &bu, &bv);
        /* the search starts here; its minimum is 2 x 2 cells */
        total += 2.0 * fmax(2.0, ceil(bu)) * fmax(2.0, ceil(bv));
    }
    free(P);
    cj_mesh_destroy(scratch);
    *triangles = total;
    return CJ_OK;
}

/* ---- parametric surfaces ------------------------------------------------------------- */

cj_status cj_tessellate_surface(const cj_param_surface *s, int nu, int nv, int32_t id,
                                cj_mesh *mesh, size_t *dropped) {
    assert(s != NULL && mesh != NULL);
    cj_status st = cj_param_surface_check(s);
    if (st) return st;
    const int pu = (s->flags & CJ_SURF_PERIODIC_U) != 0, pv = (s->flags & CJ_SURF_PERIODIC_V) != 0;
    if (nu < (pu ? 3 : 1) || nv < (pv ? 3 : 1))
        return cj_fail(CJ_ERR_ARGUMENT, "grid %d x %d too small (need >= %d x %d)", nu, nv,
                       pu ? 3 : 1, pv ? 3 : 1);
    const size_t nvert = (size_t)(nu + 1) * (size_t)(nv + 1);
    uint32_t *idx = t_alloc(mesh, sizeof(uint32_t) * nvert);
    if (!idx) return cj_fail(CJ_ERR_NOMEM, "out of memory tessellating a surface");
    const size_t v_start = mesh->vertex_count, t_start = mesh->triangle_count;
    const unsigned f = s->flags;
    size_t drop = 0;
    for (int j = 0; j <= nv; ++j)
        for (int i = 0; i <= nu; ++i) {
            int si = i, sj = j; /* the grid point whose vertex this one shares */
            if (pu && i == nu) si = 0;
            if (pv && j == nv) sj = 0;
            if ((f & CJ_SURF_COLLAPSED_V0) && sj == 0) si = 0;
            if ((f & CJ_SURF_COLLAPSED_V1) && sj == nv) si = 0;
            if ((f & CJ_SURF_COLLAPSED_U0) && si == 0) sj = 0;
            if ((f & CJ_SURF_COLLAPSED_U1) && si == nu) sj = 0;
            if (si != i || sj != j) {
                idx[j * (nu + 1) + i] = idx[sj * (nu + 1) + si];
                continue;
            }
            const double u = i == nu ? s->u1 : s->u0 + (s->u1 - s->u0) * ((double)i / nu);
            const double v = j == nv ? s->v1 : s->v0 + (s->v1 - s->v0) * ((double)j / nv);
            cj_vec3 p, n;
            if ((st = cj_surface_eval(s, u, v, &p, NULL, NULL))) goto fail;
            if ((st = cj_surface_normal(s, u, v, &n))) n = cj_v3(0.0, 0.0, 0.0);
            const double pos[3] = {p.x, p.y, p.z}, nrm[3] = {n.x, n.y, n.z}, uv[2] = {u, v};
            if ((st = cj_mesh_add_vertex(mesh, pos, nrm, uv, &idx[j * (nu + 1) + i]))) goto fail;
        }
    for (int j = 0; j < nv; ++j)
        for (int i = 0; i < nu; ++i) {
            const uint32_t A = idx[j * (nu + 1) + i], B = idx[j * (nu + 1) + i + 1],
                           C = idx[(j + 1) * (nu + 1) + i + 1], D = idx[(j + 1) * (nu + 1) + i];
            const uint32_t tri[2][3] = {{A, B, C}, {A, C, D}};
            for (int q = 0; q < 2; ++q) {
                const uint32_t a = tri[q][0], b = tri[q][1], c = tri[q][2];
                if (a == b || b == c || a == c ||
                    same_pos(mesh->positions + 3 * (size_t)a, mesh->positions + 3 * (size_t)b) ||
                    same_pos(mesh->positions + 3 * (size_t)b, mesh->positions + 3 * (size_t)c) ||
                    same_pos(mesh->positions + 3 * (size_t)a, mesh->positions + 3 * (size_t)c)) {
                    ++drop;
                    continue;
                }
                if ((st = cj_mesh_add_triangle(mesh, a, b, c, id))) goto fail;
            }
        }
    t_free(mesh, idx);
    if (dropped) *dropped = drop;
    return CJ_OK;
fail:
    t_free(mesh, idx);
    cj_mesh_truncate(mesh, v_start, t_start);
    return st;
}
