/* Writes a field file in the layout of mimas average -o from a table on
 * standard input (for the CLI tests of the analyses).  Usage:
 *   make_fields -o FILE --grid SPEC [--frames N] [--param SECTION.KEY=VALUE]... < TABLE
 * SPEC is a grid of mimas average (none, x=..., r=...); TABLE has a header
 * of field names (NAME_sem: the standard error of NAME) and one row per
 * cell, direction 0 fastest.  --param adds a run parameter: a number (REAL),
 * or a word (TEXT; "mixed" for MIXED). */
#include <config.h>

#include <getopt.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fields_file.h"
#include "grid.h"

#define MAX_COLUMNS 64

int main(int argc, char **argv)
{
    const char *out = NULL, *spec = NULL;
    int frames = 10;
    mimas_parameters params;
    mimas_parameters_init(&params);
    static const struct option opts[] = {{"output", required_argument, NULL, 'o'},
                                         {"grid", required_argument, NULL, 'g'},
                                         {"frames", required_argument, NULL, 'f'},
                                         {"param", required_argument, NULL, 'p'},
                                         {NULL, 0, NULL, 0}};
    int c;
    while ((c = getopt_long(argc, argv, "o:", opts, NULL)) != -1) {
        switch (c) {
        case 'o': out = optarg; break;
        case 'g': spec = optarg; break;
        case 'f': frames = atoi(optarg); break;
        case 'p': {
            char sec[64], key[64], val[64], *end;
            if (sscanf(optarg, "%63[^.].%63[^=]=%63s", sec, key, val) != 3) {
                fprintf(stderr, "make_fields: --param SECTION.KEY=VALUE, not '%s'\n", optarg);
                return 1;
            }
            double v = strtod(val, &end);
            mimas_parameter_kind kind = *end || end == val ? MIMAS_PARAM_TEXT : MIMAS_PARAM_REAL;
            if (kind == MIMAS_PARAM_TEXT && !strcmp(val, "mixed"))
                kind = MIMAS_PARAM_MIXED;
            if (mimas_parameters_add(&params, sec, key, kind, v, val, NULL, NULL)) {
                fprintf(stderr, "make_fields: bad --param '%s'\n", optarg);
                return 1;
            }
            break;
        }
        default: fprintf(stderr, "make_fields: bad option\n"); return 1;
        }
    }
    mimas_grid g;
    mimas_error err;
    if (!out || !spec || mimas_grid_parse(&g, spec, NULL, &err)) {
        fprintf(stderr, "make_fields: -o FILE and a valid --grid SPEC are required\n");
        return 1;
    }
    int none = !strcmp(spec, "none");
    size_t cells = mimas_grid_cells(&g);
    double *centre[3];
    for (int d = 0; d < 3; d++) {
        centre[d] = calloc((size_t)g.n[d], sizeof *centre[d]);
        for (int k = 0; g.gridded[d] && k < g.n[d]; k++)
            centre[d][k] = g.lo[d] + (g.hi[d] - g.lo[d]) * (k + 0.5) / g.n[d];
    }
    /* the header, then the cells */
    char line[8192], *names[MAX_COLUMNS];
    size_t ncol = 0;
    if (!fgets(line, sizeof line, stdin)) {
        fprintf(stderr, "make_fields: no header\n");
        return 2;
    }
    for (char *save, *t = strtok_r(line, " \t\n", &save); t && ncol < MAX_COLUMNS;
         t = strtok_r(NULL, " \t\n", &save))
        names[ncol++] = strdup(t);
    double *col[MAX_COLUMNS];
    for (size_t k = 0; k < ncol; k++)
        col[k] = malloc(cells * sizeof *col[k]);
    for (size_t cell = 0; cell < cells; cell++)
        for (size_t k = 0; k < ncol; k++)
            if (scanf("%lf", &col[k][cell]) != 1) {
                fprintf(stderr, "make_fields: the table needs %zu rows of %zu numbers\n", cells,
                        ncol);
                return 2;
            }
    /* NAME and NAME_sem pairs */
    const char *fnames[MAX_COLUMNS];
    const double *mean[MAX_COLUMNS], *sem[MAX_COLUMNS];
    size_t nf = 0;
    for (size_t k = 0; k < ncol; k++) {
        size_t len = strlen(names[k]);
        if (len > 4 && !strcmp(names[k] + len - 4, "_sem"))
            continue;
        fnames[nf] = names[k];
        mean[nf] = col[k];
        sem[nf] = NULL;
        for (size_t m = 0; m < ncol; m++)
            if (!strncmp(names[m], names[k], len) && !strcmp(names[m] + len, "_sem"))
                sem[nf] = col[m];
        nf++;
    }
    fields_file_spec s = {none ? "none"
                          : g.kind == MIMAS_GRID_CYLINDRICAL ? "cylindrical"
                                                             : "cartesian",
                          {g.n[0], g.n[1], g.n[2]},
                          {centre[0], centre[1], centre[2]},
                          {g.gridded[0], g.gridded[1], g.gridded[2]},
                          frames,
                          {0, 0},
                          &params};
    if (write_fields_file(out, &s, nf, fnames, mean, sem)) {
        fprintf(stderr, "make_fields: cannot write %s\n", out);
        return 2;
    }
    mimas_parameters_free(&params);
    return 0;
}
