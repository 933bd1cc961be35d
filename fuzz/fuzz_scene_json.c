/* libFuzzer target: the scene JSON reader (scene/). Paths in the document are resolved
 * against a folder that does not exist, so referenced files are never found. */
#include "casteljau/scene_json.h"

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
    cj_scene *scene = NULL;
    if (cj_scene_parse_json(text, "fuzz.json", "/nonexistent-cj-fuzz", NULL, &scene) == CJ_OK)
        cj_scene_destroy(scene);
    free(text);
    return 0;
}
