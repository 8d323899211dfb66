/* Native format writer (docs/format.md).  Frames are appended one at a time
 * and committed in batches, each commit ending with a flush (the rule is at
 * COMMIT_SECONDS_MIN below); file space is only ever taken from the end of the
 * file, so what a flush committed is never overwritten later: a
 * process killed in the middle of a frame leaves a file whose committed
 * frames read back intact.
 *
 * The file is written in HDF5's single-writer/multiple-reader mode (SWMR,
 * file format of HDF5 1.10): every object (group, dataset, attribute) is
 * created before the first frame is committed, which then switches the file
 * to SWMR writing; from there on frames only extend datasets, and readers
 * opening the file with SWMR read see every committed frame while the
 * writer goes on.  A frame is committed in two flushes: its data, then the
 * per-frame index (particle count, step and time, contact offsets) that
 * makes it visible, so a reader never sees a frame whose data are not on
 * disk. */
#include <config.h>

#include "native.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "h5util.h"
#include "native_layout.h"
#include "tmpfiles.h"
#include "xdmf.h"
#include "outfile.h"
#include "parameters_h5.h"

#define PARTICLE_CHUNK_MAX 32768   /* rows of a per-particle chunk */
#define ROW_CHUNK 32768            /* most rows of a per-contact chunk */
#define ROW_CHUNK_MIN 1024         /* least rows of a per-contact chunk */
#define FRAME_CHUNK 1024           /* rows of a per-frame chunk */

/* A flat (CSR) table of contacts or wall contacts over all frames. */
typedef struct flat_table {
    const mimas_table_desc *desc;
    const char *group;
    hid_t step, time, offset;
    hsize_t rows;          /* rows committed so far over all frames */
    hsize_t staged_rows;   /* rows including the staged frames' */
    size_t ncols;
    native_col *cols;
} flat_table;

struct mimas_writer {
    char *path;            /* final name */
    char *open_path;       /* name being written (temporary in atomic mode) */
    int tmp_slot;          /* open_path in the temporary-file registry, or -1 */
    int unpublished;       /* not atomic: the final name holds a file of zero frames until
                              the first commit renames open_path over it */
    mimas_writer_options opt;
    hid_t file;
    size_t frames;
    int swmr;              /* the file is in SWMR writing mode */
    /* the frames staged and not yet committed (frames committed .. frames-1):
     * the per-frame index their commit writes */
    struct staged_frame {
        int64_t step, n;
        double time;
        hsize_t end[2];    /* rows of the contact tables after the frame */
    } *staged;
    size_t nstaged, staged_cap;
    /* frame layout, fixed by the first frame */
    int started;
    int triclinic;
    int periodic[3];
    unsigned p_present, c_present, w_present;
    int has_contacts, has_walls;
    /* particles */
    hid_t clock_step, clock_time;   /* shared by every time-dependent element */
    hid_t box_edges, box_lower, box_upper, count;
    hsize_t nmax;                   /* width of the per-particle datasets */
    size_t npcols;
    native_col *pcols;
    flat_table contacts, walls;
    /* format 1.1: the tube (fixed over the file) and the gas fields */
    mimas_tube tube;
    int has_gas;
    size_t gas_cells[3];
    double gas_origin[3], gas_spacing[3];
    hid_t gas_ds[3];                /* pressure, porosity, velocity */
    /* scratch for index -> id conversion */
    int64_t *ids;
    size_t ids_cap;
    /* per-frame observables (mimas_writer_observe) */
    struct observables {
        size_t n;
        char (*name)[64], (*unit)[24];
        double *value;
        hid_t *ds;            /* created with the first frame */
        int pending;          /* values set for the next frame */
    } obs;
    /* commits: frames 0 .. committed-1 are on disk for good */
    size_t committed;
    double staged_bytes;   /* data of the frames staged since the last commit */
    double last_commit;    /* monotonic seconds */
    double opened;         /* monotonic seconds when the file was opened */
};

/* A commit (flush) rewrites the metadata of every dataset, at the end of the file, and
 * the old copies stay behind (space is never reused): it is worth it once the frames
 * since the last one hold COMMIT_DATA_PER_METADATA times as much data (what commits
 * leave behind is then at most a quarter of the data), or once the commit interval
 * has passed: 1 s at first, growing with the time the file has been open (a twentieth
 * of it, at most COMMIT_SECONDS_MAX), so that a slow simulation of an hour commits
 * every 30 s instead of every second.  A crash loses at most the frames of the last
 * interval: the last 5 % of the run, at most 30 s. */
#define COMMIT_SECONDS_MIN 1.0
#define COMMIT_SECONDS_MAX 30.0
#define COMMIT_BYTES_PER_DATASET 4096.0
#define COMMIT_DATA_PER_METADATA 4.0

static double seconds_now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

void mimas_writer_options_default(mimas_writer_options *o)
{
    memset(o, 0, sizeof *o);
    o->deflate = 1;
}

static int h5fail(mimas_writer *w, mimas_error *err, const char *what)
{
    char text[256];
    h5_error_text(text, sizeof text);
    return mimas_error_set(err, MIMAS_EIO, "%s: cannot %s%s%s", w->path, what,
                           text[0] ? ": " : "", text);
}

/* Creates name with the H5MD and mimas headers, flushed; returns the open
 * file, or H5I_INVALID_HID with err set. */
static hid_t create_with_header(mimas_writer *w, const char *name, mimas_error *err)
{
    h5_quiet q;
    h5_quiet_begin(&q);
    hid_t fcpl = H5Pcreate(H5P_FILE_CREATE);
    /* allocate only at the end of the file: never reuse space a committed
     * frame may still point to (see the comment at the top) */
    H5Pset_file_space_strategy(fcpl, H5F_FSPACE_STRATEGY_NONE, 0, (hsize_t)1);
    hid_t fapl = H5Pcreate(H5P_FILE_ACCESS);
    H5Pset_fclose_degree(fapl, H5F_CLOSE_STRONG);
    /* SWMR needs the HDF5 1.10 file format (and no newer: 1.10 reads it) */
    H5Pset_libver_bounds(fapl, H5F_LIBVER_V110, H5F_LIBVER_V110);
    hid_t file = H5Fcreate(name, H5F_ACC_TRUNC, fcpl, fapl);
    H5Pclose(fapl);
    H5Pclose(fcpl);
    int rc = MIMAS_OK;
    if (file < 0) {
        rc = h5fail(w, err, "create the file");
    } else {
        /* H5MD metadata */
        int version[2] = {1, 1};
        int fmt[2] = {MIMAS_NATIVE_VERSION_MAJOR, MIMAS_NATIVE_VERSION_MINOR};
        const char *author = w->opt.author ? w->opt.author : getenv("USER");
        hid_t g = H5Gcreate2(file, "/h5md", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
        hid_t ga = H5Gcreate2(g, "author", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
        hid_t gc = H5Gcreate2(g, "creator", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
        hid_t gm = H5Gcreate2(file, NATIVE_MIMAS, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
        /* the H5MD units module: every unit attribute is an SI unit string */
        hid_t lcpl = H5Pcreate(H5P_LINK_CREATE);
        H5Pset_create_intermediate_group(lcpl, 1);
        hid_t gu = g < 0 ? H5I_INVALID_HID
                         : H5Gcreate2(g, "modules/units", lcpl, H5P_DEFAULT, H5P_DEFAULT);
        H5Pclose(lcpl);
        int units_version[2] = {1, 0};
        if (g < 0 || ga < 0 || gc < 0 || gm < 0 || gu < 0 ||
            h5_attr_write_ints(gu, "version", units_version, 2) ||
            h5_attr_write_vlstr(gu, "system", "SI") ||
            h5_attr_write_ints(g, "version", version, 2) ||
            h5_attr_write_vlstr(ga, "name", author && author[0] ? author : "unknown") ||
            h5_attr_write_vlstr(gc, "name", PACKAGE_NAME) ||
            h5_attr_write_vlstr(gc, "version", PACKAGE_VERSION) ||
            h5_attr_write_ints(gm, "format_version", fmt, 2) ||
            (w->opt.provenance && h5_attr_write_str(gm, "provenance", w->opt.provenance)))
            rc = h5fail(w, err, "write the file header");
        H5Gclose(gu);
        H5Gclose(gm);
        H5Gclose(gc);
        H5Gclose(ga);
        H5Gclose(g);
        if (!rc && H5Fflush(file, H5F_SCOPE_LOCAL) < 0)
            rc = h5fail(w, err, "flush");
    }
    h5_quiet_end(&q);
    if (rc && file >= 0) {
        H5Fclose(file);
        file = H5I_INVALID_HID;
    }
    return rc ? H5I_INVALID_HID : file;
}

int mimas_writer_open(mimas_writer **out, const char *path, const mimas_writer_options *o,
                      mimas_error *err)
{
    *out = NULL;
    /* the file is renamed into place: never onto a device or a pipe */
    if (mimas_output_check(path, err))
        return err ? err->code : MIMAS_EUSAGE;
    mimas_writer *w = calloc(1, sizeof *w);
    if (!w)
        return mimas_error_set(err, MIMAS_EIO, "%s: out of memory for the writer", path);
    w->tmp_slot = -1;
    w->opened = seconds_now();
    if (o)
        w->opt = *o;
    else
        mimas_writer_options_default(&w->opt);
    if (w->opt.deflate < 0 || w->opt.deflate > 9) {
        int level = w->opt.deflate;
        free(w);
        return mimas_error_set(err, MIMAS_EUSAGE, "compression level %d is not in 0..9", level);
    }
    w->path = strdup(path);
    size_t len = strlen(path) + 32;
    w->open_path = malloc(len);
    if (!w->path || !w->open_path) {
        free(w->path);
        free(w->open_path);
        free(w);
        return mimas_error_set(err, MIMAS_EIO, "out of memory for the native writer");
    }
    /* the file is written under a temporary name.  Without atomic, a file of
     * zero frames (the header alone, closed: clean) takes the final name at
     * once, and the file being written replaces it when its first frame is
     * committed (the file then in SWMR mode): the final name always holds a
     * file that reads, also after a kill at any moment */
    mimas_tmpfile_name(w->open_path, len, path);
    w->tmp_slot = mimas_tmpfile_add(w->open_path);
    int rc = MIMAS_OK;
    if (!w->opt.atomic) {
        hid_t zero = create_with_header(w, w->open_path, err);
        if (zero < 0)
            rc = err ? err->code : MIMAS_EIO;
        else if (H5Fclose(zero) < 0)
            rc = h5fail(w, err, "close the file");
        else if (rename(w->open_path, w->path) != 0)
            rc = mimas_error_set(err, MIMAS_EIO, "%s: cannot create it: %s", w->path,
                                 strerror(errno));
        else
            w->unpublished = 1;
    }
    if (!rc) {
        w->file = create_with_header(w, w->open_path, err);
        if (w->file < 0)
            rc = err ? err->code : MIMAS_EIO;
    }
    if (rc) {
        mimas_writer_abort(w);
        return rc;
    }
    *out = w;
    return MIMAS_OK;
}

size_t mimas_writer_frames(const mimas_writer *w)
{
    return w->frames;
}

/* ---- layout creation (first frame) ---- */

/* Groups remember the order their members were created in, so extra
 * columns read back in the order they were written. */
static hid_t make_group(hid_t file, const char *path)
{
    return h5_group_ordered(file, path);
}

/* A time-dependent H5MD element {step, time, value}: value grows along its
 * first n_unlimited dimensions; step and time are hard links to the shared
 * clock datasets (H5MD allows sharing them between elements). */
static hid_t make_element(mimas_writer *w, const char *path, hid_t type, int rank,
                          int n_unlimited, const hsize_t *dims, const hsize_t *chunk,
                          const void *fill, int deflate, const char *unit)
{
    hid_t g = make_group(w->file, path);
    if (g < 0)
        return H5I_INVALID_HID;
    hid_t ds = h5_create_growing(g, "value", type, rank, n_unlimited, dims, chunk, fill,
                                 deflate);
    if (ds >= 0 && unit && strcmp(unit, "1") != 0)
        h5_attr_write_vlstr(ds, "unit", unit);
    if (ds >= 0 && strcmp(path, NATIVE_CLOCK) != 0 &&
        (H5Lcreate_hard(w->clock_step, ".", g, "step", H5P_DEFAULT, H5P_DEFAULT) < 0 ||
         H5Lcreate_hard(w->clock_time, ".", g, "time", H5P_DEFAULT, H5P_DEFAULT) < 0)) {
        H5Dclose(ds);
        ds = H5I_INVALID_HID;
    }
    H5Gclose(g);
    return ds;
}

static int create_particles(mimas_writer *w, const mimas_frame *f, mimas_error *err)
{
    const mimas_particles *p = &f->particles;
    hsize_t one = FRAME_CHUNK;
    hid_t gp = make_group(w->file, NATIVE_PARTICLES); /* with creation order */
    if (gp >= 0)
        H5Gclose(gp);
    hid_t g = make_group(w->file, NATIVE_CLOCK);
    if (g < 0)
        return h5fail(w, err, "create " NATIVE_CLOCK);
    hsize_t d1 = 0;
    w->clock_step = h5_create_growing(g, "step", H5T_STD_I64LE, 1, 1, &d1, &one, NULL, 0);
    w->clock_time = h5_create_growing(g, "time", H5T_IEEE_F64LE, 1, 1, &d1, &one, NULL, 0);
    H5Gclose(g);
    if (w->clock_step < 0 || w->clock_time < 0)
        return h5fail(w, err, "create the step and time datasets");
    if (h5_attr_write_vlstr(w->clock_time, "unit", "s"))
        return h5fail(w, err, "write an attribute");

    w->pcols = calloc(mimas_particles_desc.ncolumns + p->n_extra, sizeof *w->pcols);
    if (!w->pcols)
        return mimas_error_set(err, MIMAS_EIO, "out of memory for the native writer");
    w->npcols = native_cols_of(p, &mimas_particles_desc, w->pcols);
    w->nmax = 0;
    hsize_t cn = p->n < 256 ? 256 : (p->n > PARTICLE_CHUNK_MAX ? PARTICLE_CHUNK_MAX : p->n);
    for (size_t c = 0; c < w->npcols; c++) {
        native_col *nc = &w->pcols[c];
        char path[256];
        snprintf(path, sizeof path, NATIVE_PARTICLES "/%s", nc->name);
        int rank = nc->ncomp == 1 ? 2 : 3;
        hsize_t dims[3] = {0, 0, (hsize_t)nc->ncomp};
        hsize_t chunk[3] = {1, cn, (hsize_t)nc->ncomp};
        /* H5MD: absent particles carry the fill value; id -1 marks a free slot */
        const int64_t fill_id = -1;
        const int32_t fill_i32 = nc->desc_col >= 0 && !strcmp(nc->name, "species") ? -1 : 0;
        const double fill_f = 0.0 / 0.0;
        const void *fill = nc->type == MIMAS_T_F64   ? (const void *)&fill_f
                           : nc->type == MIMAS_T_I64 ? (const void *)&fill_id
                                                     : (const void *)&fill_i32;
        const char *unit = native_col_unit(p, &mimas_particles_desc, nc);
        /* two unlimited dimensions: frames and particle slots */
        nc->ds = make_element(w, path, native_file_type(nc->type), rank, 2, dims, chunk, fill,
                              w->opt.deflate, unit);
        if (nc->ds < 0)
            return h5fail(w, err, "create a particle dataset");
    }

    /* box: H5MD dimension and boundary attributes and time-dependent edges;
     * the corners lo and hi as the mimas extension elements "lower" and
     * "upper" (so that they read back bit-identical, which lo + edge is not) */
    hid_t gb = make_group(w->file, NATIVE_BOX);
    if (gb < 0)
        return h5fail(w, err, "create the box group");
    const char *bnd[3];
    for (int d = 0; d < 3; d++)
        bnd[d] = w->periodic[d] ? "periodic" : "none";
    int three = 3;
    int rc = h5_attr_write_ints(gb, "dimension", &three, 1) |
             h5_attr_write_strs(gb, "boundary", bnd, 3);
    H5Gclose(gb);
    if (rc)
        return h5fail(w, err, "write the box attributes");
    hsize_t edims[3] = {0, 3, 3}, echunk[3] = {FRAME_CHUNK, 3, 3};
    w->box_edges = make_element(w, NATIVE_BOX "/edges", H5T_IEEE_F64LE, w->triclinic ? 3 : 2,
                                1, edims, echunk, NULL, 0, "m");
    w->box_lower = make_element(w, NATIVE_BOX "/lower", H5T_IEEE_F64LE, 2, 1, edims, echunk,
                                NULL, 0, "m");
    w->box_upper = make_element(w, NATIVE_BOX "/upper", H5T_IEEE_F64LE, 2, 1, edims, echunk,
                                NULL, 0, "m");
    hsize_t cdims[1] = {0}, cchunk[1] = {FRAME_CHUNK};
    w->count = make_element(w, NATIVE_COUNT, H5T_STD_I64LE, 1, 1, cdims, cchunk, NULL, 0, NULL);
    if (w->box_edges < 0 || w->box_lower < 0 || w->box_upper < 0 || w->count < 0)
        return h5fail(w, err, "create the box and count elements");
    return MIMAS_OK;
}

/* The tube as attributes of /parameters/tube; HDF5 attributes carry no
 * attributes of their own, so each unit is the attribute NAME_unit. */
static int create_tube(mimas_writer *w, const mimas_tube *t, mimas_error *err)
{
    hid_t g = make_group(w->file, NATIVE_TUBE);
    if (g < 0)
        return h5fail(w, err, "create " NATIVE_TUBE);
    int bad = h5_attr_write_doubles(g, "origin", t->origin, 3) ||
              h5_attr_write_str(g, "origin_unit", "m") ||
              h5_attr_write_doubles(g, "direction", t->direction, 3) ||
              h5_attr_write_str(g, "direction_unit", "1") ||
              h5_attr_write_double(g, "radius", t->radius) ||
              h5_attr_write_str(g, "radius_unit", "m") ||
              h5_attr_write_double(g, "length", t->length) ||
              h5_attr_write_str(g, "length_unit", "m");
    H5Gclose(g);
    return bad ? h5fail(w, err, "write the tube attributes") : MIMAS_OK;
}

static const char *const gas_names[3] = {"pressure", "porosity", "velocity"};
static const char *const gas_units[3] = {"Pa", "1", "m s-1"};

/* /fields/gas: the grid as attributes, each field an H5MD time-dependent
 * element of shape (frames, nz, ny, nx[, 3]) sharing the particles' clock */
static int create_gas(mimas_writer *w, const mimas_gas *gs, mimas_error *err)
{
    w->has_gas = 1;
    memcpy(w->gas_cells, gs->cells, sizeof w->gas_cells);
    memcpy(w->gas_origin, gs->origin, sizeof w->gas_origin);
    memcpy(w->gas_spacing, gs->spacing, sizeof w->gas_spacing);
    hid_t g = make_group(w->file, NATIVE_GAS);
    if (g < 0)
        return h5fail(w, err, "create " NATIVE_GAS);
    int64_t cells[3] = {(int64_t)gs->cells[0], (int64_t)gs->cells[1], (int64_t)gs->cells[2]};
    int bad = h5_attr_write_doubles(g, "origin", gs->origin, 3) ||
              h5_attr_write_str(g, "origin_unit", "m") ||
              h5_attr_write_doubles(g, "spacing", gs->spacing, 3) ||
              h5_attr_write_str(g, "spacing_unit", "m") || h5_attr_write_int64s(g, "cells", cells, 3);
    H5Gclose(g);
    if (bad)
        return h5fail(w, err, "write the gas grid attributes");
    for (int k = 0; k < 3; k++) {
        char path[128];
        snprintf(path, sizeof path, NATIVE_GAS "/%s", gas_names[k]);
        hsize_t dims[5] = {0, gs->cells[2], gs->cells[1], gs->cells[0], 3};
        hsize_t chunk[5] = {1, gs->cells[2], gs->cells[1], gs->cells[0], 3};
        w->gas_ds[k] = make_element(w, path, H5T_IEEE_F64LE, k == 2 ? 5 : 4, 1, dims, chunk, NULL,
                                    w->opt.deflate, gas_units[k]);
        if (w->gas_ds[k] < 0)
            return h5fail(w, err, "create the gas fields");
    }
    return MIMAS_OK;
}

/* Rows per chunk of a flat table whose first frame has n rows.  A commit rewrites the
 * table's last, partly filled chunk (compressed, so elsewhere in the file), and space is
 * never reused (see the top): each commit leaves about half a chunk behind.  An eighth
 * of a frame's rows per chunk keeps that near 6 % of the data for one commit per frame
 * (a slow simulation), against several times the data with chunks much larger than a
 * frame; ROW_CHUNK_MIN keeps chunks of small frames worth compressing. */
static hsize_t flat_chunk_rows(size_t n)
{
    size_t rows = n / 8;
    return rows < ROW_CHUNK_MIN ? ROW_CHUNK_MIN : (rows > ROW_CHUNK ? ROW_CHUNK : rows);
}

static int create_flat(mimas_writer *w, flat_table *t, const void *tab, mimas_error *err)
{
    hid_t g = make_group(w->file, t->group);
    if (g < 0)
        return h5fail(w, err, "create a contact group");
    hsize_t zero = 0, fchunk = FRAME_CHUNK;
    t->step = h5_create_growing(g, "step", H5T_STD_I64LE, 1, 1, &zero, &fchunk, NULL, 0);
    t->time = h5_create_growing(g, "time", H5T_IEEE_F64LE, 1, 1, &zero, &fchunk, NULL, 0);
    t->offset = h5_create_growing(g, "offset", H5T_STD_I64LE, 1, 1, &zero, &fchunk, NULL, 0);
    if (t->step < 0 || t->time < 0 || t->offset < 0) {
        H5Gclose(g);
        return h5fail(w, err, "create the contact index datasets");
    }
    /* offset[k] is the first row of frame k; offset has frames + 1 entries */
    hsize_t one = 1, start = 0;
    int64_t first = 0;
    H5Dset_extent(t->offset, &one);
    hid_t fs = H5Dget_space(t->offset);
    hid_t ms = H5Screate_simple(1, &one, NULL);
    H5Sselect_hyperslab(fs, H5S_SELECT_SET, &start, NULL, &one, NULL);
    herr_t hr = H5Dwrite(t->offset, H5T_NATIVE_INT64, ms, fs, H5P_DEFAULT, &first);
    H5Sclose(ms);
    H5Sclose(fs);
    h5_attr_write_vlstr(t->time, "unit", "s");
    if (hr < 0) {
        H5Gclose(g);
        return h5fail(w, err, "write the contact offsets");
    }
    size_t n_extra = *(const size_t *)((const char *)tab + t->desc->off_n_extra);
    t->cols = calloc(t->desc->ncolumns + n_extra, sizeof *t->cols);
    if (!t->cols) {
        H5Gclose(g);
        return mimas_error_set(err, MIMAS_EIO, "out of memory for the native writer");
    }
    t->ncols = native_cols_of(tab, t->desc, t->cols);
    hsize_t rows = flat_chunk_rows(*(const size_t *)((const char *)tab + t->desc->off_n));
    for (size_t c = 0; c < t->ncols; c++) {
        native_col *nc = &t->cols[c];
        int rank = nc->ncomp == 1 ? 1 : 2;
        hsize_t dims[2] = {0, (hsize_t)nc->ncomp}, chunk[2] = {rows, (hsize_t)nc->ncomp};
        nc->ds = h5_create_growing(g, nc->name, native_file_type(nc->type), rank, 1, dims,
                                   chunk, NULL, w->opt.deflate);
        if (nc->ds < 0) {
            H5Gclose(g);
            return h5fail(w, err, "create a contact dataset");
        }
        const char *unit = native_col_unit(tab, t->desc, nc);
        if (unit && strcmp(unit, "1") != 0)
            h5_attr_write_vlstr(nc->ds, "unit", unit);
        if (nc->type == MIMAS_T_INDEX)
            h5_attr_write_str(nc->ds, "meaning", "particle id (the id element of " NATIVE_PARTICLES ")");
    }
    H5Gclose(g);
    return MIMAS_OK;
}

/* ---- consistency of later frames with the first ---- */

static int extras_match(const void *tab, const mimas_table_desc *d, const native_col *cols,
                        size_t ncols, const char *what, mimas_error *err)
{
    const size_t n_extra = *(const size_t *)((const char *)tab + d->off_n_extra);
    const mimas_extra *extra = *(mimas_extra *const *)((const char *)tab + d->off_extra);
    size_t expected = 0;
    for (size_t c = 0; c < ncols; c++) {
        if (cols[c].extra < 0)
            continue;
        expected++;
        if ((size_t)cols[c].extra >= n_extra ||
            strcmp(extra[cols[c].extra].name, cols[c].name) != 0 ||
            extra[cols[c].extra].ncomp != cols[c].ncomp)
            return mimas_error_set(err, MIMAS_EDATA,
                                   "%s column '%s' of the first frame is missing", what,
                                   cols[c].name);
    }
    if (expected != n_extra)
        return mimas_error_set(err, MIMAS_EDATA, "%s have extra columns the first frame had not",
                               what);
    return MIMAS_OK;
}

static int same_tube(const mimas_tube *a, const mimas_tube *b)
{
    return memcmp(a->origin, b->origin, sizeof a->origin) == 0 &&
           memcmp(a->direction, b->direction, sizeof a->direction) == 0 &&
           a->radius == b->radius && a->length == b->length;
}

static int check_same_layout(mimas_writer *w, const mimas_frame *f, mimas_error *err)
{
    int rc = MIMAS_OK;
    if (mimas_table_present(&f->particles, &mimas_particles_desc) != w->p_present)
        rc = mimas_error_set(err, MIMAS_EDATA,
                             "particles carry other quantities than in the first frame");
    else if (f->has_contacts != w->has_contacts || f->has_walls != w->has_walls)
        rc = mimas_error_set(err, MIMAS_EDATA,
                             "contact data present in some frames and absent in others");
    else if (w->has_contacts &&
             mimas_table_present(&f->contacts, &mimas_contacts_desc) != w->c_present)
        rc = mimas_error_set(err, MIMAS_EDATA,
                             "contacts carry other quantities than in the first frame");
    else if (w->has_walls && mimas_table_present(&f->walls, &mimas_walls_desc) != w->w_present)
        rc = mimas_error_set(err, MIMAS_EDATA,
                             "wall contacts carry other quantities than in the first frame");
    else if (!w->triclinic && mimas_box_is_triclinic(&f->box))
        rc = mimas_error_set(err, MIMAS_EDATA,
                             "the box becomes triclinic after an orthogonal first frame "
                             "(write with the triclinic option)");
    else if (memcmp(w->periodic, f->box.periodic, sizeof w->periodic) != 0)
        rc = mimas_error_set(err, MIMAS_EDATA, "the periodic boundaries change between frames");
    else if (f->tube.present != w->tube.present || (w->tube.present && !same_tube(&f->tube, &w->tube)))
        rc = mimas_error_set(err, MIMAS_EDATA, "the tube changes between frames");
    else if (f->gas.present != w->has_gas ||
             (w->has_gas && (memcmp(f->gas.cells, w->gas_cells, sizeof w->gas_cells) != 0 ||
                             memcmp(f->gas.origin, w->gas_origin, sizeof w->gas_origin) != 0 ||
                             memcmp(f->gas.spacing, w->gas_spacing, sizeof w->gas_spacing) != 0)))
        rc = mimas_error_set(err, MIMAS_EDATA, "the gas grid changes between frames");
    if (!rc)
        rc = extras_match(&f->particles, &mimas_particles_desc, w->pcols, w->npcols,
                          "particles", err);
    if (!rc && w->has_contacts)
        rc = extras_match(&f->contacts, &mimas_contacts_desc, w->contacts.cols,
                          w->contacts.ncols, "contacts", err);
    if (!rc && w->has_walls)
        rc = extras_match(&f->walls, &mimas_walls_desc, w->walls.cols, w->walls.ncols,
                          "wall contacts", err);
    return rc;
}

static int start_layout(mimas_writer *w, const mimas_frame *f, mimas_error *err)
{
    w->triclinic = w->opt.triclinic || mimas_box_is_triclinic(&f->box);
    memcpy(w->periodic, f->box.periodic, sizeof w->periodic);
    w->p_present = mimas_table_present(&f->particles, &mimas_particles_desc);
    w->has_contacts = f->has_contacts;
    w->has_walls = f->has_walls;
    w->c_present = mimas_table_present(&f->contacts, &mimas_contacts_desc);
    w->w_present = mimas_table_present(&f->walls, &mimas_walls_desc);
    w->contacts.desc = &mimas_contacts_desc;
    w->contacts.group = NATIVE_CONTACTS;
    w->walls.desc = &mimas_walls_desc;
    w->walls.group = NATIVE_WALLS;
    int rc = create_particles(w, f, err);
    if (!rc && f->tube.present) {
        w->tube = f->tube;
        rc = create_tube(w, &f->tube, err);
    }
    if (!rc && f->gas.present)
        rc = create_gas(w, &f->gas, err);
    if (!rc && w->has_contacts)
        rc = create_flat(w, &w->contacts, &f->contacts, err);
    if (!rc && w->has_walls)
        rc = create_flat(w, &w->walls, &f->walls, err);
    w->started = 1;
    return rc;
}

/* ---- appending ---- */

/* Writes `rows` rows of ncomp values at (row0[, col0]) of a dataset whose
 * dimension 0 (and 1 for rank-3 particle data) has already been extended. */
static herr_t write_block(hid_t ds, hid_t memtype, int rank, const hsize_t *start,
                          const hsize_t *count, const void *buf)
{
    hid_t fs = H5Dget_space(ds);
    hsize_t mcount = 1;
    for (int d = 0; d < rank; d++)
        mcount *= count[d];
    hid_t ms = H5Screate_simple(1, &mcount, NULL);
    herr_t rc = H5Sselect_hyperslab(fs, H5S_SELECT_SET, start, NULL, count, NULL);
    if (rc >= 0 && mcount > 0)
        rc = H5Dwrite(ds, memtype, ms, fs, H5P_DEFAULT, buf);
    H5Sclose(ms);
    H5Sclose(fs);
    return rc;
}

static herr_t append_scalar(hid_t ds, hsize_t at, hid_t memtype, const void *value)
{
    hsize_t n = at + 1, count = 1;
    if (H5Dset_extent(ds, &n) < 0)
        return -1;
    return write_block(ds, memtype, 1, &at, &count, value);
}

/* Converts index columns to particle ids in the scratch buffer. */
static int index_to_ids(mimas_writer *w, const size_t *idx, size_t n, const mimas_particles *p,
                        const char *what, mimas_error *err)
{
    if (n > w->ids_cap) {
        int64_t *b = realloc(w->ids, n * sizeof *b);
        if (!b)
            return mimas_error_set(err, MIMAS_EIO, "out of memory for the native writer");
        w->ids = b;
        w->ids_cap = n;
    }
    for (size_t k = 0; k < n; k++) {
        if (idx[k] >= p->n)
            return mimas_error_set(err, MIMAS_EDATA,
                                   "%s row %zu refers to particle %zu of a frame of %zu", what,
                                   k, idx[k], p->n);
        w->ids[k] = p->id[idx[k]];
    }
    return MIMAS_OK;
}

static int stage_particles(mimas_writer *w, const mimas_frame *f, mimas_error *err)
{
    const mimas_particles *p = &f->particles;
    hsize_t k = w->frames;
    if (p->n > w->nmax)
        w->nmax = p->n;
    for (size_t c = 0; c < w->npcols; c++) {
        native_col *nc = &w->pcols[c];
        int rank = nc->ncomp == 1 ? 2 : 3;
        hsize_t ext[3] = {k + 1, w->nmax, (hsize_t)nc->ncomp};
        hsize_t start[3] = {k, 0, 0}, count[3] = {1, p->n, (hsize_t)nc->ncomp};
        if (H5Dset_extent(nc->ds, ext) < 0 ||
            write_block(nc->ds, native_mem_type(nc->type), rank, start, count,
                        native_col_data(p, &mimas_particles_desc, nc)) < 0)
            return h5fail(w, err, "write particle data");
    }
    double edges[3][3];
    mimas_box_edges(&f->box, edges);
    double diag[3] = {edges[0][0], edges[1][1], edges[2][2]};
    hsize_t ext[3] = {k + 1, 3, 3}, start[3] = {k, 0, 0}, count[3] = {1, 3, 3};
    int64_t n = (int64_t)p->n;
    if (H5Dset_extent(w->box_edges, ext) < 0 ||
        write_block(w->box_edges, H5T_NATIVE_DOUBLE, w->triclinic ? 3 : 2, start, count,
                    w->triclinic ? (const void *)edges : (const void *)diag) < 0 ||
        H5Dset_extent(w->box_lower, ext) < 0 ||
        write_block(w->box_lower, H5T_NATIVE_DOUBLE, 2, start, count, f->box.lo) < 0 ||
        H5Dset_extent(w->box_upper, ext) < 0 ||
        write_block(w->box_upper, H5T_NATIVE_DOUBLE, 2, start, count, f->box.hi) < 0)
        return h5fail(w, err, "write the box");
    if (w->nstaged == w->staged_cap) {
        size_t cap = w->staged_cap ? 2 * w->staged_cap : 16;
        struct staged_frame *g = realloc(w->staged, cap * sizeof *g);
        if (!g)
            return mimas_error_set(err, MIMAS_EIO, "%s: out of memory for the frame index",
                                   w->path);
        w->staged = g;
        w->staged_cap = cap;
    }
    w->staged[w->nstaged] = (struct staged_frame){f->step, n, f->time, {0, 0}};
    for (int g = 0; g < 3 && w->has_gas; g++) {
        const size_t *c = w->gas_cells;
        hsize_t gext[5] = {k + 1, c[2], c[1], c[0], 3}, gstart[5] = {k, 0, 0, 0, 0};
        hsize_t gcount[5] = {1, c[2], c[1], c[0], 3};
        const void *data = g == 0 ? (const void *)f->gas.pressure
                           : g == 1 ? (const void *)f->gas.porosity
                                    : (const void *)f->gas.velocity;
        int rank = g == 2 ? 5 : 4;
        if (H5Dset_extent(w->gas_ds[g], gext) < 0 ||
            write_block(w->gas_ds[g], H5T_NATIVE_DOUBLE, rank, gstart, gcount, data) < 0)
            return h5fail(w, err, "write the gas fields");
    }
    return MIMAS_OK;
}

static int stage_flat(mimas_writer *w, flat_table *t, const void *tab, const mimas_frame *f,
                      mimas_error *err)
{
    size_t n = mimas_table_n(tab, t->desc);
    hsize_t row0 = t->staged_rows, end = t->staged_rows + n;
    for (size_t c = 0; c < t->ncols; c++) {
        native_col *nc = &t->cols[c];
        int rank = nc->ncomp == 1 ? 1 : 2;
        hsize_t ext[2] = {end, (hsize_t)nc->ncomp};
        hsize_t start[2] = {row0, 0}, count[2] = {n, (hsize_t)nc->ncomp};
        const void *data = native_col_data(tab, t->desc, nc);
        if (nc->type == MIMAS_T_INDEX) {
            int rc = index_to_ids(w, data, n, &f->particles, t->desc->name, err);
            if (rc)
                return rc;
            data = w->ids;
        }
        if (H5Dset_extent(nc->ds, ext) < 0 ||
            write_block(nc->ds, native_mem_type(nc->type), rank, start, count, data) < 0)
            return h5fail(w, err, "write contact data");
    }
    t->staged_rows = end;
    return MIMAS_OK;
}

/* ---- run parameters and per-frame observables ---- */

int mimas_writer_parameters(mimas_writer *w, const char *group, const mimas_parameters *ps,
                            mimas_error *err)
{
    /* attributes cannot be created once the first commit switched to SWMR */
    if (w->frames > 0)
        return mimas_error_set(err, MIMAS_EUSAGE, "%s: the run parameters must be written "
                               "before the first frame", w->path);
    h5_quiet q;
    h5_quiet_begin(&q);
    int rc = parameters_write_h5(w->file, group, ps) ? h5fail(w, err, "write the parameters")
                                                     : MIMAS_OK;
    if (!rc && H5Fflush(w->file, H5F_SCOPE_LOCAL) < 0)
        rc = h5fail(w, err, "flush");
    h5_quiet_end(&q);
    return rc;
}

int mimas_writer_observe(mimas_writer *w, const mimas_observable *obs, size_t n,
                         mimas_error *err)
{
    struct observables *o = &w->obs;
    if (!o->name && w->frames == 0) {
        /* the first frame fixes the names */
        o->name = calloc(n ? n : 1, sizeof *o->name);
        o->unit = calloc(n ? n : 1, sizeof *o->unit);
        o->value = calloc(n ? n : 1, sizeof *o->value);
        o->ds = calloc(n ? n : 1, sizeof *o->ds);
        if (!o->name || !o->unit || !o->value || !o->ds)
            return mimas_error_set(err, MIMAS_EIO, "out of memory");
        for (size_t k = 0; k < n; k++)
            o->ds[k] = H5I_INVALID_HID;
        for (size_t k = 0; k < n; k++) {
            if (strlen(obs[k].name) >= sizeof o->name[0] || strchr(obs[k].name, '/') ||
                (obs[k].unit && strlen(obs[k].unit) >= sizeof o->unit[0]))
                return mimas_error_set(err, MIMAS_EUSAGE, "%s: bad observable name '%s'",
                                       w->path, obs[k].name);
            snprintf(o->name[k], sizeof o->name[0], "%s", obs[k].name);
            snprintf(o->unit[k], sizeof o->unit[0], "%s", obs[k].unit ? obs[k].unit : "");
        }
        o->n = n;
    }
    /* the same names as the first frame's, in any order */
    int same = o->name && n == o->n;
    for (size_t k = 0; same && k < n; k++) {
        size_t m = 0;
        while (m < o->n && strcmp(obs[k].name, o->name[m]))
            m++;
        same = m < o->n;
        if (same)
            o->value[m] = obs[k].value;
    }
    if (!same)
        return mimas_error_set(err, MIMAS_EDATA, "%s: frame %zu: other observables than the "
                               "first frame's", w->path, w->frames);
    o->pending = 1;
    return MIMAS_OK;
}

/* Appends the pending observables at the current frame (creating their
 * elements, which share the clock, with the first frame). */
static int stage_observables(mimas_writer *w, mimas_error *err)
{
    struct observables *o = &w->obs;
    if (!o->name)
        return MIMAS_OK;
    if (!o->pending)
        return mimas_error_set(err, MIMAS_EDATA, "frame without the observables the first "
                               "frame had");
    hsize_t dims[1] = {0}, chunk[1] = {FRAME_CHUNK};
    for (size_t k = 0; k < o->n; k++) {
        if (o->ds[k] < 0) {
            char path[128];
            snprintf(path, sizeof path, NATIVE_OBSERVABLES "/%s", o->name[k]);
            o->ds[k] = make_element(w, path, H5T_IEEE_F64LE, 1, 1, dims, chunk, NULL, 0,
                                    o->unit[k][0] ? o->unit[k] : NULL);
            if (o->ds[k] < 0)
                return h5fail(w, err, "create an observable");
        }
        if (append_scalar(o->ds[k], w->frames, H5T_NATIVE_DOUBLE, &o->value[k]) < 0)
            return h5fail(w, err, "write an observable");
    }
    o->pending = 0;
    return MIMAS_OK;
}

static void release_observables(mimas_writer *w)
{
    struct observables *o = &w->obs;
    for (size_t k = 0; o->ds && k < o->n; k++)
        if (o->ds[k] >= 0)
            H5Dclose(o->ds[k]);
    free(o->name);
    free(o->unit);
    free(o->value);
    free(o->ds);
    memset(o, 0, sizeof *o);
}

/* The per-frame index of a flat table for staged frame sf (frame k): what
 * makes its rows visible. */
static int index_flat(mimas_writer *w, flat_table *t, hsize_t k, const struct staged_frame *sf,
                      int which, mimas_error *err)
{
    int64_t off = (int64_t)sf->end[which];
    if (append_scalar(t->offset, k + 1, H5T_NATIVE_INT64, &off) < 0 ||
        append_scalar(t->step, k, H5T_NATIVE_INT64, &sf->step) < 0 ||
        append_scalar(t->time, k, H5T_NATIVE_DOUBLE, &sf->time) < 0)
        return h5fail(w, err, "write the contact index");
    t->rows = sf->end[which];
    return MIMAS_OK;
}

/* The particle count, step and time of staged frame sf (frame k), then those
 * of the contact tables. */
static int write_index(mimas_writer *w, hsize_t k, const struct staged_frame *sf,
                       mimas_error *err)
{
    if (append_scalar(w->count, k, H5T_NATIVE_INT64, &sf->n) < 0 ||
        append_scalar(w->clock_step, k, H5T_NATIVE_INT64, &sf->step) < 0 ||
        append_scalar(w->clock_time, k, H5T_NATIVE_DOUBLE, &sf->time) < 0)
        return h5fail(w, err, "write the particle count, step and time");
    int rc = w->has_contacts ? index_flat(w, &w->contacts, k, sf, 0, err) : MIMAS_OK;
    if (!rc && w->has_walls)
        rc = index_flat(w, &w->walls, k, sf, 1, err);
    return rc;
}

/* Everything of an append except the commit (the flushes and the per-frame
 * index); split out so that the crash-recovery test can stop a writer
 * between the two. */
int mimas_writer_stage(mimas_writer *w, const mimas_frame *f, mimas_error *err);
int mimas_writer_commit(mimas_writer *w, mimas_error *err);

int mimas_writer_stage(mimas_writer *w, const mimas_frame *f, mimas_error *err)
{
    int rc = mimas_table_require(&f->particles, &mimas_particles_desc,
                                 mimas_particles_desc.required, err);
    if (rc)
        return mimas_error_prefix(err, "%s", w->path);
    h5_quiet q;
    h5_quiet_begin(&q);
    rc = w->started ? check_same_layout(w, f, err) : start_layout(w, f, err);
    if (!rc)
        rc = stage_observables(w, err);
    if (!rc)
        rc = stage_particles(w, f, err);
    if (!rc && w->has_contacts)
        rc = stage_flat(w, &w->contacts, &f->contacts, f, err);
    if (!rc && w->has_walls)
        rc = stage_flat(w, &w->walls, &f->walls, f, err);
    h5_quiet_end(&q);
    if (rc && rc != MIMAS_EIO)
        mimas_error_prefix(err, "%s: frame %zu (step %lld)", w->path, w->frames,
                           (long long)f->step);
    if (!rc) {
        w->staged[w->nstaged].end[0] = w->contacts.staged_rows;
        w->staged[w->nstaged].end[1] = w->walls.staged_rows;
        w->nstaged++;
        w->frames++;
        w->staged_bytes += 24.0 * ((double)f->particles.n * (double)w->npcols +
                                   (double)f->contacts.n * (double)w->contacts.ncols +
                                   (double)f->walls.n * (double)w->walls.ncols);
    }
    return rc;
}

/* The file being written takes the final name (over the file of zero frames). */
static int publish(mimas_writer *w, mimas_error *err)
{
    if (rename(w->open_path, w->path) != 0)
        return mimas_error_set(err, MIMAS_EIO, "%s: cannot rename the file into place: %s",
                               w->path, strerror(errno));
    snprintf(w->open_path, strlen(w->path) + 32, "%s", w->path);
    mimas_tmpfile_forget(w->tmp_slot);
    w->tmp_slot = -1;
    w->unpublished = 0;
    return MIMAS_OK;
}

int mimas_writer_commit(mimas_writer *w, mimas_error *err)
{
    h5_quiet q;
    h5_quiet_begin(&q);
    /* the data first, then the index that makes the frame visible */
    int rc = H5Fflush(w->file, H5F_SCOPE_LOCAL) < 0 ? h5fail(w, err, "flush") : MIMAS_OK;
    for (size_t j = 0; !rc && j < w->nstaged; j++)
        rc = write_index(w, (hsize_t)(w->committed + j), &w->staged[j], err);
    if (!rc && H5Fflush(w->file, H5F_SCOPE_LOCAL) < 0)
        rc = h5fail(w, err, "flush");
    /* every object exists now: from here on readers may follow the file */
    if (!rc && !w->swmr) {
        if (H5Fstart_swmr_write(w->file) < 0)
            rc = h5fail(w, err, "switch to single-writer/multiple-reader mode");
        else
            w->swmr = 1;
    }
    h5_quiet_end(&q);
    if (!rc && w->unpublished)
        rc = publish(w, err);
    if (!rc) {
        w->committed = w->frames;
        w->nstaged = 0;
        w->staged_bytes = 0;
        w->last_commit = seconds_now();
    }
    return rc;
}

int mimas_writer_flush(mimas_writer *w, mimas_error *err)
{
    return w->committed < w->frames ? mimas_writer_commit(w, err) : MIMAS_OK;
}

int mimas_writer_append(mimas_writer *w, const mimas_frame *f, mimas_error *err)
{
    int rc = mimas_writer_stage(w, f, err);
    if (rc)
        return rc;
    double datasets = (double)(w->npcols + 6 + (w->has_contacts ? w->contacts.ncols + 3 : 0) +
                               (w->has_walls ? w->walls.ncols + 3 : 0));
    double now = seconds_now(), interval = (now - w->opened) / 20.0;
    interval = interval < COMMIT_SECONDS_MIN
                   ? COMMIT_SECONDS_MIN
                   : (interval > COMMIT_SECONDS_MAX ? COMMIT_SECONDS_MAX : interval);
    if (w->committed == 0 ||
        w->staged_bytes >= COMMIT_DATA_PER_METADATA * COMMIT_BYTES_PER_DATASET * datasets ||
        now - w->last_commit >= interval)
        rc = mimas_writer_commit(w, err);
    return rc;
}

/* ---- closing ---- */

static void close_cols(native_col *cols, size_t n)
{
    for (size_t c = 0; c < n; c++)
        if (cols[c].ds > 0)
            H5Dclose(cols[c].ds);
    free(cols);
}

static void close_flat(flat_table *t)
{
    hid_t ids[3] = {t->step, t->time, t->offset};
    for (int k = 0; k < 3; k++)
        if (ids[k] > 0)
            H5Dclose(ids[k]);
    close_cols(t->cols, t->ncols);
}

static herr_t release(mimas_writer *w)
{
    close_cols(w->pcols, w->npcols);
    close_flat(&w->contacts);
    close_flat(&w->walls);
    hid_t ids[9] = {w->clock_step, w->clock_time, w->box_edges, w->box_lower, w->box_upper,
                    w->count, w->gas_ds[0], w->gas_ds[1], w->gas_ds[2]};
    for (int k = 0; k < 9; k++)
        if (ids[k] > 0)
            H5Dclose(ids[k]);
    release_observables(w);
    herr_t rc = w->file > 0 ? H5Fclose(w->file) : 0;
    free(w->ids);
    free(w->staged);
    return rc;
}

int mimas_writer_close(mimas_writer *w, mimas_error *err)
{
    /* the frames staged since the last commit get their index */
    int rc = w->started ? mimas_writer_flush(w, err) : MIMAS_OK;
    h5_quiet q;
    h5_quiet_begin(&q);
    if (release(w) < 0 && !rc)
        rc = h5fail(w, err, "close the file");
    h5_quiet_end(&q);
    if (!rc && (w->opt.atomic || w->unpublished) && rename(w->open_path, w->path) != 0)
        rc = mimas_error_set(err, MIMAS_EIO, "%s: cannot rename the finished file into place",
                             w->path);
    if (rc)
        remove(w->open_path);
    mimas_tmpfile_forget(w->tmp_slot);
    if (!rc && w->opt.xdmf) {
        /* the sidecar describes the finished file (a failure leaves no sidecar,
         * and the trajectory itself complete) */
        char sidecar[4200];
        mimas_xdmf_path(w->path, NULL, sidecar, sizeof sidecar);
        rc = mimas_xdmf_trajectory(w->path, sidecar, err);
    }
    free(w->path);
    free(w->open_path);
    free(w);
    return rc;
}

void mimas_writer_abort(mimas_writer *w)
{
    if (!w)
        return;
    h5_quiet q;
    h5_quiet_begin(&q);
    release(w);
    h5_quiet_end(&q);
    remove(w->open_path);
    if (w->unpublished)
        remove(w->path); /* the file of zero frames it put there */
    mimas_tmpfile_forget(w->tmp_slot);
    free(w->path);
    free(w->open_path);
    free(w);
}
