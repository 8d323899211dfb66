/* mimas disperse -o: every table as HDF5 datasets with their units and
 * definitions (docs/disperse.md, "HDF5 output"), under a temporary name
 * renamed into place when complete. */
#include <config.h>

#include <hdf5.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "disperse.h"
#include "fit.h"
#include "h5util.h"
#include "outfile.h"

#define DISPERSE_VERSION_MAJOR 1
#define DISPERSE_VERSION_MINOR 0

/* Column col of a table of n rows, taken from values[i * stride] */
static int column(hid_t g, const mimas_disperse_column *c, const double *values, size_t n,
                  size_t stride)
{
    double *v = malloc((n ? n : 1) * sizeof *v);
    if (!v)
        return -1;
    for (size_t i = 0; i < n; i++)
        v[i] = values[i * stride];
    hsize_t dim = n;
    int rc = h5_write_doubles(g, c->name, 1, &dim, v, c->unit, c->meaning);
    free(v);
    return rc;
}

static int write_lags(hid_t file, const mimas_disperse_result *r)
{
    hid_t g = H5Gcreate2(file, "/msd", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    if (g < 0)
        return -1;
    size_t n, nv;
    const mimas_disperse_column *c = mimas_disperse_columns(MIMAS_DISPERSE_LAGS, &n);
    const mimas_disperse_column *cv = mimas_disperse_columns(MIMAS_DISPERSE_VACF, &nv);
    double *lt = malloc(2 * (r->lags ? r->lags : 1) * sizeof *lt);
    int rc = lt ? 0 : -1;
    for (size_t k = 0; k < r->lags && !rc; k++) {
        lt[2 * k] = (double)k;
        lt[2 * k + 1] = (double)k * r->dt;
    }
    rc |= rc ? 0 : column(g, &c[0], lt, r->lags, 2);
    rc |= rc ? 0 : column(g, &c[1], lt + 1, r->lags, 2);
    for (int q = 0; q < MIMAS_DC_COUNT && !rc; q++) {
        rc |= column(g, &c[2 + q], r->msd + q, r->lags, MIMAS_DC_COUNT);
        if (r->vacf)
            rc |= column(g, &cv[q], r->vacf + q, r->lags, MIMAS_DC_COUNT);
    }
    rc |= rc ? 0 : column(g, &c[n - 1], r->count, r->lags, 1);
    free(lt);
    H5Gclose(g);
    return rc;
}

static int write_cohorts(hid_t file, const mimas_disperse_result *r)
{
    hid_t top = H5Gcreate2(file, "/cohorts", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    if (top < 0)
        return -1;
    size_t nc;
    const mimas_disperse_column *c = mimas_disperse_columns(MIMAS_DISPERSE_COHORTS, &nc);
    int rc = 0;
    for (size_t k = 0; k < r->ncohorts && !rc; k++) {
        const mimas_disperse_cohort *h = &r->cohorts[k];
        char name[32];
        snprintf(name, sizeof name, "%zu", k);
        hid_t g = H5Gcreate2(top, name, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
        if (g < 0) {
            rc = -1;
            break;
        }
        rc |= h5_attr_write_str(g, "spec", h->spec);
        int size = h->size > 2147483647u ? -1 : (int)h->size;
        rc |= h5_attr_write_ints(g, "size", &size, 1);
        rc |= h5_attr_write_double(g, "complete_time", h->complete_time);
        size_t m = h->nrows;
        double *v = malloc((m ? m : 1) * 8 * sizeof *v);
        if (!v)
            rc = -1;
        for (size_t i = 0; i < m && !rc; i++) {
            const mimas_disperse_cohort_row *row = &h->rows[i];
            double *o = v + 8 * i;
            o[0] = row->time;
            o[1] = (double)row->n;
            o[2] = row->mean[0];
            o[3] = row->mean[1];
            o[4] = row->mean[2];
            o[5] = row->sigma2_axial;
            o[6] = row->sigma2_transverse;
        }
        for (size_t q = 1; q < nc && !rc; q++)
            rc |= column(g, &c[q], v + q - 1, m, 8);
        free(v);
        H5Gclose(g);
    }
    H5Gclose(top);
    return rc;
}

static int write_diffusion(hid_t file, const mimas_disperse_result *r)
{
    hid_t g = H5Gcreate2(file, "/diffusion", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    if (g < 0)
        return -1;
    size_t n = r->ndiffusion, nc;
    const mimas_disperse_column *c = mimas_disperse_columns(MIMAS_DISPERSE_DIFFUSION, &nc);
    const char **what = malloc((n ? n : 1) * sizeof *what);
    const char **comp = malloc((n ? n : 1) * sizeof *comp);
    const char **status = malloc((n ? n : 1) * sizeof *status);
    double *v = malloc((n ? n : 1) * 6 * sizeof *v);
    int rc = what && comp && status && v ? 0 : -1;
    for (size_t i = 0; i < n && !rc; i++) {
        const mimas_disperse_diffusion *d = &r->diffusion[i];
        what[i] = d->what;
        comp[i] = mimas_disperse_component_name(d->component);
        status[i] = mimas_fit_status_name(d->status);
        double row[6] = {d->D, d->D_err, d->t0, d->t1, d->D_err_fit, (double)d->npts};
        memcpy(v + 6 * i, row, sizeof row);
    }
    if (!rc)
        rc |= h5_write_strs(g, c[0].name, what, n, c[0].meaning) |
              h5_write_strs(g, c[1].name, comp, n, c[1].meaning) |
              h5_write_strs(g, c[8].name, status, n, c[8].meaning);
    for (size_t q = 0; q < 6 && !rc; q++)
        rc |= column(g, &c[2 + q], v + q, n, 6);
    free(what);
    free(comp);
    free(status);
    free(v);
    H5Gclose(g);
    return rc;
}

static int write_meta(hid_t file, const mimas_disperse_result *r, const char *provenance)
{
    hid_t g = H5Gcreate2(file, "/mimas", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    if (g < 0)
        return -1;
    int version[2] = {DISPERSE_VERSION_MAJOR, DISPERSE_VERSION_MINOR};
    int counts[2] = {r->frames > 2147483647u ? -1 : (int)r->frames,
                     r->particles > 2147483647u ? -1 : (int)r->particles};
    int flags[3] = {r->axis_from_tube, r->scratch, (int)r->groups};
    int rc = h5_attr_write_ints(g, "disperse_version", version, 2);
    rc |= h5_attr_write_str(g, "creator", "mimas " PACKAGE_VERSION);
    if (provenance)
        rc |= h5_attr_write_str(g, "provenance", provenance);
    rc |= h5_attr_write_ints(g, "frames", &counts[0], 1);
    rc |= h5_attr_write_ints(g, "particles", &counts[1], 1);
    rc |= h5_attr_write_double(g, "first_time", r->t_first);
    rc |= h5_attr_write_double(g, "frame_interval", r->dt);
    rc |= h5_attr_write_double(g, "fit_lag_from", r->fit_lo);
    rc |= h5_attr_write_double(g, "fit_lag_to", r->fit_hi);
    rc |= h5_attr_write_ints(g, "axis_from_tube", &flags[0], 1);
    rc |= h5_attr_write_ints(g, "scratch_file_used", &flags[1], 1);
    rc |= h5_attr_write_ints(g, "jackknife_groups", &flags[2], 1);
    hsize_t three = 3;
    rc |= h5_write_doubles(g, "axis_origin", 1, &three, r->axis.origin, "m", "a point of the axis");
    rc |= h5_write_doubles(g, "axis_direction", 1, &three, r->axis.ez, NULL,
                           "unit vector along the axis");
    H5Gclose(g);
    return rc;
}

int mimas_disperse_write_h5(const mimas_disperse_result *r, const char *path,
                            const char *provenance, mimas_error *err)
{
    if (mimas_output_check(path, err))
        return err->code;
    char tmp[4200];
    snprintf(tmp, sizeof tmp, "%s.tmp%ld", path, (long)getpid());
    h5_quiet q;
    h5_quiet_begin(&q);
    hid_t file = H5Fcreate(tmp, H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
    int rc = file < 0;
    if (!rc)
        rc = write_meta(file, r, provenance) || write_lags(file, r) || write_cohorts(file, r) ||
             write_diffusion(file, r);
    char text[256] = "";
    if (rc)
        h5_error_text(text, sizeof text);
    if (file >= 0 && H5Fclose(file) < 0)
        rc = 1;
    h5_quiet_end(&q);
    if (!rc && rename(tmp, path) != 0)
        rc = 1;
    if (rc) {
        remove(tmp);
        return mimas_error_set(err, MIMAS_EIO, "%s: cannot write the HDF5 file%s%s", path,
                               text[0] ? ": " : "", text);
    }
    return MIMAS_OK;
}
