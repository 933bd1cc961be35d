/* The peers of bench_query_occt, in the same process as ours: OpenCASCADE's offsets
 * (bench_query_offset_peer.cpp) and kurbo 0.7's queries (bench/kurbo/lib.rs, a Rust static
 * library built offline from Debian's librust-kurbo-dev; CJ_HAVE_KURBO when linked). */
#ifndef CJ_BENCH_QUERY_PEERS_H
#define CJ_BENCH_QUERY_PEERS_H

#include <stddef.h>

/* Offsets of ncurves cubics by d at tol: ours (cj_offset_curve) and OpenCASCADE's
 * (Geom2d_OffsetCurve approximated by Geom2dConvert_ApproxCurve: 1 with C1 cubic spans, 2 with
 * C2 spans up to degree 14; only_setting 0 runs both), timed and checked by the same dense
 * comparison with the exact offset; prints the rows. */
void cj_bench_offsets_vs_occt(const double (*curves)[8], int ncurves, double d, double tol,
                              int only_setting);

#ifdef CJ_HAVE_KURBO
extern "C" {
/* kurbo's CubicBez::nearest on the cubic p (8 doubles) from (qx, qy): the distance, *t set. */
double cj_bench_kurbo_nearest(const double *p, double qx, double qy, double accuracy, double *t);
/* kurbo's PathSeg::intersect_line of the cubic p with the segment (x0,y0)-(x1,y1): up to 3
 * cubic parameters written to ts, their count returned. */
size_t cj_bench_kurbo_intersect_line(const double *p, double x0, double y0, double x1, double y1,
                                     double *ts);
}
#endif

#endif
