/* The slices of a ball inside a full annulus, PT_LANES nodes at a time (annulus_slices.c,
 * which includes this once for each build, after poly_trig.h with the same PT_LANES and
 * PT_, and with ANN_FN the function's name).  The area of a disk inside an annulus by the
 * boundary integral of docs/overlap.md ("Disk and annular sector"), as overlap.c's
 * disk_annulus_area takes it, without branches: outside the range where the circles
 * cross, h = 0 gives the limiting angles. */

/* The circle r's part of the boundary integral for the disk radii rho:
 * r (r - d) beta + r d (beta - sin beta), and the disk's arc outside the circle,
 * rho^2 (pi - tau), in *arc; beta and tau the crossing point's angles seen from the axis
 * and from the disk's centre, as circle_parts in overlap.c. */
static inline __attribute__((always_inline)) PT_(vd)
    PT_(circle_terms)(double d, PT_(vd) rho, double r, PT_(vd) *arc)
{
    const PT_(vd) zero = {0};
    const double pi = 3.14159265358979323846;
    double rmd = r - d;
    PT_(vd) rma = (rho - rmd) * (rho + rmd) / (2.0 * d), h2 = rma * (2.0 * r - rma);
    PT_(vd) h = PT_(sqrt)(PT_(sel)(h2 > zero, h2, zero));
    PT_(vd) beta = PT_(atan2)(h, r - rma), tau = PT_(atan2)(h, rmd - rma);
    *arc = rho * rho * (pi - tau);
    return r * (r - d) * beta + r * d * PT_(bms)(beta);
}

void ANN_FN(double d, double r0, double r1, double R, double ta, double dth, const double *t,
            double *f, int n)
{
    const PT_(vd) zero = {0};
    const double pi = 3.14159265358979323846, ring = pi * (r1 - r0) * (r1 + r0);
    for (int i = 0; i < n; i += PT_LANES) {
        PT_(vd) ti, arc1, arc0 = zero; /* r0 = 0: tau = pi, no arc beyond it */
        memcpy(&ti, t + i, sizeof ti);
        PT_(vd) th = ta + dth * (ti * ti * (3.0 - 2.0 * ti)), rho = R * PT_(cos)(th);
        PT_(vd) sum = PT_(circle_terms)(d, rho, r1, &arc1);
        if (r0 > 0.0)
            sum -= PT_(circle_terms)(d, rho, r0, &arc0);
        PT_(vd) lens = arc1 - arc0, disk = pi * rho * rho;
        PT_(vd) area = sum + PT_(sel)(lens > zero, lens, zero);
        PT_(vd) cap = PT_(sel)(disk < ring, disk, zero + ring);
        area = PT_(sel)(area > zero, PT_(sel)(area < cap, area, cap), zero);
        PT_(vd) v = PT_(sel)(rho > zero, area * rho * 6.0 * dth * ti * (1.0 - ti), zero);
        memcpy(f + i, &v, sizeof v);
    }
}
