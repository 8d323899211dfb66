/* The frames a command works on: the inputs' frames inside the time window
 * (--from/--to/--every), and of those, under MPI, this rank's share (frame j
 * of the selection goes to rank j mod size; the others are passed over
 * without reading their arrays where the format allows).  Without MPI this is
 * just the windowed stream.  Every frame-wise command reads through it. */
#ifndef MIMAS_CLI_FRAMES_H
#define MIMAS_CLI_FRAMES_H

#include <stddef.h>

#include "cli.h"

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

#endif
