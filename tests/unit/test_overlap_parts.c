/* The parts of the sphere-ring overlap's quadrature (averaging/overlap.c): the polynomial
 * cosine, atan2 and beta - sin(beta) of averaging/poly_trig.h against libm and against long
 * double, the builds of the slices (averaging/annulus_slices.c) against each other, and the
 * 41-point Gauss-Kronrod rule of averaging/kronrod41.h against the integrals of
 * polynomials and against GSL's gsl_integration_qk41. */
#include <config.h>

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include <float.h>
#include <gsl/gsl_integration.h>
#include <gsl/gsl_rng.h>
#include <math.h>
#include <string.h>

#include "annulus_slices.h"
#include "kronrod41.h"
#include "simd.h"

#define PT_LANES 2
#define PT_(name) pt_##name
#include "poly_trig.h"

#define PI 3.14159265358979323846

/* the functions at PT_LANES points at once, lane k of the result for x[k] (and y[k]) */
static void at_points(int which, const double *y, const double *x, double *out)
{
    pt_vd vx, vy;
    memcpy(&vx, x, sizeof vx);
    memcpy(&vy, y, sizeof vy);
    pt_vd r = which == 0 ? pt_cos(vx) : which == 1 ? pt_bms(vx) : pt_atan2(vy, vx);
    memcpy(out, &r, sizeof r);
}

/* beta - sin(beta) in long double: the series where it cancels (beta < 1/2), else the
 * difference (which loses at most a factor 25 of long double's 64 bits there) */
static long double bms_ref(long double x)
{
    if (x >= 0.5L)
        return x - sinl(x);
    long double term = x * x * x / 6.0L, sum = 0.0L;
    for (int k = 1; fabsl(term) > 1e-40L; k++) {
        sum += term;
        term *= -x * x / ((2.0L * k + 2.0L) * (2.0L * k + 3.0L));
    }
    return sum;
}

static void test_poly_trig(void **state)
{
    (void)state;
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    double worst[3] = {0.0, 0.0, 0.0};
    for (int trial = 0; trial < 50000; trial++) {
        double x[PT_LANES], y[PT_LANES], r[PT_LANES];
        /* cos on [-pi/2, pi/2]: absolute error against long double (the value <= 1) */
        for (int k = 0; k < PT_LANES; k++)
            x[k] = PI * (gsl_rng_uniform(rng) - 0.5);
        at_points(0, y, x, r);
        for (int k = 0; k < PT_LANES; k++)
            worst[0] = fmax(worst[0], (double)fabsl(r[k] - cosl(x[k])));
        /* beta - sin(beta) on [0, pi], also at tiny beta: relative error */
        for (int k = 0; k < PT_LANES; k++)
            x[k] = trial % 2 ? PI * gsl_rng_uniform(rng)
                             : pow(10.0, -8.0 * gsl_rng_uniform(rng));
        at_points(1, y, x, r);
        for (int k = 0; k < PT_LANES; k++) {
            long double want = bms_ref(x[k]);
            worst[1] = fmax(worst[1], (double)fabsl((r[k] - want) / want));
        }
        /* atan2 for y >= 0, every x, ratios from 1e-12 to 1e12: error relative to the
         * angle, against libm (within an ulp of the exact angle) */
        for (int k = 0; k < PT_LANES; k++) {
            y[k] = pow(10.0, 6.0 * (2.0 * gsl_rng_uniform(rng) - 1.0));
            double scale = pow(10.0, 6.0 * (2.0 * gsl_rng_uniform(rng) - 1.0));
            x[k] = (gsl_rng_uniform(rng) - 0.5) * scale;
        }
        at_points(2, y, x, r);
        for (int k = 0; k < PT_LANES; k++) {
            double want = atan2(y[k], x[k]);
            worst[2] = fmax(worst[2], fabs(r[k] - want) / want);
        }
    }
    print_message("# cos %.2g (absolute), bms %.2g, atan2 %.2g (relative)\n", worst[0], worst[1],
                  worst[2]);
    assert_true(worst[0] < 4.0 * DBL_EPSILON);
    assert_true(worst[1] < 8.0 * DBL_EPSILON);
    assert_true(worst[2] < 8.0 * DBL_EPSILON);
    /* the limits: atan2 at 0 and on the axes, cos at the ends, bms at 0 (PT_LANES a call) */
    double x[4] = {0.0, -1.0, 0.0, 2.0}, y[4] = {0.0, 0.0, 3.0, 0.0}, r[4];
    double e[4] = {PI / 2, -PI / 2, 0.0, 1e-300}, c[4], b[4];
    for (int k = 0; k < 4; k += PT_LANES) {
        at_points(2, y + k, x + k, r + k);
        at_points(0, y + k, e + k, c + k);
        at_points(1, y + k, e + k, b + k);
    }
    assert_true(r[0] == 0.0 && r[3] == 0.0);
    assert_true(fabs(r[1] - PI) <= 4e-16 && fabs(r[2] - PI / 2) <= 2.3e-16);
    assert_true(fabs(c[0]) < 4e-16 && fabs(c[1]) < 4e-16 && c[2] == 1.0 && c[3] == 1.0);
    assert_true(b[2] == 0.0 && b[3] == 0.0);
    gsl_rng_free(rng);
}

typedef void (*slice_build)(double, double, double, double, double, double, const double *,
                            double *, int);

/* The builds of the slices the processor runs (four and eight nodes at a time) give the
 * portable build's values (two at a time) to the bit, on random balls, annuli and bands. */
static void test_slice_builds(void **state)
{
    (void)state;
    slice_build builds[3] = {annulus_slices_portable, NULL, NULL};
#if MIMAS_X86_DISPATCH
    if (__builtin_cpu_supports("avx2"))
        builds[1] = annulus_slices_avx2;
    if (__builtin_cpu_supports("avx512f"))
        builds[2] = annulus_slices_avx512;
#endif
    if (!builds[1] && !builds[2])
        skip(); /* one build only: nothing to compare */
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    enum { N = 41, PAD = (N + ANNULUS_LANES - 1) / ANNULUS_LANES * ANNULUS_LANES };
    long compared = 0;
    for (int trial = 0; trial < 20000; trial++) {
        double R = 0.05 + gsl_rng_uniform(rng), d = 3.0 * gsl_rng_uniform(rng) + 1e-3;
        double r1 = d + R * (4.0 * gsl_rng_uniform(rng) - 2.0);
        double r0 = trial % 2 ? 0.0 : r1 * gsl_rng_uniform(rng);
        if (!(r1 > r0))
            continue;
        double ta = -PI / 2 + PI * gsl_rng_uniform(rng);
        double dth = (PI / 2 - ta) * gsl_rng_uniform(rng);
        double t[PAD] = {0}, f0[PAD], f[PAD];
        for (int i = 0; i < N; i++)
            t[i] = gsl_rng_uniform(rng);
        builds[0](d, r0, r1, R, ta, dth, t, f0, N);
        for (int b = 1; b < 3; b++) {
            if (!builds[b])
                continue;
            builds[b](d, r0, r1, R, ta, dth, t, f, N);
            assert_memory_equal(f0, f, N * sizeof(double));
            compared += N;
        }
    }
    print_message("# %ld slices compared to the bit (%s)\n", compared,
                  builds[2] ? "AVX2 and AVX-512" : "AVX2; no AVX-512 here");
    gsl_rng_free(rng);
}

/* the rule on [-1, 1] with the integrand's values at its 41 abscissae: Kronrod's and the
 * embedded Gauss rule's results */
static void rule(double (*f)(double, void *), void *p, double *kronrod, double *gauss)
{
    double k = GK41_WK[20] * f(0.0, p), g = 0.0;
    for (int j = 0; j < 20; j++) {
        double pair = f(-GK41_X[j], p) + f(GK41_X[j], p);
        k += GK41_WK[j] * pair;
        if (j & 1)
            g += GK41_WG[j / 2] * pair;
    }
    *kronrod = k;
    *gauss = g;
}

static double power(double x, void *p)
{
    return pow(x, *(const int *)p);
}

static double wiggle(double x, void *p)
{
    (void)p;
    return exp(x) / (1.5 + x);
}

static void test_kronrod41(void **state)
{
    (void)state;
    /* exact for polynomials: Kronrod to degree 61, the 20-point Gauss rule to 39 */
    for (int n = 0; n <= 61; n++) {
        double k, g, want = n % 2 ? 0.0 : 2.0 / (n + 1);
        rule(power, &n, &k, &g);
        assert_true(fabs(k - want) <= 1e-15);
        if (n <= 39)
            assert_true(fabs(g - want) <= 1e-15);
    }
    double k, g;
    /* GSL's own rule on the same integrand (its tables are the ones printed) */
    gsl_function f = {wiggle, NULL};
    double res, err, resabs, resasc;
    gsl_integration_qk41(&f, -1.0, 1.0, &res, &err, &resabs, &resasc);
    rule(wiggle, NULL, &k, &g);
    print_message("# against GSL: %.3g (relative)\n", (k - res) / res);
    assert_true(fabs(k - res) <= 4e-16 * fabs(res));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_poly_trig),
        cmocka_unit_test(test_slice_builds),
        cmocka_unit_test(test_kronrod41),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
