/* The LAMMPS/LIGGGHTS backend: a per-atom dump series, optionally joined
 * with local dumps of contacts and wall contacts at the same timesteps. */
#include <config.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "backend.h"
#include "id_index.h"
#include "lammps_atoms.h"
#include "lammps_local.h"

typedef struct local_stream {
    int on;
    dump_series s;
    local_layout layout;
    int pending; /* a header was read whose rows are not consumed */
    const char *what;
} local_stream;

typedef struct lammps_state {
    mimas_reader_options opt;
    dump_series atoms;
    atom_layout alayout;
    local_stream contacts, walls;
    mimas_id_index index;
    size_t skipped;
    int ahead;   /* the next complete snapshot's headers are read, its rows are not */
} lammps_state;

static int probe(const char *path, const char *head, size_t n)
{
    (void)path;
    /* a dump starts with one of its items (TIMESTEP, or UNITS/TIME first) */
    return n >= 11 && strncmp(head, "ITEM: ", 6) == 0;
}

static void close_state(void *state)
{
    lammps_state *st = state;
    if (!st)
        return;
    dump_series_close(&st->atoms);
    atom_layout_free(&st->alayout);
    local_stream *ls[2] = {&st->contacts, &st->walls};
    for (int k = 0; k < 2; k++)
        if (ls[k]->on) {
            dump_series_close(&ls[k]->s);
            local_layout_free(&ls[k]->layout);
        }
    mimas_id_index_free(&st->index);
    free(st);
}

static int open_local(local_stream *ls, const char *const *files, size_t n, const char *keywords,
                      int walls, void (*notify)(void *, const char *), void *notify_ctx,
                      mimas_error *err)
{
    if (n == 0)
        return MIMAS_OK;
    char **names;
    size_t count;
    int rc = reader_expand_names(files, n, &names, &count, err);
    if (rc)
        return rc;
    ls->on = 1;
    ls->what = walls ? "wall-contact" : "contact";
    ls->layout.keywords = keywords;
    ls->layout.walls = walls;
    ls->layout.notify = notify;
    ls->layout.notify_ctx = notify_ctx;
    return dump_series_open(&ls->s, names, count, err);
}

static int open_state(void **state, const char *const *inputs, size_t ninputs,
                      const mimas_reader_options *o, mimas_error *err)
{
    lammps_state *st = calloc(1, sizeof *st);
    if (!st)
        return mimas_error_set(err, MIMAS_EIO, "out of memory for the dump reader");
    st->opt = *o;
    mimas_id_index_init(&st->index);
    char **names;
    size_t count;
    int rc = reader_expand_names(inputs, ninputs, &names, &count, err);
    if (!rc)
        rc = dump_series_open(&st->atoms, names, count, err);
    if (!rc)
        rc = open_local(&st->contacts, o->contacts, o->ncontacts, o->contact_columns, 0,
                        o->notify, o->notify_ctx, err);
    if (!rc)
        rc = open_local(&st->walls, o->walls, o->nwalls, o->wall_columns, 1, o->notify,
                        o->notify_ctx, err);
    if (rc) {
        close_state(st);
        return rc;
    }
    *state = st;
    return MIMAS_OK;
}

/* Brings the local stream to timestep `step`: *found = 1 if its snapshot is
 * there (rows not yet read), 0 if the stream has none for it. */
static int sync_local(lammps_state *st, local_stream *ls, int64_t step, const char *atoms_path,
                      int *found, mimas_error *err)
{
    *found = 0;
    for (;;) {
        if (!ls->pending) {
            int rc = dump_series_header(&ls->s, err);
            if (rc == MIMAS_END) {
                if (st->opt.allow_missing_contacts)
                    return MIMAS_OK;
                return mimas_error_set(err, MIMAS_EDATA, "%s: timestep %lld has no %s snapshot "
                                       "(the %s dumps end before it)", atoms_path,
                                       (long long)step, ls->what, ls->what);
            }
            if (rc)
                return rc;
            ls->pending = 1;
        }
        if (ls->s.h.step == step) {
            *found = 1;
            return MIMAS_OK;
        }
        if (ls->s.h.step > step) {
            if (st->opt.allow_missing_contacts)
                return MIMAS_OK;
            return mimas_error_set(err, MIMAS_EDATA, "%s: timestep %lld has no %s snapshot in "
                                   "%s (next there: %lld)", atoms_path, (long long)step,
                                   ls->what, ls->s.in.path, (long long)ls->s.h.step);
        }
        /* a local snapshot without atoms */
        if (!st->opt.allow_missing_contacts)
            return text_error(&ls->s.in, err, "%s timestep %lld has no per-atom snapshot",
                              ls->what, (long long)ls->s.h.step);
        int rc = local_skip(&ls->s, err);
        if (rc)
            return rc;
        ls->pending = 0;
    }
}

/* After the last atom snapshot, a local stream must have nothing left. */
static int check_drained(lammps_state *st, local_stream *ls, mimas_error *err)
{
    if (!ls->on || st->opt.allow_missing_contacts)
        return MIMAS_OK;
    int rc = ls->pending ? MIMAS_OK : dump_series_header(&ls->s, err);
    if (rc == MIMAS_END)
        return MIMAS_OK;
    if (rc)
        return rc;
    ls->pending = 1;
    return text_error(&ls->s.in, err, "%s timestep %lld has no per-atom snapshot", ls->what,
                      (long long)ls->s.h.step);
}

/* Reads the headers of the next snapshot whose contact data are complete
 * (the atoms' and, at its timestep, the local dumps'), not its rows:
 * MIMAS_OK with st->ahead set, MIMAS_END, or an error. */
static int read_ahead(lammps_state *st, mimas_error *err)
{
    while (!st->ahead) {
        int rc = dump_series_header(&st->atoms, err);
        if (rc == MIMAS_END) {
            rc = check_drained(st, &st->contacts, err);
            if (!rc)
                rc = check_drained(st, &st->walls, err);
            return rc ? rc : MIMAS_END;
        }
        if (rc)
            return rc;
        if (st->atoms.h.entries)
            return text_error(&st->atoms.in, err, "a local dump (ITEM: ENTRIES) given as the "
                              "particle input; contacts go with --contacts");
        int64_t step = st->atoms.h.step;
        int complete = 1;
        local_stream *ls[2] = {&st->contacts, &st->walls};
        for (int k = 0; k < 2 && complete; k++) {
            if (!ls[k]->on)
                continue;
            int found;
            rc = sync_local(st, ls[k], step, st->atoms.in.path, &found, err);
            if (rc)
                return rc;
            if (!found)
                complete = 0;
            else if (!ls[k]->s.h.entries)
                return text_error(&ls[k]->s.in, err, "a per-atom dump given as %s data",
                                  ls[k]->what);
        }
        if (complete) {
            st->ahead = 1;
            break;
        }
        /* incomplete (only with allow_missing_contacts): pass over its atoms */
        rc = local_skip(&st->atoms, err);
        if (rc)
            return rc;
        st->skipped++;
    }
    return MIMAS_OK;
}

static int next(void *state, mimas_frame *f, mimas_error *err)
{
    lammps_state *st = state;
    int rc = read_ahead(st, err);
    if (rc)
        return rc;
    st->ahead = 0;
    f->has_contacts = f->has_walls = 0;
    rc = atoms_read(&st->atoms, &st->alayout, f, st->opt.density, st->opt.timestep, &st->index,
                    err);
    if (rc)
        return rc;
    local_stream *ls[2] = {&st->contacts, &st->walls};
    for (int k = 0; k < 2; k++) {
        if (!ls[k]->on)
            continue;
        rc = local_read(&ls[k]->s, &ls[k]->layout, f, &st->index, err);
        ls[k]->pending = 0;
        if (rc)
            return rc;
    }
    return MIMAS_OK;
}

/* The next snapshot's step and time from its header alone. */
static int peek(void *state, int64_t *step, double *time, mimas_error *err)
{
    lammps_state *st = state;
    int rc = read_ahead(st, err);
    if (rc)
        return rc;
    const dump_header *h = &st->atoms.h;
    *step = h->step;
    *time = h->has_time ? h->time
                        : (st->opt.timestep > 0 ? (double)h->step * st->opt.timestep : NAN);
    return MIMAS_OK;
}

/* Passes over the next snapshot's rows without parsing them. */
static int skip(void *state, mimas_error *err)
{
    lammps_state *st = state;
    int rc = read_ahead(st, err);
    if (rc)
        return rc;
    st->ahead = 0;
    rc = local_skip(&st->atoms, err);
    local_stream *ls[2] = {&st->contacts, &st->walls};
    for (int k = 0; k < 2 && !rc; k++) {
        if (!ls[k]->on)
            continue;
        rc = local_skip(&ls[k]->s, err);
        ls[k]->pending = 0;
    }
    return rc;
}

static size_t skipped(void *state)
{
    return ((lammps_state *)state)->skipped;
}

static const char *source(void *state)
{
    const lammps_state *st = state;
    return st->atoms.paths[st->atoms.cur < st->atoms.npaths ? st->atoms.cur : st->atoms.npaths - 1];
}

const reader_backend reader_lammps = {"lammps", "LAMMPS/LIGGGHTS text dump", probe, open_state,
                                      next, skipped, close_state, source, peek, skip, NULL,
                                      NULL};
