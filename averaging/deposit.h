/* Where a particle, a point or a contact's branch segment goes on a grid, and
 * with which weight (docs/theory.md §6): for each cell it touches, the callback gets
 * the cell and the weight per unit volume, so that summing weight times cell
 * volume over the cells gives 1 (bins) or the coarse-graining integral
 * (Gaussian).  Periodic boxes contribute through the images of the object
 * that reach the grid. */
#ifndef MIMAS_DEPOSIT_H
#define MIMAS_DEPOSIT_H

#include <stddef.h>

#include "frame.h"
#include "grid.h"
#include "weight.h"

/* grad: the gradient of the weight with respect to the field point (for the
 * Gaussian, at the cell centre), or NULL where the weight has none (bins) */
typedef void (*deposit_fn)(void *user, size_t cell, double weight, const double *grad);

typedef struct mimas_deposit {
    const mimas_grid *grid;
    const mimas_weight *wt;
    int none;              /* --grid none: one cell, the box, weight 1/V_box */
    double box_volume;
    int nshift;            /* periodic image shifts (the first is zero) */
    double shift[27][3];
    double h[3];           /* cell sizes of the grid */
    double cart_volume;    /* cell volume of a Cartesian grid */
} mimas_deposit;

void mimas_deposit_init(mimas_deposit *dp, const mimas_grid *g, const mimas_weight *wt,
                        const mimas_box *box, int grid_none);
/* A sphere of radius R at x (R = 0: a point). */
void mimas_deposit_sphere(const mimas_deposit *dp, const double x[3], double R, deposit_fn fn,
                          void *user);
/* The segment from a to b (a contact's branch from r_j to r_i, or from the
 * contact point to a particle centre for wall contacts). */
void mimas_deposit_segment(const mimas_deposit *dp, const double a[3], const double b[3],
                           deposit_fn fn, void *user);

#endif
