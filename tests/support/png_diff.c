/* Pixel comparison of two PNG files (png_diff.h). */
#include "png_diff.h"

#include "casteljau/image_io.h"

#include <stdint.h>
#include <stdio.h>
#include <string.h>

long cj_test_png_differ(const char *dir, const char *a, const char *b) {
    char pa[512], pb[512];
    snprintf(pa, sizeof pa, "%s/%s", dir, a);
    snprintf(pb, sizeof pb, "%s/%s", dir, b);
    int wa = 0, ha = 0, wb = 0, hb = 0;
    uint8_t *x = NULL, *y = NULL;
    long n = -2;
    if (cj_image_read(pa, &wa, &ha, &x) == CJ_OK && cj_image_read(pb, &wb, &hb, &y) == CJ_OK) {
        n = -1;
        if (wa == wb && ha == hb) {
            n = 0;
            for (long i = 0; i < (long)wa * ha; ++i) n += memcmp(x + 4 * i, y + 4 * i, 4) != 0;
        }
    }
    cj_image_free(x);
    cj_image_free(y);
    return n;
}
