/* Where a contact acts: the contact point and the branch vector from it to a
 * particle centre (PHYSICS 1, 2), shared by the averaging and the per-particle
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

/* What the averaging needs of a frame: particle radii, masses and
 * velocities, contact forces where the frame has contacts, wall-contact
 * forces and points where it has wall contacts.  MIMAS_EMISSING with a
 * message saying what is missing (and to give --density for masses). */
int mimas_frame_require_dynamics(const mimas_frame *f, mimas_error *err);

/* Every contact of the frame as the averaging sees it, given which
 * particles are used (keep[i] != 0); thread t of nt visits every nt-th:
 *   - both particles used: pair(user, k, b, at) with the branch b = r_i - r_j
 *     by the minimum image (from r_j) and the point at which the contact
 *     acts (its contact point, or r_i without one); the force is contact k's;
 *   - one particle used (the other left out, e.g. a glued wall particle), and
 *     every wall contact of a used particle: wall(user, i, c, force) with the
 *     contact point c and the force on particle i. */
typedef void (*mimas_pair_visit)(void *user, size_t k, const double b[3], const double at[3]);
typedef void (*mimas_wall_visit)(void *user, size_t i, const double c[3], const double force[3]);
void mimas_contacts_visit(const mimas_frame *f, const unsigned char *keep, size_t t, size_t nt,
                          mimas_pair_visit pair, mimas_wall_visit wall, void *user);

#endif
