/* mimas average: continuum fields on a grid from any input (docs/theory.md §6). */
#include <config.h>

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "average.h"
#include "commands.h"
#include "output_h5.h"
#include "fields.h"
#include "reader.h"

static const cli_option options[] = {
    {"grid", 0, "SPEC", "none, x=LO:HI:N[,y=..][,z=..], or r=LO:HI:N[,phi=LO:HI:N][,z=LO:HI:N]"},
    {"weight", 0, "SPEC", "bins (exact overlaps), bins:center, gauss:w=W[,cutoff=C], lucy:c=C, "
                          "shepard:w=W[,cutoff=C], voronoi (per-particle values of mimas "
                          "voronoi -o, by the centre's cell), voronoi:w=W[,cutoff=C] (by a "
                          "Gaussian)"},
    {"fields", 0, "LIST", "fields to write (comma list; 'stress' selects stress_*; default all)"},
    {"axis", 0, "X0,Y0,Z0,DX,DY,DZ", "axis of cylindrical grids (default: z through the origin)"},
    {"from", 0, "T0", "first time to use (s)"},
    {"to", 0, "T1", "last time to use (s)"},
    {"every", 0, "K", "use every K-th frame of those selected"},
    {"types", 0, "L", "use only particles of these types (comma list)"},
    {"exclude-types", 0, "L", "drop particles of these types (e.g. glued wall particles; their "
                              "contacts become wall contacts of the others)"},
    {"errors", 0, NULL, "add NAME_sem columns: the standard error over frames"},
    {"per-frame", 0, NULL, "also write each frame's fields (TSV: step and time columns; HDF5: "
                           "/frames)"},
    {"output", 'o', "FIELDS.h5", "write the fields to HDF5 (mean, standard deviation, frame "
                                 "count; with an XDMF sidecar FIELDS.xdmf for ParaView)"},
    {"tsv", 0, "FILE", "write the table to FILE, or - for standard output (the default "
                       "without -o)"},
    {"threads", 0, "N", "OpenMP threads (default: OMP_NUM_THREADS or all cores)"},
    {"diameter", 0, "D", "particle diameter for the inertial number (default: each cell's "
                         "mean diameter)"},
    {"list-fields", 0, NULL, "print the fields with their units and definitions (Markdown) and "
                             "exit"},
};

enum { O_GRID, O_WEIGHT, O_FIELDS, O_AXIS, O_FROM, O_TO, O_EVERY, O_TYPES, O_EXCLUDE,
       O_ERRORS, O_PER_FRAME, O_OUTPUT, O_TSV, O_THREADS, O_DIAMETER, O_LIST };

typedef struct average_args {
    const cli_command *cmd;
    const char *grid, *weight, *fields, *axis, *tsv, *output;
    cli_window window;
    double diameter;
    int errors;
    int threads;
    int32_t types[64];
    size_t ntypes;
    int exclude, types_given, list, per_frame;
} average_args;

static int parse_types(average_args *a, const char *arg, const char *opt)
{
    if (a->types_given)
        return cli_fail(a->cmd, 1, "--types and --exclude-types exclude each other");
    a->types_given = 1;
    return cli_parse_types(a->cmd, opt, arg, a->types, 64, &a->ntypes);
}

static int on_option(void *ctx, size_t opt, const char *arg)
{
    average_args *a = ctx;
    switch (opt) {
    case O_GRID: a->grid = arg; return 0;
    case O_WEIGHT: a->weight = arg; return 0;
    case O_FIELDS: a->fields = arg; return 0;
    case O_AXIS: a->axis = arg; return 0;
    case O_FROM:
    case O_TO: return cli_window_time(a->cmd, &a->window, opt == O_FROM, arg);
    case O_EVERY:
        if (cli_parse_long(arg, &a->window.every) || a->window.every < 1)
            return cli_fail(a->cmd, 1, "--every needs a positive whole number, not '%s'", arg);
        return 0;
    case O_TYPES: return parse_types(a, arg, "types");
    case O_EXCLUDE: a->exclude = 1; return parse_types(a, arg, "exclude-types");
    case O_ERRORS: a->errors = 1; return 0;
    case O_PER_FRAME: a->per_frame = 1; return 0;
    case O_TSV: a->tsv = arg; return 0;
    case O_OUTPUT: a->output = arg; return 0;
    case O_DIAMETER:
        if (cli_parse_double(arg, &a->diameter) || !(a->diameter > 0))
            return cli_fail(a->cmd, 1, "--diameter needs a positive length, not '%s'", arg);
        return 0;
    case O_LIST: a->list = 1; return 0;
    case O_THREADS: return cli_parse_threads(a->cmd, arg, &a->threads);
    }
    return 1;
}

/* Which derived columns to write: all that exist on this grid, or those the
 * list names (a name selects a column, or the group NAME_*). */
static int choose_fields(average_args *a, int cyl, unsigned char *want)
{
    size_t nf = mimas_fields_count();
    for (size_t k = 0; k < nf; k++)
        want[k] = !a->fields && mimas_field_name(k, cyl) != NULL;
    if (!a->fields)
        return 0;
    char *text = strdup(a->fields), *save = NULL;
    int rc = 0;
    for (char *tok = strtok_r(text, ",", &save); tok && !rc; tok = strtok_r(NULL, ",", &save)) {
        int exact = 0, any = 0;
        for (size_t k = 0; k < nf; k++) {
            const char *n = mimas_field_name(k, cyl);
            if (n && !strcmp(n, tok))
                exact = 1, want[k] = 1, any = 1;
        }
        size_t len = strlen(tok);
        for (size_t k = 0; !exact && k < nf; k++) {
            const char *n = mimas_field_name(k, cyl);
            if (n && !strncmp(n, tok, len) && n[len] == '_')
                want[k] = 1, any = 1;
        }
        if (!any)
            rc = cli_fail(a->cmd, 1, "unknown field '%s' on a %s grid (see docs/fields.md)", tok,
                          cyl ? "cylindrical" : "Cartesian");
    }
    free(text);
    return rc;
}

/* Full precision; "nan" where a field is undefined (docs/fields.md). */
static void print_value(FILE *out, const char *sep, double v)
{
    if (isnan(v))
        fprintf(out, "%snan", sep);
    else
        fprintf(out, "%s%.17g", sep, v);
}

static void write_header(FILE *out, const mimas_grid *g, int grid_none, int cyl,
                         const unsigned char *want, int errors, int per_frame)
{
    const char *sep = "";
    if (per_frame) {
        fprintf(out, "step\ttime");
        sep = "\t";
    }
    for (int d = 0; d < 3 && !grid_none; d++)
        if (g->gridded[d]) {
            fprintf(out, "%s%s", sep, mimas_grid_coord_name(g, d));
            sep = "\t";
        }
    for (size_t k = 0; k < mimas_fields_count(); k++) {
        if (!want[k])
            continue;
        fprintf(out, "%s%s", sep, mimas_field_name(k, cyl));
        sep = "\t";
        if (errors)
            fprintf(out, "\t%s_sem", mimas_field_name(k, cyl));
    }
    fputc('\n', out);
}

/* One row per cell; with frame (not NULL) the rows start with its step and time. */
static int write_rows(FILE *out, const mimas_average *avg, int grid_none,
                      const unsigned char *want, int errors, const mimas_frame *frame)
{
    const mimas_grid *g = mimas_average_grid(avg);
    size_t nf = mimas_fields_count();
    size_t cells = grid_none ? 1 : mimas_grid_cells(g);
    double *mean = malloc(cells * nf * sizeof *mean), *sd = malloc(cells * nf * sizeof *sd),
           *count = malloc(cells * nf * sizeof *count);
    int rc = mean && sd && count ? mimas_average_fields(avg, mean, sd, count) : -1;
    for (size_t cell = 0; !rc && cell < cells; cell++) {
        double ctr[3];
        if (!grid_none)
            mimas_grid_cell_centre(g, cell, ctr);
        const char *sep = "";
        if (frame) {
            fprintf(out, "%lld", (long long)frame->step);
            print_value(out, "\t", frame->time);
            sep = "\t";
        }
        for (int d = 0; d < 3 && !grid_none; d++)
            if (g->gridded[d]) {
                print_value(out, sep, ctr[d]);
                sep = "\t";
            }
        const double *m = &mean[cell * nf], *s = &sd[cell * nf], *n = &count[cell * nf];
        for (size_t k = 0; k < nf; k++) {
            if (!want[k])
                continue;
            print_value(out, sep, m[k]);
            sep = "\t";
            if (errors)
                print_value(out, sep, n[k] > 1 ? s[k] / sqrt(n[k]) : NAN);
        }
        fputc('\n', out);
    }
    free(mean);
    free(sd);
    free(count);
    return rc || ferror(out) ? -1 : 0;
}

/* The field table as docs/fields.md shows it. */
static void list_fields(void)
{
    printf("| field (Cartesian) | field (cylindrical) | unit | definition |\n|---|---|---|---|\n");
    for (size_t k = 0; k < mimas_fields_count(); k++) {
        const mimas_field_desc *f = mimas_field(k);
        const char *c = mimas_field_name(k, 0), *y = mimas_field_name(k, 1);
        printf("| %s | %s | %s | %s |\n", c ? c : "-", y ? y : "-", f->unit, f->meaning);
    }
}

static int run(const cli_command *cmd, int argc, char **argv)
{
    average_args a = {0};
    a.cmd = cmd;
    cli_inputs in = {0};
    int first;
    int rc = cli_parse(cmd, argc, argv, on_option, &a, &in, &first);
    if (!rc && a.list) {
        list_fields();
        cli_inputs_free(&in);
        return 0;
    }
    if (!rc && (!a.grid || !a.weight))
        rc = cli_fail(cmd, 1, "--grid and --weight are required (see mimas average --help)");
    mimas_average_options o;
    memset(&o, 0, sizeof o);
    mimas_error err;
    if (!rc && (mimas_grid_parse(&o.grid, a.grid, a.axis, &err) ||
                mimas_weight_parse(&o.weight, a.weight, &err)))
        rc = cli_fail(cmd, 1, "%s", err.msg);
    o.grid_none = a.grid && !strcmp(a.grid, "none");
    o.types = a.types;
    o.ntypes = a.ntypes;
    o.exclude = a.exclude;
    o.spread = a.errors || a.output; /* the HDF5 file always has the spread */
    o.threads = a.threads;
    o.diameter = a.diameter;
    int cyl = o.grid.kind == MIMAS_GRID_CYLINDRICAL && !o.grid_none;
    unsigned char want[128];
    if (!rc)
        rc = choose_fields(&a, cyl, want);
    mimas_reader *r = NULL;
    if (!rc)
        rc = cli_open_inputs(cmd, &in, argc, argv, first, &r);
    mimas_average *avg = NULL;
    if (!rc && mimas_average_create(&avg, &o, &err))
        rc = cli_fail(cmd, mimas_exit_status(err.code), "%s", err.msg);
    if (rc) {
        mimas_reader_close(r);
        cli_inputs_free(&in);
        return rc < 0 ? 0 : rc;
    }
    /* outputs: the table (a temporary name renamed at the end, or standard
     * output) unless only -o was asked for; the HDF5 file */
    cli_output table = {0};
    int status = MIMAS_OK;
    if (a.tsv || !a.output)
        status = cli_output_open(&table, a.tsv, &err);
    FILE *out = table.fp;
    mimas_fields_file *ff = NULL;
    if (!status && a.output)
        status = mimas_fields_open(&ff, a.output, &err);
    if (!status && ff)
        status = mimas_fields_parameters(ff, "scenario", mimas_reader_parameters(r), &err);
    mimas_average *one = NULL; /* the current frame alone (--per-frame) */
    if (!status && a.per_frame) {
        mimas_average_options o1 = o;
        o1.spread = 0;
        status = mimas_average_create(&one, &o1, &err);
    }
    mimas_frame f;
    mimas_frame_init(&f);
    int header_done = 0;
    cli_progress prog;
    cli_progress_start(&prog, &in);
    while (!status && (status = mimas_reader_next(r, &f, &err)) == MIMAS_OK) {
        int take = cli_window_take(&a.window, &f, argv[first], &err);
        if (take < 0) {
            status = MIMAS_EUSAGE;
            break;
        }
        if (!take)
            continue;
        status = mimas_average_add(avg, &f, &err);
        cli_progress_frame(&prog, cmd, mimas_average_frames(avg), (long long)f.step, f.time);
        if (!status && one) {
            mimas_average_reset(one);
            status = mimas_average_add(one, &f, &err);
            if (!status && out) {
                if (!header_done++)
                    write_header(out, mimas_average_grid(one), o.grid_none, cyl, want, 0, 1);
                if (write_rows(out, one, o.grid_none, want, 0, &f))
                    status = mimas_error_set(&err, MIMAS_EIO, "cannot write the table");
            }
            if (!status && ff)
                status = mimas_fields_append_frame(ff, one, f.step, f.time, &err);
        }
        if (status && status != MIMAS_EIO)
            mimas_error_prefix(&err, "%s: step %lld", argv[first], (long long)f.step);
    }
    cli_progress_done(&prog);
    size_t skipped = mimas_reader_skipped(r);
    mimas_frame_free(&f);
    mimas_reader_close(r);
    cli_inputs_free(&in);
    mimas_average_free(one);
    if (skipped && status == MIMAS_END)
        fprintf(stderr, "mimas average: skipped %zu frames whose contact data were missing\n",
                skipped);
    if (status == MIMAS_END && mimas_average_frames(avg) == 0)
        status = mimas_error_set(&err, MIMAS_EDATA, "%s: no frame in the selected time range",
                                 argv[first]);
    if (status == MIMAS_END && out && !a.per_frame) {
        write_header(out, mimas_average_grid(avg), o.grid_none, cyl, want, a.errors, 0);
        if (write_rows(out, avg, o.grid_none, want, a.errors, NULL))
            status = mimas_error_set(&err, MIMAS_EIO, "cannot write the table");
    }
    if (status == MIMAS_END && ff) {
        char *line = cli_command_line(argc, argv);
        status = mimas_fields_finish(ff, avg, line, &err);
        ff = NULL;
        free(line);
        if (!status)
            status = MIMAS_END;
    }
    mimas_average_free(avg);
    int closed = cli_output_close(&table, status == MIMAS_END, &err);
    if (closed)
        status = closed;
    mimas_fields_abort(ff);
    if (status != MIMAS_END) {
        if (status == MIMAS_EIO && a.output && !strstr(err.msg, a.output))
            mimas_error_prefix(&err, "%s", a.output);
        return cli_fail(cmd, mimas_exit_status(status), "%s", err.msg);
    }
    return 0;
}

const cli_command cmd_average = {
    "average",
    "continuum fields (density, velocity, stress, fabric, ...) on a grid",
    "[options] INPUT... --grid SPEC --weight SPEC",
    "Coarse-grains particles and contacts onto a Cartesian or cylindrical grid\n"
    "(docs/theory.md §6): number and mass density, solid fraction, velocity,\n"
    "kinetic, contact and total stress (compression positive), pressure, shear\n"
    "stress, stress ratio, granular temperature, coordination number, fabric and\n"
    "wall force density (docs/fields.md).  Time averages are taken of the primary\n"
    "sums; --errors adds the standard error over frames.  Writes a TSV table,\n"
    "one row per cell: the gridded cell-centre coordinates, then the fields.  The\n"
    "run parameters of the input (mimas simulate's scenario) go into the field\n"
    "file of -o.",
    options,
    sizeof options / sizeof options[0],
    1,
    run,
};
