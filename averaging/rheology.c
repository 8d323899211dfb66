#include <config.h>

#include "rheology.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* 000 Tables 4.6 and 4.7: small windows of shear rate (1/s) and of I */
static const mimas_rheology_window rate_windows_000[] = {
    {0.02, 0.025}, {0.03, 0.035}, {0.05, 0.055}, {0.07, 0.075}, {0.11, 0.12}};
static const mimas_rheology_window I_windows_000[] = {
    {1e-4, 1.25e-4}, {2e-4, 2.2e-4}, {4e-4, 4.5e-4}, {7e-4, 8e-4}, {1e-3, 1.2e-3}};

void mimas_rheology_options_default(mimas_rheology_options *o)
{
    memset(o, 0, sizeof *o);
    o->definition = MIMAS_RHEOLOGY_GENERAL;
    o->min_shear_rate = 0.02; /* 000 Sec. 4.2: the yield line holds above ~0.02 1/s */
    o->p_lo = 0;
    o->p_hi = INFINITY;
    o->rate_windows = rate_windows_000;
    o->nrate_windows = sizeof rate_windows_000 / sizeof rate_windows_000[0];
    o->I_windows = I_windows_000;
    o->nI_windows = sizeof I_windows_000 / sizeof I_windows_000[0];
}

int mimas_rheology_parse_windows(const char *spec, mimas_rheology_window *w, size_t max,
                                 size_t *n, mimas_error *err)
{
    *n = 0;
    const char *s = spec;
    while (*s) {
        char *end;
        double lo = strtod(s, &end), hi = NAN;
        if (end != s && *end == ':') {
            const char *t = end + 1;
            hi = strtod(t, &end);
            if (end == t)
                hi = NAN;
        }
        if (!isfinite(lo) || !isfinite(hi) || !(hi > lo) || (*end && *end != ',') ||
            (*end == ',' && !end[1]) || *n >= max)
            return mimas_error_set(err, MIMAS_EUSAGE,
                                   "windows are LO:HI[,LO:HI...] with LO < HI (at most %zu), "
                                   "not '%s'", max, spec);
        w[(*n)++] = (mimas_rheology_window){lo, hi};
        s = *end ? end + 1 : end;
    }
    if (!*n)
        return mimas_error_set(err, MIMAS_EUSAGE, "no window in '%s'", spec);
    return MIMAS_OK;
}

/* ---- the single analyses ---- */

int mimas_rheology_yield(const double *p, const double *tau, size_t n, mimas_fit *out,
                         mimas_error *err)
{
    return mimas_fit_line(p, tau, NULL, n, 3, out, err);
}

/* Jop et al. (2006): mu_s + (mu_2 - mu_s)/(1 + I0/I), fitted with
 * q = (mu_s, mu_2, ln I0) so that I0 stays positive. */
static double mu_of_I(double I, const double *q, double *grad, const void *ctx)
{
    (void)ctx;
    double r = exp(q[2]) / I, D = 1.0 + r;
    if (grad) {
        grad[0] = 1.0 - 1.0 / D;
        grad[1] = 1.0 / D;
        grad[2] = -(q[1] - q[0]) * r / (D * D);
    }
    return q[0] + (q[1] - q[0]) / D;
}

static int by_value(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

int mimas_rheology_mu_I(const double *I, const double *mu, size_t n, mimas_fit *out,
                        mimas_error *err)
{
    /* the positive I, and starting values: mu_s and mu_2 the smallest and
     * largest mu, I0 the median I */
    double *x = malloc((n ? n : 1) * sizeof *x), *y = malloc((n ? n : 1) * sizeof *y),
           *sorted = malloc((n ? n : 1) * sizeof *sorted);
    if (!x || !y || !sorted) {
        free(x), free(y), free(sorted);
        return mimas_error_set(err, MIMAS_EIO, "out of memory for the rheology");
    }
    size_t m = 0;
    double q0[3] = {INFINITY, -INFINITY, 0};
    for (size_t i = 0; i < n; i++) {
        if (!(I[i] > 0) || !isfinite(I[i]) || !isfinite(mu[i]))
            continue;
        x[m] = I[i];
        y[m] = mu[i];
        sorted[m++] = I[i];
        q0[0] = fmin(q0[0], mu[i]);
        q0[1] = fmax(q0[1], mu[i]);
    }
    if (m) {
        qsort(sorted, m, sizeof *sorted, by_value);
        q0[2] = log(sorted[m / 2]);
    }
    mimas_fit_model model = {3, mu_of_I, NULL};
    int rc = mimas_fit_nonlinear(&model, x, y, NULL, m, q0, 4, out, err);
    free(x), free(y), free(sorted);
    if (!rc && out->status == MIMAS_FIT_OK) {
        out->p[2] = exp(out->p[2]);
        out->err[2] *= out->p[2]; /* d I0 = I0 d ln I0 */
    }
    return rc;
}

int mimas_rheology_power_law(const double *x, const double *y, size_t n, mimas_fit *out,
                             mimas_error *err)
{
    double *lx = malloc((n ? n : 1) * sizeof *lx), *ly = malloc((n ? n : 1) * sizeof *ly);
    if (!lx || !ly) {
        free(lx), free(ly);
        return mimas_error_set(err, MIMAS_EIO, "out of memory for the rheology");
    }
    for (size_t i = 0; i < n; i++) {
        /* log of a value <= 0 is not finite: the fit skips it */
        lx[i] = x[i] > 0 ? log(x[i]) : NAN;
        ly[i] = y[i] > 0 ? log(y[i]) : NAN;
    }
    int rc = mimas_fit_line(lx, ly, NULL, n, 3, out, err);
    free(lx), free(ly);
    if (!rc && out->status == MIMAS_FIT_OK) {
        out->p[0] = exp(out->p[0]);
        out->err[0] *= out->p[0];
    }
    return rc;
}

void mimas_rheology_window_mean(const double *x, const double *y, size_t n,
                                const mimas_rheology_window *w, double *mean, double *sem,
                                size_t *count)
{
    double m = 0, m2 = 0;
    size_t k = 0;
    for (size_t i = 0; i < n; i++) {
        if (!(x[i] >= w->lo && x[i] < w->hi) || !isfinite(y[i]))
            continue;
        /* Welford */
        double d = y[i] - m;
        m += d / (double)++k;
        m2 += d * (y[i] - m);
    }
    *count = k;
    *mean = k ? m : NAN;
    *sem = k > 1 ? sqrt(m2 / (double)(k - 1) / (double)k) : NAN;
}

/* ---- cell selection ---- */

static void free_cells(mimas_rheology_cells *c)
{
    free(c->p);
    free(c->tau);
    free(c->shear_rate);
    free(c->mu);
    free(c->I);
    free(c->eta);
    memset(c, 0, sizeof *c);
}

static int select_cells(const mimas_fieldset *fs, const mimas_rheology_options *o,
                        mimas_rheology_cells *c, mimas_error *err)
{
    int luding = o->definition == MIMAS_RHEOLOGY_LUDING;
    const char *need[] = {"p", luding ? "tau_phi" : "tau",
                          luding ? "shear_rate_luding" : "shear_rate", "I", "shear_rate"};
    for (int k = 0; k < 5; k++)
        if (!mimas_fieldset_has(fs, need[k]))
            return mimas_error_set(err, MIMAS_EDATA,
                                   "%s: no field '%s' (the %s definition needs p, %s, %s and I%s)",
                                   mimas_fieldset_name(fs), need[k], luding ? "luding" : "general",
                                   need[1], need[2],
                                   luding ? ", which exist on cylindrical grids" : "");
    size_t cells = mimas_fieldset_grid_of(fs)->cells;
    double *f[5];
    int rc = MIMAS_OK;
    for (int k = 0; k < 5; k++)
        f[k] = malloc(cells * sizeof *f[k]);
    double **cols[6] = {&c->p, &c->tau, &c->shear_rate, &c->mu, &c->I, &c->eta};
    for (int k = 0; k < 6; k++)
        *cols[k] = malloc((cells ? cells : 1) * sizeof **cols[k]);
    for (int k = 0; k < 5; k++)
        if (!f[k])
            rc = mimas_error_set(err, MIMAS_EIO, "out of memory for the rheology");
    for (int k = 0; k < 6; k++)
        if (!*cols[k])
            rc = mimas_error_set(err, MIMAS_EIO, "out of memory for the rheology");
    for (int k = 0; !rc && k < 5; k++)
        rc = mimas_fieldset_read(fs, need[k], f[k], NULL, err);
    c->n = 0;
    for (size_t i = 0; !rc && i < cells; i++) {
        double p = f[0][i], tau = f[1][i], sr = f[2][i], I = f[3][i], sg = f[4][i];
        if (!isfinite(p) || !isfinite(tau) || !isfinite(sr) || !(sr > o->min_shear_rate) ||
            p < o->p_lo || p > o->p_hi)
            continue;
        size_t k = c->n++;
        c->p[k] = p;
        c->tau[k] = tau;
        c->shear_rate[k] = sr;
        /* mu = tau/p, eta = tau/shear rate as in docs/fields.md; I scales
         * with the shear rate (I = shear rate d sqrt(rho_p/p)) */
        c->mu[k] = p > 0 ? tau / p : NAN;
        c->eta[k] = tau / sr;
        c->I[k] = !luding ? I : sg > 0 ? I * sr / sg : NAN;
    }
    for (int k = 0; k < 5; k++)
        free(f[k]);
    if (rc)
        free_cells(c);
    return rc;
}

/* ---- the table ---- */

/* How a fit filters its points beyond finiteness. */
enum { ANY, X_POSITIVE, BOTH_POSITIVE };

/* lo, hi: the range of x over the points the fit uses. */
static void range(const double *x, const double *y, size_t n, int positive, double *lo,
                  double *hi)
{
    *lo = INFINITY;
    *hi = -INFINITY;
    for (size_t i = 0; i < n; i++) {
        if (!isfinite(x[i]) || !isfinite(y[i]) || (positive != ANY && !(x[i] > 0)) ||
            (positive == BOTH_POSITIVE && !(y[i] > 0)))
            continue;
        *lo = fmin(*lo, x[i]);
        *hi = fmax(*hi, x[i]);
    }
    if (*lo > *hi)
        *lo = *hi = NAN;
}

static void push(mimas_rheology *r, const char *table, const char *parameter, double value,
                 double error, size_t npts, double lo, double hi, mimas_fit_status s)
{
    r->rows[r->nrows++] = (mimas_rheology_row){table, parameter, value, error, npts, lo, hi, s};
}

/* A fit's parameters as rows, then its scatter: the residual standard
 * deviation sqrt(chi2/(npts - parameters)). */
static void push_fit(mimas_rheology *r, const char *table, const mimas_fit *f,
                     const char *const *names, const double *x, const double *y, int positive)
{
    double lo, hi;
    range(x, y, r->cells.n, positive, &lo, &hi);
    for (size_t k = 0; k < f->np; k++)
        push(r, table, names[k], f->p[k], f->err[k], f->npts, lo, hi, f->status);
    double scatter = f->status == MIMAS_FIT_OK ? sqrt(f->chi2 / (double)(f->npts - f->np)) : NAN;
    push(r, table, "scatter", scatter, NAN, f->npts, lo, hi, f->status);
}

static void push_windows(mimas_rheology *r, const char *table, const double *x,
                         const mimas_rheology_window *w, size_t nw)
{
    for (size_t k = 0; k < nw; k++) {
        double mean, sem;
        size_t count;
        mimas_rheology_window_mean(x, r->cells.eta, r->cells.n, &w[k], &mean, &sem, &count);
        push(r, table, "eta", mean, sem, count, w[k].lo, w[k].hi,
             count >= 2 ? MIMAS_FIT_OK : MIMAS_FIT_FEW_POINTS);
    }
}

void mimas_rheology_free(mimas_rheology *r)
{
    if (!r)
        return;
    free_cells(&r->cells);
    free(r->rows);
    free(r);
}

int mimas_rheology_analyse(const mimas_fieldset *fs, const mimas_rheology_options *o,
                           mimas_rheology **out, mimas_error *err)
{
    *out = NULL;
    mimas_rheology *r = calloc(1, sizeof *r);
    if (!r)
        return mimas_error_set(err, MIMAS_EIO, "out of memory for the rheology");
    r->opt = *o;
    r->rows = malloc((32 + o->nrate_windows + o->nI_windows) * sizeof *r->rows);
    int rc = r->rows ? select_cells(fs, o, &r->cells, err)
                     : mimas_error_set(err, MIMAS_EIO, "out of memory for the rheology");
    const mimas_rheology_cells *c = &r->cells;
    if (!rc)
        rc = mimas_rheology_yield(c->p, c->tau, c->n, &r->yield, err);
    if (!rc)
        rc = mimas_rheology_mu_I(c->I, c->mu, c->n, &r->mu_I, err);
    if (!rc)
        rc = mimas_rheology_power_law(c->shear_rate, c->eta, c->n, &r->eta_rate, err);
    if (!rc)
        rc = mimas_rheology_power_law(c->I, c->eta, c->n, &r->eta_I, err);
    if (rc) {
        mimas_rheology_free(r);
        return rc;
    }
    static const char *const line[] = {"tau0", "zeta"}, *const jop[] = {"mu_s", "mu_2", "I0"},
                             *const power[] = {"k", "n"};
    push_fit(r, "yield", &r->yield, line, c->p, c->tau, ANY);
    /* the friction angle psi = asin(zeta) (000 Table 4.5), in degrees */
    const mimas_fit *y = &r->yield;
    double zeta = y->p[1], deg = 180.0 / M_PI;
    int defined = y->status == MIMAS_FIT_OK && fabs(zeta) <= 1;
    push(r, "yield", "psi_deg", defined ? asin(zeta) * deg : NAN,
         defined ? y->err[1] / sqrt(1 - zeta * zeta) * deg : NAN, y->npts,
         r->rows[0].lo, r->rows[0].hi,
         y->status != MIMAS_FIT_OK || defined ? y->status : MIMAS_FIT_UNDETERMINED);
    push_fit(r, "mu_I", &r->mu_I, jop, c->I, c->mu, X_POSITIVE);
    push_fit(r, "eta_shear_rate", &r->eta_rate, power, c->shear_rate, c->eta, BOTH_POSITIVE);
    push_fit(r, "eta_I", &r->eta_I, power, c->I, c->eta, BOTH_POSITIVE);
    push_windows(r, "eta_window_shear_rate", c->shear_rate, o->rate_windows, o->nrate_windows);
    push_windows(r, "eta_window_I", c->I, o->I_windows, o->nI_windows);
    *out = r;
    return MIMAS_OK;
}
