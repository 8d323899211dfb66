/* LAMMPS/LIGGGHTS text dumps of frames.  Each of the (up to) three files is
 * written under a temporary name through one text sink, plain or gzip, a
 * line at a time. */
#include <config.h>

#include "lammps_write.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include <zlib.h>

typedef struct dump_file {
    char path[4096], tmp[4200];
    FILE *fp;
    gzFile gz;
    int open;
} dump_file;

struct mimas_dump_writer {
    dump_file file[3];     /* particles, contacts, wall contacts */
    size_t frames;
    char *line;            /* the line being built */
    size_t len, cap;
    int failed;            /* out of memory while building a line */
};

static int ends_with(const char *s, const char *suffix)
{
    size_t n = strlen(s), m = strlen(suffix);
    return n >= m && !strcmp(s + n - m, suffix);
}

void mimas_dump_local_path(const char *path, int walls, char *out, size_t len)
{
    const char *tag = walls ? ".walls" : ".pairs";
    const char *dot = strstr(path, ".dump");
    while (dot && strstr(dot + 1, ".dump"))
        dot = strstr(dot + 1, ".dump");
    if (dot)
        snprintf(out, len, "%.*s%s%s", (int)(dot - path), path, tag, dot);
    else
        snprintf(out, len, "%s%s", path, tag);
}

static int file_open(dump_file *df, const char *path, mimas_error *err)
{
    snprintf(df->path, sizeof df->path, "%s", path);
    snprintf(df->tmp, sizeof df->tmp, "%s.tmp%ld", path, (long)getpid());
    if (ends_with(path, ".gz"))
        df->gz = gzopen(df->tmp, "wb6");
    else
        df->fp = fopen(df->tmp, "w");
    if (!df->gz && !df->fp)
        return mimas_error_set(err, MIMAS_EIO, "%s: cannot write: %s", path, strerror(errno));
    df->open = 1;
    return MIMAS_OK;
}

/* Closes the file; with keep, renames it into place (0 on success). */
static int file_close(dump_file *df, int keep)
{
    if (!df->open)
        return 0;
    int bad = df->gz ? gzclose(df->gz) != Z_OK : (ferror(df->fp) != 0) | (fclose(df->fp) != 0);
    df->open = 0;
    df->gz = NULL;
    df->fp = NULL;
    if (keep && !bad && rename(df->tmp, df->path) == 0)
        return 0;
    remove(df->tmp);
    return keep ? -1 : 0;
}

static int file_write(dump_file *df, const char *s, size_t n)
{
    if (df->gz)
        return gzwrite(df->gz, s, (unsigned)n) == (int)n ? 0 : -1;
    return fwrite(s, 1, n, df->fp) == n ? 0 : -1;
}

/* ---- building lines ---- */

static void add(mimas_dump_writer *w, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static void add(mimas_dump_writer *w, const char *fmt, ...)
{
    for (;;) {
        va_list ap;
        va_start(ap, fmt);
        size_t room = w->cap - w->len;
        int n = w->line ? vsnprintf(w->line + w->len, room, fmt, ap) : -1;
        va_end(ap);
        if (n >= 0 && (size_t)n < room) {
            w->len += (size_t)n;
            return;
        }
        size_t cap = w->cap ? 2 * w->cap : 4096;
        while (n >= 0 && cap < w->len + (size_t)n + 1)
            cap *= 2;
        char *grown = realloc(w->line, cap);
        if (!grown) {
            w->failed = 1;
            w->len = 0;
            return;
        }
        w->line = grown;
        w->cap = cap;
    }
}

/* 17 significant digits: every double reads back as itself */
static void add_double(mimas_dump_writer *w, double v)
{
    add(w, " %.17g", v);
}

static int flush_line(mimas_dump_writer *w, dump_file *df, mimas_error *err)
{
    add(w, "\n");
    if (w->failed)
        return mimas_error_set(err, MIMAS_EIO, "out of memory");
    int rc = file_write(df, w->line, w->len);
    w->len = 0;
    return rc ? mimas_error_set(err, MIMAS_EIO, "%s: cannot write", df->path) : MIMAS_OK;
}

/* ---- headers ---- */

static int header(mimas_dump_writer *w, dump_file *df, const mimas_frame *f, const char *count,
                  size_t n, mimas_error *err)
{
    /* LAMMPS writes the time first (dump_modify time yes) */
    if (isfinite(f->time))
        add(w, "ITEM: TIME\n%.17g\n", f->time);
    add(w, "ITEM: TIMESTEP\n%lld\nITEM: NUMBER OF %s\n%zu\n", (long long)f->step, count, n);
    const mimas_box *b = &f->box;
    int tilted = mimas_box_is_triclinic(b);
    add(w, "ITEM: BOX BOUNDS%s", tilted ? " xy xz yz" : "");
    for (int d = 0; d < 3; d++)
        add(w, " %s", b->periodic[d] ? "pp" : "ff");
    add(w, "\n");
    /* tilted boxes: the bounding box, as LAMMPS' dump documentation says */
    double lo[3] = {b->lo[0], b->lo[1], b->lo[2]}, hi[3] = {b->hi[0], b->hi[1], b->hi[2]};
    if (tilted) {
        lo[0] += fmin(fmin(0.0, b->xy), fmin(b->xz, b->xy + b->xz));
        hi[0] += fmax(fmax(0.0, b->xy), fmax(b->xz, b->xy + b->xz));
        lo[1] += fmin(0.0, b->yz);
        hi[1] += fmax(0.0, b->yz);
    }
    const double tilt[3] = {b->xy, b->xz, b->yz};
    for (int d = 0; d < 3; d++) {
        add(w, "%.17g %.17g", lo[d], hi[d]);
        if (tilted)
            add_double(w, tilt[d]);
        add(w, "\n");
    }
    w->len--; /* flush_line adds the last newline */
    return flush_line(w, df, err);
}

/* The names of extra columns: NAME, or NAME[1] .. NAME[k]. */
static void extra_names(mimas_dump_writer *w, const mimas_extra *x, size_t n)
{
    for (size_t e = 0; e < n; e++) {
        if (x[e].ncomp == 1)
            add(w, " %s", x[e].name);
        else
            for (int c = 1; c <= x[e].ncomp; c++)
                add(w, " %s[%d]", x[e].name, c);
    }
}

static void extra_values(mimas_dump_writer *w, const mimas_extra *x, size_t n, size_t row)
{
    for (size_t e = 0; e < n; e++)
        for (int c = 0; c < x[e].ncomp; c++)
            add_double(w, x[e].data[row * (size_t)x[e].ncomp + (size_t)c]);
}

static void add_vec(mimas_dump_writer *w, const double *v)
{
    for (int d = 0; d < 3; d++)
        add_double(w, v[d]);
}

/* ---- particles ---- */

static int write_particles(mimas_dump_writer *w, const mimas_frame *f, mimas_error *err)
{
    const mimas_particles *p = &f->particles;
    dump_file *df = &w->file[0];
    int rc = header(w, df, f, "ATOMS", p->n, err);
    if (rc)
        return rc;
    unsigned has = p->present;
    add(w, "ITEM: ATOMS id");
    if (has & MIMAS_P_TYPE)
        add(w, " type");
    add(w, " x y z");
    if (has & MIMAS_P_IMAGE)
        add(w, " ix iy iz");
    if (has & MIMAS_P_VEL)
        add(w, " vx vy vz");
    if (has & MIMAS_P_OMEGA)
        add(w, " omegax omegay omegaz");
    if (has & MIMAS_P_FORCE)
        add(w, " fx fy fz");
    if (has & MIMAS_P_RADIUS)
        add(w, " radius");
    if (has & MIMAS_P_MASS)
        add(w, " mass");
    if (has & MIMAS_P_CG)
        add(w, " coarse_grain_factor");
    if (has & MIMAS_P_LIQUID)
        add(w, " liquid_volume");
    extra_names(w, p->extra, p->n_extra);
    rc = flush_line(w, df, err);
    for (size_t k = 0; !rc && k < p->n; k++) {
        add(w, "%lld", (long long)p->id[k]);
        if (has & MIMAS_P_TYPE)
            add(w, " %d", (int)p->type[k]);
        add_vec(w, p->pos[k]);
        if (has & MIMAS_P_IMAGE)
            add(w, " %d %d %d", (int)p->image[k][0], (int)p->image[k][1], (int)p->image[k][2]);
        if (has & MIMAS_P_VEL)
            add_vec(w, p->vel[k]);
        if (has & MIMAS_P_OMEGA)
            add_vec(w, p->omega[k]);
        if (has & MIMAS_P_FORCE)
            add_vec(w, p->force[k]);
        if (has & MIMAS_P_RADIUS)
            add_double(w, p->radius[k]);
        if (has & MIMAS_P_MASS)
            add_double(w, p->mass[k]);
        if (has & MIMAS_P_CG)
            add_double(w, p->cg[k]);
        if (has & MIMAS_P_LIQUID)
            add_double(w, p->liquid[k]);
        extra_values(w, p->extra, p->n_extra, k);
        rc = flush_line(w, df, err);
    }
    return rc;
}

/* ---- contacts and wall contacts (named local columns, docs/readers.md) ---- */

typedef struct local_view {
    size_t n;
    unsigned present, bit_force, bit_fn, bit_ft, bit_point, bit_overlap;
    double (*force)[3], (*force_n)[3], (*force_t)[3], (*point)[3];
    double *overlap;
    size_t n_extra;
    const mimas_extra *extra;
} local_view;

static int write_local(mimas_dump_writer *w, int walls, const mimas_frame *f, mimas_error *err)
{
    const mimas_contacts *c = &f->contacts;
    const mimas_wall_contacts *wc = &f->walls;
    local_view v = walls ? (local_view){wc->n, wc->present, MIMAS_W_FORCE, MIMAS_W_FORCE_N,
                                        MIMAS_W_FORCE_T, MIMAS_W_POINT, MIMAS_W_OVERLAP,
                                        wc->force, wc->force_n, wc->force_t, wc->point,
                                        wc->overlap, wc->n_extra, wc->extra}
                         : (local_view){c->n, c->present, MIMAS_C_FORCE, MIMAS_C_FORCE_N,
                                        MIMAS_C_FORCE_T, MIMAS_C_POINT, MIMAS_C_OVERLAP,
                                        c->force, c->force_n, c->force_t, c->point,
                                        c->overlap, c->n_extra, c->extra};
    dump_file *df = &w->file[walls ? 2 : 1];
    if (!df->open) {
        char path[4200];
        mimas_dump_local_path(w->file[0].path, walls, path, sizeof path);
        int rc = file_open(df, path, err);
        if (rc)
            return rc;
    }
    int rc = header(w, df, f, "ENTRIES", v.n, err);
    if (rc)
        return rc;
    add(w, "ITEM: ENTRIES id1 %s", walls ? "wall" : "id2");
    if (v.present & v.bit_force)
        add(w, " fx fy fz");
    if (v.present & v.bit_fn)
        add(w, " fnx fny fnz");
    if (v.present & v.bit_ft)
        add(w, " ftx fty ftz");
    if (v.present & v.bit_point)
        add(w, " cpx cpy cpz");
    if (v.present & v.bit_overlap)
        add(w, " delta");
    extra_names(w, v.extra, v.n_extra);
    rc = flush_line(w, df, err);
    const mimas_particles *p = &f->particles;
    for (size_t k = 0; !rc && k < v.n; k++) {
        size_t i = walls ? wc->particle[k] : c->i[k];
        size_t j = walls ? 0 : c->j[k];
        if (i >= p->n || j >= p->n)
            return mimas_error_set(err, MIMAS_EDATA, "%s row %zu refers to particle %zu of a "
                                   "frame of %zu", walls ? "wall contacts" : "contacts", k,
                                   i >= p->n ? i : j, p->n);
        if (walls)
            add(w, "%lld %d", (long long)p->id[i], (int)wc->wall[k]);
        else
            add(w, "%lld %lld", (long long)p->id[i], (long long)p->id[j]);
        if (v.present & v.bit_force)
            add_vec(w, v.force[k]);
        if (v.present & v.bit_fn)
            add_vec(w, v.force_n[k]);
        if (v.present & v.bit_ft)
            add_vec(w, v.force_t[k]);
        if (v.present & v.bit_point)
            add_vec(w, v.point[k]);
        if (v.present & v.bit_overlap)
            add_double(w, v.overlap[k]);
        extra_values(w, v.extra, v.n_extra, k);
        rc = flush_line(w, df, err);
    }
    return rc;
}

/* ---- the writer ---- */

int mimas_dump_open(mimas_dump_writer **out, const char *path, mimas_error *err)
{
    *out = NULL;
    mimas_dump_writer *w = calloc(1, sizeof *w);
    if (!w)
        return mimas_error_set(err, MIMAS_EIO, "out of memory");
    int rc = file_open(&w->file[0], path, err);
    if (rc) {
        free(w);
        return rc;
    }
    *out = w;
    return MIMAS_OK;
}

size_t mimas_dump_frames(const mimas_dump_writer *w)
{
    return w->frames;
}

int mimas_dump_append(mimas_dump_writer *w, const mimas_frame *f, mimas_error *err)
{
    int rc = write_particles(w, f, err);
    if (!rc && f->has_contacts)
        rc = write_local(w, 0, f, err);
    if (!rc && f->has_walls)
        rc = write_local(w, 1, f, err);
    if (!rc)
        w->frames++;
    else if (rc != MIMAS_EIO)
        mimas_error_prefix(err, "%s: frame %zu (step %lld)", w->file[0].path, w->frames,
                           (long long)f->step);
    return rc;
}

int mimas_dump_close(mimas_dump_writer *w, int wrote_local[2], mimas_error *err)
{
    int rc = MIMAS_OK;
    for (int k = 0; k < 3; k++) {
        int opened = w->file[k].open;
        if (k > 0 && wrote_local)
            wrote_local[k - 1] = opened;
        if (file_close(&w->file[k], rc == MIMAS_OK) && !rc)
            rc = mimas_error_set(err, MIMAS_EIO, "%s: cannot write", w->file[k].path);
    }
    if (rc) /* none of the files stays */
        for (int k = 0; k < 3; k++)
            if (w->file[k].path[0])
                remove(w->file[k].path);
    free(w->line);
    free(w);
    return rc;
}

void mimas_dump_abort(mimas_dump_writer *w)
{
    if (!w)
        return;
    for (int k = 0; k < 3; k++)
        file_close(&w->file[k], 0);
    free(w->line);
    free(w);
}
