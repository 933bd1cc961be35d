/* Shared by the two source files of test_raster_lines. */
#ifndef CJ_TEST_RASTER_LINES_H
#define CJ_TEST_RASTER_LINES_H

#include <stdint.h>

/* The run's seed (CJ_SEED replays). */
extern uint64_t g_seed;

/* raster_strokes.c */
void test_wu(void **state);
void test_stroke_area(void **state);
void test_stroke_pixels_supersampled(void **state);
void test_stroke_clip_and_errors(void **state);
void test_stroke_curves(void **state);
void test_fills(void **state);
void test_stroke_fb_matches_visit(void **state);

#endif
