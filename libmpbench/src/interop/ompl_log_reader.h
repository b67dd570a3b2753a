/*
 * ompl_log_reader.h - what the parts of the benchmark log reader share
 * (ompl_log.c, ompl_log_reader.c, ompl_log_values.c); not part of the API.
 * A cursor walks the text line by line; every line the grammar expects is
 * read by one function that says, on failure, which line and what it
 * wanted.
 */
#ifndef MPB_OMPL_LOG_READER_H
#define MPB_OMPL_LOG_READER_H

#include <stddef.h>

#include "mpbench/mpbench.h"

/* Counts above these are taken for damage, not data. */
#define MAX_COUNT 100000000L
#define MAX_PROPERTIES 10000

typedef struct reader {
    const char *p, *end;
    long line;                  /* of the line last read */
    char *buf;                  /* that line, NUL-terminated, trimmed */
    size_t cap;
    const char *raw;            /* that line as written, without its end */
    size_t raw_len;
    char *err;
    size_t errlen;
    int failed;
    struct log_enum {           /* the log's enum types */
        char *name;
        long count;             /* of its values */
    } *enums;
    long num_enums;
    struct mpb__log_reals *reals;   /* REAL texts for SQLite to read */
} reader;

/* What a run's value may be, by its property's type. */
enum value_kind { V_REAL, V_INTEGER, V_BOOLEAN, V_ENUM, V_TIME };
extern const char *const mpb__log_kind_names[V_TIME + 1];

/* ---- the cursor (ompl_log_reader.c) ---------------------------------------- */

/* Record "line N: ..." in r's error (the first failure only); MPB_EPARSE. */
int mpb__log_fail(reader *r, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;

/* The next line, without its end and surrounding blanks; NULL at the end
 * of the text. */
char *mpb__log_next_line(reader *r);

/* The next line; at the end, a failure saying what was expected. */
char *mpb__log_need_line(reader *r, const char *what);

/* s copied; NULL (and a failure) when out of memory. */
char *mpb__log_dup(reader *r, const char *s);

/* "N words...": the count, with the rest of the line checked to be words. */
int mpb__log_count_line(reader *r, const char *words, long *out);

/* "X words": the number in front. */
int mpb__log_number_line(reader *r, const char *words, double *out);

/* "<<<|" text "|>>>", each line as it is in the log, into *out (malloc). */
int mpb__log_block(reader *r, char **out);

/* Split s at sep into at most n trimmed fields; the count found. */
int mpb__log_split(char *s, char sep, char **fields, int n);

/* "WORD rest": rest, when the line starts with WORD and a space. */
const char *mpb__log_after(const char *s, const char *word);

/* ---- the values (ompl_log_values.c) ---------------------------------------- */

/* A value of a run line, NaN for "", nan, inf. */
double mpb__log_value_of(char *s);

/* 1 when [s, e) is a value of that kind as OMPL writes it (limit: an
 * ENUM's count of values, or -1). */
int mpb__log_value_ok(const char *s, char *e, int kind, long limit);

/* A run line's values, "v1; v2; ...; " (trimmed), into out[0..n); the
 * count of fields found (see ompl_log_values.c). */
int mpb__log_run_values(reader *r, mpb_ompl_planner *pl, long run, char *s,
                        double *out, int n, int *extra_empty,
                        const unsigned char *kinds, const long *limits,
                        int *bad, char **bad_text);

/*
 * A REAL's text, [s, s + n) of the log's own text, whose value *dst is to
 * be the double SQLite makes of it, as OMPL's script stores it (it binds
 * the text; a REAL column's affinity reads it). *dst holds strtod's until
 * mpb__log_reals_flush(), which the caller calls before dst may move and
 * before the text goes. 0, or -1 after a failure.
 */
int mpb__log_real_text(reader *r, double *dst, const char *s, size_t n);
int mpb__log_reals_flush(reader *r);
void mpb__log_reals_free(reader *r);

/* Each of the n properties' kind of value and, for an ENUM the log
 * declares, its count of values (else -1). */
void mpb__log_kinds_of(const reader *r, const mpb_ompl_property *p, long n,
                       unsigned char *kinds, long *limits);

/* The error for text in where, which value_ok() refused for property p. */
int mpb__log_not_a_value(reader *r, const char *where, const char *text,
                         const mpb_ompl_property *p, int kind, long limit);

#endif /* MPB_OMPL_LOG_READER_H */
