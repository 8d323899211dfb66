/* mimas xdmf: the XDMF sidecar of existing native trajectories, for ParaView. */
#include <config.h>

#include <stdio.h>
#include <string.h>

#include "commands.h"
#include "xdmf.h"

static const cli_option options[] = {
    {"output", 'o', "OUT.xdmf", "the sidecar to write (one input only; default: FILE.xdmf "
                                "beside FILE.h5)"},
};

typedef struct xdmf_args {
    const char *output;
} xdmf_args;

static int on_option(void *ctx, size_t opt, const char *arg)
{
    (void)opt;
    ((xdmf_args *)ctx)->output = arg;
    return 0;
}

static int run(const cli_command *cmd, int argc, char **argv)
{
    xdmf_args a = {NULL};
    int first;
    int rc = cli_parse(cmd, argc, argv, on_option, &a, NULL, &first);
    if (rc)
        return rc < 0 ? 0 : rc;
    if (first >= argc)
        return cli_fail(cmd, 1, "no input file (see mimas xdmf --help)");
    if (a.output && argc - first != 1)
        return cli_fail(cmd, 1, "-o names the sidecar of one input, not of %d", argc - first);
    for (int k = first; k < argc; k++) {
        char path[4200];
        if (a.output)
            snprintf(path, sizeof path, "%s", a.output);
        else
            mimas_xdmf_path(argv[k], NULL, path, sizeof path);
        mimas_error err;
        rc = mimas_xdmf_trajectory(argv[k], path, &err);
        if (rc)
            return cli_fail(cmd, mimas_exit_status(rc), "%s", err.msg);
    }
    return 0;
}

const cli_command cmd_xdmf = {
    "xdmf",
    "write the XDMF sidecar of native trajectories, so that ParaView opens them",
    "FILE.h5... [-o OUT.xdmf]",
    "Writes FILE.xdmf beside each native trajectory FILE.h5: every frame as a grid\n"
    "of points (XDMF Polyvertex) in a temporal collection, with the radius, type,\n"
    "velocity, angular velocity, force and every other per-particle quantity as\n"
    "point attributes (docs/format.md).  The data stay in FILE.h5; the sidecar\n"
    "names it without a folder, so keep the two side by side.  mimas convert,\n"
    "simulate and voronoi -o write the sidecar themselves; this command is for\n"
    "older files and for a run that is still going (its committed frames).",
    options,
    sizeof options / sizeof options[0],
    0,
    run,
};
