/* What the tube commands (mimas plugs, mimas radial) share: their tables
 * and the decision they take on the first frame.
 *
 * A table is written row by
 * row to a text stream through the shared table writer (cli_table.h: exact
 * numbers, --csv, --digits, --units-header) and/or to a group of an HDF5
 * file (mimas_otable of averaging/plugs_output.h): one column list for
 * both. */
#ifndef MIMAS_CLI_TUBE_H
#define MIMAS_CLI_TUBE_H

#include <stdio.h>

#include "cli_table.h"
#include "plugs_output.h"
#include "tube.h"

typedef struct cli_otable {
    cli_table text;
    int has_text;
    mimas_otable *h5;
    const mimas_ocolumn *cols;
    size_t ncols;
} cli_otable;

/* fp: the text stream (NULL: none), with the options o; h5: the HDF5 file
 * (NULL: none) and the group of the table there.  Writes the header. */
int cli_otable_open(cli_otable *t, FILE *fp, const cli_table_options *o, mimas_h5out *h5,
                    const char *group, const mimas_ocolumn *cols, size_t ncols,
                    mimas_error *err);
/* One row: v[c] for number columns, text[c] for text columns (text may be
 * NULL without text columns). */
int cli_otable_row(cli_otable *t, const double *v, const char *const *text, mimas_error *err);
/* Flushes and frees (a table never opened, zeroed, is fine). */
int cli_otable_close(cli_otable *t, mimas_error *err);

/* The options that fix the geometry, for the first frame. */
typedef struct cli_tube_pick {
    const char *axis;        /* --axis, or NULL */
    double radius;           /* --tube-radius, or 0 */
    const cli_types *types;  /* --types / --exclude-types */
} cli_tube_pick;
/* A cli_frame_work decide function (cli_frames.h): ctx a cli_tube_pick,
 * data a mimas_tube_setup (mimas_tube_setup_from on the frame). */
int cli_tube_decide(void *ctx, const mimas_frame *f, void *data, mimas_error *err);

#endif
