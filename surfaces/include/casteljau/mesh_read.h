/* casteljau: reading triangle meshes from Wavefront OBJ and PLY files into a cj_mesh.
 *
 * OBJ: `v x y z [w]`, `vt u v [w]`, `vn x y z`, `f` with 3 or more corners written as `v`,
 * `v/vt`, `v//vn` or `v/vt/vn` (1-based; negative indices count back from the last element
 * read so far). Polygons are fan-triangulated (corner 0, k, k+1). One mesh vertex is made per
 * distinct (v, vt, vn) triple, in order of first use, so the seams of a textured or
 * sharp-edged model stay split. `g patch_N` (as cj_mesh_write_obj writes it) sets the patch id
 * N of the following triangles; other `g` names number the groups 0, 1, 2, ... in order of
 * first appearance. `o`, `s`, `usemtl`, `mtllib`, `l`, `p` and comments are ignored; any other
 * statement is an error.
 *
 * PLY: `format ascii 1.0` or `format binary_little_endian 1.0`; element `vertex` with
 * properties x y z (required), nx ny nz, and u v or s t (texture_u/texture_v too), of any
 * scalar type (char..double, int8..float64); element `face` with a list property
 * vertex_indices (or vertex_index) of any integer count/index types; faces are fan-triangulated.
 * Other elements and properties are read and ignored.
 *
 * Vertices without a normal get the area-weighted average of the normals of the triangles
 * around them (zero if they have none); vertices without (u, v) get (0, 0). Files written by
 * cj_mesh_write_obj / cj_mesh_write_ply read back to the same triangles, positions, normals,
 * (u, v) and patch ids, bit for bit (doubles are written with 17 significant digits).
 *
 * Errors name the file and the line (OBJ, ASCII PLY) or the element and its index (binary
 * PLY): "model.obj:12: face corner 3 names vertex 40 of 38", "model.ply: face 7: vertex index
 * 12 out of range (10 vertices)". Status: CJ_ERR_IO (cannot open or read), CJ_ERR_PARSE
 * (malformed statement, unknown OBJ statement, unsupported PLY format), CJ_ERR_RANGE (an
 * index out of range, a face with fewer than 3 corners), CJ_ERR_NONFINITE (a NaN/Inf
 * coordinate), CJ_ERR_EMPTY (no triangles), CJ_ERR_NOMEM. *out is set only on success.
 */
#ifndef CASTELJAU_MESH_READ_H
#define CASTELJAU_MESH_READ_H

#include "casteljau/alloc.h"
#include "casteljau/mesh.h"
#include "casteljau/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Reads an OBJ file into a new mesh (alloc may be NULL). */
cj_status cj_mesh_read_obj(const char *path, const cj_allocator *alloc, cj_mesh **out);
/* Reads a PLY file (ASCII or binary little endian) into a new mesh. */
cj_status cj_mesh_read_ply(const char *path, const cj_allocator *alloc, cj_mesh **out);
/* By extension: ".obj" or ".ply" (any case); others CJ_ERR_ARGUMENT. */
cj_status cj_mesh_read(const char *path, const cj_allocator *alloc, cj_mesh **out);

/* Sets every vertex normal to the normalised sum of (b - a) x (c - a) over the triangles
 * (a, b, c) using the vertex (area-weighted face normals); zero for a vertex no triangle with
 * non-zero area uses. */
void cj_mesh_compute_normals(cj_mesh *mesh);

#ifdef __cplusplus
}
#endif
#endif
