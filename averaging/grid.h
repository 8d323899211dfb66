/* Averaging grids (mimas average --grid): none (one cell, the whole box),
 * Cartesian x/y/z, or cylindrical r/phi/z about an axis.  Directions that
 * are not gridded span the whole box (Cartesian) or the full circle and the
 * box's extent along the axis (cylindrical), resolved per frame. */
#ifndef MIMAS_GRID_H
#define MIMAS_GRID_H

#include <stddef.h>

#include "error.h"
#include "frame.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum mimas_grid_kind { MIMAS_GRID_CARTESIAN, MIMAS_GRID_CYLINDRICAL } mimas_grid_kind;

typedef struct mimas_grid {
    mimas_grid_kind kind;
    int gridded[3];      /* direction d (x y z, or r phi z) was given */
    double lo[3], hi[3]; /* bounds of each direction (non-gridded: set per frame) */
    int n[3];            /* cells along each direction (1 if not gridded) */
    /* the axis of cylindrical grids: origin and unit direction e_z, with
     * e_x, e_y completing a right-handed frame (phi = 0 along e_x) */
    double origin[3], ez[3], ex[3], ey[3];
} mimas_grid;

/* Parses "none", "x=LO:HI:N[,y=...][,z=...]" or "r=LO:HI:N[,phi=LO:HI:N][,z=LO:HI:N]"
 * (phi in radians).  axis is NULL (the z axis through the origin) or six
 * numbers "X0,Y0,Z0,DX,DY,DZ". */
int mimas_grid_parse(mimas_grid *g, const char *spec, const char *axis, mimas_error *err);
/* Fills the bounds of the directions that are not gridded from the box. */
void mimas_grid_fit_box(mimas_grid *g, const mimas_box *box);
size_t mimas_grid_cells(const mimas_grid *g);
/* Cell index from per-direction indices (direction 0 runs fastest). */
size_t mimas_grid_index(const mimas_grid *g, const int idx[3]);
void mimas_grid_unindex(const mimas_grid *g, size_t cell, int idx[3]);
/* Bounds and centre of a cell in grid coordinates (x y z or r phi z). */
void mimas_grid_cell_bounds(const mimas_grid *g, size_t cell, double lo[3], double hi[3]);
void mimas_grid_cell_centre(const mimas_grid *g, size_t cell, double c[3]);
double mimas_grid_cell_volume(const mimas_grid *g, size_t cell);
/* A point in the axis frame (Cartesian coordinates relative to origin along
 * ex, ey, ez); for Cartesian grids the point itself. */
void mimas_grid_to_axis(const mimas_grid *g, const double x[3], double out[3]);
/* Names of the coordinates: "x y z" or "r phi z". */
const char *mimas_grid_coord_name(const mimas_grid *g, int d);

#ifdef __cplusplus
}
#endif
#endif
