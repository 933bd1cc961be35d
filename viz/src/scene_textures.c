/* Image textures of a scene: files read through image_io.h, sRGB decoded to linear floats. */
#include "casteljau/scene_textures.h"

#include "casteljau/image_io.h"
#include "error_internal.h"

#include <assert.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static float srgb_decode(int i) {
    double c = i / 255.0;
    return (float)(c <= 0.04045 ? c / 12.92 : pow((c + 0.055) / 1.055, 2.4));
}

float cj_srgb8_to_linear(unsigned char c) {
    return srgb_decode(c);
}

cj_status cj_scene_load_textures(cj_scene *scene, const char *base_dir) {
    assert(scene != NULL);
    float srgb_table[256];
    for (int i = 0; i < 256; ++i) srgb_table[i] = srgb_decode(i);
    if (!base_dir) base_dir = "";
    const size_t n = cj_scene_texture_count(scene);
    for (size_t i = 0; i < n; ++i) {
        const cj_texture *t = cj_scene_texture(scene, (int)i);
        if (t->kind != CJ_TEX_IMAGE || t->texels) continue;
        const char *src = cj_scene_texture_source(scene, (int)i);
        char where[512];
        if (src)
            snprintf(where, sizeof where, "%s.path", src);
        else
            snprintf(where, sizeof where, "textures[%zu].path", i);
        char file[4096];
        int w = (t->path[0] == '/' || !base_dir[0])
                    ? snprintf(file, sizeof file, "%s", t->path)
                    : snprintf(file, sizeof file, "%s/%s", base_dir, t->path);
        if (w < 0 || (size_t)w >= sizeof file)
            return cj_fail(CJ_ERR_IO, "%s: path too long", where);
        int width = 0, height = 0;
        uint8_t *rgba = NULL;
        cj_status st = cj_image_read(file, &width, &height, &rgba);
        if (st) {
            char msg[512];
            snprintf(msg, sizeof msg, "%s", cj_last_error());
            return cj_fail(st, "%s: cannot read image texture '%s': %s", where, file, msg);
        }
        size_t count = (size_t)width * (size_t)height * 4;
        float *lin = malloc(count * sizeof *lin);
        if (!lin) {
            cj_image_free(rgba);
            return cj_fail(CJ_ERR_NOMEM, "%s: out of memory for %d x %d texels", where, width,
                           height);
        }
        for (size_t k = 0; k < count; k += 4) {
            lin[k] = srgb_table[rgba[k]];
            lin[k + 1] = srgb_table[rgba[k + 1]];
            lin[k + 2] = srgb_table[rgba[k + 2]];
            lin[k + 3] = rgba[k + 3] / 255.0f;
        }
        cj_image_free(rgba);
        st = cj_scene_set_texture_pixels(scene, (int)i, width, height, lin);
        free(lin);
        if (st) return st;
    }
    return CJ_OK;
}

cj_status cj_scene_load_with_textures(const char *path, const cj_scene_json_options *options,
                                      const cj_allocator *alloc, cj_scene **out) {
    assert(path && out);
    const cj_scene_json_options none = {NULL};
    cj_scene *scene = NULL;
    cj_status st = cj_scene_load_json_with_options(path, options ? options : &none, alloc, &scene);
    if (st) return st;
    /* the file's folder: "" for a bare name, "/" for a file at the root */
    const char *slash = strrchr(path, '/');
    const size_t n = slash ? (size_t)(slash - path) : 0;
    char *dir = malloc(n + 2);
    if (!dir) {
        cj_scene_destroy(scene);
        return cj_fail(CJ_ERR_NOMEM, "%s: out of memory", path);
    }
    memcpy(dir, path, n);
    dir[n] = '\0';
    if (slash && !n) strcpy(dir, "/");
    st = cj_scene_load_textures(scene, dir);
    free(dir);
    if (st) {
        cj_scene_destroy(scene);
        return st;
    }
    *out = scene;
    return CJ_OK;
}
