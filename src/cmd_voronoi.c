/* mimas voronoi: per-particle Voronoi cells (voro++): volume, local solid
 * fraction, faces, surface flags and per-particle stress (docs/theory.md §6;
 * Bierwisch 2009, Sec. 2.2 and eq. 3.8). */
#include <config.h>

#include <errno.h>

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli_table.h"
#include "cli_frames.h"
#include "commands.h"
#include "native.h"
#include "parallel.h"
#include "reader.h"
#include "voro_walls.h"
#include "voronoi.h"

static const cli_option options[] = {
    {"radical", 0, NULL, "radical (Laguerre) tessellation, for polydisperse packings"},
    {"walls", 0, "SPEC", "container walls bounding the cells: a comma list of plane:AXIS:H "
                         "(AXIS x y z -x -y -z; the particles on the side the signed axis "
                         "points to) and cylinder:R[:outer|:inner][:X0:Y0] (about an axis "
                         "parallel to z; outer: particles inside; inner: particles outside)"},
    {"max-extent", 0, "L", "cut every cell to within L of its particle (free surfaces)"},
    {"velocity-width", 0, "W", "the kinetic stress uses velocities about the Shepard mean of "
                               "a Gaussian of width W (default: V = 0)"},
    {"exclude-types", 0, "L", "particles of these types take part but are not reported "
                              "(e.g. glued wall particles)"},
    {"output", 'o', "OUT.h5", "write the frames with the per-particle values to a native file"},
    {"tsv", 0, "FILE", "write the table to FILE, or - for standard output (the default "
                       "without -o)"},
    {"threads", 0, "N", "OpenMP threads (default: OMP_NUM_THREADS or all cores)"},
    {"from", 0, "T0", "first time to use (s)"},
    {"to", 0, "T1", "last time to use (s)"},
    {"every", 0, "K", "use every K-th frame of those selected"},
    CLI_TABLE_OPTIONS,
};

enum { O_RADICAL, O_WALLS, O_EXTENT, O_VWIDTH, O_EXCLUDE, O_OUTPUT, O_TSV, O_THREADS, O_FROM,
       O_TO, O_EVERY, O_TABLE };

#define MAX_WALLS 16

typedef struct voronoi_args {
    const cli_command *cmd;
    mimas_voronoi_options o;
    mimas_voro_wall walls[MAX_WALLS];
    int32_t types[64];
    const char *tsv, *output;
    cli_table_options table;
    cli_window window;
} voronoi_args;

static int parse_types(voronoi_args *a, const char *arg)
{
    return cli_parse_types(a->cmd, "exclude-types", arg, a->types, 64, &a->o.nexclude);
}

static int positive(voronoi_args *a, size_t opt, const char *arg, double *v)
{
    if (cli_parse_double(arg, v) || !(*v > 0) || !isfinite(*v))
        return cli_fail(a->cmd, 1, "--%s needs a positive length, not '%s'", options[opt].name,
                        arg);
    return 0;
}

static int on_option(void *ctx, size_t opt, const char *arg)
{
    voronoi_args *a = ctx;
    mimas_error err;
    switch (opt) {
    case O_RADICAL: a->o.radical = 1; return 0;
    case O_WALLS:
        if (mimas_voro_walls_parse(arg, a->walls, MAX_WALLS, &a->o.nwalls, &err))
            return cli_fail(a->cmd, 1, "--walls: %s", err.msg);
        return 0;
    case O_EXTENT: return positive(a, opt, arg, &a->o.max_extent);
    case O_VWIDTH: return positive(a, opt, arg, &a->o.velocity_width);
    case O_EXCLUDE: return parse_types(a, arg);
    case O_OUTPUT: a->output = arg; return 0;
    case O_TSV: a->tsv = arg; return 0;
    case O_THREADS: return cli_parse_threads(a->cmd, arg, &a->o.threads);
    case O_FROM:
    case O_TO: return cli_window_time(a->cmd, &a->window, opt == O_FROM, arg);
    case O_EVERY: return cli_window_every(a->cmd, &a->window, arg);
    default: return cli_table_option(a->cmd, &a->table, opt - O_TABLE, arg);
    }
}

static void write_header(cli_table *t)
{
    static const struct {
        const char *name, *unit;
    } cols[] = {{"step", NULL}, {"id", NULL}, {"x", "m"}, {"y", "m"}, {"z", "m"},
                {"volume", "m3"}, {"nu", "1"}, {"faces", NULL}, {"surface", NULL}};
    for (size_t k = 0; k < sizeof cols / sizeof cols[0]; k++)
        cli_table_column(t, cols[k].name, cols[k].unit);
    static const char *const ab = "xyz";
    for (int m = 0; m < 9; m++) {
        char name[16];
        snprintf(name, sizeof name, "stress_%c%c", ab[m / 3], ab[m % 3]);
        cli_table_column(t, name, "Pa");
    }
    cli_table_header_end(t);
}

/* Rows "step id x y z volume nu faces surface stress_xx .. stress_zz" of the
 * reported particles. */
static int write_rows(const mimas_voronoi *v, const mimas_frame *f, cli_table *t,
                      mimas_error *err)
{
    const mimas_particles *p = &f->particles;
    mimas_voronoi_values val;
    mimas_voronoi_values_of(p, &val);
    for (size_t k = 0; k < p->n; k++) {
        if (!mimas_voronoi_reported(v, p, k))
            continue;
        cli_table_int(t, (long long)f->step);
        cli_table_int(t, (long long)p->id[k]);
        for (int d = 0; d < 3; d++)
            cli_table_double(t, p->pos[k][d]);
        cli_table_double(t, val.volume[k]);
        cli_table_double(t, val.nu[k]);
        cli_table_int(t, (long long)val.faces[k]);
        cli_table_int(t, (long long)val.surface[k]);
        for (int m = 0; m < 9; m++)
            cli_table_double(t, val.stress ? val.stress[9 * k + (size_t)m] : NAN);
        cli_table_row_end(t);
    }
    return ferror(t->fp) ? mimas_error_set(err, MIMAS_EIO, "cannot write the table: %s",
                                           strerror(errno))
                         : MIMAS_OK;
}

/* ---- one frame's result, written on rank 0 in frame order ---- */
typedef struct voronoi_sink {
    FILE *out;          /* the table, or NULL */
    const char *out_name;   /* its name in messages */
    mimas_writer *w;    /* -o, or NULL */
    mimas_frame frame;  /* a frame unpacked from a result */
} voronoi_sink;

/* What a frame's result holds: its table rows (formatted as the table's
 * options say), its frame with the Voronoi columns. */
typedef struct result_parts {
    int rows, frame;
    const cli_table_options *table;
} result_parts;

/* A frame's result: the length of its table rows, the rows, then the packed
 * frame (each part empty when not wanted). */
static int pack_result(const mimas_voronoi *v, const mimas_frame *f, const result_parts *parts,
                       mimas_bytes *out, mimas_error *err)
{
    char *text = NULL;
    size_t len = 0;
    if (parts->rows) {
        FILE *m = open_memstream(&text, &len);
        if (!m)
            return mimas_error_set(err, MIMAS_EIO, "out of memory");
        cli_table t;
        cli_table_start(&t, m, parts->table);
        int rc = write_rows(v, f, &t, err);
        int bad = cli_table_end(&t);
        if (fclose(m) || rc || bad) {
            free(text);
            return rc ? rc : mimas_error_set(err, MIMAS_EIO, "out of memory");
        }
    }
    mimas_bytes packed = {0};
    int rc = parts->frame ? mimas_frame_pack(f, &packed, err) : MIMAS_OK;
    uint64_t n = len;
    size_t total = sizeof n + len + packed.n;
    if (!rc && total > out->cap) {
        unsigned char *p = realloc(out->data, total);
        if (!p)
            rc = mimas_error_set(err, MIMAS_EIO, "out of memory");
        else
            out->data = p, out->cap = total;
    }
    if (!rc) {
        memcpy(out->data, &n, sizeof n);
        if (len)
            memcpy(out->data + sizeof n, text, len);
        if (packed.n)
            memcpy(out->data + sizeof n + len, packed.data, packed.n);
        out->n = total;
    }
    free(text);
    mimas_bytes_free(&packed);
    return rc;
}

static int write_frame(void *ctx, size_t position, const unsigned char *data, size_t n,
                       mimas_error *err)
{
    (void)position;
    voronoi_sink *s = ctx;
    uint64_t len;
    if (n < sizeof len)
        return mimas_error_set(err, MIMAS_EDATA, "a per-frame result is truncated");
    memcpy(&len, data, sizeof len);
    if (len > n - sizeof len)
        return mimas_error_set(err, MIMAS_EDATA, "a per-frame result is truncated");
    if (s->out && len && fwrite(data + sizeof len, 1, len, s->out) != len)
        return mimas_error_set(err, MIMAS_EIO, "%s: cannot write the table: %s", s->out_name,
                               strerror(errno));
    if (!s->w)
        return MIMAS_OK;
    size_t at = sizeof len + (size_t)len;
    int rc = mimas_frame_unpack(&s->frame, data + at, n - at, err);
    return rc ? rc : mimas_writer_append(s->w, &s->frame, err);
}

static int run(const cli_command *cmd, int argc, char **argv)
{
    voronoi_args a;
    memset(&a, 0, sizeof a);
    a.cmd = cmd;
    a.o.walls = a.walls;
    a.o.exclude = a.types;
    cli_inputs in = {0};
    int first;
    int rc = cli_parse(cmd, argc, argv, on_option, &a, &in, &first);
    if (!rc)
        rc = cli_refuse_input_as_output(cmd, a.output, &in, argv + first, argc - first) ||
             cli_refuse_input_as_output(cmd, a.tsv, &in, argv + first, argc - first);
    mimas_reader *r = NULL;
    if (!rc)
        rc = cli_open_inputs(cmd, &in, argc, argv, first, &r);
    mimas_error err;
    mimas_voronoi *vor = NULL;
    if (!rc && mimas_voronoi_create(&vor, &a.o, &err))
        rc = cli_fail(cmd, mimas_exit_status(err.code), "%s", err.msg);
    if (rc) {
        mimas_reader_close(r);
        cli_inputs_free(&in);
        return rc < 0 ? 0 : rc;
    }
    /* outputs, on rank 0 only (under MPI every rank tessellates its frames and
     * sends rank 0 the rows and the frame, written there in frame order): the
     * table unless only -o was asked for; the native file */
    int root = mimas_par_rank() == 0;
    cli_output table = {0};
    int status = MIMAS_OK;
    if (root && (a.tsv || !a.output))
        status = cli_output_open(&table, a.tsv, &err);
    FILE *out = table.fp;
    cli_table tw;
    cli_table_start(&tw, out, &a.table);
    if (out)
        write_header(&tw);
    voronoi_sink sink = {out, a.tsv && strcmp(a.tsv, "-") ? a.tsv : "standard output", NULL,
                         {0}};
    mimas_frame_init(&sink.frame);
    char *provenance = cli_command_line(argc, argv);
    if (!status && root && a.output) {
        mimas_writer_options wo;
        mimas_writer_options_default(&wo);
        wo.atomic = 1; /* no partial output */
        wo.xdmf = 1;
        wo.provenance = provenance;
        status = mimas_writer_open(&sink.w, a.output, &wo, &err);
    }
    mimas_par_ordered *order = NULL;
    if (!status)
        status = mimas_par_ordered_open(&order, write_frame, &sink, &err);
    status = mimas_par_agree(status, SIZE_MAX, &err);
    result_parts parts = {a.tsv || !a.output, a.output != NULL, &a.table};
    mimas_frame f;
    mimas_frame_init(&f);
    mimas_bytes result = {0};
    cli_progress prog;
    cli_progress_start(&prog, &in);
    cli_frames frames;
    cli_frames_init(&frames, r, &a.window, argv[first]);
    while (!status && (status = cli_frames_next(&frames, &f, &err)) == MIMAS_OK) {
        status = mimas_voronoi_frame(vor, &f, &err);
        if (status && status != MIMAS_EIO)
            mimas_error_prefix(&err, "%s: step %lld", argv[first], (long long)f.step);
        if (!status)
            status = pack_result(vor, &f, &parts, &result, &err);
        if (!status)
            status = mimas_par_ordered_put(order, frames.position, &result, &err);
        cli_progress_frame(&prog, cmd, frames.position + 1, (long long)f.step, f.time);
    }
    cli_progress_done(&prog);
    status = mimas_par_ordered_finish(order, status, frames.position, &err);
    mimas_par_ordered_free(order);
    size_t skipped = mimas_reader_skipped(r);
    mimas_bytes_free(&result);
    mimas_frame_free(&f);
    mimas_frame_free(&sink.frame);
    mimas_reader_close(r);
    cli_inputs_free(&in);
    mimas_voronoi_free(vor);
    if (status == MIMAS_END && frames.selected == 0)
        status = mimas_error_set(&err, MIMAS_EDATA, "%s: no frames", argv[first]);
    if (sink.w) {
        if (status == MIMAS_END) {
            int closed = mimas_writer_close(sink.w, &err);
            if (closed)
                status = closed;
        } else {
            mimas_writer_abort(sink.w);
        }
    }
    free(provenance);
    cli_table_end(&tw);
    int closed = cli_output_close(&table, status == MIMAS_END, &err);
    if (closed)
        status = closed;
    status = mimas_par_agree(status, SIZE_MAX, &err);
    if (status != MIMAS_END)
        return cli_fail(cmd, mimas_exit_status(status), "%s", err.msg);
    if (skipped && root)
        fprintf(stderr, "mimas voronoi: skipped %zu frames whose contact data were missing\n",
                skipped);
    return 0;
}

const cli_command cmd_voronoi = {
    "voronoi",
    "per-particle Voronoi cells: volume, local solid fraction, faces, surface, stress",
    "[options] INPUT...",
    "Tessellates every frame with voro++ (plain, or radical with --radical) in its\n"
    "box (periodic along the periodic axes; a tilted box must be periodic along\n"
    "all three and cannot have walls), bounded by the --walls (a cylinder by the\n"
    "plane tangent to it at each particle's angle, as voro++ does) and cut to\n"
    "--max-extent about each particle.  Writes one row per particle: step, id,\n"
    "position, cell volume, local solid fraction V_p/V_cell, number of faces,\n"
    "surface flags (1: the cell touches a wall or a non-periodic box face, 2: it\n"
    "was cut by --max-extent, 3: both) and, when contact data are given, the\n"
    "per-particle stress (1/V_cell)[m (v - V)(x)(v - V) + sum_j f_kj (x) (r_k - c_kj)]\n"
    "(wall contacts included; compression positive; nine components, [a][b] =\n"
    "f_a b_b).  -o writes the frames with these values as extra per-particle\n"
    "columns voronoi_volume, voronoi_nu, voronoi_faces, voronoi_surface and\n"
    "voronoi_stress (docs/format.md) for mimas average --weight voronoi.",
    options,
    sizeof options / sizeof options[0],
    1,
    run,
};
