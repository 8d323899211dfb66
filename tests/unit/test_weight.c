/* Coarse-graining kernels: normalisation, gradients and line integrals
 * against independent numerical integration. */
#include <config.h>

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include <gsl/gsl_integration.h>
#include <math.h>

#include "assert_close.h"
#include "weight.h"

static double radial(double r, void *p)
{
    const mimas_weight *wt = p;
    double d[3] = {r, 0, 0}, g[3];
    return 4 * M_PI * r * r * mimas_kernel_phi_grad(wt, d, g);
}

static void check_kernel(const char *spec)
{
    mimas_weight wt;
    mimas_error err;
    assert_int_equal(mimas_weight_parse(&wt, spec, &err), MIMAS_OK);
    /* integral over space = 1 (GSL adaptive quadrature of 4 pi r^2 phi) */
    gsl_integration_workspace *ws = gsl_integration_workspace_alloc(200);
    gsl_function F = {radial, &wt};
    double total, abserr;
    gsl_integration_qag(&F, 0, mimas_weight_reach(&wt), 1e-15, 1e-13, 200, 6, ws, &total,
                        &abserr);
    gsl_integration_workspace_free(ws);
    assert_close(total, 1.0, 1e-12);
    /* gradient = central differences of phi */
    double d[3] = {0.31 * wt.w, -0.22 * wt.w, 0.5 * wt.w}, g[3], gp[3], h = 1e-6 * wt.w;
    mimas_kernel_phi_grad(&wt, d, g);
    for (int k = 0; k < 3; k++) {
        double dp[3] = {d[0], d[1], d[2]}, dm[3] = {d[0], d[1], d[2]};
        dp[k] += h;
        dm[k] -= h;
        double fd = (mimas_kernel_phi_grad(&wt, dp, gp) - mimas_kernel_phi_grad(&wt, dm, gp)) /
                    (2 * h);
        assert_close(g[k], fd, 1e-6 * fabs(fd) + 1e-9 * wt.coef / wt.w);
    }
    /* line integral = a fine midpoint sum along the segment, for segments
     * crossing the support, ending inside it, and passing through the point */
    const double segs[3][6] = {{-2, 0.3, 0.1, 2.5, -0.2, 0.4},
                               {0.1, 0.2, 0.3, 0.9, 0.1, -0.4},
                               {-0.5, 0, 0, 0.5, 0, 0}};
    for (int s = 0; s < 3; s++) {
        double a[3], b[3], br[3], dj[3];
        for (int k = 0; k < 3; k++) {
            a[k] = segs[s][k] * wt.w;
            b[k] = segs[s][3 + k] * wt.w;
            br[k] = b[k] - a[k];
            dj[k] = -a[k]; /* field point at the origin: d = r - r_j */
        }
        double psi = mimas_kernel_line(&wt, dj, br);
        const int n = 400000;
        double sum = 0;
        for (int m = 0; m < n; m++) {
            double t = (m + 0.5) / n, p[3];
            for (int k = 0; k < 3; k++)
                p[k] = dj[k] - t * br[k];
            sum += mimas_kernel_phi_grad(&wt, p, gp) / n;
        }
        assert_close(psi, sum, 1e-8 * fabs(sum) + 1e-14 * wt.coef);
    }
}

static void test_gauss(void **state)
{
    (void)state;
    check_kernel("gauss:w=0.002");
    check_kernel("gauss:w=0.5,cutoff=2");
}

static void test_lucy(void **state)
{
    (void)state;
    check_kernel("lucy:c=0.003");
}

static void test_parse_errors(void **state)
{
    (void)state;
    mimas_weight wt;
    mimas_error err;
    const char *bad[] = {"gauss", "gauss:w=0", "gauss:w=1,cutoff=-1", "gauss:x=1", "lucy:c=",
                         "lucy:c=-2", "shepard:", "box"};
    for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++)
        if (mimas_weight_parse(&wt, bad[k], &err) != MIMAS_EUSAGE)
            fail_msg("'%s' accepted", bad[k]);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_gauss),
        cmocka_unit_test(test_lucy),
        cmocka_unit_test(test_parse_errors),
    };
    return cmocka_run_group_tests_name("weight", tests, NULL, NULL);
}
