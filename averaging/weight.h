/* Coarse-graining weights of mimas average (--weight): Heaviside bins with
 * exact overlaps, centre-in-cell bins, and the kernels (Gaussian, Lucy) with
 * their exact line integrals, their marginals (the kernel integrated over the
 * directions a grid does not resolve) and their azimuthal averages
 * (docs/fields.md; docs/theory.md §6). */
#ifndef MIMAS_WEIGHT_H
#define MIMAS_WEIGHT_H

#include "error.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum mimas_weight_kind {
    MIMAS_WEIGHT_BINS,        /* exact volume / segment overlap with the cell */
    MIMAS_WEIGHT_BINS_CENTER, /* the cell holding the centre (contact point) */
    MIMAS_WEIGHT_GAUSS,       /* Gaussian of width w, cut at cutoff*w, renormalised */
    MIMAS_WEIGHT_LUCY,        /* Lucy's polynomial of range c */
    MIMAS_WEIGHT_SHEPARD      /* ratio of Gaussian sums of per-particle values (Bierwisch 2009, eq. 2.27) */
} mimas_weight_kind;

typedef struct mimas_weight {
    mimas_weight_kind kind;
    double w;        /* Gaussian standard deviation; Lucy: the range c */
    double cutoff;   /* in units of w (default 3) */
    int shifted;     /* gauss:...,shift: the Gaussian shifted to 0 at the cutoff */
    double shift;    /* exp(-cutoff^2/2) for the shifted kernel, else 0 */
    double tail;     /* exp(-cutoff^2/2): the plain Gaussian's value at the cutoff, relative */
    double coef;     /* the 3-D kernel is coef (exp(-r^2/2w^2) - shift) for r < cutoff w
                      * (Lucy: coef (1 + 3q)(1 - q)^3, q = r/c) */
    double inv2w2;   /* 1 / (2 w^2) */
    double reach2;   /* (cutoff w)^2 */
    double kappa;    /* the part of a linear field's gradient that the plain cut's jump
                      * carries: phi(R) 4/3 pi R^3 (0 for continuous kernels) */
    int voronoi;     /* per-particle Voronoi values (mimas voronoi -o), mapped by the
                      * centre's cell (kind BINS_CENTER) or the Gaussian (kind GAUSS) */
} mimas_weight;

/* "bins", "bins:center", "gauss:w=W[,cutoff=C][,shift]", "lucy:c=C",
 * "shepard:w=W[,cutoff=C][,shift]", "voronoi", "voronoi:w=W[,cutoff=C][,shift]". */
int mimas_weight_parse(mimas_weight *wt, const char *spec, mimas_error *err);

/* The Gaussian coarse-graining function at distance vector d: the Gaussian of
 * standard deviation w cut at the cutoff (or, shifted, minus its value there),
 * normalised to integral 1. */
double mimas_gauss_phi(const mimas_weight *wt, const double d[3]);
/* Its value and gradient with respect to the field point (d = r - r_i),
 * inside the cutoff (the plain cut's jump there is not in g). */
double mimas_gauss_phi_grad(const mimas_weight *wt, const double d[3], double g[3]);
/* The line integral psi = int_0^1 phi(d - s b) ds, d = r - r_j, b = r_i - r_j,
 * in closed form with erf over the part of the segment within the cutoff. */
double mimas_gauss_line(const mimas_weight *wt, const double d[3], const double b[3]);
/* The kernel (Gaussian or Lucy) at d, its value and gradient, and its line
 * integral: the functions above for the kind of wt. */
double mimas_kernel_phi_grad(const mimas_weight *wt, const double d[3], double g[3]);
double mimas_kernel_line(const mimas_weight *wt, const double d[3], const double b[3]);
/* The support radius (Gaussian: cutoff * w; Lucy: c). */
double mimas_weight_reach(const mimas_weight *wt);

/* Marginals: the 3-D kernel integrated over all of space along 3 - dims
 * directions (dims = 1 or 2; 3 is the kernel itself), as a function of the
 * offset d (dims components) in the others; g (may be NULL) gets its
 * gradient.  They are continuous at the support's edge for both cuts. */
double mimas_kernel_marginal(const mimas_weight *wt, int dims, const double *d, double *g);
/* int_0^1 marginal(d - s b) ds (d = r - r_j, b = r_i - r_j, dims components). */
double mimas_kernel_marginal_line(const mimas_weight *wt, int dims, const double *d,
                                  const double *b);
/* The azimuthal average (1/2 pi) int_0^2pi k(D(t)) dt of the kernel (dims = 3)
 * or of its marginal over the axis (dims = 2), on the ring of radius r about
 * the axis, for a point at distance rho from the axis and axial offset dz
 * (ignored for dims = 2): D^2 = r^2 + rho^2 - 2 r rho cos t (+ dz^2).  The
 * Gaussian's full ring is closed form, e^{-((r-rho)^2+dz^2)/2w^2} I0_scaled(r rho/w^2);
 * a ring that the support cuts is a 16-point Gauss-Legendre rule in a variable that
 * makes the integrand smooth.  grad (may be NULL) gets (d/dr, d/dz). */
double mimas_kernel_ring(const mimas_weight *wt, int dims, double r, double rho, double dz,
                         double grad[2]);
/* The plain or shifted Gaussian's average (dims 3) on a ring that its support cuts
 * short, by a binomial series (exact to rounding): the same as mimas_kernel_ring for
 * D0^2 = (r - rho)^2 + dz^2 < R^2 (the caller's D02).  Returns 0 (v, grad untouched) for
 * longer arcs, where the support reaches more than a quarter of the way round
 * (sin^2(tm/2) > 1/2): the rule of mimas_kernel_ring does those. */
int mimas_gauss_ring_short(const mimas_weight *wt, double r, double rho, double dz, double D02,
                           double *v, double grad[2]);

#ifdef __cplusplus
}
#endif
#endif
