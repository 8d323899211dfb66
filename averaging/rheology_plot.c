/* The pictures of mimas rheology --plot PREFIX: the yield line, the mu(I)
 * law and the viscosity power laws over the cells they were fitted to, the
 * cells with their standard errors, the fitted parameters with theirs. */
#include <config.h>

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "plot.h"
#include "rheology.h"

/* columns of the cells file */
#define CELLS_HEADER "# p tau mu I eta shear_rate p_err tau_err mu_err I_err eta_err\n"

/* An error for the file: 0 where there is none (the point is drawn without
 * a bar; gnuplot would drop a point with a NaN column). */
static double bar(double e)
{
    return isfinite(e) && e > 0 ? e : 0;
}

/* Writes the cells with the errors of mu, I and eta propagated from those of
 * p and tau (their correlation neglected; the shear rate has no spread);
 * returns whether any cell has an error. */
static int write_cells(const mimas_rheology *r, mimas_plot *p, int *errors, mimas_error *err)
{
    FILE *fp = mimas_plot_data(p, "cells", err);
    if (!fp)
        return err->code;
    const mimas_rheology_cells *c = &r->cells;
    fputs(CELLS_HEADER, fp);
    *errors = 0;
    for (size_t i = 0; i < c->n; i++) {
        double ep = c->p_sem ? bar(c->p_sem[i]) : 0, et = c->tau_sem ? bar(c->tau_sem[i]) : 0;
        double emu = c->tau[i] != 0 && c->p[i] != 0
                         ? fabs(c->mu[i]) * hypot(et / c->tau[i], ep / c->p[i])
                         : 0;
        double eI = c->p[i] > 0 ? c->I[i] * ep / (2 * c->p[i]) : 0;
        double eeta = c->shear_rate[i] > 0 ? et / c->shear_rate[i] : 0;
        *errors |= ep > 0 || et > 0;
        fprintf(fp, "%.9g\t%.9g\t%.9g\t%.9g\t%.9g\t%.9g\t%.9g\t%.9g\t%.9g\t%.9g\t%.9g\n",
                c->p[i], c->tau[i], c->mu[i], c->I[i], c->eta[i], c->shear_rate[i], ep, et,
                bar(emu), bar(eI), bar(eeta));
    }
    return MIMAS_OK;
}

/* Cells where x (and y) can be drawn (positive on log axes). */
static size_t drawable(const double *x, const double *y, size_t n, int logx, int logy)
{
    size_t k = 0;
    for (size_t i = 0; i < n; i++)
        k += isfinite(x[i]) && isfinite(y[i]) && (!logx || x[i] > 0) && (!logy || y[i] > 0);
    return k;
}

/* The range of the drawable values of x (points, not error bars, decide),
 * with a margin that keeps them off the frame: 5 % of the span, or a factor
 * on log axes.  0 if there is none. */
static int span(const double *x, const double *y, size_t n, int logx, int logy, double *lo,
                double *hi)
{
    *lo = INFINITY, *hi = -INFINITY;
    for (size_t i = 0; i < n; i++)
        if (isfinite(x[i]) && isfinite(y[i]) && (!logx || x[i] > 0) && (!logy || y[i] > 0)) {
            *lo = fmin(*lo, x[i]);
            *hi = fmax(*hi, x[i]);
        }
    if (!(*lo <= *hi))
        return 0;
    if (logx) {
        double f = *hi > *lo ? pow(*hi / *lo, 0.05) : 2;
        *lo /= f, *hi *= f;
    } else {
        double m = *hi > *lo ? 0.05 * (*hi - *lo) : fabs(*lo) > 0 ? 0.1 * fabs(*lo) : 1;
        *lo -= m, *hi += m;
    }
    return 1;
}

/* "set xtics (...)" for a log axis: 1, 2, 5 of every decade in [lo, hi]
 * (only the decades over more than four), so that a short range still has
 * labelled tics */
static void log_tics(char axis, double lo, double hi, char *buf, size_t len)
{
    size_t k = (size_t)snprintf(buf, len, "set %ctics (", axis);
    int first = 1, d0 = (int)floor(log10(lo)), d1 = (int)ceil(log10(hi));
    static const double steps[3] = {1, 2, 5};
    for (int d = d0; d <= d1 && k + 40 < len; d++)
        for (int m = 0; m < (d1 - d0 > 4 ? 1 : 3); m++) {
            double v = steps[m] * pow(10, d);
            if (v < lo || v > hi)
                continue;
            k += (size_t)snprintf(buf + k, len - k, "%s%.3g", first ? "" : ", ", v);
            first = 0;
        }
    snprintf(buf + k, len - k, first ? ")\nset %ctics auto\n" : ")\n", axis);
}

/* "[x range][y range]" of the drawable cells, and the tics of log axes */
static void ranges(const double *x, const double *y, size_t n, int logx, int logy, char *buf,
                   size_t len, char *tics, size_t tlen)
{
    double lo[2], hi[2];
    int ok[2] = {span(x, y, n, logx, logy, &lo[0], &hi[0]),
                 span(y, x, n, logy, logx, &lo[1], &hi[1])};
    size_t k = 0, t = 0;
    tics[0] = '\0';
    for (int a = 0; a < 2; a++) {
        if (ok[a])
            k += (size_t)snprintf(buf + k, len - k, "[%.9g:%.9g]", lo[a], hi[a]);
        else
            k += (size_t)snprintf(buf + k, len - k, "[*:*]");
        if (ok[a] && (a ? logy : logx))
            log_tics(a ? 'y' : 'x', lo[a], hi[a], tics + t, tlen - t), t = strlen(tics);
    }
}

/* One panel: the cells (columns cols, with the error columns ecols and the
 * style style when there are errors) and, if fitted, the curve. */
static int panel(char *s, size_t len, const char *labels, size_t points, const char *ranges,
                 const char *cols, const char *ecols, const char *style, int errors,
                 const char *curve)
{
    if (!points)
        return snprintf(s, len, "%sset label 'no cells to draw' at graph 0.35, graph 0.5\n"
                                "plot [1:2][1:2] NaN notitle\nunset label\n", labels);
    return snprintf(s, len, "%splot %s datadir.'/cells' using %s%s with %s pt 7 ps 0.4 "
                            "lc rgb '#3060b0' title 'cells%s'%s%s\n",
                    labels, ranges, cols, errors ? ecols : "", errors ? style : "points",
                    errors ? " (error bars: standard errors over frames)" : "",
                    curve[0] ? ", " : "", curve);
}

static int render(const mimas_rheology *r, mimas_plot *p, int width, const char *script,
                  mimas_error *err)
{
    int errors;
    int rc = write_cells(r, p, &errors, err);
    if (!rc)
        rc = mimas_plot_render(p, width, width > 1000 ? 720 : 650, script, err);
    return rc;
}

/* Whether any cell has a standard error (decides the styles). */
static int has_errors(const mimas_rheology_cells *c)
{
    for (size_t i = 0; i < c->n; i++)
        if ((c->p_sem && bar(c->p_sem[i]) > 0) || (c->tau_sem && bar(c->tau_sem[i]) > 0))
            return 1;
    return 0;
}

/* Settings every panel shares: points off the frame, a grid, the key below. */
static const char common[] =
    "set grid\nset key below Left reverse height 1\nset format '%g'\n";

int mimas_rheology_plot(const mimas_rheology *r, const char *prefix, mimas_error *err)
{
    const mimas_rheology_cells *c = &r->cells;
    int luding = r->opt.definition == MIMAS_RHEOLOGY_LUDING, errors = has_errors(c);
    const char *tau = luding ? "τ_{φ}" : "τ", *rate = luding ? "γ̇_{L}" : "γ̇";
    char names[3][4200], script[3][8192], labels[1024], curve[1024];
    char a[64], b[64], d[64], rg[200], tics[512];
    const char *what[3] = {"yield", "mu_I", "eta"};
    for (int k = 0; k < 3; k++)
        snprintf(names[k], sizeof names[k], "%s.%s.png", prefix, what[k]);
    /* tau against p with the yield line */
    const mimas_fit *f = &r->yield;
    snprintf(labels, sizeof labels, "%sset xlabel 'p (Pa)'\n"
             "set ylabel '%s (Pa)'\nset title 'yield line %s = τ_0 + ζ p (%zu cells)'\n",
             common, tau, tau, f->npts);
    curve[0] = '\0';
    if (f->status == MIMAS_FIT_OK) {
        mimas_plot_value_error(f->p[0], f->err[0], a, sizeof a);
        mimas_plot_value_error(f->p[1], f->err[1], b, sizeof b);
        double psi = fabs(f->p[1]) <= 1 ? asin(f->p[1]) * 180 / M_PI : NAN;
        double epsi = f->err[1] / sqrt(1 - f->p[1] * f->p[1]) * 180 / M_PI;
        mimas_plot_value_error(psi, epsi, d, sizeof d);
        snprintf(curve, sizeof curve, "%.17g + %.17g*x with lines lw 2 lc rgb 'black' "
                 "title 'τ_0 = %s Pa, ζ = %s (ψ = asin ζ = %s°)'", f->p[0], f->p[1], a, b, d);
    }
    ranges(c->p, c->tau, c->n, 0, 0, rg, sizeof rg, tics, sizeof tics);
    strncat(labels, tics, sizeof labels - strlen(labels) - 1);
    panel(script[0], sizeof script[0], labels, drawable(c->p, c->tau, c->n, 0, 0), rg, "1:2",
          ":7:8", "xyerrorbars", errors, curve);
    /* mu against I with the mu(I) law */
    f = &r->mu_I;
    snprintf(labels, sizeof labels, "%sset logscale x\n"
             "set xlabel 'I'\nset ylabel 'μ = %s/p'\n"
             "set title 'μ(I) = μ_s + (μ_2 - μ_s)/(1 + I_0/I) (%zu cells)'\n",
             common, tau, f->npts);
    curve[0] = '\0';
    if (f->status == MIMAS_FIT_OK) {
        mimas_plot_value_error(f->p[0], f->err[0], a, sizeof a);
        mimas_plot_value_error(f->p[1], f->err[1], b, sizeof b);
        mimas_plot_value_error(f->p[2], f->err[2], d, sizeof d);
        snprintf(curve, sizeof curve, "%.17g + (%.17g - %.17g)/(1 + %.17g/x) with lines lw 2 "
                 "lc rgb 'black' title 'μ_s = %s, μ_2 = %s, I_0 = %s'", f->p[0], f->p[1],
                 f->p[0], f->p[2], a, b, d);
    }
    ranges(c->I, c->mu, c->n, 1, 0, rg, sizeof rg, tics, sizeof tics);
    strncat(labels, tics, sizeof labels - strlen(labels) - 1);
    panel(script[1], sizeof script[1], labels, drawable(c->I, c->mu, c->n, 1, 0), rg, "4:3",
          ":10:9", "xyerrorbars", errors, curve);
    /* eta against shear rate and I, log-log, with the power laws */
    int n = snprintf(script[2], sizeof script[2], "set multiplot layout 1,2\n%s"
                     "set logscale xy\n", common);
    for (int k = 0; k < 2; k++) {
        f = k ? &r->eta_I : &r->eta_rate;
        snprintf(labels, sizeof labels, "set xlabel '%s%s'\nset ylabel 'η = %s/%s (Pa s)'\n"
                 "set title 'η = k %s^n (%zu cells)'\n", k ? "I" : rate,
                 k ? "" : " (s^{-1})", tau, rate, k ? "I" : rate, f->npts);
        curve[0] = '\0';
        if (f->status == MIMAS_FIT_OK) {
            mimas_plot_value_error(f->p[0], f->err[0], a, sizeof a);
            mimas_plot_value_error(f->p[1], f->err[1], b, sizeof b);
            snprintf(curve, sizeof curve, "%.17g*x**%.17g with lines lw 2 lc rgb 'black' "
                     "title 'k = %s %s, n = %s'", f->p[0], f->p[1], a,
                     k ? "Pa s" : "Pa s^{n+1}", b);
        }
        const double *x = k ? c->I : c->shear_rate;
        ranges(x, c->eta, c->n, 1, 1, rg, sizeof rg, tics, sizeof tics);
        strncat(labels, tics, sizeof labels - strlen(labels) - 1);
        n += panel(script[2] + n, sizeof script[2] - (size_t)n, labels,
                   drawable(x, c->eta, c->n, 1, 1), rg, k ? "4:5" : "6:5", ":11", "yerrorbars",
                   errors, curve);
    }
    snprintf(script[2] + n, sizeof script[2] - (size_t)n, "unset multiplot\n");
    /* all three rendered, then all renamed into place */
    mimas_plot *p[3] = {NULL, NULL, NULL};
    int rc = MIMAS_OK;
    for (int k = 0; k < 3 && !rc; k++) {
        rc = mimas_plot_open(&p[k], names[k], err);
        if (!rc)
            rc = render(r, p[k], k == 2 ? 1500 : 850, script[k], err);
    }
    for (int k = 0; k < 3; k++) {
        if (!rc && p[k])
            rc = mimas_plot_commit(p[k], err);
        else
            mimas_plot_abort(p[k]);
    }
    return rc;
}
