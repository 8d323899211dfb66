/* LAMMPS/LIGGGHTS text dumps as a series of snapshots: the files of a series
 * in timestep order, each snapshot's header (timestep, time, count, box,
 * column names), then its rows.  Shared by per-atom and local dumps. */
#ifndef MIMAS_LAMMPS_SERIES_H
#define MIMAS_LAMMPS_SERIES_H

#include <stddef.h>
#include <stdint.h>

#include "error.h"
#include "frame.h"
#include "text_input.h"

typedef struct dump_header {
    int64_t step;
    double time;
    int has_time;
    size_t count;       /* NUMBER OF ATOMS or NUMBER OF ENTRIES */
    int entries;        /* a local dump (ITEM: ENTRIES) */
    mimas_box box;
    char *columns;      /* the names after ITEM: ATOMS / ITEM: ENTRIES */
    size_t columns_cap;
} dump_header;

typedef struct dump_series {
    char **paths;
    size_t npaths, cur;
    text_input in;
    int is_open;
    int have_last;
    int64_t last_step;
    dump_header h;
} dump_series;

/* Takes the file names (ownership passes to the series) and orders them by
 * their first timestep. */
int dump_series_open(dump_series *s, char **paths, size_t n, mimas_error *err);
/* Reads the next snapshot header: MIMAS_OK, MIMAS_END, or an error.  Steps
 * must increase strictly across the series. */
int dump_series_header(dump_series *s, mimas_error *err);
/* The next row of the current snapshot (k counts from 0 for the message). */
char *dump_series_row(dump_series *s, size_t k, int *rc, mimas_error *err);
void dump_series_close(dump_series *s);

#endif
