/* Rheology of sheared granular matter from averaged fields (docs/theory.md §7.2;
 * Uhlig 2012, Sec. 4.2): the yield line tau = tau0 + zeta p with the friction angle
 * psi = asin(zeta), the mu(I) law of Jop et al. (2006)
 * mu = mu_s + (mu_2 - mu_s)/(1 + I0/I), power laws of the viscosity
 * eta = k gammadot^n and eta = k I^n, and the mean viscosity in windows of
 * shear rate or inertial number (Uhlig 2012, Tables 4.6, 4.7).  The result is one
 * long table, a row per parameter or window (docs/rheology.md). */
#ifndef MIMAS_RHEOLOGY_H
#define MIMAS_RHEOLOGY_H

#include <stddef.h>

#include "error.h"
#include "fieldset.h"
#include "fit.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Which shear stress and shear rate: the invariants (tau = sqrt(s:s/2),
 * shear_rate = sqrt(2 D':D'), eta, mu, I as averaged), or Uhlig's ring-shear
 * forms (tau_phi, shear_rate_luding, and eta, mu, I from them). */
typedef enum mimas_rheology_definition {
    MIMAS_RHEOLOGY_GENERAL,
    MIMAS_RHEOLOGY_LUDING
} mimas_rheology_definition;

typedef struct mimas_rheology_window {
    double lo, hi; /* lo <= x < hi */
} mimas_rheology_window;

/* Parses "LO:HI[,LO:HI...]" (at most max windows, each LO < HI). */
int mimas_rheology_parse_windows(const char *spec, mimas_rheology_window *w, size_t max,
                                 size_t *n, mimas_error *err);

typedef struct mimas_rheology_options {
    mimas_rheology_definition definition;
    double min_shear_rate;    /* cells with shear rate above this (1/s) */
    double p_lo, p_hi;        /* and p_lo <= p <= p_hi */
    const mimas_rheology_window *rate_windows, *I_windows;
    size_t nrate_windows, nI_windows;
} mimas_rheology_options;

/* The defaults: general, 0.02 1/s, 0 <= p, the windows of Uhlig (2012), Tables 4.6/4.7. */
void mimas_rheology_options_default(mimas_rheology_options *o);

/* The cells an analysis uses, per the definition. */
typedef struct mimas_rheology_cells {
    size_t n;
    double *p, *tau, *shear_rate, *mu, *I, *eta;
    double *p_sem, *tau_sem;   /* standard errors over frames (NaN: none in the file) */
} mimas_rheology_cells;

/* ---- the single analyses (unweighted; errors scaled by the scatter) ---- */

/* tau = p[0] + p[1] p: tau0, zeta. */
int mimas_rheology_yield(const double *p, const double *tau, size_t n, mimas_fit *out,
                         mimas_error *err);
/* mu = mu_s + (mu_2 - mu_s)/(1 + I0/I): p[0] mu_s, p[1] mu_2, p[2] I0.
 * Points with I <= 0 are skipped. */
int mimas_rheology_mu_I(const double *I, const double *mu, size_t n, mimas_fit *out,
                        mimas_error *err);
/* y = k x^m fitted as the line ln y = ln k + m ln x: p[0] k (its error
 * k times that of ln k), p[1] m; points with x <= 0 or y <= 0 skipped; chi2
 * is in ln units. */
int mimas_rheology_power_law(const double *x, const double *y, size_t n, mimas_fit *out,
                             mimas_error *err);
/* The mean of y over the points with w->lo <= x < w->hi, its standard
 * error sd/sqrt(count) (NaN with fewer than 2 points) and the count. */
void mimas_rheology_window_mean(const double *x, const double *y, size_t n,
                                const mimas_rheology_window *w, double *mean, double *sem,
                                size_t *count);

/* ---- the whole table ---- */

typedef struct mimas_rheology_row {
    const char *table;      /* yield, mu_I, eta_shear_rate, eta_I, eta_window_shear_rate,
                               eta_window_I */
    const char *parameter;  /* zeta, tau0, psi_deg, mu_s, mu_2, I0, k, n, scatter, eta */
    double value, error;
    size_t npts;
    double lo, hi;          /* the independent variable: its range over the points (fits)
                               or the window's bounds */
    mimas_fit_status status;
} mimas_rheology_row;

typedef struct mimas_rheology {
    mimas_rheology_options opt;
    mimas_rheology_cells cells;
    mimas_fit yield, mu_I, eta_rate, eta_I;
    mimas_rheology_row *rows;
    size_t nrows;
} mimas_rheology;

/* Selects the cells of the field set and runs every analysis.  Fields the
 * definition needs but the set lacks (e.g. tau_phi on a Cartesian grid) are
 * MIMAS_EDATA naming the set. */
int mimas_rheology_analyse(const mimas_fieldset *fs, const mimas_rheology_options *o,
                           mimas_rheology **out, mimas_error *err);
void mimas_rheology_free(mimas_rheology *r);

/* PREFIX.yield.png (tau against p with the line), PREFIX.mu_I.png (mu
 * against I with the fit) and PREFIX.eta.png (eta against shear rate and I
 * with the power laws), by gnuplot; all or none. */
int mimas_rheology_plot(const mimas_rheology *r, const char *prefix, mimas_error *err);

#ifdef __cplusplus
}
#endif
#endif
