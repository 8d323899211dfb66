/* The Gaussian line integrals are built for any processor, with AVX2 and with AVX-512.  On
 * x-y-z grids (averaging/deposit_gauss.c) the AVX2 and AVX-512 builds classify a row's
 * cells and evaluate the cells the cut ball cuts four or eight at a time; on r-z grids
 * (averaging/deposit_ring.c) the AVX2 build's lanes read the table of M_{1/2} four at a
 * time, and the AVX-512 build evaluates eight branch points at a time.  Every build the
 * processor runs must give the portable build's weights to the bit, cell for cell: random
 * segments of every kind (short and long ones, along an axis, across the grid's edges and
 * its shorter last cell, near the axis, rows of fewer than four and more than eight
 * cells), for the plain and the shifted Gaussian, cutoffs 3 to 5 and widths from half to
 * three times the cell size.  The portable builds are the ones the deposits' own tests
 * check against independent integrals (test_mercurycg, test_average, test_weight).  The
 * Gaussian's particles on x-y-z grids are built the same three ways (their rows' cells four
 * or eight at a time), compared the same way and checked against the kernel here. */
#include <config.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>
#include <gsl/gsl_randist.h>
#include <gsl/gsl_rng.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "assert_close.h"
#include "deposit.h"
#include "deposit_impl.h"
#include "simd.h"
#include "weight.h"

typedef struct entry {
    size_t cell;
    double w;
} entry;

static int by_cell(const void *x, const void *y)
{
    const entry *a = x, *b = y;
    return a->cell < b->cell ? -1 : a->cell > b->cell;
}

/* The list's entries sorted by cell (the builds put them in different orders). */
static entry *sorted(const mimas_weights *ws)
{
    entry *e = malloc((ws->n ? ws->n : 1) * sizeof *e);
    assert_non_null(e);
    for (size_t k = 0; k < ws->n; k++)
        e[k] = (entry){ws->cell[k], ws->w[k]};
    qsort(e, ws->n, sizeof *e, by_cell);
    return e;
}

/* The two lists hold the same cells with the same weights to the bit. */
static void assert_same(const mimas_weights *w1, const mimas_weights *w2, const char *what,
                        int k)
{
    assert_int_equal(w1->n, w2->n);
    entry *e1 = sorted(w1), *e2 = sorted(w2);
    for (size_t m = 0; m < w1->n; m++) {
        assert_int_equal(e1[m].cell, e2[m].cell);
        if (memcmp(&e1[m].w, &e2[m].w, sizeof(double)) != 0)
            fail_msg("%s segment %d cell %zu: %.17g != %.17g", what, k, e1[m].cell, e1[m].w,
                     e2[m].w);
    }
    free(e1);
    free(e2);
}

/* The deposit of `weight` on `grid` (its bounds as given) in `box`, into g, wt and dp */
static void deposit_on(const char *grid, const char *weight, const mimas_box *box,
                       mimas_grid *g, mimas_weight *wt, mimas_deposit *dp)
{
    mimas_error err;
    assert_int_equal(mimas_grid_parse(g, grid, NULL, &err), 0);
    assert_int_equal(mimas_weight_parse(wt, weight, &err), 0);
    assert_int_equal(mimas_deposit_init(dp, g, wt, box, 0, &err), MIMAS_OK);
}

typedef int (*rz_build)(const mimas_deposit *, const double *, const double *, const double *,
                        double, double, mimas_weights *);
typedef int (*xyz_build)(const mimas_deposit *, const double *, const double *,
                         mimas_weights *);

/* n random segments on the grid with the weight: the given build (x-y-z grids: xyz, r-z
 * grids: rz) against the portable one; returns how many weights were compared. */
static size_t compare_builds(const char *grid, const char *weight, int periodic, int n,
                             unsigned long seed, xyz_build xyz, rz_build rz)
{
    mimas_grid g;
    mimas_weight wt;
    mimas_deposit dp;
    mimas_box box = {{0, 0, 0}, {0.01, 0.012, 0.009}, 0, 0, 0, {periodic, periodic, periodic}};
    deposit_on(grid, weight, &box, &g, &wt, &dp);
    assert_true(dp.gauss_xyz || dp.gauss_rz);
    mimas_gauss_tables();
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    gsl_rng_set(rng, seed);
    mimas_weights w1, w2;
    memset(&w1, 0, sizeof w1);
    memset(&w2, 0, sizeof w2);
    size_t compared = 0;
    for (int k = 0; k < n; k++) {
        double a[3], b[3], len;
        int kind = k % 5;
        /* lengths from a hundredth of the width to four widths */
        len = wt.w * (kind == 0 ? 0.01 + 0.2 * gsl_rng_uniform(rng)
                                : (kind == 4 ? 2.0 + 2.0 * gsl_rng_uniform(rng)
                                             : 0.3 + 1.5 * gsl_rng_uniform(rng)));
        for (int d = 0; d < 3; d++)
            a[d] = box.lo[d] - 0.001 + (box.hi[d] - box.lo[d] + 0.002) * gsl_rng_uniform(rng);
        double dir[3] = {gsl_ran_ugaussian(rng), gsl_ran_ugaussian(rng), gsl_ran_ugaussian(rng)};
        if (kind == 1) /* along an axis, and in a plane of two */
            dir[k / 5 % 3] = dir[(k / 5 + 1) % 3] = 0.0;
        if (kind == 2)
            dir[k / 5 % 3] = 0.0;
        double norm = sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
        if (!(norm > 0))
            dir[0] = norm = 1.0;
        for (int d = 0; d < 3; d++)
            b[d] = a[d] + len * dir[d] / norm;
        w1.n = w2.n = 0;
        int r1, r2;
        if (dp.gauss_xyz) {
            r1 = xyz(&dp, a, b, &w1);
            r2 = mimas_gauss_segment_xyz_portable(&dp, a, b, &w2);
        } else {
            double m[3] = {0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1]), 0.5 * (a[2] + b[2])};
            double reach = 0.5 * len + mimas_weight_reach(&wt);
            r1 = rz(&dp, a, b, m, reach, dp.inv_extent, &w1);
            r2 = mimas_gauss_segment_rz_portable(&dp, a, b, m, reach, dp.inv_extent, &w2);
        }
        assert_int_equal(r1, r2);
        char what[256];
        snprintf(what, sizeof what, "%s %s", grid, weight);
        assert_same(&w1, &w2, what, k);
        compared += w1.n;
    }
    mimas_weights_free(&w1);
    mimas_weights_free(&w2);
    gsl_rng_free(rng);
    return compared;
}

static void test_builds_agree(void **state)
{
    (void)state;
#if MIMAS_X86_DISPATCH
    if (!__builtin_cpu_supports("avx2"))
        skip(); /* one build only: nothing to compare */
    int avx512 = __builtin_cpu_supports("avx512f");
    if (!avx512)
        printf("# no AVX-512 on this processor: its builds not compared\n");
#else
    skip();
#endif
    /* cells of 1 mm (the last ones shorter: 10, 12, 9 mm over 10.5, 11.3, 9.7 cells) */
    const char *grid = "x=0:0.01:10,y=0:0.012:11,z=0:0.009:10";
    const char *weights[] = {"gauss:w=0.001",          "gauss:w=0.001,shift",
                             "gauss:w=0.0007,cutoff=4", "gauss:w=0.0005,cutoff=5",
                             "gauss:w=0.002",          "gauss:w=0.0012,cutoff=3.5,shift"};
    /* x-y-z grids: each build the processor runs, and the one the deposit chooses */
    xyz_build xyz[3] = {mimas_gauss_segment_xyz, NULL, NULL};
#if MIMAS_X86_DISPATCH
    xyz[1] = mimas_gauss_segment_xyz_avx2;
    xyz[2] = avx512 ? mimas_gauss_segment_xyz_avx512 : NULL;
#endif
    for (int m = 0; m < 3 && xyz[m]; m++) {
        size_t total = 0;
        for (size_t k = 0; k < sizeof weights / sizeof weights[0]; k++) {
            total += compare_builds(grid, weights[k], 0, 400, 11 + k, xyz[m], NULL);
            total += compare_builds(grid, weights[k], 1, 200, 101 + k, xyz[m], NULL);
        }
        /* a coarse grid: rows of fewer than four cells; a fine one: rows of more than
         * eight, and w = 3 h, cutoff 4: 25 cells */
        total += compare_builds("x=0:0.01:3,y=0:0.012:2,z=0:0.009:3", "gauss:w=0.002", 0, 300,
                                7, xyz[m], NULL);
        total += compare_builds("x=0:0.01:20,y=0:0.012:24,z=0:0.009:18",
                                "gauss:w=0.0015,cutoff=4", 1, 100, 8, xyz[m], NULL);
        assert_true(total > 200000); /* enough cells, cut and uncut, to mean something */
    }
    /* r-z grids, the axis at the box's corner: branches from on the axis to r = 11 mm (rules
     * of 4, 8 and 16 points: the AVX-512 build takes those of 4 to its AVX2 build), each
     * build the processor runs, and the one the deposit chooses */
    rz_build builds[3] = {mimas_gauss_segment_rz, NULL, NULL};
#if MIMAS_X86_DISPATCH
    builds[1] = mimas_gauss_segment_rz_avx2;
    builds[2] = avx512 ? mimas_gauss_segment_rz_avx512 : NULL;
#endif
    int rz_builds = 0;
    for (int m = 0; m < 3 && builds[m]; m++) {
        rz_builds++;
        size_t rz = 0;
        for (size_t k = 0; k < sizeof weights / sizeof weights[0]; k++)
            rz += compare_builds("r=0:0.011:11,z=0:0.009:9", weights[k], 0, 150, 201 + k,
                                 NULL, builds[m]);
        assert_true(rz > 20000);
    }
    assert_true(rz_builds >= 2); /* the portable build compared with at least one other */
}

typedef int (*rz_sphere_build)(const mimas_deposit *, const double *, int, double,
                               mimas_weights *);

/* Particles on an r-z grid (the axis at the box's corner: from on the axis to r = 16 mm),
 * with their gradients: each build the processor runs gives the portable build's weights
 * and gradients to the bit, and the portable build's lanes give the azimuthal average
 * mimas_kernel_ring computes cell by cell (test_weight checks it against quadratures) to
 * 1e-13 of the particle's largest weight and gradient, with no cell missing or extra. */
static void test_particles_rz(void **state)
{
    (void)state;
    const char *weights[] = {"gauss:w=0.001", "gauss:w=0.001,shift", "gauss:w=0.0007,cutoff=4",
                             "gauss:w=0.002", "gauss:w=0.0012,cutoff=3.5,shift"};
    rz_sphere_build builds[2] = {NULL, NULL};
#if MIMAS_X86_DISPATCH
    if (__builtin_cpu_supports("avx2"))
        builds[0] = mimas_gauss_sphere_rz_avx2;
    if (__builtin_cpu_supports("avx512f"))
        builds[1] = mimas_gauss_sphere_rz_avx512;
#endif
    size_t lanes = 0, compared = 0;
    for (size_t k = 0; k < sizeof weights / sizeof weights[0]; k++) {
        mimas_grid g;
        mimas_weight wt;
        mimas_deposit dp;
        mimas_box box = {{0, 0, 0}, {0.011, 0.011, 0.009}, 0, 0, 0, {0, 0, 0}};
        deposit_on("r=0:0.011:11,z=0:0.009:9", weights[k], &box, &g, &wt, &dp);
        assert_true(dp.gauss_rz);
        gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
        gsl_rng_set(rng, 301 + k);
        mimas_weights w0, w1;
        memset(&w0, 0, sizeof w0);
        memset(&w1, 0, sizeof w1);
        size_t cells = mimas_grid_cells(&g);
        for (int p = 0; p < 300; p++) {
            double a[3] = {0.0115 * gsl_rng_uniform(rng), 0.0115 * gsl_rng_uniform(rng),
                           -0.001 + 0.011 * gsl_rng_uniform(rng)};
            if (p % 50 == 0) /* on the axis */
                a[0] = a[1] = 0.0;
            w0.n = 0;
            assert_int_equal(mimas_gauss_sphere_rz_portable(&dp, a, 1, dp.inv_extent, &w0), 0);
            assert_true(w0.has_grad);
            for (int b = 0; b < 2; b++) {
                if (!builds[b])
                    continue;
                w1.n = 0;
                assert_int_equal(builds[b](&dp, a, 1, dp.inv_extent, &w1), 0);
                assert_int_equal(w1.n, w0.n); /* the same cells in the same order */
                for (size_t m = 0; m < w0.n; m++) {
                    assert_int_equal(w1.cell[m], w0.cell[m]);
                    assert_memory_equal(&w1.w[m], &w0.w[m], sizeof(double));
                    for (int d = 0; d < 3; d++)
                        assert_memory_equal(&mimas_weights_grad(&w1, d)[m],
                                            &mimas_weights_grad(&w0, d)[m], sizeof(double));
                }
                lanes += w0.n;
            }
            /* every cell against the azimuthal average at its centre */
            double rho = hypot(a[0], a[1]), *want = calloc(3 * cells, sizeof *want);
            double big = 0.0, bigg = 0.0;
            assert_non_null(want);
            for (size_t c = 0; c < cells; c++) {
                double ctr[3], gr[2];
                mimas_grid_cell_centre(&g, c, ctr);
                want[3 * c] = mimas_kernel_ring(&wt, 3, ctr[0], rho, ctr[2] - a[2], gr) *
                              dp.inv_extent;
                want[3 * c + 1] = gr[0] * dp.inv_extent;
                want[3 * c + 2] = gr[1] * dp.inv_extent;
                big = fmax(big, fabs(want[3 * c]));
                bigg = fmax(bigg, fmax(fabs(want[3 * c + 1]), fabs(want[3 * c + 2])));
            }
            double *got = calloc(3 * cells, sizeof *got);
            assert_non_null(got);
            for (size_t m = 0; m < w0.n; m++) {
                got[3 * w0.cell[m]] = w0.w[m];
                got[3 * w0.cell[m] + 1] = mimas_weights_grad(&w0, 0)[m];
                got[3 * w0.cell[m] + 2] = mimas_weights_grad(&w0, 2)[m];
            }
            for (size_t c = 0; c < cells; c++) {
                assert_true((got[3 * c] != 0.0) == (want[3 * c] != 0.0));
                assert_close(got[3 * c], want[3 * c], 1e-13 * big);
                assert_close(got[3 * c + 1], want[3 * c + 1], 1e-13 * bigg);
                assert_close(got[3 * c + 2], want[3 * c + 2], 1e-13 * bigg);
                compared += got[3 * c] != 0.0;
            }
            free(want);
            free(got);
        }
        mimas_weights_free(&w0);
        mimas_weights_free(&w1);
        gsl_rng_free(rng);
    }
    printf("# r-z particles: %zu weights against the cell-by-cell average, %zu between builds\n",
           compared, lanes);
    assert_true(compared > 20000);
}

typedef int (*xyz_sphere_build)(const mimas_deposit *, const double *, int, mimas_weights *);

/* Particles on x-y-z grids (the last cells shorter; rows of fewer than four cells and of
 * more than eight), with and without their gradients: each build the processor runs, and
 * the one the deposit chooses, gives the portable build's cells in the same order and their
 * weights and gradients to the bit; the portable build gives, at every cell centre of the
 * grid, coef (e^{-r^2/2w^2} - shift) and its gradient -(c - x)/w^2 coef e^{-r^2/2w^2}
 * inside the cut ball and nothing outside, written out here (to 1e-14 of the largest, the
 * build's factors coming from a recurrence; cells within 1e-12 of the cutoff may go either
 * way).  Particles added after a first one in the same list grow it: the first one's
 * weights and gradients stay where they were (the list keeps one plane per component). */
static void test_particles_xyz(void **state)
{
    (void)state;
    const char *grids[] = {"x=0:0.01:10,y=0:0.012:11,z=0:0.009:10",
                           "x=0:0.01:3,y=0:0.012:2,z=0:0.009:3",
                           "x=0:0.01:20,y=0:0.012:24,z=0:0.009:18"};
    const char *weights[] = {"gauss:w=0.001", "gauss:w=0.001,shift", "gauss:w=0.0007,cutoff=4",
                             "gauss:w=0.002", "gauss:w=0.0012,cutoff=3.5,shift"};
    xyz_sphere_build builds[3] = {mimas_gauss_sphere_xyz, NULL, NULL};
#if MIMAS_X86_DISPATCH
    if (__builtin_cpu_supports("avx2"))
        builds[1] = mimas_gauss_sphere_xyz_avx2;
    if (__builtin_cpu_supports("avx512f"))
        builds[2] = mimas_gauss_sphere_xyz_avx512;
#endif
    size_t checked = 0, compared = 0;
    for (size_t gi = 0; gi < sizeof grids / sizeof grids[0]; gi++)
        for (size_t k = 0; k < sizeof weights / sizeof weights[0]; k++) {
            mimas_grid g;
            mimas_weight wt;
            mimas_deposit dp;
            mimas_box box = {{0, 0, 0}, {0.01, 0.012, 0.009}, 0, 0, 0, {0, 0, 0}};
            deposit_on(grids[gi], weights[k], &box, &g, &wt, &dp);
            assert_true(dp.gauss_xyz);
            gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
            gsl_rng_set(rng, 401 + 10 * gi + k);
            mimas_weights w0, w1;
            memset(&w0, 0, sizeof w0);
            memset(&w1, 0, sizeof w1);
            size_t cells = mimas_grid_cells(&g);
            double *want = calloc(4 * cells, sizeof *want), *got = calloc(4 * cells, sizeof *got);
            assert_non_null(want);
            assert_non_null(got);
            for (int p = 0; p < 60; p++) {
                double x[3];
                for (int d = 0; d < 3; d++)
                    x[d] = box.lo[d] - 0.002 +
                           (box.hi[d] - box.lo[d] + 0.004) * gsl_rng_uniform(rng);
                int grad = p % 2;
                w0.n = 0;
                assert_int_equal(mimas_gauss_sphere_xyz_portable(&dp, x, grad, &w0), 0);
                for (int b = 0; b < 3; b++) {
                    if (!builds[b])
                        continue;
                    w1.n = 0;
                    assert_int_equal(builds[b](&dp, x, grad, &w1), 0);
                    assert_int_equal(w1.n, w0.n);
                    assert_int_equal(w1.has_grad, grad);
                    for (size_t m = 0; m < w0.n; m++) {
                        assert_int_equal(w1.cell[m], w0.cell[m]);
                        assert_memory_equal(&w1.w[m], &w0.w[m], sizeof(double));
                        for (int d = 0; grad && d < 3; d++)
                            assert_memory_equal(&mimas_weights_grad(&w1, d)[m],
                                                &mimas_weights_grad(&w0, d)[m], sizeof(double));
                    }
                    compared += w0.n;
                }
                /* every cell centre against the kernel written out */
                double big = 0.0, bigg = 0.0;
                memset(got, 0, 4 * cells * sizeof *got);
                for (size_t c = 0; c < cells; c++) {
                    double ctr[3], r2 = 0.0, dd[3];
                    mimas_grid_cell_centre(&g, c, ctr);
                    for (int d = 0; d < 3; d++) {
                        dd[d] = ctr[d] - x[d];
                        r2 += dd[d] * dd[d];
                    }
                    double e = wt.coef * exp(-r2 / (2.0 * wt.w * wt.w));
                    int in = r2 < wt.reach2;
                    want[4 * c] = in ? e - wt.coef * wt.shift : 0.0;
                    for (int d = 0; d < 3; d++)
                        want[4 * c + 1 + d] = in ? -dd[d] / (wt.w * wt.w) * e : 0.0;
                    big = fmax(big, fabs(e));
                    for (int d = 0; d < 3; d++)
                        bigg = fmax(bigg, fabs(want[4 * c + 1 + d]));
                    /* NaN: a cell at the cutoff, which may go either way */
                    if (fabs(r2 - wt.reach2) < 1e-12 * wt.reach2)
                        want[4 * c] = NAN;
                }
                for (size_t m = 0; m < w0.n; m++) {
                    size_t c = w0.cell[m];
                    assert_true(c < cells);
                    assert_true(got[4 * c] == 0.0); /* each cell once */
                    got[4 * c] = w0.w[m];
                    for (int d = 0; grad && d < 3; d++)
                        got[4 * c + 1 + d] = mimas_weights_grad(&w0, d)[m];
                    assert_true(got[4 * c] != 0.0 || wt.shifted);
                }
                for (size_t c = 0; c < cells; c++) {
                    if (isnan(want[4 * c]))
                        continue;
                    assert_close(got[4 * c], want[4 * c], 1e-14 * big);
                    for (int d = 0; grad && d < 3; d++)
                        assert_close(got[4 * c + 1 + d], want[4 * c + 1 + d], 1e-14 * bigg);
                    checked++;
                }
                /* a second particle after the first in a new list, until it grows */
                if (p == 1 && w0.n > 0) {
                    mimas_weights w2;
                    memset(&w2, 0, sizeof w2);
                    assert_int_equal(mimas_gauss_sphere_xyz_portable(&dp, x, 1, &w2), 0);
                    size_t n0 = w2.n, cap0 = w2.cap;
                    while (w2.cap == cap0) /* the same particle again: n0 more each time */
                        assert_int_equal(mimas_gauss_sphere_xyz_portable(&dp, x, 1, &w2), 0);
                    for (size_t m = 0; m < n0; m++) {
                        assert_int_equal(w2.cell[m], w0.cell[m]);
                        assert_memory_equal(&w2.w[m], &w0.w[m], sizeof(double));
                        for (int d = 0; d < 3; d++)
                            assert_memory_equal(&mimas_weights_grad(&w2, d)[m],
                                                &mimas_weights_grad(&w0, d)[m], sizeof(double));
                    }
                    mimas_weights_free(&w2);
                }
            }
            free(want);
            free(got);
            mimas_weights_free(&w0);
            mimas_weights_free(&w1);
            gsl_rng_free(rng);
        }
    printf("# particles on x-y-z grids: %zu cells checked, %zu weights compared between "
           "builds\n", checked, compared);
    assert_true(checked > 100000);
    assert_true(compared > 10000);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_builds_agree),
        cmocka_unit_test(test_particles_rz),
        cmocka_unit_test(test_particles_xyz),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
