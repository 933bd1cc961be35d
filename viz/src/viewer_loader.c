/* cj_viewer_run: opens the viewer module (viewer_plugin.h) with dlopen and runs it. The module
 * is looked for as the OpenImageIO plug-in is (image_io.c): CJ_VIEWER_PLUGIN when set, else
 * next to the object holding this code and to the running program, in their casteljau/ and
 * ../lib/casteljau/ folders, then where it was built and installed. */
#define _GNU_SOURCE /* dladdr */
#include "casteljau/viewer.h"

#include "error_internal.h"
#include "viewer_plugin.h"

#include <assert.h>
#include <dlfcn.h>
#include <limits.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#ifndef CJ_IMAGE_PLUGIN_RELDIR
#define CJ_IMAGE_PLUGIN_RELDIR "../lib/casteljau/"
#endif

typedef struct module_search {
    const cj_viewer_plugin *table;
    char error[1024]; /* the first real failure: a module that exists but cannot load */
} module_search;

static int try_module(module_search *s, const char *path) {
    if (!path || !*path) return 0;
    void *h = dlopen(path, RTLD_NOW | RTLD_LOCAL);
    if (!h) {
        const char *e = dlerror();
        if (access(path, F_OK) == 0 && !s->error[0])
            snprintf(s->error, sizeof s->error,
                     "the viewer module '%s' cannot be loaded: %s (the viewer needs GLFW and "
                     "OpenGL: Debian's libglfw3 and libgl1)",
                     path, e ? e : "dlopen failed");
        return 0;
    }
    cj_viewer_plugin_entry entry =
        (cj_viewer_plugin_entry)(uintptr_t)dlsym(h, CJ_VIEWER_PLUGIN_SYMBOL);
    const cj_viewer_plugin *table = entry ? entry() : NULL;
    if (!table || table->abi != CJ_VIEWER_PLUGIN_ABI) {
        if (!s->error[0])
            snprintf(s->error, sizeof s->error,
                     "'%s' is not a casteljau viewer module of this version", path);
        dlclose(h);
        return 0;
    }
    s->table = table; /* kept open for the life of the process */
    return 1;
}

static int try_beside(module_search *s, const char *object, const char *rel) {
    char buf[PATH_MAX];
    if (!object || !realpath(object, buf)) return 0;
    char *slash = strrchr(buf, '/');
    if (!slash) return 0;
    slash[1] = '\0';
    char cand[PATH_MAX + 64];
    if (snprintf(cand, sizeof cand, "%s%s%s", buf, rel, CJ_VIEWER_PLUGIN_FILE) >= (int)sizeof cand)
        return 0;
    return try_module(s, cand);
}

static void find_module(module_search *s) {
    const char *env = getenv("CJ_VIEWER_PLUGIN");
    if (env && *env) {
        if (!try_module(s, env) && !s->error[0])
            snprintf(s->error, sizeof s->error, "CJ_VIEWER_PLUGIN='%s' cannot be opened", env);
        return; /* an explicit choice is not second-guessed */
    }
    const char *rels[] = {"", "casteljau/", CJ_IMAGE_PLUGIN_RELDIR};
    Dl_info info;
    const char *holder = dladdr((void *)(uintptr_t)&find_module, &info) ? info.dli_fname : NULL;
    for (size_t i = 0; i < sizeof rels / sizeof rels[0]; ++i)
        if (try_beside(s, holder, rels[i]) || try_beside(s, "/proc/self/exe", rels[i])) return;
#ifdef CJ_VIEWER_PLUGIN_BUILD
    if (try_module(s, CJ_VIEWER_PLUGIN_BUILD)) return;
#endif
#ifdef CJ_VIEWER_PLUGIN_INSTALL
    if (try_module(s, CJ_VIEWER_PLUGIN_INSTALL)) return;
#endif
    if (!s->error[0])
        snprintf(s->error, sizeof s->error,
                 "the viewer module " CJ_VIEWER_PLUGIN_FILE " was not found next to the program "
                 "or library, in its ../lib/casteljau, or where it was built or installed (set "
                 "CJ_VIEWER_PLUGIN to its path)");
}

cj_status cj_viewer_run(const cj_viewer_options *opt) {
    assert(opt);
    static module_search search; /* `view` runs once per process */
    if (!search.table && !search.error[0]) find_module(&search);
    if (!search.table) return cj_fail(CJ_ERR_UNSUPPORTED, "%s", search.error);
    char why[1024] = "";
    const int st = search.table->run(opt, why, sizeof why);
    if (st) return cj_fail((cj_status)st, "%s", why[0] ? why : "the viewer failed");
    return CJ_OK;
}
