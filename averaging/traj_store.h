/* The particle-major trajectory store of mimas disperse (docs/disperse.md,
 * "Memory"): a record of ncomp doubles for every particle slot and frame,
 * written one frame at a time and read back a block of slots at a time with
 * all their frames.  A record whose first value is NaN means "absent".
 *
 * Frames are gathered in chunks laid out [slot][frame][component], so that a
 * slot's frames lie together.  Finished chunks stay in memory while their
 * total stays within the store's memory; beyond it they all go to a chunked
 * HDF5 scratch file and memory holds just the chunk being filled.  The
 * scratch file is created in the folder given and unlinked at once: it
 * lives only as long as the open file, and nothing is left behind however
 * the program ends. */
#ifndef MIMAS_TRAJ_STORE_H
#define MIMAS_TRAJ_STORE_H

#include <stddef.h>

#include "error.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct mimas_traj_store mimas_traj_store;

typedef struct mimas_traj_store_options {
    size_t ncomp;            /* doubles per record (1 to 8) */
    size_t memory;           /* bytes of records the store may hold in memory */
    const char *scratch_dir; /* folder of the scratch file (NULL: $TMPDIR, else /tmp) */
} mimas_traj_store_options;

int mimas_traj_store_create(mimas_traj_store **s, const mimas_traj_store_options *o,
                            mimas_error *err);
/* Starts the next frame with nslots slots (never fewer than before); every
 * record of it is absent until written.  MIMAS_EUSAGE when the memory
 * cannot hold one frame of nslots records. */
int mimas_traj_store_next_frame(mimas_traj_store *s, size_t nslots, mimas_error *err);
/* The record of slot (< nslots) in the current frame, to be written. */
double *mimas_traj_store_record(mimas_traj_store *s, size_t slot);
/* Ends the last frame; after it only reads. */
int mimas_traj_store_finish(mimas_traj_store *s, mimas_error *err);
/* Moves every chunk held in memory to the scratch file (after finish). */
int mimas_traj_store_spill(mimas_traj_store *s, mimas_error *err);

size_t mimas_traj_store_frames(const mimas_traj_store *s);
size_t mimas_traj_store_slots(const mimas_traj_store *s);
size_t mimas_traj_store_ncomp(const mimas_traj_store *s);
/* 1 once the scratch file is in use. */
int mimas_traj_store_on_disk(const mimas_traj_store *s);
/* Bytes of records held in memory now. */
size_t mimas_traj_store_bytes(const mimas_traj_store *s);

/* Reads slots first .. first+n-1 over all frames into out[n][frames][ncomp]
 * (after finish). */
int mimas_traj_store_read(mimas_traj_store *s, size_t first, size_t n, double *out,
                          mimas_error *err);
void mimas_traj_store_free(mimas_traj_store *s);

#ifdef __cplusplus
}
#endif
#endif
