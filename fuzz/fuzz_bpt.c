/* libFuzzer target: the .bpt patch-file reader, then the tessellation size predictor and a
 * coarse uniform tessellation of what it accepted (bounded: at most 64 patches, K = 2). */
#include "casteljau/patchset.h"
#include "casteljau/tessellate.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    if (size > (1 << 20)) return 0;
    char *text = malloc(size + 1);
    if (!text) return 0;
    memcpy(text, data, size);
    text[size] = '\0';
    cj_patchset *set = NULL;
    if (cj_patchset_parse_bpt(text, "fuzz.bpt", NULL, &set) == CJ_OK) {
        if (set->count <= 64) {
            cj_tess_options opt = {1e-2, 2, 0, 0};
            double predicted = 0.0;
            cj_mesh *mesh = NULL;
            if (cj_tessellate_predict(set->patches, set->count, &opt, &predicted) == CJ_OK &&
                cj_mesh_create(NULL, &mesh) == CJ_OK) {
                (void)cj_tessellate_patches(set->patches, set->count, &opt, mesh, NULL);
                cj_mesh_destroy(mesh);
            }
        }
        cj_patchset_destroy(set);
    }
    free(text);
    return 0;
}
