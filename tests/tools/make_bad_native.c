/* Writes a native file of three small frames with one defect that a broken
 * or hostile writer could leave (for tests/cli/bad_input.test): the file is
 * well-formed HDF5 and H5MD, only values of it are wrong.  Usage:
 *   make_bad_native DEFECT OUT.h5
 * DEFECT: good, nan-position, negative-radius, negative-mass, inverted-box,
 * negative-count, huge-count, decreasing-steps, repeated-steps, nan-time-mix,
 * inf-time, decreasing-offsets, unwrapped (positions outside the periodic
 * box by whole box lengths, a good file). */
#include <config.h>

#include <hdf5.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "native.h"

#define FRAMES 3
#define N 4

static void frame(mimas_frame *f, int k, int unwrapped)
{
    mimas_error err;
    mimas_frame_clear(f);
    f->step = 100 * k;
    f->time = 1e-3 * k;
    f->box = (mimas_box){{0, 0, 0}, {1, 1, 1}, 0, 0, 0, {1, 1, 1}};
    mimas_table_set_present(&f->particles, &mimas_particles_desc,
                            MIMAS_P_ID | MIMAS_P_TYPE | MIMAS_P_POS | MIMAS_P_RADIUS |
                                MIMAS_P_MASS | MIMAS_P_VEL,
                            &err);
    mimas_table_resize(&f->particles, &mimas_particles_desc, N, &err);
    mimas_particles *p = &f->particles;
    for (size_t i = 0; i < N; i++) {
        p->id[i] = (int64_t)i + 1;
        p->type[i] = 1;
        p->radius[i] = 0.1;
        p->mass[i] = 1e-3;
        for (int d = 0; d < 3; d++) {
            /* particle i at 0.125 + 0.25 i, moved by 3 box lengths when unwrapped */
            p->pos[i][d] = 0.125 + 0.25 * (double)i + (unwrapped && d == 0 ? 3.0 : 0.0);
            p->vel[i][d] = d == 0 ? 0.5 : 0.0;
        }
    }
    f->has_contacts = 1;
    mimas_table_set_present(&f->contacts, &mimas_contacts_desc, MIMAS_C_FORCE, &err);
    mimas_table_resize(&f->contacts, &mimas_contacts_desc, 1, &err);
    f->contacts.i[0] = 0;
    f->contacts.j[0] = 1;
    for (int d = 0; d < 3; d++)
        f->contacts.force[0][d] = 1.0;
}

/* Sets element `at` of a 1-d dataset (or the first component of row `at`). */
static int poke(hid_t file, const char *path, hsize_t at, int integer, double v)
{
    hid_t ds = H5Dopen2(file, path, H5P_DEFAULT);
    if (ds < 0)
        return -1;
    hid_t fs = H5Dget_space(ds);
    int rank = H5Sget_simple_extent_ndims(fs);
    hsize_t start[3] = {at, 0, 0}, count[3] = {1, 1, 1};
    hid_t ms = H5Screate_simple(1, count, NULL);
    H5Sselect_hyperslab(fs, H5S_SELECT_SET, start, NULL, count, NULL);
    int64_t iv = (int64_t)v;
    herr_t rc = rank > 3 ? -1
                         : H5Dwrite(ds, integer ? H5T_NATIVE_INT64 : H5T_NATIVE_DOUBLE, ms, fs,
                                    H5P_DEFAULT, integer ? (void *)&iv : (void *)&v);
    H5Sclose(ms);
    H5Sclose(fs);
    H5Dclose(ds);
    return rc < 0 ? -1 : 0;
}

int main(int argc, char **argv)
{
    if (argc != 3) {
        fprintf(stderr, "usage: make_bad_native DEFECT OUT.h5\n");
        return 1;
    }
    const char *defect = argv[1], *out = argv[2];
    mimas_writer *w;
    mimas_error err;
    if (mimas_writer_open(&w, out, NULL, &err)) {
        fprintf(stderr, "make_bad_native: %s\n", err.msg);
        return 2;
    }
    mimas_frame f;
    mimas_frame_init(&f);
    int unwrapped = !strcmp(defect, "unwrapped");
    for (int k = 0; k < FRAMES; k++) {
        frame(&f, k, unwrapped);
        if (mimas_writer_append(w, &f, &err)) {
            fprintf(stderr, "make_bad_native: %s\n", err.msg);
            return 2;
        }
    }
    mimas_frame_free(&f);
    if (mimas_writer_close(w, &err)) {
        fprintf(stderr, "make_bad_native: %s\n", err.msg);
        return 2;
    }
    static const struct {
        const char *name, *path;
        hsize_t at;
        int integer;
        double value;
    } defects[] = {
        {"nan-position", "/particles/all/position/value", 1, 0, NAN},
        {"negative-radius", "/particles/all/radius/value", 1, 0, -0.1},
        {"negative-mass", "/particles/all/mass/value", 2, 0, -1e-3},
        {"inverted-box", "/particles/all/box/upper/value", 1, 0, -1.0},
        {"negative-count", "/observables/all/particle_count/value", 1, 1, -7},
        {"huge-count", "/observables/all/particle_count/value", 2, 1, 1e15},
        {"decreasing-steps", "/particles/all/position/step", 2, 1, 50},
        {"repeated-steps", "/particles/all/position/step", 2, 1, 100},
        {"nan-time-mix", "/particles/all/position/time", 1, 0, NAN},
        {"inf-time", "/particles/all/position/time", 2, 0, INFINITY},
        {"decreasing-offsets", "/contacts/all/offset", 2, 1, 0},
    };
    if (!strcmp(defect, "good") || unwrapped)
        return 0;
    for (size_t d = 0; d < sizeof defects / sizeof defects[0]; d++) {
        if (strcmp(defect, defects[d].name))
            continue;
        hid_t file = H5Fopen(out, H5F_ACC_RDWR, H5P_DEFAULT);
        int rc = file < 0 || poke(file, defects[d].path, defects[d].at, defects[d].integer,
                                  defects[d].value);
        if (file >= 0)
            H5Fclose(file);
        if (rc) {
            fprintf(stderr, "make_bad_native: cannot write %s\n", defects[d].path);
            return 2;
        }
        return 0;
    }
    fprintf(stderr, "make_bad_native: unknown defect '%s'\n", defect);
    return 1;
}
