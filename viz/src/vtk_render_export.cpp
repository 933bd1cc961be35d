// The VTK renderer's companions (casteljau/vtk_render.h): vtkImageDifference on RGBA8 images
// and the .vtp export of the meshes a renderer drew, with the camera.
#include "casteljau/vtk_render.h"

#include "error_internal.h"
#include "vtk_render_internal.h"
#include "vtk_write.h"

#include <vtkCellData.h>
#include <vtkCellArray.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkImageDifference.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkUnsignedCharArray.h>
#include <vtkUnsignedIntArray.h>
#include <vtkXMLPolyDataWriter.h>

#include <cassert>

namespace {

vtkSmartPointer<vtkImageData> rgb_image(const uint8_t *rgba, int width, int height) {
    auto img = vtkSmartPointer<vtkImageData>::New();
    img->SetDimensions(width, height, 1);
    img->AllocateScalars(VTK_UNSIGNED_CHAR, 3);
    auto *dst = static_cast<unsigned char *>(img->GetScalarPointer());
    const size_t n = (size_t)width * (size_t)height;
    for (size_t i = 0; i < n; i++)
        for (int c = 0; c < 3; c++) dst[3 * i + c] = rgba[4 * i + c];
    return img;
}

} // namespace

cj_status cj_vtk_image_difference(const uint8_t *a, const uint8_t *b, int width, int height,
                                  int threshold, double *error, double *thresholded) {
    assert(a && b && error && thresholded);
    if (width < 1 || height < 1)
        return cj_fail(CJ_ERR_ARGUMENT, "image difference of a %d x %d image", width, height);
    if (threshold < 0 || threshold > 255 * 3)
        return cj_fail(CJ_ERR_RANGE, "image difference threshold %d must be in 0..765", threshold);
    vtkNew<vtkImageDifference> diff;
    diff->SetInputData(rgb_image(a, width, height));
    diff->SetImageData(rgb_image(b, width, height));
    diff->SetThreshold(threshold);
    diff->Update();
    *error = diff->GetError();
    *thresholded = diff->GetThresholdedError();
    return CJ_OK;
}

cj_status cj_vtk_write_scene_mesh(const char *path, const cj_vtk_view *view,
                                  const cj_vtk_object *objects, size_t count) {
    assert(path && view && (objects || count == 0));
    cj_status st = cj_vtk_check_inputs(view, objects, count);
    if (st != CJ_OK) return st;
    size_t nv = 0, nt = 0;
    for (size_t i = 0; i < count; i++) {
        nv += objects[i].mesh->vertex_count;
        nt += objects[i].mesh->triangle_count;
    }
    vtkNew<vtkPoints> pts;
    pts->SetDataTypeToDouble();
    pts->SetNumberOfPoints((vtkIdType)nv);
    vtkNew<vtkFloatArray> normals;
    normals->SetName("Normals");
    normals->SetNumberOfComponents(3);
    normals->SetNumberOfTuples((vtkIdType)nv);
    vtkNew<vtkCellArray> tris;
    tris->AllocateExact((vtkIdType)nt, 3 * (vtkIdType)nt);
    vtkNew<vtkUnsignedIntArray> ids;
    ids->SetName("object_id");
    ids->SetNumberOfTuples((vtkIdType)nt);
    vtkIdType base = 0, cell = 0;
    for (size_t i = 0; i < count; i++) {
        const cj_mesh *m = objects[i].mesh;
        for (size_t v = 0; v < m->vertex_count; v++) {
            pts->SetPoint(base + (vtkIdType)v, m->positions + 3 * v);
            normals->SetTuple(base + (vtkIdType)v, m->normals + 3 * v);
        }
        for (size_t t = 0; t < m->triangle_count; t++) {
            const vtkIdType tri[3] = {base + m->triangles[3 * t], base + m->triangles[3 * t + 1],
                                      base + m->triangles[3 * t + 2]};
            tris->InsertNextCell(3, tri);
            ids->SetValue(cell++, objects[i].id);
        }
        base += (vtkIdType)m->vertex_count;
    }
    vtkNew<vtkPolyData> pd;
    pd->SetPoints(pts);
    pd->SetPolys(tris);
    pd->GetPointData()->SetNormals(normals);
    pd->GetCellData()->AddArray(ids);

    // The camera as field data, in our notation (ParaView shows it; a reader can rebuild it).
    const cj_camera &c = view->camera;
    const double cam[] = {c.eye.x,
                          c.eye.y,
                          c.eye.z,
                          c.gaze.x,
                          c.gaze.y,
                          c.gaze.z,
                          c.up.x,
                          c.up.y,
                          c.up.z,
                          c.near,
                          c.far,
                          c.fov_y,
                          c.ortho_height,
                          (double)c.projection,
                          (double)view->width,
                          (double)view->height};
    vtkNew<vtkDoubleArray> camera;
    camera->SetName("camera_eye_gaze_up_near_far_fovy_orthoheight_projection_width_height");
    camera->SetNumberOfTuples(sizeof cam / sizeof cam[0]);
    for (size_t k = 0; k < sizeof cam / sizeof cam[0]; k++) camera->SetValue((vtkIdType)k, cam[k]);
    pd->GetFieldData()->AddArray(camera);

    vtkNew<vtkXMLPolyDataWriter> writer;
    return cj_vtk_write_xml(writer, pd, path);
}
