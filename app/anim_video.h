/* Private to the casteljau tool: a film (.mp4, .webm, .mkv, .mov) written frame by frame through
 * FFmpeg's libraries (Debian libavformat-dev, libavcodec-dev, libswscale-dev). Each frame is
 * converted and encoded as it is added; nothing but the encoder's own look-ahead is held. */
#ifndef CASTELJAU_APP_ANIM_VIDEO_H
#define CASTELJAU_APP_ANIM_VIDEO_H

#include <stdint.h>

typedef struct anim_video anim_video;

/* 1 if `path` ends in an extension written as a film (.mp4 .m4v .mov .mkv .webm), else 0. */
int anim_video_is_film(const char *path);

/* Default and range of the quality setting: 1 (smallest file) .. 100 (visually lossless). It
 * maps linearly onto the encoder's constant-quality scale: H.264 (.mp4 .m4v .mov .mkv) CRF
 * 51..0, VP9 (.webm) CRF 63..0; 55 gives CRF 23 for H.264, x264's own default. */
#define ANIM_VIDEO_QUALITY_DEFAULT 55

/* Opens `path` for width x height frames (both even: the films are 4:2:0) at `fps` frames per
 * second with the given quality. Returns NULL with a reason in why[why_size] on failure (no
 * encoder for the container, odd size, cannot create the file). */
anim_video *anim_video_open(const char *path, int width, int height, double fps, int quality,
                            char *why, int why_size);
/* Encodes a frame of opaque RGBA8 pixels, rows BOTTOM-UP (as the renderer's images). 0 on
 * success. */
int anim_video_add(anim_video *v, const uint8_t *rgba, char *why, int why_size);
/* Flushes the encoder, writes the trailer and frees everything (also after a failure). 0 on
 * success. */
int anim_video_close(anim_video *v, char *why, int why_size);

#endif
