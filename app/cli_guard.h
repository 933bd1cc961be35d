/* Private to the casteljau tool: the checks every command makes before any work, so that an
 * output never destroys an input and a bad destination is found before minutes of rendering. */
#ifndef CASTELJAU_APP_CLI_GUARD_H
#define CASTELJAU_APP_CLI_GUARD_H

#include "casteljau/status.h"

#include <stddef.h>

/* The exit status a library failure earns: 1 (CLI_EXIT_FAILURE) for CJ_ERR_NOMEM, which is no
 * fault of the input, else 2 (CLI_EXIT_USAGE). */
int cli_exit_status(cj_status st);

/* cli_fail or cli_error, as cli_exit_status chooses for st. */
int cli_fail_status(const char *cmd, cj_status st, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

/* Refuses an output that is the same file (device and inode) as any file this process has read
 * as input (file_internal.h keeps the log: scene, animation document, checkpoint, textures,
 * .bpt and OBJ files): one line naming both, exit 2. `what` names the output ("-o"). 0 if the
 * output is new or another file. */
int cli_guard_output(const char *cmd, const char *what, const char *out);

/* The same for every name a frame pattern (one %d) produces over frames fa..fb: each input whose
 * name fits the pattern is decoded to its frame number, and short ranges (<= 10000 frames) are
 * checked name by name as well (hard links). */
int cli_guard_pattern(const char *cmd, const char *what, const char *pattern, long fa, long fb);

/* Checks that an output can be created: not a folder, and its folder exists and accepts a new
 * file. One line and exit 2 otherwise. */
int cli_check_output(const char *cmd, const char *what, const char *path);

/* pattern with its one %d replaced by frame, into out[size]. */
void cli_frame_name(const char *pattern, long frame, char *out, size_t size);

#endif
