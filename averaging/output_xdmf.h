/* The XDMF sidecars of a field file (mimas average -o): what the HDF5 file
 * must hold for them (cell corners, Cartesian vectors and tensors of
 * cylindrical grids) and the sidecars themselves.  Used by output_h5.c. */
#ifndef MIMAS_OUTPUT_XDMF_H
#define MIMAS_OUTPUT_XDMF_H

#include <hdf5.h>
#include <stddef.h>

#include "error.h"
#include "grid.h"

/* A vector (3 columns) or symmetric tensor (6 columns: xx yy zz xy xz yz,
 * or rr phiphi zz rphi rz phiz) among the derived fields. */
typedef struct fields_group {
    char name[32];      /* "v", "stress", "wall_force", ... */
    size_t first;       /* its first column (mimas_field index) */
    int ncomp;          /* 3 or 6 */
} fields_group;

/* The vector and tensor groups of which every column is wanted; returns
 * their count (at most max). */
size_t fields_groups(int cylindrical, const unsigned char *want, fields_group *groups,
                     size_t max);

/* /grid/corners: the cell corners in Cartesian coordinates, shape
 * (n2 + 1, n1' + 1, n0 + 1, 3) with n1' = 0 for cylindrical grids without
 * phi cells (the r-z half plane at phi = 0). */
int fields_write_corners(hid_t grid_group, const mimas_grid *g, int none);
/* 1 if the vectors and tensors are stored under /xdmf for the sidecar:
 * cylindrical grids (their components are not Cartesian) and grids of one
 * cell (XDMF's JOIN fails on one value); else they are joined from the
 * component datasets. */
int fields_xdmf_stored(const mimas_grid *g, int none);
/* /xdmf/NAME (see fields_xdmf_stored): each group's mean in Cartesian
 * components at the cell centres (vectors x y z; tensors in XDMF's Tensor6
 * order xx xy xz yy yz zz).  mean is cells x nf, cell-major. */
int fields_write_cartesian(hid_t file, const mimas_grid *g, const fields_group *groups,
                           size_t ngroups, const double *mean, size_t nf);

/* FIELDS.xdmf for the time average (mean, NAME_std and NAME_sem of every
 * wanted column; vectors and tensors joined), and with frames > 0
 * FIELDS-frames.xdmf: the per-frame fields (/frames) as a temporal
 * collection at the given times. */
int fields_write_xdmf(const char *h5path, const mimas_grid *g, int none,
                      const unsigned char *want, size_t frames, const double *times,
                      int has_full_tensor, const char *full_tensor, mimas_error *err);

#endif
