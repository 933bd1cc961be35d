// Private to viz/: writing VTK XML files (.vtu, .vtp) so that a failed run never leaves a
// partial file.
#ifndef CASTELJAU_VTK_WRITE_H
#define CASTELJAU_VTK_WRITE_H

#include "casteljau/status.h"

class vtkDataObject;
class vtkUnstructuredGrid;
class vtkXMLWriter;

// Writes `data` through `writer` (any VTK XML writer of that kind of data; raw appended
// binary, uncompressed) to PATH.tmp, then renames it to `path`; on any failure the temporary
// is removed and CJ_ERR_IO names the file.
cj_status cj_vtk_write_xml(vtkXMLWriter *writer, vtkDataObject *data, const char *path);

// cj_vtk_write_xml of `grid` with a vtkXMLUnstructuredGridWriter (.vtu).
cj_status cj_vtk_write_grid(vtkUnstructuredGrid *grid, const char *path);

#endif
