/* The scene pass of a frame, shared by both back ends: ONE walk over the nodes that records,
 * per node, whether it is drawn (itself and every ancestor visible: parents come before their
 * children, so each node looks at its parent's flag only) and its world transform, and what
 * the drawn objects use (the feature mask). Each back end then derives its own lights and
 * materials from it and never walks the hierarchy again. */
#ifndef CJ_RENDER_SCENE_H
#define CJ_RENDER_SCENE_H

#include "casteljau/alloc.h"
#include "casteljau/scene.h"
#include "casteljau/status.h"

#include <stddef.h>
#include <stdint.h>

/* Feature bits of the drawn objects. */
enum {
    CJ_RF_PATCHES = 1u,         /* Bézier patch sets, surfaces of revolution, general cylinders */
    CJ_RF_SURFACES = 2u,        /* analytic surfaces (quadrics, spheres, tori, ...) */
    CJ_RF_MESHES = 4u,          /* triangle meshes */
    CJ_RF_OVERLAYS = 8u,        /* a drawn node is a curve or has overlays */
    CJ_RF_NORMALS_OVERLAY = 16u /* some node (drawn or not) asks for a normals overlay */
};

typedef struct cj_rscene {
    const cj_scene *scene;
    size_t node_count;
    uint8_t *drawn;     /* per node: has geometry, and it and every ancestor are visible */
    cj_xform3 *world;   /* per node: object -> world (cj_scene_node_world) where drawn */
    unsigned features;  /* CJ_RF_* */
    int overlay_node;   /* the first drawn node with overlays or a curve, or -1 */
    size_t drawn_count; /* drawn nodes */
    /* materials of the drawn surfaces (curves excluded), index material_count = the default
     * material of nodes without one: used[m], and the used ones in order of first use (node
     * order), so "the first material that ..." is the same whichever list is read */
    int material_count;
    uint8_t *material_used;
    int *material_order;
    int material_order_count;
    cj_allocator alloc;
} cj_rscene;

/* The pass over a checked scene (cj_scene_check passed). CJ_ERR_NOMEM. */
cj_status cj_rscene_prepare(const cj_scene *scene, const cj_allocator *alloc, cj_rscene *out);
void cj_rscene_free(cj_rscene *rs);

#endif
