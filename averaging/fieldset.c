#include <config.h>

#include "fieldset.h"

#include <hdf5.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fields.h"
#include "big_alloc.h"
#include "h5util.h"
#include "output_h5.h"
#include "parameters_h5.h"

struct mimas_fieldset {
    char name[4096];
    mimas_fieldset_grid grid;
    double *centre[3];
    hid_t file;                 /* a field file, or -1 */
    double *mean, *sd, *count;  /* an average in memory: cells x mimas_fields_count() */
    int cyl;
    mimas_parameters params;
};

static const char *const coord_names[2][3] = {{"x", "y", "z"}, {"r", "phi", "z"}};

static mimas_fieldset *fieldset_new(const char *name)
{
    mimas_fieldset *fs = calloc(1, sizeof *fs);
    if (!fs)
        return NULL;
    snprintf(fs->name, sizeof fs->name, "%s", name);
    fs->file = H5I_INVALID_HID;
    return fs;
}

void mimas_fieldset_close(mimas_fieldset *fs)
{
    if (!fs)
        return;
    if (fs->file >= 0) {
        h5_quiet q;
        h5_quiet_begin(&q);
        H5Fclose(fs->file);
        h5_quiet_end(&q);
    }
    for (int d = 0; d < 3; d++)
        free(fs->centre[d]);
    mimas_big_free(fs->mean);
    mimas_big_free(fs->sd);
    mimas_big_free(fs->count);
    mimas_parameters_free(&fs->params);
    free(fs);
}

const char *mimas_fieldset_name(const mimas_fieldset *fs)
{
    return fs->name;
}

const mimas_fieldset_grid *mimas_fieldset_grid_of(const mimas_fieldset *fs)
{
    return &fs->grid;
}

const mimas_parameters *mimas_fieldset_parameters(const mimas_fieldset *fs)
{
    return &fs->params;
}

int mimas_fieldset_set_parameters(mimas_fieldset *fs, const mimas_parameters *ps,
                                  mimas_error *err)
{
    return mimas_parameters_copy(&fs->params, ps, err);
}

/* ---- from an average in memory ---- */

int mimas_fieldset_from_average(mimas_fieldset **out, const mimas_average *avg, const char *name,
                                mimas_error *err)
{
    *out = NULL;
    mimas_fieldset *fs = fieldset_new(name);
    if (!fs)
        return mimas_error_set(err, MIMAS_EIO, "out of memory for the field file");
    const mimas_grid *g = mimas_average_grid(avg);
    int none = mimas_average_grid_none(avg);
    fs->cyl = !none && g->kind == MIMAS_GRID_CYLINDRICAL;
    fs->grid.kind = none ? MIMAS_FIELDSET_NONE
                         : fs->cyl ? MIMAS_FIELDSET_CYLINDRICAL : MIMAS_FIELDSET_CARTESIAN;
    fs->grid.cells = none ? 1 : mimas_grid_cells(g);
    fs->grid.frames = mimas_average_frames(avg);
    int ok = 1;
    for (int d = 0; d < 3; d++) {
        fs->grid.n[d] = none ? 1 : g->n[d];
        fs->grid.gridded[d] = !none && g->gridded[d];
        fs->centre[d] = malloc((size_t)fs->grid.n[d] * sizeof *fs->centre[d]);
        ok &= fs->centre[d] != NULL;
        for (int k = 0; ok && k < fs->grid.n[d]; k++)
            fs->centre[d][k] = g->lo[d] + (g->hi[d] - g->lo[d]) * (k + 0.5) / g->n[d];
        fs->grid.centre[d] = fs->centre[d];
    }
    size_t all = fs->grid.cells * mimas_fields_count();
    fs->mean = mimas_big_calloc(all, sizeof *fs->mean);
    fs->sd = mimas_big_calloc(all, sizeof *fs->sd);
    fs->count = mimas_big_calloc(all, sizeof *fs->count);
    if (!ok || !fs->mean || !fs->sd || !fs->count ||
        mimas_average_fields(avg, fs->mean, fs->sd, fs->count)) {
        mimas_fieldset_close(fs);
        return mimas_error_set(err, MIMAS_EIO, "out of memory for the field file");
    }
    *out = fs;
    return MIMAS_OK;
}

/* The column of a field in the average's table, or -1. */
static long column(const mimas_fieldset *fs, const char *field)
{
    size_t k;
    return mimas_field_find(field, fs->cyl, &k) ? (long)k : -1;
}

/* ---- from a field file ---- */

int mimas_fieldset_probe(const char *path)
{
    h5_quiet q;
    h5_quiet_begin(&q);
    int yes = 0;
    FILE *fp = fopen(path, "rb");
    if (fp) {
        fclose(fp);
        if (H5Fis_hdf5(path) > 0) {
            hid_t f = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
            if (f >= 0) {
                yes = H5Lexists(f, "/fields", H5P_DEFAULT) > 0 &&
                      H5Lexists(f, "/grid", H5P_DEFAULT) > 0;
                H5Fclose(f);
            }
        }
    }
    h5_quiet_end(&q);
    return yes;
}

/* A dataset of exactly n doubles, read whole. */
static int read_doubles(hid_t loc, const char *name, double *buf, size_t n)
{
    if (H5Lexists(loc, name, H5P_DEFAULT) <= 0)
        return -1;
    hid_t ds = H5Dopen2(loc, name, H5P_DEFAULT);
    if (ds < 0)
        return -1;
    hid_t s = H5Dget_space(ds);
    hssize_t count = H5Sget_simple_extent_npoints(s);
    H5Sclose(s);
    int rc = count != (hssize_t)n ||
             H5Dread(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, buf) < 0;
    H5Dclose(ds);
    return rc ? -1 : 0;
}

static int read_grid(mimas_fieldset *fs, mimas_error *err)
{
    hid_t g = H5Gopen2(fs->file, "/grid", H5P_DEFAULT);
    if (g < 0)
        return mimas_error_set(err, MIMAS_EDATA, "%s: no /grid group", fs->name);
    char kind[32];
    int n[3], rc = MIMAS_OK;
    if (h5_attr_read_str(g, "kind", kind, sizeof kind) || h5_attr_read_ints(g, "cells", n, 3) != 3)
        rc = mimas_error_set(err, MIMAS_EDATA, "%s: /grid lacks its kind or cells attribute",
                             fs->name);
    else if (!strcmp(kind, "none"))
        fs->grid.kind = MIMAS_FIELDSET_NONE;
    else if (!strcmp(kind, "cartesian"))
        fs->grid.kind = MIMAS_FIELDSET_CARTESIAN;
    else if (!strcmp(kind, "cylindrical"))
        fs->grid.kind = MIMAS_FIELDSET_CYLINDRICAL;
    else
        rc = mimas_error_set(err, MIMAS_EDATA, "%s: unknown grid kind '%s'", fs->name, kind);
    fs->cyl = fs->grid.kind == MIMAS_FIELDSET_CYLINDRICAL;
    size_t cells = 1;
    for (int d = 0; !rc && d < 3; d++) {
        int none = fs->grid.kind == MIMAS_FIELDSET_NONE;
        if (none)
            n[d] = 1;
        if (n[d] < 1 || n[d] > 100000000) {
            rc = mimas_error_set(err, MIMAS_EDATA, "%s: /grid has %d cells along direction %d",
                                 fs->name, n[d], d);
            break;
        }
        fs->grid.n[d] = n[d];
        cells *= (size_t)n[d];
        fs->centre[d] = calloc((size_t)n[d], sizeof *fs->centre[d]);
        fs->grid.centre[d] = fs->centre[d];
        if (!fs->centre[d]) {
            rc = mimas_error_set(err, MIMAS_EIO, "out of memory for the field file");
            break;
        }
        if (none)
            continue;
        const char *cname = coord_names[fs->cyl][d];
        if (read_doubles(g, cname, fs->centre[d], (size_t)n[d])) {
            rc = mimas_error_set(err, MIMAS_EDATA, "%s: /grid/%s is missing or not %d values",
                                 fs->name, cname, n[d]);
            break;
        }
        hid_t ds = H5Dopen2(g, cname, H5P_DEFAULT);
        char def[128] = "";
        h5_attr_read_str(ds, "definition", def, sizeof def);
        H5Dclose(ds);
        /* output_h5.c: "cell centres", or "cell centre (not gridded)" */
        fs->grid.gridded[d] = !strcmp(def, "cell centres");
    }
    fs->grid.cells = cells;
    H5Gclose(g);
    return rc;
}

int mimas_fieldset_open(mimas_fieldset **out, const char *path, mimas_error *err)
{
    *out = NULL;
    mimas_fieldset *fs = fieldset_new(path);
    if (!fs)
        return mimas_error_set(err, MIMAS_EIO, "out of memory for the field file");
    h5_quiet q;
    h5_quiet_begin(&q);
    int rc = MIMAS_OK;
    FILE *fp = fopen(path, "rb");
    if (!fp)
        rc = mimas_error_set(err, MIMAS_EDATA, "%s: cannot open", path);
    else
        fclose(fp);
    if (!rc && H5Fis_hdf5(path) <= 0)
        rc = mimas_error_set(err, MIMAS_EDATA, "%s: not an HDF5 file", path);
    if (!rc) {
        fs->file = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
        if (fs->file < 0)
            rc = mimas_error_set(err, MIMAS_EDATA, "%s: HDF5 cannot open it", path);
    }
    int version[2] = {0, 0};
    if (!rc && (H5Lexists(fs->file, "/fields", H5P_DEFAULT) <= 0 ||
                H5Lexists(fs->file, "/mimas", H5P_DEFAULT) <= 0))
        rc = mimas_error_set(err, MIMAS_EDATA,
                             "%s: not a field file of mimas average (no /fields group)", path);
    if (!rc) {
        hid_t m = H5Gopen2(fs->file, "/mimas", H5P_DEFAULT);
        int frames = 0;
        if (m < 0 || h5_attr_read_ints(m, "fields_version", version, 2) != 2)
            rc = mimas_error_set(err, MIMAS_EDATA, "%s: no /mimas fields_version attribute",
                                 path);
        else if (version[0] > MIMAS_FIELDS_VERSION_MAJOR)
            rc = mimas_error_set(err, MIMAS_EDATA,
                                 "%s: field file version %d.%d is newer than this mimas reads "
                                 "(%d.x)", path, version[0], version[1],
                                 MIMAS_FIELDS_VERSION_MAJOR);
        else if (h5_attr_read_ints(m, "frames", &frames, 1) == 1 && frames > 0)
            fs->grid.frames = (size_t)frames;
        if (m >= 0)
            H5Gclose(m);
    }
    if (!rc)
        rc = read_grid(fs, err);
    if (!rc && parameters_read_h5(fs->file, "scenario", &fs->params))
        rc = mimas_error_set(err, MIMAS_EDATA, "%s: cannot read /parameters/scenario", path);
    h5_quiet_end(&q);
    if (rc) {
        mimas_fieldset_close(fs);
        return rc;
    }
    *out = fs;
    return MIMAS_OK;
}

static int file_has(const mimas_fieldset *fs, const char *field)
{
    char path[256];
    if (strchr(field, '/') || snprintf(path, sizeof path, "/fields/%s", field) >= (int)sizeof path)
        return 0;
    h5_quiet q;
    h5_quiet_begin(&q);
    int yes = H5Lexists(fs->file, path, H5P_DEFAULT) > 0;
    h5_quiet_end(&q);
    return yes;
}

int mimas_fieldset_has(const mimas_fieldset *fs, const char *field)
{
    return fs->file >= 0 ? file_has(fs, field) : column(fs, field) >= 0;
}

/* sem = std/sqrt(count) where the field was defined in 2 or more frames */
static double standard_error(double sd, double count)
{
    return count >= 2 && isfinite(sd) ? sd / sqrt(count) : NAN;
}

int mimas_fieldset_read(const mimas_fieldset *fs, const char *field, double *mean, double *sem,
                        mimas_error *err)
{
    size_t cells = fs->grid.cells;
    if (!mimas_fieldset_has(fs, field))
        return mimas_error_set(err, MIMAS_EMISSING, "%s: no field '%s'", fs->name, field);
    if (fs->file < 0) {
        size_t nf = mimas_fields_count(), k = (size_t)column(fs, field);
        for (size_t c = 0; c < cells; c++) {
            mean[c] = fs->mean[c * nf + k];
            if (sem)
                sem[c] = standard_error(fs->sd[c * nf + k], fs->count[c * nf + k]);
        }
        return MIMAS_OK;
    }
    double *sd = sem ? malloc(cells * sizeof *sd) : NULL;
    double *count = sem ? malloc(cells * sizeof *count) : NULL;
    if (sem && (!sd || !count)) {
        free(sd);
        free(count);
        return mimas_error_set(err, MIMAS_EIO, "out of memory for the field file");
    }
    h5_quiet q;
    h5_quiet_begin(&q);
    hid_t g = H5Gopen2(fs->file, "/fields", H5P_DEFAULT);
    hid_t one = g >= 0 ? H5Gopen2(g, field, H5P_DEFAULT) : H5I_INVALID_HID;
    int rc = one < 0 || read_doubles(one, "mean", mean, cells);
    if (!rc && sem) {
        /* files without the spread: no standard errors */
        if (read_doubles(one, "std", sd, cells) || read_doubles(one, "count", count, cells))
            for (size_t c = 0; c < cells; c++)
                count[c] = 0;
        for (size_t c = 0; c < cells; c++)
            sem[c] = standard_error(sd[c], count[c]);
    }
    free(sd);
    free(count);
    if (one >= 0)
        H5Gclose(one);
    if (g >= 0)
        H5Gclose(g);
    h5_quiet_end(&q);
    return rc ? mimas_error_set(err, MIMAS_EDATA, "%s: /fields/%s/mean is missing or not %zu "
                                "values", fs->name, field, cells)
              : MIMAS_OK;
}
