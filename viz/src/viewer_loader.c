/* cj_viewer_run: opens the viewer module (viewer_plugin.h) and runs it. */
#include "casteljau/viewer.h"

#include "error_internal.h"
#include "module_internal.h"
#include "viewer_plugin.h"

#include <assert.h>
#include <stdio.h>

#ifndef CJ_VIEWER_PLUGIN_BUILD
#define CJ_VIEWER_PLUGIN_BUILD NULL
#endif
#ifndef CJ_VIEWER_PLUGIN_INSTALL
#define CJ_VIEWER_PLUGIN_INSTALL NULL
#endif

cj_status cj_viewer_run(const cj_viewer_options *opt) {
    assert(opt);
    static const cj_module_spec spec = {
        CJ_VIEWER_PLUGIN_FILE,
        "CJ_VIEWER_PLUGIN",
        CJ_VIEWER_PLUGIN_BUILD,
        CJ_VIEWER_PLUGIN_INSTALL,
        CJ_VIEWER_PLUGIN_SYMBOL,
        "the viewer module",
        "the viewer needs GLFW and OpenGL: Debian's libglfw3 and libgl1"};
    char why[1024];
    const cj_viewer_plugin *table =
        (const cj_viewer_plugin *)cj_module_open(&spec, why, sizeof why);
    if (!table) return cj_fail(CJ_ERR_UNSUPPORTED, "%s", why);
    if (table->abi != CJ_VIEWER_PLUGIN_ABI)
        return cj_fail(CJ_ERR_UNSUPPORTED,
                       "the viewer module is of another version (ABI %d, "
                       "want %d)",
                       table->abi, CJ_VIEWER_PLUGIN_ABI);
    why[0] = '\0';
    const int st = table->run(opt, why, sizeof why);
    if (st) return cj_fail((cj_status)st, "%s", why[0] ? why : "the viewer failed");
    return CJ_OK;
}
