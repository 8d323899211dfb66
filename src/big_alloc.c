/* Large zeroed arrays in huge pages where the kernel offers them (big_alloc.h).  Each array
 * is preceded by a 64-byte header that says how to free it: the mapping's start and length
 * (mapped from the kernel), or the start of the heap block (small arrays, arrays under
 * AddressSanitizer, and where mmap is not available). */
#include <config.h>

#include "big_alloc.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#ifdef __linux__
#include <sys/mman.h>
#endif

enum { HUGE_PAGE = 2 << 20, HEAD = 64 };

/* Under AddressSanitizer every array is a heap block, which it guards (it does not see into
 * mappings of the program's own) */
#if defined(__SANITIZE_ADDRESS__)
#define BIG_MAP 0
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define BIG_MAP 0
#endif
#endif
#ifndef BIG_MAP
#define BIG_MAP 1
#endif

typedef struct big_head {
    void *base;  /* the mapping, or the heap block */
    size_t len;  /* the mapping's length; 0: a heap block */
} big_head;

/* A heap block: the array at `align` past the block's start (the header just before it) */
static void *heap_calloc(size_t bytes, size_t align)
{
    void *base = NULL;
    if (bytes > SIZE_MAX - align || posix_memalign(&base, align, align + bytes))
        return NULL;
    char *p = (char *)base + align;
    memset(p, 0, bytes);
    big_head h = {base, 0};
    memcpy(p - HEAD, &h, sizeof h);
    return p;
}

void *mimas_big_calloc(size_t n, size_t size)
{
    if (size && n > SIZE_MAX / size)
        return NULL;
    size_t bytes = n * size;
#if defined(__linux__) && defined(MAP_ANONYMOUS)
    if (BIG_MAP && bytes >= HUGE_PAGE && bytes <= SIZE_MAX / 2) {
        /* the array from the first 2 MB boundary past the header; of the mapping's pages
         * before it only the header's is touched, after its end none (address space only) */
        size_t rounded = (bytes + HUGE_PAGE - 1) / HUGE_PAGE * HUGE_PAGE;
        size_t len = rounded + HUGE_PAGE;
        void *base = mmap(NULL, len, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
        if (base == MAP_FAILED)
            return NULL;
        uintptr_t at = ((uintptr_t)base + HEAD + HUGE_PAGE - 1) / HUGE_PAGE * HUGE_PAGE;
        char *p = (char *)at;
#ifdef MADV_HUGEPAGE
        /* advice only: without huge pages to give, the array stays in 4 kB pages */
        (void)madvise(p, rounded, MADV_HUGEPAGE);
#endif
        big_head h = {base, len};
        memcpy(p - HEAD, &h, sizeof h);
        return p;
    }
#endif
    return heap_calloc(bytes, bytes >= HUGE_PAGE ? HUGE_PAGE : HEAD);
}

void mimas_big_free(void *p)
{
    if (!p)
        return;
    big_head h;
    memcpy(&h, (char *)p - HEAD, sizeof h);
#ifdef __linux__
    if (h.len) {
        munmap(h.base, h.len);
        return;
    }
#endif
    free(h.base);
}
