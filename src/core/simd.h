/* simd.h: what the hand-vectorised modules (geom/bvh.c, denoise/nfor.c) share: forced inlining
 * and its opposite, and copies of a function compiled for AVX2, chosen at run time on a processor
 * that has it (GCC's and Clang's target attribute and __builtin_cpu_supports, x86-64 only). A
 * build already compiled for AVX2 (-mavx2, -march=native) needs no dispatch: MC_AVX2_DISPATCH is
 * then unset. */
#ifndef MC_CORE_SIMD_H
#define MC_CORE_SIMD_H

/* GCC -O2 keeps large static functions out of line, with their flags as run-time arguments;
 * forced inlining makes them constants of each caller's copy. MC_NOINLINE keeps a function that
 * is a dispatch target its own, so that the caller is a test and a jump. */
/* MC_PREFETCH(p) asks for p's cache line ahead of a read that a scattered access pattern would
 * otherwise leave waiting for memory; it changes no result. */
#if defined(__GNUC__)
#define MC_ALWAYS_INLINE inline __attribute__((always_inline))
#define MC_NOINLINE __attribute__((noinline))
#define MC_PREFETCH(p) __builtin_prefetch(p)
#else
#define MC_ALWAYS_INLINE inline
#define MC_NOINLINE
#define MC_PREFETCH(p) ((void)(p))
#endif

/* With AVX2 come BMI1 and BMI2 on every processor that has both (x86-64-v3): their bit
 * operations (tzcnt, blsr, shlx) serve the traversal's lane masks, 2.2% fewer instructions a
 * nearest-hit query and 4.4% a shadow ray on sphere-1M (callgrind, bench --quick); they change no
 * floating-point result. */
#if defined(__GNUC__) && defined(__x86_64__) && !defined(__AVX2__)
#define MC_AVX2_DISPATCH 1
#define MC_AVX2_TARGET __attribute__((target("avx2,bmi,bmi2")))
#define mc_cpu_has_avx2() (__builtin_cpu_supports("avx2") && __builtin_cpu_supports("bmi2"))
#endif

#endif
