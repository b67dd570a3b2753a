/*
 * yamldoc.c - the daemon's YAML kit (yamldoc.h): a file read as one
 * checked libyaml document, its nodes read, its faults worded with their
 * line and column.
 */
#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "mpbench/mpbench.h"
#include "yamldoc.h"
/*
 * s as text that is safe to print on one line: control bytes, DEL and
 * bytes that are not UTF-8 become \xNN (a file's binary bytes are never
 * echoed to a terminal); well-formed UTF-8 is kept.
 */
static void escape_text(const char *s, char *out, size_t n)
{
    size_t o = 0;
    const unsigned char *p = (const unsigned char *)s;
    while (*p && o + 5 < n) {
        int len = *p < 0x80 ? 1 : (*p & 0xE0) == 0xC0 && *p >= 0xC2 ? 2
                : (*p & 0xF0) == 0xE0 ? 3 : (*p & 0xF8) == 0xF0 && *p <= 0xF4
                ? 4 : 0;
        for (int k = 1; k < len; k++)
            if ((p[k] & 0xC0) != 0x80)
                len = 0;
        if (len == 1 && *p >= 0x20 && *p != 0x7f) {
            out[o++] = (char)*p++;
        } else if (len > 1 && o + (size_t)len < n) {
            memcpy(out + o, p, (size_t)len);
            o += (size_t)len;
            p += len;
        } else {
            o += (size_t)snprintf(out + o, n - o, "\\x%02x", *p++);
        }
    }
    out[o] = '\0';
}

int mpbd_yaml_vfail(mpbd_yaml *Y, const yaml_node_t *n, const char *fmt,
                    va_list ap)
{
    char raw[512], what[2048];
    if (Y->failed)
        return -1;
    vsnprintf(raw, sizeof raw, fmt, ap);
    escape_text(raw, what, sizeof what);
    if (n != NULL)
        snprintf(Y->err, Y->errlen, "%s:%lu:%lu: %s", Y->path,
                 (unsigned long)n->start_mark.line + 1,
                 (unsigned long)n->start_mark.column + 1, what);
    else if (Y->place_path != NULL)
        snprintf(Y->err, Y->errlen, "%s:%d:%d: %s", Y->place_path,
                 Y->place.line, Y->place.column, what);
    else
        snprintf(Y->err, Y->errlen, "%s: %s", Y->path, what);
    Y->failed = 1;
    return -1;
}

int mpbd_yaml_fail(mpbd_yaml *Y, const yaml_node_t *n, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    int rc = mpbd_yaml_vfail(Y, n, fmt, ap);
    va_end(ap);
    return rc;
}

yaml_node_t *mpbd_yaml_node(mpbd_yaml *Y, int id)
{
    return yaml_document_get_node(&Y->doc, id);
}

const char *mpbd_yaml_scalar(const yaml_node_t *n)
{
    return n && n->type == YAML_SCALAR_NODE ? (const char *)n->data.scalar.value
                                            : NULL;
}

/* The value under key in mapping m, or NULL. */
yaml_node_t *mpbd_yaml_get(mpbd_yaml *Y, yaml_node_t *m, const char *key)
{
    if (m == NULL || m->type != YAML_MAPPING_NODE)
        return NULL;
    for (yaml_node_pair_t *p = m->data.mapping.pairs.start;
         p < m->data.mapping.pairs.top; p++) {
        const char *k = mpbd_yaml_scalar(mpbd_yaml_node(Y, p->key));
        if (k && strcmp(k, key) == 0)
            return mpbd_yaml_node(Y, p->value);
    }
    return NULL;
}

/* Reject keys a mapping does not know: a typo must not pass silently. */
int mpbd_yaml_only_keys(mpbd_yaml *Y, yaml_node_t *m, const char *const *known)
{
    for (yaml_node_pair_t *p = m->data.mapping.pairs.start;
         p < m->data.mapping.pairs.top; p++) {
        yaml_node_t *kn = mpbd_yaml_node(Y, p->key);
        const char *k = mpbd_yaml_scalar(kn);
        int ok = 0;
        for (int i = 0; k && known[i]; i++)
            ok |= strcmp(k, known[i]) == 0;
        if (!ok)
            return mpbd_yaml_fail(Y, kn, "unknown key '%s'", k ? k : "?");
    }
    return 0;
}

/* The key node of pair i of mapping m, for sorting keys by name. */
typedef struct keyref {
    const char  *name;
    yaml_node_t *node;
} keyref;

static int keyref_cmp(const void *a, const void *b)
{
    const keyref *x = a, *y = b;
    int c = strcmp(x->name, y->name);
    if (c != 0)
        return c;
    return x->node < y->node ? -1 : x->node > y->node;
}

/* The first key (in file order) that repeats an earlier one in m, or
 * NULL; sorted, so that a mapping of many keys costs n log n. */
static yaml_node_t *repeated_key(mpbd_yaml *Y, yaml_node_t *m, keyref *keys)
{
    size_t n = 0;
    yaml_node_t *first = NULL;
    for (yaml_node_pair_t *p = m->data.mapping.pairs.start;
         p < m->data.mapping.pairs.top; p++) {
        yaml_node_t *k = mpbd_yaml_node(Y, p->key);
        if (mpbd_yaml_scalar(k) != NULL)
            keys[n++] = (keyref){mpbd_yaml_scalar(k), k};
    }
    qsort(keys, n, sizeof *keys, keyref_cmp);
    for (size_t i = 1; i < n; i++)
        if (strcmp(keys[i - 1].name, keys[i].name) == 0 &&
            (first == NULL || keys[i].node->start_mark.index <
                                  first->start_mark.index))
            first = keys[i].node;
    return first;
}

/*
 * libyaml keeps every pair of a mapping, and mpbd_yaml_get() would take
 * the first: refuse a key written twice anywhere, params included, as a typo.
 */
int mpbd_yaml_no_repeated_keys(mpbd_yaml *Y)
{
    size_t most = 0;
    keyref *keys;
    for (yaml_node_t *m = Y->doc.nodes.start; m < Y->doc.nodes.top; m++)
        if (m->type == YAML_MAPPING_NODE) {
            size_t n = (size_t)(m->data.mapping.pairs.top -
                                m->data.mapping.pairs.start);
            most = n > most ? n : most;
        }
    if ((keys = malloc((most + 1) * sizeof *keys)) == NULL)
        return mpbd_yaml_fail(Y, NULL, "out of memory");
    for (yaml_node_t *m = Y->doc.nodes.start; m < Y->doc.nodes.top; m++) {
        yaml_node_t *k;
        if (m->type == YAML_MAPPING_NODE && (k = repeated_key(Y, m, keys))) {
            free(keys);
            return mpbd_yaml_fail(Y, k, "key '%s' appears twice",
                                  mpbd_yaml_scalar(k));
        }
    }
    free(keys);
    return 0;
}

yaml_node_t *mpbd_yaml_need(mpbd_yaml *Y, yaml_node_t *m, const char *key,
                            yaml_node_type_t type, const char *what)
{
    yaml_node_t *n = mpbd_yaml_get(Y, m, key);
    if (n == NULL) {
        mpbd_yaml_fail(Y, m, "missing '%s' (%s)", key, what);
        return NULL;
    }
    if (n->type != type) {
        mpbd_yaml_fail(Y, n, "'%s' must be %s", key, what);
        return NULL;
    }
    return n;
}

char *mpbd_yaml_dup(mpbd_yaml *Y, const yaml_node_t *n, const char *s)
{
    char *d = strdup(s);
    if (d == NULL)
        mpbd_yaml_fail(Y, n, "out of memory");
    return d;
}

char *mpbd_yaml_need_string(mpbd_yaml *Y, yaml_node_t *m, const char *key)
{
    yaml_node_t *n = mpbd_yaml_need(Y, m, key, YAML_SCALAR_NODE, "a string");
    if (n == NULL)
        return NULL;
    if (mpbd_yaml_scalar(n)[0] == '\0') {
        mpbd_yaml_fail(Y, n, "'%s' must not be empty", key);
        return NULL;
    }
    return mpbd_yaml_dup(Y, n, mpbd_yaml_scalar(n));
}

/*
 * Whether s is a number as people write them in decimal: a sign, digits
 * with at most one point, an exponent. strtod() alone would also take hex
 * ("0x10"), "inf", "nan" and leading blanks.
 */
int mpbd_yaml_is_decimal(const char *s, int whole)
{
    int digits = 0;
    if (*s == '-' || *s == '+')
        s++;
    for (; isdigit((unsigned char)*s); s++)
        digits++;
    if (!whole && *s == '.')
        for (s++; isdigit((unsigned char)*s); s++)
            digits++;
    if (digits == 0)
        return 0;
    if (!whole && (*s == 'e' || *s == 'E')) {
        s++;
        if (*s == '-' || *s == '+')
            s++;
        if (!isdigit((unsigned char)*s))
            return 0;
        while (isdigit((unsigned char)*s))
            s++;
    }
    return *s == '\0';
}

int mpbd_parse_decimal(const char *s, double *out)
{
    /* Not errno: strtod() sets ERANGE for 1e-310 too, which is a number. */
    *out = mpbd_yaml_is_decimal(s, 0) ? strtod(s, NULL) : NAN;
    return isfinite(*out);
}

int mpbd_yaml_double(mpbd_yaml *Y, yaml_node_t *n, const char *what,
                     double *out)
{
    const char *s = mpbd_yaml_scalar(n);
    if (s == NULL)
        return mpbd_yaml_fail(Y, n, "%s must be a number", what);
    if (!mpbd_parse_decimal(s, out))
        return mpbd_yaml_fail(Y, n, "%s must be a number, not '%s'", what, s);
    return 0;
}

/* A whole number in lo..hi: 0 if *out was set, else -1 with the error. */
int mpbd_yaml_int_in(mpbd_yaml *Y, yaml_node_t *n, const char *what,
                     long lo, long hi, int *out)
{
    const char *s = mpbd_yaml_scalar(n);
    long v;
    if (s != NULL) {
        errno = 0;
        v = strtol(s, NULL, 10);
        if (mpbd_yaml_is_decimal(s, 1) && errno == 0 && v >= lo && v <= hi) {
            *out = (int)v;
            return 0;
        }
    }
    if (lo == 1)
        return mpbd_yaml_fail(Y, n, "%s must be a positive integer%s%s%s",
                              what, s ? ", not '" : "", s ? s : "",
                              s ? "'" : "");
    return mpbd_yaml_fail(Y, n, "%s must be a whole number from %ld to "
                          "%ld%s%s%s", what, lo, hi, s ? ", not '" : "",
                          s ? s : "", s ? "'" : "");
}

int mpbd_yaml_count(const yaml_node_t *n)
{
    return n && n->type == YAML_SEQUENCE_NODE
               ? (int)(n->data.sequence.items.top -
                       n->data.sequence.items.start)
               : 0;
}

yaml_node_t *mpbd_yaml_item(mpbd_yaml *Y, yaml_node_t *seq, int i)
{
    return mpbd_yaml_node(Y, seq->data.sequence.items.start[i]);
}

mpbd_mark mpbd_yaml_mark(const yaml_node_t *n)
{
    return (mpbd_mark){(int)n->start_mark.line + 1,
                       (int)n->start_mark.column + 1};
}

/* The line and column (from 1; columns in characters, as libyaml counts
 * them) of byte offset at of text. */
static mpbd_mark place_of(const char *text, size_t at)
{
    mpbd_mark m = {1, 1};
    for (size_t i = 0; i < at; i++) {
        unsigned char c = (unsigned char)text[i];
        if (c == '\n') {
            m.line++;
            m.column = 1;
        } else if ((c & 0xC0) != 0x80) {
            m.column++;
        }
    }
    return m;
}

int mpbd_yaml_fail_parser(mpbd_yaml *Y, const yaml_parser_t *parser)
{
    mpbd_mark at = {(int)parser->problem_mark.line + 1,
                    (int)parser->problem_mark.column + 1};
    /* A reader error (a byte that is not UTF-8, a control character)
     * comes with an offset into the input, not a place. */
    if (parser->error == YAML_READER_ERROR && Y->text != NULL &&
        parser->problem_offset <= Y->len)
        at = place_of(Y->text, parser->problem_offset);
    snprintf(Y->err, Y->errlen, "%s:%d:%d: YAML: %s", Y->path, at.line,
             at.column, parser->problem ? parser->problem : "syntax error");
    Y->failed = 1;
    return -1;
}

/* The loader reads one document: a second one (after `---`) would be
 * ignored without a word, so it is an error, as is bad YAML in it. */
static int no_second_document(mpbd_yaml *Y, yaml_parser_t *parser,
                              const char *holds)
{
    yaml_document_t next;
    if (!yaml_parser_load(parser, &next))
        return mpbd_yaml_fail_parser(Y, parser);
    int more = yaml_document_get_root_node(&next) != NULL;
    yaml_mark_t at = next.start_mark;
    yaml_document_delete(&next);
    if (!more)
        return 0;
    snprintf(Y->err, Y->errlen, "%s:%lu:%lu: a second YAML document (%s)",
             Y->path, (unsigned long)at.line + 1,
             (unsigned long)at.column + 1, holds);
    Y->failed = 1;
    return -1;
}

/* A pass over libyaml's events before it builds the document, stopping
 * at the first collection nested deeper than MPBD_YAML_DEPTH_MAX. */
static int not_too_deep(mpbd_yaml *Y, const char *text, size_t len)
{
    yaml_parser_t parser;
    yaml_event_t ev;
    int depth = 0, rc = 0;
    yaml_parser_initialize(&parser);
    yaml_parser_set_input_string(&parser, (const unsigned char *)text, len);
    for (;;) {
        if (!yaml_parser_parse(&parser, &ev)) {
            rc = mpbd_yaml_fail_parser(Y, &parser);
            break;
        }
        yaml_event_type_t type = ev.type;
        yaml_mark_t at = ev.start_mark;
        yaml_event_delete(&ev);
        if (type == YAML_STREAM_END_EVENT)
            break;
        if (type == YAML_SEQUENCE_END_EVENT || type == YAML_MAPPING_END_EVENT)
            depth--;
        else if ((type == YAML_SEQUENCE_START_EVENT ||
                  type == YAML_MAPPING_START_EVENT) &&
                 ++depth > MPBD_YAML_DEPTH_MAX) {
            snprintf(Y->err, Y->errlen, "%s:%lu:%lu: nested too deeply (more "
                     "than %d levels)", Y->path, (unsigned long)at.line + 1,
                     (unsigned long)at.column + 1, MPBD_YAML_DEPTH_MAX);
            Y->failed = 1;
            rc = -1;
            break;
        }
    }
    yaml_parser_delete(&parser);
    return rc;
}

/* mpbd_yaml_load() once the text is known to hold no NUL. */
static int load_checked(mpbd_yaml *Y, yaml_parser_t *parser, const char *holds)
{
    if (not_too_deep(Y, Y->text, Y->len) != 0)
        return -1;
    yaml_parser_initialize(parser);
    yaml_parser_set_input_string(parser, (const unsigned char *)Y->text,
                                 Y->len);
    if (!yaml_parser_load(parser, &Y->doc)) {
        mpbd_yaml_fail_parser(Y, parser);
        yaml_parser_delete(parser);
        return -1;
    }
    int rc = no_second_document(Y, parser, holds);
    yaml_parser_delete(parser);
    if (rc != 0)
        yaml_document_delete(&Y->doc);
    return rc;
}

int mpbd_yaml_load_file(mpbd_yaml *Y, char **text, const char *holds)
{
    size_t len;
    if ((*text = mpb_read_file(Y->path, 0, &len)) == NULL) {
        snprintf(Y->err, Y->errlen, "%s: cannot read: %s", Y->path,
                 strerror(errno));
        return -1;
    }
    if (mpbd_yaml_load(Y, *text, len, holds) != 0) {
        free(*text);
        *text = NULL;
        return -1;
    }
    return 0;
}

int mpbd_yaml_load(mpbd_yaml *Y, const char *text, size_t len,
                   const char *holds)
{
    yaml_parser_t parser;
    size_t nul = strlen(text);
    /* The parser would stop at a NUL: the rest would vanish unread. */
    if (nul != len) {
        mpbd_mark at = place_of(text, nul);
        snprintf(Y->err, Y->errlen, "%s:%d:%d: a NUL byte: not a text file",
                 Y->path, at.line, at.column);
        Y->failed = 1;
        return -1;
    }
    Y->text = text;
    Y->len = len;
    int rc = load_checked(Y, &parser, holds);
    Y->text = NULL;
    return rc;
}

