/* text.c - UTF-8 as the terminal and the plots show it: characters, and
 * the columns they take (two for East Asian wide ones). */
#include "mpb.h"

int tool_utf8_char(const char *s, unsigned *cp)
{
    const unsigned char *u = (const unsigned char *)s;
    int len = u[0] < 0x80 ? 1 : u[0] >= 0xc2 && u[0] <= 0xdf ? 2
              : u[0] >= 0xe0 && u[0] <= 0xef ? 3
              : u[0] >= 0xf0 && u[0] <= 0xf4 ? 4 : 0;
    unsigned c = len == 1 ? u[0] : u[0] & (0x7f >> len);
    for (int i = 1; i < len; i++) {
        if ((u[i] & 0xc0) != 0x80)
            return 0;
        c = c << 6 | (u[i] & 0x3fu);
    }
    /* Overlong forms, surrogates, beyond U+10FFFF. */
    if ((len == 3 && c < 0x800) || (len == 4 && (c < 0x10000 || c > 0x10ffff))
        || (c >= 0xd800 && c <= 0xdfff))
        return 0;
    *cp = c;
    return len;
}

/* The East Asian wide ranges, and the emoji. */
int tool_char_cols(unsigned c)
{
    return (c >= 0x1100 && c <= 0x115f) || (c >= 0x2e80 && c <= 0xa4cf) ||
           (c >= 0xac00 && c <= 0xd7a3) || (c >= 0xf900 && c <= 0xfaff) ||
           (c >= 0xfe30 && c <= 0xfe4f) || (c >= 0xff00 && c <= 0xff60) ||
           (c >= 0xffe0 && c <= 0xffe6) || (c >= 0x1f300 && c <= 0x1f64f) ||
           (c >= 0x20000 && c <= 0x3fffd) ? 2 : 1;
}

int tool_text_cols(const char *s, const char *end)
{
    int cols = 0;
    unsigned cp;
    while (*s && (end == NULL || s < end)) {
        int len = tool_utf8_char(s, &cp);
        cols += len ? tool_char_cols(cp) : 1;
        s += len ? len : 1;
    }
    return cols;
}
