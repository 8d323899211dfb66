/* mimas energy: mean energies of a run over a time window and their
 * coefficients of variation, from mimas simulate's observables or a
 * LIGGGHTS/LAMMPS log; several runs as a study (docs/energy.md). */
#include <config.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli_study.h"
#include "cli_table.h"
#include "commands.h"
#include "energy.h"
#include "native.h"

static const cli_option options[] = {
    {"from", 0, "T0", "first time to use (s)"},
    {"to", 0, "T1", "last time to use (s)"},
    {"columns", 0, "Q=COLUMN,...", "logs: the thermo column of a quantity (total, kinetic, "
                                   "rotational, elastic, bridge), as the header prints it "
                                   "(default kinetic=KinEng)"},
    {"timestep", 0, "DT", "logs without a Time column: the time step (s; default: the log's "
                          "timestep command)"},
    {"plot", 0, "FILE.png", "with a study: the mean total energy and its coefficient of "
                            "variation against the study variable (gnuplot)"},
    {"output", 'o', "FILE", "write the table to FILE (default: standard output)"},
    CLI_STUDY_TABLE_OPTIONS,
};

enum { O_FROM, O_TO, O_COLUMNS, O_TIMESTEP, O_PLOT, O_OUTPUT, O_TABLE };

typedef struct energy_args {
    const cli_command *cmd;
    mimas_energy_options o;
    cli_window window;
    char columns[512];
    const char *plot, *output;
    cli_table_options table;
    cli_study study;
} energy_args;

/* "Q=COLUMN,..." into o->columns (pointing into a->columns). */
static int parse_columns(energy_args *a, const char *arg)
{
    if (snprintf(a->columns, sizeof a->columns, "%s", arg) >= (int)sizeof a->columns)
        return cli_fail(a->cmd, 1, "--columns is too long");
    char *save = NULL;
    for (char *tok = strtok_r(a->columns, ",", &save); tok; tok = strtok_r(NULL, ",", &save)) {
        char *eq = strchr(tok, '=');
        int q = 0;
        if (eq) {
            *eq = '\0';
            while (q < MIMAS_ENERGY_N && strcmp(tok, mimas_energy_name(q)))
                q++;
        }
        if (!eq || q == MIMAS_ENERGY_N || !eq[1])
            return cli_fail(a->cmd, 1, "--columns takes QUANTITY=COLUMN,... with QUANTITY total, "
                            "kinetic, rotational, elastic or bridge, not '%s'", arg);
        a->o.columns[q] = eq + 1;
    }
    return 0;
}

static int on_option(void *ctx, size_t opt, const char *arg)
{
    energy_args *a = ctx;
    switch (opt) {
    case O_FROM:
    case O_TO: return cli_window_time(a->cmd, &a->window, opt == O_FROM, arg);
    case O_COLUMNS: return parse_columns(a, arg);
    case O_TIMESTEP:
        if (cli_parse_double(arg, &a->o.dt) || !(a->o.dt > 0))
            return cli_fail(a->cmd, 1, "--timestep needs a positive time in s, not '%s'", arg);
        return 0;
    case O_PLOT: a->plot = arg; return 0;
    case O_OUTPUT: a->output = arg; return 0;
    }
    return cli_study_table_option(a->cmd, &a->table, &a->study, opt - O_TABLE, arg);
}

/* The header of the table; with study, first the study column. */
static void write_header(cli_table *t, const cli_study *study)
{
    static const char *const cols[] = {"energy", "mean", "std", "cv_percent", "frames", "from",
                                       "to"};
    static const char *const units[] = {NULL, "J", "J", "%", NULL, "s", "s"};
    cli_study_header(t, study, cols, units, 7);
}

/* A row per quantity present; with study, first the study column holding *study. */
static void write_rows(cli_table *t, const mimas_energy *e, const double *study)
{
    for (int q = 0; q < MIMAS_ENERGY_N; q++) {
        const mimas_energy_stat *s = &e->q[q];
        if (!s->present)
            continue;
        if (study)
            cli_table_double(t, *study);
        cli_table_text(t, mimas_energy_name(q));
        cli_table_double(t, s->mean);
        cli_table_double(t, s->sd);
        cli_table_double(t, 100 * s->cv);
        cli_table_int(t, (long long)s->n);
        cli_table_double(t, e->from);
        cli_table_double(t, e->to);
        cli_table_row_end(t);
    }
}

static void write_table(cli_table *t, const void *ctx)
{
    write_header(t, NULL);
    write_rows(t, ctx, NULL);
}

/* ---- a study ---- */

typedef struct energy_study {
    const cli_study *study;
    mimas_energy *runs;
    cli_trend_row trends[2 * MIMAS_ENERGY_N];
    size_t ntrends;
} energy_study;

static void write_runs(cli_table *t, const void *ctx)
{
    const energy_study *st = ctx;
    write_header(t, st->study);
    for (size_t k = 0; k < st->study->nruns; k++)
        write_rows(t, &st->runs[k], &st->study->x[k]);
}

/* The parameters of a run: a native file's, none for a log. */
static int run_parameters(const char *path, mimas_parameters *ps, mimas_error *err)
{
    mimas_parameters_clear(ps);
    FILE *fp = fopen(path, "rb");
    char sig[8] = {0};
    size_t n = fp ? fread(sig, 1, 8, fp) : 0;
    if (fp)
        fclose(fp);
    if (n < 8 || memcmp(sig, "\x89HDF\r\n\x1a\n", 8))
        return MIMAS_OK;
    mimas_native *r;
    int rc = mimas_native_open(&r, path, err);
    if (!rc)
        rc = mimas_parameters_copy(ps, mimas_native_parameters(r), err);
    mimas_native_close(r);
    return rc;
}

/* Trends of the mean and the coefficient of variation of every quantity
 * all runs have; y holds 2 MIMAS_ENERGY_N rows of nruns values. */
static int energy_trends(energy_study *st, double *y, mimas_error *err)
{
    size_t n = st->study->nruns;
    int rc = MIMAS_OK;
    static const char *const what[2] = {"mean", "cv_percent"};
    for (int q = 0; !rc && q < MIMAS_ENERGY_N; q++) {
        int all = 1;
        for (size_t k = 0; k < n; k++)
            all &= st->runs[k].q[q].present;
        for (int w = 0; all && !rc && w < 2; w++) {
            cli_trend_row *t = &st->trends[st->ntrends++];
            double *v = y + (size_t)(2 * q + w) * n;
            t->table = mimas_energy_name(q);
            t->parameter = what[w];
            t->lo = INFINITY;
            t->hi = -INFINITY;
            for (size_t k = 0; k < n; k++) {
                const mimas_energy_stat *s = &st->runs[k].q[q];
                v[k] = w ? 100 * s->cv : s->mean;
                t->lo = fmin(t->lo, st->runs[k].from);
                t->hi = fmax(t->hi, st->runs[k].to);
            }
            rc = cli_study_trend(st->study, v, NULL, &t->trend, err);
        }
    }
    return rc;
}

static int plot_study(const energy_args *a, const energy_study *st, const double *y,
                      mimas_error *err)
{
    mimas_study_series se[2];
    mimas_study_panel pn[2];
    size_t np = 0, n = st->study->nruns;
    static const char *const title[2] = {"mean total energy", "coefficient of variation"};
    static const char *const unit[2] = {"E_total (J)", "sd/mean (%)"};
    for (size_t k = 0; k < st->ntrends; k++) {
        const cli_trend_row *t = &st->trends[k];
        if (strcmp(t->table, "total"))
            continue;
        int w = strcmp(t->parameter, "mean") != 0;
        snprintf(se[np].label, sizeof se[np].label, "total = kinetic + rotational");
        se[np].y = y + (size_t)(2 * MIMAS_ENERGY_TOTAL + w) * n;
        se[np].yerr = NULL;
        se[np].trend = &t->trend;
        pn[np] = (mimas_study_panel){title[w], unit[w], &se[np], 1};
        np++;
    }
    if (!np)
        return mimas_error_set(err, MIMAS_EDATA, "--plot: the runs have no total energy "
                               "(kinetic and rotational)");
    return mimas_study_plot(a->plot, cli_study_label(st->study), st->study->x, n, pn, np,
                            (int)np, err);
}

static int run_study(energy_args *a, char **inputs, mimas_error *err)
{
    cli_study *s = &a->study;
    size_t n = s->nruns;
    energy_study st = {s, calloc(n, sizeof *st.runs), {{0}}, 0};
    double *y = malloc(2 * MIMAS_ENERGY_N * n * sizeof *y);
    mimas_parameters ps;
    mimas_parameters_init(&ps);
    int status = st.runs && y ? MIMAS_OK : mimas_error_set(err, MIMAS_EIO, "out of memory");
    for (size_t k = 0; !status && k < n; k++) {
        status = run_parameters(inputs[k], &ps, err);
        if (!status)
            status = cli_study_take(s, k, &ps, inputs[k], err);
        if (!status)
            status = mimas_energy_of(inputs[k], &a->o, &st.runs[k], err);
    }
    mimas_parameters_free(&ps);
    if (!status) {
        cli_study_note(a->cmd, s);
        status = energy_trends(&st, y, err);
    }
    if (!status && a->plot)
        status = plot_study(a, &st, y, err);
    if (!status)
        status = cli_study_write(s, a->output, &a->table, write_runs, &st, st.trends,
                                 st.ntrends, err);
    free(st.runs);
    free(y);
    return status;
}

static int run(const cli_command *cmd, int argc, char **argv)
{
    energy_args a;
    memset(&a, 0, sizeof a);
    a.cmd = cmd;
    mimas_energy_options_default(&a.o);
    cli_study_init(&a.study);
    int first;
    int rc = cli_parse(cmd, argc, argv, on_option, &a, NULL, &first);
    if (!rc)
        rc = cli_study_begin(cmd, &a.study, argv + first, argc - first, NULL,
                             "run (RUN.h5 or a log)");
    if (!rc && a.plot && !cli_study_on(&a.study))
        rc = cli_fail(cmd, 1, "--plot draws a study: it needs --study or --study-values");
    if (!rc)
        rc = cli_refuse_input_as_output(cmd, a.output, NULL, argv + first, argc - first) ||
             cli_refuse_input_as_output(cmd, a.plot, NULL, argv + first, argc - first);
    if (rc) {
        cli_study_free(&a.study);
        return rc < 0 ? 0 : rc;
    }
    if (a.window.has_from)
        a.o.from = a.window.from;
    if (a.window.has_to)
        a.o.to = a.window.to;
    mimas_error err;
    int status;
    if (cli_study_on(&a.study)) {
        status = run_study(&a, argv + first, &err);
    } else {
        mimas_energy e;
        status = mimas_energy_of(argv[first], &a.o, &e, &err);
        if (!status)
            status = cli_table_write(a.output, &a.table, write_table, &e, &err);
    }
    cli_study_free(&a.study);
    if (status)
        return cli_fail(cmd, mimas_exit_status(status), "%s", err.msg);
    return 0;
}

const cli_command cmd_energy = {
    "energy",
    "mean energies of a run and their coefficient of variation over a time window",
    "RUN.h5|LOG [--from T0] [--to T1] [options] | RUN... --study NAME|--study-values V1,...",
    "The mean over the frames in --from .. --to of the total (kinetic +\n"
    "rotational), kinetic, rotational, elastic and bridge energy of the\n"
    "particles, the standard deviation over the frames and the coefficient of\n"
    "variation sd/mean in percent (Uhlig 2012, Table 4.4).  A native file gives\n"
    "the energies mimas simulate writes per frame (/observables/all); a LAMMPS or\n"
    "LIGGGHTS log the columns of its thermo output (kinetic: KinEng; the others\n"
    "with --columns).  Writes one row per quantity: energy mean std cv_percent\n"
    "frames from to (J; s).  With --study or --study-values every input is one\n"
    "run: the rows with a first column study, then the trends of the mean and\n"
    "of cv_percent against the study variable (docs/energy.md, docs/study.md).",
    options,
    sizeof options / sizeof options[0],
    0,
    run,
    "# the mean kinetic energy of a LIGGGHTS run from its thermo log, after 0.1 s\n"
    "mimas energy log.periodic --from 0.1\n"
    "\n"
    "# the same of two runs as a study of a value given per run, trends included\n"
    "mimas energy log.periodic log.periodic --study-values 0,0.01 --from 0.1 --trends trends.tsv",
};
