/* The shared scene pass: see render_scene.h. */
#include "render_scene.h"

#include "error_internal.h"
#include "render_internal.h"

#include <string.h>

static unsigned kind_feature(int kind) {
    switch (kind) {
    case CJ_GEOM_CURVE:
        return 0u;
    case CJ_GEOM_PATCHES:
    case CJ_GEOM_REVOLUTION:
    case CJ_GEOM_GEN_CYLINDER:
        return CJ_RF_PATCHES;
    case CJ_GEOM_MESH:
        return CJ_RF_MESHES;
    default:
        return CJ_RF_SURFACES;
    }
}

cj_status cj_rscene_prepare(const cj_scene *scene, const cj_allocator *alloc, cj_rscene *out) {
    memset(out, 0, sizeof *out);
    out->alloc = cj_render_alloc(alloc);
    out->scene = scene;
    out->overlay_node = -1;
    size_t n = cj_scene_node_count(scene);
    out->node_count = n;
    /* `visible` of the subtree, kept apart from `drawn` (groups are visible but not drawn) */
    uint8_t *shown = cj_ralloc(&out->alloc, n ? n : 1);
    out->drawn = cj_ralloc(&out->alloc, n ? n : 1);
    out->world = cj_ralloc(&out->alloc, sizeof(cj_xform3) * (n ? n : 1));
    const int nm = (int)cj_scene_material_count(scene);
    out->material_count = nm;
    out->material_used = cj_ralloc(&out->alloc, (size_t)nm + 1);
    out->material_order = cj_ralloc(&out->alloc, sizeof(int) * ((size_t)nm + 1));
    if (!shown || !out->drawn || !out->world || !out->material_used || !out->material_order) {
        cj_rfree(&out->alloc, shown);
        cj_rscene_free(out);
        return cj_fail(CJ_ERR_NOMEM, "scene pass over %zu nodes", n);
    }
    memset(out->material_used, 0, (size_t)nm + 1);
    cj_status st = CJ_OK;
    cj_scene_nodes_shown(scene, shown);
    for (size_t i = 0; i < n && !st; ++i) {
        const cj_node *nd = cj_scene_node(scene, (int)i);
        out->drawn[i] = shown[i] && nd->geometry >= 0;
        if (nd->overlay.flags & CJ_OVERLAY_NORMALS) out->features |= CJ_RF_NORMALS_OVERLAY;
        if (!out->drawn[i]) continue;
        ++out->drawn_count;
        st = cj_scene_node_world(scene, (int)i, &out->world[i]);
        const cj_geometry *g = cj_scene_geometry(scene, nd->geometry);
        if ((g->kind == CJ_GEOM_CURVE || nd->overlay.flags) && out->overlay_node < 0) {
            out->overlay_node = (int)i;
            out->features |= CJ_RF_OVERLAYS;
        }
        out->features |= kind_feature(g->kind);
        if (g->kind == CJ_GEOM_CURVE) continue;
        const int m = nd->material >= 0 ? nd->material : nm;
        if (!out->material_used[m]) {
            out->material_used[m] = 1;
            out->material_order[out->material_order_count++] = m;
        }
    }
    cj_rfree(&out->alloc, shown);
    if (st) cj_rscene_free(out);
    return st;
}

void cj_rscene_free(cj_rscene *rs) {
    cj_rfree(&rs->alloc, rs->drawn);
    cj_rfree(&rs->alloc, rs->world);
    cj_rfree(&rs->alloc, rs->material_used);
    cj_rfree(&rs->alloc, rs->material_order);
    rs->drawn = NULL;
    rs->world = NULL;
    rs->material_used = NULL;
    rs->material_order = NULL;
}
