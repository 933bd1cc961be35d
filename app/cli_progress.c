#define _POSIX_C_SOURCE 200809L /* sigaction */
#include "cli_progress.h"

#include "cli.h"

#include <signal.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

static volatile sig_atomic_t interrupted = 0;
static struct sigaction previous_sigint;
static int sigint_caught = 0;

static void on_sigint(int sig) {
    (void)sig;
    interrupted = 1;
}

void cli_progress_begin(cli_progress *p, const char *cmd, const char *unit) {
    memset(p, 0, sizeof *p);
    p->cmd = cmd;
    p->unit = unit;
    p->shown = !cli_quiet && isatty(2);
    p->t0 = p->last = cj_clock_seconds();
    interrupted = 0;
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_sigint;
    sigemptyset(&sa.sa_mask);
    /* a second Ctrl-C kills at once, as usual, when the work does not stop soon enough */
    sa.sa_flags = SA_RESETHAND;
    sigint_caught = sigaction(SIGINT, NULL, &previous_sigint) == 0 &&
                    previous_sigint.sa_handler != SIG_IGN && sigaction(SIGINT, &sa, NULL) == 0;
}

int cli_progress_interrupted(void) {
    return interrupted != 0;
}

/* "12 s", "4 min 05 s", "2 h 07 min": short enough for one line. */
static void put_duration(char *buf, size_t n, double s) {
    if (s < 0) s = 0;
    if (s < 60)
        snprintf(buf, n, "%.*f s", s < 10 ? 1 : 0, s);
    else if (s < 3600)
        snprintf(buf, n, "%d min %02d s", (int)(s / 60), (int)s % 60);
    else
        snprintf(buf, n, "%d h %02d min", (int)(s / 3600), ((int)s / 60) % 60);
}

int cli_progress_label(cli_progress *p, uint64_t done, uint64_t total, const char *label) {
    if (p->shown && total) {
        const double now = cj_clock_seconds();
        if (done <= 1 || done >= total || now - p->last >= 0.1) {
            p->last = now;
            const double elapsed = now - p->t0;
            char el[32], left[48] = "";
            put_duration(el, sizeof el, elapsed);
            if (!p->has_first) {
                p->has_first = 1;
                p->t_first = now;
                p->first_done = done;
            } else if (done > p->first_done && done < total) {
                const double per_step = (now - p->t_first) / (double)(done - p->first_done);
                char d[32];
                put_duration(d, sizeof d, per_step * (double)(total - done));
                snprintf(left, sizeof left, ", about %s left", d);
            }
            fprintf(stderr, "\rcasteljau %s: %3d%% (%llu of %llu %s%s%s), %s elapsed%s\033[K",
                    p->cmd, (int)(100.0 * (double)done / (double)total), (unsigned long long)done,
                    (unsigned long long)total, p->unit, label ? ": " : "", label ? label : "", el,
                    left);
            fflush(stderr);
            p->drawn = 1;
        }
    }
    return interrupted != 0;
}

void cli_progress_note(cli_progress *p, const char *text) {
    if (!p->shown) return;
    fprintf(stderr, "\rcasteljau %s: %s\033[K", p->cmd, text);
    fflush(stderr);
    p->drawn = 1;
}

int cli_progress_step(void *user, uint64_t done, uint64_t total) {
    return cli_progress_label((cli_progress *)user, done, total, NULL);
}

void cli_progress_end(cli_progress *p) {
    if (p->drawn) {
        fputs("\r\033[K", stderr);
        fflush(stderr);
        p->drawn = 0;
    }
    if (sigint_caught) sigaction(SIGINT, &previous_sigint, NULL);
    sigint_caught = 0;
}

static void put_size(char *buf, size_t n, double bytes) {
    if (bytes < 1024)
        snprintf(buf, n, "%.0f bytes", bytes);
    else if (bytes < 1024.0 * 1024)
        snprintf(buf, n, "%.1f KiB", bytes / 1024);
    else if (bytes < 1024.0 * 1024 * 1024)
        snprintf(buf, n, "%.1f MiB", bytes / (1024.0 * 1024));
    else
        snprintf(buf, n, "%.2f GiB", bytes / (1024.0 * 1024 * 1024));
}

void cli_summary(const char *cmd, const char *what, const char *path, const char *detail,
                 double t0) {
    if (cli_quiet || !isatty(2)) return;
    char size[32] = "", el[32];
    struct stat st;
    if (path && stat(path, &st) == 0) put_size(size, sizeof size, (double)st.st_size);
    put_duration(el, sizeof el, cj_clock_seconds() - (t0 < 0 ? cli_started : t0));
    const int paren = (detail && detail[0]) || size[0];
    fflush(stdout);
    fprintf(stderr, "casteljau %s: wrote %s%s%s%s%s%s in %s\n", cmd, what, paren ? " (" : "",
            detail ? detail : "", detail && detail[0] && size[0] ? ", " : "", size,
            paren ? ")" : "", el);
}

void cli_warn_large(const char *cmd, const char *what) {
    if (cli_quiet) return;
    cli_warn(cmd,
             "%s: this is very large work and may take long; Ctrl-C stops it (no file is "
             "written)",
             what);
}
