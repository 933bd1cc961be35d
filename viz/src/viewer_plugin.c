/* The viewer module's one exported symbol (see viewer_plugin.h). */
#include "viewer_plugin.h"

#include "casteljau/status.h"

#include <stdio.h>

static int run(const cj_viewer_options *opt, char *why, size_t why_size) {
    const cj_status st = cj_viewer_window_run(opt);
    if (st) snprintf(why, why_size, "%s", cj_last_error());
    return (int)st;
}

__attribute__((visibility("default"))) const cj_viewer_plugin *cj_viewer_plugin_v1(void);

const cj_viewer_plugin *cj_viewer_plugin_v1(void) {
    static const cj_viewer_plugin table = {CJ_VIEWER_PLUGIN_ABI, run};
    return &table;
}
