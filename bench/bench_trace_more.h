/* bench_trace's accuracy sections (bench_trace_more.c): patch tolerance against time and
 * pixels, RMSE against spp on a shipped scene, POV-Ray side by side. */
#ifndef BENCH_TRACE_MORE_H
#define BENCH_TRACE_MORE_H
#include "casteljau/mesh.h"

void bench_trace_tolerance(const char *teapot_bpt, const cj_mesh *fine, double fine_tol);
void bench_trace_rmse_shipped(const char *scene_json, const char *teapot_bpt);
void bench_trace_povray(void);
#endif
