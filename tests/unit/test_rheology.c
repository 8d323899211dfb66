/* Rheology (docs/theory.md §7.2; Uhlig 2012, Sec. 4.2): synthetic tau-p, mu(I) and eta data
 * give back their parameters; the analysis of a field file selects its
 * cells and follows the definition. */
#include <config.h>

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>
#include <gsl/gsl_randist.h>
#include <gsl/gsl_rng.h>

#include "assert_close.h"
#include "fields_file.h"
#include "fieldset.h"
#include "rheology.h"
#include "scratch.h"

#define NCELLS 200
#define SEEDS 500

/* Jop et al. (2006), glass beads: mu_s = tan 20.9 deg, mu_2 = tan 32.76 deg, I0 = 0.279 */
static const double MU_S = 0.38186, MU_2 = 0.64361, I0 = 0.279;

static double jop(double I)
{
    return MU_S + (MU_2 - MU_S) / (1 + I0 / I);
}

/* ordinary least squares in closed form, with the standard errors from the
 * residual variance s^2 = sum r^2/(n - 2) */
static void ols(const double *x, const double *y, size_t n, double *p, double *e)
{
    double mx = 0, my = 0, sxx = 0, sxy = 0, ss = 0;
    for (size_t i = 0; i < n; i++)
        mx += x[i] / (double)n, my += y[i] / (double)n;
    for (size_t i = 0; i < n; i++)
        sxx += (x[i] - mx) * (x[i] - mx), sxy += (x[i] - mx) * (y[i] - my);
    p[1] = sxy / sxx;
    p[0] = my - p[1] * mx;
    for (size_t i = 0; i < n; i++) {
        double r = y[i] - p[0] - p[1] * x[i];
        ss += r * r;
    }
    double s2 = ss / (double)(n - 2);
    e[1] = sqrt(s2 / sxx);
    e[0] = sqrt(s2 * (1.0 / (double)n + mx * mx / sxx));
}

static void test_yield_line(void **state)
{
    (void)state;
    /* Uhlig (2012), Table 4.5, D = 0.05: zeta = 0.17, tau0 = 14 Pa */
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    double p[NCELLS], tau[NCELLS], q[2], e[2];
    size_t hit[2] = {0, 0};
    for (int seed = 0; seed < SEEDS; seed++) {
        for (int i = 0; i < NCELLS; i++) {
            p[i] = 50 + 450 * gsl_rng_uniform(rng);
            tau[i] = 14 + 0.17 * p[i] + gsl_ran_gaussian(rng, 3.0);
        }
        mimas_fit f;
        mimas_error err;
        assert_int_equal(mimas_rheology_yield(p, tau, NCELLS, &f, &err), MIMAS_OK);
        assert_int_equal(f.status, MIMAS_FIT_OK);
        ols(p, tau, NCELLS, q, e);
        for (int k = 0; k < 2; k++) {
            assert_close(f.p[k], q[k], 1e-9 * fabs(q[k]));
            assert_close(f.err[k], e[k], 1e-9 * e[k]);
        }
        hit[0] += fabs(f.p[0] - 14) <= f.err[0];
        hit[1] += fabs(f.p[1] - 0.17) <= f.err[1];
    }
    print_message("# yield line: tau0 within 1 error in %.1f %%, zeta in %.1f %% of %d seeds\n",
                  100.0 * hit[0] / SEEDS, 100.0 * hit[1] / SEEDS, SEEDS);
    /* about 68 %: the binomial spread over 500 seeds is 2.1 %, +-8 % is 4 of it */
    assert_in_range((long)(1000 * hit[0] / SEEDS), 600, 760);
    assert_in_range((long)(1000 * hit[1] / SEEDS), 600, 760);
    gsl_rng_free(rng);
}

static void test_mu_of_I(void **state)
{
    (void)state;
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    gsl_rng_set(rng, 3);
    double I[NCELLS], mu[NCELLS], truth[3] = {MU_S, MU_2, I0};
    size_t hit[3] = {0, 0, 0};
    for (int seed = 0; seed < SEEDS; seed++) {
        for (int i = 0; i < NCELLS; i++) {
            I[i] = pow(10.0, -3 + 3.5 * gsl_rng_uniform(rng)); /* 1e-3 .. 3 */
            mu[i] = jop(I[i]) + gsl_ran_gaussian(rng, 0.01);
        }
        I[0] = -1; /* skipped */
        mimas_fit f;
        mimas_error err;
        assert_int_equal(mimas_rheology_mu_I(I, mu, NCELLS, &f, &err), MIMAS_OK);
        assert_int_equal(f.status, MIMAS_FIT_OK);
        assert_int_equal(f.npts, NCELLS - 1);
        for (int k = 0; k < 3; k++) {
            assert_true(fabs(f.p[k] - truth[k]) < 5 * f.err[k]);
            hit[k] += fabs(f.p[k] - truth[k]) <= f.err[k];
        }
    }
    print_message("# mu(I): mu_s within 1 error in %.1f %%, mu_2 in %.1f %%, I0 in %.1f %% of "
                  "%d seeds\n", 100.0 * hit[0] / SEEDS, 100.0 * hit[1] / SEEDS,
                  100.0 * hit[2] / SEEDS, SEEDS);
    for (int k = 0; k < 3; k++)
        assert_in_range((long)(1000 * hit[k] / SEEDS), 600, 760);
    gsl_rng_free(rng);
}

static void test_power_laws(void **state)
{
    (void)state;
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    gsl_rng_set(rng, 5);
    double x[NCELLS], eta[NCELLS];
    size_t hit[2] = {0, 0};
    for (int seed = 0; seed < SEEDS; seed++) {
        /* shear thinning, eta = 60 Pa s (rate in 1/s)^-0.85, 10 % log-normal scatter */
        for (int i = 0; i < NCELLS; i++) {
            x[i] = pow(10.0, -2 + 2 * gsl_rng_uniform(rng));
            eta[i] = 60 * pow(x[i], -0.85) * exp(gsl_ran_gaussian(rng, 0.1));
        }
        x[1] = 0;       /* no log: skipped */
        eta[2] = -3;
        mimas_fit f;
        mimas_error err;
        assert_int_equal(mimas_rheology_power_law(x, eta, NCELLS, &f, &err), MIMAS_OK);
        assert_int_equal(f.status, MIMAS_FIT_OK);
        assert_int_equal(f.npts, NCELLS - 2);
        assert_true(fabs(f.p[0] - 60) < 5 * f.err[0] && fabs(f.p[1] + 0.85) < 5 * f.err[1]);
        hit[0] += fabs(f.p[0] - 60) <= f.err[0];
        hit[1] += fabs(f.p[1] + 0.85) <= f.err[1];
    }
    print_message("# eta power law: k within 1 error in %.1f %%, n in %.1f %% of %d seeds\n",
                  100.0 * hit[0] / SEEDS, 100.0 * hit[1] / SEEDS, SEEDS);
    for (int k = 0; k < 2; k++)
        assert_in_range((long)(1000 * hit[k] / SEEDS), 600, 760);
    gsl_rng_free(rng);
}

static void test_windows(void **state)
{
    (void)state;
    double x[6] = {0.02, 0.021, 0.024, 0.025, 0.03, NAN};
    double y[6] = {1000, 1400, 1200, 5, 7, 9};
    mimas_rheology_window w = {0.02, 0.025};
    double mean, sem;
    size_t n;
    /* lo included, hi not: the first three, mean 1200, sd 200 */
    mimas_rheology_window_mean(x, y, 6, &w, &mean, &sem, &n);
    assert_int_equal(n, 3);
    assert_close(mean, 1200, 1e-9);
    assert_close(sem, 200 / sqrt(3), 1e-9);
    w = (mimas_rheology_window){0.03, 0.04};
    mimas_rheology_window_mean(x, y, 6, &w, &mean, &sem, &n);
    assert_int_equal(n, 1);
    assert_close(mean, 7, 0);
    assert_true(isnan(sem));
    mimas_rheology_window list[4];
    mimas_error err;
    assert_int_equal(mimas_rheology_parse_windows("0.02:0.025,1e-4:2e-4", list, 4, &n, &err), 0);
    assert_int_equal(n, 2);
    assert_close(list[1].lo, 1e-4, 0);
    assert_close(list[1].hi, 2e-4, 0);
    const char *bad[] = {"", "0.1", "0.2:0.1", "0.1:0.2,", "a:b", "0.1:0.2;0.3:0.4",
                         "1:2,3:4,5:6,7:8,9:10"};
    for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++)
        assert_int_equal(mimas_rheology_parse_windows(bad[k], list, 4, &n, &err), MIMAS_EUSAGE);
}

/* A cylindrical field file of NCELLS cells on a known yield line: tau_phi
 * is 0.9 tau and shear_rate_luding half the shear rate; a few cells below
 * the minimum shear rate or outside the pressure range carry nonsense. */
static const char *ring_fields(void)
{
    static double p[NCELLS], tau[NCELLS], tphi[NCELLS], sr[NCELLS], srl[NCELLS], I[NCELLS];
    double r[NCELLS], phi = 0, z = 0;
    for (int i = 0; i < NCELLS; i++) {
        r[i] = 0.01 + 0.001 * i;
        p[i] = 100 + 2 * i;
        sr[i] = 0.05 + 0.01 * i;
        tau[i] = 10 + 0.2 * p[i] + (i % 2 ? 1 : -1); /* scatter of 1 Pa about the line */
        if (i < 10)
            sr[i] = 0.01, tau[i] = 1e4;            /* below the shear rate threshold */
        if (i >= NCELLS - 10)
            p[i] = 1e5;                            /* outside the pressure range */
        tphi[i] = 0.9 * tau[i];
        srl[i] = 0.5 * sr[i];
        I[i] = 1e-3 * sr[i];
    }
    const char *names[] = {"p", "tau", "tau_phi", "shear_rate", "shear_rate_luding", "I"};
    const double *mean[] = {p, tau, tphi, sr, srl, I};
    fields_file_spec s = {"cylindrical", {NCELLS, 1, 1}, {r, &phi, &z}, {1, 0, 0}, 10, {0, 0}, NULL};
    const char *path = scratch_path("ring.h5");
    assert_int_equal(write_fields_file(path, &s, 6, names, mean, NULL), 0);
    return path;
}

static const mimas_rheology_row *row(const mimas_rheology *r, const char *table,
                                     const char *parameter)
{
    for (size_t k = 0; k < r->nrows; k++)
        if (!strcmp(r->rows[k].table, table) && !strcmp(r->rows[k].parameter, parameter))
            return &r->rows[k];
    fail_msg("no row %s %s", table, parameter);
    return NULL;
}

static void test_analysis_of_a_field_file(void **state)
{
    (void)state;
    mimas_fieldset *fs;
    mimas_error err;
    assert_int_equal(mimas_fieldset_open(&fs, ring_fields(), &err), MIMAS_OK);
    mimas_rheology_options o;
    mimas_rheology_options_default(&o);
    o.p_hi = 1000;
    mimas_rheology *g, *l;
    assert_int_equal(mimas_rheology_analyse(fs, &o, &g, &err), MIMAS_OK);
    o.definition = MIMAS_RHEOLOGY_LUDING;
    o.min_shear_rate = 0.01; /* halved like the shear rate: the same cells */
    assert_int_equal(mimas_rheology_analyse(fs, &o, &l, &err), MIMAS_OK);
    assert_int_equal(g->cells.n, NCELLS - 20);
    assert_int_equal(l->cells.n, NCELLS - 20);
    /* the kept cells alternate 1 Pa above and below tau = 10 + 0.2 p */
    const mimas_rheology_row *zeta = row(g, "yield", "zeta"), *tau0 = row(g, "yield", "tau0");
    assert_close(zeta->value, 0.2, 1e-3);
    assert_close(tau0->value, 10, 0.2);
    assert_int_equal(zeta->npts, NCELLS - 20);
    assert_close(zeta->lo, 120, 1e-9);               /* p of cell 10 */
    assert_close(zeta->hi, 100 + 2 * (NCELLS - 11), 1e-9);
    assert_close(row(g, "yield", "psi_deg")->value, asin(zeta->value) * 180 / M_PI, 1e-9);
    assert_close(row(g, "yield", "scatter")->value, 1.0, 0.02);
    /* luding: tau_phi = 0.9 tau */
    assert_close(row(l, "yield", "zeta")->value, 0.9 * zeta->value, 1e-9);
    /* eta = tau/shear rate: luding's is 0.9/0.5 of the general one, I half */
    for (size_t i = 0; i < g->cells.n; i++) {
        assert_close(l->cells.eta[i], 1.8 * g->cells.eta[i], 1e-9 * g->cells.eta[i]);
        assert_close(l->cells.I[i], 0.5 * g->cells.I[i], 1e-15);
        assert_close(l->cells.mu[i], 0.9 * g->cells.tau[i] / g->cells.p[i], 1e-12);
    }
    /* the first default window 0.02:0.025 holds no cell here: reported, not dropped */
    const mimas_rheology_row *w = row(g, "eta_window_shear_rate", "eta");
    assert_int_equal(w->npts, 0);
    assert_int_equal(w->status, MIMAS_FIT_FEW_POINTS);
    assert_true(isnan(w->value));
    assert_close(w->lo, 0.02, 0);
    mimas_rheology_free(g);
    mimas_rheology_free(l);
    mimas_fieldset_close(fs);
}

static void test_missing_fields(void **state)
{
    (void)state;
    double v[3] = {1, 2, 3}, x[3] = {0, 1, 2}, zero = 0;
    const char *names[] = {"p", "tau", "shear_rate", "I"};
    const double *mean[] = {v, v, v, v};
    fields_file_spec s = {"cartesian", {3, 1, 1}, {x, &zero, &zero}, {1, 0, 0}, 3, {0, 0}, NULL};
    const char *path = scratch_path("cart.h5");
    assert_int_equal(write_fields_file(path, &s, 4, names, mean, NULL), 0);
    mimas_fieldset *fs;
    mimas_error err;
    assert_int_equal(mimas_fieldset_open(&fs, path, &err), MIMAS_OK);
    mimas_rheology_options o;
    mimas_rheology_options_default(&o);
    o.definition = MIMAS_RHEOLOGY_LUDING;
    mimas_rheology *r;
    assert_int_equal(mimas_rheology_analyse(fs, &o, &r, &err), MIMAS_EDATA);
    assert_non_null(strstr(err.msg, "cart.h5: no field 'tau_phi'"));
    o.definition = MIMAS_RHEOLOGY_GENERAL;
    assert_int_equal(mimas_rheology_analyse(fs, &o, &r, &err), MIMAS_OK);
    /* 3 cells: enough for the yield line, mu(I) needs 4 */
    assert_int_equal(r->yield.status, MIMAS_FIT_OK);
    assert_int_equal(r->mu_I.status, MIMAS_FIT_FEW_POINTS);
    mimas_rheology_free(r);
    mimas_fieldset_close(fs);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_yield_line),
        cmocka_unit_test(test_mu_of_I),
        cmocka_unit_test(test_power_laws),
        cmocka_unit_test(test_windows),
        cmocka_unit_test(test_analysis_of_a_field_file),
        cmocka_unit_test(test_missing_fields),
    };
    return cmocka_run_group_tests(tests, scratch_setup, scratch_teardown);
}
