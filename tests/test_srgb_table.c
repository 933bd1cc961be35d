/* cj_render_image_to_srgb8 by table gives the same bytes as the threshold search it replaced.
 *
 * The oracle is the definition: the code of a linear value x in (0, 1) is the number of the 255
 * thresholds decode((k + 1/2)/255) (IEC 61966-2-1 inverse curve in double, rounded to float)
 * that are <= x, counted here by a plain scan. Both the oracle and the converter are
 * non-decreasing step functions of x, so they agree on every float once they agree at each
 * threshold and at the float just below it (where every step of either could sit), at the ends of
 * [0, 1] and beyond; the bucket edges of the table (every 2^16-th float) are checked too, and a
 * seeded random sample of floats in (0, 1) and outside it. NaN stays CJ_ERR_NONFINITE. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "casteljau/render.h"
#include "rng.h"
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static float threshold[255];

static uint8_t oracle_code(float x) {
    if (!(x > 0.0f)) return 0;
    if (x >= 1.0f) return 255;
    int n = 0;
    for (int k = 0; k < 255; ++k) n += threshold[k] <= x;
    return (uint8_t)n;
}

static float from_bits(uint32_t u) {
    float f;
    memcpy(&f, &u, sizeof f);
    return f;
}

/* Converts `values` (as the R, G and B of successive pixels; alpha = 1) and compares every
 * channel with the oracle; returns the number of mismatches. */
/* Converts `values` (as the R, G and B of successive pixels of rows of up to 1024 pixels, alpha
 * 1) with a row stride wider than the row, and compares every channel with the oracle; returns
 * the number of mismatches. */
static size_t check_values(const float *values, size_t count) {
    size_t pixels = (count + 2) / 3;
    int width = pixels < 1024 ? (int)pixels : 1024;
    int height = (int)((pixels + (size_t)width - 1) / (size_t)width);
    size_t stride = (size_t)width * 4 + 8;
    cj_render_image *img = NULL;
    assert_int_equal(cj_render_image_create(width, height, 0, NULL, &img), CJ_OK);
    for (size_t i = 0; i < (size_t)width * (size_t)height; ++i) {
        for (size_t c = 0; c < 3; ++c)
            img->rgba[4 * i + c] = i * 3 + c < count ? values[i * 3 + c] : 0.0f;
        img->rgba[4 * i + 3] = 1.0f;
    }
    uint8_t *px = malloc(stride * (size_t)height);
    assert_true(px != NULL);
    assert_int_equal(cj_render_image_to_srgb8(img, px, stride), CJ_OK);
    size_t bad = 0;
    for (size_t j = 0; j < count; ++j) {
        size_t i = j / 3, at = (i / (size_t)width) * stride + 4 * (i % (size_t)width) + j % 3;
        uint8_t got = px[at], want = oracle_code(values[j]);
        if (got != want && bad++ < 5)
            printf("  MISMATCH x = %.9g: got %u, want %u\n", (double)values[j], got, want);
        if (j % 3 == 0) assert_int_equal(px[at + 3], 255);
    }
    free(px);
    cj_render_image_destroy(img);
    return bad;
}

/* Alpha stays linear: the oracle is lrintf of the clamped value times 255 (ties to even). */
static size_t check_alpha(const float *values, size_t count) {
    size_t bad = 0;
    for (size_t at = 0; at < count; at += 1024) {
        int width = count - at < 1024 ? (int)(count - at) : 1024;
        cj_render_image *img = NULL;
        assert_int_equal(cj_render_image_create(width, 1, 0, NULL, &img), CJ_OK);
        for (int i = 0; i < width; ++i) img->rgba[4 * i + 3] = values[at + (size_t)i];
        uint8_t px[4 * 1024];
        assert_int_equal(cj_render_image_to_srgb8(img, px, 0), CJ_OK);
        for (int i = 0; i < width; ++i) {
            float a = values[at + (size_t)i];
            a = a < 0.0f ? 0.0f : a > 1.0f ? 1.0f : a;
            uint8_t want = (uint8_t)lrintf(a * 255.0f);
            if (px[4 * i + 3] != want && bad++ < 5)
                printf("  ALPHA MISMATCH a = %.9g: got %u, want %u\n",
                       (double)values[at + (size_t)i], px[4 * i + 3], want);
        }
        cj_render_image_destroy(img);
    }
    return bad;
}

static void test_same_bytes(void **state) {
    (void)state;
    for (int k = 0; k < 255; ++k) {
        double y = (k + 0.5) / 255.0;
        double lin = y <= 0.04045 ? y / 12.92 : pow((y + 0.055) / 1.055, 2.4);
        threshold[k] = (float)lin;
    }
    for (int k = 1; k < 255; ++k) assert_true(threshold[k - 1] < threshold[k]);

    /* Each threshold, the floats within two steps of it. */
    float steps[255 * 5];
    size_t n = 0;
    for (int k = 0; k < 255; ++k) {
        float t = threshold[k];
        float below = nextafterf(t, 0.0f), above = nextafterf(t, 2.0f);
        steps[n++] = nextafterf(below, 0.0f);
        steps[n++] = below;
        steps[n++] = t;
        steps[n++] = above;
        steps[n++] = nextafterf(above, 2.0f);
    }
    size_t bad = check_values(steps, n);
    printf("thresholds: %zu floats at and within two steps of the 255 thresholds, %zu mismatches\n",
           n, bad);
    assert_int_equal(bad, 0);

    /* Table bucket edges: first and last float of every 2^16-float bucket of [0, 1). */
    static float edges[2 * (0x3F800000u >> 16)];
    n = 0;
    for (uint32_t b = 0; b < (0x3F800000u >> 16); ++b) {
        edges[n++] = from_bits(b << 16);
        edges[n++] = from_bits((b << 16) | 0xFFFFu);
    }
    bad = check_values(edges, n);
    printf("bucket edges: %zu floats, %zu mismatches\n", n, bad);
    assert_int_equal(bad, 0);

    /* Special values and the ends. */
    const float special[] = {0.0f,
                             -0.0f,
                             from_bits(1),
                             -from_bits(1),
                             1e-30f,
                             -1.0f,
                             1.0f,
                             nextafterf(1.0f, 0.0f),
                             nextafterf(1.0f, 2.0f),
                             2.0f,
                             INFINITY,
                             -INFINITY,
                             0.5f,
                             0.0031308f,
                             0.04045f};
    bad = check_values(special, sizeof special / sizeof special[0]);
    printf("special values (signed zeros, denormals, 1 and its neighbours, +-Inf): %zu "
           "mismatches\n",
           bad);
    assert_int_equal(bad, 0);
    const uint8_t want_special[] = {0, 0, 0, 0, 0, 0, 255, 255, 255, 255, 255, 0};
    for (size_t i = 0; i < sizeof want_special; ++i)
        assert_int_equal(oracle_code(special[i]), want_special[i]);

    /* Random floats: uniform bit patterns over [0, 1) and uniform values over [-0.5, 1.5]. */
    uint64_t seed = 20261126;
    cj_rng rng;
    cj_rng_init(&rng, seed);
    enum { RANDOM = 300000 };
    static float sample[RANDOM];
    for (int i = 0; i < RANDOM; ++i)
        sample[i] = (i & 1) ? from_bits((uint32_t)(cj_rng_next(&rng) % 0x3F800000u))
                            : (float)cj_rng_range(&rng, -0.5, 1.5);
    bad = check_values(sample, RANDOM);
    printf("random: %d floats (seed %llu), %zu mismatches\n", RANDOM, (unsigned long long)seed,
           bad);
    assert_int_equal(bad, 0);

    /* Alpha: the same sets, and the floats within three steps of every tie (k + 1/2)/255. */
    size_t abad = check_alpha(steps, 255 * 5) + check_alpha(edges, 2 * (0x3F800000u >> 16)) +
                  check_alpha(special, sizeof special / sizeof special[0]) +
                  check_alpha(sample, RANDOM);
    static float ties[255 * 7];
    n = 0;
    for (int k = 0; k < 255; ++k) {
        float t = (float)((k + 0.5) / 255.0);
        float lo = nextafterf(nextafterf(nextafterf(t, 0.0f), 0.0f), 0.0f);
        for (int i = 0; i < 7; ++i, lo = nextafterf(lo, 2.0f)) ties[n++] = lo;
    }
    abad += check_alpha(ties, n);
    printf("alpha: the sets above and %zu floats around the 255 rounding ties, %zu mismatches\n", n,
           abad);
    assert_int_equal(abad, 0);

    /* NaN is still an error naming the pixel, and the pixels before it are written. */
    cj_render_image *img = NULL;
    assert_int_equal(cj_render_image_create(2, 1, 0, NULL, &img), CJ_OK);
    img->rgba[0] = img->rgba[1] = img->rgba[2] = img->rgba[3] = 1.0f;
    img->rgba[5] = NAN;
    uint8_t px[8] = {0};
    assert_int_equal(cj_render_image_to_srgb8(img, px, 0), CJ_ERR_NONFINITE);
    for (int c = 0; c < 4; ++c) assert_int_equal(px[c], 255);
    img->rgba[5] = 0.5f;
    img->rgba[7] = NAN; /* alpha */
    assert_int_equal(cj_render_image_to_srgb8(img, px, 0), CJ_ERR_NONFINITE);
    cj_render_image_destroy(img);
    printf("NaN colour or alpha channel: CJ_ERR_NONFINITE, the pixels before it written\n");
}

int main(void) {
    const struct CMUnitTest tests[] = {cmocka_unit_test(test_same_bytes)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}
