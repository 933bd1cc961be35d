/* cj_mesh_read: the reader chosen by the file's extension (OBJ in mesh_read_obj.c, PLY in
 * mesh_read_ply.c). */
#include "casteljau/mesh_read.h"

#include "error_internal.h"

#include <assert.h>
#include <string.h>

static int ends_with_ci(const char *s, const char *suffix) {
    size_t a = strlen(s), b = strlen(suffix);
    if (a < b) return 0;
    for (size_t i = 0; i < b; ++i) {
        char c = s[a - b + i];
        if (c >= 'A' && c <= 'Z') c = (char)(c - 'A' + 'a');
        if (c != suffix[i]) return 0;
    }
    return 1;
}

cj_status cj_mesh_read(const char *path, const cj_allocator *alloc, cj_mesh **out) {
    assert(path && out);
    if (ends_with_ci(path, ".obj")) return cj_mesh_read_obj(path, alloc, out);
    if (ends_with_ci(path, ".ply")) return cj_mesh_read_ply(path, alloc, out);
    return cj_fail(CJ_ERR_ARGUMENT, "'%s': unknown mesh extension (use .obj or .ply)", path);
}
