// Private to viz/: writing a grid as .vtu so that a failed run never leaves a partial file.
#ifndef CASTELJAU_VTK_WRITE_H
#define CASTELJAU_VTK_WRITE_H

#include "casteljau/status.h"

class vtkUnstructuredGrid;

// Writes `grid` (raw appended binary, uncompressed) to PATH.tmp, then renames it to `path`;
// on any failure the temporary is removed and CJ_ERR_IO names the file.
cj_status cj_vtk_write_grid(vtkUnstructuredGrid *grid, const char *path);

#endif
