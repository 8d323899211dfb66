/* The plain and shifted Gaussian on r-z grids (cylindrical, no phi cells): the
 * kernel's azimuthal average at each cell centre (r_i, z_j) for a particle, and its
 * Gauss-Legendre line integral along a contact's branch, split at the average's singular
 * points where one is near (ring_edges.h; docs/fields.md, "Cylindrical grids without phi
 * cells").  The average depends on the cell through
 * D0^2 = (r_i - rho)^2 + (z_j - z)^2 and r_i rho: the squared offsets are computed once per
 * column and row (per branch point for a segment); the cut arc is
 * mimas_gauss_ring_short's series (no exponential: the table of M_{1/2}) in lanes of
 * several cells or branch points, the longer arcs near the axis mimas_kernel_ring's rule.
 * The values are mimas_kernel_ring's to rounding. */
#include <config.h>

#include <math.h>
#include <string.h>

#include "deposit_impl.h"
#include "gauss_legendre.h"
#include "lanes_x86.h"
#include "ring_edges.h"
#include "ring_tables.h"

/* The average at the ring (r, z-offset dz) given (r - rho)^2. */
static double ring_value(const mimas_weight *wt, double r, double rho, double dz, double dr2,
                         double grad[2])
{
    double D02 = dr2 + dz * dz, v;
    if (!(D02 < wt->reach2)) {
        if (grad)
            grad[0] = grad[1] = 0.0;
        return 0.0;
    }
    if (r > 0 && rho > 0 && mimas_gauss_ring_short(wt, r, rho, dz, D02, &v, grad))
        return v;
    return mimas_kernel_ring(wt, 3, r, rho, dz, grad);
}

/* Cell index box of an axis-frame point's reach, and room for its cells. */
static int cell_box(const mimas_deposit *dp, const double a[3], double reach, int lo[3],
                    int hi[3], mimas_weights *ws, int *ok)
{
    *ok = dep_candidate_box(dp, a, reach, lo, hi);
    if (!*ok)
        return MIMAS_OK;
    size_t n = (size_t)(hi[0] - lo[0] + 1) * (hi[2] - lo[2] + 1);
    return mimas_weights_reserve(ws, n) ? MIMAS_EIO : MIMAS_OK;
}

/* The lanes: RING_W branch points of a contact at once for one cell, or RING_W cells of a
 * row at once for a particle (with the gradient), branch-free in GCC's vectors of RING_W
 * doubles (4 in the portable build, two SSE2 instructions each, and in the AVX2 build,
 * one instruction each; 8 in the AVX-512 build, simd.h).  Where the arc is short and far
 * from the axis (y = X/a <= RING_LANE_Y, a >= 4 (RING_LANE_N + 2), X <= RING_XMAX) the
 * series of mimas_gauss_ring_short with a fixed RING_LANE_N + 1 terms (y^{N+1} < 3e-19)
 * and T_0 = tail M_{1/2}(X) from its table; other points or cells inside the support are
 * flagged for ring_value.  The shifted kernel's tm = 2 asin(u_m) is the same series with
 * T_n = 2/(2n + 1).  Each build includes deposit_ring_lanes.h with RING_W, its vector,
 * mask and index types RING_VT, RING_MT and RING_IT, and RING_BITS (the mask as bits),
 * RING_GATHER (the table's coefficient k at each lane's row) and RING_SQRT (lanes_x86.h in
 * the vector builds): lane by lane the same operations in every build, so the same weights
 * to the bit in every build; they are mimas_gauss_ring_short's to rounding (y and 1/a from
 * 1/(4 r rho), multiplied, and a fixed number of terms).  (The helpers take their vectors
 * by address: without AVX a vector of 4 doubles is not passed in registers.) */
#define RING_LANE_N 10
#define RING_LANE_Y 0.02

/* The second tier: the lanes the first leaves to ring_value with y <= RING_TIER2_Y, near the
 * axis (a < 4 (RING_LANE_N + 2)) or with longer arcs, by gauss_ring_series's other way (the
 * one it takes nearer the axis, for any a and X): T_{N+1} = tail M_{N+3/2}(X) by its series
 * (dp->ring_terms terms, enough at the weight's largest X, cutoff^2/2), then T_n = (tail +
 * X T_{n+1})/(n + 1/2) downwards with the sum over n by Horner's rule, N = RING_TIER2_N
 * fixed (y^{N+1} <= 3.5e-18); the shifted kernel's t_m series the same way.  Lane by lane
 * the same operations in every build; gauss_ring_series's values to rounding (it stops at
 * the first y^N below 1e-17 (1 - y)). */
#define RING_TIER2_Y 0.25
#define RING_TIER2_N 28

int mimas_ring_tier2_terms(const mimas_weight *wt)
{
    double X = 0.5 * wt->cutoff * wt->cutoff, term = ring_inv_half[RING_TIER2_N + 1], T = term;
    for (int j = RING_TIER2_N + 2; j < RING_NH; j++) {
        term *= X * ring_inv_half[j];
        T += term;
        /* past the largest term and the rest below 1e-18 of the sum (they fall at least by
         * X/(j + 1/2) < 1/2 each from here) */
        if (j > RING_TIER2_N + 1 + 2.0 * X && term < 1e-18 * T)
            return j - (RING_TIER2_N + 1);
    }
    return 0;
}

/* m ? a : b lane by lane (m from a comparison: all ones or zero); whether a lane is set */
#define RING_SEL(m, a, b) ((RING_VT)(((RING_MT)(a) & (m)) | ((RING_MT)(b) & ~(m))))
#define RING_ANY(m) (RING_BITS(m) != 0)

static inline int ring_bits_p(const lane_m4 *m)
{
    int bits = 0;
    for (int l = 0; l < 4; l++)
        bits |= ((*m)[l] != 0) << l;
    return bits;
}

static inline void ring_gather_p(const double *base, const lane_i4 *row, lane_v4 *c)
{
    for (int l = 0; l < 4; l++)
        (*c)[l] = base[(*row)[l]];
}

static inline void ring_sqrt_p(const lane_v4 *Y, lane_v4 *r)
{
    for (int l = 0; l < 4; l++)
        (*r)[l] = sqrt((*Y)[l]);
}

#define RING_W 4
#define RING_VT lane_v4
#define RING_MT lane_m4
#define RING_IT lane_i4
#define RING_BITS ring_bits_p
#define RING_GATHER ring_gather_p
#define RING_SQRT ring_sqrt_p
#define RING_TABLE_FN ring_table
#define RING_REACH_FN ring_reach
#define RING_LANES_FN ring_lanes
#define RING_TIER2_FN ring_tier2
#define RING_CELLS_FN ring_cells
#define RING_SUM_FN ring_sum
#define RING_SEG_FN mimas_gauss_segment_rz_portable
#define RING_SPHERE_FN mimas_gauss_sphere_rz_portable
#include "deposit_ring_lanes.h"

#if MIMAS_X86_DISPATCH
#pragma GCC push_options
#pragma GCC target("avx2")

#define RING_W 4
#define RING_VT lane_v4
#define RING_MT lane_m4
#define RING_IT lane_i4
#define RING_BITS lane_bits4
#define RING_GATHER lane_gather4
#define RING_SQRT lane_sqrt4
#define RING_TABLE_FN ring_table_avx2
#define RING_REACH_FN ring_reach_avx2
#define RING_LANES_FN ring_lanes_avx2
#define RING_TIER2_FN ring_tier2_avx2
#define RING_CELLS_FN ring_cells_avx2
#define RING_SUM_FN ring_sum_avx2
#define RING_SEG_FN mimas_gauss_segment_rz_avx2
#define RING_SPHERE_FN mimas_gauss_sphere_rz_avx2
#include "deposit_ring_lanes.h"
#pragma GCC pop_options

#pragma GCC push_options
#pragma GCC target("avx2,avx512f")

/* the rules of 4 points (the shortest branches) in the AVX2 build */
#define RING_NARROW mimas_gauss_segment_rz_avx2
#define RING_W 8
#define RING_VT lane_v8
#define RING_MT lane_m8
#define RING_IT lane_i8
#define RING_BITS lane_bits8
#define RING_GATHER lane_gather8
#define RING_SQRT lane_sqrt8
#define RING_TABLE_FN ring_table_avx512
#define RING_REACH_FN ring_reach_avx512
#define RING_LANES_FN ring_lanes_avx512
#define RING_TIER2_FN ring_tier2_avx512
#define RING_CELLS_FN ring_cells_avx512
#define RING_SUM_FN ring_sum_avx512
#define RING_SEG_FN mimas_gauss_segment_rz_avx512
#define RING_SPHERE_FN mimas_gauss_sphere_rz_avx512
#include "deposit_ring_lanes.h"
#pragma GCC pop_options
#endif

int mimas_gauss_segment_rz(const mimas_deposit *dp, const double aa[3], const double ab[3],
                           const double am[3], double reach, double scale, mimas_weights *ws)
{
#if MIMAS_X86_DISPATCH
    if (__builtin_cpu_supports("avx512f"))
        return mimas_gauss_segment_rz_avx512(dp, aa, ab, am, reach, scale, ws);
    if (__builtin_cpu_supports("avx2"))
        return mimas_gauss_segment_rz_avx2(dp, aa, ab, am, reach, scale, ws);
#endif
    return mimas_gauss_segment_rz_portable(dp, aa, ab, am, reach, scale, ws);
}

int mimas_gauss_sphere_rz(const mimas_deposit *dp, const double a[3], int with_grad,
                          double scale, mimas_weights *ws)
{
#if MIMAS_X86_DISPATCH
    if (__builtin_cpu_supports("avx512f"))
        return mimas_gauss_sphere_rz_avx512(dp, a, with_grad, scale, ws);
    if (__builtin_cpu_supports("avx2"))
        return mimas_gauss_sphere_rz_avx2(dp, a, with_grad, scale, ws);
#endif
    return mimas_gauss_sphere_rz_portable(dp, a, with_grad, scale, ws);
}
