/* Animated GIF through giflib (file format, NETSCAPE2.0 loop block), per-frame palettes and
 * dithered remapping through libimagequant. The bytes go through the atomic writer
 * (file_internal.h): an old GIF is replaced only by a complete new one, and an interrupted run
 * leaves no temporary behind. */
#include "anim_gif.h"

#include "file_internal.h"

#include <gif_lib.h>
#include <libimagequant.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

struct anim_gif {
    GifFileType *f;
    cj_atomic_file out;
    int w, h, delay;
    float dither;
    uint8_t *rgba; /* the frame top-down, as GIF and libimagequant want it */
    GifByteType *idx;
    liq_attr *liq;
};

int anim_gif_is_gif(const char *path) {
    const size_t n = strlen(path);
    return n > 4 && !strcasecmp(path + n - 4, ".gif");
}

/* giflib's reason when it has one (a write error of ours has none: the stream says it). */
static void reason(char *why, int size, const char *what, int code) {
    const char *s = code ? GifErrorString(code) : NULL;
    if (s)
        snprintf(why, (size_t)size, "%s (%s)", what, s);
    else
        snprintf(why, (size_t)size, "%s", what);
}

static int put_bytes(GifFileType *f, const GifByteType *bytes, int n) {
    FILE *fp = f->UserData;
    return (int)fwrite(bytes, 1, (size_t)n, fp);
}

static void free_gif(anim_gif *g) {
    if (g->liq) liq_attr_destroy(g->liq);
    free(g->rgba);
    free(g->idx);
    free(g);
}

anim_gif *anim_gif_open(const char *path, int width, int height, int delay_cs, double dither,
                        char *why, int why_size) {
    int err = 0;
    anim_gif *g = calloc(1, sizeof *g);
    const size_t n = (size_t)width * (size_t)height;
    if (!g) {
        snprintf(why, (size_t)why_size, "out of memory");
        return NULL;
    }
    g->w = width;
    g->h = height;
    g->delay = delay_cs;
    g->dither = (float)dither;
    g->rgba = malloc(4 * n);
    g->idx = malloc(n);
    g->liq = liq_attr_create();
    if (!g->rgba || !g->idx || !g->liq) {
        snprintf(why, (size_t)why_size, "out of memory for %d x %d GIF frames", width, height);
        free_gif(g);
        return NULL;
    }
    if (cj_atomic_open(&g->out, path)) {
        snprintf(why, (size_t)why_size, "%s", cj_last_error());
        free_gif(g);
        return NULL;
    }
    g->f = EGifOpen(g->out.fp, put_bytes, &err);
    if (!g->f) {
        reason(why, why_size, "giflib cannot start the GIF", err);
        cj_atomic_abandon(&g->out);
        free_gif(g);
        return NULL;
    }
    EGifSetGifVersion(g->f, true);
    if (EGifPutScreenDesc(g->f, width, height, 8, 0, NULL) == GIF_ERROR) {
        reason(why, why_size, "GIF screen descriptor", g->f->Error);
        anim_gif_abandon(g);
        return NULL;
    }
    /* loop forever: NETSCAPE2.0 application extension, sub-block {1, 0, 0} */
    static const GifByteType app[11] = {'N', 'E', 'T', 'S', 'C', 'A', 'P', 'E', '2', '.', '0'};
    static const GifByteType loop[3] = {1, 0, 0};
    if (EGifPutExtensionLeader(g->f, APPLICATION_EXT_FUNC_CODE) == GIF_ERROR ||
        EGifPutExtensionBlock(g->f, 11, app) == GIF_ERROR ||
        EGifPutExtensionBlock(g->f, 3, loop) == GIF_ERROR ||
        EGifPutExtensionTrailer(g->f) == GIF_ERROR) {
        reason(why, why_size, "GIF loop block", g->f->Error);
        anim_gif_abandon(g);
        return NULL;
    }
    return g;
}

int anim_gif_add(anim_gif *g, const uint8_t *rgba, char *why, int why_size) {
    const size_t n = (size_t)g->w * (size_t)g->h, row = 4 * (size_t)g->w;
    for (int y = 0; y < g->h; ++y) /* GIF rows go top-down */
        memcpy(g->rgba + (size_t)y * row, rgba + (size_t)(g->h - 1 - y) * row, row);
    liq_image *img = liq_image_create_rgba(g->liq, g->rgba, g->w, g->h, 0);
    liq_result *res = NULL;
    if (!img || liq_image_quantize(img, g->liq, &res) != LIQ_OK) {
        if (img) liq_image_destroy(img);
        snprintf(why, (size_t)why_size, "GIF colour quantisation failed");
        return -1;
    }
    liq_set_dithering_level(res, g->dither);
    const liq_error remapped = liq_write_remapped_image(res, img, g->idx, n);
    const liq_palette *pal = liq_get_palette(res);
    GifColorType colors[256];
    memset(colors, 0, sizeof colors);
    for (unsigned i = 0; i < pal->count && i < 256; ++i) {
        colors[i].Red = pal->entries[i].r;
        colors[i].Green = pal->entries[i].g;
        colors[i].Blue = pal->entries[i].b;
    }
    liq_result_destroy(res);
    liq_image_destroy(img);
    if (remapped != LIQ_OK) {
        snprintf(why, (size_t)why_size, "GIF colour remapping failed");
        return -1;
    }
    ColorMapObject *map = GifMakeMapObject(256, colors);
    if (!map) {
        snprintf(why, (size_t)why_size, "out of memory for a GIF palette");
        return -1;
    }
    GraphicsControlBlock gcb = {DISPOSAL_UNSPECIFIED, false, g->delay, NO_TRANSPARENT_COLOR};
    GifByteType ext[4];
    const size_t len = EGifGCBToExtension(&gcb, ext);
    int ok = EGifPutExtension(g->f, GRAPHICS_EXT_FUNC_CODE, (int)len, ext) != GIF_ERROR &&
             EGifPutImageDesc(g->f, 0, 0, g->w, g->h, false, map) != GIF_ERROR;
    for (int y = 0; ok && y < g->h; ++y)
        ok = EGifPutLine(g->f, g->idx + (size_t)y * (size_t)g->w, g->w) != GIF_ERROR;
    GifFreeMapObject(map);
    if (!ok) {
        reason(why, why_size, "writing a GIF frame failed", g->f->Error);
        return -1;
    }
    return 0;
}

int anim_gif_close(anim_gif *g, char *why, int why_size) {
    int err = 0;
    const int rc = EGifCloseFile(g->f, &err); /* writes the trailer; our stream stays open */
    int bad = 0;
    if (rc == GIF_ERROR) {
        reason(why, why_size, "finishing the GIF failed", err);
        cj_atomic_abandon(&g->out);
        bad = 1;
    } else if (cj_atomic_commit(&g->out)) {
        snprintf(why, (size_t)why_size, "%s", cj_last_error());
        bad = 1;
    }
    free_gif(g);
    return bad ? -1 : 0;
}

void anim_gif_abandon(anim_gif *g) {
    if (!g) return;
    int err = 0;
    EGifCloseFile(g->f, &err);
    cj_atomic_abandon(&g->out);
    free_gif(g);
}
