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
