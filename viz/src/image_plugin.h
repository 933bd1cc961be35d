/* Private: the C ABI between casteljau_viz (image_io.c, which owns files, atomic renames and
 * error messages) and the OpenImageIO plug-in (image_oiio.cpp, a shared module opened with
 * dlopen on the first image call, so that programs which never touch an image never load
 * OpenImageIO and the few hundred libraries it pulls in).
 *
 * The plug-in exports one symbol, CJ_IMAGE_PLUGIN_SYMBOL, returning a static table. Every
 * entry returns a cj_status value and, on failure, writes a one-line reason to why[why_size]
 * (the loader passes it to cj_fail: the plug-in has no access to the library's error state).
 * Buffers it returns are malloc'd and freed by the loader with free(). */
#ifndef CASTELJAU_IMAGE_PLUGIN_H
#define CASTELJAU_IMAGE_PLUGIN_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#define CJ_IMAGE_PLUGIN_ABI    1
#define CJ_IMAGE_PLUGIN_SYMBOL "cj_image_plugin_v1"

typedef struct cj_image_pixels {
    int width, height;
    int is_float;       /* 0: RGBA8 (uint8_t), 1: RGBA float, linear; 2: the same, stored as
                           half floats where the format offers both (OpenEXR) */
    const void *pixels; /* bottom-up rows */
    size_t row_stride;  /* bytes between rows, > 0 */
} cj_image_pixels;

typedef struct cj_image_plugin {
    int abi; /* CJ_IMAGE_PLUGIN_ABI */
    /* Encodes `px` in the format OpenImageIO associates with `name`'s extension. When the
     * format can encode to memory, returns CJ_OK with *bytes (malloc'd) and *size set, and the
     * loader writes them itself (every write, fsync and close checked). Otherwise it writes the
     * file `tmp_path` through OpenImageIO and sets *bytes = NULL; the loader then calls
     * check_file, because OpenImageIO's file writers do not all report a short write.
     * Status: CJ_ERR_ARGUMENT (unknown extension, format that cannot store `px`), CJ_ERR_IO. */
    int (*encode)(const char *name, const char *tmp_path, const cj_image_pixels *px,
                  unsigned char **bytes, size_t *size, char *why, size_t why_size);
    /* Decodes the whole file again and checks its size: CJ_OK or CJ_ERR_IO. */
    int (*check_file)(const char *path, int width, int height, char *why, size_t why_size);
    /* cj_image_read's contract (RGBA8, bottom-up rows, malloc'd). */
    int (*read_rgba8)(const char *path, int *width, int *height, uint8_t **rgba, char *why,
                      size_t why_size);
    /* "OpenImageIO 2.4.7" */
    const char *(*version)(void);
} cj_image_plugin;

typedef const cj_image_plugin *(*cj_image_plugin_entry)(void);

#ifdef __cplusplus
}
#endif
#endif
