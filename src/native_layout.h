/* Names and shared pieces of the native layout, used by the writer
 * (src/native_write.c) and the reader (readers/native_read.c). */
#ifndef MIMAS_NATIVE_LAYOUT_H
#define MIMAS_NATIVE_LAYOUT_H

#include <hdf5.h>

#include "frame.h"

#define NATIVE_PARTICLES "/particles/all"
#define NATIVE_BOX NATIVE_PARTICLES "/box"
#define NATIVE_OBSERVABLES "/observables/all"
#define NATIVE_COUNT NATIVE_OBSERVABLES "/particle_count"
#define NATIVE_CONTACTS "/contacts/all"
#define NATIVE_WALLS "/contacts/walls"
#define NATIVE_MIMAS "/mimas"
/* format 1.1: the tube of a tube-flow run, gas fields on a grid */
#define NATIVE_TUBE "/parameters/tube"
#define NATIVE_GAS "/fields/gas"
/* per-particle elements share the step and time datasets of this one */
#define NATIVE_CLOCK NATIVE_PARTICLES "/position"

/* One column of a table as it is stored: a standard quantity of the table's
 * descriptor (desc_col >= 0) or an extra column (extra >= 0). */
typedef struct native_col {
    char name[64];
    mimas_elem_type type;
    int ncomp;
    long desc_col;
    long extra;
    hid_t ds;
    struct h5_direct *direct; /* the reader's: ds by its chunks (h5_direct.h), or NULL */
} native_col;

hid_t native_file_type(mimas_elem_type t);
hid_t native_mem_type(mimas_elem_type t);
/* The array a column refers to in a table (NULL when it has no such column). */
void *native_col_data(const void *tab, const mimas_table_desc *d, const native_col *c);
/* A column's unit: its descriptor's, or an extra column's own (NULL if it
 * has none). */
const char *native_col_unit(const void *tab, const mimas_table_desc *d, const native_col *c);
/* Lists the columns a table carries (present standard ones, then extras).
 * Returns the count; cols must hold desc->ncolumns + n_extra entries. */
size_t native_cols_of(const void *tab, const mimas_table_desc *d, native_col *cols);

#endif
