/* How many cores this process may use: the CPUs of its affinity mask (taskset, cpusets), cut
 * to the cgroup v2 CPU quota (containers: docker --cpus, systemd CPUQuota). A pool of one
 * thread per online core oversubscribes a container limited to 2 of 64 cores. */
#define _GNU_SOURCE /* sched_getaffinity, CPU_COUNT */
#include "render_pool.h"

#include <sched.h>
#include <stdio.h>
#include <stdlib.h>
#include <unistd.h>

int cj_cpu_quota_parse(const char *text) {
    /* "max 100000" (no limit) or "QUOTA PERIOD" in microseconds */
    char *end;
    const double quota = strtod(text, &end);
    if (end == text || quota <= 0) return 0;
    const char *p = end;
    const double period = strtod(p, &end);
    if (end == p || !(period > 0)) return 0;
    const double cpus = quota / period;
    if (!(cpus < 4096)) return 0;
    const int whole = (int)cpus;
    return whole + (cpus > whole); /* rounded up: at least 1, as cpus > 0 */
}

int cj_cpu_count(void) {
    long online = sysconf(_SC_NPROCESSORS_ONLN);
    int n = online > 0 ? (int)(online < 4096 ? online : 4096) : 1;
    cpu_set_t set;
    CPU_ZERO(&set);
    if (sched_getaffinity(0, sizeof set, &set) == 0) {
        const int allowed = CPU_COUNT(&set);
        if (allowed > 0 && allowed < n) n = allowed;
    }
    FILE *f = fopen("/sys/fs/cgroup/cpu.max", "r");
    if (f) {
        char line[128];
        if (fgets(line, sizeof line, f)) {
            const int quota = cj_cpu_quota_parse(line);
            if (quota > 0 && quota < n) n = quota;
        }
        fclose(f);
    }
    return n;
}
