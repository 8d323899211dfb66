/* Memory does not grow with the number of frames: reading and averaging 100
 * frames (a native file, a LAMMPS dump) takes no more memory than 20. */
#include <config.h>

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <unistd.h>

#include "average.h"
#include "native.h"
#include "random_frame.h"
#include "reader.h"

static char dir[] = "/tmp/mimas-test-memory-XXXXXX";

static long peak_kb(void)
{
    struct rusage u;
    getrusage(RUSAGE_SELF, &u);
    return u.ru_maxrss;
}

static void write_native(const char *path, int frames)
{
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    random_frame_spec s = {2000, 6000, 0, 0, 0, 1, 0};
    mimas_writer *w;
    mimas_error err;
    assert_int_equal(mimas_writer_open(&w, path, NULL, &err), 0);
    mimas_frame f;
    mimas_frame_init(&f);
    for (int k = 0; k < frames; k++) {
        random_frame(&f, rng, &s, k);
        for (size_t i = 0; i < f.particles.n; i++)
            f.particles.radius[i] = 1e-3; /* positive radii */
        assert_int_equal(mimas_writer_append(w, &f, &err), 0);
    }
    assert_int_equal(mimas_writer_close(w, &err), 0);
    mimas_frame_free(&f);
    gsl_rng_free(rng);
}

static void write_dump(const char *path, int frames)
{
    FILE *fp = fopen(path, "w");
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    for (int k = 0; k < frames; k++) {
        fprintf(fp, "ITEM: TIMESTEP\n%d\nITEM: NUMBER OF ATOMS\n2000\nITEM: BOX BOUNDS pp pp pp\n"
                    "0 1\n0 1\n0 1\nITEM: ATOMS id x y z vx vy vz radius mass\n", k);
        for (int i = 0; i < 2000; i++)
            fprintf(fp, "%d %g %g %g %g %g %g 0.01 0.001\n", i + 1, gsl_rng_uniform(rng),
                    gsl_rng_uniform(rng), gsl_rng_uniform(rng), gsl_rng_uniform(rng),
                    gsl_rng_uniform(rng), gsl_rng_uniform(rng));
    }
    fclose(fp);
    gsl_rng_free(rng);
}

static void average_all(const char *path)
{
    const char *inputs[1] = {path};
    mimas_reader *r;
    mimas_error err;
    assert_int_equal(mimas_reader_open(&r, inputs, 1, NULL, &err), 0);
    mimas_average_options o;
    memset(&o, 0, sizeof o);
    assert_int_equal(mimas_grid_parse(&o.grid, "x=0:1:10,y=0:1:10", NULL, &err), 0);
    assert_int_equal(mimas_weight_parse(&o.weight, "bins", &err), 0);
    o.spread = 1;
    o.threads = 1;
    mimas_average *a;
    assert_int_equal(mimas_average_create(&a, &o, &err), 0);
    mimas_frame f;
    mimas_frame_init(&f);
    int rc;
    while ((rc = mimas_reader_next(r, &f, &err)) == MIMAS_OK)
        if (mimas_average_add(a, &f, &err))
            fail_msg("%s", err.msg);
    assert_int_equal(rc, MIMAS_END);
    mimas_frame_free(&f);
    mimas_average_free(a);
    mimas_reader_close(r);
}

static void check_flat(void (*write)(const char *, int), const char *suffix)
{
    char few[300], many[300];
    snprintf(few, sizeof few, "%s/few.%s", dir, suffix);
    snprintf(many, sizeof many, "%s/many.%s", dir, suffix);
    write(few, 20);
    write(many, 100);
    average_all(few);
    long after_few = peak_kb();
    average_all(many);
    long after_many = peak_kb();
    /* a frame holds ~ 2000 particles (~ 200 kB): a frame kept per frame
     * would add ~ 16 MB over the 80 extra frames */
    if (after_many - after_few > 2048)
        fail_msg("peak memory grew by %ld kB from 20 to 100 frames", after_many - after_few);
    remove(few);
    remove(many);
}

static void test_native_stream(void **state)
{
    (void)state;
    check_flat(write_native, "h5");
}

static void test_dump_stream(void **state)
{
    (void)state;
    check_flat(write_dump, "dump");
}

static int setup(void **state)
{
    (void)state;
    return mkdtemp(dir) ? 0 : -1;
}

static int teardown(void **state)
{
    (void)state;
    return rmdir(dir);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_native_stream),
        cmocka_unit_test(test_dump_stream),
    };
    return cmocka_run_group_tests_name("stream_memory", tests, setup, teardown);
}
