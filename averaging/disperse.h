/* mimas disperse (docs/disperse.md): how particles spread along their
 * trajectories.  Per cohort (averaging/cohort.h) the mean trajectory <x>(t)
 * and the variance sigma^2(t) = <|x - <x>|^2> along an axis and across it,
 * with D from the least-squares line sigma^2 = 2 D t + c (Strauß 2005,
 * Sec. 5.7 and 6.7; docs/theory.md §7.5); and the mean-square displacement
 * of all selected particles by lag, per component, by FFT (averaging/msd.h,
 * Calandrini et al. 2011), with D from MSD = 2 d D t + c (d the component's
 * dimensions), and optionally the velocity autocorrelation with the
 * Green-Kubo D.  Errors of D: the jackknife over groups of particles.
 *
 * Frames are added one at a time (equally spaced, averaging/trajectories.h);
 * the trajectories go to a store bounded by the memory given
 * (averaging/traj_store.h); finishing runs the analysis over blocks of
 * particles. */
#ifndef MIMAS_DISPERSE_H
#define MIMAS_DISPERSE_H

#include <stddef.h>
#include <stdint.h>

#include "axis.h"
#include "error.h"
#include "fit.h"
#include "frame.h"
#include "trajectories.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum mimas_disperse_component {
    MIMAS_DC_X,
    MIMAS_DC_Y,
    MIMAS_DC_Z,
    MIMAS_DC_AXIAL,
    MIMAS_DC_TRANSVERSE,
    MIMAS_DC_TOTAL,
    MIMAS_DC_COUNT
} mimas_disperse_component;

/* "x", "y", "z", "axial", "transverse", "total" */
const char *mimas_disperse_component_name(int c);
/* The dimensions a component spans: 1, 2 (transverse) or 3 (total). */
int mimas_disperse_component_dim(int c);

/* groups of particles (and of each cohort's members) for the jackknife */
#define MIMAS_DISPERSE_GROUPS 16

typedef struct mimas_disperse_options {
    const char *axis;            /* "X0,Y0,Z0,DX,DY,DZ"; NULL: the input's tube axis, else z */
    const char *const *cohorts;  /* specifications (averaging/cohort.h); none: all */
    size_t ncohorts;
    int remove_drift;            /* MSD and VACF of x - drift(t), v - mean v(t) */
    int vacf;                    /* also the velocity autocorrelation */
    int has_fit_from;            /* cohort fits where sigma_axial > fit_from */
    double fit_from;
    int has_fit_lags;            /* fits over lo <= t <= hi: the lag time (MSD, VACF) and */
    double fit_lo, fit_hi;       /* the time since the cohort was complete (cohorts) */
    int has_max_lag;             /* lags up to max_lag (s); else all */
    double max_lag;
    const int32_t *types;        /* particle selection */
    size_t ntypes;
    int exclude;
    size_t memory;               /* bytes the process may hold at its peak */
    size_t memory_held;          /* of those, held already (code, libraries) */
    /* the process's resident bytes now (may be NULL): the analysis budgets
     * from what is held when it starts */
    size_t (*resident)(void);
    const char *scratch_dir;     /* where a scratch file goes */
    /* called now and then during the analysis (may be NULL) */
    void (*progress)(void *ctx, size_t particles_done, size_t particles);
    void *progress_ctx;
} mimas_disperse_options;

typedef struct mimas_disperse_cohort_row {
    double time;
    size_t n;                    /* members present */
    double mean[3];              /* <x>, m */
    double sigma2_axial;         /* <(s - <s>)^2>, m^2 */
    double sigma2_transverse;    /* <|x_perp - <x_perp>|^2>, m^2 */
} mimas_disperse_cohort_row;

typedef struct mimas_disperse_cohort {
    const char *spec;
    size_t size;                 /* members */
    double complete_time;        /* first frame with every member present (NaN: none) */
    size_t nrows;                /* frames with members present */
    mimas_disperse_cohort_row *rows;
} mimas_disperse_cohort;

typedef struct mimas_disperse_diffusion {
    char what[272];              /* "msd", "vacf" or "cohort:SPEC" */
    int component;               /* mimas_disperse_component */
    double D, D_err;             /* m^2/s; D_err: jackknife over particle groups */
    double t0, t1;               /* the abscissa range used (lag time, or time) */
    double D_err_fit;            /* the least-squares error (NaN for vacf) */
    double intercept;            /* c of the line (m^2; NaN for vacf) */
    size_t npts;
    mimas_fit_status status;
} mimas_disperse_diffusion;

typedef struct mimas_disperse_result {
    size_t frames, particles;
    double t_first, dt;          /* first time and frame interval, s */
    mimas_axis axis;
    int axis_from_tube;          /* the axis is the input's tube axis */
    size_t lags;                 /* 0 .. lags-1 */
    double *msd;                 /* [lags][MIMAS_DC_COUNT], m^2 */
    double *vacf;                /* [lags][MIMAS_DC_COUNT], m^2/s^2, or NULL */
    double *count;               /* [lags]: pairs of frames */
    double fit_lo, fit_hi;       /* lag-time window of the MSD and VACF fits */
    size_t ncohorts;
    mimas_disperse_cohort *cohorts;
    size_t ndiffusion;
    mimas_disperse_diffusion *diffusion;
    mimas_traj_jumps jumps;      /* ambiguous moves met while unwrapping */
    int scratch;                 /* the trajectories went to a scratch file */
    size_t groups;               /* particle groups of the jackknife */
} mimas_disperse_result;

/* The columns of the tables (TSV headers, HDF5 datasets, docs/disperse.md):
 * name, unit, definition. */
typedef struct mimas_disperse_column {
    const char *name, *unit, *meaning;
} mimas_disperse_column;

typedef enum mimas_disperse_table {
    MIMAS_DISPERSE_LAGS,       /* lag time msd_x ... msd count */
    MIMAS_DISPERSE_VACF,       /* vacf_x ... vacf (after the lag columns with --vacf) */
    MIMAS_DISPERSE_COHORTS,    /* cohort time n mean_x ... sigma2_transverse */
    MIMAS_DISPERSE_DIFFUSION   /* what component D D_err t0 t1 D_err_fit npts status */
} mimas_disperse_table;

const mimas_disperse_column *mimas_disperse_columns(mimas_disperse_table t, size_t *n);

typedef struct mimas_disperse mimas_disperse;

/* Checks the options (MIMAS_EUSAGE naming the option) and reads ids files. */
int mimas_disperse_create(mimas_disperse **d, const mimas_disperse_options *o,
                          mimas_error *err);
/* The next frame. */
int mimas_disperse_add(mimas_disperse *d, const mimas_frame *f, mimas_error *err);
/* Frames added so far. */
size_t mimas_disperse_frames(const mimas_disperse *d);
/* After the last frame: the analysis. */
int mimas_disperse_finish(mimas_disperse *d, mimas_error *err);
const mimas_disperse_result *mimas_disperse_result_of(const mimas_disperse *d);
void mimas_disperse_free(mimas_disperse *d);

/* sigma^2(t) and MSD(lag) with the fitted lines (gnuplot) into png. */
int mimas_disperse_plot(const mimas_disperse_result *r, const char *png, mimas_error *err);
/* Every table with units and definitions into an HDF5 file (written under a
 * temporary name and renamed); provenance may be NULL. */
int mimas_disperse_write_h5(const mimas_disperse_result *r, const char *path,
                            const char *provenance, mimas_error *err);

#ifdef __cplusplus
}
#endif
#endif
