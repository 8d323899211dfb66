/* Micro-macro averaging (docs/theory.md §6): frames in, time-averaged fields on a
 * grid out.  Time averages are taken of the primary sums (mass, momentum,
 * momentum flux, contact stress, fabric, ...) and the fields derived from the
 * averages; the spread over frames comes from per-frame fields. */
#ifndef MIMAS_AVERAGE_H
#define MIMAS_AVERAGE_H

#include <stddef.h>
#include <stdint.h>

#include "error.h"
#include "frame.h"
#include "frame_pack.h"
#include "grid.h"
#include "weight.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct mimas_average_options {
    mimas_grid grid;
    int grid_none;            /* one cell: the box */
    mimas_weight weight;
    const int32_t *types;     /* particle types to keep (or to drop with exclude) */
    size_t ntypes;
    int exclude;
    int spread;               /* keep per-frame statistics (standard deviation, error) */
    int threads;              /* OpenMP threads for the deposition (0: OpenMP's default) */
    double diameter;          /* d of the inertial number (0: the cell's mean diameter) */
} mimas_average_options;

typedef struct mimas_average mimas_average;

int mimas_average_create(mimas_average **a, const mimas_average_options *o, mimas_error *err);
int mimas_average_add(mimas_average *a, const mimas_frame *f, mimas_error *err);
size_t mimas_average_frames(const mimas_average *a);
/* The grid with the bounds of the first frame's box filled in. */
const mimas_grid *mimas_average_grid(const mimas_average *a);
/* 1 for --grid none (one cell: the box). */
int mimas_average_grid_none(const mimas_average *a);
/* The threads the average deposits with (its options' threads, or OpenMP's default) */
int mimas_average_threads(const mimas_average *a);
const mimas_weight *mimas_average_weight(const mimas_average *a);
/* Time-averaged fields of every cell (cells x mimas_fields_count() values,
 * cell-major), and if the average keeps the spread, the standard deviation
 * over frames and the number of frames in which each field was defined
 * (sd, count may be NULL; the strain-rate fields have none).  Returns 0: it
 * needs no memory of its own (before 2026-12 it could return -1, out of memory). */
int mimas_average_fields(const mimas_average *a, double *fields, double *sd, double *count);
/* The time-averaged primary sums of a cell: mimas_average_sums_count() values, in the
 * library's own layout, which may change between versions (docs/api.md: use the fields). */
void mimas_average_sums(const mimas_average *a, size_t cell, double *sums);
size_t mimas_average_sums_count(void);
/* The accumulated state (frames, primary sums, per-frame statistics) as
 * bytes, and merging such a state into an average of the same options: for
 * runs split over processes (frames in any order: sums add, the per-frame
 * statistics combine by Chan et al.'s pairwise formula).  The grid stays the
 * one of a's first frame (an average without frames takes the state's). */
int mimas_average_pack(const mimas_average *a, mimas_bytes *out, mimas_error *err);
int mimas_average_merge(mimas_average *a, const unsigned char *data, size_t n,
                        mimas_error *err);

/* Under MPI: merges every rank's average onto rank 0's (collective; the
 * agreed status, MIMAS_OK when fine).  One rank: nothing to do. */
int mimas_average_reduce(mimas_average *a, mimas_error *err);

/* Forgets all frames (the grid is fitted again to the next frame). */
void mimas_average_reset(mimas_average *a);
void mimas_average_free(mimas_average *a);

#ifdef __cplusplus
}
#endif
#endif
