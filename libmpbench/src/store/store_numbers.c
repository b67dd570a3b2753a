/* store_numbers.c - a query row's space-separated numbers read back. */
#include "mpbench/mpbench.h"

#include <stdlib.h>

int mpb_store_numbers(const char *text, double *out, int n)
{
    const char *p = text ? text : "";
    for (int i = 0; i < n; i++) {
        char *end;
        out[i] = strtod(p, &end);
        if (end == p)
            return MPB_EINVAL;
        p = end;
    }
    return MPB_OK;
}
