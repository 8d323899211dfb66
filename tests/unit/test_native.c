/* Native format: round trip, random access, crash recovery and bad files. */
#include <config.h>

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include <hdf5.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "native.h"
#include "random_frame.h"
#include "scratch.h"

/* internal: an append without its commit (src/native_write.c) */
int mimas_writer_stage(mimas_writer *w, const mimas_frame *f, mimas_error *err);


/* Frame k of a reproducible sequence: counts vary; frame 2 has no contacts;
 * frame 4 has more particles than any earlier one. */
static void make_frame(mimas_frame *f, unsigned long seed, size_t k, int triclinic)
{
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    gsl_rng_set(rng, seed * 1000 + k);
    random_frame_spec s = {300 + 37 * k, k == 2 ? 0 : 900 + 11 * k, 40 + k, 1, triclinic, 1, 1};
    if (k == 4)
        s.particles = 5000;
    assert_int_equal(random_frame(f, rng, &s, (int64_t)(100 * k)), 0);
    gsl_rng_free(rng);
}

/* A writer on path with the default options. */
static mimas_writer *open_writer(const char *path)
{
    mimas_writer *w;
    mimas_error err;
    mimas_writer_options o;
    mimas_writer_options_default(&o);
    if (mimas_writer_open(&w, path, &o, &err))
        fail_msg("open %s: %s", path, err.msg);
    return w;
}

static void write_frames(const char *path, unsigned long seed, size_t nframes, int triclinic)
{
    mimas_writer *w = open_writer(path);
    mimas_error err;
    mimas_frame f;
    mimas_frame_init(&f);
    for (size_t k = 0; k < nframes; k++) {
        make_frame(&f, seed, k, triclinic);
        int rc = mimas_writer_append(w, &f, &err);
        if (rc)
            fail_msg("append: %s", err.msg);
    }
    mimas_frame_free(&f);
    assert_int_equal(mimas_writer_close(w, &err), MIMAS_OK);
}

static void check_frames(const char *path, unsigned long seed, size_t nframes, int triclinic,
                         int reverse)
{
    mimas_native *r;
    mimas_error err;
    int rc = mimas_native_open(&r, path, &err);
    if (rc)
        fail_msg("open: %s", err.msg);
    assert_int_equal(mimas_native_frames(r), nframes);
    mimas_frame a, b;
    mimas_frame_init(&a);
    mimas_frame_init(&b);
    for (size_t m = 0; m < nframes; m++) {
        size_t k = reverse ? nframes - 1 - m : m;
        make_frame(&a, seed, k, triclinic);
        rc = mimas_native_read(r, k, &b, &err);
        if (rc)
            fail_msg("read %zu: %s", k, err.msg);
        char why[200];
        if (!frames_equal(&a, &b, why, sizeof why))
            fail_msg("frame %zu: %s", k, why);
        mimas_frame_meta meta;
        assert_int_equal(mimas_native_frame_meta(r, k, &meta, &err), MIMAS_OK);
        assert_int_equal(meta.n_particles, a.particles.n);
        assert_int_equal(meta.n_contacts, a.contacts.n);
        assert_int_equal(meta.n_walls, a.walls.n);
    }
    assert_int_equal(mimas_native_read(r, nframes, &b, &err), MIMAS_EUSAGE);
    mimas_frame_free(&a);
    mimas_frame_free(&b);
    mimas_native_close(r);
}

static void test_round_trip(void **state)
{
    (void)state;
    write_frames(scratch_path("rt.h5"), 1, 6, 0);
    check_frames(scratch_path("rt.h5"), 1, 6, 0, 0);
}

static void test_random_access_reverse(void **state)
{
    (void)state;
    write_frames(scratch_path("rev.h5"), 2, 6, 0);
    check_frames(scratch_path("rev.h5"), 2, 6, 0, 1);
}

static void test_triclinic_round_trip(void **state)
{
    (void)state;
    write_frames(scratch_path("tri.h5"), 3, 5, 1);
    check_frames(scratch_path("tri.h5"), 3, 5, 1, 0);
}

static off_t file_size(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0 ? st.st_size : -1;
}

/* A writer killed with SIGKILL in the middle of a frame: the child commits 4
 * frames, writes most of a fifth (large, so its data reaches the disk), and
 * is killed before committing it. */
static void test_killed_writer_keeps_committed_frames(void **state)
{
    (void)state;
    const char *path = scratch_path("killed.h5");
    int fd[2];
    assert_int_equal(pipe(fd), 0);
    pid_t pid = fork();
    assert_true(pid >= 0);
    if (pid == 0) {
        close(fd[0]);
        mimas_writer *w;
        mimas_error err;
        if (mimas_writer_open(&w, path, NULL, &err))
            _exit(3);
        mimas_frame f;
        mimas_frame_init(&f);
        for (size_t k = 0; k < 4; k++) {
            make_frame(&f, 4, k, 0);
            if (mimas_writer_append(w, &f, &err))
                _exit(3);
        }
        if (mimas_writer_flush(w, &err))
            _exit(3);
        off_t committed = file_size(path);
        if (write(fd[1], &committed, sizeof committed) != sizeof committed)
            _exit(3);
        gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
        random_frame_spec big = {200000, 600000, 1000, 1, 0, 1, 1};
        random_frame(&f, rng, &big, 999);
        mimas_writer_stage(w, &f, &err);
        raise(SIGKILL);
        _exit(4);
    }
    close(fd[1]);
    off_t committed = -1;
    assert_int_equal(read(fd[0], &committed, sizeof committed), sizeof committed);
    close(fd[0]);
    int status;
    assert_int_equal(waitpid(pid, &status, 0), pid);
    assert_true(WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL);
    off_t killed = file_size(path);
    /* the uncommitted frame's data did reach the file */
    assert_true(killed > committed + 1000000);
    check_frames(path, 4, 4, 0, 0);

    /* cut the file in the middle of the uncommitted frame: still 4 frames */
    assert_int_equal(truncate(path, committed + (killed - committed) / 2), 0);
    check_frames(path, 4, 4, 0, 0);
    /* cut right at the end of the last commit: still 4 frames */
    assert_int_equal(truncate(path, committed), 0);
    check_frames(path, 4, 4, 0, 0);

    /* cut into committed data: a clear error, not garbage */
    assert_int_equal(truncate(path, committed / 2), 0);
    mimas_native *r;
    mimas_error err;
    assert_int_equal(mimas_native_open(&r, path, &err), MIMAS_EDATA);
    assert_non_null(strstr(err.msg, path));
    assert_non_null(strstr(err.msg, "cut short"));
}

static void expect_open_error(const char *path, const char *fragment)
{
    mimas_native *r = NULL;
    mimas_error err;
    int rc = mimas_native_open(&r, path, &err);
    assert_int_equal(rc, MIMAS_EDATA);
    assert_null(r);
    assert_int_equal(mimas_exit_status(rc), 2);
    /* one line that names the file and the problem */
    assert_int_equal(strncmp(err.msg, path, strlen(path)), 0);
    assert_null(strchr(err.msg, '\n'));
    if (!strstr(err.msg, fragment))
        fail_msg("message '%s' lacks '%s'", err.msg, fragment);
}

static void test_bad_files(void **state)
{
    (void)state;
    FILE *fp = fopen(scratch_path("text.h5"), "w");
    fputs("ITEM: TIMESTEP\n0\n", fp);
    fclose(fp);
    expect_open_error(scratch_path("text.h5"), "not an HDF5 file");

    fclose(fopen(scratch_path("empty.h5"), "w"));
    expect_open_error(scratch_path("empty.h5"), "empty file");

    expect_open_error(scratch_path("does-not-exist.h5"), "No such file");

    /* an HDF5 file that is not ours */
    hid_t f = H5Fcreate(scratch_path("other.h5"), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
    H5Fclose(f);
    expect_open_error(scratch_path("other.h5"), "not an H5MD file");

    /* missing dataset */
    write_frames(scratch_path("missing.h5"), 5, 2, 0);
    f = H5Fopen(scratch_path("missing.h5"), H5F_ACC_RDWR, H5P_DEFAULT);
    assert_true(H5Ldelete(f, "/particles/all/position/value", H5P_DEFAULT) >= 0);
    H5Fclose(f);
    expect_open_error(scratch_path("missing.h5"), "missing dataset /particles/all/position/value");

    write_frames(scratch_path("nooffset.h5"), 5, 2, 0);
    f = H5Fopen(scratch_path("nooffset.h5"), H5F_ACC_RDWR, H5P_DEFAULT);
    assert_true(H5Ldelete(f, "/contacts/all/offset", H5P_DEFAULT) >= 0);
    H5Fclose(f);
    expect_open_error(scratch_path("nooffset.h5"), "missing dataset /contacts/all/offset");

    /* a newer major version */
    write_frames(scratch_path("newer.h5"), 6, 1, 0);
    f = H5Fopen(scratch_path("newer.h5"), H5F_ACC_RDWR, H5P_DEFAULT);
    hid_t g = H5Gopen2(f, "/mimas", H5P_DEFAULT);
    hid_t a = H5Aopen(g, "format_version", H5P_DEFAULT);
    int v[2] = {2, 0};
    assert_true(H5Awrite(a, H5T_NATIVE_INT, v) >= 0);
    H5Aclose(a);
    H5Gclose(g);
    H5Fclose(f);
    expect_open_error(scratch_path("newer.h5"), "format version 2.0 is newer");
}

static void test_writer_rejects_inconsistent_frames(void **state)
{
    (void)state;
    mimas_writer *w;
    mimas_error err;
    mimas_writer_options o;
    mimas_writer_options_default(&o);
    o.atomic = 1;
    const char *path = scratch_path("atomic.h5");
    assert_int_equal(mimas_writer_open(&w, path, &o, &err), MIMAS_OK);
    mimas_frame f;
    mimas_frame_init(&f);
    make_frame(&f, 7, 0, 0);
    assert_int_equal(mimas_writer_append(w, &f, &err), MIMAS_OK);
    /* atomic: nothing at the final name before close */
    assert_int_equal(file_size(path), -1);
    mimas_table_keep_only(&f.particles, &mimas_particles_desc, MIMAS_P_RADIUS);
    assert_int_equal(mimas_writer_append(w, &f, &err), MIMAS_EDATA);
    assert_non_null(strstr(err.msg, "other quantities"));
    make_frame(&f, 7, 1, 0);
    f.contacts.j[3] = f.particles.n + 5;
    assert_int_equal(mimas_writer_append(w, &f, &err), MIMAS_EDATA);
    assert_non_null(strstr(err.msg, "refers to particle"));
    mimas_writer_abort(w);
    assert_int_equal(file_size(path), -1);
    mimas_frame_free(&f);
}

static void test_unknown_contact_id_is_reported(void **state)
{
    (void)state;
    const char *path = scratch_path("badid.h5");
    write_frames(path, 8, 2, 0);
    hid_t f = H5Fopen(path, H5F_ACC_RDWR, H5P_DEFAULT);
    hid_t ds = H5Dopen2(f, "/contacts/all/j", H5P_DEFAULT);
    hid_t fs = H5Dget_space(ds);
    hsize_t start = 5, one = 1;
    H5Sselect_hyperslab(fs, H5S_SELECT_SET, &start, NULL, &one, NULL);
    hid_t ms = H5Screate_simple(1, &one, NULL);
    int64_t bogus = 2; /* ids are 3k+1: 2 is never one */
    assert_true(H5Dwrite(ds, H5T_NATIVE_INT64, ms, fs, H5P_DEFAULT, &bogus) >= 0);
    H5Sclose(ms);
    H5Sclose(fs);
    H5Dclose(ds);
    H5Fclose(f);
    mimas_native *r;
    mimas_error err;
    assert_int_equal(mimas_native_open(&r, path, &err), MIMAS_OK);
    mimas_frame fr;
    mimas_frame_init(&fr);
    assert_int_equal(mimas_native_read(r, 0, &fr, &err), MIMAS_EDATA);
    assert_non_null(strstr(err.msg, "names particle id 2"));
    assert_int_equal(mimas_native_read(r, 1, &fr, &err), MIMAS_OK);
    mimas_frame_free(&fr);
    mimas_native_close(r);
}

/* format 1.1: the tube and the gas fields travel with every frame */
static void fill_gas(mimas_frame *f, size_t k)
{
    f->tube = (mimas_tube){1, {0.1, -0.2, 0.3}, {0.6, 0, 0.8}, 0.0035, 0.525};
    assert_int_equal(mimas_gas_resize(&f->gas, 2, 3, 5, NULL), MIMAS_OK);
    f->gas.origin[0] = -0.0035;
    f->gas.origin[1] = -0.00525;
    f->gas.origin[2] = 0;
    f->gas.spacing[0] = 0.0035;
    f->gas.spacing[1] = 0.0035;
    f->gas.spacing[2] = 0.105;
    for (size_t c = 0; c < 30; c++) {
        f->gas.pressure[c] = 1000.0 * (double)k + (double)c + 0.125;
        f->gas.porosity[c] = 0.4 + 0.01 * (double)c;
        for (int d = 0; d < 3; d++)
            f->gas.velocity[c][d] = (double)(c * 3 + (size_t)d) - 0.5 * (double)k;
    }
}

static void test_tube_gas_round_trip(void **state)
{
    (void)state;
    const char *path = scratch_path("gas.h5");
    mimas_writer *w;
    mimas_error err;
    assert_int_equal(mimas_writer_open(&w, path, NULL, &err), MIMAS_OK);
    mimas_frame f, g;
    mimas_frame_init(&f);
    mimas_frame_init(&g);
    for (size_t k = 0; k < 3; k++) {
        make_frame(&f, 11, k, 0);
        fill_gas(&f, k);
        if (mimas_writer_append(w, &f, &err))
            fail_msg("%s", err.msg);
    }
    assert_int_equal(mimas_writer_close(w, &err), MIMAS_OK);
    mimas_native *r;
    assert_int_equal(mimas_native_open(&r, path, &err), MIMAS_OK);
    assert_int_equal(mimas_native_frames(r), 3);
    for (size_t k = 3; k-- > 0;) {
        fill_gas(&f, k);
        assert_int_equal(mimas_native_read(r, k, &g, &err), MIMAS_OK);
        assert_true(g.tube.present);
        assert_memory_equal(g.tube.origin, f.tube.origin, sizeof f.tube.origin);
        assert_memory_equal(g.tube.direction, f.tube.direction, sizeof f.tube.direction);
        assert_true(g.tube.radius == f.tube.radius && g.tube.length == f.tube.length);
        assert_true(g.gas.present);
        assert_memory_equal(g.gas.cells, f.gas.cells, sizeof f.gas.cells);
        assert_memory_equal(g.gas.origin, f.gas.origin, sizeof f.gas.origin);
        assert_memory_equal(g.gas.spacing, f.gas.spacing, sizeof f.gas.spacing);
        assert_memory_equal(g.gas.pressure, f.gas.pressure, 30 * sizeof *f.gas.pressure);
        assert_memory_equal(g.gas.porosity, f.gas.porosity, 30 * sizeof *f.gas.porosity);
        assert_memory_equal(g.gas.velocity, f.gas.velocity, 30 * sizeof *f.gas.velocity);
    }
    mimas_native_close(r);
    /* the layout the format documents: (frames, nz, ny, nx), x fastest; step
     * and time shared with the particles */
    hid_t file = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
    hid_t ds = H5Dopen2(file, "/fields/gas/pressure/value", H5P_DEFAULT);
    hid_t sp = H5Dget_space(ds);
    hsize_t dims[4];
    assert_int_equal(H5Sget_simple_extent_ndims(sp), 4);
    H5Sget_simple_extent_dims(sp, dims, NULL);
    assert_true(dims[0] == 3 && dims[1] == 5 && dims[2] == 3 && dims[3] == 2);
    double all[3 * 30];
    assert_true(H5Dread(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, all) >= 0);
    /* frame 1, cell (i, j, k) = (1, 2, 4): index i + nx (j + ny k) = 29 */
    assert_true(all[30 + 29] == 1000.0 + 29 + 0.125);
    H5Sclose(sp);
    H5Dclose(ds);
    H5O_info_t a, b;   /* the same object: hard links */
    H5Oget_info_by_name(file, "/fields/gas/velocity/time", &a, H5P_DEFAULT);
    H5Oget_info_by_name(file, "/particles/all/position/time", &b, H5P_DEFAULT);
    assert_true(a.addr == b.addr && a.fileno == b.fileno);
    H5Fclose(file);
    /* a frame with another grid is refused */
    assert_int_equal(mimas_writer_open(&w, scratch_path("gas2.h5"), NULL, &err), MIMAS_OK);
    make_frame(&f, 11, 0, 0);
    fill_gas(&f, 0);
    assert_int_equal(mimas_writer_append(w, &f, &err), MIMAS_OK);
    assert_int_equal(mimas_gas_resize(&f.gas, 2, 3, 6, NULL), MIMAS_OK);
    assert_int_equal(mimas_writer_append(w, &f, &err), MIMAS_EDATA);
    assert_non_null(strstr(err.msg, "gas grid changes"));
    f.gas.present = 0;
    f.tube.length = 1;
    assert_int_equal(mimas_writer_append(w, &f, &err), MIMAS_EDATA);
    assert_non_null(strstr(err.msg, "tube changes"));
    mimas_writer_abort(w);
    mimas_frame_free(&f);
    mimas_frame_free(&g);
}

/* A file of format 1.0 (tests/data/native/v1_0.h5, written by mimas 0.1.0
 * before the tube and gas fields existed) reads, without tube or gas. */
/* The file holds its data and little else when every frame is committed on its own
 * (as a slow simulation does): the contact tables' partly filled last chunk is
 * rewritten at every commit and, space never being reused, each rewrite stays behind
 * in the file; chunks sized to the frames keep that below a fraction of the data.
 * Expected: the file's size against the storage of its datasets (H5Dget_storage_size)
 * and a bound on the metadata of the commits. */
static herr_t add_storage(hid_t obj, const char *name, const H5O_info_t *info, void *sum)
{
    if (info->type != H5O_TYPE_DATASET)
        return 0;
    hid_t ds = H5Dopen2(obj, name, H5P_DEFAULT);
    if (ds < 0)
        return -1;
    *(hsize_t *)sum += H5Dget_storage_size(ds);
    H5Dclose(ds);
    return 0;
}

static void test_commits_leave_little_unused_space(void **state)
{
    (void)state;
    const char *path = scratch_path("commits.h5");
    mimas_writer *w = open_writer(path);
    mimas_error err;
    mimas_frame f;
    mimas_frame_init(&f);
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    enum { FRAMES = 120 };
    for (size_t k = 0; k < FRAMES; k++) {
        random_frame_spec s = {2000, 6000, 0, 0, 0, 1, 0};
        assert_int_equal(random_frame(&f, rng, &s, (int64_t)k), 0);
        assert_int_equal(mimas_writer_append(w, &f, &err), MIMAS_OK);
        assert_int_equal(mimas_writer_flush(w, &err), MIMAS_OK);
    }
    gsl_rng_free(rng);
    mimas_frame_free(&f);
    assert_int_equal(mimas_writer_close(w, &err), MIMAS_OK);
    hid_t file = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
    assert_true(file >= 0);
    hsize_t data = 0;
    assert_true(H5Ovisit2(file, H5_INDEX_NAME, H5_ITER_NATIVE, add_storage, &data,
                          H5O_INFO_BASIC) >= 0);
    H5Fclose(file);
    struct stat st;
    assert_int_equal(stat(path, &st), 0);
    /* the metadata of a commit: a few kB (chunk index, extents); allow 16 kB each */
    double size = (double)st.st_size, allowed = 1.25 * (double)data + 16384.0 * FRAMES;
    if (size > allowed)
        fail_msg("file of %.0f bytes for %.0f bytes of data (allowed %.0f)", size, (double)data,
                 allowed);
    unlink(path);
}

static void test_format_1_0_reads(void **state)
{
    (void)state;
    char path[512];
    const char *top = getenv("TEST_SRCDIR");
    snprintf(path, sizeof path, "%s/data/native/v1_0.h5", top ? top : "tests");
    mimas_native *r;
    mimas_error err;
    if (mimas_native_open(&r, path, &err))
        fail_msg("%s", err.msg);
    assert_int_equal(mimas_native_frames(r), 3);
    mimas_frame f;
    mimas_frame_init(&f);
    f.tube.present = 1;
    f.gas.present = 1;
    assert_int_equal(mimas_native_read(r, 2, &f, &err), MIMAS_OK);
    assert_int_equal(f.particles.n, 8);
    assert_true(f.step == 200);
    assert_false(f.tube.present);
    assert_false(f.gas.present);
    mimas_frame_free(&f);
    mimas_native_close(r);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_round_trip),
        cmocka_unit_test(test_random_access_reverse),
        cmocka_unit_test(test_triclinic_round_trip),
        cmocka_unit_test(test_killed_writer_keeps_committed_frames),
        cmocka_unit_test(test_bad_files),
        cmocka_unit_test(test_writer_rejects_inconsistent_frames),
        cmocka_unit_test(test_unknown_contact_id_is_reported),
        cmocka_unit_test(test_tube_gas_round_trip),
        cmocka_unit_test(test_format_1_0_reads),
        cmocka_unit_test(test_commits_leave_little_unused_space),
    };
    return cmocka_run_group_tests_name("native", tests, scratch_setup, scratch_teardown);
}
