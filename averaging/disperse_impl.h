/* Internals of mimas disperse shared by disperse.c (the sweep over the
 * trajectories), disperse_stats.c (cohort statistics) and disperse_fit.c
 * (the tables and the fits of D).  Not installed. */
#ifndef MIMAS_DISPERSE_IMPL_H
#define MIMAS_DISPERSE_IMPL_H

#include <stddef.h>

#include "cohort.h"
#include "disperse.h"
#include "msd.h"

/* The components the correlations run on: x, y, z, and, unless the axis
 * is a coordinate axis (then axial and transverse are among x, y, z), the
 * three components along e_x, e_y, e_z of the axis frame. */
typedef struct disperse_comps {
    size_t n;          /* 3 or 6 */
    int axial;         /* index of the axial component */
    int trans[2];      /* indices of the transverse ones */
} disperse_comps;

void disperse_comps_choose(disperse_comps *c, const mimas_axis *a);
/* The components of the vector v into out[0 .. c->n - 1]. */
void disperse_comps_project(const disperse_comps *c, const mimas_axis *a, const double v[3],
                            double *out);
/* The table's six components from the n of the correlations. */
void disperse_comps_expand(const disperse_comps *c, const double *in, double out[6]);

/* The members' statistics of one cohort per frame and member group g
 * (member j in group j mod MIMAS_DISPERSE_GROUPS): count, mean and sum of
 * squared deviations of the axis-frame components (Welford), so that the
 * groups merge exactly (Chan et al.) and the jackknife leaves one out. */
typedef struct cohort_stats {
    size_t frames;
    size_t members;    /* added so far */
    double *acc;       /* [frames][groups][7]: n, mean[3], m2[3] */
} cohort_stats;

size_t cohort_stats_bytes(size_t frames);
int cohort_stats_init(cohort_stats *s, size_t frames, mimas_error *err);
/* Member "member" (0, 1, ...) at frame t, axis-frame position l. */
void cohort_stats_add(cohort_stats *s, size_t member, size_t t, const double l[3]);
/* Merged over every group but skip (SIZE_MAX: all). */
void cohort_stats_merged(const cohort_stats *s, size_t t, size_t skip, double *n,
                         double mean[3], double m2[3]);
void cohort_stats_free(cohort_stats *s);

/* The lags of the MSD fit window (klo > khi: none). */
void disperse_window(const mimas_disperse_result *r, size_t *klo, size_t *khi);
/* Appends a row to r's diffusion table. */
int disperse_push_diffusion(mimas_disperse_result *r, const mimas_disperse_diffusion *row,
                            mimas_error *err);
/* The MSD (vacf 0) or VACF table of r from the sums of every particle,
 * and the D rows of the six components (fits over r->fit_lo .. r->fit_hi),
 * their jackknife from the per-group sums (over the window's lags; for the
 * VACF from lag 0). */
int disperse_lag_tables(mimas_disperse_result *r, const mimas_msd_sums *all,
                        const mimas_msd_sums *groups, size_t ngroups, const disperse_comps *cm,
                        int vacf, mimas_error *err);
/* The rows of cohort k of r from its statistics, and its two D rows. */
int disperse_cohort_table(mimas_disperse_result *r, size_t k, const mimas_cohort *c,
                          const cohort_stats *st, const double *times,
                          const mimas_disperse_options *o, mimas_error *err);

#endif
