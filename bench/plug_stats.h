/* Measurements on plug-conveying runs for the validation against Strauß
 * (2005): axial porosity profiles by exact slice overlaps, plugs as runs of
 * slices below a porosity threshold, plug velocities by matching plugs of
 * consecutive frames, and the dispersion coefficient of a cohort.  Used by
 * bench/plug_measure (docs/plugconveying.md); tested in
 * tests/unit/test_plug_stats.c. */
#ifndef MIMAS_BENCH_PLUG_STATS_H
#define MIMAS_BENCH_PLUG_STATS_H

#include <stddef.h>

#include "frame.h"

/* Porosity of n slices of width w along z from 0, in a tube of radius R:
 * 1 - (volume of the particles' spheres inside the slice)/(pi R^2 w), with
 * the exact sphere-slab overlaps; particles of type skip_type (> 0) are left
 * out. */
void plug_porosity(const mimas_frame *f, double R, size_t n, double w, int skip_type,
                   double *porosity);

typedef struct plug {
    double lo, hi;      /* ends of the run of slices, m */
    double centre;      /* centre of mass of the solid in the run, m */
} plug;

/* The maximal runs of at least min_slices slices with porosity below
 * threshold (at most max of them); returns their number. */
size_t plug_find(const double *porosity, size_t n, double w, double threshold, size_t min_slices,
                 plug *plugs, size_t max);

/* Velocities of the plugs of frame b matched one-to-one to those of frame a
 * (dt later): greedily by the smallest distance between centres, a match
 * only within `gate`.  Writes the velocity of each matched plug of b into v
 * (NaN when unmatched) and returns the number matched. */
size_t plug_match(const plug *a, size_t na, const plug *b, size_t nb, double dt, double gate,
                  double *v);

/* Least-squares slope of y over x (n points); the diffusion coefficient of a
 * cohort is half the slope of its variance over time. */
double plug_slope(const double *x, const double *y, size_t n);

#endif
