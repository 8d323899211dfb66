/* mimas simulate: runs a DEM scenario (ring shear cell, periodic box,
 * liquid-bridge pull-off, plug conveying in a tube) and writes particles,
 * contacts and wall contacts (and a tube's gas fields) in the native format. */
#include <config.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#ifdef _OPENMP
#include <omp.h>
#endif

#include "commands.h"
#include "scenario.h"
#include "simulate.h"

static const cli_option options[] = {
    {"output", 'o', "RUN.h5", "the output file (required to run)"},
    {"threads", 0, "N", "OpenMP threads (default: OMP_NUM_THREADS or all cores)"},
    {"resume", 0, NULL, "continue from the checkpoint RUN.h5.ckpt"},
    {"stop-at", 0, "STEP", "stop after this step, leaving a checkpoint for --resume"},
    {"print-defaults", 0, "TYPE", "print a complete scenario file of TYPE (ringshear, box, "
                                  "pulloff, plugtube) with every default, and exit"},
    {"quiet", 'q', NULL, "no progress line"},
    {"list-keys", 0, NULL, "print every scenario key with its unit and meaning (Markdown) and exit"},
    {"force", 0, NULL, "replace an existing RUN.h5 (without it, an existing output is refused)"},
};

typedef struct simulate_args {
    const cli_command *cmd;
    const char *output, *defaults;
    int threads;
    long stop_at;
    int resume, quiet, list_keys, force;
} simulate_args;

static int on_option(void *ctx, size_t opt, const char *arg)
{
    simulate_args *a = ctx;
    switch (opt) {
    case 0: a->output = arg; return 0;
    case 1: return cli_parse_threads(a->cmd, arg, &a->threads);
    case 2: a->resume = 1; return 0;
    case 3:
        if (cli_parse_long(arg, &a->stop_at) || a->stop_at < 1)
            return cli_fail(a->cmd, 1, "--stop-at needs a step number >= 1, not '%s'", arg);
        return 0;
    case 4: a->defaults = arg; return 0;
    case 5: a->quiet = 1; return 0;
    case 6: a->list_keys = 1; return 0;
    default: a->force = 1; return 0;
    }
}

static void show_progress(void *ctx, const sim_progress *p)
{
    (void)ctx;
    double eta = p->eta;
    fprintf(stderr, "\rmimas simulate: step %lld/%lld  t = %.4g s  %.0f steps/s  "
                    "%.3g particle-steps/s  %zu frames  ETA %02d:%02d:%02d ",
            (long long)p->step, (long long)p->total, p->time, p->steps_per_s,
            p->steps_per_s * (double)p->particles, p->frames, (int)(eta / 3600),
            (int)fmod(eta / 60, 60), (int)fmod(eta, 60));
    fflush(stderr);
}

static int run(const cli_command *cmd, int argc, char **argv)
{
    simulate_args a = {0};
    a.cmd = cmd;
    int first;
    int rc = cli_parse(cmd, argc, argv, on_option, &a, NULL, &first);
    if (rc)
        return rc < 0 ? 0 : rc;
    if (a.list_keys) {
        sim_scenario_print_doc(stdout);
        return 0;
    }
    if (a.defaults) {
        int type = sim_scenario_type(a.defaults);
        if (type < 0)
            return cli_fail(cmd, 1, "--print-defaults needs ringshear, box, pulloff or plugtube, "
                                    "not '%s'", a.defaults);
        sim_scenario s;
        sim_scenario_defaults(&s, type);
        sim_scenario_print(&s, stdout);
        return 0;
    }
    if (argc - first != 1)
        return cli_fail(cmd, 1, "needs one scenario file (see --print-defaults)");
    if (!a.output)
        return cli_fail(cmd, 1, "needs -o RUN.h5");
    if (cli_refuse_input_as_output(cmd, a.output, NULL, argv + first, 1))
        return 1;
    if (!a.resume && !a.force && access(a.output, F_OK) == 0)
        return cli_fail(cmd, 1, "%s exists: give --force to replace it (or --resume to continue "
                        "its run)", a.output);
#ifdef _OPENMP
    if (a.threads > 0)
        omp_set_num_threads(a.threads);
#endif
    mimas_error err;
    sim_scenario sc;
    if ((rc = sim_scenario_load(&sc, argv[first], &err)))
        return cli_fail(cmd, mimas_exit_status(rc), "%s", err.msg);
    char *line = cli_command_line(argc, argv);
    int tty = !a.quiet && isatty(STDERR_FILENO);
    sim_run_options o = {a.output, a.resume, a.stop_at, line, tty ? show_progress : NULL, NULL,
                         argv[first]};
    rc = sim_run(&sc, &o, &err);
    if (tty)
        fputc('\n', stderr);
    free(line);
    if (rc)
        return cli_fail(cmd, mimas_exit_status(rc), "%s", err.msg);
    return 0;
}

const cli_command cmd_simulate = {
    "simulate",
    "run a DEM scenario: split-bottom ring shear cell, periodic box, liquid-bridge pull-off, "
    "plug conveying",
    "SCENARIO.ini -o RUN.h5 [--threads N] [--resume]",
    "Runs the discrete element simulation the scenario file describes (INI; every\n"
    "key and its default: --print-defaults TYPE; docs/simulate.md) and writes a\n"
    "frame every output_every steps with all particles, all particle-particle\n"
    "contacts and all wall contacts (contact point, force and its normal and\n"
    "tangential parts, overlap, liquid-bridge volume) in the native format; a\n"
    "plugtube run also writes the tube and its gas fields (pressure, porosity,\n"
    "superficial gas velocity) and feeds and removes grains (docs/plugconveying.md).\n"
    "The scenario is checked and the initial state built before RUN.h5 is\n"
    "created; an existing RUN.h5 is refused unless --force (or --resume) is given.\n"
    "RUN.h5 is readable from the moment it exists (zero frames at first); each\n"
    "frame is flushed when written, so a killed run leaves a file readable up to\n"
    "its last complete frame.  A run whose state blows up (values that are not\n"
    "finite, a particle moving more than its radius per step or leaving the\n"
    "domain, overlaps beyond the smaller radius) stops with a message naming the\n"
    "step, the particle and the likely cause; its frames so far stay readable.\n"
    "A checkpoint (RUN.h5.ckpt) is written with the first frame, then with a frame\n"
    "at most once a minute (or every checkpoint_every steps), at --stop-at and at\n"
    "the end; --resume continues from it, bit for bit as if the run had not stopped.\n"
    "Forces are computed with OpenMP; the results are identical for any number of\n"
    "threads.",
    options,
    sizeof options / sizeof options[0],
    0,
    run,
};
