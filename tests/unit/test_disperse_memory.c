/* mimas disperse beyond its memory: 2000 particles over 1000 and 2000
 * frames with velocities (96 and 192 MB of trajectories) analysed with
 * --memory 32M go through the scratch file, raise the peak resident memory
 * by less than 32 MB either way (flat in the frames), leave no file behind,
 * and give the very numbers of the same analysis in memory (the particles
 * are transformed in the same blocks and groups either way).  Not run under
 * the sanitizers: their quarantine keeps freed memory resident. */
#include <config.h>

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include <dirent.h>
#include <gsl/gsl_randist.h>
#include <gsl/gsl_rng.h>
#include <hdf5.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>

#include "disperse.h"
#include "scratch.h"

#define N 2000

static long peak_kb(void)
{
    struct rusage u;
    getrusage(RUSAGE_SELF, &u);
    return u.ru_maxrss;
}

/* The same walk on every call: particles enter over the first 100 frames
 * and the last 100 leave early, one in 7 skips a frame now and then. */
static mimas_disperse *analyse(int T, size_t memory, const char *dir)
{
    static const char *cohorts[] = {"all", "inserted:0:0.5"};
    mimas_disperse_options o;
    memset(&o, 0, sizeof o);
    o.axis = "0,0,0,1,1,0";
    o.vacf = 1;
    o.remove_drift = 1;
    o.cohorts = cohorts;
    o.ncohorts = 2;
    o.memory = memory;
    o.scratch_dir = dir;
    mimas_disperse *d;
    mimas_error err;
    assert_int_equal(mimas_disperse_create(&d, &o, &err), MIMAS_OK);
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    gsl_rng_set(rng, 5);
    static double x[N][3];
    for (int i = 0; i < N; i++)
        for (int c = 0; c < 3; c++)
            x[i][c] = gsl_rng_uniform(rng);
    mimas_frame f;
    mimas_frame_init(&f);
    for (int t = 0; t < T; t++) {
        mimas_frame_clear(&f);
        f.time = 0.01 * t;
        assert_int_equal(mimas_table_set_present(&f.particles, &mimas_particles_desc,
                                                 MIMAS_P_ID | MIMAS_P_POS | MIMAS_P_VEL, &err),
                         MIMAS_OK);
        assert_int_equal(mimas_table_resize(&f.particles, &mimas_particles_desc, N, &err),
                         MIMAS_OK);
        size_t n = 0;
        for (int i = 0; i < N; i++) {
            double v[3];
            for (int c = 0; c < 3; c++) {
                v[c] = 0.1 * (c + 1) + gsl_ran_gaussian(rng, 0.3);
                x[i][c] += 0.01 * v[c];
            }
            int absent = t < i / 20 || (i >= N - 100 && t > T - (i - N + 100)) ||
                         (i % 7 == 0 && gsl_rng_uniform(rng) < 0.05);
            if (absent)
                continue;
            f.particles.id[n] = i;
            memcpy(f.particles.pos[n], x[i], sizeof x[i]);
            memcpy(f.particles.vel[n], v, sizeof v);
            n++;
        }
        mimas_table_resize(&f.particles, &mimas_particles_desc, n, &err);
        assert_int_equal(mimas_disperse_add(d, &f, &err), MIMAS_OK);
    }
    mimas_frame_free(&f);
    gsl_rng_free(rng);
    assert_int_equal(mimas_disperse_finish(d, &err), MIMAS_OK);
    return d;
}

static int same(double a, double b) { return a == b || (isnan(a) && isnan(b)); }

static size_t files_in(const char *dir)
{
    DIR *d = opendir(dir);
    size_t n = 0;
    struct dirent *e;
    while ((e = readdir(d)))
        n += e->d_name[0] != '.' || (strcmp(e->d_name, ".") && strcmp(e->d_name, ".."));
    closedir(d);
    return n;
}

static void test_scratch_equals_memory(void **state)
{
    (void)state;
    const char *dir = scratch_path("");
    /* HDF5 set up before measuring: the limit is on the work */
    H5open();
    const size_t limit = 32u << 20;
    long before = peak_kb();
    mimas_disperse *disk = analyse(1000, limit, dir);
    long grown = peak_kb() - before;
    print_message("1000 frames: peak memory grew by %ld kB with --memory %zu kB\n", grown,
                  limit / 1024);
    assert_true(grown * 1024 < (long)limit);
    mimas_disperse_free(disk);
    disk = analyse(2000, limit, dir);
    grown = peak_kb() - before;
    print_message("2000 frames: peak memory grew by %ld kB with --memory %zu kB\n", grown,
                  limit / 1024);
    assert_true(grown * 1024 < (long)limit);
    const mimas_disperse_result *a = mimas_disperse_result_of(disk);
    assert_true(a->scratch);
    assert_int_equal(files_in(dir), 0);

    mimas_disperse *mem = analyse(2000, 1u << 30, dir);
    const mimas_disperse_result *b = mimas_disperse_result_of(mem);
    assert_false(b->scratch);
    assert_int_equal(a->lags, b->lags);
    assert_int_equal(a->particles, b->particles);
    for (size_t k = 0; k < a->lags; k++) {
        assert_true(same(a->count[k], b->count[k]));
        for (int c = 0; c < MIMAS_DC_COUNT; c++) {
            assert_true(same(a->msd[k * MIMAS_DC_COUNT + c], b->msd[k * MIMAS_DC_COUNT + c]));
            assert_true(same(a->vacf[k * MIMAS_DC_COUNT + c], b->vacf[k * MIMAS_DC_COUNT + c]));
        }
    }
    assert_int_equal(a->ndiffusion, b->ndiffusion);
    for (size_t i = 0; i < a->ndiffusion; i++) {
        assert_true(same(a->diffusion[i].D, b->diffusion[i].D));
        assert_true(same(a->diffusion[i].D_err, b->diffusion[i].D_err));
    }
    for (size_t k = 0; k < a->ncohorts; k++) {
        assert_int_equal(a->cohorts[k].nrows, b->cohorts[k].nrows);
        for (size_t i = 0; i < a->cohorts[k].nrows; i++) {
            assert_true(same(a->cohorts[k].rows[i].sigma2_axial,
                             b->cohorts[k].rows[i].sigma2_axial));
            assert_true(same(a->cohorts[k].rows[i].mean[2], b->cohorts[k].rows[i].mean[2]));
        }
    }
    mimas_disperse_free(disk);
    mimas_disperse_free(mem);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_scratch_equals_memory),
    };
    return cmocka_run_group_tests(tests, scratch_setup, scratch_teardown);
}
