/* mimas plot: the picture of one field of a field file (docs/plot.md). */
#include <config.h>

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "commands.h"
#include "fieldset.h"

static const cli_option options[] = {
    {"output", 'o', "FILE.png", "the picture to write (required)"},
    {"error", 0, NULL, "draw the field's standard error over frames instead of its mean"},
    {"log", 0, NULL, "logarithmic colour scale (maps) or value axis (profiles)"},
    {"range", 0, "LO:HI", "the value range (colour bar or value axis; either bound may be left "
                          "out; default: from the data)"},
};

enum { O_OUTPUT, O_ERROR, O_LOG, O_RANGE };

typedef struct plot_args {
    const cli_command *cmd;
    const char *output;
    mimas_fieldset_plot_options o;
} plot_args;

static int on_option(void *ctx, size_t opt, const char *arg)
{
    plot_args *a = ctx;
    switch (opt) {
    case O_OUTPUT: a->output = arg; return 0;
    case O_ERROR: a->o.error = 1; return 0;
    case O_LOG: a->o.logscale = 1; return 0;
    default:
        if (cli_parse_range(arg, &a->o.lo, &a->o.hi))
            return cli_fail(a->cmd, 1, "--range needs LO:HI, LO: or :HI with LO < HI, not '%s'",
                            arg);
        return 0;
    }
}

static int run(const cli_command *cmd, int argc, char **argv)
{
    plot_args a;
    memset(&a, 0, sizeof a);
    a.cmd = cmd;
    a.o.lo = a.o.hi = NAN;
    int first;
    int rc = cli_parse(cmd, argc, argv, on_option, &a, NULL, &first);
    if (!rc && argc - first != 2)
        rc = cli_fail(cmd, 1, "needs a field file and a field name (see mimas plot --help)");
    if (!rc && !a.output)
        rc = cli_fail(cmd, 1, "needs -o FILE.png");
    if (rc)
        return rc < 0 ? 0 : rc;
    if (isinf(a.o.lo))
        a.o.lo = NAN;
    if (isinf(a.o.hi))
        a.o.hi = NAN;
    mimas_error err;
    mimas_fieldset *fs = NULL;
    int status = mimas_fieldset_open(&fs, argv[first], &err);
    if (!status)
        status = mimas_fieldset_plot(fs, argv[first + 1], &a.o, a.output, &err);
    mimas_fieldset_close(fs);
    if (status)
        return cli_fail(cmd, mimas_exit_status(status), "%s", err.msg);
    return 0;
}

const cli_command cmd_plot = {
    "plot",
    "a picture of one field of a field file: a map on 2-D grids, a profile on 1-D grids",
    "FIELDS.h5 FIELD -o FILE.png [options]",
    "Draws the field FIELD (a name of docs/fields.md) of a field file of mimas\n"
    "average with gnuplot.  On a grid with two directions of more than one cell\n"
    "(r-z, x-z, x-y, ...) it is a colour map of the cells, drawn to scale, with a\n"
    "colour bar in the field's unit; cells where the field is undefined (nan) stay\n"
    "white.  On a grid with one such direction it is the profile with the standard\n"
    "errors over frames as error bars.  --error draws the standard error itself.\n"
    "The picture is written under a temporary name and renamed when complete.",
    options,
    sizeof options / sizeof options[0],
    0,
    run,
    "# the solid fraction and the angular velocity of a ring shear cell on an r-z grid\n"
    "mimas average run.h5 --grid r=0.0147:0.11:39,z=0:0.038:20 --weight bins --from 5 \\\n"
    "    --exclude-types 2 -o fields.h5\n"
    "mimas plot fields.h5 nu -o nu.png\n"
    "mimas plot fields.h5 omega -o omega.png\n"
    "\n"
    "# the standard error of the pressure, on a logarithmic colour scale\n"
    "mimas plot fields.h5 p --error --log -o p_sem.png\n"
    "\n"
    "# a vertical profile of the solid fraction with its error bars, between 0 and 0.7\n"
    "mimas average run.h5 --grid z=0:0.038:38 --weight bins --from 5 -o profile.h5\n"
    "mimas plot profile.h5 nu --range 0:0.7 -o nu_z.png",
};
