/* error.c - names and descriptions of the MPB_E... error codes. */
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
