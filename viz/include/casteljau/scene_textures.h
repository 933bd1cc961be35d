/* casteljau: reading the image textures of a scene (viz/, built when CJ_WITH_OIIO is ON).
 *
 * A scene stores an image texture's path only (casteljau/scene.h); the pixels are read here
 * through casteljau/image_io.h (8-bit RGBA, any format OpenImageIO reads), converted from sRGB
 * to LINEAR floats (IEC 61966-2-1: c/12.92 for c <= 0.04045, else ((c + 0.055)/1.055)^2.4;
 * alpha is linear, /255), bottom row first as the file is read, and stored with
 * cj_scene_set_texture_pixels.
 */
#ifndef CASTELJAU_SCENE_TEXTURES_H
#define CASTELJAU_SCENE_TEXTURES_H

#include "casteljau/scene.h"
#include "casteljau/scene_json.h"
#include "casteljau/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Reads every image texture of the scene that has no pixels yet. Relative paths are resolved
 * against base_dir (the scene file's folder; NULL or "" = the current folder); absolute ones
 * are used as they are. On failure the message names where the texture was defined
 * (cj_scene_texture_source: "scene.json:12: textures[0].path") or, for a scene built from
 * code, "textures[i].path", then the file and the reason. Textures read before the failure
 * keep their pixels. Status: CJ_ERR_IO (missing or unreadable image), CJ_ERR_NOMEM, or what
 * cj_scene_set_texture_pixels reports. */
cj_status cj_scene_load_textures(cj_scene *scene, const char *base_dir);

/* "Load a scene and its textures", written once for the tool and the viewer: reads the scene
 * file (cj_scene_load_json_with_options; options may be NULL), then its image textures with
 * cj_scene_load_textures against the file's folder. On failure nothing is kept (*out
 * untouched) and the status and message are those of the step that failed; CJ_ERR_NOMEM. */
cj_status cj_scene_load_with_textures(const char *path, const cj_scene_json_options *options,
                                      const cj_allocator *alloc, cj_scene **out);

/* The sRGB 8-bit code c (0..255) as a linear value in [0, 1]. */
float cj_srgb8_to_linear(unsigned char c);

#ifdef __cplusplus
}
#endif
#endif
