/* Private: the C ABI between casteljau_viz (viewer_loader.c, which defines cj_viewer_run) and
 * the viewer module libcasteljau_viewer.so (the window, GLFW, OpenGL and their X11 libraries),
 * opened with dlopen only when `casteljau view` runs, so that the program and the libraries
 * link no graphics library at all.
 *
 * The module exports one symbol, CJ_VIEWER_PLUGIN_SYMBOL, returning a static table. `run` is
 * cj_viewer_run's contract; on failure it writes the module's one-line message to
 * why[why_size] (the module holds its own copy of the library's error state when the libraries
 * are static, so the message crosses the boundary as text, as the image plug-in's do). */
#ifndef CASTELJAU_VIEWER_PLUGIN_H
#define CASTELJAU_VIEWER_PLUGIN_H

#include "casteljau/viewer.h"

#include <stddef.h>

#define CJ_VIEWER_PLUGIN_ABI    1
#define CJ_VIEWER_PLUGIN_SYMBOL "cj_viewer_plugin_v1"
#define CJ_VIEWER_PLUGIN_FILE   "libcasteljau_viewer.so"

typedef struct cj_viewer_plugin {
    int abi; /* CJ_VIEWER_PLUGIN_ABI */
    int (*run)(const cj_viewer_options *opt, char *why, size_t why_size);
} cj_viewer_plugin;

typedef const cj_viewer_plugin *(*cj_viewer_plugin_entry)(void);

/* Inside the module (viewer_window.c): the window itself. */
cj_status cj_viewer_window_run(const cj_viewer_options *opt);

#endif
