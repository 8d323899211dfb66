/* Checkpoints for `mimas simulate --resume`: the complete dynamic state (all
 * particle arrays, wall histories, the moving parts, the neighbour list with
 * its contact history) in a binary file written under a temporary name and
 * renamed, so a killed run leaves the previous checkpoint intact.  The
 * format is native-endian and meant for the same machine; it starts with a
 * magic string and a version and is checked for truncation. */
#ifndef MIMAS_SIM_CHECKPOINT_H
#define MIMAS_SIM_CHECKPOINT_H

#include "dem.h"

int sim_checkpoint_write(const dem_system *s, const char *path, mimas_error *err);
/* Restores the state into s, which must have been set up from the same
 * scenario (same particle count and walls). */
int sim_checkpoint_read(dem_system *s, const char *path, mimas_error *err);

#endif
