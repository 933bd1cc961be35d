/* libFuzzer target: image and texture files through cj_image_read (viz/, the OpenImageIO
 * plug-in): the regular-file and size checks, the header's dimensions checked against the
 * pixel cap before decoding, and the decoders themselves, with their messages captured. The
 * input is written to a file (the plug-in reads by name) under /dev/shm when it exists. The
 * extension is chosen from the first byte, so that format detection by name is exercised too. */
#define _GNU_SOURCE
#include "casteljau/image_io.h"

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

int LLVMFuzzerInitialize(int *argc, char ***argv);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

/* A target whose decoders cannot load would test nothing: say so and stop. */
int LLVMFuzzerInitialize(int *argc, char ***argv) {
    (void)argc;
    (void)argv;
    if (!cj_image_backend()) {
        fprintf(stderr, "fuzz_image: %s\n", cj_last_error());
        exit(1);
    }
    return 0;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    static const char *const ext[] = {"png", "jpg", "tif", "bmp", "gif",  "exr", "ppm", "tga",
                                      "hdr", "iff", "dds", "psd", "webp", "ico", "sgi", "bin"};
    if (size > (1 << 20)) return 0;
    char path[128];
    const char *base = access("/dev/shm", W_OK) == 0 ? "/dev/shm" : "/tmp";
    snprintf(path, sizeof path, "%s/cj_fuzz_image_%ld.%s", base, (long)getpid(),
             ext[size ? data[0] % 16 : 0]);
    FILE *f = fopen(path, "wb");
    if (!f) return 0;
    const int ok = fwrite(data, 1, size, f) == size;
    if (fclose(f) != 0 || !ok) {
        unlink(path);
        return 0;
    }
    int w = 0, h = 0;
    uint8_t *px = NULL;
    if (cj_image_read(path, &w, &h, &px) == CJ_OK) {
        if (w < 1 || h < 1 || (long long)w * h > CJ_IMAGE_MAX_PIXELS) abort();
        cj_image_free(px);
    }
    unlink(path);
    return 0;
}
