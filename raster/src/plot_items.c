/* Drawing one plot item in pixel space: Bézier curves with their control polygon, hull,
 * de Casteljau construction and frames; splines with knots; contours, polylines and points.
 * Curves are flattened in pixel coordinates and stroked anti-aliased (plot_draw.c). */
#include "casteljau/flatten.h"
#include "casteljau/rational.h"
#include "error_internal.h"
#include "plot_items_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static void to_px(const xform *x, const double *in, double *out) {
    out[0] = x->ox + x->s * (in[0] - x->cx);
    out[1] = x->oy + x->s * (in[1] - x->cy);
}

static cj_rgba with_alpha(cj_rgba c, uint8_t a) {
    c.a = (uint8_t)((unsigned)c.a * a / 255u);
    return c;
}

/* Flattens a 2D Bézier given in pixel coordinates into the scratch polyline. */
/* (An affine map of the control points maps a rational curve exactly too, weights unchanged.) */
static cj_status flatten_px(cj_plot_canvas *cv, const double *ctrl_px, const double *weights,
                            int degree) {
    cj_bezier b = cj_bezier_view(degree, 2, ctrl_px);
    cj_rbezier rb = cj_rbezier_view(degree, 2, ctrl_px, weights);
    cj_flatten_opts fo = cj_flatten_defaults(CJ_FLATTEN_NEAR_OPTIMAL, CJ_PLOT_FLATTEN_TOL);
    size_t n = 0;
    cj_status st = weights ? cj_flatten_rbezier(&rb, &fo, NULL, 0, &n, NULL)
                           : cj_flatten_bezier(&b, &fo, NULL, 0, &n, NULL);
    if (st) return st;
    if ((st = cj_plot_canvas_reserve(cv, n))) return st;
    st = weights ? cj_flatten_rbezier(&rb, &fo, cv->poly, cv->poly_cap, &n, NULL)
                 : cj_flatten_bezier(&b, &fo, cv->poly, cv->poly_cap, &n, NULL);
    if (st) return st;
    cv->poly_n = n;
    return CJ_OK;
}

static const cj_rgba level_colors[] = {{0xff, 0x7f, 0x0e, 255}, {0x2c, 0xa0, 0x2c, 255},
                                       {0xd6, 0x27, 0x28, 255}, {0x94, 0x67, 0xbd, 255},
                                       {0x8c, 0x56, 0x4b, 255}, {0xe3, 0x77, 0xc2, 255},
                                       {0x17, 0xbe, 0xcf, 255}, {0xbc, 0xbd, 0x22, 255}};

static cj_status draw_bezier(cj_plot_canvas *cv, const xform *x, const plot_item *it) {
    const int n = it->degree;
    const size_t np = (size_t)n + 1;
    const cj_plot_bezier_opts *o = &it->bopts;
    double *px = malloc(np * 2 * sizeof *px);
    if (!px) return cj_fail(CJ_ERR_NOMEM, "no memory for %zu control points", np);
    for (size_t i = 0; i < np; ++i) to_px(x, it->pts + 2 * i, px + 2 * i);
    cj_status st = CJ_OK;
    const cj_rgba grey = cj_rgba_make(0x70, 0x70, 0x70, 255);
    cj_bezier c = cj_bezier_view(n, 2, it->pts);

    if (o->hull && n >= 1) {
        int *idx = malloc(np * sizeof *idx);
        double *hull = malloc(np * 2 * sizeof *hull);
        int count = 0;
        if (!idx || !hull) st = cj_fail(CJ_ERR_NOMEM, "no memory for a hull");
        if (!st) st = cj_bezier_hull2d(&c, idx, &count);
        if (!st && count >= 3) {
            for (int k = 0; k < count; ++k) {
                hull[2 * k] = px[2 * idx[k]];
                hull[2 * k + 1] = px[2 * idx[k] + 1];
            }
            cj_plot_fill_convex(cv, hull, (size_t)count, with_alpha(it->color, 36));
            st = cj_plot_stroke(cv, hull, (size_t)count, 1, with_alpha(it->color, 110), 1.0);
        } else if (st == CJ_ERR_DEGENERATE) {
            st = CJ_OK; /* collinear or coincident points: no area to fill */
        }
        free(idx);
        free(hull);
    }
    if (!st && o->control_polygon && n >= 1)
        st = cj_plot_stroke(cv, px, np, 0, with_alpha(grey, 200), 1.25);
    if (!st) st = flatten_px(cv, px, it->weights, n);
    if (!st) st = cj_plot_stroke(cv, cv->poly, cv->poly_n, 0, it->color, it->width);

    if (!st && o->construction && n >= 1) {
        /* The de Casteljau triangle at t: level r has points b_i^r, i = 0..n-r; each level's
         * polygon is drawn in its own colour, its points as small dots. */
        double *tri = malloc(np * 3 * sizeof *tri);
        if (!tri) st = cj_fail(CJ_ERR_NOMEM, "no memory for the construction");
        const double t = o->construction_t;
        /* tri[3i..3i+2] = (x, y, w); rational levels are convex combinations with weights
         * (1-t) w_i, t w_{i+1} (the projection of the homogeneous de Casteljau step). */
        for (size_t i = 0; !st && i < np; ++i) {
            tri[3 * i] = it->pts[2 * i];
            tri[3 * i + 1] = it->pts[2 * i + 1];
            tri[3 * i + 2] = it->weights ? it->weights[i] : 1.0;
        }
        for (int r = 1; !st && r <= n; ++r) {
            for (int i = 0; i + r <= n; ++i) {
                double *a = tri + 3 * i, *b = tri + 3 * (i + 1);
                const double wa = (1.0 - t) * a[2], wb = t * b[2], w = wa + wb;
                for (int k = 0; k < 2; ++k)
                    a[k] = it->weights ? (wa * a[k] + wb * b[k]) / w : (1.0 - t) * a[k] + t * b[k];
                a[2] = w;
            }
            const size_t m = (size_t)(n - r + 1);
            double *lp = malloc(m * 2 * sizeof *lp);
            if (!lp) {
                st = cj_fail(CJ_ERR_NOMEM, "no memory for the construction");
                break;
            }
            for (size_t i = 0; i < m; ++i) to_px(x, tri + 3 * i, lp + 2 * i);
            cj_rgba lc = level_colors[(r - 1) % (int)(sizeof level_colors / sizeof *level_colors)];
            if (m >= 2) st = cj_plot_stroke(cv, lp, m, 0, lc, 1.5);
            for (size_t i = 0; !st && i < m; ++i) {
                if (r == n) {
                    cj_plot_disc(cv, lp[0], lp[1], 5.5, cj_rgba_make(0x20, 0x20, 0x20, 255));
                    cj_plot_disc(cv, lp[0], lp[1], 3.5, cj_rgba_make(0xd6, 0x27, 0x28, 255));
                } else {
                    cj_plot_disc(cv, lp[2 * i], lp[2 * i + 1], 3.0, lc);
                }
            }
            free(lp);
        }
        free(tri);
    }
    if (!st && o->control_points) {
        for (size_t i = 0; i < np; ++i) {
            cj_plot_disc(cv, px[2 * i], px[2 * i + 1], 4.5, cj_rgba_make(0x30, 0x30, 0x30, 255));
            cj_plot_disc(cv, px[2 * i], px[2 * i + 1], 2.75, cj_rgba_make(255, 255, 255, 255));
        }
    }
    for (size_t f = 0; !st && f < o->nframes; ++f) {
        double p[2], tan[2], nor[2], pp[2];
        if (it->weights) {
            /* Rational: c' from the quotient rule; a zero first derivative has no arrow. */
            double d[4];
            cj_rbezier rc = cj_rbezier_view(n, 2, it->pts, it->weights);
            if (cj_rbezier_eval_derivs(&rc, o->frames_t[f], 1, d) != CJ_OK) continue;
            const double len = hypot(d[2], d[3]);
            if (!(len > 0.0)) continue;
            p[0] = d[0], p[1] = d[1], tan[0] = d[2] / len, tan[1] = d[3] / len;
            nor[0] = -tan[1], nor[1] = tan[0];
        } else {
            if (cj_bezier_eval_decasteljau(&c, o->frames_t[f], p) != CJ_OK) continue;
            if (cj_bezier_tangent(&c, o->frames_t[f], tan, NULL) != CJ_OK) continue;
            if (cj_bezier_normal(&c, o->frames_t[f], nor) != CJ_OK) nor[0] = nor[1] = 0.0;
        }
        to_px(x, p, pp);
        const double len = cv->arrow_len;
        st = cj_plot_arrow(cv, pp[0], pp[1], pp[0] + len * tan[0], pp[1] + len * tan[1],
                           cj_rgba_make(0xd6, 0x27, 0x28, 255), 2.0);
        if (!st && o->normals && (nor[0] != 0.0 || nor[1] != 0.0))
            st = cj_plot_arrow(cv, pp[0], pp[1], pp[0] + len * nor[0], pp[1] + len * nor[1],
                               cj_rgba_make(0x2c, 0xa0, 0x2c, 255), 2.0);
        if (!st) cj_plot_disc(cv, pp[0], pp[1], 3.5, cj_rgba_make(0x20, 0x20, 0x20, 255));
    }
    free(px);
    return st;
}

static cj_status draw_spline(cj_plot_canvas *cv, const xform *x, const plot_item *it) {
    cj_status st = CJ_OK;
    double seg[8];
    /* Flatten piece by piece; consecutive pieces share end points, so stroking each piece
     * separately joins them (round joins of the stroker). */
    for (size_t s = 0; !st && s < it->nsegs; ++s) {
        for (int i = 0; i < 4; ++i) to_px(x, it->segs + 8 * s + 2 * i, seg + 2 * i);
        st = flatten_px(cv, seg, NULL, 3);
        if (!st) st = cj_plot_stroke(cv, cv->poly, cv->poly_n, 0, it->color, it->width);
    }
    if (!st && it->markers)
        for (size_t i = 0; i < it->npts; ++i) {
            double p[2];
            to_px(x, it->pts + 2 * i, p);
            cj_plot_disc(cv, p[0], p[1], 5.0, cj_rgba_make(0x20, 0x20, 0x20, 255));
            cj_plot_disc(cv, p[0], p[1], 3.5, it->color);
        }
    return st;
}

static cj_status draw_pointlist(cj_plot_canvas *cv, const xform *x, const double *pts, size_t n,
                                int closed, cj_rgba color, double width) {
    cj_status st = cj_plot_canvas_reserve(cv, n);
    if (st) return st;
    for (size_t i = 0; i < n; ++i) to_px(x, pts + 2 * i, cv->poly + 2 * i);
    return cj_plot_stroke(cv, cv->poly, n, closed, color, width);
}

cj_status cj_plot_draw_item(cj_plot_canvas *cv, const xform *x, const plot_item *it) {
    cj_status st = CJ_OK;
    switch (it->type) {
    case ITEM_BEZIER:
        st = draw_bezier(cv, x, it);
        break;
    case ITEM_SPLINE:
        st = draw_spline(cv, x, it);
        break;
    case ITEM_IMPLICIT:
        for (size_t k = 0; !st && k < it->nsegs; ++k)
            st = draw_pointlist(cv, x, it->pts + 2 * it->offsets[k],
                                it->offsets[k + 1] - it->offsets[k], it->closed_flags[k], it->color,
                                it->width);
        break;
    case ITEM_POLYLINE:
        st = draw_pointlist(cv, x, it->pts, it->npts, it->closed, it->color, it->width);
        if (!st && it->markers)
            for (size_t k = 0; k < it->npts; ++k) {
                double p[2];
                to_px(x, it->pts + 2 * k, p);
                cj_plot_disc(cv, p[0], p[1], 1.5 + it->width, it->color);
            }
        break;
    case ITEM_POINTS:
        for (size_t k = 0; k < it->npts; ++k) {
            double p[2];
            to_px(x, it->pts + 2 * k, p);
            cj_plot_disc(cv, p[0], p[1], it->width, it->color);
        }
        break;
    }
    return st;
}
