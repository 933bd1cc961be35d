/* The section of a model by a plane: each patch's polylines (patch_section.c) joined across
 * shared patch edges into chains, every run of a chain fitted by cubic pieces
 * (patch_section_fit.c). Contract in patch_section.h (cj_patches_section_curves). */
#include "casteljau/patch_section.h"
#include "error_internal.h"
#include "patch_section_internal.h"

#include <assert.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* A polyline end: 2 * line + (0 start, 1 end). */
typedef struct pend {
    double x[3];
    int id;
} pend;

typedef struct cand {
    double dist;
    int a, b;
} cand;

typedef struct line_ref {
    int patch, k; /* polyline k of patch's section */
    int closed;
} line_ref;

static int cmp_pend(const void *a, const void *b) {
    const pend *x = a, *y = b;
    if (x->x[0] != y->x[0]) return x->x[0] < y->x[0] ? -1 : 1;
    return (x->id > y->id) - (x->id < y->id);
}

static int cmp_cand(const void *a, const void *b) {
    const cand *x = a, *y = b;
    if (x->dist != y->dist) return x->dist < y->dist ? -1 : 1;
    if (x->a != y->a) return x->a < y->a ? -1 : 1;
    return (x->b > y->b) - (x->b < y->b);
}

static double dist3(const double a[3], const double b[3]) {
    return sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                (a[2] - b[2]) * (a[2] - b[2]));
}

void cj_section_curves_free(cj_section_curves *s) {
    if (!s) return;
    free(s->ctrl);
    free(s->piece_starts);
    free(s->pts);
    free(s->pt_starts);
    free(s->closed);
    free(s->unresolved);
    memset(s, 0, sizeof *s);
}

/* Growing arrays of the output. */
typedef struct build {
    double *pts;
    int npts, cappts;
    int *pstarts, *vstarts;
    unsigned char *closed;
    int nchains, capchains;
    int nomem;
} build;

static void push_point(build *b, const double x[3]) {
    if (b->npts == b->cappts) {
        int cap = b->cappts ? 2 * b->cappts : 256;
        double *p = realloc(b->pts, (size_t)cap * 3 * sizeof *p);
        if (!p) {
            b->nomem = 1;
            return;
        }
        b->pts = p;
        b->cappts = cap;
    }
    memcpy(b->pts + 3 * b->npts++, x, 3 * sizeof(double));
}

static void push_chain(build *b, int piece_start, int vertex_start, int closed) {
    if (b->nchains + 1 >= b->capchains) {
        int cap = b->capchains ? 2 * b->capchains : 32;
        int *ps = realloc(b->pstarts, (size_t)cap * sizeof *ps);
        if (ps) b->pstarts = ps;
        int *vs = realloc(b->vstarts, (size_t)cap * sizeof *vs);
        if (vs) b->vstarts = vs;
        unsigned char *c = realloc(b->closed, (size_t)cap);
        if (c) b->closed = c;
        if (!ps || !vs || !c) {
            b->nomem = 1;
            return;
        }
        b->capchains = cap;
    }
    b->pstarts[b->nchains] = piece_start;
    b->vstarts[b->nchains] = vertex_start;
    b->closed[b->nchains++] = (unsigned char)closed;
}

/* The unit tangent of the section at a vertex: n x N (N the surface normal there), oriented
 * along the run (prev -> next); the chord direction where that is degenerate. */
static void tangent(const cj_patch *p, const double n[3], const double uv[2], const double *prev,
                    const double *next, double T[3]) {
    double N[3], dir[3] = {next[0] - prev[0], next[1] - prev[1], next[2] - prev[2]};
    double t[3] = {0, 0, 0};
    int order;
    if (cj_patch_normal(p, uv[0], uv[1], N, &order) == CJ_OK) {
        t[0] = n[1] * N[2] - n[2] * N[1];
        t[1] = n[2] * N[0] - n[0] * N[2];
        t[2] = n[0] * N[1] - n[1] * N[0];
    }
    double tl = sqrt(t[0] * t[0] + t[1] * t[1] + t[2] * t[2]);
    double dl = sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
    double nl = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    double s = t[0] * dir[0] + t[1] * dir[1] + t[2] * dir[2];
    /* the surface normal is not across the plane (a tangent plane), or the polyline turns away
     * from it by more than 60 degrees (a corner of the section at a crease): use the chord */
    if (!(tl > 1e-9 * nl) || !(fabs(s) > 0.5 * tl * dl)) {
        for (int k = 0; k < 3; ++k) T[k] = dl > 0 ? dir[k] / dl : 0.0;
        return;
    }
    for (int k = 0; k < 3; ++k) T[k] = (s < 0 ? -t[k] : t[k]) / tl;
}

/* Fits one run: polyline k of section s (forward or backward), its first and last points
 * replaced by first/last (the joined points, bit for bit). */
static int fit_run(const cj_patch *p, const cj_patch_section *s, int k, int backward,
                   const double *first, const double *last, int close, const double n[3],
                   double target, double margin, cj_sect_pieces *pieces, build *b,
                   int push_vertices) {
    int a = s->starts[k], e = s->starts[k + 1], cnt = e - a, np = cnt + (close ? 1 : 0);
    if (np < 2) np = 2; /* a one-point polyline: one piece of length zero */
    double *P = malloc((size_t)np * 6 * sizeof *P);
    double *UV = malloc((size_t)np * 2 * sizeof *UV);
    if (!P || !UV) {
        free(P), free(UV);
        return -1;
    }
    double *T = P + 3 * np;
    for (int i = 0; i < np; ++i) {
        int src = a + (backward ? cnt - 1 - (i % cnt) : i % cnt);
        memcpy(P + 3 * i, s->pts + 3 * src, 3 * sizeof(double));
        memcpy(UV + 2 * i, s->uv + 2 * src, 2 * sizeof(double));
    }
    if (first) memcpy(P, first, 3 * sizeof(double));
    if (last) memcpy(P + 3 * (np - 1), last, 3 * sizeof(double));
    for (int i = 0; i < np; ++i) {
        const double *prev = P + 3 * (i > 0 ? i - 1 : i), *next = P + 3 * (i + 1 < np ? i + 1 : i);
        tangent(p, n, UV + 2 * i, prev, next, T + 3 * i);
    }
    cj_sect_fit_run(P, T, np, target, margin, pieces);
    if (push_vertices)
        for (int i = 0; i < np - 1; ++i)
            push_point(b, P + 3 * i); /* the last is the next's first */
    free(P), free(UV);
    return pieces->nomem ? -1 : 0;
}

static void bez3(const double *B, double t, double x[3]) {
    double s = 1.0 - t;
    for (int k = 0; k < 3; ++k)
        x[k] = s * s * s * B[k] + 3 * s * s * t * B[3 + k] + 3 * s * t * t * B[6 + k] +
               t * t * t * B[9 + k];
}

/* Upper bound of the distance from x to piece B: 16 samples, then golden section about the
 * best (every value the distance to an evaluated point). */
static double piece_dist(const double *B, const double x[3]) {
    int bs = 0;
    double bd = INFINITY, p[3];
    for (int i = 0; i <= 16; ++i) {
        bez3(B, i / 16.0, p);
        double dd = dist3(p, x);
        if (dd < bd) bd = dd, bs = i;
    }
    double a = fmax(0.0, (bs - 1) / 16.0), b = fmin(1.0, (bs + 1) / 16.0);
    for (int it = 0; it < 40; ++it) {
        double m1 = a + 0.381966 * (b - a), m2 = b - 0.381966 * (b - a), p1[3], p2[3];
        bez3(B, m1, p1);
        bez3(B, m2, p2);
        double d1 = dist3(p1, x), d2 = dist3(p2, x);
        bd = fmin(bd, fmin(d1, d2));
        if (d1 < d2)
            b = m2;
        else
            a = m1;
    }
    return bd;
}

/* An unresolved cell (its centre x, every section point of it within poly_deviation of x)
 * whose centre lies within tol - poly_deviation of a piece is covered by the pieces: dropped,
 * the deviation raised to poly_deviation + that distance if needed (still <= tol). This is the
 * edge of a patch lying in the plane (the teapot's y = 0), found as a polyline by the patch on
 * one side and as unresolved cells by the patch on the other. */
static void absorb_unresolved(cj_section_curves *out, double tol, double margin) {
    double budget = tol - out->poly_deviation - margin;
    int kept = 0;
    for (int u = 0; u < out->nunresolved; ++u) {
        const double *x = out->unresolved + 3 * u;
        double best = INFINITY;
        for (int k = 0; k < out->npieces && best > budget; ++k) {
            const double *B = out->ctrl + 12 * k;
            int near = 1;
            for (int q = 0; q < 3 && near; ++q) {
                double lo = fmin(fmin(B[q], B[3 + q]), fmin(B[6 + q], B[9 + q]));
                double hi = fmax(fmax(B[q], B[3 + q]), fmax(B[6 + q], B[9 + q]));
                near = x[q] >= lo - budget && x[q] <= hi + budget;
            }
            if (near) best = fmin(best, piece_dist(B, x));
        }
        if (best <= budget) {
            out->deviation = fmax(out->deviation, out->poly_deviation + best + margin);
            continue;
        }
        memmove(out->unresolved + 3 * kept++, x, 3 * sizeof(double));
    }
    out->nunresolved = kept;
}

cj_status cj_patches_section_curves(const cj_patch *patches, size_t count, const double n[3],
                                    double d, double tol, cj_section_curves *out) {
    assert(patches && n && out);
    memset(out, 0, sizeof *out);
    if (count == 0) return cj_fail(CJ_ERR_ARGUMENT, "plane section: a model of 0 patches");
    if (count > (size_t)1 << 24)
        return cj_fail(CJ_ERR_ARGUMENT, "plane section: %zu patches (at most 2^24)", count);
    cj_patch_section *secs = calloc(count, sizeof *secs);
    if (!secs) return cj_fail(CJ_ERR_NOMEM, "plane section of %zu patches", count);
    cj_status st = CJ_OK;
    double size = 0.0;
    for (size_t i = 0; i < count; ++i) {
        st = cj_patch_section_plane(&patches[i], n, d, 0.25 * tol, &secs[i]);
        if (st != CJ_OK) {
            char msg[512];
            snprintf(msg, sizeof msg, "%s", cj_last_error());
            for (size_t j = 0; j < i; ++j) cj_patch_section_free(&secs[j]);
            free(secs);
            return cj_fail(st, "patch %zu: %s", i, msg);
        }
        const cj_patch *p = &patches[i];
        for (int k = 0; k < 3 * (p->deg_u + 1) * (p->deg_v + 1); ++k)
            size = fmax(size, fabs(p->pts[k]));
    }
    /* lines and their ends */
    int nlines = 0, nunres = 0;
    for (size_t i = 0; i < count; ++i) nlines += secs[i].nlines, nunres += secs[i].nunresolved;
    line_ref *lines = malloc((size_t)(nlines ? nlines : 1) * sizeof *lines);
    pend *ends = malloc((size_t)(2 * nlines + 1) * sizeof *ends);
    int *partner = malloc((size_t)(2 * nlines + 1) * sizeof *partner);
    unsigned char *used = calloc((size_t)nlines + 1, 1);
    cand *cands = NULL;
    cj_sect_pieces pieces = {0};
    build b = {0};
    if (!lines || !ends || !partner || !used) goto nomem;
    int nl = 0, ne = 0;
    for (size_t i = 0; i < count; ++i)
        for (int k = 0; k < secs[i].nlines; ++k) {
            lines[nl].patch = (int)i, lines[nl].k = k, lines[nl].closed = secs[i].closed[k];
            partner[2 * nl] = partner[2 * nl + 1] = -1;
            if (!lines[nl].closed)
                for (int e = 0; e < 2; ++e) {
                    int at = e ? secs[i].starts[k + 1] - 1 : secs[i].starts[k];
                    memcpy(ends[ne].x, secs[i].pts + 3 * at, sizeof ends[ne].x);
                    ends[ne++].id = 2 * nl + e;
                }
            ++nl;
        }
    /* join: candidate pairs within join_eps, closest first */
    double eps = tol / 256;
    qsort(ends, (size_t)ne, sizeof *ends, cmp_pend);
    int ncand = 0, capcand = 0;
    for (int i = 0; i < ne; ++i)
        for (int j = i + 1; j < ne && ends[j].x[0] - ends[i].x[0] <= eps; ++j) {
            double dd = dist3(ends[i].x, ends[j].x);
            if (!(dd <= eps)) continue;
            if (ncand == capcand) {
                capcand = capcand ? 2 * capcand : 64;
                cand *c = realloc(cands, (size_t)capcand * sizeof *c);
                if (!c) goto nomem;
                cands = c;
            }
            cands[ncand].dist = dd, cands[ncand].a = ends[i].id, cands[ncand].b = ends[j].id;
            ++ncand;
        }
    if (ncand) qsort(cands, (size_t)ncand, sizeof *cands, cmp_cand);
    for (int c = 0; c < ncand; ++c) {
        int a = cands[c].a, e = cands[c].b;
        if (partner[a] >= 0 || partner[e] >= 0) continue;
        /* the two ends of a one-segment line are not one point */
        partner[a] = e, partner[e] = a;
        out->joins++;
        out->join_gap = fmax(out->join_gap, cands[c].dist);
    }
    /* chains: from unpartnered ends first (open chains), then cycles, then closed polylines */
    double target = 0.75 * tol, margin = size * 0x1p-44;
    double joint[3];
    for (int pass = 0; pass < 2; ++pass)
        for (int l0 = 0; l0 < nl; ++l0) {
            if (used[l0]) continue;
            int enter;
            if (lines[l0].closed) {
                if (pass == 0) continue;
                enter = 0;
            } else if (pass == 0) {
                if (partner[2 * l0] < 0)
                    enter = 0;
                else if (partner[2 * l0 + 1] < 0)
                    enter = 1;
                else
                    continue;
            } else {
                enter = 0;
            }
            push_chain(&b, pieces.count, b.npts, 0);
            if (b.nomem) goto nomem;
            const cj_patch_section *s0 = &secs[lines[l0].patch];
            int first_at = enter ? s0->starts[lines[l0].k + 1] - 1 : s0->starts[lines[l0].k];
            const double *chain_first = s0->pts + 3 * first_at, *prev_last = NULL;
            int l = l0, closed = 0;
            if (lines[l0].closed) { /* a loop inside one patch */
                used[l] = 1;
                if (fit_run(&patches[lines[l].patch], s0, lines[l].k, 0, NULL, chain_first, 1, n,
                            target, margin, &pieces, &b, 1))
                    goto nomem;
                b.closed[b.nchains - 1] = 1;
                continue;
            }
            for (;;) {
                used[l] = 1;
                const cj_patch_section *s = &secs[lines[l].patch];
                int exit_end = 2 * l + 1 - enter, nxt = partner[exit_end];
                int nxt_line = nxt >= 0 ? nxt / 2 : -1;
                const double *last = NULL;
                int done = nxt < 0 || used[nxt_line];
                if (nxt >= 0 && used[nxt_line]) { /* back at the chain's first end */
                    closed = 1;
                    last = chain_first;
                }
                if (fit_run(&patches[lines[l].patch], s, lines[l].k, enter, prev_last, last, 0, n,
                            target, margin, &pieces, &b, 1) ||
                    b.nomem)
                    goto nomem;
                /* the shared point: the last vertex pushed is this run's end, kept for the next */
                const double *end_pt = pieces.ctrl + 12 * (pieces.count - 1) + 9;
                if (done) {
                    if (!closed) push_point(&b, end_pt);
                    break;
                }
                /* the next run starts at this run's end point, bit for bit */
                memcpy(joint, end_pt, sizeof joint);
                prev_last = joint;
                l = nxt_line;
                enter = nxt % 2;
            }
            b.closed[b.nchains - 1] = (unsigned char)closed;
        }
    if (b.nomem || pieces.nomem) goto nomem;
    push_chain(&b, pieces.count, b.npts, 0);
    if (b.nomem) goto nomem;
    --b.nchains; /* the sentinel offsets stay, not a chain */
    out->ctrl = pieces.ctrl;
    out->npieces = pieces.count;
    out->piece_starts = b.pstarts;
    out->pt_starts = b.vstarts;
    out->closed = b.closed;
    out->nchains = b.nchains;
    out->pts = b.pts;
    out->npts = b.npts;
    out->unresolved = malloc((size_t)(nunres ? nunres : 1) * 3 * sizeof(double));
    if (!out->unresolved) {
        pieces.ctrl = NULL, b.pstarts = b.vstarts = NULL, b.closed = NULL, b.pts = NULL;
        cj_section_curves_free(out);
        goto nomem;
    }
    for (size_t i = 0; i < count; ++i) {
        if (secs[i].nunresolved) /* a section without any holds no array (NULL) */
            memcpy(out->unresolved + 3 * out->nunresolved, secs[i].unresolved,
                   (size_t)secs[i].nunresolved * 3 * sizeof(double));
        out->nunresolved += secs[i].nunresolved;
        out->ambiguous += secs[i].ambiguous;
        out->cells += secs[i].cells;
        out->poly_deviation = fmax(out->poly_deviation, secs[i].deviation);
        out->plane_gap = fmax(out->plane_gap, secs[i].plane_gap);
    }
    out->deviation = out->poly_deviation + pieces.worst;
    absorb_unresolved(out, tol, margin);
    st = CJ_OK;
    goto done;
nomem:
    free(pieces.ctrl);
    free(b.pts);
    free(b.pstarts);
    free(b.vstarts);
    free(b.closed);
    st = cj_fail(CJ_ERR_NOMEM, "plane section: joining the polylines of %zu patches", count);
done:
    for (size_t i = 0; i < count; ++i) cj_patch_section_free(&secs[i]);
    free(secs);
    free(lines);
    free(ends);
    free(partner);
    free(used);
    free(cands);
    return st;
}
