/* The field-set reader: a field file of mimas average reads back as the
 * average it was written from; other files are told apart. */
#include <config.h>

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>
#include <gsl/gsl_rng.h>
#include <hdf5.h>

#include "assert_close.h"
#include "fieldset.h"
#include "h5util.h"
#include "native.h"
#include "output_h5.h"
#include "ring_frame.h"
#include "scratch.h"

/* Three frames of the ring cell averaged on an r-z grid. */
static mimas_average *ring_average(const char *grid, mimas_frame *f)
{
    ring_spec s;
    ring_spec_default(&s);
    s.particles = 3000;
    s.noise = 0.001;
    mimas_average_options o;
    memset(&o, 0, sizeof o);
    mimas_error err;
    assert_int_equal(mimas_grid_parse(&o.grid, grid, NULL, &err), 0);
    assert_int_equal(mimas_weight_parse(&o.weight, "bins", &err), 0);
    o.spread = 1;
    o.grid_none = !strcmp(grid, "none");
    mimas_average *avg;
    assert_int_equal(mimas_average_create(&avg, &o, &err), MIMAS_OK);
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    for (int k = 0; k < 3; k++) {
        assert_int_equal(ring_frame(f, rng, &s, k), 0);
        assert_int_equal(mimas_average_add(avg, f, &err), MIMAS_OK);
    }
    gsl_rng_free(rng);
    return avg;
}

static void same_values(const double *a, const double *b, size_t n)
{
    for (size_t i = 0; i < n; i++)
        assert_true((isnan(a[i]) && isnan(b[i])) || a[i] == b[i]);
}

static void test_file_reads_back_as_the_average(void **state)
{
    (void)state;
    mimas_frame f;
    mimas_frame_init(&f);
    mimas_average *avg = ring_average("r=0.0147:0.11:10,z=0:0.038:3", &f);
    mimas_error err;
    mimas_fields_file *ff;
    const char *path = scratch_path("ring.h5");
    assert_int_equal(mimas_fields_open(&ff, path, NULL, &err), MIMAS_OK);
    assert_int_equal(mimas_fields_finish(ff, avg, "test", &err), MIMAS_OK);
    mimas_fieldset *file, *mem;
    assert_true(mimas_fieldset_probe(path));
    assert_int_equal(mimas_fieldset_open(&file, path, &err), MIMAS_OK);
    assert_int_equal(mimas_fieldset_from_average(&mem, avg, "memory", &err), MIMAS_OK);
    const mimas_fieldset_grid *gf = mimas_fieldset_grid_of(file),
                              *gm = mimas_fieldset_grid_of(mem);
    assert_int_equal(gf->kind, MIMAS_FIELDSET_CYLINDRICAL);
    assert_int_equal(gf->cells, 30);
    assert_int_equal(gf->frames, 3);
    assert_int_equal(gm->frames, 3);
    int want_n[3] = {10, 1, 3}, want_gridded[3] = {1, 0, 1};
    for (int d = 0; d < 3; d++) {
        assert_int_equal(gf->n[d], want_n[d]);
        assert_int_equal(gf->gridded[d], want_gridded[d]);
        assert_int_equal(gm->gridded[d], want_gridded[d]);
        same_values(gf->centre[d], gm->centre[d], (size_t)want_n[d]);
    }
    /* cell centres: r = 0.0147 + (k + 1/2) h */
    assert_close(gf->centre[0][3], 0.0147 + 3.5 * (0.11 - 0.0147) / 10, 1e-15);
    const char *fields[] = {"omega", "v_phi", "p", "nu", "shear_rate"};
    double a[30], b[30], sa[30], sb[30];
    for (size_t k = 0; k < sizeof fields / sizeof fields[0]; k++) {
        assert_true(mimas_fieldset_has(file, fields[k]) && mimas_fieldset_has(mem, fields[k]));
        assert_int_equal(mimas_fieldset_read(file, fields[k], a, sa, &err), MIMAS_OK);
        assert_int_equal(mimas_fieldset_read(mem, fields[k], b, sb, &err), MIMAS_OK);
        same_values(a, b, 30);
        same_values(sa, sb, 30);
    }
    /* omega has standard errors; the strain rates have none */
    assert_int_equal(mimas_fieldset_read(file, "omega", a, sa, &err), MIMAS_OK);
    assert_true(isfinite(sa[5]) && sa[5] > 0);
    assert_int_equal(mimas_fieldset_read(file, "shear_rate", a, sa, &err), MIMAS_OK);
    assert_true(isnan(sa[5]) && isfinite(a[5]));
    /* a Cartesian name on a cylindrical grid */
    assert_false(mimas_fieldset_has(file, "v_x"));
    assert_int_equal(mimas_fieldset_read(file, "v_x", a, NULL, &err), MIMAS_EMISSING);
    assert_non_null(strstr(err.msg, "ring.h5: no field 'v_x'"));
    assert_false(mimas_fieldset_has(file, "../grid"));
    mimas_fieldset_close(file);
    mimas_fieldset_close(mem);
    mimas_average_free(avg);
    /* --grid none and Cartesian grids */
    avg = ring_average("none", &f);
    assert_int_equal(mimas_fieldset_from_average(&mem, avg, "none", &err), MIMAS_OK);
    assert_int_equal(mimas_fieldset_grid_of(mem)->kind, MIMAS_FIELDSET_NONE);
    assert_int_equal(mimas_fieldset_grid_of(mem)->cells, 1);
    mimas_fieldset_close(mem);
    mimas_average_free(avg);
    avg = ring_average("x=-0.11:0.11:2,y=-0.11:0.11:2", &f);
    assert_int_equal(mimas_fieldset_from_average(&mem, avg, "cart", &err), MIMAS_OK);
    assert_int_equal(mimas_fieldset_grid_of(mem)->kind, MIMAS_FIELDSET_CARTESIAN);
    assert_true(mimas_fieldset_has(mem, "v_x") && !mimas_fieldset_has(mem, "omega"));
    mimas_fieldset_close(mem);
    mimas_average_free(avg);
    mimas_frame_free(&f);
}

static void test_other_files_are_refused(void **state)
{
    (void)state;
    mimas_error err;
    mimas_fieldset *fs;
    /* a particle file in the native format */
    mimas_frame f;
    mimas_frame_init(&f);
    mimas_average_free(ring_average("none", &f));
    mimas_writer *w;
    mimas_writer_options o;
    mimas_writer_options_default(&o);
    const char *native = scratch_path("particles.h5");
    assert_int_equal(mimas_writer_open(&w, native, &o, &err), MIMAS_OK);
    assert_int_equal(mimas_writer_append(w, &f, &err), MIMAS_OK);
    assert_int_equal(mimas_writer_close(w, &err), MIMAS_OK);
    mimas_frame_free(&f);
    assert_false(mimas_fieldset_probe(native));
    assert_int_equal(mimas_fieldset_open(&fs, native, &err), MIMAS_EDATA);
    assert_non_null(strstr(err.msg, "particles.h5: not a field file of mimas average"));
    /* no file, a text file */
    assert_false(mimas_fieldset_probe(scratch_path("nothing.h5")));
    assert_int_equal(mimas_fieldset_open(&fs, scratch_path("nothing.h5"), &err), MIMAS_EDATA);
    assert_non_null(strstr(err.msg, "nothing.h5: cannot open"));
    FILE *fp = fopen(scratch_path("text.h5"), "w");
    fputs("z Rc\n", fp);
    fclose(fp);
    assert_false(mimas_fieldset_probe(scratch_path("text.h5")));
    assert_int_equal(mimas_fieldset_open(&fs, scratch_path("text.h5"), &err), MIMAS_EDATA);
    assert_non_null(strstr(err.msg, "text.h5: not an HDF5 file"));
    /* a field file of a newer major version */
    mimas_frame_init(&f);
    mimas_average *avg = ring_average("r=0.0147:0.11:4", &f);
    mimas_frame_free(&f);
    mimas_fields_file *ff;
    const char *newer = scratch_path("newer.h5");
    assert_int_equal(mimas_fields_open(&ff, newer, NULL, &err), MIMAS_OK);
    assert_int_equal(mimas_fields_finish(ff, avg, NULL, &err), MIMAS_OK);
    mimas_average_free(avg);
    hid_t file = H5Fopen(newer, H5F_ACC_RDWR, H5P_DEFAULT);
    hid_t g = H5Gopen2(file, "/mimas", H5P_DEFAULT);
    int v[2] = {MIMAS_FIELDS_VERSION_MAJOR + 1, 0};
    assert_int_equal(h5_attr_write_ints(g, "fields_version", v, 2), 0);
    H5Gclose(g);
    H5Fclose(file);
    assert_true(mimas_fieldset_probe(newer));
    assert_int_equal(mimas_fieldset_open(&fs, newer, &err), MIMAS_EDATA);
    assert_non_null(strstr(err.msg, "newer.h5: field file version 2.0 is newer than this mimas "
                                    "reads (1.x)"));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_file_reads_back_as_the_average),
        cmocka_unit_test(test_other_files_are_refused),
    };
    return cmocka_run_group_tests(tests, scratch_setup, scratch_teardown);
}
