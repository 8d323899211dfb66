/* mimas disperse: dispersion of cohorts and the mean-square displacement of
 * all particles, with diffusion coefficients (docs/disperse.md). */
#include <config.h>

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <unistd.h>

#include "commands.h"
#include "parallel.h"
#include "disperse.h"
#include "fit.h"
#include "h5util.h"
#include "outfile.h"
#include "plot.h"
#include "reader.h"

static const cli_option options[] = {
    {"cohort", 0, "SPEC", "particles followed together (repeat for several; default all): all, "
                          "types:L, ids:FILE, inserted:T0:T1 (first seen at T0 <= t <= T1), "
                          "region:box:X0,Y0,Z0:X1,Y1,Z1@T, region:slab:S0:S1@T or "
                          "region:cylinder:R[:S0:S1]@T (inside in the first frame at or after "
                          "T; slab and cylinder about --axis)"},
    {"axis", 0, "X0,Y0,Z0,DX,DY,DZ", "the transport axis: components along and across it "
                                     "(default: the input's tube axis, else z through the "
                                     "origin)"},
    {"remove-drift", 0, NULL, "MSD and VACF of the motion relative to the selection's mean "
                              "displacement and velocity"},
    {"fit-from", 0, "L", "cohort fits over the frames where sigma along the axis exceeds L (m; "
                         "Strauss 2005: the plug length)"},
    {"fit-lags", 0, "T0:T1", "fits over lag times T0 to T1 (s); for cohorts, the time since "
                             "every member is present (default: 10 % to 50 % of the longest "
                             "lag; cohorts: every frame with all members)"},
    {"max-lag", 0, "T", "lags up to T (s) (default: all)"},
    {"vacf", 0, NULL, "also the velocity autocorrelation and the Green-Kubo D (needs "
                      "velocities)"},
    {"from", 0, "T0", "first time to use (s)"},
    {"to", 0, "T1", "last time to use (s)"},
    {"every", 0, "K", "use every K-th frame of those selected (frames must end up equally "
                      "spaced)"},
    {"types", 0, "L", "use only particles of these types (comma list)"},
    {"exclude-types", 0, "L", "leave out particles of these types"},
    {"memory", 0, "BYTES", "the peak memory of the run, with suffix k, M or G (default: a "
                           "quarter of the RAM); trajectories beyond it go to a scratch file "
                           "next to the output"},
    {"output", 'o', "OUT.h5", "write every table to HDF5 with units and definitions"},
    {"tsv", 0, "FILE", "write the MSD table to FILE, or - for standard output (the default "
                       "without -o)"},
    {"cohorts", 0, "FILE", "write the cohort table (sigma^2(t)) to FILE, or -"},
    {"diffusion", 0, "FILE", "write the diffusion coefficients to FILE, or -"},
    {"plot", 0, "FILE.png", "draw sigma^2(t) and MSD(lag) with the fitted lines (gnuplot)"},
};

enum { O_COHORT, O_AXIS, O_DRIFT, O_FIT_FROM, O_FIT_LAGS, O_MAX_LAG, O_VACF, O_FROM, O_TO,
       O_EVERY, O_TYPES, O_EXCLUDE, O_MEMORY, O_OUTPUT, O_TSV, O_COHORTS, O_DIFFUSION,
       O_PLOT };

typedef struct disperse_args {
    const cli_command *cmd;
    mimas_disperse_options o;
    const char *cohorts[64];
    size_t ncohorts;
    int32_t types[64];
    int types_given, memory_given;
    cli_window window;
    const char *output, *tsv, *cohort_table, *diffusion_table, *plot;
} disperse_args;

/* BYTES with an optional suffix k, M, G or T (powers of 1024). */
static int parse_bytes(const char *arg, size_t *v)
{
    char *end;
    errno = 0;
    double x = strtod(arg, &end);
    double scale = 1;
    switch (*end) {
    case 'k': case 'K': scale = 1024.0; end++; break;
    case 'm': case 'M': scale = 1024.0 * 1024; end++; break;
    case 'g': case 'G': scale = 1024.0 * 1024 * 1024; end++; break;
    case 't': case 'T': scale = 1024.0 * 1024 * 1024 * 1024; end++; break;
    }
    if (end == arg || *end || errno == ERANGE || !(x > 0) || !(x * scale < 1e18))
        return -1;
    *v = (size_t)(x * scale);
    return 0;
}

static int on_option(void *ctx, size_t opt, const char *arg)
{
    disperse_args *a = ctx;
    mimas_disperse_options *o = &a->o;
    switch (opt) {
    case O_COHORT:
        if (a->ncohorts >= 64)
            return cli_fail(a->cmd, 1, "at most 64 --cohort options");
        a->cohorts[a->ncohorts++] = arg;
        return 0;
    case O_AXIS: o->axis = arg; return 0;
    case O_DRIFT: o->remove_drift = 1; return 0;
    case O_FIT_FROM:
        if (cli_parse_double(arg, &o->fit_from) || !(o->fit_from >= 0))
            return cli_fail(a->cmd, 1, "--fit-from needs a length of at least 0 (m), not '%s'",
                            arg);
        o->has_fit_from = 1;
        return 0;
    case O_FIT_LAGS:
        if (cli_parse_pair(arg, &o->fit_lo, &o->fit_hi) || !(o->fit_lo >= 0) ||
            !(o->fit_hi > o->fit_lo))
            return cli_fail(a->cmd, 1, "--fit-lags needs T0:T1 with 0 <= T0 < T1 (s), not '%s'",
                            arg);
        o->has_fit_lags = 1;
        return 0;
    case O_MAX_LAG:
        if (cli_parse_double(arg, &o->max_lag) || !(o->max_lag > 0))
            return cli_fail(a->cmd, 1, "--max-lag needs a positive time (s), not '%s'", arg);
        o->has_max_lag = 1;
        return 0;
    case O_VACF: o->vacf = 1; return 0;
    case O_FROM:
    case O_TO: return cli_window_time(a->cmd, &a->window, opt == O_FROM, arg);
    case O_EVERY: return cli_window_every(a->cmd, &a->window, arg);
    case O_TYPES:
    case O_EXCLUDE:
        if (a->types_given++)
            return cli_fail(a->cmd, 1, "--types and --exclude-types exclude each other");
        o->exclude = opt == O_EXCLUDE;
        return cli_parse_types(a->cmd, opt == O_TYPES ? "types" : "exclude-types", arg,
                               a->types, 64, &o->ntypes);
    case O_MEMORY:
        if (parse_bytes(arg, &o->memory))
            return cli_fail(a->cmd, 1, "--memory needs a size in bytes (suffix k, M or G), not "
                            "'%s'", arg);
        a->memory_given = 1;
        return 0;
    case O_OUTPUT: a->output = arg; return 0;
    case O_TSV: a->tsv = arg; return 0;
    case O_COHORTS: a->cohort_table = arg; return 0;
    case O_DIFFUSION: a->diffusion_table = arg; return 0;
    case O_PLOT: a->plot = arg; return 0;
    }
    return 1;
}

static int is_stdout(const char *path) { return path && !strcmp(path, "-"); }

/* Which tables go where: the MSD table to standard output unless -o or
 * another table takes it; at most one table there. */
static int settle_outputs(disperse_args *a)
{
    int taken = is_stdout(a->cohort_table) + is_stdout(a->diffusion_table);
    if (!a->tsv && !a->output && !taken)
        a->tsv = "-";
    if (taken + is_stdout(a->tsv) > 1)
        return cli_fail(a->cmd, 1, "only one table can go to standard output (--tsv, "
                        "--cohorts, --diffusion)");
    return 0;
}

/* The folder of the first output that is a file (not standard output, a
 * device or a pipe: /dev is no place for scratch): the scratch file goes there. */
static void scratch_folder(const disperse_args *a, char *dir, size_t len)
{
    const char *paths[] = {a->output, a->tsv, a->cohort_table, a->diffusion_table, a->plot};
    dir[0] = '\0';
    for (size_t k = 0; k < sizeof paths / sizeof paths[0]; k++) {
        if (!paths[k] || is_stdout(paths[k]) || mimas_output_is_special(paths[k]))
            continue;
        const char *slash = strrchr(paths[k], '/');
        if (!slash)
            snprintf(dir, len, ".");
        else if (slash == paths[k])
            snprintf(dir, len, "/");
        else
            snprintf(dir, len, "%.*s", (int)(slash - paths[k]), paths[k]);
        return;
    }
}

/* The resident memory the process holds now (Linux: /proc/self/statm;
 * elsewhere the peak so far). */
static size_t resident_now(void)
{
    FILE *fp = fopen("/proc/self/statm", "r");
    unsigned long size, pages;
    int got = fp && fscanf(fp, "%lu %lu", &size, &pages) == 2;
    if (fp)
        fclose(fp);
    if (got)
        return (size_t)pages * (size_t)sysconf(_SC_PAGESIZE);
    struct rusage u;
    return getrusage(RUSAGE_SELF, &u) == 0 ? (size_t)u.ru_maxrss * 1024 : 0;
}

static size_t quarter_of_ram(void)
{
    long pages = sysconf(_SC_PHYS_PAGES), size = sysconf(_SC_PAGESIZE);
    if (pages <= 0 || size <= 0)
        return (size_t)1 << 30;
    return (size_t)pages / 4 * (size_t)size;
}

/* ---- the tables ---- */

static void value(FILE *out, const char *sep, double v)
{
    if (isnan(v))
        fprintf(out, "%snan", sep);
    else
        fprintf(out, "%s%.17g", sep, v);
}

static void header(FILE *out, mimas_disperse_table t, const char *sep)
{
    size_t n;
    const mimas_disperse_column *c = mimas_disperse_columns(t, &n);
    for (size_t k = 0; k < n; k++)
        fprintf(out, "%s%s", k ? "\t" : sep, c[k].name);
}

static void write_lags(FILE *out, const void *ctx)
{
    const mimas_disperse_result *r = ctx;
    header(out, MIMAS_DISPERSE_LAGS, "");
    if (r->vacf)
        header(out, MIMAS_DISPERSE_VACF, "\t");
    fputc('\n', out);
    for (size_t k = 0; k < r->lags; k++) {
        fprintf(out, "%zu", k);
        value(out, "\t", (double)k * r->dt);
        for (int c = 0; c < MIMAS_DC_COUNT; c++)
            value(out, "\t", r->msd[k * MIMAS_DC_COUNT + c]);
        fprintf(out, "\t%.0f", r->count[k]);
        for (int c = 0; r->vacf && c < MIMAS_DC_COUNT; c++)
            value(out, "\t", r->vacf[k * MIMAS_DC_COUNT + c]);
        fputc('\n', out);
    }
}

static void write_cohorts(FILE *out, const void *ctx)
{
    const mimas_disperse_result *r = ctx;
    header(out, MIMAS_DISPERSE_COHORTS, "");
    fputc('\n', out);
    for (size_t k = 0; k < r->ncohorts; k++)
        for (size_t i = 0; i < r->cohorts[k].nrows; i++) {
            const mimas_disperse_cohort_row *row = &r->cohorts[k].rows[i];
            fputs(r->cohorts[k].spec, out);
            value(out, "\t", row->time);
            fprintf(out, "\t%zu", row->n);
            for (int d = 0; d < 3; d++)
                value(out, "\t", row->mean[d]);
            value(out, "\t", row->sigma2_axial);
            value(out, "\t", row->sigma2_transverse);
            fputc('\n', out);
        }
}

static void write_diffusion(FILE *out, const void *ctx)
{
    const mimas_disperse_result *r = ctx;
    header(out, MIMAS_DISPERSE_DIFFUSION, "");
    fputc('\n', out);
    for (size_t i = 0; i < r->ndiffusion; i++) {
        const mimas_disperse_diffusion *d = &r->diffusion[i];
        fprintf(out, "%s\t%s", d->what, mimas_disperse_component_name(d->component));
        value(out, "\t", d->D);
        value(out, "\t", d->D_err);
        value(out, "\t", d->t0);
        value(out, "\t", d->t1);
        value(out, "\t", d->D_err_fit);
        fprintf(out, "\t%zu\t%s\n", d->npts, mimas_fit_status_name(d->status));
    }
}

/* ---- the run ---- */

static void progress(void *ctx, size_t done, size_t total)
{
    void **pair = ctx;
    cli_progress_count(pair[0], pair[1], "particles analysed:", done, total);
}

/* Reads the frames into d. */
static int stream(disperse_args *a, cli_inputs *in, mimas_reader *r, const char *input,
                  mimas_disperse *d, mimas_error *err)
{
    mimas_frame f;
    mimas_frame_init(&f);
    cli_progress prog;
    cli_progress_start(&prog, in);
    cli_progress_total(&prog, r);
    size_t nread = 0;
    int status;
    while ((status = mimas_reader_next(r, &f, err)) == MIMAS_OK) {
        cli_progress_frame(&prog, a->cmd, ++nread, (long long)f.step, f.time);
        int take = cli_window_take(&a->window, &f, input, err);
        if (take < 0) {
            status = MIMAS_EUSAGE;
            break;
        }
        if (!take)
            continue;
        status = mimas_disperse_add(d, &f, err);
        if (status) {
            if (status != MIMAS_EIO && status != MIMAS_EUSAGE)
                mimas_error_prefix(err, "%s: step %lld", input, (long long)f.step);
            break;
        }
    }
    cli_progress_done(&prog);
    mimas_frame_free(&f);
    if (status == MIMAS_END && !mimas_disperse_frames(d))
        status = mimas_error_set(err, MIMAS_EDATA, "%s: no frame in the selected time range",
                                 input);
    return status == MIMAS_END ? MIMAS_OK : status;
}

static void warnings(const disperse_args *a, const cli_inputs *in,
                     const mimas_disperse_result *r, const char *scratch)
{
    const char *name = a->cmd->name;
    if (r->jumps.count)
        fprintf(stderr, "mimas %s: warning: %zu moves of more than a quarter of the box between "
                "frames (the first: particle %lld at time %.10g): the unwrapping may be "
                "ambiguous; use image flags or closer frames\n", name, r->jumps.count,
                (long long)r->jumps.first_id, r->jumps.first_time);
    for (size_t k = 0; k < r->ncohorts; k++)
        if (!r->cohorts[k].size)
            fprintf(stderr, "mimas %s: warning: --cohort %s has no particle\n", name,
                    r->cohorts[k].spec);
    if (r->scratch && !in->quiet)
        fprintf(stderr, "mimas %s: the trajectories exceeded --memory and went to a scratch "
                "file in %s (removed)\n", name, scratch[0] ? scratch : "$TMPDIR or /tmp");
}

/* Every output: the plot and the HDF5 file first, then the tables (under
 * temporary names; one on standard output comes last of all); nothing is
 * left of any if one fails. */
static int write_outputs(const disperse_args *a, const mimas_disperse_result *r, int argc,
                         char **argv, mimas_error *err)
{
    int rc = MIMAS_OK, plotted = 0, written = 0;
    if (a->plot)
        plotted = !(rc = mimas_disperse_plot(r, a->plot, err));
    if (!rc && a->output) {
        char *line = cli_command_line(argc, argv);
        written = !(rc = mimas_disperse_write_h5(r, a->output, line, err));
        free(line);
    }
    const char *paths[3] = {a->tsv, a->cohort_table, a->diffusion_table};
    void (*writers[3])(FILE *, const void *) = {write_lags, write_cohorts, write_diffusion};
    cli_output outs[3];
    memset(outs, 0, sizeof outs);
    /* the files first, standard output last */
    for (int pass = 0; pass < 2; pass++)
        for (int k = 0; k < 3 && !rc; k++) {
            if (!paths[k] || is_stdout(paths[k]) != pass)
                continue;
            rc = cli_output_open(&outs[k], paths[k], err);
            if (!rc) {
                writers[k](outs[k].fp, r);
                if (ferror(outs[k].fp))
                    rc = mimas_error_set(err, MIMAS_EIO, "%s: cannot write the table", paths[k]);
            }
        }
    int ok = rc == MIMAS_OK;
    for (int k = 0; k < 3; k++) {
        int closed = cli_output_close(&outs[k], ok, err);
        if (closed && !rc)
            rc = closed;
    }
    /* a table that could not be put in place takes the others with it */
    if (rc && plotted)
        remove(a->plot);
    if (rc && written)
        remove(a->output);
    return rc;
}

static int run(const cli_command *cmd, int argc, char **argv)
{
    disperse_args a;
    memset(&a, 0, sizeof a);
    a.cmd = cmd;
    cli_inputs in = {0};
    int first;
    int rc = cli_parse(cmd, argc, argv, on_option, &a, &in, &first);
    if (!rc)
        rc = settle_outputs(&a);
    char scratch[4096];
    scratch_folder(&a, scratch, sizeof scratch);
    a.o.types = a.types;
    a.o.cohorts = a.cohorts;
    a.o.ncohorts = a.ncohorts;
    a.o.scratch_dir = scratch[0] ? scratch : NULL;
    if (!a.memory_given)
        a.o.memory = quarter_of_ram();
    /* --memory bounds the whole process, with what it holds already */
    a.o.memory_held = resident_now();
    a.o.resident = resident_now;
    /* HDF5's own free lists within the headroom --memory leaves */
    h5_limit_free_lists((size_t)2 << 20);
    cli_progress prog;
    cli_progress_start(&prog, &in);
    void *pair[2] = {&prog, (void *)cmd};
    a.o.progress = progress;
    a.o.progress_ctx = pair;
    mimas_error err;
    mimas_disperse *d = NULL;
    if (!rc && mimas_disperse_create(&d, &a.o, &err))
        rc = cli_fail(cmd, mimas_exit_status(err.code), "%s", err.msg);
    mimas_reader *r = NULL;
    if (!rc)
        rc = cli_open_inputs(cmd, &in, argc, argv, first, &r);
    if (rc) {
        mimas_disperse_free(d);
        mimas_reader_close(r);
        cli_inputs_free(&in);
        return rc < 0 ? 0 : rc;
    }
    int status = stream(&a, &in, r, argv[first], d, &err);
    mimas_reader_close(r);
    /* under MPI every rank reads every frame; the analysis splits the particles */
    status = mimas_par_agree(status, SIZE_MAX, &err);
    if (!status)
        status = mimas_disperse_finish(d, &err);
    cli_progress_done(&prog);
    if (status && status != MIMAS_EUSAGE && status != MIMAS_EIO && !strstr(err.msg, argv[first]))
        mimas_error_prefix(&err, "%s", argv[first]);
    /* under MPI the tables are rank 0's (the others' sums are merged into
     * its own); the others end with its status */
    const mimas_disperse_result *res = mimas_disperse_result_of(d);
    if (!status && mimas_par_rank() == 0) {
        warnings(&a, &in, res, scratch);
        status = write_outputs(&a, res, argc, argv, &err);
    }
    status = mimas_par_share(status, NULL, 0, &err);
    mimas_disperse_free(d);
    cli_inputs_free(&in);
    if (status)
        return cli_fail(cmd, mimas_exit_status(status), "%s", err.msg);
    return 0;
}

const cli_command cmd_disperse = {
    "disperse",
    "dispersion of cohorts and mean-square displacement, with diffusion coefficients",
    "INPUT... [--cohort SPEC]... [--axis X0,Y0,Z0,DX,DY,DZ] [--remove-drift] "
    "[--fit-from L | --fit-lags T0:T1] [--max-lag T] [--vacf] [--from T0] [--to T1] "
    "[--every K] [--types L | --exclude-types L] [--memory BYTES] [-o OUT.h5] [--tsv FILE|-] "
    "[--cohorts FILE|-] [--diffusion FILE|-] [--plot FILE.png]",
    "Follows every particle by its id through equally spaced frames, unwrapped\n"
    "through periodic faces (image flags when the input has them, else the\n"
    "minimum image between frames).  Per cohort (--cohort): the mean trajectory\n"
    "<x>(t) and sigma^2(t) = <|x - <x>|^2> along --axis and across it, with D from\n"
    "the line sigma^2 = 2 D t + c (Strauss 2005).  For all selected particles: the\n"
    "mean-square displacement by lag, per component, by FFT (Calandrini et al.\n"
    "2011), with D from MSD = 2 d D t + c for each component of d dimensions;\n"
    "--vacf adds the velocity autocorrelation and the Green-Kubo D.  D_err is the\n"
    "jackknife over 16 groups of particles.  Tables: the MSD (--tsv, standard output\n"
    "by default), the cohorts (--cohorts), the coefficients (--diffusion), all of\n"
    "them in -o OUT.h5.  Trajectories beyond --memory go to a scratch file\n"
    "(docs/disperse.md).",
    options,
    sizeof options / sizeof options[0],
    1,
    run,
    "# the grains that entered in the first half second, fitted where their spread\n"
    "# exceeds a plug length of 5 cm, and the MSD of all grains relative to the\n"
    "# conveying (docs/disperse.md)\n"
    "mimas disperse run.h5 --cohort inserted:0:0.5 --fit-from 0.05 --remove-drift \\\n"
    "    --cohorts cohort.tsv --diffusion D.tsv --plot disperse.png >msd.tsv\n"
    "\n"
    "# the MSD and the velocity autocorrelation of all particles, to standard output\n"
    "mimas disperse run.h5 --vacf",
};
