/* Tessellation of Bézier patches (uniform / adaptive with a proven bound, watertight) and of
 * parametric surfaces. See tessellate.h for the rules and the proof of the bound. */
#include "casteljau/tessellate.h"
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

/* Norm of a difference vector inflated by 8u times the magnitude of its terms (covers the
 * rounding of the difference and of the norm). */
static double diff_norm(const double d[3], const double mag[3]) {
    double e2 = 0.0;
    for (int k = 0; k < 3; ++k) {
        const double e = fabs(d[k]) + 8.0 * U_ROUND * mag[k];
        e2 += e * e;
    }
    return sqrt(e2) * (1.0 + 4.0 * U_ROUND);
}

/* Second-derivative bounds of a polynomial net (dimension 3) of degree (m,n) over [0,1]^2. */
static dbounds net_bounds(const double *h, int m, int n) {
    dbounds b = {0.0, 0.0, 0.0};
    const int m1 = m + 1;
#define P(i, j) (h + 3 * ((j)*m1 + (i)))
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= m; ++i) {
            double d[3], mag[3];
            if (i + 2 <= m) {
                for (int k = 0; k < 3; ++k) {
                    d[k] = (P(i + 2, j)[k] - 2.0 * P(i + 1, j)[k]) + P(i, j)[k];
                    mag[k] = fabs(P(i + 2, j)[k]) + 2.0 * fabs(P(i + 1, j)[k]) + fabs(P(i, j)[k]);
                }
                const double x = diff_norm(d, mag);
                if (x > b.uu) b.uu = x;
            }
            if (j + 2 <= n) {
                for (int k = 0; k < 3; ++k) {
                    d[k] = (P(i, j + 2)[k] - 2.0 * P(i, j + 1)[k]) + P(i, j)[k];
                    mag[k] = fabs(P(i, j + 2)[k]) + 2.0 * fabs(P(i, j + 1)[k]) + fabs(P(i, j)[k]);
                }
                const double x = diff_norm(d, mag);
                if (x > b.vv) b.vv = x;
            }
            if (i + 1 <= m && j + 1 <= n) {
                for (int k = 0; k < 3; ++k) {
                    d[k] = (P(i + 1, j + 1)[k] - P(i + 1, j)[k]) - (P(i, j + 1)[k] - P(i, j)[k]);
                    mag[k] = fabs(P(i + 1, j + 1)[k]) + fabs(P(i + 1, j)[k]) +
                             fabs(P(i, j + 1)[k]) + fabs(P(i, j)[k]);
                }
                const double x = diff_norm(d, mag);
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
        const double x = diff_norm(d, mag);
        if (x > mx) mx = x;
    }
    const double m2 = mx * (double)degree * (double)(degree - 1);
    if (m2 == 0.0) return 1;
    const double k = ceil(sqrt(m2 / (8.0 * tol)));
    if (!(k <= (double)cap)) return cap + 1;
    return k < 1.0 ? 1 : (int)k;
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
    edge_info e[4];
    cj_mesh *mesh;
    int measure;
    /* results of one build */
    double bound, measured;
    double worst_terms[3]; /* uu, uv, vv contributions of the worst triangle */
    size_t dropped;
    /* strip bounds, rescaled to the patch's parameters */
    dbounds *row; /* nv entries */
    dbounds col0, col1;
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
    if (cj_patch_normal_unchecked(P->p, P->h, P->hd, u, v, nrm, NULL) != CJ_OK)
        nrm[0] = nrm[1] = nrm[2] = 0.0; /* a patch collapsed to a curve: no normal */
    return cj_mesh_add_vertex(P->mesh, pos, nrm, uv, idx);
}

static int same_pos(const double *a, const double *b) {
    return a[0] == b[0] && a[1] == b[1] && a[2] == b[2];
}

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
    if (!P->rational) {
        const double du = fmax(fmax(ua[0], ub[0]), uc[0]) - fmin(fmin(ua[0], ub[0]), uc[0]);
        const double dv = fmax(fmax(ua[1], ub[1]), uc[1]) - fmin(fmin(ua[1], ub[1]), uc[1]);
        const double t0 = db->uu * du * du, t1 = 2.0 * db->uv * du * dv, t2 = db->vv * dv * dv;
        const double bnd = (t0 + t1 + t2) * 0.125 * (1.0 + 8.0 * U_ROUND) + P->evalerr;
        if (bnd > P->bound) {
            P->bound = bnd;
            P->worst_terms[0] = t0;
            P->worst_terms[1] = t1;
            P->worst_terms[2] = t2;
        }
    }
    const double *pa = M->positions + 3 * (size_t)a, *pb = M->positions + 3 * (size_t)b,
                 *pc = M->positions + 3 * (size_t)c;
    if (P->measure > 0) {
        const int L = P->measure;
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
                const double dev = sqrt(d2);
                if (dev > P->measured) P->measured = dev;
            }
    }
    if (same_pos(pa, pb) || same_pos(pb, pc) || same_pos(pa, pc)) {
        ++P->dropped;
        return CJ_OK;
    }
    return cj_mesh_add_triangle(M, a, b, c, P->id);
}

/* Sub-net bounds over [u0,u1]x[v0,v1], rescaled to the patch's parameters. */
static dbounds strip_bounds(const ptess *P, double u0, double u1, double v0, double v1) {
    double sub[CJ_PATCH_NET_MAX];
    cj_patch_sub_h(P->h, P->hd, P->m, P->n, u0, u1, v0, v1, sub);
    dbounds b = net_bounds(sub, P->m, P->n);
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

/* Zipper between outer points o[0..k] (side parameters a/k) and inner points in[0..L] with
 * side parameters tin[0..L]. */
static cj_status zipper(ptess *P, const uint32_t *o, int k, const uint32_t *in, const double *tin,
                        int L, const dbounds *db) {
    int a = 0, b = 0;
    while (a < k || b < L) {
        int adv_outer;
        if (a == k)
            adv_outer = 0;
        else if (b == L)
            adv_outer = 1;
        else
            adv_outer = ((double)a + 0.5) / (double)k < 0.5 * (tin[b] + tin[b + 1]);
        cj_status st;
        if (adv_outer) {
            st = add_tri(P, o[a], o[a + 1], in[b], db);
            ++a;
        } else {
            st = add_tri(P, o[a], in[b + 1], in[b], db);
            ++b;
        }
        if (st) return st;
    }
    return CJ_OK;
}

/* One build of a patch with grid nu x nv and edge counts k[4]. */
static cj_status build_patch(ptess *P, int nu, int nv, const int k[4]) {
    const int m = P->m, n = P->n;
    cj_status st = CJ_OK;
    P->bound = 0.0;
    P->measured = 0.0;
    P->dropped = 0;
    P->worst_terms[0] = P->worst_terms[1] = P->worst_terms[2] = 0.0;
    const int regular = k[0] == nu && k[2] == nu && k[1] == nv && k[3] == nv;
    size_t nouter = (size_t)(k[0] + k[1] + k[2] + k[3] + 4);
    size_t ngrid = (size_t)(nu + 1) * (size_t)(nv + 1);
    uint32_t *buf = malloc(sizeof(uint32_t) * (nouter + ngrid));
    double *tin = malloc(sizeof(double) * (size_t)(nu > nv ? nu : nv) + sizeof(double));
    uint32_t *inner = malloc(sizeof(uint32_t) * (size_t)(nu > nv ? nu : nv) + sizeof(uint32_t));
    P->row = malloc(sizeof(dbounds) * (size_t)nv);
    if (!buf || !tin || !inner || !P->row) {
        st = cj_fail(CJ_ERR_NOMEM, "out of memory tessellating patch %d", (int)P->id);
        goto done;
    }
    if (!P->rational) {
        for (int j = 0; j < nv; ++j)
            P->row[j] = strip_bounds(P, 0.0, 1.0, (double)j / nv, (double)(j + 1) / nv);
        P->col0 = strip_bounds(P, 0.0, 1.0 / nu, 0.0, 1.0);
        P->col1 = strip_bounds(P, (double)(nu - 1) / nu, 1.0, 0.0, 1.0);
    }
    uint32_t *o[4];
    o[0] = buf;
    for (int s = 1; s < 4; ++s) o[s] = o[s - 1] + k[s - 1] + 1;
    uint32_t *g = buf + nouter; /* grid indices, (j*(nu+1)+i) */
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
            const double t = (double)a / k[s];
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
            const double u = (double)i / nu, v = (double)j / nv;
            eval_point(P, u, v, pos);
            if ((st = add_vertex(P, pos, u, v, &g[j * (nu + 1) + i]))) goto done;
        }
    static const dbounds zero = {0.0, 0.0, 0.0};
    if (regular) {
        for (int i = 0; i <= nu; ++i) {
            g[i] = o[0][i];
            g[nv * (nu + 1) + i] = o[2][i];
        }
        for (int j = 0; j <= nv; ++j) {
            g[j * (nu + 1)] = o[3][j];
            g[j * (nu + 1) + nu] = o[1][j];
        }
        for (int j = 0; j < nv; ++j)
            for (int i = 0; i < nu; ++i) {
                const dbounds *db = P->rational ? &zero : &P->row[j];
                const uint32_t A = g[j * (nu + 1) + i], B = g[j * (nu + 1) + i + 1],
                               C = g[(j + 1) * (nu + 1) + i + 1], D = g[(j + 1) * (nu + 1) + i];
                if ((st = add_tri(P, A, B, C, db))) goto done;
                if ((st = add_tri(P, A, C, D, db))) goto done;
            }
    } else {
        assert(nu >= 2 && nv >= 2);
        /* bottom: inner row j=1, i=1..nu-1 */
        int L = nu - 2;
        for (int i = 1; i < nu; ++i) {
            inner[i - 1] = g[1 * (nu + 1) + i];
            tin[i - 1] = (double)i / nu;
        }
        if ((st = zipper(P, o[0], k[0], inner, tin, L, P->rational ? &zero : &P->row[0])))
            goto done;
        for (int i = 1; i < nu; ++i) inner[i - 1] = g[(nv - 1) * (nu + 1) + i];
        if ((st = zipper(P, o[2], k[2], inner, tin, L, P->rational ? &zero : &P->row[nv - 1])))
            goto done;
        L = nv - 2;
        for (int j = 1; j < nv; ++j) {
            inner[j - 1] = g[j * (nu + 1) + 1];
            tin[j - 1] = (double)j / nv;
        }
        if ((st = zipper(P, o[3], k[3], inner, tin, L, P->rational ? &zero : &P->col0))) goto done;
        for (int j = 1; j < nv; ++j) inner[j - 1] = g[j * (nu + 1) + nu - 1];
        if ((st = zipper(P, o[1], k[1], inner, tin, L, P->rational ? &zero : &P->col1))) goto done;
        for (int j = 1; j + 1 < nv; ++j)
            for (int i = 1; i + 1 < nu; ++i) {
                const dbounds *db = P->rational ? &zero : &P->row[j];
                const uint32_t A = g[j * (nu + 1) + i], B = g[j * (nu + 1) + i + 1],
                               C = g[(j + 1) * (nu + 1) + i + 1], D = g[(j + 1) * (nu + 1) + i];
                if ((st = add_tri(P, A, B, C, db))) goto done;
                if ((st = add_tri(P, A, C, D, db))) goto done;
            }
    }
    if (P->rational) P->bound = INFINITY;
done:
    free(buf);
    free(tin);
    free(inner);
    free(P->row);
    P->row = NULL;
    return st;
}

static int ceil_grow(int x) {
    const int y = (int)ceil(x * 1.25);
    return y > x ? y : x + 1;
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
        if (patches[q].weights && opt->uniform == 0)
            return cj_fail(CJ_ERR_UNSUPPORTED,
                           "patch %zu is rational: adaptive tessellation has no proven bound for "
                           "rational patches (use uniform mode)",
                           q);
    }
    ptess *P = malloc(sizeof *P);
    if (!P) return cj_fail(CJ_ERR_NOMEM, "out of memory");
    const size_t v_start = mesh->vertex_count, t_start = mesh->triangle_count;
    cj_status st = CJ_OK;
    for (size_t q = 0; q < count && !st; ++q) {
        const cj_patch *p = &patches[q];
        memset(P, 0, sizeof *P);
        P->p = p;
        P->id = (int32_t)q;
        P->m = p->deg_u;
        P->n = p->deg_v;
        P->hd = cj_patch_load_h(p, P->h);
        P->rational = p->weights != NULL;
        P->mesh = mesh;
        P->measure = opt->measure;
        double mx = 0.0;
        for (size_t i = 0; i < 3 * cj_patch_point_count(p); ++i) mx = fmax(mx, fabs(p->pts[i]));
        /* vertex rounding (de Casteljau) plus the sample's own rounding, in 3D norm */
        P->evalerr = 2.0 * cj_gamma(3 * (P->m + P->n) + 4) * mx * sqrt(3.0);
        for (int s = 0; s < 4; ++s) edge_setup(p, s, &P->e[s]);
        int k[4], nu, nv;
        if (opt->uniform > 0) {
            nu = nv = opt->uniform;
            for (int s = 0; s < 4; ++s) k[s] = opt->uniform;
            st = build_patch(P, nu, nv, k);
        } else {
            const double tol = opt->tol;
            int ke[4];
            for (int s = 0; s < 4; ++s) {
                ke[s] = P->e[s].collapsed
                            ? 0
                            : cj_tess_edge_segments(P->e[s].pts, P->e[s].degree, 0.25 * tol, cap);
                if (ke[s] > cap) {
                    st = cj_fail(CJ_ERR_CAP,
                                 "patch %zu, edge %d needs more than %d segments for "
                                 "tolerance %.3g",
                                 q, s, cap, tol);
                    break;
                }
            }
            if (st) break;
            const dbounds gb = net_bounds(P->h, P->m, P->n);
            const double rho = (gb.uu > 0.0 && gb.vv > 0.0) ? gb.uv / sqrt(gb.uu * gb.vv) : 0.0;
            const double a = sqrt(4.0 * tol / (1.0 + rho));
            nu = (int)fmin(ceil(sqrt(gb.uu) / a), (double)cap + 1.0);
            nv = (int)fmin(ceil(sqrt(gb.vv) / a), (double)cap + 1.0);
            if (nu < 1) nu = 1;
            if (nv < 1) nv = 1;
            while ((gb.uu / ((double)nu * nu) + 2.0 * gb.uv / ((double)nu * nv) +
                    gb.vv / ((double)nv * nv)) *
                           0.125 >
                       tol &&
                   nu <= cap && nv <= cap) {
                if (gb.uu / ((double)nu * nu) >= gb.vv / ((double)nv * nv))
                    nu = ceil_grow(nu);
                else
                    nv = ceil_grow(nv);
            }
            for (int iter = 0;; ++iter) {
                for (int s = 0; s < 4; ++s) k[s] = P->e[s].collapsed ? ((s & 1) ? nv : nu) : ke[s];
                const int regular = k[0] == nu && k[2] == nu && k[1] == nv && k[3] == nv;
                if (!regular) {
                    if (nu < 2) nu = 2;
                    if (nv < 2) nv = 2;
                    for (int s = 0; s < 4; ++s)
                        k[s] = P->e[s].collapsed ? ((s & 1) ? nv : nu) : ke[s];
                }
                if (nu > cap || nv > cap) {
                    st = cj_fail(CJ_ERR_CAP,
                                 "patch %zu needs more than %d segments per direction "
                                 "for tolerance %.3g",
                                 q, cap, tol);
                    break;
                }
                const size_t vs = mesh->vertex_count, ts = mesh->triangle_count;
                if ((st = build_patch(P, nu, nv, k))) break;
                if (P->bound <= tol) break;
                cj_mesh_truncate(mesh, vs, ts);
                const double *w = P->worst_terms;
                const int grow_u = w[0] >= w[2] || iter >= 4 || w[1] > w[0] + w[2];
                const int grow_v = w[2] >= w[0] || iter >= 4 || w[1] > w[0] + w[2];
                if (grow_u) nu = ceil_grow(nu);
                if (grow_v) nv = ceil_grow(nv);
            }
        }
        if (st) break;
        if (P->bound > rep.bound || isinf(P->bound)) rep.bound = fmax(rep.bound, P->bound);
        if (opt->measure > 0 && P->measured > rep.measured) rep.measured = P->measured;
        rep.dropped += P->dropped;
        if (nu > rep.max_nu) rep.max_nu = nu;
        if (nv > rep.max_nv) rep.max_nv = nv;
    }
    free(P);
    rep.vertices = mesh->vertex_count - v_start;
    rep.triangles = mesh->triangle_count - t_start;
    if (report) *report = rep;
    return st;
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
    uint32_t *idx = malloc(sizeof(uint32_t) * nvert);
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
    free(idx);
    if (dropped) *dropped = drop;
    return CJ_OK;
fail:
    free(idx);
    cj_mesh_truncate(mesh, v_start, t_start);
    return st;
}
