/* The Gaussian on Cartesian x-y-z grids, separable (docs/fields.md, "The line
 * integral"; docs/theory.md §6): a particle is a product of three rows of 1-D
 * factors inside the cut ball; a contact's line integral is, where the whole
 * branch lies within the cutoff of the cell centre, a Gauss-Legendre sum whose
 * every node is such a product, and where the cut ball cuts the branch a closed
 * form in e^{u^2} erf(u) (from a table) and separable exponentials. */
#include <config.h>

#include <math.h>
#include <pthread.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "deposit_impl.h"
#include "gauss_legendre.h"
#include "simd.h"

#if MIMAS_X86_DISPATCH
#include <immintrin.h>
#endif

/* ---- G(u) = e^{u^2} erf(u) and H(u) = e^{u^2} erfc(u) ---------------------------------
 * G' = 2u G + 2/sqrt(pi) and H' = 2u H - 2/sqrt(pi): the Taylor coefficients of either about
 * u_c follow from a_0 (its value at u_c) by (k + 1) a_{k+1} = 2 u_c a_k + 2 a_{k-1}, a_1 =
 * 2 u_c a_0 +- 2/sqrt(pi).  Degree 8 on 256 intervals of 1/64 covering [0, 4] leaves a
 * relative truncation error below 1e-18 (for G the remainder a_9 (1/128)^9 against G; H's
 * derivatives are bounded by those of e^{-s^2} integrals and fall faster), so G and H are as
 * exact as a_0 = e^{u_c^2} erf(u_c) or e^{u_c^2} erfc(u_c) (a few ulp; H checked against
 * 30-digit values: 5e-16).  The tables are the same for every kernel: made once. */
enum { GT_N = 256, GT_DEG = 8 };
static const double GT_DU = 1.0 / 64.0;
/* [0]: G, [1]: H, in one array for the AVX2 build's gathers */
static double ghtab[2][GT_N][GT_DEG + 1];
static pthread_once_t gtab_once = PTHREAD_ONCE_INIT;

static void taylor_row(double uc, double a0, double sign, double *a)
{
    a[0] = a0;
    a[1] = 2.0 * uc * a0 + sign * 2.0 / sqrt(M_PI);
    for (int k = 1; k < GT_DEG; k++)
        a[k + 1] = (2.0 * uc * a[k] + 2.0 * a[k - 1]) / (k + 1);
}

static void gtab_setup(void)
{
    for (int m = 0; m < GT_N; m++) {
        double uc = (m + 0.5) * GT_DU, e = exp(uc * uc);
        taylor_row(uc, e * erf(uc), 1.0, ghtab[0][m]);
        taylor_row(uc, e * erfc(uc), -1.0, ghtab[1][m]);
    }
}

/* The table's polynomial at 0 <= x < 4 */
static inline double tab_eval(const double (*tab)[GT_DEG + 1], double x)
{
    int m = (int)(x * 64.0);
    if (m >= GT_N)
        m = GT_N - 1;
    const double *a = tab[m];
    double d = x - (m + 0.5) * GT_DU, v = a[GT_DEG];
    for (int k = GT_DEG - 1; k >= 0; k--)
        v = v * d + a[k];
    return v;
}

/* G(u) for 0 <= u < 4 */
static inline double g_eval(double u)
{
    return tab_eval(ghtab[0], u);
}

/* H(u) for 0 <= u < 4 */
static inline double h_eval(double u)
{
    return tab_eval(ghtab[1], u);
}

/* e^{-(c_i - x)^2 k}, k = 1/2w^2, for the cells i = 0..n-1 of direction d from lo, c_i their
 * centres (uniform spacing h inside the grid): from the cell nearest to x
 * outwards by the Gaussian recurrence e_{i+1} = e_i r_i, r_{i+1} = r_i e^{-2 h^2 k}
 * (two products per cell; rounding grows by an ulp or two per step, ~1e-15 over
 * the few cells of a kernel), every value checked against the cutoff by the
 * caller.  The last cell of a grid may be shorter: its centre is taken exactly.
 * Inline, in the callers' vector build: three or six rows an object. */
static inline void gauss_row(const mimas_deposit *dp, int d, int lo, int n, double x, double *e)
{
    double h = dp->h[d];
    int m = (int)floor((x - dep_centre(dp, d, lo)) / h + 0.5);
    if (m < 0)
        m = 0;
    if (m > n - 1)
        m = n - 1;
    double c = dep_centre(dp, d, lo + m) - x, k = dp->wt->inv2w2;
    double q = dp->gq[d];
    double e0 = exp(-c * c * k);
    e[m] = e0;
    /* upwards: (c + h)^2 - c^2 = 2 c h + h^2; downwards the ratio is q / that */
    double up = exp(-(2.0 * c * h + h * h) * k), r = up, v = e0;
    for (int i = m + 1; i < n; i++) {
        v *= r;
        r *= q;
        e[i] = v;
    }
    r = q / up;
    v = e0;
    for (int i = m - 1; i >= 0; i--) {
        v *= r;
        r *= q;
        e[i] = v;
    }
    /* the grid's last cell (its upper edge is the grid's bound): exact */
    const mimas_grid *g = dp->grid;
    if (lo + n == g->n[d] && n > 0 && m != n - 1) {
        double cl = dep_centre(dp, d, lo + n - 1) - x;
        e[n - 1] = exp(-cl * cl * k);
    }
}

/* ---- particles --------------------------------------------------------------------- */

MIMAS_SIMD
int mimas_gauss_sphere_xyz(const mimas_deposit *dp, const double x[3], int with_grad,
                           mimas_weights *ws)
{
    const mimas_weight *wt = dp->wt;
    double reach = mimas_weight_reach(wt);
    int lo[3], hi[3];
    if (!dep_candidate_box(dp, x, reach, lo, hi))
        return MIMAS_OK;
    int len[3];
    for (int d = 0; d < 3; d++)
        len[d] = hi[d] - lo[d] + 1;
    if (mimas_weights_reserve(ws, (size_t)len[0] * len[1] * len[2]))
        return MIMAS_EIO;
    /* factors, squared offsets and gradient factors -(c - x)/w^2, per direction */
    size_t total = (size_t)len[0] + len[1] + len[2];
    double *buf = mimas_weights_scratch(ws, 3 * total);
    if (!buf)
        return MIMAS_EIO;
    double *e[3], *q[3], *gf[3];
    for (int d = 0, off = 0; d < 3; d++) {
        e[d] = buf + off;
        q[d] = buf + total + off;
        gf[d] = buf + 2 * total + off;
        off += len[d];
        for (int i = 0; i < len[d]; i++) {
            double dd = dep_centre(dp, d, lo[d] + i) - x[d];
            q[d][i] = dd * dd;
            gf[d][i] = -2.0 * wt->inv2w2 * dd;
        }
        gauss_row(dp, d, lo[d], len[d], x[d], e[d]);
    }
    const mimas_grid *g = dp->grid;
    double coef = wt->coef, sh = coef * wt->shift, R2 = wt->reach2;
    for (int k = 0; k < len[2]; k++)
        for (int j = 0; j < len[1]; j++) {
            double qyz = q[1][j] + q[2][k];
            if (qyz >= R2)
                continue;
            /* the cells of the row inside the ball: an interval (q[0] is convex) */
            int i0 = 0, i1 = len[0] - 1;
            while (i0 <= i1 && q[0][i0] + qyz >= R2)
                i0++;
            while (i1 >= i0 && q[0][i1] + qyz >= R2)
                i1--;
            double eyz = coef * e[1][j] * e[2][k];
            size_t row = (size_t)lo[0] + (size_t)g->n[0] * ((size_t)(lo[1] + j) +
                                                            (size_t)g->n[1] * (size_t)(lo[2] + k));
            if (with_grad) {
                double gy = gf[1][j], gz = gf[2][k];
                for (int i = i0; i <= i1; i++) {
                    double v = e[0][i] * eyz;
                    dep_put_grad(ws, row + (size_t)i, v - sh, v * gf[0][i], v * gy, v * gz);
                }
            } else {
                for (int i = i0; i <= i1; i++)
                    dep_put(ws, row + (size_t)i, e[0][i] * eyz - sh);
            }
        }
    ws->has_grad = with_grad;
    return MIMAS_OK;
}

/* ---- segments ---------------------------------------------------------------------- */

/* The Gauss-Legendre rule for the uncut line integral over a branch of length l
 * (units of w): its nodes per piece and the pieces.  The relative error of the rule,
 * against 30-digit quadrature over every foot position that keeps both ends within the
 * cutoff, is below 3e-16 with these nodes: 8 up to l = 1 (cutoff <= 3; 0.75 up to
 * cutoff 5), 10 up to 1.5, 12 up to 2; longer branches in pieces of 1.5 with 10 each. */
static int line_rule(double l, double cutoff, const double **xs, const double **wsg,
                     int *pieces)
{
    *pieces = 1;
    if (l <= (cutoff <= 3.0 ? 1.0 : 0.75)) {
        *xs = gl8_x;
        *wsg = gl8_w;
        return 8;
    }
    *xs = gl10_x;
    *wsg = gl10_w;
    if (l <= 1.5)
        return 10;
    if (l <= 2.0) {
        *xs = gl12_x;
        *wsg = gl12_w;
        return 12;
    }
    *pieces = (int)ceil(l / 1.5);
    return 10;
}

/* The line integral where the cut ball about the cell centre cuts the segment (one end
 * inside, the other outside, or both outside and the segment crossing the ball): with t
 * the foot of the perpendicular along the branch from a, h^2 = e - t^2 its distance^2,
 * c = sqrt(R^2 - h^2) the chord's half-length, k = 1/(sqrt2 w), and
 * G(x) = e^{x^2 k^2} erf(x k), H(x) = e^{x^2 k^2} erfc(x k),
 *   e^{-h^2 k^2} erf(c k) = e^{-C^2/2} G(c),    e^{-h^2 k^2} erfc(c k) = e^{-C^2/2} H(c),
 *   e^{-h^2 k^2} erf(t k) = e^{-|r - a|^2 k^2} G(t) (and the same about b, with H too).
 * The chord [0, t + c] (a inside) holds the foot when t >= 0: psi = scale [e^{-C^2/2} G(c) +
 * e^{-|r-a|^2 k^2} G(t)], a sum of two positive terms; when t < 0 it lies beyond the foot,
 * where erf(c k) - erf(|t| k) would cancel (both near 1 far from the foot), and the tails
 * are used instead: psi = scale [e^{-|r-a|^2 k^2} H(|t|) - e^{-C^2/2} H(c)], each term below
 * e^{-|r-a|^2 k^2} (no large terms cancel).  The mirror image about b for [t - c, len];
 * 2 e^{-C^2/2} G(c) for [t - c, t + c].  G and H from the tables, the exponentials
 * separable.  scale = coef sqrt(pi/2) w / len; the error is a few ulp of the terms, which
 * carry the conditioning of e^{-h^2 k^2} itself (h^2 to rounding: C^2/2 ulp relative). */
typedef struct shell_consts {
    double R2, k, tail, scale, shift_scale; /* shift_scale = coef shift / len */
} shell_consts;

/* The chord from an end inside the ball to where the branch leaves it: t the foot from
 * that end (towards the other), e_end = e^{-|r - end|^2 k^2}. */
static inline double chord_from_end(const shell_consts *sc, double t, double c, double e_end)
{
    if (t >= 0)
        return sc->tail * g_eval(c * sc->k) + e_end * g_eval(t * sc->k);
    return e_end * h_eval(-t * sc->k) - sc->tail * h_eval(c * sc->k);
}

static inline double shell_cell(const shell_consts *sc, int a_in, int b_in, double t,
                                double e, double len, double ea, double eb)
{
    double h2 = e - t * t;
    if (h2 < 0)
        h2 = 0;
    if (h2 >= sc->R2)
        return 0.0;
    double c = sqrt(sc->R2 - h2), chord, v;
    if (a_in) {
        v = chord_from_end(sc, t, c, ea);
        chord = t + c;
    } else if (b_in) {
        v = chord_from_end(sc, len - t, c, eb);
        chord = len - t + c;
    } else if (t > 0 && t < len) {
        v = 2.0 * sc->tail * g_eval(c * sc->k);
        chord = 2.0 * c;
    } else {
        return 0.0;
    }
    return sc->scale * v - sc->shift_scale * chord;
}

enum { SEG_MAXNODE = 64 };

/* vrow[c] = sum_k f[k] ex[k n + c] for the cells c of [c0, c1) (c1 - c0 a multiple of 4) */
static inline __attribute__((always_inline)) void node_sums_n(const double *ex, size_t n,
                                                              const double *f, int nq, int c0,
                                                              int c1, double *vrow)
{
    for (int c = c0; c < c1; c += 4) {
#if defined(MIMAS_HAVE_V4D)
        v4d acc = {0, 0, 0, 0};
        for (int k = 0; k < nq; k++)
            acc += *(const v4d *)(ex + (size_t)k * n + c) * f[k];
        *(v4d *)(vrow + c) = acc;
#else
        for (int u = 0; u < 4; u++) {
            double acc = 0.0;
            for (int k = 0; k < nq; k++)
                acc += ex[(size_t)k * n + c + u] * f[k];
            vrow[c + u] = acc;
        }
#endif
    }
}

/* The same with the usual node counts known to the compiler (its loop unrolled). */
static inline void node_sums(const double *ex, size_t n, const double *f, int nq, int c0,
                             int c1, double *vrow)
{
    switch (nq) {
    case 8:
        node_sums_n(ex, n, f, 8, c0, c1, vrow);
        break;
    case 10:
        node_sums_n(ex, n, f, 10, c0, c1, vrow);
        break;
    case 12:
        node_sums_n(ex, n, f, 12, c0, c1, vrow);
        break;
    default:
        node_sums_n(ex, n, f, nq, c0, c1, vrow);
    }
}

/* A row of cells along x and the segment: what the distance from a cell centre to the
 * segment needs (the cell's offsets from a and b squared, along x and across). */
typedef struct row_geom {
    const double *qa0, *qb0, *dx0; /* per cell: (c - a_x)^2, (c - b_x)^2, c - a_x */
    double qay, qby, tyz;           /* across: |r - a|^2, |r - b|^2, (r - a).b */
    double bx, l2, inv_l2, R2;
} row_geom;

/* Whether cell i of the row is within R of the segment: its distance to the nearest
 * point, a, b or the foot of the perpendicular. */
static inline int within_reach(const row_geom *rg, int i)
{
    double t = rg->dx0[i] * rg->bx + rg->tyz, dist2;
    if (t <= 0)
        dist2 = rg->qa0[i] + rg->qay;
    else if (t >= rg->l2)
        dist2 = rg->qb0[i] + rg->qby;
    else
        dist2 = rg->qa0[i] + rg->qay - t * t * rg->inv_l2;
    return dist2 < rg->R2;
}

/* The cells [c0, c1] of the row (n cells) within R of the segment, given the position
 * xs (in cells from the first cell's centre) of the row's point nearest to it; 0 when
 * there are none.  The set is an interval holding xs: if it holds a cell, it holds the
 * nearest cell on that side of xs, so the two cells about xs decide. */
static inline int reach_span(const row_geom *rg, double xs, int n, int *c0, int *c1)
{
    double f = floor(xs);
    int s0 = f < 0 ? -1 : (f >= n ? n - 1 : (int)f), s;
    if (s0 >= 0 && within_reach(rg, s0))
        s = s0;
    else if (s0 + 1 < n && within_reach(rg, s0 + 1))
        s = s0 + 1;
    else
        return 0;
    int lo = s, hi = s;
    while (lo > 0 && within_reach(rg, lo - 1))
        lo--;
    while (hi < n - 1 && within_reach(rg, hi + 1))
        hi++;
    *c0 = lo;
    *c1 = hi;
    return 1;
}

/* The powers X_k^i (i < n) of the nq nodes' factors (nq a multiple of 4), four nodes at a
 * time: node-minor (p[i nq + k]) when n0p is 0, else node-major in rows of n0p, padded
 * with zeros (p[k n0p + i]).  Each power is the running product, as one node at a time. */
static inline void node_powers(const double *X, int nq, int n, int n0p, double *restrict p)
{
    for (int k = 0; k < nq; k += 4) {
#if defined(MIMAS_HAVE_V4D)
        /* the four running products in one register: node-minor rows are one store */
        v4d Xk = *(const v4d *)(X + k), v = {1.0, 1.0, 1.0, 1.0};
        for (int i = 0; i < n; i++) {
            if (n0p)
                for (int u = 0; u < 4; u++)
                    p[(size_t)(k + u) * n0p + i] = v[u];
            else
                *(v4d *)(p + (size_t)i * nq + k) = v;
            v *= Xk;
        }
#else
        double Xk[4] = {X[k], X[k + 1], X[k + 2], X[k + 3]}, v[4] = {1.0, 1.0, 1.0, 1.0};
        for (int i = 0; i < n; i++) {
            for (int u = 0; u < 4; u++) {
                if (n0p)
                    p[(size_t)(k + u) * n0p + i] = v[u];
                else
                    p[(size_t)i * nq + k + u] = v[u];
                v[u] *= Xk[u];
            }
        }
#endif
        for (int u = 0; n0p && u < 4; u++)
            for (int i = n; i < n0p; i++)
                p[(size_t)(k + u) * n0p + i] = 0.0;
    }
}

/* Per row j of a plane of the box (across x, offsets dz, squared offsets qaz, qbz from a
 * and b): |r - a|^2 and |r - b|^2 across x, (r - a).b across x, the parameter ty of the
 * segment's point nearest to the row in the y-z projection, and the row's squared
 * distance from that point.  The rows four at a time, each by the operations of one
 * row; n1p rows (the box's rows rounded up to 4: the last ones are not used, the
 * arrays read are followed by more of the scratch space). */
typedef struct plane_rows {
    double *qay, *qby, *tyz, *ty, *rr;
} plane_rows;

static inline void plane_rows_at(const double *dx1, const double *qa1, const double *qb1,
                                 double dz, double qaz, double qbz, const double bv[3],
                                 double inv_pyz, int n1p, const plane_rows *pr)
{
    double tz = dz * bv[2];
    for (int j = 0; j < n1p; j += 4) {
#if defined(MIMAS_HAVE_V4D)
        typedef long long v4l __attribute__((vector_size(32)));
        const v4d one = {1.0, 1.0, 1.0, 1.0};
        v4d y = *(const v4d *)(dx1 + j), tyz = y * bv[1] + tz, ty = tyz * inv_pyz;
        v4l below = ty < 0, above = ty > 1; /* ty < 0 ? 0 : (ty > 1 ? 1 : ty) */
        ty = (v4d)(((v4l)ty & ~(below | above)) | ((v4l)one & above));
        v4d ry = y - ty * bv[1], rz = dz - ty * bv[2];
        *(v4d *)(pr->qay + j) = *(const v4d *)(qa1 + j) + qaz;
        *(v4d *)(pr->qby + j) = *(const v4d *)(qb1 + j) + qbz;
        *(v4d *)(pr->tyz + j) = tyz;
        *(v4d *)(pr->ty + j) = ty;
        *(v4d *)(pr->rr + j) = ry * ry + rz * rz;
#else
        for (int u = j; u < j + 4; u++) {
            double tyz = dx1[u] * bv[1] + tz, ty = tyz * inv_pyz;
            ty = ty < 0 ? 0.0 : (ty > 1 ? 1.0 : ty);
            double ry = dx1[u] - ty * bv[1], rz = dz - ty * bv[2];
            pr->qay[u] = qa1[u] + qaz;
            pr->qby[u] = qb1[u] + qbz;
            pr->tyz[u] = tyz;
            pr->ty[u] = ty;
            pr->rr[u] = ry * ry + rz * rz;
        }
#endif
    }
}

/* ---- the line integral, twice: for any processor, and with AVX2 -------------------- */

#define SEG_FN mimas_gauss_segment_xyz_portable
#define SEG_AVX2 0
#include "deposit_gauss_segment.h"
#undef SEG_FN
#undef SEG_AVX2

#if MIMAS_X86_DISPATCH
#pragma GCC push_options
#pragma GCC target("avx2")

/* The cells where the cut ball cuts the segment, queued as the rows are classified (a row
 * has one or two at either end) and evaluated four at a time: each cell's index and what
 * shell_cell takes of it (|r - a|^2, |r - b|^2, the foot t, the Gaussian factors about a
 * and b). */
typedef struct cut_queue {
    size_t *cell;
    double *e, *qb, *t, *ea, *eb;
    int n;
} cut_queue;

static inline void cut_push(cut_queue *q, size_t cell, double e, double qb, double t, double ea,
                            double eb)
{
    int k = q->n++;
    q->cell[k] = cell;
    q->e[k] = e;
    q->qb[k] = qb;
    q->t[k] = t;
    q->ea[k] = ea;
    q->eb[k] = eb;
}

/* tab_eval at four arguments 0 <= x (lane by lane from H's table where h, else G's): the
 * same operations, the coefficients gathered. */
static inline __m256d tab_eval4(__m256d x, __m256d h)
{
    __m128i m = _mm256_cvttpd_epi32(_mm256_mul_pd(x, _mm256_set1_pd(64.0)));
    m = _mm_min_epi32(m, _mm_set1_epi32(GT_N - 1));
    __m256d mid = _mm256_mul_pd(_mm256_add_pd(_mm256_cvtepi32_pd(m), _mm256_set1_pd(0.5)),
                                _mm256_set1_pd(GT_DU));
    __m256d d = _mm256_sub_pd(x, mid);
    __m128i tab = _mm256_cvttpd_epi32(_mm256_and_pd(h, _mm256_set1_pd((double)GT_N)));
    __m128i row = _mm_mullo_epi32(_mm_add_epi32(m, tab), _mm_set1_epi32(GT_DEG + 1));
    const double *base = &ghtab[0][0][0];
    __m256d v = _mm256_i32gather_pd(base + GT_DEG, row, 8);
    for (int k = GT_DEG - 1; k >= 0; k--)
        v = _mm256_add_pd(_mm256_mul_pd(v, d), _mm256_i32gather_pd(base + k, row, 8));
    return v;
}

/* Evaluates the queued cells four at a time, shell_cell's operations lane by lane, and
 * puts those with a weight; a last group of fewer than four only when all (else it stays,
 * moved to the front). */
static void cut_flush4(cut_queue *q, const shell_consts *sc, double len, int all,
                       dep_cursor *cur)
{
    int n = q->n, done = all ? n : n & ~3;
    for (int m = n; all && (m & 3); m++) /* lanes that give 0: h^2 = R^2 */
        cut_push(q, 0, sc->R2, sc->R2, 0.0, 0.0, 0.0);
    const __m256d zero = _mm256_setzero_pd(), R2 = _mm256_set1_pd(sc->R2);
    const __m256d lenv = _mm256_set1_pd(len), k = _mm256_set1_pd(sc->k);
    const __m256d tail = _mm256_set1_pd(sc->tail), tail2 = _mm256_set1_pd(2.0 * sc->tail);
    const __m256d scale = _mm256_set1_pd(sc->scale), shs = _mm256_set1_pd(sc->shift_scale);
    for (int i = 0; i < done; i += 4) {
        __m256d e = _mm256_loadu_pd(q->e + i), qb = _mm256_loadu_pd(q->qb + i);
        __m256d t = _mm256_loadu_pd(q->t + i);
        __m256d h2 = _mm256_sub_pd(e, _mm256_mul_pd(t, t));
        h2 = _mm256_blendv_pd(h2, zero, _mm256_cmp_pd(h2, zero, _CMP_LT_OQ));
        __m256d valid = _mm256_cmp_pd(h2, R2, _CMP_LT_OQ), a_in = _mm256_cmp_pd(e, R2, _CMP_LT_OQ);
        __m256d end = _mm256_or_pd(a_in, _mm256_cmp_pd(qb, R2, _CMP_LT_OQ));
        __m256d across = _mm256_and_pd(_mm256_cmp_pd(t, zero, _CMP_GT_OQ),
                                       _mm256_cmp_pd(t, lenv, _CMP_LT_OQ));
        __m256d keep = _mm256_and_pd(valid, _mm256_or_pd(end, across));
        __m256d c = _mm256_sqrt_pd(_mm256_blendv_pd(zero, _mm256_sub_pd(R2, h2), valid));
        /* the foot from the end inside the ball (a's when both are), its factor */
        __m256d tp = _mm256_blendv_pd(_mm256_sub_pd(lenv, t), t, a_in);
        __m256d e_end = _mm256_blendv_pd(_mm256_loadu_pd(q->eb + i), _mm256_loadu_pd(q->ea + i),
                                         a_in);
        __m256d neg = _mm256_cmp_pd(tp, zero, _CMP_LT_OQ);
        __m256d abs_tp = _mm256_blendv_pd(tp, _mm256_xor_pd(tp, _mm256_set1_pd(-0.0)), neg);
        __m256d T1 = tab_eval4(_mm256_and_pd(keep, _mm256_mul_pd(c, k)), _mm256_and_pd(end, neg));
        __m256d T2 = tab_eval4(_mm256_and_pd(_mm256_and_pd(keep, end), _mm256_mul_pd(abs_tp, k)),
                               neg);
        __m256d sum = _mm256_add_pd(_mm256_mul_pd(tail, T1), _mm256_mul_pd(e_end, T2));
        __m256d tails = _mm256_sub_pd(_mm256_mul_pd(e_end, T2), _mm256_mul_pd(tail, T1));
        __m256d v = _mm256_blendv_pd(_mm256_mul_pd(tail2, T1), _mm256_blendv_pd(sum, tails, neg),
                                     end);
        __m256d chord = _mm256_blendv_pd(_mm256_mul_pd(_mm256_set1_pd(2.0), c),
                                         _mm256_add_pd(tp, c), end);
        __m256d w = _mm256_and_pd(keep, _mm256_sub_pd(_mm256_mul_pd(scale, v),
                                                      _mm256_mul_pd(shs, chord)));
        double wv[4];
        _mm256_storeu_pd(wv, w);
        for (int u = 0; u < 4 && i + u < n; u++)
            if (wv[u] != 0.0)
                dep_cursor_put(cur, q->cell[i + u], wv[u]);
    }
    q->n = 0; /* the rest to the front (done >= where each goes) */
    for (int m = done; m < n; m++)
        cut_push(q, q->cell[m], q->e[m], q->qb[m], q->t[m], q->ea[m], q->eb[m]);
}

/* Puts the cells of the bits of m (of the four from cell `first`): ayz ea vrow - sh, the
 * weights of uncut cells, four at a time; the selected lanes moved to the front (a
 * permutation per mask) and all four written, the cursor moved on by those selected (the
 * list has room for 4 more than its cells). */
static const int32_t put4_perm[16][8] = {
    {0, 1, 2, 3, 4, 5, 6, 7}, {0, 1, 2, 3, 4, 5, 6, 7}, {2, 3, 0, 1, 4, 5, 6, 7},
    {0, 1, 2, 3, 4, 5, 6, 7}, {4, 5, 0, 1, 2, 3, 6, 7}, {0, 1, 4, 5, 2, 3, 6, 7},
    {2, 3, 4, 5, 0, 1, 6, 7}, {0, 1, 2, 3, 4, 5, 6, 7}, {6, 7, 0, 1, 2, 3, 4, 5},
    {0, 1, 6, 7, 2, 3, 4, 5}, {2, 3, 6, 7, 0, 1, 4, 5}, {0, 1, 2, 3, 6, 7, 4, 5},
    {4, 5, 6, 7, 0, 1, 2, 3}, {0, 1, 4, 5, 6, 7, 2, 3}, {2, 3, 4, 5, 6, 7, 0, 1},
    {0, 1, 2, 3, 4, 5, 6, 7}};

static inline void put4(dep_cursor *cur, size_t first, int m, double ayz, const double *ea,
                        const double *vrow, double sh)
{
    __m256d w = _mm256_sub_pd(_mm256_mul_pd(_mm256_mul_pd(_mm256_set1_pd(ayz),
                                                          _mm256_loadu_pd(ea)),
                                            _mm256_loadu_pd(vrow)),
                              _mm256_set1_pd(sh));
    __m256i cell = _mm256_add_epi64(_mm256_set1_epi64x((long long)first),
                                    _mm256_setr_epi64x(0, 1, 2, 3));
    __m256i p = _mm256_loadu_si256((const __m256i *)put4_perm[m]);
    _mm256_storeu_pd(cur->w, _mm256_castps_pd(_mm256_permutevar8x32_ps(_mm256_castpd_ps(w), p)));
    _mm256_storeu_si256((__m256i *)cur->cell, _mm256_permutevar8x32_epi32(cell, p));
    int k = __builtin_popcount((unsigned)m);
    cur->w += k;
    cur->cell += k;
}

/* Queues the cells of the bits of m (of the four from cell `first` of a row): what
 * shell_cell takes of each, |r - a|^2 = qa + qay, |r - b|^2 = qb + qby, the foot
 * (dx b_x + tyz) / len and the factors ea eayz, eb ebyz, four at a time (the same
 * operations as cut_push's callers lane by lane), the selected lanes moved to the front
 * and all four written (the queue has room for 4 more than a row's cells). */
static inline void cut_push4(cut_queue *q, size_t first, int m, const double *qa,
                             const double *qb, const double *dx, const double *ea,
                             const double *eb, double qay, double qby, double bx, double tyz,
                             double inv_len, double eayz, double ebyz)
{
    __m256i p = _mm256_loadu_si256((const __m256i *)put4_perm[m]);
#define CUT_STORE(dst, v)                                                                         \
    _mm256_storeu_pd((dst) + q->n,                                                            \
                     _mm256_castps_pd(_mm256_permutevar8x32_ps(_mm256_castpd_ps(v), p)))
    __m256d t = _mm256_add_pd(_mm256_mul_pd(_mm256_loadu_pd(dx), _mm256_set1_pd(bx)),
                              _mm256_set1_pd(tyz));
    CUT_STORE(q->e, _mm256_add_pd(_mm256_loadu_pd(qa), _mm256_set1_pd(qay)));
    CUT_STORE(q->qb, _mm256_add_pd(_mm256_loadu_pd(qb), _mm256_set1_pd(qby)));
    CUT_STORE(q->t, _mm256_mul_pd(t, _mm256_set1_pd(inv_len)));
    CUT_STORE(q->ea, _mm256_mul_pd(_mm256_loadu_pd(ea), _mm256_set1_pd(eayz)));
    CUT_STORE(q->eb, _mm256_mul_pd(_mm256_loadu_pd(eb), _mm256_set1_pd(ebyz)));
#undef CUT_STORE
    __m256i cell = _mm256_add_epi64(_mm256_set1_epi64x((long long)first),
                                    _mm256_setr_epi64x(0, 1, 2, 3));
    _mm256_storeu_si256((__m256i *)(q->cell + q->n), _mm256_permutevar8x32_epi32(cell, p));
    q->n += __builtin_popcount((unsigned)m);
}

/* What row_classify4 takes, in every lane: the segment's (b_x, |b|^2, 1/|b|^2, R^2) and
 * the row's (across x: (r - a).b, |r - a|^2, |r - b|^2, R^2 less the latter two). */
typedef struct row_reach4 {
    __m256d bx, l2, inv_l2, R2, tyz, qay, qby, ra, rb;
} row_reach4;

static inline row_reach4 row_reach4_at(double bx, double l2, double inv_l2, double R2)
{
    __m256d z = _mm256_setzero_pd();
    return (row_reach4){_mm256_set1_pd(bx), _mm256_set1_pd(l2), _mm256_set1_pd(inv_l2),
                        _mm256_set1_pd(R2), z, z, z, z, z};
}

static inline void row_reach4_across(row_reach4 *rr, double qay, double qby, double tyz,
                                     double R2)
{
    rr->tyz = _mm256_set1_pd(tyz);
    rr->qay = _mm256_set1_pd(qay);
    rr->qby = _mm256_set1_pd(qby);
    rr->ra = _mm256_set1_pd(R2 - qay);
    rr->rb = _mm256_set1_pd(R2 - qby);
}

/* Four cells of a row (their offsets dx from a along x, squared offsets qa, qb from a and b
 * along x): the bits of those within R of the segment (returned) and, of those, of the
 * ones with the whole segment within R (*uncut).  With t = (r - a).b the distance^2 is
 * |r - a|^2 for t <= 0, |r - b|^2 for t >= |b|^2, else |r - a|^2 - t^2/|b|^2; whole when
 * (c - a_x)^2 < R^2 - |r - a|^2 across x and the same about b.  The cells past the row's
 * end have dx = 0 and qa = qb = infinity: never within R. */
static inline int row_classify4(const row_reach4 *rr, const double *dx, const double *qa,
                                const double *qb, int *uncut)
{
    __m256d A = _mm256_loadu_pd(qa), B = _mm256_loadu_pd(qb);
    __m256d t = _mm256_add_pd(_mm256_mul_pd(_mm256_loadu_pd(dx), rr->bx), rr->tyz);
    __m256d qai = _mm256_add_pd(A, rr->qay);
    __m256d d2 = _mm256_sub_pd(qai, _mm256_mul_pd(_mm256_mul_pd(t, t), rr->inv_l2));
    d2 = _mm256_blendv_pd(d2, _mm256_add_pd(B, rr->qby), _mm256_cmp_pd(t, rr->l2, _CMP_GE_OQ));
    d2 = _mm256_blendv_pd(d2, qai, _mm256_cmp_pd(t, _mm256_setzero_pd(), _CMP_LE_OQ));
    __m256d within = _mm256_cmp_pd(d2, rr->R2, _CMP_LT_OQ);
    __m256d whole = _mm256_and_pd(_mm256_cmp_pd(A, rr->ra, _CMP_LT_OQ),
                                  _mm256_cmp_pd(B, rr->rb, _CMP_LT_OQ));
    *uncut = _mm256_movemask_pd(_mm256_and_pd(within, whole));
    return _mm256_movemask_pd(within);
}

#define SEG_FN segment_xyz_avx2
#define SEG_AVX2 1
#include "deposit_gauss_segment.h"
#undef SEG_FN
#undef SEG_AVX2
#pragma GCC pop_options
#endif

int mimas_gauss_segment_xyz(const mimas_deposit *dp, const double a[3], const double b[3],
                            mimas_weights *ws)
{
#if MIMAS_X86_DISPATCH
    if (__builtin_cpu_supports("avx2"))
        return segment_xyz_avx2(dp, a, b, ws);
#endif
    return mimas_gauss_segment_xyz_portable(dp, a, b, ws);
}

void mimas_gauss_tables(void)
{
    pthread_once(&gtab_once, gtab_setup);
}
