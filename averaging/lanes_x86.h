/* Lanes for the vector builds of the Gaussian's deposits (deposit_gauss.c on x-y-z grids,
 * deposit_ring.c on r-z grids): GCC's vectors of 4 and 8 doubles, their masks (from
 * comparisons: all ones or zero) and 32-bit row indices, and what those builds take from
 * the processor's own instructions, with AVX2 for 4 lanes (lane_bits4, ...) and AVX-512 for
 * 8 (lane_bits8, ...): a mask as bits, a gather of table coefficients, a square root
 * (exact to rounding, as sqrt) and m ? a : b.  Each lane is the operation a scalar build
 * does on its value, so the builds give the same numbers to the bit.  The helpers take
 * their vectors by address (without AVX a vector of 4 doubles is not passed in
 * registers), except lane_sel, which only the vector builds call. */
#ifndef MIMAS_LANES_X86_H
#define MIMAS_LANES_X86_H

#include "simd.h"

typedef double lane_v4 __attribute__((vector_size(32)));
typedef long long lane_m4 __attribute__((vector_size(32)));
typedef int lane_i4 __attribute__((vector_size(16)));
typedef double lane_v8 __attribute__((vector_size(64)));
typedef long long lane_m8 __attribute__((vector_size(64)));
typedef int lane_i8 __attribute__((vector_size(32)));

#if MIMAS_X86_DISPATCH
#include <immintrin.h>

#pragma GCC push_options
#pragma GCC target("avx2")
static inline int lane_bits4(const lane_m4 *m)
{
    return _mm256_movemask_pd((__m256d)*m);
}

static inline void lane_gather4(const double *base, const lane_i4 *row, lane_v4 *c)
{
    *c = (lane_v4)_mm256_i32gather_pd(base, (__m128i)*row, 8);
}

static inline void lane_sqrt4(const lane_v4 *x, lane_v4 *r)
{
    *r = (lane_v4)_mm256_sqrt_pd((__m256d)*x);
}

static inline lane_v4 lane_sel4(lane_m4 m, lane_v4 a, lane_v4 b)
{
    return (lane_v4)_mm256_blendv_pd((__m256d)b, (__m256d)a, (__m256d)m);
}
#pragma GCC pop_options

#pragma GCC push_options
#pragma GCC target("avx2,avx512f")
static inline int lane_bits8(const lane_m8 *m)
{
    return (int)_mm512_test_epi64_mask((__m512i)*m, (__m512i)*m);
}

static inline void lane_gather8(const double *base, const lane_i8 *row, lane_v8 *c)
{
    *c = (lane_v8)_mm512_i32gather_pd((__m256i)*row, base, 8);
}

static inline void lane_sqrt8(const lane_v8 *x, lane_v8 *r)
{
    *r = (lane_v8)_mm512_sqrt_pd((__m512d)*x);
}

static inline lane_v8 lane_sel8(lane_m8 m, lane_v8 a, lane_v8 b)
{
    __mmask8 k = _mm512_test_epi64_mask((__m512i)m, (__m512i)m);
    return (lane_v8)_mm512_mask_blend_pd(k, (__m512d)b, (__m512d)a);
}
#pragma GCC pop_options
#endif

#endif
