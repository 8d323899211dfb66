/* Per-atom dump snapshots (dump custom / dump atom) into a frame's particles. */
#ifndef MIMAS_LAMMPS_ATOMS_H
#define MIMAS_LAMMPS_ATOMS_H

#include "id_index.h"
#include "lammps_series.h"

typedef struct atom_layout {
    dump_columns c;     /* targets: the enum in lammps_atoms.c */
    int pos_target;     /* which position columns are used */
    unsigned bits;      /* particle quantities the columns give */
} atom_layout;

/* Parses the rows of the current snapshot of s into f->particles (and sets
 * step, time, box) and builds index (id -> row).  density > 0 gives masses
 * to dumps without a mass column; dt > 0 gives times to dumps without
 * ITEM: TIME (else the time is NaN, "unknown"). */
int atoms_read(dump_series *s, atom_layout *l, mimas_frame *f, double density, double dt,
               mimas_id_index *index, mimas_error *err);
void atom_layout_free(atom_layout *l);

#endif
