/* Where a contact acts: the contact point and the branch vector from it to a
 * particle centre (docs/theory.md §1), shared by the averaging and the per-particle
 * Voronoi stress. */
#ifndef MIMAS_CONTACT_POINT_H
#define MIMAS_CONTACT_POINT_H

#include <stddef.h>

#include "frame.h"

/* The contact point of contact k of f, next to particle i (one of its two
 * particles): the stored contact point, or c = r_i - (R_i - delta/2) n with
 * n the unit vector from the other particle to i by the minimum image. */
void mimas_contact_point(const mimas_frame *f, size_t k, size_t i, double c[3]);
/* The branch vector b = r - c by the minimum image. */
void mimas_branch(const mimas_box *box, const double r[3], const double c[3], double b[3]);

#endif
