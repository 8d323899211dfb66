/* mimas: git-style front end.  One table maps subcommand names to their
 * declarations (src/cmd_*.c); everything else lives in libmimas. */
#include <config.h>

#include <errno.h>
#include <gsl/gsl_errno.h>
#include <stdio.h>
#include <string.h>

#include "commands.h"
#include "parallel.h"

static const cli_command *const commands[] = {
    &cmd_info,
    &cmd_convert,
    &cmd_average,
    &cmd_voronoi,
    &cmd_simulate,
    &cmd_shearband,
    &cmd_rheology,
    &cmd_energy,
    &cmd_xdmf,
    &cmd_disperse,
    &cmd_plugs,
    &cmd_radial,
    &cmd_plot,
};
#define NCOMMANDS (sizeof commands / sizeof commands[0])

/* The commands that split their frames over MPI ranks (docs/parallel.md). */
static int frame_parallel(const char *name)
{
    static const char *const names[] = {"average", "voronoi", "shearband", "disperse", "plugs",
                                        "radial"};
    for (size_t k = 0; k < sizeof names / sizeof names[0]; k++)
        if (!strcmp(names[k], name))
            return 1;
    return 0;
}

static void usage(FILE *out)
{
    fprintf(out,
            "Usage: mimas COMMAND [options] INPUT...\n"
            "       mimas help [COMMAND] | mimas --version\n\n"
            "mimas runs granular (DEM) simulations and turns their particle and contact\n"
            "data (or LIGGGHTS, LAMMPS and MercuryDPM output) into continuum fields and\n"
            "the analyses built on them.\n\nCommands:\n");
    for (size_t k = 0; k < NCOMMANDS; k++)
        fprintf(out, "  %-12s %s\n", commands[k]->name, commands[k]->summary);
    fprintf(out, "\n'mimas COMMAND --help' describes a command's options.\n");
}

static void man_page(FILE *out)
{
    fprintf(out, ".TH MIMAS 1 \"\" \"mimas %s\" \"mimas manual\"\n"
                 ".SH NAME\nmimas \\- micro\\-macro averaging and analysis of granular (DEM) "
                 "simulation data\n.SH SYNOPSIS\n.B mimas\n\\fICOMMAND\\fR [options] "
                 "\\fIINPUT\\fR...\n.br\n.B mimas help\n[\\fICOMMAND\\fR]\n"
                 ".SH COMMANDS\n", PACKAGE_VERSION);
    for (size_t k = 0; k < NCOMMANDS; k++)
        fprintf(out, ".TP\n.BR mimas\\-%s (1)\n%s\n", commands[k]->name, commands[k]->summary);
    fprintf(out, ".SH EXIT STATUS\n0 on success, 1 on bad usage, 2 on bad input data.\n");
}

static const cli_command *find(const char *name)
{
    for (size_t k = 0; k < NCOMMANDS; k++)
        if (strcmp(commands[k]->name, name) == 0)
            return commands[k];
    return NULL;
}

static int dispatch(int argc, char **argv);

int main(int argc, char **argv)
{
    /* before MPI starts: cli_start may re-execute the program (OpenMP's
     * passive waiting), and a process re-executed after MPI_Init cannot
     * initialise MPI again */
    cli_start(argc, argv);
    /* under mpirun: MPI for the frame-parallel commands (docs/parallel.md) */
    if (mimas_par_init(&argc, &argv)) {
        fprintf(stderr, "mimas: MPI could not start\n");
        return 2;
    }
    int rc = dispatch(argc, argv);
    mimas_par_finalize();
    return rc;
}

static int dispatch(int argc, char **argv)
{
    /* the library checks GSL's return codes (a fit that fails has a status);
     * GSL's default handler would abort the program instead */
    gsl_set_error_handler_off();
    if (argc < 2) {
        usage(stderr);
        return 1;
    }
    const char *name = argv[1];
    if (!strcmp(name, "--version") || !strcmp(name, "-V")) {
        const char *mpi = mimas_par_library();
        if (mimas_par_rank() == 0)
            printf("mimas %s (%s)\n", PACKAGE_VERSION,
                   mpi ? mpi : "serial build, without MPI");
        return 0;
    }
    if (!strcmp(name, "--help") || !strcmp(name, "-h")) {
        usage(stdout);
        return 0;
    }
    if (!strcmp(name, "help")) {
        /* help --man [COMMAND]: the man pages are generated from the same tables */
        if (argc >= 3 && !strcmp(argv[2], "--man")) {
            const cli_command *c = argc >= 4 ? find(argv[3]) : NULL;
            if (argc >= 4 && !c) {
                fprintf(stderr, "mimas: unknown command '%s' (see mimas help)\n", argv[3]);
                return 1;
            }
            if (c)
                cli_print_man(c, PACKAGE_VERSION, stdout);
            else
                man_page(stdout);
            return 0;
        }
        if (argc < 3) {
            usage(stdout);
            return 0;
        }
        const cli_command *c = find(argv[2]);
        if (!c) {
            fprintf(stderr, "mimas: unknown command '%s' (see mimas help)\n", argv[2]);
            return 1;
        }
        cli_print_help(c, stdout);
        return 0;
    }
    const cli_command *c = find(name);
    if (!c) {
        fprintf(stderr, "mimas: unknown command '%s' (see mimas help)\n", name);
        return 1;
    }
    int rc;
    if (mimas_par_size() == 1 || frame_parallel(c->name)) {
        rc = c->run(c, argc - 1, argv + 1);
    } else {
        /* under mpirun, a command that is not frame-parallel runs on rank 0
         * alone; the other ranks end with its exit status */
        rc = mimas_par_rank() == 0 ? c->run(c, argc - 1, argv + 1) : 0;
        mimas_par_share(MIMAS_OK, &rc, sizeof rc, NULL);
    }
    /* what went to standard output must have arrived (a full disk, /dev/full) */
    errno = 0;
    if ((fflush(stdout) != 0 || ferror(stdout)) && rc == 0)
        rc = cli_fail(c, 2, "cannot write to standard output: %s",
                      errno ? strerror(errno) : "write error");
    return rc;
}
