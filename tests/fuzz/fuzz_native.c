/* Fuzz target: the native reader's validation.  The bytes do not become the
 * file itself (that would fuzz HDF5's own parser, whose crashes on damaged
 * files mimas cannot mend) but what a hostile or broken writer could put in
 * a well-formed file: a frame written by the native writer whose values,
 * and whose per-frame index (particle counts, steps, times, box corners,
 * contact offsets), are then overwritten with the fuzzer's numbers.  The
 * file is read back through the reader and through the index (mimas info's
 * path); any error is fine, a crash or a sanitizer report is not. */
#include <config.h>

#include <hdf5.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "fuzz_input.h"
#include "native.h"

typedef struct bytes {
    const uint8_t *p;
    size_t n;
} bytes;

static double take_double(bytes *b)
{
    static const double special[8] = {NAN, INFINITY, -INFINITY, -1.0, 0.0, 1e308, -1e-300, 5e-324};
    if (!b->n)
        return 0.5;
    uint8_t tag = *b->p++;
    b->n--;
    if (tag < 32)
        return special[tag % 8];
    double v = 0;
    if (b->n >= sizeof v) {
        memcpy(&v, b->p, sizeof v);
        b->p += sizeof v;
        b->n -= sizeof v;
        return v;
    }
    return (double)tag / 64.0 - 1.0;
}

static int64_t take_int(bytes *b)
{
    if (!b->n)
        return 1;
    int8_t v = (int8_t)*b->p++;
    b->n--;
    return v;
}

/* Overwrites elements of a dataset of doubles or int64 with fuzzed ones. */
static void scribble(hid_t file, const char *path, int integer, bytes *b)
{
    if (H5Lexists(file, path, H5P_DEFAULT) <= 0 || !b->n)
        return;
    hid_t ds = H5Dopen2(file, path, H5P_DEFAULT);
    if (ds < 0)
        return;
    hid_t sp = H5Dget_space(ds);
    hssize_t n = H5Sget_simple_extent_npoints(sp);
    H5Sclose(sp);
    if (n > 0 && n <= 4096) {
        void *buf = malloc((size_t)n * 8);
        hid_t t = integer ? H5T_NATIVE_INT64 : H5T_NATIVE_DOUBLE;
        if (buf && H5Dread(ds, t, H5S_ALL, H5S_ALL, H5P_DEFAULT, buf) >= 0) {
            for (hssize_t k = 0; k < n && b->n; k++) {
                if (b->n && (*b->p & 1)) {
                    if (integer)
                        ((int64_t *)buf)[k] += take_int(b);
                    else
                        ((double *)buf)[k] = take_double(b);
                } else if (b->n) {
                    b->p++, b->n--;
                }
            }
            H5Dwrite(ds, t, H5S_ALL, H5S_ALL, H5P_DEFAULT, buf);
        }
        free(buf);
    }
    H5Dclose(ds);
}

static void make_frame(mimas_frame *f, int64_t step, size_t n)
{
    mimas_error err;
    mimas_frame_clear(f);
    f->step = step;
    f->time = 1e-3 * (double)step;
    f->box = (mimas_box){{0, 0, 0}, {1, 1, 1}, 0, 0, 0, {1, 0, 0}};
    mimas_table_set_present(&f->particles, &mimas_particles_desc,
                            MIMAS_P_ID | MIMAS_P_POS | MIMAS_P_RADIUS | MIMAS_P_MASS |
                                MIMAS_P_VEL, &err);
    mimas_table_resize(&f->particles, &mimas_particles_desc, n, &err);
    for (size_t k = 0; k < n; k++) {
        f->particles.id[k] = (int64_t)k + 1;
        f->particles.radius[k] = 0.05;
        f->particles.mass[k] = 1e-3;
        for (int d = 0; d < 3; d++) {
            f->particles.pos[k][d] = 0.1 + 0.2 * (double)k + 0.1 * d;
            f->particles.vel[k][d] = 0.0;
        }
    }
    f->has_contacts = 1;
    mimas_table_set_present(&f->contacts, &mimas_contacts_desc, MIMAS_C_FORCE, &err);
    mimas_table_resize(&f->contacts, &mimas_contacts_desc, n > 1 ? 1 : 0, &err);
    if (n > 1) {
        f->contacts.i[0] = 0;
        f->contacts.j[0] = 1;
        f->contacts.force[0][0] = f->contacts.force[0][1] = f->contacts.force[0][2] = 1.0;
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    const char *path = fuzz_file(data, 0, "h5", 0);
    if (!path)
        return 0;
    unlink(path);
    bytes b = {data, size};
    mimas_writer *w;
    mimas_error err;
    if (mimas_writer_open(&w, path, NULL, &err))
        return 0;
    mimas_frame f;
    mimas_frame_init(&f);
    size_t frames = 1 + (size ? data[0] % 3 : 0);
    for (size_t k = 0; k < frames; k++) {
        make_frame(&f, 10 * (int64_t)k, 2 + k);
        mimas_writer_append(w, &f, &err);
    }
    mimas_frame_free(&f);
    mimas_writer_close(w, &err);
    /* the fuzzer's numbers over the index and the values */
    H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
    hid_t file = H5Fopen(path, H5F_ACC_RDWR, H5P_DEFAULT);
    if (file >= 0) {
        static const struct {
            const char *path;
            int integer;
        } targets[] = {
            {"/observables/all/particle_count/value", 1}, {"/particles/all/position/step", 1},
            {"/particles/all/position/time", 0},          {"/particles/all/box/lower/value", 0},
            {"/particles/all/box/upper/value", 0},        {"/contacts/all/offset", 1},
            {"/contacts/all/step", 1},                    {"/particles/all/radius/value", 0},
            {"/particles/all/position/value", 0},         {"/particles/all/mass/value", 0},
            {"/particles/all/id/value", 1},               {"/contacts/all/i", 1},
            {"/contacts/all/force", 0},                   {"/particles/all/box/edges/value", 0},
        };
        for (size_t t = 0; t < sizeof targets / sizeof targets[0]; t++)
            scribble(file, targets[t].path, targets[t].integer, &b);
        H5Fclose(file);
    }
    /* read it as mimas average and mimas info would */
    mimas_reader_options o;
    mimas_reader_options_default(&o);
    o.format = "native";
    fuzz_read_all(&path, 1, &o);
    mimas_native *r;
    if (mimas_native_open(&r, path, &err) == MIMAS_OK) {
        mimas_frame_meta m;
        for (size_t k = 0; k < mimas_native_frames(r); k++)
            if (mimas_native_frame_meta(r, k, &m, &err))
                break;
        mimas_native_close(r);
    }
    unlink(path);
    return 0;
}
