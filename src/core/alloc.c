/* alloc.c: the library's allocator, with the failure injection of alloc.h. */
#include "core/alloc.h"

#include <stdlib.h>
#include <string.h>

#include "core/atomic.h"

/* Allocations counted since the last mc_alloc_fail_nth, and the one that fails (0: none). The
 * target is set by a test before the calls it watches, on the same thread, so it needs no
 * atomicity of its own. */
static mc_atomic_size alloc_count;
static size_t fail_at;

/* Count an allocation; whether it is the one to fail. */
static int injected_failure(void)
{
    return mc_atomic_fetch_add(&alloc_count, 1) + 1 == fail_at;
}

void *mc_malloc(size_t bytes) { return injected_failure() ? NULL : malloc(bytes); }

void *mc_calloc(size_t count, size_t size)
{
    return injected_failure() ? NULL : calloc(count, size);
}

void *mc_realloc(void *p, size_t bytes) { return injected_failure() ? NULL : realloc(p, bytes); }

void *mc_aligned_alloc(size_t align, size_t bytes)
{
    void *p = NULL;
    if (injected_failure() || posix_memalign(&p, align, bytes ? bytes : 1) != 0)
        return NULL;
    return p;
}

void *mc_shrink(void *p, size_t bytes)
{
    void *q;
    if (!p || bytes == 0)
        return p;
    q = realloc(p, bytes);
    return q ? q : p;
}

char *mc_strdup(const char *s)
{
    char *p = mc_malloc(strlen(s) + 1);
    return p ? strcpy(p, s) : NULL;
}

void mc_alloc_fail_nth(size_t n)
{
    fail_at = n;
    alloc_count = 0;
}

size_t mc_alloc_count(void) { return mc_atomic_fetch_add(&alloc_count, 0); }

#ifdef MCRT_ATOMIC_FALLBACK
#include <pthread.h>
/* atomic.h's fetch-and-add where there are no atomics: here, beside its main user, so that every
 * build has it. */
static pthread_mutex_t atomic_lock = PTHREAD_MUTEX_INITIALIZER;
size_t mc_atomic_fetch_add(mc_atomic_size *p, size_t v)
{
    size_t old;
    pthread_mutex_lock(&atomic_lock);
    old = *p;
    *p = old + v;
    pthread_mutex_unlock(&atomic_lock);
    return old;
}
#endif
