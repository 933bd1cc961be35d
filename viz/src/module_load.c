/* cj_module_open (module_internal.h). */
#define _GNU_SOURCE /* dladdr */
#include "module_internal.h"

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

typedef struct search {
    const cj_module_spec *spec;
    const void *table;
    char *why; /* the first real failure: a module that exists but cannot load */
    size_t why_size;
} search;

typedef const void *(*module_entry)(void);

static int try_module(search *s, const char *path) {
    if (!path || !*path) return 0;
    void *h = dlopen(path, RTLD_NOW | RTLD_LOCAL);
    if (!h) {
        const char *e = dlerror();
        if (access(path, F_OK) == 0 && !s->why[0])
            snprintf(s->why, s->why_size, "%s '%s' cannot be loaded: %s (%s)", s->spec->what, path,
                     e ? e : "dlopen failed", s->spec->needs);
        return 0;
    }
    module_entry entry = (module_entry)(uintptr_t)dlsym(h, s->spec->symbol);
    const void *table = entry ? entry() : NULL;
    if (!table) {
        if (!s->why[0])
            snprintf(s->why, s->why_size, "'%s' is not %s of this version", path, s->spec->what);
        dlclose(h);
        return 0;
    }
    s->table = table;
    return 1;
}

static int try_beside(search *s, const char *object, const char *rel) {
    char buf[PATH_MAX];
    if (!object || !realpath(object, buf)) return 0;
    char *slash = strrchr(buf, '/');
    if (!slash) return 0;
    slash[1] = '\0';
    char cand[PATH_MAX + 128];
    if (snprintf(cand, sizeof cand, "%s%s%s", buf, rel, s->spec->file) >= (int)sizeof cand)
        return 0;
    return try_module(s, cand);
}

const void *cj_module_open(const cj_module_spec *spec, char *why, size_t why_size) {
    why[0] = '\0';
    search s = {spec, NULL, why, why_size};
    const char *env = getenv(spec->env);
    if (env && *env) {
        if (!try_module(&s, env) && !why[0])
            snprintf(why, why_size, "%s=%s: %s cannot be opened", spec->env, env, spec->what);
        return s.table; /* an explicit choice is not second-guessed */
    }
    const char *rels[] = {"", "casteljau/", CJ_IMAGE_PLUGIN_RELDIR};
    Dl_info info;
    const char *holder = dladdr((void *)(uintptr_t)&cj_module_open, &info) ? info.dli_fname : NULL;
    for (size_t i = 0; i < sizeof rels / sizeof rels[0]; ++i)
        if (try_beside(&s, holder, rels[i]) || try_beside(&s, "/proc/self/exe", rels[i]))
            return s.table;
    if (try_module(&s, spec->build_path) || try_module(&s, spec->install_path)) return s.table;
    if (!why[0])
        snprintf(why, why_size,
                 "%s %s was not found next to the program or library, in its ../lib/casteljau, "
                 "or where it was built or installed (set %s to its path)",
                 spec->what, spec->file, spec->env);
    return NULL;
}
