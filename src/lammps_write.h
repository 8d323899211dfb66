/* Frames as LAMMPS/LIGGGHTS text dumps (docs/readers.md, "Writing dumps"):
 * the particles as a `dump custom` file, the contacts and wall contacts as
 * `dump local` files with named columns, plain or gzip-compressed (a name
 * ending in .gz), every number with 17 significant digits so that reading
 * the dumps back gives the frames bit for bit.  Nothing appears at the
 * given names until close. */
#ifndef MIMAS_LAMMPS_WRITE_H
#define MIMAS_LAMMPS_WRITE_H

#include <stddef.h>

#include "error.h"
#include "frame.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct mimas_dump_writer mimas_dump_writer;

/* path: the per-atom dump; the contacts go to the name with ".pairs"
 * inserted before ".dump" (else appended), the wall contacts with ".walls"
 * (mimas_dump_local_path), created with the first frame that has them. */
int mimas_dump_open(mimas_dump_writer **w, const char *path, mimas_error *err);
int mimas_dump_append(mimas_dump_writer *w, const mimas_frame *f, mimas_error *err);
size_t mimas_dump_frames(const mimas_dump_writer *w);
/* The name of the contact (walls = 0) or wall-contact (walls = 1) dump of
 * the per-atom dump path. */
void mimas_dump_local_path(const char *path, int walls, char *out, size_t len);
/* Renames the finished files into place; frees w.  *wrote_local[k] (may be
 * NULL) says whether the contact and wall-contact dumps were written. */
int mimas_dump_close(mimas_dump_writer *w, int wrote_local[2], mimas_error *err);
/* Removes the unfinished files; frees w. */
void mimas_dump_abort(mimas_dump_writer *w);

#ifdef __cplusplus
}
#endif
#endif
