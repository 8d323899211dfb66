#include <config.h>

#include "cli_table.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "numfmt.h"

int cli_table_option(const cli_command *cmd, cli_table_options *o, size_t k, const char *arg)
{
    long v;
    switch (k) {
    case 0: o->csv = 1; return 0;
    case 1:
        if (cli_parse_long(arg, &v) || v < 1 || v > 17)
            return cli_fail(cmd, 1, "--digits needs a number from 1 to 17, not '%s'", arg);
        o->digits = (int)v;
        return 0;
    case 2: o->units = 1; return 0;
    }
    return 1;
}

void cli_table_start(cli_table *t, FILE *fp, const cli_table_options *o)
{
    memset(t, 0, sizeof *t);
    t->fp = fp;
    if (o)
        t->o = *o;
}

/* The gathered text to the stream. */
static void flush(cli_table *t)
{
    if (t->len)
        fwrite(t->buf, 1, t->len, t->fp);
    t->len = 0;
}

/* Room for n more bytes in the buffer (n <= CLI_TABLE_BUFFER). */
static char *room(cli_table *t, size_t n)
{
    if (t->len + n > sizeof t->buf)
        flush(t);
    return t->buf + t->len;
}

static void put(cli_table *t, const char *s, size_t n)
{
    if (n > sizeof t->buf / 2) { /* a long word: straight to the stream */
        flush(t);
        fwrite(s, 1, n, t->fp);
        return;
    }
    memcpy(room(t, n), s, n);
    t->len += n;
}

static void put_char(cli_table *t, char c)
{
    *room(t, 1) = c;
    t->len++;
}

static void separator(cli_table *t)
{
    if (t->col++)
        put_char(t, t->o.csv ? ',' : '\t');
}

/* A word; in CSV quoted when it holds a comma, a quote or a line break. */
static void word(cli_table *t, const char *s)
{
    if (!t->o.csv || !s[strcspn(s, ",\"\n\r")]) {
        put(t, s, strlen(s));
        return;
    }
    put_char(t, '"');
    for (; *s; s++) {
        if (*s == '"')
            put_char(t, '"');
        put_char(t, *s);
    }
    put_char(t, '"');
}

static void units_add(cli_table *t, const char *unit)
{
    size_t n = strlen(unit) + 2;
    if (t->units_len + n + 1 > t->units_cap) {
        size_t cap = (t->units_cap ? 2 * t->units_cap : 256) + n;
        char *u = realloc(t->units, cap);
        if (!u)
            return; /* the units line is then cut short; the table itself is not */
        t->units = u;
        t->units_cap = cap;
    }
    t->units_len += (size_t)snprintf(t->units + t->units_len, t->units_cap - t->units_len, "%s%s",
                                     t->units_len ? (t->o.csv ? "," : "\t") : "# ", unit);
}

void cli_table_column(cli_table *t, const char *name, const char *unit)
{
    separator(t);
    word(t, name);
    if (t->o.units)
        units_add(t, unit && unit[0] ? unit : "-");
}

void cli_table_columns(cli_table *t, const char *const *names, const char *const *units,
                       size_t n)
{
    for (size_t k = 0; k < n; k++)
        cli_table_column(t, names[k], units ? units[k] : NULL);
}

void cli_table_header_end(cli_table *t)
{
    put_char(t, '\n');
    flush(t);
    if (t->o.units && t->units)
        fprintf(t->fp, "%s\n", t->units);
    t->col = 0;
}

void cli_table_double(cli_table *t, double v)
{
    /* the separator and the shortest decimal that reads back as v (0.025, not
     * 0.025000000000000001; "nan" for NaN) straight into the row: exact, and much faster
     * than printf's 15-17 digits */
    char *o = room(t, MIMAS_NUMFMT_MAX + 1), *start = o;
    if (t->col++)
        *o++ = t->o.csv ? ',' : '\t';
    if (t->o.digits && !isnan(v))
        o += snprintf(o, MIMAS_NUMFMT_MAX, "%.*g", t->o.digits, v);
    else
        o += mimas_format_double(v, o);
    t->len += (size_t)(o - start);
}

void cli_table_doubles(cli_table *t, const double *v, size_t n)
{
    if (t->o.digits) {
        for (size_t k = 0; k < n; k++)
            cli_table_double(t, v[k]);
        return;
    }
    /* as cli_table_double, the table's length and column in locals (the text written
     * through a char pointer would otherwise make the compiler reload them) */
    char sep = t->o.csv ? ',' : '\t';
    size_t len = t->len, col = t->col;
    for (size_t k = 0; k < n; k++) {
        if (len + MIMAS_NUMFMT_MAX + 1 > sizeof t->buf) {
            t->len = len;
            flush(t);
            len = 0;
        }
        char *o = t->buf + len;
        if (col++)
            *o++ = sep;
        len = (size_t)(o - t->buf) + mimas_format_double(v[k], o);
    }
    t->len = len;
    t->col = col;
}

void cli_table_int(cli_table *t, long long v)
{
    char *o = room(t, 24), *start = o;
    if (t->col++)
        *o++ = t->o.csv ? ',' : '\t';
    o += snprintf(o, 22, "%lld", v);
    t->len += (size_t)(o - start);
}

void cli_table_text(cli_table *t, const char *s)
{
    separator(t);
    word(t, s);
}

void cli_table_row_end(cli_table *t)
{
    put_char(t, '\n');
    flush(t);
    t->col = 0;
}

void cli_table_block_end(cli_table *t, int end_of_set)
{
    if (t->o.blocks)
        put(t, end_of_set ? "\n\n" : "\n", end_of_set ? 2 : 1);
    flush(t);
}

int cli_table_end(cli_table *t)
{
    if (t->fp)
        flush(t);
    free(t->units);
    t->units = NULL;
    return t->fp && ferror(t->fp) ? -1 : 0;
}

typedef struct table_job {
    const cli_table_options *o;
    void (*write)(cli_table *t, const void *ctx);
    const void *ctx;
} table_job;

static void run_job(FILE *fp, const void *ctx)
{
    const table_job *j = ctx;
    cli_table t;
    cli_table_start(&t, fp, j->o);
    j->write(&t, j->ctx);
    cli_table_end(&t);
}

int cli_table_write(const char *path, const cli_table_options *o,
                    void (*write)(cli_table *t, const void *ctx), const void *ctx,
                    mimas_error *err)
{
    table_job j = {o, write, ctx};
    return cli_write_table(path, run_job, &j, err);
}
