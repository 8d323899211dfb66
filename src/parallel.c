#include <config.h>

#include "parallel.h"

#include <limits.h>
#include <stdio.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#ifdef MIMAS_HAVE_MPI
#include <mpi.h>
#endif

struct mimas_par_ordered {
    mimas_par_sink_fn sink;
    void *ctx;
    /* the first failure seen (rank 0: of any rank; others: their own) */
    int failed;
    size_t fail_position;
    mimas_error why;
    size_t next;      /* rank 0: the next position the sink receives */
    int stopped;      /* rank 0 told the others to stop / a worker was told */
    int *done;        /* rank 0: worker k has sent DONE */
    void *stop_requests;  /* rank 0: the STOP messages in flight (MPI_Request[size]) */
};

/* Keeps the failure with the smallest position. */
static void note_failure(mimas_par_ordered *o, size_t position, int code, const char *msg)
{
    if (o->failed && o->fail_position <= position)
        return;
    o->failed = code;
    o->fail_position = position;
    o->why.code = code;
    snprintf(o->why.msg, sizeof o->why.msg, "%s", msg);
}

int mimas_par_ordered_open(mimas_par_ordered **out, mimas_par_sink_fn sink, void *ctx,
                           mimas_error *err)
{
    *out = calloc(1, sizeof **out);
    if (!*out)
        return mimas_error_set(err, MIMAS_EIO, "out of memory");
    (*out)->sink = sink;
    (*out)->ctx = ctx;
    if (mimas_par_size() > 1 && mimas_par_rank() == 0) {
        (*out)->done = calloc((size_t)mimas_par_size(), sizeof *(*out)->done);
        if (!(*out)->done) {
            free(*out);
            *out = NULL;
            return mimas_error_set(err, MIMAS_EIO, "out of memory");
        }
    }
    return MIMAS_OK;
}

void mimas_par_ordered_free(mimas_par_ordered *o)
{
    if (!o)
        return;
    free(o->done);
    free(o->stop_requests);
    free(o);
}

int mimas_par_ordered_stopped(mimas_par_ordered *o)
{
    return o->stopped || o->failed;
}

#ifndef MIMAS_HAVE_MPI
/* ---- one rank ---- */
int mimas_par_init(int *argc, char ***argv)
{
    (void)argc, (void)argv;
    return MIMAS_OK;
}
void mimas_par_finalize(void) {}
int mimas_par_rank(void)
{
    return 0;
}
int mimas_par_size(void)
{
    return 1;
}
const char *mimas_par_library(void)
{
    return NULL;
}
int mimas_par_agree(int status, size_t position, mimas_error *err)
{
    (void)position, (void)err;
    return status;
}
int mimas_par_reduce(void *obj, mimas_par_pack_fn pack, mimas_par_merge_fn merge,
                     mimas_error *err)
{
    (void)obj, (void)pack, (void)merge, (void)err;
    return MIMAS_OK;
}
int mimas_par_share(int status, void *data, size_t n, mimas_error *err)
{
    (void)data, (void)n, (void)err;
    return status;
}
int mimas_par_ordered_put(mimas_par_ordered *o, size_t position, const mimas_bytes *result,
                          mimas_error *err)
{
    if (o->failed)
        return MIMAS_END;
    o->next = position + 1;
    return o->sink(o->ctx, position, result->data, result->n, err);
}
void mimas_par_ordered_fail(mimas_par_ordered *o, size_t position, const mimas_error *why)
{
    note_failure(o, position, why->code ? why->code : MIMAS_EIO, why->msg);
}
int mimas_par_ordered_finish(mimas_par_ordered *o, int status, size_t position,
                             mimas_error *err)
{
    (void)position;
    if (o->failed) {
        if (err)
            *err = o->why;
        return o->failed;
    }
    return status;
}
#else
/* ---- MPI ---- */
enum { TAG_DATA = 711, TAG_FAIL, TAG_DONE, TAG_STOP, TAG_REDUCE };

static int rank_cached = -1, size_cached = 1;

int mimas_par_init(int *argc, char ***argv)
{
    int inited = 0;
    MPI_Initialized(&inited);
    if (!inited && MPI_Init(argc, argv) != MPI_SUCCESS)
        return MIMAS_EIO;
    /* errors are reported through our own status agreement */
    MPI_Comm_set_errhandler(MPI_COMM_WORLD, MPI_ERRORS_RETURN);
    MPI_Comm_rank(MPI_COMM_WORLD, &rank_cached);
    MPI_Comm_size(MPI_COMM_WORLD, &size_cached);
    return MIMAS_OK;
}

void mimas_par_finalize(void)
{
    int inited = 0, done = 0;
    MPI_Initialized(&inited);
    MPI_Finalized(&done);
    if (inited && !done)
        MPI_Finalize();
}

int mimas_par_rank(void)
{
    return rank_cached < 0 ? 0 : rank_cached;
}

int mimas_par_size(void)
{
    return rank_cached < 0 ? 1 : size_cached;
}

const char *mimas_par_library(void)
{
    static char text[MPI_MAX_LIBRARY_VERSION_STRING];
    int len = 0;
    if (MPI_Get_library_version(text, &len) != MPI_SUCCESS)
        return "MPI";
    /* the first line only */
    text[strcspn(text, "\n,")] = '\0';
    return text;
}

int mimas_par_agree(int status, size_t position, mimas_error *err)
{
    int size = mimas_par_size(), rank = mimas_par_rank();
    if (size == 1)
        return status;
    int failed = status != MIMAS_OK && status != MIMAS_END;
    /* key = position * size + rank, positions capped so that it cannot overflow
     * (and SIZE_MAX, "before any frame" or "after all", sorts last) */
    uint64_t cap = (UINT64_MAX - (uint64_t)size) / (uint64_t)size - 1;
    uint64_t pos = (uint64_t)position > cap ? cap : (uint64_t)position;
    uint64_t key = failed ? pos * (uint64_t)size + (uint64_t)rank : UINT64_MAX,
             best = UINT64_MAX;
    MPI_Allreduce(&key, &best, 1, MPI_UINT64_T, MPI_MIN, MPI_COMM_WORLD);
    if (best == UINT64_MAX) {
        /* nobody failed: all ended (END) unless all are fine (OK) */
        int mine = status == MIMAS_END, all = 0;
        MPI_Allreduce(&mine, &all, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
        return all ? MIMAS_END : MIMAS_OK;
    }
    int root = (int)(best % (uint64_t)size);
    struct {
        int code;
        char msg[MIMAS_ERROR_MSG_MAX];
    } m;
    memset(&m, 0, sizeof m);
    if (rank == root) {
        m.code = status;
        if (err)
            memcpy(m.msg, err->msg, sizeof m.msg);
    }
    MPI_Bcast(&m, (int)sizeof m, MPI_BYTE, root, MPI_COMM_WORLD);
    if (err) {
        err->code = m.code;
        memcpy(err->msg, m.msg, sizeof err->msg);
        err->msg[sizeof err->msg - 1] = '\0';
    }
    return m.code;
}

int mimas_par_share(int status, void *data, size_t n, mimas_error *err)
{
    if (mimas_par_size() == 1)
        return status;
    if (n > INT_MAX)
        return mimas_error_set(err, MIMAS_EIO, "MPI: %zu bytes are too many to share", n);
    struct {
        int code;
        char msg[MIMAS_ERROR_MSG_MAX];
    } m;
    memset(&m, 0, sizeof m);
    if (mimas_par_rank() == 0) {
        m.code = status;
        if (status && err)
            memcpy(m.msg, err->msg, sizeof m.msg);
    }
    MPI_Bcast(&m, (int)sizeof m, MPI_BYTE, 0, MPI_COMM_WORLD);
    if (m.code == MIMAS_OK && n)
        MPI_Bcast(data, (int)n, MPI_BYTE, 0, MPI_COMM_WORLD);
    if (m.code && err) {
        err->code = m.code;
        memcpy(err->msg, m.msg, sizeof err->msg);
        err->msg[sizeof err->msg - 1] = '\0';
    }
    return m.code;
}

/* Receives one message of any size from src with tag (or any tag), into b. */
static int recv_bytes(int src, int tag, mimas_bytes *b, int *tag_out, mimas_error *err)
{
    MPI_Status st;
    if (MPI_Probe(src, tag, MPI_COMM_WORLD, &st) != MPI_SUCCESS)
        return mimas_error_set(err, MIMAS_EIO, "MPI: cannot receive from rank %d", src);
    int n = 0;
    MPI_Get_count(&st, MPI_BYTE, &n);
    if ((size_t)n > b->cap) {
        unsigned char *p = realloc(b->data, (size_t)n ? (size_t)n : 1);
        if (!p)
            return mimas_error_set(err, MIMAS_EIO, "out of memory receiving %d bytes", n);
        b->data = p;
        b->cap = (size_t)n;
    }
    b->n = (size_t)n;
    if (MPI_Recv(b->data, n, MPI_BYTE, st.MPI_SOURCE, st.MPI_TAG, MPI_COMM_WORLD,
                 MPI_STATUS_IGNORE) != MPI_SUCCESS)
        return mimas_error_set(err, MIMAS_EIO, "MPI: cannot receive from rank %d", src);
    if (tag_out)
        *tag_out = st.MPI_TAG;
    return MIMAS_OK;
}

static int send_bytes(int dest, int tag, const void *data, size_t n, mimas_error *err)
{
    if (n > INT_MAX)
        return mimas_error_set(err, MIMAS_EIO, "MPI: a message of %zu bytes is too large", n);
    if (MPI_Send(data, (int)n, MPI_BYTE, dest, tag, MPI_COMM_WORLD) != MPI_SUCCESS)
        return mimas_error_set(err, MIMAS_EIO, "MPI: cannot send to rank %d", dest);
    return MIMAS_OK;
}

int mimas_par_reduce(void *obj, mimas_par_pack_fn pack, mimas_par_merge_fn merge,
                     mimas_error *err)
{
    int size = mimas_par_size(), rank = mimas_par_rank();
    if (size == 1)
        return MIMAS_OK;
    mimas_bytes b = {0};
    int rc = MIMAS_OK;
    /* binary tree: at distance step, rank r (r mod 2 step == step) sends its
     * merged state to r - step; a leading status byte carries a failure up */
    for (int step = 1; step < size; step <<= 1) {
        if (rank % (2 * step) == step) {
            unsigned char ok = rc == MIMAS_OK;
            if (ok) {
                rc = pack(obj, &b, err);
                ok = rc == MIMAS_OK;
            }
            mimas_bytes msg = {0};
            int prc = 0;
            {
                size_t n = 1 + (ok ? b.n : 0);
                msg.data = malloc(n);
                if (!msg.data)
                    prc = mimas_error_set(err, MIMAS_EIO, "out of memory");
                else {
                    msg.data[0] = ok;
                    if (ok && b.n)
                        memcpy(msg.data + 1, b.data, b.n);
                    msg.n = n;
                }
            }
            if (!prc)
                prc = send_bytes(rank - step, TAG_REDUCE, msg.data, msg.n, err);
            free(msg.data);
            if (!rc)
                rc = prc;
            break;
        }
        if (rank % (2 * step) == 0 && rank + step < size) {
            int r2 = recv_bytes(rank + step, TAG_REDUCE, &b, NULL, err);
            if (!r2 && b.n >= 1 && b.data[0] && !rc)
                r2 = merge(obj, b.data + 1, b.n - 1, err);
            else if (!r2 && !rc && (b.n < 1 || !b.data[0]))
                r2 = mimas_error_set(err, MIMAS_EIO, "rank %d could not pack its results",
                                     rank + step);
            if (!rc)
                rc = r2;
        }
    }
    mimas_bytes_free(&b);
    return mimas_par_agree(rc, SIZE_MAX, err);
}

/* ---- ordered per-frame results ---- */
/* Rank 0: tells every worker to stop (non-blocking: a worker may be busy
 * sending; the sends complete in mimas_par_ordered_finish). */
static void stop_workers(mimas_par_ordered *o)
{
    if (o->stopped)
        return;
    o->stopped = 1;
    int size = mimas_par_size();
    MPI_Request *req = calloc((size_t)size, sizeof *req);
    static char none;
    for (int k = 1; req && k < size; k++)
        MPI_Isend(&none, 0, MPI_BYTE, k, TAG_STOP, MPI_COMM_WORLD, &req[k]);
    if (!req)
        for (int k = 1; k < size; k++)
            MPI_Send(&none, 0, MPI_BYTE, k, TAG_STOP, MPI_COMM_WORLD);
    o->stop_requests = req;
}

/* Rank 0: one message from worker src, handled. Returns 1 on DONE. */
static int take_message(mimas_par_ordered *o, int src, size_t expect, mimas_bytes *b,
                        int sink_on)
{
    int tag = 0;
    mimas_error e;
    if (recv_bytes(src, MPI_ANY_TAG, b, &tag, &e)) {
        note_failure(o, expect, MIMAS_EIO, e.msg);
        return 1;
    }
    uint64_t pos = 0;
    if ((tag == TAG_DATA || tag == TAG_FAIL) && b->n >= sizeof pos)
        memcpy(&pos, b->data, sizeof pos);
    if (tag == TAG_DONE)
        return 1;
    if (tag == TAG_FAIL && b->n >= sizeof pos + sizeof(int32_t)) {
        int32_t code;
        memcpy(&code, b->data + sizeof pos, sizeof code);
        size_t off = sizeof pos + sizeof code;
        char msg[MIMAS_ERROR_MSG_MAX];
        size_t len = b->n - off < sizeof msg - 1 ? b->n - off : sizeof msg - 1;
        memcpy(msg, b->data + off, len);
        msg[len] = '\0';
        note_failure(o, (size_t)pos, code, msg);
        return 0;
    }
    if (tag == TAG_DATA && sink_on && !o->failed) {
        if ((size_t)pos != expect) {
            note_failure(o, expect, MIMAS_EIO, "MPI ranks disagree on the frames of the input");
            return 0;
        }
        int rc = o->sink(o->ctx, (size_t)pos, b->data + sizeof pos, b->n - sizeof pos, &e);
        if (rc)
            note_failure(o, (size_t)pos, rc, e.msg);
        else
            o->next++;
    }
    return 0;
}

/* Rank 0: hands the others' results up to (not including) position to the
 * sink, in order. */
static void drain_until(mimas_par_ordered *o, size_t position, int *done)
{
    int size = mimas_par_size();
    mimas_bytes b = {0};
    while (!o->failed && o->next < position) {
        int src = (int)(o->next % (size_t)size);
        if (src == 0 || done[src]) {
            note_failure(o, o->next, MIMAS_EIO, "MPI ranks disagree on the frames of the input");
            break;
        }
        if (take_message(o, src, o->next, &b, 1))
            done[src] = 1;
    }
    mimas_bytes_free(&b);
}

int mimas_par_ordered_put(mimas_par_ordered *o, size_t position, const mimas_bytes *result,
                          mimas_error *err)
{
    if (mimas_par_size() == 1) {
        o->next = position + 1;
        return o->sink(o->ctx, position, result->data, result->n, err);
    }
    if (mimas_par_rank() == 0) {
        drain_until(o, position, o->done);
        if (!o->failed) {
            mimas_error e;
            int rc = o->sink(o->ctx, position, result->data, result->n, &e);
            if (rc)
                note_failure(o, position, rc, e.msg);
            else
                o->next = position + 1;
        }
        if (o->failed) {
            stop_workers(o);
            return MIMAS_END;
        }
        return MIMAS_OK;
    }
    /* a worker: stop when told, else send */
    int flag = 0;
    MPI_Iprobe(0, TAG_STOP, MPI_COMM_WORLD, &flag, MPI_STATUS_IGNORE);
    if (flag || o->failed) {
        o->stopped = 1;
        return MIMAS_END;
    }
    uint64_t pos = position;
    unsigned char *msg = malloc(sizeof pos + result->n);
    if (!msg)
        return mimas_error_set(err, MIMAS_EIO, "out of memory");
    memcpy(msg, &pos, sizeof pos);
    if (result->n)
        memcpy(msg + sizeof pos, result->data, result->n);
    int rc = send_bytes(0, TAG_DATA, msg, sizeof pos + result->n, err);
    free(msg);
    return rc;
}

void mimas_par_ordered_fail(mimas_par_ordered *o, size_t position, const mimas_error *why)
{
    int code = why->code ? why->code : MIMAS_EIO;
    if (mimas_par_size() == 1 || mimas_par_rank() == 0) {
        if (mimas_par_size() > 1)
            drain_until(o, position, o->done);
        note_failure(o, position, code, why->msg);
        if (mimas_par_size() > 1)
            stop_workers(o);
        return;
    }
    if (o->failed)
        return;
    note_failure(o, position, code, why->msg);
    uint64_t pos = position;
    int32_t c = code;
    size_t len = strlen(why->msg);
    unsigned char msg[sizeof pos + sizeof c + MIMAS_ERROR_MSG_MAX];
    memcpy(msg, &pos, sizeof pos);
    memcpy(msg + sizeof pos, &c, sizeof c);
    memcpy(msg + sizeof pos + sizeof c, why->msg, len);
    send_bytes(0, TAG_FAIL, msg, sizeof pos + sizeof c + len, NULL);
}

int mimas_par_ordered_finish(mimas_par_ordered *o, int status, size_t position,
                             mimas_error *err)
{
    int size = mimas_par_size(), rank = mimas_par_rank();
    int failed = status != MIMAS_OK && status != MIMAS_END;
    if (size == 1) {
        if (failed)
            note_failure(o, position, status, err ? err->msg : "");
        if (o->failed) {
            if (err)
                *err = o->why;
            return o->failed;
        }
        return status;
    }
    if (failed && !o->failed)
        mimas_par_ordered_fail(o, position, err);
    if (rank == 0) {
        int *done = o->done;
        mimas_bytes b = {0};
        /* the rest in order: positions beyond the last frame do not exist */
        while (!o->failed) {
            int src = (int)(o->next % (size_t)size);
            if (src == 0 || done[src])
                break;
            if (take_message(o, src, o->next, &b, 1))
                done[src] = 1;
        }
        stop_workers(o);
        for (int k = 1; k < size; k++)
            while (!done[k])
                if (take_message(o, k, o->next, &b, 0))
                    done[k] = 1;
        mimas_bytes_free(&b);
        MPI_Request *req = o->stop_requests;
        for (int k = 1; req && k < size; k++)
            MPI_Wait(&req[k], MPI_STATUS_IGNORE);
    } else {
        char none = 0;
        MPI_Send(&none, 0, MPI_BYTE, 0, TAG_DONE, MPI_COMM_WORLD);
        MPI_Recv(&none, 0, MPI_BYTE, 0, TAG_STOP, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    }
    mimas_error mine = o->why;
    int rc = mimas_par_agree(o->failed ? o->failed : MIMAS_END,
                             o->failed ? o->fail_position : 0, &mine);
    if (err && rc != MIMAS_END && rc != MIMAS_OK)
        *err = mine;
    return rc;
}
#endif
