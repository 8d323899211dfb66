/* The study options of the analyses that compare runs (mimas rheology,
 * shearband, energy; docs/study.md): --study NAME or --study-values
 * V1,V2,... make every input one run with a study value, --study-range
 * limits the runs the trend lines use, --trends puts the trends table into a
 * file of its own. */
#ifndef MIMAS_CLI_STUDY_H
#define MIMAS_CLI_STUDY_H

#include <stddef.h>
#include <stdio.h>

#include "cli.h"
#include "cli_table.h"
#include "parameters.h"
#include "study.h"

/* The option table entries, in this order, for a command's cli_option list. */
#define CLI_STUDY_OPTIONS                                                                        \
    {"study", 0, "NAME", "compare the inputs as runs of a study of the run parameter NAME "     \
                         "(SECTION.KEY, or KEY: liquid_content, friction, omega, ...)"},         \
    {"study-values", 0, "V1,V2,...", "compare the inputs as runs with these study values, "      \
                                     "one per input"},                                           \
    {"study-range", 0, "LO:HI", "fit the trend lines over the runs with LO <= value <= HI "      \
                                "(either may be left out; default all)"},                        \
    {"trends", 0, "FILE", "write the trends table to FILE (default: after the runs' table, "     \
                          "two empty lines apart)"}
#define CLI_STUDY_NOPTIONS 4
/* The table options (CLI_TABLE_OPTIONS) and then the study options, as the
 * analyses that compare runs declare them at the end of their option table. */
#define CLI_STUDY_TABLE_OPTIONS CLI_TABLE_OPTIONS, CLI_STUDY_OPTIONS

typedef struct cli_study {
    const char *name;         /* --study */
    const char *values;       /* --study-values */
    double lo, hi;            /* --study-range */
    const char *trends;       /* --trends */
    double *x;                /* the runs' study values */
    size_t nruns;
    mimas_parameters *params; /* the runs' parameters (cli_study_take) */
    char unit[24];            /* the study variable's unit ("" if none or unknown) */
} cli_study;

void cli_study_init(cli_study *s);
void cli_study_free(cli_study *s);
/* Handles option k (0 .. CLI_STUDY_NOPTIONS - 1 of CLI_STUDY_OPTIONS);
 * returns 0 or the exit status after the usage message. */
int cli_study_option(const cli_command *cmd, cli_study *s, size_t k, const char *arg);
/* Option k of CLI_STUDY_TABLE_OPTIONS: a table option into t, a study
 * option into s. */
int cli_study_table_option(const cli_command *cmd, cli_table_options *t, cli_study *s, size_t k,
                           const char *arg);
/* 1 if a study was asked for. */
int cli_study_on(const cli_study *s);
/* After parsing, with the inputs (and the contact files of in, may be
 * NULL): checks the combination (at least two runs, as many --study-values
 * as inputs; without a study exactly one input when one is not NULL, then
 * named by it in the message; a --trends file that is not an input) and
 * prepares the study values.  Returns 0 or the exit status after the
 * message. */
int cli_study_begin(const cli_command *cmd, cli_study *s, char *const *inputs, int ninputs,
                    const cli_inputs *in, const char *one);
/* The study value of run k from its run parameters (with --study) or from
 * --study-values; source names the run in messages.  The parameters are
 * kept for cli_study_note. */
int cli_study_take(cli_study *s, size_t k, const mimas_parameters *ps, const char *source,
                   mimas_error *err);
/* Says on standard error which other parameters the runs differ in (with
 * --study; not an error: a study may vary the seed as well). */
void cli_study_note(const cli_command *cmd, const cli_study *s);
/* The x axis label of a study's pictures. */
const char *cli_study_label(const cli_study *s);
/* The trend of row values y (errors e) over the runs, fitted over --study-range. */
int cli_study_trend(const cli_study *s, const double *y, const double *e, mimas_trend *t,
                    mimas_error *err);
/* A row of the trends table: a per-run result and its trend. */
typedef struct cli_trend_row {
    const char *table, *parameter;  /* the per-run result the trend is of */
    double lo, hi;                  /* its window (or the envelope of its ranges) */
    mimas_trend trend;
} cli_trend_row;

/* The first column of a study's runs table: "study", with the variable's unit. */
void cli_study_column(cli_table *t, const cli_study *s);
/* A whole header: the study column (s NULL: none), then names[k] with
 * units[k] (units NULL: all "-"), then the end of the header line. */
void cli_study_header(cli_table *t, const cli_study *s, const char *const *names,
                      const char *const *units, size_t n);
/* Writes the runs' table (write_runs writes its header and rows into t) to
 * output and the trends table (docs/study.md: table parameter lo hi nruns A1
 * A1_err A2 A2_err change_first change_first_err change_rest change_rest_err
 * status) to --trends or after it, both in the format of to (--csv,
 * --digits, --units-header), without partial files. */
int cli_study_write(const cli_study *s, const char *output, const cli_table_options *to,
                    void (*write_runs)(cli_table *t, const void *ctx), const void *ctx,
                    const cli_trend_row *rows, size_t nrows, mimas_error *err);

#endif
