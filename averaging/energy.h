/* Energy statistics of a run (Uhlig 2012, Sec. 4.2 and Table 4.4): the mean
 * over a time window of the total, kinetic, rotational, elastic and bridge
 * energy of the particles, their standard deviation over the frames and the
 * coefficient of variation sd/mean, from the observables mimas simulate
 * writes per frame or from the thermo output of a LIGGGHTS/LAMMPS log
 * (docs/energy.md).  Frames are taken one at a time. */
#ifndef MIMAS_ENERGY_H
#define MIMAS_ENERGY_H

#include <stddef.h>

#include "error.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The quantities; total is kinetic + rotational (Uhlig's E_ges). */
enum { MIMAS_ENERGY_TOTAL, MIMAS_ENERGY_KINETIC, MIMAS_ENERGY_ROTATIONAL, MIMAS_ENERGY_ELASTIC,
       MIMAS_ENERGY_BRIDGE, MIMAS_ENERGY_N };

/* "total", "kinetic", "rotational", "elastic", "bridge" */
const char *mimas_energy_name(int q);

typedef struct mimas_energy_stat {
    int present;      /* the input has this quantity */
    size_t n;         /* frames it was defined in */
    double mean, sd;  /* sd: the sample standard deviation over the frames (NaN below 2) */
    double cv;        /* sd/mean */
} mimas_energy_stat;

typedef struct mimas_energy {
    mimas_energy_stat q[MIMAS_ENERGY_N];
    size_t frames;     /* frames (thermo rows) in the window */
    double from, to;   /* the times of the first and the last of them */
} mimas_energy;

typedef struct mimas_energy_options {
    double from, to;   /* the window: frames with from <= t <= to (-+INFINITY: open) */
    double dt;         /* logs without a Time column: the time step (0: the log's) */
    /* the thermo column of each quantity in a log (NULL: kinetic is KinEng,
     * the others absent; total, if not given, is kinetic + rotational) */
    const char *columns[MIMAS_ENERGY_N];
} mimas_energy_options;

void mimas_energy_options_default(mimas_energy_options *o);
/* The statistics of a native file (its observables kinetic_energy,
 * rotational_energy, elastic_energy, bridge_energy) or of a LAMMPS/LIGGGHTS
 * log, told apart by content.  A file with none of the quantities, an empty
 * window, or a window on a log whose times are unknown is MIMAS_EDATA or
 * MIMAS_EUSAGE naming the file. */
int mimas_energy_of(const char *path, const mimas_energy_options *o, mimas_energy *e,
                    mimas_error *err);

#ifdef __cplusplus
}
#endif
#endif
