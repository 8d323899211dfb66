/* Sphere-cell volumes and segment-cell fractions for Heaviside bins.  The
 * formulas are derived in docs/overlap.md; the section names below refer to
 * it. */
#include <config.h>

#include "overlap.h"

#include <float.h>
#include <math.h>
#include <string.h>

#include "annulus_slices.h"
#include "kronrod41.h"

static const double PI = 3.14159265358979323846;
static const double TWO_PI = 6.28318530717958647693;
static const double FOUR_THIRDS_PI = 4.18879020478639098462;

/* ---- ball and box: closed forms ("Ball and box") ------------------------- */

/* Volume of the unit ball in the half-space x > a, -1 <= a <= 1 (a cap). */
static double unit_cap(double a)
{
    double h = 1.0 - a;
    return PI / 3.0 * h * h * (3.0 - h);
}

/* Volume of the unit ball in x > a, y > b; a, b >= 0, a^2 + b^2 < 1. */
static double unit_wedge(double a, double b)
{
    double s = sqrt((1.0 - a * a) - b * b);
    return (2.0 * atan2(s, a * b) - a * (3.0 - a * a) * atan2(s, b) -
            b * (3.0 - b * b) * atan2(s, a) + 2.0 * a * b * s) /
           3.0;
}

/* Volume of the unit ball in x > a, y > b, z > c; a, b, c >= 0,
 * a^2 + b^2 + c^2 < 1: divergence theorem with the solid angle from
 * Gauss-Bonnet. */
static double unit_octant(double a, double b, double c)
{
    double sab = sqrt((1.0 - a * a) - b * b);
    double sac = sqrt((1.0 - a * a) - c * c);
    double sbc = sqrt((1.0 - b * b) - c * c);
    double corners = atan2(sab, a * b) + atan2(sac, a * c) + atan2(sbc, b * c) - PI;
    double ta = atan2(sab * sac - b * c, b * sac + c * sab);
    double tb = atan2(sab * sbc - a * c, a * sbc + c * sab);
    double tc = atan2(sac * sbc - a * b, a * sbc + b * sac);
    double v = corners -
               0.5 * (a * (3.0 - a * a) * ta + b * (3.0 - b * b) * tb + c * (3.0 - c * c) * tc) -
               3.0 * a * b * c + a * b * sab + a * c * sac + b * c * sbc;
    return v / 3.0;
}

/* Unit ball in {x_k > t_k} for the n thresholds t (all >= 0). */
static double unit_corner(int n, const double *t)
{
    double q = 0.0;
    for (int k = 0; k < n; k++)
        q += t[k] * t[k];
    if (q >= 1.0)
        return 0.0;
    switch (n) {
    case 0:
        return FOUR_THIRDS_PI;
    case 1:
        return unit_cap(t[0]);
    case 2:
        return unit_wedge(t[0], t[1]);
    default:
        return unit_octant(t[0], t[1], t[2]);
    }
}

/* unit_corner() of the thresholds tx, ty, tz (NO_CUT: that axis unconstrained), computed
 * once for each ball: *memo holds it (NaN until computed); the memo's entry for each
 * combination of thresholds is the sum of the offsets the axes give their thresholds. */
#define NO_CUT (-1.0)
static double memo_corner(double *memo, double tx, double ty, double tz)
{
    if (isnan(*memo)) {
        double t[3] = {tx, ty, tz}, tt[3];
        int n = 0;
        for (int d = 0; d < 3; d++)
            if (t[d] != NO_CUT)
                tt[n++] = t[d];
        *memo = unit_corner(n, tt);
    }
    return *memo;
}

/* One axis of a box seen from the ball, all that depends on that axis alone: the bounds
 * relative to the centre in units of R (l, h), whether the axis puts the box off the ball
 * (or is not a number), how many of its bounds cut the ball, the larger square of l and h,
 * and its interval's indicator as a signed sum of nt half-line indicators {s x > t} with
 * t >= 0 (t is l if l >= 0 else -l, h if h > 0 else -h) or no constraint (NO_CUT), each
 * with its offset in the memo of corner volumes (0 for no constraint). */
enum { AXIS_OK, AXIS_OFF, AXIS_NAN };
typedef struct axis_cut {
    double l, h, far;
    int state, cuts, nt;
    int off[3];
    double t[3], sg[3];
} axis_cut;

/* The thresholds a box's bounds give (see axis_cut) */
static double threshold_l(double l)
{
    return l >= 0.0 ? l : -l;
}

static double threshold_h(double h)
{
    return h > 0.0 ? h : -h;
}

/* An axis with bounds l, h whose thresholds have the offsets lo and ho in the memo. */
static void axis_setup(axis_cut *a, double l, double h, int lo, int ho)
{
    double tl = threshold_l(l), th = threshold_h(h);
    a->l = l, a->h = h;
    a->state = isnan(l) || isnan(h) ? AXIS_NAN
               : !(l < h) || l >= 1.0 || h <= -1.0 ? AXIS_OFF : AXIS_OK;
    if (a->state != AXIS_OK)
        return;
    int lc = l > -1.0, hc = h < 1.0, k = 0;
    a->cuts = lc + hc;
    a->far = l * l > h * h ? l * l : h * h;
#define HALF_LINE(o, tv, s) (a->off[k] = (o), a->t[k] = (tv), a->sg[k++] = (s))
    if (l >= 0.0) {
        HALF_LINE(lo, tl, 1.0);
        if (hc)
            HALF_LINE(ho, th, -1.0);
    } else if (h <= 0.0) {
        HALF_LINE(ho, th, 1.0);
        if (lc)
            HALF_LINE(lo, tl, -1.0);
    } else {
        HALF_LINE(0, NO_CUT, 1.0);
        if (lc)
            HALF_LINE(lo, tl, -1.0);
        if (hc)
            HALF_LINE(ho, th, -1.0);
    }
#undef HALF_LINE
    a->nt = k;
}

/* Volume of the ball of radius R in the box with axes x, y, z (bounds lo..hi, for the box
 * inside the ball), the corner volumes from m. */
static double ball_in_box(double R, const axis_cut *x, const axis_cut *y, const axis_cut *z,
                          const double lo[3], const double hi[3], double *memo)
{
    const axis_cut *a[3] = {x, y, z};
    for (int i = 0; i < 3; i++)
        if (a[i]->state != AXIS_OK)
            return a[i]->state == AXIS_NAN ? NAN : 0.0;
    int cuts = x->cuts + y->cuts + z->cuts;
    double V = FOUR_THIRDS_PI * R * R * R;
    if (cuts == 0)
        return V;
    /* the box inside the ball */
    if (x->far + y->far + z->far <= 1.0)
        return (hi[0] - lo[0]) * (hi[1] - lo[1]) * (hi[2] - lo[2]);
    /* one cut plane: a cap */
    if (cuts == 1) {
        for (int i = 0; i < 3; i++) {
            if (a[i]->l > -1.0)
                return R * R * R * unit_cap(a[i]->l);
            if (a[i]->h < 1.0)
                return R * R * R * unit_cap(-a[i]->h);
        }
    }
    /* Inclusion-exclusion: the product of the axes' signed sums; by symmetry the ball in
     * {s_k x_k > t_k} is a unit_corner(). */
    double sum = 0.0;
    for (int i = 0; i < x->nt; i++)
        for (int j = 0; j < y->nt; j++)
            for (int k = 0; k < z->nt; k++) {
                double w = memo_corner(memo + x->off[i] + y->off[j] + z->off[k], x->t[i],
                                       y->t[j], z->t[k]);
                if (w != 0.0)
                    sum += x->sg[i] * y->sg[j] * z->sg[k] * w;
            }
    double v = sum * R * R * R;
    return v > 0.0 ? (v < V ? v : V) : 0.0;
}

double overlap_sphere_box(const double c[3], double R, const double lo[3], const double hi[3])
{
    if (!(R > 0.0))
        return R == R ? 0.0 : R;
    axis_cut a[3];
    double memo[27];
    for (int d = 0, stride = 1; d < 3; d++, stride *= 3)
        axis_setup(&a[d], (lo[d] - c[d]) / R, (hi[d] - c[d]) / R, stride, 2 * stride);
    for (int k = 0; k < 27; k++)
        memo[k] = NAN;
    return ball_in_box(R, &a[0], &a[1], &a[2], lo, hi, memo);
}

/* The slot of threshold v among the axis's thresholds t[1..*n] (equal to the bit: a
 * threshold of -0 and one of +0 are different arguments), added if new. */
static int threshold_slot(double *t, int *n, double v)
{
    for (int s = 1; s <= *n; s++)
        if (memcmp(&t[s], &v, sizeof v) == 0)
            return s;
    t[++*n] = v;
    return *n;
}

enum { CELLS_AXIS_MAX = 16, CELLS_MEMO_MAX = 1024 };

void overlap_sphere_cells(const double c[3], double R, const int n[3], const double *const lo[3],
                          const double *const hi[3], double *vol)
{
    size_t ncell = (size_t)n[0] * n[1] * n[2];
    if (!(R > 0.0)) {
        for (size_t q = 0; q < ncell; q++)
            vol[q] = R == R ? 0.0 : R;
        return;
    }
    axis_cut a[3][CELLS_AXIS_MAX];
    double t[2 * CELLS_AXIS_MAX + 1];
    int size = 1;
    for (int d = 0; d < 3; d++) {
        if (n[d] > CELLS_AXIS_MAX)
            size = CELLS_MEMO_MAX + 1;
        int nt = 0;
        for (int k = 0; k < n[d] && k < CELLS_AXIS_MAX; k++) {
            double l = (lo[d][k] - c[d]) / R, h = (hi[d][k] - c[d]) / R;
            /* only thresholds below 1 are ever used (the others give no cut) */
            int ls = fabs(l) < 1.0 ? threshold_slot(t, &nt, threshold_l(l)) : 0;
            int hs = fabs(h) < 1.0 ? threshold_slot(t, &nt, threshold_h(h)) : 0;
            axis_setup(&a[d][k], l, h, ls * size, hs * size);
        }
        size *= nt + 1;
    }
    /* a ball over many cells (more thresholds than the memo holds): cell by cell */
    int block = size <= CELLS_MEMO_MAX;
    double memo[CELLS_MEMO_MAX];
    for (int k = 0; block && k < size; k++)
        memo[k] = NAN;
    size_t q = 0;
    for (int k = 0; k < n[2]; k++)
        for (int j = 0; j < n[1]; j++)
            for (int i = 0; i < n[0]; i++) {
                double clo[3] = {lo[0][i], lo[1][j], lo[2][k]};
                double chi[3] = {hi[0][i], hi[1][j], hi[2][k]};
                vol[q++] = block ? ball_in_box(R, &a[0][i], &a[1][j], &a[2][k], clo, chi, memo)
                                 : overlap_sphere_box(c, R, clo, chi);
            }
}

/* ---- segment and box ------------------------------------------------------ */

double segment_fraction_box(const double a[3], const double b[3], const double lo[3],
                            const double hi[3])
{
    double t0 = 0.0, t1 = 1.0, w = 1.0;
    for (int i = 0; i < 3; i++) {
        if (isnan(a[i]) || isnan(b[i]) || isnan(lo[i]) || isnan(hi[i]))
            return NAN;
        if (!(lo[i] < hi[i]))
            return 0.0;
        double d = b[i] - a[i];
        if (d == 0.0) {
            if (a[i] < lo[i] || a[i] > hi[i])
                return 0.0;
            if (a[i] == lo[i] || a[i] == hi[i])
                w *= 0.5;
        } else {
            double u = (lo[i] - a[i]) / d, v = (hi[i] - a[i]) / d;
            if (d < 0.0) {
                double s = u;
                u = v;
                v = s;
            }
            t0 = fmax(t0, u);
            t1 = fmin(t1, v);
        }
    }
    return t1 > t0 ? w * (t1 - t0) : 0.0;
}

/* ---- cylindrical cells ----------------------------------------------------- */

typedef struct cylcell {
    double r0, r1;       /* 0 <= r0 < r1 (r1 may be infinite) */
    double z0, z1;       /* z0 < z1 */
    int full;            /* no angular bounds */
    int wide;            /* opening angle > pi */
    double dphi;         /* opening angle, (0, 2 pi] */
    double e0[2], e1[2]; /* unit vectors along the rays phi0 and phi1 */
} cylcell;

/* Unit vector at angle phi, reduced modulo 2 pi first so that phi and
 * phi + 2 pi give the same vector, with components below 1e-15 set to 0 so
 * that multiples of pi/2 give the axes exactly. */
static void unit_dir(double phi, double e[2])
{
    double p = fmod(phi, TWO_PI);
    if (p < 0.0)
        p += TWO_PI;
    e[0] = cos(p);
    e[1] = sin(p);
    if (fabs(e[0]) < 1e-15)
        e[0] = 0.0, e[1] = e[1] > 0.0 ? 1.0 : -1.0;
    else if (fabs(e[1]) < 1e-15)
        e[1] = 0.0, e[0] = e[0] > 0.0 ? 1.0 : -1.0;
}

/* -1: a NaN argument; 0: an empty cell; 1: set up. */
static int cell_setup(cylcell *g, double r0, double r1, double phi0, double phi1, double z0,
                      double z1)
{
    if (isnan(r0) || isnan(r1) || isnan(phi0) || isnan(phi1) || isnan(z0) || isnan(z1))
        return -1;
    if (r0 < 0.0)
        r0 = 0.0;
    if (!(r1 > r0) || !(phi1 > phi0) || !(z1 > z0))
        return 0;
    g->r0 = r0;
    g->r1 = r1;
    g->z0 = z0;
    g->z1 = z1;
    double dphi = phi1 - phi0;
    /* the full circle, also when phi0 + 2 pi was rounded down */
    if (dphi >= TWO_PI * (1.0 - 4.0 * DBL_EPSILON)) {
        g->full = 1;
        g->wide = 1;
        g->dphi = TWO_PI;
        g->e0[0] = g->e1[0] = 1.0;
        g->e0[1] = g->e1[1] = 0.0;
    } else {
        g->full = 0;
        g->wide = dphi > PI;
        g->dphi = dphi;
        unit_dir(phi0, g->e0);
        unit_dir(phi1, g->e1);
    }
    return 1;
}

static double cross2(const double u[2], double x, double y)
{
    return u[0] * y - u[1] * x;
}

/* Is the point (x, y) in the closed wedge? (the axis is) */
static int in_wedge(const cylcell *g, double x, double y)
{
    if (g->full)
        return 1;
    double s0 = cross2(g->e0, x, y);  /* > 0: counterclockwise of ray 0 */
    double s1 = -cross2(g->e1, x, y); /* > 0: clockwise of ray 1 */
    return g->wide ? (s0 >= 0.0 || s1 >= 0.0) : (s0 >= 0.0 && s1 >= 0.0);
}

enum { W_INSIDE, W_OUTSIDE, W_CUT };

/* Position of the disk |x - p| <= rho (p at distance d from the axis)
 * relative to the wedge; *rays gets bit k set when ray k meets the disk. */
static int disk_wedge(const cylcell *g, double px, double py, double d, double rho, int *rays)
{
    *rays = 0;
    if (g->full)
        return W_INSIDE;
    const double *e[2] = {g->e0, g->e1};
    for (int k = 0; k < 2; k++) {
        double s = e[k][0] * px + e[k][1] * py;
        double dist = s > 0.0 ? fabs(cross2(e[k], px, py)) : d;
        if (dist < rho)
            *rays |= 1 << k;
    }
    if (*rays)
        return W_CUT;
    return in_wedge(g, px, py) ? W_INSIDE : W_OUTSIDE;
}

/* beta - sin(beta), accurate for small beta (Taylor series to beta^17) */
static double bms(double x)
{
    if (fabs(x) < 0.5) {
        double y = x * x;
        return x * y *
               (1.0 / 6 -
                y * (1.0 / 120 -
                     y * (1.0 / 5040 -
                          y * (1.0 / 362880 -
                               y * (1.0 / 39916800 -
                                    y * (1.0 / 6227020800 - y / 1307674368000.0))))));
    }
    return x - sin(x);
}

/* sorts v and carries t along */
static void sort_pairs(double *v, double *t, int n)
{
    for (int i = 1; i < n; i++) {
        double x = v[i], y = t[i];
        int j = i - 1;
        while (j >= 0 && v[j] > x) {
            v[j + 1] = v[j];
            t[j + 1] = t[j];
            j--;
        }
        v[j + 1] = x;
        t[j + 1] = y;
    }
}

static void sort_doubles(double *v, int n)
{
    for (int i = 1; i < n; i++) {
        double x = v[i];
        int j = i - 1;
        while (j >= 0 && v[j] > x) {
            v[j + 1] = v[j];
            j--;
        }
        v[j + 1] = x;
    }
}

/* Where the circle of radius rho about p (|p| = d > 0) meets the circle of
 * radius r about the axis, as angles in [0, pi] from the direction u = p/d:
 * the points p + rho (cos tau, sin tau) (in the frame of u) with
 * |tau| >= *tau lie inside the circle r, the points r (cos beta, sin beta)
 * with |beta| <= *beta inside the disk.  The crossing points are
 * X = a u +- h v (v = u turned by 90 degrees); r - a and h are computed
 * without cancellation. */
static void circle_parts(double d, double rho, double r, double *tau, double *beta)
{
    double rmd = r - d;
    double rma = (rho - rmd) * (rho + rmd) / (2.0 * d); /* r - a */
    if (rma > 0.0 && rma < 2.0 * r) {
        double h = sqrt(rma * (2.0 * r - rma));
        *beta = atan2(h, r - rma);
        *tau = atan2(h, rmd - rma);
    } else if (rma <= 0.0) { /* the disk inside (d < r) or outside the circle */
        *tau = d < r ? 0.0 : PI;
        *beta = 0.0;
    } else { /* the disk contains the circle */
        *tau = PI;
        *beta = PI;
    }
}

/* Area of the disk |x - p| <= rho intersected with the annulus (no wedge):
 * the boundary integral below with the arcs found directly. */
static double disk_annulus_area(double d, double rho, double r0, double r1)
{
    double t1, b1, t0 = PI, b0 = 0.0;
    circle_parts(d, rho, r1, &t1, &b1);
    if (r0 > 0.0)
        circle_parts(d, rho, r0, &t0, &b0);
    double sum = 2.0 * rho * rho * fmax(0.0, t0 - t1);
    sum += 2.0 * (r1 * (r1 - d) * b1 + r1 * d * bms(b1));
    if (r0 > 0.0)
        sum -= 2.0 * (r0 * (r0 - d) * b0 + r0 * d * bms(b0));
    return 0.5 * sum;
}

/* A disk centre p seen from the cell: what does not depend on the radius. */
typedef struct disk_view {
    const cylcell *g;
    double px, py, d;
    double ux, uy;            /* p / d */
    double s[2], cc[2];       /* ray k: p = s[k] e_k + cc[k] (e_k turned by +90 degrees) */
    double eb[2], feb[2];     /* direction of ray k seen from the axis, from u; bms() */
    double ex[2], ey[2];      /* ray k's unit vector in the frame (u, v) */
} disk_view;

static void view_setup(disk_view *v, const cylcell *g, double px, double py, double d)
{
    v->g = g;
    v->px = px;
    v->py = py;
    v->d = d;
    v->ux = d > 0.0 ? px / d : 1.0;
    v->uy = d > 0.0 ? py / d : 0.0;
    const double *e[2] = {g->e0, g->e1};
    for (int k = 0; k < 2 && !g->full; k++) { /* the rays, of a wedge only */
        v->s[k] = e[k][0] * px + e[k][1] * py;
        v->cc[k] = cross2(e[k], px, py);
        v->ex[k] = v->ux * e[k][0] + v->uy * e[k][1];
        v->ey[k] = v->ux * e[k][1] - v->uy * e[k][0];
        v->eb[k] = atan2(v->ey[k], v->ex[k]);
        v->feb[k] = bms(v->eb[k]);
    }
}

/* Is the direction at angle beta from u inside the wedge? */
static int beta_in_wedge(const disk_view *v, double beta)
{
    double rel = beta - v->eb[0];
    if (rel < 0.0)
        rel += TWO_PI;
    if (rel >= TWO_PI)
        rel -= TWO_PI;
    return rel <= v->g->dphi;
}

/* Area of the disk |x - p| <= rho intersected with the annular sector:
 * Green's theorem, area = 1/2 closed integral of (x - p) x dx along the
 * boundary of the intersection, taken about p so that no large terms cancel
 * ("Disk and annular sector" in docs/overlap.md).  The boundary consists of
 * arcs of the disk's circle (contributing rho^2 dtau), arcs of the circles
 * r1 and r0 (r (r - d) dbeta + r d d(beta - sin beta)) and pieces of the two
 * rays (length times the distance of p from the ray). */
static double disk_cell_area(const disk_view *v, double rho)
{
    const cylcell *g = v->g;
    double r0 = g->r0, r1 = g->r1, d = v->d;
    if (!(rho > 0.0))
        return 0.0;
    double cap = PI * rho * rho;
    if (isfinite(r1))
        cap = fmin(cap, 0.5 * g->dphi * (r1 - r0) * (r1 + r0));
    if (d == 0.0) {
        double ro = fmin(rho, r1);
        return ro > r0 ? 0.5 * g->dphi * (ro - r0) * (ro + r0) : 0.0;
    }
    if (g->full) {
        double area = disk_annulus_area(d, rho, r0, r1);
        return area > 0.0 ? fmin(area, cap) : 0.0;
    }
    double t1, b1, t0 = PI, b0 = 0.0;
    circle_parts(d, rho, r1, &t1, &b1);
    if (r0 > 0.0)
        circle_parts(d, rho, r0, &t0, &b0);
    double tau[8];
    int nt = 0;
    double sum = 0.0;
    /* the side of ray k's line: s_k = (e_k x q) along the circle
     * q = p + rho (cos tau, sin tau) changes sign at two angles lo < hi;
     * pos_in[k]: s_k > 0 for lo < tau < hi */
    double lo[2] = {0.0, 0.0}, hi[2] = {0.0, 0.0};
    int pos_in[2];
    for (int k = 0; k < 2; k++) {
        double cc = v->cc[k], s = v->s[k];
        if (!(fabs(cc) < rho)) {
            pos_in[k] = cc < 0.0; /* no crossing: the empty (lo, hi) is "in" */
            continue;
        }
        double hh = sqrt((rho - cc) * (rho + cc));
        /* the ray's line crosses the circle at s +- hh along the ray:
         * X - p = +-hh e - cc w, in the frame of u */
        double ex = v->ex[k], ey = v->ey[k];
        double ta = atan2(hh * ey - cc * ex, hh * ex + cc * ey);
        double tz = atan2(-hh * ey - cc * ex, -hh * ex + cc * ey);
        lo[k] = fmin(ta, tz);
        hi[k] = fmax(ta, tz);
        tau[nt++] = ta;
        tau[nt++] = tz;
        /* s_k at tau = 0 and tau = pi; the larger in magnitude decides */
        double s0 = cc - rho * ey, spi = cc + rho * ey;
        if (fabs(s0) >= fabs(spi))
            pos_in[k] = (lo[k] < 0.0 && 0.0 < hi[k]) ? s0 > 0.0 : !(s0 > 0.0);
        else
            pos_in[k] = !(spi > 0.0);
        /* the ray segment r0 <= s <= r1 inside the disk; ray 0 runs outwards
         * along the boundary, ray 1 inwards */
        double sa = fmax(r0, s - hh), sb = fmin(r1, s + hh);
        if (sb > sa)
            sum += (k == 0 ? 1.0 : -1.0) * (sb - sa) * cc;
    }
    if (t1 > 0.0 && t1 < PI)
        tau[nt++] = t1, tau[nt++] = -t1;
    if (t0 > 0.0 && t0 < PI)
        tau[nt++] = t0, tau[nt++] = -t0;
    /* arcs of the disk's circle inside the cell */
    sort_doubles(tau, nt);
    double prev = -PI, arcs = 0.0;
    for (int i = 0; i <= nt; i++) {
        double next = i < nt ? tau[i] : PI;
        if (next > prev) {
            double tm = 0.5 * (prev + next), am = fabs(tm);
            if (am >= t1 && am <= t0) {
                int in0 = (lo[0] < tm && tm < hi[0]) ? pos_in[0] : !pos_in[0];
                int in1 = (lo[1] < tm && tm < hi[1]) ? !pos_in[1] : pos_in[1];
                if (g->wide ? (in0 || in1) : (in0 && in1))
                    arcs += next - prev;
            }
        }
        prev = next;
    }
    sum += rho * rho * arcs;
    /* arcs of the circles r1 (counterclockwise) and r0 (clockwise) inside the
     * disk and the wedge */
    for (int k = 0; k < (r0 > 0.0 ? 2 : 1); k++) {
        double r = k == 0 ? r1 : r0, b = k == 0 ? b1 : b0;
        if (!(b > 0.0))
            continue;
        double bk[4] = {v->eb[0], v->eb[1]}, fk[4] = {v->feb[0], v->feb[1]};
        int nb = 2;
        if (b < PI) {
            double fb = bms(b);
            bk[nb] = b, fk[nb++] = fb;
            bk[nb] = -b, fk[nb++] = -fb;
        }
        sort_pairs(bk, fk, nb);
        double bprev = -PI, fprev = -PI, part = 0.0; /* bms(-pi) = -pi */
        for (int i = 0; i <= nb; i++) {
            double next = i < nb ? bk[i] : PI, fnext = i < nb ? fk[i] : PI;
            if (next > bprev) {
                double bm = 0.5 * (bprev + next);
                if (fabs(bm) <= b && beta_in_wedge(v, bm))
                    part += r * (r - d) * (next - bprev) + r * d * (fnext - fprev);
                fprev = fnext;
            }
            bprev = next;
        }
        sum += k == 0 ? part : -part;
    }
    double area = 0.5 * sum;
    return area > 0.0 ? fmin(area, cap) : 0.0;
}

enum { K_EMPTY, K_DISK_IN, K_CELL_IN, K_CUT };

/* How the disk |x - p| <= rho meets the annular sector. */
static int disk_cell_kind(const cylcell *g, double px, double py, double d, double rho)
{
    double r0 = g->r0, r1 = g->r1;
    if (d - rho >= r1 || d + rho <= r0)
        return K_EMPTY;
    int rays, w = disk_wedge(g, px, py, d, rho, &rays);
    if (w == W_OUTSIDE)
        return K_EMPTY;
    if (w == W_INSIDE && d + rho <= r1 && (r0 == 0.0 || d - rho >= r0))
        return K_DISK_IN;
    /* the sector inside the disk: its farthest point from p is */
    double far = r0 == 0.0 ? d : 0.0;
    for (int k = 0; k < (r0 > 0.0 ? 2 : 1); k++) {
        double r = k == 0 ? r1 : r0, f;
        if (in_wedge(g, -px, -py)) {
            f = r + d;
        } else {
            double a0 = hypot(r * g->e0[0] - px, r * g->e0[1] - py);
            double a1 = hypot(r * g->e1[0] - px, r * g->e1[1] - py);
            f = fmax(a0, a1);
        }
        far = fmax(far, f);
    }
    return far <= rho ? K_CELL_IN : K_CUT;
}

/* pi * integral of (R^2 - w^2) over wa <= w <= wb, -R <= wa <= wb <= R: the
 * part of the ball between two parallel planes, without cancellation. */
static double zone(double R, double wa, double wb)
{
    double pa = R - wa, ma = R + wa, pb = R - wb, mb = R + wb;
    return PI * (wb - wa) * (pa * ma + pb * mb + 0.5 * (pa * mb + ma * pb)) / 3.0;
}

/* ---- adaptive quadrature --------------------------------------------------- */

/* The slices of a latitude band theta_a..theta_a + dth, z = cz + R sin(theta), taken at
 * theta = theta_a + dth S(t), S(t) = t^2 (3 - 2t), 0 <= t <= 1: dtheta = 6 dth t (1 - t) dt
 * vanishes at both ends, where the area behaves like a power 1/2 or 3/2 of the distance
 * to an event, so that the integrand in t is smooth there. */
typedef struct slice_par {
    const disk_view *v;
    double R, ta, dth;
} slice_par;

/* The band's integrand at the n values t[i]: the slice's area times dz/dt. */
static void slice_areas(const slice_par *s, const double *t, double *f, int n)
{
    const cylcell *g = s->v->g;
    if (g->full && s->v->d > 0.0) {
        annulus_slices(s->v->d, g->r0, g->r1, s->R, s->ta, s->dth, t, f, n);
        return;
    }
    for (int i = 0; i < n; i++) {
        double th = s->ta + s->dth * (t[i] * t[i] * (3.0 - 2.0 * t[i]));
        double rho = s->R * cos(th);
        f[i] = rho > 0.0 ? disk_cell_area(s->v, rho) * rho * 6.0 * s->dth * t[i] * (1.0 - t[i])
                         : 0.0; /* dz = rho dtheta */
    }
}

/* One interval t in [a, b] of a band of the global adaptive scheme. */
typedef struct quad_piece {
    double ta, dth, a, b, res, err;
} quad_piece;

/* QUADPACK's error estimate of a Gauss-Kronrod rule (Piessens et al. 1983, as in GSL's
 * gsl_integration_qk): |K - G| scaled by the integrand's variation about its mean, and
 * not below 50 eps of the integral of |f|. */
static double gk_error(double diff, double resabs, double resasc)
{
    double err = fabs(diff);
    if (resasc != 0.0 && err != 0.0) {
        double x = 200.0 * err / resasc, scale = x * sqrt(x); /* x^1.5 */
        err = scale < 1.0 ? resasc * scale : resasc;
    }
    if (resabs > DBL_MIN / (50.0 * DBL_EPSILON) && err < 50.0 * DBL_EPSILON * resabs)
        err = 50.0 * DBL_EPSILON * resabs;
    return err;
}

/* The 41-point Gauss-Kronrod rule (kronrod41.h) on the piece, its integrand taken at all
 * nodes in one call (slice_areas' loop over them is vectorised). */
static void piece_eval(quad_piece *q, slice_par *sp)
{
    enum { PADDED = (41 + ANNULUS_LANES - 1) / ANNULUS_LANES * ANNULUS_LANES };
    double c = 0.5 * (q->a + q->b), h = 0.5 * (q->b - q->a), t[PADDED] = {0}, f[PADDED];
    for (int j = 0; j < 20; j++) {
        t[j] = c - h * GK41_X[j];
        t[40 - j] = c + h * GK41_X[j];
    }
    t[20] = c;
    sp->ta = q->ta;
    sp->dth = q->dth;
    slice_areas(sp, t, f, 41);
    double resk = f[20] * GK41_WK[20], resg = 0.0, resabs = fabs(resk);
    for (int j = 0; j < 20; j++) {
        double pair = f[j] + f[40 - j];
        resk += GK41_WK[j] * pair;
        resabs += GK41_WK[j] * (fabs(f[j]) + fabs(f[40 - j]));
        if (j & 1)
            resg += GK41_WG[j / 2] * pair;
    }
    double mean = 0.5 * resk, resasc = GK41_WK[20] * fabs(f[20] - mean);
    for (int j = 0; j < 20; j++)
        resasc += GK41_WK[j] * (fabs(f[j] - mean) + fabs(f[40 - j] - mean));
    q->res = resk * h;
    q->err = gk_error((resk - resg) * h, resabs * fabs(h), resasc * fabs(h));
}

#define QUAD_LIMIT 96

/* QUADPACK's QAGP strategy with the 41-point Gauss-Kronrod rule: every band is one
 * interval to start with, then the interval with the largest error estimate is bisected
 * until the total error estimate is below max(epsabs, epsrel |total|), total = known +
 * the integrals. */
static double integrate_bands(quad_piece *q, int n, slice_par *sp, double known, double epsabs,
                              double epsrel)
{
    for (int i = 0; i < n; i++)
        piece_eval(&q[i], sp);
    for (;;) {
        double tot = known, err = 0.0;
        int worst = 0;
        for (int i = 0; i < n; i++) {
            tot += q[i].res;
            err += q[i].err;
            if (q[i].err > q[worst].err)
                worst = i;
        }
        if (err <= fmax(epsabs, epsrel * fabs(tot)) || n >= QUAD_LIMIT)
            return tot;
        quad_piece *w = &q[worst];
        double mid = 0.5 * (w->a + w->b);
        if (!(mid > w->a && mid < w->b))
            return tot;
        q[n] = *w;
        q[n].a = mid;
        w->b = mid;
        piece_eval(w, sp);
        piece_eval(&q[n], sp);
        n++;
    }
}

static void add_radius(double *v, int *n, double rho)
{
    if (rho > 0.0 && isfinite(rho))
        v[(*n)++] = rho;
}

double overlap_sphere_cylcell(const double c[3], double R, double r0, double r1, double phi0,
                              double phi1, double z0, double z1)
{
    if (isnan(c[0]) || isnan(c[1]) || isnan(c[2]) || isnan(R))
        return NAN;
    if (!(R > 0.0))
        return 0.0;
    cylcell g;
    int st = cell_setup(&g, r0, r1, phi0, phi1, z0, z1);
    if (st <= 0)
        return st < 0 ? NAN : 0.0;
    double cz = c[2];
    double wlo = fmax(z0 - cz, -R), whi = fmin(z1 - cz, R);
    if (!(wlo < whi))
        return 0.0;
    double px = c[0], py = c[1], d = hypot(px, py);
    if (d - R >= g.r1 || d + R <= g.r0)
        return 0.0;
    /* drop the bounds that do not meet the ball */
    if (g.r0 > 0.0 && d - R >= g.r0)
        g.r0 = 0.0;
    if (d + R <= g.r1)
        g.r1 = INFINITY;
    int rays, w = disk_wedge(&g, px, py, d, R, &rays);
    if (w == W_OUTSIDE)
        return 0.0;
    if (w == W_INSIDE && !g.full) {
        g.full = 1;
        g.wide = 1;
        g.dphi = TWO_PI;
    }
    int radial = g.r0 > 0.0 || isfinite(g.r1);
    if (!radial && g.full) {
        if (wlo == -R && whi == R)
            return FOUR_THIRDS_PI * R * R * R;
        return zone(R, wlo, whi);
    }
    /* one ray of a wedge and a ball away from the axis: a half-space cut */
    if (!radial && (rays == 1 || rays == 2) && d > R) {
        const double *e = rays == 1 ? g.e0 : g.e1;
        /* inward normal of the ray's plane: e rotated by +90 (ray 0) or -90 */
        double dist = rays == 1 ? cross2(e, px, py) : -cross2(e, px, py);
        double cc[3] = {dist, 0.0, 0.0};
        double lo[3] = {0.0, -INFINITY, wlo}, hi[3] = {INFINITY, INFINITY, whi};
        return overlap_sphere_box(cc, R, lo, hi);
    }
    if (isinf(g.r1))
        g.r1 = d + 2.0 * R; /* same cell as far as the ball sees */

    /* Disk radii at which the cross-section changes shape ("Quadrature"). */
    double rk[16];
    int nk = 0;
    double rb[2] = {g.r1, g.r0};
    for (int k = 0; k < (g.r0 > 0.0 ? 2 : 1); k++) {
        if (in_wedge(&g, px, py))
            add_radius(rk, &nk, fabs(d - rb[k]));
        if (in_wedge(&g, -px, -py))
            add_radius(rk, &nk, d + rb[k]);
    }
    if (!g.full) {
        const double *e[2] = {g.e0, g.e1};
        for (int k = 0; k < 2; k++) {
            double s = e[k][0] * px + e[k][1] * py, cc = cross2(e[k], px, py);
            if (s >= g.r0 && s <= g.r1)
                add_radius(rk, &nk, fabs(cc));
            add_radius(rk, &nk, hypot(g.r1 - s, cc));
            add_radius(rk, &nk, g.r0 > 0.0 ? hypot(g.r0 - s, cc) : d);
        }
    }
    /* the slices in between: by the latitude theta (z = cz + R sin(theta),
     * rho = R cos(theta)), in which the area is analytic between the events
     * and at the poles */
    double wb[34], tb[34];
    int nw = 0;
    wb[nw] = wlo, tb[nw++] = atan2(wlo, sqrt((R - wlo) * (R + wlo)));
    wb[nw] = whi, tb[nw++] = atan2(whi, sqrt((R - whi) * (R + whi)));
    for (int k = 0; k < nk; k++) {
        if (rk[k] >= R)
            continue;
        double h = sqrt((R - rk[k]) * (R + rk[k])), t = atan2(h, rk[k]);
        if (-h > wlo && -h < whi)
            wb[nw] = -h, tb[nw++] = -t;
        if (h > wlo && h < whi)
            wb[nw] = h, tb[nw++] = t;
    }
    sort_pairs(wb, tb, nw);

    disk_view view;
    view_setup(&view, &g, px, py, d);
    slice_par sp = {&view, R, 0.0, 0.0};
    quad_piece bands[QUAD_LIMIT];
    int nb = 0;
    double vol = 0.0;
    for (int i = 0; i + 1 < nw; i++) {
        double wa = wb[i], wz = wb[i + 1];
        if (!(wz > wa))
            continue;
        double tm = 0.5 * (tb[i] + tb[i + 1]);
        switch (disk_cell_kind(&g, px, py, d, R * cos(tm))) {
        case K_EMPTY:
            break;
        case K_DISK_IN:
            vol += zone(R, wa, wz);
            break;
        case K_CELL_IN:
            vol += 0.5 * g.dphi * (g.r1 - g.r0) * (g.r1 + g.r0) * (wz - wa);
            break;
        default:
            bands[nb++] = (quad_piece){tb[i], tb[i + 1] - tb[i], 0.0, 1.0, 0.0, 0.0};
            break;
        }
    }
    if (nb > 0)
        vol = integrate_bands(bands, nb, &sp, vol, 1e-14 * R * R * R, 1e-12);
    double V = FOUR_THIRDS_PI * R * R * R;
    return vol > 0.0 ? fmin(vol, V) : 0.0;
}

void overlap_sphere_rings(const double c[3], double R, int n, const double *r, double z0,
                          double z1, double *vol)
{
    /* the largest circle of the ball in the slab: the ball's part in the slab lies in
     * d - rho <= r <= d + rho, and a ring outside that range gets an exact 0 (the two
     * cylinders' volumes are then equal, but come from different quadratures) */
    double w0 = z0 - c[2], w1 = z1 - c[2];
    double wn = w0 > 0.0 ? w0 : (w1 < 0.0 ? w1 : 0.0);
    double rho = fabs(wn) < R ? sqrt((R - wn) * (R + wn)) : 0.0, d = hypot(c[0], c[1]);
    /* the ball inside the cylinder r <= r[k] (none inside r <= 0) */
    double inner = NAN;
    for (int k = 0; k < n; k++) {
        if (!(r[k + 1] > d - rho && r[k] < d + rho)) {
            vol[k] = isnan(d + rho + R) ? NAN : 0.0;
            inner = NAN;
            continue;
        }
        if (isnan(inner))
            inner = r[k] > 0.0 ? overlap_sphere_cylcell(c, R, 0.0, r[k], 0.0, TWO_PI, z0, z1) : 0.0;
        double outer = overlap_sphere_cylcell(c, R, 0.0, r[k + 1], 0.0, TWO_PI, z0, z1);
        double v = outer - inner;
        vol[k] = v > 0.0 ? v : (isnan(v) ? v : 0.0);
        inner = outer;
    }
}

/* ---- segment and cylindrical cell ----------------------------------------- */

/* The fraction of a small ball about (x, y, z) inside the cell. */
static double cell_density(const cylcell *g, double x, double y, double z)
{
    double w = 1.0;
    if (z < g->z0 || z > g->z1)
        return 0.0;
    if (z == g->z0 || z == g->z1)
        w *= 0.5;
    double q = x * x + y * y;
    if (q > g->r1 * g->r1 || q < g->r0 * g->r0)
        return 0.0;
    if (q == g->r1 * g->r1 || (g->r0 > 0.0 && q == g->r0 * g->r0))
        w *= 0.5;
    if (g->full)
        return w;
    if (x == 0.0 && y == 0.0)
        return w * g->dphi / TWO_PI;
    double s0 = cross2(g->e0, x, y), s1 = -cross2(g->e1, x, y);
    if ((s0 == 0.0 && g->e0[0] * x + g->e0[1] * y > 0.0) ||
        (s1 == 0.0 && g->e1[0] * x + g->e1[1] * y > 0.0))
        return 0.5 * w;
    return in_wedge(g, x, y) ? w : 0.0;
}

static void add_param(double *t, int *n, double v)
{
    if (v > 0.0 && v < 1.0)
        t[(*n)++] = v;
}

double segment_fraction_cylcell(const double a[3], const double b[3], double r0, double r1,
                                double phi0, double phi1, double z0, double z1)
{
    for (int i = 0; i < 3; i++)
        if (isnan(a[i]) || isnan(b[i]))
            return NAN;
    cylcell g;
    int st = cell_setup(&g, r0, r1, phi0, phi1, z0, z1);
    if (st <= 0)
        return st < 0 ? NAN : 0.0;
    double dx = b[0] - a[0], dy = b[1] - a[1], dz = b[2] - a[2];
    double t[12];
    int n = 0;
    t[n++] = 0.0;
    if (dz != 0.0) {
        add_param(t, &n, (z0 - a[2]) / dz);
        add_param(t, &n, (z1 - a[2]) / dz);
    }
    double A = dx * dx + dy * dy;
    if (A > 0.0) {
        double B = a[0] * dx + a[1] * dy, C = a[0] * a[0] + a[1] * a[1];
        add_param(t, &n, -B / A); /* closest to the axis (crossing it, maybe) */
        double rr[2] = {g.r1, g.r0};
        for (int k = 0; k < 2; k++) {
            if (!(rr[k] > 0.0) || !isfinite(rr[k]))
                continue;
            double cr = C - rr[k] * rr[k], disc = B * B - A * cr;
            if (!(disc > 0.0))
                continue;
            double q = -(B + copysign(sqrt(disc), B));
            if (q != 0.0) {
                add_param(t, &n, q / A);
                add_param(t, &n, cr / q);
            }
        }
        if (!g.full) {
            const double *e[2] = {g.e0, g.e1};
            for (int k = 0; k < 2; k++) {
                double den = cross2(e[k], dx, dy);
                if (den != 0.0)
                    add_param(t, &n, -cross2(e[k], a[0], a[1]) / den);
            }
        }
    }
    t[n++] = 1.0;
    sort_doubles(t, n);
    double f = 0.0;
    for (int i = 0; i + 1 < n; i++) {
        if (!(t[i + 1] > t[i]))
            continue;
        double tm = 0.5 * (t[i] + t[i + 1]);
        double w = cell_density(&g, a[0] + tm * dx, a[1] + tm * dy, a[2] + tm * dz);
        f += w * (t[i + 1] - t[i]);
    }
    return f;
}

double overlap_sphere_sphere(double d, double R1, double R2)
{
    if (isnan(d) || isnan(R1) || isnan(R2))
        return NAN;
    if (!(R1 > 0.0) || !(R2 > 0.0))
        return 0.0;
    d = fabs(d);
    if (d >= R1 + R2)
        return 0.0;
    double rmin = fmin(R1, R2);
    if (d <= fabs(R1 - R2))
        return FOUR_THIRDS_PI * rmin * rmin * rmin;
    double g = R1 + R2 - d, m = R1 - R2;
    return M_PI * g * g * (d * d + 2.0 * d * (R1 + R2) - 3.0 * m * m) / (12.0 * d);
}
