/* casteljau: the stage report shared by the rasterizer, the ray tracer and the animation
 * (the library's third promise: simulate only the effects a scene calls for).
 *
 * A renderer or simulation assembles its pipeline from the features the scene uses. For EVERY
 * stage it knows, built or not, it records one entry: whether it ran, the scene feature that
 * decided it (a short phrase: "no lights", "material 2 has texture 0", "spp = 1"), what went
 * in and came out (triangles, pixels, rays...) and the wall time it took.
 *
 * The report is a plain value struct with fixed capacity: no allocation, so a renderer can
 * fill it from its hot paths' counters without cost. cj_stage_report_json() prints it.
 */
#ifndef CASTELJAU_STAGE_REPORT_H
#define CASTELJAU_STAGE_REPORT_H

#include "casteljau/status.h"
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#ifdef __cplusplus
extern "C" {
#endif

#define CJ_STAGE_MAX       48
#define CJ_STAGE_NAME_MAX  32
#define CJ_STAGE_WHY_MAX   96
#define CJ_STAGE_UNIT_MAX  16
#define CJ_STAGE_EXTRA_MAX 8

typedef struct cj_stage_value {
    char key[CJ_STAGE_NAME_MAX]; /* e.g. "bound_px", "triangles" */
    double value;
} cj_stage_value;

typedef struct cj_stage {
    char name[CJ_STAGE_NAME_MAX]; /* "tessellate", "shade_phong", "shadow_rays", ... */
    int ran;                      /* 1 built and run, 0 left out */
    char why[CJ_STAGE_WHY_MAX];   /* the feature that decided it */
    char unit_in[CJ_STAGE_UNIT_MAX], unit_out[CJ_STAGE_UNIT_MAX]; /* "triangles", "pixels" */
    uint64_t in, out;
    double seconds; /* wall time of the stage (summed over threads' wall time: see docs) */
    int extra_count;
    cj_stage_value extra[CJ_STAGE_EXTRA_MAX];
} cj_stage;

typedef struct cj_stage_report {
    char renderer[CJ_STAGE_NAME_MAX]; /* "raster", "trace", "animate" */
    int count;
    cj_stage stages[CJ_STAGE_MAX];
    double total_seconds;
} cj_stage_report;

/* Empties the report and names the renderer. */
void cj_stage_report_init(cj_stage_report *r, const char *renderer);

/* Adds (or, if a stage of that name exists, returns) the stage `name`; NULL when full. */
cj_stage *cj_stage_report_stage(cj_stage_report *r, const char *name);

/* Records a stage as run or left out with the reason (printf-style). Returns the stage or
 * NULL when the report is full. */
cj_stage *cj_stage_report_set(cj_stage_report *r, const char *name, int ran, const char *why_fmt,
                              ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 4, 5)))
#endif
    ;

/* Sets the figures of the stage `name` (added if new; its decision is left as recorded): the
 * work in and out with their units ("patches" in, "triangles" out) and the seconds it took.
 * Returns the stage, or NULL when the report is full. */
cj_stage *cj_stage_report_figures(cj_stage_report *r, const char *name, const char *unit_in,
                                  uint64_t in, const char *unit_out, uint64_t out, double seconds);

/* Adds an extra named figure to a stage (ignored beyond CJ_STAGE_EXTRA_MAX). */
void cj_stage_add_value(cj_stage *s, const char *key, double value);

/* The stage of that name, or NULL. */
const cj_stage *cj_stage_report_find(const cj_stage_report *r, const char *name);

/* Writes the report as one JSON object:
 *   {"renderer": "raster", "total_seconds": t,
 *    "stages": [{"name": ..., "ran": true, "why": ..., "in": n, "unit_in": ..., "out": n,
 *                "unit_out": ..., "seconds": t, "values": {"key": v, ...}}, ...]}
 * CJ_ERR_IO if writing fails. */
cj_status cj_stage_report_json(const cj_stage_report *r, FILE *f);

#ifdef __cplusplus
}
#endif
#endif
