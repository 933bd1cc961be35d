/* Private to the casteljau tool: how long work shows itself. On a terminal (stderr a tty) a
 * command that works for a while keeps one status line on stderr up to date (percent done,
 * elapsed, an estimate of what is left) and ends with a one-line summary (what was written,
 * its size, the time). Nothing of this is printed when stderr is not a terminal (scripts and
 * logs see only errors and warnings) or after --quiet. Ctrl-C during a progress run asks the
 * work to stop cleanly (the callback returns nonzero, the library cancels, no file is
 * written). */
#ifndef CASTELJAU_APP_CLI_PROGRESS_H
#define CASTELJAU_APP_CLI_PROGRESS_H

#include "clock_internal.h"

#include <stdint.h>

/* Set by --quiet (the shared parser, app/cli_common.c): no progress, no summary, no
 * "large work" notice. Errors and other warnings still print. */
extern int cli_quiet;

/* When the command started (set by cli_parser_init), on the library's one monotonic clock
 * (cj_clock_seconds, clock_internal.h). Both live beside the parser (cli_common.c), which sets
 * them. */
extern double cli_started;

typedef struct cli_progress {
    const char *cmd;  /* "render" */
    const char *unit; /* "tiles", "sections" */
    int shown;        /* 1: the status line is on a terminal and not --quiet */
    int drawn;        /* a status line is on screen (to be cleared) */
    double t0, last;  /* start and last redraw (cj_clock_seconds) */
    double t_first;   /* the first step: the rate (and so the time left) is measured from it,
                         since the set-up before it (buffers, tessellation) is not a step */
    uint64_t first_done;
    int has_first;
} cli_progress;

/* Starts the clock, decides whether the status line shows (isatty(2) && !cli_quiet) and
 * catches SIGINT (Ctrl-C) until cli_progress_end so that the work can stop cleanly (unless
 * SIGINT was ignored, as in a background job of a script: it stays ignored). */
void cli_progress_begin(cli_progress *p, const char *cmd, const char *unit);

/* A cj_render_progress_fn (user = the cli_progress): redraws the line at the first and last
 * step and at most ten times a second between; `label` (may be NULL) names the current step.
 * Returns 1 once Ctrl-C was pressed (the caller stops), else 0. */
int cli_progress_step(void *user, uint64_t done, uint64_t total);
int cli_progress_label(cli_progress *p, uint64_t done, uint64_t total, const char *label);

/* Shows `text` as the status line (e.g. what is done before the first step). */
void cli_progress_note(cli_progress *p, const char *text);

/* 1 once Ctrl-C was pressed since cli_progress_begin. */
int cli_progress_interrupted(void);

/* Clears the status line and restores the previous SIGINT handling. */
void cli_progress_end(cli_progress *p);

/* The summary, on a terminal and not --quiet: "casteljau CMD: wrote WHAT (SIZE) in T s", where
 * SIZE is the size of the file `path` (omitted when path is NULL or cannot be read) and
 * `detail` (may be NULL) is added before it, e.g. "640 x 480"; T is the time since t0, or
 * since the command started (cli_started) when t0 < 0. */
void cli_summary(const char *cmd, const char *what, const char *path, const char *detail,
                 double t0);

/* Before very large work (e.g. render --width 20000 --height 20000): unless --quiet, prints one
 * warning line on stderr saying how large and how to stop (Ctrl-C). */
void cli_warn_large(const char *cmd, const char *what);

#endif
