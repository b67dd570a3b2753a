/*
 * error.c - names and descriptions of the MPB_E... error codes, and the
 * messages the library's functions write into a caller's buffer.
 */
#include <stdio.h>

#include "core/errbuf.h"
#include "mpbench/mpbench.h"

const char *mpb_strerror(int code)
{
    switch (code) {
#define MPB__ERRNO_TEXT(name, value, text) case (value): return text;
        MPB_ERRNO_MAP(MPB__ERRNO_TEXT)
#undef MPB__ERRNO_TEXT
    }
    return "unknown error code";
}

const char *mpb_err_name(int code)
{
    switch (code) {
#define MPB__ERRNO_NAME(name, value, text) case (value): return "MPB_E" #name;
        MPB_ERRNO_MAP(MPB__ERRNO_NAME)
#undef MPB__ERRNO_NAME
    }
    return "MPB_E?";
}

void mpb__set_err_v(char *err, size_t errlen, const char *fmt, va_list ap)
{
    if (err == NULL || errlen == 0)
        return;
    vsnprintf(err, errlen, fmt, ap);
    for (char *p = err; *p; p++)
        if (*p == '\n' || *p == '\r')
            *p = ' ';
}

void mpb__set_err(char *err, size_t errlen, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    mpb__set_err_v(err, errlen, fmt, ap);
    va_end(ap);
}
