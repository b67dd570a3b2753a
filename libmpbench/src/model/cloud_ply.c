/*
 * cloud_ply.c - a PLY file's header: its format, its "vertex" element's
 * count and the places of x, y and z, the elements before it to skip.
 */
#include "mpbench/mpbench.h"
#include "mpbench/cloud.h"
#include "model/cloud_internal.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MAX_WORDS 8

static int ply_type(const char *w)
{
    static const struct { const char *a, *b; int t; } T[] = {
        {"char", "int8", MPB__CT_I8},     {"uchar", "uint8", MPB__CT_U8},
        {"short", "int16", MPB__CT_I16},  {"ushort", "uint16", MPB__CT_U16},
        {"int", "int32", MPB__CT_I32},    {"uint", "uint32", MPB__CT_U32},
        {"float", "float32", MPB__CT_F32}, {"double", "float64", MPB__CT_F64}};
    for (size_t i = 0; i < sizeof T / sizeof T[0]; i++)
        if (strcmp(w, T[i].a) == 0 || strcmp(w, T[i].b) == 0)
            return T[i].t;
    return -1;
}

int mpb__ply_header(const char *bytes, size_t len, mpb__cloud_layout *L,
                    char *why, size_t whylen)
{
    memset(L, 0, sizeof *L);
    L->unit = "vertex";
    const char *p = bytes, *end = bytes + len;
    int line = 0, format = -1, in_vertex = 0, seen_vertex = 0, after = 0;
    int have[3] = {0, 0, 0};
    long count = 0;
    size_t record = 0;          /* of the element being read */
    int nprops = 0, has_list = 0;
    char w[MAX_WORDS][64];
    for (;;) {
        line++;
        const char *e = p < end ? memchr(p, '\n', (size_t)(end - p)) : NULL;
        if (!e) {
            snprintf(why, whylen, "line %d: the header ends before 'end_header'", line);
            return MPB_EPARSE;
        }
        int n = mpb__cloud_words(p, e, &w[0][0], MAX_WORDS, sizeof w[0]);
        p = e + 1;
        if (line == 1) {
            if (n != 1 || strcmp(w[0], "ply") != 0) {
                snprintf(why, whylen, "line 1: not a PLY file (expected 'ply')");
                return MPB_EPARSE;
            }
            continue;
        }
        if (n == 0 || strcmp(w[0], "comment") == 0 || strcmp(w[0], "obj_info") == 0)
            continue;
        /* the element before this line is complete: what to skip */
        if (strcmp(w[0], "element") == 0 || strcmp(w[0], "end_header") == 0) {
            if (in_vertex) {
                L->n = count;
                L->record = record;
                L->nvalues = nprops;
                seen_vertex = 1;
                in_vertex = 0;
                after = 1;
            } else if (!after && (count > 0 || record > 0)) {
                if (has_list) {
                    snprintf(why, whylen, "line %d: an element with list "
                             "properties before 'vertex' is not supported", line);
                    return MPB_EUNSUPPORTED;
                }
                L->skip_lines += count;
                if (record > 0 && (size_t)count > (size_t)-1 / record / 2) {
                    snprintf(why, whylen, "line %d: an element before 'vertex' "
                             "is larger than any file", line);
                    return MPB_EPARSE;
                }
                L->skip_bytes += (size_t)count * record;
            }
            if (strcmp(w[0], "end_header") == 0)
                break;
            if (n != 3 || !mpb__cloud_count(w[2], &count)) {
                snprintf(why, whylen, "line %d: element needs <name> <count>", line);
                return MPB_EPARSE;
            }
            record = 0;
            nprops = 0;
            has_list = 0;
            if (strcmp(w[1], "vertex") == 0) {
                if (seen_vertex) {
                    snprintf(why, whylen, "line %d: a second 'vertex' element", line);
                    return MPB_EPARSE;
                }
                in_vertex = 1;
            }
            continue;
        }
        if (strcmp(w[0], "format") == 0) {
            if (n != 3 || strcmp(w[2], "1.0") != 0) {
                snprintf(why, whylen, "line %d: format needs <ascii|binary_little_endian|"
                         "binary_big_endian> 1.0", line);
                return MPB_EPARSE;
            }
            if (strcmp(w[1], "ascii") == 0)
                format = MPB__CLOUD_ASCII;
            else if (strcmp(w[1], "binary_little_endian") == 0)
                format = MPB__CLOUD_LE;
            else if (strcmp(w[1], "binary_big_endian") == 0)
                format = MPB__CLOUD_BE;
            else {
                snprintf(why, whylen, "line %d: unknown format '%s'", line, w[1]);
                return MPB_EPARSE;
            }
            continue;
        }
        if (strcmp(w[0], "property") == 0) {
            if (n >= 2 && strcmp(w[1], "list") == 0) {
                if (n != 5 || ply_type(w[2]) < 0 || ply_type(w[3]) < 0) {
                    snprintf(why, whylen, "line %d: property list needs <count type> "
                             "<item type> <name>", line);
                    return MPB_EPARSE;
                }
                if (in_vertex) {
                    snprintf(why, whylen, "line %d: a list property of 'vertex' is "
                             "not supported", line);
                    return MPB_EUNSUPPORTED;
                }
                has_list = 1;
                continue;
            }
            int t = n == 3 ? ply_type(w[1]) : -1;
            if (t < 0) {
                snprintf(why, whylen, "line %d: property needs <type> <name> (types "
                         "char uchar short ushort int uint float double)", line);
                return MPB_EPARSE;
            }
            if (in_vertex) {
                int k = strcmp(w[2], "x") == 0 ? 0 : strcmp(w[2], "y") == 0 ? 1
                        : strcmp(w[2], "z") == 0 ? 2 : -1;
                if (k >= 0) {
                    have[k] = 1;
                    L->type[k] = t;
                    L->off[k] = record;
                    L->tok[k] = nprops;
                }
            }
            record += mpb__cloud_type_size(t);
            nprops++;
            continue;
        }
        snprintf(why, whylen, "line %d: unknown header line '%s'", line, w[0]);
        return MPB_EPARSE;
    }
    if (format < 0) {
        snprintf(why, whylen, "line %d: the header has no 'format' line", line);
        return MPB_EPARSE;
    }
    if (!seen_vertex || !have[0] || !have[1] || !have[2]) {
        snprintf(why, whylen, "line %d: no 'vertex' element with x, y and z", line);
        return MPB_EPARSE;
    }
    L->format = format;
    L->body = (size_t)(p - bytes);
    L->body_line = line + 1;
    return MPB_OK;
}
