#define _POSIX_C_SOURCE 200809L
#include "timeline.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

enum { TIMELINE_MAX = 1 << 22 };

void cj_test_sleep(double s) {
    struct timespec ts = {(time_t)s, (long)((s - (double)(time_t)s) * 1e9)};
    nanosleep(&ts, NULL);
}

char *cj_timeline_read(const char *path) {
    FILE *f = fopen(path, "r");
    char *buf = malloc(f ? TIMELINE_MAX : 1);
    if (!buf) abort();
    buf[0] = '\0';
    if (!f) return buf;
    const size_t n = fread(buf, 1, TIMELINE_MAX - 1, f);
    buf[n] = '\0';
    fclose(f);
    return buf;
}

long cj_timeline_size(const char *path) {
    char *tl = cj_timeline_read(path);
    const long n = (long)strlen(tl);
    free(tl);
    return n;
}

long cj_timeline_wait_line(const char *path, long from, const char *what, double timeout) {
    for (double t = 0; t < timeout; t += 0.05) {
        char *tl = cj_timeline_read(path);
        const long len = (long)strlen(tl);
        const char *hit = from <= len ? strstr(tl + from, what) : NULL;
        long at = -1;
        if (hit) {
            while (hit > tl && hit[-1] != '\n') --hit;
            at = (long)(hit - tl);
        }
        free(tl);
        if (at >= 0) return at;
        cj_test_sleep(0.05);
    }
    return -1;
}
