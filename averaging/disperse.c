/* mimas disperse: the frames into trajectories and cohorts, then one sweep
 * over the stored trajectories a block of particles at a time: the cohort
 * statistics and the FFT correlations, per particle group (for the
 * jackknife), then the tables and fits (disperse_fit.c). */
#include <config.h>

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "disperse_impl.h"
#include "parallel.h"
#include "h5util.h"

/* the default fit window: this share of the longest lag */
#define FIT_LO_SHARE 0.1
#define FIT_HI_SHARE 0.5
/* particles read from the store at once, at most */
#define MAX_READ_BLOCK 4096
/* what the libraries take beside the budget (HDF5's caches and free lists,
 * FFTW's plans, the reader's frame, the heap's slack): this much plus a
 * quarter of the memory is kept free */
#define HEADROOM ((size_t)8 << 20)

const char *mimas_disperse_component_name(int c)
{
    static const char *const names[MIMAS_DC_COUNT] = {"x", "y", "z", "axial", "transverse",
                                                      "total"};
    return c >= 0 && c < MIMAS_DC_COUNT ? names[c] : "?";
}

int mimas_disperse_component_dim(int c)
{
    return c == MIMAS_DC_TRANSVERSE ? 2 : c == MIMAS_DC_TOTAL ? 3 : 1;
}

struct mimas_disperse {
    mimas_disperse_options opt;
    int32_t types[64];
    mimas_axis axis;
    int axis_given, axis_set;
    mimas_trajectories *traj;
    mimas_cohorts *cohorts;
    mimas_disperse_result res;
    int finished;
};

/* What the process may hold beside the budget. */
static size_t kept_free(const mimas_disperse_options *o)
{
    return o->memory_held + HEADROOM + o->memory / 4;
}

/* The bytes disperse may allocate: --memory less the rest. */
static size_t budget(const mimas_disperse_options *o)
{
    return o->memory > kept_free(o) ? o->memory - kept_free(o) : 0;
}

int mimas_disperse_create(mimas_disperse **out, const mimas_disperse_options *o,
                          mimas_error *err)
{
    *out = NULL;
    if (o->has_fit_from && o->has_fit_lags)
        return mimas_error_set(err, MIMAS_EUSAGE, "--fit-from and --fit-lags exclude each "
                               "other");
    if (o->has_fit_from && !(o->fit_from >= 0))
        return mimas_error_set(err, MIMAS_EUSAGE, "--fit-from needs a length of at least 0");
    if (o->has_fit_lags && !(o->fit_lo >= 0 && o->fit_hi > o->fit_lo))
        return mimas_error_set(err, MIMAS_EUSAGE, "--fit-lags needs T0:T1 with 0 <= T0 < T1");
    if (o->has_max_lag && !(o->max_lag > 0))
        return mimas_error_set(err, MIMAS_EUSAGE, "--max-lag needs a positive time");
    if (o->ntypes > 64)
        return mimas_error_set(err, MIMAS_EUSAGE, "at most 64 particle types");
    mimas_disperse *d = calloc(1, sizeof *d);
    if (!d)
        return mimas_error_set(err, MIMAS_EIO, "out of memory");
    d->opt = *o;
    if (o->ntypes)
        memcpy(d->types, o->types, o->ntypes * sizeof *d->types);
    d->opt.types = d->types;
    d->opt.cohorts = NULL; /* parsed below; the strings are not kept */
    int rc = MIMAS_OK;
    if (o->axis) {
        rc = mimas_axis_parse(&d->axis, o->axis, err);
        d->axis_given = d->axis_set = 1;
    }
    if (!rc)
        rc = mimas_cohorts_create(&d->cohorts, o->cohorts, o->ncohorts, err);
    if (!rc && o->memory <= kept_free(o))
        rc = mimas_error_set(err, MIMAS_EUSAGE, "--memory %zu bytes leaves nothing for the "
                             "trajectories: give more than %zu", o->memory,
                             (o->memory_held + HEADROOM) / 3 * 4 + 1);
    mimas_traj_options to = {d->types, o->ntypes, o->exclude, o->vacf, budget(o), o->scratch_dir};
    if (!rc)
        rc = mimas_traj_create(&d->traj, &to, err);
    if (rc) {
        mimas_disperse_free(d);
        return rc;
    }
    *out = d;
    return MIMAS_OK;
}

int mimas_disperse_add(mimas_disperse *d, const mimas_frame *f, mimas_error *err)
{
    if (d->finished)
        return mimas_error_set(err, MIMAS_EUSAGE, "the analysis is finished");
    if (!d->axis_set) {
        /* the default axis: the tube of a tube-flow run, else z */
        int rc = f->tube.present ? mimas_axis_set(&d->axis, f->tube.origin, f->tube.direction,
                                                  err)
                                 : mimas_axis_parse(&d->axis, NULL, err);
        if (rc)
            return rc;
        d->res.axis_from_tube = f->tube.present;
        d->axis_set = 1;
    }
    int rc = mimas_traj_add(d->traj, f, err);
    if (!rc)
        rc = mimas_cohorts_frame(d->cohorts, f, mimas_traj_frame_slots(d->traj),
                                 mimas_traj_frame_new(d->traj), &d->axis, err);
    return rc;
}

size_t mimas_disperse_frames(const mimas_disperse *d)
{
    return mimas_traj_frames(d->traj);
}

const mimas_disperse_result *mimas_disperse_result_of(const mimas_disperse *d)
{
    return &d->res;
}

/* What the analysis may allocate besides the trajectories held: --memory
 * less what the process holds now (as the caller measures it, else what it
 * held at the start plus the trajectories in memory), the headroom and an
 * eighth. */
static size_t analysis_budget(const mimas_disperse *d, const mimas_traj_store *store)
{
    const mimas_disperse_options *o = &d->opt;
    size_t held = o->memory_held + mimas_traj_store_bytes(store);
    size_t now = o->resident ? o->resident() : 0;
    size_t keep = (now > held ? now : held) + HEADROOM + o->memory / 8;
    return o->memory > keep ? o->memory - keep : 0;
}

/* Everything the sweep needs. */
typedef struct sweep {
    mimas_disperse *d;
    mimas_traj_store *store;
    size_t T, N, K1, rc_n;        /* frames, particles, lags, record values */
    disperse_comps cm;
    mimas_msd *msd, *vacf;
    /* [0]: every particle (every lag); [1 + g]: group g (the fit window's lags) */
    mimas_msd_sums sums[1 + MIMAS_DISPERSE_GROUPS], vsums[1 + MIMAS_DISPERSE_GROUPS];
    size_t ngroups;
    cohort_stats *cstats;
    size_t *members;              /* per cohort: members met so far */
    size_t block;                 /* particles read at once */
    double *rec, *ser, *vser;     /* [block][T][rc_n], [block][T][cm.n] */
} sweep;

static void sweep_free(sweep *s)
{
    mimas_msd_free(s->msd);
    mimas_msd_free(s->vacf);
    for (size_t g = 0; g <= MIMAS_DISPERSE_GROUPS; g++) {
        mimas_msd_sums_free(&s->sums[g]);
        mimas_msd_sums_free(&s->vsums[g]);
    }
    size_t nc = s->d ? mimas_cohorts_count(s->d->cohorts) : 0;
    for (size_t k = 0; s->cstats && k < nc; k++)
        cohort_stats_free(&s->cstats[k]);
    free(s->cstats);
    free(s->members);
    free(s->rec);
    free(s->ser);
    free(s->vser);
}

/* Workspaces, sums and statistics; the read block from the memory left. */
static int sweep_init(sweep *s, mimas_disperse *d, mimas_error *err)
{
    mimas_disperse_result *r = &d->res;
    s->d = d;
    s->store = mimas_traj_store_of(d->traj);
    s->T = r->frames;
    s->N = r->particles;
    s->K1 = r->lags;
    s->rc_n = mimas_traj_store_ncomp(s->store);
    disperse_comps_choose(&s->cm, &r->axis);
    s->ngroups = s->N < MIMAS_DISPERSE_GROUPS ? s->N : MIMAS_DISPERSE_GROUPS;
    int vacf = d->opt.vacf;
    size_t nc = mimas_cohorts_count(d->cohorts), n = s->cm.n;
    size_t klo, khi;
    disperse_window(r, &klo, &khi);
    size_t wlags = khi + 1 - klo, vlags = khi + 1;
    size_t fixed = (1 + (size_t)vacf) * mimas_msd_bytes(s->T, s->K1 - 1, n) +
                   (n + 1) * sizeof(double) *
                       ((1 + (size_t)vacf) * s->K1 + s->ngroups * (wlags + (vacf ? vlags : 0))) +
                   nc * cohort_stats_bytes(s->T) + 3 * s->K1 * MIMAS_DC_COUNT * sizeof(double);
    size_t per = s->T * (s->rc_n + n * (1 + (size_t)vacf)) * sizeof(double);
    size_t mem = analysis_budget(d, s->store);
    int rc = MIMAS_OK;
    if (mimas_traj_store_bytes(s->store) && fixed + MIMAS_MSD_BLOCK * per > mem) {
        rc = mimas_traj_store_spill(s->store, err);
        mem = analysis_budget(d, s->store);
    }
    if (rc)
        return rc;
    if (fixed + per > mem)
        return mimas_error_set(err, MIMAS_EUSAGE, "--memory %zu bytes is too small for the "
                               "analysis of %zu frames: give at least %zu", d->opt.memory, s->T,
                               d->opt.memory + (fixed + per - mem) / 7 * 8 + 1);
    size_t b = (mem - fixed) / per;
    b = b > MAX_READ_BLOCK ? MAX_READ_BLOCK : b;
    if (b >= MIMAS_MSD_BLOCK)
        b -= b % MIMAS_MSD_BLOCK;
    if (b > s->N)
        b = s->N;
    s->block = b;
    rc = mimas_msd_create(&s->msd, MIMAS_MSD_DISPLACEMENT, s->T, s->K1 - 1, n, err);
    if (!rc && vacf)
        rc = mimas_msd_create(&s->vacf, MIMAS_MSD_AUTOCORRELATION, s->T, s->K1 - 1, n, err);
    for (size_t g = 0; g <= s->ngroups && !rc; g++) {
        rc = mimas_msd_sums_init(&s->sums[g], n, g ? klo : 0, g ? wlags : s->K1, err);
        if (!rc && vacf)
            rc = mimas_msd_sums_init(&s->vsums[g], n, 0, g ? vlags : s->K1, err);
    }
    if (rc)
        return rc;
    s->cstats = calloc(nc, sizeof *s->cstats);
    s->members = calloc(nc, sizeof *s->members);
    s->rec = malloc(b * s->T * s->rc_n * sizeof *s->rec);
    s->ser = malloc(b * s->T * n * sizeof *s->ser);
    s->vser = vacf ? malloc(b * s->T * n * sizeof *s->vser) : NULL;
    if (!s->cstats || !s->members || !s->rec || !s->ser || (vacf && !s->vser))
        return mimas_error_set(err, MIMAS_EIO, "out of memory");
    for (size_t k = 0; k < nc && !rc; k++)
        rc = cohort_stats_init(&s->cstats[k], s->T, err);
    return rc;
}

/* The cohort members of the block [first, first + n) into their statistics. */
static void add_cohorts(sweep *s, size_t first, size_t n)
{
    const mimas_axis *a = &s->d->res.axis;
    size_t nc = mimas_cohorts_count(s->d->cohorts);
    for (size_t j = 0; j < n; j++) {
        uint64_t mask = mimas_cohorts_mask(s->d->cohorts, first + j);
        for (size_t k = 0; k < nc; k++) {
            if (!(mask >> k & 1))
                continue;
            size_t member = s->members[k]++;
            for (size_t t = 0; t < s->T; t++) {
                const double *u = s->rec + (j * s->T + t) * s->rc_n;
                if (isnan(u[0]))
                    continue;
                double l[3];
                mimas_axis_to_local(a, u, l);
                cohort_stats_add(&s->cstats[k], member, t, l);
            }
        }
    }
}

/* The correlation series of the block: positions (and velocities) less the
 * drift when asked, in the components of s->cm; NaN where absent. */
static void make_series(sweep *s, size_t n)
{
    const mimas_axis *a = &s->d->res.axis;
    int drift = s->d->opt.remove_drift, vacf = s->d->opt.vacf;
    const double *R = mimas_traj_drift(s->d->traj), *V = mimas_traj_mean_velocity(s->d->traj);
    size_t nc = s->cm.n;
    for (size_t j = 0; j < n; j++)
        for (size_t t = 0; t < s->T; t++) {
            const double *u = s->rec + (j * s->T + t) * s->rc_n;
            double *x = s->ser + (j * s->T + t) * nc;
            double *v = vacf ? s->vser + (j * s->T + t) * nc : NULL;
            if (isnan(u[0])) {
                for (size_t c = 0; c < nc; c++) {
                    x[c] = NAN;
                    if (v)
                        v[c] = NAN;
                }
                continue;
            }
            double p[3], w[3];
            for (int c = 0; c < 3; c++) {
                p[c] = u[c] - (drift ? R[3 * t + c] : 0);
                if (v)
                    w[c] = u[3 + c] - (drift ? V[3 * t + c] : 0);
            }
            disperse_comps_project(&s->cm, a, p, x);
            if (v)
                disperse_comps_project(&s->cm, a, w, v);
        }
}

/* Under MPI the groups are shared out over the ranks (group g to rank
 * g mod size); a rank passes over the others' groups counting their cohort
 * members, so that every member keeps its serial number (and jackknife
 * group). */
static int group_is_mine(size_t g)
{
    return g % (size_t)mimas_par_size() == (size_t)mimas_par_rank();
}

static void count_members(sweep *s, size_t lo, size_t hi)
{
    size_t nc = mimas_cohorts_count(s->d->cohorts);
    for (size_t j = lo; j < hi; j++) {
        uint64_t mask = mimas_cohorts_mask(s->d->cohorts, j);
        for (size_t k = 0; k < nc; k++)
            s->members[k] += mask >> k & 1;
    }
}

/* One pass over the particles, group by group (contiguous slot ranges). */
static int run_sweep(sweep *s, mimas_error *err)
{
    int rc = MIMAS_OK;
    const mimas_disperse_options *o = &s->d->opt;
    for (size_t g = 0; g < s->ngroups && !rc; g++) {
        size_t lo = g * s->N / s->ngroups, hi = (g + 1) * s->N / s->ngroups;
        if (!group_is_mine(g)) {
            count_members(s, lo, hi);
            continue;
        }
        for (size_t a = lo; a < hi && !rc; a += s->block) {
            size_t n = hi - a < s->block ? hi - a : s->block;
            rc = mimas_traj_store_read(s->store, a, n, s->rec, err);
            if (rc)
                break;
            add_cohorts(s, a, n);
            make_series(s, n);
            rc = mimas_msd_add(s->msd, s->ser, n, s->cm.n, err);
            if (!rc && s->vacf)
                rc = mimas_msd_add(s->vacf, s->vser, n, s->cm.n, err);
            if (o->progress)
                o->progress(o->progress_ctx, a + n, s->N);
        }
        /* into the sums of every particle and those of the group */
        mimas_msd_sums two[2] = {s->sums[0], s->sums[1 + g]};
        if (!rc)
            rc = mimas_msd_flush(s->msd, two, 2, err);
        mimas_msd_sums vtwo[2] = {s->vsums[0], s->vsums[1 + g]};
        if (!rc && s->vacf)
            rc = mimas_msd_flush(s->vacf, vtwo, 2, err);
    }
    return rc;
}

/* ---- the ranks' sums merged onto rank 0 (MPI) ---- */
static size_t cohort_values(const sweep *s)
{
    return s->T * MIMAS_DISPERSE_GROUPS * 7;
}

/* The values of every sum of the sweep: the MSD (and VACF) sums of all
 * particles and of each group, then the cohort accumulators. */
static size_t sweep_values(const sweep *s)
{
    size_t nc = mimas_cohorts_count(s->d->cohorts), n = 0;
    for (size_t g = 0; g <= s->ngroups; g++)
        for (int v = 0; v < 1 + (s->vacf != NULL); v++) {
            const mimas_msd_sums *m = v ? &s->vsums[g] : &s->sums[g];
            n += (m->ncomp + 1) * m->nlags;
        }
    return n + nc * cohort_values(s);
}

static int pack_sweep(const void *obj, mimas_bytes *out, mimas_error *err)
{
    const sweep *s = obj;
    size_t nc = mimas_cohorts_count(s->d->cohorts), n = sweep_values(s);
    if (n * sizeof(double) > out->cap) {
        unsigned char *p = realloc(out->data, n * sizeof(double));
        if (!p)
            return mimas_error_set(err, MIMAS_EIO, "out of memory");
        out->data = p;
        out->cap = n * sizeof(double);
    }
    unsigned char *p = out->data;
    for (size_t g = 0; g <= s->ngroups; g++)
        for (int v = 0; v < 1 + (s->vacf != NULL); v++) {
            const mimas_msd_sums *m = v ? &s->vsums[g] : &s->sums[g];
            memcpy(p, m->num, m->ncomp * m->nlags * sizeof(double));
            p += m->ncomp * m->nlags * sizeof(double);
            memcpy(p, m->count, m->nlags * sizeof(double));
            p += m->nlags * sizeof(double);
        }
    for (size_t k = 0; k < nc; k++) {
        memcpy(p, s->cstats[k].acc, cohort_values(s) * sizeof(double));
        p += cohort_values(s) * sizeof(double);
    }
    out->n = n * sizeof(double);
    return MIMAS_OK;
}

static int merge_sweep(void *obj, const unsigned char *data, size_t bytes, mimas_error *err)
{
    sweep *s = obj;
    if (bytes != sweep_values(s) * sizeof(double))
        return mimas_error_set(err, MIMAS_EDATA, "the ranks' dispersion sums differ in size");
    const unsigned char *p = data;
    double v;
    for (size_t g = 0; g <= s->ngroups; g++)
        for (int w = 0; w < 1 + (s->vacf != NULL); w++) {
            mimas_msd_sums *m = w ? &s->vsums[g] : &s->sums[g];
            for (size_t i = 0; i < m->ncomp * m->nlags; i++, p += sizeof v) {
                memcpy(&v, p, sizeof v);
                m->num[i] += v;
            }
            for (size_t i = 0; i < m->nlags; i++, p += sizeof v) {
                memcpy(&v, p, sizeof v);
                m->count[i] += v;
            }
        }
    /* cohort accumulators: n, mean[3], m2[3] per frame and group (Chan's merge) */
    size_t nc = mimas_cohorts_count(s->d->cohorts);
    for (size_t k = 0; k < nc; k++)
        for (size_t i = 0; i < s->T * MIMAS_DISPERSE_GROUPS; i++, p += 7 * sizeof v) {
            double b[7], *a = s->cstats[k].acc + 7 * i;
            memcpy(b, p, sizeof b);
            if (b[0] == 0)
                continue;
            double na = a[0], nt = na + b[0];
            for (int c = 0; c < 3; c++) {
                double d = b[1 + c] - a[1 + c];
                a[1 + c] += d * b[0] / nt;
                a[4 + c] += b[4 + c] + d * d * na * b[0] / nt;
            }
            a[0] = nt;
        }
    return MIMAS_OK;
}

/* Frames, lags and the fit window. */
static int plan(mimas_disperse *d, mimas_error *err)
{
    mimas_disperse_result *r = &d->res;
    r->frames = mimas_traj_frames(d->traj);
    r->particles = mimas_traj_slots(d->traj);
    if (r->frames < 2)
        return mimas_error_set(err, MIMAS_EDATA, "dispersion needs at least two frames, the "
                               "selection has %zu", r->frames);
    if (!r->particles)
        return mimas_error_set(err, MIMAS_EDATA, "no particle in the selected frames and types");
    r->axis = d->axis;
    r->t_first = mimas_traj_times(d->traj)[0];
    r->dt = mimas_traj_interval(d->traj);
    size_t K = r->frames - 1;
    if (d->opt.has_max_lag) {
        double k = floor(d->opt.max_lag / r->dt * (1 + 1e-9));
        if (k < (double)K)
            K = (size_t)k;
    }
    r->lags = K + 1;
    if (d->opt.has_fit_lags) {
        r->fit_lo = d->opt.fit_lo;
        r->fit_hi = d->opt.fit_hi;
    } else {
        r->fit_lo = FIT_LO_SHARE * (double)K * r->dt;
        r->fit_hi = FIT_HI_SHARE * (double)K * r->dt;
    }
    r->jumps = *mimas_traj_jumps_seen(d->traj);
    size_t cells = r->lags * MIMAS_DC_COUNT;
    r->msd = malloc(cells * sizeof *r->msd);
    r->count = malloc(r->lags * sizeof *r->count);
    r->vacf = d->opt.vacf ? malloc(cells * sizeof *r->vacf) : NULL;
    r->ncohorts = mimas_cohorts_count(d->cohorts);
    r->cohorts = calloc(r->ncohorts, sizeof *r->cohorts);
    if (!r->msd || !r->count || (d->opt.vacf && !r->vacf) || !r->cohorts)
        return mimas_error_set(err, MIMAS_EIO, "out of memory");
    return MIMAS_OK;
}

int mimas_disperse_finish(mimas_disperse *d, mimas_error *err)
{
    if (d->finished)
        return MIMAS_OK;
    d->finished = 1;
    int rc = mimas_traj_finish(d->traj, err);
    /* what reading left in HDF5's free lists, back to the heap for the analysis */
    h5_release_free_lists();
    if (!rc)
        rc = plan(d, err);
    sweep s;
    memset(&s, 0, sizeof s);
    if (!rc)
        rc = sweep_init(&s, d, err);
    if (!rc)
        rc = run_sweep(&s, err);
    /* under MPI: every rank's groups onto rank 0, which makes the tables */
    rc = mimas_par_agree(rc, SIZE_MAX, err);
    if (!rc)
        rc = mimas_par_reduce(&s, pack_sweep, merge_sweep, err);
    if (!rc && mimas_par_rank() != 0) {
        sweep_free(&s);
        return MIMAS_OK;
    }
    mimas_disperse_result *r = &d->res;
    r->scratch = mimas_traj_store_on_disk(mimas_traj_store_of(d->traj));
    r->groups = s.ngroups;
    if (!rc)
        rc = disperse_lag_tables(r, &s.sums[0], &s.sums[1], s.ngroups, &s.cm, 0, err);
    if (!rc && d->opt.vacf)
        rc = disperse_lag_tables(r, &s.vsums[0], &s.vsums[1], s.ngroups, &s.cm, 1, err);
    for (size_t k = 0; k < r->ncohorts && !rc; k++)
        rc = disperse_cohort_table(r, k, mimas_cohorts_get(d->cohorts, k), &s.cstats[k],
                                   mimas_traj_times(d->traj), &d->opt, err);
    sweep_free(&s);
    return rc;
}

void mimas_disperse_free(mimas_disperse *d)
{
    if (!d)
        return;
    mimas_disperse_result *r = &d->res;
    free(r->msd);
    free(r->vacf);
    free(r->count);
    for (size_t k = 0; r->cohorts && k < r->ncohorts; k++)
        free(r->cohorts[k].rows);
    free(r->cohorts);
    free(r->diffusion);
    mimas_traj_free(d->traj);
    mimas_cohorts_free(d->cohorts);
    free(d);
}
