/* Particles binned by their fractional position in a (possibly triclinic)
 * box, for visiting every particle within a distance R of a point, by the
 * minimum image along the periodic axes (docs/theory.md §1). */
#ifndef MIMAS_CELL_LIST_H
#define MIMAS_CELL_LIST_H

#include <stddef.h>

#include "error.h"
#include "frame.h"

typedef struct mimas_cell_list {
    mimas_box box;
    double reach;
    int nb[3];          /* bins along the three edge vectors */
    size_t *start;      /* nb[0] nb[1] nb[2] + 1 offsets into index */
    size_t *index;      /* the particles, sorted by bin */
    size_t *bin;        /* scratch: each particle's bin */
    size_t bins_cap, n_cap;
} mimas_cell_list;

void mimas_cell_list_init(mimas_cell_list *cl);
/* Bins the particles k < n with use[k] (use NULL: all) for queries of
 * radius reach, which must be less than half the box's width along its
 * periodic axes (so that one image is within reach). */
int mimas_cell_list_build(mimas_cell_list *cl, const mimas_box *box, size_t n,
                          const double (*pos)[3], const unsigned char *use, double reach,
                          mimas_error *err);
/* Calls fn for every binned particle j with |d| < reach, d = x - pos[j] by
 * the minimum image. */
typedef void (*mimas_neighbour_fn)(void *user, size_t j, const double d[3], double d2);
void mimas_cell_list_query(const mimas_cell_list *cl, const double x[3], const double (*pos)[3],
                           mimas_neighbour_fn fn, void *user);
void mimas_cell_list_free(mimas_cell_list *cl);

#endif
