/* The slices of a ball inside a full annulus (annulus_slices.h): the area of a disk inside
 * an annulus by the boundary integral of docs/overlap.md ("Disk and annulus"), as
 * overlap.c's disk_annulus_area takes it, four nodes at a time without branches, with
 * poly_trig.h's functions instead of libm's; built for AVX2 as well (MIMAS_SIMD), the same
 * operations lane by lane, so the same bits on every processor. */
#include <config.h>

#include "annulus_slices.h"

#include <string.h>

#include "poly_trig.h"
#include "simd.h"

/* Vectors cross no call here (every helper is inlined), so GCC's note that their ABI
 * differs without AVX does not concern this file. */
#pragma GCC diagnostic ignored "-Wpsabi"

static const double PI = 3.14159265358979323846;

_Static_assert(PT_LANES == ANNULUS_LANES, "a batch is taken a vector at a time");

/* The circle r's part of the boundary integral for PT_LANES disk radii rho, without
 * branches (outside the range where the circles cross, h = 0 gives the limiting angles):
 * r (r - d) beta + r d (beta - sin beta), and the disk's arc outside the circle,
 * rho^2 (pi - tau), in *arc; beta and tau the crossing point's angles seen from the axis
 * and from the disk's centre, as circle_parts in overlap.c. */
static inline __attribute__((always_inline)) pt_vd circle_terms(double d, pt_vd rho, double r,
                                                                pt_vd *arc)
{
    const pt_vd zero = {0};
    double rmd = r - d;
    pt_vd rma = (rho - rmd) * (rho + rmd) / (2.0 * d), h2 = rma * (2.0 * r - rma);
    pt_vd h = pt_sqrt(pt_sel(h2 > zero, h2, zero));
    pt_vd beta = poly_atan2(h, r - rma), tau = poly_atan2(h, rmd - rma);
    *arc = rho * rho * (PI - tau);
    return r * (r - d) * beta + r * d * poly_bms(beta);
}

MIMAS_SIMD void annulus_slices(double d, double r0, double r1, double R, double ta, double dth,
                               const double *t, double *f, int n)
{
    const pt_vd zero = {0};
    double ring = PI * (r1 - r0) * (r1 + r0);
    for (int i = 0; i < n; i += PT_LANES) {
        pt_vd ti, arc1, arc0 = zero; /* r0 = 0: tau = pi, no arc beyond it */
        memcpy(&ti, t + i, sizeof ti);
        pt_vd th = ta + dth * (ti * ti * (3.0 - 2.0 * ti)), rho = R * poly_cos(th);
        pt_vd sum = circle_terms(d, rho, r1, &arc1);
        if (r0 > 0.0)
            sum -= circle_terms(d, rho, r0, &arc0);
        pt_vd lens = arc1 - arc0, disk = PI * rho * rho;
        pt_vd area = sum + pt_sel(lens > zero, lens, zero);
        pt_vd cap = pt_sel(disk < ring, disk, zero + ring);
        area = pt_sel(area > zero, pt_sel(area < cap, area, cap), zero);
        pt_vd v = pt_sel(rho > zero, area * rho * 6.0 * dth * ti * (1.0 - ti), zero);
        memcpy(f + i, &v, sizeof v);
    }
}
