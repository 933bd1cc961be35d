/* The viewer's --timeline file as the X input tests read it (test_viewer_live, test_viewer_drag):
 * one event per line, appended by the viewer while the test drives it with real input. */
#ifndef CJ_TEST_TIMELINE_H
#define CJ_TEST_TIMELINE_H

/* Sleeps s seconds (fractions included). */
void cj_test_sleep(double s);

/* The whole timeline so far, NUL-terminated, at most 4 MiB (an empty string while the file does
 * not exist yet); the caller frees it. Aborts when out of memory. */
char *cj_timeline_read(const char *path);

/* Length in bytes of the timeline so far. */
long cj_timeline_size(const char *path);

/* Waits up to `timeout` seconds for a line containing `what` that starts at or after byte `from`
 * (polling every 50 ms); returns the offset of that line's start, or -1. */
long cj_timeline_wait_line(const char *path, long from, const char *what, double timeout);

#endif
