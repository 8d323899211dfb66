/* The mimas native file format (docs/format.md): H5MD 1.1 particles plus the
 * /contacts extension, one frame appended at a time. */
#ifndef MIMAS_NATIVE_H
#define MIMAS_NATIVE_H

#include <stddef.h>
#include <stdint.h>

#include "error.h"
#include "frame.h"
#include "parameters.h"

#ifdef __cplusplus
extern "C" {
#endif

#define MIMAS_NATIVE_VERSION_MAJOR 1
#define MIMAS_NATIVE_VERSION_MINOR 1

/* ---- writer ---- */
typedef struct mimas_writer mimas_writer;

typedef struct mimas_writer_options {
    int deflate;        /* gzip level 0..9 for per-particle and per-contact data (default 1) */
    int atomic;         /* write under a temporary name, rename on close (default 0) */
    int triclinic;      /* store edge vectors even if the first box is orthogonal */
    const char *author; /* H5MD author name (default: $USER or "unknown") */
    const char *provenance; /* free text, e.g. the command line (may be NULL) */
    int xdmf;           /* on close, write the XDMF sidecar (FILE.xdmf) for ParaView */
} mimas_writer_options;

void mimas_writer_options_default(mimas_writer_options *o);
/* Creates (truncates) the file.  With atomic, nothing appears at path until close. */
int mimas_writer_open(mimas_writer **w, const char *path, const mimas_writer_options *o,
                      mimas_error *err);
/* Appends one frame.  Frames are committed (flushed) in batches: the first
 * at once, later ones when the frames since the last commit hold about as
 * much data as a commit writes of metadata, or a second after the last
 * commit, so the cost of a frame is proportional to its size.  A crash
 * leaves a file that reads back every committed frame.  Every frame must
 * carry the same set of quantities as the first. */
int mimas_writer_append(mimas_writer *w, const mimas_frame *f, mimas_error *err);
/* Commits the frames appended so far now. */
int mimas_writer_flush(mimas_writer *w, mimas_error *err);
/* Number of frames appended so far. */
size_t mimas_writer_frames(const mimas_writer *w);
/* Closes the file (renaming it into place in atomic mode) and frees w. */
int mimas_writer_close(mimas_writer *w, mimas_error *err);
/* Closes and deletes the file being written (no partial output); frees w. */
void mimas_writer_abort(mimas_writer *w);

/* Run parameters and per-frame observables (docs/format.md). */
/* Writes the parameters as the attributes of /parameters/GROUP (once per
 * group, before the first frame; "scenario" for the keys of mimas
 * simulate's scenario file). */
int mimas_writer_parameters(mimas_writer *w, const char *group, const mimas_parameters *ps,
                            mimas_error *err);
/* A scalar per frame, the H5MD observable /observables/all/NAME. */
typedef struct mimas_observable {
    const char *name;   /* e.g. "kinetic_energy" */
    const char *unit;   /* SI unit, or NULL */
    double value;
} mimas_observable;
/* Sets the observables of the frame the next mimas_writer_append writes.
 * A file has observables in every frame or in none: the first frame fixes
 * their names, and a later frame without them (or with others) is an error. */
int mimas_writer_observe(mimas_writer *w, const mimas_observable *obs, size_t n,
                         mimas_error *err);

/* ---- reader (random access) ---- */
typedef struct mimas_native mimas_native;

int mimas_native_open(mimas_native **r, const char *path, mimas_error *err);
size_t mimas_native_frames(const mimas_native *r);
/* Reads frame k into f (reusing its memory); reads nothing of other frames. */
int mimas_native_read(mimas_native *r, size_t k, mimas_frame *f, mimas_error *err);
/* Step, time, box and row counts of frame k without reading its arrays. */
typedef struct mimas_frame_meta {
    int64_t step;
    double time;
    mimas_box box;
    size_t n_particles, n_contacts, n_walls;
} mimas_frame_meta;
int mimas_native_frame_meta(mimas_native *r, size_t k, mimas_frame_meta *m, mimas_error *err);
/* Which tables the file has. */
int mimas_native_has_contacts(const mimas_native *r);
int mimas_native_has_walls(const mimas_native *r);
const char *mimas_native_creator(const mimas_native *r);
/* The run parameters of /parameters/scenario (empty if the file has none). */
const mimas_parameters *mimas_native_parameters(const mimas_native *r);
/* The per-frame observables of /observables/all other than particle_count:
 * their number, the name and unit ("" if none) of observable i, and n values
 * of it from frame k0 on. */
size_t mimas_native_observables(const mimas_native *r);
const char *mimas_native_observable_name(const mimas_native *r, size_t i, const char **unit);
int mimas_native_observable_read(mimas_native *r, size_t i, size_t k0, size_t n, double *values,
                                 mimas_error *err);
/* The per-particle datasets as stored (for sidecars such as XDMF): name
 * (the element under /particles/all), the stored number type, components and
 * the dataset's extent (frames [including any not yet committed], slots
 * [, components]). */
typedef struct mimas_native_column {
    const char *name;
    int is_float;       /* floating point, else integer */
    int precision;      /* bytes per value */
    int ncomp;
    int rank;
    unsigned long long dims[3];
} mimas_native_column;
size_t mimas_native_particle_columns(const mimas_native *r);
void mimas_native_particle_column(const mimas_native *r, size_t k, mimas_native_column *c);
void mimas_native_close(mimas_native *r);

#ifdef __cplusplus
}
#endif
#endif
