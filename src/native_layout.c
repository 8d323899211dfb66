#include <config.h>

#include "native_layout.h"

#include <stdio.h>
#include <string.h>

hid_t native_file_type(mimas_elem_type t)
{
    switch (t) {
    case MIMAS_T_F64: return H5T_IEEE_F64LE;
    case MIMAS_T_I32: return H5T_STD_I32LE;
    case MIMAS_T_I64:
    case MIMAS_T_INDEX: return H5T_STD_I64LE; /* indices are stored as particle ids */
    }
    return H5T_IEEE_F64LE;
}

hid_t native_mem_type(mimas_elem_type t)
{
    switch (t) {
    case MIMAS_T_F64: return H5T_NATIVE_DOUBLE;
    case MIMAS_T_I32: return H5T_NATIVE_INT32;
    case MIMAS_T_I64:
    case MIMAS_T_INDEX: return H5T_NATIVE_INT64;
    }
    return H5T_NATIVE_DOUBLE;
}

void *native_col_data(const void *tab, const mimas_table_desc *d, const native_col *c)
{
    if (c->desc_col >= 0)
        return mimas_table_column(tab, d, (size_t)c->desc_col);
    const size_t n_extra = *(const size_t *)((const char *)tab + d->off_n_extra);
    const mimas_extra *extra = *(mimas_extra *const *)((const char *)tab + d->off_extra);
    if (c->extra < 0 || (size_t)c->extra >= n_extra)
        return NULL;
    return extra[c->extra].data;
}

const char *native_col_unit(const void *tab, const mimas_table_desc *d, const native_col *c)
{
    if (c->desc_col >= 0)
        return d->columns[c->desc_col].unit;
    const size_t n_extra = *(const size_t *)((const char *)tab + d->off_n_extra);
    const mimas_extra *extra = *(mimas_extra *const *)((const char *)tab + d->off_extra);
    if (c->extra < 0 || (size_t)c->extra >= n_extra || !extra[c->extra].unit[0])
        return NULL;
    return extra[c->extra].unit;
}

size_t native_cols_of(const void *tab, const mimas_table_desc *d, native_col *cols)
{
    size_t k = 0;
    unsigned present = mimas_table_present(tab, d);
    for (size_t c = 0; c < d->ncolumns; c++) {
        if (!(present & d->columns[c].bit))
            continue;
        native_col *nc = &cols[k++];
        snprintf(nc->name, sizeof nc->name, "%s", d->columns[c].name);
        nc->type = d->columns[c].type;
        nc->ncomp = d->columns[c].ncomp;
        nc->desc_col = (long)c;
        nc->extra = -1;
        nc->ds = H5I_INVALID_HID;
    }
    const size_t n_extra = *(const size_t *)((const char *)tab + d->off_n_extra);
    const mimas_extra *extra = *(mimas_extra *const *)((const char *)tab + d->off_extra);
    for (size_t e = 0; e < n_extra; e++) {
        native_col *nc = &cols[k++];
        snprintf(nc->name, sizeof nc->name, "%s", extra[e].name);
        nc->type = MIMAS_T_F64;
        nc->ncomp = extra[e].ncomp;
        nc->desc_col = -1;
        nc->extra = (long)e;
        nc->ds = H5I_INVALID_HID;
    }
    return k;
}
