/* The columns of the tables of mimas disperse, described once for the TSV
 * headers, the HDF5 attributes and docs/disperse.md. */
#include <config.h>

#include "disperse.h"

static const mimas_disperse_column lags[] = {
    {"lag", "1", "lag k in frames"},
    {"time", "s", "lag time k dt (dt the frame interval)"},
    {"msd_x", "m2", "mean-square displacement <(x(t+k dt) - x(t))^2> over particles and time "
                    "origins"},
    {"msd_y", "m2", "the same of y"},
    {"msd_z", "m2", "the same of z"},
    {"msd_axial", "m2", "the same of the component along the axis"},
    {"msd_transverse", "m2", "the same of the two components across the axis (summed)"},
    {"msd", "m2", "<|x(t+k dt) - x(t)|^2>, the sum of msd_x, msd_y, msd_z"},
    {"count", "1", "pairs of frames k apart with the particle present in both"},
};

static const mimas_disperse_column vacf[] = {
    {"vacf_x", "m2 s-2", "velocity autocorrelation <v_x(t) v_x(t+k dt)>"},
    {"vacf_y", "m2 s-2", "the same of v_y"},
    {"vacf_z", "m2 s-2", "the same of v_z"},
    {"vacf_axial", "m2 s-2", "the same of the velocity component along the axis"},
    {"vacf_transverse", "m2 s-2", "the same of the two components across the axis (summed)"},
    {"vacf", "m2 s-2", "<v(t) . v(t+k dt)>, the sum of vacf_x, vacf_y, vacf_z"},
};

static const mimas_disperse_column cohorts[] = {
    {"cohort", "-", "the cohort as given to --cohort"},
    {"time", "s", "frame time"},
    {"n", "1", "members present"},
    {"mean_x", "m", "mean trajectory <x>, x component (unwrapped positions)"},
    {"mean_y", "m", "the same, y"},
    {"mean_z", "m", "the same, z"},
    {"sigma2_axial", "m2", "<(s - <s>)^2>, s the position along the axis"},
    {"sigma2_transverse", "m2", "<|x_perp - <x_perp>|^2>, x_perp the position across the axis"},
};

static const mimas_disperse_column diffusion[] = {
    {"what", "-", "msd, vacf (Green-Kubo) or cohort:SPEC"},
    {"component", "-", "x, y, z, axial, transverse (per component: MSD = 4 D t) or total "
                       "(MSD = 6 D t)"},
    {"D", "m2 s-1", "diffusion coefficient of one component: slope / (2 d) of the line "
                    "through MSD or sigma^2 against time, d the dimensions"},
    {"D_err", "m2 s-1", "its standard error: the jackknife over 16 groups of particles"},
    {"t0", "s", "first abscissa of the fit (lag time; time for cohorts)"},
    {"t1", "s", "last abscissa of the fit"},
    {"D_err_fit", "m2 s-1", "the least-squares error of the slope / (2 d) (points strongly "
                            "correlated: too small)"},
    {"npts", "1", "points of the fit"},
    {"status", "-", "ok, few_points, no_convergence or undetermined"},
};

const mimas_disperse_column *mimas_disperse_columns(mimas_disperse_table t, size_t *n)
{
    switch (t) {
    case MIMAS_DISPERSE_LAGS: *n = sizeof lags / sizeof lags[0]; return lags;
    case MIMAS_DISPERSE_VACF: *n = sizeof vacf / sizeof vacf[0]; return vacf;
    case MIMAS_DISPERSE_COHORTS: *n = sizeof cohorts / sizeof cohorts[0]; return cohorts;
    case MIMAS_DISPERSE_DIFFUSION: *n = sizeof diffusion / sizeof diffusion[0]; return diffusion;
    }
    *n = 0;
    return NULL;
}
