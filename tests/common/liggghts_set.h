/* The LIGGGHTS reference data of tests/data/liggghts (its README.md): paths
 * and readers over a per-atom dump with its pair/gran/local and
 * wall/gran/local files. */
#ifndef MIMAS_TEST_LIGGGHTS_SET_H
#define MIMAS_TEST_LIGGGHTS_SET_H

#include "reader.h"

/* The keywords of the shipped local dumps, in LIGGGHTS' column order. */
#define LIGGGHTS_KEYS "pos,vel,id,force,force_normal,force_tangential,torque,torque_normal," \
                      "torque_tangential,history,contactArea,delta,contactPoint"

/* "$TEST_SRCDIR/data/liggghts/REL" (8 rotating buffers). */
const char *liggghts_data(const char *rel);
/* A reader over atoms with the contacts in pgl and the wall contacts in wgl
 * (either may be NULL). */
int liggghts_open(mimas_reader **r, const char *atoms, const char *pgl, const char *wgl,
                  mimas_error *err);
/* The last frame of the set into f. */
int liggghts_last_frame(const char *atoms, const char *pgl, const char *wgl, mimas_frame *f,
                        mimas_error *err);

#endif
