/*
 * yamldoc.h - the daemon's YAML kit: a file read as one libyaml document
 * (through the document API, so that every node keeps its line and
 * column), checked as a whole (nesting depth, one document, keys written
 * once), and helpers that read its nodes and word a fault as one line,
 * "<file>:<line>:<column>: <what>". Shared by the experiment files
 * (experiment*.c) and the MoveIt files (moveit.c).
 */
#ifndef MPBD_YAMLDOC_H
#define MPBD_YAMLDOC_H

#include <stdarg.h>
#include <stddef.h>

#include <yaml.h>

/* A place in a file, counting from 1. */
typedef struct mpbd_mark {
    int line, column;
} mpbd_mark;

/* One file being read: its document, and where its first fault goes. */
typedef struct mpbd_yaml {
    yaml_document_t doc;
    const char *path;
    char       *err;          /* the caller's buffer for the fault */
    size_t      errlen;
    int         failed;       /* a fault is in err; later ones are dropped */
    /* Where a fault with no node of this file goes (a place in another
     * file, e.g. a MoveIt file read for an experiment); or NULL. */
    const char *place_path;
    mpbd_mark   place;
    const char *text;         /* while mpbd_yaml_load() reads: the text */
    size_t      len;
} mpbd_yaml;

/* Far deeper than any file read needs (an experiment six levels, a
 * MoveIt message eight); libyaml spends time in proportion to the depth
 * on every token, so a hundred thousand '[' took minutes. */
#define MPBD_YAML_DEPTH_MAX 100

/*
 * Parse text (len bytes, NUL-terminated) of the file Y->path into Y->doc:
 * a NUL byte, bytes that are not UTF-8 (each at its line and column),
 * nesting deeper than MPBD_YAML_DEPTH_MAX and a second document are
 * faults ("holds" words what the file holds, for the message: "an
 * experiment file holds one"). 0 with a document to free with
 * yaml_document_delete(&Y->doc); else -1 with the fault in Y->err and
 * nothing to free.
 */
int mpbd_yaml_load(mpbd_yaml *Y, const char *text, size_t len,
                   const char *holds);

/* Read the file Y->path and mpbd_yaml_load() it: 0 with the document and
 * its text in *text (free() it after yaml_document_delete()); else -1
 * with the fault in Y->err ("cannot read" and why, or the parser's). */
int mpbd_yaml_load_file(mpbd_yaml *Y, char **text, const char *holds);

/*
 * Record a fault, "<path>:<line>:<column>: <what>" at node n (or at
 * Y->place_path's place, or at the file, when n is NULL), unless one is
 * recorded already; bytes that are not printable UTF-8 are written as
 * \xNN. Always -1.
 */
int mpbd_yaml_fail(mpbd_yaml *Y, const yaml_node_t *n, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;
int mpbd_yaml_vfail(mpbd_yaml *Y, const yaml_node_t *n, const char *fmt,
                    va_list ap)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 0)))
#endif
    ;
/* libyaml's own complaint, at the place it names. -1. */
int mpbd_yaml_fail_parser(mpbd_yaml *Y, const yaml_parser_t *parser);

/* Node id of the document; a scalar's text (NULL for other nodes); the
 * value under key in mapping m (NULL if none, or m is no mapping); the
 * items of a sequence (0 for anything else) and item i; n's place. */
yaml_node_t *mpbd_yaml_node(mpbd_yaml *Y, int id);
const char  *mpbd_yaml_scalar(const yaml_node_t *n);
yaml_node_t *mpbd_yaml_get(mpbd_yaml *Y, yaml_node_t *m, const char *key);
int          mpbd_yaml_count(const yaml_node_t *n);
yaml_node_t *mpbd_yaml_item(mpbd_yaml *Y, yaml_node_t *seq, int i);
mpbd_mark    mpbd_yaml_mark(const yaml_node_t *n);

/* A fault at the first key of mapping m not in the NULL-terminated list
 * known (a typo must not pass silently): -1; else 0. */
int mpbd_yaml_only_keys(mpbd_yaml *Y, yaml_node_t *m,
                        const char *const *known);
/* A fault at the first key written twice in any mapping of the document
 * (get() would take the first): -1; else 0. n log n. */
int mpbd_yaml_no_repeated_keys(mpbd_yaml *Y);
/* The value under key of the given type; else NULL with a fault saying
 * it must be `what`. */
yaml_node_t *mpbd_yaml_need(mpbd_yaml *Y, yaml_node_t *m, const char *key,
                            yaml_node_type_t type, const char *what);
/* A copy of s (to free), or NULL with a fault at n. */
char *mpbd_yaml_dup(mpbd_yaml *Y, const yaml_node_t *n, const char *s);
/* A copy of the non-empty string under key, or NULL with a fault. */
char *mpbd_yaml_need_string(mpbd_yaml *Y, yaml_node_t *m, const char *key);

/*
 * Whether s is a number as people write them in decimal: a sign, digits
 * (whole: nothing else; else with at most one point and an exponent).
 * strtod() alone would also take hex ("0x10"), "inf", "nan" and blanks.
 */
int mpbd_yaml_is_decimal(const char *s, int whole);
/*
 * Whether s is a finite decimal number (no hex, inf or nan), into *out:
 * 1 if so, else 0.
 */
int mpbd_parse_decimal(const char *s, double *out);
/* Node n as a decimal number into *out, or a fault naming `what`: 0/-1. */
int mpbd_yaml_double(mpbd_yaml *Y, yaml_node_t *n, const char *what,
                     double *out);
/* Node n as a whole number in lo..hi into *out, or a fault: 0/-1. */
int mpbd_yaml_int_in(mpbd_yaml *Y, yaml_node_t *n, const char *what,
                     long lo, long hi, int *out);

#endif
