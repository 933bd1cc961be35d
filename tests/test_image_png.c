/* The libpng path (viz/src/image_png.c) against the OpenImageIO plug-in it replaced for PNG:
 * - random RGBA8 images (padded strides too) encoded by both and decoded by both: all four
 *   decodes equal the source, byte for byte;
 * - PNGs of every colour type and bit depth (gray 1/2/4/8/16, gray+alpha, RGB 8/16 with and
 *   without tRNS, palettes with tRNS, RGBA 16, Adam7 interlace, a gAMA chunk) written here with
 *   libpng and decoded by both: identical RGBA8;
 * - errors: a truncated file (CJ_ERR_IO, "truncated"), a CRC error (libpng's message in ours),
 *   a header claiming 16000^2 pixels (CJ_ERR_RANGE before decoding), not a PNG; nothing is
 *   printed on stderr by libpng.
 * The plug-in is opened directly from where it was built (CJ_TEST_OIIO_PLUGIN). */
#define _GNU_SOURCE
#include "image_png_internal.h"

#include "casteljau/image_io.h"
#include "casteljau/status.h"

#include <dlfcn.h>
#include <png.h>
#include <zlib.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <setjmp.h>

#include <cmocka.h>

#include "rng.h"

static const cj_image_plugin *oiio;
static char dir[64];
static uint64_t seed;

static void load_oiio(void) {
    void *h = dlopen(CJ_TEST_OIIO_PLUGIN, RTLD_NOW | RTLD_LOCAL);
    if (!h) fail_msg("cannot open %s: %s", CJ_TEST_OIIO_PLUGIN, dlerror());
    cj_image_plugin_entry entry =
        (cj_image_plugin_entry)(uintptr_t)dlsym(h, CJ_IMAGE_PLUGIN_SYMBOL);
    assert_non_null(entry);
    oiio = entry();
    assert_non_null(oiio);
}

static void path_in(char *out, size_t n, const char *name) {
    snprintf(out, n, "%s/%s", dir, name);
}

static void put_bytes(const char *path, const unsigned char *b, size_t n) {
    FILE *f = fopen(path, "wb");
    assert_non_null(f);
    assert_int_equal(fwrite(b, 1, n, f), n);
    assert_int_equal(fclose(f), 0);
}

/* Decodes `path` with both readers; both must succeed with the same size and pixels. Returns
 * the libpng decode (caller frees). */
static uint8_t *decode_both(const char *path, const char *what, int *w, int *h) {
    char why[512] = "";
    int w1 = 0, h1 = 0, w2 = 0, h2 = 0;
    uint8_t *a = NULL, *b = NULL;
    int st = cj_png_read_rgba8(path, &w1, &h1, &a, why, sizeof why);
    if (st != CJ_OK) fail_msg("%s: libpng decode failed (%d): %s", what, st, why);
    st = oiio->read_rgba8(path, &w2, &h2, &b, why, sizeof why);
    if (st != CJ_OK) fail_msg("%s: OpenImageIO decode failed (%d): %s", what, st, why);
    if (w1 != w2 || h1 != h2) fail_msg("%s: %d x %d versus %d x %d", what, w1, h1, w2, h2);
    for (size_t i = 0; i < (size_t)w1 * h1 * 4; ++i)
        if (a[i] != b[i])
            fail_msg("%s: pixel %zu channel %zu: libpng %d, OpenImageIO %d", what, i / 4, i % 4,
                     a[i], b[i]);
    free(b);
    *w = w1;
    *h = h1;
    return a;
}

static void test_encoders_agree(void **state) {
    (void)state;
    cj_rng r;
    cj_rng_init(&r, seed);
    const int sizes[][3] = {{1, 1, 0}, {2, 3, 0}, {64, 64, 0}, {37, 19, 12}, {300, 7, 4}};
    for (size_t k = 0; k < sizeof sizes / sizeof sizes[0]; ++k) {
        const int w = sizes[k][0], h = sizes[k][1], pad = sizes[k][2];
        const size_t stride = (size_t)w * 4 + (size_t)pad;
        uint8_t *src = malloc(stride * (size_t)h);
        assert_non_null(src);
        for (size_t i = 0; i < stride * (size_t)h; ++i) src[i] = (uint8_t)cj_rng_next(&r);
        /* a few fully transparent pixels: alpha 0 must not lose the colour */
        for (int x = 0; x < w; x += 3) src[4 * x + 3] = 0;
        cj_image_pixels px = {w, h, 0, src, stride};
        char why[512] = "";
        for (int enc = 0; enc < 2; ++enc) {
            unsigned char *bytes = NULL;
            size_t size = 0;
            char p[256];
            path_in(p, sizeof p, enc ? "oiio.png" : "libpng.png");
            int st = enc ? oiio->encode("x.png", p, &px, &bytes, &size, why, sizeof why)
                         : cj_png_encode(&px, &bytes, &size, why, sizeof why);
            if (st != CJ_OK) fail_msg("encoder %d: %s", enc, why);
            if (bytes) put_bytes(p, bytes, size);
            free(bytes);
            int bw, bh;
            uint8_t *back = decode_both(p, enc ? "OpenImageIO's PNG" : "libpng's PNG", &bw, &bh);
            assert_int_equal(bw, w);
            assert_int_equal(bh, h);
            for (int y = 0; y < h; ++y)
                if (memcmp(back + (size_t)y * w * 4, src + (size_t)y * stride, (size_t)w * 4))
                    fail_msg("%d x %d, encoder %d: row %d differs from the source", w, h, enc, y);
            free(back);
        }
        free(src);
    }
    printf("test_image_png: RGBA8 images 1x1 .. 300x7 (padded strides, alpha 0) encoded by "
           "libpng and by OpenImageIO, each decoded by both: all equal the source\n");
}

/* Writes a PNG of the given colour type and depth, random samples, through libpng. */
typedef struct variant {
    const char *name;
    int color, depth, interlace, trns, gamma;
} variant;

static void write_variant(const char *path, const variant *v, cj_rng *r, int w, int h) {
    FILE *f = fopen(path, "wb");
    assert_non_null(f);
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, NULL, NULL, NULL);
    assert_non_null(png);
    png_infop info = png_create_info_struct(png);
    assert_non_null(info);
    if (setjmp(png_jmpbuf(png))) fail_msg("libpng failed writing %s", v->name);
    png_init_io(png, f);
    png_set_IHDR(png, info, (png_uint_32)w, (png_uint_32)h, v->depth, v->color, v->interlace,
                 PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    const int entries = v->color == PNG_COLOR_TYPE_PALETTE ? 1 << v->depth : 0;
    png_color pal[256];
    png_byte alpha[256];
    for (int i = 0; i < entries; ++i) {
        pal[i].red = (png_byte)cj_rng_next(r), pal[i].green = (png_byte)cj_rng_next(r);
        pal[i].blue = (png_byte)cj_rng_next(r), alpha[i] = (png_byte)cj_rng_next(r);
    }
    if (entries) png_set_PLTE(png, info, pal, entries);
    if (v->trns) {
        png_color_16 key = {0, 0, 0, 0, 0};
        const int maxv = (1 << v->depth) - 1;
        key.gray = (png_uint_16)(maxv / 3);
        key.red = key.green = key.blue = (png_uint_16)(maxv / 3);
        png_set_tRNS(png, info, alpha, entries ? entries / 2 : 0, entries ? NULL : &key);
    }
    if (v->gamma) png_set_gAMA(png, info, 1.0); /* must not change the decoded samples */
    png_write_info(png, info);
    const int channels = v->color == PNG_COLOR_TYPE_GRAY         ? 1
                         : v->color == PNG_COLOR_TYPE_GRAY_ALPHA ? 2
                         : v->color == PNG_COLOR_TYPE_RGB        ? 3
                         : v->color == PNG_COLOR_TYPE_RGBA       ? 4
                                                                 : 1;
    const size_t row_bytes = ((size_t)w * channels * v->depth + 7) / 8;
    png_bytep rows_mem = malloc(row_bytes * (size_t)h);
    png_bytep *rows = malloc(sizeof(png_bytep) * (size_t)h);
    assert_true(rows_mem && rows);
    for (size_t i = 0; i < row_bytes * (size_t)h; ++i) rows_mem[i] = (png_byte)cj_rng_next(r);
    /* some samples equal to the tRNS key, so that the transparency is exercised */
    if (v->trns && !entries && v->depth == 8)
        for (int y = 0; y < h; ++y) memset(rows_mem + row_bytes * (size_t)y, 85, row_bytes / 4);
    for (int y = 0; y < h; ++y) rows[y] = rows_mem + row_bytes * (size_t)y;
    png_write_image(png, rows);
    png_write_end(png, info);
    png_destroy_write_struct(&png, &info);
    free(rows);
    free(rows_mem);
    assert_int_equal(fclose(f), 0);
}

static void test_decoders_agree(void **state) {
    (void)state;
    cj_rng r;
    cj_rng_init(&r, seed + 1);
    const variant vs[] = {
        {"gray 1", PNG_COLOR_TYPE_GRAY, 1, 0, 0, 0},
        {"gray 2", PNG_COLOR_TYPE_GRAY, 2, 0, 0, 0},
        {"gray 4 tRNS", PNG_COLOR_TYPE_GRAY, 4, 0, 1, 0},
        {"gray 8", PNG_COLOR_TYPE_GRAY, 8, 0, 0, 1},
        {"gray 8 tRNS", PNG_COLOR_TYPE_GRAY, 8, 0, 1, 0},
        {"gray 16", PNG_COLOR_TYPE_GRAY, 16, 0, 0, 0},
        {"gray+alpha 8", PNG_COLOR_TYPE_GRAY_ALPHA, 8, 0, 0, 0},
        {"gray+alpha 16", PNG_COLOR_TYPE_GRAY_ALPHA, 16, 0, 0, 0},
        {"rgb 8", PNG_COLOR_TYPE_RGB, 8, 0, 0, 1},
        {"rgb 8 tRNS", PNG_COLOR_TYPE_RGB, 8, 0, 1, 0},
        {"rgb 16", PNG_COLOR_TYPE_RGB, 16, 0, 0, 0},
        {"rgba 8 Adam7", PNG_COLOR_TYPE_RGBA, 8, PNG_INTERLACE_ADAM7, 0, 0},
        {"rgba 16", PNG_COLOR_TYPE_RGBA, 16, 0, 0, 1},
        {"palette 1", PNG_COLOR_TYPE_PALETTE, 1, 0, 0, 0},
        {"palette 4 tRNS", PNG_COLOR_TYPE_PALETTE, 4, 0, 1, 0},
        {"palette 8 tRNS Adam7", PNG_COLOR_TYPE_PALETTE, 8, PNG_INTERLACE_ADAM7, 1, 0},
    };
    for (size_t i = 0; i < sizeof vs / sizeof vs[0]; ++i) {
        char p[256];
        path_in(p, sizeof p, "variant.png");
        write_variant(p, &vs[i], &r, 23, 11);
        int w, h;
        uint8_t *px = decode_both(p, vs[i].name, &w, &h);
        assert_int_equal(w, 23);
        assert_int_equal(h, 11);
        free(px);
    }
    printf("test_image_png: %zu PNG kinds (gray 1-16 bit, gray+alpha, RGB/RGBA 8 and 16, "
           "palettes, tRNS, Adam7, gAMA) decode identically through libpng and OpenImageIO\n",
           sizeof vs / sizeof vs[0]);
}

static unsigned char *slurp(const char *path, size_t *n) {
    FILE *f = fopen(path, "rb");
    assert_non_null(f);
    fseek(f, 0, SEEK_END);
    long len = ftell(f);
    fseek(f, 0, SEEK_SET);
    unsigned char *b = malloc((size_t)len);
    assert_non_null(b);
    assert_int_equal(fread(b, 1, (size_t)len, f), (size_t)len);
    fclose(f);
    *n = (size_t)len;
    return b;
}

static void expect_error(const char *path, int want, const char *needle) {
    char why[512] = "";
    int w = -1, h = -1;
    uint8_t *px = (uint8_t *)&w;
    int st = cj_png_read_rgba8(path, &w, &h, &px, why, sizeof why);
    if (st != want || !strstr(why, needle))
        fail_msg("%s: status %d (want %d), message '%s' (want '%s')", path, st, want, why, needle);
    /* outputs untouched */
    assert_int_equal(w, -1);
    assert_true(px == (uint8_t *)&w);
    if (strchr(why, '\n')) fail_msg("message of two lines: %s", why);
    printf("  %s: %s\n", strrchr(path, '/') + 1, why);
}

static void test_errors(void **state) {
    (void)state;
    /* a good file to damage */
    static uint8_t src[64 * 64 * 4];
    for (size_t i = 0; i < sizeof src; ++i) src[i] = (uint8_t)(i * 7 + i / 5);
    cj_image_pixels px = {64, 64, 0, src, 256};
    unsigned char *bytes = NULL;
    size_t size = 0;
    char why[512];
    assert_int_equal(cj_png_encode(&px, &bytes, &size, why, sizeof why), CJ_OK);
    char p[256];
    /* libpng must print nothing: stderr goes to a file while the errors are provoked */
    char errp[256];
    path_in(errp, sizeof errp, "stderr.txt");
    fflush(stderr);
    int saved = dup(2);
    FILE *errf = freopen(errp, "w", stderr);
    assert_non_null(errf);

    path_in(p, sizeof p, "cut.png");
    put_bytes(p, bytes, size / 2);
    expect_error(p, CJ_ERR_IO, "truncated");
    path_in(p, sizeof p, "header_only.png");
    put_bytes(p, bytes, 33);
    expect_error(p, CJ_ERR_IO, "truncated");
    /* flip a byte inside the IHDR data: its CRC fails */
    unsigned char *bad = malloc(size);
    assert_non_null(bad);
    memcpy(bad, bytes, size);
    bad[20] ^= 0x40;
    path_in(p, sizeof p, "crc.png");
    put_bytes(p, bad, size);
    expect_error(p, CJ_ERR_IO, "libpng: ");
    /* the header says 16000 x 16000 (CRC fixed up): refused before any pixel */
    memcpy(bad, bytes, size);
    const unsigned char dims[8] = {0, 0, 0x3e, 0x80, 0, 0, 0x3e, 0x80};
    memcpy(bad + 16, dims, 8);
    const uLong crc = crc32(crc32(0, NULL, 0), bad + 12, 17);
    bad[29] = (unsigned char)(crc >> 24), bad[30] = (unsigned char)(crc >> 16);
    bad[31] = (unsigned char)(crc >> 8), bad[32] = (unsigned char)crc;
    path_in(p, sizeof p, "huge.png");
    put_bytes(p, bad, size);
    expect_error(p, CJ_ERR_RANGE, "16000 x 16000");
    path_in(p, sizeof p, "text.png");
    put_bytes(p, (const unsigned char *)"not a png at all, just text\n", 28);
    expect_error(p, CJ_ERR_IO, "libpng: ");
    path_in(p, sizeof p, "missing.png");
    expect_error(p, CJ_ERR_IO, "No such file");
    free(bad);
    free(bytes);

    fflush(stderr);
    assert_true(dup2(saved, 2) >= 0);
    close(saved);
    setvbuf(stderr, NULL, _IONBF, 0);
    size_t n = 0;
    unsigned char *printed = slurp(errp, &n);
    if (n) fail_msg("libpng printed on stderr: %.*s", (int)n, (const char *)printed);
    free(printed);
    /* float pixels: the same refusal as the plug-in gave */
    float one[4] = {1, 1, 1, 1};
    cj_image_pixels fpx = {1, 1, 1, one, 16};
    assert_int_equal(cj_png_encode(&fpx, &bytes, &size, why, sizeof why), CJ_ERR_ARGUMENT);
    assert_non_null(strstr(why, "floating-point"));
    printf("test_image_png: truncated, CRC-damaged, oversized (16000^2 header), non-PNG and "
           "missing files refused with one-line messages, outputs untouched, nothing printed "
           "by libpng; float pixels refused\n");
}

int main(void) {
    seed = cj_test_seed("test_image_png", 20261126);
    load_oiio();
    snprintf(dir, sizeof dir, "/tmp/cj_test_image_png_XXXXXX");
    assert_non_null(mkdtemp(dir));
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_encoders_agree),
        cmocka_unit_test(test_decoders_agree),
        cmocka_unit_test(test_errors),
    };
    int rc = cmocka_run_group_tests(tests, NULL, NULL);
    const char *names[] = {"oiio.png", "libpng.png", "variant.png", "cut.png",        "crc.png",
                           "huge.png", "text.png",   "stderr.txt",  "header_only.png"};
    for (size_t i = 0; i < sizeof names / sizeof names[0]; ++i) {
        char p[256];
        path_in(p, sizeof p, names[i]);
        unlink(p);
    }
    rmdir(dir);
    return rc;
}
