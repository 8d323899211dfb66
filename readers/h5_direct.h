/* Reading a chunked HDF5 dataset by its chunks (h5_direct.c): what H5Dread gives,
 * with the shuffle and deflate filters undone faster than HDF5's own. */
#ifndef MIMAS_H5_DIRECT_H
#define MIMAS_H5_DIRECT_H

#include <hdf5.h>

#define H5_DIRECT_MAX_RANK 3

typedef struct h5_direct h5_direct;

/* A reader of ds by its chunks, or NULL where it does not apply (not chunked, rank
 * above 3, filters other than shuffle and deflate, a file type other than memtype,
 * out of memory): read such a dataset with H5Dread.  ds stays the caller's. */
h5_direct *h5_direct_open(hid_t ds, hid_t memtype);
void h5_direct_close(h5_direct *d);

/* Working space for decoding, shared by the readers of a file (zero it to start). */
typedef struct h5_direct_scratch {
    unsigned char *raw, *tmp;
    size_t raw_cap, tmp_cap;
} h5_direct_scratch;
void h5_direct_scratch_free(h5_direct_scratch *s);

/* The block [start, start + count) (one entry per dimension) into buf in row order,
 * as H5Dread with a memory space of the block's shape; 0, or -1 if it cannot (a
 * chunk not written, data that do not decode, out of memory): read it with H5Dread
 * then, which also reports a damaged file. */
int h5_direct_read(h5_direct *d, h5_direct_scratch *s, const hsize_t *start,
                   const hsize_t *count, void *buf);

#endif
