// Private to viz/: pieces of the VTK renderer (vtk_render.cpp) shared with its exporter.
#ifndef CASTELJAU_VTK_RENDER_INTERNAL_H
#define CASTELJAU_VTK_RENDER_INTERNAL_H

#include "casteljau/vtk_render.h"

#include <vtkSmartPointer.h>

class vtkCamera;
class vtkPolyData;

// Validates view and objects as documented for cj_vtk_renderer_create.
cj_status cj_vtk_check_inputs(const cj_vtk_view *view, const cj_vtk_object *objects, size_t count);

// The mesh as VTK poly data: double points, float point normals "Normals", triangles.
vtkSmartPointer<vtkPolyData> cj_vtk_mesh_polydata(const cj_mesh *mesh);

// Our camera as a vtkCamera (see casteljau/vtk_render.h).
void cj_vtk_apply_camera(vtkCamera *vc, const cj_camera *cam);

#endif
