/* grow.h - how libmpbench's files grow an array; not part of the API. */
#ifndef MPB_GROW_H
#define MPB_GROW_H

#include <limits.h>
#include <stdlib.h>

#include "mpbench/mpbench.h"

/*
 * Make *arr hold at least need elements of size bytes each, *cap being
 * how many it holds now. The capacity doubles, so n appends cost O(n)
 * copies. MPB_OK, or MPB_ENOMEM with *arr and *cap as they were.
 */
static inline int mpb__grow(void **arr, int *cap, int need, size_t size)
{
    if (need <= *cap)
        return MPB_OK;
    int c = *cap > 0 ? *cap : 8;
    while (c < need) {
        if (c > INT_MAX / 2)
            return MPB_ENOMEM;
        c *= 2;
    }
    void *a = realloc(*arr, (size_t)c * size);
    if (a == NULL)
        return MPB_ENOMEM;
    *arr = a;
    *cap = c;
    return MPB_OK;
}

#endif /* MPB_GROW_H */
