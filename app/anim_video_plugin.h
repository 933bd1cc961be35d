/* Private to the casteljau tool: the film writer (anim_video.c) is the module
 * libcasteljau_video.so, opened with dlopen by anim_video_loader.c only when a film is written,
 * so that no command maps FFmpeg and its ~100 codec libraries at start-up (they cost ~30 ms
 * and ~28 MB per launch). The module exports CJ_VIDEO_PLUGIN_SYMBOL, returning this table;
 * each entry has the contract of the anim_video.h function of the same name. */
#ifndef CASTELJAU_APP_ANIM_VIDEO_PLUGIN_H
#define CASTELJAU_APP_ANIM_VIDEO_PLUGIN_H

#include "anim_video.h"

#define ANIM_VIDEO_PLUGIN_ABI  1
#define CJ_VIDEO_PLUGIN_SYMBOL "cj_video_plugin_v1"
#define CJ_VIDEO_PLUGIN_FILE   "libcasteljau_video.so"

typedef struct anim_video_plugin {
    int abi; /* ANIM_VIDEO_PLUGIN_ABI */
    anim_video *(*open)(const char *path, int width, int height, double fps, int quality, char *why,
                        int why_size);
    int (*add)(anim_video *v, const uint8_t *rgba, char *why, int why_size);
    int (*close)(anim_video *v, char *why, int why_size);
} anim_video_plugin;

#endif
