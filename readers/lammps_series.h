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

/* What the columns of a snapshot are, as a per-format parser decided: a
 * target (the parser's enum) and component per column, plus the extra
 * columns (named values kept as they are).  Rebuilt when the header text
 * changes. */
typedef struct dump_col {
    int target;
    int comp;
    size_t extra;
} dump_col;

typedef struct dump_columns {
    char *header;       /* the column names this layout was built from */
    size_t ncols;
    dump_col *cols;
    size_t nextra;
    char (*extra_name)[64];
    int *extra_ncomp;
    size_t *slots, nslots;  /* hash of the extra names: index + 1, 0 free */
} dump_columns;

/* 1 if c was built from this header text. */
int dump_columns_current(const dump_columns *c, const char *header);
/* Frees c and allocates room for the columns of header; ncols is 0. */
int dump_columns_reset(dump_columns *c, const char *header, mimas_error *err);
size_t dump_columns_add_extra(dump_columns *c, const char *name, int ncomp);
/* The extra column of that name, or (size_t)-1 (a hash: headers of 10^5
 * columns take linear time). */
size_t dump_columns_find_extra(const dump_columns *c, const char *name);
/* Makes column col (named name) an extra column: consecutive NAME[1],
 * NAME[2], ... form one extra of that many components (*prev_idx: the
 * index of the previous column, 0 after a column that is not an extra).
 * Sets col->extra and col->comp, leaves col->target to the caller; -1 if
 * the name repeats an earlier extra. */
int dump_columns_extra_column(dump_columns *c, dump_col *col, const char *name, int *prev_idx);
/* Gives the table exactly c's extra columns (kept if they are already those). */
int dump_columns_extras_to(const dump_columns *c, void *tab, const mimas_table_desc *d,
                           mimas_error *err);
void dump_columns_free(dump_columns *c);

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
