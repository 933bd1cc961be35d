#define _POSIX_C_SOURCE 200809L /* readlink */
#include "cli.h"
#include "cli_progress.h"

#include "casteljau/patch.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* Escapes control characters (and DEL) so that echoed input cannot break a message's line. */
static void put_escaped(FILE *f, const char *s) {
    for (const unsigned char *c = (const unsigned char *)s; *c; ++c) {
        if (*c == '\n')
            fputs("\\n", f);
        else if (*c == '\t')
            fputs("\\t", f);
        else if (*c == '\r')
            fputs("\\r", f);
        else if (*c < 0x20 || *c == 0x7f)
            fprintf(f, "\\x%02x", *c);
        else
            fputc(*c, f);
    }
}

static void vreport(const char *cmd, const char *prefix, const char *fmt, va_list ap) {
    char msg[2048];
    vsnprintf(msg, sizeof msg, fmt, ap);
    fflush(stdout);
    fprintf(stderr, "casteljau %s: %s", cmd, prefix);
    put_escaped(stderr, msg);
    fputc('\n', stderr);
}

int cli_fail(const char *cmd, const char *fmt, ...) {
    va_list ap;
    va_start(ap, fmt);
    vreport(cmd, "", fmt, ap);
    va_end(ap);
    return CLI_EXIT_USAGE;
}

int cli_error(const char *cmd, const char *fmt, ...) {
    va_list ap;
    va_start(ap, fmt);
    vreport(cmd, "", fmt, ap);
    va_end(ap);
    return CLI_EXIT_FAILURE;
}

void cli_warn(const char *cmd, const char *fmt, ...) {
    va_list ap;
    va_start(ap, fmt);
    vreport(cmd, "warning: ", fmt, ap);
    va_end(ap);
}

const char *cli_quote(const char *s, char *out, size_t out_size) {
    size_t n = 0;
    for (const unsigned char *c = (const unsigned char *)s; *c; ++c) {
        char esc[8];
        if (*c == '\n')
            snprintf(esc, sizeof esc, "\\n");
        else if (*c == '\t')
            snprintf(esc, sizeof esc, "\\t");
        else if (*c < 0x20 || *c == 0x7f)
            snprintf(esc, sizeof esc, "\\x%02x", *c);
        else
            esc[0] = (char)*c, esc[1] = '\0';
        size_t k = strlen(esc);
        if (n + k + 4 > out_size) {
            if (out_size >= 4) {
                memcpy(out + (n < out_size - 4 ? n : out_size - 4), "...", 4);
                return out;
            }
            break;
        }
        memcpy(out + n, esc, k);
        n += k;
    }
    if (out_size) out[n < out_size ? n : out_size - 1] = '\0';
    return out;
}

#ifndef CJ_VERSION
#define CJ_VERSION "0.1.0"
#endif

/* The parser's state that the progress line reads (cli_progress.h): kept here, beside the parser
 * that sets it, so that cli_progress.c calls this file and not the other way round. */
int cli_quiet = 0;
double cli_started = 0.0;

const char *cli_version(void) {
    return "casteljau " CJ_VERSION;
}

void cli_parser_init(cli_parser *p, const char *cmd, const char *usage, int argc, char **argv,
                     const cli_opt *opts, size_t nopts) {
    cli_started = cj_clock_seconds();
    p->cmd = cmd;
    p->usage = usage;
    p->argc = argc;
    p->argv = argv;
    p->i = 1;
    p->only_positionals = 0;
    p->opts = opts;
    p->nopts = nopts;
}

/* "-0.5", "-1e3", "-.5", "-0x1p-3": a negative number, not an option. */
static int is_number(const char *s) {
    double v;
    return cli_parse_double(s, &v) == 0;
}

int cli_next(cli_parser *p, const char **value) {
    *value = NULL;
    if (p->i >= p->argc) return CLI_END;
    const char *a = p->argv[p->i++];
    if (p->only_positionals || a[0] != '-' || a[1] == '\0' || is_number(a)) {
        *value = a;
        return CLI_POSITIONAL;
    }
    if (!strcmp(a, "--")) {
        p->only_positionals = 1;
        return cli_next(p, value);
    }
    const char *eq = a[1] == '-' ? strchr(a, '=') : NULL;
    const size_t len = eq ? (size_t)(eq - a) : strlen(a);
    char q[160];
    /* -h is help only as the command's one argument: elsewhere it is a slip (for --height, in
     * "--width 640 -h 480") and must not print help and exit 0 without doing the work */
    if (!strcmp(a, "--help") || (!strcmp(a, "-h") && p->argc == 2)) {
        fputs(p->usage, stdout);
        int has_output = 0;
        for (size_t k = 0; k < p->nopts; ++k) has_output |= !strcmp(p->opts[k].name, "--output");
        printf("Every command also takes --help (or -h alone), --version, --quiet (no\n"
               "progress line and no summary on a terminal) and --list-options (its options, one\n"
               "per line)%s.\n",
               has_output ? "; -o is short for --output" : "");
        return CLI_EXIT_OK;
    }
    if (!strcmp(a, "-h")) {
        cli_fail(p->cmd,
                 "'-h' means help only on its own ('casteljau %s -h'); among other "
                 "arguments write --help%s",
                 p->cmd, cli_suggest("--height", 8, p->opts, p->nopts) ? " (or --height H)" : "");
        return CLI_BAD;
    }
    if (!strcmp(a, "--list-options")) { /* for shell completion and the usage test */
        for (size_t k = 0; k < p->nopts; ++k)
            printf("%s\n%s%s", p->opts[k].name, p->opts[k].alias ? p->opts[k].alias : "",
                   p->opts[k].alias ? "\n" : "");
        fputs("--help\n--quiet\n--version\n", stdout);
        return CLI_EXIT_OK;
    }
    if (!strcmp(a, "--quiet")) { /* every command: see cli_progress.h */
        cli_quiet = 1;
        return cli_next(p, value);
    }
    if (!strcmp(a, "--version")) {
        printf("%s\n", cli_version());
        return CLI_EXIT_OK;
    }
    for (size_t k = 0; k < p->nopts; ++k) {
        const cli_opt *o = &p->opts[k];
        const int match = (strlen(o->name) == len && !strncmp(a, o->name, len)) ||
                          (o->alias && !eq && !strcmp(a, o->alias));
        if (!match) continue;
        if (!o->has_value) {
            if (eq) {
                cli_fail(p->cmd, "option %s takes no value (got '%s')", o->name,
                         cli_quote(eq + 1, q, sizeof q));
                return CLI_BAD;
            }
            return (int)k;
        }
        if (eq) {
            *value = eq + 1;
            return (int)k;
        }
        if (p->i >= p->argc) {
            cli_fail(p->cmd, "option %s needs a value", a);
            return CLI_BAD;
        }
        *value = p->argv[p->i++];
        return (int)k;
    }
    char name[96];
    snprintf(name, sizeof name, "%.*s", (int)(len < 80 ? len : 80), a);
    const char *near = cli_suggest(a, len, p->opts, p->nopts);
    if (near)
        cli_fail(p->cmd, "unknown option '%s': did you mean '%s'? (see 'casteljau %s --help')",
                 cli_quote(name, q, sizeof q), near, p->cmd);
    else
        cli_fail(p->cmd, "unknown option '%s' (try 'casteljau %s --help')",
                 cli_quote(name, q, sizeof q), p->cmd);
    return CLI_BAD;
}

/* Edit distance (insertions, deletions, substitutions, swaps of neighbours) between a[0..na)
 * and b[0..nb), both at most 63 characters (longer: a large number). */
static size_t edit_distance(const char *a, size_t na, const char *b, size_t nb) {
    enum { MAXLEN = 64 };
    if (na >= MAXLEN || nb >= MAXLEN) return (size_t)-1 / 2;
    size_t d[MAXLEN][MAXLEN];
    for (size_t i = 0; i <= na; ++i) d[i][0] = i;
    for (size_t j = 0; j <= nb; ++j) d[0][j] = j;
    for (size_t i = 1; i <= na; ++i)
        for (size_t j = 1; j <= nb; ++j) {
            size_t best = d[i - 1][j - 1] + (a[i - 1] != b[j - 1]);
            if (d[i - 1][j] + 1 < best) best = d[i - 1][j] + 1;
            if (d[i][j - 1] + 1 < best) best = d[i][j - 1] + 1;
            if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1] &&
                d[i - 2][j - 2] + 1 < best)
                best = d[i - 2][j - 2] + 1;
            d[i][j] = best;
        }
    return d[na][nb];
}

/* Keeps `name` in *best when it is nearer to typed[0..len) than *best_d and near enough to be
 * a slip. `prefix` characters at the start of every name ("--") do not count as its length. */
static void consider(const char *typed, size_t len, const char *name, size_t prefix,
                     const char **best, size_t *best_d) {
    const size_t n = strlen(name);
    size_t dist = edit_distance(typed, len, name, n);
    /* a cut-short name ("--wid" for "--width", "rend" for "render") is as near as one slip */
    if (len >= prefix + 2 && len < n && !strncmp(typed, name, len) && dist > 1) dist = 1;
    /* near: at most 2 edits, and at most a third of the name after the prefix (so "--x"
     * suggests nothing) */
    if (n >= prefix && dist <= 2 && 3 * dist <= n - prefix && dist < *best_d)
        *best = name, *best_d = dist;
}

const char *cli_suggest(const char *typed, size_t len, const cli_opt *opts, size_t nopts) {
    static const char *const everywhere[] = {"--help", "--version", "--quiet"};
    const char *best = NULL;
    size_t best_d = (size_t)-1;
    for (size_t k = 0; k < nopts + 3; ++k)
        consider(typed, len, k < nopts ? opts[k].name : everywhere[k - nopts], 2, &best, &best_d);
    return best;
}

const char *cli_suggest_word(const char *typed, const char *const *names, size_t count) {
    const char *best = NULL;
    size_t best_d = (size_t)-1;
    for (size_t k = 0; k < count; ++k) consider(typed, strlen(typed), names[k], 0, &best, &best_d);
    return best;
}

int cli_next_arg(cli_parser *p, int *k, const char **value, int *status) {
    *k = cli_next(p, value);
    *status = *k == CLI_END ? -1 : *k == CLI_EXIT_OK ? 0 : CLI_EXIT_USAGE;
    return *k >= 0 || *k == CLI_POSITIONAL;
}

int cli_has_ext(const char *path, const char *ext) {
    size_t a = strlen(path), b = strlen(ext);
    if (a <= b) return 0;
    for (size_t i = 0; i < b; ++i) {
        char c = path[a - b + i];
        if (c >= 'A' && c <= 'Z') c = (char)(c - 'A' + 'a');
        if (c != ext[i]) return 0;
    }
    return 1;
}

int cli_parse_int(const char *s, long lo, long hi, long *out) {
    char *end = NULL;
    errno = 0;
    long v = strtol(s, &end, 10);
    if (end == s || *end != '\0' || errno == ERANGE || v < lo || v > hi) return -1;
    *out = v;
    return 0;
}

int cli_parse_double(const char *s, double *out) {
    while (*s == ' ' || *s == '\t') ++s;
    if (*s == '\0') return -1;
    char *end = NULL;
    errno = 0;
    double v = strtod(s, &end);
    while (*end == ' ' || *end == '\t') ++end;
    if (end == s || *end != '\0' || !isfinite(v)) return -1;
    *out = v;
    return 0;
}

/* Splits `text` on `sep` into a malloc'd copy with separators replaced by NUL; returns the
 * number of fields (an empty string has one empty field). */
static char *split_fields(const char *text, char sep, size_t *nfields) {
    size_t len = strlen(text);
    char *copy = malloc(len + 1);
    if (!copy) return NULL;
    memcpy(copy, text, len + 1);
    size_t n = 1;
    for (size_t i = 0; i < len; ++i)
        if (copy[i] == sep) {
            copy[i] = '\0';
            ++n;
        }
    *nfields = n;
    return copy;
}

int cli_parse_points(const char *text, double **pts, size_t *count, int *dim, char *why,
                     size_t why_size) {
    size_t npoints = 0;
    char *copy = split_fields(text, ';', &npoints);
    if (!copy) {
        snprintf(why, why_size, "out of memory");
        return -1;
    }
    /* A trailing ';' is tolerated: "1,2;3,4;" has two points. */
    size_t len = strlen(text);
    if (len > 0 && text[len - 1] == ';') --npoints;
    if (len == 0 || npoints == 0) {
        free(copy);
        snprintf(why, why_size, "no control points given");
        return -1;
    }
    double *out = NULL;
    int d = -1;
    const char *field = copy;
    for (size_t i = 0; i < npoints; ++i) {
        size_t ncoord = 0;
        char *coords = split_fields(field, ',', &ncoord);
        if (!coords) {
            snprintf(why, why_size, "out of memory");
            goto fail;
        }
        if (d < 0) {
            d = (int)ncoord;
            out = malloc(sizeof(double) * npoints * (size_t)d);
            if (!out) {
                free(coords);
                snprintf(why, why_size, "out of memory");
                goto fail;
            }
        } else if ((int)ncoord != d) {
            snprintf(why, why_size, "point %zu has %zu coordinates but point 0 has %d", i, ncoord,
                     d);
            free(coords);
            goto fail;
        }
        const char *c = coords;
        for (int k = 0; k < d; ++k) {
            if (cli_parse_double(c, &out[i * (size_t)d + (size_t)k]) != 0) {
                snprintf(why, why_size, "point %zu, coordinate %d: '%s' is not a finite number", i,
                         k, c);
                free(coords);
                goto fail;
            }
            c += strlen(c) + 1;
        }
        free(coords);
        field += strlen(field) + 1;
    }
    free(copy);
    *pts = out;
    *count = npoints;
    *dim = d;
    return 0;
fail:
    free(out);
    free(copy);
    return -1;
}

int cli_parse_list(const char *text, double **values, size_t *count, char *why, size_t why_size) {
    size_t n = 0;
    char sep = strchr(text, ';') ? ';' : ',';
    char *copy = split_fields(text, sep, &n);
    if (!copy) {
        snprintf(why, why_size, "out of memory");
        return -1;
    }
    double *out = malloc(sizeof(double) * n);
    if (!out) {
        free(copy);
        snprintf(why, why_size, "out of memory");
        return -1;
    }
    const char *f = copy;
    for (size_t i = 0; i < n; ++i) {
        if (cli_parse_double(f, &out[i]) != 0) {
            snprintf(why, why_size, "value %zu: '%s' is not a finite number", i, f);
            free(out);
            free(copy);
            return -1;
        }
        f += strlen(f) + 1;
    }
    free(copy);
    *values = out;
    *count = n;
    return 0;
}

void cli_print_double(double v) {
    printf("%.17g", v);
}

#ifndef CJ_TEAPOT_SOURCE
#define CJ_TEAPOT_SOURCE "data/teapot.bpt"
#endif
#ifndef CJ_TEAPOT_INSTALLED
#define CJ_TEAPOT_INSTALLED "/usr/local/share/casteljau/teapot.bpt"
#endif
#ifndef CJ_TEAPOT_FROM_BINDIR
#define CJ_TEAPOT_FROM_BINDIR "../share/casteljau/teapot.bpt"
#endif

const char *cli_teapot_path(void) {
    static char found[4096 + 64];
    char exe[4096];
    ssize_t n = readlink("/proc/self/exe", exe, sizeof exe - 1);
    if (n > 0) {
        exe[n] = '\0';
        char *slash = strrchr(exe, '/');
        if (slash) {
            slash[1] = '\0';
            snprintf(found, sizeof found, "%s%s", exe, CJ_TEAPOT_FROM_BINDIR);
            if (access(found, R_OK) == 0) return found;
        }
    }
    return access(CJ_TEAPOT_SOURCE, R_OK) == 0 ? CJ_TEAPOT_SOURCE : CJ_TEAPOT_INSTALLED;
}

int cli_parse_degree(const char *text, int *m, int *n) {
    const char *comma = strchr(text, ',');
    char tmp[64];
    long a, b;
    if (!comma || (size_t)(comma - text) >= sizeof tmp) return -1;
    memcpy(tmp, text, (size_t)(comma - text));
    tmp[comma - text] = '\0';
    if (cli_parse_int(tmp, 0, CJ_PATCH_MAX_DEGREE, &a) ||
        cli_parse_int(comma + 1, 0, CJ_PATCH_MAX_DEGREE, &b))
        return -1;
    *m = (int)a;
    *n = (int)b;
    return 0;
}
