/* The keywords of a LIGGGHTS compute pair/gran/local or wall/gran/local
 * told from the column count of its dump, and the check of that guess on
 * the data (docs/readers.md, "Inferred columns"). */
#ifndef MIMAS_LAMMPS_INFER_H
#define MIMAS_LAMMPS_INFER_H

#include <stddef.h>

#include "frame.h"

/* The keyword sets a count can name: LIGGGHTS' default set
 * (pos,vel,id,force,torque,history,contactArea: 22 + H columns, H >= 1) and
 * every keyword (pos .. contactPoint: 38 + H, H >= 0).  Of those that fit
 * ncols, the one with the fewest history columns (the history of a contact
 * model is a few values: 41 columns are every keyword with 3, not the default
 * set with 19).  Writes it as --contact-columns takes it; -1 if none fits. */
int gran_infer_keywords(size_t ncols, char *buf, size_t len);

/* Checks the contacts (walls: the wall contacts) of frame f, read with the
 * inferred keywords, against what the particles imply: overlap = R_i + R_j -
 * |r_i - r_j| (walls: R - |r - c|), the contact point on the segment between
 * the centres, the contact area of the two spheres, force_normal +
 * force_tangential = force with force_normal along the branch vector; each
 * within the 6 significant digits LIGGGHTS prints.  Returns 0, or -1 with
 * why set to the first contact that does not fit. */
int gran_check_inferred(const mimas_frame *f, int walls, char *why, size_t len);

#endif
