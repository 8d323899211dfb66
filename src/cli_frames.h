/* The frames a command works on: the inputs' frames inside the time window
 * (--from/--to/--every), and of those, under MPI, this rank's share (frame j
 * of the selection goes to rank j mod size; the others are passed over
 * without reading their arrays where the format allows).  Without MPI this is
 * just the windowed stream.  Every frame-wise command reads through it. */
#ifndef MIMAS_CLI_FRAMES_H
#define MIMAS_CLI_FRAMES_H

#include <stddef.h>

#include "cli.h"
#include "parallel.h"

typedef struct cli_frames {
    mimas_reader *r;
    cli_window *window;
    const char *input;   /* for messages: the first input's name */
    int rank, size;
    size_t selected;     /* frames of the window so far, over all ranks */
    size_t position;     /* the window index of the frame returned last (or failing) */
} cli_frames;

void cli_frames_init(cli_frames *s, mimas_reader *r, cli_window *window, const char *input);
/* This rank's next frame: MIMAS_OK (position says which of the window it
 * is), MIMAS_END, or an error (position: the frame it belongs to). */
int cli_frames_next(cli_frames *s, mimas_frame *f, mimas_error *err);

/* The defaults a command takes from the data, decided once: every rank
 * reads its first frame into f; rank 0 calls decide(ctx, f, data, err) on
 * its frame (the first of the selection), which fills n bytes at data, and
 * every rank gets them.  Returns MIMAS_OK with *have set when this rank
 * holds a frame in f to work on (*have 0: none, the loop is over), or a
 * failure: rank 0's (no frame in the time window, decide's), the same on
 * every rank, or this rank's own reading failure (position says where;
 * the ranks agree on it later, as for any frame). */
int cli_frames_first(cli_frames *s, mimas_frame *f,
                     int (*decide)(void *ctx, const mimas_frame *f, void *data,
                                   mimas_error *err),
                     void *ctx, void *data, size_t n, int *have, mimas_error *err);

/* A frame-parallel command whose frames each give a small result that
 * rank 0 uses in frame order (mimas plugs, mimas radial): the defaults from
 * the data decided once (cli_frames_first), then every frame of this rank
 * computed and its result used on rank 0 in the serial order, so that the
 * output is the serial output. */
typedef struct cli_frame_work {
    void *ctx;
    /* rank 0, on the first frame of the selection: fills n bytes at data
     * (called with decide_ctx) */
    int (*decide)(void *ctx, const mimas_frame *f, void *data, mimas_error *err);
    void *decide_ctx;
    void *data;
    size_t n;
    /* every rank, once, with the decided data */
    int (*setup)(void *ctx, const void *data, mimas_error *err);
    /* each frame of this rank (position: its place in the selection) */
    int (*frame)(void *ctx, const mimas_frame *f, size_t position, mimas_bytes *result,
                 mimas_error *err);
    /* rank 0: every frame's result, in frame order */
    mimas_par_sink_fn use;
} cli_frame_work;
/* Runs it over the frames of s; MIMAS_END when every frame was used, else
 * the agreed failure, the same status and message on every rank (a
 * frame's data failure named "INPUT: step N: ..."). */
int cli_frames_run(cli_frames *s, const cli_frame_work *w, const cli_command *cmd,
                   cli_progress *prog, mimas_error *err);

#endif
