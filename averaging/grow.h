/* Growing an array by doubling (lists of plugs, tracks, events). */
#ifndef MIMAS_GROW_H
#define MIMAS_GROW_H

#include <stddef.h>

#include "error.h"

/* Makes *array hold at least need elements of size elem (doubling *cap,
 * at least first); MIMAS_EIO "out of memory" with err set otherwise (the
 * array is left as it was). */
int mimas_grow(void **array, size_t *cap, size_t need, size_t elem, size_t first,
               mimas_error *err);

#endif
