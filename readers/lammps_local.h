/* Local dumps of contacts (LIGGGHTS compute pair/gran/local and
 * wall/gran/local, LAMMPS compute pair/local + property/local) into a
 * frame's contacts or wall contacts (docs/readers.md). */
#ifndef MIMAS_LAMMPS_LOCAL_H
#define MIMAS_LAMMPS_LOCAL_H

#include "id_index.h"
#include "lammps_series.h"

typedef struct local_layout {
    int walls;           /* wall/gran/local rather than pair contacts */
    const char *keywords;/* --contact-columns / --wall-columns (may be NULL) */
    void (*notify)(void *ctx, const char *message); /* mimas_reader_options' */
    void *notify_ctx;
    char inferred[512];  /* the keywords told from the column count, or "" */
    int check_pending;   /* the inferred keywords still need checking on data */
    dump_columns c;      /* targets: the enum in lammps_local.c */
    unsigned bits;       /* contact quantities given by columns */
    int derive_point;    /* contact point from positions and radii */
    int derive_overlap;  /* overlap from a distance column */
} local_layout;

/* Parses the rows of the current snapshot of s into f->contacts (or
 * f->walls), resolving ids through index. */
int local_read(dump_series *s, local_layout *l, mimas_frame *f, const mimas_id_index *index,
               mimas_error *err);
/* Reads and drops the rows of the current snapshot. */
int local_skip(dump_series *s, mimas_error *err);
void local_layout_free(local_layout *l);

#endif
