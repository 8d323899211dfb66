/* Plug detection in one frame's axial profile (mimas plugs; Strauß 2005,
 * Sec. 4.3; docs/theory.md §7.3, docs/plugs.md): a plug is a maximal run of
 * slices whose porosity is below a threshold, at least a minimum length
 * long.  Per-frame, like the profile it reads. */
#ifndef MIMAS_PLUGS_H
#define MIMAS_PLUGS_H

#include <stddef.h>

#include "axial_profile.h"
#include "error.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct mimas_plug {
    size_t frame;          /* index of the frame among those used */
    double time;
    long track;            /* set by the tracking; 0 before */
    double centre;         /* centre of mass of the particle volume in the run's slices, m */
    double front, back;    /* the run's ends: front towards the outlet (larger s), m */
    double length;         /* front - back, m */
    double count;          /* particles (volume fractions summed) */
    double mass;           /* kg */
    double velocity;       /* mass-weighted mean axial particle velocity, m/s */
    double min_porosity;
    double wall_pressure;  /* normal force on the wall in the run / (2 pi R length), Pa */
    int cut;               /* the run touches an end of the slices' range */
    size_t k0, k1;         /* the run: slices k0..k1 */
} mimas_plug;

typedef struct mimas_plug_options {
    double threshold;      /* porosity below which a slice is dense (default 0.6) */
    double min_length;     /* m */
} mimas_plug_options;

/* A growing list of one frame's plugs. */
typedef struct mimas_plug_list {
    mimas_plug *p;
    size_t n, cap;
} mimas_plug_list;
void mimas_plug_list_free(mimas_plug_list *l);

/* Replaces l's contents by the plugs of the profile (frame index and time
 * given), ordered by increasing s. */
int mimas_plugs_detect(const mimas_axial *ax, const mimas_plug_options *o, size_t frame,
                       double time, mimas_plug_list *l, mimas_error *err);

/* Bins of the distance from a plug centre in units of a length d (the
 * plug-centred profiles): bin b covers [lo + b w, lo + (b + 1) w]. */
typedef struct mimas_profile_bins {
    double d, lo, w;
    size_t n;
} mimas_profile_bins;
/* The plug-centred profile of one plug: for each bin and axial field the
 * mean over the slices whose centre falls into the bin, NaN where none
 * (values: n x MIMAS_AX_NFIELDS); count is a workspace of as many
 * elements. */
void mimas_plug_profile(const mimas_axial *ax, const mimas_plug *plug,
                        const mimas_profile_bins *bins, double *values, size_t *count);

#ifdef __cplusplus
}
#endif
#endif
