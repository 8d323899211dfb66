/* A frame of particles made by hand in the tests. */
#ifndef MIMAS_TEST_PARTICLE_FRAME_H
#define MIMAS_TEST_PARTICLE_FRAME_H

#include "frame.h"

/* Clears f and gives it n particles with ids and positions (not set) and
 * the quantities in bits, at time (step: time * 1000, rounded). */
int particle_frame(mimas_frame *f, size_t n, unsigned bits, double time, mimas_error *err);

#endif
