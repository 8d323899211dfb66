/* Plug measurements (plug_stats.h). */
#include <config.h>

#include "plug_stats.h"

#include <gsl/gsl_fit.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "overlap.h"

void plug_porosity(const mimas_frame *f, double R, size_t n, double w, int skip_type,
                   double *porosity)
{
    const mimas_particles *p = &f->particles;
    double *solid = porosity;
    memset(solid, 0, n * sizeof *solid);
    for (size_t k = 0; k < p->n; k++) {
        if (skip_type > 0 && p->type && p->type[k] == skip_type)
            continue;
        double r = p->radius ? p->radius[k] : 0, z = p->pos[k][2];
        long a = (long)floor((z - r) / w), b = (long)floor((z + r) / w);
        for (long s = a < 0 ? 0 : a; s <= b && s < (long)n; s++) {
            double lo[3] = {-INFINITY, -INFINITY, (double)s * w},
                   hi[3] = {INFINITY, INFINITY, (double)(s + 1) * w};
            solid[s] += overlap_sphere_box(p->pos[k], r, lo, hi);
        }
    }
    double v = M_PI * R * R * w;
    for (size_t s = 0; s < n; s++)
        porosity[s] = 1 - solid[s] / v;
}

size_t plug_find(const double *porosity, size_t n, double w, double threshold, size_t min_slices,
                 plug *plugs, size_t max)
{
    size_t count = 0;
    for (size_t s = 0; s < n;) {
        if (!(porosity[s] < threshold)) {
            s++;
            continue;
        }
        size_t e = s;
        double m = 0, mz = 0;
        while (e < n && porosity[e] < threshold) {
            double solid = 1 - porosity[e];
            m += solid;
            mz += solid * ((double)e + 0.5) * w;
            e++;
        }
        if (e - s >= min_slices && count < max)
            plugs[count++] = (plug){(double)s * w, (double)e * w, mz / m};
        s = e;
    }
    return count;
}

size_t plug_match(const plug *a, size_t na, const plug *b, size_t nb, double dt, double gate,
                  double *v)
{
    unsigned char *used_a = calloc(na ? na : 1, 1), *used_b = calloc(nb ? nb : 1, 1);
    for (size_t j = 0; j < nb; j++)
        v[j] = NAN;
    size_t matched = 0;
    for (;;) {
        double best = gate;
        size_t bi = 0, bj = 0;
        int found = 0;
        for (size_t i = 0; i < na; i++)
            for (size_t j = 0; j < nb; j++) {
                double d = fabs(b[j].centre - a[i].centre);
                if (!used_a[i] && !used_b[j] && d <= best) {
                    best = d;
                    bi = i;
                    bj = j;
                    found = 1;
                }
            }
        if (!found)
            break;
        used_a[bi] = used_b[bj] = 1;
        v[bj] = (b[bj].centre - a[bi].centre) / dt;
        matched++;
    }
    free(used_a);
    free(used_b);
    return matched;
}

double plug_slope(const double *x, const double *y, size_t n)
{
    double c0, c1, cov00, cov01, cov11, sumsq;
    gsl_fit_linear(x, 1, y, 1, n, &c0, &c1, &cov00, &cov01, &cov11, &sumsq);
    return c1;
}
