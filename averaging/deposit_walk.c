/* Bins on a Cartesian grid: a segment walked through the cells (docs/fields.md, "Bins").
 * The grid's planes along d are P_0 = lo, P_k = lo + k h (0 < k < n) and P_n = hi, the
 * cells' own faces.  The segment from a to b crosses them at t = (P_k - a_d) / (b_d - a_d);
 * between two crossings it lies in one cell, whose index changes by one along the
 * direction of the plane crossed (the next crossings of the three directions merged in
 * order along the segment: Amanatides and Woo, "A fast voxel traversal algorithm for ray
 * tracing", 1987).  Every piece in the grid gets its exact length fraction, the pieces add
 * up to the part of the segment on the grid, and the parts off it (index -1 or n along
 * some direction) are left out. */
#include <config.h>

#include <math.h>

#include "deposit_impl.h"

/* Plane k along d (0 <= k <= n) */
static inline double plane(const mimas_grid *g, const double *h, int d, int k)
{
    return k == g->n[d] ? g->hi[d] : g->lo[d] + h[d] * k;
}

/* The cell along d of the points just above x (up) or just below it: the k with
 * P_k <= x < P_{k+1} (up) or P_k < x <= P_{k+1}; -1 below the grid, n above it.  The
 * guess from x's offset is corrected against the planes themselves, so that the index
 * agrees with the crossings, which are computed from them. */
static inline int cell_along(const mimas_deposit *dp, int d, double x, int up)
{
    const mimas_grid *g = dp->grid;
    int n = g->n[d];
    if (!(up ? x >= g->lo[d] : x > g->lo[d])) /* (NaN too: on no grid) */
        return -1;
    if (up ? x >= g->hi[d] : x > g->hi[d])
        return n;
    double f = (x - g->lo[d]) * dp->inv_h[d]; /* >= 0: truncation is floor */
    int k = f > n - 1 ? n - 1 : (int)f;
    while (k > 0 && (up ? plane(g, dp->h, d, k) > x : plane(g, dp->h, d, k) >= x))
        k--;
    while (k < n - 1 && (up ? plane(g, dp->h, d, k + 1) <= x : plane(g, dp->h, d, k + 1) < x))
        k++;
    return k;
}

/* The parameter where the segment leaves cell idx along d (step +-1; 0: never), or
 * infinity when b lies before that plane (or on it) or the cell is off the grid's end. */
static inline double next_crossing(const mimas_grid *g, const double *h, int d, int idx,
                                   int step, double a, double b, double len)
{
    if (step > 0) {
        if (idx >= g->n[d])
            return INFINITY;
        double p = plane(g, h, d, idx + 1);
        return p < b ? (p - a) / len : INFINITY;
    }
    if (step < 0) {
        if (idx < 0)
            return INFINITY;
        double p = plane(g, h, d, idx);
        return p > b ? (p - a) / len : INFINITY;
    }
    return INFINITY;
}

int dep_walk_segment(const mimas_deposit *dp, const double a[3], const double b[3],
                     mimas_weights *ws)
{
    const mimas_grid *g = dp->grid;
    const double *h = dp->h;
    int idx[3], step[3];
    double tnext[3], len[3], pieces = 1;
    for (int d = 0; d < 3; d++) {
        len[d] = b[d] - a[d];
        step[d] = len[d] > 0 ? 1 : (len[d] < 0 ? -1 : 0);
        if (step[d])
            idx[d] = cell_along(dp, d, a[d], step[d] > 0);
        else /* in the plane x_d = a_d: the cell holding it, the last one at hi */
            idx[d] = a[d] == g->hi[d] ? g->n[d] - 1 : cell_along(dp, d, a[d], 1);
        tnext[d] = next_crossing(g, h, d, idx[d], step[d], a[d], b[d], len[d]);
        pieces += fabs(len[d]) * dp->inv_h[d] + 2; /* at least the planes crossed */
    }
    if (isnan(pieces)) /* a position that is not a number: on no grid */
        return MIMAS_OK;
    if (!(pieces < 1e9) || mimas_weights_reserve(ws, (size_t)pieces))
        return MIMAS_EIO;
    size_t sy = (size_t)g->n[0], sz = sy * (size_t)g->n[1];
    double t = 0.0;
    for (;;) {
        int d = tnext[0] <= tnext[1] ? (tnext[0] <= tnext[2] ? 0 : 2)
                                     : (tnext[1] <= tnext[2] ? 1 : 2);
        double t1 = tnext[d] < 1.0 ? tnext[d] : 1.0;
        if (t1 > t && (unsigned)idx[0] < (unsigned)g->n[0] &&
            (unsigned)idx[1] < (unsigned)g->n[1] && (unsigned)idx[2] < (unsigned)g->n[2])
            dep_put(ws, (size_t)idx[0] + sy * (size_t)idx[1] + sz * (size_t)idx[2],
                    (t1 - t) / dp->cart_volume);
        if (!(tnext[d] < 1.0))
            break;
        t = t1;
        idx[d] += step[d];
        tnext[d] = next_crossing(g, h, d, idx[d], step[d], a[d], b[d], len[d]);
    }
    return MIMAS_OK;
}
