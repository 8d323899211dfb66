#include <config.h>

#include "frac_image.h"

#include <math.h>

void min_image_frac(const mimas_box *b, double d[3])
{
    double Lx = b->hi[0] - b->lo[0], Ly = b->hi[1] - b->lo[1], Lz = b->hi[2] - b->lo[2];
    double s2 = d[2] / Lz;
    double s1 = (d[1] - s2 * b->yz) / Ly;
    double s0 = (d[0] - s1 * b->xy - s2 * b->xz) / Lx;
    double s[3] = {s0, s1, s2};
    for (int k = 0; k < 3; k++)
        if (b->periodic[k])
            s[k] -= round(s[k]);
    d[0] = s[0] * Lx + s[1] * b->xy + s[2] * b->xz;
    d[1] = s[1] * Ly + s[2] * b->yz;
    d[2] = s[2] * Lz;
}
