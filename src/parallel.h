/* Frame-parallel runs under MPI (docs/parallel.md): one thin layer that every
 * frame-wise command uses.  Ranks split the selected frames round-robin
 * (frame j of the selection goes to rank j mod size); accumulators are merged
 * onto rank 0 by a reduction tree; per-frame results reach rank 0 in frame
 * order; failures are agreed on so that every rank ends with the same status
 * and message (the failure of the earliest frame, as a serial run reports it)
 * and no rank waits forever.  Built without MPI, there is one rank and every
 * function is the serial no-op: one code path for both builds. */
#ifndef MIMAS_PARALLEL_H
#define MIMAS_PARALLEL_H

#include <stddef.h>

#include "error.h"
#include "frame_pack.h"

#ifdef __cplusplus
extern "C" {
#endif

/* MPI_Init (when built with MPI); call once at the start of main(). */
int mimas_par_init(int *argc, char ***argv);
void mimas_par_finalize(void);
int mimas_par_rank(void);
int mimas_par_size(void);
/* "Open MPI v4.1.4, ..." (the MPI library's own words), or NULL without MPI. */
const char *mimas_par_library(void);

/* Every rank passes its status (MIMAS_OK or MIMAS_END when fine) and, for a
 * failure, the selected-frame index where it happened (SIZE_MAX: before any
 * frame) with its message in err.  Returns the status of the failure with the
 * smallest index (ties: the lowest rank), and every rank's err gets its
 * message; without failures, returns status unchanged.  Collective. */
int mimas_par_agree(int status, size_t position, mimas_error *err);

/* Rank 0's status and, when it is MIMAS_OK, its n bytes at data, given to
 * every rank (a failure comes with rank 0's message in err).  Collective. */
int mimas_par_share(int status, void *data, size_t n, mimas_error *err);

/* Merging accumulators onto rank 0: pack writes an object's state, merge adds
 * a packed state to an object.  After the call rank 0's object holds the
 * merge of all ranks' objects (in a fixed tree order); the others' objects
 * are left as they were.  Returns the agreed status (a failure to pack or
 * merge on any rank fails all).  Collective. */
typedef int (*mimas_par_pack_fn)(const void *obj, mimas_bytes *out, mimas_error *err);
typedef int (*mimas_par_merge_fn)(void *obj, const unsigned char *data, size_t n,
                                  mimas_error *err);
int mimas_par_reduce(void *obj, mimas_par_pack_fn pack, mimas_par_merge_fn merge,
                     mimas_error *err);

/* Per-frame results on rank 0 in frame order.  Each rank calls
 * mimas_par_ordered_put for every frame it handled, in its order, with the
 * frame's selected index and the packed result; rank 0's sink then receives
 * every frame's result in index order (its own and the others').  A rank
 * whose frame failed calls mimas_par_ordered_fail instead.  At the end every
 * rank calls mimas_par_ordered_finish, which returns the agreed status.
 * mimas_par_ordered_stopped tells a rank to stop early (another rank failed). */
typedef int (*mimas_par_sink_fn)(void *ctx, size_t position, const unsigned char *data,
                                 size_t n, mimas_error *err);
typedef struct mimas_par_ordered mimas_par_ordered;
int mimas_par_ordered_open(mimas_par_ordered **o, mimas_par_sink_fn sink, void *ctx,
                           mimas_error *err);
int mimas_par_ordered_put(mimas_par_ordered *o, size_t position, const mimas_bytes *result,
                          mimas_error *err);
void mimas_par_ordered_fail(mimas_par_ordered *o, size_t position, const mimas_error *why);
int mimas_par_ordered_stopped(mimas_par_ordered *o);
/* status: this rank's outcome of its own loop (MIMAS_END when it ran out of
 * frames; a failure already given to _fail may be passed again). */
int mimas_par_ordered_finish(mimas_par_ordered *o, int status, size_t position,
                             mimas_error *err);
void mimas_par_ordered_free(mimas_par_ordered *o);

#ifdef __cplusplus
}
#endif
#endif
