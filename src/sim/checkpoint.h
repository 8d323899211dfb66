/* Checkpoints for `mimas simulate --resume`: the complete dynamic state (all
 * particle arrays, wall histories, the moving parts, the neighbour list with
 * its contact history) in a binary file written under a temporary name and
 * renamed, so a killed run leaves the previous checkpoint intact.  The
 * format is native-endian and meant for the same machine; it starts with a
 * magic string and a version and is checked for truncation. */
#ifndef MIMAS_SIM_CHECKPOINT_H
#define MIMAS_SIM_CHECKPOINT_H

#include "dem.h"

/* State of a scenario beyond the DEM system (a gas field, a feed), saved
 * and restored as raw blocks of fixed size. */
typedef struct sim_ck_chunk {
    void *data;
    size_t size;
} sim_ck_chunk;

int sim_checkpoint_write(const dem_system *s, const sim_ck_chunk *extra, size_t nextra,
                         const char *path, mimas_error *err);
/* Restores the state into s, which must have been set up from the same
 * scenario (same walls and moving parts; the particle count may differ, for
 * scenarios that insert and remove particles), and the extra blocks, which
 * must have the sizes they were written with. */
int sim_checkpoint_read(dem_system *s, const sim_ck_chunk *extra, size_t nextra,
                        const char *path, mimas_error *err);

#endif
