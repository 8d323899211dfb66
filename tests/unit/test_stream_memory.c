/* Memory does not grow with the number of frames: streaming and averaging a
 * native file and a LAMMPS dump of 300 frames, the peak memory after frame
 * 300 is that after frame 100 (HDF5's caches warm up over the first ~150
 * frames and then stay; a frame kept per frame would add ~40 MB). */
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
#include "scratch.h"
#include "reader.h"


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
    mimas_writer_options o;
    mimas_writer_options_default(&o);
    o.deflate = 0;
    assert_int_equal(mimas_writer_open(&w, path, &o, &err), 0);
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

static void average_all(const char *path, long *peak_early, long *peak_late)
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
    int rc, k = 0;
    while ((rc = mimas_reader_next(r, &f, &err)) == MIMAS_OK) {
        if (mimas_average_add(a, &f, &err))
            fail_msg("%s", err.msg);
        if (++k == 150)
            *peak_early = peak_kb();
    }
    *peak_late = peak_kb();
    assert_int_equal(k, 300);
    assert_int_equal(rc, MIMAS_END);
    mimas_frame_free(&f);
    mimas_average_free(a);
    mimas_reader_close(r);
}

static void check_flat(void (*write)(const char *, int), const char *suffix)
{

    char name[32];
    snprintf(name, sizeof name, "frames.%s", suffix);
    const char *path = scratch_path(name);
    write(path, 300);
    long early = 0, late = 0;
    average_all(path, &early, &late);
    remove(path);
    if (late - early > 1024)
        fail_msg("peak memory grew by %ld kB from frame 150 to frame 300", late - early);
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

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_native_stream),
        cmocka_unit_test(test_dump_stream),
    };
    return cmocka_run_group_tests_name("stream_memory", tests, scratch_setup, scratch_teardown);
}
