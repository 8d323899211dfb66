/* C interface to voro++ (Rycroft): per-particle Voronoi cells.  The
 * implementation, averaging/voro_cells.cc, is the only C++ in mimas. */
#ifndef MIMAS_VORO_CELLS_H
#define MIMAS_VORO_CELLS_H

#include <stddef.h>
#include <stdint.h>

#include "error.h"
#include "frame.h"

#ifdef __cplusplus
extern "C" {
#endif

/* A container wall that bounds the cells (docs/theory.md §6: cells at free surfaces
 * and walls must be bounded).  voro++ cuts the cell of a particle at x by one
 * plane per wall: the wall plane itself, or for a cylinder the plane tangent
 * to it at x's angle about the axis (voro++'s own cylinder approximation). */
typedef enum mimas_voro_wall_kind { MIMAS_VORO_PLANE, MIMAS_VORO_CYLINDER } mimas_voro_wall_kind;

typedef struct mimas_voro_wall {
    mimas_voro_wall_kind kind;
    double normal[3];  /* plane: unit normal, pointing to the particles' side */
    double offset;     /* plane: the particles lie where normal . x >= offset */
    double axis[2];    /* cylinder: its axis is parallel to z through (axis[0], axis[1]) */
    double radius;     /* cylinder radius */
    int inner;         /* cylinder: 0 = the particles are inside it (an outer wall),
                        * 1 = outside it (the inner wall of an annulus) */
} mimas_voro_wall;

typedef struct mimas_voro_options {
    const double *radius;          /* radii: radical (Laguerre) tessellation; NULL: plain */
    const mimas_voro_wall *walls;  /* walls (orthogonal boxes only) */
    size_t nwalls;
    double max_extent;             /* > 0: cut every cell to within this distance of its
                                    * particle (14 planes, see below); 0: no cut */
    int threads;                   /* OpenMP threads over blocks of cells (0: OpenMP's
                                    * default) */
    const int64_t *id;             /* particle ids for messages (NULL: indices) */
} mimas_voro_options;

/* Flags of mimas_voro_cells' surface output. */
enum {
    MIMAS_VORO_TOUCHES_WALL = 1,   /* a face on a wall or a non-periodic box face */
    MIMAS_VORO_CUT = 2             /* a face from the max_extent cut (a free surface) */
};

/* Computes the Voronoi cell of every particle in the box: plain Voronoi, or
 * radical when o->radius is given (docs/theory.md §6).  An orthogonal box may be
 * periodic along any axes and have walls; a triclinic box must be periodic
 * along all three and cannot have walls.  Writes the cell volume, face
 * count and surface flags of particle k to volume[k], faces[k] and
 * surface[k] (faces and surface may be NULL); a particle whose cell is empty
 * (a radical cell of a small sphere overlapping a big one) gets 0 for all
 * three.  A particle outside a non-periodic box or a wall is an error
 * naming it.
 *
 * max_extent cuts each cell by the 6 faces of a cube and the 8 faces of an
 * octahedron about the particle, all at distance L = max_extent: the cut
 * cell lies within L along the axes and within 1.24 L in any direction.
 *
 * voro++ decides with absolute tolerances (1e-11), so the points are handed
 * to it in units of the mean spacing (V_box/n)^(1/3) and the volumes scaled
 * back.  With threads > 1 every thread builds its own container (voro++'s
 * containers keep per-computation state) and computes a contiguous share of
 * the cells. */
int mimas_voro_cells(const mimas_box *box, size_t n, const double (*pos)[3],
                     const mimas_voro_options *o, double *volume, int *faces,
                     unsigned char *surface, mimas_error *err);

/* The bare voro++ loop (container, put, compute every cell's volume and face
 * count) over the same points, without anything of the above: no rescaling,
 * walls, flags or threads; orthogonal boxes only.  The reference that
 * bench/bench_voronoi.c compares mimas_voro_cells with. */
int mimas_voro_reference(const mimas_box *box, size_t n, const double (*pos)[3],
                         const double *radius, double *volume, int *faces, mimas_error *err);

#ifdef __cplusplus
}
#endif
#endif
