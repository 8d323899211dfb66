#include <config.h>

#include "frame_pack.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#define PACK_MAGIC 0x6d696d61734652ULL /* "mimasFR" */

void mimas_bytes_free(mimas_bytes *b)
{
    free(b->data);
    memset(b, 0, sizeof *b);
}

static int put(mimas_bytes *b, const void *p, size_t n, mimas_error *err)
{
    if (n > SIZE_MAX - b->n)
        return mimas_error_set(err, MIMAS_EIO, "frame too large to pack");
    if (b->n + n > b->cap) {
        size_t cap = b->cap ? b->cap : 4096;
        while (cap < b->n + n)
            cap = cap > SIZE_MAX / 2 ? b->n + n : 2 * cap;
        unsigned char *q = realloc(b->data, cap);
        if (!q)
            return mimas_error_set(err, MIMAS_EIO, "out of memory packing a frame (%zu bytes)",
                                   cap);
        b->data = q;
        b->cap = cap;
    }
    if (n)
        memcpy(b->data + b->n, p, n);
    b->n += n;
    return MIMAS_OK;
}

static int put_size(mimas_bytes *b, size_t v, mimas_error *err)
{
    uint64_t u = v;
    return put(b, &u, sizeof u, err);
}

static int pack_table(const void *tab, const mimas_table_desc *d, mimas_bytes *b,
                      mimas_error *err)
{
    size_t n = mimas_table_n(tab, d);
    unsigned present = mimas_table_present(tab, d);
    int rc = put_size(b, n, err) || put_size(b, present, err);
    for (size_t c = 0; !rc && c < d->ncolumns; c++)
        if (present & d->columns[c].bit)
            rc = put(b, mimas_table_column(tab, d, c),
                     n * mimas_elem_size(d->columns[c].type) * (size_t)d->columns[c].ncomp, err);
    size_t n_extra = *(const size_t *)((const char *)tab + d->off_n_extra);
    const mimas_extra *x = *(mimas_extra *const *)((const char *)tab + d->off_extra);
    if (!rc)
        rc = put_size(b, n_extra, err);
    for (size_t e = 0; !rc && e < n_extra; e++) {
        size_t len = strlen(x[e].name);
        rc = put_size(b, len, err) || put(b, x[e].name, len, err) ||
             put_size(b, (size_t)x[e].ncomp, err) || put(b, x[e].unit, sizeof x[e].unit, err) ||
             put(b, x[e].data, n * (size_t)x[e].ncomp * sizeof(double), err);
    }
    return rc;
}

int mimas_frame_pack(const mimas_frame *f, mimas_bytes *b, mimas_error *err)
{
    b->n = 0;
    uint64_t magic = PACK_MAGIC;
    int32_t flags[2] = {f->has_contacts, f->has_walls};
    int rc = put(b, &magic, sizeof magic, err) || put(b, &f->step, sizeof f->step, err) ||
             put(b, &f->time, sizeof f->time, err) || put(b, &f->box, sizeof f->box, err) ||
             put(b, flags, sizeof flags, err) || put(b, &f->tube, sizeof f->tube, err);
    if (!rc)
        rc = pack_table(&f->particles, &mimas_particles_desc, b, err) ||
             pack_table(&f->contacts, &mimas_contacts_desc, b, err) ||
             pack_table(&f->walls, &mimas_walls_desc, b, err);
    size_t cells = mimas_gas_cells(&f->gas);
    if (!rc)
        rc = put_size(b, cells ? f->gas.cells[0] : 0, err) ||
             put_size(b, cells ? f->gas.cells[1] : 0, err) ||
             put_size(b, cells ? f->gas.cells[2] : 0, err);
    if (!rc && cells)
        rc = put(b, f->gas.origin, sizeof f->gas.origin, err) ||
             put(b, f->gas.spacing, sizeof f->gas.spacing, err) ||
             put(b, f->gas.pressure, cells * sizeof(double), err) ||
             put(b, f->gas.porosity, cells * sizeof(double), err) ||
             put(b, f->gas.velocity, cells * 3 * sizeof(double), err);
    return rc ? (err ? err->code : MIMAS_EIO) : MIMAS_OK;
}

/* ---- reading back ---- */
typedef struct cursor {
    const unsigned char *p;
    size_t left;
} cursor;

static int get(cursor *c, void *out, size_t n, mimas_error *err)
{
    if (n > c->left)
        return mimas_error_set(err, MIMAS_EDATA, "packed frame is truncated");
    if (n)
        memcpy(out, c->p, n);
    c->p += n;
    c->left -= n;
    return MIMAS_OK;
}

static int get_size(cursor *c, size_t *v, size_t max, mimas_error *err)
{
    uint64_t u = 0;
    int rc = get(c, &u, sizeof u, err);
    if (!rc && u > max)
        return mimas_error_set(err, MIMAS_EDATA, "packed frame has a count of %llu",
                               (unsigned long long)u);
    if (!rc)
        *v = (size_t)u;
    return rc;
}

static int unpack_table(void *tab, const mimas_table_desc *d, cursor *c, mimas_error *err)
{
    size_t n = 0, present = 0;
    int rc = get_size(c, &n, c->left, err) || get_size(c, &present, UINT32_MAX, err);
    unsigned known = 0;
    for (size_t k = 0; k < d->ncolumns; k++)
        known |= d->columns[k].bit;
    if (!rc && (((unsigned)present & ~known) || ((unsigned)present & d->required) != d->required))
        rc = mimas_error_set(err, MIMAS_EDATA, "packed frame: bad %s columns", d->name);
    if (!rc) {
        mimas_table_keep_only(tab, d, (unsigned)present);
        mimas_table_drop_extras(tab, d);
        rc = mimas_table_set_present(tab, d, (unsigned)present, err) ||
             mimas_table_resize(tab, d, n, err);
    }
    for (size_t k = 0; !rc && k < d->ncolumns; k++)
        if (present & d->columns[k].bit) {
            size_t row = mimas_elem_size(d->columns[k].type) * (size_t)d->columns[k].ncomp;
            if (n && row > c->left / n)
                return mimas_error_set(err, MIMAS_EDATA, "packed frame is truncated");
            rc = get(c, mimas_table_column(tab, d, k), n * row, err);
        }
    size_t n_extra = 0;
    if (!rc)
        rc = get_size(c, &n_extra, c->left, err);
    for (size_t e = 0; !rc && e < n_extra; e++) {
        size_t len = 0, ncomp = 0, index = 0;
        char name[256];
        rc = get_size(c, &len, sizeof name - 1, err) || get(c, name, len, err) ||
             get_size(c, &ncomp, 64, err);
        if (rc)
            break;
        name[len] = '\0';
        rc = mimas_table_add_extra(tab, d, name, (int)ncomp, &index, err);
        mimas_extra *x = *(mimas_extra **)((char *)tab + d->off_extra);
        if (!rc)
            rc = get(c, x[index].unit, sizeof x[index].unit, err);
        if (!rc) {
            x[index].unit[sizeof x[index].unit - 1] = '\0';
            if (n && ncomp * sizeof(double) > c->left / n)
                return mimas_error_set(err, MIMAS_EDATA, "packed frame is truncated");
            rc = get(c, x[index].data, n * ncomp * sizeof(double), err);
        }
    }
    return rc;
}

int mimas_frame_unpack(mimas_frame *f, const unsigned char *data, size_t n, mimas_error *err)
{
    cursor c = {data, n};
    uint64_t magic = 0;
    int32_t flags[2];
    int rc = get(&c, &magic, sizeof magic, err);
    if (!rc && magic != PACK_MAGIC)
        return mimas_error_set(err, MIMAS_EDATA, "not a packed frame");
    mimas_frame_clear(f);
    if (!rc)
        rc = get(&c, &f->step, sizeof f->step, err) || get(&c, &f->time, sizeof f->time, err) ||
             get(&c, &f->box, sizeof f->box, err) || get(&c, flags, sizeof flags, err) ||
             get(&c, &f->tube, sizeof f->tube, err);
    if (!rc) {
        f->has_contacts = flags[0];
        f->has_walls = flags[1];
        rc = unpack_table(&f->particles, &mimas_particles_desc, &c, err) ||
             unpack_table(&f->contacts, &mimas_contacts_desc, &c, err) ||
             unpack_table(&f->walls, &mimas_walls_desc, &c, err);
    }
    size_t cells[3] = {0, 0, 0};
    if (!rc)
        rc = get_size(&c, &cells[0], c.left, err) || get_size(&c, &cells[1], c.left, err) ||
             get_size(&c, &cells[2], c.left, err);
    if (!rc && cells[0]) {
        rc = mimas_gas_resize(&f->gas, cells[0], cells[1], cells[2], err);
        size_t m = mimas_gas_cells(&f->gas);
        if (!rc && m > c.left / (5 * sizeof(double)))
            return mimas_error_set(err, MIMAS_EDATA, "packed frame is truncated");
        if (!rc)
            rc = get(&c, f->gas.origin, sizeof f->gas.origin, err) ||
                 get(&c, f->gas.spacing, sizeof f->gas.spacing, err) ||
                 get(&c, f->gas.pressure, m * sizeof(double), err) ||
                 get(&c, f->gas.porosity, m * sizeof(double), err) ||
                 get(&c, f->gas.velocity, m * 3 * sizeof(double), err);
    }
    if (!rc && c.left)
        rc = mimas_error_set(err, MIMAS_EDATA, "packed frame has %zu bytes too many", c.left);
    return rc ? (err ? err->code : MIMAS_EDATA) : MIMAS_OK;
}
