/* rss.h: the resident memory a step of a benchmark adds, from Linux's /proc/self/status, shared by
 * the benchmark programs (bench.c's BVH builds, bench_obj.c's OBJ loads). */
#ifndef MCRT_RSS_H
#define MCRT_RSS_H

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#ifdef __GLIBC__
#include <malloc.h>
#endif

/* A field of /proc/self/status ("VmRSS", "VmHWM") in bytes, or -1 where there is none. */
static long long status_bytes(const char *field)
{
    FILE *f = fopen("/proc/self/status", "r");
    char line[256];
    long long kb = -1;
    size_t n = strlen(field);
    if (!f)
        return -1;
    while (fgets(line, sizeof line, f))
        if (strncmp(line, field, n) == 0 && line[n] == ':') {
            kb = atoll(line + n + 1);
            break;
        }
    fclose(f);
    return kb < 0 ? -1 : kb * 1024;
}

/* Peak resident memory of a step: mark_rss() gives freed heap back to the system and resets the
 * process's high-water mark (Linux: writing 5 to /proc/self/clear_refs), and returns the resident
 * bytes then; after the step, VmHWM minus that is the most the step added at any moment, and
 * VmRSS minus it what stays. -1 where Linux's counters are not there. */
static long long mark_rss(void)
{
    FILE *f;
#ifdef __GLIBC__
    malloc_trim(0);
#endif
    f = fopen("/proc/self/clear_refs", "w");
    if (!f)
        return -1;
    fputs("5", f);
    fclose(f);
    return status_bytes("VmRSS");
}

struct rss {
    double peak, kept; /* bytes per item (triangle); negative: unknown */
};

static struct rss rss_since(long long mark, size_t items)
{
    struct rss r = {-1, -1};
    long long hwm = status_bytes("VmHWM"), now;
    /* Kept is what the step still holds: heap it freed is given back first, as for the mark. */
#ifdef __GLIBC__
    malloc_trim(0);
#endif
    now = status_bytes("VmRSS");
    if (mark >= 0 && hwm >= 0 && now >= 0) {
        r.peak = (double)(hwm - mark) / (double)items;
        r.kept = (double)(now - mark) / (double)items;
    }
    return r;
}

#endif
