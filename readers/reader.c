/* The reader interface: picks the backend (by --format, else by the content
 * of the first input) and passes frames through. */
#include <config.h>

#include "reader.h"

#include <glob.h>
#include <stdlib.h>
#include <string.h>
#include <zlib.h>

#include "backend.h"

static const reader_backend *const backends[] = {&reader_native, &reader_lammps,
                                                 &reader_mercury};
#define NBACKENDS (sizeof backends / sizeof backends[0])

struct mimas_reader {
    const reader_backend *be;
    void *state;
    char **inputs;   /* after '*' expansion */
    size_t ninputs;
    mimas_reader_options opt;
    mimas_frame ahead;   /* a frame read by peek for a format that cannot peek */
    int has_ahead;
};

void mimas_reader_options_default(mimas_reader_options *o)
{
    memset(o, 0, sizeof *o);
}

int reader_expand_names(const char *const *in, size_t n, char ***out, size_t *nout,
                        mimas_error *err)
{
    char **names = NULL;
    size_t count = 0;
    for (size_t k = 0; k < n; k++) {
        glob_t g;
        memset(&g, 0, sizeof g);
        int globbed = strchr(in[k], '*') && glob(in[k], 0, NULL, &g) == 0;
        size_t add = globbed ? g.gl_pathc : 1;
        char **grown = realloc(names, (count + add) * sizeof *grown);
        int ok = grown != NULL;
        if (grown)
            names = grown;
        for (size_t m = 0; ok && m < add; m++) {
            char *name = strdup(globbed ? g.gl_pathv[m] : in[k]);
            ok = name != NULL;
            if (name)
                names[count++] = name;
        }
        if (globbed)
            globfree(&g);
        if (!ok) {
            reader_free_names(names, count);
            return mimas_error_set(err, MIMAS_EIO, "out of memory");
        }
    }
    *out = names;
    *nout = count;
    return MIMAS_OK;
}

void reader_free_names(char **names, size_t n)
{
    for (size_t k = 0; k < n; k++)
        free(names[k]);
    free(names);
}

/* The first bytes of a file, decompressed if it is gzip. */
static int peek(const char *path, char *head, size_t cap, size_t *n)
{
    gzFile gz = gzopen(path, "rb");
    if (!gz)
        return -1;
    int got = gzread(gz, head, (unsigned)cap);
    gzclose(gz);
    *n = got > 0 ? (size_t)got : 0;
    return 0;
}

static int detect(mimas_reader *r, mimas_error *err)
{
    const char *path = r->inputs[0];
    if (r->opt.format) {
        for (size_t k = 0; k < NBACKENDS; k++)
            if (!strcmp(r->opt.format, backends[k]->name)) {
                r->be = backends[k];
                return MIMAS_OK;
            }
        return mimas_error_set(err, MIMAS_EUSAGE,
                               "unknown format '%s' (native, lammps or mercury)", r->opt.format);
    }
    char head[4096];
    size_t n;
    /* HDF5 first, on the raw bytes (gzread would pass them through anyway) */
    if (peek(path, head, sizeof head - 1, &n) != 0)
        return mimas_error_set(err, MIMAS_EDATA, "%s: cannot open", path);
    if (n == 0)
        return mimas_error_set(err, MIMAS_EDATA, "%s: empty file", path);
    head[n] = '\0';
    for (size_t k = 0; k < NBACKENDS; k++)
        if (backends[k]->probe(path, head, n)) {
            r->be = backends[k];
            return MIMAS_OK;
        }
    return mimas_error_set(err, MIMAS_EDATA,
                           "%s:1: not a format mimas reads (native HDF5, LAMMPS/LIGGGHTS dump, "
                           "MercuryDPM .data); --format names one", path);
}

void mimas_reader_close(mimas_reader *r)
{
    if (!r)
        return;
    if (r->be && r->state)
        r->be->close(r->state);
    reader_free_names(r->inputs, r->ninputs);
    mimas_frame_free(&r->ahead);
    free(r);
}

int mimas_reader_open(mimas_reader **out, const char *const *inputs, size_t ninputs,
                      const mimas_reader_options *o, mimas_error *err)
{
    *out = NULL;
    if (ninputs == 0)
        return mimas_error_set(err, MIMAS_EUSAGE, "no input file");
    mimas_reader *r = calloc(1, sizeof *r);
    if (!r)
        return mimas_error_set(err, MIMAS_EIO, "out of memory");
    if (o)
        r->opt = *o;
    mimas_frame_init(&r->ahead);
    if (r->opt.density < 0 || r->opt.timestep < 0) {
        free(r);
        return mimas_error_set(err, MIMAS_EUSAGE, "density and time step must be positive");
    }
    int rc = reader_expand_names(inputs, ninputs, &r->inputs, &r->ninputs, err);
    if (!rc)
        rc = detect(r, err);
    if (!rc)
        rc = r->be->open(&r->state, (const char *const *)r->inputs, r->ninputs, &r->opt, err);
    if (rc) {
        r->state = NULL;
        mimas_reader_close(r);
        return rc;
    }
    *out = r;
    return MIMAS_OK;
}

int mimas_reader_next(mimas_reader *r, mimas_frame *f, mimas_error *err)
{
    if (r->has_ahead) {
        /* hand over the frame read ahead; f's memory is kept for the next one */
        mimas_frame t = *f;
        *f = r->ahead;
        r->ahead = t;
        r->has_ahead = 0;
        return MIMAS_OK;
    }
    return r->be->next(r->state, f, err);
}

int mimas_reader_peek(mimas_reader *r, int64_t *step, double *time, mimas_error *err)
{
    if (!r->has_ahead && r->be->peek)
        return r->be->peek(r->state, step, time, err);
    if (!r->has_ahead) {
        int rc = r->be->next(r->state, &r->ahead, err);
        if (rc)
            return rc;
        r->has_ahead = 1;
    }
    *step = r->ahead.step;
    *time = r->ahead.time;
    return MIMAS_OK;
}

int mimas_reader_skip(mimas_reader *r, mimas_error *err)
{
    if (r->has_ahead) {
        r->has_ahead = 0;
        return MIMAS_OK;
    }
    if (r->be->skip)
        return r->be->skip(r->state, err);
    return r->be->next(r->state, &r->ahead, err);
}

const char *mimas_reader_format(const mimas_reader *r)
{
    return r->be->title;
}

size_t mimas_reader_skipped(const mimas_reader *r)
{
    return r->be->skipped ? r->be->skipped(r->state) : 0;
}

const mimas_parameters *mimas_reader_parameters(const mimas_reader *r)
{
    static const mimas_parameters none = {0, 0, NULL};
    return r->be->parameters ? r->be->parameters(r->state) : &none;
}
