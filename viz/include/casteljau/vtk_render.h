/* casteljau: rendering our triangles with VTK (OpenGL through Mesa, offscreen), as an
 * independent cross-check of the rasterizer (casteljau/render.h) and as the reference the
 * renderer bench races against.
 *
 * Built only with CJ_WITH_VTK (VTK 9.1 from Debian's libvtk9-dev); C API in front, C++ inside.
 *
 * WHAT IS RENDERED. World-space triangle meshes (cj_mesh with unit per-vertex normals, e.g. the
 * triangles our renderer drew), each with a cj_material and an object id, seen by a cj_camera
 * under cj_lights. The mapping to VTK:
 *   - camera: vtkCamera with position ē, focal point ē + g⃗, view up t⃗, clipping range (−f, −F);
 *     perspective: view angle = fov_y in degrees (vertical, as ours); orthographic: parallel
 *     projection with parallel scale = ortho_height / 2. VTK's projection then equals ours
 *     (cj_camera_projection): the same frustum, window depth 0 at the near plane and 1 at the
 *     far plane, so our pseudodepth is 2·depth − 1 (perspective and orthographic alike).
 *   - lights: VTK's automatic headlight is off; a point light becomes a positional scene light
 *     (cone angle 180°, attenuation (1, 0, 0): none, like ours), a directional one a scene light
 *     shining along `direction`; colour × intensity is the light colour. The ambient lights'
 *     Σ colour × intensity (I_a) goes into each actor's ambient colour c_r·I_a with ambient
 *     coefficient r_a (VTK's lights add no ambient term). Spot and area lights are
 *     CJ_ERR_UNSUPPORTED.
 *   - material: diffuse colour c_r with coefficient r_d, specular colour c_p with r_s and
 *     specular power α, opacity; FLAT shading → flat interpolation, GOURAUD/PHONG → VTK's
 *     per-fragment lighting with interpolated normals (VTK's OpenGL2 back end lights every
 *     fragment, so our GOURAUD, which interpolates colours, differs inside triangles);
 *     one-sided materials cull back faces (by screen-space winding, which equals our
 *     (p̄ − ē)·n⃗ > 0 test for a triangle counter-clockwise from outside), two-sided ones light
 *     both sides (VTK's two-sided lighting flips the normal on back-facing triangles, by the
 *     triangle's facing). Textures are ignored; opacity < 1 is blended in draw order (no
 *     sorting, no depth peeling).
 *   KNOWN DIFFERENCE: VTK's specular term is Phong's (r⃗·v⃗)^α with r⃗ the reflected light
 *   direction, gated by n⃗·l⃗ > 0; ours is Blinn's (n⃗·h⃗)^α (casteljau/scene.h), which
 *   CJ_VTK_BLINN_SPECULAR patches into VTK's shader; ambient and diffuse terms are the same
 *   formula. Colours are written to an 8-bit framebuffer without gamma, so the colour
 *   plane holds linear values quantised to k/255 (clamped to [0, 1]).
 *   - no multisampling, no FXAA, no depth peeling: one sample per pixel at the pixel centre,
 *     like our rasterizer at 1 spp.
 *
 * DISPLAY. VTK 9.1 on Debian draws through GLX, so an X display is needed even offscreen: run
 * under Xvfb (the tests start one; Mesa then renders with llvmpipe, whose thread count
 * LP_NUM_THREADS sets before the first window is created). Without a reachable display the
 * functions return CJ_ERR_UNSUPPORTED naming $DISPLAY (VTK itself would abort).
 *
 * OUTPUT PLANES (caller-owned, width × height each, BOTTOM ROW FIRST like cj_render_image; any
 * may be NULL): rgba (4 floats per pixel, linear, k/255), ids (the object id seen at the pixel
 * centre, 0 = background; drawn in a second, unlit pass with each triangle coloured by its id),
 * depth (pseudodepth in [−1, 1], +1 = background).
 */
#ifndef CASTELJAU_VTK_RENDER_H
#define CASTELJAU_VTK_RENDER_H

#include "casteljau/mesh.h"
#include "casteljau/scene.h"
#include "casteljau/status.h"
#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* One object: its world-space mesh (triangles counter-clockwise from outside, unit normals),
 * its material and its id (1 .. 2^24 − 1, written to the id plane). The renderer copies the
 * mesh into VTK arrays when it is created; the caller's mesh may go afterwards. */
typedef struct cj_vtk_object {
    const cj_mesh *mesh;
    const cj_material *material;
    uint32_t id;
} cj_vtk_object;

/* What the objects are seen with. */
typedef struct cj_vtk_view {
    cj_camera camera;
    const cj_light *lights; /* light_count lights (ambient, point, directional) */
    size_t light_count;
    cj_rgb background; /* linear, each in [0, 1] */
    int width, height; /* 1 .. 4096 each */
    unsigned flags;    /* CJ_VTK_* below */
} cj_vtk_view;

/* cj_vtk_view.flags. */
enum {
    /* Our specular term instead of VTK's: c_p r_s Σ I max(0, n⃗·h⃗)^α with h⃗ the unit half
     * vector of the light and eye directions, not gated by n⃗·l⃗ (casteljau/scene.h), patched
     * into VTK's fragment shader (VTK 9.1's line for scenes with a positional light; a light
     * of intensity 1e-20 far away is added when the scene has none, so that VTK emits that
     * line). Orthographic views use the view axis as the eye direction, as ours do. */
    CJ_VTK_BLINN_SPECULAR = 1u
};

/* Caller-owned output planes (see OUTPUT PLANES above); any may be NULL. */
typedef struct cj_vtk_frame {
    float *rgba;
    uint32_t *ids;
    float *depth;
} cj_vtk_frame;

/* Wall-clock seconds of the parts of one draw. */
typedef struct cj_vtk_timing {
    double render;   /* the shaded frame: vtkRenderWindow::Render and glFinish */
    double readback; /* reading colour and depth back into the caller's planes */
    double ids;      /* the id pass (render and read), 0 when ids is NULL */
} cj_vtk_timing;

typedef struct cj_vtk_renderer cj_vtk_renderer;

/* Creates an offscreen VTK render window of the view's size with the objects uploaded as VTK
 * poly data (one actor per object). Status: CJ_ERR_ARGUMENT (count 0, an object without a
 * mesh, material or id, an id >= 2^24, a size out of range), errors of cj_camera_check,
 * CJ_ERR_NONFINITE (a NaN/Inf position or normal, named), CJ_ERR_RANGE (a material or light
 * value out of range, named; a triangle index out of range), CJ_ERR_UNSUPPORTED (a spot or area
 * light; no X display), CJ_ERR_NOMEM. */
cj_status cj_vtk_renderer_create(const cj_vtk_view *view, const cj_vtk_object *objects,
                                 size_t count, cj_vtk_renderer **out);

/* Renders one frame into the planes `frame` asks for; timing may be NULL. Repeated draws render
 * the same scene again (the mesh stays on the "GPU"), which is what the bench times.
 * Status: CJ_ERR_IO if VTK could not read the framebuffer back. */
cj_status cj_vtk_renderer_draw(cj_vtk_renderer *r, const cj_vtk_frame *frame,
                               cj_vtk_timing *timing);

/* The OpenGL renderer string of the window's context (e.g. "llvmpipe (LLVM 15.0.6, 256 bits)"),
 * truncated to cap − 1 characters; renders a frame first if none was drawn yet. CJ_ERR_IO if
 * VTK cannot report it. */
cj_status cj_vtk_renderer_gl_name(cj_vtk_renderer *r, char *buf, size_t cap);

/* Releases the window, its GL context and the VTK data; NULL is a no-op. */
void cj_vtk_renderer_destroy(cj_vtk_renderer *r);

/* One shot: create, draw once, destroy. */
cj_status cj_vtk_render_mesh(const cj_vtk_view *view, const cj_vtk_object *objects, size_t count,
                             const cj_vtk_frame *frame, cj_vtk_timing *timing);

/* A renderer for what our rasterizer draws of `scene`: `mesh` is the scene's world-space mesh
 * as cj_render_scene_mesh returns it (triangle_patch = the object id, cj_node.id); each object
 * id gets the material of its node, the view is the scene's camera, lights and background, at
 * width × height (0: the scene's settings). Objects without triangles are left out; textures,
 * overlays and transparency sorting are not reproduced. Status: CJ_ERR_ARGUMENT (a triangle
 * whose id names no visible object, a mesh without triangles), otherwise as
 * cj_vtk_renderer_create. */
cj_status cj_vtk_renderer_create_scene(const cj_scene *scene, const cj_mesh *mesh, int width,
                                       int height, unsigned flags, cj_vtk_renderer **out);

/* vtkImageDifference (VTK 9.1 with its defaults, AllowShift and Averaging on) between two
 * width × height RGBA8 images (alpha ignored), as VTK reports it: *thresholded is
 * GetThresholdedError, which accumulates, per pixel, the excess over `threshold` (0..255 units
 * per channel) of the best match among the other image's pixel, its 3 × 3 shifts and 3 × 3
 * averages: it is 0 exactly when every pixel finds a match within `threshold`. *error is
 * GetError, VTK's unthresholded figure, reported for reference only. */
cj_status cj_vtk_image_difference(const uint8_t *a, const uint8_t *b, int width, int height,
                                  int threshold, double *error, double *thresholded);

/* Writes the objects' meshes as one VTK poly data file (.vtp, binary appended) with point
 * normals, cell data "object_id" and the camera as field data
 * "camera_eye_gaze_up_near_far_fovy_orthoheight_projection_width_height" (16 doubles in that
 * order: ē, g⃗, t⃗, f, F, fov_y, ortho_height, projection, width, height), so ParaView shows what
 * the renderer drew and from where.
 * Written to "<path>.tmp" and renamed. Status: as cj_vtk_renderer_create for the inputs,
 * CJ_ERR_IO naming the path. */
cj_status cj_vtk_write_scene_mesh(const char *path, const cj_vtk_view *view,
                                  const cj_vtk_object *objects, size_t count);

/* The .vtp export of what our rasterizer draws of `scene` (mesh as for
 * cj_vtk_renderer_create_scene), with the scene's camera and the image size (0: the scene's
 * settings). Status as cj_vtk_renderer_create_scene (without a display: none is needed) and
 * cj_vtk_write_scene_mesh. */
cj_status cj_vtk_write_scene(const char *path, const cj_scene *scene, const cj_mesh *mesh,
                             int width, int height);

#ifdef __cplusplus
}
#endif
#endif
