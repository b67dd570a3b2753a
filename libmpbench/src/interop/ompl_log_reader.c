/*
 * ompl_log_reader.c - the cursor of the benchmark log reader
 * (ompl_log_reader.h): lines, counts, numbers and "<<<|" blocks, each
 * failure naming its line.
 */
#include <ctype.h>
#include <errno.h>
#include <float.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "interop/ompl_log_reader.h"

const char *const mpb__log_kind_names[V_TIME + 1] = {"REAL", "INTEGER",
                                                     "BOOLEAN", "ENUM", "time"};

int mpb__log_fail(reader *r, const char *fmt, ...)
{
    if (!r->failed && r->err && r->errlen) {
        int n = snprintf(r->err, r->errlen, "line %ld: ", r->line);
        va_list ap;
        va_start(ap, fmt);
        if (n >= 0 && (size_t)n < r->errlen)
            vsnprintf(r->err + n, r->errlen - (size_t)n, fmt, ap);
        va_end(ap);
    }
    r->failed = 1;
    return MPB_EPARSE;
}

/* The next line, without its end and surrounding blanks; NULL at the end
 * of the text. */
char *mpb__log_next_line(reader *r)
{
    if (r->p >= r->end)
        return NULL;
    const char *nl = memchr(r->p, '\n', (size_t)(r->end - r->p));
    const char *stop = nl ? nl : r->end;
    size_t n = (size_t)(stop - r->p);
    if (memchr(r->p, '\0', n) != NULL) {
        r->line++;
        mpb__log_fail(r, "a NUL byte: not a benchmark log");
        return NULL;
    }
    if (n + 1 > r->cap) {
        size_t cap = n + 1 > 2 * r->cap ? n + 1 : 2 * r->cap;
        char *b = realloc(r->buf, cap);
        if (b == NULL)
            return NULL;
        r->buf = b;
        r->cap = cap;
    }
    memcpy(r->buf, r->p, n);
    r->buf[n] = '\0';
    r->raw = r->p;
    r->raw_len = n > 0 && r->p[n - 1] == '\r' ? n - 1 : n;
    r->p = nl ? nl + 1 : r->end;
    r->line++;
    char *s = r->buf;
    while (*s && isspace((unsigned char)*s))
        s++;
    char *e = s + strlen(s);
    while (e > s && isspace((unsigned char)e[-1]))
        *--e = '\0';
    return s;
}

char *mpb__log_need_line(reader *r, const char *what)
{
    char *s = mpb__log_next_line(r);
    if (s == NULL && !r->failed) {
        r->line++;
        mpb__log_fail(r, "the log ends where %s was expected", what);
    }
    return s;
}

char *mpb__log_dup(reader *r, const char *s)
{
    char *d = strdup(s);
    if (d == NULL)
        mpb__log_fail(r, "out of memory");
    return d;
}

/* "N words...": the count, with the rest of the line checked to be words. */
int mpb__log_count_line(reader *r, const char *words, long *out)
{
    char *s = mpb__log_need_line(r, words);
    if (s == NULL)
        return -1;
    char *end;
    errno = 0;
    long v = strtol(s, &end, 10);
    while (*end == ' ')
        end++;
    if (end == s || errno || v < 0 || strcmp(end, words) != 0)
        return mpb__log_fail(r, "expected 'N %s', found '%.60s'", words, s);
    if (v > MAX_COUNT)
        return mpb__log_fail(r, "%ld %s is more than a log holds", v, words);
    *out = v;
    return 0;
}

/* "X words": the number in front. */
int mpb__log_number_line(reader *r, const char *words, double *out)
{
    char *s = mpb__log_need_line(r, words);
    if (s == NULL)
        return -1;
    char *end;
    double v = strtod(s, &end);
    while (*end == ' ')
        end++;
    if (end == s || strcmp(end, words) != 0)
        return mpb__log_fail(r, "expected 'X %s', found '%.60s'", words, s);
    if (!(v >= 0 && v <= DBL_MAX))
        return mpb__log_fail(r, "'%.60s': X must be a number no less than 0", s);
    *out = v;
    return 0;
}

/* "<<<|" text "|>>>", each line as it is in the log (blanks and all,
 * only "\r\n" read as "\n"), as OMPL's script keeps it. */
int mpb__log_block(reader *r, char **out)
{
    char *s = mpb__log_need_line(r, "'<<<|'");
    if (s == NULL)
        return -1;
    if (strcmp(s, "<<<|") != 0)
        return mpb__log_fail(r, "expected '<<<|', found '%.60s'", s);
    size_t len = 0, cap = 64;
    char *text = malloc(cap);
    if (text == NULL)
        return mpb__log_fail(r, "out of memory");
    text[0] = '\0';
    for (;;) {
        const char *raw = r->p;
        s = mpb__log_need_line(r, "'|>>>'");
        if (s == NULL) {
            free(text);
            return -1;
        }
        size_t n = (size_t)(r->p - raw);
        if (n > 0 && raw[n - 1] == '\n')
            n--;
        if (n > 0 && raw[n - 1] == '\r')
            n--;
        /* The end is a line that starts with it, as OMPL's own script
         * reads it: an indented one is text (mpb export --ompl-log writes
         * one so, from a setup that holds a log's). */
        if (s == r->buf && strcmp(s, "|>>>") == 0)
            break;
        if (len + n + 2 > cap) {
            cap = 2 * (len + n + 2);
            char *t = realloc(text, cap);
            if (t == NULL) {
                free(text);
                return mpb__log_fail(r, "out of memory");
            }
            text = t;
        }
        memcpy(text + len, raw, n);
        len += n;
        text[len++] = '\n';
        text[len] = '\0';
    }
    *out = text;
    return 0;
}

/* Split s at sep into at most n trimmed fields; the count found. */
int mpb__log_split(char *s, char sep, char **fields, int n)
{
    int k = 0;
    while (*s && k < n) {
        char *next = strchr(s, sep);
        if (next)
            *next = '\0';
        while (*s == ' ')
            s++;
        char *e = s + strlen(s);
        while (e > s && e[-1] == ' ')
            *--e = '\0';
        fields[k++] = s;
        if (!next)
            break;
        s = next + 1;
    }
    return k;
}

/* "WORD rest": rest, when the line starts with WORD and a space. */
const char *mpb__log_after(const char *s, const char *word)
{
    size_t n = strlen(word);
    return strncmp(s, word, n) == 0 && s[n] == ' ' ? s + n + 1 : NULL;
}
