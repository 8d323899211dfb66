/* Plug tracking, plug-centred profiles and statistics along the tube
 * (plug_tracking.h). */
#include <config.h>

#include "plug_tracking.h"
#include "grow.h"
#include "sample_mean.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Least squares of y(t) by running sums about the first point. */
typedef struct line {
    size_t n;
    double t0, y0, St, Stt, Sy, Sty, Syy;
} line;

static void line_add(line *l, double t, double y)
{
    if (!l->n) {
        l->t0 = t;
        l->y0 = y;
    }
    t -= l->t0;
    y -= l->y0;
    l->n++;
    l->St += t;
    l->Stt += t * t;
    l->Sy += y;
    l->Sty += t * y;
    l->Syy += y * y;
}

/* The slope and its standard error from the scatter about the line (as
 * gsl_fit_linear estimates it): NaN slope below two points, NaN error
 * below three. */
static void line_slope(const line *l, double *slope, double *err)
{
    *slope = *err = NAN;
    if (l->n < 2)
        return;
    double n = (double)l->n, mt = l->St / n, my = l->Sy / n;
    double stt = l->Stt - n * mt * mt, sty = l->Sty - n * mt * my, syy = l->Syy - n * my * my;
    if (!(stt > 0))
        return;
    *slope = sty / stt;
    if (l->n < 3)
        return;
    double s2 = fmax(0.0, syy - *slope * sty) / (n - 2.0);
    *err = sqrt(s2 / stt);
}

typedef struct track {
    long id;
    double first_time, last_time;
    size_t frames, uncut;
    line centre, front, back;
    double sum_v, sum_len, sum_mass;
    double last_centre, last_time_seen, velocity; /* the prediction's velocity */
    int has_velocity;
    double *psum;          /* plug-centred profile sums, bins x fields */
    size_t *pcnt;
    long window;           /* statistics window of the open sample, -1: none */
    double wsum[MIMAS_ST_N];
    size_t wcnt[MIMAS_ST_N];
} track;

struct mimas_tracker {
    mimas_tracking_options o;
    size_t nprof;          /* bins x fields */
    long next_id;
    /* the previous frame: its plugs and the open track of each */
    mimas_plug *prev;
    track **prev_track;
    size_t nprev, cap_prev;
    size_t frames;
    double first_time, last_time;
    /* results */
    mimas_track_row *rows;
    size_t nrows, cap_rows;
    mimas_event *events;
    size_t nevents, cap_events;
    mimas_sample_mean *profile;          /* nprof */
    mimas_sample_mean *stats;            /* stats_n x MIMAS_ST_N */
    long *passages;        /* stats_n */
    int sorted;
};

static const char *const kind_names[] = {"merge", "split", "regroup"};
static const char *const stat_names[MIMAS_ST_N] = {"plug_velocity", "particle_velocity",
                                                   "length", "min_porosity", "wall_pressure"};
static const char *const stat_units[MIMAS_ST_N] = {"m s-1", "m s-1", "m", "1", "Pa"};

const char *mimas_event_kind_name(int kind)
{
    return kind >= 0 && kind <= MIMAS_EVENT_REGROUP ? kind_names[kind] : "?";
}

const char *mimas_stat_name(int q)
{
    return q >= 0 && q < MIMAS_ST_N ? stat_names[q] : NULL;
}

const char *mimas_stat_unit(int q)
{
    return q >= 0 && q < MIMAS_ST_N ? stat_units[q] : NULL;
}

int mimas_tracker_create(mimas_tracker **tp, const mimas_tracking_options *o, mimas_error *err)
{
    mimas_tracker *t = calloc(1, sizeof *t);
    if (!t)
        return mimas_error_set(err, MIMAS_EIO, "out of memory");
    t->o = *o;
    t->nprof = o->bins.n * MIMAS_AX_NFIELDS;
    t->next_id = 1;
    t->profile = calloc(t->nprof ? t->nprof : 1, sizeof *t->profile);
    t->stats = calloc(o->stats_n ? o->stats_n * MIMAS_ST_N : 1, sizeof *t->stats);
    t->passages = calloc(o->stats_n ? o->stats_n : 1, sizeof *t->passages);
    if (!t->profile || !t->stats || !t->passages) {
        mimas_tracker_free(t);
        return mimas_error_set(err, MIMAS_EIO, "out of memory");
    }
    *tp = t;
    return MIMAS_OK;
}

static void track_free(track *k)
{
    if (!k)
        return;
    free(k->psum);
    free(k->pcnt);
    free(k);
}

void mimas_tracker_free(mimas_tracker *t)
{
    if (!t)
        return;
    for (size_t i = 0; i < t->nprev; i++)
        track_free(t->prev_track[i]);
    free(t->prev);
    free(t->prev_track);
    free(t->rows);
    for (size_t i = 0; i < t->nevents; i++)
        free(t->events[i].tracks);
    free(t->events);
    free(t->profile);
    free(t->stats);
    free(t->passages);
    free(t);
}

static track *track_new(mimas_tracker *t)
{
    track *k = calloc(1, sizeof *k);
    if (!k)
        return NULL;
    if (t->nprof) {
        k->psum = calloc(t->nprof, sizeof *k->psum);
        k->pcnt = calloc(t->nprof, sizeof *k->pcnt);
        if (!k->psum || !k->pcnt) {
            track_free(k);
            return NULL;
        }
    }
    k->id = t->next_id++;
    k->window = -1;
    return k;
}

/* The open statistics sample of a track goes into its window's means. */
static void flush_window(mimas_tracker *t, track *k)
{
    if (k->window < 0)
        return;
    mimas_sample_mean *a = &t->stats[(size_t)k->window * MIMAS_ST_N];
    for (int q = 0; q < MIMAS_ST_N; q++) {
        if (k->wcnt[q])
            mimas_sample_mean_add(&a[q], k->wsum[q] / (double)k->wcnt[q]);
        k->wsum[q] = 0;
        k->wcnt[q] = 0;
    }
    k->window = -1;
}

/* A track ends: its row, its profile sample. */
static int track_close(mimas_tracker *t, track *k, mimas_error *err)
{
    flush_window(t, k);
    for (size_t q = 0; q < t->nprof; q++)
        if (k->pcnt[q])
            mimas_sample_mean_add(&t->profile[q], k->psum[q] / (double)k->pcnt[q]);
    int rc = mimas_grow((void **)&t->rows, &t->cap_rows, t->nrows + 1, sizeof *t->rows, 64, err);
    if (rc)
        return rc;
    mimas_track_row *r = &t->rows[t->nrows++];
    r->track = k->id;
    r->first_time = k->first_time;
    r->last_time = k->last_time;
    r->frames = k->frames;
    r->fitted = k->uncut;
    line_slope(&k->centre, &r->plug_velocity, &r->plug_velocity_err);
    double e;
    line_slope(&k->front, &r->front_velocity, &e);
    line_slope(&k->back, &r->back_velocity, &e);
    double n = (double)k->uncut;
    r->particle_velocity = k->uncut ? k->sum_v / n : NAN;
    r->length = k->uncut ? k->sum_len / n : NAN;
    r->mass = k->uncut ? k->sum_mass / n : NAN;
    track_free(k);
    return MIMAS_OK;
}

static long window_of(const mimas_tracker *t, double s)
{
    if (!t->o.stats_n)
        return -1;
    double w = floor((s - t->o.stats_s0) / t->o.stats_w);
    return w >= 0 && w < (double)t->o.stats_n ? (long)w : -1;
}

static void window_add(mimas_tracker *t, track *k, long w, int q, double x)
{
    if (w < 0 || isnan(x))
        return;
    if (k->window != w) {
        flush_window(t, k);
        k->window = w;
    }
    k->wsum[q] += x;
    k->wcnt[q]++;
}

/* The plug p (with its profile) is the track's next instance; prev is its
 * previous instance when the track goes on (NULL: a new track). */
static void track_extend(mimas_tracker *t, track *k, const mimas_plug *p, const mimas_plug *prev,
                         const double *profile)
{
    if (!k->frames)
        k->first_time = p->time;
    k->frames++;
    k->last_time = p->time;
    double v_inst = NAN;
    if (prev) {
        k->velocity = (p->centre - prev->centre) / (p->time - prev->time);
        k->has_velocity = 1;
        if (!p->cut && !prev->cut)
            v_inst = k->velocity;
        /* passages through the windows' centre planes */
        for (size_t w = 0; w < t->o.stats_n; w++) {
            double sw = t->o.stats_s0 + ((double)w + 0.5) * t->o.stats_w;
            if (prev->centre < sw && p->centre >= sw)
                t->passages[w]++;
            else if (prev->centre >= sw && p->centre < sw)
                t->passages[w]--;
        }
    }
    k->last_centre = p->centre;
    k->last_time_seen = p->time;
    if (p->cut)
        return;
    k->uncut++;
    line_add(&k->centre, p->time, p->centre);
    line_add(&k->front, p->time, p->front);
    line_add(&k->back, p->time, p->back);
    k->sum_v += p->velocity;
    k->sum_len += p->length;
    k->sum_mass += p->mass;
    long w = window_of(t, p->centre);
    window_add(t, k, w, MIMAS_ST_PLUG_VELOCITY, v_inst);
    window_add(t, k, w, MIMAS_ST_PARTICLE_VELOCITY, p->velocity);
    window_add(t, k, w, MIMAS_ST_LENGTH, p->length);
    window_add(t, k, w, MIMAS_ST_MIN_POROSITY, p->min_porosity);
    window_add(t, k, w, MIMAS_ST_WALL_PRESSURE, p->wall_pressure);
    if (profile && t->nprof && p->velocity >= t->o.v0 && p->velocity <= t->o.v1 &&
        p->length >= t->o.l0 && p->length <= t->o.l1)
        for (size_t q = 0; q < t->nprof; q++)
            if (!isnan(profile[q])) {
                k->psum[q] += profile[q];
                k->pcnt[q]++;
            }
}

/* The gate: half the smallest distance between neighbouring plug centres
 * in either frame; with no two plugs in a frame, the longest plug. */
static double gate(const mimas_tracker *t, const mimas_plug_list *q)
{
    if (!isnan(t->o.max_shift))
        return t->o.max_shift;
    double m = INFINITY, longest = 0;
    for (size_t i = 0; i < t->nprev; i++) {
        if (i)
            m = fmin(m, t->prev[i].centre - t->prev[i - 1].centre);
        longest = fmax(longest, t->prev[i].length);
    }
    for (size_t j = 0; j < q->n; j++) {
        if (j)
            m = fmin(m, q->p[j].centre - q->p[j - 1].centre);
        longest = fmax(longest, q->p[j].length);
    }
    return isfinite(m) ? 0.5 * m : longest;
}

static size_t find(size_t *parent, size_t x)
{
    while (parent[x] != x)
        x = parent[x] = parent[parent[x]];
    return x;
}

static int add_event(mimas_tracker *t, int kind, double time, double centre, const long *ids,
                     size_t nb, size_t na, mimas_error *err)
{
    int rc = mimas_grow((void **)&t->events, &t->cap_events, t->nevents + 1, sizeof *t->events,
                        32, err);
    if (rc)
        return rc;
    mimas_event *e = &t->events[t->nevents];
    e->tracks = malloc((nb + na) * sizeof *e->tracks);
    if (!e->tracks)
        return mimas_error_set(err, MIMAS_EIO, "out of memory");
    memcpy(e->tracks, ids, (nb + na) * sizeof *ids);
    e->time = time;
    e->centre = centre;
    e->kind = kind;
    e->nbefore = nb;
    e->nafter = na;
    t->nevents++;
    return MIMAS_OK;
}

int mimas_tracker_add(mimas_tracker *t, double time, mimas_plug_list *q, const double *profiles,
                      mimas_error *err)
{
    if (!isfinite(time))
        return mimas_error_set(err, MIMAS_EDATA, "the frame has no time (give --timestep)");
    if (t->frames && !(time > t->last_time))
        return mimas_error_set(err, MIMAS_EDATA, "frame times must increase (%g after %g)", time,
                               t->last_time);
    if (!t->frames)
        t->first_time = time;
    t->frames++;
    t->last_time = time;
    size_t np = t->nprev, nq = q->n, nn = np + nq;
    size_t *parent = malloc((nn ? nn : 1) * sizeof *parent);
    size_t *np_of = calloc(nn ? nn : 1, sizeof *np_of), *nq_of = calloc(nn ? nn : 1, sizeof *nq_of);
    track **next = malloc((nq ? nq : 1) * sizeof *next);
    long *ids = malloc((nn ? nn : 1) * sizeof *ids);
    int rc = MIMAS_OK;
    if (!parent || !np_of || !nq_of || !next || !ids) {
        rc = mimas_error_set(err, MIMAS_EIO, "out of memory");
        goto done;
    }
    for (size_t x = 0; x < nn; x++)
        parent[x] = x;
    /* candidates: the predicted extent meets the plug's, or the predicted
     * centre is within the gate */
    double g = nq && np ? gate(t, q) : 0.0;
    for (size_t i = 0; i < np; i++) {
        const mimas_plug *a = &t->prev[i];
        const track *k = t->prev_track[i];
        double dt = time - a->time, v = k->has_velocity ? k->velocity : a->velocity;
        double shift = isfinite(v) ? v * dt : 0.0;
        for (size_t j = 0; j < nq; j++) {
            const mimas_plug *b = &q->p[j];
            int meet = fmin(a->front + shift, b->front) > fmax(a->back + shift, b->back);
            if (meet || fabs(a->centre + shift - b->centre) <= g) {
                size_t ra = find(parent, i), rb = find(parent, np + j);
                if (ra != rb)
                    parent[ra] = rb;
            }
        }
    }
    for (size_t i = 0; i < np; i++)
        np_of[find(parent, i)]++;
    for (size_t j = 0; j < nq; j++)
        nq_of[find(parent, np + j)]++;
    /* components: 1 -> 1 goes on, 1 -> 0 ends, 0 -> 1 starts, others are events */
    for (size_t j = 0; j < nq; j++)
        next[j] = NULL;
    for (size_t j = 0; !rc && j < nq; j++) {
        size_t root = find(parent, np + j);
        if (np_of[root] == 1 && nq_of[root] == 1) {
            for (size_t i = 0; i < np; i++)
                if (find(parent, i) == root) {
                    next[j] = t->prev_track[i];
                    t->prev_track[i] = NULL;
                    track_extend(t, next[j], &q->p[j], &t->prev[i],
                                 profiles ? &profiles[j * t->nprof] : NULL);
                }
        }
    }
    /* events: the tracks before, the new ones after */
    for (size_t j = 0; !rc && j < nq; j++) {
        if (next[j])
            continue;
        size_t root = find(parent, np + j);
        if (np_of[root] == 0) {
            if (!(next[j] = track_new(t)))
                rc = mimas_error_set(err, MIMAS_EIO, "out of memory");
            else
                track_extend(t, next[j], &q->p[j], NULL, profiles ? &profiles[j * t->nprof] : NULL);
            continue;
        }
        /* the first plug of an event component: make the whole event */
        size_t nb = 0, na = 0;
        double cm = 0, mass = 0;
        for (size_t i = 0; i < np; i++)
            if (find(parent, i) == root)
                ids[nb++] = t->prev_track[i]->id;
        for (size_t m = j; !rc && m < nq; m++) {
            if (find(parent, np + m) != root)
                continue;
            if (!(next[m] = track_new(t))) {
                rc = mimas_error_set(err, MIMAS_EIO, "out of memory");
                break;
            }
            ids[nb + na++] = next[m]->id;
            track_extend(t, next[m], &q->p[m], NULL, profiles ? &profiles[m * t->nprof] : NULL);
            cm += q->p[m].centre * q->p[m].mass;
            mass += q->p[m].mass;
        }
        int kind = na == 1 ? MIMAS_EVENT_MERGE : nb == 1 ? MIMAS_EVENT_SPLIT : MIMAS_EVENT_REGROUP;
        if (!rc)
            rc = add_event(t, kind, time, mass > 0 ? cm / mass : NAN, ids, nb, na, err);
    }
    /* the tracks of the previous frame not carried on end here */
    for (size_t i = 0; i < np; i++) {
        if (t->prev_track[i] && !rc)
            rc = track_close(t, t->prev_track[i], err);
        else if (t->prev_track[i])
            track_free(t->prev_track[i]);
        t->prev_track[i] = NULL;
    }
    t->nprev = 0;
    if (rc) {
        for (size_t j = 0; j < nq; j++)
            track_free(next[j]);
        goto done;
    }
    /* this frame becomes the previous one */
    if (nq > t->cap_prev) {
        mimas_plug *p = realloc(t->prev, nq * sizeof *p);
        if (p)
            t->prev = p;
        track **k = p ? realloc(t->prev_track, nq * sizeof *k) : NULL;
        if (k)
            t->prev_track = k;
        if (!p || !k) {
            for (size_t j = 0; j < nq; j++)
                track_free(next[j]);
            rc = mimas_error_set(err, MIMAS_EIO, "out of memory");
            goto done;
        }
        t->cap_prev = nq;
    }
    for (size_t j = 0; j < nq; j++) {
        q->p[j].track = next[j]->id;
        t->prev[j] = q->p[j];
        t->prev_track[j] = next[j];
    }
    t->nprev = nq;
done:
    free(parent);
    free(np_of);
    free(nq_of);
    free(next);
    free(ids);
    return rc;
}

int mimas_tracker_finish(mimas_tracker *t, mimas_error *err)
{
    int rc = MIMAS_OK;
    for (size_t i = 0; i < t->nprev; i++) {
        if (!rc)
            rc = track_close(t, t->prev_track[i], err);
        else
            track_free(t->prev_track[i]);
        t->prev_track[i] = NULL;
    }
    t->nprev = 0;
    return rc;
}

static int by_id(const void *a, const void *b)
{
    long x = ((const mimas_track_row *)a)->track, y = ((const mimas_track_row *)b)->track;
    return (x > y) - (x < y);
}

size_t mimas_tracker_ntracks(const mimas_tracker *t)
{
    return t->nrows;
}

const mimas_track_row *mimas_tracker_track(const mimas_tracker *t, size_t k)
{
    if (!t->sorted) {
        mimas_tracker *w = (mimas_tracker *)t;
        qsort(w->rows, w->nrows, sizeof *w->rows, by_id);
        w->sorted = 1;
    }
    return &t->rows[k];
}

size_t mimas_tracker_nevents(const mimas_tracker *t)
{
    return t->nevents;
}

const mimas_event *mimas_tracker_event(const mimas_tracker *t, size_t k)
{
    return &t->events[k];
}

void mimas_tracker_profile(const mimas_tracker *t, size_t b, int f, double *mean, double *sem,
                           size_t *n)
{
    mimas_sample_mean_get(&t->profile[b * MIMAS_AX_NFIELDS + (size_t)f], mean, sem, n);
}

void mimas_tracker_stat(const mimas_tracker *t, size_t w, int q, double *mean, double *sem,
                        size_t *n)
{
    mimas_sample_mean_get(&t->stats[w * MIMAS_ST_N + (size_t)q], mean, sem, n);
}

void mimas_tracker_passages(const mimas_tracker *t, size_t w, long *passages, double *rate,
                            double *err)
{
    double span = mimas_tracker_span(t);
    *passages = t->passages[w];
    *rate = span > 0 ? (double)t->passages[w] / span : NAN;
    *err = span > 0 ? sqrt(fabs((double)t->passages[w])) / span : NAN;
}

double mimas_tracker_span(const mimas_tracker *t)
{
    return t->frames > 1 ? t->last_time - t->first_time : 0.0;
}

size_t mimas_tracker_frames(const mimas_tracker *t)
{
    return t->frames;
}
