/* mimas radial: radial profiles of a tube flow by probe spheres
 * (docs/radial.md; Strauß 2005, Sec. 4.2, 5.6, 6.6; docs/theory.md §7.4). */
#include <config.h>

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "axial_profile.h"
#include "cli_frames.h"
#include "cli_tube.h"
#include "cli_table.h"
#include "commands.h"
#include "frame_pack.h"
#include "parallel.h"
#include "plugs.h"
#include "plugs_output.h"
#include "radial.h"
#include "reader.h"

static const cli_option options[] = {
    CLI_TUBE_OPTIONS,
    {"probe", 0, "D", "probe sphere diameter (m; default a quarter of the mean diameter)"},
    {"planes", 0, "N", "probe planes in a group (default 4)"},
    {"plane-spread", 0, "X", "axial distance from the first to the last plane of a group (m; "
                             "default 1.5 diameters)"},
    {"dr", 0, "H", "radial step of the probe circles (m; default half the probe diameter)"},
    {"at", 0, "S0:S1", "axial window: planes repeated along it at the group's spacing "
                       "(default: the tube, else the particles of the first frame)"},
    {"in-plugs", 0, NULL, "one group of planes at each plug's centre (plugs as in mimas plugs; "
                          "cut plugs are left out): radial plug profiles"},
    {"output", 'o', "FILE", "write the table to FILE (default: standard output)"},
    {"from", 0, "T0", "first time to use (s)"},
    {"to", 0, "T1", "last time to use (s)"},
    {"every", 0, "K", "use every K-th frame of those selected"},
    CLI_TABLE_OPTIONS,
};

enum { O_PROBE = CLI_TUBE_NOPTIONS, O_PLANES, O_SPREAD, O_DR, O_AT, O_INPLUGS, O_OUTPUT,
       O_FROM, O_TO, O_EVERY, O_TABLE };

typedef struct radial_args {
    const cli_command *cmd;
    const char *output;
    cli_tube_args tube;
    double probe, spread, dr, at0, at1;
    long planes;
    int has_at, in_plugs;
    cli_window window;
    cli_table_options table;
} radial_args;

static int on_option(void *ctx, size_t opt, const char *arg)
{
    radial_args *a = ctx;
    if (opt < CLI_TUBE_NOPTIONS)
        return cli_tube_option(a->cmd, &a->tube, (int)opt, arg);
    switch (opt) {
    case O_PROBE: return cli_positive_option(a->cmd, "probe", arg, &a->probe);
    case O_PLANES:
        if (cli_parse_long(arg, &a->planes) || a->planes < 1 || a->planes > 1000)
            return cli_fail(a->cmd, 1, "--planes needs a whole number 1..1000, not '%s'", arg);
        return 0;
    case O_SPREAD: return cli_positive_option(a->cmd, "plane-spread", arg, &a->spread);
    case O_DR: return cli_positive_option(a->cmd, "dr", arg, &a->dr);
    case O_AT: a->has_at = 1; return cli_pair_option(a->cmd, "at", "S0:S1", arg, &a->at0, &a->at1);
    case O_INPLUGS: a->in_plugs = 1; return 0;
    case O_OUTPUT: a->output = arg; return 0;
    case O_FROM:
    case O_TO: return cli_window_time(a->cmd, &a->window, opt == O_FROM, arg);
    case O_EVERY: return cli_window_every(a->cmd, &a->window, arg);
    default: return cli_table_option(a->cmd, &a->table, opt - O_TABLE, arg);
    }
}

typedef struct radial_run {
    radial_args *a;
    mimas_radial *rad;
    mimas_axial *ax;           /* --in-plugs */
    mimas_plug_options po;
    mimas_plug_list list;
    double *planes;            /* the planes of a sample */
    size_t nplanes, cap;
    double spacing;            /* between the planes of a group */
} radial_run;

/* The probes (ts: decided on the first frame, the same on every rank). */
static int setup(void *ctx, const void *data, mimas_error *err)
{
    radial_run *u = ctx;
    const mimas_tube_setup *ts = data;
    radial_args *a = u->a;
    mimas_radial_options o;
    memset(&o, 0, sizeof o);
    o.geom = ts->geom;
    double d = a->tube.diameter > 0 ? a->tube.diameter : ts->diameter, s0, s1;
    int rc, known = isfinite(o.geom.length);
    if (a->in_plugs) {
        /* plugs found as mimas plugs finds them, over --range */
        mimas_axial_options ao;
        if ((rc = cli_tube_plug_setup(&a->tube, ts, &ao, &u->po, &d, &s0, &s1, err)) ||
            (rc = mimas_axial_create(&u->ax, &ao, err)))
            return rc;
    } else {
        s0 = a->has_at ? a->at0 : known ? 0.0 : ts->s_min;
        s1 = a->has_at ? a->at1 : known ? o.geom.length : ts->s_max;
        if ((rc = mimas_tube_defaults_known(d, s0, s1, err)))
            return rc;
    }
    o.probe = a->probe > 0 ? a->probe : 0.25 * d;
    o.dr = a->dr > 0 ? a->dr : 0.5 * o.probe;
    o.temperature = a->tube.temperature;
    o.types = a->tube.types.types;
    o.ntypes = a->tube.types.n;
    o.exclude = a->tube.types.exclude;
    o.check_inside = 1;
    if ((rc = mimas_radial_create(&u->rad, &o, err)))
        return rc;
    double spread = a->spread > 0 ? a->spread : 1.5 * d;
    size_t P = (size_t)a->planes;
    u->spacing = P > 1 ? spread / (double)(P - 1) : spread;
    if (a->in_plugs) {
        u->cap = P;
    } else {
        double n = floor((s1 - s0) / u->spacing + 1e-9) + 1;
        if (n > 1e6)
            return mimas_error_set(err, MIMAS_EUSAGE, "--at %g:%g: too many planes", s0, s1);
        u->cap = u->nplanes = (size_t)n;
        double first = s0 + 0.5 * ((s1 - s0) - (n - 1) * u->spacing);
        u->planes = malloc(u->cap * sizeof *u->planes);
        for (size_t k = 0; u->planes && k < u->nplanes; k++)
            u->planes[k] = first + (double)k * u->spacing;
    }
    if (!u->planes && !(u->planes = malloc(u->cap * sizeof *u->planes)))
        return mimas_error_set(err, MIMAS_EIO, "out of memory");
    return MIMAS_OK;
}

/* One sample's values appended to the frame's result b. */
static int keep_sample(const radial_run *u, mimas_bytes *b, mimas_error *err)
{
    size_t n = mimas_radial_nradii(u->rad) * MIMAS_RAD_NFIELDS * sizeof(double);
    if (b->n + n > b->cap) {
        size_t cap = 2 * (b->n + n);
        unsigned char *p = realloc(b->data, cap);
        if (!p)
            return mimas_error_set(err, MIMAS_EIO, "out of memory");
        b->data = p;
        b->cap = cap;
    }
    memcpy(b->data + b->n, mimas_radial_values(u->rad), n);
    b->n += n;
    return MIMAS_OK;
}

/* The frame's samples (the frame, or its plugs) into result, on the rank
 * that owns the frame; index: the frame's place in the selection. */
static int one_frame(void *ctx, const mimas_frame *f, size_t index, mimas_bytes *result,
                     mimas_error *err)
{
    radial_run *u = ctx;
    int rc = MIMAS_OK;
    result->n = 0;
    if (!u->ax) {
        rc = mimas_radial_probe(u->rad, f, u->planes, u->nplanes, err);
        return rc ? rc : keep_sample(u, result, err);
    }
    if ((rc = mimas_axial_compute(u->ax, f, err)) ||
        (rc = mimas_plugs_detect(u->ax, &u->po, index, f->time, &u->list, err)))
        return rc;
    size_t P = u->cap;
    for (size_t j = 0; !rc && j < u->list.n; j++) {
        const mimas_plug *p = &u->list.p[j];
        if (p->cut)
            continue;
        for (size_t k = 0; k < P; k++)
            u->planes[k] = p->centre + ((double)k - 0.5 * (double)(P - 1)) * u->spacing;
        if (!(rc = mimas_radial_probe(u->rad, f, u->planes, P, err)))
            rc = keep_sample(u, result, err);
    }
    return rc;
}

/* Rank 0, in frame order: a frame's samples into the averages (the same
 * order as a serial run, so the same numbers). */
static int add_samples(void *ctx, size_t position, const unsigned char *data, size_t n,
                       mimas_error *err)
{
    (void)position;
    radial_run *u = ctx;
    size_t one = mimas_radial_nradii(u->rad) * MIMAS_RAD_NFIELDS;
    if (n % (one * sizeof(double)))
        return mimas_error_set(err, MIMAS_EDATA, "a per-frame result is truncated");
    double *v = malloc(one * sizeof *v);
    if (!v)
        return mimas_error_set(err, MIMAS_EIO, "out of memory");
    for (size_t at = 0; at < n; at += one * sizeof(double)) {
        memcpy(v, data + at, one * sizeof *v);
        mimas_radial_add(u->rad, v);
    }
    free(v);
    return MIMAS_OK;
}

static int write_results(const radial_run *u, const char *path, mimas_error *err)
{
    mimas_ocolumn cols[2 + 2 * MIMAS_RAD_NFIELDS + 1];
    char sem[MIMAS_RAD_NFIELDS][32];
    size_t n = 0;
    cols[n++] = (mimas_ocolumn){"r", "m", "radius of the probe circle", 0, 0};
    for (int q = 0; q < MIMAS_RAD_NFIELDS; q++) {
        const mimas_radial_field_desc *d = mimas_radial_field(q);
        cols[n++] = (mimas_ocolumn){d->name, d->unit, d->meaning, 0, 0};
    }
    cols[n++] = (mimas_ocolumn){"count", "1", "samples (frames, or plugs with --in-plugs)", 0, 1};
    for (int q = 0; q < MIMAS_RAD_NFIELDS; q++) {
        const mimas_radial_field_desc *d = mimas_radial_field(q);
        snprintf(sem[q], sizeof sem[q], "%s_sem", d->name);
        cols[n++] = (mimas_ocolumn){sem[q], d->unit, "standard error over the samples", 0, 0};
    }
    cols[n++] = (mimas_ocolumn){"probes", "1", "probes per circle and plane", 0, 1};
    cli_output out = {0};
    cli_otable t = {0};
    int rc = cli_output_open(&out, path, err);
    if (!rc)
        rc = cli_otable_open(&t, out.fp, &u->a->table, NULL, NULL, cols, n, err);
    for (size_t k = 0; !rc && k < mimas_radial_nradii(u->rad); k++) {
        double row[2 + 2 * MIMAS_RAD_NFIELDS + 1], sd;
        size_t c = 0, cnt = 0;
        row[c++] = mimas_radial_radius(u->rad, k);
        for (int q = 0; q < MIMAS_RAD_NFIELDS; q++) {
            size_t m;
            mimas_radial_result(u->rad, k, q, &row[c++], &sd, &m);
            row[1 + MIMAS_RAD_NFIELDS + 1 + q] = sd;
            if (q == MIMAS_RAD_POROSITY)
                cnt = m;
        }
        row[c] = (double)cnt;
        row[2 + 2 * MIMAS_RAD_NFIELDS] = (double)mimas_radial_probes(u->rad, k);
        rc = cli_otable_row(&t, row, NULL, err);
    }
    int closed = cli_otable_close(&t, err);
    if (!rc)
        rc = closed;
    closed = cli_output_close(&out, rc == MIMAS_OK, err);
    return rc ? rc : closed;
}

static int run(const cli_command *cmd, int argc, char **argv)
{
    radial_args a;
    memset(&a, 0, sizeof a);
    a.cmd = cmd;
    a.planes = 4;
    cli_tube_args_init(&a.tube);
    cli_inputs in = {0};
    int first;
    int rc = cli_parse(cmd, argc, argv, on_option, &a, &in, &first);
    if (!rc && first >= argc)
        rc = cli_fail(cmd, 1, "no input file (see mimas radial --help)");
    if (!rc && a.in_plugs && a.has_at)
        rc = cli_fail(cmd, 1, "--at and --in-plugs exclude each other");
    if (!rc)
        rc = cli_refuse_input_as_output(cmd, a.output, &in, argv + first, argc - first);
    mimas_reader *r = NULL;
    if (!rc)
        rc = cli_open_inputs(cmd, &in, argc, argv, first, &r);
    if (rc) {
        cli_inputs_free(&in);
        return rc < 0 ? 0 : rc;
    }
    radial_run u;
    memset(&u, 0, sizeof u);
    u.a = &a;
    mimas_error err;
    cli_progress prog;
    cli_progress_start(&prog, &in);
    /* under MPI: frame j on rank j mod N; the geometry from the first frame
     * (rank 0's), each frame's samples to rank 0 in frame order */
    cli_frames frames;
    cli_frames_init(&frames, r, &a.window, argv[first]);
    mimas_tube_setup ts;
    memset(&ts, 0, sizeof ts);
    cli_frame_work work = {&u, cli_tube_decide, &a.tube, &ts, sizeof ts, setup, one_frame,
                           add_samples};
    int status = cli_frames_run(&frames, &work, cmd, &prog, &err);
    cli_progress_done(&prog);
    mimas_reader_close(r);
    cli_inputs_free(&in);
    if (status == MIMAS_END && mimas_par_rank() == 0)
        status = write_results(&u, a.output, &err);
    status = mimas_par_share(status, NULL, 0, &err);
    mimas_radial_free(u.rad);
    mimas_axial_free(u.ax);
    mimas_plug_list_free(&u.list);
    free(u.planes);
    if (status && status != MIMAS_END)
        return cli_fail(cmd, mimas_exit_status(status), "%s", err.msg);
    return 0;
}

const cli_command cmd_radial = {
    "radial",
    "radial profiles of a tube flow by probe spheres",
    "INPUT... [--axis X0,Y0,Z0,DX,DY,DZ] [--tube-radius R] [options]",
    "Places probe spheres of diameter --probe on circles about the tube axis in\n"
    "groups of --planes planes spread over --plane-spread, at radii 0, --dr, ...\n"
    "up to R - probe/2, and weights each particle by the exact lens volume it\n"
    "shares with a probe.  Per radius: porosity, solid fraction, velocity (r, phi,\n"
    "s), granular temperature and rotational energy, averaged over the probes of\n"
    "the radius, then over frames (or plugs with --in-plugs) with standard\n"
    "errors.  Writes r porosity nu v_r v_phi v_s T E_rot count, the _sem columns\n"
    "and probes (docs/radial.md, docs/theory.md section 7.4).  The options of\n"
    "plug detection (--range, --slice, --threshold, --min-length) matter only\n"
    "with --in-plugs.",
    options,
    sizeof options / sizeof options[0],
    1,
    run,
    "# radial profiles over the whole tube, every frame (docs/radial.md)\n"
    "mimas radial tube.h5 -o radial.tsv\n"
    "\n"
    "# radial profiles in the plugs only, one group of probe planes at each plug's\n"
    "# centre, from 0.05 s on\n"
    "mimas radial tube.h5 --in-plugs --from 0.05 >radial-plugs.tsv",
};
