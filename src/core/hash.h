/* hash.h: FNV-1a 64 (Fowler, Noll and Vo), folded over bytes one piece after another: the
 * fingerprint of a scene's inputs (its text, then every file it read) that render states carry.
 * Not a defence against a chosen collision, only against resuming or merging a render of another
 * scene by mistake. */
#ifndef MCRT_CORE_HASH_H
#define MCRT_CORE_HASH_H

#include <stddef.h>
#include <stdint.h>

/* The hash of no bytes (FNV-1a's offset basis). */
#define MC_HASH_INIT 0xcbf29ce484222325ULL

/* h, the hash of what came before, continued over n more bytes. */
static inline uint64_t mc_hash(uint64_t h, const void *bytes, size_t n)
{
    const unsigned char *p = bytes;
    size_t i;
    for (i = 0; i < n; i++) {
        h ^= p[i];
        h *= 0x100000001b3ULL; /* FNV's 64-bit prime */
    }
    return h;
}

#endif
