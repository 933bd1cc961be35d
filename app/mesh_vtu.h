/* Private to the casteljau tool: a triangle mesh as a VTK XML .vtu file (atomic, checked). */
#ifndef CASTELJAU_APP_MESH_VTU_H
#define CASTELJAU_APP_MESH_VTU_H

#include "casteljau/mesh.h"
#include <stddef.h>

/* 0 on success; -1 with a one-line reason naming the path (nothing is left behind). */
int mesh_write_vtu(const cj_mesh *mesh, const char *path, char *why, size_t why_size);

#endif
