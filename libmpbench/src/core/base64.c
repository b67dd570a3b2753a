/*
 * base64.c - RFC 4648 base64, for binary data in text formats.
 */
#include "mpbench/mpbench.h"
#include "core/base64.h"

#include <stdlib.h>
#include <string.h>

static const char ABC[] =
    "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";

int mpb__base64_encode(const void *data, size_t n, char **out, size_t *outlen)
{
    const unsigned char *p = data;
    size_t chars = (n + 2) / 3 * 4, lines = (chars + 75) / 76;
    char *s = malloc(chars + lines + 1), *q = s;
    if (!s)
        return MPB_ENOMEM;
    size_t col = 0;
    for (size_t i = 0; i < n; i += 3) {
        unsigned v = (unsigned)p[i] << 16;
        if (i + 1 < n)
            v |= (unsigned)p[i + 1] << 8;
        if (i + 2 < n)
            v |= p[i + 2];
        *q++ = ABC[v >> 18 & 63];
        *q++ = ABC[v >> 12 & 63];
        *q++ = i + 1 < n ? ABC[v >> 6 & 63] : '=';
        *q++ = i + 2 < n ? ABC[v & 63] : '=';
        col += 4;
        if (col == 76 || i + 3 >= n) {
            *q++ = '\n';
            col = 0;
        }
    }
    *q = '\0';
    if (outlen)
        *outlen = (size_t)(q - s);
    *out = s;
    return MPB_OK;
}

static int val(char c)
{
    const char *f = c ? strchr(ABC, c) : NULL;
    return f ? (int)(f - ABC) : -1;
}

long mpb__base64_decode(const char *s, size_t len, unsigned char *out, size_t *n)
{
    size_t w = 0;
    if (len % 4 != 0)
        return -1 - (long)(len / 4 * 4);
    for (size_t i = 0; i < len; i += 4) {
        int v[4], pad = 0;
        for (int k = 0; k < 4; k++) {
            if (s[i + k] == '=' && i + 4 == len && k >= 2) {
                v[k] = 0;
                pad++;
                continue;
            }
            if (pad || (v[k] = val(s[i + k])) < 0)
                return -1 - (long)(i + (size_t)k);
        }
        unsigned x = (unsigned)v[0] << 18 | (unsigned)v[1] << 12 | (unsigned)v[2] << 6 |
                     (unsigned)v[3];
        out[w++] = (unsigned char)(x >> 16);
        if (pad < 2)
            out[w++] = (unsigned char)(x >> 8);
        if (pad < 1)
            out[w++] = (unsigned char)x;
    }
    *n = w;
    return 0;
}
