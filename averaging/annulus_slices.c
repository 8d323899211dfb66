/* The slices of a ball inside a full annulus (annulus_slices.h): annulus_lanes.h with
 * poly_trig.h's functions instead of libm's, two nodes at a time in SSE2 registers, four
 * with AVX2 and eight with AVX-512 (chosen when called, as the Gaussian's deposits do:
 * simd.h); the same operations lane by lane, so the same bits in every build. */
#include <config.h>

#include "annulus_slices.h"

#include <string.h>

#include "simd.h"

#define PT_LANES 2
#define PT_(name) pt2_##name
#include "poly_trig.h"
#define ANN_FN annulus_slices_portable
#include "annulus_lanes.h"
#undef ANN_FN
#undef PT_
#undef PT_LANES

#if MIMAS_X86_DISPATCH
#pragma GCC push_options
#pragma GCC target("avx2")
#define PT_LANES 4
#define PT_(name) pt4_##name
#include "poly_trig.h"
#define ANN_FN annulus_slices_avx2
#include "annulus_lanes.h"
#undef ANN_FN
#undef PT_
#undef PT_LANES
#pragma GCC pop_options

#pragma GCC push_options
#pragma GCC target("avx2,avx512f")
#define PT_LANES 8
#define PT_(name) pt8_##name
#include "poly_trig.h"
#define ANN_FN annulus_slices_avx512
#include "annulus_lanes.h"
#undef ANN_FN
#undef PT_
#undef PT_LANES
#pragma GCC pop_options
#endif

void annulus_slices(double d, double r0, double r1, double R, double ta, double dth,
                    const double *t, double *f, int n)
{
#if MIMAS_X86_DISPATCH
    if (__builtin_cpu_supports("avx512f")) {
        annulus_slices_avx512(d, r0, r1, R, ta, dth, t, f, n);
        return;
    }
    if (__builtin_cpu_supports("avx2")) {
        annulus_slices_avx2(d, r0, r1, R, ta, dth, t, f, n);
        return;
    }
#endif
    annulus_slices_portable(d, r0, r1, R, ta, dth, t, f, n);
}
