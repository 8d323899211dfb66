/* Random frames for tests, the benchmark and the demonstration file. */
#ifndef MIMAS_TEST_RANDOM_FRAME_H
#define MIMAS_TEST_RANDOM_FRAME_H

#include <gsl/gsl_rng.h>

#include "frame.h"

typedef struct random_frame_spec {
    size_t particles, contacts, walls;
    int optional;     /* also fill every optional quantity and two extra columns */
    int triclinic;    /* tilted, fully periodic box */
    int with_contacts, with_walls;
} random_frame_spec;

/* Fills f (which must be initialised) with random content: unique shuffled
 * ids, positions inside the box, contacts between distinct particles. */
int random_frame(mimas_frame *f, gsl_rng *rng, const random_frame_spec *spec, int64_t step);

/* 1 if a and b hold the same quantities and bit-identical values. */
int frames_equal(const mimas_frame *a, const mimas_frame *b, char *why, size_t whylen);

#endif
