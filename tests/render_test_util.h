/* Helpers shared by the renderer tests (include after cmocka.h). */
#ifndef CJ_TEST_RENDER_UTIL_H
#define CJ_TEST_RENDER_UTIL_H

#include "casteljau/render.h"
#include "render_scenes.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static inline int ran(const cj_stage_report *r, const char *name) {
    const cj_stage *s = cj_stage_report_find(r, name);
    assert_non_null(s);
    return s->ran;
}

/* Renders and returns the report; the image is freed unless wanted. */
static inline cj_render_image *render(const cj_scene *s, const cj_render_options *o,
                                      unsigned planes, cj_stage_report *rep) {
    cj_render_image *img = NULL;
    cj_stage_report local;
    cj_status st = cj_render_raster(s, o, planes, NULL, &img, rep ? rep : &local);
    if (st) fprintf(stderr, "render failed: %s\n", cj_last_error());
    assert_int_equal(st, CJ_OK);
    return img;
}

/* CJ_RENDER_DUMP=dir writes the images a test looks at as PPM (sRGB), to look at them. */
static inline void dump(const cj_render_image *img, const char *name) {
    const char *dir = getenv("CJ_RENDER_DUMP");
    if (!dir) return;
    char path[512];
    snprintf(path, sizeof path, "%s/%s.ppm", dir, name);
    FILE *f = fopen(path, "wb");
    if (!f) return;
    uint8_t *px = malloc((size_t)img->width * (size_t)img->height * 4);
    if (px && cj_render_image_to_srgb8(img, px, 0) == CJ_OK) {
        fprintf(f, "P6\n%d %d\n255\n", img->width, img->height);
        for (int y = img->height - 1; y >= 0; --y)
            for (int x = 0; x < img->width; ++x)
                fwrite(px + 4 * ((size_t)y * img->width + x), 1, 3, f);
    }
    free(px);
    fclose(f);
}

static inline int same_image(const cj_render_image *a, const cj_render_image *b) {
    size_t n = (size_t)a->width * (size_t)a->height;
    return a->width == b->width && a->height == b->height &&
           !memcmp(a->rgba, b->rgba, n * 4 * sizeof(float));
}

#endif
