/* The picture of mimas disperse --plot: sigma^2_axial(t) of every cohort
 * with its fitted line (left), and the MSD by lag time on log-log axes,
 * total, axial and transverse, with the fitted lines (right). */
#include <config.h>

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "disperse.h"
#include "plot.h"

#define CURVE_POINTS 40
#define SCRIPT_BYTES (256u * 1024u)

/* The gnuplot script being written. */
typedef struct script {
    char *s;
    size_t used;
    int full;
} script;

static void say(script *sc, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static void say(script *sc, const char *fmt, ...)
{
    if (sc->full)
        return;
    va_list ap;
    va_start(ap, fmt);
    int w = vsnprintf(sc->s + sc->used, SCRIPT_BYTES - sc->used, fmt, ap);
    va_end(ap);
    if (w < 0 || (size_t)w >= SCRIPT_BYTES - sc->used)
        sc->full = 1;
    else
        sc->used += (size_t)w;
}

/* The row of the diffusion table for what and component, or NULL. */
static const mimas_disperse_diffusion *find(const mimas_disperse_result *r, const char *what,
                                            int component)
{
    for (size_t i = 0; i < r->ndiffusion; i++)
        if (!strcmp(r->diffusion[i].what, what) && r->diffusion[i].component == component)
            return &r->diffusion[i];
    return NULL;
}

/* The fitted line 2 d D t + c over the fit's range as one block of points
 * (on a log axis from t0 > 0); 1 if written. */
static int curve(FILE *fp, const mimas_disperse_diffusion *d, int logx)
{
    if (!d || d->status != MIMAS_FIT_OK || !(d->t1 > d->t0))
        return 0;
    double dim = mimas_disperse_component_dim(d->component);
    double a = d->t0, b = d->t1;
    if (logx && !(a > 0))
        a = b / 1e3;
    for (int i = 0; i < CURVE_POINTS; i++) {
        double s = (double)i / (CURVE_POINTS - 1);
        double t = logx ? a * pow(b / a, s) : a + (b - a) * s;
        fprintf(fp, "%.10g\t%.10g\n", t, 2 * dim * d->D * t + d->intercept);
    }
    fputs("\n\n", fp);
    return 1;
}

/* The left panel. */
static int cohort_panel(const mimas_disperse_result *r, mimas_plot *p, script *sc,
                        mimas_error *err)
{
    FILE *data = mimas_plot_data(p, "cohorts", err);
    FILE *fits = data ? mimas_plot_data(p, "cohort_fits", err) : NULL;
    if (!fits)
        return err->code;
    int block = 0, fblock = 0;
    size_t start = sc->used;
    say(sc, "set title 'sigma^2 along the axis per cohort'\nset xlabel 'time (s)'\n"
            "set ylabel 'sigma^2 axial (m^2)'\nset key top left\nplot ");
    for (size_t k = 0; k < r->ncohorts; k++) {
        const mimas_disperse_cohort *h = &r->cohorts[k];
        if (!h->nrows)
            continue;
        for (size_t i = 0; i < h->nrows; i++)
            fprintf(data, "%.10g\t%.10g\n", h->rows[i].time, h->rows[i].sigma2_axial);
        fputs("\n\n", data);
        char title[600], q[1300], what[300];
        snprintf(title, sizeof title, "%s (%zu)", h->spec, h->size);
        mimas_plot_quote(title, q, sizeof q);
        say(sc, "%sdatadir.'/cohorts' index %d using 1:2 with lines lw 2 lc %zu title %s",
            block ? ", " : "", block, k + 1, q);
        block++;
        snprintf(what, sizeof what, "cohort:%s", h->spec);
        const mimas_disperse_diffusion *d = find(r, what, MIMAS_DC_AXIAL);
        if (curve(fits, d, 0)) {
            snprintf(title, sizeof title, "D = %.3g m^2/s", d->D);
            mimas_plot_quote(title, q, sizeof q);
            say(sc, ", datadir.'/cohort_fits' index %d using 1:2 with lines dt 2 lw 2 "
                    "lc 'black' title %s", fblock++, q);
        }
    }
    if (!block) {
        sc->used = start;
        sc->s[start] = '\0';
        say(sc, "set title 'sigma^2 per cohort'\nset label 'no cohort member' at graph 0.35, "
                "graph 0.5\nplot [0:1][0:1] NaN notitle\nunset label");
        fputs("0\tnan\n", data);
    }
    /* gnuplot refuses an empty data file: keep a harmless point */
    if (!fblock)
        fputs("0\tnan\n", fits);
    say(sc, "\n");
    return MIMAS_OK;
}

static int msd_panel(const mimas_disperse_result *r, mimas_plot *p, script *sc,
                     mimas_error *err)
{
    FILE *data = mimas_plot_data(p, "msd", err);
    FILE *fits = data ? mimas_plot_data(p, "msd_fits", err) : NULL;
    if (!fits)
        return err->code;
    size_t positive = 0;
    for (size_t k = 1; k < r->lags; k++) {
        const double *m = r->msd + k * MIMAS_DC_COUNT;
        fprintf(data, "%.10g\t%.10g\t%.10g\t%.10g\n", (double)k * r->dt, m[MIMAS_DC_TOTAL],
                m[MIMAS_DC_AXIAL], m[MIMAS_DC_TRANSVERSE]);
        positive += m[MIMAS_DC_TOTAL] > 0;
    }
    if (!positive) {
        fputs("1\tnan\tnan\tnan\n", data);
        fputs("1\tnan\n", fits);
        say(sc, "set title 'MSD'\nset label 'no displacement' at graph 0.35, graph 0.5\n"
                "plot [1:2][1:2] NaN notitle\nunset label\n");
        return MIMAS_OK;
    }
    say(sc, "set title 'mean-square displacement'\nset logscale xy\nset format x '%%g'\n"
            "set format y '%%g'\nset xlabel 'lag time (s)'\nset ylabel 'MSD (m^2)'\n"
            "set key top left\nplot datadir.'/msd' using 1:2 with points pt 7 ps 0.5 lc 1 "
            "title 'total', '' using 1:3 with points pt 7 ps 0.5 lc 2 title 'axial', '' using "
            "1:4 with points pt 7 ps 0.5 lc 3 title 'transverse'");
    static const int comps[3] = {MIMAS_DC_TOTAL, MIMAS_DC_AXIAL, MIMAS_DC_TRANSVERSE};
    int block = 0;
    for (int q = 0; q < 3; q++) {
        const mimas_disperse_diffusion *d = find(r, "msd", comps[q]);
        if (!curve(fits, d, 1))
            continue;
        char title[200], qt[420];
        snprintf(title, sizeof title, "D %s = %.3g m^2/s", mimas_disperse_component_name(comps[q]),
                 d->D);
        mimas_plot_quote(title, qt, sizeof qt);
        say(sc, ", datadir.'/msd_fits' index %d using 1:2 with lines lw 2 dt 2 lc %d title %s",
            block++, q + 1, qt);
    }
    if (!block)
        fputs("1\tnan\n", fits);
    say(sc, "\n");
    return MIMAS_OK;
}

int mimas_disperse_plot(const mimas_disperse_result *r, const char *png, mimas_error *err)
{
    script sc = {malloc(SCRIPT_BYTES), 0, 0};
    if (!sc.s)
        return mimas_error_set(err, MIMAS_EIO, "out of memory");
    sc.s[0] = '\0';
    mimas_plot *p;
    int rc = mimas_plot_open(&p, png, err);
    if (rc) {
        free(sc.s);
        return rc;
    }
    say(&sc, "set multiplot layout 1,2\n");
    rc = cohort_panel(r, p, &sc, err);
    if (!rc)
        rc = msd_panel(r, p, &sc, err);
    say(&sc, "unset multiplot\n");
    if (!rc && sc.full)
        rc = mimas_error_set(err, MIMAS_EUSAGE, "%s: too many cohorts to plot", png);
    if (!rc)
        rc = mimas_plot_render(p, 1400, 600, sc.s, err);
    free(sc.s);
    if (rc) {
        mimas_plot_abort(p);
        return rc;
    }
    return mimas_plot_commit(p, err);
}
