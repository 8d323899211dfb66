/* XDMF (eXtensible Data Model and Format, version 2) sidecars: small XML
 * files that describe the heavy data of an HDF5 file so that ParaView (and
 * VisIt) open it.  One writer for every sidecar mimas writes: the particle
 * trajectories of native files (src/xdmf_trajectory.c) and the field files
 * of mimas average (averaging/output_xdmf.c).  The sidecar is written under
 * a temporary name and renamed into place when complete. */
#ifndef MIMAS_XDMF_H
#define MIMAS_XDMF_H

#include <stddef.h>
#include <stdio.h>

#include "error.h"

#ifdef __cplusplus
extern "C" {
#endif

/* FILE.h5 -> FILE.xdmf (other names: NAME.xdmf), with suffix inserted
 * before ".xdmf" (e.g. "-frames"; may be ""). */
void mimas_xdmf_path(const char *h5path, const char *suffix, char *out, size_t len);

/* Writes the sidecar of a native trajectory: the particles of every
 * committed frame as a polyvertex grid in a temporal collection, with every
 * per-particle quantity as an attribute (docs/format.md, "XDMF"). */
int mimas_xdmf_trajectory(const char *h5path, const char *xdmf_path, mimas_error *err);

/* ---- the writer the sidecars share ---- */

#define XDMF_MAX_RANK 5

/* A dataset of the HDF5 file, or a hyperslab of it. */
typedef struct xdmf_item {
    const char *dataset;                      /* path in the HDF5 file */
    int is_float;                             /* Float, else Int */
    int precision;                            /* bytes: 4 or 8 */
    int rank;
    unsigned long long dims[XDMF_MAX_RANK];   /* the whole dataset */
    int slab;                                 /* 1: only start .. start + count */
    unsigned long long start[XDMF_MAX_RANK], count[XDMF_MAX_RANK];
    int out_rank;                             /* the shape XDMF sees (slabs: count */
    unsigned long long out[XDMF_MAX_RANK];    /* without the leading 1s) */
} xdmf_item;

typedef struct xdmf_writer {
    FILE *fp;
    char path[4096], tmp[4200];
    char h5name[1024];     /* the HDF5 file as the sidecar names it (same folder) */
} xdmf_writer;

/* Starts the sidecar at path describing the HDF5 file h5path. */
int xdmf_begin(xdmf_writer *x, const char *path, const char *h5path, mimas_error *err);
/* Finishes it: with ok, closes and renames it into place; else removes it. */
int xdmf_end(xdmf_writer *x, int ok, mimas_error *err);

/* A whole dataset: out = dims. */
void xdmf_item_whole(xdmf_item *it, const char *dataset, int is_float, int precision, int rank,
                     const unsigned long long *dims);
/* Only entry k along dimension 0 (and the first n along dimension 1 when
 * n1 is not 0): out drops dimension 0. */
void xdmf_item_frame(xdmf_item *it, unsigned long long k, unsigned long long n1);
/* The shape XDMF is to see (the same number of values), e.g. cells
 * (n2, n0) of a dataset (n2, 1, n0). */
void xdmf_item_shape(xdmf_item *it, int rank, const unsigned long long *out);
/* Writes it as a DataItem at the given indent. */
void xdmf_write_item(xdmf_writer *x, int indent, const xdmf_item *it);
/* An attribute of one item (type "Scalar", "Vector", "Tensor6", "Tensor";
 * center "Node" or "Cell"). */
void xdmf_write_attribute(xdmf_writer *x, int indent, const char *name, const char *type,
                          const char *center, const xdmf_item *it);
/* An attribute joined from n items of equal shape (JOIN($0, ..., $n-1)):
 * the components of a vector or tensor stored as separate datasets. */
void xdmf_write_joined(xdmf_writer *x, int indent, const char *name, const char *type,
                       const char *center, const xdmf_item *items, int n);

#ifdef __cplusplus
}
#endif
#endif
