/* Reading by chunks (readers/h5_direct.c) gives what H5Dread gives: datasets of
 * rank 1 to 3 made here with HDF5 itself, every pipeline the reader takes (none,
 * deflate, shuffle, shuffle + deflate) and chunks that do not divide the extent,
 * random blocks read in random order (so that the kept chunk is reused and
 * replaced), a chunk written with deflate skipped (its filter mask), and the
 * datasets the reader must leave to H5Dread. */
#include <config.h>

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include <gsl/gsl_rng.h>
#include <hdf5.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "h5_direct.h"

enum { PIPE_NONE, PIPE_DEFLATE, PIPE_SHUFFLE, PIPE_BOTH, PIPE_FLETCHER };

static hid_t make_dataset(hid_t file, const char *name, int rank, const hsize_t *dims,
                          const hsize_t *chunk, int pipe, hid_t type, const void *data)
{
    hid_t space = H5Screate_simple(rank, dims, NULL), dcpl = H5Pcreate(H5P_DATASET_CREATE);
    H5Pset_chunk(dcpl, rank, chunk);
    if (pipe == PIPE_SHUFFLE || pipe == PIPE_BOTH)
        H5Pset_shuffle(dcpl);
    if (pipe == PIPE_DEFLATE || pipe == PIPE_BOTH)
        H5Pset_deflate(dcpl, 3);
    if (pipe == PIPE_FLETCHER)
        H5Pset_fletcher32(dcpl);
    hid_t ds = H5Dcreate2(file, name, type, space, H5P_DEFAULT, dcpl, H5P_DEFAULT);
    assert_true(ds >= 0);
    assert_true(H5Dwrite(ds, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data) >= 0);
    H5Pclose(dcpl);
    H5Sclose(space);
    return ds;
}

/* H5Dread of the block, with a memory space of its shape */
static void reference_read(hid_t ds, hid_t type, int rank, const hsize_t *start,
                           const hsize_t *count, void *buf)
{
    hid_t fs = H5Dget_space(ds), ms = H5Screate_simple(rank, count, NULL);
    assert_true(H5Sselect_hyperslab(fs, H5S_SELECT_SET, start, NULL, count, NULL) >= 0);
    assert_true(H5Dread(ds, type, ms, fs, H5P_DEFAULT, buf) >= 0);
    H5Sclose(ms);
    H5Sclose(fs);
}

static void random_blocks(gsl_rng *rng, hid_t ds, hid_t type, size_t elem, int rank,
                          const hsize_t *dims)
{
    h5_direct *d = h5_direct_open(ds, type);
    h5_direct_scratch scratch = {0};
    assert_non_null(d);
    size_t total = elem;
    for (int k = 0; k < rank; k++)
        total *= dims[k];
    unsigned char *got = malloc(total), *want = malloc(total);
    for (int trial = 0; trial < 60; trial++) {
        hsize_t start[3], count[3];
        for (int k = 0; k < rank; k++) {
            start[k] = gsl_rng_uniform_int(rng, dims[k]);
            count[k] = 1 + gsl_rng_uniform_int(rng, dims[k] - start[k]);
        }
        if (trial == 0) /* the whole dataset */
            for (int k = 0; k < rank; k++) {
                start[k] = 0;
                count[k] = dims[k];
            }
        size_t n = elem;
        for (int k = 0; k < rank; k++)
            n *= count[k];
        memset(got, 0xA5, n);
        assert_int_equal(h5_direct_read(d, &scratch, start, count, got), 0);
        reference_read(ds, type, rank, start, count, want);
        assert_memory_equal(got, want, n);
    }
    free(got);
    free(want);
    h5_direct_close(d);
    h5_direct_scratch_free(&scratch);
}

static char *temp_name(void)
{
    static char path[64];
    snprintf(path, sizeof path, "/tmp/test_h5_direct_%ld.h5", (long)getpid());
    return path;
}

static void test_same_as_h5dread(void **state)
{
    (void)state;
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    const char *path = temp_name();
    hid_t file = H5Fcreate(path, H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
    assert_true(file >= 0);
    struct {
        int rank;
        hsize_t dims[3], chunk[3];
    } shapes[4] = {{1, {1000}, {64}},
                   {2, {777, 3}, {100, 3}},
                   {3, {5, 301, 3}, {1, 128, 3}},
                   {3, {4, 37, 5}, {3, 16, 2}}};
    enum { NMAX = 5 * 301 * 3 };
    double *v = malloc(NMAX * sizeof *v);
    int64_t *iv = malloc(NMAX * sizeof *iv);
    int32_t *i32 = malloc(NMAX * sizeof *i32);
    for (int m = 0; m < NMAX; m++) {
        v[m] = (gsl_rng_uniform(rng) - 0.5) * 1e-3; /* doubles: shuffle's 8-byte case */
        iv[m] = (int64_t)gsl_rng_uniform_int(rng, 100000) - 7;
        i32[m] = (int32_t)iv[m];
    }
    for (int s = 0; s < 4; s++)
        for (int pipe = PIPE_NONE; pipe <= PIPE_BOTH; pipe++)
            for (int t = 0; t < 3; t++) {
                char name[64];
                snprintf(name, sizeof name, "d%d_%d_%d", s, pipe, t);
                /* doubles, 64-bit and 32-bit integers (shuffle's element sizes 8 and 4) */
                hid_t type = t == 0 ? H5T_NATIVE_DOUBLE : t == 1 ? H5T_NATIVE_INT64
                                                                 : H5T_NATIVE_INT32;
                size_t elem = t == 2 ? 4 : 8;
                const void *data = t == 0 ? (const void *)v : t == 1 ? (const void *)iv : i32;
                hid_t ds = make_dataset(file, name, shapes[s].rank, shapes[s].dims,
                                        shapes[s].chunk, pipe, type, data);
                random_blocks(rng, ds, type, elem, shapes[s].rank, shapes[s].dims);
                H5Dclose(ds);
            }
    free(v);
    free(iv);
    free(i32);
    H5Fclose(file);
    remove(path);
    gsl_rng_free(rng);
}

/* A chunk stored with deflate skipped (filter mask bit 1): shuffled only. */
static void test_skipped_filter(void **state)
{
    (void)state;
    const char *path = temp_name();
    hid_t file = H5Fcreate(path, H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
    hsize_t dims[1] = {64}, chunk[1] = {32};
    double v[64], shuffled[32], got[64], want[64];
    for (int m = 0; m < 64; m++)
        v[m] = 1.0 / (m + 3);
    hid_t ds = make_dataset(file, "x", 1, dims, chunk, PIPE_BOTH, H5T_NATIVE_DOUBLE, v);
    /* chunk 1 again, by hand: byte k of element i at k 32 + i, not deflated */
    unsigned char *raw = (unsigned char *)shuffled;
    for (int i = 0; i < 32; i++)
        for (int k = 0; k < 8; k++)
            raw[k * 32 + i] = ((const unsigned char *)&v[32 + i])[k];
    hsize_t at[1] = {32};
    assert_true(H5Dwrite_chunk(ds, H5P_DEFAULT, 2u /* filter 1, deflate, skipped */, at,
                               sizeof shuffled, shuffled) >= 0);
    H5Fflush(file, H5F_SCOPE_LOCAL);
    h5_direct *d = h5_direct_open(ds, H5T_NATIVE_DOUBLE);
    h5_direct_scratch scratch = {0};
    assert_non_null(d);
    hsize_t start[1] = {0}, count[1] = {64};
    assert_int_equal(h5_direct_read(d, &scratch, start, count, got), 0);
    reference_read(ds, H5T_NATIVE_DOUBLE, 1, start, count, want);
    assert_memory_equal(got, want, sizeof got);
    assert_memory_equal(got, v, sizeof v);
    h5_direct_close(d);
    h5_direct_scratch_free(&scratch);
    H5Dclose(ds);
    H5Fclose(file);
    remove(path);
}

/* Left to H5Dread: another filter, a type conversion, a contiguous dataset; and a chunk
 * never written is refused (H5Dread gives its fill value). */
static void test_left_to_h5dread(void **state)
{
    (void)state;
    const char *path = temp_name();
    hid_t file = H5Fcreate(path, H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
    hsize_t dims[1] = {100}, chunk[1] = {10};
    double v[100];
    for (int m = 0; m < 100; m++)
        v[m] = m;
    hid_t a = make_dataset(file, "fletcher", 1, dims, chunk, PIPE_FLETCHER, H5T_NATIVE_DOUBLE, v);
    assert_null(h5_direct_open(a, H5T_NATIVE_DOUBLE));
    hid_t b = make_dataset(file, "float", 1, dims, chunk, PIPE_BOTH, H5T_NATIVE_FLOAT, v);
    assert_null(h5_direct_open(b, H5T_NATIVE_DOUBLE)); /* stored as float, read as double */
    hid_t space = H5Screate_simple(1, dims, NULL);
    hid_t c = H5Dcreate2(file, "contiguous", H5T_NATIVE_DOUBLE, space, H5P_DEFAULT,
                         H5P_DEFAULT, H5P_DEFAULT);
    assert_null(h5_direct_open(c, H5T_NATIVE_DOUBLE));
    hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);
    H5Pset_chunk(dcpl, 1, chunk);
    H5Pset_deflate(dcpl, 1);
    hid_t e = H5Dcreate2(file, "empty", H5T_NATIVE_DOUBLE, space, H5P_DEFAULT, dcpl,
                         H5P_DEFAULT);
    h5_direct *d = h5_direct_open(e, H5T_NATIVE_DOUBLE);
    h5_direct_scratch scratch = {0};
    assert_non_null(d);
    hsize_t start[1] = {5}, count[1] = {20};
    double got[20];
    assert_int_equal(h5_direct_read(d, &scratch, start, count, got), -1);
    h5_direct_close(d);
    h5_direct_scratch_free(&scratch);
    H5Pclose(dcpl);
    H5Sclose(space);
    H5Dclose(a);
    H5Dclose(b);
    H5Dclose(c);
    H5Dclose(e);
    H5Fclose(file);
    remove(path);
}

int main(void)
{
    H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_same_as_h5dread),
        cmocka_unit_test(test_skipped_filter),
        cmocka_unit_test(test_left_to_h5dread),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
