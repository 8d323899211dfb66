/* Large zeroed arrays (a frame's sums and the fields over a grid: megabytes to gigabytes).
 * They start on a cache line; from 2 MB up they are mapped from the kernel, start on a
 * 2 MB boundary and are advised for transparent huge pages: where the kernel offers them
 * on request (its "madvise" mode, or "always"), it takes one page fault per 2 MB that the
 * array first touches, not one per 4 kB, and its fresh pages are zero without a pass of
 * the program's own (docs/performance.md, "Memory").  Under AddressSanitizer they are
 * heap blocks, which it guards. */
#ifndef MIMAS_BIG_ALLOC_H
#define MIMAS_BIG_ALLOC_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* n elements of size bytes, zeroed, on a 64-byte boundary (a 2 MB one from 2 MB up); NULL
 * when out of memory or when n size overflows.  Freed by mimas_big_free only. */
void *mimas_big_calloc(size_t n, size_t size);
/* Frees what mimas_big_calloc returned; NULL is ignored. */
void mimas_big_free(void *p);

#ifdef __cplusplus
}
#endif

#endif
