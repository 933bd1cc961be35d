/* Overlays as depth-tested lines (control nets, wireframes, iso-parameter lines, normals) and
 * CJ_GEOM_CURVE objects, through the exact line code of line.h.
 *
 * Every 3D segment is clipped in homogeneous coordinates (near and far planes, and a guard band
 * of twice the view volume's width so that the visible part of a line keeps its exact pixels),
 * projected once for the whole image and binned into tiles; each tile draws its segments with
 * cj_line_visit_d clipped to the tile, which visits exactly the pixels of the unclipped
 * line inside it, so the picture does not depend on the tiling. Depth is the pseudodepth of the
 * ends interpolated along the major axis (pseudodepth is affine in screen space); a pixel
 * takes the line's colour in every sample whose stored depth is strictly larger, and that depth
 * is lowered to the line's, so transparent surfaces behind a line do not cover it.
 *
 * DEPTH OFFSET: overlay ends are moved towards the eye along their view ray (which keeps their
 * pixel) by two pixel sizes at their depth; the tessellation's deviation is at most tol_px
 * (0.25 pixel) so a line lying on the surface stays in front of the triangles drawn for it
 * except where the surface is seen nearly edge-on. Curves get no offset. */
#include "render_pipe.h"

#include "casteljau/catmull_rom.h"
#include "casteljau/flatten.h"
#include "casteljau/line.h"
#include "error_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef struct emit_ctx {
    cj_rctx *c;
    const cj_allocator *a;
    const cj_xform3 *world; /* object -> world of the current object */
    float rgb[3];
    int offset, width;
    cj_status st;
    int have_prev;
    double prev[3];
} emit_ctx;

static void to_world(const cj_xform3 *m, const double p[3], double out[3]) {
    for (int r = 0; r < 3; ++r)
        out[r] = m->m[r][0] * p[0] + m->m[r][1] * p[1] + m->m[r][2] * p[2] + m->m[r][3];
}

static void offset_point(const cj_rview *v, double p[3]) {
    if (v->cam.projection == CJ_PROJ_PERSPECTIVE) {
        double d[3] = {v->eye.x - p[0], v->eye.y - p[1], v->eye.z - p[2]};
        double len = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        double depth = -(v->world_to_cam.m[2][0] * p[0] + v->world_to_cam.m[2][1] * p[1] +
                         v->world_to_cam.m[2][2] * p[2] + v->world_to_cam.m[2][3]);
        if (!(len > 0.0) || !(depth > 0.0)) return;
        double delta = 2.0 * cj_rview_pixel_size(v, depth);
        if (delta > 0.5 * len) delta = 0.5 * len;
        for (int k = 0; k < 3; ++k) p[k] += d[k] / len * delta;
    } else {
        double delta = 2.0 * v->px_ortho;
        p[0] -= v->gaze_unit.x * delta;
        p[1] -= v->gaze_unit.y * delta;
        p[2] -= v->gaze_unit.z * delta;
    }
}

/* One world segment: clip, project, append. */
static void emit_world(emit_ctx *e, const double p[3], const double q[3]) {
    if (e->st) return;
    cj_rctx *c = e->c;
    cj_rlines *L = &c->lines;
    ++L->world_segments;
    double a[3] = {p[0], p[1], p[2]}, b[3] = {q[0], q[1], q[2]};
    if (e->offset) {
        offset_point(c->view, a);
        offset_point(c->view, b);
    }
    double ca[4], cb[4];
    const cj_xform3 *M = &c->view->world_to_clip;
    for (int r = 0; r < 4; ++r) {
        ca[r] = M->m[r][0] * a[0] + M->m[r][1] * a[1] + M->m[r][2] * a[2] + M->m[r][3];
        cb[r] = M->m[r][0] * b[0] + M->m[r][1] * b[1] + M->m[r][2] * b[2] + M->m[r][3];
    }
    double t0 = 0.0, t1 = 1.0;
    for (int pl = 0; pl < 6; ++pl) {
        double da, db;
        switch (pl) {
        case 0:
            da = ca[3] + ca[2], db = cb[3] + cb[2];
            break;
        case 1:
            da = ca[3] - ca[2], db = cb[3] - cb[2];
            break;
        case 2:
            da = 2 * ca[3] - ca[0], db = 2 * cb[3] - cb[0];
            break;
        case 3:
            da = 2 * ca[3] + ca[0], db = 2 * cb[3] + cb[0];
            break;
        case 4:
            da = 2 * ca[3] - ca[1], db = 2 * cb[3] - cb[1];
            break;
        default:
            da = 2 * ca[3] + ca[1], db = 2 * cb[3] + cb[1];
            break;
        }
        if (da < 0.0 && db < 0.0) return;
        if (da < 0.0) {
            double t = da / (da - db);
            if (t > t0) t0 = t;
        } else if (db < 0.0) {
            double t = da / (da - db);
            if (t < t1) t1 = t;
        }
    }
    if (t0 > t1) return;
    double pa[4], pb[4];
    for (int r = 0; r < 4; ++r) {
        pa[r] = ca[r] + t0 * (cb[r] - ca[r]);
        pb[r] = ca[r] + t1 * (cb[r] - ca[r]);
    }
    if (!(pa[3] > 0.0) || !(pb[3] > 0.0)) return;
    if (L->count == L->cap) {
        size_t nc = L->cap ? 2 * L->cap : 1024;
        cj_rseg *ns = cj_ralloc(e->a, nc * sizeof *ns);
        if (!ns) {
            e->st = cj_fail(CJ_ERR_NOMEM, "%zu overlay segments", nc);
            return;
        }
        if (L->segs) memcpy(ns, L->segs, L->count * sizeof *ns);
        cj_rfree(e->a, L->segs);
        L->segs = ns;
        L->cap = nc;
    }
    cj_rseg *s = &L->segs[L->count++];
    s->x0 = (pa[0] / pa[3] + 1.0) * 0.5 * c->width;
    s->y0 = (pa[1] / pa[3] + 1.0) * 0.5 * c->height;
    s->x1 = (pb[0] / pb[3] + 1.0) * 0.5 * c->width;
    s->y1 = (pb[1] / pb[3] + 1.0) * 0.5 * c->height;
    s->z0 = (float)(pa[2] / pa[3]);
    s->z1 = (float)(pb[2] / pb[3]);
    memcpy(s->rgb, e->rgb, sizeof s->rgb);
    s->width = e->width > 1 ? e->width : 1;
}

static void emit_object(emit_ctx *e, const double p[3], const double q[3]) {
    double a[3], b[3];
    to_world(e->world, p, a);
    to_world(e->world, q, b);
    emit_world(e, a, b);
}

/* Flattener sink: consecutive vertices (object space) become segments. */
static void poly_sink(void *user, const double *pt, int dim, size_t piece, double t) {
    (void)dim;
    (void)piece;
    (void)t;
    emit_ctx *e = user;
    if (e->have_prev) emit_object(e, e->prev, pt);
    memcpy(e->prev, pt, 3 * sizeof(double));
    e->have_prev = 1;
}

static void control_net(emit_ctx *e, const cj_patch *p) {
    int m = p->deg_u, n = p->deg_v;
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= m; ++i) {
            const double *b = p->pts + 3 * (j * (m + 1) + i);
            if (i < m) emit_object(e, b, b + 3);
            if (j < n) emit_object(e, b, b + 3 * (m + 1));
        }
}

static void iso_lines(emit_ctx *e, const cj_patch *p, int count, double tol) {
    double pts[3 * (CJ_PATCH_MAX_DEGREE + 1)], w[CJ_PATCH_MAX_DEGREE + 1];
    for (int dir = 0; dir < 2; ++dir)
        for (int i = 0; i <= count; ++i) {
            double s = (double)i / count;
            int deg = dir == 0 ? p->deg_v : p->deg_u;
            cj_status st = dir == 0 ? cj_patch_iso_u(p, s, pts, p->weights ? w : NULL)
                                    : cj_patch_iso_v(p, s, pts, p->weights ? w : NULL);
            if (st) continue;
            cj_flatten_opts fo = cj_flatten_defaults(CJ_FLATTEN_NEAR_OPTIMAL, tol);
            e->have_prev = 0;
            if (p->weights) {
                cj_rbezier rb = {deg, 3, pts, w};
                st = cj_flatten_rbezier_cb(&rb, &fo, poly_sink, e, NULL);
            } else {
                cj_bezier bz = cj_bezier_view(deg, 3, pts);
                st = cj_flatten_bezier_cb(&bz, &fo, poly_sink, e, NULL);
            }
            (void)st; /* a curve the flattener refuses (tolerance below rounding) is skipped */
        }
}

/* Iso-parameter lines of an analytic surface as polylines through the tessellation grid's
 * points: each is a chord polygon of the curve within the grid's proven bound. */
static void surface_iso(emit_ctx *e, const cj_rsurf *rs, int count, int nu, int nv) {
    const cj_param_surface *ps = &rs->s;
    for (int dir = 0; dir < 2; ++dir)
        for (int i = 0; i <= count; ++i) {
            double a = (double)i / count;
            int steps = dir == 0 ? nv : nu;
            double prev[3];
            for (int j = 0; j <= steps; ++j) {
                double b = (double)j / steps;
                double u = ps->u0 + (ps->u1 - ps->u0) * (dir == 0 ? a : b);
                double v = ps->v0 + (ps->v1 - ps->v0) * (dir == 0 ? b : a);
                cj_vec3 p;
                if (cj_surface_eval(ps, u, v, &p, NULL, NULL)) return;
                double q[3] = {p.x + rs->offset.x, p.y + rs->offset.y, p.z + rs->offset.z};
                if (j) emit_object(e, prev, q);
                memcpy(prev, q, sizeof prev);
            }
        }
}

static double curve_tol(const cj_rctx *c, const cj_robject *o, const double *pts, size_t n) {
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY}, d;
    for (size_t i = 0; i < n; ++i)
        for (int k = 0; k < 3; ++k) {
            if (pts[3 * i + k] < lo[k]) lo[k] = pts[3 * i + k];
            if (pts[3 * i + k] > hi[k]) hi[k] = pts[3 * i + k];
        }
    if (!cj_rview_box_depth(c->view, &o->world, lo, hi, &d)) return 0.0;
    return cj_rview_world_tol(c->view, d, c->b->tol_px) / o->sigma;
}

static void curve_lines(emit_ctx *e, const cj_robject *o, const cj_geometry *g, unsigned flags) {
    const double *pts = g->u.curve.pts;
    size_t n = g->u.curve.count;
    if (n == 0) return;
    double w = g->u.curve.width_px;
    e->width = w > 1.0 ? (int)(w + 0.5) : 1;
    if (e->width > 64) e->width = 64;
    double tol = curve_tol(e->c, o, pts, n);
    if (tol > 0.0) {
        cj_flatten_opts fo = cj_flatten_defaults(CJ_FLATTEN_NEAR_OPTIMAL, tol);
        e->have_prev = 0;
        if (g->u.curve.kind == CJ_CURVE_SPLINE) {
            cj_spline_options so = cj_spline_defaults();
            so.kind = g->u.curve.spline;
            so.tension = g->u.curve.tension;
            so.continuity = g->u.curve.continuity;
            so.bias = g->u.curve.bias;
            so.closed = g->u.curve.closed;
            size_t ns = cj_spline_segment_count(n, so.closed);
            double *segs = ns ? cj_ralloc(e->a, sizeof(double) * 12 * ns) : NULL;
            cj_flatten_piece *pc = ns ? cj_ralloc(e->a, sizeof *pc * ns) : NULL;
            if (segs && pc && !cj_catmull_rom(pts, n, 3, &so, segs, ns, &ns, NULL)) {
                for (size_t s = 0; s < ns; ++s) {
                    pc[s].curve = cj_bezier_view(3, 3, segs + 12 * s);
                    pc[s].weights = NULL;
                }
                (void)cj_flatten_sequence_cb(pc, ns, &fo, poly_sink, e, NULL);
            }
            cj_rfree(e->a, segs);
            cj_rfree(e->a, pc);
        } else if (g->u.curve.kind == CJ_CURVE_RATIONAL) {
            cj_rbezier rb = {g->u.curve.degree, 3, pts, g->u.curve.weights};
            (void)cj_flatten_rbezier_cb(&rb, &fo, poly_sink, e, NULL);
        } else {
            cj_bezier bz = cj_bezier_view(g->u.curve.degree, 3, pts);
            (void)cj_flatten_bezier_cb(&bz, &fo, poly_sink, e, NULL);
        }
    }
    if (flags & CJ_OVERLAY_CONTROL_NET)
        for (size_t i = 0; i + 1 < n; ++i) emit_object(e, pts + 3 * i, pts + 3 * i + 3);
}

cj_status cj_rlines_build(cj_rctx *c, const cj_scene *scene, const cj_allocator *a) {
    cj_rlines *L = &c->lines;
    const cj_rbuild *b = c->b;
    emit_ctx e;
    memset(&e, 0, sizeof e);
    e.c = c;
    e.a = a;
    for (size_t oi = 0; oi < b->object_count && !e.st; ++oi) {
        const cj_robject *o = &b->objects[oi];
        const cj_node *nd = cj_scene_node(scene, o->node);
        const cj_geometry *g = cj_scene_geometry(scene, o->geometry);
        unsigned fl = nd->overlay.flags;
        e.world = &o->world;
        if (g->kind == CJ_GEOM_CURVE) {
            e.offset = 0;
            e.rgb[0] = (float)g->u.curve.color.r;
            e.rgb[1] = (float)g->u.curve.color.g;
            e.rgb[2] = (float)g->u.curve.color.b;
            curve_lines(&e, o, g, fl);
            e.width = 1;
            continue;
        }
        if (!fl) continue;
        e.offset = 1;
        e.rgb[0] = (float)nd->overlay.color.r;
        e.rgb[1] = (float)nd->overlay.color.g;
        e.rgb[2] = (float)nd->overlay.color.b;
        const cj_patch *pt = NULL;
        size_t np = 0;
        cj_patch *conv = NULL;
        double *cp = NULL, *cw = NULL;
        if (g->kind == CJ_GEOM_PATCHES) {
            pt = g->u.patches.patches;
            np = g->u.patches.count;
        } else if (g->kind == CJ_GEOM_REVOLUTION || g->kind == CJ_GEOM_GEN_CYLINDER) {
            e.st = cj_render_geometry_patches(g, a, &conv, &np, &cp, &cw);
            pt = conv;
        }
        for (size_t i = 0; i < np && !e.st; ++i) {
            if (fl & CJ_OVERLAY_CONTROL_NET) control_net(&e, &pt[i]);
            if ((fl & CJ_OVERLAY_ISO_LINES) && o->tol_obj > 0.0)
                iso_lines(&e, &pt[i], nd->overlay.iso_count > 0 ? nd->overlay.iso_count : 1,
                          o->tol_obj);
        }
        cj_rfree(a, conv);
        cj_rfree(a, cp);
        cj_rfree(a, cw);
        if ((fl & CJ_OVERLAY_ISO_LINES) && !pt && g->kind != CJ_GEOM_MESH && o->grid_nu > 0) {
            cj_rsurf rs;
            if (!cj_rsurf_init(g, &rs))
                surface_iso(&e, &rs, nd->overlay.iso_count > 0 ? nd->overlay.iso_count : 1,
                            o->grid_nu, o->grid_nv);
        }
        /* world-space lines from the triangles the pipeline built */
        e.world = NULL;
        if (fl & CJ_OVERLAY_WIREFRAME)
            for (size_t t = o->t0; t < o->t1; ++t) {
                const uint32_t *tv = b->tris + 3 * t;
                for (int k = 0; k < 3; ++k)
                    emit_world(&e, b->pos + 3 * (size_t)tv[k],
                               b->pos + 3 * (size_t)tv[(k + 1) % 3]);
            }
        if ((fl & CJ_OVERLAY_NORMALS) && b->nrm)
            for (size_t v = o->v0; v < o->v1; ++v) {
                const double *p = b->pos + 3 * v;
                const float *n = b->nrm + 3 * v;
                double len = nd->overlay.normal_length, q[3];
                for (int k = 0; k < 3; ++k) q[k] = p[k] + len * n[k];
                emit_world(&e, p, q);
            }
    }
    if (e.st) return e.st;
    /* bin by tile (CSR), keeping the global order within each tile */
    int tx = c->tiles_x, ty = (c->height + c->tile_size - 1) / c->tile_size;
    size_t tiles = (size_t)tx * (size_t)ty;
    L->bin_start = cj_ralloc(a, sizeof(size_t) * (tiles + 1));
    if (!L->bin_start) return cj_fail(CJ_ERR_NOMEM, "line bins");
    memset(L->bin_start, 0, sizeof(size_t) * (tiles + 1));
    for (int pass = 0; pass < 2; ++pass) {
        size_t *fill = NULL;
        if (pass == 1) {
            for (size_t t = 0; t < tiles; ++t) L->bin_start[t + 1] += L->bin_start[t];
            L->bin_items = cj_ralloc(a, sizeof(uint32_t) * (L->bin_start[tiles] + 1));
            fill = cj_ralloc(a, sizeof(size_t) * (tiles + 1));
            if (!L->bin_items || !fill) {
                cj_rfree(a, fill);
                return cj_fail(CJ_ERR_NOMEM, "line bins");
            }
            memcpy(fill, L->bin_start, sizeof(size_t) * tiles);
        }
        for (size_t s = 0; s < L->count; ++s) {
            const cj_rseg *g = &L->segs[s];
            double hw = g->width / 2 + 1;
            double xl = floor(fmin(g->x0, g->x1)) - hw, xh = floor(fmax(g->x0, g->x1)) + hw;
            double yl = floor(fmin(g->y0, g->y1)) - hw, yh = floor(fmax(g->y0, g->y1)) + hw;
            if (xh < 0 || yh < 0 || xl >= c->width || yl >= c->height) continue;
            int ax = xl < 0 ? 0 : (int)xl / c->tile_size,
                bx = xh >= c->width ? tx - 1 : (int)xh / c->tile_size;
            int ay = yl < 0 ? 0 : (int)yl / c->tile_size,
                by = yh >= c->height ? ty - 1 : (int)yh / c->tile_size;
            for (int y = ay; y <= by; ++y)
                for (int x = ax; x <= bx; ++x) {
                    size_t t = (size_t)y * (size_t)tx + (size_t)x;
                    if (pass == 0)
                        ++L->bin_start[t + 1];
                    else
                        L->bin_items[fill[t]++] = (uint32_t)s;
                }
        }
        cj_rfree(a, fill);
    }
    return CJ_OK;
}

void cj_rlines_free(cj_rlines *l, const cj_allocator *a) {
    cj_rfree(a, l->segs);
    cj_rfree(a, l->bin_start);
    cj_rfree(a, l->bin_items);
    memset(l, 0, sizeof *l);
}

typedef struct line_px {
    const cj_rseg *s;
    const cj_tile *t;
    float *col;
    double X0, Y0, X1, Y1;
    int xmajor;
    uint64_t pixels;
} line_px;

static void line_pixel(void *user, int x, int y) {
    line_px *u = user;
    double t;
    if (u->xmajor)
        t = u->X1 != u->X0 ? (x - u->X0) / (u->X1 - u->X0) : 0.0;
    else
        t = (y - u->Y0) / (u->Y1 - u->Y0);
    float z = (float)(u->s->z0 + t * ((double)u->s->z1 - u->s->z0));
    const cj_tile *tl = u->t;
    size_t base =
        ((size_t)(y - tl->y0) * (size_t)(tl->x1 - tl->x0) + (size_t)(x - tl->x0)) * (size_t)tl->spp;
    for (int s = 0; s < tl->spp; ++s) {
        cj_vis_sample *vs = &tl->samples[base + (size_t)s];
        if (z < vs->depth) {
            vs->depth = z;
            float *cc = u->col + 4 * (base + (size_t)s);
            cc[0] = u->s->rgb[0];
            cc[1] = u->s->rgb[1];
            cc[2] = u->s->rgb[2];
            cc[3] = 1.0f;
        }
    }
    ++u->pixels;
}

void cj_rlines_tile(const cj_rctx *c, const cj_tile *t, float *col, uint64_t *pixels) {
    const cj_rlines *L = &c->lines;
    cj_line_rect r = {t->x0, t->y0, t->x1 - 1, t->y1 - 1};
    for (size_t k = L->bin_start[t->index]; k < L->bin_start[t->index + 1]; ++k) {
        const cj_rseg *s = &L->segs[L->bin_items[k]];
        line_px u = {s, t, col, floor(s->x0), floor(s->y0), floor(s->x1), floor(s->y1), 0, 0};
        u.xmajor = fabs(u.X1 - u.X0) >= fabs(u.Y1 - u.Y0);
        for (int off = -(s->width - 1) / 2; off <= s->width / 2; ++off) {
            /* a wide line: exact lines shifted by whole pixels along the minor axis */
            double dx = u.xmajor ? 0.0 : off, dy = u.xmajor ? off : 0.0;
            u.X0 = floor(s->x0) + dx;
            u.X1 = floor(s->x1) + dx;
            u.Y0 = floor(s->y0) + dy;
            u.Y1 = floor(s->y1) + dy;
            (void)cj_line_visit_d(s->x0 + dx, s->y0 + dy, s->x1 + dx, s->y1 + dy, r, line_pixel, &u,
                                  NULL);
        }
        *pixels += u.pixels;
    }
}
