/* A private Xvfb X server for the VTK rendering test and bench: VTK 9.1 draws through GLX and
 * needs a display even offscreen, and CI has none. Always a fresh server (never the caller's
 * DISPLAY), so the pictures come from Mesa's llvmpipe wherever the test runs. */
#ifndef CJ_TEST_XVFB_H
#define CJ_TEST_XVFB_H

#include <sys/types.h>

/* Starts `Xvfb -displayfd` (it picks a free display number itself: no races between parallel
 * tests) with one width × height × 24 screen, waits until it accepts connections, and sets
 * DISPLAY to it (and LIBGL_ALWAYS_SOFTWARE=1). -noreset: without it the server resets whenever
 * its last client disconnects and refuses connections meanwhile, so a second render window
 * opened right after the first one closed could find no server. The server dies with this process
 * (PR_SET_PDEATHSIG) if cj_test_xvfb_stop is never called. Returns the server's pid, or -1
 * (with a message on stderr) if Xvfb could not be started. */
pid_t cj_test_xvfb_start(int width, int height);

/* Terminates the server started above and reaps it. */
void cj_test_xvfb_stop(pid_t pid);

#endif
