/* Private to the casteljau tool: what the commands that draw scenes (render, trace, animate)
 * share: loading a scene file with its textures, and writing a rendered image. */
#ifndef CASTELJAU_APP_SCENE_CLI_H
#define CASTELJAU_APP_SCENE_CLI_H

#include "casteljau/render.h"
#include "casteljau/scene.h"

/* Loads a JSON scene and its image textures (resolved against the scene file's folder) into
 * *out. On failure prints one line (file:line: JSON path ...) and returns CLI_EXIT_USAGE. */
int cli_load_scene(const char *cmd, const char *path, cj_scene **out);

/* Checks -o before any work: it must end in .png (8-bit sRGB) or .exr (linear half float), in
 * a folder that can be written. Sets *exr; on failure prints one line and returns
 * CLI_EXIT_USAGE. */
int cli_render_output(const char *cmd, const char *out, int *exr);

/* Writes img opaque (alpha 1): sRGB PNG or linear EXR. Prints a line and returns non-zero on
 * failure (1 for a failed write, as every writer of the tool). */
int cli_write_render(const char *cmd, const char *out, int exr, const cj_render_image *img);

#endif
