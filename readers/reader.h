/* One reader interface for every input format (docs/readers.md, docs/api.md):
 * open a list of inputs, take frames one at a time, close.  The format is
 * detected from the content unless options say otherwise. */
#ifndef MIMAS_READER_H
#define MIMAS_READER_H

#include <stddef.h>
#include <stdint.h>

#include "error.h"
#include "frame.h"
#include "parameters.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct mimas_reader mimas_reader;

typedef struct mimas_reader_options {
    const char *format;              /* NULL: detect; "native", "lammps", "mercury" */
    const char *const *contacts;     /* contact files (LAMMPS/LIGGGHTS local dumps, .fstat) */
    size_t ncontacts;
    const char *const *walls;        /* wall-contact files (LIGGGHTS wall/gran/local) */
    size_t nwalls;
    const char *contact_columns;     /* the keywords a LIGGGHTS compute was given, or
                                        LAMMPS pair/local names (see docs/readers.md) */
    const char *wall_columns;
    double density;                  /* particle density for masses (0: none given) */
    double timestep;                 /* dt: time = step * dt for dumps without ITEM: TIME
                                        (0: such frames have time NaN, "unknown") */
    int allow_missing_contacts;      /* skip frames that lack contact data */
    /* told what the reader found out by itself (e.g. the columns of a
     * LIGGGHTS local dump inferred from their count), one line naming the
     * file; NULL: nobody is told */
    void (*notify)(void *ctx, const char *message);
    void *notify_ctx;
} mimas_reader_options;

void mimas_reader_options_default(mimas_reader_options *o);

/* Opens the inputs (several files, or LAMMPS series given as files or a '*'
 * pattern, are read in timestep order).  The strings of o must outlive r. */
int mimas_reader_open(mimas_reader **r, const char *const *inputs, size_t ninputs,
                      const mimas_reader_options *o, mimas_error *err);
/* Fills f with the next frame: MIMAS_OK, MIMAS_END after the last frame, or
 * an error whose message names the file and line. */
int mimas_reader_next(mimas_reader *r, mimas_frame *f, mimas_error *err);
/* The step and time of the next frame without taking it (MIMAS_OK,
 * MIMAS_END or an error), and passing over the next frame.  Native files do
 * both without reading the frame's arrays; other formats read the frame (so
 * a following mimas_reader_next costs nothing). */
int mimas_reader_peek(mimas_reader *r, int64_t *step, double *time, mimas_error *err);
int mimas_reader_skip(mimas_reader *r, mimas_error *err);

/* The detected format's name ("mimas native", "LAMMPS dump", "MercuryDPM"). */
const char *mimas_reader_format(const mimas_reader *r);
/* Frames dropped so far because their contact data were missing
 * (only with allow_missing_contacts). */
size_t mimas_reader_skipped(const mimas_reader *r);
/* The number of frames the inputs hold, when the format records it (native
 * files: counted at open), else 0 (dumps are not read ahead). */
size_t mimas_reader_total(const mimas_reader *r);
/* The run parameters the inputs record (native files: /parameters/scenario,
 * docs/format.md); empty for formats without them.  A parameter the inputs
 * disagree on is MIXED.  Valid until the reader is closed. */
const mimas_parameters *mimas_reader_parameters(const mimas_reader *r);
void mimas_reader_close(mimas_reader *r);

#ifdef __cplusplus
}
#endif
#endif
