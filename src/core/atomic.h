/* atomic.h: the few atomic operations the library needs, for a C99 code base.
 *
 * Every use in mcrt is relaxed: a cancel flag that workers poll, a work counter that hands out
 * items, an out-of-memory flag, the allocation counter of core/alloc.h. Relaxed means each access
 * is indivisible and there is one order of the writes to each object, and nothing more: no data
 * is published through these objects. What the threads share otherwise is handed over by
 * pthread_create, pthread_join and mutexes, which order memory themselves.
 *
 * Objects touched from several threads are declared mc_atomic_int or mc_atomic_size and only
 * accessed through the functions below. Which implementation is used, in order of preference:
 *   - C11 <stdatomic.h> (compiled as C11 or later, atomics not opted out): the types are _Atomic
 *     and the functions are the *_explicit calls with memory_order_relaxed;
 *   - GCC's and clang's __atomic builtins (C99 mode, mcrt's own build): plain types, the same
 *     relaxed operations;
 *   - otherwise a fallback: loads and stores are volatile accesses (indivisible for an aligned
 *     int on the machines POSIX threads run on, though C99 does not promise it; relaxed order is
 *     all that is asked), and fetch-and-add takes one process-wide pthread mutex (then
 *     sequentially consistent, more than asked). Stores stay lock-free, so mcrt_render_cancel may
 *     still be called from a signal handler. */
#ifndef MCRT_ATOMIC_H
#define MCRT_ATOMIC_H

#include <stddef.h>

#if defined(__STDC_VERSION__) && __STDC_VERSION__ >= 201112L && !defined(__STDC_NO_ATOMICS__)
#include <stdatomic.h>
typedef _Atomic int mc_atomic_int;
typedef _Atomic size_t mc_atomic_size;
static inline int mc_atomic_load(mc_atomic_int *p)
{
    return atomic_load_explicit(p, memory_order_relaxed);
}
static inline void mc_atomic_store(mc_atomic_int *p, int v)
{
    atomic_store_explicit(p, v, memory_order_relaxed);
}
static inline size_t mc_atomic_fetch_add(mc_atomic_size *p, size_t v)
{
    return atomic_fetch_add_explicit(p, v, memory_order_relaxed);
}
#elif defined(__ATOMIC_RELAXED)
typedef int mc_atomic_int;
typedef size_t mc_atomic_size;
static inline int mc_atomic_load(mc_atomic_int *p) { return __atomic_load_n(p, __ATOMIC_RELAXED); }
static inline void mc_atomic_store(mc_atomic_int *p, int v)
{
    __atomic_store_n(p, v, __ATOMIC_RELAXED);
}
static inline size_t mc_atomic_fetch_add(mc_atomic_size *p, size_t v)
{
    return __atomic_fetch_add(p, v, __ATOMIC_RELAXED);
}
#else
#define MCRT_ATOMIC_FALLBACK 1
typedef volatile int mc_atomic_int;
typedef volatile size_t mc_atomic_size;
static inline int mc_atomic_load(mc_atomic_int *p) { return *p; }
static inline void mc_atomic_store(mc_atomic_int *p, int v) { *p = v; }
/* In core/alloc.c, under its mutex. */
size_t mc_atomic_fetch_add(mc_atomic_size *p, size_t v);
#endif

#endif
