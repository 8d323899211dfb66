/* Small HDF5 helpers shared by the native writer and reader: silencing
 * HDF5's own error printing, turning its error stack into one message, and
 * attribute and extendible-dataset chores. */
#ifndef MIMAS_H5UTIL_H
#define MIMAS_H5UTIL_H

#include <hdf5.h>
#include <stddef.h>
#include <stdint.h>

/* While "quiet", HDF5 prints nothing; mimas reports errors itself. */
typedef struct h5_quiet {
    H5E_auto2_t func;
    void *data;
} h5_quiet;
void h5_quiet_begin(h5_quiet *q);
void h5_quiet_end(const h5_quiet *q);

/* The innermost HDF5 error description of the current error stack
 * ("truncated file: eof = ...", "unable to open file"), or "" if none. */
void h5_error_text(char *buf, size_t len);

int h5_attr_write_str(hid_t obj, const char *name, const char *value);
/* A scalar variable-length string attribute (what H5MD 1.1 asks of its
 * string attributes, e.g. unit). */
int h5_attr_write_vlstr(hid_t obj, const char *name, const char *value);
int h5_attr_write_strs(hid_t obj, const char *name, const char *const *values, size_t n);
int h5_attr_write_ints(hid_t obj, const char *name, const int *values, size_t n);
int h5_attr_write_double(hid_t obj, const char *name, double value);
/* 1-d attributes of n values (a scalar for n = 1) and their reading (up to
 * n values; the number stored, or -1). */
int h5_attr_write_doubles(hid_t obj, const char *name, const double *values, size_t n);
int h5_attr_write_int64s(hid_t obj, const char *name, const int64_t *values, size_t n);
int h5_attr_read_doubles(hid_t obj, const char *name, double *values, size_t n);
int h5_attr_read_int64s(hid_t obj, const char *name, int64_t *values, size_t n);
/* Reads up to n ints; returns the number stored in the attribute, or -1. */
int h5_attr_read_ints(hid_t obj, const char *name, int *values, size_t n);
/* Reads a scalar string attribute (fixed or variable length); -1 if absent. */
int h5_attr_read_str(hid_t obj, const char *name, char *buf, size_t len);
/* Reads a 1-d string-array attribute into fixed-size slots; returns count or -1. */
int h5_attr_read_strs(hid_t obj, const char *name, char (*values)[16], size_t n);

/* Writes a dataset of doubles of the given rank and dimensions, with the
 * string attributes unit (unless NULL or "1") and definition (unless NULL). */
int h5_write_doubles(hid_t loc, const char *name, int rank, const hsize_t *dims,
                     const double *data, const char *unit, const char *meaning);

/* HDF5 keeps freed blocks in free lists of its own, without bound by
 * default (tens of MB after reading many chunks).  Gives them back to the
 * heap, and (glibc) the heap's free pages to the system: */
void h5_release_free_lists(void);
/* Bounds them for the process to about bytes in all. */
void h5_limit_free_lists(size_t bytes);

/* Writes a 1-d dataset of n fixed-length strings with the attribute
 * definition (unless NULL). */
int h5_write_strs(hid_t loc, const char *name, const char *const *values, size_t n,
                  const char *meaning);

/* Creates a chunked dataset of rank `rank` whose leading dimensions marked
 * unlimited start at 0.  dims gives the fixed trailing sizes (leading entries
 * ignored); chunk the chunk shape; fill is the fill value or NULL; deflate the
 * gzip level (0: none, with shuffle otherwise). */
hid_t h5_create_growing(hid_t loc, const char *name, hid_t type, int rank, int n_unlimited,
                        const hsize_t *dims, const hsize_t *chunk, const void *fill,
                        int deflate);

/* Opens the group at path, or creates it (with the groups above it) so that
 * its members and attributes remember the order they were created in (they
 * read back in written order). */
hid_t h5_group_ordered(hid_t loc, const char *path);

/* Writes row k (extending dimension 0 to k + 1) of a growing dataset of
 * rank 1 + rank, whose trailing dimensions are dims; memtype describes
 * row's elements (H5T_NATIVE_DOUBLE, ...).  0 on success. */
int h5_append_row(hid_t ds, hsize_t k, int rank, const hsize_t *dims, hid_t memtype,
                  const void *row);

/* Current extent of dimension 0 (or 0 on error). */
hsize_t h5_extent0(hid_t dset);

#endif
