/* Run parameters in HDF5 files (docs/format.md, "Run parameters"): one
 * attribute per parameter on the group /parameters/GROUP, shared by the
 * native writer and reader and by the field file of mimas average. */
#ifndef MIMAS_PARAMETERS_H5_H
#define MIMAS_PARAMETERS_H5_H

#include <hdf5.h>

#include "parameters.h"

/* Writes the parameters as attributes of /parameters/GROUP under loc (a file
 * or group): the value as a float64 (REAL), int64 (INTEGER) or string (TEXT;
 * MIXED: "mixed") attribute named SECTION.KEY, and its unit, when it has
 * one, as the string attribute SECTION.KEY.unit.  Nothing is written for an
 * empty list.  Returns 0, or -1 on an HDF5 error. */
int parameters_write_h5(hid_t loc, const char *group, const mimas_parameters *ps);
/* Reads /parameters/GROUP of loc into ps (emptied first); without the group
 * the list is empty.  Returns 0, or -1 when the group cannot be read (an
 * attribute that is neither a number nor a string, an overlong name or
 * value, no memory). */
int parameters_read_h5(hid_t loc, const char *group, mimas_parameters *ps);

#endif
