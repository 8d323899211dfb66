/* The outputs of the tube analyses (mimas plugs, mimas radial): tables as
 * HDF5 groups of column datasets written row by row (their text form is
 * the commands' shared table writer, src/cli_table.h), HDF5
 * files that appear only when complete, and the space-time fields of the
 * axial profiles (slice x frame, with an XDMF sidecar for ParaView). */
#ifndef MIMAS_PLUGS_OUTPUT_H
#define MIMAS_PLUGS_OUTPUT_H

#include <stdint.h>
#include <stdio.h>

#include "axial_profile.h"
#include "error.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- an HDF5 file written under a temporary name ---- */
typedef struct mimas_h5out mimas_h5out;
int mimas_h5out_open(mimas_h5out **o, const char *path, mimas_error *err);
/* Writes the provenance attributes (command line, version), closes and
 * renames the file into place; frees o. */
int mimas_h5out_commit(mimas_h5out *o, const char *provenance, mimas_error *err);
/* Closes and removes the unfinished file; frees o (NULL is fine). */
void mimas_h5out_abort(mimas_h5out *o);

/* ---- a table as an HDF5 group ---- */
typedef struct mimas_ocolumn {
    const char *name;
    const char *unit;      /* "1" for dimensionless, "" for none */
    const char *meaning;
    int text;              /* a string column (else numbers) */
    int integer;           /* a number column of whole numbers (printed without exponent) */
} mimas_ocolumn;
typedef struct mimas_otable mimas_otable;
/* The table is the group of that name in h5, one dataset per column (with
 * its unit and definition as attributes).  The columns must outlive the
 * table. */
int mimas_otable_open(mimas_otable **t, mimas_h5out *h5, const char *group,
                      const mimas_ocolumn *cols, size_t ncols, mimas_error *err);
/* One row: v[c] for number columns (NaN prints "nan"), text[c] for text
 * columns (text may be NULL without text columns). */
int mimas_otable_row(mimas_otable *t, const double *v, const char *const *text,
                     mimas_error *err);
/* Flushes the HDF5 rows; frees t (NULL is fine). */
int mimas_otable_close(mimas_otable *t, mimas_error *err);

/* ---- space-time fields of the axial profiles (--axial FILE.h5) ---- */
typedef struct mimas_spacetime mimas_spacetime;
int mimas_spacetime_open(mimas_spacetime **st, const char *path, const mimas_axial *ax,
                         mimas_error *err);
int mimas_spacetime_append(mimas_spacetime *st, const mimas_axial *ax, int64_t step, double time,
                           mimas_error *err);
/* Writes the sidecar PATH.xdmf (PATH less .h5), renames both into place;
 * frees st. */
int mimas_spacetime_finish(mimas_spacetime *st, const char *provenance, mimas_error *err);
void mimas_spacetime_abort(mimas_spacetime *st);

#ifdef __cplusplus
}
#endif
#endif
