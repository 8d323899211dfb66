#include <config.h>

#include "fit.h"

#include <gsl/gsl_blas.h>
#include <gsl/gsl_fit.h>
#include <gsl/gsl_multifit_nlinear.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* the solver's limits: a fit that needs more is reported as not converged */
#define MAX_ITER 500
#define XTOL 1e-10
#define GTOL 1e-10
/* below this reciprocal condition number of the Jacobian a parameter is
 * taken as undetermined by the data */
#define MIN_RCOND 1e-12

const char *mimas_fit_status_name(mimas_fit_status s)
{
    switch (s) {
    case MIMAS_FIT_OK: return "ok";
    case MIMAS_FIT_FEW_POINTS: return "few_points";
    case MIMAS_FIT_NO_CONVERGENCE: return "no_convergence";
    case MIMAS_FIT_UNDETERMINED: return "undetermined";
    case MIMAS_FIT_IMPLAUSIBLE: return "implausible";
    }
    return "unknown";
}

/* The valid points, copied; w the weights 1/sigma^2 (NULL if unweighted). */
typedef struct points {
    double *x, *y, *w;
    size_t n;
} points;

static int collect(const double *x, const double *y, const double *sigma, size_t n, points *pt)
{
    memset(pt, 0, sizeof *pt);
    pt->x = malloc((n ? n : 1) * sizeof *pt->x);
    pt->y = malloc((n ? n : 1) * sizeof *pt->y);
    pt->w = sigma ? malloc((n ? n : 1) * sizeof *pt->w) : NULL;
    if (!pt->x || !pt->y || (sigma && !pt->w))
        return -1;
    for (size_t i = 0; i < n; i++) {
        if (!isfinite(x[i]) || !isfinite(y[i]))
            continue;
        if (sigma && !(isfinite(sigma[i]) && sigma[i] > 0))
            continue;
        pt->x[pt->n] = x[i];
        pt->y[pt->n] = y[i];
        if (sigma)
            pt->w[pt->n] = 1.0 / (sigma[i] * sigma[i]);
        pt->n++;
    }
    return 0;
}

static void release(points *pt)
{
    free(pt->x);
    free(pt->y);
    free(pt->w);
}

/* Starts a result: NaN parameters, the given status. */
static void blank(mimas_fit *out, size_t np, size_t npts, int weighted, mimas_fit_status s)
{
    memset(out, 0, sizeof *out);
    out->np = np;
    out->npts = npts;
    out->weighted = weighted;
    out->status = s;
    out->chi2 = NAN;
    for (size_t k = 0; k < MIMAS_FIT_MAXP; k++)
        out->p[k] = out->err[k] = NAN;
}

/* Keeps the result only if every number is finite (else undetermined). */
static void settle(mimas_fit *out)
{
    int finite = isfinite(out->chi2);
    for (size_t k = 0; k < out->np; k++)
        finite &= isfinite(out->p[k]) && isfinite(out->err[k]);
    if (finite)
        return;
    mimas_fit_status s = MIMAS_FIT_UNDETERMINED;
    blank(out, out->np, out->npts, out->weighted, s);
}

typedef struct nl_data {
    const mimas_fit_model *m;
    const points *pt;
} nl_data;

static int nl_f(const gsl_vector *p, void *params, gsl_vector *f)
{
    const nl_data *d = params;
    double q[MIMAS_FIT_MAXP];
    for (size_t k = 0; k < d->m->np; k++)
        q[k] = gsl_vector_get(p, k);
    for (size_t i = 0; i < d->pt->n; i++) {
        double v = d->m->f(d->pt->x[i], q, NULL, d->m->ctx);
        if (!isfinite(v))
            return GSL_EDOM;
        gsl_vector_set(f, i, v - d->pt->y[i]);
    }
    return GSL_SUCCESS;
}

static int nl_df(const gsl_vector *p, void *params, gsl_matrix *J)
{
    const nl_data *d = params;
    double q[MIMAS_FIT_MAXP], g[MIMAS_FIT_MAXP];
    for (size_t k = 0; k < d->m->np; k++)
        q[k] = gsl_vector_get(p, k);
    for (size_t i = 0; i < d->pt->n; i++) {
        d->m->f(d->pt->x[i], q, g, d->m->ctx);
        for (size_t k = 0; k < d->m->np; k++) {
            if (!isfinite(g[k]))
                return GSL_EDOM;
            gsl_matrix_set(J, i, k, g[k]);
        }
    }
    return GSL_SUCCESS;
}

/* The trust-region solve on valid points (pt->n > np). */
static int solve(const mimas_fit_model *m, const points *pt, const double *p0, mimas_fit *out)
{
    size_t np = m->np, n = pt->n;
    nl_data d = {m, pt};
    gsl_multifit_nlinear_fdf fdf;
    memset(&fdf, 0, sizeof fdf);
    fdf.f = nl_f;
    fdf.df = nl_df;
    fdf.n = n;
    fdf.p = np;
    fdf.params = &d;
    gsl_multifit_nlinear_parameters par = gsl_multifit_nlinear_default_parameters();
    gsl_multifit_nlinear_workspace *w =
        gsl_multifit_nlinear_alloc(gsl_multifit_nlinear_trust, &par, n, np);
    gsl_matrix *covar = gsl_matrix_alloc(np, np);
    if (!w || !covar) {
        if (w)
            gsl_multifit_nlinear_free(w);
        if (covar)
            gsl_matrix_free(covar);
        return -1;
    }
    gsl_vector_const_view x0 = gsl_vector_const_view_array(p0, np);
    int status;
    if (pt->w) {
        gsl_vector_const_view wts = gsl_vector_const_view_array(pt->w, n);
        status = gsl_multifit_nlinear_winit(&x0.vector, &wts.vector, &fdf, w);
    } else {
        status = gsl_multifit_nlinear_init(&x0.vector, &fdf, w);
    }
    int info = 0;
    if (status == GSL_SUCCESS)
        status = gsl_multifit_nlinear_driver(MAX_ITER, XTOL, GTOL, 0.0, NULL, NULL, &info, w);
    if (status != GSL_SUCCESS) {
        out->status = MIMAS_FIT_NO_CONVERGENCE;
    } else {
        const gsl_vector *res = gsl_multifit_nlinear_residual(w);
        const gsl_vector *x = gsl_multifit_nlinear_position(w);
        double chi2, rcond = 0;
        gsl_blas_ddot(res, res, &chi2);
        gsl_multifit_nlinear_rcond(&rcond, w);
        gsl_multifit_nlinear_covar(gsl_multifit_nlinear_jac(w), 0.0, covar);
        /* weighted: absolute errors; unweighted: scaled by the scatter */
        double scale = pt->w ? 1.0 : sqrt(chi2 / (double)(n - np));
        out->chi2 = chi2;
        for (size_t k = 0; k < np; k++) {
            out->p[k] = gsl_vector_get(x, k);
            out->err[k] = scale * sqrt(gsl_matrix_get(covar, k, k));
        }
        out->status = rcond >= MIN_RCOND ? MIMAS_FIT_OK : MIMAS_FIT_UNDETERMINED;
    }
    gsl_multifit_nlinear_free(w);
    gsl_matrix_free(covar);
    return 0;
}

int mimas_fit_nonlinear(const mimas_fit_model *m, const double *x, const double *y,
                        const double *sigma, size_t n, const double *p0, size_t min_points,
                        mimas_fit *out, mimas_error *err)
{
    points pt;
    if (m->np < 1 || m->np > MIMAS_FIT_MAXP)
        return mimas_error_set(err, MIMAS_EUSAGE, "a fit takes 1 to %d parameters",
                               MIMAS_FIT_MAXP);
    if (collect(x, y, sigma, n, &pt)) {
        release(&pt);
        return mimas_error_set(err, MIMAS_EIO, "out of memory for the fit");
    }
    size_t need = min_points > m->np + 1 ? min_points : m->np + 1;
    blank(out, m->np, pt.n, sigma != NULL,
          pt.n < need ? MIMAS_FIT_FEW_POINTS : MIMAS_FIT_OK);
    int rc = 0;
    if (out->status == MIMAS_FIT_OK)
        rc = solve(m, &pt, p0, out);
    release(&pt);
    if (rc)
        return mimas_error_set(err, MIMAS_EIO, "out of memory for the fit");
    if (out->status == MIMAS_FIT_OK)
        settle(out);
    else
        blank(out, m->np, out->npts, out->weighted, out->status);
    return MIMAS_OK;
}

int mimas_fit_line(const double *x, const double *y, const double *sigma, size_t n,
                   size_t min_points, mimas_fit *out, mimas_error *err)
{
    points pt;
    if (collect(x, y, sigma, n, &pt)) {
        release(&pt);
        return mimas_error_set(err, MIMAS_EIO, "out of memory for the fit");
    }
    size_t need = min_points > 3 ? min_points : 3;
    blank(out, 2, pt.n, sigma != NULL, pt.n < need ? MIMAS_FIT_FEW_POINTS : MIMAS_FIT_OK);
    if (out->status == MIMAS_FIT_OK) {
        double c0, c1, c00, c01, c11, chi2;
        /* gsl_fit_linear scales the covariance by the scatter, gsl_fit_wlinear
         * does not: the conventions of fit.h */
        if (pt.w)
            gsl_fit_wlinear(pt.x, 1, pt.w, 1, pt.y, 1, pt.n, &c0, &c1, &c00, &c01, &c11, &chi2);
        else
            gsl_fit_linear(pt.x, 1, pt.y, 1, pt.n, &c0, &c1, &c00, &c01, &c11, &chi2);
        out->p[0] = c0;
        out->p[1] = c1;
        out->err[0] = sqrt(c00);
        out->err[1] = sqrt(c11);
        out->chi2 = chi2;
        /* all x equal: the slope is not determined */
        double lo = pt.x[0], hi = pt.x[0];
        for (size_t i = 1; i < pt.n; i++) {
            lo = fmin(lo, pt.x[i]);
            hi = fmax(hi, pt.x[i]);
        }
        if (!(hi > lo))
            out->p[1] = NAN;
        settle(out);
    }
    release(&pt);
    return MIMAS_OK;
}
