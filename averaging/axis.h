/* An axis in space (cylindrical grids, tubes, dispersion along a transport
 * direction): a point on it and a right-handed orthonormal frame whose e_z is
 * the axis direction.  Parsed from the option form X0,Y0,Z0,DX,DY,DZ. */
#ifndef MIMAS_AXIS_H
#define MIMAS_AXIS_H

#include "error.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct mimas_axis {
    double origin[3];
    double ez[3];    /* unit direction of the axis */
    double ex[3];    /* phi = 0: the global x (or y for an axis near x) made normal to e_z */
    double ey[3];    /* e_z x e_x */
} mimas_axis;

/* The axis through origin along dir (need not be unit length); MIMAS_EUSAGE
 * when dir is zero or not finite. */
int mimas_axis_set(mimas_axis *a, const double origin[3], const double dir[3], mimas_error *err);
/* "X0,Y0,Z0,DX,DY,DZ" (NULL: the z axis through the origin); MIMAS_EUSAGE
 * with a message naming --axis otherwise. */
int mimas_axis_parse(mimas_axis *a, const char *spec, mimas_error *err);
/* x in the axis frame: its components along e_x, e_y, e_z relative to origin. */
void mimas_axis_to_local(const mimas_axis *a, const double x[3], double out[3]);
/* A vector (not a point) in the axis frame. */
void mimas_axis_vector_to_local(const mimas_axis *a, const double v[3], double out[3]);

#ifdef __cplusplus
}
#endif
#endif
