/* C interface to voro++ (Rycroft): per-particle Voronoi cells.  The
 * implementation, averaging/voro_cells.cc, is the only C++ in mimas. */
#ifndef MIMAS_VORO_CELLS_H
#define MIMAS_VORO_CELLS_H

#include <stddef.h>

#include "error.h"
#include "frame.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Computes the Voronoi cell of every particle in the box: plain Voronoi when
 * radius is NULL, radical (Laguerre) when radii are given (PHYSICS 6).  An
 * orthogonal box may be periodic along any axes; a triclinic box must be
 * periodic along all three.  Writes the cell volume and face count of
 * particle k to volume[k] and faces[k] (faces may be NULL); a particle whose
 * radical cell is empty (possible for overlapping spheres) gets 0 and 0.  A
 * particle outside a non-periodic box is an error naming it. */
int mimas_voro_cells(const mimas_box *box, size_t n, const double (*pos)[3],
                     const double *radius, double *volume, int *faces, mimas_error *err);

#ifdef __cplusplus
}
#endif
#endif
