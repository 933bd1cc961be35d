// VTK rendering of our triangles (casteljau/vtk_render.h): an offscreen vtkRenderWindow through
// Mesa, with our camera, lights and Phong parameters mapped onto VTK's.
#include "casteljau/vtk_render.h"

#include "error_internal.h"
#include "vtk_render_internal.h"

#include <vtkActor.h>
#include <vtkAutoInit.h>
#include <vtkCamera.h>
#include <vtkCellArray.h>
#include <vtkFloatArray.h>
#include <vtkLight.h>
#include <vtkNew.h>
#include <vtkOpenGLRenderWindow.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkShaderProperty.h>
#include <vtkSmartPointer.h>
#include <vtkUnsignedCharArray.h>

#include <X11/Xlib.h>

#include <cassert>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <new>
#include <vector>

// The OpenGL2 back end registers the concrete render window with VTK's object factory; without
// this, vtkRenderWindow::New() has no implementation to return.
VTK_MODULE_INIT(vtkRenderingOpenGL2);

namespace {

const int kMaxSide = 4096;
const uint32_t kMaxId = (1u << 24) - 1u;

double now() {
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch())
        .count();
}

bool finite3(const double *v) {
    return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]);
}

cj_status check_unit_range(double v, const char *what, size_t index) {
    if (!std::isfinite(v))
        return cj_fail(CJ_ERR_NONFINITE, "objects[%zu].material.%s is not finite", index, what);
    if (v < 0.0 || v > 1.0)
        return cj_fail(CJ_ERR_RANGE, "objects[%zu].material.%s must be in [0, 1]", index, what);
    return CJ_OK;
}

cj_status check_material(const cj_material *m, size_t i) {
    const double unit[] = {m->color.r,    m->color.g,    m->color.b, m->specular.r,
                           m->specular.g, m->specular.b, m->opacity};
    const char *names[] = {"color.r",    "color.g",    "color.b", "specular.r",
                           "specular.g", "specular.b", "opacity"};
    for (int k = 0; k < 7; k++) {
        cj_status st = check_unit_range(unit[k], names[k], i);
        if (st != CJ_OK) return st;
    }
    const double coef[] = {m->ka, m->kd, m->ks, m->alpha};
    const char *cnames[] = {"ka", "kd", "ks", "alpha"};
    for (int k = 0; k < 4; k++) {
        if (!std::isfinite(coef[k]))
            return cj_fail(CJ_ERR_NONFINITE, "objects[%zu].material.%s is not finite", i,
                           cnames[k]);
        if (coef[k] < 0.0)
            return cj_fail(CJ_ERR_RANGE, "objects[%zu].material.%s must be >= 0", i, cnames[k]);
    }
    return CJ_OK;
}

cj_status check_light(const cj_light *l, size_t i) {
    const double v[] = {l->color.r, l->color.g, l->color.b, l->intensity};
    for (double x : v)
        if (!std::isfinite(x))
            return cj_fail(CJ_ERR_NONFINITE, "lights[%zu]: colour or intensity is not finite", i);
    if (l->intensity < 0.0 || l->color.r < 0.0 || l->color.g < 0.0 || l->color.b < 0.0)
        return cj_fail(CJ_ERR_RANGE, "lights[%zu]: colour and intensity must be >= 0", i);
    switch (l->kind) {
    case CJ_LIGHT_AMBIENT:
        return CJ_OK;
    case CJ_LIGHT_POINT:
        if (!finite3(&l->position.x))
            return cj_fail(CJ_ERR_NONFINITE, "lights[%zu].position is not finite", i);
        return CJ_OK;
    case CJ_LIGHT_DIRECTIONAL: {
        const cj_vec3 d = l->direction;
        if (!finite3(&d.x))
            return cj_fail(CJ_ERR_NONFINITE, "lights[%zu].direction is not finite", i);
        if (d.x == 0.0 && d.y == 0.0 && d.z == 0.0)
            return cj_fail(CJ_ERR_DEGENERATE, "lights[%zu].direction is zero", i);
        return CJ_OK;
    }
    default:
        return cj_fail(CJ_ERR_UNSUPPORTED,
                       "lights[%zu]: VTK cross-check renders ambient, point and directional "
                       "lights only",
                       i);
    }
}

cj_status check_mesh(const cj_mesh *mesh, size_t i) {
    for (size_t v = 0; v < mesh->vertex_count; v++) {
        if (!finite3(mesh->positions + 3 * v))
            return cj_fail(CJ_ERR_NONFINITE, "objects[%zu].mesh vertex %zu is not finite", i, v);
        if (!finite3(mesh->normals + 3 * v))
            return cj_fail(CJ_ERR_NONFINITE, "objects[%zu].mesh normal %zu is not finite", i, v);
    }
    for (size_t t = 0; t < 3 * mesh->triangle_count; t++)
        if (mesh->triangles[t] >= mesh->vertex_count)
            return cj_fail(CJ_ERR_RANGE, "objects[%zu].mesh triangle %zu names vertex %u of %zu", i,
                           t / 3, (unsigned)mesh->triangles[t], mesh->vertex_count);
    return CJ_OK;
}

// VTK aborts the process when it cannot open the X display; ask first.
cj_status probe_display() {
    const char *name = std::getenv("DISPLAY");
    if (!name || !*name)
        return cj_fail(CJ_ERR_UNSUPPORTED,
                       "VTK rendering needs an X display and DISPLAY is not set (run under Xvfb)");
    Display *d = XOpenDisplay(name);
    if (!d) return cj_fail(CJ_ERR_UNSUPPORTED, "cannot open the X display DISPLAY=%s", name);
    XCloseDisplay(d);
    return CJ_OK;
}

} // namespace

cj_status cj_vtk_check_inputs(const cj_vtk_view *view, const cj_vtk_object *objects, size_t count) {
    if (view->width < 1 || view->width > kMaxSide || view->height < 1 || view->height > kMaxSide)
        return cj_fail(CJ_ERR_ARGUMENT, "VTK image size %d x %d must be 1..%d each", view->width,
                       view->height, kMaxSide);
    cj_status st = cj_camera_check(&view->camera);
    if (st != CJ_OK) return st;
    const double bg[] = {view->background.r, view->background.g, view->background.b};
    for (double c : bg)
        if (!(c >= 0.0 && c <= 1.0))
            return cj_fail(CJ_ERR_RANGE, "background colour must be in [0, 1]");
    if (view->light_count > 0 && !view->lights)
        return cj_fail(CJ_ERR_ARGUMENT, "view has %zu lights and no light array",
                       view->light_count);
    for (size_t i = 0; i < view->light_count; i++)
        if ((st = check_light(&view->lights[i], i)) != CJ_OK) return st;
    if (count == 0) return cj_fail(CJ_ERR_ARGUMENT, "no objects to render with VTK");
    for (size_t i = 0; i < count; i++) {
        const cj_vtk_object &o = objects[i];
        if (!o.mesh || !o.material)
            return cj_fail(CJ_ERR_ARGUMENT, "objects[%zu] has no mesh or no material", i);
        if (o.id == 0 || o.id > kMaxId)
            return cj_fail(CJ_ERR_ARGUMENT, "objects[%zu].id %u must be in 1..%u", i,
                           (unsigned)o.id, (unsigned)kMaxId);
        if ((st = check_material(o.material, i)) != CJ_OK) return st;
        if ((st = check_mesh(o.mesh, i)) != CJ_OK) return st;
    }
    return CJ_OK;
}

vtkSmartPointer<vtkPolyData> cj_vtk_mesh_polydata(const cj_mesh *mesh) {
    auto pd = vtkSmartPointer<vtkPolyData>::New();
    vtkNew<vtkPoints> pts;
    pts->SetDataTypeToDouble();
    pts->SetNumberOfPoints((vtkIdType)mesh->vertex_count);
    vtkNew<vtkFloatArray> normals;
    normals->SetName("Normals");
    normals->SetNumberOfComponents(3);
    normals->SetNumberOfTuples((vtkIdType)mesh->vertex_count);
    for (size_t v = 0; v < mesh->vertex_count; v++) {
        pts->SetPoint((vtkIdType)v, mesh->positions + 3 * v);
        normals->SetTuple((vtkIdType)v, mesh->normals + 3 * v);
    }
    vtkNew<vtkCellArray> tris;
    tris->AllocateExact((vtkIdType)mesh->triangle_count, 3 * (vtkIdType)mesh->triangle_count);
    for (size_t t = 0; t < mesh->triangle_count; t++) {
        const vtkIdType ids[3] = {mesh->triangles[3 * t], mesh->triangles[3 * t + 1],
                                  mesh->triangles[3 * t + 2]};
        tris->InsertNextCell(3, ids);
    }
    pd->SetPoints(pts);
    pd->SetPolys(tris);
    pd->GetPointData()->SetNormals(normals);
    return pd;
}

void cj_vtk_apply_camera(vtkCamera *vc, const cj_camera *cam) {
    const cj_vec3 e = cam->eye, g = cam->gaze;
    vc->SetPosition(e.x, e.y, e.z);
    vc->SetFocalPoint(e.x + g.x, e.y + g.y, e.z + g.z);
    vc->SetViewUp(cam->up.x, cam->up.y, cam->up.z);
    vc->SetClippingRange(-cam->near, -cam->far);
    if (cam->projection == CJ_PROJ_ORTHOGRAPHIC) {
        vc->ParallelProjectionOn();
        vc->SetParallelScale(cam->ortho_height / 2.0);
    } else {
        vc->ParallelProjectionOff();
        vc->SetViewAngle(cam->fov_y * 180.0 / M_PI);
    }
}

struct cj_vtk_renderer {
    vtkSmartPointer<vtkRenderWindow> window;
    vtkSmartPointer<vtkRenderer> renderer;
    std::vector<vtkSmartPointer<vtkActor>> shaded; // one per object
    std::vector<vtkSmartPointer<vtkActor>> unlit;  // id pass: colour = id bytes, no lighting
    vtkSmartPointer<vtkUnsignedCharArray> pixels;
    std::vector<float> zbuf;
    cj_rgb background;
    int width, height;
    bool drawn = false;
};

namespace {

// VTK 9.1's specular line for light complexity 3 (any positional light), and ours in its place:
// h = normalize(v + l) with v = normalize(-vertexVC) towards the eye and l = -vertLightDirectionVC
// towards the light; not gated by the diffuse term.
const char *const kVtkSpecular =
    "sf = sign(df)*attenuation*pow( max(0.0, dot( reflect(vertLightDirectionVC, "
    "normalVCVSOutput), normalize(-vertexVC.xyz))), specularPower);";
const char *const kBlinnSpecular =
    "sf = attenuation*pow(max(0.0, dot(normalVCVSOutput, normalize(normalize(-vertexVC.xyz) - "
    "vertLightDirectionVC))), specularPower);";
// Orthographic: the eye direction is the view axis everywhere (VTK's own line uses the
// fragment's position even then).
const char *const kBlinnSpecularOrtho =
    "sf = attenuation*pow(max(0.0, dot(normalVCVSOutput, normalize(vec3(0.0, 0.0, 1.0) - "
    "vertLightDirectionVC))), specularPower);";

void add_lights(vtkRenderer *ren, const cj_vtk_view *view, double ambient[3]) {
    ambient[0] = ambient[1] = ambient[2] = 0.0;
    bool positional = false;
    for (size_t i = 0; i < view->light_count; i++) {
        const cj_light &l = view->lights[i];
        if (l.kind == CJ_LIGHT_AMBIENT) {
            ambient[0] += l.color.r * l.intensity;
            ambient[1] += l.color.g * l.intensity;
            ambient[2] += l.color.b * l.intensity;
            continue;
        }
        vtkNew<vtkLight> vl;
        vl->SetLightTypeToSceneLight();
        vl->SetColor(l.color.r, l.color.g, l.color.b);
        vl->SetIntensity(l.intensity);
        vl->SetAttenuationValues(1.0, 0.0, 0.0);
        if (l.kind == CJ_LIGHT_POINT) {
            positional = true;
            vl->PositionalOn();
            vl->SetConeAngle(180.0);
            vl->SetPosition(l.position.x, l.position.y, l.position.z);
            // Unused for an omnidirectional positional light, but VTK wants it distinct.
            vl->SetFocalPoint(l.position.x, l.position.y, l.position.z - 1.0);
        } else { // directional: VTK's light shines from Position towards FocalPoint
            vl->PositionalOff();
            vl->SetPosition(-l.direction.x, -l.direction.y, -l.direction.z);
            vl->SetFocalPoint(0.0, 0.0, 0.0);
        }
        ren->AddLight(vl);
    }
    if ((view->flags & CJ_VTK_BLINN_SPECULAR) && !positional) {
        // VTK writes the per-fragment light loop we patch only when a light is positional.
        vtkNew<vtkLight> vl;
        vl->SetLightTypeToSceneLight();
        vl->PositionalOn();
        vl->SetConeAngle(180.0);
        vl->SetIntensity(1e-20);
        vl->SetPosition(0.0, 0.0, 1e6);
        vl->SetFocalPoint(0.0, 0.0, 0.0);
        ren->AddLight(vl);
    }
}

void set_material(vtkProperty *p, const cj_material *m, const double ambient[3]) {
    p->SetAmbient(m->ka);
    p->SetAmbientColor(m->color.r * ambient[0], m->color.g * ambient[1], m->color.b * ambient[2]);
    p->SetDiffuse(m->kd);
    p->SetDiffuseColor(m->color.r, m->color.g, m->color.b);
    p->SetSpecular(m->ks);
    p->SetSpecularColor(m->specular.r, m->specular.g, m->specular.b);
    p->SetSpecularPower(m->alpha);
    p->SetOpacity(m->opacity);
    if (m->shading == CJ_SHADE_FLAT)
        p->SetInterpolationToFlat();
    else
        p->SetInterpolationToPhong();
    p->SetBackfaceCulling(m->two_sided ? 0 : 1);
}

// The id pass: VTK's unlit shader writes ambient + diffuse colour; with ambient 0 and diffuse
// 1 a colour of k/255 lands in the 8-bit framebuffer as exactly k.
void set_id_colour(vtkProperty *p, const cj_material *m, uint32_t id) {
    p->LightingOff();
    p->SetAmbient(0.0);
    p->SetDiffuse(1.0);
    p->SetSpecular(0.0);
    p->SetDiffuseColor((id & 255u) / 255.0, ((id >> 8) & 255u) / 255.0,
                       ((id >> 16) & 255u) / 255.0);
    p->SetOpacity(1.0);
    p->SetBackfaceCulling(m->two_sided ? 0 : 1);
}

} // namespace

cj_status cj_vtk_renderer_create(const cj_vtk_view *view, const cj_vtk_object *objects,
                                 size_t count, cj_vtk_renderer **out) {
    assert(view && out && (objects || count == 0));
    cj_status st = cj_vtk_check_inputs(view, objects, count);
    if (st != CJ_OK) return st;
    if ((st = probe_display()) != CJ_OK) return st;
    cj_vtk_renderer *r = new (std::nothrow) cj_vtk_renderer();
    if (!r) return cj_fail(CJ_ERR_NOMEM, "VTK renderer");
    r->width = view->width;
    r->height = view->height;
    r->background = view->background;
    r->renderer = vtkSmartPointer<vtkRenderer>::New();
    r->renderer->AutomaticLightCreationOff();
    r->renderer->TwoSidedLightingOn();
    r->renderer->SetBackground(view->background.r, view->background.g, view->background.b);
    r->renderer->SetBackgroundAlpha(0.0);
    r->renderer->UseFXAAOff();
    r->renderer->UseDepthPeelingOff();
    double ambient[3];
    add_lights(r->renderer, view, ambient);

    for (size_t i = 0; i < count; i++) {
        vtkSmartPointer<vtkPolyData> pd = cj_vtk_mesh_polydata(objects[i].mesh);
        vtkNew<vtkPolyDataMapper> mapper, id_mapper;
        mapper->SetInputData(pd);
        mapper->ScalarVisibilityOff();
        id_mapper->SetInputData(pd);
        id_mapper->ScalarVisibilityOff();
        auto actor = vtkSmartPointer<vtkActor>::New();
        actor->SetMapper(mapper);
        set_material(actor->GetProperty(), objects[i].material, ambient);
        if (view->flags & CJ_VTK_BLINN_SPECULAR)
            actor->GetShaderProperty()->AddFragmentShaderReplacement(
                kVtkSpecular, false,
                view->camera.projection == CJ_PROJ_ORTHOGRAPHIC ? kBlinnSpecularOrtho
                                                                : kBlinnSpecular,
                true);
        auto id_actor = vtkSmartPointer<vtkActor>::New();
        id_actor->SetMapper(id_mapper);
        set_id_colour(id_actor->GetProperty(), objects[i].material, objects[i].id);
        id_actor->VisibilityOff();
        r->renderer->AddActor(actor);
        r->renderer->AddActor(id_actor);
        r->shaded.push_back(actor);
        r->unlit.push_back(id_actor);
    }
    vtkCamera *cam = r->renderer->GetActiveCamera();
    cj_vtk_apply_camera(cam, &view->camera);

    r->window = vtkSmartPointer<vtkRenderWindow>::New();
    r->window->SetOffScreenRendering(1);
    r->window->SetMultiSamples(0);
    r->window->SetAlphaBitPlanes(1);
    r->window->SetSize(view->width, view->height);
    r->window->AddRenderer(r->renderer);
    r->pixels = vtkSmartPointer<vtkUnsignedCharArray>::New();
    try {
        r->zbuf.resize((size_t)view->width * (size_t)view->height);
    } catch (const std::bad_alloc &) {
        cj_vtk_renderer_destroy(r);
        return cj_fail(CJ_ERR_NOMEM, "VTK depth buffer of %d x %d", view->width, view->height);
    }
    *out = r;
    return CJ_OK;
}

namespace {

cj_status read_colour(cj_vtk_renderer *r) {
    const int ok = r->window->GetRGBACharPixelData(0, 0, r->width - 1, r->height - 1, 0, r->pixels);
    if (!ok || r->pixels->GetNumberOfTuples() != (vtkIdType)r->width * r->height)
        return cj_fail(CJ_ERR_IO, "VTK could not read the %d x %d colour buffer back", r->width,
                       r->height);
    return CJ_OK;
}

} // namespace

cj_status cj_vtk_renderer_draw(cj_vtk_renderer *r, const cj_vtk_frame *frame,
                               cj_vtk_timing *timing) {
    assert(r && frame);
    cj_vtk_timing t = {0.0, 0.0, 0.0};
    const size_t n = (size_t)r->width * (size_t)r->height;

    double t0 = now();
    r->window->Render();
    r->window->WaitForCompletion();
    t.render = now() - t0;
    r->drawn = true;

    t0 = now();
    if (frame->rgba) {
        cj_status st = read_colour(r);
        if (st != CJ_OK) return st;
        const unsigned char *px = r->pixels->GetPointer(0);
        for (size_t i = 0; i < 4 * n; i++) frame->rgba[i] = (float)px[i] / 255.0f;
    }
    if (frame->depth) {
        if (!r->window->GetZbufferData(0, 0, r->width - 1, r->height - 1, r->zbuf.data()))
            return cj_fail(CJ_ERR_IO, "VTK could not read the %d x %d depth buffer back", r->width,
                           r->height);
        // Window depth d in [0, 1] (glDepthRange 0..1) of the same frustum as ours: our
        // pseudodepth is the normalised-device z, 2d - 1; the cleared 1 becomes +1.
        for (size_t i = 0; i < n; i++) frame->depth[i] = 2.0f * r->zbuf[i] - 1.0f;
    }
    t.readback = now() - t0;

    if (frame->ids) {
        t0 = now();
        for (size_t i = 0; i < r->shaded.size(); i++) {
            r->shaded[i]->VisibilityOff();
            r->unlit[i]->VisibilityOn();
        }
        r->renderer->SetBackground(0.0, 0.0, 0.0);
        r->window->Render();
        cj_status st = read_colour(r);
        for (size_t i = 0; i < r->shaded.size(); i++) {
            r->shaded[i]->VisibilityOn();
            r->unlit[i]->VisibilityOff();
        }
        r->renderer->SetBackground(r->background.r, r->background.g, r->background.b);
        if (st != CJ_OK) return st;
        const unsigned char *px = r->pixels->GetPointer(0);
        for (size_t i = 0; i < n; i++)
            frame->ids[i] =
                (uint32_t)px[4 * i] | (uint32_t)px[4 * i + 1] << 8 | (uint32_t)px[4 * i + 2] << 16;
        t.ids = now() - t0;
    }
    if (timing) *timing = t;
    return CJ_OK;
}

cj_status cj_vtk_renderer_gl_name(cj_vtk_renderer *r, char *buf, size_t cap) {
    assert(r && buf && cap > 0);
    auto *gl = vtkOpenGLRenderWindow::SafeDownCast(r->window);
    if (!gl) return cj_fail(CJ_ERR_IO, "the VTK render window is not an OpenGL window");
    if (!r->drawn) {
        r->window->Render();
        r->drawn = true;
    }
    // ReportCapabilities lists "OpenGL renderer string: <name>" among other lines.
    const std::string caps = gl->ReportCapabilities() ? gl->ReportCapabilities() : "";
    const std::string key = "OpenGL renderer string: ";
    const size_t at = caps.find(key);
    if (at == std::string::npos)
        return cj_fail(CJ_ERR_IO, "VTK did not report the OpenGL renderer");
    const size_t end = caps.find('\n', at);
    const std::string name = caps.substr(
        at + key.size(), end == std::string::npos ? std::string::npos : end - at - key.size());
    const size_t first = name.find_first_not_of(' ');
    std::snprintf(buf, cap, "%s", first == std::string::npos ? "" : name.c_str() + first);
    return CJ_OK;
}

void cj_vtk_renderer_destroy(cj_vtk_renderer *r) {
    if (!r) return;
    if (r->window) r->window->Finalize();
    delete r;
}

cj_status cj_vtk_render_mesh(const cj_vtk_view *view, const cj_vtk_object *objects, size_t count,
                             const cj_vtk_frame *frame, cj_vtk_timing *timing) {
    cj_vtk_renderer *r = nullptr;
    cj_status st = cj_vtk_renderer_create(view, objects, count, &r);
    if (st != CJ_OK) return st;
    st = cj_vtk_renderer_draw(r, frame, timing);
    cj_vtk_renderer_destroy(r);
    return st;
}
