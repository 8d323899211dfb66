/* Reading a chunked dataset by its chunks: HDF5's direct chunk read, then the
 * filters undone here (deflate by libdeflate, shuffle 16 elements at a time),
 * instead of H5Dread's zlib inflate, scalar Adler-32 and byte-loop shuffle.  HDF5
 * does not let a program replace its built-in filters (H5Zregister refuses their
 * identifiers), so the native reader reads its columns this way; on the
 * 20,000-sphere frame of docs/fields.md this halves the instructions of reading.
 * The last decoded chunk is kept: consecutive frames of a contact table share
 * chunks.  Anything else (other filters, a type conversion, a chunk not
 * written, data that do not decode) is left to H5Dread by the caller. */
#include <config.h>

#include "h5_direct.h"

#include <libdeflate.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#ifdef __SSE2__
#include <emmintrin.h>
#endif

enum { MAX_FILTERS = 2 };
/* Larger chunks are left to H5Dread (a decoded chunk is kept per dataset) */
#define MAX_CHUNK_BYTES ((size_t)8 << 20)

struct h5_direct {
    hid_t ds;
    int rank;
    hsize_t chunk[H5_DIRECT_MAX_RANK];
    size_t elem, chunk_bytes, raw_cap;
    int nfilters;
    H5Z_filter_t filter[MAX_FILTERS]; /* in the order they were applied on writing */
    unsigned char *data;              /* the last chunk decoded */
    struct libdeflate_decompressor *inflater;
    int cached;                       /* data holds the chunk at cached_at */
    hsize_t cached_at[H5_DIRECT_MAX_RANK];
};

/* ---- shuffle undone: byte k of element i is stored at k n + i --------------------------- */

#ifdef __SSE2__
/* 8-byte elements, 16 at a time: the 8 planes' next 16 bytes interleaved by bytes, then
 * byte pairs, then fours, are the 16 elements in order.  Returns how many it did. */
static size_t unshuffle8_sse2(const uint8_t *src, uint8_t *dst, size_t n)
{
    size_t i = 0;
    for (; i + 16 <= n; i += 16) {
        __m128i p[8], a[8], b[8];
        for (int k = 0; k < 8; k++)
            p[k] = _mm_loadu_si128((const __m128i *)(src + (size_t)k * n + i));
        for (int k = 0; k < 4; k++) { /* bytes 2k, 2k+1 of elements 0-7 and 8-15 */
            a[2 * k] = _mm_unpacklo_epi8(p[2 * k], p[2 * k + 1]);
            a[2 * k + 1] = _mm_unpackhi_epi8(p[2 * k], p[2 * k + 1]);
        }
        for (int k = 0; k < 2; k++) { /* bytes 4k..4k+3 of elements 0-3, 4-7, 8-11, 12-15 */
            b[4 * k] = _mm_unpacklo_epi16(a[4 * k], a[4 * k + 2]);
            b[4 * k + 1] = _mm_unpackhi_epi16(a[4 * k], a[4 * k + 2]);
            b[4 * k + 2] = _mm_unpacklo_epi16(a[4 * k + 1], a[4 * k + 3]);
            b[4 * k + 3] = _mm_unpackhi_epi16(a[4 * k + 1], a[4 * k + 3]);
        }
        for (int m = 0; m < 4; m++) { /* elements 4m .. 4m + 3 whole */
            uint8_t *o = dst + (i + 4 * (size_t)m) * 8;
            _mm_storeu_si128((__m128i *)o, _mm_unpacklo_epi32(b[m], b[4 + m]));
            _mm_storeu_si128((__m128i *)(o + 16), _mm_unpackhi_epi32(b[m], b[4 + m]));
        }
    }
    return i;
}
#endif

/* nbytes of elements of size bytes (the bytes past the last whole element stay) */
static void unshuffle(const uint8_t *src, uint8_t *dst, size_t nbytes, size_t size)
{
    size_t n = nbytes / size, i = 0;
    if (size <= 1 || n <= 1) { /* as HDF5: left as they are */
        memcpy(dst, src, nbytes);
        return;
    }
#ifdef __SSE2__
    if (size == 8)
        i = unshuffle8_sse2(src, dst, n);
#endif
    for (; i < n; i++)
        for (size_t k = 0; k < size; k++)
            dst[i * size + k] = src[k * n + i];
    memcpy(dst + n * size, src + n * size, nbytes - n * size);
}

/* ---- opening -------------------------------------------------------------------------- */

h5_direct *h5_direct_open(hid_t ds, hid_t memtype)
{
    hid_t dcpl = H5Dget_create_plist(ds), ftype = H5Dget_type(ds), space = H5Dget_space(ds);
    h5_direct *d = NULL;
    int ok = dcpl >= 0 && ftype >= 0 && space >= 0 && H5Pget_layout(dcpl) == H5D_CHUNKED &&
             H5Tequal(ftype, memtype) > 0;
    int rank = ok ? H5Sget_simple_extent_ndims(space) : -1;
    ok = ok && rank >= 1 && rank <= H5_DIRECT_MAX_RANK && (d = calloc(1, sizeof *d));
    if (ok) {
        d->ds = ds;
        d->rank = rank;
        d->elem = H5Tget_size(ftype);
        ok = H5Pget_chunk(dcpl, rank, d->chunk) == rank && d->elem > 0;
        d->chunk_bytes = d->elem;
        for (int k = 0; ok && k < rank; k++) {
            ok = d->chunk[k] > 0 && d->chunk_bytes <= MAX_CHUNK_BYTES / d->chunk[k];
            d->chunk_bytes *= ok ? d->chunk[k] : 1;
        }
        int nf = ok ? H5Pget_nfilters(dcpl) : -1;
        ok = nf >= 0 && nf <= MAX_FILTERS;
        for (int k = 0; ok && k < nf; k++) {
            unsigned flags, cd[8], conf;
            size_t ncd = 8;
            H5Z_filter_t id = H5Pget_filter2(dcpl, (unsigned)k, &flags, &ncd, cd, 0, NULL, &conf);
            /* shuffle's parameter is the element size it was applied with */
            ok = id == H5Z_FILTER_DEFLATE ||
                 (id == H5Z_FILTER_SHUFFLE && (ncd < 1 || cd[0] == d->elem));
            d->filter[k] = id;
        }
        d->nfilters = ok ? nf : 0;
        /* a stored chunk is at most what deflate may make of it (zlib's bound, with room) or
         * the chunk itself (an optional filter that failed is skipped) */
        d->raw_cap = d->chunk_bytes + d->chunk_bytes / 512 + 1024;
        ok = ok && (d->inflater = libdeflate_alloc_decompressor());
    }
    if (dcpl >= 0)
        H5Pclose(dcpl);
    if (ftype >= 0)
        H5Tclose(ftype);
    if (space >= 0)
        H5Sclose(space);
    if (!ok) {
        h5_direct_close(d);
        return NULL;
    }
    return d;
}

void h5_direct_close(h5_direct *d)
{
    if (!d)
        return;
    if (d->inflater)
        libdeflate_free_decompressor(d->inflater);
    free(d->data);
    free(d);
}

/* ---- reading -------------------------------------------------------------------------- */

/* Decodes the chunk at (element) offset at into d->data; -1 if it cannot. */
/* Room for n bytes in one of the scratch buffers; NULL when out of memory. */
static unsigned char *room(unsigned char **buf, size_t *cap, size_t n)
{
    if (n > *cap) {
        unsigned char *b = realloc(*buf, n);
        if (!b)
            return NULL;
        *buf = b;
        *cap = n;
    }
    return *buf;
}

static int decode_into(h5_direct *d, const hsize_t *at, unsigned char *raw, unsigned char *tmp);

static int decode(h5_direct *d, h5_direct_scratch *s, const hsize_t *at)
{
    d->cached = 0;
    if (!d->data && !(d->data = malloc(d->chunk_bytes)))
        return -1;
    unsigned char *raw = room(&s->raw, &s->raw_cap, d->raw_cap),
                  *tmp = room(&s->tmp, &s->tmp_cap, d->chunk_bytes);
    return raw && tmp ? decode_into(d, at, raw, tmp) : -1;
}

void h5_direct_scratch_free(h5_direct_scratch *s)
{
    free(s->raw);
    free(s->tmp);
    memset(s, 0, sizeof *s);
}

/* decode with the buffers for the stored chunk and a step between filters */
static int decode_into(h5_direct *d, const hsize_t *at, unsigned char *raw, unsigned char *tmp)
{
    hsize_t stored = 0;
    uint32_t mask = 0;
    if (H5Dget_chunk_storage_size(d->ds, at, &stored) < 0 || stored == 0 ||
        stored > d->raw_cap || H5Dread_chunk(d->ds, H5P_DEFAULT, at, &mask, raw) < 0)
        return -1;
    /* the filters applied (not skipped on writing: mask) in reverse, each from in to the
     * other buffer, the last into data */
    int todo[MAX_FILTERS], ntodo = 0;
    for (int k = d->nfilters - 1; k >= 0; k--)
        if (!(mask & (1u << k)))
            todo[ntodo++] = k;
    unsigned char *in = raw;
    size_t n = (size_t)stored;
    for (int t = 0; t < ntodo; t++) {
        int k = todo[t];
        unsigned char *out = t == ntodo - 1 ? d->data : tmp;
        if (d->filter[k] == H5Z_FILTER_DEFLATE) {
            size_t got = 0, used = 0;
            if (libdeflate_zlib_decompress_ex(d->inflater, in, n, out, d->chunk_bytes, &used,
                                              &got) != LIBDEFLATE_SUCCESS)
                return -1;
            n = got;
        } else {
            unshuffle(in, out, n, d->elem);
        }
        in = out;
    }
    if (n != d->chunk_bytes)
        return -1;
    if (in != d->data)
        memcpy(d->data, in, n);
    memcpy(d->cached_at, at, (size_t)d->rank * sizeof *at);
    d->cached = 1;
    return 0;
}

int h5_direct_read(h5_direct *d, h5_direct_scratch *s, const hsize_t *start,
                   const hsize_t *count, void *buf)
{
    const int R = d->rank;
    hsize_t first[H5_DIRECT_MAX_RANK], last[H5_DIRECT_MAX_RANK];
    for (int k = 0; k < R; k++) {
        if (count[k] == 0)
            return 0;
        first[k] = start[k] / d->chunk[k];
        last[k] = (start[k] + count[k] - 1) / d->chunk[k];
    }
    /* chunk by chunk (row order of their indices), the part of the block in it */
    hsize_t c[H5_DIRECT_MAX_RANK];
    memcpy(c, first, (size_t)R * sizeof *c);
    for (;;) {
        hsize_t at[H5_DIRECT_MAX_RANK], lo[H5_DIRECT_MAX_RANK], hi[H5_DIRECT_MAX_RANK];
        int same = d->cached;
        for (int k = 0; k < R; k++) {
            at[k] = c[k] * d->chunk[k];
            lo[k] = start[k] > at[k] ? start[k] : at[k]; /* element range in this chunk */
            hi[k] = start[k] + count[k] < at[k] + d->chunk[k] ? start[k] + count[k]
                                                              : at[k] + d->chunk[k];
            same = same && d->cached_at[k] == at[k];
        }
        if (!same && decode(d, s, at))
            return -1;
        /* rows of the innermost direction: contiguous in the chunk and in buf */
        size_t run = (size_t)(hi[R - 1] - lo[R - 1]) * d->elem;
        hsize_t i[H5_DIRECT_MAX_RANK];
        memcpy(i, lo, (size_t)R * sizeof *i);
        for (;;) {
            size_t src = 0, dst = 0;
            for (int k = 0; k < R; k++) {
                src = src * d->chunk[k] + (i[k] - at[k]);
                dst = dst * count[k] + (i[k] - start[k]);
            }
            memcpy((unsigned char *)buf + dst * d->elem, d->data + src * d->elem, run);
            int k = R - 2;
            while (k >= 0 && ++i[k] == hi[k]) {
                i[k] = lo[k];
                k--;
            }
            if (k < 0)
                break;
        }
        int k = R - 1;
        while (k >= 0 && ++c[k] > last[k]) {
            c[k] = first[k];
            k--;
        }
        if (k < 0)
            break;
    }
    return 0;
}
