/* The slices of a ball inside a full annulus, the integrand of the sphere-ring overlap's
 * quadrature (overlap.c, "Quadrature" in docs/overlap.md), several nodes at a time. */
#ifndef MIMAS_ANNULUS_SLICES_H
#define MIMAS_ANNULUS_SLICES_H

/* Nodes are taken up to this many at a time (the widest build): t and f have room for n
 * rounded up to a multiple of it. */
#define ANNULUS_LANES 8

/* For a ball of radius R whose centre is d > 0 from the axis, the latitude band
 * theta_a .. theta_a + dth (z = z_centre + R sin(theta)) taken at theta = ta + dth S(t),
 * S(t) = t^2 (3 - 2t): f[i] = A(rho) rho 6 dth t (1 - t) at t = t[i] (i < n), rho = R
 * cos(theta), with A(rho) the area of the disk of radius rho about the centre's foot inside
 * the annulus r0 <= r <= r1 (r0 >= 0, r1 finite), at most pi rho^2 and the annulus' area. */
void annulus_slices(double d, double r0, double r1, double R, double ta, double dth,
                    const double *t, double *f, int n);

/* The builds annulus_slices chooses from: two nodes at a time (any processor), four (AVX2)
 * and eight (AVX-512; x86-64 only, where the processor has them): the same values to the
 * bit (tests/unit/test_overlap_parts.c). */
void annulus_slices_portable(double d, double r0, double r1, double R, double ta, double dth,
                             const double *t, double *f, int n);
void annulus_slices_avx2(double d, double r0, double r1, double R, double ta, double dth,
                         const double *t, double *f, int n);
void annulus_slices_avx512(double d, double r0, double r1, double R, double ta, double dth,
                           const double *t, double *f, int n);

#endif
