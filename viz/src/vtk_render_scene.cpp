// VTK rendering and export of a scene's drawn mesh (cj_vtk_renderer_create_scene,
// cj_vtk_write_scene): the mesh split into one VTK object per object id, with the material of
// the node carrying that id, seen with the scene's camera and lights.
#include "casteljau/vtk_render.h"

#include "error_internal.h"

#include <cassert>
#include <cstdint>
#include <new>
#include <vector>

namespace {

// The view and per-object meshes of a scene; owns the sub-meshes.
struct scene_split {
    cj_vtk_view view{};
    std::vector<cj_light> lights;
    std::vector<cj_mesh *> meshes;
    std::vector<cj_vtk_object> objects;
    ~scene_split() {
        for (cj_mesh *m : meshes) cj_mesh_destroy(m);
    }
};

cj_status split_scene(const cj_scene *scene, const cj_mesh *mesh, int width, int height,
                      unsigned flags, scene_split &out) {
    cj_status st = cj_scene_check(scene);
    if (st != CJ_OK) return st;
    if (mesh->triangle_count == 0)
        return cj_fail(CJ_ERR_ARGUMENT, "the scene's mesh has no triangles");
    const cj_scene_settings *set = cj_scene_get_settings(scene);
    cj_vtk_view &view = out.view;
    view.camera = *cj_scene_get_camera(scene);
    view.light_count = cj_scene_light_count(scene);
    for (size_t i = 0; i < view.light_count; i++)
        out.lights.push_back(*cj_scene_light(scene, (int)i));
    view.lights = out.lights.empty() ? nullptr : out.lights.data();
    view.background = set->background;
    view.width = width > 0 ? width : set->width;
    view.height = height > 0 ? height : set->height;
    view.flags = flags;

    // object id -> node index
    std::vector<int> node_of;
    const size_t nodes = cj_scene_node_count(scene);
    for (size_t i = 0; i < nodes; i++) {
        const cj_node *n = cj_scene_node(scene, (int)i);
        if (n->geometry < 0 || !cj_scene_node_shown(scene, (int)i)) continue;
        if (node_of.size() <= n->id) node_of.resize(n->id + 1, -1);
        node_of[n->id] = (int)i;
    }
    // One sub-mesh per id, vertices renumbered in first-use order.
    std::vector<uint32_t> remap(mesh->vertex_count, UINT32_MAX);
    std::vector<int32_t> remap_owner(mesh->vertex_count, -1);
    std::vector<int> slot(node_of.size(), -1);
    for (size_t t = 0; t < mesh->triangle_count; t++) {
        const int32_t id = mesh->triangle_patch[t];
        if (id <= 0 || (size_t)id >= node_of.size() || node_of[id] < 0)
            return cj_fail(CJ_ERR_ARGUMENT,
                           "scene mesh triangle %zu has object id %d, which names no visible "
                           "object",
                           t, (int)id);
        if (slot[id] < 0) {
            cj_mesh *m = nullptr;
            if ((st = cj_mesh_create(nullptr, &m)) != CJ_OK) return st;
            out.meshes.push_back(m);
            const cj_node *n = cj_scene_node(scene, node_of[id]);
            cj_vtk_object o = {m, cj_scene_material(scene, n->material), (uint32_t)id};
            slot[id] = (int)out.objects.size();
            out.objects.push_back(o);
        }
        cj_mesh *m = out.meshes[slot[id]];
        uint32_t v[3];
        for (int k = 0; k < 3; k++) {
            const uint32_t src = mesh->triangles[3 * t + k];
            if (src >= mesh->vertex_count)
                return cj_fail(CJ_ERR_RANGE, "scene mesh triangle %zu names vertex %u of %zu", t,
                               (unsigned)src, mesh->vertex_count);
            if (remap_owner[src] != id) {
                if ((st = cj_mesh_add_vertex(m, mesh->positions + 3 * src, mesh->normals + 3 * src,
                                             mesh->uvs + 2 * src, &remap[src])) != CJ_OK)
                    return st;
                remap_owner[src] = id;
            }
            v[k] = remap[src];
        }
        if ((st = cj_mesh_add_triangle(m, v[0], v[1], v[2], id)) != CJ_OK) return st;
    }
    return CJ_OK;
}

} // namespace

cj_status cj_vtk_renderer_create_scene(const cj_scene *scene, const cj_mesh *mesh, int width,
                                       int height, unsigned flags, cj_vtk_renderer **out) {
    assert(scene && mesh && out);
    try {
        scene_split s;
        cj_status st = split_scene(scene, mesh, width, height, flags, s);
        if (st != CJ_OK) return st;
        return cj_vtk_renderer_create(&s.view, s.objects.data(), s.objects.size(), out);
    } catch (const std::bad_alloc &) {
        return cj_fail(CJ_ERR_NOMEM, "splitting the scene mesh for VTK");
    }
}

cj_status cj_vtk_write_scene(const char *path, const cj_scene *scene, const cj_mesh *mesh,
                             int width, int height) {
    assert(path && scene && mesh);
    try {
        scene_split s;
        cj_status st = split_scene(scene, mesh, width, height, 0, s);
        if (st != CJ_OK) return st;
        return cj_vtk_write_scene_mesh(path, &s.view, s.objects.data(), s.objects.size());
    } catch (const std::bad_alloc &) {
        return cj_fail(CJ_ERR_NOMEM, "splitting the scene mesh for VTK");
    }
}
