/* Private to the casteljau command-line tool: shared argument parsing and error reporting. */
#ifndef CASTELJAU_APP_CLI_H
#define CASTELJAU_APP_CLI_H

#include <stddef.h>

/* Exit status for bad arguments or bad input (the documented contract of every command). */
#define CLI_EXIT_USAGE 2

/* Prints "casteljau <cmd>: <message>" on stderr and returns CLI_EXIT_USAGE. */
int cli_fail(const char *cmd, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;

/* Parses one number with strtod (decimal or C99 hex float); the whole string must be consumed
 * and the value finite. Returns 0 on success, -1 otherwise. */
int cli_parse_double(const char *s, double *out);

/* Parses "x0,y0;x1,y1;..." into a newly allocated array (point-major). All points must have the
 * same dimension. On success returns 0 and sets *pts, *count, *dim (the caller frees *pts). On
 * failure returns -1 and writes a one-line reason (naming the point and coordinate) to
 * why[why_size]. */
int cli_parse_points(const char *text, double **pts, size_t *count, int *dim, char *why,
                     size_t why_size);

/* Parses "a;b;c" (or "a,b,c") into a newly allocated list of doubles; same conventions. */
int cli_parse_list(const char *text, double **values, size_t *count, char *why, size_t why_size);

/* Prints a value with %.17g (round-trips every double). */
void cli_print_double(double v);

/* One entry per sub-command. */
int cmd_eval(int argc, char **argv);
int cmd_interp(int argc, char **argv);
int cmd_contour(int argc, char **argv);
int cmd_plot(int argc, char **argv);
int cmd_tessellate(int argc, char **argv);
int cmd_render(int argc, char **argv);
int cmd_trace(int argc, char **argv);

#endif
