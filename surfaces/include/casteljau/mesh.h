/* casteljau: an indexed triangle mesh with per-vertex position, normal and (u,v), a patch id
 * per triangle, and its export to OBJ and PLY.
 *
 * Layout (all arrays owned by the mesh, grown by the add functions):
 *   positions[3*i+k], normals[3*i+k] (unit, or 0 when unknown), uvs[2*i+{0,1}] for vertex i;
 *   triangles[3*t+{0,1,2}] vertex indices of triangle t, COUNTER-CLOCKWISE SEEN FROM OUTSIDE
 *   (from the side the normals point to); triangle_patch[t] the patch (or surface) id it
 *   came from. Triangles of one patch are contiguous when produced by the tessellators.
 * The fields are public for reading; change them only through the functions below.
 *
 * Memory: cj_mesh_create takes an optional allocator (NULL: malloc/free); every array the
 * mesh owns goes through it; cj_mesh_destroy releases everything.
 *
 * Status codes: CJ_ERR_NOMEM (allocation failed; the mesh is unchanged), CJ_ERR_NONFINITE
 * (a NaN/Inf coordinate added), CJ_ERR_RANGE (a triangle index >= vertex_count, named),
 * CJ_ERR_CAP (more than CJ_MESH_MAX_VERTICES vertices), CJ_ERR_IO (a file could not be written,
 * named with the system's reason), CJ_ERR_ARGUMENT (an unknown file extension).
 */
#ifndef CASTELJAU_MESH_H
#define CASTELJAU_MESH_H

#include "casteljau/alloc.h"
#include "casteljau/status.h"
#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Objects of surfaces/ that own memory take an optional cj_allocator (casteljau/alloc.h). */

#define CJ_MESH_MAX_VERTICES 0x7fffffffu

typedef struct cj_mesh {
    size_t vertex_count;
    size_t triangle_count;
    double *positions;       /* 3 per vertex */
    double *normals;         /* 3 per vertex */
    double *uvs;             /* 2 per vertex */
    uint32_t *triangles;     /* 3 per triangle, CCW from outside */
    int32_t *triangle_patch; /* 1 per triangle */
    /* private */
    size_t vcap_, tcap_;
    cj_allocator alloc_;
} cj_mesh;

/* Creates an empty mesh (*out receives it). alloc may be NULL. */
cj_status cj_mesh_create(const cj_allocator *alloc, cj_mesh **out);
/* Releases the mesh and its arrays; NULL is a no-op. */
void cj_mesh_destroy(cj_mesh *mesh);
/* Empties the mesh, keeping its capacity. */
void cj_mesh_clear(cj_mesh *mesh);
/* Ensures room for `vertices` and `triangles` in total without further allocation. */
cj_status cj_mesh_reserve(cj_mesh *mesh, size_t vertices, size_t triangles);

/* Appends a vertex; normal and uv may be NULL (stored as zeros). *index (may be NULL) receives
 * its index. */
cj_status cj_mesh_add_vertex(cj_mesh *mesh, const double position[3], const double normal[3],
                             const double uv[2], uint32_t *index);
/* Appends triangle (a, b, c), counter-clockwise seen from outside, from patch `patch_id`. */
cj_status cj_mesh_add_triangle(cj_mesh *mesh, uint32_t a, uint32_t b, uint32_t c, int32_t patch_id);
/* Shrinks the mesh back to its first `vertices` vertices and `triangles` triangles (undo of
 * appends); larger counts are ignored. */
void cj_mesh_truncate(cj_mesh *mesh, size_t vertices, size_t triangles);

/* Merges vertices whose positions are identical (compared as doubles: bit-identical up to
 * the sign of zero), keeping the first one's normal and uv, and drops triangles that become
 * degenerate (two equal indices). *dropped (may be NULL) receives the number of triangles
 * removed. O(V log V) time; allocates a temporary index table. */
cj_status cj_mesh_weld(cj_mesh *mesh, size_t *dropped);

/* Topology of the mesh with vertices identified by position (as in cj_mesh_weld, without
 * changing the mesh) and degenerate triangles ignored. */
typedef struct cj_mesh_topology {
    size_t vertices;          /* distinct positions referenced by a triangle */
    size_t edges;             /* distinct undirected edges */
    size_t faces;             /* non-degenerate triangles */
    size_t boundary_edges;    /* edges used by exactly one triangle (cracks show up here) */
    size_t nonmanifold_edges; /* edges used by more than two triangles */
    size_t misoriented_edges; /* edges used twice in the same direction (flipped neighbour) */
    long euler;               /* vertices - edges + faces */
    double boundary_length;   /* total length of the boundary edges */
} cj_mesh_topology;

cj_status cj_mesh_topology_compute(const cj_mesh *mesh, cj_mesh_topology *out);

/* Wavefront OBJ: one `v` per distinct position (so the file is welded and watertight), one
 * `vt` (the vertex's (u,v)) and one `vn` per mesh vertex, a `g patch_K` line whenever the
 * patch id changes, faces `f p/t/n` (1-based). Written to "<path>.tmp" then renamed, so a
 * failure leaves no partial file at `path`. Numbers are printed with %.17g. */
cj_status cj_mesh_write_obj(const cj_mesh *mesh, const char *path);

/* PLY with per-vertex x y z nx ny nz u v (double) and faces as `list uchar uint`;
 * binary != 0 writes binary_little_endian, else ascii. Temporary file then rename. */
cj_status cj_mesh_write_ply(const cj_mesh *mesh, const char *path, int binary);

/* By extension: ".obj", ".ply" (binary little endian); others CJ_ERR_ARGUMENT. */
cj_status cj_mesh_write(const cj_mesh *mesh, const char *path);

#ifdef __cplusplus
}
#endif
#endif
