#include <config.h>

#include "axis.h"

#include <math.h>
#include <stdlib.h>

int mimas_axis_set(mimas_axis *a, const double origin[3], const double dir[3], mimas_error *err)
{
    double len = sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
    if (!(len > 0) || !isfinite(len))
        return mimas_error_set(err, MIMAS_EUSAGE, "--axis direction is zero");
    for (int d = 0; d < 3; d++) {
        a->origin[d] = origin[d];
        a->ez[d] = dir[d] / len;
    }
    /* e_x: the global x (or y if the axis is along x) made normal to e_z */
    double ref[3] = {1, 0, 0};
    if (fabs(a->ez[0]) > 0.9) {
        ref[0] = 0;
        ref[1] = 1;
    }
    double dot = ref[0] * a->ez[0] + ref[1] * a->ez[1] + ref[2] * a->ez[2];
    double n = 0;
    for (int d = 0; d < 3; d++) {
        a->ex[d] = ref[d] - dot * a->ez[d];
        n += a->ex[d] * a->ex[d];
    }
    n = sqrt(n);
    for (int d = 0; d < 3; d++)
        a->ex[d] /= n;
    a->ey[0] = a->ez[1] * a->ex[2] - a->ez[2] * a->ex[1];
    a->ey[1] = a->ez[2] * a->ex[0] - a->ez[0] * a->ex[2];
    a->ey[2] = a->ez[0] * a->ex[1] - a->ez[1] * a->ex[0];
    return MIMAS_OK;
}

int mimas_axis_parse(mimas_axis *a, const char *spec, mimas_error *err)
{
    double v[6] = {0, 0, 0, 0, 0, 1};
    if (spec) {
        char *end;
        const char *p = spec;
        for (int k = 0; k < 6; k++) {
            v[k] = strtod(p, &end);
            if (end == p || !isfinite(v[k]) || (k < 5 ? *end != ',' : *end != '\0'))
                return mimas_error_set(err, MIMAS_EUSAGE,
                                       "--axis needs six numbers X0,Y0,Z0,DX,DY,DZ, not '%s'",
                                       spec);
            p = end + 1;
        }
    }
    return mimas_axis_set(a, v, v + 3, err);
}

void mimas_axis_vector_to_local(const mimas_axis *a, const double v[3], double out[3])
{
    double o0 = v[0] * a->ex[0] + v[1] * a->ex[1] + v[2] * a->ex[2];
    double o1 = v[0] * a->ey[0] + v[1] * a->ey[1] + v[2] * a->ey[2];
    double o2 = v[0] * a->ez[0] + v[1] * a->ez[1] + v[2] * a->ez[2];
    out[0] = o0, out[1] = o1, out[2] = o2;
}

void mimas_axis_to_local(const mimas_axis *a, const double x[3], double out[3])
{
    double d[3] = {x[0] - a->origin[0], x[1] - a->origin[1], x[2] - a->origin[2]};
    mimas_axis_vector_to_local(a, d, out);
}
