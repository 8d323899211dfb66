/* Run parameters: a small list of named values (parameters.h) and their
 * storage as HDF5 attributes (parameters_h5.h). */
#include <config.h>

#include "parameters.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "h5util.h"
#include "parameters_h5.h"

#define UNIT_SUFFIX ".unit"
#define MIXED_TEXT "mixed"

void mimas_parameters_init(mimas_parameters *ps)
{
    memset(ps, 0, sizeof *ps);
}

void mimas_parameters_free(mimas_parameters *ps)
{
    free(ps->p);
    mimas_parameters_init(ps);
}

void mimas_parameters_clear(mimas_parameters *ps)
{
    ps->n = 0;
}

/* A number as text with the digits that give it back exactly. */
static void number_text(double v, int integer, char *buf, size_t len)
{
    if (integer) {
        snprintf(buf, len, "%.0f", v);
        return;
    }
    snprintf(buf, len, "%.15g", v);
    if (strtod(buf, NULL) != v)
        snprintf(buf, len, "%.17g", v);
}

static mimas_parameter *find_exact(const mimas_parameters *ps, const char *name)
{
    for (size_t k = 0; k < ps->n; k++)
        if (!strcmp(ps->p[k].name, name))
            return &ps->p[k];
    return NULL;
}

const mimas_parameter *mimas_parameters_get(const mimas_parameters *ps, const char *name)
{
    return find_exact(ps, name);
}

/* Adds (or replaces) q. */
static int put(mimas_parameters *ps, const mimas_parameter *q, mimas_error *err)
{
    mimas_parameter *old = find_exact(ps, q->name);
    if (old) {
        *old = *q;
        return MIMAS_OK;
    }
    if (ps->n == ps->cap) {
        size_t cap = ps->cap ? 2 * ps->cap : 64;
        mimas_parameter *grown = realloc(ps->p, cap * sizeof *grown);
        if (!grown)
            return mimas_error_set(err, MIMAS_EIO, "out of memory");
        ps->p = grown;
        ps->cap = cap;
    }
    ps->p[ps->n++] = *q;
    return MIMAS_OK;
}

/* q with its name, kind and value; 0, or -1 if a string does not fit. */
static int make(mimas_parameter *q, const char *name, mimas_parameter_kind kind, double value,
                const char *text, const char *unit)
{
    memset(q, 0, sizeof *q);
    if (strlen(name) >= sizeof q->name || (unit && strlen(unit) >= sizeof q->unit) ||
        (kind == MIMAS_PARAM_TEXT && (!text || strlen(text) >= sizeof q->text)))
        return -1;
    snprintf(q->name, sizeof q->name, "%s", name);
    q->kind = kind;
    if (unit)
        snprintf(q->unit, sizeof q->unit, "%s", unit);
    if (kind == MIMAS_PARAM_TEXT || kind == MIMAS_PARAM_MIXED) {
        q->value = NAN;
        snprintf(q->text, sizeof q->text, "%s", kind == MIMAS_PARAM_TEXT ? text : MIXED_TEXT);
    } else {
        q->value = value;
        number_text(value, kind == MIMAS_PARAM_INTEGER, q->text, sizeof q->text);
    }
    return 0;
}

int mimas_parameters_add(mimas_parameters *ps, const char *section, const char *key,
                         mimas_parameter_kind kind, double value, const char *text,
                         const char *unit, mimas_error *err)
{
    char name[sizeof ((mimas_parameter *)0)->name];
    mimas_parameter q;
    if (strchr(section, '.') || strchr(key, '.') ||
        snprintf(name, sizeof name, "%s.%s", section, key) >= (int)sizeof name ||
        make(&q, name, kind, value, text, unit))
        return mimas_error_set(err, MIMAS_EUSAGE, "bad parameter [%s] %s", section, key);
    return put(ps, &q, err);
}

int mimas_parameters_copy(mimas_parameters *dst, const mimas_parameters *src, mimas_error *err)
{
    mimas_parameters_clear(dst);
    for (size_t k = 0; k < src->n; k++) {
        int rc = put(dst, &src->p[k], err);
        if (rc)
            return rc;
    }
    return MIMAS_OK;
}

static int same(const mimas_parameter *a, const mimas_parameter *b)
{
    return a->kind == b->kind && a->kind != MIMAS_PARAM_MIXED && !strcmp(a->text, b->text);
}

int mimas_parameters_merge(mimas_parameters *ps, const mimas_parameters *other,
                           mimas_error *err)
{
    for (size_t k = 0; k < ps->n; k++) {
        const mimas_parameter *q = find_exact(other, ps->p[k].name);
        mimas_parameter old = ps->p[k];
        if (!q || !same(&old, q))
            make(&ps->p[k], old.name, MIMAS_PARAM_MIXED, NAN, NULL, old.unit);
    }
    for (size_t k = 0; k < other->n; k++) {
        if (find_exact(ps, other->p[k].name))
            continue;
        mimas_parameter q;
        make(&q, other->p[k].name, MIMAS_PARAM_MIXED, NAN, NULL, other->p[k].unit);
        int rc = put(ps, &q, err);
        if (rc)
            return rc;
    }
    return MIMAS_OK;
}

int mimas_parameters_find(const mimas_parameters *ps, const char *name,
                          const mimas_parameter **out, mimas_error *err)
{
    *out = NULL;
    if (strchr(name, '.')) {
        *out = find_exact(ps, name);
        return *out ? MIMAS_OK
                    : mimas_error_set(err, MIMAS_EDATA, "no parameter '%s'", name);
    }
    char list[320] = "";
    size_t matches = 0, at = 0;
    for (size_t k = 0; k < ps->n; k++) {
        const char *dot = strchr(ps->p[k].name, '.');
        if (!dot || strcmp(dot + 1, name))
            continue;
        if (!matches++)
            *out = &ps->p[k];
        if (at < sizeof list)
            at += (size_t)snprintf(list + at, sizeof list - at, "%s%s", matches > 1 ? ", " : "",
                                   ps->p[k].name);
    }
    if (matches == 1)
        return MIMAS_OK;
    *out = NULL;
    if (!matches)
        return mimas_error_set(err, MIMAS_EDATA, "no parameter '%s'", name);
    return mimas_error_set(err, MIMAS_EDATA, "'%s' is a key of several sections (%s): give "
                           "SECTION.KEY", name, list);
}

/* ---- HDF5 ---- */

int parameters_write_h5(hid_t loc, const char *group, const mimas_parameters *ps)
{
    if (!ps->n)
        return 0;
    char path[256];
    if (snprintf(path, sizeof path, "/parameters/%s", group) >= (int)sizeof path)
        return -1;
    hid_t g = h5_group_ordered(loc, path);   /* attributes read back in written order */
    if (g < 0)
        return -1;
    int rc = 0;
    for (size_t k = 0; !rc && k < ps->n; k++) {
        const mimas_parameter *q = &ps->p[k];
        if (q->kind == MIMAS_PARAM_REAL) {
            rc = h5_attr_write_double(g, q->name, q->value);
        } else if (q->kind == MIMAS_PARAM_INTEGER) {
            long long v = (long long)q->value;
            hid_t s = H5Screate(H5S_SCALAR);
            hid_t a = H5Acreate2(g, q->name, H5T_STD_I64LE, s, H5P_DEFAULT, H5P_DEFAULT);
            rc = a < 0 || H5Awrite(a, H5T_NATIVE_LLONG, &v) < 0;
            if (a >= 0)
                H5Aclose(a);
            H5Sclose(s);
        } else {
            rc = h5_attr_write_str(g, q->name, q->text);
        }
        char uname[sizeof q->name + sizeof UNIT_SUFFIX];
        snprintf(uname, sizeof uname, "%s%s", q->name, UNIT_SUFFIX);
        if (!rc && q->unit[0])
            rc = h5_attr_write_str(g, uname, q->unit);
    }
    H5Gclose(g);
    return rc ? -1 : 0;
}

typedef struct read_ctx {
    mimas_parameters *ps;
    int bad;
} read_ctx;

static int is_unit_name(const char *name)
{
    size_t n = strlen(name), s = strlen(UNIT_SUFFIX);
    return n > s && !strcmp(name + n - s, UNIT_SUFFIX);
}

/* One attribute: a value (the units are picked up afterwards). */
static herr_t read_one(hid_t g, const char *name, const H5A_info_t *info, void *data)
{
    (void)info;
    read_ctx *c = data;
    if (is_unit_name(name))
        return 0;
    hid_t a = H5Aopen(g, name, H5P_DEFAULT);
    if (a < 0) {
        c->bad = 1;
        return 1;
    }
    hid_t t = H5Aget_type(a);
    H5T_class_t cls = H5Tget_class(t);
    hid_t s = H5Aget_space(a);
    int scalar = H5Sget_simple_extent_npoints(s) == 1;
    H5Sclose(s);
    H5Tclose(t);
    H5Aclose(a);
    mimas_parameter q;
    int rc = -1;
    if (scalar && cls == H5T_FLOAT) {
        double v;
        hid_t aa = H5Aopen(g, name, H5P_DEFAULT);
        rc = H5Aread(aa, H5T_NATIVE_DOUBLE, &v) < 0 ? -1
                                                     : make(&q, name, MIMAS_PARAM_REAL, v, NULL, NULL);
        H5Aclose(aa);
    } else if (scalar && cls == H5T_INTEGER) {
        long long v;
        hid_t aa = H5Aopen(g, name, H5P_DEFAULT);
        rc = H5Aread(aa, H5T_NATIVE_LLONG, &v) < 0
                 ? -1
                 : make(&q, name, MIMAS_PARAM_INTEGER, (double)v, NULL, NULL);
        H5Aclose(aa);
    } else if (scalar && cls == H5T_STRING) {
        char text[sizeof q.text];
        rc = h5_attr_read_str(g, name, text, sizeof text);
        if (!rc)
            rc = make(&q, name, strcmp(text, MIXED_TEXT) ? MIMAS_PARAM_TEXT : MIMAS_PARAM_MIXED,
                      NAN, text, NULL);
    }
    if (rc || put(c->ps, &q, NULL)) {
        c->bad = 1;
        return 1;
    }
    return 0;
}

int parameters_read_h5(hid_t loc, const char *group, mimas_parameters *ps)
{
    mimas_parameters_clear(ps);
    char path[256];
    if (snprintf(path, sizeof path, "/parameters/%s", group) >= (int)sizeof path)
        return -1;
    h5_quiet q;
    h5_quiet_begin(&q);
    int rc = 0;
    if (H5Lexists(loc, "/parameters", H5P_DEFAULT) > 0 && H5Lexists(loc, path, H5P_DEFAULT) > 0) {
        hid_t g = H5Gopen2(loc, path, H5P_DEFAULT);
        read_ctx c = {ps, g < 0};
        if (g >= 0) {
            hid_t gcpl = H5Gget_create_plist(g);
            unsigned order = 0;
            H5Pget_attr_creation_order(gcpl, &order);
            H5Pclose(gcpl);
            H5_index_t by = (order & H5P_CRT_ORDER_INDEXED) ? H5_INDEX_CRT_ORDER : H5_INDEX_NAME;
            hsize_t at = 0;
            if (H5Aiterate2(g, by, H5_ITER_INC, &at, read_one, &c) < 0)
                c.bad = 1;
            for (size_t k = 0; !c.bad && k < ps->n; k++) {
                char uname[sizeof ps->p[k].name + sizeof UNIT_SUFFIX];
                snprintf(uname, sizeof uname, "%s%s", ps->p[k].name, UNIT_SUFFIX);
                if (H5Aexists(g, uname) > 0 &&
                    h5_attr_read_str(g, uname, ps->p[k].unit, sizeof ps->p[k].unit))
                    c.bad = 1;
            }
            H5Gclose(g);
        }
        rc = c.bad ? -1 : 0;
    }
    h5_quiet_end(&q);
    if (rc)
        mimas_parameters_clear(ps);
    return rc;
}
