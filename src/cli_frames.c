#include <config.h>

#include "cli_frames.h"

#include <stdint.h>

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

int cli_frames_run(cli_frames *s, const cli_frame_work *w, const cli_command *cmd,
                   cli_progress *prog, mimas_error *err)
{
    mimas_par_ordered *order = NULL;
    int status = mimas_par_ordered_open(&order, w->use, w->ctx, err);
    status = mimas_par_agree(status, SIZE_MAX, err);
    if (status)
        return status;
    mimas_frame f;
    mimas_frame_init(&f);
    mimas_bytes result = {0};
    int have = 0;
    status = cli_frames_first(s, &f, w->decide, w->decide_ctx, w->data, w->n, &have, err);
    if (!status)
        status = w->setup(w->ctx, w->data, err);
    if (!status && !have)
        status = MIMAS_END;
    while (status == MIMAS_OK) {
        status = w->frame(w->ctx, &f, s->position, &result, err);
        if (status && status != MIMAS_EIO && status != MIMAS_EUSAGE)
            mimas_error_prefix(err, "%s: step %lld", s->input, (long long)f.step);
        if (!status)
            status = mimas_par_ordered_put(order, s->position, &result, err);
        cli_progress_frame(prog, cmd, s->position + 1, (long long)f.step, f.time);
        if (!status)
            status = cli_frames_next(s, &f, err);
    }
    status = mimas_par_ordered_finish(order, status, s->position, err);
    mimas_par_ordered_free(order);
    mimas_bytes_free(&result);
    mimas_frame_free(&f);
    return status;
}
