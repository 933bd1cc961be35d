/* Private: finding and opening the optional modules of casteljau (the viewer, the film
 * writer), shared objects opened with dlopen only by the commands that need them, so that the
 * program starts without mapping their libraries (GLFW and OpenGL; FFmpeg and its codecs).
 * Each module exports one symbol returning a static table of functions. */
#ifndef CASTELJAU_MODULE_INTERNAL_H
#define CASTELJAU_MODULE_INTERNAL_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct cj_module_spec {
    const char *file;         /* "libcasteljau_viewer.so" */
    const char *env;          /* environment variable naming the module explicitly */
    const char *build_path;   /* where the build put it, or NULL */
    const char *install_path; /* where `cmake --install` puts it, or NULL */
    const char *symbol;       /* the entry: const void *entry(void) */
    const char *what;         /* "the viewer module", for messages */
    const char *needs;        /* what a failing dlopen most likely lacks, for messages */
} cj_module_spec;

/* Opens the module and returns what its entry returned (its table). The module is looked for
 * as the image plug-in is: spec->env when set (and then only there), else next to the object
 * holding this code and to the running program, in their casteljau/ and ../lib/casteljau/
 * folders, then at build_path and install_path. Returns NULL with a one-line reason in
 * why[why_size]: not found (where it looked, and the variable to set), or found but not
 * loadable (dlerror's reason and spec->needs). The module stays open for the process. */
const void *cj_module_open(const cj_module_spec *spec, char *why, size_t why_size);

#ifdef __cplusplus
}
#endif
#endif
