/*
 * cloud_internal.h - what the PLY and PCD header readers (cloud_ply.c,
 * cloud_pcd.c) tell the body reader (cloud.c): where the points are and
 * how each is laid out.
 */
#ifndef MPB_CLOUD_INTERNAL_H
#define MPB_CLOUD_INTERNAL_H

#include <stddef.h>

enum { MPB__CT_I8, MPB__CT_U8, MPB__CT_I16, MPB__CT_U16, MPB__CT_I32,
       MPB__CT_U32, MPB__CT_F32, MPB__CT_F64 };

enum { MPB__CLOUD_ASCII, MPB__CLOUD_LE, MPB__CLOUD_BE };

typedef struct mpb__cloud_layout {
    int    format;      /* MPB__CLOUD_* */
    long   n;           /* points */
    const char *unit;   /* "vertex" or "point", for messages */
    int    nvalues;     /* ASCII: numbers a point */
    size_t record;      /* binary: bytes a point */
    int    type[3];     /* x y z: MPB__CT_* */
    size_t off[3];      /* binary: byte offsets in a record */
    int    tok[3];      /* ASCII: their places among the numbers */
    size_t body;        /* where the data starts (after the header) */
    int    body_line;   /* its line */
    long   skip_lines;  /* ASCII: lines of elements before the points */
    size_t skip_bytes;  /* binary: bytes of elements before the points */
} mpb__cloud_layout;

/* The size of a type (1 to 8). */
size_t mpb__cloud_type_size(int type);

/* Split the line [b, e) at blanks into words (core/words.h): the first
 * rows of them (at most MPB__CLOUD_WORDS_MAX) into w, a row of cols bytes
 * each, cut to cols - 1 characters. Returns how many words the line has
 * (more than rows when some did not fit). */
#define MPB__CLOUD_WORDS_MAX 65     /* a PCD header's 64 fields and its key */
int mpb__cloud_words(const char *b, const char *e, char *w, int rows,
                     size_t cols);

/* A header's count: a whole number >= 0, capped at MPB_CLOUD_MAX_POINTS
 * + 1 so the caller's limit check says "too many". Returns 1, or 0
 * when w is no such number. */
int mpb__cloud_count(const char *w, long *v);

/* Read a header (bytes, len) into *L; MPB_OK, or MPB_EPARSE /
 * MPB_EUNSUPPORTED with one line in why ("line 4: ..."). */
int mpb__ply_header(const char *bytes, size_t len, mpb__cloud_layout *L,
                    char *why, size_t whylen);
int mpb__pcd_header(const char *bytes, size_t len, mpb__cloud_layout *L,
                    char *why, size_t whylen);

#endif /* MPB_CLOUD_INTERNAL_H */
