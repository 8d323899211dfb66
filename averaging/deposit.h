/* Where a particle, a point or a contact's branch segment goes on a grid, and
 * with which weight (docs/fields.md; docs/theory.md §6): the cells it touches
 * and the weight per unit volume in each, so that summing weight times cell
 * volume over the cells gives 1 (bins) or the coarse-graining integral
 * (kernels).  Kernels are integrated over the directions the grid does not
 * resolve (their marginals; the azimuthal average on cylindrical grids
 * without phi cells).  Periodic boxes contribute through the images of the
 * object that reach the grid. */
#ifndef MIMAS_DEPOSIT_H
#define MIMAS_DEPOSIT_H

#include <stddef.h>

#include "frame.h"
#include "grid.h"
#include "weight.h"

/* The weights of one object: n cells with their weights and, for kernels
 * that have one (particles only), the weight's gradient with respect to the
 * field point (in the grid's x y z or physical r phi z components), one plane
 * per component: component d of entry k is grad[d cap + k]
 * (mimas_weights_grad).  Reused from object to object; grow as needed. */
typedef struct mimas_weights {
    size_t n, cap;
    size_t *cell;
    double *w;
    double *grad;
    int has_grad;   /* set by the deposit: grad holds the gradients */
    double *scratch; /* the deposit's own working space */
    size_t scratch_cap;
} mimas_weights;

void mimas_weights_free(mimas_weights *ws);

/* Component d of the gradients: entry k's is mimas_weights_grad(ws, d)[k]. */
static inline double *mimas_weights_grad(const mimas_weights *ws, int d)
{
    return ws->grad + (size_t)d * ws->cap;
}

/* The periodic images an object may need along each edge of the box: those up to
 * MIMAS_IMAGE_RANGE box widths away (a kernel reaching further is refused) */
#define MIMAS_IMAGE_RANGE 3
#define MIMAS_DEPOSIT_SHIFTS                                                                     \
    ((2 * MIMAS_IMAGE_RANGE + 1) * (2 * MIMAS_IMAGE_RANGE + 1) * (2 * MIMAS_IMAGE_RANGE + 1))

typedef struct mimas_deposit {
    const mimas_grid *grid;
    const mimas_weight *wt;
    int none;              /* --grid none: one cell, the box, weight 1/V_box */
    double box_volume;
    int nshift;            /* periodic image shifts (the first is zero) */
    double shift[MIMAS_DEPOSIT_SHIFTS][3];
    double image_margin;   /* Cartesian grids: an object whose bounding box lies inside
                            * the grid by more than this on every side has no image
                            * that reaches it (INFINITY: always search the images) */
    double h[3];           /* cell sizes of the grid */
    double inv_h[3];       /* their reciprocals */
    double cart_volume;    /* cell volume of a Cartesian grid */
    int kernel;            /* a kernel weight (Gaussian, Lucy, Shepard) */
    int dims;              /* kernels: the dimension the kernel is resolved in (1-3) */
    int gdir[3];           /* Cartesian: the gridded directions, dims of them */
    double inv_extent;     /* kernels: 1 / the box's extent along the directions
                            * they are integrated over (Cartesian; cylindrical z) */
    int gauss_rz;          /* the plain or shifted Gaussian on an r-z grid: the ring
                            * series cell by cell (deposit_ring.c) */
    int ring_terms;        /* gauss_rz: the terms of the ring lanes' second tier's series
                            * for T_{N+1} (0: no second tier) */
    int gauss_xyz;         /* the Gaussian on an x-y-z grid: separable (deposit_gauss.c) */
    double gq[3];          /* e^{-2 h^2 / 2w^2} per direction, for its 1-D factors */
} mimas_deposit;

/* MIMAS_EUSAGE (in err) when the images a kernel reaches lie more than MIMAS_IMAGE_RANGE
 * widths of a periodic box away (a field that would average over so many images of each
 * particle), when the kernel is integrated along a direction whose periodic edge a tilt
 * turns into a resolved one (docs/fields.md), or when a direction not gridded has no extent
 * (a grid not fitted to the box: mimas_grid_fit_box). */
int mimas_deposit_init(mimas_deposit *dp, const mimas_grid *g, const mimas_weight *wt,
                       const mimas_box *box, int grid_none, mimas_error *err);
/* A sphere of radius R at x (R = 0: a point); with_grad: kernels also give
 * their gradient.  Appends to ws (ws->n = 0 first for a new object).
 * Returns MIMAS_OK or MIMAS_EIO when out of memory. */
int mimas_deposit_sphere(const mimas_deposit *dp, const double x[3], double R, int with_grad,
                         mimas_weights *ws);
/* The segment from a to b (a contact's branch from r_j to r_i, or from the
 * contact point to a particle centre for wall contacts); no gradients. */
int mimas_deposit_segment(const mimas_deposit *dp, const double a[3], const double b[3],
                          mimas_weights *ws);

#endif
