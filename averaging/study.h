/* Studies across runs (docs/study.md): the same analysis of several runs that
 * differ in one parameter, the study variable (the liquid content D of the
 * wet ring shear cells of Uhlig 2012, Sec. 4.2, or a friction, a rotation
 * rate ...).  Each result a run has (a yield-line parameter, a windowed
 * viscosity, the band of the surface layer) becomes a trend against the
 * study variable x: the least-squares line y = A1 x + A2 and the percentage
 * changes between the lowest study values and to the highest one. */
#ifndef MIMAS_STUDY_H
#define MIMAS_STUDY_H

#include <stddef.h>

#include "error.h"
#include "fit.h"
#include "parameters.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The study variable of a run: the parameter NAME ("SECTION.KEY", or a KEY
 * one section alone has) of the run's parameters ps, as a number.
 * MIMAS_EDATA naming source when the run has no parameters, no such
 * parameter, an ambiguous key, a value that is not a number, or a value its
 * inputs disagree on. */
int mimas_study_value(const mimas_parameters *ps, const char *source, const char *name,
                      double *value, mimas_error *err);
/* "V1,V2,..." into v (at most max); MIMAS_EUSAGE on anything else. */
int mimas_study_parse_values(const char *spec, double *v, size_t max, size_t *n,
                             mimas_error *err);
/* The parameters, other than the study variable's, in which the n runs
 * differ, as "SECTION.KEY, ..." into buf ("" if none).  name is the study
 * variable (or NULL: --study-values, then every difference is listed). */
void mimas_study_differences(const mimas_parameters *const *ps, size_t n, const char *name,
                             char *buf, size_t len);

typedef struct mimas_trend {
    mimas_fit line;           /* y = p[0] + p[1] x: p[1] = A1 (slope), p[0] = A2 */
    /* percentage changes between the runs at the distinct study values
     * x_1 < x_2 < ... < x_m (runs of equal x averaged):
     * 100 (y_2 - y_1)/y_1 and 100 (y_m - y_2)/y_2 (Uhlig's dry to slightly
     * wet and slightly wet to the wettest), with errors propagated from the
     * runs' errors; NaN when there are too few values or errors */
    double change_first, change_first_err;
    double change_rest, change_rest_err;
} mimas_trend;

/* The trend of y over x for n runs: y NaN where a run has no value; yerr
 * the runs' errors (NULL or NaN: none).  The line is an unweighted least
 * squares over the runs with lo <= x <= hi (errors scaled by the scatter,
 * status few_points below 3 runs); the changes use every run with a value. */
int mimas_study_trend(const double *x, const double *y, const double *yerr, size_t n,
                      double lo, double hi, mimas_trend *t, mimas_error *err);

/* ---- pictures: the runs' values against the study variable with error
 * bars, and the lines ---- */

typedef struct mimas_study_series {
    char label[96];           /* legend */
    const double *y, *yerr;   /* per run (NaN: none) */
    const mimas_trend *trend; /* its line (drawn when ok) */
} mimas_study_series;

typedef struct mimas_study_panel {
    const char *title, *ylabel;
    const mimas_study_series *series;
    size_t nseries;
} mimas_study_panel;

/* Draws the panels, columns to a row, into png by gnuplot (x: the runs'
 * study values, labelled xlabel). */
int mimas_study_plot(const char *png, const char *xlabel, const double *x, size_t nruns,
                     const mimas_study_panel *panels, size_t npanels, int columns,
                     mimas_error *err);

#ifdef __cplusplus
}
#endif
#endif
