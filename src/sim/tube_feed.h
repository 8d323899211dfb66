/* The feed of a tube: a packed column of grains, built from copies of one
 * block that is periodic along the tube, so that the copies join without
 * overlaps or gaps. */
#ifndef MIMAS_SIM_TUBE_FEED_H
#define MIMAS_SIM_TUBE_FEED_H

#include <stddef.h>

#include "error.h"
#include "scenario.h"

typedef struct sim_feed_block {
    double length;           /* along z, m */
    size_t n;
    double (*x)[3];          /* positions, 0 <= z < length, inside the tube */
    double porosity;         /* 1 - n V_p/(A length) */
} sim_feed_block;

/* Packs a block of length about 10 d in a tube of radius R at porosity phi:
 * random positions at half the radius, then the radii grow to their value
 * while a frictionless, damped DEM run (contact law of the scenario,
 * periodic along z) pushes the particles apart, then the block relaxes.
 * sc must be resolved (dt, k_n); MIMAS_EDATA if the packing keeps overlaps
 * above 1 % of d (phi too low). */
int sim_feed_block_make(sim_feed_block *b, const sim_scenario *sc, double R, double phi,
                        mimas_error *err);
void sim_feed_block_free(sim_feed_block *b);

#endif
