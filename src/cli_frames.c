#include <config.h>

#include "cli_frames.h"

#include "parallel.h"

void cli_frames_init(cli_frames *s, mimas_reader *r, cli_window *window, const char *input)
{
    s->r = r;
    s->window = window;
    s->input = input;
    s->rank = mimas_par_rank();
    s->size = mimas_par_size();
    s->selected = 0;
    s->position = 0;
}

int cli_frames_next(cli_frames *s, mimas_frame *f, mimas_error *err)
{
    for (;;) {
        s->position = s->selected;
        if (s->size == 1) {
            /* serial: read the frame itself, no look-ahead needed */
            int rc = mimas_reader_next(s->r, f, err);
            if (rc)
                return rc;
            int take = cli_window_take(s->window, f, s->input, err);
            if (take < 0)
                return MIMAS_EUSAGE;
            if (take) {
                s->selected++;
                return MIMAS_OK;
            }
            continue;
        }
        mimas_frame head; /* only step and time: what the window looks at */
        head.step = 0;
        head.time = 0;
        int rc = mimas_reader_peek(s->r, &head.step, &head.time, err);
        if (rc)
            return rc;
        int take = cli_window_take(s->window, &head, s->input, err);
        if (take < 0)
            return MIMAS_EUSAGE;
        if (take && s->selected++ % (size_t)s->size == (size_t)s->rank)
            return mimas_reader_next(s->r, f, err);
        rc = mimas_reader_skip(s->r, err);
        if (rc)
            return rc;
    }
}

int cli_frames_first(cli_frames *s, mimas_frame *f,
                     int (*decide)(void *ctx, const mimas_frame *f, void *data,
                                   mimas_error *err),
                     void *ctx, void *data, size_t n, int *have, mimas_error *err)
{
    int own = cli_frames_next(s, f, err);
    *have = own == MIMAS_OK;
    int root = s->rank == 0, status = own;
    if (root && own == MIMAS_OK)
        status = decide(ctx, f, data, err);
    if (root && own == MIMAS_END)
        status = mimas_error_set(err, MIMAS_EDATA, "%s: no frame in the selected time range",
                                 s->input);
    mimas_error mine = *err;
    int shared = mimas_par_share(root ? status : MIMAS_OK, data, n, err);
    if (shared)
        return shared;
    if (own != MIMAS_OK && own != MIMAS_END) {
        *err = mine; /* this rank's reading failure: agreed on with the others' later */
        return own;
    }
    return MIMAS_OK;
}
