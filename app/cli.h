/* Private to the casteljau command-line tool: shared argument parsing and error reporting. */
#ifndef CASTELJAU_APP_CLI_H
#define CASTELJAU_APP_CLI_H

#include <stddef.h>

/* Exit status for bad arguments or bad input (the documented contract of every command). */
#define CLI_EXIT_USAGE 2

/* Exit status when the input was fine but the run failed (no memory, a write that failed). */
#define CLI_EXIT_FAILURE 1

#if defined(__GNUC__)
#define CLI_PRINTF(a, b) __attribute__((format(printf, a, b)))
#else
#define CLI_PRINTF(a, b)
#endif

/* Prints "casteljau <cmd>: <message>" on stderr as ONE line and returns CLI_EXIT_USAGE. Control
 * characters in the formatted message (from input echoed into it) are escaped as \n, \t, \r or
 * \xNN, so that a message is always a single line. */
int cli_fail(const char *cmd, const char *fmt, ...) CLI_PRINTF(2, 3);

/* The same, returning CLI_EXIT_FAILURE (for failures that are not the user's input). */
int cli_error(const char *cmd, const char *fmt, ...) CLI_PRINTF(2, 3);

/* The same, prefixed "warning: ", returning nothing. */
void cli_warn(const char *cmd, const char *fmt, ...) CLI_PRINTF(2, 3);

/* Copies `s` into out[out_size] with control characters escaped (as cli_fail does) and cut
 * to fit (marked "..."): for echoing user input into a message. Returns out. */
const char *cli_quote(const char *s, char *out, size_t out_size);

/* ---- option parsing shared by the commands ----
 * Options may come in any order and between positional arguments; "--opt value" and
 * "--opt=value" are the same; "--" ends the options (everything after it is positional); an
 * argument that reads as a number ("-0.5", "-1e3") is positional, so negative parameters
 * need no "--". "--help" (anywhere) or "-h" (only as the one argument: elsewhere it is an
 * error, never a silent exit) prints the command's usage and "--version" the version (the
 * command then exits 0). "--quiet" sets cli_quiet (cli_progress.h: no progress line, no
 * summary) and is otherwise skipped; "--list-options" prints every option the command takes,
 * one per line (for shell completion), and exits 0. An option not in the table is reported as
 * unknown, by name, with the nearest known option when one is near (cli_suggest). */
typedef struct cli_opt {
    const char *name;  /* "--points" */
    const char *alias; /* "-o", or NULL */
    int has_value;
} cli_opt;

typedef struct cli_parser {
    const char *cmd, *usage;
    int argc, i, only_positionals;
    char **argv;
    const cli_opt *opts;
    size_t nopts;
} cli_parser;

enum {
    CLI_POSITIONAL = -1, /* *value is the argument */
    CLI_END = -2,        /* no more arguments */
    CLI_EXIT_OK = -3,    /* --help or --version was printed: return 0 */
    CLI_BAD = -4         /* a message was printed: return CLI_EXIT_USAGE */
};

void cli_parser_init(cli_parser *p, const char *cmd, const char *usage, int argc, char **argv,
                     const cli_opt *opts, size_t nopts);

/* The next argument: the index in opts of an option (its value in *value when it takes one,
 * else *value = NULL), or one of the CLI_* codes above. */
int cli_next(cli_parser *p, const char **value);

/* The option of the table (or --help, --version, --quiet) nearest to typed[0..len) when it is
 * near enough to be a slip (at most 2 edits or a cut-short name, e.g. "--sp" -> "--spp"), else
 * NULL. Used by cli_next for its "did you mean" message. */
const char *cli_suggest(const char *typed, size_t len, const cli_opt *opts, size_t nopts);

/* The same rule for a word among names[0..count) (no "--" prefix): "rendr" -> "render". */
const char *cli_suggest_word(const char *typed, const char *const *names, size_t count);

/* cli_next for the loop of a command, the control codes handled: returns 1 while there is an
 * argument, with *k its index in opts or CLI_POSITIONAL and *value as cli_next; returns 0 when
 * the loop must end, with *status -1 when every argument was read (go on), else the exit status
 * to return now (0 after --help or --version, CLI_EXIT_USAGE after a message). Use:
 *     while (cli_next_arg(&ps, &k, &v, &status)) { ... }
 *     if (status >= 0) return status; */
int cli_next_arg(cli_parser *p, int *k, const char **value, int *status);

/* The Utah teapot of this installation: beside the executable (<bindir>/../share/casteljau, so
 * a moved prefix still works), then the source tree of a build, then the configured prefix. */
const char *cli_teapot_path(void);

/* The version line "casteljau X.Y.Z". */
const char *cli_version(void);
/* Where `make install` puts the documentation and the shipped scenes (app/CMakeLists.txt sets
   both to the configured prefix's folders); help texts name these, not source paths. */
#ifndef CJ_DOC_DIR
#define CJ_DOC_DIR "/usr/local/share/doc/casteljau"
#endif
#ifndef CJ_DATA_DIR
#define CJ_DATA_DIR "/usr/local/share/casteljau"
#endif

/* Parses a whole number in [lo, hi] (decimal); 0 on success, -1 otherwise. */
int cli_parse_int(const char *s, long lo, long hi, long *out);
/* --degree M,N of a patch: two integers in [0, CJ_PATCH_MAX_DEGREE] separated by a comma;
 * 0 or -1 when malformed or out of range. */
int cli_parse_degree(const char *text, int *m, int *n);

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

/* 1 when path ends in ext (given in lower case, with its dot: ".png") and has a name before
 * it, ignoring the case of path's letters; else 0. */
int cli_has_ext(const char *path, const char *ext);

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
int cmd_animate(int argc, char **argv);
int cmd_view(int argc, char **argv);
int cmd_report(int argc, char **argv);
int cmd_fit(int argc, char **argv);
int cmd_intersect(int argc, char **argv);
int cmd_nearest(int argc, char **argv);
int cmd_offset(int argc, char **argv);
int cmd_reduce(int argc, char **argv);
int cmd_section(int argc, char **argv);
/* nearest with a patch model (--teapot, --bpt, --patch): cmd_nearest hands over. */
int cmd_nearest_patch(int argc, char **argv);

#endif
