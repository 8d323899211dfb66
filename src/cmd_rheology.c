/* mimas rheology: yield line, mu(I), viscosity power laws and windowed
 * viscosities from a field file (docs/theory.md §7.2, docs/rheology.md). */
#include <config.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

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
    {"plot", 0, "PREFIX", "draw PREFIX.yield.png, PREFIX.mu_I.png and PREFIX.eta.png (gnuplot)"},
    {"output", 'o', "FILE", "write the table to FILE (default: standard output)"},
    CLI_TABLE_OPTIONS,
};

enum { O_MIN_RATE, O_P_RANGE, O_RATE_WINDOWS, O_I_WINDOWS, O_DEFINITION, O_PLOT, O_OUTPUT,
       O_TABLE };

typedef struct rheology_args {
    const cli_command *cmd;
    mimas_rheology_options o;
    mimas_rheology_window rate[MAX_WINDOWS], I[MAX_WINDOWS];
    const char *plot, *output;
    cli_table_options table;
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
    default: return cli_table_option(a->cmd, &a->table, opt - O_TABLE, arg);
    }
}

typedef struct rheology_table {
    const rheology_args *a;
    const mimas_rheology *r;
} rheology_table;

/* The units of value, error, lo and hi depend on the row (docs/rheology.md): "-". */
static void write_table(FILE *out, const void *ctx)
{
    const rheology_table *rt = ctx;
    cli_table t;
    cli_table_start(&t, out, &rt->a->table);
    static const char *const cols[] = {"table", "parameter", "value", "error", "npts", "lo",
                                       "hi", "status"};
    for (int k = 0; k < 8; k++)
        cli_table_column(&t, cols[k], NULL);
    cli_table_header_end(&t);
    for (size_t k = 0; k < rt->r->nrows; k++) {
        const mimas_rheology_row *w = &rt->r->rows[k];
        cli_table_text(&t, w->table);
        cli_table_text(&t, w->parameter);
        cli_table_double(&t, w->value);
        cli_table_double(&t, w->error);
        cli_table_int(&t, (long long)w->npts);
        cli_table_double(&t, w->lo);
        cli_table_double(&t, w->hi);
        cli_table_text(&t, mimas_fit_status_name(w->status));
        cli_table_row_end(&t);
    }
    cli_table_end(&t);
}

static int run(const cli_command *cmd, int argc, char **argv)
{
    rheology_args a;
    memset(&a, 0, sizeof a);
    a.cmd = cmd;
    mimas_rheology_options_default(&a.o);
    int first;
    int rc = cli_parse(cmd, argc, argv, on_option, &a, NULL, &first);
    if (!rc && argc - first != 1)
        rc = cli_fail(cmd, 1, "needs one field file (mimas average -o FIELDS.h5), not %d inputs",
                      argc - first);
    if (!rc)
        rc = cli_refuse_input_as_output(cmd, a.output, NULL, argv + first, argc - first) ||
             cli_refuse_input_as_output(cmd, a.plot, NULL, argv + first, argc - first);
    if (rc)
        return rc < 0 ? 0 : rc;
    mimas_error err;
    mimas_fieldset *fs = NULL;
    mimas_rheology *r = NULL;
    int status = mimas_fieldset_open(&fs, argv[first], &err);
    if (!status)
        status = mimas_rheology_analyse(fs, &a.o, &r, &err);
    mimas_fieldset_close(fs);
    if (!status && a.plot)
        status = mimas_rheology_plot(r, a.plot, &err);
    rheology_table rt = {&a, r};
    if (!status)
        status = cli_write_table(a.output, write_table, &rt, &err);
    mimas_rheology_free(r);
    if (status)
        return cli_fail(cmd, mimas_exit_status(status), "%s", err.msg);
    return 0;
}

const cli_command cmd_rheology = {
    "rheology",
    "yield line, mu(I), viscosity power laws and windows from a field file",
    "FIELDS.h5 [options]",
    "Over the cells of a field file of mimas average whose shear rate exceeds\n"
    "--min-shear-rate and whose pressure is in --p-range: the yield line\n"
    "tau = tau0 + zeta p with psi = asin(zeta), the mu(I) law mu = mu_s +\n"
    "(mu_2 - mu_s)/(1 + I0/I), the power laws eta = k shear_rate^n and\n"
    "eta = k I^n, and the mean viscosity in windows of shear rate and of I\n"
    "(docs/theory.md §7.2; Uhlig 2012, Sec. 4.2).  Writes one long table, a row per parameter or\n"
    "window: table parameter value error npts lo hi status (docs/rheology.md).",
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
