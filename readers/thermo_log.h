/* The thermo output of a LAMMPS or LIGGGHTS log (log.lammps, log.liggghts):
 * the tables that every run command prints, a header line that starts with
 * "Step" and one row of numbers per thermo output, read row by row (memory
 * does not grow with the rows).  Rows are returned with the values of the
 * columns asked for by name; the time is the Time column when the log has
 * one, else step * dt with dt from the option or the last echoed "timestep"
 * command.  The first row of a run repeats the last of the run before (the
 * same step): it is returned once. */
#ifndef MIMAS_THERMO_LOG_H
#define MIMAS_THERMO_LOG_H

#include <stddef.h>
#include <stdint.h>

#include "error.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct mimas_thermo_log mimas_thermo_log;

/* 1 if the first n bytes of a file look like a LAMMPS/LIGGGHTS log. */
int mimas_thermo_log_probe(const char *head, size_t n);
/* Opens the log; the rows will carry the columns named in names[0..n-1]
 * (header names as printed: KinEng, or rke for c_rke).  dt: the time step
 * for logs without a Time column (0: take it from the log). */
int mimas_thermo_log_open(mimas_thermo_log **log, const char *path, const char *const *names,
                          size_t n, double dt, mimas_error *err);
/* The next row: step, time (NaN when neither a Time column nor a time step
 * is known) and values[k] of names[k] (NaN where the row's run does not
 * print that column).  MIMAS_OK, MIMAS_END after the last row, or
 * MIMAS_EDATA naming the file and line. */
int mimas_thermo_log_next(mimas_thermo_log *log, int64_t *step, double *time, double *values,
                          mimas_error *err);
/* 1 if some run of the log printed column k (after the rows were read). */
int mimas_thermo_log_has(const mimas_thermo_log *log, size_t k);
void mimas_thermo_log_close(mimas_thermo_log *log);

#ifdef __cplusplus
}
#endif
#endif
