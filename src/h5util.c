#include <config.h>

#include "h5util.h"

#include <stdio.h>
#include <stdlib.h>
#ifdef __GLIBC__
#include <malloc.h>
#endif
#include <string.h>

void h5_quiet_begin(h5_quiet *q)
{
    H5Eget_auto2(H5E_DEFAULT, &q->func, &q->data);
    H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
}

void h5_quiet_end(const h5_quiet *q)
{
    H5Eset_auto2(H5E_DEFAULT, q->func, q->data);
}

typedef struct {
    char *buf;
    size_t len;
} err_sink;

static herr_t take_desc(unsigned n, const H5E_error2_t *e, void *data)
{
    (void)n;
    err_sink *s = data;
    /* walking upward: the first entry is the innermost (most specific) one */
    if (s->buf[0] == '\0' && e->desc && e->desc[0])
        snprintf(s->buf, s->len, "%s", e->desc);
    return 0;
}

void h5_error_text(char *buf, size_t len)
{
    if (!len)
        return;
    buf[0] = '\0';
    err_sink s = {buf, len};
    H5Ewalk2(H5E_DEFAULT, H5E_WALK_UPWARD, take_desc, &s);
    /* a failed write reads "file write failed: time = ..., errno = 28,
     * error message = 'No space left on device', ..." over several lines:
     * keep its first words and the system's message, on one line */
    const char *m = strstr(buf, "error message = '");
    if (m) {
        const char *from = m + strlen("error message = '"), *to = strchr(from, '\'');
        size_t head = strcspn(buf, ":\n");
        char text[256];
        snprintf(text, sizeof text, "%.*s: %.*s", (int)head, buf,
                 (int)(to ? (size_t)(to - from) : strlen(from)), from);
        snprintf(buf, len, "%s", text);
    }
    buf[strcspn(buf, "\n")] = '\0';
}

static int write_attr(hid_t obj, const char *name, hid_t type, hid_t space, const void *buf)
{
    if (H5Aexists(obj, name) > 0)
        H5Adelete(obj, name);
    hid_t a = H5Acreate2(obj, name, type, space, H5P_DEFAULT, H5P_DEFAULT);
    if (a < 0)
        return -1;
    herr_t rc = H5Awrite(a, type, buf);
    H5Aclose(a);
    return rc < 0 ? -1 : 0;
}

int h5_attr_write_str(hid_t obj, const char *name, const char *value)
{
    hid_t t = H5Tcopy(H5T_C_S1);
    H5Tset_size(t, strlen(value) + 1);
    H5Tset_strpad(t, H5T_STR_NULLTERM);
    hid_t s = H5Screate(H5S_SCALAR);
    int rc = write_attr(obj, name, t, s, value);
    H5Sclose(s);
    H5Tclose(t);
    return rc;
}

int h5_attr_write_vlstr(hid_t obj, const char *name, const char *value)
{
    hid_t t = H5Tcopy(H5T_C_S1);
    H5Tset_size(t, H5T_VARIABLE);
    H5Tset_cset(t, H5T_CSET_UTF8);
    hid_t s = H5Screate(H5S_SCALAR);
    int rc = write_attr(obj, name, t, s, &value);
    H5Sclose(s);
    H5Tclose(t);
    return rc;
}

/* n strings packed into slots of the longest length + 1 (malloc'd), with
 * their HDF5 type and the 1-d space of n; NULL when out of memory. */
static char *pack_strs(const char *const *values, size_t n, hid_t *type, hid_t *space)
{
    size_t w = 1;
    for (size_t k = 0; k < n; k++)
        if (strlen(values[k]) + 1 > w)
            w = strlen(values[k]) + 1;
    char *buf = calloc(n ? n : 1, w);
    if (!buf)
        return NULL;
    for (size_t k = 0; k < n; k++)
        memcpy(buf + k * w, values[k], strlen(values[k]));
    *type = H5Tcopy(H5T_C_S1);
    H5Tset_size(*type, w);
    H5Tset_strpad(*type, H5T_STR_NULLTERM);
    hsize_t dim = n;
    *space = H5Screate_simple(1, &dim, NULL);
    return buf;
}

int h5_attr_write_strs(hid_t obj, const char *name, const char *const *values, size_t n)
{
    hid_t t, s;
    char *buf = pack_strs(values, n, &t, &s);
    if (!buf)
        return -1;
    int rc = write_attr(obj, name, t, s, buf);
    H5Sclose(s);
    H5Tclose(t);
    free(buf);
    return rc;
}


int h5_attr_write_double(hid_t obj, const char *name, double value)
{
    hid_t s = H5Screate(H5S_SCALAR);
    int rc = write_attr(obj, name, H5T_NATIVE_DOUBLE, s, &value);
    H5Sclose(s);
    return rc;
}

/* The attribute, or a negative id if it does not exist. */
static hid_t open_attr(hid_t obj, const char *name)
{
    return H5Aexists(obj, name) > 0 ? H5Aopen(obj, name, H5P_DEFAULT) : H5I_INVALID_HID;
}

/* a 1-d (or scalar for n = 1) attribute of n values of memory type t */
static int write_array_attr(hid_t obj, const char *name, hid_t t, const void *values, size_t n)
{
    hsize_t dim = n;
    hid_t s = n == 1 ? H5Screate(H5S_SCALAR) : H5Screate_simple(1, &dim, NULL);
    int rc = write_attr(obj, name, t, s, values);
    H5Sclose(s);
    return rc;
}

int h5_attr_write_doubles(hid_t obj, const char *name, const double *values, size_t n)
{
    return write_array_attr(obj, name, H5T_NATIVE_DOUBLE, values, n);
}

int h5_attr_write_int64s(hid_t obj, const char *name, const int64_t *values, size_t n)
{
    return write_array_attr(obj, name, H5T_NATIVE_INT64, values, n);
}

static int read_array_attr(hid_t obj, const char *name, hid_t t, void *values, size_t n)
{
    hid_t a = open_attr(obj, name);
    if (a < 0)
        return -1;
    hid_t s = H5Aget_space(a);
    hssize_t count = H5Sget_simple_extent_npoints(s);
    H5Sclose(s);
    int rc = -1;
    if (count >= 1 && (size_t)count <= n && H5Aread(a, t, values) >= 0)
        rc = (int)count;
    H5Aclose(a);
    return rc;
}

int h5_attr_read_doubles(hid_t obj, const char *name, double *values, size_t n)
{
    return read_array_attr(obj, name, H5T_NATIVE_DOUBLE, values, n);
}

int h5_attr_read_int64s(hid_t obj, const char *name, int64_t *values, size_t n)
{
    return read_array_attr(obj, name, H5T_NATIVE_INT64, values, n);
}

int h5_attr_write_ints(hid_t obj, const char *name, const int *values, size_t n)
{
    return write_array_attr(obj, name, H5T_NATIVE_INT, values, n);
}

int h5_attr_read_ints(hid_t obj, const char *name, int *values, size_t n)
{
    return read_array_attr(obj, name, H5T_NATIVE_INT, values, n);
}

int h5_attr_read_str(hid_t obj, const char *name, char *buf, size_t len)
{
    hid_t a = open_attr(obj, name);
    if (a < 0)
        return -1;
    hid_t ft = H5Aget_type(a);
    int rc = -1;
    if (H5Tget_class(ft) == H5T_STRING) {
        if (H5Tis_variable_str(ft) > 0) {
            char *v = NULL;
            hid_t mt = H5Tcopy(H5T_C_S1);
            H5Tset_size(mt, H5T_VARIABLE);
            H5Tset_cset(mt, H5Tget_cset(ft)); /* HDF5 does not convert ASCII <-> UTF-8 */
            if (H5Aread(a, mt, &v) >= 0 && v) {
                snprintf(buf, len, "%s", v);
                H5free_memory(v);
                rc = 0;
            }
            H5Tclose(mt);
        } else {
            size_t sz = H5Tget_size(ft);
            char tmp[1024];
            if (sz < sizeof tmp) {
                hid_t mt = H5Tcopy(H5T_C_S1);
                H5Tset_size(mt, sz + 1);
                H5Tset_strpad(mt, H5T_STR_NULLTERM);
                H5Tset_cset(mt, H5Tget_cset(ft));
                if (H5Aread(a, mt, tmp) >= 0) {
                    tmp[sz] = '\0';
                    snprintf(buf, len, "%s", tmp);
                    rc = 0;
                }
                H5Tclose(mt);
            }
        }
    }
    H5Tclose(ft);
    H5Aclose(a);
    return rc;
}

int h5_attr_read_strs(hid_t obj, const char *name, char (*values)[16], size_t n)
{
    hid_t a = open_attr(obj, name);
    if (a < 0)
        return -1;
    hid_t s = H5Aget_space(a);
    hssize_t count = H5Sget_simple_extent_npoints(s);
    H5Sclose(s);
    int rc = -1;
    if (count >= 1 && (size_t)count <= n) {
        hid_t mt = H5Tcopy(H5T_C_S1);
        H5Tset_size(mt, 16);
        H5Tset_strpad(mt, H5T_STR_NULLTERM);
        hid_t ft = H5Aget_type(a);
        if (H5Tget_class(ft) == H5T_STRING && H5Tis_variable_str(ft) <= 0 &&
            H5Aread(a, mt, values) >= 0) {
            for (hssize_t k = 0; k < count; k++)
                values[k][15] = '\0';
            rc = (int)count;
        }
        H5Tclose(ft);
        H5Tclose(mt);
    }
    H5Aclose(a);
    return rc;
}

int h5_write_doubles(hid_t loc, const char *name, int rank, const hsize_t *dims,
                     const double *data, const char *unit, const char *meaning)
{
    hid_t s = H5Screate_simple(rank, dims, NULL);
    hid_t ds = H5Dcreate2(loc, name, H5T_IEEE_F64LE, s, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    int rc = ds < 0 || H5Dwrite(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, data) < 0;
    if (!rc && unit && strcmp(unit, "1") != 0)
        rc |= h5_attr_write_str(ds, "unit", unit);
    if (!rc && meaning)
        rc |= h5_attr_write_str(ds, "definition", meaning);
    if (ds >= 0)
        H5Dclose(ds);
    H5Sclose(s);
    return rc;
}

void h5_release_free_lists(void)
{
    H5garbage_collect();
#ifdef __GLIBC__
    /* and the heap's free pages back to the system */
    malloc_trim(0);
#endif
}

void h5_limit_free_lists(size_t bytes)
{
    int all = bytes / 3 > 0x7fffffff ? 0x7fffffff : (int)(bytes / 3), one = all / 4;
    /* regular, array and block lists: a third each, a quarter of that per list */
    H5set_free_list_limits(all, one, all, one, all, one);
}

int h5_write_strs(hid_t loc, const char *name, const char *const *values, size_t n,
                  const char *meaning)
{
    hid_t t, s;
    char *buf = pack_strs(values, n, &t, &s);
    if (!buf)
        return -1;
    hid_t ds = H5Dcreate2(loc, name, t, s, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    int rc = ds < 0 || H5Dwrite(ds, t, H5S_ALL, H5S_ALL, H5P_DEFAULT, buf) < 0;
    if (!rc && meaning)
        rc |= h5_attr_write_str(ds, "definition", meaning);
    if (ds >= 0)
        H5Dclose(ds);
    H5Sclose(s);
    H5Tclose(t);
    free(buf);
    return rc;
}

hid_t h5_create_growing(hid_t loc, const char *name, hid_t type, int rank, int n_unlimited,
                        const hsize_t *dims, const hsize_t *chunk, const void *fill,
                        int deflate)
{
    hsize_t cur[8], max[8];
    if (rank < 1 || rank > 8)
        return H5I_INVALID_HID;
    for (int d = 0; d < rank; d++) {
        cur[d] = d < n_unlimited ? 0 : dims[d];
        max[d] = d < n_unlimited ? H5S_UNLIMITED : dims[d];
    }
    hid_t space = H5Screate_simple(rank, cur, max);
    hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);
    H5Pset_chunk(dcpl, rank, chunk);
    if (fill)
        H5Pset_fill_value(dcpl, type, fill);
    H5Pset_fill_time(dcpl, H5D_FILL_TIME_IFSET);
    H5Pset_alloc_time(dcpl, H5D_ALLOC_TIME_INCR);
    if (deflate > 0) {
        H5Pset_shuffle(dcpl);
        H5Pset_deflate(dcpl, (unsigned)deflate);
    }
    hid_t lcpl = H5Pcreate(H5P_LINK_CREATE);
    H5Pset_create_intermediate_group(lcpl, 1);
    hid_t ds = H5Dcreate2(loc, name, type, space, lcpl, dcpl, H5P_DEFAULT);
    H5Pclose(lcpl);
    H5Pclose(dcpl);
    H5Sclose(space);
    return ds;
}

hid_t h5_group_ordered(hid_t loc, const char *path)
{
    if (H5Lexists(loc, path, H5P_DEFAULT) > 0)
        return H5Gopen2(loc, path, H5P_DEFAULT);
    hid_t lcpl = H5Pcreate(H5P_LINK_CREATE);
    H5Pset_create_intermediate_group(lcpl, 1);
    hid_t gcpl = H5Pcreate(H5P_GROUP_CREATE);
    unsigned order = H5P_CRT_ORDER_TRACKED | H5P_CRT_ORDER_INDEXED;
    H5Pset_link_creation_order(gcpl, order);
    H5Pset_attr_creation_order(gcpl, order);
    hid_t g = H5Gcreate2(loc, path, lcpl, gcpl, H5P_DEFAULT);
    H5Pclose(gcpl);
    H5Pclose(lcpl);
    return g;
}

hsize_t h5_extent0(hid_t dset)
{
    hsize_t dims[4] = {0};
    hid_t s = H5Dget_space(dset);
    if (s < 0)
        return 0;
    if (H5Sget_simple_extent_ndims(s) < 1 || H5Sget_simple_extent_ndims(s) > 4)
        dims[0] = 0;
    else
        H5Sget_simple_extent_dims(s, dims, NULL);
    H5Sclose(s);
    return dims[0];
}

int h5_append_row(hid_t ds, hsize_t k, int rank, const hsize_t *dims, hid_t memtype,
                  const void *row)
{
    hsize_t ext[5] = {k + 1}, start[5] = {k}, count[5] = {1};
    if (rank < 0 || rank > 4)
        return -1;
    for (int d = 0; d < rank; d++) {
        ext[d + 1] = dims[d];
        start[d + 1] = 0;
        count[d + 1] = dims[d];
    }
    if (H5Dset_extent(ds, ext) < 0)
        return -1;
    hid_t fs = H5Dget_space(ds);
    hsize_t n = 1;
    for (int d = 0; d < rank; d++)
        n *= dims[d];
    hid_t ms = H5Screate_simple(1, &n, NULL);
    int rc = H5Sselect_hyperslab(fs, H5S_SELECT_SET, start, NULL, count, NULL) < 0 ||
             H5Dwrite(ds, memtype, ms, fs, H5P_DEFAULT, row) < 0;
    H5Sclose(ms);
    H5Sclose(fs);
    return rc;
}
