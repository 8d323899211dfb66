/* The table of the fields mimas average derives (docs/fields.md): name on
 * Cartesian and on cylindrical grids, unit and definition of each column of
 * mimas_average_fields().  Public: it maps the columns of an average held in
 * memory to their names. */
#ifndef MIMAS_FIELD_TABLE_H
#define MIMAS_FIELD_TABLE_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct mimas_field_desc {
    const char *name;   /* for Cartesian grids ("" : not there) */
    const char *cname;  /* for cylindrical grids (NULL: same name; "" : not there) */
    const char *unit;
    const char *meaning;
} mimas_field_desc;

/* All derived columns, in output order. */
size_t mimas_fields_count(void);
const mimas_field_desc *mimas_field(size_t k);
/* The column's name on a grid of this kind (NULL if the field does not exist there). */
const char *mimas_field_name(size_t k, int cylindrical);
/* The column of the field called name on a grid of this kind: 1 and *k, or
 * 0 if there is no such field there. */
int mimas_field_find(const char *name, int cylindrical, size_t *k);
/* Index of the velocity columns (3 consecutive). */
size_t mimas_fields_velocity(void);

#ifdef __cplusplus
}
#endif
#endif
