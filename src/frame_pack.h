/* A frame as one flat byte buffer and back: everything the frame holds (step,
 * time, box, the three tables with their optional and extra columns, the
 * tube, the gas fields), in the layout of this build (native byte order and
 * sizes: for passing frames between processes of one program, e.g. MPI ranks,
 * not for files). */
#ifndef MIMAS_FRAME_PACK_H
#define MIMAS_FRAME_PACK_H

#include <stddef.h>

#include "error.h"
#include "frame.h"

#ifdef __cplusplus
extern "C" {
#endif

/* A growable byte buffer (free with mimas_bytes_free). */
typedef struct mimas_bytes {
    unsigned char *data;
    size_t n, cap;
} mimas_bytes;
void mimas_bytes_free(mimas_bytes *b);

/* Replaces b's content by the packed frame. */
int mimas_frame_pack(const mimas_frame *f, mimas_bytes *b, mimas_error *err);
/* Fills f (reusing its memory) from a buffer mimas_frame_pack wrote; a buffer
 * that is short or inconsistent is MIMAS_EDATA. */
int mimas_frame_unpack(mimas_frame *f, const unsigned char *data, size_t n, mimas_error *err);

#ifdef __cplusplus
}
#endif
#endif
