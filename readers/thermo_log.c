#include <config.h>

#include "thermo_log.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "numparse.h"
#include "text_input.h"

#define MAX_COLUMNS 512

struct mimas_thermo_log {
    text_input t;
    size_t nwant;
    char **want;            /* the column names asked for */
    int *seen;              /* some run printed want[k] */
    /* the current run's table */
    int in_table;
    size_t ncols;
    long col_of[64];        /* want[k] -> column of the current table, or -1 */
    long step_col, time_col;
    double dt_option, dt_log;
    int64_t last_step;
    int have_last;
    double *row;
};

static int is_blank(char c)
{
    return c == ' ' || c == '\t' || c == '\r';
}

/* The first token of a line in tok (empty if none); returns the rest. */
static char *first_token(char *line, char *tok, size_t len)
{
    while (is_blank(*line))
        line++;
    size_t k = 0;
    while (*line && !is_blank(*line)) {
        if (k + 1 < len)
            tok[k++] = *line;
        line++;
    }
    tok[k] = '\0';
    return line;
}

int mimas_thermo_log_probe(const char *head, size_t n)
{
    /* LAMMPS and LIGGGHTS start their log with their name and version */
    return (n >= 7 && !strncmp(head, "LAMMPS ", 7)) || (n >= 9 && !strncmp(head, "LIGGGHTS ", 9));
}

void mimas_thermo_log_close(mimas_thermo_log *log)
{
    if (!log)
        return;
    text_close(&log->t);
    for (size_t k = 0; log->want && k < log->nwant; k++)
        free(log->want[k]);
    free(log->want);
    free(log->seen);
    free(log->row);
    free(log);
}

int mimas_thermo_log_open(mimas_thermo_log **out, const char *path, const char *const *names,
                          size_t n, double dt, mimas_error *err)
{
    *out = NULL;
    if (n > 64)
        return mimas_error_set(err, MIMAS_EUSAGE, "at most 64 thermo columns");
    mimas_thermo_log *log = calloc(1, sizeof *log);
    if (!log)
        return mimas_error_set(err, MIMAS_EIO, "out of memory");
    log->want = calloc(n ? n : 1, sizeof *log->want);
    log->seen = calloc(n ? n : 1, sizeof *log->seen);
    log->row = malloc(MAX_COLUMNS * sizeof *log->row);
    int ok = log->want && log->seen && log->row;
    for (size_t k = 0; ok && k < n; k++)
        ok = (log->want[k] = strdup(names[k])) != NULL;
    log->nwant = n;
    if (!ok) {
        mimas_thermo_log_close(log);
        return mimas_error_set(err, MIMAS_EIO, "out of memory");
    }
    log->dt_option = dt;
    int rc = text_open(&log->t, path, err);
    if (rc) {
        mimas_thermo_log_close(log);
        return rc;
    }
    *out = log;
    return MIMAS_OK;
}

/* A header line "Step Name Name ...": the columns of the run's table;
 * -1 if it has too many. */
static int start_table(mimas_thermo_log *log, char *line)
{
    char tok[128];
    size_t c = 0;
    log->step_col = log->time_col = -1;
    for (size_t k = 0; k < log->nwant; k++)
        log->col_of[k] = -1;
    for (char *p = first_token(line, tok, sizeof tok); tok[0];
         p = first_token(p, tok, sizeof tok), c++) {
        if (c >= MAX_COLUMNS)
            return -1;
        if (!strcmp(tok, "Step"))
            log->step_col = (long)c;
        if (!strcmp(tok, "Time"))
            log->time_col = (long)c;
        for (size_t k = 0; k < log->nwant; k++)
            if (!strcmp(tok, log->want[k]))
                log->col_of[k] = (long)c;
    }
    log->ncols = c;
    log->in_table = 1;
    for (size_t k = 0; k < log->nwant; k++)
        log->seen[k] |= log->col_of[k] >= 0;
    return MIMAS_OK;
}

/* 1 if line is a row of the current table: exactly ncols numbers. */
static int parse_row(mimas_thermo_log *log, char *line)
{
    char *p = line;
    for (size_t c = 0; c < log->ncols; c++)
        if (parse_double(&p, &log->row[c]))
            return 0;
    double extra;
    return parse_double(&p, &extra) == -1;
}

int mimas_thermo_log_next(mimas_thermo_log *log, int64_t *step, double *time, double *values,
                          mimas_error *err)
{
    size_t len;
    int rc = MIMAS_OK;
    char *line;
    while ((line = text_line(&log->t, &len, &rc, err)) != NULL) {
        char tok[64];
        char *rest = first_token(line, tok, sizeof tok);
        if (!strcmp(tok, "Step")) {
            if (start_table(log, line))
                return text_error(&log->t, err, "a thermo header of more than %d columns",
                                  MAX_COLUMNS);
            continue;
        }
        if (!strcmp(tok, "Loop")) {
            log->in_table = 0;
            continue;
        }
        if (!log->in_table) {
            /* an echoed "timestep DT" command sets the step for what follows */
            double dt;
            char *p = rest;
            if (!strcmp(tok, "timestep") && !parse_double(&p, &dt) && dt > 0)
                log->dt_log = dt;
            continue;
        }
        /* inside a table, lines of other output (INFO:, WARNING:) are passed over */
        if (!parse_row(log, line))
            continue;
        double s = log->step_col >= 0 ? log->row[log->step_col] : NAN;
        if (!(s == floor(s)))
            return text_error(&log->t, err, "a thermo row without a whole step number");
        int64_t st = (int64_t)s;
        if (log->have_last && st == log->last_step)
            continue; /* the first row of a run repeats the last of the one before */
        log->last_step = st;
        log->have_last = 1;
        *step = st;
        double dt = log->dt_option > 0 ? log->dt_option : log->dt_log;
        *time = log->time_col >= 0 ? log->row[log->time_col] : dt > 0 ? (double)st * dt : NAN;
        for (size_t k = 0; k < log->nwant; k++)
            values[k] = log->col_of[k] >= 0 ? log->row[log->col_of[k]] : NAN;
        return MIMAS_OK;
    }
    return rc ? rc : MIMAS_END;
}

int mimas_thermo_log_has(const mimas_thermo_log *log, size_t k)
{
    return k < log->nwant && log->seen[k];
}
