/* libFuzzer target: the plot JSON parser (formats/src/plot_json.c), which also contours the
 * implicit items and builds every plot: a document is parsed, rendered into a small framebuffer (no
 * font: the layout and drawing code without text) and freed. */
#include "plot_json.h"

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
    cj_plot_doc doc;
    if (cj_plot_json_parse("fuzz", text, &doc) == CJ_OK) {
        cj_framebuffer *fb = NULL;
        /* a small image whatever the document asks for: layout and drawing, not pixels */
        if (cj_framebuffer_create(96, 80, 0, NULL, &fb) == CJ_OK) {
            doc.width = 96;
            doc.height = 80;
            (void)cj_plot_doc_render(&doc, fb, NULL);
            cj_framebuffer_destroy(fb);
        }
        cj_plot_doc_free(&doc);
    }
    free(text);
    return 0;
}
