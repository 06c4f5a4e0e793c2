/* alloc.h: the library's allocator. Every allocation of libmcrt goes through these, so that a test
 * can make any one of them fail (mc_alloc_fail_nth) and check that the call reports
 * MCRT_ERR_NOMEM, leaks nothing and does not crash, in the manner of Lua's ltests.c. Memory from
 * all of them is released with free().
 *
 * libpng and OpenEXR are given mc_malloc and free for their own allocations (io/png.c, io/exr.c),
 * so their failures are injected too.
 *
 * The hook is internal, not a public mcrt_set_allocator. Failure injection is what the tests
 * need, and it needs no public promise; a caller's allocator would be one: every free, the
 * image libraries' included, would have to reach it, it would have to be thread-safe (the BVH
 * build allocates on its worker threads), and no user has asked for it. Should one, mc_malloc and
 * its siblings are the one place to call it from. */
#ifndef MCRT_ALLOC_H
#define MCRT_ALLOC_H

#include <stddef.h>

void *mc_malloc(size_t bytes);
void *mc_calloc(size_t count, size_t size);
void *mc_realloc(void *p, size_t bytes);
/* bytes (at least 1) aligned to align, a power of two multiple of sizeof(void *); NULL when out of
 * memory. */
void *mc_aligned_alloc(size_t align, size_t bytes);
/* p (from these functions) cut to its first bytes, perhaps moved; p itself, unchanged, when the
 * system cannot or bytes is 0. Giving back a tail cannot fail from the caller's side, so it is
 * not an allocation the tests make fail. */
void *mc_shrink(void *p, size_t bytes);
/* A copy of the string s (not NULL); NULL when out of memory. */
char *mc_strdup(const char *s);

/* Testing: make the n-th allocation from now on fail (n >= 1), once, and count allocations from
 * zero; n = 0 only restarts the count. Allocations on every thread count (the BVH build allocates
 * on its workers), so with several threads which one is the n-th may vary between runs. */
void mc_alloc_fail_nth(size_t n);
/* Allocations asked for since the last mc_alloc_fail_nth, the failed one included. */
size_t mc_alloc_count(void);

#endif
