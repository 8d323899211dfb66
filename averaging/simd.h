/* MIMAS_SIMD marks a hot function whose loops the compiler also builds for
 * AVX2 (4 doubles per instruction), the variant chosen when the library loads
 * (GCC's target_clones; elsewhere the one portable build).  The results are the
 * same bit for bit: the loops are vectorised across independent sums, and ISO C
 * mode (-std=c17) fuses no multiply-add (-ffp-contract=off), which AVX2 alone
 * would not offer anyway. */
#ifndef MIMAS_SIMD_H
#define MIMAS_SIMD_H

#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && defined(__linux__) && \
    __GNUC__ >= 6
#define MIMAS_SIMD __attribute__((target_clones("avx2", "default")))
/* the same processors: a function built twice, once under #pragma GCC target("avx2")
 * with its intrinsics, chosen by __builtin_cpu_supports (the Gaussian's line integrals,
 * deposit_gauss.c and deposit_ring.c) */
#define MIMAS_X86_DISPATCH 1
#else
#define MIMAS_SIMD
#define MIMAS_X86_DISPATCH 0
#endif

/* v4d: four doubles in one register where the compiler has vector types (GCC,
 * Clang), for loops the compiler does not vectorise by itself; unaligned and
 * aliasing anything, so that any double array can be read and written four at a
 * time.  Element by element the same operations as the scalar code. */
#if defined(__GNUC__)
#define MIMAS_HAVE_V4D 1
typedef double v4d __attribute__((vector_size(32), aligned(8), may_alias));
#endif

#endif
