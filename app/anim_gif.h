/* Private to the casteljau tool: an animated GIF written frame by frame through giflib (Debian
 * libgif-dev), each frame quantised to its own 256-colour palette by libimagequant (Debian
 * libimagequant-dev) and remapped with Floyd-Steinberg dithering, so smooth shading does not
 * fall into bands. */
#ifndef CASTELJAU_APP_ANIM_GIF_H
#define CASTELJAU_APP_ANIM_GIF_H

#include <stdint.h>

typedef struct anim_gif anim_gif;

/* 1 if path ends in .gif (any case). */
int anim_gif_is_gif(const char *path);

/* Opens `path` for width x height frames shown `delay_cs` hundredths of a second each, looping
 * forever, dithered at `dither` in [0, 1] (0: none, 1: full error diffusion). Returns NULL with
 * a reason in why[why_size] on failure. */
anim_gif *anim_gif_open(const char *path, int width, int height, int delay_cs, double dither,
                        char *why, int why_size);
/* Appends a frame of RGBA8 pixels, rows BOTTOM-UP (as the renderer's images). 0 on success. */
int anim_gif_add(anim_gif *g, const uint8_t *rgba, char *why, int why_size);
/* Finishes the file: written to a temporary beside `path`, renamed onto it only when every byte
 * reached the disk. 0 on success; on failure `path` keeps its old content. Frees g. */
int anim_gif_close(anim_gif *g, char *why, int why_size);
/* Drops the GIF (after a failure elsewhere): the temporary is removed, `path` untouched. */
void anim_gif_abandon(anim_gif *g);

#endif
