/* Studies across runs: the trend line against the closed-form least squares
 * (slope, intercept, their errors scaled by the scatter), the study range,
 * the percentage changes with their propagated errors, runs of equal study
 * value and runs without a value; the study variable looked up among the
 * run parameters, and its errors. */
#include <config.h>

#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#include "assert_close.h"
#include "study.h"

/* Least squares y = a + b x over the points with lo <= x <= hi and finite
 * y, by the textbook sums: a, b, their standard errors s sqrt(1/n + m^2/Sxx)
 * and s/sqrt(Sxx) with s^2 = SSR/(n - 2). */
static void closed_form(const double *x, const double *y, size_t n, double lo, double hi,
                        double *a, double *b, double *ea, double *eb, size_t *used)
{
    double sx = 0, sy = 0;
    size_t m = 0;
    for (size_t k = 0; k < n; k++)
        if (x[k] >= lo && x[k] <= hi && isfinite(y[k])) {
            sx += x[k];
            sy += y[k];
            m++;
        }
    double mx = sx / (double)m, my = sy / (double)m, sxx = 0, sxy = 0, ssr = 0;
    for (size_t k = 0; k < n; k++)
        if (x[k] >= lo && x[k] <= hi && isfinite(y[k])) {
            sxx += (x[k] - mx) * (x[k] - mx);
            sxy += (x[k] - mx) * (y[k] - my);
        }
    *b = sxy / sxx;
    *a = my - *b * mx;
    for (size_t k = 0; k < n; k++)
        if (x[k] >= lo && x[k] <= hi && isfinite(y[k]))
            ssr += pow(y[k] - *a - *b * x[k], 2);
    double s2 = ssr / (double)(m - 2);
    *eb = sqrt(s2 / sxx);
    *ea = sqrt(s2 * (1.0 / (double)m + mx * mx / sxx));
    *used = m;
}

/* Uhlig's liquid contents; eta = 300 D + 1200 with deviations that leave
 * a scatter, and a dry run well below the line (as in Uhlig's Table 4.6) */
static const double D[6] = {0, 0.01, 0.05, 0.1, 0.2, 0.4};
static const double dev[6] = {-400, 3, -5, 2, 6, -4};

static void test_line_is_least_squares(void **state)
{
    (void)state;
    double y[6], a, b, ea, eb;
    size_t used;
    for (int k = 0; k < 6; k++)
        y[k] = 300 * D[k] + 1200 + dev[k];
    mimas_trend t;
    mimas_error err;
    assert_int_equal(mimas_study_trend(D, y, NULL, 6, -INFINITY, INFINITY, &t, &err), MIMAS_OK);
    closed_form(D, y, 6, -INFINITY, INFINITY, &a, &b, &ea, &eb, &used);
    assert_int_equal(t.line.status, MIMAS_FIT_OK);
    assert_int_equal(t.line.npts, 6);
    assert_close(t.line.p[1], b, 1e-10 * fabs(b));
    assert_close(t.line.p[0], a, 1e-12 * fabs(a));
    assert_close(t.line.err[1], eb, 1e-10 * eb);
    assert_close(t.line.err[0], ea, 1e-10 * ea);
    /* the wet runs only (Uhlig fits D >= 0.01): the slope comes back near 300 */
    assert_int_equal(mimas_study_trend(D, y, NULL, 6, 0.01, INFINITY, &t, &err), MIMAS_OK);
    closed_form(D, y, 6, 0.01, INFINITY, &a, &b, &ea, &eb, &used);
    assert_int_equal(used, 5);
    assert_int_equal(t.line.npts, 5);
    assert_close(t.line.p[1], b, 1e-10 * fabs(b));
    assert_close(t.line.p[0], a, 1e-12 * fabs(a));
    assert_close(t.line.err[1], eb, 1e-10 * eb);
    assert_true(fabs(b - 300) < 30);
    /* the changes use every run, also those outside the range:
     * dry -> 0.01 and 0.01 -> 0.4 */
    assert_close(t.change_first, 100 * (y[1] - y[0]) / y[0], 1e-12);
    assert_close(t.change_rest, 100 * (y[5] - y[1]) / y[1], 1e-12);
    assert_true(isnan(t.change_first_err)); /* no errors given */
}

static void test_changes_and_their_errors(void **state)
{
    (void)state;
    /* runs given out of order; the error of (b - a)/a for independent a, b:
     * |b/a| sqrt((ea/a)^2 + (eb/b)^2) */
    const double x[4] = {0.05, 0, 0.01, 0.05}, y[4] = {130, 100, 150, 126},
                 e[4] = {2, 3, 4, 2};
    mimas_trend t;
    mimas_error err;
    assert_int_equal(mimas_study_trend(x, y, e, 4, -INFINITY, INFINITY, &t, &err), MIMAS_OK);
    assert_close(t.change_first, 50, 1e-12);
    assert_close(t.change_first_err, 100 * 1.5 * sqrt(pow(3.0 / 100, 2) + pow(4.0 / 150, 2)),
                 1e-12);
    /* the two runs at 0.05 are averaged: 128 with error sqrt(2^2 + 2^2)/2 */
    double b = 128, eb = sqrt(8.0) / 2;
    assert_close(t.change_rest, 100 * (b - 150) / 150, 1e-12);
    assert_close(t.change_rest_err, 100 * (b / 150) * sqrt(pow(4.0 / 150, 2) + pow(eb / b, 2)),
                 1e-12);
    /* the line uses all four runs (the tie too) */
    double a0, b0, ea, eb0;
    size_t used;
    closed_form(x, y, 4, -INFINITY, INFINITY, &a0, &b0, &ea, &eb0, &used);
    assert_close(t.line.p[1], b0, 1e-10 * fabs(b0));
    assert_int_equal(t.line.npts, 4);
}

static void test_few_runs_and_missing_values(void **state)
{
    (void)state;
    const double x[3] = {0, 0.01, 0.05}, y[3] = {10, NAN, 14};
    mimas_trend t;
    mimas_error err;
    /* two runs with a value: no line (a line of two points has no scatter),
     * but the first change; the second needs three study values */
    assert_int_equal(mimas_study_trend(x, y, NULL, 3, -INFINITY, INFINITY, &t, &err), MIMAS_OK);
    assert_int_equal(t.line.status, MIMAS_FIT_FEW_POINTS);
    assert_int_equal(t.line.npts, 2);
    assert_true(isnan(t.line.p[0]) && isnan(t.line.p[1]));
    assert_close(t.change_first, 40, 1e-12);
    assert_true(isnan(t.change_rest));
    /* every run at the same study value: the slope is not determined */
    const double same[3] = {0.1, 0.1, 0.1}, z[3] = {1, 2, 3};
    assert_int_equal(mimas_study_trend(same, z, NULL, 3, -INFINITY, INFINITY, &t, &err),
                     MIMAS_OK);
    assert_int_equal(t.line.status, MIMAS_FIT_UNDETERMINED);
    assert_true(isnan(t.change_first));
    /* a change from 0 is not a number */
    const double zero[3] = {0, 1, 2};
    assert_int_equal(mimas_study_trend(x, zero, NULL, 3, -INFINITY, INFINITY, &t, &err),
                     MIMAS_OK);
    assert_true(isnan(t.change_first));
    assert_close(t.change_rest, 100, 1e-12);
}

static void fill(mimas_parameters *ps)
{
    mimas_parameters_init(ps);
    mimas_error err;
    assert_int_equal(mimas_parameters_add(ps, "particles", "liquid_content", MIMAS_PARAM_REAL,
                                          0.05, NULL, "", &err), MIMAS_OK);
    assert_int_equal(mimas_parameters_add(ps, "contact", "friction", MIMAS_PARAM_REAL, 0.5, NULL,
                                          NULL, &err), MIMAS_OK);
    assert_int_equal(mimas_parameters_add(ps, "contact wall-1", "friction", MIMAS_PARAM_REAL,
                                          0.3, NULL, NULL, &err), MIMAS_OK);
    assert_int_equal(mimas_parameters_add(ps, "contact", "model", MIMAS_PARAM_TEXT, 0, "linear",
                                          NULL, &err), MIMAS_OK);
    assert_int_equal(mimas_parameters_add(ps, "ringshear", "omega", MIMAS_PARAM_REAL, 0.5, NULL,
                                          "rad s-1", &err), MIMAS_OK);
    assert_int_equal(mimas_parameters_add(ps, "ringshear", "count", MIMAS_PARAM_INTEGER, 6500,
                                          NULL, NULL, &err), MIMAS_OK);
}

static void test_study_variable(void **state)
{
    (void)state;
    mimas_parameters ps;
    fill(&ps);
    mimas_error err;
    double v;
    assert_int_equal(mimas_study_value(&ps, "a.h5", "liquid_content", &v, &err), MIMAS_OK);
    assert_true(v == 0.05);
    assert_int_equal(mimas_study_value(&ps, "a.h5", "ringshear.omega", &v, &err), MIMAS_OK);
    assert_true(v == 0.5);
    assert_int_equal(mimas_study_value(&ps, "a.h5", "count", &v, &err), MIMAS_OK);
    assert_true(v == 6500);
    assert_int_equal(mimas_study_value(&ps, "a.h5", "contact wall-1.friction", &v, &err),
                     MIMAS_OK);
    assert_true(v == 0.3);
    /* the errors name the file and what is wrong */
    assert_int_equal(mimas_study_value(&ps, "a.h5", "friction", &v, &err), MIMAS_EDATA);
    assert_non_null(strstr(err.msg, "a.h5: 'friction' is a key of several sections "
                                    "(contact.friction, contact wall-1.friction)"));
    assert_int_equal(mimas_study_value(&ps, "a.h5", "model", &v, &err), MIMAS_EDATA);
    assert_string_equal(err.msg, "a.h5: contact.model is 'linear', not a number");
    assert_int_equal(mimas_study_value(&ps, "a.h5", "liquid_density", &v, &err), MIMAS_EDATA);
    assert_string_equal(err.msg, "a.h5: no parameter 'liquid_density'");
    assert_int_equal(mimas_study_value(&ps, "a.h5", "particles.omega", &v, &err), MIMAS_EDATA);
    assert_true(isnan(v));
    /* a run averaged from inputs that differ in the variable */
    mimas_parameters other;
    fill(&other);
    assert_int_equal(mimas_parameters_add(&other, "particles", "liquid_content",
                                          MIMAS_PARAM_REAL, 0.01, NULL, "", &err), MIMAS_OK);
    assert_int_equal(mimas_parameters_merge(&ps, &other, &err), MIMAS_OK);
    assert_int_equal(mimas_study_value(&ps, "b.h5", "liquid_content", &v, &err), MIMAS_EDATA);
    assert_string_equal(err.msg, "b.h5: the runs averaged into it differ in "
                                 "particles.liquid_content");
    assert_int_equal(mimas_study_value(&ps, "b.h5", "omega", &v, &err), MIMAS_OK);
    /* no parameters at all */
    mimas_parameters none;
    mimas_parameters_init(&none);
    assert_int_equal(mimas_study_value(&none, "c.h5", "omega", &v, &err), MIMAS_EDATA);
    assert_non_null(strstr(err.msg, "c.h5: no run parameters"));
    mimas_parameters_free(&ps);
    mimas_parameters_free(&other);
}

static void test_differences_and_values(void **state)
{
    (void)state;
    mimas_parameters a, b, c;
    fill(&a);
    fill(&b);
    fill(&c);
    mimas_error err;
    assert_int_equal(mimas_parameters_add(&b, "particles", "liquid_content", MIMAS_PARAM_REAL,
                                          0.01, NULL, "", &err), MIMAS_OK);
    assert_int_equal(mimas_parameters_add(&c, "scenario", "seed", MIMAS_PARAM_INTEGER, 7, NULL,
                                          NULL, &err), MIMAS_OK);
    assert_int_equal(mimas_parameters_add(&c, "ringshear", "omega", MIMAS_PARAM_REAL, 0.25,
                                          NULL, "rad s-1", &err), MIMAS_OK);
    const mimas_parameters *runs[3] = {&a, &b, &c};
    char list[256];
    mimas_study_differences(runs, 3, "liquid_content", list, sizeof list);
    assert_string_equal(list, "ringshear.omega, scenario.seed");
    mimas_study_differences(runs, 2, "liquid_content", list, sizeof list);
    assert_string_equal(list, "");
    mimas_study_differences(runs, 2, NULL, list, sizeof list);
    assert_string_equal(list, "particles.liquid_content");
    double v[8];
    size_t n;
    assert_int_equal(mimas_study_parse_values("0,0.01,5e-2", v, 8, &n, &err), MIMAS_OK);
    assert_int_equal(n, 3);
    assert_true(v[0] == 0 && v[1] == 0.01 && v[2] == 0.05);
    assert_int_equal(mimas_study_parse_values("0,,1", v, 8, &n, &err), MIMAS_EUSAGE);
    assert_int_equal(mimas_study_parse_values("0,dry", v, 8, &n, &err), MIMAS_EUSAGE);
    assert_int_equal(mimas_study_parse_values("1,2,", v, 8, &n, &err), MIMAS_EUSAGE);
    mimas_parameters_free(&a);
    mimas_parameters_free(&b);
    mimas_parameters_free(&c);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_line_is_least_squares),
        cmocka_unit_test(test_changes_and_their_errors),
        cmocka_unit_test(test_few_runs_and_missing_values),
        cmocka_unit_test(test_study_variable),
        cmocka_unit_test(test_differences_and_values),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
