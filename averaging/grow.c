#include <config.h>

#include "grow.h"

#include <stdlib.h>

int mimas_grow(void **array, size_t *cap, size_t need, size_t elem, size_t first,
               mimas_error *err)
{
    if (need <= *cap)
        return MIMAS_OK;
    size_t n = *cap ? *cap : first;
    while (n < need)
        n *= 2;
    void *p = realloc(*array, n * elem);
    if (!p)
        return mimas_error_set(err, MIMAS_EIO, "out of memory");
    *array = p;
    *cap = n;
    return MIMAS_OK;
}
