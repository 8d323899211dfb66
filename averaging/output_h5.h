/* The field file of mimas average -o: HDF5 with every field's mean,
 * standard deviation over frames and frame count, its unit and definition,
 * the grid, provenance, and an XDMF sidecar that ParaView opens. */
#ifndef MIMAS_OUTPUT_H5_H
#define MIMAS_OUTPUT_H5_H

#include "average.h"
#include "error.h"

#define MIMAS_FIELDS_VERSION_MAJOR 1
#define MIMAS_FIELDS_VERSION_MINOR 0

/* Writes PATH (and PATH with .xdmf instead of .h5) under temporary names,
 * renamed when complete.  provenance: the command line (may be NULL). */
int mimas_fields_write_h5(const mimas_average *a, const char *path, const char *provenance,
                          mimas_error *err);

#endif
