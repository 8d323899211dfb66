/* Maps particle ids to indices into a frame's particle arrays (contacts are
 * stored by id in files and by index in memory). */
#ifndef MIMAS_ID_INDEX_H
#define MIMAS_ID_INDEX_H

#include <stddef.h>
#include <stdint.h>

#include "error.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct mimas_id_index {
    size_t n;
    int64_t min_id;
    size_t span;        /* dense mode: table covers min_id .. min_id+span-1 */
    size_t *dense;      /* dense mode: index or SIZE_MAX; NULL in sorted mode */
    int64_t *ids;       /* sorted mode: ids ascending */
    size_t *idx;        /* sorted mode: their indices */
    size_t cap_dense, cap_sorted;
    int64_t duplicate;  /* after a build failed on a repeated id: that id */
} mimas_id_index;

void mimas_id_index_init(mimas_id_index *x);
/* Builds the map; a repeated id is an error naming it. */
int mimas_id_index_build(mimas_id_index *x, const int64_t *ids, size_t n, mimas_error *err);
/* Returns 1 and sets *index if id is known, else 0. */
int mimas_id_index_find(const mimas_id_index *x, int64_t id, size_t *index);
void mimas_id_index_free(mimas_id_index *x);

#ifdef __cplusplus
}
#endif
#endif
