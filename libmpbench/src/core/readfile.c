/* readfile.c - a whole file into memory: mpb_read_file() and its loaders' form. */
#include "mpbench/mpbench.h"

#include <errno.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "core/errbuf.h"
#include "core/readfile.h"

char *mpb_read_file(const char *path, size_t max, size_t *len)
{
    if (len)
        *len = 0;
    if (path == NULL) {
        errno = EINVAL;
        return NULL;
    }
    FILE *f = fopen(path, "rb");
    if (f == NULL)
        return NULL;            /* errno says why */
    /* fopen() opens a folder; reading it would say "Input/output error". */
    struct stat st;
    if (fstat(fileno(f), &st) == 0 && S_ISDIR(st.st_mode)) {
        fclose(f);
        errno = EISDIR;
        return NULL;
    }
    char *buf = NULL;
    size_t n = 0, cap = 0;
    int fault = 0;
    for (;;) {
        if (cap - n < 4096 + 1) {       /* room for a read and the NUL */
            size_t ncap = cap ? 2 * cap : 65536;
            char *nb = cap <= SIZE_MAX / 2 ? realloc(buf, ncap) : NULL;
            if (nb == NULL) {
                fault = ENOMEM;
                break;
            }
            buf = nb;
            cap = ncap;
        }
        size_t got = fread(buf + n, 1, cap - n - 1, f);
        n += got;
        if (max > 0 && n > max) {
            fault = EFBIG;
            break;
        }
        if (got == 0) {
            if (ferror(f))
                fault = EIO;
            break;
        }
    }
    fclose(f);
    if (fault) {
        free(buf);
        errno = fault;
        return NULL;
    }
    buf[n] = '\0';
    if (len)
        *len = n;
    return buf;
}

int mpb__read_file(const char *path, size_t max, char **text, size_t *len,
                   char *err, size_t errlen)
{
    *text = mpb_read_file(path, max, len);
    if (*text != NULL)
        return MPB_OK;
    int e = errno;
    if (e == ENOMEM) {
        mpb__set_err(err, errlen, "%s: out of memory", path);
        return MPB_ENOMEM;
    }
    if (e == EFBIG)
        mpb__set_err(err, errlen, "%s: larger than %zu bytes", path, max);
    else if (e == EIO)
        mpb__set_err(err, errlen, "%s: read error", path);
    else
        mpb__set_err(err, errlen, "%s: cannot open: %s", path, strerror(e));
    return MPB_EIO;
}
