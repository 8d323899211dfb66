/* The --walls specification of mimas voronoi: container walls for the
 * Voronoi cells (voro_cells.h). */
#ifndef MIMAS_VORO_WALLS_H
#define MIMAS_VORO_WALLS_H

#include <stddef.h>

#include "error.h"
#include "voro_cells.h"

/* Parses a comma list of walls into walls[0 .. *n-1] (at most max):
 *   plane:AXIS:H      AXIS x, y, z, -x, -y or -z: the plane AXIS = H, with
 *                     the particles on the side the signed axis points to
 *                     (plane:z:0 a floor, plane:-z:0.04 a lid at z = 0.04)
 *   cylinder:R[:outer|:inner][:X0:Y0]
 *                     the cylinder of radius R about the axis parallel to z
 *                     through (X0, Y0) (default the z axis); outer (the
 *                     default): the particles are inside it; inner: they are
 *                     outside it (the inner wall of an annulus). */
int mimas_voro_walls_parse(const char *spec, mimas_voro_wall *walls, size_t max, size_t *n,
                           mimas_error *err);

#endif
