/* The stage report: fixed-capacity records of what a renderer built, and why. */
#include "casteljau/stage_report.h"

#include "error_internal.h"

#include <stdarg.h>
#include <string.h>

void cj_stage_report_init(cj_stage_report *r, const char *renderer) {
    memset(r, 0, sizeof *r);
    snprintf(r->renderer, sizeof r->renderer, "%s", renderer ? renderer : "");
}

cj_stage *cj_stage_report_stage(cj_stage_report *r, const char *name) {
    for (int i = 0; i < r->count; ++i)
        if (!strcmp(r->stages[i].name, name)) return &r->stages[i];
    if (r->count >= CJ_STAGE_MAX) return NULL;
    cj_stage *s = &r->stages[r->count++];
    memset(s, 0, sizeof *s);
    snprintf(s->name, sizeof s->name, "%s", name);
    return s;
}

cj_stage *cj_stage_report_set(cj_stage_report *r, const char *name, int ran, const char *why_fmt,
                              ...) {
    cj_stage *s = cj_stage_report_stage(r, name);
    if (!s) return NULL;
    s->ran = ran != 0;
    va_list ap;
    va_start(ap, why_fmt);
    vsnprintf(s->why, sizeof s->why, why_fmt, ap);
    va_end(ap);
    return s;
}

void cj_stage_add_value(cj_stage *s, const char *key, double value) {
    if (!s) return;
    for (int i = 0; i < s->extra_count; ++i)
        if (!strcmp(s->extra[i].key, key)) {
            s->extra[i].value = value;
            return;
        }
    if (s->extra_count >= CJ_STAGE_EXTRA_MAX) return;
    cj_stage_value *v = &s->extra[s->extra_count++];
    snprintf(v->key, sizeof v->key, "%s", key);
    v->value = value;
}

const cj_stage *cj_stage_report_find(const cj_stage_report *r, const char *name) {
    for (int i = 0; i < r->count; ++i)
        if (!strcmp(r->stages[i].name, name)) return &r->stages[i];
    return NULL;
}

/* Writes s as a JSON string (the texts here are our own, but quotes and control characters are
 * escaped all the same so the output always parses). */
static void put_string(FILE *f, const char *s) {
    fputc('"', f);
    for (; *s; ++s) {
        unsigned char c = (unsigned char)*s;
        if (c == '"' || c == '\\')
            fprintf(f, "\\%c", c);
        else if (c < 0x20)
            fprintf(f, "\\u%04x", c);
        else
            fputc(c, f);
    }
    fputc('"', f);
}

/* JSON has no NaN or infinity: such a figure is written as null. */
static void put_number(FILE *f, double v) {
    if (v != v || v > 1.79e308 || v < -1.79e308)
        fputs("null", f);
    else
        fprintf(f, "%.17g", v);
}

cj_status cj_stage_report_json(const cj_stage_report *r, FILE *f) {
    fputs("{\"renderer\": ", f);
    put_string(f, r->renderer);
    fputs(", \"total_seconds\": ", f);
    put_number(f, r->total_seconds);
    fputs(", \"stages\": [", f);
    for (int i = 0; i < r->count; ++i) {
        const cj_stage *s = &r->stages[i];
        fputs(i ? ",\n  {\"name\": " : "\n  {\"name\": ", f);
        put_string(f, s->name);
        fprintf(f, ", \"ran\": %s, \"why\": ", s->ran ? "true" : "false");
        put_string(f, s->why);
        fprintf(f, ", \"in\": %llu, \"unit_in\": ", (unsigned long long)s->in);
        put_string(f, s->unit_in);
        fprintf(f, ", \"out\": %llu, \"unit_out\": ", (unsigned long long)s->out);
        put_string(f, s->unit_out);
        fputs(", \"seconds\": ", f);
        put_number(f, s->seconds);
        fputs(", \"values\": {", f);
        for (int k = 0; k < s->extra_count; ++k) {
            if (k) fputs(", ", f);
            put_string(f, s->extra[k].key);
            fputs(": ", f);
            put_number(f, s->extra[k].value);
        }
        fputs("}}", f);
    }
    fputs("]}\n", f);
    return ferror(f) ? cj_fail(CJ_ERR_IO, "writing the stage report failed") : CJ_OK;
}
