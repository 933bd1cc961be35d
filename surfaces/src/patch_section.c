/* Plane sections of Bézier patches: cells by exact halving, sign tests on the scalar Bézier
 * form of n . S - d, marching squares in the leaves, segments chained (patch_section.h). */
#include "casteljau/patch_section.h"
#include "error_internal.h"
#include "query_internal.h"

#include <assert.h>
#include <stdlib.h>
#include <string.h>

#define MAXP      (CJ_PATCH_SECTION_MAX_DEGREE + 1)
#define MIN_WIDTH 0x1p-40
#define MAX_LEVEL 84 /* 2 x 42 halvings: both sides below MIN_WIDTH */
#define MERGE_EPS 0x1p-40

/* A cell: parameters, rounding bounds, and per control point F then (w x, w y, w z, w). */
typedef struct cell {
    double u0, u1, v0, v1;
    double errF, err[4];
    int level;
    double c[MAXP * MAXP][5];
} cell;

typedef struct segment {
    double uv[2][2];
} segment;

typedef struct srun {
    const cj_patch *p;
    int m, n, rational;
    double nrm[3], d, tol;
    double magF, mag[4];
    double F[MAXP * MAXP]; /* coefficients of f for the whole patch (rounded) */
    segment *segs;
    long nsegs, capsegs;
    double *unres;
    int nunres, capunres;
    int ambiguous;
    long cells;
    double deviation;
    int nomem;
} srun;

/* ---- f and S at a parameter: one deterministic evaluation of the whole patch ------------ */

static double f_at(const srun *R, double u, double v) {
    int m = R->m, n = R->n;
    double col[MAXP], w[MAXP];
    for (int j = 0; j <= n; ++j) {
        for (int i = 0; i <= m; ++i) w[i] = R->F[j * (m + 1) + i];
        for (int r = m; r > 0; --r)
            for (int i = 0; i < r; ++i) w[i] = (1.0 - u) * w[i] + u * w[i + 1];
        col[j] = w[0];
    }
    for (int r = n; r > 0; --r)
        for (int i = 0; i < r; ++i) col[i] = (1.0 - v) * col[i] + v * col[i + 1];
    return col[0];
}

static int sgn(double f) {
    return f >= 0.0 ? 1 : -1;
}

/* The double in [a, b] where the sign of f along the edge changes (a and b have opposite
 * signs): plain bisection, deterministic for a given edge. along_u: the edge runs in u at
 * fixed v = fixed, else in v at u = fixed. */
static double edge_root(const srun *R, int along_u, double fixed, double a, double b) {
    int sa = sgn(along_u ? f_at(R, a, fixed) : f_at(R, fixed, a));
    for (int it = 0; it < 80; ++it) {
        double mid = 0.5 * (a + b);
        if (!(mid > a && mid < b)) break;
        int s = sgn(along_u ? f_at(R, mid, fixed) : f_at(R, fixed, mid));
        if (s == sa)
            a = mid;
        else
            b = mid;
    }
    return 0.5 * (a + b);
}

/* ---- cells --------------------------------------------------------------------------------- */

/* Halves c along u (dir 0) or v (dir 1) into lo and hi: de Casteljau at 1/2 on every row (or
 * column) of the five-component net; errors grow as in query_piece.c (n averagings of
 * magnitudes below mag, each off by u mag plus the halving's 2^-1075). */
static void halve(const srun *R, const cell *c, int dir, cell *lo, cell *hi) {
    int m = R->m, n = R->n;
    int len = dir == 0 ? m : n, lines = dir == 0 ? n + 1 : m + 1;
    int stride = dir == 0 ? 1 : m + 1, step = dir == 0 ? m + 1 : 1;
    double w[MAXP][5];
    for (int l = 0; l < lines; ++l) {
        int base = l * step;
        for (int i = 0; i <= len; ++i)
            for (int k = 0; k < 5; ++k) w[i][k] = c->c[base + i * stride][k];
        for (int k = 0; k < 5; ++k) lo->c[base][k] = w[0][k];
        for (int r = len; r > 0; --r) {
            for (int i = 0; i < r; ++i)
                for (int k = 0; k < 5; ++k) w[i][k] = 0.5 * (w[i][k] + w[i + 1][k]);
            for (int k = 0; k < 5; ++k) lo->c[base + (len - r + 1) * stride][k] = w[0][k];
        }
        for (int i = 0; i <= len; ++i)
            for (int k = 0; k < 5; ++k) hi->c[base + i * stride][k] = w[i][k];
    }
    double grow = (double)len;
    lo->errF = hi->errF =
        (c->errF + grow * ((R->magF + c->errF) * 0x1p-53 + 0x1p-1074)) * (1.0 + 0x1p-40);
    for (int k = 0; k < 4; ++k) {
        double e =
            (c->err[k] + grow * ((R->mag[k] + c->err[k]) * 0x1p-53 + 0x1p-1074)) * (1.0 + 0x1p-40);
        lo->err[k] = hi->err[k] = (k == 3 && !R->rational) ? 0.0 : e;
    }
    lo->u0 = c->u0, lo->u1 = c->u1, lo->v0 = c->v0, lo->v1 = c->v1;
    hi->u0 = c->u0, hi->u1 = c->u1, hi->v0 = c->v0, hi->v1 = c->v1;
    if (dir == 0) {
        double mid = 0.5 * (c->u0 + c->u1);
        lo->u1 = hi->u0 = mid;
    } else {
        double mid = 0.5 * (c->v0 + c->v1);
        lo->v1 = hi->v0 = mid;
    }
    lo->level = hi->level = c->level + 1;
}

/* 1 if every F coefficient has one proven sign (no point of the section in the cell). */
static int one_sign(const srun *R, const cell *c) {
    int cnt = (R->m + 1) * (R->n + 1), pos = 0, neg = 0;
    double e = c->errF;
    for (int i = 0; i < cnt; ++i) {
        if (c->c[i][0] > e)
            ++pos;
        else if (c->c[i][0] < -e)
            ++neg;
        else
            return 0;
        if (pos && neg) return 0;
    }
    return 1;
}

/* Box of the cell's control points (outward rounded): every point of the sub-patch lies in
 * it. Returns its diagonal (+inf if a weight enclosure reaches zero). */
static double cell_box(const srun *R, const cell *c, double lo[3], double hi[3]) {
    int cnt = (R->m + 1) * (R->n + 1);
    for (int k = 0; k < 3; ++k) lo[k] = INFINITY, hi[k] = -INFINITY;
    for (int i = 0; i < cnt; ++i) {
        cj_ivl W = cj_iv2(cj_down(c->c[i][4] - c->err[3]), cj_up(c->c[i][4] + c->err[3]));
        if (!(W.lo > 0.0)) return INFINITY;
        for (int k = 0; k < 3; ++k) {
            cj_ivl X =
                cj_iv2(cj_down(c->c[i][1 + k] - c->err[k]), cj_up(c->c[i][1 + k] + c->err[k]));
            cj_ivl x = R->rational ? cj_idiv(X, W) : X;
            lo[k] = fmin(lo[k], x.lo);
            hi[k] = fmax(hi[k], x.hi);
        }
    }
    double dx = cj_up(hi[0] - lo[0]), dy = cj_up(hi[1] - lo[1]), dz = cj_up(hi[2] - lo[2]);
    return cj_up(sqrt(cj_up(cj_up(cj_up(dx * dx) + cj_up(dy * dy)) + cj_up(dz * dz))));
}

static void add_segment(srun *R, const double a[2], const double b[2]) {
    if (R->nsegs == R->capsegs) {
        long cap = R->capsegs ? 2 * R->capsegs : 256;
        segment *s = realloc(R->segs, (size_t)cap * sizeof *s);
        if (!s) {
            R->nomem = 1;
            return;
        }
        R->segs = s;
        R->capsegs = cap;
    }
    segment *s = &R->segs[R->nsegs++];
    s->uv[0][0] = a[0], s->uv[0][1] = a[1];
    s->uv[1][0] = b[0], s->uv[1][1] = b[1];
}

static void add_unresolved(srun *R, double u, double v) {
    if (R->nunres == R->capunres) {
        int cap = R->capunres ? 2 * R->capunres : 16;
        double *s = realloc(R->unres, (size_t)cap * 3 * sizeof *s);
        if (!s) {
            R->nomem = 1;
            return;
        }
        R->unres = s;
        R->capunres = cap;
    }
    double pt[3];
    if (cj_patch_eval(R->p, CJ_EVAL_DECASTELJAU, u, v, pt) != CJ_OK) pt[0] = pt[1] = pt[2] = NAN;
    memcpy(R->unres + 3 * R->nunres++, pt, sizeof pt);
}

/* Marching squares in a leaf: corners c0 (u0,v0), c1 (u1,v0), c2 (u1,v1), c3 (u0,v1); edge k
 * joins corner k and k+1. */
static void leaf(srun *R, const cell *c) {
    double cu[4] = {c->u0, c->u1, c->u1, c->u0}, cv[4] = {c->v0, c->v0, c->v1, c->v1};
    int s[4];
    for (int k = 0; k < 4; ++k) s[k] = sgn(f_at(R, cu[k], cv[k]));
    double x[4][2];
    int crossed[4], nc = 0;
    for (int k = 0; k < 4; ++k) {
        int k1 = (k + 1) & 3;
        crossed[k] = s[k] != s[k1];
        if (!crossed[k]) continue;
        ++nc;
        if (k == 0 || k == 2) { /* along u at v = cv[k] */
            double r = edge_root(R, 1, cv[k], c->u0, c->u1);
            x[k][0] = r, x[k][1] = cv[k];
        } else {
            double r = edge_root(R, 0, cu[k], c->v0, c->v1);
            x[k][0] = cu[k], x[k][1] = r;
        }
    }
    if (nc == 0) {
        add_unresolved(R, 0.5 * (c->u0 + c->u1), 0.5 * (c->v0 + c->v1));
        return;
    }
    if (nc == 2) {
        int a = -1, b = -1;
        for (int k = 0; k < 4; ++k)
            if (crossed[k]) {
                if (a < 0)
                    a = k;
                else
                    b = k;
            }
        add_segment(R, x[a], x[b]);
        return;
    }
    /* four crossings: s0 = s2 != s1 = s3 */
    ++R->ambiguous;
    int sc = sgn(f_at(R, 0.5 * (c->u0 + c->u1), 0.5 * (c->v0 + c->v1)));
    if (sc == s[0]) { /* c0 and c2 joined through the centre: cut off c1 and c3 */
        add_segment(R, x[0], x[1]);
        add_segment(R, x[2], x[3]);
    } else {
        add_segment(R, x[3], x[0]);
        add_segment(R, x[1], x[2]);
    }
}

/* Depth first over an explicit stack of cells (two per level at most are pending). */
static cj_status walk(srun *R, cell *stack) {
    int top = 1;
    while (top > 0 && !R->nomem) {
        cell *c = &stack[--top];
        if (++R->cells > CJ_PATCH_SECTION_MAX_CELLS)
            return cj_fail(CJ_ERR_CAP,
                           "plane section: more than %ld cells (tol too small for "
                           "the patch?)",
                           CJ_PATCH_SECTION_MAX_CELLS);
        if (one_sign(R, c)) continue;
        double lo[3], hi[3];
        double diag = cell_box(R, c, lo, hi);
        int can_u = c->u1 - c->u0 > MIN_WIDTH, can_v = c->v1 - c->v0 > MIN_WIDTH;
        if (diag <= R->tol || (!can_u && !can_v) || c->level >= MAX_LEVEL) {
            R->deviation = fmax(R->deviation, diag);
            leaf(R, c);
            continue;
        }
        /* split the side that is longer in space: the sum of the two edge chords */
        int m = R->m, n = R->n, dir;
        if (!can_u || !can_v) {
            dir = can_u ? 0 : 1;
        } else {
            double lu = 0.0, lv = 0.0;
            int c00 = 0, c10 = m, c01 = n * (m + 1), c11 = n * (m + 1) + m;
            for (int k = 1; k <= 3; ++k) {
                double w00 = c->c[c00][4], w10 = c->c[c10][4], w01 = c->c[c01][4],
                       w11 = c->c[c11][4];
                lu += fabs(c->c[c10][k] / w10 - c->c[c00][k] / w00) +
                      fabs(c->c[c11][k] / w11 - c->c[c01][k] / w01);
                lv += fabs(c->c[c01][k] / w01 - c->c[c00][k] / w00) +
                      fabs(c->c[c11][k] / w11 - c->c[c10][k] / w10);
            }
            dir = lu >= lv ? 0 : 1;
        }
        cell tmp = *c;
        halve(R, &tmp, dir, &stack[top], &stack[top + 1]);
        top += 2;
    }
    return R->nomem ? cj_fail(CJ_ERR_NOMEM, "plane section: segment list") : CJ_OK;
}

/* ---- chaining ------------------------------------------------------------------------------ */

typedef struct endref {
    double u, v;
    long id; /* 2 * segment + end */
} endref;

static int cmp_end(const void *a, const void *b) {
    const endref *x = a, *y = b;
    if (x->u != y->u) return x->u < y->u ? -1 : 1;
    if (x->v != y->v) return x->v < y->v ? -1 : 1;
    return (x->id > y->id) - (x->id < y->id);
}

static long find(long *parent, long x) {
    while (parent[x] != x) {
        parent[x] = parent[parent[x]];
        x = parent[x];
    }
    return x;
}

/* Chains the segments into polylines: ends within MERGE_EPS of each other in both parameters
 * (the same crossing found from two cells) are one vertex. */
static cj_status chain(srun *R, cj_patch_section *out) {
    long ns = R->nsegs, ne = 2 * ns;
    endref *ends = malloc((size_t)(ne ? ne : 1) * sizeof *ends);
    long *parent = malloc((size_t)(ne ? ne : 1) * sizeof *parent);
    long *vid = malloc((size_t)(ne ? ne : 1) * sizeof *vid);
    long *deg = NULL, *adj = NULL, *adjstart = NULL;
    unsigned char *used = malloc((size_t)(ns ? ns : 1));
    cj_status st = CJ_OK;
    if (!ends || !parent || !vid || !used) goto nomem;
    for (long i = 0; i < ne; ++i) {
        ends[i].u = R->segs[i / 2].uv[i % 2][0];
        ends[i].v = R->segs[i / 2].uv[i % 2][1];
        ends[i].id = i;
        parent[i] = i;
    }
    qsort(ends, (size_t)ne, sizeof *ends, cmp_end);
    for (long i = 0; i < ne; ++i)
        for (long j = i + 1; j < ne && ends[j].u - ends[i].u <= MERGE_EPS; ++j)
            if (fabs(ends[j].v - ends[i].v) <= MERGE_EPS) {
                long a = find(parent, ends[i].id), b = find(parent, ends[j].id);
                if (a != b) parent[a] = b;
            }
    /* vertex ids: the roots, numbered */
    long nv = 0;
    for (long i = 0; i < ne; ++i) vid[i] = -1;
    long *rootid = malloc((size_t)(ne ? ne : 1) * sizeof *rootid);
    if (!rootid) goto nomem;
    for (long i = 0; i < ne; ++i) rootid[i] = -1;
    for (long i = 0; i < ne; ++i) {
        long r = find(parent, i);
        if (rootid[r] < 0) rootid[r] = nv++;
        vid[i] = rootid[r];
    }
    free(rootid);
    deg = calloc((size_t)(nv + 1), sizeof *deg);
    adjstart = calloc((size_t)(nv + 1), sizeof *adjstart);
    adj = malloc((size_t)(ne ? ne : 1) * sizeof *adj);
    if (!deg || !adjstart || !adj) goto nomem;
    for (long i = 0; i < ne; ++i) ++deg[vid[i]];
    for (long v = 0; v < nv; ++v) adjstart[v + 1] = adjstart[v] + deg[v];
    {
        long *fill = calloc((size_t)(nv + 1), sizeof *fill);
        if (!fill) goto nomem;
        for (long i = 0; i < ne; ++i) {
            long v = vid[i];
            adj[adjstart[v] + fill[v]++] = i / 2; /* the segment */
        }
        free(fill);
    }
    memset(used, 0, (size_t)(ns ? ns : 1));
    /* output: at most ne points (each segment adds one point to its chain, plus starts) */
    out->pts = malloc((size_t)(ne + 1) * 3 * sizeof(double));
    out->uv = malloc((size_t)(ne + 1) * 2 * sizeof(double));
    out->starts = malloc((size_t)(ns + 2) * sizeof(int));
    out->closed = malloc((size_t)(ns + 1));
    if (!out->pts || !out->uv || !out->starts || !out->closed) goto nomem;
    int np = 0, nl = 0;
    out->starts[0] = 0;
    /* two passes: chains from vertices of degree != 2 (open ends, branch points), then cycles */
    for (int pass = 0; pass < 2; ++pass)
        for (long s0 = 0; s0 < ns; ++s0) {
            if (used[s0]) continue;
            long end0 = 2 * s0, v0 = vid[end0];
            if (pass == 0) {
                /* start only at an end of degree != 2 */
                if (deg[vid[2 * s0]] != 2)
                    end0 = 2 * s0;
                else if (deg[vid[2 * s0 + 1]] != 2)
                    end0 = 2 * s0 + 1;
                else
                    continue;
                v0 = vid[end0];
            }
            /* walk: from end0's vertex along s0 */
            long seg = s0, at = end0;
            double *uvs = R->segs[seg].uv[at % 2];
            out->uv[2 * np] = uvs[0], out->uv[2 * np + 1] = uvs[1];
            ++np;
            int closed = 0;
            for (;;) {
                used[seg] = 1;
                long other = 2 * seg + 1 - at % 2;
                long v = vid[other];
                if (pass == 1 && v == v0) {
                    closed = 1;
                    break;
                }
                const double *ouv = R->segs[seg].uv[other % 2];
                out->uv[2 * np] = ouv[0], out->uv[2 * np + 1] = ouv[1];
                ++np;
                if (deg[v] != 2) break;
                long next = -1;
                for (long k = adjstart[v]; k < adjstart[v + 1]; ++k)
                    if (!used[adj[k]]) next = adj[k];
                if (next < 0) {
                    if (v == v0) { /* back at the start through the last segment */
                        --np;
                        closed = 1;
                    }
                    break;
                }
                at = vid[2 * next] == v ? 2 * next : 2 * next + 1;
                seg = next;
            }
            out->closed[nl] = (unsigned char)closed;
            out->starts[++nl] = np;
        }
    out->npts = np;
    out->nlines = nl;
    for (int i = 0; i < np; ++i)
        if (cj_patch_eval(R->p, CJ_EVAL_DECASTELJAU, out->uv[2 * i], out->uv[2 * i + 1],
                          out->pts + 3 * i) != CJ_OK)
            out->pts[3 * i] = out->pts[3 * i + 1] = out->pts[3 * i + 2] = NAN;
    goto done;
nomem:
    st = cj_fail(CJ_ERR_NOMEM, "plane section: chaining %ld segments", ns);
done:
    free(ends);
    free(parent);
    free(vid);
    free(used);
    free(deg);
    free(adj);
    free(adjstart);
    return st;
}

/* ---- entry --------------------------------------------------------------------------------- */

void cj_patch_section_free(cj_patch_section *s) {
    if (!s) return;
    free(s->pts);
    free(s->uv);
    free(s->starts);
    free(s->closed);
    free(s->unresolved);
    memset(s, 0, sizeof *s);
}

cj_status cj_patch_section_plane(const cj_patch *p, const double n[3], double d, double tol,
                                 cj_patch_section *out) {
    assert(p && n && out);
    memset(out, 0, sizeof *out);
    cj_status st = cj_patch_check(p);
    if (st != CJ_OK) return st;
    if (p->deg_u > CJ_PATCH_SECTION_MAX_DEGREE || p->deg_v > CJ_PATCH_SECTION_MAX_DEGREE)
        return cj_fail(CJ_ERR_DEGREE, "plane section: patch degree %d,%d above %d", p->deg_u,
                       p->deg_v, CJ_PATCH_SECTION_MAX_DEGREE);
    for (int k = 0; k < 3; ++k)
        if (!isfinite(n[k]))
            return cj_fail(CJ_ERR_NONFINITE, "plane normal component %d is not finite", k);
    if (!isfinite(d)) return cj_fail(CJ_ERR_NONFINITE, "plane offset d is not finite");
    if (n[0] == 0.0 && n[1] == 0.0 && n[2] == 0.0)
        return cj_fail(CJ_ERR_DEGENERATE, "plane normal is (0, 0, 0)");
    srun *R = calloc(1, sizeof *R);
    if (!R) return cj_fail(CJ_ERR_NOMEM, "plane section work space");
    R->p = p;
    R->m = p->deg_u;
    R->n = p->deg_v;
    R->rational = p->weights != NULL;
    R->d = d;
    R->tol = tol;
    for (int k = 0; k < 3; ++k) R->nrm[k] = n[k];
    int cnt = (p->deg_u + 1) * (p->deg_v + 1);
    double scale = 0.0;
    for (int i = 0; i < 3 * cnt; ++i) scale = fmax(scale, fabs(p->pts[i]));
    cell *stack = NULL;
    if (!isfinite(tol) || !(tol > 0.0) || tol < scale * 0x1p-36) {
        st = cj_fail(CJ_ERR_ARGUMENT,
                     "plane section: tol %g must be finite, > 0 and at least %g (2^-36 times "
                     "the patch's size %g)",
                     tol, scale * 0x1p-36, scale);
        goto done;
    }
    stack = malloc((size_t)(2 * MAX_LEVEL + 4) * sizeof *stack);
    if (!stack) {
        st = cj_fail(CJ_ERR_NOMEM, "plane section work space");
        goto done;
    }
    /* the root cell: F_ij = w_ij (n . b_ij - d) rounded, with one bound for all of them:
     * n . b - d is three products and three sums (off by at most 4u (|n||b| + |d|)), times w
     * one more rounding */
    cell *c = &stack[0];
    c->u0 = c->v0 = 0.0;
    c->u1 = c->v1 = 1.0;
    c->level = 0;
    double eF = 0.0;
    for (int i = 0; i < cnt; ++i) {
        const double *b = p->pts + 3 * i;
        double w = R->rational ? p->weights[i] : 1.0;
        double f = n[0] * b[0] + n[1] * b[1] + n[2] * b[2] - d;
        double mag = fabs(n[0] * b[0]) + fabs(n[1] * b[1]) + fabs(n[2] * b[2]) + fabs(d);
        c->c[i][0] = R->F[i] = w * f;
        eF = fmax(eF, w * mag * 0x1.4p-51);
        for (int k = 0; k < 3; ++k) c->c[i][1 + k] = w * b[k];
        c->c[i][4] = w;
    }
    if (!isfinite(eF)) {
        st = cj_fail(CJ_ERR_RANGE, "plane section: n . b - d overflows");
        goto done;
    }
    c->errF = eF * (1.0 + 0x1p-40) + 0x1p-1070;
    c->err[0] = c->err[1] = c->err[2] = 0.0;
    c->err[3] = 0.0;
    if (R->rational) /* w b rounded once */
        for (int i = 0; i < cnt; ++i)
            for (int k = 0; k < 3; ++k)
                c->err[k] = fmax(c->err[k], fabs(c->c[i][1 + k]) * 0x1p-52 + 0x1p-1074);
    R->magF = 0.0;
    for (int k = 0; k < 4; ++k) R->mag[k] = 0.0;
    for (int i = 0; i < cnt; ++i) {
        R->magF = fmax(R->magF, fabs(c->c[i][0]));
        for (int k = 0; k < 4; ++k) R->mag[k] = fmax(R->mag[k], fabs(c->c[i][1 + k]));
    }
    if ((st = walk(R, stack)) != CJ_OK) goto done;
    if ((st = chain(R, out)) != CJ_OK) {
        cj_patch_section_free(out);
        goto done;
    }
    out->unresolved = R->unres;
    R->unres = NULL;
    out->nunresolved = R->nunres;
    out->ambiguous = R->ambiguous;
    out->cells = R->cells;
    out->deviation = R->deviation;
    double nn = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (int i = 0; i < out->npts; ++i) {
        const double *x = out->pts + 3 * i;
        double g = fabs(n[0] * x[0] + n[1] * x[1] + n[2] * x[2] - d) / nn;
        out->plane_gap = fmax(out->plane_gap, g);
    }
done:
    free(stack);
    free(R->segs);
    free(R->unres);
    free(R);
    return st;
}
