/* Geometric kernels of Heaviside-bin averaging (docs/theory.md §6): the volume of a
 * sphere inside a rectangular or cylindrical cell, and the fraction of a
 * straight segment (a contact branch vector) inside such a cell.  Exact to
 * rounding (closed forms) or to ~1e-12 (adaptive quadrature of exact
 * cross-section areas); formulas, conventions and accuracy in docs/overlap.md.
 *
 * No state, no allocation, no output: every function is re-entrant and
 * thread-safe.  Infinite bounds are allowed wherever a cell bound is taken
 * (slabs, half-spaces, unbounded rings); an empty cell (lo >= hi, r1 <= r0,
 * phi1 <= phi0, z1 <= z0) gives 0.  A NaN argument gives NaN; otherwise the
 * result is finite. */
#ifndef MIMAS_OVERLAP_H
#define MIMAS_OVERLAP_H

#ifdef __cplusplus
extern "C" {
#endif

/* Volume of the intersection of the ball |x - c| <= R with the box
 * lo <= x <= hi (componentwise; any bound may be -INFINITY/INFINITY, so
 * slabs and half-spaces work).  R <= 0 gives 0.  Closed form. */
double overlap_sphere_box(const double c[3], double R, const double lo[3], const double hi[3]);

/* The volumes of the ball |x - c| <= R in every cell of a block of boxes: the box
 * (i, j, k) spans lo[d][i_d] <= x_d <= hi[d][i_d] along each axis d (i_d < n[d]), and its
 * volume goes to vol[i + n[0] (j + n[1] k)].  Each is overlap_sphere_box() of that box to the
 * bit; the corner volumes of the ball that neighbouring boxes share (the costly part) are
 * computed once for the block instead of once for each box. */
void overlap_sphere_cells(const double c[3], double R, const int n[3], const double *const lo[3],
                          const double *const hi[3], double *vol);

/* Volume of the intersection of the ball |x - c| <= R (c in Cartesian
 * coordinates whose z axis is the cylinder axis) with the cylindrical cell
 * r0 <= r <= r1, phi0 <= phi <= phi1 (radians, counterclockwise from +x;
 * phi1 - phi0 >= 2 pi is the full circle), z0 <= z <= z1.  r0 may be 0 (or
 * negative, taken as 0); r1, z0 and z1 may be infinite.  Closed form when the
 * cell cuts the ball with planes only, otherwise adaptive quadrature over z
 * of the exact area of a disk intersected with an annular sector. */
double overlap_sphere_cylcell(const double c[3], double R, double r0, double r1, double phi0,
                              double phi1, double z0, double z1);

/* The volumes of the ball |x - c| <= R in the rings r[k] <= r <= r[k + 1] (k < n, r[k] <
 * r[k + 1]) of the full circle in the slab z0..z1 (as overlap_sphere_cylcell): each the
 * difference of the ball's volumes inside the cylinders r <= r[k + 1] and r <= r[k], so
 * that each cylinder, whose circle needs the quadrature where it cuts the ball, is
 * integrated once for the two rings it bounds instead of once for each.  A ring that
 * misses the ball's part in the slab gets an exact 0; the others are exact to about 1e-14
 * of the ball's volume (absolute, the quadrature's tolerance); the rings add up to the
 * ball's volume in the slab between r[0] and r[n] to rounding.  A NaN in c or R gives NaN. */
void overlap_sphere_rings(const double c[3], double R, int n, const double *r, double z0,
                          double z1, double *vol);

/* Fraction (0..1) of the straight segment from a to b inside the box (or the
 * cylindrical cell), from the parameters where the segment crosses the faces.
 * Where the segment lies in a face, each point counts with the fraction of a
 * small ball about it that lies in the cell: 1/2 on a face, 1/4 on an edge of
 * a box, (phi1 - phi0)/(2 pi) on the axis; so fractions over cells that tile
 * space always sum to 1.  A degenerate segment (a == b) counts 1 if the point
 * is inside the cell, 0 if outside (and so 1/2 on a face).  a and b must be
 * finite. */
/* Volume of the intersection of two balls of radii R1 and R2 whose centres
 * are d apart (the lens of two spheres; probe spheres of mimas radial):
 * 0 for d >= R1 + R2, the smaller ball for d <= |R1 - R2|, else
 * pi (R1 + R2 - d)^2 (d^2 + 2 d (R1 + R2) - 3 (R1 - R2)^2) / (12 d).
 * Closed form; R <= 0 gives 0. */
double overlap_sphere_sphere(double d, double R1, double R2);

double segment_fraction_box(const double a[3], const double b[3], const double lo[3],
                            const double hi[3]);
double segment_fraction_cylcell(const double a[3], const double b[3], double r0, double r1,
                                double phi0, double phi1, double z0, double z1);

#ifdef __cplusplus
}
#endif
#endif
