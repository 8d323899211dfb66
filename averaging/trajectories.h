/* Trajectories by particle id across a stream of frames (docs/disperse.md,
 * "Trajectories and unwrapping"): every selected id gets a slot when it is
 * first seen, and each frame's positions are unwrapped through the periodic
 * faces and kept in a trajectory store, with the velocities when asked.
 *
 * Unwrapping: x_u = x + n_a a + n_b b + n_c c with the box edge vectors and
 * per-particle image counts n.  When the first frame has image flags, n are
 * the flags; otherwise (and from the first frame without flags on) n follow
 * the minimum image of each particle's move since the frame it was last
 * seen (the box's convention, triclinic too), and a move of more than a
 * quarter of the box along a periodic edge is counted as ambiguous.
 *
 * The frames must be equally spaced in time: a frame whose interval to the
 * previous one differs from the first interval by more than 1e-6 of it is
 * refused.  Per frame the selection's mean velocity and the cumulated mean
 * displacement (the drift: the mean move of the particles present in this
 * and the previous frame, summed) are kept. */
#ifndef MIMAS_TRAJECTORIES_H
#define MIMAS_TRAJECTORIES_H

#include <stddef.h>
#include <stdint.h>

#include "error.h"
#include "frame.h"
#include "traj_store.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct mimas_traj_options {
    const int32_t *types;     /* particle selection by type (NULL: all) */
    size_t ntypes;
    int exclude;              /* 1: types are left out; 0: only they are used */
    int velocities;           /* keep velocities: records (x_u, v), else x_u */
    size_t memory;            /* bytes the store may hold in memory */
    const char *scratch_dir;  /* folder of the store's scratch file */
} mimas_traj_options;

/* Moves of more than a quarter box (minimum-image unwrapping). */
typedef struct mimas_traj_jumps {
    size_t count;
    int64_t first_id;         /* the first such move: particle and frame time */
    double first_time;
} mimas_traj_jumps;

typedef struct mimas_trajectories mimas_trajectories;

int mimas_traj_create(mimas_trajectories **t, const mimas_traj_options *o, mimas_error *err);
/* Adds the next frame.  MIMAS_EDATA for unequal spacing, a frame without
 * time, a repeated id; MIMAS_EMISSING when types (with a selection) or
 * velocities (when kept) are absent. */
int mimas_traj_add(mimas_trajectories *t, const mimas_frame *f, mimas_error *err);
/* For the frame added last: each particle's slot (SIZE_MAX: not selected)
 * and whether that was its first frame. */
const size_t *mimas_traj_frame_slots(const mimas_trajectories *t);
const unsigned char *mimas_traj_frame_new(const mimas_trajectories *t);
/* Ends the stream (the store becomes readable). */
int mimas_traj_finish(mimas_trajectories *t, mimas_error *err);

size_t mimas_traj_frames(const mimas_trajectories *t);
size_t mimas_traj_slots(const mimas_trajectories *t);
const int64_t *mimas_traj_ids(const mimas_trajectories *t);   /* by slot */
const double *mimas_traj_times(const mimas_trajectories *t);  /* by frame */
/* (t_last - t_first) / (frames - 1); NaN with fewer than two frames. */
double mimas_traj_interval(const mimas_trajectories *t);
/* [frame][3]: the cumulated mean displacement (0 at the first frame) and
 * the mean velocity (NaN without velocities or particles). */
const double *mimas_traj_drift(const mimas_trajectories *t);
const double *mimas_traj_mean_velocity(const mimas_trajectories *t);
const mimas_traj_jumps *mimas_traj_jumps_seen(const mimas_trajectories *t);
mimas_traj_store *mimas_traj_store_of(mimas_trajectories *t);
void mimas_traj_free(mimas_trajectories *t);

#ifdef __cplusplus
}
#endif
#endif
