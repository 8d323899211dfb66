/* A set of time-averaged fields on a grid, for the analyses that work on
 * the output of mimas average (shear band, rheology, ...): read from a
 * field file (mimas average -o, layout in output_h5.c and docs/format.md)
 * or taken from an average held in memory.  Each field comes as its mean
 * and standard error per cell; cells are numbered like the grid's
 * (direction 0 fastest). */
#ifndef MIMAS_FIELDSET_H
#define MIMAS_FIELDSET_H

#include <stddef.h>

#include "average.h"
#include "error.h"
#include "parameters.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum mimas_fieldset_kind {
    MIMAS_FIELDSET_NONE,        /* --grid none: one cell */
    MIMAS_FIELDSET_CARTESIAN,   /* directions x y z */
    MIMAS_FIELDSET_CYLINDRICAL  /* directions r phi z */
} mimas_fieldset_kind;

typedef struct mimas_fieldset_grid {
    mimas_fieldset_kind kind;
    int n[3];                /* cells along each direction */
    int gridded[3];          /* the direction was given in --grid */
    const double *centre[3]; /* the cell centres along each direction (n[d] values) */
    size_t cells;
    size_t frames;           /* frames averaged */
} mimas_fieldset_grid;

typedef struct mimas_fieldset mimas_fieldset;

/* 1 if path is an HDF5 file with the groups of a field file (/grid and
 * /fields), 0 otherwise (another HDF5 file, a dump, no file). */
int mimas_fieldset_probe(const char *path);
/* Opens a field file; rejects files that are not field files or have a
 * newer major version than MIMAS_FIELDS_VERSION_MAJOR.  Messages name path. */
int mimas_fieldset_open(mimas_fieldset **fs, const char *path, mimas_error *err);
/* The fields of an average held in memory (copied; avg may be freed after),
 * named name in messages. */
int mimas_fieldset_from_average(mimas_fieldset **fs, const mimas_average *avg, const char *name,
                                mimas_error *err);
void mimas_fieldset_close(mimas_fieldset *fs);

const char *mimas_fieldset_name(const mimas_fieldset *fs);
/* The run parameters the fields were made from: a field file's
 * /parameters/scenario (mimas average copies the input's), or those given
 * to a set from memory with mimas_fieldset_set_parameters; else empty. */
const mimas_parameters *mimas_fieldset_parameters(const mimas_fieldset *fs);
int mimas_fieldset_set_parameters(mimas_fieldset *fs, const mimas_parameters *ps,
                                  mimas_error *err);
const mimas_fieldset_grid *mimas_fieldset_grid_of(const mimas_fieldset *fs);
/* 1 if the set holds the field (docs/fields.md names). */
int mimas_fieldset_has(const mimas_fieldset *fs, const char *field);
/* The field's mean per cell (NaN where undefined) and, if sem is not NULL,
 * its standard error std/sqrt(count) over frames (NaN where it was defined
 * in fewer than 2 frames, and for the fields without spread, such as the
 * strain rates).  Arrays of grid->cells values.  MIMAS_EMISSING if the field
 * is absent. */
int mimas_fieldset_read(const mimas_fieldset *fs, const char *field, double *mean, double *sem,
                        mimas_error *err);

/* The picture of one field (mimas plot): on a grid with two directions of
 * more than one cell a colour map of the cells (drawn to scale where both
 * are lengths; undefined cells white) with a colour bar in the field's
 * unit, on a grid with one such direction the profile with its standard
 * errors; by gnuplot, into png (written under a temporary name, renamed
 * when complete).  MIMAS_EMISSING for a field the set does not hold,
 * MIMAS_EDATA for a grid with no or three such directions. */
typedef struct mimas_fieldset_plot_options {
    int error;      /* draw the standard error instead of the mean */
    int logscale;   /* logarithmic colour scale (map) or value axis (profile) */
    double lo, hi;  /* the value range; not finite: from the data */
} mimas_fieldset_plot_options;
int mimas_fieldset_plot(const mimas_fieldset *fs, const char *field,
                        const mimas_fieldset_plot_options *o, const char *png, mimas_error *err);

#ifdef __cplusplus
}
#endif
#endif
