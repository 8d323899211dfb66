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

static void separator(cli_table *t)
{
    if (t->col++)
        fputc(t->o.csv ? ',' : '\t', t->fp);
}

/* A word; in CSV quoted when it holds a comma, a quote or a line break. */
static void word(FILE *fp, int csv, const char *s)
{
    if (!csv || !s[strcspn(s, ",\"\n\r")]) {
        fputs(s, fp);
        return;
    }
    fputc('"', fp);
    for (; *s; s++) {
        if (*s == '"')
            fputc('"', fp);
        fputc(*s, fp);
    }
    fputc('"', fp);
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
    word(t->fp, t->o.csv, name);
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
    fputc('\n', t->fp);
    if (t->o.units && t->units)
        fprintf(t->fp, "%s\n", t->units);
    t->col = 0;
}

void cli_table_double(cli_table *t, double v)
{
    if (t->o.digits && !isnan(v)) {
        separator(t);
        fprintf(t->fp, "%.*g", t->o.digits, v);
        return;
    }
    /* the separator and the shortest decimal that reads back as v (0.025, not
     * 0.025000000000000001; "nan" for NaN) in one write: exact, and several times faster
     * than printf's 15-17 digits */
    char buf[MIMAS_NUMFMT_MAX + 1];
    size_t n = 0;
    if (t->col++)
        buf[n++] = t->o.csv ? ',' : '\t';
    n += mimas_format_double(v, buf + n);
#ifdef __GLIBC__
    fwrite_unlocked(buf, 1, n, t->fp); /* one thread writes a table */
#else
    fwrite(buf, 1, n, t->fp);
#endif
}

void cli_table_int(cli_table *t, long long v)
{
    separator(t);
    fprintf(t->fp, "%lld", v);
}

void cli_table_text(cli_table *t, const char *s)
{
    separator(t);
    word(t->fp, t->o.csv, s);
}

void cli_table_row_end(cli_table *t)
{
    fputc('\n', t->fp);
    t->col = 0;
}

void cli_table_block_end(cli_table *t, int end_of_set)
{
    if (t->o.blocks)
        fputs(end_of_set ? "\n\n" : "\n", t->fp);
}

int cli_table_end(cli_table *t)
{
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
