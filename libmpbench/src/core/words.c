/* words.c - a line split at blanks (words.h). */
#include "core/words.h"

static int is_blank(char c)
{
    return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f';
}

int mpb__split_words(const char *b, const char *e, mpb__word *w, int max)
{
    int n = 0;
    while (b < e) {
        while (b < e && is_blank(*b))
            b++;
        if (b >= e)
            break;
        const char *s = b;
        while (b < e && !is_blank(*b))
            b++;
        if (n < max) {
            w[n].p = s;
            w[n].len = (int)(b - s);
        }
        n++;
    }
    return n;
}
