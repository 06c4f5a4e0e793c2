/* t.h: the test harness for tests/unit (after Redis's testhelp.h).
 * T_CHECK records one check; T_NEAR compares within an absolute tolerance (both take a printf
 * format and arguments for the failure message); t_done() prints
 * "N passed, N failed" as the last line and returns the exit status. */
#ifndef MCRT_T_H
#define MCRT_T_H

#include <math.h>
#include <stdio.h>

static int t_passed, t_failed;

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

/* Print a named measurement so that test logs carry the numbers behind each verdict. */
#define T_NOTE(...)                                                                            \
    do {                                                                                       \
        printf("  note: ");                                                                    \
        printf(__VA_ARGS__);                                                                   \
        printf("\n");                                                                          \
    } while (0)

static inline int t_done(void)
{
    printf("%d passed, %d failed\n", t_passed, t_failed);
    return t_failed ? 1 : 0;
}

#endif
