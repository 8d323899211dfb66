/* The least-squares fits and their error conventions (averaging/fit.h),
 * against the closed-form straight-line solution. */
#include <config.h>

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "assert_close.h"
#include "fit.h"

#define N 12

/* y = 1 + 2x with fixed deviations, and sigmas from 0.1 to 1.2 */
static void data(double *x, double *y, double *s)
{
    static const double dev[N] = {0.3, -0.2, 0.1, 0.05, -0.4, 0.2, -0.1, 0.35, -0.25, 0.0,
                                  0.15, -0.3};
    for (int i = 0; i < N; i++) {
        x[i] = 0.5 * i;
        y[i] = 1 + 2 * x[i] + dev[i];
        s[i] = 0.1 * (i + 1);
    }
}

/* The weighted straight line in closed form: with S = sum w, Sx = sum w x,
 * ..., D = S Sxx - Sx^2: intercept (Sxx Sy - Sx Sxy)/D, slope
 * (S Sxy - Sx Sy)/D, variances Sxx/D and S/D (w = 1/sigma^2, or 1). */
static void closed_form(const double *x, const double *y, const double *s, double *p,
                        double *var, double *chi2)
{
    double S = 0, Sx = 0, Sy = 0, Sxx = 0, Sxy = 0;
    for (int i = 0; i < N; i++) {
        double w = s ? 1 / (s[i] * s[i]) : 1;
        S += w, Sx += w * x[i], Sy += w * y[i], Sxx += w * x[i] * x[i], Sxy += w * x[i] * y[i];
    }
    double D = S * Sxx - Sx * Sx;
    p[0] = (Sxx * Sy - Sx * Sxy) / D;
    p[1] = (S * Sxy - Sx * Sy) / D;
    var[0] = Sxx / D;
    var[1] = S / D;
    *chi2 = 0;
    for (int i = 0; i < N; i++) {
        double r = (y[i] - p[0] - p[1] * x[i]) / (s ? s[i] : 1);
        *chi2 += r * r;
    }
}

static double line(double x, const double *p, double *grad, const void *ctx)
{
    (void)ctx;
    if (grad) {
        grad[0] = 1;
        grad[1] = x;
    }
    return p[0] + p[1] * x;
}

static void check(const mimas_fit *f, const double *p, const double *var, double chi2,
                  double scale, double tol)
{
    assert_int_equal(f->status, MIMAS_FIT_OK);
    assert_int_equal(f->npts, N);
    for (int k = 0; k < 2; k++) {
        assert_close(f->p[k], p[k], tol * fabs(p[k]));
        assert_close(f->err[k], scale * sqrt(var[k]), tol * scale * sqrt(var[k]));
    }
    assert_close(f->chi2, chi2, tol * chi2);
}

static void test_conventions(void **state)
{
    (void)state;
    double x[N], y[N], s[N], p[2], var[2], chi2, p0[2] = {0, 0};
    data(x, y, s);
    mimas_fit f;
    mimas_error err;
    mimas_fit_model m = {2, line, NULL};
    /* weighted: the covariance (X^T W X)^-1 as it is */
    closed_form(x, y, s, p, var, &chi2);
    assert_int_equal(mimas_fit_line(x, y, s, N, 3, &f, &err), MIMAS_OK);
    check(&f, p, var, chi2, 1.0, 1e-10);
    assert_true(f.weighted);
    assert_int_equal(mimas_fit_nonlinear(&m, x, y, s, N, p0, 3, &f, &err), MIMAS_OK);
    check(&f, p, var, chi2, 1.0, 1e-7);
    /* unweighted: scaled by sqrt(chi2/dof) */
    closed_form(x, y, NULL, p, var, &chi2);
    double scale = sqrt(chi2 / (N - 2));
    assert_int_equal(mimas_fit_line(x, y, NULL, N, 3, &f, &err), MIMAS_OK);
    check(&f, p, var, chi2, scale, 1e-10);
    assert_false(f.weighted);
    assert_int_equal(mimas_fit_nonlinear(&m, x, y, NULL, N, p0, 3, &f, &err), MIMAS_OK);
    check(&f, p, var, chi2, scale, 1e-7);
    /* weighted errors are absolute: sigmas ten times larger, errors too */
    double s10[N];
    for (int i = 0; i < N; i++)
        s10[i] = 10 * s[i];
    mimas_fit g;
    assert_int_equal(mimas_fit_line(x, y, s, N, 3, &f, &err), MIMAS_OK);
    assert_int_equal(mimas_fit_line(x, y, s10, N, 3, &g, &err), MIMAS_OK);
    assert_close(g.err[1], 10 * f.err[1], 1e-12 * g.err[1]);
    assert_close(g.p[1], f.p[1], 1e-12);
}

static void test_invalid_points_and_status(void **state)
{
    (void)state;
    double x[N], y[N], s[N], p0[2] = {0, 0};
    data(x, y, s);
    y[3] = NAN;
    x[5] = INFINITY;
    s[7] = 0;      /* an unusable standard error */
    s[8] = NAN;
    mimas_fit f;
    mimas_error err;
    mimas_fit_model m = {2, line, NULL};
    assert_int_equal(mimas_fit_line(x, y, NULL, N, 3, &f, &err), MIMAS_OK);
    assert_int_equal(f.npts, N - 2);
    assert_int_equal(mimas_fit_nonlinear(&m, x, y, s, N, p0, 3, &f, &err), MIMAS_OK);
    assert_int_equal(f.npts, N - 4);
    assert_int_equal(f.status, MIMAS_FIT_OK);
    /* too few: asked for more than there are, or no degree of freedom */
    assert_int_equal(mimas_fit_line(x, y, NULL, N, N, &f, &err), MIMAS_OK);
    assert_int_equal(f.status, MIMAS_FIT_FEW_POINTS);
    assert_true(isnan(f.p[0]) && isnan(f.err[1]) && isnan(f.chi2));
    assert_int_equal(mimas_fit_nonlinear(&m, x, y, NULL, 2, p0, 1, &f, &err), MIMAS_OK);
    assert_int_equal(f.status, MIMAS_FIT_FEW_POINTS);
    /* all x equal: the slope is not determined */
    for (int i = 0; i < N; i++)
        x[i] = 1.5;
    assert_int_equal(mimas_fit_line(x, y, NULL, N, 3, &f, &err), MIMAS_OK);
    assert_int_equal(f.status, MIMAS_FIT_UNDETERMINED);
    assert_int_equal(mimas_fit_nonlinear(&m, x, y, NULL, N, p0, 3, &f, &err), MIMAS_OK);
    assert_int_equal(f.status, MIMAS_FIT_UNDETERMINED);
    assert_true(isnan(f.p[1]));
    assert_string_equal(mimas_fit_status_name(MIMAS_FIT_NO_CONVERGENCE), "no_convergence");
    assert_string_equal(mimas_fit_status_name(MIMAS_FIT_UNDETERMINED), "undetermined");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_conventions),
        cmocka_unit_test(test_invalid_points_and_status),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
