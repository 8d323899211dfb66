/* The picture of mimas shearband --plot: the profiles with their fits, and
 * the band centre Rc(z) with its error bars and the band edges Rc -+ W. */
#include <config.h>

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "plot.h"
#include "shearband.h"

#define CURVE_SAMPLES 100

/* The data files; returns the numbers of valid points and fitted layers. */
static int write_data(const mimas_band *b, mimas_plot *p, size_t *npoints, size_t *nfits,
                      mimas_error *err)
{
    FILE *pts = mimas_plot_data(p, "points", err);
    FILE *fit = pts ? mimas_plot_data(p, "curves", err) : NULL;
    FILE *rc = fit ? mimas_plot_data(p, "rc", err) : NULL;
    if (!rc)
        return err->code;
    *npoints = *nfits = 0;
    for (size_t k = 0; k < b->nlayers; k++) {
        const mimas_band_layer *l = &b->layers[k];
        for (size_t i = 0; i < l->nr; i++) {
            if (!isfinite(l->y[i]) || (b->weighted && !isfinite(l->sigma[i])))
                continue;
            double s = b->weighted ? l->sigma[i] : 0.0;
            fprintf(pts, "%.9g\t%.9g\t%.9g\t%.9g\n", l->r[i], l->y[i], s, l->z);
            (*npoints)++;
        }
        if (l->fit.status != MIMAS_FIT_OK)
            continue;
        (*nfits)++;
        double r0 = l->r[0], r1 = l->r[l->nr - 1];
        for (int s = 0; s <= CURVE_SAMPLES; s++) {
            double r = r0 + (r1 - r0) * s / CURVE_SAMPLES;
            fprintf(fit, "%.9g\t%.9g\t%.9g\n", r, mimas_band_profile(b->model, l->fit.p, r), l->z);
        }
        fputs("\n", fit); /* one line per layer */
        const double *q = l->fit.p;
        fprintf(rc, "%.9g\t%.9g\t%.9g\t%.9g\n", l->z, q[MIMAS_BAND_RC], l->fit.err[MIMAS_BAND_RC],
                fabs(q[MIMAS_BAND_W]));
    }
    return MIMAS_OK;
}

int mimas_band_plot(const mimas_band *b, const mimas_band_plot_options *o, const char *png,
                    mimas_error *err)
{
    mimas_plot *p;
    int rc = mimas_plot_open(&p, png, err);
    if (rc)
        return rc;
    size_t npoints = 0, nfits = 0;
    rc = write_data(b, p, &npoints, &nfits, err);
    if (rc) {
        mimas_plot_abort(p);
        return rc;
    }
    char vel[64], script[8192];
    mimas_plot_symbol(b->velocity, vel, sizeof vel);
    /* left: the profiles, coloured by height; offsets keep the points off the
     * frame, the margins make room for the tick labels and the colour bar */
    int n = snprintf(script, sizeof script,
                     "set multiplot layout 1,2\n"
                     "set lmargin 10\nset rmargin 14\n"
                     "set palette rgbformulae 33,13,10\nset cblabel 'z (m)'\n"
                     "set xlabel 'r (m)'\nset ylabel 'ω/Ω%s%s%s'\n"
                     "set offsets graph 0.02, graph 0.02, graph 0.04, graph 0.04\nset autoscale fix\n"
                     "set key below horizontal\nset grid\n"
                     "set title 'angular velocity profiles (model %d%s)'\n",
                     strcmp(b->velocity, "omega") ? " (from " : "",
                     strcmp(b->velocity, "omega") ? vel : "",
                     strcmp(b->velocity, "omega") ? "/r)" : "", b->model,
                     b->weighted ? ", weighted by the standard errors" : ", unweighted");
    if (!npoints)
        n += snprintf(script + n, sizeof script - (size_t)n,
                      "set label 'no valid cells' at graph 0.4, graph 0.5\n"
                      "plot [0:1][0:1] NaN notitle\n");
    else
        n += snprintf(script + n, sizeof script - (size_t)n,
                      "plot datadir.'/points' using 1:2:3:4 with yerrorbars pt 7 ps 0.5 "
                      "lc palette z title 'cells'%s\n",
                      nfits ? ", datadir.'/curves' using 1:2:3 with lines lw 1.5 lc palette z "
                              "title 'fits'" : "");
    /* right: the band centre with its errors, the edges, and the prediction */
    char extra[1024] = "";
    if (o && o->rs > 0 && o->h > 0) {
        double pred = mimas_band_fenistein_rc(o->rs, o->h);
        snprintf(extra, sizeof extra,
                 ", '+' using (%.9g):(%.9g) every ::0::0 with points pt 3 ps 2.5 lw 2 lc rgb '#d03020' "
                 "title 'Fenistein \\& van Hecke: R_c(H) = %.4g m', "
                 "'+' using (%.9g):(0) every ::0::0 with points pt 9 ps 2 lc rgb '#d03020' "
                 "title 'split R_s = %.4g m'",
                 pred, o->h, pred, o->rs, o->rs);
    }
    n += snprintf(script + n, sizeof script - (size_t)n,
                  "unset label\nunset colorbox\nset rmargin 4\n"
                  "set title 'band centre R_c and edges R_c ± W'\n"
                  "set xlabel 'r (m)'\nset ylabel 'z (m)'\n"
                  "set offsets graph 0.05, graph 0.05, graph 0.04, graph 0.04\nset autoscale fix\n"
                  "set key below horizontal maxcols 2\n");
    if (!nfits)
        snprintf(script + n, sizeof script - (size_t)n,
                 "set label 'no layer could be fitted' at graph 0.3, graph 0.5\n"
                 "plot [0:1][0:1] NaN notitle%s\nunset multiplot\n", extra);
    else
        snprintf(script + n, sizeof script - (size_t)n,
                 "plot datadir.'/rc' using 2:1:3 with xerrorbars pt 7 lc rgb 'black' "
                 "title 'R_c', '' using ($2-$4):1 with lines dt 2 lc rgb 'black' title "
                 "'R_c ± W', '' using ($2+$4):1 with lines dt 2 lc rgb 'black' notitle%s\n"
                 "unset multiplot\n", extra);
    rc = mimas_plot_render(p, 1500, 760, script, err);
    if (rc) {
        mimas_plot_abort(p);
        return rc;
    }
    return mimas_plot_commit(p, err);
}
