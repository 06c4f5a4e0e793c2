/* t.h: the test harness for tests/unit (after Redis's testhelp.h).
 * T_CHECK records one check; T_NEAR compares within an absolute tolerance (both take a printf
 * format and arguments for the failure message); T_SKIP records checks this machine or build
 * cannot make (a library not built in, a tool not installed), neither passed nor failed, with
 * the reason; t_done() prints "N passed, N failed" (", N skipped" when some were) as the last
 * line and returns the exit status. */
#ifndef MCRT_T_H
#define MCRT_T_H

#include <math.h>
#include <stdio.h>

static int t_passed, t_failed, t_skipped;

#define T_CHECK(cond, ...)                                                                     \
    do {                                                                                       \
        if (cond) {                                                                            \
            t_passed++;                                                                        \
        } else {                                                                               \
            t_failed++;                                                                        \
            printf("FAIL %s:%d: %s: ", __FILE__, __LINE__, #cond);                             \
            printf(__VA_ARGS__);                                                               \
            printf("\n");                                                                      \
        }                                                                                      \
    } while (0)

#define T_NEAR(a, b, tol, ...)                                                                 \
    do {                                                                                       \
        double t_a_ = (double)(a), t_b_ = (double)(b), t_tol_ = (double)(tol);                 \
        if (fabs(t_a_ - t_b_) <= t_tol_) {                                                     \
            t_passed++;                                                                        \
        } else {                                                                               \
            t_failed++;                                                                        \
            printf("FAIL %s:%d: %s vs %s: %.9g vs %.9g (tol %.3g): ", __FILE__, __LINE__, #a,  \
                   #b, t_a_, t_b_, t_tol_);                                                    \
            printf(__VA_ARGS__);                                                               \
            printf("\n");                                                                      \
        }                                                                                      \
    } while (0)

/* Record a check, or a group of checks, that cannot be made here, and print why, as
 * "skip file:line: reason" (tests/run.sh lists every skip above its total). */
#define T_SKIP(...)                                                                            \
    do {                                                                                       \
        t_skipped++;                                                                           \
        printf("skip %s:%d: ", __FILE__, __LINE__);                                            \
        printf(__VA_ARGS__);                                                                   \
        printf("\n");                                                                          \
    } while (0)

/* Print a named measurement so that test logs carry the numbers behind each verdict. */
#define T_NOTE(...)                                                                            \
    do {                                                                                       \
        printf("  note: ");                                                                    \
        printf(__VA_ARGS__);                                                                   \
        printf("\n");                                                                          \
    } while (0)

static inline int t_done(void)
{
    printf("%d passed, %d failed", t_passed, t_failed);
    if (t_skipped)
        printf(", %d skipped", t_skipped);
    printf("\n");
    return t_failed ? 1 : 0;
}

#endif
