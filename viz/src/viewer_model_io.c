/* Curve documents of the viewer as plot JSON files (the format of `casteljau plot`, read by
 * formats/): written atomically with every number round-tripping, read back with cJSON; the
 * "bspline" items through the formats/ B-spline reader and writer (bspline_json.h) that
 * `casteljau plot`, `fit` and `eval --curve` use.
 * Also the plot the viewer draws, built with the same calls the plot reader makes for the
 * written file, so the two pictures are the same pixels. */
#define _POSIX_C_SOURCE 200809L
#include "casteljau/viewer_model.h"

#include "bspline_json.h"
#include "error_internal.h"
#include "file_internal.h"

#include <cJSON.h>

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* ---- the plot -------------------------------------------------------------------------- */

static cj_status add_item(cj_plot *plot, const cj_vcurve *c, const cj_vdoc_display *d, int sel) {
    if (c->kind == CJ_VCURVE_BSPLINE) {
        cj_plot_bspline_opts bo = cj_plot_bspline_defaults();
        bo.color = c->color;
        bo.width = c->width;
        bo.control_polygon = c->control_polygon;
        bo.control_points = c->control_points;
        bo.knot_markers = c->knots;
        const cj_bspline b = cj_vcurve_bspline(c);
        return cj_plot_add_bspline(plot, &b, &bo);
    }
    if (c->kind == CJ_VCURVE_SPLINE)
        return cj_plot_add_spline(plot, c->pts, c->count, &c->spline, c->color, c->width, c->knots);
    cj_plot_bezier_opts o = cj_plot_bezier_defaults();
    o.color = c->color;
    o.width = c->width;
    o.control_polygon = c->control_polygon;
    o.control_points = c->control_points;
    o.hull = c->hull;
    o.normals = c->normals;
    o.nframes = c->nframes;
    memcpy(o.frames_t, c->frames_t, sizeof o.frames_t);
    if (sel && d->construction) {
        o.construction = 1;
        o.construction_t = d->t;
    }
    if (sel && d->frame && o.nframes < CJ_PLOT_MAX_FRAMES) o.frames_t[o.nframes++] = d->t;
    const int deg = (int)c->count - 1;
    if (c->kind == CJ_VCURVE_RATIONAL) {
        cj_rbezier rb = cj_rbezier_view(deg, 2, c->pts, c->weights);
        return cj_plot_add_rbezier(plot, &rb, &o);
    }
    cj_bezier b = cj_bezier_view(deg, 2, c->pts);
    return cj_plot_add_bezier(plot, &b, &o);
}

cj_status cj_vdoc_build_plot(const cj_vdoc *doc, const cj_vview *v, const cj_vdoc_display *disp,
                             cj_plot **out) {
    cj_plot *plot = NULL;
    cj_status st = cj_plot_create(NULL, &plot);
    if (st) return st;
    cj_plot_set_background(plot, disp->background);
    cj_plot_set_axes(plot, 0);
    st = cj_plot_set_margin(plot, 0.0);
    if (!st) st = cj_plot_set_view(plot, v->x0, v->y0, v->x1, v->y1);
    for (size_t i = 0; !st && i < cj_vdoc_curve_count(doc); ++i)
        st = add_item(plot, cj_vdoc_curve(doc, i), disp, (long)i == disp->curve);
    if (st) {
        cj_plot_destroy(plot);
        return st;
    }
    *out = plot;
    return CJ_OK;
}

/* ---- writing --------------------------------------------------------------------------- */

static void put_color(FILE *f, cj_rgba c) {
    fprintf(f, "\"#%02x%02x%02x%02x\"", c.r, c.g, c.b, c.a);
}

static void put_points(FILE *f, const double *p, size_t n) {
    fputc('[', f);
    for (size_t i = 0; i < n; ++i)
        fprintf(f, "%s[%.17g, %.17g]", i ? ", " : "", p[2 * i], p[2 * i + 1]);
    fputc(']', f);
}

static void put_curve(FILE *f, const cj_vcurve *c, const cj_vdoc_display *d, int sel) {
    if (c->kind == CJ_VCURVE_BSPLINE) { /* the formats/ writer of `casteljau fit` */
        char style[256];
        snprintf(style, sizeof style,
                 "\"width\": %.17g, \"control_polygon\": %s, \"control_points\": %s, "
                 "\"knot_markers\": %s, \"color\": \"#%02x%02x%02x%02x\"",
                 c->width, c->control_polygon ? "true" : "false",
                 c->control_points ? "true" : "false", c->knots ? "true" : "false", c->color.r,
                 c->color.g, c->color.b, c->color.a);
        const cj_bspline b = cj_vcurve_bspline(c);
        bsp_json_write_styled(f, &b, "    ", style);
        return;
    }
    if (c->kind == CJ_VCURVE_SPLINE) {
        static const char *const kinds[] = {"uniform", "centripetal", "chordal"};
        fprintf(f,
                "    {\"type\": \"catmull-rom\", \"kind\": \"%s\", \"tension\": %.17g, "
                "\"closed\": %s, \"knots\": %s, \"width\": %.17g, \"color\": ",
                kinds[c->spline.kind], c->spline.tension, c->spline.closed ? "true" : "false",
                c->knots ? "true" : "false", c->width);
        put_color(f, c->color);
        fputs(",\n     \"points\": ", f);
        put_points(f, c->pts, c->count);
        fputc('}', f);
        return;
    }
    fprintf(f,
            "    {\"type\": \"bezier\", \"width\": %.17g, \"control_polygon\": %s, "
            "\"control_points\": %s, \"hull\": %s, \"normals\": %s, \"color\": ",
            c->width, c->control_polygon ? "true" : "false", c->control_points ? "true" : "false",
            c->hull ? "true" : "false", c->normals ? "true" : "false");
    put_color(f, c->color);
    if (sel && d->construction) fprintf(f, ", \"construction_t\": %.17g", d->t);
    const int extra = sel && d->frame && c->nframes < CJ_PLOT_MAX_FRAMES;
    if (c->nframes || extra) {
        fputs(", \"frames_t\": [", f);
        for (size_t i = 0; i < c->nframes; ++i)
            fprintf(f, "%s%.17g", i ? ", " : "", c->frames_t[i]);
        if (extra) fprintf(f, "%s%.17g", c->nframes ? ", " : "", d->t);
        fputc(']', f);
    }
    fputs(",\n     \"points\": ", f);
    put_points(f, c->pts, c->count);
    if (c->weights) {
        fputs(",\n     \"weights\": [", f);
        for (size_t i = 0; i < c->count; ++i) fprintf(f, "%s%.17g", i ? ", " : "", c->weights[i]);
        fputc(']', f);
    }
    fputc('}', f);
}

cj_status cj_vdoc_save_json(const cj_vdoc *doc, const cj_vview *v, const cj_vdoc_display *disp,
                            const char *path) {
    for (size_t i = 0; i < cj_vdoc_curve_count(doc); ++i)
        if (cj_vdoc_curve(doc, i)->kind == CJ_VCURVE_SPLINE &&
            cj_vdoc_curve(doc, i)->spline.kind == CJ_SPLINE_KOCHANEK_BARTELS)
            return cj_fail(CJ_ERR_UNSUPPORTED,
                           "%s: curve %zu is a Kochanek-Bartels spline, which plot JSON cannot "
                           "describe",
                           path, i);
    const size_t n = strlen(path);
    char *tmp = malloc(n + 16);
    if (!tmp) return cj_fail(CJ_ERR_NOMEM, "%s: out of memory", path);
    memcpy(tmp, path, n);
    memcpy(tmp + n, ".tmp.XXXXXX", 12);
    const int fd = mkstemp(tmp);
    if (fd < 0) {
        cj_status st =
            cj_fail(CJ_ERR_IO, "%s: cannot create a temporary file: %s", path, strerror(errno));
        free(tmp);
        return st;
    }
    /* mkstemp made it 0600: give it the mode of the file it replaces, else 0666 & ~umask */
    struct stat sb;
    mode_t mode;
    if (stat(path, &sb) == 0) {
        mode = sb.st_mode & 07777;
    } else {
        mode = umask(0);
        umask(mode);
        mode = 0666 & ~mode;
    }
    (void)fchmod(fd, mode);
    FILE *f = fdopen(fd, "w");
    if (!f) {
        close(fd);
        unlink(tmp);
        free(tmp);
        return cj_fail(CJ_ERR_IO, "%s: cannot write: %s", path, strerror(errno));
    }
    fprintf(f, "{\"width\": %d, \"height\": %d, \"background\": ", v->width, v->height);
    put_color(f, disp->background);
    fprintf(f,
            ", \"axes\": false, \"margin\": 0,\n \"view\": [%.17g, %.17g, %.17g, %.17g],\n"
            " \"items\": [\n",
            v->x0, v->y0, v->x1, v->y1);
    for (size_t i = 0; i < cj_vdoc_curve_count(doc); ++i) {
        put_curve(f, cj_vdoc_curve(doc, i), disp, (long)i == disp->curve);
        fputs(i + 1 < cj_vdoc_curve_count(doc) ? ",\n" : "\n", f);
    }
    fputs(" ]}\n", f);
    int bad = fflush(f) != 0 || ferror(f) || fsync(fileno(f)) != 0;
    const int err = errno;
    bad |= fclose(f) != 0;
    if (!bad && rename(tmp, path) != 0) bad = 1;
    cj_status st = CJ_OK;
    if (bad) {
        unlink(tmp);
        st = cj_fail(CJ_ERR_IO, "%s: write failed: %s", path, strerror(err ? err : errno));
    }
    free(tmp);
    return st;
}

/* ---- reading --------------------------------------------------------------------------- */

typedef struct rd {
    const char *path;
} rd;

static cj_status bad(const rd *r, const char *where, const char *what) {
    return cj_fail(CJ_ERR_PARSE, "%s: %s %s", r->path, where, what);
}

static int get_bool(const cJSON *o, const char *k, int *out) {
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(o, k);
    if (!v) return 0;
    if (!cJSON_IsBool(v)) return -1;
    *out = cJSON_IsTrue(v);
    return 0;
}

static int get_num(const cJSON *o, const char *k, double *out) {
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(o, k);
    if (!v) return 0;
    if (!cJSON_IsNumber(v) || !isfinite(v->valuedouble)) return -1;
    *out = v->valuedouble;
    return 0;
}

static int parse_color(const cJSON *v, cj_rgba *out) {
    unsigned r, g, b, a = 255;
    if (!cJSON_IsString(v) || v->valuestring[0] != '#') return -1;
    const char *s = v->valuestring + 1;
    const size_t n = strlen(s);
    if (strspn(s, "0123456789abcdefABCDEF") != n) return -1;
    if (n == 6 || n == 8) {
        if (sscanf(s, "%2x%2x%2x", &r, &g, &b) != 3) return -1;
        if (n == 8 && sscanf(s + 6, "%2x", &a) != 1) return -1;
    } else if (n == 3) {
        if (sscanf(s, "%1x%1x%1x", &r, &g, &b) != 3) return -1;
        r *= 17, g *= 17, b *= 17;
    } else {
        return -1;
    }
    *out = cj_rgba_make((uint8_t)r, (uint8_t)g, (uint8_t)b, (uint8_t)a);
    return 0;
}

static cj_status read_points(const rd *r, const cJSON *a, const char *where, double **pts,
                             size_t *n) {
    if (!cJSON_IsArray(a)) return bad(r, where, "is not an array of [x, y] points");
    *n = (size_t)cJSON_GetArraySize(a);
    *pts = malloc((*n ? *n : 1) * 2 * sizeof(double));
    if (!*pts) return cj_fail(CJ_ERR_NOMEM, "%s: out of memory", r->path);
    size_t i = 0;
    for (const cJSON *p = a->child; p; p = p->next, ++i) {
        if (!cJSON_IsArray(p) || cJSON_GetArraySize(p) != 2 || !cJSON_IsNumber(p->child) ||
            !cJSON_IsNumber(p->child->next)) {
            free(*pts);
            return cj_fail(CJ_ERR_PARSE, "%s: %s[%zu] is not a pair of numbers", r->path, where, i);
        }
        (*pts)[2 * i] = p->child->valuedouble;
        (*pts)[2 * i + 1] = p->child->next->valuedouble;
    }
    return CJ_OK;
}

static const cj_rgba palette[] = {{0x1f, 0x77, 0xb4, 255}, {0xff, 0x7f, 0x0e, 255},
                                  {0x2c, 0xa0, 0x2c, 255}, {0xd6, 0x27, 0x28, 255},
                                  {0x94, 0x67, 0xbd, 255}, {0x8c, 0x56, 0x4b, 255},
                                  {0xe3, 0x77, 0xc2, 255}, {0x17, 0xbe, 0xcf, 255}};

/* A "bspline" item, read by the formats/ reader of `casteljau plot` and `eval --curve`; the
 * drawing options are the plot's (plot_json_bspline.c). */
static cj_status read_bspline(const rd *r, const cJSON *it, size_t idx, const char *where,
                              cj_vdoc *doc) {
    static const char *const extra[] = {"color",          "width",        "control_polygon",
                                        "control_points", "knot_markers", NULL};
    bsp_json b;
    char why[400];
    if (bsp_json_parse(it, where, extra, (size_t)1 << 20, &b, why, sizeof why))
        return cj_fail(CJ_ERR_PARSE, "%s: %s", r->path, why);
    cj_status st = CJ_OK;
    if (b.dim != 2)
        st = cj_fail(CJ_ERR_PARSE,
                     "%s: %s.points: the editor edits 2D B-splines, not %d coordinates", r->path,
                     where, b.dim);
    cj_vcurve c = cj_vcurve_init(CJ_VCURVE_BSPLINE, (size_t)b.npts, b.pts, b.weights);
    c.degree = b.degree;
    c.knot_vector = b.knots;
    c.color = palette[idx % 8];
    const cj_plot_bspline_opts d = cj_plot_bspline_defaults();
    c.width = d.width;
    c.control_polygon = d.control_polygon;
    c.control_points = d.control_points;
    c.knots = d.knot_markers;
    const cJSON *col = cJSON_GetObjectItemCaseSensitive(it, "color");
    int e = col ? parse_color(col, &c.color) : 0;
    e |= get_num(it, "width", &c.width);
    e |= get_bool(it, "control_polygon", &c.control_polygon);
    e |= get_bool(it, "control_points", &c.control_points);
    e |= get_bool(it, "knot_markers", &c.knots);
    if (!st && e) st = bad(r, where, "has a drawing option of the wrong type or value");
    if (!st && (st = cj_vdoc_add_curve(doc, &c)))
        st = cj_fail(st, "%s: %s: %s", r->path, where, cj_last_error());
    bsp_json_free(&b);
    return st;
}

static cj_status read_item(const rd *r, const cJSON *it, size_t idx, cj_vdoc *doc,
                           cj_vdoc_display *disp) {
    char where[64];
    snprintf(where, sizeof where, "items[%zu]", idx);
    const cJSON *type = cJSON_GetObjectItemCaseSensitive(it, "type");
    if (!cJSON_IsString(type)) return bad(r, where, "has no \"type\" string");
    const int spline = !strcmp(type->valuestring, "catmull-rom");
    if (!strcmp(type->valuestring, "bspline")) return read_bspline(r, it, idx, where, doc);
    if (!spline && strcmp(type->valuestring, "bezier"))
        return cj_fail(CJ_ERR_PARSE,
                       "%s: %s is a '%s' item; the editor edits bezier, bspline and "
                       "catmull-rom items only",
                       r->path, where, type->valuestring);
    double *pts = NULL, *w = NULL;
    size_t n = 0;
    char pw[96];
    snprintf(pw, sizeof pw, "%s.points", where);
    cj_status st = read_points(r, cJSON_GetObjectItemCaseSensitive(it, "points"), pw, &pts, &n);
    if (st) return st;
    cj_vcurve c = cj_vcurve_init(spline ? CJ_VCURVE_SPLINE : CJ_VCURVE_BEZIER, n, pts, NULL);
    c.color = palette[idx % 8]; /* the plot reader's default colours */
    const cJSON *col = cJSON_GetObjectItemCaseSensitive(it, "color");
    int e = col ? parse_color(col, &c.color) : 0;
    e |= get_num(it, "width", &c.width);
    double ct = -1.0;
    if (spline) {
        e |= get_num(it, "tension", &c.spline.tension);
        e |= get_bool(it, "closed", &c.spline.closed);
        e |= get_bool(it, "knots", &c.knots);
        const cJSON *k = cJSON_GetObjectItemCaseSensitive(it, "kind");
        if (k) {
            const char *s = cJSON_IsString(k) ? k->valuestring : "";
            c.spline.kind = !strcmp(s, "centripetal") ? CJ_SPLINE_CENTRIPETAL
                            : !strcmp(s, "chordal")   ? CJ_SPLINE_CHORDAL
                                                      : CJ_SPLINE_CATMULL_ROM;
            e |= strcmp(s, "uniform") && c.spline.kind == CJ_SPLINE_CATMULL_ROM;
        }
    } else {
        e |= get_bool(it, "control_polygon", &c.control_polygon);
        e |= get_bool(it, "control_points", &c.control_points);
        e |= get_bool(it, "hull", &c.hull);
        e |= get_bool(it, "normals", &c.normals);
        e |= get_num(it, "construction_t", &ct);
        const cJSON *ft = cJSON_GetObjectItemCaseSensitive(it, "frames_t");
        if (ft) {
            if (!cJSON_IsArray(ft) || cJSON_GetArraySize(ft) > CJ_PLOT_MAX_FRAMES) e = -1;
            for (const cJSON *x = ft ? ft->child : NULL; !e && x; x = x->next) {
                if (!cJSON_IsNumber(x))
                    e = -1;
                else
                    c.frames_t[c.nframes++] = x->valuedouble;
            }
        }
        const cJSON *wv = cJSON_GetObjectItemCaseSensitive(it, "weights");
        if (wv && !e) {
            if (!cJSON_IsArray(wv) || (size_t)cJSON_GetArraySize(wv) != n ||
                !(w = malloc((n ? n : 1) * sizeof *w))) {
                e = -1;
            } else {
                size_t i = 0;
                for (const cJSON *x = wv->child; x; x = x->next, ++i) {
                    if (!cJSON_IsNumber(x)) e = -1;
                    w[i] = cJSON_IsNumber(x) ? x->valuedouble : 1.0;
                }
                c.kind = CJ_VCURVE_RATIONAL;
                c.weights = w;
            }
        }
    }
    if (e) st = bad(r, where, "has a field of the wrong type or value");
    if (!st && ct >= 0.0) {
        if (ct > 1.0) st = bad(r, where, "construction_t is not in [0, 1]");
        disp->curve = (long)idx;
        disp->t = ct;
        disp->construction = 1;
    }
    if (!st) st = cj_vdoc_add_curve(doc, &c);
    if (st && st != CJ_ERR_PARSE) st = cj_fail(st, "%s: %s: %s", r->path, where, cj_last_error());
    free(pts);
    free(w);
    return st;
}

cj_status cj_vdoc_load_json(const char *path, cj_vdoc **out, cj_vview *v, cj_vdoc_display *disp) {
    rd r = {path};
    char *text = NULL;
    size_t len = 0;
    cj_status rs = cj_file_read_all(path, CJ_FILE_MAX_BYTES, "viewer document", &text, &len);
    if (rs) return rs;
    cJSON *root = cJSON_Parse(text);
    free(text);
    if (!root) return cj_fail(CJ_ERR_PARSE, "%s: not a JSON document (syntax error)", path);
    cj_vdoc *doc = NULL;
    cj_status st = cj_vdoc_create(&doc);
    cj_vdoc_display d = {cj_rgba_make(255, 255, 255, 255), -1, 0.5, 0, 0};
    cj_vview view = {0, 0, 1, 1, 800, 600};
    double wd = 800, ht = 600, box[4];
    int have_view = 0;
    if (!st && !cJSON_IsObject(root)) st = bad(&r, "the document", "is not an object");
    if (!st && cJSON_GetObjectItemCaseSensitive(root, "panels"))
        st = bad(&r, "the document", "has panels; the editor edits a single plot");
    if (!st && (get_num(root, "width", &wd) || get_num(root, "height", &ht) || wd < 64 || ht < 64 ||
                wd > 8192 || ht > 8192 || wd != floor(wd) || ht != floor(ht)))
        st = bad(&r, "width/height", "is not a whole number of pixels in [64, 8192]");
    const cJSON *bg = cJSON_GetObjectItemCaseSensitive(root, "background");
    if (!st && bg && parse_color(bg, &d.background))
        st = bad(&r, "background", "is not a colour \"#rrggbb[aa]\"");
    const cJSON *vw = cJSON_GetObjectItemCaseSensitive(root, "view");
    if (!st && vw) {
        int k = 0;
        for (const cJSON *x = cJSON_IsArray(vw) ? vw->child : NULL; x && k < 4; x = x->next)
            box[k++] = cJSON_IsNumber(x) ? x->valuedouble : NAN;
        if (k != 4 || cJSON_GetArraySize(vw) != 4 || !(box[0] < box[2]) || !(box[1] < box[3]) ||
            !isfinite(box[2] - box[0]) || !isfinite(box[3] - box[1]))
            st = bad(&r, "view", "is not [x0, y0, x1, y1] with x0 < x1 and y0 < y1");
        have_view = 1;
    }
    const cJSON *items = cJSON_GetObjectItemCaseSensitive(root, "items");
    if (!st && (!cJSON_IsArray(items) || !cJSON_GetArraySize(items)))
        st = bad(&r, "items", "is missing or not a non-empty array");
    size_t i = 0;
    for (const cJSON *it = st ? NULL : items->child; it && !st; it = it->next, ++i)
        st = read_item(&r, it, i, doc, &d);
    cJSON_Delete(root);
    if (st) {
        cj_vdoc_destroy(doc);
        return st;
    }
    view.width = (int)wd;
    view.height = (int)ht;
    if (have_view)
        view.x0 = box[0], view.y0 = box[1], view.x1 = box[2], view.y1 = box[3];
    else
        cj_vview_fit(&view, doc, 0.1);
    cj_vdoc_clear_log(doc); /* a freshly loaded document has nothing to undo */
    *out = doc;
    *v = view;
    *disp = d;
    return CJ_OK;
}
