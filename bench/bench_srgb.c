/* bench_srgb: cj_render_image_to_srgb8 on a 1024 x 1024 float image (issue 20, "sRGB by
 * table"). The pixels are a seeded spread over [-0.1, 1.1] per channel, so every code and both
 * clamps occur.
 *
 * Usage: bench_srgb [repetitions (default 15)]
 *            median wall and thread-CPU ms per conversion, and ns per pixel
 *        bench_srgb cg [conversions (default 2)]
 *            one warm-up, then callgrind collects only the conversions:
 *            valgrind --tool=callgrind --collect-atstart=no bench_srgb cg 2
 *            (instructions per pixel = total / conversions / 1048576). */
#define _POSIX_C_SOURCE 200809L
#include "bench_clock.h"

#include "casteljau/render.h"
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <valgrind/callgrind.h>

enum { SIDE = 1024 };

static void die(const char *what) {
    fprintf(stderr, "bench_srgb: %s failed\n", what);
    exit(1);
}

static cj_render_image *make_image(void) {
    cj_render_image *img = NULL;
    if (cj_render_image_create(SIDE, SIDE, 0, NULL, &img)) die("image");
    uint64_t state = 0x9E3779B97F4A7C15u;
    for (size_t i = 0; i < (size_t)SIDE * SIDE * 4; ++i) {
        state = state * 6364136223846793005u + 1442695040888963407u;
        double u = (double)(state >> 11) * 0x1p-53;
        img->rgba[i] = (i % 4 == 3) ? (float)u : (float)(-0.1 + 1.2 * u);
    }
    return img;
}

int main(int argc, char **argv) {
    cj_render_image *img = make_image();
    uint8_t *px = malloc((size_t)SIDE * SIDE * 4);
    if (!px) die("malloc");
    if (cj_render_image_to_srgb8(img, px, 0)) die("convert");
    if (argc > 1 && argv[1][0] == 'c') {
        int n = argc > 2 ? atoi(argv[2]) : 2;
        CALLGRIND_START_INSTRUMENTATION;
        CALLGRIND_TOGGLE_COLLECT;
        for (int i = 0; i < n; ++i) cj_render_image_to_srgb8(img, px, 0);
        CALLGRIND_TOGGLE_COLLECT;
        CALLGRIND_STOP_INSTRUMENTATION;
        printf("%d conversions of %d x %d collected (divide the callgrind total by %d)\n", n, SIDE,
               SIDE, n * SIDE * SIDE);
    } else {
        int reps = argc > 1 ? atoi(argv[1]) : 15;
        if (reps < 1 || reps > 1000) reps = 15;
        double wall[1000], cpu[1000];
        for (int i = 0; i < reps; ++i) {
            double w0 = cj_bench_wall(), c0 = cj_bench_thread_cpu();
            if (cj_render_image_to_srgb8(img, px, 0)) die("convert");
            cpu[i] = cj_bench_thread_cpu() - c0;
            wall[i] = cj_bench_wall() - w0;
        }
        qsort(wall, (size_t)reps, sizeof(double), cj_bench_cmp_double);
        qsort(cpu, (size_t)reps, sizeof(double), cj_bench_cmp_double);
        double c = cpu[reps / 2];
        printf("to_srgb8 %dx%d: median wall %.3f ms, thread CPU %.3f ms (%.2f ns per pixel), "
               "%d repetitions\n",
               SIDE, SIDE, 1e3 * wall[reps / 2], 1e3 * c, 1e9 * c / (SIDE * SIDE), reps);
    }
    unsigned sum = 0;
    for (size_t i = 0; i < (size_t)SIDE * SIDE * 4; ++i) sum += px[i];
    printf("checksum %u\n", sum);
    free(px);
    cj_render_image_destroy(img);
    return 0;
}
