/* The MPI layer (src/parallel.c), on whatever number of ranks it is started
 * with (one without mpirun; tests/cli/mpi.test runs it on 2 and 3): status
 * agreement picks the failure of the earliest frame, the reduction merges
 * every rank's state exactly once, ordered results reach rank 0 in frame
 * order, a failure on any rank stops all without a hang.  Prints TAP from
 * rank 0; every rank exits non-zero on a failed check. */
#include <config.h>

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "parallel.h"

static int failures, tests;

static void check(int ok, const char *what)
{
    tests++;
    if (!ok)
        failures++;
    if (mimas_par_rank() == 0)
        printf("%s %d - %s\n", ok ? "ok" : "not ok", tests, what);
    else if (!ok)
        fprintf(stderr, "rank %d: not ok - %s\n", mimas_par_rank(), what);
}

/* ---- agreement ---- */
static void test_agree(void)
{
    int rank = mimas_par_rank(), size = mimas_par_size();
    mimas_error err;
    mimas_error_clear(&err);
    check(mimas_par_agree(MIMAS_END, 0, &err) == MIMAS_END, "agree: all ended");
    check(mimas_par_agree(MIMAS_OK, 0, &err) == MIMAS_OK, "agree: all fine");
    /* the last rank fails at frame 5, rank 0 at frame 9: frame 5 wins */
    int st = MIMAS_END;
    size_t pos = 0;
    if (rank == size - 1) {
        st = mimas_error_set(&err, MIMAS_EDATA, "bad frame five");
        pos = 5;
    } else if (rank == 0) {
        st = mimas_error_set(&err, MIMAS_EIO, "bad frame nine");
        pos = 9;
    }
    int got = mimas_par_agree(st, pos, &err);
    /* (one rank: it is the last one, failing at frame 5) */
    check(got == MIMAS_EDATA && !strcmp(err.msg, "bad frame five"),
          "agree: the earliest failure, its message");
}

/* ---- reduction: each rank holds its own counts ---- */
typedef struct counts {
    double sum;
    uint64_t ranks;   /* bit k: rank k's share is in */
} counts;

static int pack_counts(const void *obj, mimas_bytes *out, mimas_error *err)
{
    (void)err;
    if (out->cap < sizeof(counts)) {
        out->data = realloc(out->data, sizeof(counts));
        out->cap = sizeof(counts);
    }
    memcpy(out->data, obj, sizeof(counts));
    out->n = sizeof(counts);
    return MIMAS_OK;
}

static int merge_counts(void *obj, const unsigned char *data, size_t n, mimas_error *err)
{
    counts *c = obj, o;
    if (n != sizeof o)
        return mimas_error_set(err, MIMAS_EDATA, "bad size");
    memcpy(&o, data, sizeof o);
    if (c->ranks & o.ranks)
        return mimas_error_set(err, MIMAS_EDATA, "a rank merged twice");
    c->sum += o.sum;
    c->ranks |= o.ranks;
    return MIMAS_OK;
}

static int merge_fails(void *obj, const unsigned char *data, size_t n, mimas_error *err)
{
    (void)obj, (void)data, (void)n;
    return mimas_error_set(err, MIMAS_EDATA, "merge refused");
}

static void test_reduce(void)
{
    int rank = mimas_par_rank(), size = mimas_par_size();
    counts c = {rank + 1.0, 1ull << rank};
    mimas_error err;
    int rc = mimas_par_reduce(&c, pack_counts, merge_counts, &err);
    if (rank == 0)
        check(rc == MIMAS_OK && c.sum == size * (size + 1) / 2.0 &&
                  c.ranks == (size == 64 ? ~0ull : (1ull << size) - 1),
              "reduce: every rank merged once onto rank 0");
    else
        check(rc == MIMAS_OK, "reduce: fine on the other ranks");
    counts d = {1, 1ull << rank};
    rc = mimas_par_reduce(&d, pack_counts, merge_fails, &err);
    check(size == 1 ? rc == MIMAS_OK : (rc == MIMAS_EDATA && !strcmp(err.msg, "merge refused")),
          "reduce: a failed merge fails every rank");
}

/* ---- sharing ---- */
static void test_share(void)
{
    int rank = mimas_par_rank();
    double v[3] = {rank == 0 ? 1.5 : 0, rank == 0 ? -2 : 0, rank == 0 ? 7 : 0};
    mimas_error err;
    int rc = mimas_par_share(MIMAS_OK, v, sizeof v, &err);
    check(rc == MIMAS_OK && v[0] == 1.5 && v[1] == -2 && v[2] == 7, "share: rank 0's data");
    if (rank == 0)
        mimas_error_set(&err, MIMAS_EDATA, "rank 0 has no frame");
    rc = mimas_par_share(rank == 0 ? MIMAS_EDATA : MIMAS_OK, v, sizeof v, &err);
    check(rc == MIMAS_EDATA && !strcmp(err.msg, "rank 0 has no frame"),
          "share: rank 0's failure with its message");
}

/* ---- ordered results ---- */
typedef struct order_sink {
    size_t next, seen;
    int in_order;
} order_sink;

static int sink(void *ctx, size_t position, const unsigned char *data, size_t n,
                mimas_error *err)
{
    (void)err;
    order_sink *s = ctx;
    uint64_t v = 0;
    if (n == sizeof v)
        memcpy(&v, data, sizeof v);
    if (position != s->next || v != 1000 + position)
        s->in_order = 0;
    s->next = position + 1;
    s->seen++;
    return MIMAS_OK;
}

/* Frames 0..total-1 over the ranks; frame `fail_at` (if any) fails on its rank. */
static int run_ordered(size_t total, size_t fail_at, order_sink *s, mimas_error *err)
{
    int rank = mimas_par_rank(), size = mimas_par_size();
    mimas_par_ordered *o;
    memset(s, 0, sizeof *s);
    s->in_order = 1;
    int rc = mimas_par_ordered_open(&o, sink, s, err);
    if (rc)
        return rc;
    int status = MIMAS_OK;
    size_t pos = 0;
    for (size_t j = (size_t)rank; j < total && status == MIMAS_OK; j += (size_t)size) {
        pos = j;
        if (j == fail_at) {
            status = mimas_error_set(err, MIMAS_EDATA, "frame %zu is bad", j);
            break;
        }
        uint64_t v = 1000 + j;
        mimas_bytes b = {(unsigned char *)&v, sizeof v, sizeof v};
        status = mimas_par_ordered_put(o, j, &b, err);
    }
    if (status == MIMAS_OK)
        status = MIMAS_END;
    rc = mimas_par_ordered_finish(o, status, pos, err);
    mimas_par_ordered_free(o);
    return rc;
}

static void test_ordered(void)
{
    int rank = mimas_par_rank(), size = mimas_par_size();
    order_sink s;
    mimas_error err;
    int rc = run_ordered(23, SIZE_MAX, &s, &err);
    if (rank == 0)
        check(rc == MIMAS_END && s.in_order && s.seen == 23, "ordered: 23 frames in order");
    else
        check(rc == MIMAS_END && s.seen == 0, "ordered: the others sink nothing");
    rc = run_ordered(1, SIZE_MAX, &s, &err);
    check(rc == MIMAS_END && (rank != 0 || (s.seen == 1 && s.in_order)),
          "ordered: fewer frames than ranks");
    /* frame 7 fails on rank 7 mod size: everyone gets that failure, rank 0
     * saw frames 0..6 in order and nothing after */
    rc = run_ordered(40, 7, &s, &err);
    check(rc == MIMAS_EDATA && !strcmp(err.msg, "frame 7 is bad"),
          "ordered: a failure on any rank reaches all, with its message");
    if (rank == 0)
        check(s.in_order && s.seen == 7, "ordered: the frames before the failure, in order");
    (void)size;
}

int main(int argc, char **argv)
{
    if (mimas_par_init(&argc, &argv)) {
        fprintf(stderr, "MPI could not start\n");
        return 2;
    }
    if (mimas_par_rank() == 0)
        printf("1..11\n");
    test_agree();
    test_reduce();
    test_share();
    test_ordered();
    mimas_par_finalize();
    return failures ? 1 : 0;
}
