/* The kernel deposits on random x-y-z grids in random boxes against the kernel written out
 * here and integrated by GSL, summed over every periodic image: boxes of 3 to 15 mm,
 * periodic or not along each edge, tilted or not; grids inside the box, smaller or
 * reaching beyond it, with any of the directions left out (the kernel's marginal along
 * them, divided by the grid's extent there); the Gaussian (cutoffs 2 to 5, plain or
 * shifted) and Lucy's kernel, 0.5 to 2.5 mm wide, often reaching across the box; points
 * and branches up to 2 mm long.  Each cell's weight must be the reference's within 1e-11
 * of the kernel's peak (1e-9 for Lucy's marginals, whose r^3 term limits their rule,
 * docs/fields.md).  A configuration mimas refuses (a reach of 2.5 box widths or more, a
 * profile across a tilt) must be one the reference cannot average either: checked by the
 * reasons themselves in test_weight; here it is skipped.  On r-z grids the Gaussian's
 * points are exact too (1e-11 of the peak), its branches a Gauss-Legendre rule of the
 * azimuthal average split where the average's square-root edges (the support's edge, or
 * near the axis the arc's end, the whole ring inside the support) cross the branch and made
 * smooth at them and at nearby singular points off the branch (docs/fields.md):
 * test_random_ring_branches checks every cell to 1e-8 of the peak. */
#include <config.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>
#include <gsl/gsl_rng.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "deposit.h"
#include "ring_branch_ref.h"
#include "weight.h"

/* ---- the reference: the 3-D kernel, its marginals and line integrals, by GSL ---- */

typedef struct kernel_ref {
    double w, cut, coef, shift; /* Lucy: w = c, cut = 1 */
    int lucy;
    int gridded[3];
    double extent[3]; /* the grid's extent along the directions left out */
} kernel_ref;

static kernel_ref K;
static gsl_integration_workspace *WS_LINE, *WS_MARG;

static double reach(void)
{
    return K.cut * K.w;
}

static double phi(double r)
{
    if (K.lucy) {
        double q = r / K.w;
        return q < 1 ? K.coef * (1 + 3 * q) * pow(1 - q, 3) : 0.0;
    }
    return r < reach() ? K.coef * (exp(-r * r / (2 * K.w * K.w)) - K.shift) : 0.0;
}

static double RHO2; /* the squared offset in the gridded directions */

static double chord(double t, void *p)
{
    (void)p;
    return 2.0 * phi(sqrt(RHO2 + t * t));
}

static double disc(double s, void *p)
{
    (void)p;
    return 2.0 * M_PI * s * phi(sqrt(RHO2 + s * s));
}

/* The kernel at squared gridded offset rho2, integrated over the directions left out and
 * divided by the grid's extent along them */
static double marginal(double rho2)
{
    int out = 0;
    double ext = 1.0;
    for (int d = 0; d < 3; d++)
        if (!K.gridded[d]) {
            out++;
            ext *= K.extent[d];
        }
    if (out == 0)
        return phi(sqrt(rho2));
    if (!(rho2 < reach() * reach()))
        return 0.0;
    RHO2 = rho2;
    gsl_function F = {out == 1 ? chord : disc, NULL};
    double v, err;
    gsl_integration_qag(&F, 0, sqrt(reach() * reach() - rho2), 0, 1e-13, 1000, 6, WS_MARG, &v,
                        &err);
    return v / ext;
}

typedef struct branch {
    double d[3], b[3]; /* the cell centre from the branch's start; the branch */
} branch;

static double along(double s, void *p)
{
    const branch *c = p;
    double r2 = 0;
    for (int k = 0; k < 3; k++)
        if (K.gridded[k])
            r2 += (c->d[k] - s * c->b[k]) * (c->d[k] - s * c->b[k]);
    return marginal(r2);
}

/* The line integral over s in [0, 1], over the part within reach (the quadratic's roots) */
static double line(const branch *c)
{
    double a = 0, h = 0, e = 0, R = reach();
    for (int k = 0; k < 3; k++)
        if (K.gridded[k]) {
            a += c->b[k] * c->b[k];
            h += c->d[k] * c->b[k];
            e += c->d[k] * c->d[k];
        }
    if (!(a > 0)) /* along the directions left out only */
        return marginal(e);
    double disc2 = h * h - a * (e - R * R);
    if (!(disc2 > 0))
        return 0.0;
    double s0 = fmax(0.0, (h - sqrt(disc2)) / a), s1 = fmin(1.0, (h + sqrt(disc2)) / a);
    if (!(s1 > s0))
        return 0.0;
    gsl_function F = {along, (void *)c};
    double v, err;
    gsl_integration_qag(&F, s0, s1, 0, 1e-13, 1000, 6, WS_LINE, &v, &err);
    return v;
}

/* ---- the random configurations ---- */

static double uniform(gsl_rng *rng, double lo, double hi)
{
    return lo + (hi - lo) * gsl_rng_uniform(rng);
}

/* One random box, grid and kernel, and four objects on it (points and branches); the
 * worst deviation from the reference in units of the kernel's peak in *worst; 0 when
 * mimas refuses the configuration. */
static int check_one(gsl_rng *rng, double *worst, double *tol)
{
    mimas_box box;
    memset(&box, 0, sizeof box);
    double L[3];
    for (int d = 0; d < 3; d++) {
        box.lo[d] = uniform(rng, -0.005, 0.005);
        L[d] = uniform(rng, 0.003, 0.015);
        box.hi[d] = box.lo[d] + L[d];
        box.periodic[d] = gsl_rng_uniform(rng) < 0.6;
    }
    if (gsl_rng_uniform(rng) < 0.5) { /* tilts, where their direction is periodic */
        if (box.periodic[1])
            box.xy = uniform(rng, -0.4, 0.4) * L[0];
        if (box.periodic[2] && gsl_rng_uniform(rng) < 0.5)
            box.xz = uniform(rng, -0.4, 0.4) * L[0];
        if (box.periodic[2] && gsl_rng_uniform(rng) < 0.5)
            box.yz = uniform(rng, -0.4, 0.4) * L[1];
    }
    double e[3][3];
    mimas_box_edges(&box, e);
    char spec[128], grid[256] = "";
    memset(&K, 0, sizeof K);
    K.lucy = gsl_rng_uniform(rng) < 0.3;
    K.w = uniform(rng, 0.0005, 0.0025);
    if (K.lucy) {
        K.cut = 1.0;
        snprintf(spec, sizeof spec, "lucy:c=%.17g", K.w);
    } else {
        K.cut = 2 + (double)gsl_rng_uniform_int(rng, 4);
        int shifted = gsl_rng_uniform(rng) < 0.3;
        K.shift = shifted ? exp(-0.5 * K.cut * K.cut) : 0.0;
        snprintf(spec, sizeof spec, "gauss:w=%.17g,cutoff=%g%s", K.w, K.cut,
                 shifted ? ",shift" : "");
    }
    mimas_weight wt;
    mimas_error err;
    assert_int_equal(mimas_weight_parse(&wt, spec, &err), MIMAS_OK);
    K.coef = wt.coef;
    int mask = 1 + (int)gsl_rng_uniform_int(rng, 7);
    for (int d = 0; d < 3; d++) {
        K.gridded[d] = mask >> d & 1;
        if (!K.gridded[d])
            continue;
        /* from inside the box to a little beyond it */
        double lo = box.lo[d] + (gsl_rng_uniform(rng) < 0.5 ? uniform(rng, -0.15, 0.35) : 0) * L[d];
        double hi = box.hi[d] - (gsl_rng_uniform(rng) < 0.5 ? uniform(rng, -0.15, 0.35) : 0) * L[d];
        snprintf(grid + strlen(grid), sizeof grid - strlen(grid), "%s%c=%.17g:%.17g:%d",
                 grid[0] ? "," : "", "xyz"[d], lo, hi, 1 + (int)gsl_rng_uniform_int(rng, 7));
    }
    mimas_grid g;
    assert_int_equal(mimas_grid_parse(&g, grid, NULL, &err), MIMAS_OK);
    mimas_grid_fit_box(&g, &box);
    for (int d = 0; d < 3; d++)
        K.extent[d] = g.hi[d] - g.lo[d];
    mimas_deposit dp;
    if (mimas_deposit_init(&dp, &g, &wt, &box, 0, &err))
        return 0;
    *tol = K.lucy && mask != 7 ? 1e-9 : 1e-11;
    size_t nc = mimas_grid_cells(&g);
    double *dense = calloc(nc, sizeof *dense), peak = marginal(0.0);
    assert_non_null(dense);
    mimas_weights ws = {0};
    /* the images along the periodic edges of the gridded directions (those of the others
     * lie along directions left out, where the marginal holds them: mimas refuses the
     * tilts that would not), enough either way to pass the reach, the branch and the
     * grid's overhang (0.35 box widths at most) */
    int m[3];
    for (int d = 0; d < 3; d++)
        m[d] = box.periodic[d] && K.gridded[d] ? (int)ceil((reach() + 0.002) / L[d] + 0.5) + 1
                                                : 0;
    for (int o = 0; o < 4; o++) {
        double a[3] = {box.lo[0], box.lo[1], box.lo[2]}, b[3], u[3], un = 0;
        double len = o % 2 ? uniform(rng, 0.0, 0.002) : 0.0;
        for (int q = 0; q < 3; q++) {
            double s = gsl_rng_uniform(rng); /* fractional: inside the (tilted) box */
            for (int d = 0; d < 3; d++)
                a[d] += s * e[q][d];
            u[q] = gsl_rng_uniform(rng) - 0.5;
            un += u[q] * u[q];
        }
        for (int d = 0; d < 3; d++)
            b[d] = a[d] + len * u[d] / sqrt(un);
        ws.n = 0;
        int rc = len > 0 ? mimas_deposit_segment(&dp, a, b, &ws)
                         : mimas_deposit_sphere(&dp, a, 0.0, 0, &ws);
        assert_int_equal(rc, MIMAS_OK);
        memset(dense, 0, nc * sizeof *dense);
        for (size_t k = 0; k < ws.n; k++)
            dense[ws.cell[k]] += ws.w[k];
        for (size_t c = 0; c < nc; c++) {
            double ctr[3], ref = 0.0;
            mimas_grid_cell_centre(&g, c, ctr);
            for (int i = -m[0]; i <= m[0]; i++)
                for (int j = -m[1]; j <= m[1]; j++)
                    for (int k = -m[2]; k <= m[2]; k++) {
                        branch br;
                        double r2 = 0;
                        for (int d = 0; d < 3; d++) {
                            br.d[d] = ctr[d] - a[d] - i * e[0][d] - j * e[1][d] - k * e[2][d];
                            br.b[d] = b[d] - a[d];
                            if (K.gridded[d])
                                r2 += br.d[d] * br.d[d];
                        }
                        if (!(sqrt(r2) < reach() + len))
                            continue;
                        ref += len > 0 ? line(&br) : marginal(r2);
                    }
            double dev = fabs(dense[c] - ref) / peak;
            *worst = fmax(*worst, dev);
            if (!(dev < *tol))
                print_message("# %s on %s (periodic %d%d%d, tilts %g %g %g), object %d, cell "
                              "%zu: %.17g, reference %.17g\n",
                              spec, grid, box.periodic[0], box.periodic[1], box.periodic[2],
                              box.xy, box.xz, box.yz, o, c, dense[c], ref);
            assert_true(dev < *tol);
        }
    }
    mimas_weights_free(&ws);
    free(dense);
    return 1;
}

static void test_random_deposits(void **state)
{
    (void)state;
    gsl_set_error_handler_off();
    WS_LINE = gsl_integration_workspace_alloc(1000);
    WS_MARG = gsl_integration_workspace_alloc(1000);
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    gsl_rng_set(rng, 20261203);
    int checked = 0;
    double worst3 = 0, worst_m = 0;
    for (int t = 0; t < 150; t++) {
        double worst = 0, tol = 0;
        if (!check_one(rng, &worst, &tol))
            continue;
        checked++;
        if (tol < 1e-10)
            worst3 = fmax(worst3, worst);
        else
            worst_m = fmax(worst_m, worst);
    }
    print_message("# %d random configurations: worst %.2g of the peak (%.2g for Lucy's "
                  "marginals)\n", checked, worst3, worst_m);
    assert_true(checked >= 100);
    gsl_rng_free(rng);
    gsl_integration_workspace_free(WS_LINE);
    gsl_integration_workspace_free(WS_MARG);
}

/* ---- r-z grids: the azimuthal average along branches ---- */

static double RING_R, RING_RHO, RING_DZ;

static double ring_integrand(double t, void *p)
{
    (void)p;
    double d2 = RING_R * RING_R + RING_RHO * RING_RHO - 2 * RING_R * RING_RHO * cos(t);
    return phi(sqrt(d2 + RING_DZ * RING_DZ));
}

/* (1/pi) int_0^pi of the kernel around the ring r at height offset dz from a point at
 * distance rho from the axis, up to the arc's end t_m where the ring leaves the support */
static double ring_average(double r, double rho, double dz)
{
    double R = reach(), base = r * r + rho * rho + dz * dz;
    double k = r * rho > 0 ? (base - R * R) / (2 * r * rho) : (base < R * R ? -2 : 2);
    double tm = k <= -1 ? M_PI : (k >= 1 ? 0 : acos(k));
    if (!(tm > 0))
        return 0.0;
    RING_R = r, RING_RHO = rho, RING_DZ = dz;
    gsl_function F = {ring_integrand, NULL};
    double v, err;
    gsl_integration_qag(&F, 0, tm, 0, 1e-13, 1000, 6, WS_MARG, &v, &err);
    return v / M_PI;
}

static double RING_CR, RING_CZ, RING_A[3], RING_B[3];

static double ring_along(double s, void *p)
{
    (void)p;
    double x = RING_A[0] + s * RING_B[0], y = RING_A[1] + s * RING_B[1];
    return ring_average(RING_CR, hypot(x, y), RING_CZ - RING_A[2] - s * RING_B[2]);
}

/* The distance of the branch's point s from the ring's nearest (sign -1: the support's
 * edge) or farthest point (+1: the arc's end, the whole ring inside), minus the reach */
static double ring_edge(double s, double sign, void *p)
{
    (void)p;
    double rho = hypot(RING_A[0] + s * RING_B[0], RING_A[1] + s * RING_B[1]);
    return hypot(rho + sign * RING_CR, RING_CZ - RING_A[2] - s * RING_B[2]) - reach();
}

/* The adaptive integral along the branch of the exact average, split where either edge
 * crosses it (ring_branch_ref.h: sign changes on 4096 intervals, then bisection,
 * independent of mimas's quartic); *edges their number. */
static double ring_reference(int *edges)
{
    return ring_branch_integral(ring_along, ring_edge, NULL, 4096, 1e-14 * phi(0.0), edges);
}

/* The segment a -> b deposited, its weights summed into dense (nc cells) */
static void dense_segment(const mimas_deposit *dp, const double a[3], const double b[3],
                          mimas_weights *ws, double *dense, size_t nc)
{
    ws->n = 0;
    assert_int_equal(mimas_deposit_segment(dp, a, b, ws), MIMAS_OK);
    memset(dense, 0, nc * sizeof *dense);
    for (size_t k = 0; k < ws->n; k++)
        dense[ws->cell[k]] += ws->w[k];
}

/* Random branches (up to 1.5 mm, anywhere within 6 mm of the axis, every fifth starting
 * within 0.3 mm of it) on an r-z grid of 0.5 mm cells, the plain Gaussian (w = 1 mm) at
 * cutoffs 2 and 3, against the adaptive integral along the branch of the exact azimuthal
 * average, split at its edges: every cell within tol of the peak, also where an edge
 * crosses the branch or nearly touches it, or the branch passes near the axis (1.4e-9 of
 * the peak seen; with the rule along the whole branch 8.1e-3 at cutoff 2 and 6.2e-4 at 3). */
static void check_ring_branches(double cut, double tol)
{
    char spec[64];
    snprintf(spec, sizeof spec, "gauss:w=0.001,cutoff=%g", cut);
    mimas_weight wt;
    mimas_error err;
    assert_int_equal(mimas_weight_parse(&wt, spec, &err), MIMAS_OK);
    memset(&K, 0, sizeof K);
    K.w = 0.001, K.cut = cut, K.coef = wt.coef;
    K.gridded[0] = K.gridded[1] = K.gridded[2] = 1;
    mimas_grid g;
    assert_int_equal(mimas_grid_parse(&g, "r=0:0.01:20,z=-0.005:0.005:20", NULL, &err),
                     MIMAS_OK);
    mimas_box box = {{-0.02, -0.02, -0.01}, {0.02, 0.02, 0.01}, 0, 0, 0, {0, 0, 0}};
    mimas_grid_fit_box(&g, &box);
    mimas_deposit dp;
    assert_int_equal(mimas_deposit_init(&dp, &g, &wt, &box, 0, &err), MIMAS_OK);
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    gsl_rng_set(rng, 7);
    size_t nc = mimas_grid_cells(&g);
    double *dense = calloc(nc, sizeof *dense), peak = phi(0.0), worst_edge = 0, worst = 0;
    assert_non_null(dense);
    mimas_weights ws = {0};
    for (int o = 0; o < 60; o++) {
        double a[3], b[3], u[3], un = 0, len = uniform(rng, 0.0002, 0.0015);
        double rho = uniform(rng, 0.0, o % 5 ? 0.006 : 0.0003), t = uniform(rng, 0, 2 * M_PI);
        a[0] = rho * cos(t), a[1] = rho * sin(t), a[2] = uniform(rng, -0.002, 0.002);
        for (int d = 0; d < 3; d++) {
            u[d] = gsl_rng_uniform(rng) - 0.5;
            un += u[d] * u[d];
        }
        for (int d = 0; d < 3; d++)
            b[d] = a[d] + len * u[d] / sqrt(un);
        dense_segment(&dp, a, b, &ws, dense, nc);
        for (size_t c = 0; c < nc; c++) {
            double ctr[3];
            mimas_grid_cell_centre(&g, c, ctr);
            /* out of reach (the ends' distances from the ring beyond the reach by more than
             * the branch's length): no weight either */
            double ra = hypot(a[0], a[1]), rb = hypot(b[0], b[1]);
            if (hypot(ra - ctr[0], a[2] - ctr[2]) - reach() > len &&
                hypot(rb - ctr[0], b[2] - ctr[2]) - reach() > len) {
                assert_true(dense[c] == 0.0);
                continue;
            }
            RING_CR = ctr[0], RING_CZ = ctr[2];
            for (int d = 0; d < 3; d++) {
                RING_A[d] = a[d];
                RING_B[d] = b[d] - a[d];
            }
            int edge;
            double ref = ring_reference(&edge);
            double dev = fabs(dense[c] - ref) / peak;
            if (edge)
                worst_edge = fmax(worst_edge, dev);
            else
                worst = fmax(worst, dev);
            if (!(dev < tol))
                print_message("# cutoff %g, branch %d, cell %zu (edges %d): %.17g, reference "
                              "%.17g\n", cut, o, c, edge, dense[c], ref);
            assert_true(dev < tol);
        }
    }
    print_message("# r-z branches, cutoff %g: worst %.2g of the peak where an edge of the average "
                  "crosses the branch, %.2g elsewhere\n", cut, worst_edge, worst);
    mimas_weights_free(&ws);
    free(dense);
    gsl_rng_free(rng);
}

static void test_random_ring_branches(void **state)
{
    (void)state;
    gsl_set_error_handler_off();
    WS_MARG = gsl_integration_workspace_alloc(1000);
    check_ring_branches(2.0, 1e-8);
    check_ring_branches(3.0, 1e-8);
    gsl_integration_workspace_free(WS_MARG);
}

/* Branches of 1e-8 w (each the azimuthal average at its point, to ~1e-14) near the axis, the
 * plain and the shifted Gaussian at cutoffs 2, 3 and 5, against the adaptive average: where
 * the arc is long (sin^2(t_m/2) = y between 0.02 and 0.25: the ring lanes' second tier, at
 * least 500 cells of each weight) every cell within 1e-12 of its value (and 1e-16 of the
 * peak); for y > 1/2 (mimas_kernel_ring's rule of 32 points; with 16, 5e-12 at cutoff 3 and
 * 7.8e-9 at 5) and elsewhere (the first tier, the scalar series) within 1e-13 of the peak
 * (the reference's relative tolerance; 6e-16 seen).  Lucy's kernel (the rule of 32 points
 * everywhere) within 1e-10 of the peak (1.9e-11 seen; 1.8e-8 with 16 points).  Cells whose
 * edge passes within 1e-2 w of the point, where the average is not smooth on the branch's
 * scale, are left out. */
static void test_ring_points(void **state)
{
    (void)state;
    gsl_set_error_handler_off();
    WS_MARG = gsl_integration_workspace_alloc(1000);
    const char *specs[] = {"gauss:w=0.001,cutoff=2", "gauss:w=0.001", "gauss:w=0.001,cutoff=5",
                           "gauss:w=0.001,shift", "gauss:w=0.001,cutoff=5,shift", "lucy:c=0.003"};
    mimas_box box = {{-0.02, -0.02, -0.01}, {0.02, 0.02, 0.01}, 0, 0, 0, {0, 0, 0}};
    mimas_grid g;
    mimas_error err;
    assert_int_equal(mimas_grid_parse(&g, "r=0:0.01:20,z=-0.005:0.005:20", NULL, &err), MIMAS_OK);
    mimas_grid_fit_box(&g, &box);
    size_t nc = mimas_grid_cells(&g);
    double *dense = calloc(nc, sizeof *dense);
    assert_non_null(dense);
    mimas_weights ws = {0};
    for (size_t k = 0; k < sizeof specs / sizeof specs[0]; k++) {
        mimas_weight wt;
        assert_int_equal(mimas_weight_parse(&wt, specs[k], &err), MIMAS_OK);
        memset(&K, 0, sizeof K);
        K.lucy = wt.kind == MIMAS_WEIGHT_LUCY;
        K.w = wt.w, K.cut = K.lucy ? 1.0 : wt.cutoff, K.coef = wt.coef, K.shift = wt.shift;
        K.gridded[0] = K.gridded[1] = K.gridded[2] = 1;
        mimas_deposit dp;
        assert_int_equal(mimas_deposit_init(&dp, &g, &wt, &box, 0, &err), MIMAS_OK);
        gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
        gsl_rng_set(rng, 11 + k);
        double peak = phi(0.0), worst[3] = {0, 0, 0}, R = reach(), len = 1e-8 * K.w;
        int tier2 = 0;
        for (int o = 0; o < 40; o++) {
            double rho = uniform(rng, 0.0, 3.0 * K.w), t = uniform(rng, 0, 2 * M_PI);
            double a[3] = {rho * cos(t), rho * sin(t), uniform(rng, -0.002, 0.002)};
            double b[3] = {a[0] + len * cos(t + 1), a[1] + len * sin(t + 1), a[2] + 0.5 * len};
            double m[3] = {0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1]), 0.5 * (a[2] + b[2])};
            double rho_m = hypot(m[0], m[1]);
            dense_segment(&dp, a, b, &ws, dense, nc);
            for (size_t c = 0; c < nc; c++) {
                double ctr[3];
                mimas_grid_cell_centre(&g, c, ctr);
                double dz = ctr[2] - m[2], near = hypot(ctr[0] - rho_m, dz) - R;
                double far = hypot(ctr[0] + rho_m, dz) - R;
                if (fabs(near) < 1e-2 * K.w || fabs(far) < 1e-2 * K.w)
                    continue;
                double y = (R * R - (ctr[0] - rho_m) * (ctr[0] - rho_m) - dz * dz) /
                           (4 * ctr[0] * rho_m);
                /* 0: the rest, 1: the second tier, 2: the long arcs */
                int kind = near < 0 && y > 0.02 && y <= 0.25 ? 1 : (near < 0 && y > 0.5 ? 2 : 0);
                tier2 += kind == 1;
                double ref = ring_average(ctr[0], rho_m, dz), dev = fabs(dense[c] - ref) / peak;
                if (kind == 1 && !K.lucy) /* relative to the value itself */
                    dev = fabs(dense[c] - ref) / (fabs(ref) + 1e-4 * peak);
                double tol = K.lucy ? 1e-10 : (kind == 1 ? 1e-12 : 1e-13);
                if (!(dev < tol))
                    print_message("# %s, point %d, cell %zu (y %g): %.17g, reference %.17g\n",
                                  specs[k], o, c, y, dense[c], ref);
                assert_true(dev < tol);
                worst[kind] = fmax(worst[kind], dev);
            }
        }
        print_message("# r-z points, %s: worst %.2g of the value (Lucy: of the peak) at the %d "
                      "cells with 0.02 < y <= 0.25, of the peak %.2g with y > 1/2, %.2g "
                      "elsewhere\n",
                      specs[k], worst[1], tier2, worst[2], worst[0]);
        assert_true(K.lucy || tier2 >= 500);
        gsl_rng_free(rng);
    }
    mimas_weights_free(&ws);
    free(dense);
    gsl_integration_workspace_free(WS_MARG);
}

int main(void)
{
    const struct CMUnitTest tests[] = {cmocka_unit_test(test_random_deposits),
                                       cmocka_unit_test(test_random_ring_branches),
                                       cmocka_unit_test(test_ring_points)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}
