/* Coarse-graining weights of mimas average (--weight): Heaviside bins with
 * exact overlaps, centre-in-cell bins, and the Gaussian coarse-graining
 * function with its exact line integral (docs/theory.md §6). */
#ifndef MIMAS_WEIGHT_H
#define MIMAS_WEIGHT_H

#include "error.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum mimas_weight_kind {
    MIMAS_WEIGHT_BINS,        /* exact volume / segment overlap with the cell */
    MIMAS_WEIGHT_BINS_CENTER, /* the cell holding the centre (contact point) */
    MIMAS_WEIGHT_GAUSS,       /* normalised Gaussian of width w, cut at cutoff*w */
    MIMAS_WEIGHT_LUCY,        /* Lucy's polynomial of range c */
    MIMAS_WEIGHT_SHEPARD      /* Shepard's ratio of Gaussian sums (Bierwisch 2009, eq. 2.27) */
} mimas_weight_kind;

typedef struct mimas_weight {
    mimas_weight_kind kind;
    double w;        /* Gaussian standard deviation; Lucy: the range c */
    double cutoff;   /* in units of w (default 3) */
    double shift;    /* exp(-cutoff^2/2): the kernel is shifted to 0 at the cutoff */
    double norm;     /* 1 / integral of the cut, shifted Gaussian (renormalisation) */
    double coef;     /* norm / (2 pi w^2)^{3/2} */
    double inv2w2;   /* 1 / (2 w^2) */
    double reach2;   /* (cutoff w)^2 */
    int voronoi;     /* per-particle Voronoi values (mimas voronoi -o), mapped by the
                      * centre's cell (kind BINS_CENTER) or the Gaussian (kind GAUSS) */
} mimas_weight;

/* "bins", "bins:center", "gauss:w=W[,cutoff=C]", "lucy:c=C", "shepard:w=W[,cutoff=C]",
 * "voronoi", "voronoi:w=W[,cutoff=C]". */
int mimas_weight_parse(mimas_weight *wt, const char *spec, mimas_error *err);

/* The Gaussian coarse-graining function at distance vector d: the Gaussian
 * of standard deviation w shifted down by its value at the cutoff (so it is
 * continuous, zero from the cutoff on), normalised to integral 1. */
double mimas_gauss_phi(const mimas_weight *wt, const double d[3]);
/* Its value and gradient with respect to the field point (d = r - r_i). */
double mimas_gauss_phi_grad(const mimas_weight *wt, const double d[3], double g[3]);
/* The line integral psi = int_0^1 phi(d - s b) ds, d = r - r_j, b = r_i - r_j,
 * in closed form with erf, restricted to the part of the segment within the
 * cutoff. */
double mimas_gauss_line(const mimas_weight *wt, const double d[3], const double b[3]);
/* The kernel (Gaussian or Lucy) at d, its value and gradient, and its line
 * integral: the functions above for the kind of wt. */
double mimas_kernel_phi_grad(const mimas_weight *wt, const double d[3], double g[3]);
double mimas_kernel_line(const mimas_weight *wt, const double d[3], const double b[3]);
/* The support radius (Gaussian: cutoff * w; Lucy: c). */
double mimas_weight_reach(const mimas_weight *wt);

#ifdef __cplusplus
}
#endif
#endif
