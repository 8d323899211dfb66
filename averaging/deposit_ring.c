/* The plain and shifted Gaussian on r-z grids (cylindrical, no phi cells): the
 * kernel's azimuthal average at each cell centre (r_i, z_j) for a particle, and its
 * Gauss-Legendre line integral along a contact's branch (docs/fields.md, "Cylindrical
 * grids without phi cells").  The average depends on the cell through
 * D0^2 = (r_i - rho)^2 + (z_j - z)^2 and r_i rho: the squared offsets are computed once per
 * column and row (per branch point for a segment); the cut arc is
 * mimas_gauss_ring_short's series (no exponential: the table of M_{1/2}), the longer
 * arcs near the axis mimas_kernel_ring's rule.  The values are mimas_kernel_ring's. */
#include <config.h>

#include <math.h>
#include <string.h>

#include "deposit_impl.h"
#include "gauss_legendre.h"
#include "ring_tables.h"
#include "simd.h"

#if MIMAS_X86_DISPATCH
#include <immintrin.h>
#endif

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

int mimas_gauss_sphere_rz(const mimas_deposit *dp, const double a[3], int with_grad,
                          double scale, mimas_weights *ws)
{
    const mimas_weight *wt = dp->wt;
    int lo[3], hi[3], ok;
    ws->has_grad = with_grad;
    if (cell_box(dp, a, mimas_weight_reach(wt), lo, hi, ws, &ok) || !ok)
        return ok ? MIMAS_EIO : MIMAS_OK;
    int nr = hi[0] - lo[0] + 1, nz = hi[2] - lo[2] + 1;
    double *t = mimas_weights_scratch(ws, 2 * (size_t)nr + (size_t)nz);
    if (!t)
        return MIMAS_EIO;
    double *rc = t, *dr2 = t + nr, *dz = t + 2 * nr;
    double rho = hypot(a[0], a[1]);
    for (int i = 0; i < nr; i++) {
        rc[i] = dep_centre(dp, 0, lo[0] + i);
        dr2[i] = (rc[i] - rho) * (rc[i] - rho);
    }
    for (int j = 0; j < nz; j++)
        dz[j] = dep_centre(dp, 2, lo[2] + j) - a[2];
    int idx[3] = {0, lo[1], 0};
    for (int j = 0; j < nz; j++)
        for (int i = 0; i < nr; i++) {
            double g[2] = {0, 0};
            double v = ring_value(wt, rc[i], rho, dz[j], dr2[i], with_grad ? g : NULL);
            if (v == 0.0 && g[0] == 0.0 && g[1] == 0.0)
                continue;
            idx[0] = lo[0] + i;
            idx[2] = lo[2] + j;
            size_t cell = mimas_grid_index(dp->grid, idx);
            if (with_grad)
                dep_put_grad(ws, cell, v * scale, g[0] * scale, 0.0, g[1] * scale);
            else
                dep_put(ws, cell, v * scale);
        }
    return MIMAS_OK;
}

/* The contacts' lanes: 4 branch points at once for one cell, branch-free in GCC's vectors
 * of 4 doubles (one AVX2 instruction each in the AVX2 build, simd.h; two SSE2 ones else).
 * Where the arc is short and far from the axis (y = X/a <= RING_LANE_Y,
 * a >= 4 (RING_LANE_N + 2), X <= RING_XMAX) the series of mimas_gauss_ring_short with a
 * fixed RING_LANE_N + 1 terms (y^{N+1} < 3e-19) and T_0 = tail M_{1/2}(X) from its table;
 * other points inside the support are flagged for ring_value.  The shifted kernel's
 * tm = 2 asin(u_m) is the same series with T_n = 2/(2n + 1). */
#define RING_LANE_N 10
#define RING_LANE_Y 0.02

typedef double ring_v4 __attribute__((vector_size(32)));
typedef long long ring_m4 __attribute__((vector_size(32)));
/* m ? a : b lane by lane (m from a comparison: all ones or zero) */
#define RING_SEL(m, a, b) ((ring_v4)(((ring_m4)(a) & (m)) | ((ring_m4)(b) & ~(m))))

#define RING_LANES_FN ring_lanes
#define RING_SEG_FN mimas_gauss_segment_rz_portable
#define RING_AVX2 0
#include "deposit_ring_segment.h"
#undef RING_LANES_FN
#undef RING_SEG_FN
#undef RING_AVX2

#if MIMAS_X86_DISPATCH
#pragma GCC push_options
#pragma GCC target("avx2")

/* ring_m_half_at at four points (X >= 0, taken as RING_XMAX beyond it), lane by lane the
 * same operations, the coefficients gathered. */
static inline __m256d ring_m_half4(__m256d X)
{
    X = _mm256_min_pd(X, _mm256_set1_pd(RING_XMAX));
    __m128i m = _mm256_cvttpd_epi32(_mm256_mul_pd(X, _mm256_set1_pd(RING_STEP)));
    m = _mm_min_epi32(m, _mm_set1_epi32(RING_STEP * RING_XMAX - 1));
    __m256d mid = _mm256_div_pd(_mm256_add_pd(_mm256_cvtepi32_pd(m), _mm256_set1_pd(0.5)),
                                _mm256_set1_pd(RING_STEP));
    __m256d t = _mm256_sub_pd(X, mid), t2 = _mm256_mul_pd(t, t);
    __m128i row = _mm_mullo_epi32(m, _mm_set1_epi32(RING_DEG + 1));
    const double *base = &ring_m_half[0][0];
    __m256d c[RING_DEG + 1];
    for (int k = 0; k <= RING_DEG; k++)
        c[k] = _mm256_i32gather_pd(base + k, row, 8);
    __m256d lo = _mm256_add_pd(_mm256_add_pd(c[0], _mm256_mul_pd(c[1], t)),
                               _mm256_mul_pd(t2, _mm256_add_pd(c[2], _mm256_mul_pd(c[3], t))));
    __m256d hi = _mm256_add_pd(_mm256_add_pd(c[4], _mm256_mul_pd(c[5], t)),
                               _mm256_mul_pd(t2, _mm256_add_pd(c[6], _mm256_mul_pd(c[7], t))));
    return _mm256_add_pd(lo, _mm256_mul_pd(_mm256_mul_pd(t2, t2), hi));
}

#define RING_LANES_FN ring_lanes_avx2
#define RING_SEG_FN segment_rz_avx2
#define RING_AVX2 1
#include "deposit_ring_segment.h"
#undef RING_LANES_FN
#undef RING_SEG_FN
#undef RING_AVX2
#pragma GCC pop_options
#endif

int mimas_gauss_segment_rz(const mimas_deposit *dp, const double aa[3], const double ab[3],
                           const double am[3], double reach, double scale, mimas_weights *ws)
{
#if MIMAS_X86_DISPATCH
    if (__builtin_cpu_supports("avx2"))
        return segment_rz_avx2(dp, aa, ab, am, reach, scale, ws);
#endif
    return mimas_gauss_segment_rz_portable(dp, aa, ab, am, reach, scale, ws);
}
