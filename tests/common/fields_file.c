#include <config.h>

#include "fields_file.h"

#include <hdf5.h>
#include <math.h>
#include <stdlib.h>

#include "h5util.h"
#include "output_h5.h"
#include "parameters_h5.h"

static int write_grid(hid_t file, const fields_file_spec *s)
{
    static const char *const names[2][3] = {{"x", "y", "z"}, {"r", "phi", "z"}};
    int cyl = s->kind[0] == 'c' && s->kind[1] == 'y';
    hid_t g = H5Gcreate2(file, "/grid", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    int rc = g < 0 || h5_attr_write_str(g, "kind", s->kind) ||
             h5_attr_write_ints(g, "cells", s->n, 3);
    for (int d = 0; !rc && d < 3; d++) {
        hsize_t len = (hsize_t)s->n[d];
        double *c = calloc(len, sizeof *c);
        for (hsize_t k = 0; c && s->centre[d] && k < len; k++)
            c[k] = s->centre[d][k];
        rc = !c || h5_write_doubles(g, names[cyl][d], 1, &len, c, "m",
                                    s->gridded[d] ? "cell centres" : "cell centre (not gridded)");
        free(c);
    }
    if (g >= 0)
        H5Gclose(g);
    return rc;
}

int write_fields_file(const char *path, const fields_file_spec *s, size_t nfields,
                      const char *const *names, const double *const *mean,
                      const double *const *sem)
{
    hid_t file = H5Fcreate(path, H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
    if (file < 0)
        return -1;
    int version[2] = {MIMAS_FIELDS_VERSION_MAJOR, MIMAS_FIELDS_VERSION_MINOR};
    if (s->version[0] || s->version[1])
        version[0] = s->version[0], version[1] = s->version[1];
    hid_t m = H5Gcreate2(file, "/mimas", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    int rc = m < 0 || h5_attr_write_ints(m, "fields_version", version, 2) ||
             h5_attr_write_ints(m, "frames", &s->frames, 1);
    if (m >= 0)
        H5Gclose(m);
    rc = rc || write_grid(file, s) || (s->params && parameters_write_h5(file, "scenario", s->params));
    size_t cells = (size_t)s->n[0] * (size_t)s->n[1] * (size_t)s->n[2];
    hsize_t dims[3] = {(hsize_t)s->n[2], (hsize_t)s->n[1], (hsize_t)s->n[0]};
    double *sd = malloc(cells * sizeof *sd), *count = malloc(cells * sizeof *count);
    hid_t gf = rc ? -1 : H5Gcreate2(file, "/fields", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    rc = rc || gf < 0 || !sd || !count;
    for (size_t k = 0; !rc && k < nfields; k++) {
        for (size_t c = 0; c < cells; c++) {
            count[c] = isnan(mean[k][c]) ? 0 : s->frames;
            sd[c] = sem && sem[k] ? sem[k][c] * sqrt(s->frames) : NAN;
        }
        hid_t one = H5Gcreate2(gf, names[k], H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
        rc = one < 0 || h5_write_doubles(one, "mean", 3, dims, mean[k], NULL, NULL) ||
             h5_write_doubles(one, "std", 3, dims, sd, NULL, NULL) ||
             h5_write_doubles(one, "count", 3, dims, count, NULL, NULL);
        if (one >= 0)
            H5Gclose(one);
    }
    if (gf >= 0)
        H5Gclose(gf);
    free(sd);
    free(count);
    return H5Fclose(file) < 0 || rc ? -1 : 0;
}
