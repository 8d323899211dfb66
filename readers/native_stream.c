/* The native format as a stream backend: frames of several files in order. */
#include <config.h>

#include <stdlib.h>
#include <string.h>

#include "backend.h"
#include "native.h"

typedef struct native_stream {
    const char *const *inputs;
    size_t ninputs, file;
    size_t frame;
    mimas_native *cur;
    size_t total;   /* frames of all inputs, counted at open */
    mimas_parameters params;   /* of all inputs (mimas_parameters_merge) */
} native_stream;

static int probe(const char *path, const char *head, size_t n)
{
    (void)path;
    static const char sig[8] = {'\x89', 'H', 'D', 'F', '\r', '\n', '\x1a', '\n'};
    return n >= 8 && memcmp(head, sig, 8) == 0;
}

static int open_stream(void **state, const char *const *inputs, size_t ninputs,
                       const mimas_reader_options *o, mimas_error *err)
{
    if (o->ncontacts || o->nwalls)
        return mimas_error_set(err, MIMAS_EUSAGE,
                               "%s: a native file holds its own contacts; --contacts and "
                               "--wall-contacts do not apply", inputs[0]);
    native_stream *s = calloc(1, sizeof *s);
    if (!s)
        return mimas_error_set(err, MIMAS_EIO, "out of memory for the native reader");
    s->inputs = inputs;
    s->ninputs = ninputs;
    /* open every file once up front so a bad one is reported before any work */
    for (size_t k = 0; k < ninputs; k++) {
        mimas_native *r = NULL;
        int rc = mimas_native_open(&r, inputs[k], err);
        if (!rc && k == 0)
            s->cur = r;
        if (!rc)
            rc = k == 0 ? mimas_parameters_copy(&s->params, mimas_native_parameters(r), err)
                        : mimas_parameters_merge(&s->params, mimas_native_parameters(r), err);
        if (!rc)
            s->total += mimas_native_frames(r);
        if (k > 0)
            mimas_native_close(r);
        if (rc) {
            mimas_native_close(s->cur);
            mimas_parameters_free(&s->params);
            free(s);
            return rc;
        }
    }
    *state = s;
    return MIMAS_OK;
}

/* Moves to the file holding the next frame; 0 when there is none. */
static int advance(native_stream *s, mimas_error *err)
{
    while (s->cur && s->frame >= mimas_native_frames(s->cur)) {
        mimas_native_close(s->cur);
        s->cur = NULL;
        s->frame = 0;
        if (++s->file < s->ninputs) {
            int rc = mimas_native_open(&s->cur, s->inputs[s->file], err);
            if (rc)
                return rc;
        }
    }
    return s->cur ? MIMAS_OK : MIMAS_END;
}

static int next(void *state, mimas_frame *f, mimas_error *err)
{
    native_stream *s = state;
    int rc = advance(s, err);
    return rc ? rc : mimas_native_read(s->cur, s->frame++, f, err);
}

static int peek(void *state, int64_t *step, double *time, mimas_error *err)
{
    native_stream *s = state;
    int rc = advance(s, err);
    mimas_frame_meta m;
    if (!rc)
        rc = mimas_native_frame_meta(s->cur, s->frame, &m, err);
    if (!rc) {
        *step = m.step;
        *time = m.time;
    }
    return rc;
}

static int skip(void *state, mimas_error *err)
{
    native_stream *s = state;
    int rc = advance(s, err);
    if (!rc)
        s->frame++;
    return rc;
}

static void close_stream(void *state)
{
    native_stream *s = state;
    if (s) {
        mimas_native_close(s->cur);
        mimas_parameters_free(&s->params);
    }
    free(s);
}

static size_t total(void *state)
{
    return ((native_stream *)state)->total;
}

static const mimas_parameters *parameters(void *state)
{
    return &((native_stream *)state)->params;
}

static const char *source(void *state)
{
    const native_stream *s = state;
    return s->inputs[s->file < s->ninputs ? s->file : s->ninputs - 1];
}

const reader_backend reader_native = {"native", "mimas native (HDF5, H5MD 1.1)", probe,
                                      open_stream, next, NULL, close_stream, source, peek, skip,
                                      total, parameters};
