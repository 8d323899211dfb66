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

int cli_study_begin(const cli_command *cmd, cli_study *s, size_t ninputs)
{
    if (s->name && s->values)
        return cli_fail(cmd, 1, "--study and --study-values exclude each other");
    if (!cli_study_on(s)) {
        if (s->trends || isfinite(s->lo) || isfinite(s->hi))
            return cli_fail(cmd, 1, "--study-range and --trends need --study or --study-values");
        return 0;
    }
    if (ninputs < 2)
        return cli_fail(cmd, 1, "a study compares two or more runs, not %zu", ninputs);
    s->nruns = ninputs;
    s->x = malloc(ninputs * sizeof *s->x);
    if (!s->x)
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
    if (s->values)
        return MIMAS_OK;
    return mimas_study_value(ps, source, s->name, &s->x[k], err);
}

void cli_study_note(const cli_command *cmd, const cli_study *s,
                    const mimas_parameters *const *ps, size_t n)
{
    if (!s->name)
        return;
    char list[1024];
    mimas_study_differences(ps, n, s->name, list, sizeof list);
    if (list[0])
        fprintf(stderr, "mimas %s: note: the runs differ also in %s\n", cmd->name, list);
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

int cli_study_write(const cli_study *s, const char *output,
                    void (*write_runs)(FILE *fp, const void *ctx), const void *ctx,
                    const mimas_trend_row *rows, size_t nrows, mimas_error *err)
{
    cli_output runs = {0}, trends = {0};
    int rc = cli_output_open(&runs, output, err);
    if (!rc && s->trends)
        rc = cli_output_open(&trends, s->trends, err);
    if (!rc) {
        write_runs(runs.fp, ctx);
        FILE *fp = s->trends ? trends.fp : runs.fp;
        if (!s->trends)
            fputs("\n\n", fp);
        mimas_trend_table_write(fp, rows, nrows);
    }
    int c1 = s->trends ? cli_output_close(&trends, !rc, err) : MIMAS_OK;
    int c2 = cli_output_close(&runs, !rc && !c1, err);
    return rc ? rc : c1 ? c1 : c2;
}
