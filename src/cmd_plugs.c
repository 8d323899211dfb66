/* mimas plugs: axial profiles, plugs, plug tracks, plug-centred profiles,
 * statistics along the tube and the space-time diagram of a tube flow
 * (docs/plugs.md; Strauß 2005, Ch. 4-6; docs/theory.md §7.3). */
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
#include "plug_tracking.h"
#include "plugs.h"
#include "plugs_output.h"
#include "plugs_plot.h"
#include "reader.h"
#include "sample_mean.h"

static const cli_option options[] = {
    CLI_TUBE_OPTIONS,
    {"max-shift", 0, "X", "tracking gate: largest distance of a plug's centre from its "
                          "predicted position (m; default half the smallest plug distance)"},
    {"profile-range", 0, "A:B", "plug-centred profiles over A..B diameters from the centre "
                                "(default -20:20)"},
    {"profile-bin", 0, "B", "bin of the plug-centred profiles in diameters (default 0.5)"},
    {"velocity-window", 0, "V0:V1", "plug-centred profiles of plugs whose particle velocity "
                                    "lies in V0..V1 (m/s; default all)"},
    {"length-window", 0, "L0:L1", "plug-centred profiles of plugs of length L0..L1 (m; default "
                                  "all)"},
    {"stats-window", 0, "W", "window of the statistics along the tube (m; default a tenth of "
                             "the range)"},
    {"flow-at", 0, "S", "cross-section of the solid mass flow rate (m; default the middle of "
                        "the range)"},
    {"plugs", 0, "FILE", "write the plug table to FILE, or - for standard output (the default, "
                         "unless -o or another table takes standard output)"},
    {"tracks", 0, "FILE", "write the track table to FILE (- : standard output)"},
    {"events", 0, "FILE", "write the merge and split events to FILE (- : standard output)"},
    {"profiles", 0, "FILE", "write the plug-centred profiles to FILE (- : standard output)"},
    {"stats", 0, "FILE", "write the statistics along the tube to FILE (- : standard output)"},
    {"summary", 0, "FILE", "write the whole-run figures to FILE (- : standard output)"},
    {"axial", 0, "FILE.h5", "write the axial profiles as space-time fields (slice x frame; "
                            "XDMF sidecar FILE.xdmf)"},
    {"axial-tsv", 0, "FILE", "write the axial profiles as a long table (- : standard output)"},
    {"spacetime", 0, "FILE.png", "draw the space-time porosity diagram with the plug centres "
                                 "(gnuplot)"},
    {"output", 'o', "FILE.h5", "write every table to one HDF5 file (a group per table)"},
    {"from", 0, "T0", "first time to use (s)"},
    {"to", 0, "T1", "last time to use (s)"},
    {"every", 0, "K", "use every K-th frame of those selected"},
    CLI_TABLE_OPTIONS,
};

enum { O_MAXSHIFT = CLI_TUBE_NOPTIONS, O_PRANGE, O_PBIN, O_VWIN, O_LWIN, O_SWIN, O_FLOWAT,
       O_PLUGS, O_TRACKS, O_EVENTS, O_PROFILES, O_STATS, O_SUMMARY, O_AXIAL, O_AXIAL_TSV,
       O_SPACETIME, O_OUTPUT, O_FROM, O_TO, O_EVERY, O_TABLE };

typedef struct plugs_args {
    const cli_command *cmd;
    cli_tube_args tube;
    double max_shift;
    double p0, p1, pbin, v0, v1, l0, l1, stats_w, flow_at;
    int has_flow_at;
    int plugs_off;             /* another table takes standard output */
    const char *plugs, *tracks, *events, *profiles, *stats, *summary, *axial, *axial_tsv,
        *spacetime, *output;
    cli_window window;
    cli_table_options table;
} plugs_args;

static int on_option(void *ctx, size_t opt, const char *arg)
{
    plugs_args *a = ctx;
    if (opt < CLI_TUBE_NOPTIONS)
        return cli_tube_option(a->cmd, &a->tube, (int)opt, arg);
    switch (opt) {
    case O_MAXSHIFT: return cli_positive_option(a->cmd, "max-shift", arg, &a->max_shift);
    case O_PRANGE: return cli_pair_option(a->cmd, "profile-range", "A:B", arg, &a->p0, &a->p1);
    case O_PBIN: return cli_positive_option(a->cmd, "profile-bin", arg, &a->pbin);
    case O_VWIN: return cli_pair_option(a->cmd, "velocity-window", "V0:V1", arg, &a->v0, &a->v1);
    case O_LWIN: return cli_pair_option(a->cmd, "length-window", "L0:L1", arg, &a->l0, &a->l1);
    case O_SWIN: return cli_positive_option(a->cmd, "stats-window", arg, &a->stats_w);
    case O_FLOWAT:
        if (cli_parse_double(arg, &a->flow_at))
            return cli_fail(a->cmd, 1, "--flow-at needs an axial position (m), not '%s'", arg);
        a->has_flow_at = 1;
        return 0;
    case O_PLUGS: a->plugs = arg; return 0;
    case O_TRACKS: a->tracks = arg; return 0;
    case O_EVENTS: a->events = arg; return 0;
    case O_PROFILES: a->profiles = arg; return 0;
    case O_STATS: a->stats = arg; return 0;
    case O_SUMMARY: a->summary = arg; return 0;
    case O_AXIAL: a->axial = arg; return 0;
    case O_AXIAL_TSV: a->axial_tsv = arg; return 0;
    case O_SPACETIME: a->spacetime = arg; return 0;
    case O_OUTPUT: a->output = arg; return 0;
    case O_FROM:
    case O_TO: return cli_window_time(a->cmd, &a->window, opt == O_FROM, arg);
    case O_EVERY: return cli_window_every(a->cmd, &a->window, arg);
    default: return cli_table_option(a->cmd, &a->table, opt - O_TABLE, arg);
    }
}

/* ---- the tables' columns ---- */

static const mimas_ocolumn plug_cols[] = {
    {"frame", "1", "index of the frame among those used (from 0)", 0, 1},
    {"time", "s", "simulation time", 0, 0},
    {"track", "1", "track id (from 1)", 0, 1},
    {"centre", "m", "centre of mass of the particle volume in the plug's slices", 0, 0},
    {"front", "m", "end of the plug towards the outlet (larger s)", 0, 0},
    {"back", "m", "end of the plug towards the inlet", 0, 0},
    {"length", "m", "front - back", 0, 0},
    {"count", "1", "particles in the plug (volume fractions summed)", 0, 0},
    {"mass", "kg", "mass in the plug's slices", 0, 0},
    {"velocity", "m s-1", "mass-weighted mean axial particle velocity", 0, 0},
    {"min_porosity", "1", "smallest slice porosity in the plug", 0, 0},
    {"wall_pressure", "Pa", "normal force on the wall along the plug / (2 pi R length)", 0, 0},
    {"cut", "1", "1 if the plug touches an end of the range (its extent is not known)", 0, 1},
};
enum { NPLUGCOLS = sizeof plug_cols / sizeof plug_cols[0] };

static const mimas_ocolumn track_cols[] = {
    {"track", "1", "track id", 0, 1},
    {"first_time", "s", "first frame of the track", 0, 0},
    {"last_time", "s", "last frame of the track", 0, 0},
    {"frames", "1", "frames the plug was seen in", 0, 1},
    {"plug_velocity", "m s-1", "least-squares slope of the centre's trajectory", 0, 0},
    {"plug_velocity_err", "m s-1", "its standard error (from the scatter about the line)", 0, 0},
    {"front_velocity", "m s-1", "least-squares slope of the front's trajectory", 0, 0},
    {"back_velocity", "m s-1", "least-squares slope of the back's trajectory", 0, 0},
    {"particle_velocity", "m s-1", "mean mass-weighted particle velocity in the plug", 0, 0},
    {"length", "m", "mean length", 0, 0},
    {"mass", "kg", "mean mass", 0, 0},
    {"fitted", "1", "frames used for the velocities and means (the plug not cut)", 0, 1},
};
enum { NTRACKCOLS = sizeof track_cols / sizeof track_cols[0] };

static const mimas_ocolumn event_cols[] = {
    {"time", "s", "frame in which the plugs after the event are first seen", 0, 0},
    {"kind", "", "merge (n plugs -> 1), split (1 -> n) or regroup (n -> m)", 1, 0},
    {"tracks", "", "the tracks that end > the tracks that start, comma lists", 1, 0},
    {"centre", "m", "mass-weighted centre of the plugs after the event", 0, 0},
};

static const mimas_ocolumn summary_cols[] = {
    {"quantity", "", "name", 1, 0},
    {"value", "", "mean over the frames used (or a count)", 0, 0},
    {"error", "", "standard error over frames (nan where it does not apply)", 0, 0},
    {"unit", "", "SI unit", 1, 0},
};

/* ---- the run ---- */

typedef struct plugs_run {
    plugs_args *a;
    cli_inputs *in;
    const char *input;
    mimas_axial_options ao;
    mimas_plug_options po;
    mimas_tracking_options to;
    mimas_axial *ax;
    mimas_tracker *tr;
    mimas_plug_list list;
    double *prof;
    size_t prof_cap;
    size_t *prof_count;        /* bins x fields, the profiles' workspace */
    /* rank 0: a frame's result unpacked, in frame order */
    mimas_plug_list got;
    double *got_prof;
    size_t got_cap;
    /* outputs */
    mimas_h5out *h5;
    cli_output plug_out, axial_out;
    cli_otable plug_tab, axial_tab;
    int plug_on, axial_on;     /* the tables are open */
    FILE *plug_tmp;            /* the plug table on its way to standard output */
    mimas_ocolumn axial_cols[3 + MIMAS_AX_NFIELDS];
    mimas_spacetime *st;
    mimas_stplot *plot;
    /* whole-run figures */
    mimas_sample_mean particles, mass, flow, dp;
    size_t plugs_seen;
    size_t frames;
} plugs_run;

/* The slices, detection and tracking options and the defaults that depend
 * on the data (ts: from the first frame, the same on every rank); rank 0
 * opens the per-frame outputs. */
static int setup(void *ctx, const void *data, mimas_error *err)
{
    plugs_run *u = ctx;
    const mimas_tube_setup *ts = data;
    plugs_args *a = u->a;
    mimas_axial_options *o = &u->ao;
    double d, s0, s1;
    int rc = cli_tube_plug_setup(&a->tube, ts, o, &u->po, &d, &s0, &s1, err);
    if (rc)
        return rc;
    o->flow_at = a->has_flow_at ? a->flow_at : 0.5 * (s0 + s1);
    mimas_tracking_options *t = &u->to;
    t->max_shift = a->max_shift > 0 ? a->max_shift : NAN;
    t->bins.d = d;
    t->bins.lo = a->p0;
    t->bins.w = a->pbin;
    double nb = ceil((a->p1 - a->p0) / a->pbin - 1e-9);
    if (nb > 1e5)
        return mimas_error_set(err, MIMAS_EUSAGE, "--profile-range over --profile-bin: too many "
                               "bins");
    t->bins.n = (size_t)nb;
    t->v0 = a->v0;
    t->v1 = a->v1;
    t->l0 = a->l0;
    t->l1 = a->l1;
    t->stats_s0 = s0;
    double sw = a->stats_w > 0 ? a->stats_w : 0.1 * (s1 - s0);
    double ns = round((s1 - s0) / sw);
    if (ns > 1e6)
        return mimas_error_set(err, MIMAS_EUSAGE, "--stats-window: too many windows");
    t->stats_n = ns < 1 ? 1 : (size_t)ns;
    t->stats_w = (s1 - s0) / (double)t->stats_n;
    int root = mimas_par_rank() == 0;
    if ((rc = mimas_axial_create(&u->ax, o, err)) ||
        (rc = mimas_tracker_create(&u->tr, t, err)))
        return rc;
    /* the per-frame outputs */
    if (!root)
        return MIMAS_OK;
    if (a->axial && (rc = mimas_spacetime_open(&u->st, a->axial, u->ax, err)))
        return rc;
    if (a->spacetime && (rc = mimas_stplot_open(&u->plot, a->spacetime, &o->slices, err)))
        return rc;
    if (a->axial_tsv) {
        static const mimas_ocolumn lead[3] = {{"frame", "1", "frame index", 0, 1},
                                              {"time", "s", "time", 0, 0},
                                              {"s", "m", "slice centre", 0, 0}};
        memcpy(u->axial_cols, lead, sizeof lead);
        for (int k = 0; k < MIMAS_AX_NFIELDS; k++) {
            const mimas_axial_field_desc *fd = mimas_axial_field(k);
            u->axial_cols[3 + k] = (mimas_ocolumn){fd->name, fd->unit, fd->meaning, 0, 0};
        }
        if ((rc = cli_output_open(&u->axial_out, a->axial_tsv, err)) ||
            (rc = cli_otable_open(&u->axial_tab, u->axial_out.fp, &a->table, NULL, NULL,
                                  u->axial_cols, 3 + MIMAS_AX_NFIELDS, err)))
            return rc;
        u->axial_on = 1;
    }
    /* the defaults taken, once everything is set up (an error is then its one line) */
    if (!u->in->quiet && (!a->tube.has_range || !(a->tube.slice > 0) || !(a->tube.diameter > 0)))
        fprintf(stderr, "mimas plugs: tube radius %g m, %zu slices of %g m over %g:%g m, "
                        "d = %g m\n", o->geom.radius, o->slices.n, o->slices.w, s0, s1, d);
    return MIMAS_OK;
}

/* ---- a frame: computed on the rank that owns it, used on rank 0 ---- */

/* A frame's result: step, time, the plug count n, the whole-frame figures,
 * the slices' fields, the n plugs and their plug-centred profiles. */
typedef struct frame_head {
    int64_t step;
    double time;
    uint64_t nplugs;
    mimas_axial_totals totals;
} frame_head;

static int pack_frame(const plugs_run *u, const mimas_frame *f, mimas_bytes *b,
                      mimas_error *err)
{
    size_t ns = u->ao.slices.n, np = u->list.n, nb = u->to.bins.n * MIMAS_AX_NFIELDS;
    size_t nf = ns * MIMAS_AX_NFIELDS * sizeof(double);
    size_t total = sizeof(frame_head) + nf + np * (sizeof(mimas_plug) + nb * sizeof(double));
    if (total > b->cap) {
        unsigned char *q = realloc(b->data, total);
        if (!q)
            return mimas_error_set(err, MIMAS_EIO, "out of memory");
        b->data = q;
        b->cap = total;
    }
    frame_head h = {f->step, f->time, np, mimas_axial_frame_totals(u->ax)};
    unsigned char *at = b->data;
    memcpy(at, &h, sizeof h);
    at += sizeof h;
    for (size_t k = 0; k < ns; k++, at += MIMAS_AX_NFIELDS * sizeof(double))
        memcpy(at, mimas_axial_row(u->ax, k), MIMAS_AX_NFIELDS * sizeof(double));
    if (np) {
        memcpy(at, u->list.p, np * sizeof(mimas_plug));
        at += np * sizeof(mimas_plug);
        memcpy(at, u->prof, np * nb * sizeof(double));
    }
    b->n = total;
    return MIMAS_OK;
}

/* The per-frame part: slice profiles, the frame's plugs and their
 * plug-centred profiles, packed into result; index: the frame's place in
 * the selection. */
static int one_frame(void *ctx, const mimas_frame *f, size_t index, mimas_bytes *result,
                     mimas_error *err)
{
    plugs_run *u = ctx;
    int rc = MIMAS_OK;
    if ((rc = mimas_axial_compute(u->ax, f, err)) ||
        (rc = mimas_plugs_detect(u->ax, &u->po, index, f->time, &u->list, err)))
        return rc;
    size_t need = u->list.n * u->to.bins.n * MIMAS_AX_NFIELDS;
    if (need > u->prof_cap) {
        double *p = realloc(u->prof, need * sizeof *p);
        if (!p)
            return mimas_error_set(err, MIMAS_EIO, "out of memory");
        u->prof = p;
        u->prof_cap = need;
    }
    if (!u->prof_count &&
        !(u->prof_count = malloc((u->to.bins.n * MIMAS_AX_NFIELDS + 1) * sizeof *u->prof_count)))
        return mimas_error_set(err, MIMAS_EIO, "out of memory");
    for (size_t j = 0; j < u->list.n; j++)
        mimas_plug_profile(u->ax, &u->list.p[j], &u->to.bins,
                           &u->prof[j * u->to.bins.n * MIMAS_AX_NFIELDS], u->prof_count);
    return pack_frame(u, f, result, err);
}

static int frame_outputs(plugs_run *u, const frame_head *h, mimas_error *err)
{
    int rc = MIMAS_OK;
    size_t idx = u->frames;
    if (u->st)
        rc = mimas_spacetime_append(u->st, u->ax, h->step, h->time, err);
    if (!rc && u->plot)
        rc = mimas_stplot_frame(u->plot, u->ax, h->time, &u->got, err);
    for (size_t k = 0; !rc && u->axial_on && k < u->ao.slices.n; k++) {
        double row[3 + MIMAS_AX_NFIELDS] = {(double)idx, h->time,
                                            mimas_slice_centre(&u->ao.slices, k)};
        memcpy(row + 3, mimas_axial_row(u->ax, k), MIMAS_AX_NFIELDS * sizeof(double));
        rc = cli_otable_row(&u->axial_tab, row, NULL, err);
    }
    for (size_t j = 0; !rc && u->plug_on && j < u->got.n; j++) {
        const mimas_plug *p = &u->got.p[j];
        double row[NPLUGCOLS] = {(double)p->frame, p->time, (double)p->track, p->centre,
                                 p->front, p->back, p->length, p->count, p->mass, p->velocity,
                                 p->min_porosity, p->wall_pressure, (double)p->cut};
        rc = cli_otable_row(&u->plug_tab, row, NULL, err);
    }
    return rc;
}

/* The sequential part, on rank 0 in frame order: a frame's result into the
 * tracking, the per-frame outputs and the whole-run figures. */
static int use_frame(void *ctx, size_t position, const unsigned char *data, size_t n,
                     mimas_error *err)
{
    (void)position;
    plugs_run *u = ctx;
    frame_head h;
    size_t ns = u->ao.slices.n, nb = u->to.bins.n * MIMAS_AX_NFIELDS;
    size_t nf = ns * MIMAS_AX_NFIELDS * sizeof(double);
    if (n < sizeof h + nf)
        return mimas_error_set(err, MIMAS_EDATA, "a per-frame result is truncated");
    memcpy(&h, data, sizeof h);
    size_t np = (size_t)h.nplugs;
    if (n != sizeof h + nf + np * (sizeof(mimas_plug) + nb * sizeof(double)))
        return mimas_error_set(err, MIMAS_EDATA, "a per-frame result is truncated");
    const unsigned char *at = data + sizeof h;
    double *fields = malloc(nf ? nf : 1);
    if (!fields)
        return mimas_error_set(err, MIMAS_EIO, "out of memory");
    memcpy(fields, at, nf);
    mimas_axial_load(u->ax, fields, &h.totals);
    free(fields);
    at += nf;
    if (np > u->got.cap) {
        mimas_plug *p = realloc(u->got.p, np * sizeof *p);
        if (!p)
            return mimas_error_set(err, MIMAS_EIO, "out of memory");
        u->got.p = p;
        u->got.cap = np;
    }
    if (np * nb > u->got_cap) {
        double *q = realloc(u->got_prof, np * nb * sizeof *q);
        if (!q)
            return mimas_error_set(err, MIMAS_EIO, "out of memory");
        u->got_prof = q;
        u->got_cap = np * nb;
    }
    u->got.n = np;
    if (np) {
        memcpy(u->got.p, at, np * sizeof(mimas_plug));
        memcpy(u->got_prof, at + np * sizeof(mimas_plug), np * nb * sizeof(double));
    }
    int rc = mimas_tracker_add(u->tr, h.time, &u->got, u->got_prof, err);
    if (rc && rc != MIMAS_EIO && rc != MIMAS_EUSAGE)
        mimas_error_prefix(err, "%s: step %lld", u->input, (long long)h.step);
    if (rc || (rc = frame_outputs(u, &h, err)))
        return rc;
    mimas_sample_mean_add(&u->particles, h.totals.particles);
    mimas_sample_mean_add(&u->mass, h.totals.mass);
    mimas_sample_mean_add(&u->flow, h.totals.flow_rate);
    if (!isnan(h.totals.pressure_drop))
        mimas_sample_mean_add(&u->dp, h.totals.pressure_drop);
    u->plugs_seen += np;
    u->frames++;
    return MIMAS_OK;
}

/* ---- the tables written at the end ---- */

/* Opens a table at path (TSV, "-" standard output) and/or in group name of
 * the HDF5 output, writes rows with fill(), closes. */
typedef int (*fill_fn)(const plugs_run *u, cli_otable *t, mimas_error *err);

static int write_table(plugs_run *u, const char *path, const char *group,
                       const mimas_ocolumn *cols, size_t n, fill_fn fill, mimas_error *err)
{
    if (!path && !u->h5)
        return MIMAS_OK;
    cli_output out = {0};
    int rc = path ? cli_output_open(&out, path, err) : MIMAS_OK;
    cli_otable t = {0};
    if (!rc)
        rc = cli_otable_open(&t, path ? out.fp : NULL, &u->a->table, u->h5, group, cols, n, err);
    if (!rc)
        rc = fill(u, &t, err);
    int closed = cli_otable_close(&t, err);
    if (!rc)
        rc = closed;
    closed = cli_output_close(&out, rc == MIMAS_OK, err);
    return rc ? rc : closed;
}

static int fill_tracks(const plugs_run *u, cli_otable *t, mimas_error *err)
{
    int rc = MIMAS_OK;
    for (size_t k = 0; !rc && k < mimas_tracker_ntracks(u->tr); k++) {
        const mimas_track_row *r = mimas_tracker_track(u->tr, k);
        double row[NTRACKCOLS] = {(double)r->track, r->first_time, r->last_time,
                                  (double)r->frames, r->plug_velocity, r->plug_velocity_err,
                                  r->front_velocity, r->back_velocity, r->particle_velocity,
                                  r->length, r->mass, (double)r->fitted};
        rc = cli_otable_row(t, row, NULL, err);
    }
    return rc;
}

static int fill_events(const plugs_run *u, cli_otable *t, mimas_error *err)
{
    int rc = MIMAS_OK;
    for (size_t k = 0; !rc && k < mimas_tracker_nevents(u->tr); k++) {
        const mimas_event *e = mimas_tracker_event(u->tr, k);
        char ids[1024];
        size_t len = 0;
        for (size_t m = 0; m < e->nbefore + e->nafter && len < sizeof ids - 32; m++)
            len += (size_t)snprintf(ids + len, sizeof ids - len, "%s%ld",
                                    m == 0 ? "" : m == e->nbefore ? ">" : ",", e->tracks[m]);
        double row[4] = {e->time, 0, 0, e->centre};
        const char *text[4] = {NULL, mimas_event_kind_name(e->kind), ids, NULL};
        rc = cli_otable_row(t, row, text, err);
    }
    return rc;
}

static int fill_profiles(const plugs_run *u, cli_otable *t, mimas_error *err)
{
    int rc = MIMAS_OK;
    const mimas_profile_bins *b = &u->to.bins;
    for (size_t k = 0; !rc && k < b->n; k++) {
        double row[2 + 2 * MIMAS_AX_NFIELDS];
        row[0] = b->lo + ((double)k + 0.5) * b->w;
        size_t n = 0, nt = 0;
        for (int f = 0; f < MIMAS_AX_NFIELDS; f++) {
            mimas_tracker_profile(u->tr, k, f, &row[1 + 2 * f], &row[2 + 2 * f], &n);
            if (f == MIMAS_AX_POROSITY)
                nt = n;
        }
        row[1 + 2 * MIMAS_AX_NFIELDS] = (double)nt;
        rc = cli_otable_row(t, row, NULL, err);
    }
    return rc;
}

static int fill_stats(const plugs_run *u, cli_otable *t, mimas_error *err)
{
    int rc = MIMAS_OK;
    for (size_t w = 0; !rc && w < u->to.stats_n; w++) {
        double row[3 + 3 * MIMAS_ST_N + 3];
        row[0] = u->to.stats_s0 + (double)w * u->to.stats_w;
        row[1] = row[0] + u->to.stats_w;
        row[2] = 0.5 * (row[0] + row[1]);
        for (int q = 0; q < MIMAS_ST_N; q++) {
            size_t n;
            mimas_tracker_stat(u->tr, w, q, &row[3 + 3 * q], &row[4 + 3 * q], &n);
            row[5 + 3 * q] = (double)n;
        }
        long passages;
        double *r = &row[3 + 3 * MIMAS_ST_N];
        mimas_tracker_passages(u->tr, w, &passages, &r[1], &r[2]);
        r[0] = (double)passages;
        rc = cli_otable_row(t, row, NULL, err);
    }
    return rc;
}

static int fill_summary(const plugs_run *u, cli_otable *t, mimas_error *err)
{
    size_t merges = 0, splits = 0;
    for (size_t k = 0; k < mimas_tracker_nevents(u->tr); k++) {
        int kind = mimas_tracker_event(u->tr, k)->kind;
        merges += kind == MIMAS_EVENT_MERGE;
        splits += kind == MIMAS_EVENT_SPLIT;
    }
    struct {
        const char *name, *unit;
        const mimas_sample_mean *m;
        double count;
    } rows[] = {
        {"frames", "1", NULL, (double)u->frames},
        {"time_span", "s", NULL, mimas_tracker_span(u->tr)},
        {"particles_in_tube", "1", &u->particles, 0},
        {"mass_in_tube", "kg", &u->mass, 0},
        {"mass_flow_rate", "kg s-1", &u->flow, 0},
        {"pressure_drop", "Pa", &u->dp, 0},
        {"plugs", "1", NULL, (double)u->plugs_seen},
        {"tracks", "1", NULL, (double)mimas_tracker_ntracks(u->tr)},
        {"merges", "1", NULL, (double)merges},
        {"splits", "1", NULL, (double)splits},
    };
    int rc = MIMAS_OK;
    for (size_t k = 0; !rc && k < sizeof rows / sizeof rows[0]; k++) {
        double v[4] = {0, rows[k].count, NAN, 0};
        if (rows[k].m)
            mimas_sample_mean_get(rows[k].m, &v[1], &v[2], NULL);
        const char *text[4] = {rows[k].name, NULL, NULL, rows[k].unit};
        rc = cli_otable_row(t, v, text, err);
    }
    return rc;
}

/* Column lists that depend on the fields: the profiles and the statistics. */
typedef struct colbuf {
    mimas_ocolumn c[2 + 2 * MIMAS_AX_NFIELDS + 3 + 3 * MIMAS_ST_N + 3];
    char names[2 + 2 * MIMAS_AX_NFIELDS + 3 * MIMAS_ST_N][48];
    size_t n;
} colbuf;

static void col(colbuf *b, const char *name, const char *unit, const char *meaning, int own)
{
    if (own) {
        snprintf(b->names[b->n], sizeof b->names[0], "%s", name);
        name = b->names[b->n];
    }
    b->c[b->n++] = (mimas_ocolumn){name, unit, meaning, 0, 0};
}

static void profile_columns(colbuf *b)
{
    b->n = 0;
    col(b, "ds", "1", "distance of the bin centre from the plug centre in diameters", 0);
    for (int f = 0; f < MIMAS_AX_NFIELDS; f++) {
        const mimas_axial_field_desc *d = mimas_axial_field(f);
        char sem[48];
        snprintf(sem, sizeof sem, "%s_sem", d->name);
        col(b, d->name, d->unit, "mean over tracks of the per-track mean", 0);
        col(b, sem, d->unit, "standard error over tracks", 1);
    }
    col(b, "tracks", "1", "tracks with a porosity value in the bin", 0);
    b->c[b->n - 1].integer = 1;
}

static void stats_columns(colbuf *b)
{
    b->n = 0;
    col(b, "s_lo", "m", "window start", 0);
    col(b, "s_hi", "m", "window end", 0);
    col(b, "s", "m", "window centre", 0);
    for (int q = 0; q < MIMAS_ST_N; q++) {
        char e[48], n[48];
        snprintf(e, sizeof e, "%s_err", mimas_stat_name(q));
        snprintf(n, sizeof n, "%s_n", mimas_stat_name(q));
        col(b, mimas_stat_name(q), mimas_stat_unit(q), "mean over tracks of the per-track mean "
            "of the plugs centred in the window", 0);
        col(b, e, mimas_stat_unit(q), "standard error over tracks", 1);
        col(b, n, "1", "tracks", 1);
        b->c[b->n - 1].integer = 1;
    }
    col(b, "passages", "1", "net passages of plug centres through the window centre", 0);
    b->c[b->n - 1].integer = 1;
    col(b, "passage_rate", "s-1", "passages / time span", 0);
    col(b, "passage_rate_err", "s-1", "sqrt(|passages|) / time span", 0);
}

/* The temporary file to standard output; 0 on success. */
static int copy_out(FILE *tmp)
{
    char buf[65536];
    size_t n;
    rewind(tmp);
    while ((n = fread(buf, 1, sizeof buf, tmp)) > 0)
        if (fwrite(buf, 1, n, stdout) != n)
            return -1;
    return ferror(tmp) || fflush(stdout) != 0 ? -1 : 0;
}

static int finish(plugs_run *u, int argc, char **argv, mimas_error *err)
{
    plugs_args *a = u->a;
    int rc = mimas_tracker_finish(u->tr, err);
    colbuf pc, sc;
    profile_columns(&pc);
    stats_columns(&sc);
    if (!rc)
        rc = write_table(u, a->tracks, "/tracks", track_cols, NTRACKCOLS, fill_tracks, err);
    if (!rc)
        rc = write_table(u, a->events, "/events", event_cols, 4, fill_events, err);
    if (!rc)
        rc = write_table(u, a->profiles, "/profiles", pc.c, pc.n, fill_profiles, err);
    if (!rc)
        rc = write_table(u, a->stats, "/stats", sc.c, sc.n, fill_stats, err);
    if (!rc)
        rc = write_table(u, a->summary, "/summary", summary_cols, 4, fill_summary, err);
    char *line = cli_command_line(argc, argv);
    if (!rc && u->st) {
        rc = mimas_spacetime_finish(u->st, line, err);
        u->st = NULL;
    }
    if (!rc && u->plot) {
        rc = mimas_stplot_finish(u->plot, err);
        u->plot = NULL;
    }
    int closed = cli_otable_close(&u->plug_tab, err);
    if (!rc)
        rc = closed;
    closed = cli_otable_close(&u->axial_tab, err);
    if (!rc)
        rc = closed;
    if (!rc && u->h5) {
        rc = mimas_h5out_commit(u->h5, line, err);
        u->h5 = NULL;
    }
    free(line);
    if (!rc && u->plug_tmp && copy_out(u->plug_tmp))
        rc = mimas_error_set(err, MIMAS_EIO, "cannot write the plug table");
    closed = cli_output_close(&u->plug_out, rc == MIMAS_OK, err);
    if (!rc)
        rc = closed;
    closed = cli_output_close(&u->axial_out, rc == MIMAS_OK, err);
    return rc ? rc : closed;
}

static void cleanup(plugs_run *u, mimas_error *err)
{
    mimas_error junk;
    cli_otable_close(&u->plug_tab, &junk);
    cli_otable_close(&u->axial_tab, &junk);
    cli_output_close(&u->plug_out, 0, &junk);
    cli_output_close(&u->axial_out, 0, &junk);
    mimas_spacetime_abort(u->st);
    mimas_stplot_abort(u->plot);
    mimas_h5out_abort(u->h5);
    if (u->plug_tmp)
        fclose(u->plug_tmp);
    mimas_axial_free(u->ax);
    mimas_tracker_free(u->tr);
    mimas_plug_list_free(&u->list);
    mimas_plug_list_free(&u->got);
    free(u->got_prof);
    free(u->prof);
    free(u->prof_count);
    (void)err;
}

static int run(const cli_command *cmd, int argc, char **argv)
{
    plugs_args a;
    memset(&a, 0, sizeof a);
    a.cmd = cmd;
    cli_tube_args_init(&a.tube);
    a.p0 = -20;
    a.p1 = 20;
    a.pbin = 0.5;
    a.v0 = a.l0 = -INFINITY;
    a.v1 = a.l1 = INFINITY;
    cli_inputs in = {0};
    int first;
    int rc = cli_parse(cmd, argc, argv, on_option, &a, &in, &first);
    if (!rc && first >= argc)
        rc = cli_fail(cmd, 1, "no input file (see mimas plugs --help)");
    /* one table at most on standard output ("-"); the plug table goes there
     * unless another table or -o takes its place */
    const char *const tables[] = {a.plugs, a.tracks, a.events, a.profiles, a.stats, a.summary,
                                  a.axial_tsv};
    static const char *const table_opts[] = {"plugs", "tracks", "events", "profiles", "stats",
                                             "summary", "axial-tsv"};
    int on_stdout = -1;
    for (int k = 0; !rc && k < 7; k++) {
        if (!tables[k] || strcmp(tables[k], "-"))
            continue;
        if (on_stdout >= 0)
            rc = cli_fail(cmd, 1, "--%s - and --%s -: only one table can go to standard output",
                          table_opts[on_stdout], table_opts[k]);
        on_stdout = k;
    }
    if (on_stdout > 0 && !a.plugs)
        a.plugs_off = 1;
    for (int k = 0; !rc && k < 7; k++)
        rc = cli_refuse_input_as_output(cmd, tables[k], &in, argv + first, argc - first);
    if (!rc)
        rc = cli_refuse_input_as_output(cmd, a.output, &in, argv + first, argc - first) ||
             cli_refuse_input_as_output(cmd, a.axial, &in, argv + first, argc - first);
    mimas_reader *r = NULL;
    if (!rc)
        rc = cli_open_inputs(cmd, &in, argc, argv, first, &r);
    if (rc) {
        cli_inputs_free(&in);
        return rc < 0 ? 0 : rc;
    }
    plugs_run u;
    memset(&u, 0, sizeof u);
    u.a = &a;
    u.in = &in;
    u.input = argv[first];
    mimas_error err;
    int status = MIMAS_OK;
    /* the outputs on rank 0 only (under MPI frame j is computed on rank
     * j mod N and its result used on rank 0 in frame order) */
    int root = mimas_par_rank() == 0;
    if (root && a.output)
        status = mimas_h5out_open(&u.h5, a.output, &err);
    /* the plug table streams; for standard output through a temporary file,
     * so that a failed run prints nothing */
    int to_tsv = root && !a.plugs_off && (a.plugs || !a.output);
    int to_stdout = to_tsv && (!a.plugs || !strcmp(a.plugs, "-"));
    if (!status && to_stdout && !(u.plug_tmp = tmpfile()))
        status = mimas_error_set(&err, MIMAS_EIO, "cannot make a temporary file");
    if (!status && to_tsv && !to_stdout)
        status = cli_output_open(&u.plug_out, a.plugs, &err);
    FILE *plug_fp = to_stdout ? u.plug_tmp : to_tsv ? u.plug_out.fp : NULL;
    if (!status && root)
        status = cli_otable_open(&u.plug_tab, plug_fp, &a.table, u.h5, "/plugs", plug_cols,
                                 NPLUGCOLS, &err);
    u.plug_on = root && !status;
    status = mimas_par_agree(status, SIZE_MAX, &err);
    cli_progress prog;
    cli_progress_start(&prog, &in);
    cli_frames frames;
    cli_frames_init(&frames, r, &a.window, argv[first]);
    mimas_tube_setup ts;
    memset(&ts, 0, sizeof ts);
    cli_frame_work work = {&u, cli_tube_decide, &a.tube, &ts, sizeof ts, setup, one_frame,
                           use_frame};
    if (!status)
        status = cli_frames_run(&frames, &work, cmd, &prog, &err);
    cli_progress_done(&prog);
    mimas_reader_close(r);
    if (status == MIMAS_END && root)
        status = finish(&u, argc, argv, &err);
    status = mimas_par_share(status, NULL, 0, &err);
    cleanup(&u, &err);
    cli_inputs_free(&in);
    if (status && status != MIMAS_END)
        return cli_fail(cmd, mimas_exit_status(status), "%s", err.msg);
    return 0;
}

const cli_command cmd_plugs = {
    "plugs",
    "axial profiles, plugs, plug tracks and statistics of a tube flow",
    "INPUT... [--axis X0,Y0,Z0,DX,DY,DZ] [--tube-radius R] [options]",
    "Cuts every frame into slices along the tube axis, each particle weighted by\n"
    "the exact volume of its sphere in the slice, and computes per slice the\n"
    "porosity, velocity, granular temperature, axial and radial stress, wall\n"
    "pressure and shear, and the gas pressure where the input has gas fields.\n"
    "A plug is a maximal run of slices with porosity below --threshold at least\n"
    "--min-length long; plugs of consecutive frames are tracked (merges and\n"
    "splits are events), giving plug and particle velocities per track,\n"
    "plug-centred profiles and statistics along the tube (docs/plugs.md,\n"
    "docs/theory.md section 7.3).  Writes the plug table (frame time track centre\n"
    "front back length count mass velocity min_porosity wall_pressure cut) to\n"
    "standard output; the other tables, the space-time fields and diagram on\n"
    "request.  The tube comes from the input (mimas simulate) or from --axis and\n"
    "--tube-radius.",
    options,
    sizeof options / sizeof options[0],
    1,
    run,
    "# plugs of a tube-flow run whose file records its tube (mimas simulate's\n"
    "# plugtube): the plug list, the tracks, statistics along the tube and the\n"
    "# space-time porosity diagram (docs/plugs.md)\n"
    "mimas plugs tube.h5 --tracks tracks.tsv --stats stats.tsv --spacetime spacetime.png \\\n"
    "    >plugs.tsv\n"
    "\n"
    "# every table in one HDF5 file, the axial profiles as space-time fields for\n"
    "# ParaView, plugs denser than a porosity of 0.5 only\n"
    "mimas plugs tube.h5 --threshold 0.5 -o plugs.h5 --axial axial.h5",
};
