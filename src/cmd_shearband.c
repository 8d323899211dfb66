/* mimas shearband: the shear band's centre and width per height layer
 * from erf fits of the angular velocity profile (docs/theory.md §7.1, docs/shearband.md). */
#include <config.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "average.h"
#include "cli_frames.h"
#include "cli_table.h"
#include "commands.h"
#include "fieldset.h"
#include "parallel.h"
#include "reader.h"
#include "shearband.h"

static const cli_option options[] = {
    {"omega", 0, "OMEGA", "rotation rate of the cell's moving part (rad/s); the profile is "
                          "omega(r)/OMEGA (required)"},
    {"model", 0, "2|4", "2: 0.5 + 0.5 erf((r - Rc)/W) (default); 4: A + B erf((r - Rc)/W)"},
    {"min-points", 0, "N", "valid radial cells a layer needs for a fit (default 5)"},
    {"unweighted", 0, NULL, "ignore the standard errors (fit unweighted, errors scaled by the "
                            "scatter)"},
    {"fenistein", 0, "RS,H", "add the surface-layer prediction Rc = RS (1 - (H/RS)^2.5) for split "
                             "radius RS and fill height H"},
    {"plot", 0, "FILE.png", "draw the profiles with their fits and Rc(z) (gnuplot)"},
    {"output", 'o', "FILE", "write the table to FILE (default: standard output)"},
    {"from", 0, "T0", "raw input: first time to average (s)"},
    {"to", 0, "T1", "raw input: last time to average (s)"},
    {"exclude-types", 0, "L", "raw input: leave out particles of these types (e.g. glued wall "
                              "particles)"},
    CLI_TABLE_OPTIONS,
};

enum { O_OMEGA, O_MODEL, O_MIN, O_UNWEIGHTED, O_FENISTEIN, O_PLOT, O_OUTPUT, O_FROM, O_TO,
       O_EXCLUDE, O_TABLE };

typedef struct band_args {
    const cli_command *cmd;
    mimas_band_options o;
    int has_omega, fenistein;
    double rs, h;
    const char *plot, *output;
    cli_window window;
    int32_t types[64];
    size_t ntypes;
    cli_table_options table;
} band_args;

static int on_option(void *ctx, size_t opt, const char *arg)
{
    band_args *a = ctx;
    long v;
    switch (opt) {
    case O_OMEGA:
        if (cli_parse_double(arg, &a->o.omega) || a->o.omega == 0)
            return cli_fail(a->cmd, 1, "--omega needs a non-zero rate in rad/s, not '%s'", arg);
        a->has_omega = 1;
        return 0;
    case O_MODEL:
        if (cli_parse_long(arg, &v) || (v != 2 && v != 4))
            return cli_fail(a->cmd, 1, "--model is 2 or 4, not '%s'", arg);
        a->o.model = (int)v;
        return 0;
    case O_MIN:
        if (cli_parse_long(arg, &v) || v < 1 || v > 1000000)
            return cli_fail(a->cmd, 1, "--min-points needs a positive whole number, not '%s'",
                            arg);
        a->o.min_points = (size_t)v;
        return 0;
    case O_UNWEIGHTED: a->o.unweighted = 1; return 0;
    case O_FENISTEIN: {
        char *end;
        a->rs = strtod(arg, &end);
        a->h = *end == ',' ? strtod(end + 1, &end) : NAN;
        if (*end || !(a->rs > 0) || !(a->h > 0) || !isfinite(a->rs) || !isfinite(a->h))
            return cli_fail(a->cmd, 1, "--fenistein needs RS,H (two positive lengths), not '%s'",
                            arg);
        a->fenistein = 1;
        return 0;
    }
    case O_PLOT: a->plot = arg; return 0;
    case O_OUTPUT: a->output = arg; return 0;
    case O_FROM:
    case O_TO: return cli_window_time(a->cmd, &a->window, opt == O_FROM, arg);
    case O_EXCLUDE:
        return cli_parse_types(a->cmd, "exclude-types", arg, a->types, 64, &a->ntypes);
    default: return cli_table_option(a->cmd, &a->table, opt - O_TABLE, arg);
    }
}

/* cli_frames_first's decision on rank 0: the grid of the first frame, its
 * spec (ctx, 512 bytes) said on standard error */
static int choose_grid(void *ctx, const mimas_frame *f, void *data, mimas_error *err)
{
    return mimas_band_choose_grid(f, data, ctx, 512, err);
}

/* Raw particle input: average with bins on an r-z grid chosen from the
 * first frame used (said on standard error). */
static int average_input(const band_args *a, const cli_inputs *in, mimas_reader *r,
                         const char *input, mimas_fieldset **fs, mimas_error *err)
{
    mimas_average_options o;
    memset(&o, 0, sizeof o);
    o.types = a->types;
    o.ntypes = a->ntypes;
    o.exclude = 1;
    o.spread = 1;
    cli_window w = a->window;
    int status = mimas_weight_parse(&o.weight, "bins", err);
    mimas_average *avg = NULL;
    mimas_frame f;
    mimas_frame_init(&f);
    cli_progress prog;
    cli_progress_start(&prog, in);
    cli_progress_total(&prog, r);
    cli_frames frames;
    cli_frames_init(&frames, r, &w, input);
    /* the grid comes from the first frame of the selection (rank 0's first
     * frame under MPI, shared with the others) */
    char spec[512] = "";
    int have = 0;
    if (!status)
        status = cli_frames_first(&frames, &f, choose_grid, spec, &o.grid, sizeof o.grid, &have,
                                  err);
    if (!status) {
        status = mimas_average_create(&avg, &o, err);
        if (!status && mimas_par_rank() == 0 && !in->quiet)
            fprintf(stderr, "mimas shearband: averaging the particles with --weight bins %s\n",
                    spec);
        if (!status && !have)
            status = MIMAS_END; /* this rank has no frame at all */
    }
    while (status == MIMAS_OK) {
        status = mimas_average_add(avg, &f, err);
        if (status && status != MIMAS_EIO)
            mimas_error_prefix(err, "%s: step %lld", input, (long long)f.step);
        cli_progress_frame(&prog, a->cmd, frames.consumed, (long long)f.step, f.time);
        if (!status)
            status = cli_frames_next(&frames, &f, err);
    }
    status = mimas_par_agree(status, frames.position, err);
    if (status == MIMAS_END)
        status = mimas_average_reduce(avg, err);
    if (status == MIMAS_OK)
        status = MIMAS_END;
    cli_progress_done(&prog);
    mimas_frame_free(&f);
    if (status == MIMAS_END)
        status = mimas_fieldset_from_average(fs, avg, input, err);
    mimas_average_free(avg);
    return status;
}

typedef struct band_table {
    const band_args *a;
    const mimas_band *b;
} band_table;

static void write_table(FILE *out, const void *ctx)
{
    const band_args *a = ((const band_table *)ctx)->a;
    const mimas_band *b = ((const band_table *)ctx)->b;
    cli_table t;
    cli_table_start(&t, out, &a->table);
    static const char *const cols[] = {"z", "Rc", "Rc_err", "W", "W_err"};
    for (int k = 0; k < 5; k++)
        cli_table_column(&t, cols[k], "m");
    cli_table_column(&t, "chi2", "1");
    cli_table_column(&t, "npts", NULL);
    static const char *const ab[] = {"A", "A_err", "B", "B_err"};
    for (int k = 0; b->model == 4 && k < 4; k++)
        cli_table_column(&t, ab[k], "1");
    if (a->fenistein)
        cli_table_column(&t, "Rc_fenistein", "m");
    cli_table_column(&t, "status", NULL);
    cli_table_header_end(&t);
    for (size_t k = 0; k < b->nlayers; k++) {
        const mimas_fit *f = &b->layers[k].fit;
        cli_table_double(&t, b->layers[k].z);
        for (int q = MIMAS_BAND_RC; q <= MIMAS_BAND_W; q++) {
            cli_table_double(&t, f->p[q]);
            cli_table_double(&t, f->err[q]);
        }
        cli_table_double(&t, f->chi2);
        cli_table_int(&t, (long long)f->npts);
        for (int q = MIMAS_BAND_A; b->model == 4 && q <= MIMAS_BAND_B; q++) {
            cli_table_double(&t, f->p[q]);
            cli_table_double(&t, f->err[q]);
        }
        if (a->fenistein)
            cli_table_double(&t, mimas_band_fenistein_rc(a->rs, a->h));
        cli_table_text(&t, mimas_fit_status_name(f->status));
        cli_table_row_end(&t);
    }
    cli_table_end(&t);
}

static int run(const cli_command *cmd, int argc, char **argv)
{
    band_args a;
    memset(&a, 0, sizeof a);
    a.cmd = cmd;
    a.o.model = 2;
    a.o.min_points = 5;
    cli_inputs in = {0};
    int first;
    int rc = cli_parse(cmd, argc, argv, on_option, &a, &in, &first);
    if (!rc && !a.has_omega)
        rc = cli_fail(cmd, 1, "--omega is required (the rotation rate, rad/s)");
    if (!rc && first >= argc)
        rc = cli_fail(cmd, 1, "no input file (see mimas shearband --help)");
    if (!rc && (size_t)a.o.model >= a.o.min_points)
        rc = cli_fail(cmd, 1, "--min-points must exceed the %d parameters of the model",
                      a.o.model);
    if (!rc)
        rc = cli_refuse_input_as_output(cmd, a.output, &in, argv + first, argc - first) ||
             cli_refuse_input_as_output(cmd, a.plot, &in, argv + first, argc - first);
    mimas_error err;
    mimas_fieldset *fs = NULL;
    int status = MIMAS_OK;
    if (!rc && argc - first == 1 && mimas_fieldset_probe(argv[first])) {
        if (a.window.has_from || a.window.has_to || a.ntypes)
            rc = cli_fail(cmd, 1, "--from, --to and --exclude-types apply to particle input, "
                          "not to a field file");
        else
            status = mimas_fieldset_open(&fs, argv[first], &err);
    } else if (!rc) {
        mimas_reader *r = NULL;
        rc = cli_open_inputs(cmd, &in, argc, argv, first, &r);
        if (!rc)
            status = average_input(&a, &in, r, argv[first], &fs, &err);
        mimas_reader_close(r);
    }
    cli_inputs_free(&in);
    if (rc)
        return rc < 0 ? 0 : rc;
    /* under MPI the fits and the output are rank 0's (its average holds every
     * rank's frames); the others end with its status */
    int root = mimas_par_rank() == 0;
    mimas_band *b = NULL;
    if (!status && root)
        status = mimas_band_analyse(fs, &a.o, &b, &err);
    mimas_fieldset_close(fs);
    mimas_band_plot_options po = {a.fenistein ? a.rs : 0, a.fenistein ? a.h : 0};
    if (!status && root && a.plot)
        status = mimas_band_plot(b, &po, a.plot, &err);
    band_table t = {&a, b};
    if (!status && root)
        status = cli_write_table(a.output, write_table, &t, &err);
    mimas_band_free(b);
    status = mimas_par_share(status, NULL, 0, &err);
    if (status)
        return cli_fail(cmd, mimas_exit_status(status), "%s", err.msg);
    return 0;
}

const cli_command cmd_shearband = {
    "shearband",
    "shear band centre and width per layer from erf fits of omega(r)",
    "FIELDS.h5|INPUT... --omega OMEGA [options]",
    "Fits the angular velocity profile of every height layer of an r-z field\n"
    "file of mimas average (omega, or v_phi/r) by omega(r)/OMEGA = 0.5 + 0.5\n"
    "erf((r - Rc)/W) (--model 2) or A + B erf((r - Rc)/W) (--model 4) with GSL's\n"
    "trust-region least squares, weighted by the standard errors when the file\n"
    "has them (docs/theory.md §7.1).  Raw particle input is first averaged with bins on an\n"
    "r-z grid chosen from the data (the grid is said on standard error).  Writes\n"
    "one row per layer: z Rc Rc_err W W_err chi2 npts [A A_err B B_err]\n"
    "[Rc_fenistein] status; a layer that could not be fitted has nan values and\n"
    "the status few_points, no_convergence or undetermined (docs/shearband.md).",
    options,
    sizeof options / sizeof options[0],
    1,
    run,
    "# the band of a ring shear cell turning at Omega = 2 pi 0.01 rad/s, from the field\n"
    "# file of mimas average, with Fenistein and van Hecke's prediction for a split radius\n"
    "# of 0.085 m and a fill height of 0.038 m, and a picture; the layers that could be fitted\n"
    "mimas average run.h5 --grid r=0.0147:0.11:39,z=0:0.038:20 --weight bins --from 5 \\\n"
    "    --exclude-types 2 -o fields.h5\n"
    "mimas shearband fields.h5 --omega 0.0628319 --fenistein 0.085,0.038 --plot band.png \\\n"
    "    | awk '$NF == \"ok\"'\n"
    "\n"
    "# straight from the particles (the r-z grid it chooses is said on standard error),\n"
    "# with the four-parameter profile\n"
    "mimas shearband run.h5 --omega 0.0628319 --from 5 --model 4",
};
