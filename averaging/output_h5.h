/* The field file of mimas average -o: HDF5 with every field's mean,
 * standard deviation over frames, frame count and standard error, its unit
 * and definition, the grid, provenance, and the XDMF sidecars that
 * ParaView opens (output_xdmf.c). */
#ifndef MIMAS_OUTPUT_H5_H
#define MIMAS_OUTPUT_H5_H

#include <stdint.h>

#include "average.h"
#include "error.h"
#include "parameters.h"

#define MIMAS_FIELDS_VERSION_MAJOR 1
#define MIMAS_FIELDS_VERSION_MINOR 1

typedef struct mimas_fields_file mimas_fields_file;

/* Starts PATH under a temporary name; want[k] says which of the
 * mimas_field() columns to write (NULL: all).  PATH's XDMF sidecars
 * (PATH with .xdmf instead of .h5, and -frames.xdmf with --per-frame) are
 * written by mimas_fields_finish. */
int mimas_fields_open(mimas_fields_file **ff, const char *path, const unsigned char *want,
                      mimas_error *err);
/* Appends the fields of one frame (an average holding just that frame) to
 * /frames (--per-frame). */
int mimas_fields_append_frame(mimas_fields_file *ff, const mimas_average *frame, int64_t step,
                              double time, mimas_error *err);
/* Copies the run parameters of the input (mimas_reader_parameters) into
 * /parameters/GROUP of the field file, laid out as in the native file. */
int mimas_fields_parameters(mimas_fields_file *ff, const char *group, const mimas_parameters *ps,
                            mimas_error *err);
/* Writes the time average, the grid and the provenance (the command line,
 * may be NULL), closes and renames the files into place; frees ff. */
int mimas_fields_finish(mimas_fields_file *ff, const mimas_average *a, const char *provenance,
                        mimas_error *err);
/* Closes and removes the unfinished files; frees ff. */
void mimas_fields_abort(mimas_fields_file *ff);

#endif
