/* The film writer of a build without FFmpeg's libraries: every film is refused, saying why. */
#include "anim_video.h"

#include <stdio.h>
#include <string.h>
#include <strings.h>

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
    (void)path, (void)width, (void)height, (void)fps, (void)quality;
    snprintf(why, (size_t)why_size,
             "this build writes no films (configure with FFmpeg's libavformat, libavcodec and "
             "libswscale)");
    return NULL;
}

int anim_video_add(anim_video *v, const uint8_t *rgba, char *why, int why_size) {
    (void)v, (void)rgba, (void)why, (void)why_size;
    return -1;
}

int anim_video_close(anim_video *v, char *why, int why_size) {
    (void)v, (void)why, (void)why_size;
    return 0;
}
