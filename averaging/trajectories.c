#include <config.h>

#include "trajectories.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "id_index.h"

/* frame intervals may differ by this fraction of the first one */
#define INTERVAL_TOLERANCE 1e-6
/* a move of more than this fraction of a periodic edge is ambiguous */
#define QUARTER_BOX 0.25

/* per slot: what unwrapping needs of the frame the particle was last seen in */
typedef struct slot_state {
    double wrapped[3];   /* position as read */
    double unwrapped[3];
    double image[3];     /* whole edge vectors added (integers) */
    size_t frame;        /* frame index */
} slot_state;

struct mimas_trajectories {
    mimas_traj_options opt;
    int32_t *types;
    mimas_traj_store *store;
    size_t ncomp;
    /* slots */
    size_t nslots, cap_ids, cap_state;
    int64_t *ids;
    slot_state *state;
    mimas_id_index index;
    /* frames */
    size_t frames, cap_times, cap_drift, cap_vmean;
    double *times, *drift, *vmean;
    int flags;           /* -1 before the first frame; 1 while image flags are used */
    /* the frame added last */
    size_t cap_slot_of, cap_is_new, cap_new_ids;
    size_t *slot_of;
    unsigned char *is_new;
    int64_t *new_ids;
    mimas_traj_jumps jumps;
};

/* *p to hold at least need elements of size elem (doubling). */
static int reserve(void **p, size_t *cap, size_t need, size_t elem)
{
    if (need <= *cap)
        return 0;
    size_t n = *cap ? *cap : 64;
    while (n < need)
        n *= 2;
    void *q = realloc(*p, n * elem);
    if (!q)
        return -1;
    *p = q;
    *cap = n;
    return 0;
}

int mimas_traj_create(mimas_trajectories **out, const mimas_traj_options *o, mimas_error *err)
{
    *out = NULL;
    mimas_trajectories *t = calloc(1, sizeof *t);
    if (!t)
        return mimas_error_set(err, MIMAS_EIO, "out of memory");
    t->opt = *o;
    t->flags = -1;
    mimas_id_index_init(&t->index);
    if (o->ntypes) {
        t->types = malloc(o->ntypes * sizeof *t->types);
        if (!t->types) {
            free(t);
            return mimas_error_set(err, MIMAS_EIO, "out of memory");
        }
        memcpy(t->types, o->types, o->ntypes * sizeof *t->types);
        t->opt.types = t->types;
    }
    t->ncomp = o->velocities ? 6 : 3;
    mimas_traj_store_options so = {t->ncomp, o->memory, o->scratch_dir};
    int rc = mimas_traj_store_create(&t->store, &so, err);
    if (rc) {
        mimas_traj_free(t);
        return rc;
    }
    *out = t;
    return MIMAS_OK;
}

void mimas_traj_free(mimas_trajectories *t)
{
    if (!t)
        return;
    mimas_traj_store_free(t->store);
    mimas_id_index_free(&t->index);
    free(t->types);
    free(t->ids);
    free(t->state);
    free(t->times);
    free(t->drift);
    free(t->vmean);
    free(t->slot_of);
    free(t->is_new);
    free(t->new_ids);
    free(t);
}

static int selected(const mimas_trajectories *t, const mimas_particles *p, size_t i)
{
    if (!t->opt.ntypes)
        return 1;
    int in = 0;
    for (size_t k = 0; k < t->opt.ntypes && !in; k++)
        in = p->type[i] == t->opt.types[k];
    return t->opt.exclude ? !in : in;
}

/* The frame's time: known, after the previous one, at the first interval. */
static int check_time(mimas_trajectories *t, const mimas_frame *f, mimas_error *err)
{
    double now = f->time;
    if (!isfinite(now))
        return mimas_error_set(err, MIMAS_EDATA, "the frame at step %lld has no time (give "
                               "--timestep for dumps without ITEM: TIME)", (long long)f->step);
    if (t->frames == 0)
        return MIMAS_OK;
    double prev = t->times[t->frames - 1], dt = now - prev;
    if (!(dt > 0))
        return mimas_error_set(err, MIMAS_EDATA, "the frame at time %.10g follows one at time "
                               "%.10g: frames must come in increasing time", now, prev);
    if (t->frames >= 2) {
        double dt0 = t->times[1] - t->times[0];
        if (fabs(dt - dt0) > INTERVAL_TOLERANCE * dt0)
            return mimas_error_set(err, MIMAS_EDATA, "the frame interval changes at time %.10g "
                                   "(%.10g s after the previous frame, the first interval is "
                                   "%.10g s): the MSD by lag needs equally spaced frames; "
                                   "select them with --every K or --from/--to", now, dt, dt0);
    }
    return MIMAS_OK;
}

static int check_quantities(const mimas_trajectories *t, const mimas_particles *p,
                            mimas_error *err)
{
    if (p->n && t->opt.ntypes && !(p->present & MIMAS_P_TYPE))
        return mimas_error_set(err, MIMAS_EMISSING, "the particles have no types: --types and "
                               "--exclude-types need them");
    if (p->n && t->opt.velocities && !(p->present & MIMAS_P_VEL))
        return mimas_error_set(err, MIMAS_EMISSING, "the particles have no velocities: "
                               "--vacf needs them");
    return MIMAS_OK;
}

/* Slots for the ids first seen in this frame, in the order met; fills
 * slot_of and is_new. */
static int assign_slots(mimas_trajectories *t, const mimas_frame *f, mimas_error *err)
{
    const mimas_particles *p = &f->particles;
    size_t n = p->n, nnew = 0;
    if (reserve((void **)&t->slot_of, &t->cap_slot_of, n, sizeof *t->slot_of) ||
        reserve((void **)&t->is_new, &t->cap_is_new, n, sizeof *t->is_new) ||
        reserve((void **)&t->new_ids, &t->cap_new_ids, n, sizeof *t->new_ids))
        return mimas_error_set(err, MIMAS_EIO, "out of memory");
    for (size_t i = 0; i < n; i++) {
        size_t s = SIZE_MAX;
        int known = selected(t, p, i) ? mimas_id_index_find(&t->index, p->id[i], &s) : 1;
        t->slot_of[i] = known ? s : t->nslots + nnew;
        t->is_new[i] = !known;
        if (!known)
            t->new_ids[nnew++] = p->id[i];
    }
    if (!nnew)
        return MIMAS_OK;
    size_t total = t->nslots + nnew;
    if (reserve((void **)&t->ids, &t->cap_ids, total, sizeof *t->ids) ||
        reserve((void **)&t->state, &t->cap_state, total, sizeof *t->state))
        return mimas_error_set(err, MIMAS_EIO, "out of memory");
    memcpy(t->ids + t->nslots, t->new_ids, nnew * sizeof *t->ids);
    int rc = mimas_id_index_build(&t->index, t->ids, total, err);
    if (rc) {
        /* a new id twice in this frame: the index stays that of the known ids */
        mimas_id_index_build(&t->index, t->ids, t->nslots, NULL);
        return mimas_error_prefix(err, "in the frame at time %.10g", f->time);
    }
    for (size_t k = t->nslots; k < total; k++)
        t->state[k].frame = SIZE_MAX;
    t->nslots = total;
    return MIMAS_OK;
}

/* The fraction of the edges a displacement d spans (edge vectors a, b, c:
 * d = f0 a + f1 b + f2 c). */
static void edge_fractions(const mimas_box *b, const double d[3], double f[3])
{
    double L[3] = {b->hi[0] - b->lo[0], b->hi[1] - b->lo[1], b->hi[2] - b->lo[2]};
    f[2] = d[2] / L[2];
    f[1] = (d[1] - f[2] * b->yz) / L[1];
    f[0] = (d[0] - f[1] * b->xy - f[2] * b->xz) / L[0];
}

/* Unwraps particle i of the frame (box edges e) into its slot's state; 1
 * when it was also present in the previous frame (its move is in *move). */
static int unwrap(mimas_trajectories *t, const mimas_frame *f, const double e[3][3], size_t i,
                  size_t s, int first, double move[3])
{
    const mimas_particles *p = &f->particles;
    slot_state *st = &t->state[s];
    if (t->flags == 1) {
        for (int d = 0; d < 3; d++)
            st->image[d] = p->image[i][d];
    } else if (first) {
        st->image[0] = st->image[1] = st->image[2] = 0;
    } else {
        double d[3], k[3], fr[3];
        for (int c = 0; c < 3; c++)
            d[c] = p->pos[i][c] - st->wrapped[c];
        mimas_box_min_image_shift(&f->box, d, k);
        edge_fractions(&f->box, d, fr);
        int far = 0;
        for (int c = 0; c < 3; c++) {
            st->image[c] -= k[c];
            far |= f->box.periodic[c] && fabs(fr[c]) > QUARTER_BOX;
        }
        if (far && !t->jumps.count++) {
            t->jumps.first_id = p->id[i];
            t->jumps.first_time = f->time;
        }
    }
    double u[3];
    for (int c = 0; c < 3; c++)
        u[c] = p->pos[i][c] + st->image[0] * e[0][c] + st->image[1] * e[1][c] +
               st->image[2] * e[2][c];
    int adjacent = !first && st->frame + 1 == t->frames;
    for (int c = 0; c < 3; c++) {
        move[c] = adjacent ? u[c] - st->unwrapped[c] : 0;
        st->unwrapped[c] = u[c];
        st->wrapped[c] = p->pos[i][c];
    }
    return adjacent;
}

static int grow_frames(mimas_trajectories *t, mimas_error *err)
{
    size_t need = t->frames + 1;
    if (reserve((void **)&t->times, &t->cap_times, need, sizeof *t->times) ||
        reserve((void **)&t->drift, &t->cap_drift, need, 3 * sizeof *t->drift) ||
        reserve((void **)&t->vmean, &t->cap_vmean, need, 3 * sizeof *t->vmean))
        return mimas_error_set(err, MIMAS_EIO, "out of memory");
    return MIMAS_OK;
}

int mimas_traj_add(mimas_trajectories *t, const mimas_frame *f, mimas_error *err)
{
    const mimas_particles *p = &f->particles;
    int rc = check_time(t, f, err);
    if (!rc)
        rc = check_quantities(t, p, err);
    if (!rc)
        rc = grow_frames(t, err);
    if (!rc)
        rc = assign_slots(t, f, err);
    if (!rc)
        rc = mimas_traj_store_next_frame(t->store, t->nslots, err);
    if (rc)
        return rc;
    int images = (p->present & MIMAS_P_IMAGE) != 0;
    if (t->flags < 0)
        t->flags = images;
    else if (!images)
        t->flags = 0;
    size_t fr = t->frames;
    double e[3][3];
    mimas_box_edges(&f->box, e);
    double inc[3] = {0, 0, 0}, vsum[3] = {0, 0, 0};
    size_t nmove = 0, nsel = 0;
    for (size_t i = 0; i < p->n; i++) {
        size_t s = t->slot_of[i];
        if (s == SIZE_MAX)
            continue;
        if (t->state[s].frame == fr)
            return mimas_error_set(err, MIMAS_EDATA, "particle id %lld appears twice in the "
                                   "frame at time %.10g", (long long)p->id[i], f->time);
        double move[3];
        nmove += (size_t)unwrap(t, f, e, i, s, t->is_new[i], move);
        t->state[s].frame = fr;
        nsel++;
        double *rec = mimas_traj_store_record(t->store, s);
        for (int c = 0; c < 3; c++) {
            rec[c] = t->state[s].unwrapped[c];
            inc[c] += move[c];
            if (t->opt.velocities) {
                rec[3 + c] = p->vel[i][c];
                vsum[c] += p->vel[i][c];
            }
        }
    }
    t->times[fr] = f->time;
    for (int c = 0; c < 3; c++) {
        double prev = fr ? t->drift[3 * (fr - 1) + c] : 0;
        t->drift[3 * fr + c] = prev + (nmove ? inc[c] / (double)nmove : 0);
        t->vmean[3 * fr + c] = t->opt.velocities && nsel ? vsum[c] / (double)nsel : NAN;
    }
    t->frames++;
    return MIMAS_OK;
}

const size_t *mimas_traj_frame_slots(const mimas_trajectories *t) { return t->slot_of; }
const unsigned char *mimas_traj_frame_new(const mimas_trajectories *t) { return t->is_new; }
int mimas_traj_finish(mimas_trajectories *t, mimas_error *err)
{
    return mimas_traj_store_finish(t->store, err);
}
size_t mimas_traj_frames(const mimas_trajectories *t) { return t->frames; }
size_t mimas_traj_slots(const mimas_trajectories *t) { return t->nslots; }
const int64_t *mimas_traj_ids(const mimas_trajectories *t) { return t->ids; }
const double *mimas_traj_times(const mimas_trajectories *t) { return t->times; }
const double *mimas_traj_drift(const mimas_trajectories *t) { return t->drift; }
const double *mimas_traj_mean_velocity(const mimas_trajectories *t) { return t->vmean; }
const mimas_traj_jumps *mimas_traj_jumps_seen(const mimas_trajectories *t) { return &t->jumps; }
mimas_traj_store *mimas_traj_store_of(mimas_trajectories *t) { return t->store; }

double mimas_traj_interval(const mimas_trajectories *t)
{
    if (t->frames < 2)
        return NAN;
    return (t->times[t->frames - 1] - t->times[0]) / (double)(t->frames - 1);
}
