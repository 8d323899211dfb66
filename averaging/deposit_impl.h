/* Internal to the deposits (deposit.c, deposit_gauss.c): the weight list's
 * storage, the grid's cells and the Gaussian's separable fast paths on x-y-z
 * grids. */
#ifndef MIMAS_DEPOSIT_IMPL_H
#define MIMAS_DEPOSIT_IMPL_H

#include <math.h>
#include <stddef.h>

#include "deposit.h"

/* Room for k more entries; MIMAS_EIO when out of memory. */
int mimas_weights_reserve(mimas_weights *ws, size_t k);
/* n doubles of scratch space kept with the list (NULL when out of memory). */
double *mimas_weights_scratch(mimas_weights *ws, size_t n);

static inline void dep_put(mimas_weights *ws, size_t cell, double w)
{
    ws->cell[ws->n] = cell;
    ws->w[ws->n] = w;
    ws->n++;
}

static inline void dep_put_grad(mimas_weights *ws, size_t cell, double w, double g0, double g1,
                                double g2)
{
    double *g = ws->grad + ws->n;
    g[0] = g0;
    g[ws->cap] = g1;
    g[2 * ws->cap] = g2;
    dep_put(ws, cell, w);
}

/* A write position in the list for a loop that puts many entries: its pointers stay in
 * registers, where ws->n would be stored and reloaded at every entry. */
typedef struct dep_cursor {
    size_t *restrict cell;
    double *restrict w;
} dep_cursor;

static inline dep_cursor dep_cursor_at(mimas_weights *ws)
{
    return (dep_cursor){ws->cell + ws->n, ws->w + ws->n};
}

static inline void dep_cursor_put(dep_cursor *c, size_t cell, double w)
{
    *c->cell++ = cell;
    *c->w++ = w;
}

/* The list ends where the cursor is. */
static inline void dep_cursor_done(mimas_weights *ws, const dep_cursor *c)
{
    ws->n = (size_t)(c->cell - ws->cell);
}

/* The centre of cell i along direction d (the last cell's upper edge is the grid's). */
static inline double dep_centre(const mimas_deposit *dp, int d, int i)
{
    const mimas_grid *g = dp->grid;
    double lo = g->lo[d] + dp->h[d] * i, hi = i + 1 == g->n[d] ? g->hi[d] : lo + dp->h[d];
    return 0.5 * (lo + hi);
}
/* The index box of the cells that may meet the ball of radius reach about the
 * axis-frame point a; 0 if there are none. */
int dep_candidate_box(const mimas_deposit *dp, const double a[3], double reach, int lo[3],
                      int hi[3]);
/* Cell index range [i0, i1] of direction d overlapping [lo, hi] (grid
 * coordinates); 0 if none.  Directions a kernel is integrated over have
 * their one cell whatever the range.  Inline: the deposits call it for every
 * object and direction. */
static inline int dep_index_range(const mimas_deposit *dp, int d, double lo, double hi, int *i0, int *i1)
{
    const mimas_grid *g = dp->grid;
    if (dp->kernel && !g->gridded[d] && (g->kind == MIMAS_GRID_CARTESIAN || d == 2)) {
        *i0 = *i1 = 0;
        return 1;
    }
    if (hi < g->lo[d] || lo > g->hi[d])
        return 0;
    double a = floor((lo - g->lo[d]) / dp->h[d]), b = floor((hi - g->lo[d]) / dp->h[d]);
    *i0 = a < 0 ? 0 : (int)a;
    *i1 = b >= g->n[d] ? g->n[d] - 1 : (int)b;
    return *i0 <= *i1;
}

/* The Gaussian on a Cartesian x-y-z grid (dp->gauss_xyz): a particle (its value and
 * gradient at the cell centres) and a segment's exact line integral.  The segment
 * returns -1 when it leaves it to the cell-by-cell closed form (a branch longer
 * than the quadrature covers, or factors beyond the range of doubles). */
int mimas_gauss_sphere_xyz(const mimas_deposit *dp, const double x[3], int with_grad,
                           mimas_weights *ws);
int mimas_gauss_segment_xyz(const mimas_deposit *dp, const double a[3], const double b[3],
                            mimas_weights *ws);
/* The same built for any processor, and (x86-64) with AVX2 and with AVX-512, which
 * mimas_gauss_segment_xyz and mimas_gauss_sphere_xyz choose from the processor's features:
 * the same weights (and gradients) to the bit (tests/unit/test_segment_builds.c; the last
 * two to be called only where __builtin_cpu_supports says so). */
int mimas_gauss_segment_xyz_portable(const mimas_deposit *dp, const double a[3],
                                     const double b[3], mimas_weights *ws);
int mimas_gauss_segment_xyz_avx2(const mimas_deposit *dp, const double a[3], const double b[3],
                                 mimas_weights *ws);
int mimas_gauss_segment_xyz_avx512(const mimas_deposit *dp, const double a[3],
                                   const double b[3], mimas_weights *ws);
int mimas_gauss_sphere_xyz_portable(const mimas_deposit *dp, const double x[3], int with_grad,
                                    mimas_weights *ws);
int mimas_gauss_sphere_xyz_avx2(const mimas_deposit *dp, const double x[3], int with_grad,
                                mimas_weights *ws);
int mimas_gauss_sphere_xyz_avx512(const mimas_deposit *dp, const double x[3], int with_grad,
                                  mimas_weights *ws);
/* Makes the table the segment's closed form uses (once; thread-safe). */
void mimas_gauss_tables(void);

/* The Gaussian on an r-z grid (dp->gauss_rz): a particle at axis-frame a (its azimuthal
 * average and gradient at the cell centres) and a segment aa -> ab (Gauss-Legendre along
 * it, dep_ring_rule, split at the average's singular points where one is near: ring_edges.h)
 * over the cells within reach of its midpoint am, by the ring series per cell
 * (deposit_ring.c); scale multiplies every weight. */
int mimas_gauss_sphere_rz(const mimas_deposit *dp, const double a[3], int with_grad,
                          double scale, mimas_weights *ws);
/* The terms the ring lanes' second tier sums for T_{N+1} at wt's largest X (dp->ring_terms;
 * 0 where the table of 1/(j + 1/2) is too short for them). */
int mimas_ring_tier2_terms(const mimas_weight *wt);
int mimas_gauss_segment_rz(const mimas_deposit *dp, const double aa[3], const double ab[3],
                           const double am[3], double reach, double scale, mimas_weights *ws);
/* The same built for any processor, and (x86-64) with AVX2 and with AVX-512, which
 * mimas_gauss_segment_rz and mimas_gauss_sphere_rz choose from the processor's features:
 * the same weights (and gradients) to the bit (the last two to be called only where
 * __builtin_cpu_supports says so). */
int mimas_gauss_segment_rz_portable(const mimas_deposit *dp, const double aa[3],
                                    const double ab[3], const double am[3], double reach,
                                    double scale, mimas_weights *ws);
int mimas_gauss_segment_rz_avx2(const mimas_deposit *dp, const double aa[3],
                                const double ab[3], const double am[3], double reach,
                                double scale, mimas_weights *ws);
int mimas_gauss_segment_rz_avx512(const mimas_deposit *dp, const double aa[3],
                                  const double ab[3], const double am[3], double reach,
                                  double scale, mimas_weights *ws);
int mimas_gauss_sphere_rz_portable(const mimas_deposit *dp, const double a[3], int with_grad,
                                   double scale, mimas_weights *ws);
int mimas_gauss_sphere_rz_avx2(const mimas_deposit *dp, const double a[3], int with_grad,
                               double scale, mimas_weights *ws);
int mimas_gauss_sphere_rz_avx512(const mimas_deposit *dp, const double a[3], int with_grad,
                                 double scale, mimas_weights *ws);
/* Bins on a Cartesian grid: the segment a-b walked through the cells, each piece's
 * length fraction over the cell volume (deposit_walk.c). */
int dep_walk_segment(const mimas_deposit *dp, const double a[3], const double b[3],
                     mimas_weights *ws);
/* The Gauss-Legendre rule along a segment of length len for the azimuthal average: 4, 8
 * or 16 points for segments up to w/2, 2w or longer (the kernel varies on the scale w;
 * Lucy's on c/3).  Returns n and sets its nodes and weights (gauss_legendre.h). */
int dep_ring_rule(const mimas_weight *wt, double len, const double **x, const double **w);
/* The longest segment the rule of n points takes (infinite for 16). */
double dep_ring_longest(const mimas_weight *wt, int n);

#endif
