/* The space-time diagram of mimas plugs --spacetime (Strauß 2005, Fig. 5.2):
 * time on x, axial position on y, grey = porosity (dark = dense), the
 * tracked plug centres on top.  The porosity goes frame by frame to a
 * binary file in the plot's scratch folder (not to memory), the centres to
 * a text file; gnuplot draws them at the end. */
#include <config.h>

#include "plugs_plot.h"

#include <math.h>
#include <stdlib.h>

#include "plot.h"

struct mimas_stplot {
    mimas_plot *plot;
    FILE *grey, *centres;
    size_t ns, frames;
    double s0, w, t0, t1;
    float *row;
};

int mimas_stplot_open(mimas_stplot **sp, const char *png, const mimas_slices *sl,
                      mimas_error *err)
{
    mimas_stplot *p = calloc(1, sizeof *p);
    if (!p || !(p->row = malloc(sl->n * sizeof *p->row))) {
        free(p);
        return mimas_error_set(err, MIMAS_EIO, "out of memory");
    }
    p->ns = sl->n;
    p->s0 = sl->s0;
    p->w = sl->w;
    int rc = mimas_plot_open(&p->plot, png, err);
    if (!rc && !(p->grey = mimas_plot_data(p->plot, "porosity", err)))
        rc = err->code;
    if (!rc && !(p->centres = mimas_plot_data(p->plot, "centres", err)))
        rc = err->code;
    if (rc) {
        mimas_stplot_abort(p);
        return rc;
    }
    *sp = p;
    return MIMAS_OK;
}

int mimas_stplot_frame(mimas_stplot *p, const mimas_axial *ax, double time,
                       const mimas_plug_list *plugs, mimas_error *err)
{
    for (size_t k = 0; k < p->ns; k++)
        p->row[k] = (float)mimas_axial_value(ax, k, MIMAS_AX_POROSITY);
    if (fwrite(p->row, sizeof *p->row, p->ns, p->grey) != p->ns)
        return mimas_error_set(err, MIMAS_EIO, "cannot write the space-time data");
    for (size_t j = 0; j < plugs->n; j++)
        fprintf(p->centres, "%.9g\t%.9g\t%ld\n", time, plugs->p[j].centre, plugs->p[j].track);
    if (!p->frames)
        p->t0 = time;
    p->t1 = time;
    p->frames++;
    return MIMAS_OK;
}

int mimas_stplot_finish(mimas_stplot *p, mimas_error *err)
{
    char script[2048];
    /* frames drawn at equal intervals over the span */
    double dt = p->frames > 1 ? (p->t1 - p->t0) / (double)(p->frames - 1) : 1.0;
    if (!(dt > 0))
        dt = 1.0;
    snprintf(script, sizeof script,
             "set xlabel 'time (s)'\nset ylabel 's (m)'\n"
             "set title 'porosity (dark = dense) and plug centres'\n"
             "set palette gray\nset cbrange [0:1]\nset cblabel 'porosity'\n"
             "set xrange [%.9g:%.9g]\nset yrange [%.9g:%.9g]\n"
             "plot datadir.'/porosity' binary array=(%zu,%zu) scan=yx format='%%float32' "
             "dx=%.9g dy=%.9g origin=(%.9g,%.9g) using 1 with image notitle, "
             "datadir.'/centres' using 1:2 with points pt 7 ps 0.4 lc rgb 'red' "
             "title 'plug centres'\n",
             p->t0 - 0.5 * dt, p->t1 + 0.5 * dt, p->s0, p->s0 + (double)p->ns * p->w, p->frames,
             p->ns, dt, p->w, p->t0, p->s0 + 0.5 * p->w);
    if (!p->frames)
        snprintf(script, sizeof script, "set label 'no frames' at graph 0.4, graph 0.5\n"
                                        "plot [0:1][0:1] NaN notitle\n");
    /* a file without plugs still draws (gnuplot skips an empty file with a warning) */
    int rc = mimas_plot_render(p->plot, 1200, 700, script, err);
    p->grey = p->centres = NULL; /* closed by the render */
    if (!rc) {
        rc = mimas_plot_commit(p->plot, err);
        p->plot = NULL;
    }
    mimas_stplot_abort(p);
    return rc;
}

void mimas_stplot_abort(mimas_stplot *p)
{
    if (!p)
        return;
    mimas_plot_abort(p->plot);
    free(p->row);
    free(p);
}
