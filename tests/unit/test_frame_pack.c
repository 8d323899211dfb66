/* Frames packed into one buffer and unpacked again (the transport between MPI
 * ranks): bit-identical round trips with every optional quantity, extras,
 * the tube and the gas fields; any truncation or corruption is an error, not
 * a crash. */
#include <config.h>

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "frame_pack.h"
#include "random_frame.h"

static void add_tube_and_gas(mimas_frame *f)
{
    f->tube.present = 1;
    f->tube.origin[2] = -0.25;
    f->tube.direction[2] = 1.0;
    f->tube.radius = 0.0035;
    f->tube.length = 0.525;
    assert_int_equal(mimas_gas_resize(&f->gas, 5, 2, 3, NULL), MIMAS_OK);
    for (int d = 0; d < 3; d++)
        f->gas.origin[d] = -0.1 * d, f->gas.spacing[d] = 0.0035;
    for (size_t c = 0; c < 30; c++) {
        f->gas.pressure[c] = 101325.0 + (double)c;
        f->gas.porosity[c] = 0.4 + 0.01 * (double)c;
        for (int d = 0; d < 3; d++)
            f->gas.velocity[c][d] = (double)c * (d + 1);
    }
}

static void check_round_trip(const random_frame_spec *spec, int gas)
{
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    gsl_rng_set(rng, 7);
    mimas_frame a, b;
    mimas_frame_init(&a);
    mimas_frame_init(&b);
    assert_int_equal(random_frame(&a, rng, spec, 1234), MIMAS_OK);
    if (gas)
        add_tube_and_gas(&a);
    /* b starts dirty: a different frame with other quantities */
    random_frame_spec other = {40, 30, 5, !spec->optional, !spec->triclinic, 1, 1};
    assert_int_equal(random_frame(&b, rng, &other, 99), MIMAS_OK);
    if (!gas)
        add_tube_and_gas(&b);
    mimas_bytes buf = {0};
    mimas_error err;
    assert_int_equal(mimas_frame_pack(&a, &buf, &err), MIMAS_OK);
    assert_int_equal(mimas_frame_unpack(&b, buf.data, buf.n, &err), MIMAS_OK);
    char why[256] = "";
    if (!frames_equal(&a, &b, why, sizeof why))
        fail_msg("round trip differs: %s", why);
    assert_true(a.step == b.step && a.time == b.time);
    assert_int_equal(a.has_contacts, b.has_contacts);
    assert_int_equal(a.has_walls, b.has_walls);
    assert_int_equal(a.tube.present, b.tube.present);
    assert_int_equal(a.gas.present, b.gas.present);
    if (gas) {
        assert_memory_equal(&a.tube, &b.tube, sizeof a.tube);
        assert_int_equal(mimas_gas_cells(&b.gas), 30);
        assert_memory_equal(a.gas.pressure, b.gas.pressure, 30 * sizeof(double));
        assert_memory_equal(a.gas.porosity, b.gas.porosity, 30 * sizeof(double));
        assert_memory_equal(a.gas.velocity, b.gas.velocity, 90 * sizeof(double));
        assert_memory_equal(a.gas.spacing, b.gas.spacing, sizeof a.gas.spacing);
    }
    /* every truncation is refused */
    for (size_t n = 0; n < buf.n; n += 1 + n / 7)
        assert_int_equal(mimas_frame_unpack(&b, buf.data, n, &err), MIMAS_EDATA);
    /* a trailing byte too many, or a wrong magic */
    unsigned char *longer = malloc(buf.n + 1);
    memcpy(longer, buf.data, buf.n);
    longer[buf.n] = 0;
    assert_int_equal(mimas_frame_unpack(&b, longer, buf.n + 1, &err), MIMAS_EDATA);
    longer[0] ^= 0xff;
    assert_int_equal(mimas_frame_unpack(&b, longer, buf.n, &err), MIMAS_EDATA);
    free(longer);
    mimas_bytes_free(&buf);
    mimas_frame_free(&a);
    mimas_frame_free(&b);
    gsl_rng_free(rng);
}

static void test_plain_frame(void **state)
{
    (void)state;
    random_frame_spec s = {200, 0, 0, 0, 0, 0, 0};
    check_round_trip(&s, 0);
}

static void test_everything(void **state)
{
    (void)state;
    random_frame_spec s = {500, 900, 60, 1, 1, 1, 1};
    check_round_trip(&s, 1);
}

static void test_empty_frame(void **state)
{
    (void)state;
    mimas_frame a, b;
    mimas_frame_init(&a);
    mimas_frame_init(&b);
    a.step = 5;
    a.time = 0.5;
    a.has_contacts = 1;
    a.box.hi[0] = a.box.hi[1] = a.box.hi[2] = 1.0;
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    random_frame_spec s = {30, 20, 3, 1, 0, 1, 1};
    assert_int_equal(random_frame(&b, rng, &s, 9), MIMAS_OK);
    mimas_bytes buf = {0};
    assert_int_equal(mimas_frame_pack(&a, &buf, NULL), MIMAS_OK);
    assert_int_equal(mimas_frame_unpack(&b, buf.data, buf.n, NULL), MIMAS_OK);
    char why[256] = "";
    if (!frames_equal(&a, &b, why, sizeof why))
        fail_msg("round trip differs: %s", why);
    assert_int_equal(b.particles.n, 0);
    assert_int_equal(b.contacts.n, 0);
    assert_true(b.has_contacts && !b.has_walls && b.step == 5 && b.time == 0.5);
    mimas_bytes_free(&buf);
    mimas_frame_free(&a);
    mimas_frame_free(&b);
    gsl_rng_free(rng);
}

/* A corrupted count inside the buffer cannot make the reader allocate or read
 * beyond it. */
static void test_corrupt_counts(void **state)
{
    (void)state;
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    random_frame_spec s = {50, 40, 4, 1, 0, 1, 1};
    mimas_frame a, b;
    mimas_frame_init(&a);
    mimas_frame_init(&b);
    assert_int_equal(random_frame(&a, rng, &s, 1), MIMAS_OK);
    mimas_bytes buf = {0};
    assert_int_equal(mimas_frame_pack(&a, &buf, NULL), MIMAS_OK);
    unsigned char *copy = malloc(buf.n);
    for (size_t at = 0; at + 8 <= buf.n; at += 8) {
        memcpy(copy, buf.data, buf.n);
        uint64_t huge = UINT64_MAX / 3;
        memcpy(copy + at, &huge, sizeof huge);
        mimas_error err;
        int rc = mimas_frame_unpack(&b, copy, buf.n, &err);
        /* a changed double may still unpack; a changed count must not */
        assert_true(rc == MIMAS_OK || rc == MIMAS_EDATA);
    }
    free(copy);
    mimas_bytes_free(&buf);
    mimas_frame_free(&a);
    mimas_frame_free(&b);
    gsl_rng_free(rng);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_plain_frame),
        cmocka_unit_test(test_everything),
        cmocka_unit_test(test_empty_frame),
        cmocka_unit_test(test_corrupt_counts),
    };
    return cmocka_run_group_tests_name("frame_pack", tests, NULL, NULL);
}
