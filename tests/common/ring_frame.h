/* Frames of a split-bottom ring shear cell for the shear-band tests:
 * particles spread uniformly over an annulus, moving about the z axis with
 * the angular velocity Omega (0.5 + 0.5 erf((r - Rc(z))/W)) (docs/theory.md §7.1;
 * Uhlig 2012, eq. 2.11), Rc(z) = rc + rc_slope z, plus Gaussian velocity noise. */
#ifndef MIMAS_TEST_RING_FRAME_H
#define MIMAS_TEST_RING_FRAME_H

#include <gsl/gsl_rng.h>

#include "frame.h"

typedef struct ring_spec {
    double r_in, r_out, height;   /* the annulus the spheres lie in (box z from 0) */
    double diameter, density;
    double omega;                 /* rotation rate of the outer part (rad/s) */
    double rc, rc_slope, w;       /* band centre at z = 0, its slope dRc/dz, width */
    double noise;                 /* velocity noise, standard deviation in m/s */
    size_t particles;
} ring_spec;

/* The dry band of Uhlig (2012, Table 4.8) in Uhlig's cell (docs/theory.md §7.1). */
void ring_spec_default(ring_spec *s);
/* omega(r, z)/Omega of the spec. */
double ring_profile(const ring_spec *s, double r, double z);
/* Fills f (initialised) with one frame. */
int ring_frame(mimas_frame *f, gsl_rng *rng, const ring_spec *s, int64_t step);

#endif
