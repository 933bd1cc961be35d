/* The default thread count honours CPU affinity and the cgroup quota (raster/src/cpu_count.c):
 * the quota parser on cgroup v2 cpu.max lines, the count within [1, online CPUs], and after
 * sched_setaffinity to one CPU the count (and the pool's default plan) is 1. */
#define _GNU_SOURCE /* sched_setaffinity, CPU_SET */
#include "render_pool.h"

#include "check.h"

#include <sched.h>
#include <stdio.h>
#include <unistd.h>

int main(void) {
    static const struct {
        const char *text;
        int want;
    } lines[] = {{"max 100000\n", 0},     {"200000 100000\n", 2}, {"150000 100000\n", 2},
                 {"50000 100000\n", 1},   {"100000 100000", 1},   {"", 0},
                 {"garbage\n", 0},        {"100000 0\n", 0},      {"-5 100000\n", 0},
                 {"6400000 100000\n", 64}};
    for (size_t i = 0; i < sizeof lines / sizeof lines[0]; ++i) {
        const int got = cj_cpu_quota_parse(lines[i].text);
        CHECK(got == lines[i].want, "cpu.max '%s': %d, want %d", lines[i].text, got, lines[i].want);
    }
    printf("cpu.max parsing: %zu lines (max, whole and fractional quotas rounded up, garbage)\n",
           sizeof lines / sizeof lines[0]);

    const long online = sysconf(_SC_NPROCESSORS_ONLN);
    const int n = cj_cpu_count();
    CHECK(n >= 1 && n <= online, "cj_cpu_count %d outside [1, %ld]", n, online);
    printf("cj_cpu_count: %d of %ld online CPUs\n", n, online);

    cpu_set_t set;
    CPU_ZERO(&set);
    if (sched_getaffinity(0, sizeof set, &set) != 0) {
        fprintf(stderr, "sched_getaffinity failed\n");
        return 1;
    }
    int first = 0;
    while (first < CPU_SETSIZE && !CPU_ISSET(first, &set)) ++first;
    cpu_set_t one;
    CPU_ZERO(&one);
    CPU_SET(first, &one);
    CHECK(sched_setaffinity(0, sizeof one, &one) == 0, "sched_setaffinity to CPU %d", first);
    CHECK(cj_cpu_count() == 1, "pinned to one CPU: cj_cpu_count %d", cj_cpu_count());
    CHECK(cj_rpool_plan(0, 1000) == 1, "pinned: the default plan uses %d workers",
          cj_rpool_plan(0, 1000));
    CHECK(cj_rpool_plan(3, 1000) == 3, "an explicit thread count is kept");
    printf("pinned to CPU %d: cj_cpu_count 1, the default pool plan 1 worker (explicit 3 kept)\n",
           first);
    return cj_check_exit();
}
