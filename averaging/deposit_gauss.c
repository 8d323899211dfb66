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
#include "lanes_x86.h"

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

/* What a particle's cells need, per direction d of its box of cells (len[d] from lo[d]):
 * the Gaussian's factors e[d], the squared offsets q[d] of the cell centres from the
 * particle and the gradient's factors gf[d] = -(c - x)/w^2.  Along x (the rows) the three
 * arrays are padded to whole vectors of the build (deposit_gauss_sphere.h): q with
 * +infinity (outside the ball), e and gf with zeros. */
typedef struct sphere_box {
    int lo[3], len[3];
    double *e[3], *q[3], *gf[3];
} sphere_box;

/* The box of cells a particle at x may reach and its factors, the list with room for
 * every cell of the box and `lanes` more; 1 when the particle reaches no cell, MIMAS_EIO
 * when out of memory. */
static inline int sphere_setup(const mimas_deposit *dp, const double x[3], int lanes,
                               mimas_weights *ws, sphere_box *sb)
{
    const mimas_weight *wt = dp->wt;
    int hi[3];
    if (!dep_candidate_box(dp, x, mimas_weight_reach(wt), sb->lo, hi))
        return 1;
    for (int d = 0; d < 3; d++)
        sb->len[d] = hi[d] - sb->lo[d] + 1;
    if (mimas_weights_reserve(ws, (size_t)sb->len[0] * sb->len[1] * sb->len[2] + lanes))
        return MIMAS_EIO;
    int x_room = (sb->len[0] + lanes - 1) / lanes * lanes; /* along x: whole vectors */
    int room[3] = {x_room, sb->len[1], sb->len[2]};
    size_t total = (size_t)room[0] + room[1] + room[2];
    double *buf = mimas_weights_scratch(ws, 3 * total);
    if (!buf)
        return MIMAS_EIO;
    for (int d = 0, off = 0; d < 3; d++) {
        sb->e[d] = buf + off;
        sb->q[d] = buf + total + off;
        sb->gf[d] = buf + 2 * total + off;
        off += room[d];
        for (int i = 0; i < sb->len[d]; i++) {
            double dd = dep_centre(dp, d, sb->lo[d] + i) - x[d];
            sb->q[d][i] = dd * dd;
            sb->gf[d][i] = -2.0 * wt->inv2w2 * dd;
        }
        gauss_row(dp, d, sb->lo[d], sb->len[d], x[d], sb->e[d]);
        for (int i = sb->len[d]; i < room[d]; i++) {
            sb->q[d][i] = INFINITY;
            sb->e[d][i] = sb->gf[d][i] = 0.0;
        }
    }
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
#define SEG_LANES 1
#include "deposit_gauss_segment.h"
#define SPH_FN mimas_gauss_sphere_xyz_portable
#include "deposit_gauss_sphere.h"
#undef SPH_FN
#undef SEG_FN
#undef SEG_LANES

/* The cells where the cut ball cuts the segment, queued as the rows are classified (a row
 * has one or two at either end) and evaluated several at a time (the vector builds'
 * cut_flush4, cut_flush8): each cell's index and what shell_cell takes of it (|r - a|^2,
 * |r - b|^2, the foot t, the Gaussian factors about a and b). */
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

/* What the vector builds' row_classify takes: the segment's b_x, |b|^2, 1/|b|^2 and R^2,
 * and the row's (across x: (r - a).b, |r - a|^2, |r - b|^2, R^2 less the latter two). */
typedef struct row_reach {
    double bx, l2, inv_l2, R2, tyz, qay, qby, ra, rb;
} row_reach;

static inline void row_reach_across(row_reach *rr, double qay, double qby, double tyz)
{
    rr->tyz = tyz;
    rr->qay = qay;
    rr->qby = qby;
    rr->ra = rr->R2 - qay;
    rr->rb = rr->R2 - qby;
}

/* the helper f of the build of SEG_LANES lanes (f4, f8), and the names
 * deposit_gauss_lanes.h takes (lanes_x86.h's lane_v4, lane_bits4, ..., and the packs
 * below, or the same with 8) */
#define SEG_CAT_(f, n) f##n
#define SEG_CAT(f, n) SEG_CAT_(f, n)
#define SEG_V(f) SEG_CAT(f, SEG_LANES)
#define SEG_VT SEG_V(lane_v)
#define SEG_MT SEG_V(lane_m)
#define SEG_IT SEG_V(lane_i)
#define SEG_BITS SEG_V(lane_bits)
#define SEG_SEL SEG_V(lane_sel)
#define SEG_GATHER SEG_V(lane_gather)
#define SEG_SQRT SEG_V(lane_sqrt)
#define SEG_PACK SEG_V(seg_pack)
#define SEG_PACK_CELLS SEG_V(seg_pack_cells)
#define SEG_PACK_RUN SEG_V(seg_pack_run)

#if MIMAS_X86_DISPATCH
/* The vector builds: deposit_gauss_lanes.h's helpers with four lanes (AVX2) and with eight
 * (AVX-512; a row of a kernel of w = h and cutoff 3 has eight cells or fewer), then the
 * line integral that calls them. */
#pragma GCC push_options
#pragma GCC target("avx2")
/* The lanes of the bits of m moved to the front: a permutation of 32-bit halves per mask */
static const int32_t pack4_perm[16][8] = {
    {0, 1, 2, 3, 4, 5, 6, 7}, {0, 1, 2, 3, 4, 5, 6, 7}, {2, 3, 0, 1, 4, 5, 6, 7},
    {0, 1, 2, 3, 4, 5, 6, 7}, {4, 5, 0, 1, 2, 3, 6, 7}, {0, 1, 4, 5, 2, 3, 6, 7},
    {2, 3, 4, 5, 0, 1, 6, 7}, {0, 1, 2, 3, 4, 5, 6, 7}, {6, 7, 0, 1, 2, 3, 4, 5},
    {0, 1, 6, 7, 2, 3, 4, 5}, {2, 3, 6, 7, 0, 1, 4, 5}, {0, 1, 2, 3, 6, 7, 4, 5},
    {4, 5, 6, 7, 0, 1, 2, 3}, {0, 1, 4, 5, 6, 7, 2, 3}, {2, 3, 4, 5, 6, 7, 0, 1},
    {0, 1, 2, 3, 4, 5, 6, 7}};

static inline void seg_pack4(double *dst, lane_v4 v, int m)
{
    __m256i p = _mm256_loadu_si256((const __m256i *)pack4_perm[m]);
    __m256 x = _mm256_castpd_ps((__m256d)v);
    _mm256_storeu_pd(dst, _mm256_castps_pd(_mm256_permutevar8x32_ps(x, p)));
}

static inline void seg_pack_i4(size_t *dst, __m256i c, int m)
{
    __m256i p = _mm256_loadu_si256((const __m256i *)pack4_perm[m]);
    _mm256_storeu_si256((__m256i *)dst, _mm256_permutevar8x32_epi32(c, p));
}

static inline void seg_pack_cells4(size_t *dst, const size_t *cell, int m)
{
    seg_pack_i4(dst, _mm256_loadu_si256((const __m256i *)cell), m);
}

static inline void seg_pack_run4(size_t *dst, size_t first, int m)
{
    seg_pack_i4(dst, _mm256_add_epi64(_mm256_set1_epi64x((long long)first),
                                      _mm256_setr_epi64x(0, 1, 2, 3)), m);
}

#define SEG_LANES 4
#include "deposit_gauss_lanes.h"
#define SEG_FN mimas_gauss_segment_xyz_avx2
#include "deposit_gauss_segment.h"
#define SPH_FN mimas_gauss_sphere_xyz_avx2
#include "deposit_gauss_sphere.h"
#undef SPH_FN
#undef SEG_FN
#undef SEG_LANES
#pragma GCC pop_options

#pragma GCC push_options
#pragma GCC target("avx2,avx512f")
static inline void seg_pack8(double *dst, lane_v8 v, int m)
{
    _mm512_storeu_pd(dst, _mm512_maskz_compress_pd((__mmask8)m, (__m512d)v));
}

static inline void seg_pack_cells8(size_t *dst, const size_t *cell, int m)
{
    _mm512_storeu_si512(dst, _mm512_maskz_compress_epi64((__mmask8)m, _mm512_loadu_si512(cell)));
}

static inline void seg_pack_run8(size_t *dst, size_t first, int m)
{
    __m512i c = _mm512_add_epi64(_mm512_set1_epi64((long long)first),
                                 _mm512_setr_epi64(0, 1, 2, 3, 4, 5, 6, 7));
    _mm512_storeu_si512(dst, _mm512_maskz_compress_epi64((__mmask8)m, c));
}

#define SEG_LANES 8
#include "deposit_gauss_lanes.h"
#define SEG_FN mimas_gauss_segment_xyz_avx512
#include "deposit_gauss_segment.h"
#define SPH_FN mimas_gauss_sphere_xyz_avx512
#include "deposit_gauss_sphere.h"
#undef SPH_FN
#undef SEG_FN
#undef SEG_LANES
#pragma GCC pop_options
#endif

int mimas_gauss_sphere_xyz(const mimas_deposit *dp, const double x[3], int with_grad,
                           mimas_weights *ws)
{
#if MIMAS_X86_DISPATCH
    if (__builtin_cpu_supports("avx512f"))
        return mimas_gauss_sphere_xyz_avx512(dp, x, with_grad, ws);
    if (__builtin_cpu_supports("avx2"))
        return mimas_gauss_sphere_xyz_avx2(dp, x, with_grad, ws);
#endif
    return mimas_gauss_sphere_xyz_portable(dp, x, with_grad, ws);
}

int mimas_gauss_segment_xyz(const mimas_deposit *dp, const double a[3], const double b[3],
                            mimas_weights *ws)
{
#if MIMAS_X86_DISPATCH
    if (__builtin_cpu_supports("avx512f"))
        return mimas_gauss_segment_xyz_avx512(dp, a, b, ws);
    if (__builtin_cpu_supports("avx2"))
        return mimas_gauss_segment_xyz_avx2(dp, a, b, ws);
#endif
    return mimas_gauss_segment_xyz_portable(dp, a, b, ws);
}

void mimas_gauss_tables(void)
{
    pthread_once(&gtab_once, gtab_setup);
}
