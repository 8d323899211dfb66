#include <config.h>

#include "cli_study.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

void cli_study_init(cli_study *s)
{
    memset(s, 0, sizeof *s);
    s->lo = -INFINITY;
    s->hi = INFINITY;
}

void cli_study_free(cli_study *s)
{
    for (size_t k = 0; s->params && k < s->nruns; k++)
        mimas_parameters_free(&s->params[k]);
    free(s->params);
    free(s->x);
    cli_study_init(s);
}

int cli_study_on(const cli_study *s)
{
    return s->name || s->values;
}

int cli_study_option(const cli_command *cmd, cli_study *s, size_t k, const char *arg)
{
    switch (k) {
    case 0: s->name = arg; return 0;
    case 1: s->values = arg; return 0;
    case 2:
        if (cli_parse_range(arg, &s->lo, &s->hi))
            return cli_fail(cmd, 1, "--study-range needs LO:HI with LO < HI (either may be left "
                            "out), not '%s'", arg);
        return 0;
    case 3: s->trends = arg; return 0;
    }
    return 1;
}

int cli_study_table_option(const cli_command *cmd, cli_table_options *t, cli_study *s, size_t k,
                           const char *arg)
{
    return k < CLI_TABLE_NOPTIONS ? cli_table_option(cmd, t, k, arg)
                                  : cli_study_option(cmd, s, k - CLI_TABLE_NOPTIONS, arg);
}

int cli_study_begin(const cli_command *cmd, cli_study *s, char *const *inputs, int ninput,
                    const cli_inputs *in, const char *one)
{
    size_t ninputs = ninput > 0 ? (size_t)ninput : 0;
    if (cli_refuse_input_as_output(cmd, s->trends, in, inputs, ninput))
        return 1;
    if (s->name && s->values)
        return cli_fail(cmd, 1, "--study and --study-values exclude each other");
    if (!cli_study_on(s)) {
        if (s->trends || isfinite(s->lo) || isfinite(s->hi))
            return cli_fail(cmd, 1, "--study-range and --trends need --study or --study-values");
        if (one && ninputs != 1)
            return cli_fail(cmd, 1, "needs one %s, or several with --study or --study-values; "
                            "not %zu inputs", one, ninputs);
        return 0;
    }
    if (ninputs < 2)
        return cli_fail(cmd, 1, "a study compares two or more runs, not %zu", ninputs);
    s->nruns = ninputs;
    s->x = malloc(ninputs * sizeof *s->x);
    s->params = calloc(ninputs, sizeof *s->params);
    if (!s->x || !s->params)
        return cli_fail(cmd, 2, "out of memory");
    if (!s->values)
        return 0;
    size_t n, max = ninputs + 4096;
    mimas_error err;
    double *v = malloc(max * sizeof *v);
    int rc = !v ? cli_fail(cmd, 2, "out of memory")
             : mimas_study_parse_values(s->values, v, max, &n, &err)
                 ? cli_fail(cmd, 1, "--study-values: %s", err.msg)
             : n != ninputs ? cli_fail(cmd, 1, "--study-values gives %zu values for %zu inputs",
                                       n, ninputs)
                            : 0;
    if (!rc)
        memcpy(s->x, v, ninputs * sizeof *v);
    free(v);
    return rc;
}

int cli_study_take(cli_study *s, size_t k, const mimas_parameters *ps, const char *source,
                   mimas_error *err)
{
    int rc = mimas_parameters_copy(&s->params[k], ps, err);
    if (rc || s->values)
        return rc;
    rc = mimas_study_value(ps, source, s->name, &s->x[k], err);
    const mimas_parameter *p = NULL;
    if (!rc && k == 0 && mimas_parameters_find(ps, s->name, &p, NULL) == MIMAS_OK && p)
        snprintf(s->unit, sizeof s->unit, "%s", p->unit);
    return rc;
}

void cli_study_note(const cli_command *cmd, const cli_study *s)
{
    const mimas_parameters **ps = malloc(s->nruns * sizeof *ps);
    if (!s->name || !ps) {
        free(ps);
        return;
    }
    for (size_t k = 0; k < s->nruns; k++)
        ps[k] = &s->params[k];
    char list[1024];
    mimas_study_differences(ps, s->nruns, s->name, list, sizeof list);
    if (list[0])
        fprintf(stderr, "mimas %s: note: the runs differ also in %s\n", cmd->name, list);
    free(ps);
}

const char *cli_study_label(const cli_study *s)
{
    return s->name ? s->name : "study value";
}

int cli_study_trend(const cli_study *s, const double *y, const double *e, mimas_trend *t,
                    mimas_error *err)
{
    return mimas_study_trend(s->x, y, e, s->nruns, s->lo, s->hi, t, err);
}

void cli_study_column(cli_table *t, const cli_study *s)
{
    cli_table_column(t, "study", s->unit[0] ? s->unit : NULL);
}

void cli_study_header(cli_table *t, const cli_study *s, const char *const *names,
                      const char *const *units, size_t n)
{
    if (s)
        cli_study_column(t, s);
    cli_table_columns(t, names, units, n);
    cli_table_header_end(t);
}

static void write_trends(FILE *out, const cli_table_options *to, const cli_trend_row *rows,
                         size_t n)
{
    cli_table t;
    cli_table_start(&t, out, to);
    static const char *const cols[] = {"table", "parameter", "lo", "hi", "nruns", "A1",
                                       "A1_err", "A2", "A2_err", "change_first",
                                       "change_first_err", "change_rest", "change_rest_err",
                                       "status"};
    static const char *const units[] = {NULL, NULL, NULL, NULL, NULL, NULL, NULL, NULL, NULL,
                                        "%", "%", "%", "%", NULL};
    cli_study_header(&t, NULL, cols, units, sizeof cols / sizeof cols[0]);
    for (size_t k = 0; k < n; k++) {
        const mimas_trend *tr = &rows[k].trend;
        cli_table_text(&t, rows[k].table);
        cli_table_text(&t, rows[k].parameter);
        cli_table_double(&t, rows[k].lo);
        cli_table_double(&t, rows[k].hi);
        cli_table_int(&t, (long long)tr->line.npts);
        const double v[8] = {tr->line.p[1], tr->line.err[1], tr->line.p[0], tr->line.err[0],
                             tr->change_first, tr->change_first_err, tr->change_rest,
                             tr->change_rest_err};
        for (int q = 0; q < 8; q++)
            cli_table_double(&t, v[q]);
        cli_table_text(&t, mimas_fit_status_name(tr->line.status));
        cli_table_row_end(&t);
    }
    cli_table_end(&t);
}

int cli_study_write(const cli_study *s, const char *output, const cli_table_options *to,
                    void (*write_runs)(cli_table *t, const void *ctx), const void *ctx,
                    const cli_trend_row *rows, size_t nrows, mimas_error *err)
{
    cli_output runs = {0}, trends = {0};
    int rc = cli_output_open(&runs, output, err);
    if (!rc && s->trends)
        rc = cli_output_open(&trends, s->trends, err);
    int bad = 0;
    if (!rc) {
        cli_table t;
        cli_table_start(&t, runs.fp, to);
        write_runs(&t, ctx);
        cli_table_end(&t);
        FILE *fp = s->trends ? trends.fp : runs.fp;
        if (!s->trends)
            fputs("\n\n", fp);
        write_trends(fp, to, rows, nrows);
        bad = ferror(runs.fp) || (s->trends && ferror(trends.fp));
    }
    int c1 = s->trends ? cli_output_close(&trends, !rc && !bad, err) : MIMAS_OK;
    int c2 = cli_output_close(&runs, !rc && !bad && !c1, err);
    if (!rc && bad && !c1 && !c2)
        rc = mimas_error_set(err, MIMAS_EIO, "%s: cannot write the table",
                             output ? output : "-");
    return rc ? rc : c1 ? c1 : c2;
}
