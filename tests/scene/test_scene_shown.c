/* The one walk up the parent chain for visibility (cj_scene_node_shown, cj_scene_nodes_shown in
 * scene/src/scene.c), which the renderers' scene pass, the viewer and the VTK export share: a
 * hidden group hides its whole subtree, a hidden leaf only itself; the per-node walk and the
 * one-pass table agree on every node of a seeded random hierarchy, and an index that names no
 * node is not shown. */
#include "casteljau/scene.h"

#include "check.h"
#include "rng.h"

#include <stdio.h>
#include <string.h>

static int add_node(cj_scene *s, int parent, int geometry, int material, int visible) {
    cj_node n = cj_node_defaults(geometry, material);
    n.parent = parent;
    n.visible = visible;
    int index = -1;
    cj_status st = cj_scene_add_node(s, &n, &index);
    CHECK(st == CJ_OK, "add node: %s", cj_last_error());
    return index;
}

int main(void) {
    cj_scene *s = NULL;
    if (cj_scene_create(NULL, &s)) return 1;
    cj_geometry g;
    memset(&g, 0, sizeof g);
    g.kind = CJ_GEOM_SPHERE;
    g.u.sphere.radius = 1.0;
    int gi = -1, mi = -1;
    cj_material m = cj_material_defaults();
    CHECK(!cj_scene_add_geometry(s, &g, &gi) && !cj_scene_add_material(s, &m, &mi), "%s",
          cj_last_error());

    /* root group (shown) > hidden group > leaf (visible itself) ; root > hidden leaf */
    const int root = add_node(s, -1, -1, -1, 1);
    const int hidden_group = add_node(s, root, -1, -1, 0);
    const int under_hidden = add_node(s, hidden_group, gi, mi, 1);
    const int hidden_leaf = add_node(s, root, gi, mi, 0);
    const int shown_leaf = add_node(s, root, gi, mi, 1);
    CHECK(cj_scene_node_shown(s, root), "the root group is shown");
    CHECK(!cj_scene_node_shown(s, hidden_group), "a hidden group is not shown");
    CHECK(!cj_scene_node_shown(s, under_hidden), "a visible leaf under a hidden group is hidden");
    CHECK(!cj_scene_node_shown(s, hidden_leaf), "a hidden leaf is not shown");
    CHECK(cj_scene_node_shown(s, shown_leaf), "a visible leaf under shown groups is shown");
    CHECK(!cj_scene_node_shown(s, -1) && !cj_scene_node_shown(s, 99), "no node, not shown");
    printf("hand-built hierarchy: a hidden group hides its subtree, a hidden leaf only itself\n");

    /* seeded random forest: the walk and the table agree, and both match the definition */
    const uint64_t seed = cj_test_seed("test_scene_shown", 26);
    cj_rng rng;
    cj_rng_init(&rng, seed);
    int groups[64], ngroups = 1;
    groups[0] = root;
    for (int i = 0; i < 400; ++i) {
        const int parent = cj_rng_int(&rng, 0, 3) ? groups[cj_rng_int(&rng, 0, ngroups - 1)] : -1;
        const int group = ngroups < 64 && cj_rng_int(&rng, 0, 2) == 0;
        const int idx =
            add_node(s, parent, group ? -1 : gi, group ? -1 : mi, cj_rng_int(&rng, 0, 4) != 0);
        if (group) groups[ngroups++] = idx;
    }
    const size_t n = cj_scene_node_count(s);
    unsigned char shown[512];
    cj_scene_nodes_shown(s, shown);
    size_t agree = 0, hidden = 0;
    for (size_t i = 0; i < n; ++i) {
        int expect = 1; /* the definition, written out: every node up the chain is visible */
        for (int k = (int)i; k >= 0; k = cj_scene_node(s, k)->parent)
            expect &= cj_scene_node(s, k)->visible != 0;
        CHECK(shown[i] == expect && cj_scene_node_shown(s, (int)i) == expect,
              "node %zu: table %d, walk %d, definition %d (seed %llu)", i, shown[i],
              cj_scene_node_shown(s, (int)i), expect, (unsigned long long)seed);
        agree += shown[i] == expect;
        hidden += !expect;
    }
    printf("random forest of %zu nodes (seed %llu): table and walk agree with the definition on "
           "%zu nodes, %zu of them hidden\n",
           n, (unsigned long long)seed, agree, hidden);
    cj_scene_destroy(s);
    return cj_check_exit();
}
