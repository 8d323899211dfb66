/* The pictures of mimas rheology --plot PREFIX: the yield line, the mu(I)
 * law and the viscosity power laws over the cells they were fitted to. */
#include <config.h>

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "plot.h"
#include "rheology.h"

/* columns of the cells file */
#define CELLS_HEADER "# p tau mu I eta shear_rate\n"

static int write_cells(const mimas_rheology *r, mimas_plot *p, mimas_error *err)
{
    FILE *fp = mimas_plot_data(p, "cells", err);
    if (!fp)
        return err->code;
    const mimas_rheology_cells *c = &r->cells;
    fputs(CELLS_HEADER, fp);
    for (size_t i = 0; i < c->n; i++)
        fprintf(fp, "%.9g\t%.9g\t%.9g\t%.9g\t%.9g\t%.9g\n", c->p[i], c->tau[i], c->mu[i], c->I[i],
                c->eta[i], c->shear_rate[i]);
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

/* One panel: the cells (columns cx:cy) and, if fitted, the curve. */
static int panel(char *s, size_t len, const char *labels, size_t points, const char *cols,
                 const char *curve)
{
    if (!points)
        return snprintf(s, len, "%sset label 'no cells to draw' at graph 0.35, graph 0.5\n"
                                "plot [1:2][1:2] NaN notitle\nunset label\n", labels);
    return snprintf(s, len, "%splot datadir.'/cells' using %s with points pt 7 ps 0.4 "
                            "lc rgb '#3060b0' title 'cells'%s%s\n",
                    labels, cols, curve[0] ? ", " : "", curve);
}

static int render(const mimas_rheology *r, mimas_plot *p, int width, const char *script,
                  mimas_error *err)
{
    int rc = write_cells(r, p, err);
    if (!rc)
        rc = mimas_plot_render(p, width, 600, script, err);
    return rc;
}

int mimas_rheology_plot(const mimas_rheology *r, const char *prefix, mimas_error *err)
{
    const mimas_rheology_cells *c = &r->cells;
    int luding = r->opt.definition == MIMAS_RHEOLOGY_LUDING;
    const char *tau = luding ? "tau_phi" : "tau", *rate = luding ? "shear_rate_luding"
                                                                  : "shear_rate";
    char names[3][4200], script[3][4096], labels[512], curve[512];
    const char *what[3] = {"yield", "mu_I", "eta"};
    for (int k = 0; k < 3; k++)
        snprintf(names[k], sizeof names[k], "%s.%s.png", prefix, what[k]);
    /* tau against p with the yield line */
    const mimas_fit *f = &r->yield;
    snprintf(labels, sizeof labels, "set xlabel 'p (Pa)'\nset ylabel '%s (Pa)'\nset key top left\n"
             "set title 'yield line %s = tau0 + zeta p (%zu cells)'\n", tau, tau, f->npts);
    curve[0] = '\0';
    if (f->status == MIMAS_FIT_OK)
        snprintf(curve, sizeof curve, "%.17g + %.17g*x with lines lw 2 lc rgb 'black' "
                 "title 'tau0 = %.4g Pa, zeta = %.4g'", f->p[0], f->p[1], f->p[0], f->p[1]);
    panel(script[0], sizeof script[0], labels, drawable(c->p, c->tau, c->n, 0, 0), "1:2", curve);
    /* mu against I with the mu(I) law */
    f = &r->mu_I;
    snprintf(labels, sizeof labels, "set logscale x\nset format x '%%g'\nset xlabel 'I'\n"
             "set ylabel 'mu = %s/p'\nset key top left\nset title 'mu(I) law'\n", tau);
    curve[0] = '\0';
    if (f->status == MIMAS_FIT_OK)
        snprintf(curve, sizeof curve, "%.17g + (%.17g - %.17g)/(1 + %.17g/x) with lines lw 2 "
                 "lc rgb 'black' title 'mu_s = %.4g, mu_2 = %.4g, I0 = %.4g'", f->p[0], f->p[1],
                 f->p[0], f->p[2], f->p[0], f->p[1], f->p[2]);
    panel(script[1], sizeof script[1], labels, drawable(c->I, c->mu, c->n, 1, 0), "4:3", curve);
    /* eta against shear rate and I, log-log, with the power laws */
    int n = snprintf(script[2], sizeof script[2], "set multiplot layout 1,2\nset logscale xy\n"
                     "set format x '%%g'\nset format y '%%g'\nset key top right\n");
    for (int k = 0; k < 2; k++) {
        f = k ? &r->eta_I : &r->eta_rate;
        snprintf(labels, sizeof labels, "set xlabel '%s%s'\nset ylabel 'eta (Pa s)'\n"
                 "set title 'eta = k %s^n'\n", k ? "I" : rate, k ? "" : " (1/s)", k ? "I" : rate);
        curve[0] = '\0';
        if (f->status == MIMAS_FIT_OK)
            snprintf(curve, sizeof curve, "%.17g*x**%.17g with lines lw 2 lc rgb 'black' "
                     "title 'k = %.4g, n = %.4g'", f->p[0], f->p[1], f->p[0], f->p[1]);
        const double *x = k ? c->I : c->shear_rate;
        n += panel(script[2] + n, sizeof script[2] - (size_t)n, labels,
                   drawable(x, c->eta, c->n, 1, 1), k ? "4:5" : "6:5", curve);
    }
    snprintf(script[2] + n, sizeof script[2] - (size_t)n, "unset multiplot\n");
    /* all three rendered, then all renamed into place */
    mimas_plot *p[3] = {NULL, NULL, NULL};
    int rc = MIMAS_OK;
    for (int k = 0; k < 3 && !rc; k++) {
        rc = mimas_plot_open(&p[k], names[k], err);
        if (!rc)
            rc = render(r, p[k], k == 2 ? 1400 : 800, script[k], err);
    }
    for (int k = 0; k < 3; k++) {
        if (!rc && p[k])
            rc = mimas_plot_commit(p[k], err);
        else
            mimas_plot_abort(p[k]);
    }
    return rc;
}
