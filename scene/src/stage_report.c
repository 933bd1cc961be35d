/* The stage report: fixed-capacity records of what a renderer built, and why. */
#include "casteljau/stage_report.h"

#include "error_internal.h"
#include "json_write_internal.h"

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

cj_stage *cj_stage_report_figures(cj_stage_report *r, const char *name, const char *unit_in,
                                  uint64_t in, const char *unit_out, uint64_t out, double seconds) {
    cj_stage *s = cj_stage_report_stage(r, name);
    if (!s) return NULL;
    snprintf(s->unit_in, sizeof s->unit_in, "%s", unit_in);
    snprintf(s->unit_out, sizeof s->unit_out, "%s", unit_out);
    s->in = in;
    s->out = out;
    s->seconds = seconds;
    return s;
}

const cj_stage *cj_stage_report_find(const cj_stage_report *r, const char *name) {
    for (int i = 0; i < r->count; ++i)
        if (!strcmp(r->stages[i].name, name)) return &r->stages[i];
    return NULL;
}

/* Built as a cJSON tree and printed by cJSON (json_write_internal.h): strings escaped by the
 * printer, numbers in their shortest exact form, NaN and infinity as null. */
static int add_stage(cJSON *stages, const cj_stage *s) {
    cJSON *o = cJSON_CreateObject(), *values = cJSON_CreateObject();
    if (!o || !values || !cJSON_AddItemToArray(stages, o)) {
        cJSON_Delete(o);
        cJSON_Delete(values);
        return -1;
    }
    int bad =
        !cJSON_AddStringToObject(o, "name", s->name) || !cJSON_AddBoolToObject(o, "ran", s->ran) ||
        !cJSON_AddStringToObject(o, "why", s->why) || cj_json_add_number(o, "in", (double)s->in) ||
        !cJSON_AddStringToObject(o, "unit_in", s->unit_in) ||
        cj_json_add_number(o, "out", (double)s->out) ||
        !cJSON_AddStringToObject(o, "unit_out", s->unit_out) ||
        cj_json_add_number(o, "seconds", s->seconds);
    if (!cJSON_AddItemToObject(o, "values", values)) {
        cJSON_Delete(values);
        return -1;
    }
    for (int k = 0; !bad && k < s->extra_count; ++k)
        bad = cj_json_add_number(values, s->extra[k].key, s->extra[k].value);
    return bad ? -1 : 0;
}

cj_status cj_stage_report_json(const cj_stage_report *r, FILE *f) {
    cJSON *root = cJSON_CreateObject(), *stages = cJSON_CreateArray();
    int bad = !root || !stages || !cJSON_AddStringToObject(root, "renderer", r->renderer) ||
              cj_json_add_number(root, "total_seconds", r->total_seconds);
    if (!bad && !cJSON_AddItemToObject(root, "stages", stages))
        bad = 1;
    else if (!bad)
        stages = NULL; /* owned by root now */
    for (int i = 0; !bad && i < r->count; ++i)
        bad = add_stage(cJSON_GetObjectItem(root, "stages"), &r->stages[i]);
    cj_status st = bad ? cj_fail(CJ_ERR_NOMEM, "stage report: out of memory")
                       : cj_json_print(root, 0, f, "stage report");
    cJSON_Delete(stages);
    cJSON_Delete(root);
    return st;
}
