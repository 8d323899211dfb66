/* mimas average: continuum fields on a grid from any input (docs/theory.md §6). */
#include <config.h>

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "average.h"
#include "big_alloc.h"
#include "cli_frames.h"
#include "cli_table.h"
#include "commands.h"
#include "output_h5.h"
#include "fields.h"
#include "parallel.h"
#include "reader.h"
#include "xdmf.h"

static const cli_option options[] = {
    {"grid", 0, "SPEC", "none, x=LO:HI:N[,y=..][,z=..], or r=LO:HI:N[,phi=LO:HI:N][,z=LO:HI:N]"},
    {"weight", 0, "SPEC", "bins (exact overlaps), bins:center, gauss:w=W[,cutoff=C] (the "
                          "Gaussian cut at C W, default 3, renormalised; ,shift: shifted to 0 "
                          "there), lucy:c=C, shepard:w=W[,cutoff=C], voronoi (per-particle "
                          "values of mimas voronoi -o, by the centre's cell), "
                          "voronoi:w=W[,cutoff=C] (by a Gaussian)"},
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
    CLI_TABLE_BLOCKS_OPTION,
    CLI_TABLE_OPTIONS,
};

enum { O_GRID, O_WEIGHT, O_FIELDS, O_AXIS, O_FROM, O_TO, O_EVERY, O_TYPES, O_EXCLUDE,
       O_ERRORS, O_PER_FRAME, O_OUTPUT, O_TSV, O_THREADS, O_DIAMETER, O_LIST, O_BLOCKS,
       O_TABLE };

typedef struct average_args {
    const cli_command *cmd;
    const char *grid, *weight, *fields, *axis, *tsv, *output;
    cli_window window;
    double diameter;
    int errors;
    int threads;
    cli_types types;
    int list, per_frame;
    cli_table_options table;
} average_args;

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
    case O_EVERY: return cli_window_every(a->cmd, &a->window, arg);
    case O_TYPES:
    case O_EXCLUDE: return cli_types_option(a->cmd, &a->types, opt == O_EXCLUDE, arg);
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
    case O_BLOCKS: a->table.blocks = 1; return 0;
    default: return cli_table_option(a->cmd, &a->table, opt - O_TABLE, arg);
    }
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

static void write_header(cli_table *t, const mimas_grid *g, int grid_none, int cyl,
                         const unsigned char *want, int errors, int per_frame)
{
    if (per_frame) {
        cli_table_column(t, "step", NULL);
        cli_table_column(t, "time", "s");
    }
    for (int d = 0; d < 3 && !grid_none; d++)
        if (g->gridded[d])
            cli_table_column(t, mimas_grid_coord_name(g, d),
                             cyl && d == 1 ? "rad" : "m");
    for (size_t k = 0; k < mimas_fields_count(); k++) {
        if (!want[k])
            continue;
        const char *name = mimas_field_name(k, cyl), *unit = mimas_field(k)->unit;
        cli_table_column(t, name, unit);
        if (errors) {
            char sem[80];
            snprintf(sem, sizeof sem, "%s_sem", name);
            cli_table_column(t, sem, unit);
        }
    }
    cli_table_header_end(t);
}

/* What the rows of a table are made from (write_rows) */
typedef struct row_source {
    const mimas_grid *g;
    int grid_none, errors, gridded, fast; /* fast: the fastest gridded direction */
    size_t cells, nf;
    const unsigned char *want;
    const double *mean, *sd, *count;
    const mimas_frame *frame;
} row_source;

/* The row of one cell, row[] room for its numbers */
static void put_row(cli_table *t, const row_source *rs, size_t cell, double *row)
{
    const mimas_grid *g = rs->g;
    size_t nf = rs->nf, nr = 0;
    double ctr[3];
    if (!rs->grid_none)
        mimas_grid_cell_centre(g, cell, ctr);
    if (rs->frame) {
        cli_table_int(t, (long long)rs->frame->step);
        row[nr++] = rs->frame->time;
    }
    for (int d = 0; d < 3 && !rs->grid_none; d++)
        if (g->gridded[d])
            row[nr++] = ctr[d];
    const double *m = &rs->mean[cell * nf], *s = rs->errors ? &rs->sd[cell * nf] : NULL,
                 *n = rs->errors ? &rs->count[cell * nf] : NULL;
    for (size_t k = 0; k < nf; k++) {
        if (!rs->want[k])
            continue;
        row[nr++] = m[k];
        if (rs->errors)
            row[nr++] = n[k] > 1 ? s[k] / sqrt(n[k]) : NAN;
    }
    cli_table_doubles(t, row, nr);
    cli_table_row_end(t);
    int idx[3] = {0, 0, 0};
    if (!rs->grid_none)
        mimas_grid_unindex(g, cell, idx);
    int last = cell + 1 == rs->cells;
    if (rs->frame && last)
        cli_table_block_end(t, 1);
    else if (rs->gridded >= 2 && idx[rs->fast] == g->n[rs->fast] - 1)
        cli_table_block_end(t, 0);
}

/* The rows of cells [c0, c1) into t; -1 when out of memory */
static int put_range(cli_table *t, const row_source *rs, size_t c0, size_t c1)
{
    double *row = malloc((4 + 2 * rs->nf) * sizeof *row);
    if (!row)
        return -1;
    for (size_t cell = c0; cell < c1; cell++)
        put_row(t, rs, cell, row);
    free(row);
    return 0;
}

/* Rows [c0, c1) into a text of their own (*text, *len: open_memstream's, freed by the
 * caller), laid out as t lays them out; -1 when out of memory */
static int rows_to_text(const cli_table *t, const row_source *rs, size_t c0, size_t c1,
                        char **text, size_t *len)
{
    *text = NULL;
    *len = 0;
    FILE *fp = open_memstream(text, len);
    cli_table *tt = malloc(sizeof *tt);
    int bad = !fp || !tt;
    if (!bad) {
        cli_table_start(tt, fp, &t->o);
        bad = put_range(tt, rs, c0, c1) || ferror(fp);
    }
    if (fp && fclose(fp))
        bad = 1;
    free(tt);
    return bad ? -1 : 0;
}

/* The rows a thread formats at a time: the threads format their runs of rows side by side,
 * each into a text of its own, and the texts are written in order (the same bytes as one
 * thread's), a round of threads x ROW_RUN rows at a time */
#define ROW_RUN 2048

static int put_rows(cli_table *t, const row_source *rs, int threads)
{
    if (threads > 1 && rs->cells > ROW_RUN) {
#ifdef _OPENMP
        char *text[64];
        size_t len[64];
        int nt = threads < 64 ? threads : 64, bad = 0;
        for (size_t start = 0; start < rs->cells && !bad; start += (size_t)nt * ROW_RUN) {
#pragma omp parallel for num_threads(nt) schedule(static, 1) reduction(| : bad)
            for (int u = 0; u < nt; u++) {
                size_t c0 = start + (size_t)u * ROW_RUN, c1 = c0 + ROW_RUN;
                c0 = c0 < rs->cells ? c0 : rs->cells;
                c1 = c1 < rs->cells ? c1 : rs->cells;
                bad |= rows_to_text(t, rs, c0, c1, &text[u], &len[u]);
            }
            for (int u = 0; u < nt; u++) {
                if (!bad && len[u] && fwrite(text[u], 1, len[u], t->fp) != len[u])
                    bad = 1;
                free(text[u]);
            }
        }
        return bad ? -1 : 0;
#endif
    }
    return put_range(t, rs, 0, rs->cells);
}

/* One row per cell ("nan" where a field is undefined, docs/fields.md); with
 * frame (not NULL) the rows start with its step and time.  With blocks, a
 * blank line ends each row of a grid with two or more gridded directions,
 * and two end each frame.  The numbers of large tables are formatted by the
 * average's threads (put_rows). */
static int write_rows(cli_table *t, const mimas_average *avg, int grid_none,
                      const unsigned char *want, int errors, const mimas_frame *frame)
{
    const mimas_grid *g = mimas_average_grid(avg);
    row_source rs = {g, grid_none, errors, 0, -1, grid_none ? 1 : mimas_grid_cells(g),
                     mimas_fields_count(), want, NULL, NULL, NULL, frame};
    for (int d = 0; d < 3 && !grid_none; d++)
        if (g->gridded[d]) {
            rs.gridded++;
            if (rs.fast < 0)
                rs.fast = d;
        }
    /* the spread only for --errors */
    size_t cells = rs.cells, nf = rs.nf;
    double *mean = mimas_big_calloc(cells * nf, sizeof *mean),
           *sd = errors ? mimas_big_calloc(cells * nf, sizeof *sd) : NULL,
           *count = errors ? mimas_big_calloc(cells * nf, sizeof *count) : NULL;
    int rc = mean && (!errors || (sd && count)) ? mimas_average_fields(avg, mean, sd, count)
                                                : -1;
    rs.mean = mean, rs.sd = sd, rs.count = count;
    if (!rc)
        rc = put_rows(t, &rs, mimas_average_threads(avg));
    mimas_big_free(mean);
    mimas_big_free(sd);
    mimas_big_free(count);
    return rc || ferror(t->fp) ? -1 : 0;
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

/* ---- frames split over MPI ranks (docs/parallel.md) ---- */
/* --per-frame: one frame's average with its step and time, written on rank 0
 * in frame order. */
typedef struct per_frame_sink {
    const mimas_average_options *o;
    int cyl;
    const unsigned char *want;
    cli_table *tw;          /* the table, or NULL */
    const char *tw_name;    /* its name in messages */
    mimas_fields_file *ff;  /* -o, or NULL */
    mimas_average *other;   /* a frame's average unpacked on rank 0 */
    int header_done;
} per_frame_sink;

static int pack_frame(const mimas_average *one, const mimas_frame *f, mimas_bytes *out,
                      mimas_error *err)
{
    int rc = mimas_average_pack(one, out, err);
    size_t head = sizeof f->step + sizeof f->time;
    if (!rc && out->n + head > out->cap) {
        unsigned char *p = realloc(out->data, out->n + head);
        if (!p)
            return mimas_error_set(err, MIMAS_EIO, "out of memory");
        out->data = p;
        out->cap = out->n + head;
    }
    if (!rc) {
        memcpy(out->data + out->n, &f->step, sizeof f->step);
        memcpy(out->data + out->n + sizeof f->step, &f->time, sizeof f->time);
        out->n += head;
    }
    return rc;
}

static int write_frame(void *ctx, size_t position, const unsigned char *data, size_t n,
                       mimas_error *err)
{
    (void)position;
    per_frame_sink *s = ctx;
    mimas_frame f; /* only step and time */
    size_t head = sizeof f.step + sizeof f.time;
    if (n < head)
        return mimas_error_set(err, MIMAS_EDATA, "a per-frame result is truncated");
    memcpy(&f.step, data + n - head, sizeof f.step);
    memcpy(&f.time, data + n - sizeof f.time, sizeof f.time);
    mimas_average_reset(s->other);
    int rc = mimas_average_merge(s->other, data, n - head, err);
    if (!rc && s->tw) {
        if (!s->header_done++)
            write_header(s->tw, mimas_average_grid(s->other), s->o->grid_none, s->cyl,
                         s->want, 0, 1);
        if (write_rows(s->tw, s->other, s->o->grid_none, s->want, 0, &f))
            rc = mimas_error_set(err, MIMAS_EIO, "%s: cannot write the table: %s", s->tw_name,
                                 strerror(errno));
    }
    if (!rc && s->ff)
        rc = mimas_fields_append_frame(s->ff, s->other, f.step, f.time, err);
    return rc;
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
    o.types = a.types.types;
    o.ntypes = a.types.n;
    o.exclude = a.types.exclude;
    o.spread = a.errors || a.output; /* the HDF5 file always has the spread */
    o.threads = a.threads;
    o.diameter = a.diameter;
    int cyl = o.grid.kind == MIMAS_GRID_CYLINDRICAL && !o.grid_none;
    unsigned char want[128];
    if (!rc)
        rc = choose_fields(&a, cyl, want);
    if (!rc) {
        /* the field file, its XDMF sidecar and the table */
        char xdmf[4200] = "";
        if (a.output)
            mimas_xdmf_path(a.output, NULL, xdmf, sizeof xdmf);
        rc = cli_refuse_input_as_output(cmd, a.output, &in, argv + first, argc - first) ||
             cli_refuse_input_as_output(cmd, a.output ? xdmf : NULL, &in, argv + first,
                                        argc - first) ||
             cli_refuse_input_as_output(cmd, a.tsv, &in, argv + first, argc - first);
    }
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
    /* outputs, on rank 0 only (under MPI the others only compute): the table
     * (a temporary name renamed at the end, or standard output) unless only
     * -o was asked for; the HDF5 file */
    int root = mimas_par_rank() == 0;
    cli_output table = {0};
    int status = MIMAS_OK;
    if (root && (a.tsv || !a.output))
        status = cli_output_open(&table, a.tsv, &err);
    FILE *out = table.fp;
    cli_table tw;
    cli_table_start(&tw, out, &a.table);
    per_frame_sink sink = {&o, cyl, want, out ? &tw : NULL,
                           a.tsv && strcmp(a.tsv, "-") ? a.tsv : "standard output", NULL, NULL,
                           0};
    if (!status && root && a.output)
        status = mimas_fields_open(&sink.ff, a.output, want, &err);
    if (!status && sink.ff)
        status = mimas_fields_parameters(sink.ff, "scenario", mimas_reader_parameters(r), &err);
    mimas_average *one = NULL; /* the current frame alone (--per-frame) */
    mimas_par_ordered *order = NULL;
    if (!status && a.per_frame) {
        mimas_average_options o1 = o;
        o1.spread = 0;
        status = mimas_average_create(&one, &o1, &err);
        if (!status && root)
            status = mimas_average_create(&sink.other, &o1, &err);
        if (!status)
            status = mimas_par_ordered_open(&order, write_frame, &sink, &err);
    }
    status = mimas_par_agree(status, SIZE_MAX, &err);
    mimas_frame f;
    mimas_frame_init(&f);
    mimas_bytes packed = {0};
    cli_progress prog;
    cli_progress_start(&prog, &in);
    cli_progress_total(&prog, r);
    cli_frames frames;
    cli_frames_init(&frames, r, &a.window, argv[first]);
    while (!status && (status = cli_frames_next(&frames, &f, &err)) == MIMAS_OK) {
        status = mimas_average_add(avg, &f, &err);
        cli_progress_frame(&prog, cmd, frames.consumed, (long long)f.step, f.time);
        if (!status && one) {
            mimas_average_reset(one);
            status = mimas_average_add(one, &f, &err);
            if (!status)
                status = pack_frame(one, &f, &packed, &err);
            if (!status)
                status = mimas_par_ordered_put(order, frames.position, &packed, &err);
        }
        if (status && status != MIMAS_EIO && status != MIMAS_END)
            mimas_error_prefix(&err, "%s: step %lld", argv[first], (long long)f.step);
    }
    cli_progress_done(&prog);
    if (order)
        status = mimas_par_ordered_finish(order, status, frames.position, &err);
    else
        status = mimas_par_agree(status, frames.position, &err);
    if (status == MIMAS_END)
        status = mimas_average_reduce(avg, &err);
    if (status == MIMAS_OK)
        status = MIMAS_END;
    size_t skipped = mimas_reader_skipped(r);
    mimas_bytes_free(&packed);
    mimas_frame_free(&f);
    mimas_reader_close(r);
    cli_inputs_free(&in);
    mimas_average_free(one);
    mimas_average_free(sink.other);
    mimas_par_ordered_free(order);
    mimas_fields_file *ff = sink.ff;
    if (root && skipped && status == MIMAS_END)
        fprintf(stderr, "mimas average: skipped %zu frames whose contact data were missing\n",
                skipped);
    if (status == MIMAS_END && frames.selected == 0)
        status = mimas_error_set(&err, MIMAS_EDATA, "%s: no frame in the selected time range",
                                 argv[first]);
    if (root && status == MIMAS_END && out && !a.per_frame) {
        write_header(&tw, mimas_average_grid(avg), o.grid_none, cyl, want, a.errors, 0);
        if (write_rows(&tw, avg, o.grid_none, want, a.errors, NULL))
            status = mimas_error_set(&err, MIMAS_EIO, "%s: cannot write the table: %s",
                                     a.tsv && strcmp(a.tsv, "-") ? a.tsv : "standard output",
                                     strerror(errno));
    }
    if (root && status == MIMAS_END && ff) {
        char *line = cli_command_line(argc, argv);
        status = mimas_fields_finish(ff, avg, line, &err);
        ff = NULL;
        free(line);
        if (!status)
            status = MIMAS_END;
    }
    mimas_average_free(avg);
    cli_table_end(&tw);
    int closed = cli_output_close(&table, status == MIMAS_END, &err);
    if (closed)
        status = closed;
    mimas_fields_abort(ff);
    /* a failure of rank 0's output reaches the others too */
    status = mimas_par_agree(status, SIZE_MAX, &err);
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
    "(docs/theory.md §6): number and mass density, solid fraction, velocity, kinetic,\n"
    "contact and total stress (compression positive), pressure, shear stress,\n"
    "stress ratio, granular temperature, coordination number, fabric and wall\n"
    "force density (docs/fields.md).  Time averages are taken of the primary\n"
    "sums; --errors adds the standard error over frames.  Kernels are integrated\n"
    "over the directions a grid leaves out, and averaged exactly over the azimuth\n"
    "on cylindrical grids without phi cells.  Writes a TSV table, one row per\n"
    "cell: the gridded cell-centre coordinates, then the fields.  The run\n"
    "parameters of the input (mimas simulate's scenario) go into the field file\n"
    "of -o.",
    options,
    sizeof options / sizeof options[0],
    1,
    run,
    "# the fields of a ring shear cell on an r-z grid, averaged over t >= 5 s with\n"
    "# standard errors, the glued wall particles (type 2) left out: the field file for\n"
    "# mimas shearband and mimas rheology, and the same as a table\n"
    "mimas average run.h5 --grid r=0.0147:0.11:39,z=0:0.038:20 --weight bins \\\n"
    "    --from 5 --exclude-types 2 --errors -o fields.h5 --tsv fields.tsv\n"
    "\n"
    "# a vertical profile of three fields by a Gaussian of width 1 mm, to standard output\n"
    "mimas average run.h5 --grid z=0:0.038:38 --weight gauss:w=0.001 --fields nu,v_z,p\n"
    "\n"
    "# the whole box as one cell\n"
    "mimas average run.h5 --grid none --weight bins --fields nu,stress,p\n"
    "\n"
    "# every field with its unit and definition\n"
    "mimas average --list-fields",
};
