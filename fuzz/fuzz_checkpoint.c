/* libFuzzer target: animation checkpoints (cj_anim_doc_load_state: the frame, the cloth's state,
 * the particle system's state), then one frame simulated from what was accepted: a checkpoint
 * that loads must describe a state that simulates in bounded time (no NaN, inf or huge
 * emission fraction gets through). The document is fixed: a 4 x 4 cloth and 20 particles from
 * one emitter, so that the seeds (fuzz/corpus/checkpoint, written by `casteljau animate
 * fuzz/checkpoint_doc.json --no-render --checkpoint-out ...`) match it. */
#define _POSIX_C_SOURCE 200809L /* fmemopen */
#include "casteljau/anim_json.h"
#include "casteljau/scene.h"

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* the same document as fuzz/checkpoint_doc.json */
static const char doc_text[] =
    "{\"scene\": \"checkpoint_scene.json\", \"fps\": 24, \"frames\": [0, 5],\n"
    " \"gravity\": [0, -9.81, 0],\n"
    " \"cloth\": {\"grid\": [4, 4], \"steps_per_frame\": 2, \"pinned\": [0, 3]},\n"
    " \"particles\": {\"capacity\": 20, \"seed\": 3, \"emitters\": [{\"position\": [0, 1, 0],\n"
    "   \"direction\": [0, 1, 0], \"rate\": 40, \"lifetime\": 0.5}]}}\n";

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    if (size == 0 || size > (1 << 20)) return 0;
    cj_anim_doc *doc = NULL;
    cj_scene *scene = NULL;
    if (cj_anim_doc_parse(doc_text, "checkpoint_doc.json", "", &doc) != CJ_OK) abort();
    if (cj_scene_create(NULL, &scene) != CJ_OK || cj_anim_doc_attach(doc, scene) != CJ_OK) abort();
    FILE *f = fmemopen((void *)data, size, "rb");
    if (f) {
        if (cj_anim_doc_load_state(doc, f) == CJ_OK)
            (void)cj_anim_doc_frame(doc, scene, doc->sim_frame + 1, NULL);
        fclose(f);
    }
    cj_scene_destroy(scene);
    cj_anim_doc_destroy(doc);
    return 0;
}
