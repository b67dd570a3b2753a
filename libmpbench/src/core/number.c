/* number.c - a finite number filling a whole token of text (number.h). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/number.h"

int mpb__number(const char *p, int len, double *v)
{
    char buf[64];
    if (len <= 0 || len >= (int)sizeof buf)
        return 0;
    memcpy(buf, p, (size_t)len);
    buf[len] = '\0';
    char *end;
    double x = strtod(buf, &end);
    if (end != buf + len || !isfinite(x))
        return 0;
    *v = x;
    return 1;
}
