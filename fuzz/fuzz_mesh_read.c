/* libFuzzer target: the OBJ and PLY mesh readers (surfaces/mesh_read.h). They read files, so
 * the input goes to an in-memory file (memfd) read through /proc/self/fd; the first byte picks
 * the format. */
#define _GNU_SOURCE
#include "casteljau/mesh_read.h"

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <sys/mman.h>
#include <unistd.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    if (size < 1 || size > (1 << 20)) return 0;
    int fd = memfd_create("cj_fuzz_mesh", 0);
    if (fd < 0) return 0;
    if (write(fd, data + 1, size - 1) == (ssize_t)(size - 1)) {
        char path[64];
        snprintf(path, sizeof path, "/proc/self/fd/%d", fd);
        cj_mesh *mesh = NULL;
        cj_status st =
            data[0] & 1 ? cj_mesh_read_ply(path, NULL, &mesh) : cj_mesh_read_obj(path, NULL, &mesh);
        if (st == CJ_OK) cj_mesh_destroy(mesh);
    }
    close(fd);
    return 0;
}
