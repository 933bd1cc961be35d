/* libFuzzer target: animation documents (scene/anim_json.c), then what a run does with an
 * accepted one: attach to an empty scene, a frame rate given later (--fps), and the first
 * frames of the simulation. Everything a document can ask for is bounded by the reader
 * (anim_json.h), so every input must finish quickly; small grids and step counts are
 * simulated, larger ones only parsed, to keep the executions per second high. */
#include "casteljau/anim_json.h"
#include "casteljau/scene.h"

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
    cj_anim_doc *doc = NULL;
    if (cj_anim_doc_parse(text, "fuzz.json", "/nonexistent-cj-fuzz", &doc) == CJ_OK) {
        (void)cj_anim_doc_set_fps(doc, 0.5 + (double)(size % 97), "--fps");
        const int small = doc->steps_per_frame <= 8 && doc->particle_steps <= 8 &&
                          doc->cloth_nu * doc->cloth_nv <= 400 && doc->pdesc.capacity <= 500 &&
                          doc->frame_last - doc->frame_first < 1000;
        cj_scene *scene = NULL;
        if (small && cj_scene_create(NULL, &scene) == CJ_OK) {
            if (cj_anim_doc_attach(doc, scene) == CJ_OK)
                for (long f = 0; f < 3; ++f)
                    if (cj_anim_doc_frame(doc, scene, f, NULL) != CJ_OK) break;
            cj_scene_destroy(scene);
        }
        cj_anim_doc_destroy(doc);
    }
    free(text);
    return 0;
}
