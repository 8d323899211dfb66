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

#include "axial_profile.h"
#include "cli.h"
#include "cli_table.h"
#include "plugs.h"
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

/* The options both tube commands take: the geometry (fixed on the first frame), the
 * particles, and the slices and plug criterion of plug detection (mimas radial
 * --in-plugs finds plugs exactly as mimas plugs does).  Zeros: the defaults. */
typedef struct cli_tube_args {
    const char *axis;        /* --axis, or NULL */
    double radius;           /* --tube-radius, or 0 */
    double s0, s1;           /* --range */
    int has_range;
    double slice, diameter;  /* --slice, --diameter, or 0 */
    unsigned temperature;    /* --temperature-components */
    double threshold;        /* --threshold (cli_tube_args_init: 0.6) */
    double min_length;       /* --min-length, or 0 */
    cli_types types;         /* --types / --exclude-types */
} cli_tube_args;

/* Those options, which every tube command declares first in its option table, in
 * this order (their indices 0 .. CLI_TUBE_NOPTIONS - 1 are the keys of
 * cli_tube_option). */
#define CLI_TUBE_OPTIONS                                                                        \
    {"axis", 0, "X0,Y0,Z0,DX,DY,DZ", "tube axis: a point at s = 0 and the direction of +s "      \
                                     "(default: the input's tube, else the z axis)"},          \
        {"tube-radius", 0, "R", "inner tube radius (m; default: the input's tube)"},            \
        {"range", 0, "S0:S1", "axial range of the slices of plug detection (m; default: the "   \
                              "tube, else the particles of the first frame)"},                 \
        {"slice", 0, "W", "slice thickness of plug detection (m; default: half the diameter)"}, \
        {"diameter", 0, "D", "particle diameter d, the unit of lengths given in diameters "     \
                             "(default: the mean of the first frame)"},                        \
        {"temperature-components", 0, "LIST", "velocity components of the granular "            \
                                              "temperature: a comma list of s, r, phi "       \
                                              "(default all)"},                                \
        {"threshold", 0, "P", "porosity below which a slice belongs to a plug (default 0.6)"},  \
        {"min-length", 0, "L", "shortest plug (m; default one diameter)"},                     \
        {"types", 0, "L", "use only particles of these types (comma list)"},                   \
        {"exclude-types", 0, "L", "drop particles of these types (e.g. glued wall particles; "  \
                                  "their contacts become wall contacts of the others)"}
enum {
    CLI_TUBE_AXIS, CLI_TUBE_RADIUS, CLI_TUBE_RANGE, CLI_TUBE_SLICE, CLI_TUBE_DIAMETER,
    CLI_TUBE_TEMP, CLI_TUBE_THRESHOLD, CLI_TUBE_MINLEN, CLI_TUBE_TYPES, CLI_TUBE_EXCLUDE,
    CLI_TUBE_NOPTIONS
};

void cli_tube_args_init(cli_tube_args *t);
/* Option key (CLI_TUBE_*) of CLI_TUBE_OPTIONS with its argument; prints the usage error
 * and returns 1 on a bad argument. */
int cli_tube_option(const cli_command *cmd, cli_tube_args *t, int key, const char *arg);

/* A cli_frame_work decide function (cli_frames.h): ctx a cli_tube_args, data a
 * mimas_tube_setup (mimas_tube_setup_from on the frame). */
int cli_tube_decide(void *ctx, const mimas_frame *f, void *data, mimas_error *err);

/* Plug detection from the options and the first frame's set-up ts: the axial
 * profiles' options ao (geometry, slices over --range or the tube, particles,
 * temperature components; no flow rate) and the plug criterion po; *d the particle diameter in
 * use, [*s0, *s1] the range. */
int cli_tube_plug_setup(const cli_tube_args *t, const mimas_tube_setup *ts,
                        mimas_axial_options *ao, mimas_plug_options *po, double *d, double *s0,
                        double *s1, mimas_error *err);

#endif
