/* The minimum image by fractional coordinates, an independent route from
 * the library's mimas_box_min_image for the tests: s = h^-1 d, s -= round(s)
 * along the periodic axes, d = h s (h = [a b c], LAMMPS tilt convention). */
#ifndef MIMAS_TEST_FRAC_IMAGE_H
#define MIMAS_TEST_FRAC_IMAGE_H

#include "frame.h"

void min_image_frac(const mimas_box *b, double d[3]);

#endif
