/* The one writer of the plot format (plot_json.c documents it): a single-plot page of curves,
 * built as a cJSON tree and printed by cJSON with the JSON writing kit
 * (scene/src/json_write_internal.h), so every number is in its shortest exact form and the file
 * is replaced atomically. What it writes, cj_plot_json_read_page reads back bit-identical. */
#include "plot_json_internal.h"

#include "bspline_json.h"

#include "error_internal.h"
#include "json_write_internal.h"

#include <stdio.h>

static cJSON *color_json(cj_rgba c) {
    char hex[10];
    snprintf(hex, sizeof hex, "#%02x%02x%02x%02x", c.r, c.g, c.b, c.a);
    return cJSON_CreateString(hex);
}

static int add(cJSON *obj, const char *key, cJSON *item) {
    if (item && cJSON_AddItemToObject(obj, key, item)) return 0;
    cJSON_Delete(item);
    return -1;
}

/* A "bspline" item: the B-spline item's own writer, then the plot's drawing options. */
static cJSON *bspline_json(const cj_plot_json_curve *k) {
    const cj_bspline b =
        cj_bspline_view(k->degree, 2, (int)k->count, k->points, k->weights, k->knot_vector);
    cJSON *it = cj_bsp_json_item(&b);
    if (!it) return NULL;
    const cj_plot_bspline_opts *o = &k->bspline_opts;
    int bad = add(it, "control_polygon", cJSON_CreateBool(o->control_polygon));
    bad |= add(it, "control_points", cJSON_CreateBool(o->control_points));
    bad |= add(it, "knot_markers", cJSON_CreateBool(o->knot_markers));
    bad |= cj_json_add_number(it, "width", o->width);
    bad |= add(it, "color", color_json(o->color));
    if (bad) {
        cJSON_Delete(it);
        return NULL;
    }
    return it;
}

static cJSON *curve_json(const cj_plot_json_curve *k) {
    static const char *const kinds[] = {"uniform", "centripetal", "chordal"};
    const cj_plot_bezier_opts *o = &k->bezier;
    if (k->bspline) return bspline_json(k);
    cJSON *it = cJSON_CreateObject();
    if (!it) return NULL;
    int bad = add(it, "type", cJSON_CreateString(k->spline ? "catmull-rom" : "bezier"));
    if (k->spline) {
        bad |= add(it, "kind", cJSON_CreateString(kinds[k->spline_options.kind]));
        bad |= cj_json_add_number(it, "tension", k->spline_options.tension);
        bad |= add(it, "closed", cJSON_CreateBool(k->spline_options.closed));
        bad |= add(it, "knots", cJSON_CreateBool(k->knots));
    } else {
        bad |= add(it, "control_polygon", cJSON_CreateBool(o->control_polygon));
        bad |= add(it, "control_points", cJSON_CreateBool(o->control_points));
        bad |= add(it, "hull", cJSON_CreateBool(o->hull));
        bad |= add(it, "normals", cJSON_CreateBool(o->normals));
        if (o->construction) bad |= cj_json_add_number(it, "construction_t", o->construction_t);
        if (o->nframes) bad |= add(it, "frames_t", cj_json_number_array(o->frames_t, o->nframes));
    }
    bad |= cj_json_add_number(it, "width", o->width);
    bad |= add(it, "color", color_json(o->color));
    bad |= add(it, "points", cj_json_point_array(k->points, k->count, 2));
    if (!k->spline && k->weights)
        bad |= add(it, "weights", cj_json_number_array(k->weights, k->count));
    if (bad) {
        cJSON_Delete(it);
        return NULL;
    }
    return it;
}

/* The page's settings first, then its items. */
static cJSON *page_json(const cj_plot_json_page *page) {
    cJSON *root = cJSON_CreateObject(), *items = cJSON_CreateArray();
    int bad = !root || !items;
    if (!bad) {
        bad |= cj_json_add_number(root, "width", page->width);
        bad |= cj_json_add_number(root, "height", page->height);
        bad |= add(root, "background", color_json(page->background));
        bad |= add(root, "axes", cJSON_CreateBool(page->axes));
        bad |= cj_json_add_number(root, "margin", page->margin);
        if (page->title) bad |= add(root, "title", cJSON_CreateString(page->title));
        if (page->have_view) bad |= add(root, "view", cj_json_number_array(page->view, 4));
    }
    for (size_t i = 0; !bad && i < page->ncurves; ++i) {
        cJSON *it = curve_json(&page->curves[i]);
        if (!it || !cJSON_AddItemToArray(items, it)) {
            cJSON_Delete(it);
            bad = 1;
        }
    }
    if (!bad) {
        bad = add(root, "items", items); /* takes items, also on failure */
        items = NULL;
    }
    if (bad) {
        cJSON_Delete(items);
        cJSON_Delete(root);
        return NULL;
    }
    return root;
}

cj_status cj_plot_json_write_page(const cj_plot_json_page *page, const char *path) {
    for (size_t i = 0; i < page->ncurves; ++i)
        if (page->curves[i].spline &&
            page->curves[i].spline_options.kind != CJ_SPLINE_CATMULL_ROM &&
            page->curves[i].spline_options.kind != CJ_SPLINE_CENTRIPETAL &&
            page->curves[i].spline_options.kind != CJ_SPLINE_CHORDAL)
            return cj_fail(CJ_ERR_UNSUPPORTED,
                           "%s: curve %zu is a Kochanek-Bartels spline, which plot JSON cannot "
                           "describe",
                           path, i);
    cJSON *root = page_json(page);
    if (!root) return cj_fail(CJ_ERR_NOMEM, "%s: out of memory", path);
    const cj_status st = cj_json_write_file(root, path, path);
    cJSON_Delete(root);
    return st;
}

cj_status cj_plot_json_print_fit(FILE *f, const cj_bspline *c, const double *data, int n,
                                 const char *title) {
    cJSON *root = cJSON_CreateObject(), *items = cJSON_CreateArray();
    cJSON *curve = cj_bsp_json_item(c);
    int bad = !root || !items || !curve || add(root, "title", cJSON_CreateString(title)) ||
              !cJSON_AddItemToArray(items, curve);
    if (!bad) curve = NULL; /* owned by items */
    if (!bad && c->dim == 2) {
        cJSON *pts = cJSON_CreateObject();
        bad = !pts || !cJSON_AddItemToArray(items, pts);
        if (bad) cJSON_Delete(pts);
        bad = bad || add(pts, "type", cJSON_CreateString("points")) ||
              cj_json_add_number(pts, "radius", 2) ||
              add(pts, "color", cJSON_CreateString("#d62728")) ||
              add(pts, "points", cj_json_point_array(data, (size_t)n, 2));
    }
    if (!bad) {
        bad = add(root, "items", items); /* takes items, also on failure */
        items = NULL;
    }
    cj_status st = bad ? cj_fail(CJ_ERR_NOMEM, "fit: out of memory writing the document")
                       : cj_json_print(root, 1, f, "fit");
    cJSON_Delete(curve);
    cJSON_Delete(items);
    cJSON_Delete(root);
    return st;
}
