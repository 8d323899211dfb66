/* Trajectories by id (averaging/trajectories.h): unwrapping across periodic
 * faces many times, by image flags and by the minimum image, orthogonal
 * and tilted boxes, against the straight lines the particles were moved on;
 * the quarter-box count; equal frame spacing; slots of inserted and removed
 * particles, repeated ids, missing quantities; the drift.  The store holds
 * the same records in memory and through its scratch file (slots growing,
 * chunks ended early), and spills on demand. */
#include <config.h>

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "assert_close.h"
#include "particle_frame.h"
#include "trajectories.h"

#define frame_of(f, n, bits, time) \
    assert_int_equal(particle_frame(f, n, bits, time, NULL), MIMAS_OK)

static mimas_trajectories *open_traj(int velocities)
{
    mimas_traj_options o = {NULL, 0, 0, velocities, 64u << 20, NULL};
    mimas_trajectories *t;
    mimas_error err;
    assert_int_equal(mimas_traj_create(&t, &o, &err), MIMAS_OK);
    return t;
}

/* All frames of slot s (3 values a record unless velocities). */
static double *read_slot(mimas_trajectories *t, size_t s)
{
    mimas_traj_store *st = mimas_traj_store_of(t);
    size_t T = mimas_traj_store_frames(st), nc = mimas_traj_store_ncomp(st);
    double *out = malloc(T * nc * sizeof *out);
    mimas_error err;
    assert_int_equal(mimas_traj_store_read(st, s, 1, out, &err), MIMAS_OK);
    return out;
}

/* x wrapped into [lo, lo + L) and the whole periods taken off. */
static double wrap(double x, double lo, double L, int *image)
{
    double k = floor((x - lo) / L);
    *image = (int)k;
    return x - k * L;
}

/* One particle on a straight line through a periodic cube (x, z periodic,
 * y not) crossing the x faces ~26 times and the z faces backwards. */
static void line_through_cube(int flags, double step)
{
    mimas_trajectories *t = open_traj(0);
    mimas_frame f;
    mimas_frame_init(&f);
    mimas_error err;
    const size_t T = 200;
    double x0[3] = {0.2, 0.5, 0.7}, v[3] = {step, 0.01, -0.07};
    for (size_t k = 0; k < T; k++) {
        frame_of(&f, 1, flags ? MIMAS_P_IMAGE : 0, 0.5 * (double)k);
        f.box = (mimas_box){{0, 0, 0}, {1, 2, 1}, 0, 0, 0, {1, 0, 1}};
        f.particles.id[0] = 7;
        for (int d = 0; d < 3; d++) {
            double x = x0[d] + v[d] * (double)k;
            int img = 0;
            f.particles.pos[0][d] = d == 1 ? x : wrap(x, 0, 1, &img);
            if (flags)
                f.particles.image[0][d] = img;
        }
        assert_int_equal(mimas_traj_add(t, &f, &err), MIMAS_OK);
    }
    assert_int_equal(mimas_traj_finish(t, &err), MIMAS_OK);
    double *u = read_slot(t, 0);
    int ambiguous = !flags && fabs(step) > 0.25;
    for (size_t k = 0; k < T && !(ambiguous && step > 0.5); k++)
        for (int d = 0; d < 3; d++)
            assert_close(u[3 * k + d], x0[d] + v[d] * (double)k, 1e-12);
    const mimas_traj_jumps *j = mimas_traj_jumps_seen(t);
    assert_int_equal(j->count, ambiguous ? T - 1 : 0);
    if (ambiguous) {
        assert_int_equal(j->first_id, 7);
        assert_close(j->first_time, 0.5, 0);
    }
    free(u);
    mimas_frame_free(&f);
    mimas_traj_free(t);
}

static void test_unwrap_min_image(void **state)
{
    (void)state;
    line_through_cube(0, 0.13);
    line_through_cube(0, -0.24);
}

static void test_unwrap_image_flags(void **state)
{
    (void)state;
    /* 0.6 of the box a frame: only the flags can tell */
    line_through_cube(1, 0.6);
    line_through_cube(1, 0.13);
}

static void test_quarter_box(void **state)
{
    (void)state;
    /* a move of 0.3 L still unwraps right, but is counted as ambiguous */
    line_through_cube(0, 0.3);
}

static void test_unwrap_without_flags_is_wrong_beyond_half(void **state)
{
    (void)state;
    /* 0.6 L a frame looks like -0.4 L: the minimum image goes backwards */
    mimas_trajectories *t = open_traj(0);
    mimas_frame f;
    mimas_frame_init(&f);
    mimas_error err;
    for (size_t k = 0; k < 5; k++) {
        frame_of(&f, 1, 0, (double)k);
        f.box = (mimas_box){{0, 0, 0}, {1, 1, 1}, 0, 0, 0, {1, 1, 1}};
        f.particles.id[0] = 1;
        int img;
        f.particles.pos[0][0] = wrap(0.1 + 0.6 * (double)k, 0, 1, &img);
        f.particles.pos[0][1] = f.particles.pos[0][2] = 0.5;
        assert_int_equal(mimas_traj_add(t, &f, &err), MIMAS_OK);
    }
    assert_int_equal(mimas_traj_finish(t, &err), MIMAS_OK);
    double *u = read_slot(t, 0);
    assert_close(u[3 * 4], 0.1 - 0.4 * 4, 1e-12);
    assert_int_equal(mimas_traj_jumps_seen(t)->count, 4);
    free(u);
    mimas_frame_free(&f);
    mimas_traj_free(t);
}

/* A tilted periodic box: positions wrapped in fractional coordinates. */
static void test_unwrap_triclinic(void **state)
{
    (void)state;
    const double L[3] = {1.0, 1.2, 0.9}, xy = 0.3, xz = -0.2, yz = 0.25;
    double e[3][3] = {{L[0], 0, 0}, {xy, L[1], 0}, {xz, yz, L[2]}};
    for (int flags = 0; flags < 2; flags++) {
        mimas_trajectories *t = open_traj(0);
        mimas_frame f;
        mimas_frame_init(&f);
        mimas_error err;
        const size_t T = 150;
        double x0[3] = {0.1, 0.2, 0.3}, v[3] = {0.11, -0.09, 0.07};
        for (size_t k = 0; k < T; k++) {
            frame_of(&f, 1, flags ? MIMAS_P_IMAGE : 0, 0.01 * (double)k);
            f.box = (mimas_box){{0, 0, 0}, {L[0], L[1], L[2]}, xy, xz, yz, {1, 1, 1}};
            f.particles.id[0] = 3;
            double x[3], fr[3];
            for (int d = 0; d < 3; d++)
                x[d] = x0[d] + v[d] * (double)k;
            /* fractional coordinates (a triangular solve), wrapped into [0, 1) */
            fr[2] = x[2] / L[2];
            fr[1] = (x[1] - fr[2] * yz) / L[1];
            fr[0] = (x[0] - fr[1] * xy - fr[2] * xz) / L[0];
            double k3[3];
            for (int d = 0; d < 3; d++)
                k3[d] = floor(fr[d]);
            for (int d = 0; d < 3; d++) {
                f.particles.pos[0][d] = x[d] - k3[0] * e[0][d] - k3[1] * e[1][d] - k3[2] * e[2][d];
                if (flags)
                    f.particles.image[0][d] = (int32_t)k3[d];
            }
            assert_int_equal(mimas_traj_add(t, &f, &err), MIMAS_OK);
        }
        assert_int_equal(mimas_traj_finish(t, &err), MIMAS_OK);
        double *u = read_slot(t, 0);
        for (size_t k = 0; k < T; k++)
            for (int d = 0; d < 3; d++)
                assert_close(u[3 * k + d], x0[d] + v[d] * (double)k, 1e-12);
        assert_int_equal(mimas_traj_jumps_seen(t)->count, 0);
        free(u);
        mimas_frame_free(&f);
        mimas_traj_free(t);
    }
}

static void test_frame_spacing(void **state)
{
    (void)state;
    const double bad[][4] = {{0, 0.1, 0.2, 0.35}, {0, 0.1, 0.1, 0.2}, {0, 0.1, 0.05, 0.2},
                             {0, 0.1, NAN, 0.3}};
    const char *says[] = {"frame interval changes at time 0.35", "increasing time",
                          "increasing time", "has no time"};
    for (int c = 0; c < 4; c++) {
        mimas_trajectories *t = open_traj(0);
        mimas_frame f;
        mimas_frame_init(&f);
        mimas_error err;
        int rc = MIMAS_OK;
        for (int k = 0; k < 4 && !rc; k++) {
            frame_of(&f, 1, 0, bad[c][k]);
            f.particles.id[0] = 1;
            rc = mimas_traj_add(t, &f, &err);
        }
        assert_int_equal(rc, MIMAS_EDATA);
        assert_non_null(strstr(err.msg, says[c]));
        mimas_frame_free(&f);
        mimas_traj_free(t);
    }
    /* equal to printing precision is equal */
    mimas_trajectories *t = open_traj(0);
    mimas_frame f;
    mimas_frame_init(&f);
    mimas_error err;
    for (int k = 0; k < 10; k++) {
        frame_of(&f, 1, 0, 0.1 * k + (k == 5 ? 1e-9 : 0));
        f.particles.id[0] = 1;
        assert_int_equal(mimas_traj_add(t, &f, &err), MIMAS_OK);
    }
    assert_close(mimas_traj_interval(t), 0.1, 1e-15);
    mimas_frame_free(&f);
    mimas_traj_free(t);
}

/* Ids 10, 20, 30 at frame 0; 20 leaves at 1; 40 and 5 come at 2; 20 is back at 3. */
static void test_slots(void **state)
{
    (void)state;
    static const int64_t ids[4][4] = {{30, 10, 20, 0}, {10, 30, 0, 0}, {40, 10, 5, 30},
                                      {20, 5, 0, 0}};
    static const size_t n[4] = {3, 2, 4, 2};
    static const size_t slot[4][4] = {{0, 1, 2}, {1, 0}, {3, 1, 4, 0}, {2, 4}};
    static const unsigned char fresh[4][4] = {{1, 1, 1}, {0, 0}, {1, 0, 1, 0}, {0, 0}};
    mimas_trajectories *t = open_traj(1);
    mimas_frame f;
    mimas_frame_init(&f);
    mimas_error err;
    for (int k = 0; k < 4; k++) {
        frame_of(&f, n[k], MIMAS_P_VEL, k);
        for (size_t i = 0; i < n[k]; i++) {
            f.particles.id[i] = ids[k][i];
            for (int d = 0; d < 3; d++) {
                f.particles.pos[i][d] = (double)ids[k][i] + 0.1 * k;
                f.particles.vel[i][d] = -(double)ids[k][i];
            }
        }
        assert_int_equal(mimas_traj_add(t, &f, &err), MIMAS_OK);
        for (size_t i = 0; i < n[k]; i++) {
            assert_int_equal(mimas_traj_frame_slots(t)[i], slot[k][i]);
            assert_int_equal(mimas_traj_frame_new(t)[i], fresh[k][i]);
        }
    }
    assert_int_equal(mimas_traj_slots(t), 5);
    static const int64_t by_slot[5] = {30, 10, 20, 40, 5};
    for (int s = 0; s < 5; s++)
        assert_int_equal(mimas_traj_ids(t)[s], by_slot[s]);
    assert_int_equal(mimas_traj_finish(t, &err), MIMAS_OK);
    /* slot 2 (id 20): frames 0 and 3, absent at 1 and 2; records (x, v) */
    double *u = read_slot(t, 2);
    assert_close(u[0], 20, 0);
    assert_close(u[3], -20, 0);
    assert_true(isnan(u[6]) && isnan(u[12]));
    assert_close(u[18], 20.3, 1e-12);
    free(u);
    mimas_frame_free(&f);
    mimas_traj_free(t);
}

static void test_bad_ids_and_quantities(void **state)
{
    (void)state;
    mimas_frame f;
    mimas_frame_init(&f);
    mimas_error err;
    /* a known id twice, a new id twice */
    for (int c = 0; c < 2; c++) {
        mimas_trajectories *t = open_traj(0);
        frame_of(&f, 2, 0, 0);
        f.particles.id[0] = 1;
        f.particles.id[1] = 2;
        assert_int_equal(mimas_traj_add(t, &f, &err), MIMAS_OK);
        frame_of(&f, 3, 0, 1);
        f.particles.id[0] = c ? 9 : 2;
        f.particles.id[1] = 1;
        f.particles.id[2] = c ? 9 : 2;
        assert_int_equal(mimas_traj_add(t, &f, &err), MIMAS_EDATA);
        assert_non_null(strstr(err.msg, c ? "duplicate particle id 9" : "id 2 appears twice"));
        mimas_traj_free(t);
    }
    /* velocities asked for but absent; types selected but absent */
    mimas_trajectories *t = open_traj(1);
    frame_of(&f, 1, 0, 0);
    f.particles.id[0] = 1;
    assert_int_equal(mimas_traj_add(t, &f, &err), MIMAS_EMISSING);
    assert_non_null(strstr(err.msg, "--vacf"));
    mimas_traj_free(t);
    int32_t types[1] = {2};
    mimas_traj_options o = {types, 1, 0, 0, 1u << 20, NULL};
    assert_int_equal(mimas_traj_create(&t, &o, &err), MIMAS_OK);
    assert_int_equal(mimas_traj_add(t, &f, &err), MIMAS_EMISSING);
    assert_non_null(strstr(err.msg, "no types"));
    /* with types: only type 2 gets slots */
    frame_of(&f, 3, MIMAS_P_TYPE, 0);
    for (int i = 0; i < 3; i++) {
        f.particles.id[i] = i + 1;
        f.particles.type[i] = i == 1 ? 2 : 1;
    }
    assert_int_equal(mimas_traj_add(t, &f, &err), MIMAS_OK);
    assert_int_equal(mimas_traj_slots(t), 1);
    assert_int_equal(mimas_traj_frame_slots(t)[0], SIZE_MAX);
    assert_int_equal(mimas_traj_frame_slots(t)[1], 0);
    mimas_traj_free(t);
    mimas_frame_free(&f);
}

/* The drift: the mean move of those present in both frames, summed. */
static void test_drift(void **state)
{
    (void)state;
    mimas_trajectories *t = open_traj(0);
    mimas_frame f;
    mimas_frame_init(&f);
    mimas_error err;
    const int T = 30, N = 12;
    double want[3] = {0, 0, 0};
    for (int k = 0; k < T; k++) {
        /* particle i is present from frame i to frame i + 15 */
        size_t n = 0;
        frame_of(&f, N, 0, k);
        double sum[3] = {0, 0, 0};
        int moved = 0;
        for (int i = 0; i < N; i++) {
            if (k < i || k > i + 15)
                continue;
            f.particles.id[n] = i;
            for (int d = 0; d < 3; d++)
                f.particles.pos[n][d] = 0.5 * k * (d + 1) + i * i * 0.01 * k * (d == 2);
            if (k > i)
                for (int d = 0; d < 3; d++) {
                    sum[d] += 0.5 * (d + 1) + i * i * 0.01 * (d == 2);
                    moved += d == 0;
                }
            n++;
        }
        mimas_table_resize(&f.particles, &mimas_particles_desc, n, &err);
        assert_int_equal(mimas_traj_add(t, &f, &err), MIMAS_OK);
        for (int d = 0; d < 3 && moved; d++)
            want[d] += sum[d] / moved;
        for (int d = 0; d < 3; d++)
            assert_close(mimas_traj_drift(t)[3 * k + d], want[d], 1e-12 * (1 + fabs(want[d])));
    }
    assert_true(isnan(mimas_traj_mean_velocity(t)[0]));
    mimas_frame_free(&f);
    mimas_traj_free(t);
}

/* record value of slot s at frame t, component c (slot s exists from frame s / 3 on) */
static double record_value(size_t s, size_t t, size_t c) { return 1000.0 * s + t + 0.25 * c; }

static void fill_store(mimas_traj_store *st, size_t frames)
{
    mimas_error err;
    for (size_t t = 0; t < frames; t++) {
        size_t n = 3 * t + 3 < 400 ? 3 * t + 3 : 400;
        assert_int_equal(mimas_traj_store_next_frame(st, n, &err), MIMAS_OK);
        for (size_t s = 0; s < n; s++) {
            if ((s + t) % 11 == 0)
                continue; /* absent now and then */
            double *r = mimas_traj_store_record(st, s);
            for (size_t c = 0; c < 2; c++)
                r[c] = record_value(s, t, c);
        }
    }
    assert_int_equal(mimas_traj_store_finish(st, &err), MIMAS_OK);
}

static void check_store(mimas_traj_store *st, size_t frames)
{
    mimas_error err;
    assert_int_equal(mimas_traj_store_frames(st), frames);
    assert_int_equal(mimas_traj_store_slots(st), 400);
    double *out = malloc(37 * frames * 2 * sizeof *out);
    for (size_t a = 0; a < 400; a += 37) {
        size_t n = 400 - a < 37 ? 400 - a : 37;
        assert_int_equal(mimas_traj_store_read(st, a, n, out, &err), MIMAS_OK);
        for (size_t j = 0; j < n; j++)
            for (size_t t = 0; t < frames; t++) {
                size_t s = a + j;
                const double *r = out + (j * frames + t) * 2;
                int there = s < 3 * t + 3 && (s + t) % 11 != 0;
                for (size_t c = 0; c < 2; c++)
                    if (there)
                        assert_true(r[c] == record_value(s, t, c));
                    else
                        assert_true(isnan(r[c]));
            }
    }
    free(out);
}

static void test_store_memory_and_disk(void **state)
{
    (void)state;
    mimas_error err;
    /* 300 frames of up to 400 slots of 2 values: 1.9 MB of records */
    const size_t sizes[3] = {64u << 20, 256u << 10, 20u << 10};
    for (int k = 0; k < 3; k++) {
        mimas_traj_store_options o = {2, sizes[k], NULL};
        mimas_traj_store *st;
        assert_int_equal(mimas_traj_store_create(&st, &o, &err), MIMAS_OK);
        fill_store(st, 300);
        assert_int_equal(mimas_traj_store_on_disk(st), k > 0);
        check_store(st, 300);
        if (k == 0) {
            /* held in memory, then moved out on demand */
            assert_true(mimas_traj_store_bytes(st) >= 400 * 2 * 8 * 200);
            assert_int_equal(mimas_traj_store_spill(st, &err), MIMAS_OK);
            assert_true(mimas_traj_store_on_disk(st));
            assert_int_equal(mimas_traj_store_bytes(st), 0);
            check_store(st, 300);
        }
        mimas_traj_store_free(st);
    }
    /* too little memory for one frame */
    mimas_traj_store_options o = {2, 1000, NULL};
    mimas_traj_store *st;
    assert_int_equal(mimas_traj_store_create(&st, &o, &err), MIMAS_OK);
    assert_int_equal(mimas_traj_store_next_frame(st, 100, &err), MIMAS_EUSAGE);
    assert_non_null(strstr(err.msg, "cannot hold one frame of 100 particles"));
    mimas_traj_store_free(st);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_unwrap_min_image),
        cmocka_unit_test(test_unwrap_image_flags),
        cmocka_unit_test(test_quarter_box),
        cmocka_unit_test(test_unwrap_without_flags_is_wrong_beyond_half),
        cmocka_unit_test(test_unwrap_triclinic),
        cmocka_unit_test(test_frame_spacing),
        cmocka_unit_test(test_slots),
        cmocka_unit_test(test_bad_ids_and_quantities),
        cmocka_unit_test(test_drift),
        cmocka_unit_test(test_store_memory_and_disk),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
