/* The Gaussian on Cartesian x-y-z grids, separable (docs/fields.md, "The line
 * integral"; docs/theory.md §6): a particle is a product of three rows of 1-D
 * factors inside the cut ball; a contact's line integral is, where the whole
 * branch lies within the cutoff of the cell centre, a Gauss-Legendre sum whose
 * every node is such a product, and where the cut ball cuts the branch a closed
 * form in e^{u^2} erf(u) (from a table) and separable exponentials. */
#include <config.h>

#include <math.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>

#include "deposit_impl.h"
#include "gauss_legendre.h"
#include "simd.h"

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
static double gtab[GT_N][GT_DEG + 1], htab[GT_N][GT_DEG + 1];
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
        taylor_row(uc, e * erf(uc), 1.0, gtab[m]);
        taylor_row(uc, e * erfc(uc), -1.0, htab[m]);
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
    return tab_eval(gtab, u);
}

/* H(u) for 0 <= u < 4 */
static inline double h_eval(double u)
{
    return tab_eval(htab, u);
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

/* The uncut part: with d = r - a (the cell centre from a), node s of the rule and
 * k = 1/2w^2,
 *   e^{-|d - s b|^2 k} = e^{-|d|^2 k} e^{(2 s d_0.b - s^2 |b|^2) k} prod_x X_x(s)^{i_x},
 * d_0 the offset of the first cell of the box, i_x the cell's index in it and
 * X_x(s) = e^{2 s b_x h_x k}: per node one exponential and one per direction, the
 * powers by products.  The rows along x are summed 4 cells at a time over the nodes. */
MIMAS_SIMD
int mimas_gauss_segment_xyz(const mimas_deposit *dp, const double a[3], const double b[3],
                            mimas_weights *ws)
{
    const mimas_weight *wt = dp->wt;
    const mimas_grid *g = dp->grid;
    double bv[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    double l2 = bv[0] * bv[0] + bv[1] * bv[1] + bv[2] * bv[2], len = sqrt(l2);
    double R = mimas_weight_reach(wt), R2 = wt->reach2, kap = wt->inv2w2;
    if (!(len > 0) || wt->cutoff > 5.0)
        return -1;
    /* the cells within R of the segment's bounding box */
    int lo[3], hi[3], n[3];
    for (int d = 0; d < 3; d++) {
        double lo_d = a[d] < b[d] ? a[d] : b[d], hi_d = a[d] < b[d] ? b[d] : a[d];
        if (!dep_index_range(dp, d, lo_d - R, hi_d + R, &lo[d], &hi[d]))
            return MIMAS_OK;
        n[d] = hi[d] - lo[d] + 1;
    }
    const double *xs, *wsg;
    int pieces, per = line_rule(len / wt->w, wt->cutoff, &xs, &wsg, &pieces);
    int nq = per * pieces, nqp = (nq + 3) & ~3, n0p = (n[0] + 3) & ~3;
    if (nq > SEG_MAXNODE)
        return -1;
    double tau0 = 0.0; /* d_0.b */
    for (int d = 0; d < 3; d++)
        tau0 += (dep_centre(dp, d, lo[d]) - a[d]) * bv[d];
    /* the largest exponent of the factors: beyond the range of doubles, cell by cell */
    double big = fabs(2.0 * tau0 * kap) + l2 * kap;
    for (int d = 0; d < 3; d++) {
        double d0 = dep_centre(dp, d, lo[d]) - a[d];
        big += fabs(2.0 * bv[d] * dp->h[d] * kap) * n[d] + fabs(2.0 * bv[d] * d0 * kap);
    }
    if (big > 600.0)
        return -1;
    if (mimas_weights_reserve(ws, (size_t)n[0] * n[1] * n[2]))
        return MIMAS_EIO;
    /* per direction: offsets from a, squared offsets from a and b, the Gaussian factors
     * about a and b; the nodes' powers X^i: x node-major (rows padded to 4), y and z
     * node-minor; the row's sums; the row scalars of a plane (plane_rows_at) */
    size_t total = (size_t)n[0] + n[1] + n[2];
    int n1p = (n[1] + 3) & ~3;
    size_t nbuf = 5 * total + (size_t)nqp * ((size_t)n0p + n[1] + n[2]) + (size_t)n0p +
                  5 * (size_t)n1p;
    double *buf = mimas_weights_scratch(ws, nbuf);
    if (!buf)
        return MIMAS_EIO;
    double *dx[3], *qa[3], *qb[3], *ea[3], *eb[3];
    double sq[SEG_MAXNODE], wq[SEG_MAXNODE], eyz[SEG_MAXNODE];
    for (int p = 0, k = 0; p < pieces; p++)
        for (int m = 0; m < per; m++, k++) {
            gl_node(xs, wsg, per, m, (double)p / pieces, (double)(p + 1) / pieces, &sq[k], &wq[k]);
            wq[k] *= exp((2.0 * sq[k] * tau0 - sq[k] * sq[k] * l2) * kap);
        }
    for (int k = nq; k < nqp; k++)
        sq[k] = wq[k] = 0.0;
    double *ex0 = buf + 5 * total, *exy = ex0 + (size_t)nqp * n0p, *exz = exy + (size_t)nqp * n[1];
    double *restrict vrow = exz + (size_t)nqp * n[2];
    double *pbuf = vrow + n0p;
    plane_rows pr = {pbuf, pbuf + n1p, pbuf + 2 * n1p, pbuf + 3 * n1p, pbuf + 4 * n1p};
    for (int d = 0, o = 0; d < 3; d++) {
        dx[d] = buf + o;
        qa[d] = buf + total + o;
        qb[d] = buf + 2 * total + o;
        ea[d] = buf + 3 * total + o;
        eb[d] = buf + 4 * total + o;
        for (int i = 0; i < n[d]; i++) {
            double c = dep_centre(dp, d, lo[d] + i), da = c - a[d], db = c - b[d];
            dx[d][i] = da;
            qa[d][i] = da * da;
            qb[d][i] = db * db;
        }
        gauss_row(dp, d, lo[d], n[d], a[d], ea[d]);
        /* X(s) for the node pairs s = c_p -+ x_m of each piece p: e^{c_p beta} e^{-+x_m beta},
         * one exponential per piece and per pair */
        double beta = 2.0 * bv[d] * dp->h[d] * kap, X[SEG_MAXNODE];
        int half = per / 2;
        for (int p = 0; p < pieces; p++) {
            double cp = exp((p + 0.5) / pieces * beta);
            for (int m = 0; m < half; m++) {
                double xm = exp(0.5 / pieces * xs[m] * beta);
                X[p * per + m] = cp / xm;        /* gl_node: the first half are the -x_m */
                X[p * per + half + m] = cp * xm;
            }
        }
        for (int k = nq; k < nqp; k++)
            X[k] = 0.0;
        node_powers(X, nqp, n[d], d == 0 ? n0p : 0, d == 0 ? ex0 : (d == 1 ? exy : exz));
        gauss_row(dp, d, lo[d], n[d], b[d], eb[d]);
        o += n[d];
    }
    dep_cursor cur = dep_cursor_at(ws);
    double coef = wt->coef, sh = coef * wt->shift, pyz = bv[1] * bv[1] + bv[2] * bv[2];
    double inv_l2 = 1.0 / l2, inv_len = 1.0 / len, inv_pyz = pyz > 0 ? 1.0 / pyz : 0.0;
    shell_consts sc = {R2, 1.0 / (M_SQRT2 * wt->w), wt->tail,
                       coef * sqrt(M_PI / 2.0) * wt->w / len, coef * wt->shift / len};
    for (int kz = 0; kz < n[2]; kz++) {
        size_t plane = (size_t)lo[0] + (size_t)g->n[0] * (size_t)g->n[1] * (size_t)(lo[2] + kz);
        plane_rows_at(dx[1], qa[1], qb[1], dx[2][kz], qa[2][kz], qb[2][kz], bv, inv_pyz, n1p, &pr);
        for (int j = 0; j < n[1]; j++) {
            /* the row (a line along x) is out of reach when the segment's projection
             * on the y-z plane stays R or more from the row's (y, z) */
            if (pr.rr[j] >= R2)
                continue;
            double qay = pr.qay[j], qby = pr.qby[j], tyz = pr.tyz[j], ty = pr.ty[j];
            size_t row = plane + (size_t)g->n[0] * (size_t)(lo[1] + j);
            /* The cells within R of the segment form an interval of the row (the
             * distance to a segment is convex along a line), holding the point nearest
             * to the segment, x = a + ty b: walk out from the cells on either side of
             * it.  The cells with the whole segment within R (the two balls'
             * intersection) are an interval inside it. */
            row_geom rg = {qa[0], qb[0], dx[0], qay, qby, tyz, bv[0], l2, inv_l2, R2};
            int c0, c1;
            if (!reach_span(&rg, (ty * bv[0] - dx[0][0]) / dp->h[0], n[0], &c0, &c1))
                continue;
            double ra = R2 - qay, rb = R2 - qby;
            int i0 = c0, i1 = c1;
            while (i0 <= i1 && !(qa[0][i0] < ra && qb[0][i0] < rb))
                i0++;
            while (i1 >= i0 && !(qa[0][i1] < ra && qb[0][i1] < rb))
                i1--;
            if (i0 <= i1) {
                /* the uncut line integral, 4 cells at a time over the nodes */
                const double *ey = exy + (size_t)j * nqp, *ez = exz + (size_t)kz * nqp;
                for (int k = 0; k < nqp; k++)
                    eyz[k] = wq[k] * ey[k] * ez[k];
                node_sums(ex0, (size_t)n0p, eyz, nq, i0 & ~3, (i1 + 4) & ~3, vrow);
                double ayz = coef * ea[1][j] * ea[2][kz];
                for (int i = i0; i <= i1; i++)
                    dep_cursor_put(&cur, row + (size_t)i, ayz * ea[0][i] * vrow[i] - sh);
            } else {
                i0 = c1 + 1; /* no such cells: every cell of [c0, c1] is cut */
                i1 = c1;
            }
            /* the others, where the cut ball cuts the segment: [c0, i0) and (i1, c1] */
            double ebyz = eb[1][j] * eb[2][kz], eayz = ea[1][j] * ea[2][kz];
            for (int i = c0; i <= c1; i++) {
                if (i == i0) {
                    i = i1;
                    continue;
                }
                double qai = qa[0][i] + qay, qbi = qb[0][i] + qby;
                double t = dx[0][i] * bv[0] + tyz;
                double v = shell_cell(&sc, qai < R2, qbi < R2, t * inv_len, qai, len,
                                      ea[0][i] * eayz, eb[0][i] * ebyz);
                if (v != 0.0)
                    dep_cursor_put(&cur, row + (size_t)i, v);
            }
        }
    }
    dep_cursor_done(ws, &cur);
    return MIMAS_OK;
}

void mimas_gauss_tables(void)
{
    pthread_once(&gtab_once, gtab_setup);
}
