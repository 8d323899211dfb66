/* The tests' reference for a contact's weight on a cylindrical grid: the integral along the
 * branch of the kernel's azimuthal average, split where the average has its square-root
 * edges, found without mimas's quartic. */
#ifndef MIMAS_TEST_RING_BRANCH_REF_H
#define MIMAS_TEST_RING_BRANCH_REF_H

/* The integral over s in [0, 1] of average(s): split where edge(s, -1) (the ring's nearest
 * point's distance from the branch's point s, minus the reach) or edge(s, +1) (its farthest
 * point's) changes sign, found on `intervals` equal intervals and bisected to the double's
 * resolution, then GSL's qags on each piece (absolute tolerance abs_tol, relative 1e-13).
 * *edges, unless NULL: the number of splits.  GSL's error handler should be off: the
 * pieces' integrals are asked for near their rounding. */
double ring_branch_integral(double (*average)(double s, void *ctx),
                            double (*edge)(double s, double sign, void *ctx), void *ctx,
                            int intervals, double abs_tol, int *edges);

#endif
