/* Heaviside-bin kernels (averaging/overlap.c): sphere-cell volumes and
 * segment-cell fractions against analytic values, against partitions of
 * space (the pieces must add up to the whole), against each other (a wedge
 * of a cylindrical cell that is a box) and against a brute-force nested
 * quadrature written here. */
#include <config.h>

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "assert_close.h"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>
#include <gsl/gsl_rng.h>
#include <math.h>

#include "overlap.h"

#define PI 3.14159265358979323846
#define INF INFINITY

static double ball(double R)
{
    return 4.0 / 3.0 * PI * R * R * R;
}

/* the cap of height h of a ball of radius R */
static double cap(double R, double h)
{
    return PI * h * h * (3.0 * R - h) / 3.0;
}

/* the part of the ball between z = zc + wa and zc + wb, as a difference of caps */
static double slab(double R, double wa, double wb)
{
    wa = fmax(wa, -R);
    wb = fmin(wb, R);
    if (!(wb > wa))
        return 0.0;
    return cap(R, R - wa) - cap(R, R - wb);
}

/* cell edges along one axis: from below lo to above hi, random widths
 * between wmin and wmax; the outer edges are infinite when open_ends */
static int edges(gsl_rng *rng, double lo, double hi, double wmin, double wmax, int open_ends,
                 double *e, int max)
{
    int n = 0;
    double x = lo - wmin - (wmax - wmin) * gsl_rng_uniform(rng);
    e[n++] = open_ends ? -INF : x;
    while (x < hi && n < max - 2) {
        x += wmin + (wmax - wmin) * gsl_rng_uniform(rng);
        e[n++] = x;
    }
    if (open_ends)
        e[n++] = INF;
    return n;
}

/* ---- ball and box ----------------------------------------------------------- */

static void test_box_analytic(void **state)
{
    (void)state;
    const double R = 0.7, c[3] = {0.1, -0.3, 0.45};
    const double V = ball(R);
    /* inside, outside, far corners */
    double lo[3] = {-1, -1, -1}, hi[3] = {1, 1, 2};
    assert_close(overlap_sphere_box(c, R, lo, hi), V, 1e-15 * V);
    double lo2[3] = {0.8, -INF, -INF}, hi2[3] = {INF, INF, INF};
    assert_true(overlap_sphere_box(c, R, lo2, hi2) == 0.0);
    double all_lo[3] = {-INF, -INF, -INF}, all_hi[3] = {INF, INF, INF};
    assert_close(overlap_sphere_box(c, R, all_lo, all_hi), V, 1e-15 * V);
    /* one cut plane along each axis, from either side: caps */
    for (int ax = 0; ax < 3; ax++)
        for (double h = 0.0; h <= 2.0 * R; h += 0.1 * R) {
            double l[3] = {-INF, -INF, -INF}, u[3] = {INF, INF, INF};
            l[ax] = c[ax] + R - h;
            assert_close(overlap_sphere_box(c, R, l, u), cap(R, h), 1e-14 * V);
            l[ax] = -INF;
            u[ax] = c[ax] - R + h;
            assert_close(overlap_sphere_box(c, R, l, u), cap(R, h), 1e-14 * V);
            /* a slab: two parallel planes */
            l[ax] = c[ax] - 0.3 * h;
            assert_close(overlap_sphere_box(c, R, l, u), slab(R, -0.3 * h, -R + h), 1e-14 * V);
        }
    /* centred on a face, an edge, a corner of the unit cube (R < 1) */
    const double z[3] = {0, 0, 0}, one[3] = {1, 1, 1};
    double cf[3] = {0.5, 0.5, 0.0}, ce[3] = {0.5, 0.0, 0.0}, cc[3] = {0, 0, 0};
    double r = 0.45, v = ball(r);
    assert_close(overlap_sphere_box(cf, r, z, one), v / 2, 1e-15 * v);
    assert_close(overlap_sphere_box(ce, r, z, one), v / 4, 1e-15 * v);
    assert_close(overlap_sphere_box(cc, r, z, one), v / 8, 1e-15 * v);
    /* the same at every corner and edge of the cube, and large balls with
     * infinite boxes */
    for (int k = 0; k < 8; k++) {
        double p[3] = {(double)(k & 1), (double)((k >> 1) & 1), (double)((k >> 2) & 1)};
        assert_close(overlap_sphere_box(p, r, z, one), v / 8, 1e-15 * v);
        double l[3], u[3];
        for (int i = 0; i < 3; i++) {
            l[i] = p[i] == 0.0 ? 0.0 : -INF;
            u[i] = p[i] == 0.0 ? INF : 1.0;
        }
        assert_close(overlap_sphere_box(p, 7.0, l, u), ball(7.0) / 8, 1e-15 * ball(7.0));
    }
    /* the box inside the ball */
    double bl[3] = {0.0, -0.4, 0.3}, bh[3] = {0.2, -0.1, 0.5};
    assert_close(overlap_sphere_box(c, R, bl, bh), 0.2 * 0.3 * 0.2, 1e-16);
    /* empty or degenerate boxes and balls */
    double e_lo[3] = {0, 0, 0.3}, e_hi[3] = {1, 1, 0.3};
    assert_true(overlap_sphere_box(c, R, e_lo, e_hi) == 0.0);
    assert_true(overlap_sphere_box(c, 0.0, lo, hi) == 0.0);
    assert_true(overlap_sphere_box(c, -1.0, lo, hi) == 0.0);
    assert_true(isnan(overlap_sphere_box(c, NAN, lo, hi)));
}

static void test_box_partition(void **state)
{
    (void)state;
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    gsl_rng_set(rng, 11);
    double worst = 0.0;
    for (int trial = 0; trial < 300; trial++) {
        double c[3], R = 0.05 + gsl_rng_uniform(rng);
        for (int i = 0; i < 3; i++)
            c[i] = gsl_rng_uniform(rng) - 0.5;
        /* cell edges from R/5 to 2R: both smaller and larger than R */
        double e[3][64];
        int n[3];
        double wmin = 0.2 * R * (1 + (trial % 3)), wmax = 2.0 * R;
        for (int i = 0; i < 3; i++)
            n[i] = edges(rng, c[i] - R, c[i] + R, wmin, wmax, trial % 2, e[i], 64);
        double sum = 0.0;
        for (int i = 0; i + 1 < n[0]; i++)
            for (int j = 0; j + 1 < n[1]; j++)
                for (int k = 0; k + 1 < n[2]; k++) {
                    double lo[3] = {e[0][i], e[1][j], e[2][k]};
                    double hi[3] = {e[0][i + 1], e[1][j + 1], e[2][k + 1]};
                    double v = overlap_sphere_box(c, R, lo, hi);
                    assert_true(v >= 0.0 && isfinite(v));
                    sum += v;
                }
        worst = fmax(worst, fabs(sum / ball(R) - 1.0));
        assert_close(sum, ball(R), 1e-12 * ball(R));
    }
    print_message("# box partition: worst relative error %.2g\n", worst);
    gsl_rng_free(rng);
}

/* ---- brute force: the volume as the integral over the cross-section of the
 * length of the vertical chord inside the cell, by nested adaptive
 * quadrature (GSL QAGS/QAGP) ---- */

typedef struct brute {
    double c[3], R, z0, z1;
    /* box: x0..x1, y0..y1; cylinder: r0..r1, phi0..phi1 */
    double u0, u1, v0, v1;
    int cyl;
    double u; /* the outer variable during the inner integration */
    gsl_integration_workspace *win, *wout;
} brute;

/* length of [cz - s, cz + s] inside [z0, z1], s^2 = R^2 - q */
static double chord(const brute *b, double q)
{
    double s2 = b->R * b->R - q;
    if (!(s2 > 0.0))
        return 0.0;
    double s = sqrt(s2);
    double len = fmin(b->z1, b->c[2] + s) - fmax(b->z0, b->c[2] - s);
    return len > 0.0 ? len : 0.0;
}

static double inner_f(double v, void *p)
{
    const brute *b = p;
    double x, y;
    if (b->cyl) {
        x = b->u * cos(v);
        y = b->u * sin(v);
    } else {
        x = b->u;
        y = v;
    }
    double dx = x - b->c[0], dy = y - b->c[1];
    return chord(b, dx * dx + dy * dy);
}

/* the inner integral, with breakpoints where the chord starts or is clipped */
static double outer_f(double u, void *p)
{
    brute *b = p;
    b->u = u;
    double pts[16];
    int n = 0;
    pts[n++] = b->v0;
    double lev[3] = {b->R, fabs(b->z1 - b->c[2]), fabs(b->c[2] - b->z0)};
    for (int k = 0; k < 3; k++) {
        double s = lev[k];
        if (!(s > 0.0 && s <= b->R))
            continue;
        double q = b->R * b->R - (k ? s * s : 0.0); /* |x - c|^2 at the kink */
        if (!b->cyl) {
            double w2 = q - (u - b->c[0]) * (u - b->c[0]);
            if (w2 > 0.0) {
                double vv[2] = {b->c[1] - sqrt(w2), b->c[1] + sqrt(w2)};
                for (int j = 0; j < 2; j++)
                    if (vv[j] > b->v0 && vv[j] < b->v1)
                        pts[n++] = vv[j];
            }
        } else {
            double d = hypot(b->c[0], b->c[1]), pc = atan2(b->c[1], b->c[0]);
            if (d * u == 0.0)
                continue;
            double cs = (u * u + d * d - q) / (2.0 * u * d);
            if (fabs(cs) < 1.0) {
                double a = acos(cs);
                double vv[2] = {pc - a, pc + a};
                for (int j = 0; j < 2; j++)
                    for (int m = -2; m <= 2; m++) {
                        double t = vv[j] + 2.0 * PI * m;
                        if (t > b->v0 && t < b->v1)
                            pts[n++] = t;
                    }
            }
        }
    }
    pts[n++] = b->v1;
    for (int i = 1; i < n; i++) /* sort */
        for (int j = i; j > 0 && pts[j] < pts[j - 1]; j--) {
            double t = pts[j];
            pts[j] = pts[j - 1];
            pts[j - 1] = t;
        }
    int m = 1; /* drop repeated points */
    for (int i = 1; i < n; i++)
        if (pts[i] > pts[m - 1])
            pts[m++] = pts[i];
    n = m;
    if (n < 2)
        return 0.0;
    gsl_function f = {inner_f, b};
    double res, err;
    gsl_integration_qagp(&f, pts, (size_t)n, 1e-14, 1e-12, 1000, b->win, &res, &err);
    return b->cyl ? res * u : res;
}

/* breakpoints of the outer integral: where the kink circles (radius^2 = q
 * about the centre) touch the line u = const or cross the inner bounds */
static int outer_breaks(const brute *b, double lo, double hi, double *pts)
{
    int n = 0;
    pts[n++] = lo;
    double lev[3] = {b->R, fabs(b->z1 - b->c[2]), fabs(b->c[2] - b->z0)};
    double d = hypot(b->c[0], b->c[1]);
    for (int k = 0; k < 3; k++) {
        double s = lev[k];
        if (!(s > 0.0 && s <= b->R))
            continue;
        double q = b->R * b->R - (k ? s * s : 0.0), rq = sqrt(q), cand[6];
        int nc = 0;
        if (!b->cyl) {
            cand[nc++] = b->c[0] - rq;
            cand[nc++] = b->c[0] + rq;
            double vb[2] = {b->v0, b->v1};
            for (int j = 0; j < 2; j++) {
                double w2 = q - (vb[j] - b->c[1]) * (vb[j] - b->c[1]);
                if (w2 > 0.0) {
                    cand[nc++] = b->c[0] - sqrt(w2);
                    cand[nc++] = b->c[0] + sqrt(w2);
                }
            }
        } else {
            cand[nc++] = fabs(d - rq);
            cand[nc++] = d + rq;
            double vb[2] = {b->v0, b->v1};
            for (int j = 0; j < 2 && b->v1 - b->v0 < 2 * PI; j++) {
                double ex = cos(vb[j]), ey = sin(vb[j]);
                double sp = ex * b->c[0] + ey * b->c[1], cc = ex * b->c[1] - ey * b->c[0];
                if (q > cc * cc) {
                    cand[nc++] = sp - sqrt(q - cc * cc);
                    cand[nc++] = sp + sqrt(q - cc * cc);
                }
            }
        }
        for (int j = 0; j < nc; j++)
            if (cand[j] > lo && cand[j] < hi)
                pts[n++] = cand[j];
    }
    pts[n++] = hi;
    for (int i = 1; i < n; i++)
        for (int j = i; j > 0 && pts[j] < pts[j - 1]; j--) {
            double t = pts[j];
            pts[j] = pts[j - 1];
            pts[j - 1] = t;
        }
    int m = 1;
    for (int i = 1; i < n; i++)
        if (pts[i] > pts[m - 1])
            pts[m++] = pts[i];
    return m;
}

static double brute_volume(brute *b)
{
    b->win = gsl_integration_workspace_alloc(1000);
    b->wout = gsl_integration_workspace_alloc(1000);
    double lo, hi;
    if (b->cyl) {
        double d = hypot(b->c[0], b->c[1]);
        lo = fmax(b->u0, d - b->R);
        hi = fmin(b->u1, d + b->R);
    } else {
        lo = fmax(b->u0, b->c[0] - b->R);
        hi = fmin(b->u1, b->c[0] + b->R);
        b->v0 = fmax(b->v0, b->c[1] - b->R);
        b->v1 = fmin(b->v1, b->c[1] + b->R);
    }
    double res = 0.0, err, pts[32];
    gsl_function f = {outer_f, b};
    if (hi > lo) {
        int n = outer_breaks(b, lo, hi, pts);
        gsl_integration_qagp(&f, pts, (size_t)n, 1e-15, 1e-13, 1000, b->wout, &res, &err);
    }
    gsl_integration_workspace_free(b->win);
    gsl_integration_workspace_free(b->wout);
    return res;
}

static void test_box_brute_force(void **state)
{
    (void)state;
    gsl_error_handler_t *old = gsl_set_error_handler_off();
    /* centre, radius, box: edges, corners, thin boxes, a box inside */
    const double cases[][10] = {
        {0.1, 0.2, 0.3, 0.5, 0.0, 1.0, 0.0, 1.0, 0.0, 1.0},          /* corner */
        {0.1, 0.2, 0.3, 0.5, 0.0, 1.0, 0.25, 1.0, -1.0, 1.0},        /* edge */
        {0.1, 0.2, 0.3, 0.5, 0.2, 0.35, -1.0, 0.4, 0.05, 0.55},      /* many faces */
        {0.0, 0.0, 0.0, 1.0, 0.3, 0.5, 0.3, 0.9, 0.3, 0.5},          /* cell smaller than R */
        {0.5, 0.5, 0.5, 0.3, 0.6, 0.7, 0.55, INF, -INF, 0.45},       /* thin */
        {-0.2, 0.1, 0.0, 0.7, -INF, -0.3, -INF, 0.0, -0.5, INF},     /* infinite */
    };
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        const double *q = cases[k];
        brute b = {{q[0], q[1], q[2]}, q[3], q[8], q[9], q[4], q[5], q[6], q[7], 0, 0, 0, 0};
        double lo[3] = {q[4], q[6], q[8]}, hi[3] = {q[5], q[7], q[9]};
        double v = overlap_sphere_box(q, q[3], lo, hi), w = brute_volume(&b);
        print_message("# box case %zu: %.15g brute force %.15g (rel %.1g)\n", k, v, w,
                      fabs(v - w) / w);
        assert_close(v, w, 1e-13 * w); /* the brute force to 1e-13: 3e-15 seen */
    }
    gsl_set_error_handler(old);
}

/* Random blocks of boxes laid out as a grid lays out its cells (each box's upper bound is its
 * lower bound plus the spacing, the next box's lower bound the origin plus a multiple of it,
 * which can differ in the last bit), some with the centre on a plane (thresholds of +0 and -0),
 * some infinite, some larger than the memo holds: overlap_sphere_cells() must give every box
 * overlap_sphere_box()'s volume to the bit, and a block that holds the ball the whole ball. */
static void test_box_cells(void **state)
{
    (void)state;
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    enum { MAXN = 20 };
    size_t boxes = 0, covered = 0;
    for (int trial = 0; trial < 3000; trial++) {
        int n[3];
        double lo[3][MAXN], hi[3][MAXN], c[3];
        double R = trial % 500 == 7 ? 0.0 : 0.02 + 0.6 * gsl_rng_uniform(rng);
        for (int d = 0; d < 3; d++) {
            double h = 0.1 + 0.3 * gsl_rng_uniform(rng), o = -0.5 + 0.2 * gsl_rng_uniform(rng);
            n[d] = 1 + (int)gsl_rng_uniform_int(rng, trial % 100 == 3 ? MAXN : 6);
            if (trial % 100 == 3) /* many cells: more thresholds than the memo holds */
                h = 0.02, R = 0.6;
            for (int k = 0; k < n[d]; k++) {
                lo[d][k] = o + h * k;
                hi[d][k] = lo[d][k] + h;
            }
            if (trial % 7 == 0) /* the outer cells reach out to infinity */
                lo[d][0] = -INF, hi[d][n[d] - 1] = INF;
            int k = (int)gsl_rng_uniform_int(rng, (unsigned long)n[d]);
            c[d] = trial % 5 == 0 && isfinite(lo[d][k])
                       ? lo[d][k]
                       : o - 0.2 + (h * n[d] + 0.4) * gsl_rng_uniform(rng);
        }
        const double *pl[3] = {lo[0], lo[1], lo[2]}, *ph[3] = {hi[0], hi[1], hi[2]};
        double vol[MAXN * MAXN * MAXN], sum = 0.0;
        overlap_sphere_cells(c, R, n, pl, ph, vol);
        size_t q = 0;
        int holds = 1;
        for (int d = 0; d < 3; d++)
            holds &= lo[d][0] <= c[d] - R && hi[d][n[d] - 1] >= c[d] + R &&
                     (trial % 7 == 0 || n[d] == 1 || hi[d][0] == lo[d][1]);
        for (int k = 0; k < n[2]; k++)
            for (int j = 0; j < n[1]; j++)
                for (int i = 0; i < n[0]; i++, q++) {
                    double blo[3] = {lo[0][i], lo[1][j], lo[2][k]};
                    double bhi[3] = {hi[0][i], hi[1][j], hi[2][k]};
                    double v = overlap_sphere_box(c, R, blo, bhi);
                    assert_memory_equal(&vol[q], &v, sizeof v);
                    sum += vol[q];
                    boxes++;
                }
        if (holds && R > 0) { /* gaps of one ulp between boxes change nothing at 1e-12 */
            assert_close(sum, ball(R), 1e-12 * ball(R));
            covered++;
        }
    }
    /* a radius or a centre that is not a number */
    double c[3] = {0.1, NAN, 0.2}, l0[1] = {0.0}, h0[1] = {1.0}, vol[1];
    const double *pl[3] = {l0, l0, l0}, *ph[3] = {h0, h0, h0};
    int one[3] = {1, 1, 1};
    overlap_sphere_cells(c, 0.5, one, pl, ph, vol);
    assert_true(isnan(vol[0]));
    c[1] = 0.3;
    overlap_sphere_cells(c, NAN, one, pl, ph, vol);
    assert_true(isnan(vol[0]));
    print_message("# %zu boxes in 3000 blocks, %zu blocks holding the ball\n", boxes, covered);
    assert_true(covered > 100);
    gsl_rng_free(rng);
}

/* ---- ball and cylindrical cell ------------------------------------------------ */

static void test_cyl_analytic(void **state)
{
    (void)state;
    const double R = 0.6, V = ball(R);
    /* on the axis, full circle, r1 >= R: the ball cut by the z planes */
    double ca[3] = {0.0, 0.0, 0.2};
    for (double z0 = -0.5; z0 < 0.8; z0 += 0.1)
        for (double z1 = z0 + 0.05; z1 < 1.0; z1 += 0.15) {
            double want = slab(R, z0 - 0.2, z1 - 0.2);
            assert_close(overlap_sphere_cylcell(ca, R, 0.0, R, 0.0, 2 * PI, z0, z1), want,
                         1e-14 * V);
            assert_close(overlap_sphere_cylcell(ca, R, 0.0, 5.0, -PI, PI, z0, z1), want,
                         1e-14 * V);
            /* half circle: half; a sector: its share */
            assert_close(overlap_sphere_cylcell(ca, R, 0.0, 1.0, 0.0, PI, z0, z1), want / 2,
                         1e-14 * V);
            assert_close(overlap_sphere_cylcell(ca, R, 0.0, 1.0, 1.0, 1.0 + PI / 3, z0, z1),
                         want / 6, 1e-14 * V);
        }
    /* on the axis, r1 < R: the ball minus the napkin ring of height
     * 2 sqrt(R^2 - r1^2), whose volume is pi/6 height^3 */
    for (double r1 = 0.05; r1 < R; r1 += 0.05) {
        double ring = 4.0 / 3.0 * PI * pow(R * R - r1 * r1, 1.5);
        assert_close(overlap_sphere_cylcell(ca, R, 0.0, r1, 0.0, 2 * PI, -INF, INF), V - ring,
                     1e-13 * V);
        assert_close(overlap_sphere_cylcell(ca, R, r1, INF, 0.0, 2 * PI, -INF, INF), ring,
                     1e-13 * V);
        assert_close(overlap_sphere_cylcell(ca, R, 0.0, r1, 0.5, 0.5 + PI / 2, -INF, INF),
                     (V - ring) / 4, 1e-13 * V);
    }
    /* away from the axis, one ray cuts: a cap */
    double cr[3] = {5.0, 0.2, 0.0};
    assert_close(overlap_sphere_cylcell(cr, R, 0.0, INF, 0.0, PI / 2, -INF, INF),
                 cap(R, R + 0.2), 1e-14 * V);
    assert_close(overlap_sphere_cylcell(cr, R, 1.0, 100.0, -PI / 2, 0.0, -INF, INF),
                 cap(R, R - 0.2), 1e-14 * V);
    /* a ball on a ring boundary far from the axis: about half */
    double cf[3] = {0.0, 1000.0, 0.0};
    double hv = overlap_sphere_cylcell(cf, R, 0.0, 1000.0, 0.0, PI, -INF, INF);
    assert_close(hv, V / 2, 1e-3 * V);
    assert_close(hv + overlap_sphere_cylcell(cf, R, 1000.0, 2000.0, 0.0, PI, -INF, INF), V,
                 1e-12 * V);
    /* nothing: outside the ring, wedge or slab; zero radius; empty cells */
    assert_true(overlap_sphere_cylcell(cr, R, 6.0, 7.0, 0.0, 2 * PI, -INF, INF) == 0.0);
    assert_true(overlap_sphere_cylcell(cr, R, 0.0, 4.0, 0.0, 2 * PI, -INF, INF) == 0.0);
    assert_true(overlap_sphere_cylcell(cr, R, 0.0, 9.0, PI / 2, PI, -INF, INF) == 0.0);
    assert_true(overlap_sphere_cylcell(cr, R, 0.0, 9.0, 0.0, 2 * PI, 1.0, 2.0) == 0.0);
    assert_true(overlap_sphere_cylcell(cr, 0.0, 0.0, 9.0, 0.0, 2 * PI, -1.0, 2.0) == 0.0);
    assert_true(overlap_sphere_cylcell(cr, R, 3.0, 3.0, 0.0, 2 * PI, -1.0, 2.0) == 0.0);
    assert_true(overlap_sphere_cylcell(cr, R, 0.0, 9.0, 1.0, 1.0, -1.0, 2.0) == 0.0);
    assert_true(isnan(overlap_sphere_cylcell(cr, R, 0.0, NAN, 1.0, 1.0, -1.0, 2.0)));
    /* everything: the whole ball exactly */
    assert_close(overlap_sphere_cylcell(cr, R, 0.0, INF, -INF, INF, -INF, INF), V, 1e-15 * V);
    assert_close(overlap_sphere_cylcell(cr, R, 4.0, 6.0, -0.5, 0.5, -1.0, 1.0), V, 1e-15 * V);
}

/* Wedges of a cylindrical cell that are boxes: quadrants and half-planes
 * through the axis, slabs in z.  Different code paths (Green's theorem and
 * quadrature against the closed forms) must agree. */
static void test_cyl_against_box(void **state)
{
    (void)state;
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    gsl_rng_set(rng, 5);
    double worst = 0.0;
    for (int trial = 0; trial < 200; trial++) {
        double R = 0.1 + gsl_rng_uniform(rng);
        double c[3] = {2 * gsl_rng_uniform(rng) - 1, 2 * gsl_rng_uniform(rng) - 1,
                       2 * gsl_rng_uniform(rng) - 1};
        double z0 = trial % 3 ? -INF : c[2] - R * gsl_rng_uniform(rng);
        double z1 = trial % 5 ? INF : c[2] + R * gsl_rng_uniform(rng);
        int q = (int)gsl_rng_uniform_int(rng, 4);
        double phi0 = q * PI / 2;
        /* quadrant q is x in [lo0, hi0], y in [lo1, hi1] */
        double sx = (q == 0 || q == 3) ? 1 : -1, sy = q < 2 ? 1 : -1;
        double lo[3] = {sx > 0 ? 0 : -INF, sy > 0 ? 0 : -INF, z0};
        double hi[3] = {sx > 0 ? INF : 0, sy > 0 ? INF : 0, z1};
        double want = overlap_sphere_box(c, R, lo, hi);
        double got = overlap_sphere_cylcell(c, R, 0.0, INF, phi0, phi0 + PI / 2, z0, z1);
        worst = fmax(worst, fabs(got - want) / ball(R));
        assert_close(got, want, 1e-12 * ball(R));
        /* three quadrants: the ball minus one */
        double all_lo[3] = {-INF, -INF, z0}, all_hi[3] = {INF, INF, z1};
        double whole = overlap_sphere_box(c, R, all_lo, all_hi);
        got = overlap_sphere_cylcell(c, R, 0.0, INF, phi0 + PI / 2, phi0 + 2 * PI, z0, z1);
        assert_close(got, whole - want, 1e-12 * ball(R));
        /* the half-plane y >= 0 */
        double hl[3] = {-INF, 0, z0};
        got = overlap_sphere_cylcell(c, R, 0.0, INF, 0.0, PI, z0, z1);
        assert_close(got, overlap_sphere_box(c, R, hl, all_hi), 1e-12 * ball(R));
    }
    print_message("# cylinder wedge vs box: worst error %.2g of the ball volume\n", worst);
    gsl_rng_free(rng);
}

static void cyl_partition(gsl_rng *rng, const double c[3], double R, double *worst)
{
    double d = hypot(c[0], c[1]);
    /* rings from 0, or from an inner radius with nothing inside it */
    double re[64];
    int nr = 0;
    double x = 0.0;
    double wr = (0.15 + gsl_rng_uniform(rng)) * R;
    if (d - R > 0.0 && (gsl_rng_uniform(rng) < 0.5 || d + R > 40.0 * wr))
        x = fmax(0.0, d - R - 2.0 * wr * gsl_rng_uniform(rng));
    re[nr++] = x;
    while (x < d + R && nr < 62) {
        x += wr * (0.5 + gsl_rng_uniform(rng));
        re[nr++] = x;
    }
    assert_true(x >= d + R);
    if (gsl_rng_uniform(rng) < 0.5)
        re[nr++] = INF;
    /* sectors of random widths over the full circle from a random start */
    int np = 1 + (int)gsl_rng_uniform_int(rng, 12);
    double pe[16], start = 2 * PI * gsl_rng_uniform(rng);
    pe[0] = start;
    for (int j = 1; j < np; j++)
        pe[j] = start + 2 * PI * (j + 0.6 * (gsl_rng_uniform(rng) - 0.5)) / np;
    pe[np] = start + 2 * PI;
    /* slabs */
    double ze[64];
    int nz = edges(rng, c[2] - R, c[2] + R, 0.3 * R, 1.5 * R, (int)gsl_rng_uniform_int(rng, 2),
                   ze, 64);
    double sum = 0.0;
    for (int i = 0; i + 1 < nr; i++)
        for (int j = 0; j < np; j++)
            for (int k = 0; k + 1 < nz; k++) {
                double v = overlap_sphere_cylcell(c, R, re[i], re[i + 1], pe[j], pe[j + 1],
                                                  ze[k], ze[k + 1]);
                assert_true(v >= 0.0 && isfinite(v));
                sum += v;
            }
    *worst = fmax(*worst, fabs(sum / ball(R) - 1.0));
    assert_close(sum, ball(R), 1e-12 * ball(R));
}

static void test_cyl_partition(void **state)
{
    (void)state;
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    gsl_rng_set(rng, 7);
    double worst = 0.0;
    for (int trial = 0; trial < 150; trial++) {
        double R = 0.1 + gsl_rng_uniform(rng);
        /* a third of the balls contain the axis */
        double d = trial % 3 == 0 ? R * gsl_rng_uniform(rng) : R + 3.0 * gsl_rng_uniform(rng);
        double a = 2 * PI * gsl_rng_uniform(rng);
        double c[3] = {d * cos(a), d * sin(a), gsl_rng_uniform(rng) - 0.5};
        cyl_partition(rng, c, R, &worst);
    }
    /* centred on the axis, far from it (ring shear cell: d/R = 100 .. 1000) */
    for (int trial = 0; trial < 20; trial++) {
        double R = 0.5 + gsl_rng_uniform(rng);
        double d = trial < 5 ? 0.0 : R * (trial < 12 ? 100.0 : 1000.0);
        double c[3] = {d * cos(trial), d * sin(trial), 0.3};
        cyl_partition(rng, c, R, &worst);
    }
    print_message("# cylinder partition: worst relative error %.2g\n", worst);
    gsl_rng_free(rng);
}

static void test_cyl_brute_force(void **state)
{
    (void)state;
    gsl_error_handler_t *old = gsl_set_error_handler_off();
    /* centre, radius, r0, r1, phi0, phi1, z0, z1 */
    const double cases[][10] = {
        {0.8, 0.3, 0.1, 0.5, 0.6, 1.2, 0.0, 0.9, 0.0, 0.4},      /* annular sector */
        {0.2, -0.1, 0.0, 0.5, 0.0, 0.4, -0.3, 2.0, -1.0, 1.0},   /* ball around the axis */
        {0.0, 0.0, 0.0, 0.5, 0.3, 0.7, 0.5, 2.5, 0.2, 0.9},      /* centred on the axis */
        {1.0, 1.0, 0.2, 0.3, 1.55, 1.75, 0.7, 0.8, 0.35, 0.55},  /* cell smaller than R */
        {0.3, 0.1, 0.0, 0.5, 0.2, 0.6, 0.0, 2 * PI, -0.1, 0.3},  /* annulus, full circle */
        {-0.6, 0.5, 0.0, 0.45, 0.4, 1.0, 1.0, 4.5, -INF, 0.2},   /* wide wedge, slab */
        {0.0, 3.0, 0.0, 0.4, 2.9, 3.2, 1.5, 1.6, -INF, INF},     /* two rays, ring */
        /* full rings (overlap.c's vector path): the circle r = 4 passes 8.4e-4 from the
         * centre's foot, so the slices change shape near the poles; a ball near the axis;
         * an annulus that cuts the ball on both sides */
        {3.8383563724910985, -1.1227217222308301, 2.5508205406367779, 0.34402809948660429,
         3.0, 4.0, 0.0, 2 * PI, 2.0, 3.0},
        {0.05, 0.02, 0.0, 0.3, 0.0, 0.1, 0.0, 2 * PI, -0.1, 0.2},
        {1.0, 0.0, 0.0, 0.5, 0.8, 1.2, 0.0, 2 * PI, -0.2, 0.3},
        {1.0, 0.2, 0.4, 0.5, 1.0, 1.9, 0.0, 2 * PI, -INF, INF},
    };
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        const double *q = cases[k];
        brute b = {{q[0], q[1], q[2]}, q[3], q[8], q[9], q[4], q[5], q[6], q[7], 1, 0, 0, 0};
        double v = overlap_sphere_cylcell(q, q[3], q[4], q[5], q[6], q[7], q[8], q[9]);
        double w = brute_volume(&b);
        print_message("# cylinder case %zu: %.15g brute force %.15g (rel %.1g)\n", k, v, w,
                      fabs(v - w) / w);
        assert_close(v, w, 1e-13 * w); /* the brute force to 1e-13: 3e-15 seen */
    }
    gsl_set_error_handler(old);
}

/* ---- segments --------------------------------------------------------------- */

/* Rings of the full circle in a slab, by differences of cylinders (overlap_sphere_rings),
 * against the cells one by one (overlap_sphere_cylcell): every ring within 1e-13 of the
 * ball's volume, an exact 0 where the cell misses the ball, and rings from the axis to
 * beyond the ball adding up to the ball's slab; and each cell against the sum of its two
 * half circles, whose slices take another path (libm's functions, a node at a time). */
static void test_cyl_rings(void **state)
{
    (void)state;
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    enum { N = 12 };
    double worst = 0.0, worst_halves = 0.0;
    int zeros = 0;
    for (int trial = 0; trial < 400; trial++) {
        double R = 0.1 + gsl_rng_uniform(rng), dist = 3.0 * gsl_rng_uniform(rng);
        double phi = 2 * PI * gsl_rng_uniform(rng);
        double c[3] = {dist * cos(phi), dist * sin(phi), gsl_rng_uniform(rng) - 0.5};
        if (trial % 10 == 0) /* on the axis */
            c[0] = c[1] = 0.0;
        double h = 0.05 + 0.5 * gsl_rng_uniform(rng), r[N + 1];
        r[0] = trial % 3 == 0 ? 0.0 : fmax(0.0, hypot(c[0], c[1]) - R - h * gsl_rng_uniform(rng));
        for (int k = 1; k <= N; k++)
            r[k] = r[0] + h * k;
        double z0 = c[2] - 1.2 * R + 1.5 * R * gsl_rng_uniform(rng);
        double z1 = z0 + (trial % 4 == 0 ? 4.0 * R : 0.8 * R * gsl_rng_uniform(rng));
        double vol[N], sum = 0.0;
        overlap_sphere_rings(c, R, N, r, z0, z1, vol);
        for (int k = 0; k < N; k++) {
            double cell = overlap_sphere_cylcell(c, R, r[k], r[k + 1], 0.0, 2 * PI, z0, z1);
            if (cell == 0.0) {
                assert_true(vol[k] == 0.0);
                zeros++;
            }
            assert_true(vol[k] >= 0.0);
            worst = fmax(worst, fabs(vol[k] - cell) / ball(R));
            assert_close(vol[k], cell, 1e-13 * ball(R));
            /* the full circle's vectorised areas (annulus_slices.c) against two half
             * circles, whose areas come one at a time from libm */
            double halves = overlap_sphere_cylcell(c, R, r[k], r[k + 1], 0.0, PI, z0, z1) +
                            overlap_sphere_cylcell(c, R, r[k], r[k + 1], PI, 2 * PI, z0, z1);
            worst_halves = fmax(worst_halves, fabs(cell - halves) / ball(R));
            assert_close(cell, halves, 1e-13 * ball(R));
            sum += vol[k];
        }
        if (r[0] == 0.0 && r[N] >= hypot(c[0], c[1]) + R)
            assert_close(sum, slab(R, z0 - c[2], z1 - c[2]), 1e-13 * ball(R));
    }
    double c[3] = {NAN, 0.0, 0.0}, r[2] = {0.0, 1.0}, vol[1];
    overlap_sphere_rings(c, 0.5, 1, r, -1.0, 1.0, vol);
    assert_true(isnan(vol[0]));
    print_message("# rings against cells: worst %.2g of the ball, %d empty rings; cells against "
                  "half circles %.2g\n", worst, zeros, worst_halves);
    assert_true(zeros > 100);
    gsl_rng_free(rng);
}

static void test_segment_box(void **state)
{
    (void)state;
    const double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
    double a[3] = {0.5, 0.5, 0.5}, b[3] = {1.5, 0.5, 0.5};
    assert_close(segment_fraction_box(a, b, lo, hi), 0.5, 1e-16);
    assert_close(segment_fraction_box(b, a, lo, hi), 0.5, 1e-16);
    /* through the box diagonally: enters at t = 1/4, leaves at t = 3/4 */
    double p[3] = {-0.5, -0.5, -0.5}, q[3] = {1.5, 1.5, 1.5};
    assert_close(segment_fraction_box(p, q, lo, hi), 0.5, 1e-16);
    /* missing the box */
    double m0[3] = {-1, 2, 0.5}, m1[3] = {2, 2, 0.5};
    assert_true(segment_fraction_box(m0, m1, lo, hi) == 0.0);
    /* inside; in a face (1/2); along an edge (1/4); partly in a face */
    double i0[3] = {0.2, 0.3, 0.4}, i1[3] = {0.9, 0.1, 0.6};
    assert_true(segment_fraction_box(i0, i1, lo, hi) == 1.0);
    double f0[3] = {0.2, 0.3, 1.0}, f1[3] = {0.9, 0.1, 1.0};
    assert_true(segment_fraction_box(f0, f1, lo, hi) == 0.5);
    double e0[3] = {0.2, 1.0, 1.0}, e1[3] = {0.9, 1.0, 1.0};
    assert_true(segment_fraction_box(e0, e1, lo, hi) == 0.25);
    double g0[3] = {0.5, 0.5, 0.0}, g1[3] = {1.5, 0.5, 0.0};
    assert_close(segment_fraction_box(g0, g1, lo, hi), 0.25, 1e-16);
    /* degenerate segments: a point inside, outside, on a face */
    assert_true(segment_fraction_box(i0, i0, lo, hi) == 1.0);
    assert_true(segment_fraction_box(m0, m0, lo, hi) == 0.0);
    assert_true(segment_fraction_box(f0, f0, lo, hi) == 0.5);
    /* infinite bounds: a half-space */
    double hl[3] = {-INF, -INF, 0.75}, hh[3] = {INF, INF, INF};
    double s0[3] = {3, -7, 0.5}, s1[3] = {-2, 9, 1.5};
    assert_close(segment_fraction_box(s0, s1, hl, hh), 0.75, 1e-16);
    /* an empty box */
    double el[3] = {0, 0, 0.5}, eh[3] = {1, 1, 0.5};
    assert_true(segment_fraction_box(i0, i1, el, eh) == 0.0);
}

static void test_segment_box_partition(void **state)
{
    (void)state;
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    gsl_rng_set(rng, 3);
    double worst = 0.0;
    for (int trial = 0; trial < 400; trial++) {
        double e[3][16];
        int n[3];
        for (int i = 0; i < 3; i++)
            n[i] = edges(rng, 0.0, 1.0, 0.1, 0.4, 1, e[i], 16);
        double a[3], b[3];
        for (int i = 0; i < 3; i++) {
            a[i] = 1.4 * gsl_rng_uniform(rng) - 0.2;
            b[i] = 1.4 * gsl_rng_uniform(rng) - 0.2;
        }
        /* some segments lie in grid planes, along grid lines, or are points */
        int kind = trial % 5;
        if (kind >= 1)
            a[0] = b[0] = e[0][1 + (int)gsl_rng_uniform_int(rng, (unsigned long)(n[0] - 2))];
        if (kind >= 2)
            a[1] = b[1] = e[1][1 + (int)gsl_rng_uniform_int(rng, (unsigned long)(n[1] - 2))];
        if (kind == 4)
            for (int i = 0; i < 3; i++)
                b[i] = a[i];
        double sum = 0.0;
        for (int i = 0; i + 1 < n[0]; i++)
            for (int j = 0; j + 1 < n[1]; j++)
                for (int k = 0; k + 1 < n[2]; k++) {
                    double lo[3] = {e[0][i], e[1][j], e[2][k]};
                    double hi[3] = {e[0][i + 1], e[1][j + 1], e[2][k + 1]};
                    double f = segment_fraction_box(a, b, lo, hi);
                    assert_true(f >= 0.0 && f <= 1.0);
                    sum += f;
                }
        worst = fmax(worst, fabs(sum - 1.0));
        assert_close(sum, 1.0, 1e-14);
    }
    print_message("# segment box partition: worst error %.2g\n", worst);
    gsl_rng_free(rng);
}

static void test_segment_cyl(void **state)
{
    (void)state;
    /* a segment crossing a ring twice: y = 0.5, x from -2 to 2, ring r in
     * [0.6, 1]: inside where 0.11 <= x^2 <= 0.75 */
    double a[3] = {-2, 0.5, 0}, b[3] = {2, 0.5, 0};
    assert_close(segment_fraction_cylcell(a, b, 0.6, 1.0, 0, 2 * PI, -1, 1),
                 (sqrt(0.75) - sqrt(0.11)) / 2, 1e-15);
    assert_close(segment_fraction_cylcell(a, b, 0.0, 1.0, 0, 2 * PI, -1, 1), sqrt(0.75) / 2,
                 1e-15);
    /* the upper half plane holds all of it, the first quadrant half of it */
    assert_close(segment_fraction_cylcell(a, b, 0.6, 1.0, 0, PI, -1, 1),
                 (sqrt(0.75) - sqrt(0.11)) / 2, 1e-15);
    assert_close(segment_fraction_cylcell(a, b, 0.6, 1.0, 0, PI / 2, -1, 1),
                 (sqrt(0.75) - sqrt(0.11)) / 4, 1e-15);
    /* a segment through the axis, at 45 degrees */
    double p[3] = {-1, -1, 0.5}, q[3] = {1, 1, 0.5};
    assert_close(segment_fraction_cylcell(p, q, 0.0, 2.0, 0, PI / 2, 0, 1), 0.5, 1e-15);
    assert_close(segment_fraction_cylcell(p, q, 0.0, 2.0, PI / 2, PI, 0, 1), 0.0, 1e-15);
    assert_close(segment_fraction_cylcell(p, q, 0.0, 2.0, PI, 1.5 * PI, 0, 1), 0.5, 1e-15);
    assert_close(segment_fraction_cylcell(p, q, 0.0, 2.0, 0, 2 * PI, 0, 1), 1.0, 1e-15);
    /* r = sqrt(2) |2t - 1|: the hole r < 0.5 takes |2t - 1| < 0.5/sqrt(2) */
    assert_close(segment_fraction_cylcell(p, q, 0.5, 2.0, -PI, PI, -1, 1), 1.0 - 0.5 / sqrt(2.0),
                 1e-15);
    /* along a ray face: half; along the axis: the sector's share of the circle */
    double r0[3] = {0.2, 0, 0}, r1[3] = {0.8, 0, 0};
    assert_true(segment_fraction_cylcell(r0, r1, 0.0, 1.0, 0, PI / 2, -1, 1) == 0.5);
    assert_true(segment_fraction_cylcell(r0, r1, 0.0, 1.0, -PI / 2, 0, -1, 1) == 0.5);
    assert_true(segment_fraction_cylcell(r0, r1, 0.0, 1.0, 0.1, 1, -1, 1) == 0.0);
    double x0[3] = {0, 0, 0}, x1[3] = {0, 0, 1};
    assert_close(segment_fraction_cylcell(x0, x1, 0.0, 1.0, 0, PI / 3, -1, 2), 1.0 / 6, 1e-15);
    assert_close(segment_fraction_cylcell(x0, x1, 0.0, 1.0, 0, PI / 3, 0.5, 2), 1.0 / 12,
                 1e-15);
    assert_true(segment_fraction_cylcell(x0, x1, 0.1, 1.0, 0, 2 * PI, -1, 2) == 0.0);
    /* in a z face: half */
    double z0[3] = {0.3, 0.1, 1.0}, z1[3] = {0.1, 0.4, 1.0};
    assert_true(segment_fraction_cylcell(z0, z1, 0.0, 1.0, 0, 2 * PI, -1, 1) == 0.5);
    /* parallel to the axis on the cylinder r = 1: half */
    double c0[3] = {0, 1, 0}, c1[3] = {0, 1, 3};
    assert_close(segment_fraction_cylcell(c0, c1, 0.5, 1.0, 0, PI, -INF, 1.5), 0.25, 1e-15);
    /* degenerate: points */
    double in[3] = {0.3, 0.4, 0.0}, out[3] = {0.3, -0.4, 0.0}, on[3] = {0.0, 0.5, 0.0};
    assert_true(segment_fraction_cylcell(in, in, 0.0, 1.0, 0, PI, -1, 1) == 1.0);
    assert_true(segment_fraction_cylcell(out, out, 0.0, 1.0, 0, PI, -1, 1) == 0.0);
    assert_true(segment_fraction_cylcell(on, on, 0.5, 1.0, 0, PI, -1, 1) == 0.5);
}

static void test_segment_cyl_partition(void **state)
{
    (void)state;
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    gsl_rng_set(rng, 9);
    double worst = 0.0;
    for (int trial = 0; trial < 400; trial++) {
        double re[16];
        int nr = edges(rng, 0.0, 1.0, 0.1, 0.4, 1, re, 15);
        re[0] = 0.0;
        int np = 1 + (int)gsl_rng_uniform_int(rng, 8);
        double pe[16];
        for (int j = 0; j <= np; j++)
            pe[j] = 2 * PI * j / np;
        double ze[16];
        int nz = edges(rng, -0.5, 0.5, 0.2, 0.5, 1, ze, 16);
        double a[3], b[3];
        for (int i = 0; i < 3; i++) {
            a[i] = 2.4 * gsl_rng_uniform(rng) - 1.2;
            b[i] = 2.4 * gsl_rng_uniform(rng) - 1.2;
        }
        switch (trial % 6) {
        case 1: /* through the axis */
            b[0] = -a[0] * 0.7;
            b[1] = -a[1] * 0.7;
            break;
        case 2: /* along the axis */
            a[0] = a[1] = b[0] = b[1] = 0.0;
            break;
        case 3: /* in a z face */
            a[2] = b[2] = ze[1 + (int)gsl_rng_uniform_int(rng, (unsigned long)(nz - 2))];
            break;
        case 4: /* in the planes x = 0 or y = 0 (rays when np is 4 or 8) */
            a[(trial / 6) % 2] = b[(trial / 6) % 2] = 0.0;
            break;
        case 5: /* a point */
            for (int i = 0; i < 3; i++)
                b[i] = a[i];
            break;
        }
        double sum = 0.0;
        for (int i = 0; i + 1 < nr; i++)
            for (int j = 0; j < np; j++)
                for (int k = 0; k + 1 < nz; k++) {
                    double f = segment_fraction_cylcell(a, b, re[i], re[i + 1], pe[j],
                                                        pe[j + 1], ze[k], ze[k + 1]);
                    assert_true(f >= 0.0 && f <= 1.0);
                    sum += f;
                }
        worst = fmax(worst, fabs(sum - 1.0));
        assert_close(sum, 1.0, 1e-14);
    }
    print_message("# segment cylinder partition: worst error %.2g\n", worst);
    gsl_rng_free(rng);
}

/* ---- degenerate input: finite, sensible values --------------------------------- */

static void test_no_nan(void **state)
{
    (void)state;
    const double R = 0.5, V = ball(R);
    /* centres on faces, edges, corners of cells; on the axis; on ray planes */
    const double pts[][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0.5, 0, 1}, {1, 1, 1},
                             {0, 0, 1}, {0.5, 0.5, 0.5}, {-1, 0, 0}, {0, 0.5, 0}};
    const double lims[][6] = {{0, 1, 0, 1, 0, 1},          {-INF, 0, 0, INF, 0, 0.5},
                              {0, 0.5, -INF, INF, 1, INF}, {1, 1.5, 0, 1, 0, 1},
                              {-INF, INF, -INF, INF, 0, 0}};
    const double cyl[][6] = {{0, 1, 0, PI / 2, 0, 1},        {0, 0.5, 0, 2 * PI, -INF, INF},
                             {0.5, 1, -PI, PI, 0, INF},      {1, INF, PI / 2, PI, -1, 0},
                             {0, 0.001, 0, 2 * PI, -1, 1},   {0, 1, 0, 1e-9, -1, 1},
                             {0, 1, 0, 2 * PI - 1e-12, 0, 1}, {0, 1, -INF, INF, -INF, INF}};
    for (size_t i = 0; i < sizeof pts / sizeof pts[0]; i++) {
        for (double r = 0.0; r <= 2.0; r += 0.5) {
            for (size_t k = 0; k < sizeof lims / sizeof lims[0]; k++) {
                const double *L = lims[k];
                double lo[3] = {L[0], L[2], L[4]}, hi[3] = {L[1], L[3], L[5]};
                double v = overlap_sphere_box(pts[i], r, lo, hi);
                assert_true(isfinite(v) && v >= 0.0 && v <= ball(r) * (1 + 1e-15));
                double f = segment_fraction_box(pts[i], pts[(i + 1) % 9], lo, hi);
                assert_true(isfinite(f) && f >= 0.0 && f <= 1.0);
            }
            for (size_t k = 0; k < sizeof cyl / sizeof cyl[0]; k++) {
                const double *L = cyl[k];
                double v = overlap_sphere_cylcell(pts[i], r, L[0], L[1], L[2], L[3], L[4], L[5]);
                assert_true(isfinite(v) && v >= 0.0 && v <= ball(r) * (1 + 1e-15));
                for (size_t j = 0; j < sizeof pts / sizeof pts[0]; j++) {
                    double f = segment_fraction_cylcell(pts[i], pts[j], L[0], L[1], L[2], L[3],
                                                        L[4], L[5]);
                    assert_true(isfinite(f) && f >= 0.0 && f <= 1.0);
                }
            }
        }
    }
    /* a sphere whose pole touches a cell boundary, tangent rings and rays */
    double c[3] = {0.0, 1.0, 0.0};
    assert_close(overlap_sphere_cylcell(c, R, 0.5, 1.5, 0, PI, -INF, INF), V, 1e-15 * V);
    assert_close(overlap_sphere_cylcell(c, R, 0.0, 1.0, 0, PI, -INF, 0.5) +
                     overlap_sphere_cylcell(c, R, 1.0, 2.0, 0, PI, -INF, 0.5),
                 V, 1e-12 * V);
    double c2[3] = {0.5, 0.0, 0.0};
    assert_close(overlap_sphere_cylcell(c2, R, 0.0, 1.0, 0, PI, -INF, INF), V / 2, 1e-13 * V);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_box_analytic),
        cmocka_unit_test(test_box_partition),
        cmocka_unit_test(test_box_brute_force),
        cmocka_unit_test(test_box_cells),
        cmocka_unit_test(test_cyl_analytic),
        cmocka_unit_test(test_cyl_against_box),
        cmocka_unit_test(test_cyl_partition),
        cmocka_unit_test(test_cyl_rings),
        cmocka_unit_test(test_cyl_brute_force),
        cmocka_unit_test(test_segment_box),
        cmocka_unit_test(test_segment_box_partition),
        cmocka_unit_test(test_segment_cyl),
        cmocka_unit_test(test_segment_cyl_partition),
        cmocka_unit_test(test_no_nan),
    };
    return cmocka_run_group_tests_name("overlap", tests, NULL, NULL);
}
