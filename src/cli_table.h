/* The one table writer of the commands that print tables (mimas average,
 * voronoi, shearband, rheology, ...): a header line of column names, an
 * optional units line, rows of numbers, integers and words, tab- or
 * comma-separated, numbers exact by default.  Commands declare the shared
 * options with CLI_TABLE_OPTIONS and hand them to cli_table_option. */
#ifndef MIMAS_CLI_TABLE_H
#define MIMAS_CLI_TABLE_H

#include <stddef.h>
#include <stdio.h>

#include "cli.h"

typedef struct cli_table_options {
    int csv;        /* comma-separated (words with commas or quotes quoted), else tabs */
    int digits;     /* significant digits (0: the fewest that give the double back exactly) */
    int units;      /* a second header line "# UNIT UNIT ..." */
    int blocks;     /* gnuplot grid blocks: cli_table_block_end writes a blank line */
} cli_table_options;

/* The options every table-writing command declares, in this order, at the
 * end of its option table (their indices: first .. first + 2). */
#define CLI_TABLE_OPTIONS                                                                      \
    {"csv", 0, NULL, "write the table as comma-separated values (default: tab-separated)"},   \
        {"digits", 0, "N", "significant digits of the numbers, 1-17 (default: as many as "     \
                           "give each number back exactly, at most 17)"},                   \
        {"units-header", 0, NULL, "a second header line '# UNIT ...' with each column's unit " \
                                  "(1: dimensionless, -: none)"}
#define CLI_TABLE_NOPTIONS 3
/* The --blocks option (for grids): declared by the commands whose rows form a grid. */
#define CLI_TABLE_BLOCKS_OPTION                                                               \
    {"blocks", 0, NULL, "a blank line after each row of a 2-d or 3-d grid (gnuplot's grid "  \
                        "blocks, for splot and pm3d)"}
/* Option k (0 .. CLI_TABLE_NOPTIONS - 1) of CLI_TABLE_OPTIONS; prints the
 * usage error and returns 1 on a bad argument. */
int cli_table_option(const cli_command *cmd, cli_table_options *o, size_t k, const char *arg);

/* The text of a row is gathered in the table and handed to the stream in one
 * write at the end of the row (and of the header, a block, the table), so
 * between rows everything written is in fp. */
#define CLI_TABLE_BUFFER 4096
typedef struct cli_table {
    FILE *fp;
    cli_table_options o;
    size_t col;           /* columns written in the current row / header */
    char *units;          /* the units line being built */
    size_t units_len, units_cap;
    size_t len;           /* bytes in buf not yet written to fp */
    char buf[CLI_TABLE_BUFFER];
} cli_table;

void cli_table_start(cli_table *t, FILE *fp, const cli_table_options *o);
/* Header: one call per column (unit NULL: "-"), then cli_table_header_end. */
void cli_table_column(cli_table *t, const char *name, const char *unit);
void cli_table_header_end(cli_table *t);
/* n columns at once: names[k] with units[k] (units NULL: all "-"). */
void cli_table_columns(cli_table *t, const char *const *names, const char *const *units,
                       size_t n);
/* Rows: values in column order, then cli_table_row_end.  NaN is "nan". */
void cli_table_double(cli_table *t, double v);
/* n numbers at once (a row's: as n cli_table_double calls, faster). */
void cli_table_doubles(cli_table *t, const double *v, size_t n);
void cli_table_int(cli_table *t, long long v);
void cli_table_text(cli_table *t, const char *s);
void cli_table_row_end(cli_table *t);
/* The end of a grid row (a blank line with blocks); end_of_set: also the
 * end of one of several grids in the table (a second blank line: gnuplot's
 * index). */
void cli_table_block_end(cli_table *t, int end_of_set);
/* Frees the table's memory (the stream stays open); 0, or -1 if writing failed. */
int cli_table_end(cli_table *t);

/* A whole table into path (NULL or "-": standard output) without partial
 * files (cli_write_table): write puts its header and rows into t, started
 * in the format o. */
int cli_table_write(const char *path, const cli_table_options *o,
                    void (*write)(cli_table *t, const void *ctx), const void *ctx,
                    mimas_error *err);

#endif
