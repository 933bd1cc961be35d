/* Private: helpers shared by the OBJ and PLY readers. */
#ifndef CASTELJAU_MESH_READ_INTERNAL_H
#define CASTELJAU_MESH_READ_INTERNAL_H

#include "casteljau/mesh.h"
#include "casteljau/status.h"
#include <stddef.h>

/* Reads a whole file into a NUL-terminated malloc'ed buffer (CJ_ERR_IO naming the path). */
cj_status cj_mesh_slurp_(const char *path, char **text, size_t *len);
/* Sets the normals of the vertices with have[i] == 0 from the triangles around them. */
cj_status cj_mesh_fill_missing_normals_(cj_mesh *m, const unsigned char *have);

#endif
