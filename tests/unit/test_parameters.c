/* Run parameters and observables through the files: the scenario's keys as
 * parameters (every key of the scenario type, [contact A-B] sections where
 * they differ), their round trip through the native writer and reader
 * (kinds, bit-exact values, units, order), the reader's merge of several
 * inputs, the field file of an average, and the per-frame observables
 * (values back, the same names every frame). */
#include <config.h>

#include <hdf5.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#include "assert_close.h"
#include "fieldset.h"
#include "native.h"
#include "output_h5.h"
#include "random_frame.h"
#include "reader.h"
#include "scenario.h"
#include "scratch.h"

static void load(sim_scenario *sc, const char *text)
{
    mimas_error err;
    if (sim_scenario_load_string(sc, text, "test", &err))
        fail_msg("%s", err.msg);
}

/* The number of keys sim_scenario_print writes for the scenario type: its
 * "key = value" lines, counted independently of the parameter code. */
static size_t printed_keys(const sim_scenario *sc)
{
    char *buf = NULL;
    size_t len = 0, n = 0;
    FILE *fp = open_memstream(&buf, &len);
    sim_scenario_print(sc, fp);
    fclose(fp);
    for (char *line = strtok(buf, "\n"); line; line = strtok(NULL, "\n"))
        n += line[0] != '#' && line[0] != ';' && line[0] != '[' && strstr(line, " = ") != NULL;
    free(buf);
    return n;
}

static void test_scenario_parameters(void **state)
{
    (void)state;
    sim_scenario sc;
    load(&sc, "[scenario]\ntype = ringshear\n[particles]\nliquid_content = 0.05\n"
              "[contact]\nfriction = 0.5\n[contact wall-1]\nfriction = 0.3\n"
              "[ringshear]\nomega = 0.5\n");
    mimas_parameters ps;
    mimas_parameters_init(&ps);
    mimas_error err;
    assert_int_equal(sim_scenario_parameters(&sc, &ps, &err), MIMAS_OK);
    /* every key of the type, plus the one pair section that differs */
    assert_int_equal(ps.n, printed_keys(&sc) + 1);
    const mimas_parameter *q = mimas_parameters_get(&ps, "particles.liquid_content");
    assert_non_null(q);
    assert_int_equal(q->kind, MIMAS_PARAM_REAL);
    assert_true(q->value == 0.05);
    assert_string_equal(q->text, "0.05");
    q = mimas_parameters_get(&ps, "contact.friction");
    assert_non_null(q);
    assert_true(q->value == 0.5);
    q = mimas_parameters_get(&ps, "contact wall-1.friction");
    assert_non_null(q);
    assert_true(q->value == 0.3);
    assert_null(mimas_parameters_get(&ps, "contact wall-1.stiffness_normal"));
    q = mimas_parameters_get(&ps, "ringshear.omega");
    assert_string_equal(q->unit, "rad s-1");
    q = mimas_parameters_get(&ps, "contact.model");
    assert_int_equal(q->kind, MIMAS_PARAM_TEXT);
    assert_string_equal(q->text, "linear");
    q = mimas_parameters_get(&ps, "ringshear.rough_bottom");
    assert_string_equal(q->text, "yes");
    q = mimas_parameters_get(&ps, "ringshear.count");
    assert_int_equal(q->kind, MIMAS_PARAM_INTEGER);
    assert_null(mimas_parameters_get(&ps, "box.count")); /* another type's key */
    mimas_parameters_free(&ps);
}

/* A native file of two random frames (steps step0, step0 + 10; times 0.5
 * apart) with the scenario's parameters and two observables; value k of
 * observable q is 10 q + k + 0.1. */
static void write_run(const char *path, const char *scenario, int observe, int64_t step0)
{
    sim_scenario sc;
    load(&sc, scenario);
    mimas_parameters ps;
    mimas_parameters_init(&ps);
    mimas_error err;
    assert_int_equal(sim_scenario_parameters(&sc, &ps, &err), MIMAS_OK);
    mimas_writer *w;
    assert_int_equal(mimas_writer_open(&w, path, NULL, &err), MIMAS_OK);
    /* the parameters before the first frame (attributes, before SWMR) */
    assert_int_equal(mimas_writer_parameters(w, "scenario", &ps, &err), MIMAS_OK);
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    mimas_frame f;
    mimas_frame_init(&f);
    random_frame_spec spec = {50, 60, 5, 0, 0, 1, 1};
    for (int k = 0; k < 2; k++) {
        assert_int_equal(random_frame(&f, rng, &spec, step0 + 10 * k), 0);
        f.time = 0.05 * (double)step0 + 0.5 * k;
        mimas_observable obs[2] = {{"a_energy", "J", 0.1 + k}, {"b_count", NULL, 10.1 + k}};
        if (observe)
            assert_int_equal(mimas_writer_observe(w, obs, 2, &err), MIMAS_OK);
        assert_int_equal(mimas_writer_append(w, &f, &err), MIMAS_OK);
    }
    /* and not after it */
    assert_int_equal(mimas_writer_parameters(w, "scenario", &ps, &err), MIMAS_EUSAGE);
    assert_non_null(strstr(err.msg, "before the first frame"));
    assert_int_equal(mimas_writer_close(w, &err), MIMAS_OK);
    mimas_frame_free(&f);
    gsl_rng_free(rng);
    mimas_parameters_free(&ps);
}

static const char *const wet = "[scenario]\ntype = ringshear\n[particles]\n"
                               "liquid_content = 0.05\n[ringshear]\nomega = 0.3\n";

static void test_native_round_trip(void **state)
{
    (void)state;
    write_run(scratch_path("run.h5"), wet, 1, 0);
    sim_scenario sc;
    load(&sc, wet);
    mimas_parameters want;
    mimas_parameters_init(&want);
    mimas_error err;
    assert_int_equal(sim_scenario_parameters(&sc, &want, &err), MIMAS_OK);
    mimas_native *r;
    assert_int_equal(mimas_native_open(&r, scratch_path("run.h5"), &err), MIMAS_OK);
    const mimas_parameters *got = mimas_native_parameters(r);
    assert_int_equal(got->n, want.n);
    for (size_t k = 0; k < want.n; k++) {
        /* the order written, the kind, the text and the unit; numbers bit for bit */
        assert_string_equal(got->p[k].name, want.p[k].name);
        assert_int_equal(got->p[k].kind, want.p[k].kind);
        assert_string_equal(got->p[k].text, want.p[k].text);
        assert_string_equal(got->p[k].unit, want.p[k].unit);
        if (want.p[k].kind != MIMAS_PARAM_TEXT)
            assert_memory_equal(&got->p[k].value, &want.p[k].value, sizeof(double));
    }
    /* the observables, in name order, with their units and values */
    assert_int_equal(mimas_native_observables(r), 2);
    const char *unit;
    assert_string_equal(mimas_native_observable_name(r, 0, &unit), "a_energy");
    assert_string_equal(unit, "J");
    assert_string_equal(mimas_native_observable_name(r, 1, &unit), "b_count");
    assert_string_equal(unit, "");
    double v[2];
    assert_int_equal(mimas_native_observable_read(r, 1, 0, 2, v, &err), MIMAS_OK);
    assert_true(v[0] == 10.1 && v[1] == 11.1);
    assert_int_equal(mimas_native_observable_read(r, 0, 1, 1, v, &err), MIMAS_OK);
    assert_true(v[0] == 1.1);
    assert_int_equal(mimas_native_observable_read(r, 0, 1, 2, v, &err), MIMAS_EUSAGE);
    mimas_native_close(r);
    mimas_parameters_free(&want);
    /* h5py's view: the attribute is a plain float64 */
    hid_t f = H5Fopen(scratch_path("run.h5"), H5F_ACC_RDONLY, H5P_DEFAULT);
    hid_t g = H5Gopen2(f, "/parameters/scenario", H5P_DEFAULT);
    hid_t a = H5Aopen(g, "particles.liquid_content", H5P_DEFAULT);
    double D = 0;
    hid_t t = H5Aget_type(a);
    assert_int_equal(H5Tget_class(t), H5T_FLOAT);
    assert_true(H5Aread(a, H5T_NATIVE_DOUBLE, &D) >= 0);
    assert_true(D == 0.05);
    assert_true(H5Aexists(g, "ringshear.omega.unit") > 0);
    H5Tclose(t);
    H5Aclose(a);
    H5Gclose(g);
    H5Fclose(f);
}

static void test_observables_every_frame(void **state)
{
    (void)state;
    mimas_error err;
    mimas_writer *w;
    assert_int_equal(mimas_writer_open(&w, scratch_path("obs.h5"), NULL, &err), MIMAS_OK);
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    mimas_frame f;
    mimas_frame_init(&f);
    random_frame_spec spec = {20, 0, 0, 0, 0, 0, 0};
    assert_int_equal(random_frame(&f, rng, &spec, 0), 0);
    mimas_observable obs[2] = {{"x", NULL, 1}, {"y", NULL, 2}};
    assert_int_equal(mimas_writer_observe(w, obs, 2, &err), MIMAS_OK);
    assert_int_equal(mimas_writer_append(w, &f, &err), MIMAS_OK);
    /* the same names in another order are the same observables (a later
     * step: a reader refuses repeated ones) */
    f.step = 10;
    f.time += 0.1;
    mimas_observable swapped[2] = {{"y", NULL, 4}, {"x", NULL, 3}};
    assert_int_equal(mimas_writer_observe(w, swapped, 2, &err), MIMAS_OK);
    assert_int_equal(mimas_writer_append(w, &f, &err), MIMAS_OK);
    mimas_observable other[1] = {{"z", NULL, 1}};
    assert_int_equal(mimas_writer_observe(w, other, 1, &err), MIMAS_EDATA);
    assert_non_null(strstr(err.msg, "other observables than the first frame's"));
    /* a frame without them */
    assert_int_equal(mimas_writer_append(w, &f, &err), MIMAS_EDATA);
    assert_non_null(strstr(err.msg, "without the observables"));
    assert_int_equal(mimas_writer_close(w, &err), MIMAS_OK);
    mimas_native *r;
    assert_int_equal(mimas_native_open(&r, scratch_path("obs.h5"), &err), MIMAS_OK);
    assert_int_equal(mimas_native_frames(r), 2);
    double x[2], y[2];
    assert_int_equal(mimas_native_observable_read(r, 0, 0, 2, x, &err), MIMAS_OK);
    assert_int_equal(mimas_native_observable_read(r, 1, 0, 2, y, &err), MIMAS_OK);
    assert_true(x[0] == 1 && x[1] == 3 && y[0] == 2 && y[1] == 4);
    assert_int_equal(mimas_native_parameters(r)->n, 0);
    mimas_native_close(r);
    /* observables must start with the first frame */
    assert_int_equal(mimas_writer_open(&w, scratch_path("late.h5"), NULL, &err), MIMAS_OK);
    assert_int_equal(mimas_writer_append(w, &f, &err), MIMAS_OK);
    assert_int_equal(mimas_writer_observe(w, obs, 2, &err), MIMAS_EDATA);
    mimas_writer_abort(w);
    mimas_frame_free(&f);
    gsl_rng_free(rng);
}

static void test_reader_merges_inputs(void **state)
{
    (void)state;
    /* the second run continues the first's clock (a reader refuses repeated steps) */
    write_run(scratch_path("m1.h5"), wet, 0, 0);
    write_run(scratch_path("m2.h5"), "[scenario]\ntype = ringshear\n[particles]\n"
                                     "liquid_content = 0.01\n[ringshear]\nomega = 0.3\n", 0,
              20);
    mimas_error err;
    mimas_reader *r;
    const char *one[1] = {scratch_path("m1.h5")};
    assert_int_equal(mimas_reader_open(&r, one, 1, NULL, &err), MIMAS_OK);
    const mimas_parameter *q = mimas_parameters_get(mimas_reader_parameters(r),
                                                    "particles.liquid_content");
    assert_true(q && q->kind == MIMAS_PARAM_REAL && q->value == 0.05);
    mimas_reader_close(r);
    const char *both[2] = {scratch_path("m1.h5"), scratch_path("m2.h5")};
    assert_int_equal(mimas_reader_open(&r, both, 2, NULL, &err), MIMAS_OK);
    const mimas_parameters *ps = mimas_reader_parameters(r);
    q = mimas_parameters_get(ps, "particles.liquid_content");
    assert_true(q && q->kind == MIMAS_PARAM_MIXED && isnan(q->value));
    assert_string_equal(q->text, "mixed");
    q = mimas_parameters_get(ps, "ringshear.omega");
    assert_true(q && q->kind == MIMAS_PARAM_REAL && q->value == 0.3);
    /* the field file of an average keeps them, the mixed one as "mixed" */
    mimas_average_options o;
    memset(&o, 0, sizeof o);
    assert_int_equal(mimas_grid_parse(&o.grid, "x=0:1:2", NULL, &err), MIMAS_OK);
    assert_int_equal(mimas_weight_parse(&o.weight, "bins", &err), MIMAS_OK);
    o.spread = 1;
    mimas_average *avg;
    assert_int_equal(mimas_average_create(&avg, &o, &err), MIMAS_OK);
    mimas_frame f;
    mimas_frame_init(&f);
    int rc;
    while ((rc = mimas_reader_next(r, &f, &err)) == MIMAS_OK)
        assert_int_equal(mimas_average_add(avg, &f, &err), MIMAS_OK);
    assert_int_equal(rc, MIMAS_END);
    assert_int_equal(mimas_average_frames(avg), 4);
    mimas_fields_file *ff;
    assert_int_equal(mimas_fields_open(&ff, scratch_path("fields.h5"), NULL, &err), MIMAS_OK);
    assert_int_equal(mimas_fields_parameters(ff, "scenario", ps, &err), MIMAS_OK);
    assert_int_equal(mimas_fields_finish(ff, avg, NULL, &err), MIMAS_OK);
    mimas_average_free(avg);
    mimas_frame_free(&f);
    mimas_fieldset *fs;
    assert_int_equal(mimas_fieldset_open(&fs, scratch_path("fields.h5"), &err), MIMAS_OK);
    const mimas_parameters *back = mimas_fieldset_parameters(fs);
    assert_int_equal(back->n, ps->n);
    for (size_t k = 0; k < ps->n; k++) {
        assert_string_equal(back->p[k].name, ps->p[k].name);
        assert_int_equal(back->p[k].kind, ps->p[k].kind);
        assert_string_equal(back->p[k].text, ps->p[k].text);
        assert_string_equal(back->p[k].unit, ps->p[k].unit);
    }
    mimas_fieldset_close(fs);
    mimas_reader_close(r);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_scenario_parameters),
        cmocka_unit_test(test_native_round_trip),
        cmocka_unit_test(test_observables_every_frame),
        cmocka_unit_test(test_reader_merges_inputs),
    };
    return cmocka_run_group_tests(tests, scratch_setup, scratch_teardown);
}
