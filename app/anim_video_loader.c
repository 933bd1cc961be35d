/* anim_video.h in the program: the film writer itself is the module libcasteljau_video.so
 * (anim_video_plugin.h), opened on the first film. */
#include "anim_video.h"
#include "anim_video_plugin.h"
#include "module_internal.h"

#include <stdio.h>
#include <string.h>
#include <strings.h>

#ifndef CJ_VIDEO_PLUGIN_BUILD
#define CJ_VIDEO_PLUGIN_BUILD NULL
#endif
#ifndef CJ_VIDEO_PLUGIN_INSTALL
#define CJ_VIDEO_PLUGIN_INSTALL NULL
#endif

/* The module of the open film (set by anim_video_open). */
static const anim_video_plugin *loaded;

int anim_video_is_film(const char *path) {
    static const char *const ext[] = {".mp4", ".m4v", ".mov", ".mkv", ".webm"};
    const size_t n = strlen(path);
    for (size_t i = 0; i < sizeof ext / sizeof ext[0]; ++i) {
        const size_t k = strlen(ext[i]);
        if (n > k && !strcasecmp(path + n - k, ext[i])) return 1;
    }
    return 0;
}

anim_video *anim_video_open(const char *path, int width, int height, double fps, int quality,
                            char *why, int why_size) {
    static const cj_module_spec spec = {
        CJ_VIDEO_PLUGIN_FILE,
        "CJ_VIDEO_PLUGIN",
        CJ_VIDEO_PLUGIN_BUILD,
        CJ_VIDEO_PLUGIN_INSTALL,
        CJ_VIDEO_PLUGIN_SYMBOL,
        "the film module",
        "films need FFmpeg's libraries: Debian's libavformat59, libavcodec59 and libswscale6"};
    /* dlopen of a module already open only counts a reference */
    const anim_video_plugin *table =
        (const anim_video_plugin *)cj_module_open(&spec, why, (size_t)why_size);
    if (!table) return NULL;
    if (table->abi != ANIM_VIDEO_PLUGIN_ABI) {
        snprintf(why, (size_t)why_size, "the film module is of another version (ABI %d, want %d)",
                 table->abi, ANIM_VIDEO_PLUGIN_ABI);
        return NULL;
    }
    anim_video *v = table->open(path, width, height, fps, quality, why, why_size);
    if (v) loaded = table;
    return v;
}

int anim_video_add(anim_video *v, const uint8_t *rgba, char *why, int why_size) {
    if (!loaded) {
        snprintf(why, (size_t)why_size, "no film is open");
        return -1;
    }
    return loaded->add(v, rgba, why, why_size);
}

int anim_video_close(anim_video *v, char *why, int why_size) {
    if (!loaded) return 0; /* nothing was opened: nothing to close */
    return loaded->close(v, why, why_size);
}
