/* Native format reader (docs/format.md): random access to frame k, reading
 * nothing of the other frames.  The frame count is the number of frames whose
 * every dataset is complete, so a file cut off while a frame was being
 * written shows the frames before it.  Files are opened for SWMR reading, so
 * a file that mimas simulate is still writing yields the frames committed
 * when it was opened. */
#include <config.h>

#include "native.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "h5_direct.h"
#include "h5util.h"
#include "id_index.h"
#include "native_layout.h"
#include "parameters_h5.h"

typedef struct read_flat {
    int present;
    hid_t step, time, offset;
    hsize_t rows;
    size_t ncols;
    native_col *cols;
} read_flat;

struct mimas_native {
    char *path;
    hid_t file;
    size_t frames;
    int triclinic;
    int periodic[3];
    hid_t clock_step, clock_time, count, box_edges, box_lower, box_upper;
    hsize_t nmax;
    size_t npcols;
    native_col *pcols;
    unsigned p_bits;
    read_flat contacts, walls;
    mimas_tube tube;           /* format 1.1, optional */
    int has_gas;
    size_t gas_cells[3];
    double gas_origin[3], gas_spacing[3];
    hid_t gas_ds[3];           /* pressure, porosity, velocity */
    mimas_id_index index;
    int64_t *ids;
    size_t ids_cap;
    h5_direct_scratch direct;  /* the columns' decoding space */
    char creator[96];
    mimas_parameters params;     /* /parameters/scenario */
    size_t nobs;                 /* /observables/all/NAME but particle_count */
    struct native_obs {
        char name[64], unit[24];
        hid_t ds;
    } *obs;
};

/* A data error: "PATH: message". */
static int bad(mimas_native *r, mimas_error *err, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));
static int bad(mimas_native *r, mimas_error *err, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    mimas_error_set(err, MIMAS_EDATA, "%s", "");
    if (err)
        vsnprintf(err->msg, sizeof err->msg, fmt, ap);
    va_end(ap);
    return mimas_error_prefix(err, "%s", r->path);
}

static hid_t open_ds(mimas_native *r, const char *path, int *rc, mimas_error *err)
{
    if (*rc)
        return H5I_INVALID_HID;
    hid_t ds = H5Lexists(r->file, path, H5P_DEFAULT) > 0 ? H5Dopen2(r->file, path, H5P_DEFAULT)
                                                         : H5I_INVALID_HID;
    if (ds < 0)
        *rc = bad(r, err, "missing dataset %s", path);
    return ds;
}

/* Rank and dimensions of a dataset. */
static int ds_shape(hid_t ds, hsize_t dims[4])
{
    hid_t s = H5Dget_space(ds);
    int rank = H5Sget_simple_extent_ndims(s);
    if (rank >= 1 && rank <= 4)
        H5Sget_simple_extent_dims(s, dims, NULL);
    H5Sclose(s);
    return rank;
}

static size_t min_frames(size_t a, hsize_t b)
{
    return (hsize_t)a < b ? a : (size_t)b;
}

/* Identifies a stored column by name: a standard quantity of the table, or an
 * extra column of doubles. */
static int classify(mimas_native *r, const mimas_table_desc *d, native_col *nc, hid_t ds,
                    int row_rank, const char *path, mimas_error *err)
{
    hsize_t dims[4];
    int rank = ds_shape(ds, dims);
    if (rank != row_rank && rank != row_rank + 1)
        return bad(r, err, "dataset %s has an unexpected rank", path);
    nc->ncomp = rank == row_rank ? 1 : (int)dims[row_rank];
    nc->ds = ds;
    nc->extra = -1;
    nc->desc_col = -1;
    const mimas_column_desc *cd = mimas_table_find(d, nc->name);
    hid_t ft = H5Dget_type(ds);
    H5T_class_t cls = H5Tget_class(ft);
    H5Tclose(ft);
    if (cd) {
        nc->desc_col = cd - d->columns;
        nc->type = cd->type;
        if (cd->ncomp != nc->ncomp)
            return bad(r, err, "dataset %s has the wrong number of components", path);
        if ((cd->type == MIMAS_T_F64) != (cls == H5T_FLOAT))
            return bad(r, err, "dataset %s has the wrong type", path);
        return MIMAS_OK;
    }
    if (cls != H5T_FLOAT && cls != H5T_INTEGER)
        return bad(r, err, "dataset %s is neither integer nor floating point", path);
    nc->type = MIMAS_T_F64;  /* extra columns are read as doubles */
    return MIMAS_OK;
}

typedef struct {
    mimas_native *r;
    const char *group;
    read_flat *flat;        /* NULL: the particle group */
    int rc;
    mimas_error *err;
} scan_ctx;

static herr_t scan_member(hid_t g, const char *name, scan_ctx *s)
{
    mimas_native *r = s->r;
    if (s->rc)
        return 1;
    char path[400];
    native_col nc;
    memset(&nc, 0, sizeof nc);
    snprintf(nc.name, sizeof nc.name, "%s", name);
    if (s->flat) {
        if (!strcmp(name, "step") || !strcmp(name, "time") || !strcmp(name, "offset"))
            return 0;
        snprintf(path, sizeof path, "%s/%s", s->group, name);
        hid_t ds = H5Dopen2(g, name, H5P_DEFAULT);
        if (ds < 0) {
            s->rc = bad(r, s->err, "%s is not a dataset", path);
            return 1;
        }
        const mimas_table_desc *d = s->flat == &r->contacts ? &mimas_contacts_desc
                                                            : &mimas_walls_desc;
        s->rc = classify(r, d, &nc, ds, 1, path, s->err);
        if (!s->rc)
            nc.direct = h5_direct_open(ds, native_mem_type(nc.type));
        native_col *grown = realloc(s->flat->cols, (s->flat->ncols + 1) * sizeof nc);
        if (!grown) {
            h5_direct_close(nc.direct);
            H5Dclose(ds);
            s->rc = mimas_error_set(s->err, MIMAS_EIO, "out of memory for the native reader");
            return 1;
        }
        s->flat->cols = grown;
        s->flat->cols[s->flat->ncols++] = nc;
        return s->rc ? 1 : 0;
    }
    if (!strcmp(name, "box"))
        return 0;
    snprintf(path, sizeof path, "%s/%s/value", s->group, name);
    char rel[300];
    snprintf(rel, sizeof rel, "%s/value", name);
    if (H5Lexists(g, rel, H5P_DEFAULT) <= 0)
        return 0;  /* not a time-dependent element */
    hid_t ds = H5Dopen2(g, rel, H5P_DEFAULT);
    if (ds < 0)
        return 0;
    s->rc = classify(r, &mimas_particles_desc, &nc, ds, 2, path, s->err);
    if (!s->rc)
        nc.direct = h5_direct_open(ds, native_mem_type(nc.type));
    native_col *grown = realloc(r->pcols, (r->npcols + 1) * sizeof nc);
    if (!grown) {
        h5_direct_close(nc.direct);
        H5Dclose(ds);
        s->rc = mimas_error_set(s->err, MIMAS_EIO, "out of memory for the native reader");
        return 1;
    }
    r->pcols = grown;
    r->pcols[r->npcols++] = nc;
    return s->rc ? 1 : 0;
}

static int scan_group(mimas_native *r, const char *group, read_flat *flat, mimas_error *err)
{
    hid_t g = H5Gopen2(r->file, group, H5P_DEFAULT);
    if (g < 0)
        return bad(r, err, "missing group %s", group);
    scan_ctx s = {r, group, flat, MIMAS_OK, err};
    H5G_info_t gi;
    if (H5Gget_info(g, &gi) < 0)
        s.rc = bad(r, err, "cannot list group %s", group);
    /* creation order where the writer kept it (extras in written order) */
    hid_t gcpl = H5Gget_create_plist(g);
    unsigned order = 0;
    H5Pget_link_creation_order(gcpl, &order);
    H5Pclose(gcpl);
    H5_index_t by = (order & H5P_CRT_ORDER_INDEXED) ? H5_INDEX_CRT_ORDER : H5_INDEX_NAME;
    for (hsize_t k = 0; !s.rc && k < gi.nlinks; k++) {
        char name[64];
        ssize_t len = H5Lget_name_by_idx(g, ".", by, H5_ITER_INC, k, name, sizeof name,
                                         H5P_DEFAULT);
        if (len < 0 || (size_t)len >= sizeof name)
            s.rc = bad(r, err, "a member of %s has an unreadable or overlong name", group);
        else if (scan_member(g, name, &s) && !s.rc)
            break;
    }
    H5Gclose(g);
    return s.rc;
}

static int open_flat(mimas_native *r, read_flat *t, const char *group, mimas_error *err)
{
    if (H5Lexists(r->file, "/contacts", H5P_DEFAULT) <= 0 ||
        H5Lexists(r->file, group, H5P_DEFAULT) <= 0)
        return MIMAS_OK;
    t->present = 1;
    char p[128];
    int rc = MIMAS_OK;
    snprintf(p, sizeof p, "%s/step", group);
    t->step = open_ds(r, p, &rc, err);
    snprintf(p, sizeof p, "%s/time", group);
    t->time = open_ds(r, p, &rc, err);
    snprintf(p, sizeof p, "%s/offset", group);
    t->offset = open_ds(r, p, &rc, err);
    if (!rc)
        rc = scan_group(r, group, t, err);
    if (rc)
        return rc;
    const mimas_table_desc *d = t == &r->contacts ? &mimas_contacts_desc : &mimas_walls_desc;
    t->rows = (hsize_t)-1;
    for (size_t c = 0; c < t->ncols; c++) {
        hsize_t n = h5_extent0(t->cols[c].ds);
        if (n < t->rows)
            t->rows = n;
    }
    for (size_t c = 0; c < d->ncolumns; c++) {
        if (!(d->required & d->columns[c].bit))
            continue;
        int found = 0;
        for (size_t k = 0; k < t->ncols; k++)
            found |= t->cols[k].desc_col == (long)c;
        if (!found) {
            return bad(r, err, "missing dataset %s/%s", group, d->columns[c].name);
        }
    }
    hsize_t nofs = h5_extent0(t->offset);
    r->frames = min_frames(r->frames, nofs ? nofs - 1 : 0);
    r->frames = min_frames(r->frames, h5_extent0(t->step));
    r->frames = min_frames(r->frames, h5_extent0(t->time));
    return MIMAS_OK;
}

/* /parameters/tube (format 1.1; absent in 1.0 files) */
static int open_tube(mimas_native *r, mimas_error *err)
{
    if (H5Lexists(r->file, "/parameters", H5P_DEFAULT) <= 0 ||
        H5Lexists(r->file, NATIVE_TUBE, H5P_DEFAULT) <= 0)
        return MIMAS_OK;
    hid_t g = H5Gopen2(r->file, NATIVE_TUBE, H5P_DEFAULT);
    mimas_tube *t = &r->tube;
    int ok = g >= 0 && h5_attr_read_doubles(g, "origin", t->origin, 3) == 3 &&
             h5_attr_read_doubles(g, "direction", t->direction, 3) == 3 &&
             h5_attr_read_doubles(g, "radius", &t->radius, 1) == 1 &&
             h5_attr_read_doubles(g, "length", &t->length, 1) == 1;
    if (g >= 0)
        H5Gclose(g);
    double dn = sqrt(t->direction[0] * t->direction[0] + t->direction[1] * t->direction[1] +
                     t->direction[2] * t->direction[2]);
    if (!ok || !(t->radius > 0) || !(t->length > 0) || !(fabs(dn - 1) < 1e-9))
        return bad(r, err, "%s", NATIVE_TUBE " lacks origin, direction (a unit vector), "
                   "radius > 0 or length > 0");
    t->present = 1;
    return MIMAS_OK;
}

/* /fields/gas (format 1.1; absent in 1.0 files) */
static int open_gas(mimas_native *r, mimas_error *err)
{
    if (H5Lexists(r->file, "/fields", H5P_DEFAULT) <= 0 ||
        H5Lexists(r->file, NATIVE_GAS, H5P_DEFAULT) <= 0)
        return MIMAS_OK;
    hid_t g = H5Gopen2(r->file, NATIVE_GAS, H5P_DEFAULT);
    int64_t cells[3];
    int ok = g >= 0 && h5_attr_read_doubles(g, "origin", r->gas_origin, 3) == 3 &&
             h5_attr_read_doubles(g, "spacing", r->gas_spacing, 3) == 3 &&
             h5_attr_read_int64s(g, "cells", cells, 3) == 3;
    if (g >= 0)
        H5Gclose(g);
    for (int d = 0; d < 3 && ok; d++) {
        ok = cells[d] >= 1 && cells[d] <= (1 << 24) && r->gas_spacing[d] > 0;
        r->gas_cells[d] = ok ? (size_t)cells[d] : 0;
    }
    if (!ok)
        return bad(r, err, "%s", NATIVE_GAS " lacks origin, spacing > 0 or cells >= 1");
    static const char *const names[3] = {"pressure", "porosity", "velocity"};
    int rc = MIMAS_OK;
    for (int k = 0; k < 3 && !rc; k++) {
        char path[128];
        snprintf(path, sizeof path, NATIVE_GAS "/%s/value", names[k]);
        r->gas_ds[k] = open_ds(r, path, &rc, err);
        if (rc)
            break;
        hsize_t dims[5];
        hid_t sp = H5Dget_space(r->gas_ds[k]);
        int rank = H5Sget_simple_extent_ndims(sp);
        if (rank == (k == 2 ? 5 : 4))
            H5Sget_simple_extent_dims(sp, dims, NULL);
        H5Sclose(sp);
        if (rank != (k == 2 ? 5 : 4) || dims[1] != r->gas_cells[2] || dims[2] != r->gas_cells[1] ||
            dims[3] != r->gas_cells[0] || (k == 2 && dims[4] != 3))
            return bad(r, err, "%s does not have the shape (frames, %zu, %zu, %zu%s)", path,
                       r->gas_cells[2], r->gas_cells[1], r->gas_cells[0], k == 2 ? ", 3" : "");
        r->frames = min_frames(r->frames, dims[0]);
    }
    r->has_gas = !rc;
    return rc;
}

static int check_version(mimas_native *r, mimas_error *err)
{
    if (H5Lexists(r->file, "/h5md", H5P_DEFAULT) <= 0)
        return bad(r, err, "%s", "not an H5MD file (no /h5md group)");
    hid_t g = H5Lexists(r->file, NATIVE_MIMAS, H5P_DEFAULT) > 0
                  ? H5Gopen2(r->file, NATIVE_MIMAS, H5P_DEFAULT)
                  : H5I_INVALID_HID;
    int v[2] = {0, 0};
    int n = g >= 0 ? h5_attr_read_ints(g, "format_version", v, 2) : -1;
    if (g >= 0)
        H5Gclose(g);
    if (n != 2)
        return bad(r, err, "%s", "not a mimas native file (no /mimas format_version)");
    if (v[0] > MIMAS_NATIVE_VERSION_MAJOR)
        return bad(r, err, "format version %d.%d is newer than this mimas reads (%d.x); "
                   "update mimas", v[0], v[1], MIMAS_NATIVE_VERSION_MAJOR);
    hid_t gc = H5Lexists(r->file, "/h5md/creator", H5P_DEFAULT) > 0
                   ? H5Gopen2(r->file, "/h5md/creator", H5P_DEFAULT)
                   : H5I_INVALID_HID;
    char name[48] = "", version[40] = "";
    if (gc >= 0) {
        h5_attr_read_str(gc, "name", name, sizeof name);
        h5_attr_read_str(gc, "version", version, sizeof version);
        H5Gclose(gc);
    }
    snprintf(r->creator, sizeof r->creator, "%s %s", name[0] ? name : "unknown", version);
    return MIMAS_OK;
}

static int open_particles(mimas_native *r, mimas_error *err)
{
    int rc = MIMAS_OK;
    if (H5Lexists(r->file, "/particles", H5P_DEFAULT) <= 0) {
        /* the writer's header without a first frame: a file of zero frames */
        r->frames = 0;
        return MIMAS_OK;
    }
    r->clock_step = open_ds(r, NATIVE_CLOCK "/step", &rc, err);
    r->clock_time = open_ds(r, NATIVE_CLOCK "/time", &rc, err);
    r->count = open_ds(r, NATIVE_COUNT "/value", &rc, err);
    r->box_edges = open_ds(r, NATIVE_BOX "/edges/value", &rc, err);
    r->box_lower = open_ds(r, NATIVE_BOX "/lower/value", &rc, err);
    r->box_upper = open_ds(r, NATIVE_BOX "/upper/value", &rc, err);
    if (rc)
        return rc;
    hid_t gb = H5Gopen2(r->file, NATIVE_BOX, H5P_DEFAULT);
    char bnd[3][16];
    int nb = gb >= 0 ? h5_attr_read_strs(gb, "boundary", bnd, 3) : -1;
    if (gb >= 0)
        H5Gclose(gb);
    if (nb != 3)
        return bad(r, err, "%s", "the box has no 3-d boundary attribute");
    for (int d = 0; d < 3; d++)
        r->periodic[d] = !strcmp(bnd[d], "periodic");
    hsize_t dims[4];
    int erank = ds_shape(r->box_edges, dims);
    if (erank != 2 && erank != 3)
        return bad(r, err, "%s", "box edges have an unexpected shape");
    r->triclinic = erank == 3;
    rc = scan_group(r, NATIVE_PARTICLES, NULL, err);
    if (rc)
        return rc;
    r->frames = (size_t)-1;
    r->frames = min_frames(r->frames, h5_extent0(r->clock_step));
    r->frames = min_frames(r->frames, h5_extent0(r->clock_time));
    r->frames = min_frames(r->frames, h5_extent0(r->count));
    r->frames = min_frames(r->frames, h5_extent0(r->box_edges));
    r->frames = min_frames(r->frames, h5_extent0(r->box_lower));
    r->frames = min_frames(r->frames, h5_extent0(r->box_upper));
    r->nmax = (hsize_t)-1;
    for (size_t c = 0; c < r->npcols; c++) {
        ds_shape(r->pcols[c].ds, dims);
        r->frames = min_frames(r->frames, dims[0]);
        if (dims[1] < r->nmax)
            r->nmax = dims[1];
        if (r->pcols[c].desc_col >= 0)
            r->p_bits |= mimas_particles_desc.columns[r->pcols[c].desc_col].bit;
    }
    if (!(r->p_bits & MIMAS_P_ID))
        return bad(r, err, "missing dataset %s", NATIVE_PARTICLES "/id/value");
    if (!(r->p_bits & MIMAS_P_POS))
        return bad(r, err, "missing dataset %s", NATIVE_PARTICLES "/position/value");
    return MIMAS_OK;
}

/* ---- the per-frame index, checked once at open ---- */

#define INDEX_BLOCK 4096   /* frames per read: memory does not grow with the file */

static herr_t read_block(hid_t ds, hid_t memtype, int rank, const hsize_t *start,
                         const hsize_t *count, void *buf);

typedef struct index_block {
    int64_t step[INDEX_BLOCK], count[INDEX_BLOCK], ofs[2][INDEX_BLOCK + 1];
    int64_t cstep[2][INDEX_BLOCK];
    double time[INDEX_BLOCK], lo[INDEX_BLOCK][3], hi[INDEX_BLOCK][3], edges[INDEX_BLOCK][9];
} index_block;

/* Frames k0 .. k0+n-1 of the step, time, count, box and contact offsets. */
static int read_index(mimas_native *r, size_t k0, size_t n, index_block *b, mimas_error *err)
{
    hsize_t start[3] = {k0, 0, 0}, one[1] = {n}, vec[3] = {n, 3, 3};
    if (read_block(r->clock_step, H5T_NATIVE_INT64, 1, start, one, b->step) < 0 ||
        read_block(r->clock_time, H5T_NATIVE_DOUBLE, 1, start, one, b->time) < 0 ||
        read_block(r->count, H5T_NATIVE_INT64, 1, start, one, b->count) < 0)
        return bad(r, err, "%s", "cannot read the step, time and particle count of the frames");
    if (read_block(r->box_lower, H5T_NATIVE_DOUBLE, 2, start, vec, b->lo) < 0 ||
        read_block(r->box_upper, H5T_NATIVE_DOUBLE, 2, start, vec, b->hi) < 0 ||
        read_block(r->box_edges, H5T_NATIVE_DOUBLE, r->triclinic ? 3 : 2, start, vec,
                   b->edges) < 0)
        return bad(r, err, "%s", "cannot read the box of the frames");
    read_flat *fl[2] = {&r->contacts, &r->walls};
    for (int t = 0; t < 2; t++) {
        if (!fl[t]->present)
            continue;
        hsize_t n1 = n + 1;
        if (read_block(fl[t]->offset, H5T_NATIVE_INT64, 1, start, &n1, b->ofs[t]) < 0 ||
            read_block(fl[t]->step, H5T_NATIVE_INT64, 1, start, one, b->cstep[t]) < 0)
            return bad(r, err, "cannot read the index of the %s", t ? "wall contacts"
                                                                   : "contacts");
    }
    return MIMAS_OK;
}

/* What every frame's index must satisfy (as a text dump's header must):
 * counts within the stored slots, steps increasing, times all known (finite,
 * not decreasing) or all unknown (NaN), boxes finite and not inverted,
 * contact offsets starting at 0 and not decreasing, contact steps equal to
 * the particle steps. */
static int check_index(mimas_native *r, mimas_error *err)
{
    if (r->frames == 0)
        return MIMAS_OK;
    index_block *b = malloc(sizeof *b);
    if (!b)
        return mimas_error_set(err, MIMAS_EIO, "%s: out of memory for the frame index", r->path);
    int rc = MIMAS_OK, have_last = 0;
    int64_t last_step = 0;
    double last_time = 0;
    const char *names[2] = {"contact", "wall-contact"};
    read_flat *fl[2] = {&r->contacts, &r->walls};
    for (size_t k0 = 0; !rc && k0 < r->frames; k0 += INDEX_BLOCK) {
        size_t n = r->frames - k0 < INDEX_BLOCK ? r->frames - k0 : INDEX_BLOCK;
        rc = read_index(r, k0, n, b, err);
        for (size_t m = 0; !rc && m < n; m++) {
            size_t k = k0 + m;
            mimas_box box = {{b->lo[m][0], b->lo[m][1], b->lo[m][2]},
                             {b->hi[m][0], b->hi[m][1], b->hi[m][2]},
                             r->triclinic ? b->edges[m][3] : 0,
                             r->triclinic ? b->edges[m][6] : 0,
                             r->triclinic ? b->edges[m][7] : 0, {0, 0, 0}};
            if (b->count[m] < 0 || (hsize_t)b->count[m] > r->nmax)
                rc = bad(r, err, "frame %zu claims %lld particles; the file stores at most %llu",
                         k, (long long)b->count[m], (unsigned long long)r->nmax);
            else if (have_last && b->step[m] <= last_step)
                rc = bad(r, err, "frame %zu has step %lld after step %lld: steps must increase",
                         k, (long long)b->step[m], (long long)last_step);
            else if (isinf(b->time[m]) || (have_last && isnan(b->time[m]) != isnan(last_time)))
                rc = bad(r, err, "frame %zu has time %g: times must be finite in every frame "
                         "or unknown (NaN) in every frame", k, b->time[m]);
            else if (have_last && b->time[m] < last_time)
                rc = bad(r, err, "frame %zu has time %.17g after time %.17g: times must not "
                         "decrease", k, b->time[m], last_time);
            else if (mimas_box_check(&box, err))
                rc = mimas_error_prefix(err, "%s: frame %zu", r->path, k);
            for (int t = 0; !rc && t < 2; t++) {
                if (!fl[t]->present)
                    continue;
                int64_t lo = b->ofs[t][m], hi = b->ofs[t][m + 1];
                if ((k == 0 && lo != 0) || lo < 0 || hi < lo || (hsize_t)hi > fl[t]->rows)
                    rc = bad(r, err, "%s offsets of frame %zu (%lld..%lld) are out of order or "
                             "beyond the %llu rows stored", names[t], k, (long long)lo,
                             (long long)hi, (unsigned long long)fl[t]->rows);
                else if (b->cstep[t][m] != b->step[m])
                    rc = bad(r, err, "frame %zu: the %s step %lld differs from the particle "
                             "step %lld", k, names[t], (long long)b->cstep[t][m],
                             (long long)b->step[m]);
            }
            have_last = 1;
            last_step = b->step[m];
            last_time = b->time[m];
        }
    }
    free(b);
    return rc;
}

static void close_cols(native_col *cols, size_t n)
{
    for (size_t c = 0; c < n; c++) {
        h5_direct_close(cols[c].direct);
        if (cols[c].ds > 0)
            H5Dclose(cols[c].ds);
    }
    free(cols);
}

void mimas_native_close(mimas_native *r)
{
    if (!r)
        return;
    h5_quiet q;
    h5_quiet_begin(&q);
    close_cols(r->pcols, r->npcols);
    read_flat *fl[2] = {&r->contacts, &r->walls};
    for (int k = 0; k < 2; k++) {
        hid_t ids[3] = {fl[k]->step, fl[k]->time, fl[k]->offset};
        for (int m = 0; m < 3; m++)
            if (ids[m] > 0)
                H5Dclose(ids[m]);
        close_cols(fl[k]->cols, fl[k]->ncols);
    }
    hid_t ids[9] = {r->clock_step, r->clock_time, r->count, r->box_edges, r->box_lower,
                    r->box_upper, r->gas_ds[0], r->gas_ds[1], r->gas_ds[2]};
    for (int k = 0; k < 9; k++)
        if (ids[k] > 0)
            H5Dclose(ids[k]);
    for (size_t k = 0; k < r->nobs; k++)
        if (r->obs[k].ds > 0)
            H5Dclose(r->obs[k].ds);
    free(r->obs);
    mimas_parameters_free(&r->params);
    if (r->file > 0)
        H5Fclose(r->file);
    h5_quiet_end(&q);
    mimas_id_index_free(&r->index);
    free(r->ids);
    h5_direct_scratch_free(&r->direct);
    free(r->path);
    free(r);
}

static int open_metadata(mimas_native *r, mimas_error *err);

int mimas_native_open(mimas_native **out, const char *path, mimas_error *err)
{
    *out = NULL;
    mimas_native *r = calloc(1, sizeof *r);
    if (!r || !(r->path = strdup(path))) {
        free(r);
        return mimas_error_set(err, MIMAS_EIO, "out of memory for the native reader");
    }
    mimas_id_index_init(&r->index);
    struct stat st;
    if (stat(path, &st) != 0) {
        int e = errno;
        mimas_native_close(r);
        return mimas_error_set(err, MIMAS_EDATA, "%s: cannot open: %s", path, strerror(e));
    }
    if (st.st_size == 0) {
        mimas_native_close(r);
        return mimas_error_set(err, MIMAS_EDATA, "%s: empty file", path);
    }
    h5_quiet q;
    h5_quiet_begin(&q);
    int rc = MIMAS_OK;
    if (H5Fis_hdf5(path) <= 0) {
        rc = mimas_error_set(err, MIMAS_EDATA, "%s: not an HDF5 file", path);
    } else {
        hid_t fapl = H5Pcreate(H5P_FILE_ACCESS);
        H5Pset_fclose_degree(fapl, H5F_CLOSE_STRONG);
        /* single-writer/multiple-reader read: the committed frames of a file
         * that is still being written; files of the older format (or not
         * written in SWMR mode) are opened plainly */
        char text[256] = "", text2[256] = "";
        r->file = H5Fopen(path, H5F_ACC_RDONLY | H5F_ACC_SWMR_READ, fapl);
        if (r->file < 0) {
            h5_error_text(text, sizeof text); /* before any other call clears the stack */
            r->file = H5Fopen(path, H5F_ACC_RDONLY, fapl);
            if (r->file < 0)
                h5_error_text(text2, sizeof text2);
            if (!strstr(text, "truncated") || strstr(text2, "truncated"))
                memcpy(text, text2, sizeof text);
        } else {
            /* SWMR readers skip HDF5's end-of-file check (a writer may be
             * extending the file): the committed end must be there */
            haddr_t eoa = 0;
            struct stat now;
            if (H5Fget_eoa(r->file, &eoa) >= 0 && stat(path, &now) == 0 &&
                (haddr_t)now.st_size < eoa) {
                H5Fclose(r->file);
                r->file = H5I_INVALID_HID;
                snprintf(text, sizeof text, "truncated file: eof = %lld, eoa = %llu",
                         (long long)now.st_size, (unsigned long long)eoa);
            }
        }
        H5Pclose(fapl);
        if (r->file < 0) {
            rc = mimas_error_set(err, MIMAS_EDATA,
                                 strstr(text, "truncated")
                                     ? "%s: the file is cut short below its last committed "
                                       "frame and cannot be read (HDF5: %s)"
                                     : "%s: HDF5 cannot open it (%s)",
                                 path, text);
        }
    }
    if (!rc)
        rc = check_version(r, err);
    if (!rc)
        rc = open_particles(r, err);
    if (!rc)
        rc = open_flat(r, &r->contacts, NATIVE_CONTACTS, err);
    if (!rc)
        rc = open_flat(r, &r->walls, NATIVE_WALLS, err);
    if (!rc)
        rc = open_tube(r, err);
    if (!rc)
        rc = open_gas(r, err);
    if (!rc)
        rc = check_index(r, err);
    if (!rc)
        rc = open_metadata(r, err);
    h5_quiet_end(&q);
    if (rc) {
        mimas_native_close(r);
        return rc;
    }
    *out = r;
    return MIMAS_OK;
}

size_t mimas_native_frames(const mimas_native *r)
{
    return r->frames;
}

int mimas_native_has_contacts(const mimas_native *r)
{
    return r->contacts.present;
}

int mimas_native_has_walls(const mimas_native *r)
{
    return r->walls.present;
}

const char *mimas_native_creator(const mimas_native *r)
{
    return r->creator;
}

size_t mimas_native_particle_columns(const mimas_native *r)
{
    return r->npcols;
}

void mimas_native_particle_column(const mimas_native *r, size_t k, mimas_native_column *c)
{
    const native_col *nc = &r->pcols[k];
    memset(c, 0, sizeof *c);
    c->name = nc->name;
    c->ncomp = nc->ncomp;
    h5_quiet q;
    h5_quiet_begin(&q);
    hid_t ft = H5Dget_type(nc->ds);
    c->is_float = H5Tget_class(ft) == H5T_FLOAT;
    c->precision = (int)H5Tget_size(ft);
    H5Tclose(ft);
    hsize_t dims[4] = {0};
    c->rank = ds_shape(nc->ds, dims);
    if (c->rank > 3)
        c->rank = 3;
    for (int d = 0; d < c->rank; d++)
        c->dims[d] = dims[d];
    h5_quiet_end(&q);
}

/* ---- reading frame k ---- */

static herr_t read_block(hid_t ds, hid_t memtype, int rank, const hsize_t *start,
                         const hsize_t *count, void *buf)
{
    hid_t fs = H5Dget_space(ds);
    hsize_t mcount = 1;
    for (int d = 0; d < rank; d++)
        mcount *= count[d];
    herr_t rc = 0;
    if (mcount > 0) {
        /* the memory space has the selection's own shape (the buffer is the block in row
         * order either way): HDF5 then copies whole rows of each chunk instead of
         * iterating over elements (a sixth of the run of `mimas average` on a native file) */
        hid_t ms = H5Screate_simple(rank, count, NULL);
        rc = H5Sselect_hyperslab(fs, H5S_SELECT_SET, start, NULL, count, NULL);
        if (rc >= 0)
            rc = H5Dread(ds, memtype, ms, fs, H5P_DEFAULT, buf);
        H5Sclose(ms);
    }
    H5Sclose(fs);
    return rc;
}

/* A column's block: by its chunks where it can (h5_direct.h), else by H5Dread. */
static herr_t read_col(mimas_native *r, const native_col *c, int rank, const hsize_t *start,
                       const hsize_t *count, void *buf)
{
    if (c->direct && h5_direct_read(c->direct, &r->direct, start, count, buf) == 0)
        return 0;
    return read_block(c->ds, native_mem_type(c->type), rank, start, count, buf);
}

static herr_t read_at(hid_t ds, hsize_t k, hid_t memtype, void *value)
{
    hsize_t one = 1;
    return read_block(ds, memtype, 1, &k, &one, value);
}

/* Makes the frame's table carry exactly the file's columns, keeping the
 * memory of those it already has. */
static int shape_table(void *tab, const mimas_table_desc *d, const native_col *cols,
                       size_t ncols, native_col *bound, mimas_error *err)
{
    unsigned bits = 0;
    size_t n_extra_file = 0;
    for (size_t c = 0; c < ncols; c++) {
        if (cols[c].desc_col >= 0)
            bits |= d->columns[cols[c].desc_col].bit;
        else
            n_extra_file++;
    }
    mimas_table_keep_only(tab, d, bits);
    int rc = mimas_table_set_present(tab, d, bits, err);
    /* extras: keep them if they are already the file's, else rebuild */
    const size_t n_extra = *(const size_t *)((const char *)tab + d->off_n_extra);
    const mimas_extra *extra = *(mimas_extra *const *)((const char *)tab + d->off_extra);
    int same = n_extra == n_extra_file;
    for (size_t c = 0, e = 0; same && c < ncols; c++)
        if (cols[c].desc_col < 0) {
            same = !strcmp(extra[e].name, cols[c].name) && extra[e].ncomp == cols[c].ncomp;
            e++;
        }
    if (!same)
        mimas_table_drop_extras(tab, d);
    for (size_t c = 0; !rc && c < ncols; c++) {
        bound[c] = cols[c];
        if (cols[c].desc_col < 0) {
            size_t idx;
            rc = mimas_table_add_extra(tab, d, cols[c].name, cols[c].ncomp, &idx, err);
            bound[c].extra = (long)idx;
            mimas_extra *x = &(*(mimas_extra **)((char *)tab + d->off_extra))[idx];
            if (!rc && h5_attr_read_str(cols[c].ds, "unit", x->unit, sizeof x->unit) < 0)
                x->unit[0] = '\0';
        }
    }
    return rc;
}

static int ensure_ids(mimas_native *r, size_t n)
{
    if (n <= r->ids_cap)
        return 0;
    int64_t *b = realloc(r->ids, n * sizeof *b);
    if (!b)
        return -1;
    r->ids = b;
    r->ids_cap = n;
    return 0;
}

static int read_particles(mimas_native *r, size_t k, mimas_frame *f, mimas_error *err)
{
    int64_t n64;
    if (read_at(r->count, k, H5T_NATIVE_INT64, &n64) < 0)
        return bad(r, err, "cannot read %s", NATIVE_COUNT "/value");
    if (n64 < 0 || (hsize_t)n64 > r->nmax)
        return bad(r, err, "frame %zu claims %lld particles, more than stored", k,
                   (long long)n64);
    size_t n = (size_t)n64;
    mimas_particles *p = &f->particles;
    native_col bound[64];
    if (r->npcols > 64)
        return bad(r, err, "%s", "too many particle quantities");
    int rc = shape_table(p, &mimas_particles_desc, r->pcols, r->npcols, bound, err);
    if (!rc)
        rc = mimas_table_resize(p, &mimas_particles_desc, n, err);
    for (size_t c = 0; !rc && c < r->npcols; c++) {
        int rank = bound[c].ncomp == 1 ? 2 : 3;
        hsize_t start[3] = {k, 0, 0}, count[3] = {1, n, (hsize_t)bound[c].ncomp};
        if (read_col(r, &bound[c], rank, start, count,
                     native_col_data(p, &mimas_particles_desc, &bound[c])) < 0)
            rc = bad(r, err, "cannot read %s of frame %zu", bound[c].name, k);
    }
    return rc;
}

static int read_box(mimas_native *r, size_t k, mimas_frame *f, mimas_error *err)
{
    double e[3][3] = {{0}}, diag[3];
    mimas_box *b = &f->box;
    hsize_t start[3] = {k, 0, 0}, count[3] = {1, 3, 3};
    if (read_block(r->box_edges, H5T_NATIVE_DOUBLE, r->triclinic ? 3 : 2, start, count,
                   r->triclinic ? (void *)e : (void *)diag) < 0 ||
        read_block(r->box_lower, H5T_NATIVE_DOUBLE, 2, start, count, b->lo) < 0 ||
        read_block(r->box_upper, H5T_NATIVE_DOUBLE, 2, start, count, b->hi) < 0)
        return bad(r, err, "%s", "cannot read the box");
    /* tilts are the off-diagonal entries of the edge vectors (LAMMPS order) */
    b->xy = e[1][0];
    b->xz = e[2][0];
    b->yz = e[2][1];
    for (int d = 0; d < 3; d++)
        b->periodic[d] = r->periodic[d];
    return MIMAS_OK;
}

static int read_flat_frame(mimas_native *r, read_flat *t, size_t k, void *tab,
                           const mimas_table_desc *d, mimas_error *err)
{
    int64_t ofs[2];
    hsize_t start = k, two = 2;
    if (read_block(t->offset, H5T_NATIVE_INT64, 1, &start, &two, ofs) < 0)
        return bad(r, err, "cannot read the offsets of %s", d->name);
    if (ofs[0] < 0 || ofs[1] < ofs[0] || (hsize_t)ofs[1] > t->rows)
        return bad(r, err, "%s offsets of frame %zu (%lld..%lld) are out of range", d->name, k,
                   (long long)ofs[0], (long long)ofs[1]);
    size_t n = (size_t)(ofs[1] - ofs[0]);
    native_col bound[64];
    if (t->ncols > 64)
        return bad(r, err, "too many %s quantities", d->name);
    int rc = shape_table(tab, d, t->cols, t->ncols, bound, err);
    if (!rc)
        rc = mimas_table_resize(tab, d, n, err);
    for (size_t c = 0; !rc && c < t->ncols; c++) {
        int rank = bound[c].ncomp == 1 ? 1 : 2;
        hsize_t s[2] = {(hsize_t)ofs[0], 0}, cnt[2] = {n, (hsize_t)bound[c].ncomp};
        void *dst = native_col_data(tab, d, &bound[c]);
        int is_index = bound[c].type == MIMAS_T_INDEX;
        if (is_index && ensure_ids(r, n))
            return mimas_error_set(err, MIMAS_EIO, "out of memory for the native reader");
        if (read_col(r, &bound[c], rank, s, cnt, is_index ? (void *)r->ids : dst) < 0)
            return bad(r, err, "cannot read %s/%s of frame %zu", d->name, bound[c].name, k);
        if (!is_index)
            continue;
        size_t *idx = dst;
        for (size_t m = 0; m < n; m++) {
            if (!mimas_id_index_find(&r->index, r->ids[m], &idx[m]))
                return bad(r, err, "%s row %lld (frame %zu) names particle id %lld, which the "
                           "frame does not have", d->name, (long long)(ofs[0] + (int64_t)m), k,
                           (long long)r->ids[m]);
        }
    }
    return rc;
}

static int read_gas(mimas_native *r, size_t k, mimas_gas *g, mimas_error *err)
{
    const size_t *c = r->gas_cells;
    int rc = mimas_gas_resize(g, c[0], c[1], c[2], err);
    if (rc)
        return mimas_error_prefix(err, "%s", r->path);
    memcpy(g->origin, r->gas_origin, sizeof g->origin);
    memcpy(g->spacing, r->gas_spacing, sizeof g->spacing);
    void *dst[3] = {g->pressure, g->porosity, g->velocity};
    for (int m = 0; m < 3; m++) {
        hsize_t start[5] = {k, 0, 0, 0, 0}, count[5] = {1, c[2], c[1], c[0], 3};
        if (read_block(r->gas_ds[m], H5T_NATIVE_DOUBLE, m == 2 ? 5 : 4, start, count, dst[m]) < 0)
            return bad(r, err, "cannot read the gas fields of frame %zu", k);
    }
    return MIMAS_OK;
}

int mimas_native_read(mimas_native *r, size_t k, mimas_frame *f, mimas_error *err)
{
    if (k >= r->frames)
        return mimas_error_set(err, MIMAS_EUSAGE, "%s: frame %zu does not exist (%zu frames)",
                               r->path, k, r->frames);
    h5_quiet q;
    h5_quiet_begin(&q);
    int rc = MIMAS_OK;
    if (read_at(r->clock_step, k, H5T_NATIVE_INT64, &f->step) < 0 ||
        read_at(r->clock_time, k, H5T_NATIVE_DOUBLE, &f->time) < 0)
        rc = bad(r, err, "%s", "cannot read step and time");
    if (!rc)
        rc = read_box(r, k, f, err);
    if (!rc)
        rc = read_particles(r, k, f, err);
    f->has_contacts = r->contacts.present;
    f->has_walls = r->walls.present;
    if (!rc && (r->contacts.present || r->walls.present)) {
        rc = mimas_id_index_build(&r->index, f->particles.id, f->particles.n, err);
        if (rc)
            mimas_error_prefix(err, "%s: frame %zu", r->path, k);
    }
    if (!rc && r->contacts.present)
        rc = read_flat_frame(r, &r->contacts, k, &f->contacts, &mimas_contacts_desc, err);
    else if (!rc)
        mimas_table_resize(&f->contacts, &mimas_contacts_desc, 0, NULL);
    if (!rc && r->walls.present)
        rc = read_flat_frame(r, &r->walls, k, &f->walls, &mimas_walls_desc, err);
    else if (!rc)
        mimas_table_resize(&f->walls, &mimas_walls_desc, 0, NULL);
    f->tube = r->tube;
    f->gas.present = 0;
    if (!rc && r->has_gas)
        rc = read_gas(r, k, &f->gas, err);
    h5_quiet_end(&q);
    /* the values, as strictly as a text reader checks them */
    if (!rc && mimas_frame_check(f, err))
        rc = mimas_error_prefix(err, "%s: frame %zu (step %lld)", r->path, k,
                                (long long)f->step);
    return rc;
}

int mimas_native_frame_meta(mimas_native *r, size_t k, mimas_frame_meta *m, mimas_error *err)
{
    if (k >= r->frames)
        return mimas_error_set(err, MIMAS_EUSAGE, "%s: frame %zu does not exist", r->path, k);
    h5_quiet q;
    h5_quiet_begin(&q);
    int64_t n = 0, ofs[2] = {0, 0};
    hsize_t start = k, two = 2;
    int rc = MIMAS_OK;
    memset(m, 0, sizeof *m);
    if (read_at(r->clock_step, k, H5T_NATIVE_INT64, &m->step) < 0 ||
        read_at(r->clock_time, k, H5T_NATIVE_DOUBLE, &m->time) < 0 ||
        read_at(r->count, k, H5T_NATIVE_INT64, &n) < 0)
        rc = bad(r, err, "%s", "cannot read the frame index");
    m->n_particles = (size_t)n;
    if (!rc) {
        mimas_frame tmp;  /* only its box is filled */
        memset(&tmp.box, 0, sizeof tmp.box); /* and its padding (mimas info memcmps boxes) */
        rc = read_box(r, k, &tmp, err);
        m->box = tmp.box;
    }
    if (!rc && r->contacts.present) {
        if (read_block(r->contacts.offset, H5T_NATIVE_INT64, 1, &start, &two, ofs) < 0)
            rc = bad(r, err, "%s", "cannot read the contact offsets");
        m->n_contacts = (size_t)(ofs[1] - ofs[0]);
    }
    if (!rc && r->walls.present) {
        if (read_block(r->walls.offset, H5T_NATIVE_INT64, 1, &start, &two, ofs) < 0)
            rc = bad(r, err, "%s", "cannot read the wall-contact offsets");
        m->n_walls = (size_t)(ofs[1] - ofs[0]);
    }
    h5_quiet_end(&q);
    return rc;
}

/* ---- run parameters and per-frame observables ---- */

/* Member name of /observables/all: recorded if it is a scalar element. */
static int note_observable(mimas_native *r, hid_t g, const char *name)
{
    char rel[128];
    if (!strcmp(name, "particle_count") || strlen(name) >= sizeof r->obs[0].name ||
        snprintf(rel, sizeof rel, "%s/value", name) >= (int)sizeof rel ||
        H5Lexists(g, name, H5P_DEFAULT) <= 0 || H5Lexists(g, rel, H5P_DEFAULT) <= 0)
        return 0;
    hid_t ds = H5Dopen2(g, rel, H5P_DEFAULT);
    if (ds < 0)
        return 0;
    hsize_t dims[4];
    hid_t t = H5Dget_type(ds);
    int scalar = ds_shape(ds, dims) == 1 && H5Tget_class(t) == H5T_FLOAT;
    H5Tclose(t);
    struct native_obs *grown = scalar ? realloc(r->obs, (r->nobs + 1) * sizeof *grown) : NULL;
    if (!grown) {
        H5Dclose(ds);
        return scalar ? -1 : 0;
    }
    r->obs = grown;
    struct native_obs *o = &r->obs[r->nobs++];
    snprintf(o->name, sizeof o->name, "%s", name);
    o->unit[0] = '\0';
    h5_attr_read_str(ds, "unit", o->unit, sizeof o->unit);
    o->ds = ds;
    r->frames = min_frames(r->frames, dims[0]);
    return 0;
}

static int open_metadata(mimas_native *r, mimas_error *err)
{
    if (parameters_read_h5(r->file, "scenario", &r->params))
        return bad(r, err, "%s", "cannot read /parameters/scenario (an attribute that is "
                   "neither a number nor a string?)");
    hid_t g = H5Lexists(r->file, "/observables", H5P_DEFAULT) > 0 &&
                      H5Lexists(r->file, NATIVE_OBSERVABLES, H5P_DEFAULT) > 0
                  ? H5Gopen2(r->file, NATIVE_OBSERVABLES, H5P_DEFAULT)
                  : H5I_INVALID_HID;
    H5G_info_t gi;
    int rc = 0;
    if (g >= 0 && H5Gget_info(g, &gi) >= 0)
        for (hsize_t k = 0; !rc && k < gi.nlinks; k++) {
            char name[64];
            ssize_t len = H5Lget_name_by_idx(g, ".", H5_INDEX_NAME, H5_ITER_INC, k, name,
                                             sizeof name, H5P_DEFAULT);
            if (len > 0 && (size_t)len < sizeof name)
                rc = note_observable(r, g, name);
        }
    if (g >= 0)
        H5Gclose(g);
    return rc < 0 ? mimas_error_set(err, MIMAS_EIO, "out of memory") : MIMAS_OK;
}

const mimas_parameters *mimas_native_parameters(const mimas_native *r)
{
    return &r->params;
}

size_t mimas_native_observables(const mimas_native *r)
{
    return r->nobs;
}

const char *mimas_native_observable_name(const mimas_native *r, size_t i, const char **unit)
{
    if (unit)
        *unit = i < r->nobs ? r->obs[i].unit : "";
    return i < r->nobs ? r->obs[i].name : NULL;
}

int mimas_native_observable_read(mimas_native *r, size_t i, size_t k0, size_t n, double *values,
                                 mimas_error *err)
{
    if (i >= r->nobs || k0 > r->frames || n > r->frames - k0)
        return mimas_error_set(err, MIMAS_EUSAGE, "%s: no observable %zu of frames %zu..%zu",
                               r->path, i, k0, k0 + n);
    h5_quiet q;
    h5_quiet_begin(&q);
    hsize_t start = k0, count = n;
    int rc = n && read_block(r->obs[i].ds, H5T_NATIVE_DOUBLE, 1, &start, &count, values) < 0
                 ? bad(r, err, "cannot read %s/%s of frames %zu..%zu", NATIVE_OBSERVABLES,
                       r->obs[i].name, k0, k0 + n - 1)
                 : MIMAS_OK;
    h5_quiet_end(&q);
    return rc;
}
