/* One tiny program per component of an installed casteljau (tests/install/run_install_test.cmake
 * builds it once per CJ_PART_* with find_package and once with pkg-config): each calls its
 * module's library through the installed headers only and prints what it got. */
#include <casteljau/status.h>

#include <stdio.h>

#if defined(CJ_PART_SURFACES)
#include <casteljau/patch.h>
int main(void) {
    /* The bilinear patch through (0,0,0) (1,0,0) (0,1,0) (1,1,1): S(1/2,1/2) = (1/2, 1/2, 1/4). */
    const double pts[] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 1};
    cj_patch p = cj_patch_view(1, 1, pts, NULL);
    double s[3];
    if (cj_patch_eval(&p, CJ_EVAL_DECASTELJAU, 0.5, 0.5, s) != CJ_OK) return 1;
    printf("casteljau surfaces: S(0.5,0.5) = %g %g %g\n", s[0], s[1], s[2]);
    return 0;
}
#elif defined(CJ_PART_SCENE)
#include <casteljau/scene.h>
int main(void) {
    cj_scene *s = NULL;
    if (cj_scene_create(NULL, &s) != CJ_OK) return 1;
    cj_light key = cj_light_defaults(CJ_LIGHT_POINT);
    if (cj_scene_add_light(s, &key, NULL) != CJ_OK) return 1;
    printf("casteljau scene: %zu light, %zu nodes\n", cj_scene_light_count(s),
           cj_scene_node_count(s));
    cj_scene_destroy(s);
    return 0;
}
#elif defined(CJ_PART_RASTER)
#include <casteljau/framebuffer.h>
int main(void) {
    cj_framebuffer *fb = NULL;
    if (cj_framebuffer_create(8, 4, 0, NULL, &fb) != CJ_OK) return 1;
    cj_framebuffer_clear(fb, cj_rgba_make(10, 20, 30, 255));
    cj_rgba px;
    if (cj_framebuffer_getpixel(fb, 7, 3, &px) != CJ_OK) return 1;
    printf("casteljau raster: pixel (7,3) = %d %d %d %d\n", px.r, px.g, px.b, px.a);
    cj_framebuffer_destroy(fb);
    return 0;
}
#elif defined(CJ_PART_VIZ)
#include <casteljau/image_io.h>
#include <stdint.h>
#include <stdlib.h>
int main(int argc, char **argv) {
    /* A 2 x 2 PNG written and read back through the installed OpenImageIO plug-in. */
    const char *path = argc > 1 ? argv[1] : "viz.png";
    const uint8_t rgba[16] = {255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 9, 9, 9, 255};
    if (cj_image_write(path, 2, 2, rgba, 0) != CJ_OK) {
        fprintf(stderr, "write: %s\n", cj_last_error());
        return 1;
    }
    int w = 0, h = 0;
    uint8_t *back = NULL;
    if (cj_image_read(path, &w, &h, &back) != CJ_OK) {
        fprintf(stderr, "read: %s\n", cj_last_error());
        return 1;
    }
    int same = w == 2 && h == 2;
    for (int i = 0; same && i < 16; ++i) same = back[i] == rgba[i];
    printf("casteljau viz: %s %dx%d read back %s\n", path, w, h, same ? "identical" : "DIFFERENT");
    cj_image_free(back);
    return same ? 0 : 1;
}
#else
#error "define one CJ_PART_*"
#endif
