#include <config.h>

#include "output_h5.h"

#include <errno.h>
#include <hdf5.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "fields.h"
#include "big_alloc.h"
#include "h5util.h"
#include "output_xdmf.h"
#include "tmpfiles.h"
#include "xdmf.h"
#include "outfile.h"
#include "parameters_h5.h"

/* Dimensions of a field dataset: (n2, n1, n0), direction 0 fastest like the
 * cell index. */
static void dims_of(const mimas_grid *g, int none, hsize_t dims[3])
{
    for (int d = 0; d < 3; d++)
        dims[2 - d] = none ? 1 : (hsize_t)g->n[d];
}

/* Cell-centre positions in Cartesian coordinates (for XDMF), n x 3. */
static void centres(const mimas_grid *g, int none, size_t cells, double *xyz)
{
    for (size_t c = 0; c < cells; c++) {
        double q[3] = {0, 0, 0}, p[3];
        if (!none)
            mimas_grid_cell_centre(g, c, q);
        if (g->kind == MIMAS_GRID_CYLINDRICAL && !none) {
            /* back from the axis frame: origin + r cos(phi) ex + r sin(phi) ey + z ez */
            double a0 = q[0] * cos(q[1]), a1 = q[0] * sin(q[1]);
            for (int d = 0; d < 3; d++)
                p[d] = g->origin[d] + a0 * g->ex[d] + a1 * g->ey[d] + q[2] * g->ez[d];
        } else {
            memcpy(p, q, sizeof p);
        }
        memcpy(&xyz[3 * c], p, sizeof p);
    }
}

static int write_grid(hid_t file, const mimas_grid *g, int none, size_t cells)
{
    hid_t gg = H5Gcreate2(file, "/grid", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    if (gg < 0)
        return -1;
    int rc = h5_attr_write_str(gg, "kind", none ? "none"
                                           : g->kind == MIMAS_GRID_CYLINDRICAL ? "cylindrical"
                                                                               : "cartesian");
    int n[3] = {g->n[0], g->n[1], g->n[2]};
    rc |= h5_attr_write_ints(gg, "cells", n, 3);
    for (int d = 0; d < 3 && !none; d++) {
        /* cell-centre coordinates along each direction */
        hsize_t len = (hsize_t)g->n[d];
        double *c = malloc(len * sizeof *c);
        if (!c)
            return H5Gclose(gg), -1;
        for (hsize_t k = 0; k < len; k++)
            c[k] = g->lo[d] + (g->hi[d] - g->lo[d]) * ((double)k + 0.5) / g->n[d];
        rc |= h5_write_doubles(gg, mimas_grid_coord_name(g, d), 1, &len, c,
                          g->kind == MIMAS_GRID_CYLINDRICAL && d == 1 ? "rad" : "m",
                          g->gridded[d] ? "cell centres" : "cell centre (not gridded)");
        free(c);
    }
    if (g->kind == MIMAS_GRID_CYLINDRICAL && !none) {
        hsize_t six = 3;
        rc |= h5_write_doubles(gg, "axis_origin", 1, &six, g->origin, "m", "a point of the axis");
        rc |= h5_write_doubles(gg, "axis_direction", 1, &six, g->ez, NULL, "unit vector e_z");
        rc |= h5_write_doubles(gg, "axis_phi0", 1, &six, g->ex, NULL, "unit vector e_x (phi = 0)");
    }
    double *xyz = malloc(cells * 3 * sizeof *xyz);
    if (!xyz)
        return H5Gclose(gg), -1;
    centres(g, none, cells, xyz);
    hsize_t pd[4];
    dims_of(g, none, pd);
    pd[3] = 3;
    rc |= h5_write_doubles(gg, "points", 4, pd, xyz, "m", "cell centres, Cartesian");
    free(xyz);
    rc |= fields_write_corners(gg, g, none);
    H5Gclose(gg);
    return rc;
}

struct mimas_fields_file {
    char path[4096], tmp[4200];
    unsigned char want[128];   /* the fields to write */
    hid_t file;
    hid_t step, time;          /* /frames/step and /frames/time */
    hid_t *per;                /* /frames/<field>, one per field (or 0) */
    hsize_t frames;
    h5_quiet quiet;
    int slot;                  /* tmp in the temporary-file registry */
};

/* Forgets the temporary name (renamed or removed) and frees ff. */
static void release_names(mimas_fields_file *ff)
{
    mimas_tmpfile_forget(ff->slot);
    free(ff);
}

int mimas_fields_open(mimas_fields_file **out, const char *path, const unsigned char *want,
                      mimas_error *err)
{
    *out = NULL;
    if (mimas_output_check(path, err))
        return err->code;
    mimas_fields_file *ff = calloc(1, sizeof *ff);
    if (!ff)
        return mimas_error_set(err, MIMAS_EIO, "%s: out of memory for the field file", path);
    ff->slot = -1;
    int w = snprintf(ff->path, sizeof ff->path, "%s", path);
    if (w < 0 || (size_t)w >= sizeof ff->path - 8 ||
        mimas_tmpfile_name(ff->tmp, sizeof ff->tmp, path)) {
        free(ff);
        return mimas_error_set(err, MIMAS_EUSAGE, "%s: the file name is too long", path);
    }
    ff->slot = mimas_tmpfile_add(ff->tmp);
    for (size_t k = 0; k < mimas_fields_count() && k < sizeof ff->want; k++)
        ff->want[k] = want ? want[k] : 1;
    h5_quiet_begin(&ff->quiet);
    ff->file = H5Fcreate(ff->tmp, H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
    char text[256];
    h5_error_text(text, sizeof text);
    h5_quiet_end(&ff->quiet);
    if (ff->file < 0) {
        release_names(ff);
        return mimas_error_set(err, MIMAS_EIO, "%s: cannot create the field file%s%s", path,
                               text[0] ? ": " : "", text);
    }
    *out = ff;
    return MIMAS_OK;
}

static void close_frames(mimas_fields_file *ff)
{
    if (ff->step > 0)
        H5Dclose(ff->step);
    if (ff->time > 0)
        H5Dclose(ff->time);
    for (size_t k = 0; ff->per && k < mimas_fields_count(); k++)
        if (ff->per[k] > 0)
            H5Dclose(ff->per[k]);
    free(ff->per);
    ff->per = NULL;
}

void mimas_fields_abort(mimas_fields_file *ff)
{
    if (!ff)
        return;
    h5_quiet_begin(&ff->quiet);
    close_frames(ff);
    H5Fclose(ff->file);
    h5_quiet_end(&ff->quiet);
    remove(ff->tmp);
    release_names(ff);
}

int mimas_fields_parameters(mimas_fields_file *ff, const char *group, const mimas_parameters *ps,
                            mimas_error *err)
{
    h5_quiet_begin(&ff->quiet);
    int rc = parameters_write_h5(ff->file, group, ps);
    h5_quiet_end(&ff->quiet);
    return rc ? mimas_error_set(err, MIMAS_EIO, "%s: cannot write the run parameters", ff->path)
              : MIMAS_OK;
}

/* One field's column, col[c] = src[c * nf] for the cells c < n, from fields stored cell by
 * cell (nf per cell): four cells an iteration, their rows too far apart for vectors. */
static void field_column(const double *src, size_t nf, size_t n, double *col)
{
    size_t c = 0;
    for (; c + 4 <= n; c += 4, src += 4 * nf) {
        col[c] = src[0];
        col[c + 1] = src[nf];
        col[c + 2] = src[2 * nf];
        col[c + 3] = src[3 * nf];
    }
    for (; c < n; c++, src += nf)
        col[c] = src[0];
}

/* Appends one row (at index k) of a growing dataset of rank 1 + rank(dims). */
static int append_row(hid_t ds, hsize_t k, int rank, const hsize_t *dims, const double *row)
{
    return h5_append_row(ds, k, rank, dims, H5T_NATIVE_DOUBLE, row);
}

int mimas_fields_append_frame(mimas_fields_file *ff, const mimas_average *frame, int64_t step,
                              double time, mimas_error *err)
{
    const mimas_grid *g = mimas_average_grid(frame);
    int none = mimas_average_grid_none(frame);
    int cyl = g->kind == MIMAS_GRID_CYLINDRICAL && !none;
    size_t cells = none ? 1 : mimas_grid_cells(g), nf = mimas_fields_count();
    hsize_t dims[3];
    dims_of(g, none, dims);
    double *all = mimas_big_calloc(cells * nf, sizeof *all), *col = malloc(cells * sizeof *col);
    int rc = !all || !col || mimas_average_fields(frame, all, NULL, NULL);
    h5_quiet_begin(&ff->quiet);
    if (!rc && !ff->per) {
        ff->per = calloc(nf, sizeof *ff->per);
        hid_t lcpl = H5Pcreate(H5P_LINK_CREATE);
        H5Pset_create_intermediate_group(lcpl, 1);
        hid_t gf = H5Gcreate2(ff->file, "/frames", lcpl, H5P_DEFAULT, H5P_DEFAULT);
        H5Pclose(lcpl);
        hsize_t zero = 0, chunk1 = 256;
        ff->step = h5_create_growing(gf, "step", H5T_STD_I64LE, 1, 1, &zero, &chunk1, NULL, 0);
        ff->time = h5_create_growing(gf, "time", H5T_IEEE_F64LE, 1, 1, &zero, &chunk1, NULL, 0);
        hsize_t d4[4] = {0, dims[0], dims[1], dims[2]}, c4[4] = {1, dims[0], dims[1], dims[2]};
        for (size_t k = 0; ff->per && k < nf; k++) {
            const char *name = mimas_field_name(k, cyl);
            if (!name || !ff->want[k])
                continue;
            ff->per[k] = h5_create_growing(gf, name, H5T_IEEE_F64LE, 4, 1, d4, c4, NULL, 1);
            if (ff->per[k] < 0 || h5_attr_write_vlstr(ff->per[k], "unit", mimas_field(k)->unit) ||
                h5_attr_write_str(ff->per[k], "definition", mimas_field(k)->meaning))
                rc = 1;
        }
        if (gf >= 0)
            H5Gclose(gf);
        rc |= !ff->per || ff->step < 0 || ff->time < 0;
    }
    if (!rc) {
        hsize_t one = 1;
        hsize_t k = ff->frames;
        hsize_t ext = k + 1;
        hid_t fs;
        /* step (int64) and time */
        int64_t s64 = step;
        if (H5Dset_extent(ff->step, &ext) < 0)
            rc = 1;
        else {
            fs = H5Dget_space(ff->step);
            hid_t ms = H5Screate_simple(1, &one, NULL);
            H5Sselect_hyperslab(fs, H5S_SELECT_SET, &k, NULL, &one, NULL);
            rc |= H5Dwrite(ff->step, H5T_NATIVE_INT64, ms, fs, H5P_DEFAULT, &s64) < 0;
            H5Sclose(ms);
            H5Sclose(fs);
        }
        rc |= append_row(ff->time, k, 0, dims, &time);
        for (size_t q = 0; !rc && q < nf; q++) {
            if (ff->per[q] <= 0)
                continue;
            field_column(all + q, nf, cells, col);
            rc |= append_row(ff->per[q], k, 3, dims, col);
        }
        if (!rc)
            ff->frames++;
    }
    h5_quiet_end(&ff->quiet);
    mimas_big_free(all);
    free(col);
    return rc ? mimas_error_set(err, MIMAS_EIO, "%s: cannot write the fields of step %lld",
                                ff->path, (long long)step)
              : MIMAS_OK;
}

int mimas_fields_finish(mimas_fields_file *ff, const mimas_average *a, const char *provenance,
                        mimas_error *err)
{
    const mimas_grid *g = mimas_average_grid(a);
    int none = mimas_average_grid_none(a);
    int cyl = g->kind == MIMAS_GRID_CYLINDRICAL && !none;
    size_t cells = none ? 1 : mimas_grid_cells(g), nf = mimas_fields_count();
    double *mean = mimas_big_calloc(cells * nf, sizeof *mean),
           *sd = mimas_big_calloc(cells * nf, sizeof *sd),
           *count = mimas_big_calloc(cells * nf, sizeof *count),
           *col = malloc(cells * sizeof *col), *col_sd = malloc(cells * sizeof *col_sd);
    if (!mean || !sd || !count || !col || !col_sd || mimas_average_fields(a, mean, sd, count)) {
        mimas_big_free(mean), mimas_big_free(sd), mimas_big_free(count), free(col), free(col_sd);
        int code = mimas_error_set(err, MIMAS_EIO, "%s: out of memory for the fields of %zu "
                                   "cells", ff->path, cells);
        mimas_fields_abort(ff);
        return code;
    }
    h5_quiet q;
    h5_quiet_begin(&q);
    hid_t file = ff->file;
    int rc = 0;
    char why[300] = "";
    /* the times of the frames, for the per-frame sidecar */
    size_t nframes = (size_t)ff->frames;
    double *times = malloc((nframes ? nframes : 1) * sizeof *times);
    rc |= !times || (nframes && H5Dread(ff->time, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL,
                                        H5P_DEFAULT, times) < 0);
    close_frames(ff);
    {
        hid_t gm = H5Gcreate2(file, "/mimas", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
        int v[2] = {MIMAS_FIELDS_VERSION_MAJOR, MIMAS_FIELDS_VERSION_MINOR};
        long frames = (long)mimas_average_frames(a);
        int fr = (int)frames;
        rc |= gm < 0 || h5_attr_write_ints(gm, "fields_version", v, 2) ||
              h5_attr_write_str(gm, "creator", PACKAGE_NAME " " PACKAGE_VERSION) ||
              h5_attr_write_ints(gm, "frames", &fr, 1) ||
              (provenance && h5_attr_write_str(gm, "provenance", provenance));
        if (gm >= 0)
            H5Gclose(gm);
        rc |= write_grid(file, g, none, cells);
        hid_t gf = H5Gcreate2(file, "/fields", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
        hsize_t dims[3];
        dims_of(g, none, dims);
        for (size_t k = 0; !rc && k < nf; k++) {
            const char *name = mimas_field_name(k, cyl);
            if (!name || !ff->want[k])
                continue;
            const mimas_field_desc *fd = mimas_field(k);
            hid_t one = H5Gcreate2(gf, name, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
            rc |= one < 0 || h5_attr_write_vlstr(one, "unit", fd->unit) ||
                  h5_attr_write_str(one, "definition", fd->meaning);
            const double *src[3] = {mean, sd, count};
            const char *what[4] = {"mean", "std", "count", "sem"};
            const char *desc[4] = {"the field from the time-averaged sums",
                                   "standard deviation of the per-frame field over frames",
                                   "frames in which the field was defined",
                                   "standard error std/sqrt(count) (nan where count < 2)"};
            for (int m = 0; m < 4 && !rc; m++) {
                if (m < 3) /* the std column stays in col_sd for the sem */
                    field_column(src[m] + k, nf, cells, m == 1 ? col_sd : col);
                else
                    for (size_t c = 0; c < cells; c++) /* col holds the counts */
                        col[c] = col[c] > 1 ? col_sd[c] / sqrt(col[c]) : NAN;
                rc |= h5_write_doubles(one, what[m], 3, dims, m == 1 ? col_sd : col,
                                       m == 2 ? NULL : fd->unit, desc[m]);
            }
            if (one >= 0)
                H5Gclose(one);
        }
        if (gf >= 0)
            H5Gclose(gf);
        /* the full (non-symmetric) contact stress from the time-averaged sums;
         * Voronoi averages: the mean of the per-particle stresses instead */
        int vor = mimas_average_weight(a)->voronoi;
        double *full = rc ? NULL : malloc(cells * 9 * sizeof *full);
        if (!rc && full) {
            double S[NSUMS];
            for (size_t c = 0; c < cells; c++) {
                mimas_average_sums(a, c, S);
                for (int k = 0; k < 9; k++)
                    full[9 * c + (size_t)k] = vor ? S[S_VS + k] / S[S_VSC] : S[S_C + k];
            }
            hsize_t td[5] = {dims[0], dims[1], dims[2], 3, 3};
            hid_t gt = H5Gcreate2(file, "/tensors", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
            char def[200];
            snprintf(def, sizeof def, "%s, full tensor [a][b] = f_a b_b in (%s) components",
                     vor ? "stress sum_k V_k sigma_k phi / sum_k V_k phi of the per-particle "
                           "Voronoi stresses"
                         : "contact stress sum_c f_ij (x) (r_i - r_j) psi_ij",
                     cyl ? "r, phi, z" : "x, y, z");
            rc |= gt < 0 || h5_write_doubles(gt, vor ? "stress" : "cstress", 5, td, full, "Pa", def);
            if (gt >= 0)
                H5Gclose(gt);
        }
        rc |= !full;
        free(full);
        /* vectors and tensors of cylindrical grids in Cartesian components */
        fields_group groups[16];
        size_t ng = fields_xdmf_stored(g, none) ? fields_groups(cyl, ff->want, groups, 16) : 0;
        if (!rc && ng)
            rc |= fields_write_cartesian(file, g, groups, ng, mean, nf);
        char text[256];
        h5_error_text(text, sizeof text);
        rc |= H5Fclose(file) < 0;
        if (rc && !text[0])
            h5_error_text(text, sizeof text);
        snprintf(why, sizeof why, "%s", text);
        if (!rc && fields_write_xdmf(ff->path, g, none, ff->want, nframes, times, 1,
                                     vor ? "stress" : "cstress", err))
            rc = 2;
    }
    h5_quiet_end(&q);
    mimas_big_free(mean), mimas_big_free(sd), mimas_big_free(count);
    free(col), free(col_sd), free(times);
    if (!rc && rename(ff->tmp, ff->path) != 0) {
        rc = 1;
        snprintf(why, sizeof why, "cannot rename it into place: %s", strerror(errno));
    }
    if (rc) {
        remove(ff->tmp);
        char side[4200];
        mimas_xdmf_path(ff->path, NULL, side, sizeof side);
        remove(side);
        mimas_xdmf_path(ff->path, "-frames", side, sizeof side);
        remove(side);
        int code = rc == 2 ? MIMAS_EIO
                           : mimas_error_set(err, MIMAS_EIO, "%s: cannot write the field file%s%s",
                                             ff->path, why[0] ? ": " : "", why);
        release_names(ff);
        return code;
    }
    release_names(ff);
    return MIMAS_OK;
}
