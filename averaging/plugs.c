/* Plug detection (plugs.h). */
#include <config.h>

#include "plugs.h"

#include "grow.h"

#include <math.h>
#include <stdlib.h>

void mimas_plug_list_free(mimas_plug_list *l)
{
    free(l->p);
    l->p = NULL;
    l->n = l->cap = 0;
}

static int push(mimas_plug_list *l, const mimas_plug *p, mimas_error *err)
{
    int rc = mimas_grow((void **)&l->p, &l->cap, l->n + 1, sizeof *l->p, 16, err);
    if (rc)
        return rc;
    l->p[l->n++] = *p;
    return MIMAS_OK;
}

/* The plug of slices k0..k1. */
static void describe(const mimas_axial *ax, size_t k0, size_t k1, mimas_plug *p)
{
    const mimas_axial_options *o = mimas_axial_opts(ax);
    const mimas_slices *sl = &o->slices;
    double moment = 0, mass = 0, count = 0, ps = 0, wall = 0, minp = INFINITY;
    for (size_t k = k0; k <= k1; k++) {
        moment += mimas_axial_sum(ax, k, MIMAS_AS_MOMENT);
        mass += mimas_axial_sum(ax, k, MIMAS_AS_MASS);
        count += mimas_axial_sum(ax, k, MIMAS_AS_N);
        ps += mimas_axial_sum(ax, k, MIMAS_AS_P);
        wall += mimas_axial_sum(ax, k, MIMAS_AS_WALL_N);
        minp = fmin(minp, mimas_axial_value(ax, k, MIMAS_AX_POROSITY));
    }
    p->k0 = k0;
    p->k1 = k1;
    p->back = sl->s0 + (double)k0 * sl->w;
    p->front = sl->s0 + (double)(k1 + 1) * sl->w;
    p->length = p->front - p->back;
    p->centre = mass > 0 ? moment / mass : 0.5 * (p->front + p->back);
    p->count = count;
    p->mass = mass;
    p->velocity = mass > 0 ? ps / mass : NAN;
    p->min_porosity = minp;
    p->wall_pressure = wall / (2.0 * M_PI * o->geom.radius * p->length);
    p->cut = k0 == 0 || k1 + 1 == sl->n;
}

int mimas_plugs_detect(const mimas_axial *ax, const mimas_plug_options *o, size_t frame,
                       double time, mimas_plug_list *l, mimas_error *err)
{
    const mimas_slices *sl = &mimas_axial_opts(ax)->slices;
    l->n = 0;
    size_t k = 0;
    while (k < sl->n) {
        if (!(mimas_axial_value(ax, k, MIMAS_AX_POROSITY) < o->threshold)) {
            k++;
            continue;
        }
        size_t k0 = k;
        while (k + 1 < sl->n && mimas_axial_value(ax, k + 1, MIMAS_AX_POROSITY) < o->threshold)
            k++;
        size_t k1 = k++;
        /* at least min_length long (up to rounding of the slice width) */
        if ((double)(k1 - k0 + 1) * sl->w < o->min_length * (1.0 - 1e-9))
            continue;
        mimas_plug p = {0};
        p.frame = frame;
        p.time = time;
        describe(ax, k0, k1, &p);
        int rc = push(l, &p, err);
        if (rc)
            return rc;
    }
    return MIMAS_OK;
}

void mimas_plug_profile(const mimas_axial *ax, const mimas_plug *plug,
                        const mimas_profile_bins *bins, double *values, size_t *count)
{
    const mimas_slices *sl = &mimas_axial_opts(ax)->slices;
    size_t nv = bins->n * MIMAS_AX_NFIELDS;
    /* values holds sums first */
    for (size_t q = 0; q < nv; q++) {
        values[q] = 0.0;
        count[q] = 0;
    }
    double lo = plug->centre + bins->lo * bins->d, hi = lo + (double)bins->n * bins->w * bins->d;
    size_t k0, k1;
    if (mimas_slices_range(sl, lo, hi, &k0, &k1))
        for (size_t k = k0; k <= k1; k++) {
            double x = (mimas_slice_centre(sl, k) - plug->centre) / bins->d;
            double b = floor((x - bins->lo) / bins->w);
            if (!(b >= 0) || !(b < (double)bins->n))
                continue;
            const double *row = mimas_axial_row(ax, k);
            for (int f = 0; f < MIMAS_AX_NFIELDS; f++) {
                size_t q = (size_t)b * MIMAS_AX_NFIELDS + (size_t)f;
                if (!isnan(row[f])) {
                    values[q] += row[f];
                    count[q]++;
                }
            }
        }
    for (size_t q = 0; q < nv; q++)
        values[q] = count[q] ? values[q] / (double)count[q] : NAN;
}
