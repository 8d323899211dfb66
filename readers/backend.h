/* What each input format provides to readers/reader.c (one file per format
 * under readers/).  A backend streams frames of one or more inputs. */
#ifndef MIMAS_READER_BACKEND_H
#define MIMAS_READER_BACKEND_H

#include <stddef.h>

#include "error.h"
#include "frame.h"
#include "reader.h"

typedef struct reader_backend {
    const char *name;   /* --format value: "native", "lammps", "mercury" */
    const char *title;  /* shown by mimas info: "LAMMPS/LIGGGHTS dump" */
    /* 1 if a file whose first n bytes (decompressed if gzip) are head looks
     * like this format's main input */
    int (*probe)(const char *path, const char *head, size_t n);
    int (*open)(void **state, const char *const *inputs, size_t ninputs,
                const mimas_reader_options *o, mimas_error *err);
    /* MIMAS_OK with the next frame in f, MIMAS_END, or an error */
    int (*next)(void *state, mimas_frame *f, mimas_error *err);
    size_t (*skipped)(void *state); /* may be NULL */
    void (*close)(void *state);
    /* the file the last frame came from (for messages) */
    const char *(*source)(void *state);
    /* optional, for formats that can do them without reading the frame's
     * arrays (NULL: readers/reader.c reads the frame instead): the step and
     * time of the next frame without consuming it, and passing over it (both
     * or neither) */
    int (*peek)(void *state, int64_t *step, double *time, mimas_error *err);
    int (*skip)(void *state, mimas_error *err);
    /* frames the inputs hold, when the format says (0: unknown); may be NULL */
    size_t (*total)(void *state);
    /* the run parameters of the inputs (may be NULL: the format has none) */
    const mimas_parameters *(*parameters)(void *state);
} reader_backend;

/* Expands '*' patterns in a list of file names (sorted matches); names
 * without '*' are kept.  Free the result with reader_free_names. */
int reader_expand_names(const char *const *in, size_t n, char ***out, size_t *nout,
                        mimas_error *err);
void reader_free_names(char **names, size_t n);

extern const reader_backend reader_native;
extern const reader_backend reader_lammps;
extern const reader_backend reader_mercury;

#endif
