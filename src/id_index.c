#include <config.h>

#include "id_index.h"

#include <stdlib.h>
#include <string.h>

void mimas_id_index_init(mimas_id_index *x)
{
    memset(x, 0, sizeof *x);
}

void mimas_id_index_free(mimas_id_index *x)
{
    free(x->dense);
    free(x->ids);
    free(x->idx);
    mimas_id_index_init(x);
}

typedef struct {
    int64_t id;
    size_t idx;
} id_pair;

static int cmp_pair(const void *a, const void *b)
{
    int64_t x = ((const id_pair *)a)->id, y = ((const id_pair *)b)->id;
    return (x > y) - (x < y);
}

static int build_sorted(mimas_id_index *x, const int64_t *ids, size_t n, mimas_error *err)
{
    id_pair *p = malloc((n ? n : 1) * sizeof *p);
    if (!p)
        return mimas_error_set(err, MIMAS_EIO, "out of memory for the particle id index");
    for (size_t k = 0; k < n; k++)
        p[k] = (id_pair){ids[k], k};
    qsort(p, n, sizeof *p, cmp_pair);
    if (n > x->cap_sorted) {
        int64_t *ni = realloc(x->ids, n * sizeof *ni);
        if (ni)
            x->ids = ni;
        size_t *nx = realloc(x->idx, n * sizeof *nx);
        if (nx)
            x->idx = nx;
        if (!ni || !nx) {
            free(p);
            return mimas_error_set(err, MIMAS_EIO, "out of memory for the particle id index");
        }
        x->cap_sorted = n;
    }
    for (size_t k = 0; k < n; k++) {
        if (k > 0 && p[k].id == p[k - 1].id) {
            int64_t dup = p[k].id;
            x->duplicate = dup;
            free(p);
            return mimas_error_set(err, MIMAS_EDATA, "duplicate particle id %lld",
                                   (long long)dup);
        }
        x->ids[k] = p[k].id;
        x->idx[k] = p[k].idx;
    }
    free(p);
    return MIMAS_OK;
}

int mimas_id_index_build(mimas_id_index *x, const int64_t *ids, size_t n, mimas_error *err)
{
    x->n = n;
    x->span = 0;
    if (n == 0)
        return MIMAS_OK;
    int64_t lo = ids[0], hi = ids[0];
    for (size_t k = 1; k < n; k++) {
        if (ids[k] < lo)
            lo = ids[k];
        if (ids[k] > hi)
            hi = ids[k];
    }
    x->min_id = lo;
    /* ids are usually 0..N-1 or 1..N: a direct table then costs O(N) memory */
    unsigned long long span = (unsigned long long)hi - (unsigned long long)lo + 1ull;
    if (span > 4ull * n + 1024ull)
        return build_sorted(x, ids, n, err);
    if (span > x->cap_dense) {
        size_t *d = realloc(x->dense, (size_t)span * sizeof *d);
        if (!d)
            return mimas_error_set(err, MIMAS_EIO, "out of memory for the particle id index");
        x->dense = d;
        x->cap_dense = (size_t)span;
    }
    x->span = (size_t)span;
    memset(x->dense, 0xff, x->span * sizeof *x->dense);
    for (size_t k = 0; k < n; k++) {
        size_t *slot = &x->dense[ids[k] - lo];
        if (*slot != SIZE_MAX) {
            x->duplicate = ids[k];
            return mimas_error_set(err, MIMAS_EDATA, "duplicate particle id %lld",
                                   (long long)ids[k]);
        }
        *slot = k;
    }
    return MIMAS_OK;
}

int mimas_id_index_find(const mimas_id_index *x, int64_t id, size_t *index)
{
    if (x->n == 0)
        return 0;
    if (x->span) {
        if (id < x->min_id || (uint64_t)(id - x->min_id) >= x->span)
            return 0;
        size_t k = x->dense[id - x->min_id];
        if (k == SIZE_MAX)
            return 0;
        *index = k;
        return 1;
    }
    size_t lo = 0, hi = x->n;
    while (lo < hi) {
        size_t mid = lo + (hi - lo) / 2;
        if (x->ids[mid] < id)
            lo = mid + 1;
        else
            hi = mid;
    }
    if (lo < x->n && x->ids[lo] == id) {
        *index = x->idx[lo];
        return 1;
    }
    return 0;
}
