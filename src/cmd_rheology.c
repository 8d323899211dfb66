/* mimas rheology: yield line, mu(I), viscosity power laws and windowed
 * viscosities from a field file, or from several as runs of a study
 * (docs/theory.md §7.2, docs/rheology.md, docs/study.md). */
#include <config.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli_study.h"
#include "cli_table.h"
#include "commands.h"
#include "fieldset.h"
#include "rheology.h"

#define MAX_WINDOWS 64

static const cli_option options[] = {
    {"min-shear-rate", 0, "G", "use the cells whose shear rate exceeds G (1/s; default 0.02)"},
    {"p-range", 0, "LO:HI", "and whose pressure is within LO:HI (Pa; either may be left out; "
                            "default 0:)"},
    {"shear-rate-windows", 0, "LO:HI,...", "shear-rate windows for the mean viscosity (default: "
                                           "those of Uhlig 2012, Table 4.6)"},
    {"I-windows", 0, "LO:HI,...", "inertial-number windows for the mean viscosity (default: "
                                  "those of Uhlig 2012, Table 4.7)"},
    {"definition", 0, "general|luding", "general: tau, shear_rate (invariants; default); luding: "
                                        "tau_phi, shear_rate_luding (Uhlig 2012; cylindrical grids)"},
    {"plot", 0, "PREFIX", "draw PREFIX.yield.png, PREFIX.mu_I.png and PREFIX.eta.png (gnuplot); "
                          "with a study PREFIX.study.png"},
    {"output", 'o', "FILE", "write the table to FILE (default: standard output)"},
    CLI_STUDY_TABLE_OPTIONS,
};

enum { O_MIN_RATE, O_P_RANGE, O_RATE_WINDOWS, O_I_WINDOWS, O_DEFINITION, O_PLOT, O_OUTPUT,
       O_TABLE };

typedef struct rheology_args {
    const cli_command *cmd;
    mimas_rheology_options o;
    mimas_rheology_window rate[MAX_WINDOWS], I[MAX_WINDOWS];
    const char *plot, *output;
    cli_table_options table;
    cli_study study;
} rheology_args;

static int on_option(void *ctx, size_t opt, const char *arg)
{
    rheology_args *a = ctx;
    mimas_error err;
    switch (opt) {
    case O_MIN_RATE:
        if (cli_parse_double(arg, &a->o.min_shear_rate) || a->o.min_shear_rate < 0)
            return cli_fail(a->cmd, 1, "--min-shear-rate needs a rate >= 0, not '%s'", arg);
        return 0;
    case O_P_RANGE:
        if (cli_parse_range(arg, &a->o.p_lo, &a->o.p_hi))
            return cli_fail(a->cmd, 1, "--p-range needs LO:HI with LO < HI (either may be left "
                            "out), not '%s'", arg);
        return 0;
    case O_RATE_WINDOWS:
    case O_I_WINDOWS: {
        int rate = opt == O_RATE_WINDOWS;
        size_t *n = rate ? &a->o.nrate_windows : &a->o.nI_windows;
        if (mimas_rheology_parse_windows(arg, rate ? a->rate : a->I, MAX_WINDOWS, n, &err))
            return cli_fail(a->cmd, 1, "--%s: %s", options[opt].name, err.msg);
        if (rate)
            a->o.rate_windows = a->rate;
        else
            a->o.I_windows = a->I;
        return 0;
    }
    case O_DEFINITION:
        if (!strcmp(arg, "general"))
            a->o.definition = MIMAS_RHEOLOGY_GENERAL;
        else if (!strcmp(arg, "luding"))
            a->o.definition = MIMAS_RHEOLOGY_LUDING;
        else
            return cli_fail(a->cmd, 1, "--definition is general or luding, not '%s'", arg);
        return 0;
    case O_PLOT: a->plot = arg; return 0;
    case O_OUTPUT: a->output = arg; return 0;
    }
    return cli_study_table_option(a->cmd, &a->table, &a->study, opt - O_TABLE, arg);
}

/* The header and rows of one analysis; with study, first the study column
 * holding *study. */
static void table_header(cli_table *t, const cli_study *study)
{
    static const char *const cols[] = {"table", "parameter", "value", "error", "npts", "lo",
                                       "hi", "status"};
    cli_study_header(t, study, cols, NULL, 8);
}

static void table_rows(cli_table *t, const mimas_rheology *r, const double *study)
{
    for (size_t k = 0; k < r->nrows; k++) {
        const mimas_rheology_row *w = &r->rows[k];
        if (study)
            cli_table_double(t, *study);
        cli_table_text(t, w->table);
        cli_table_text(t, w->parameter);
        cli_table_double(t, w->value);
        cli_table_double(t, w->error);
        cli_table_int(t, (long long)w->npts);
        cli_table_double(t, w->lo);
        cli_table_double(t, w->hi);
        cli_table_text(t, mimas_fit_status_name(w->status));
        cli_table_row_end(t);
    }
}

/* The units of value, error, lo and hi depend on the row (docs/rheology.md): "-". */
static void write_table(cli_table *t, const void *ctx)
{
    table_header(t, NULL);
    table_rows(t, ctx, NULL);
}

static int run_one(const rheology_args *a, const char *input, mimas_error *err)
{
    mimas_fieldset *fs = NULL;
    mimas_rheology *r = NULL;
    int status = mimas_fieldset_open(&fs, input, err);
    if (!status)
        status = mimas_rheology_analyse(fs, &a->o, &r, err);
    mimas_fieldset_close(fs);
    if (!status && a->plot)
        status = mimas_rheology_plot(r, a->plot, err);
    if (!status)
        status = cli_table_write(a->output, &a->table, write_table, r, err);
    mimas_rheology_free(r);
    return status;
}

/* ---- a study: every input one run ---- */

typedef struct study_result {
    const cli_study *study;
    mimas_rheology **runs;
    cli_trend_row *trends;     /* one per row of an analysis */
    size_t nrows;
} study_result;

static void write_runs(cli_table *t, const void *ctx)
{
    const study_result *res = ctx;
    table_header(t, res->study);
    for (size_t k = 0; k < res->study->nruns; k++)
        table_rows(t, res->runs[k], &res->study->x[k]);
}

/* The trend of every row: the runs' values where they are ok. */
static int trends_of(study_result *res, mimas_error *err)
{
    size_t n = res->study->nruns;
    double *y = malloc(2 * n * sizeof *y), *e = y + n;
    res->trends = calloc(res->nrows, sizeof *res->trends);
    int rc = y && res->trends ? MIMAS_OK : mimas_error_set(err, MIMAS_EIO, "out of memory");
    for (size_t j = 0; !rc && j < res->nrows; j++) {
        cli_trend_row *t = &res->trends[j];
        const mimas_rheology_row *first = &res->runs[0]->rows[j];
        t->table = first->table;
        t->parameter = first->parameter;
        t->lo = INFINITY;
        t->hi = -INFINITY;
        for (size_t k = 0; k < n; k++) {
            const mimas_rheology_row *w = &res->runs[k]->rows[j];
            int ok = w->status == MIMAS_FIT_OK;
            y[k] = ok ? w->value : NAN;
            e[k] = ok ? w->error : NAN;
            t->lo = fmin(t->lo, w->lo);
            t->hi = fmax(t->hi, w->hi);
        }
        if (!(t->lo <= t->hi))
            t->lo = t->hi = NAN;
        rc = cli_study_trend(res->study, y, e, &t->trend, err);
    }
    free(y);
    return rc;
}

/* PREFIX.study.png: tau0, zeta, psi against the study variable, and the
 * windowed viscosities, with their lines. */
static int plot_study(const rheology_args *a, const study_result *res, mimas_error *err)
{
    size_t n = res->study->nruns, nr = res->nrows;
    double *vals = malloc(2 * n * nr * sizeof *vals);
    mimas_study_series *series = calloc(nr, sizeof *series);
    int rc = vals && series ? MIMAS_OK : mimas_error_set(err, MIMAS_EIO, "out of memory");
    static const char *const names[] = {"tau0", "zeta", "psi_deg"};
    static const char *const units[] = {"tau0 (Pa)", "zeta", "psi (deg)"};
    static const char *const windows[] = {"eta_window_shear_rate", "eta_window_I"};
    mimas_study_panel panels[5];
    size_t used = 0;
    for (size_t p = 0; !rc && p < 5; p++) {
        mimas_study_panel *pn = &panels[p];
        pn->series = series + used;
        pn->nseries = 0;
        pn->title = p < 3 ? names[p] : p == 3 ? "eta in shear-rate windows"
                                               : "eta in I windows";
        pn->ylabel = p < 3 ? units[p] : "eta (Pa s)";
        for (size_t j = 0; j < nr; j++) {
            const mimas_rheology_row *w = &res->runs[0]->rows[j];
            int take = p < 3 ? !strcmp(w->table, "yield") && !strcmp(w->parameter, names[p])
                             : !strcmp(w->table, windows[p - 3]);
            if (!take)
                continue;
            mimas_study_series *se = &series[used++];
            double *y = vals + 2 * n * j, *e = y + n;
            for (size_t k = 0; k < n; k++) {
                const mimas_rheology_row *v = &res->runs[k]->rows[j];
                y[k] = v->status == MIMAS_FIT_OK ? v->value : NAN;
                e[k] = v->status == MIMAS_FIT_OK ? v->error : NAN;
            }
            se->y = y;
            se->yerr = e;
            se->trend = &res->trends[j].trend;
            if (p < 3)
                snprintf(se->label, sizeof se->label, "%s", names[p]);
            else
                snprintf(se->label, sizeof se->label, "%.4g <= %s < %.4g", w->lo,
                         p == 3 ? "shear rate" : "I", w->hi);
            pn->nseries++;
        }
    }
    char png[4200];
    snprintf(png, sizeof png, "%s.study.png", a->plot);
    if (!rc)
        rc = mimas_study_plot(png, cli_study_label(res->study), res->study->x, n, panels, 5, 3,
                              err);
    free(vals);
    free(series);
    return rc;
}

static int run_study(rheology_args *a, char **inputs, mimas_error *err)
{
    cli_study *st = &a->study;
    size_t n = st->nruns;
    study_result res = {st, calloc(n, sizeof *res.runs), NULL, 0};
    int status = res.runs ? MIMAS_OK : mimas_error_set(err, MIMAS_EIO, "out of memory");
    for (size_t k = 0; !status && k < n; k++) {
        mimas_fieldset *fs = NULL;
        status = mimas_fieldset_open(&fs, inputs[k], err);
        if (!status)
            status = cli_study_take(st, k, mimas_fieldset_parameters(fs), inputs[k], err);
        if (!status)
            status = mimas_rheology_analyse(fs, &a->o, &res.runs[k], err);
        mimas_fieldset_close(fs);
    }
    if (!status) {
        cli_study_note(a->cmd, st);
        res.nrows = res.runs[0]->nrows;
        status = trends_of(&res, err);
    }
    if (!status && a->plot)
        status = plot_study(a, &res, err);
    if (!status)
        status = cli_study_write(st, a->output, &a->table, write_runs, &res, res.trends,
                                 res.nrows, err);
    for (size_t k = 0; res.runs && k < n; k++)
        mimas_rheology_free(res.runs[k]);
    free(res.runs);
    free(res.trends);
    return status;
}

static int run(const cli_command *cmd, int argc, char **argv)
{
    rheology_args a;
    memset(&a, 0, sizeof a);
    a.cmd = cmd;
    cli_study_init(&a.study);
    mimas_rheology_options_default(&a.o);
    int first;
    int rc = cli_parse(cmd, argc, argv, on_option, &a, NULL, &first);
    if (!rc)
        rc = cli_study_begin(cmd, &a.study, argv + first, argc - first, NULL,
                             "field file (mimas average -o FIELDS.h5)");
    if (!rc)
        rc = cli_refuse_input_as_output(cmd, a.output, NULL, argv + first, argc - first) ||
             cli_refuse_input_as_output(cmd, a.plot, NULL, argv + first, argc - first);
    if (rc) {
        cli_study_free(&a.study);
        return rc < 0 ? 0 : rc;
    }
    mimas_error err;
    int status = cli_study_on(&a.study) ? run_study(&a, argv + first, &err)
                                        : run_one(&a, argv[first], &err);
    cli_study_free(&a.study);
    if (status)
        return cli_fail(cmd, mimas_exit_status(status), "%s", err.msg);
    return 0;
}

const cli_command cmd_rheology = {
    "rheology",
    "yield line, mu(I), viscosity power laws and windows from field files",
    "FIELDS.h5 [options] | FIELDS.h5... --study NAME|--study-values V1,V2,... [options]",
    "Over the cells of a field file of mimas average whose shear rate exceeds\n"
    "--min-shear-rate and whose pressure is in --p-range: the yield line\n"
    "tau = tau0 + zeta p with psi = asin(zeta), the mu(I) law mu = mu_s +\n"
    "(mu_2 - mu_s)/(1 + I0/I), the power laws eta = k shear_rate^n and\n"
    "eta = k I^n, and the mean viscosity in windows of shear rate and of I\n"
    "(docs/theory.md §7.2; Uhlig 2012, Sec. 4.2).  Writes one long table, a row per\n"
    "parameter or window: table parameter value error npts lo hi status\n"
    "(docs/rheology.md).  With --study NAME (a run parameter the field files\n"
    "carry, such as liquid_content) or --study-values, every field file is one\n"
    "run: the rows of every run with a first column study, then the trends table:\n"
    "per row the least-squares line value = A1 study + A2 over the runs and the\n"
    "percentage changes between the lowest study values and to the highest\n"
    "(docs/study.md).",
    options,
    sizeof options / sizeof options[0],
    0,
    run,
    "# yield line, mu(I) and viscosity laws with the shear stress and shear rate of\n"
    "# Uhlig (2012), and the plots wet.yield.png, wet.mu_I.png, wet.eta.png\n"
    "mimas average run.h5 --grid r=0.0147:0.11:39,z=0:0.038:20 --weight bins --from 5 \\\n"
    "    --exclude-types 2 -o fields.h5\n"
    "mimas rheology fields.h5 --definition luding --plot wet\n"
    "\n"
    "# the shear-rate controlled regime only (p > 250 Pa), into a file\n"
    "mimas rheology fields.h5 --definition luding --p-range 250: -o windows.tsv\n"
    "\n"
    "# one number: the slope of the yield line and its error\n"
    "mimas rheology fields.h5 | awk '$1 == \"yield\" && $2 == \"zeta\" { print $3, $4 }'",
};
