/* clock.h: wall-clock seconds on the monotonic clock, for render times and time budgets. */
#ifndef MCRT_CLOCK_H
#define MCRT_CLOCK_H

#include <time.h>

static inline double mc_seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

#endif
