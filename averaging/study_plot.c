/* The picture of a study (--plot with --study or --study-values): per panel,
 * the runs' values against the study variable with their error bars, and the
 * least-squares lines of their trends. */
#include <config.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "plot.h"
#include "study.h"

/* One data file per panel, a gnuplot index block (two empty lines apart)
 * per series: x y yerr.  Returns the number of drawable points. */
static size_t write_panel(FILE *fp, const double *x, size_t nruns, const mimas_study_panel *pn)
{
    size_t points = 0;
    for (size_t s = 0; s < pn->nseries; s++) {
        const mimas_study_series *se = &pn->series[s];
        size_t here = 0;
        for (size_t r = 0; r < nruns; r++) {
            if (!isfinite(x[r]) || !isfinite(se->y[r]))
                continue;
            double e = se->yerr && isfinite(se->yerr[r]) ? se->yerr[r] : 0.0;
            fprintf(fp, "%.10g\t%.10g\t%.10g\n", x[r], se->y[r], e);
            here++;
        }
        if (!here) /* an empty block would shift the indices */
            fputs("nan\tnan\t0\n", fp);
        fputs("\n\n", fp);
        points += here;
    }
    return points;
}

/* The plot command of one panel into s. */
static int panel_script(char *s, size_t len, int k, const mimas_study_panel *pn, size_t points)
{
    char title[256], ylabel[256];
    mimas_plot_quote(pn->title, title, sizeof title);
    mimas_plot_quote(pn->ylabel, ylabel, sizeof ylabel);
    int n = snprintf(s, len, "set title %s\nset ylabel %s\n", title, ylabel);
    if (!points)
        return n + snprintf(s + n, len - (size_t)n,
                            "set label 'no values' at graph 0.4, graph 0.5\n"
                            "plot [0:1][0:1] NaN notitle\nunset label\n");
    n += snprintf(s + n, len - (size_t)n, "plot ");
    for (size_t q = 0; q < pn->nseries && (size_t)n < len; q++) {
        const mimas_study_series *se = &pn->series[q];
        char label[256];
        mimas_plot_quote(se->label, label, sizeof label);
        n += snprintf(s + n, len - (size_t)n,
                      "%sdatadir.'/panel%d' index %zu using 1:2:3 with yerrorbars pt 7 lc %zu "
                      "title %s", q ? ", " : "", k, q, q + 1, label);
        const mimas_fit *f = &se->trend->line;
        if (f->status == MIMAS_FIT_OK)
            n += snprintf(s + n, len - (size_t)n, ", %.17g + %.17g*x with lines lc %zu notitle",
                          f->p[0], f->p[1], q + 1);
    }
    return n + snprintf(s + n, len - (size_t)n, "\n");
}

int mimas_study_plot(const char *png, const char *xlabel, const double *x, size_t nruns,
                     const mimas_study_panel *panels, size_t npanels, int columns,
                     mimas_error *err)
{
    mimas_plot *p;
    int rc = mimas_plot_open(&p, png, err);
    if (rc)
        return rc;
    int rows = (int)((npanels + (size_t)columns - 1) / (size_t)columns);
    size_t len = 4096 + npanels * 1024;
    for (size_t k = 0; k < npanels; k++)
        len += panels[k].nseries * 512;
    char *script = malloc(len), q[256];
    if (!script) {
        mimas_plot_abort(p);
        return mimas_error_set(err, MIMAS_EIO, "out of memory");
    }
    mimas_plot_quote(xlabel, q, sizeof q);
    int n = snprintf(script, len, "set multiplot layout %d,%d\nset xlabel %s\nset key top left "
                     "font ',8'\nset format y '%%g'\n"
                     "set offsets graph 0.05, graph 0.05, graph 0.1, graph 0.1\n",
                     rows, columns, q);
    for (size_t k = 0; !rc && k < npanels; k++) {
        char name[32];
        snprintf(name, sizeof name, "panel%zu", k);
        FILE *fp = mimas_plot_data(p, name, err);
        if (!fp) {
            rc = err->code;
            break;
        }
        size_t points = write_panel(fp, x, nruns, &panels[k]);
        n += panel_script(script + n, len - (size_t)n, (int)k, &panels[k], points);
    }
    if (!rc) {
        snprintf(script + n, len - (size_t)n, "unset multiplot\n");
        rc = mimas_plot_render(p, 600 * columns, 450 * rows, script, err);
    }
    free(script);
    if (rc) {
        mimas_plot_abort(p);
        return rc;
    }
    return mimas_plot_commit(p, err);
}
