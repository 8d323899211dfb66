/* Least-squares fits shared by the analyses (shear band, rheology): a
 * nonlinear model by GSL's trust-region solver (multifit_nlinear) and a
 * straight line (gsl_fit), weighted by 1/sigma^2 when standard errors are
 * given.  Parameter errors come from the covariance (J^T W J)^-1: taken as
 * they are when weighted (the sigmas are trusted as absolute errors), scaled
 * by sqrt(chi2/dof) when unweighted (the scatter about the fit estimates the
 * noise).  A fit that cannot be made is not an error: its status says why. */
#ifndef MIMAS_FIT_H
#define MIMAS_FIT_H

#include <stddef.h>

#include "error.h"

#ifdef __cplusplus
extern "C" {
#endif

#define MIMAS_FIT_MAXP 4

typedef enum mimas_fit_status {
    MIMAS_FIT_OK,
    MIMAS_FIT_FEW_POINTS,     /* fewer valid points than asked for (at least parameters + 1) */
    MIMAS_FIT_NO_CONVERGENCE, /* the solver stopped without meeting its tolerances */
    MIMAS_FIT_UNDETERMINED,   /* converged, but some parameter is not determined by the data
                                 (singular covariance, non-finite values) */
    MIMAS_FIT_IMPLAUSIBLE     /* converged to what the model does not allow (a negative band
                                 width) or with errors larger than the range of the data */
} mimas_fit_status;

/* "ok", "few_points", "no_convergence", "undetermined", "implausible" (the
 * status column). */
const char *mimas_fit_status_name(mimas_fit_status s);

/* A model y = f(x; p): returns the value and, when grad is not NULL, fills
 * grad[k] = df/dp_k.  ctx is passed through. */
typedef double (*mimas_fit_fn)(double x, const double *p, double *grad, const void *ctx);

typedef struct mimas_fit_model {
    size_t np; /* parameters (at most MIMAS_FIT_MAXP) */
    mimas_fit_fn f;
    const void *ctx;
} mimas_fit_model;

typedef struct mimas_fit {
    size_t np;
    double p[MIMAS_FIT_MAXP], err[MIMAS_FIT_MAXP];
    double chi2;     /* sum of squared residuals, each divided by its sigma when weighted */
    size_t npts;     /* valid points used */
    int weighted;
    mimas_fit_status status;
} mimas_fit;

/* Fits the model to the points (x[i], y[i]) from the start p0.  Points whose
 * x or y is not finite, or (when sigma is not NULL) whose sigma is not finite
 * and positive, are skipped.  With fewer than max(min_points, np + 1) valid
 * points the status is MIMAS_FIT_FEW_POINTS.  Parameters and errors are NaN
 * unless the status is MIMAS_FIT_OK.  Returns MIMAS_OK, or MIMAS_EIO when
 * out of memory. */
int mimas_fit_nonlinear(const mimas_fit_model *m, const double *x, const double *y,
                        const double *sigma, size_t n, const double *p0, size_t min_points,
                        mimas_fit *out, mimas_error *err);

/* The straight line y = p[0] + p[1] x (gsl_fit_linear, or gsl_fit_wlinear
 * with sigma), same conventions. */
int mimas_fit_line(const double *x, const double *y, const double *sigma, size_t n,
                   size_t min_points, mimas_fit *out, mimas_error *err);

#ifdef __cplusplus
}
#endif
#endif
