/*
 * cloud_pcd.c - a PCD file's header (PCL's format, v0.5 to v0.7): its
 * fields with their sizes, types and counts, the point count, the data
 * format; the places of x, y and z.
 */
#include "mpbench/mpbench.h"
#include "mpbench/cloud.h"
#include "model/cloud_internal.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MAX_FIELDS 64

int mpb__pcd_header(const char *bytes, size_t len, mpb__cloud_layout *L,
                    char *why, size_t whylen)
{
    memset(L, 0, sizeof *L);
    L->unit = "point";
    char w[MAX_FIELDS + 1][32];
    char names[MAX_FIELDS][32];
    long size[MAX_FIELDS], count[MAX_FIELDS];
    char type[MAX_FIELDS];
    int nf = -1, have_size = 0, have_type = 0;
    long points = -1, width = -1, height = 1;
    for (int i = 0; i < MAX_FIELDS; i++)
        count[i] = 1;
    const char *p = bytes, *end = bytes + len;
    int line = 0;
    for (;;) {
        line++;
        const char *e = p < end ? memchr(p, '\n', (size_t)(end - p)) : NULL;
        if (!e) {
            snprintf(why, whylen, "line %d: the header ends before its DATA line", line);
            return MPB_EPARSE;
        }
        int n = mpb__cloud_words(p, e, &w[0][0], MAX_FIELDS + 1, sizeof w[0]);
        p = e + 1;
        if (n == 0 || w[0][0] == '#')
            continue;
        if (n - 1 > MAX_FIELDS) {
            snprintf(why, whylen, "line %d: more than %d fields", line, MAX_FIELDS);
            return MPB_EUNSUPPORTED;
        }
        const char *k = w[0];
        if (strcmp(k, "VERSION") == 0 || strcmp(k, "VIEWPOINT") == 0)
            continue;
        if (strcmp(k, "FIELDS") == 0 || strcmp(k, "COLUMNS") == 0) {
            nf = n - 1;
            for (int i = 0; i < nf; i++)
                strcpy(names[i], w[i + 1]);
        } else if (strcmp(k, "SIZE") == 0 || strcmp(k, "TYPE") == 0 ||
                   strcmp(k, "COUNT") == 0) {
            if (nf < 0 || n - 1 != nf) {
                snprintf(why, whylen, "line %d: %s needs one value per field (%d)",
                         line, k, nf < 0 ? 0 : nf);
                return MPB_EPARSE;
            }
            for (int i = 0; i < nf; i++) {
                if (k[0] == 'T') {
                    if (strlen(w[i + 1]) != 1 || !strchr("IUF", w[i + 1][0])) {
                        snprintf(why, whylen, "line %d: TYPE '%s' is none of I U F",
                                 line, w[i + 1]);
                        return MPB_EPARSE;
                    }
                    type[i] = w[i + 1][0];
                } else {
                    long v;
                    if (!mpb__cloud_count(w[i + 1], &v) || v < 1 || v > 1000) {
                        snprintf(why, whylen, "line %d: %s '%s' is not a count", line,
                                 k, w[i + 1]);
                        return MPB_EPARSE;
                    }
                    (k[0] == 'S' ? size : count)[i] = v;
                }
            }
            have_size |= k[0] == 'S';
            have_type |= k[0] == 'T';
        } else if (strcmp(k, "WIDTH") == 0 || strcmp(k, "HEIGHT") == 0 ||
                   strcmp(k, "POINTS") == 0) {
            long v;
            if (n != 2 || !mpb__cloud_count(w[1], &v)) {
                snprintf(why, whylen, "line %d: %s needs a count", line, k);
                return MPB_EPARSE;
            }
            *(k[0] == 'W' ? &width : k[0] == 'H' ? &height : &points) = v;
        } else if (strcmp(k, "DATA") == 0) {
            if (n != 2) {
                snprintf(why, whylen, "line %d: DATA needs ascii or binary", line);
                return MPB_EPARSE;
            }
            if (strcmp(w[1], "ascii") == 0)
                L->format = MPB__CLOUD_ASCII;
            else if (strcmp(w[1], "binary") == 0)
                L->format = MPB__CLOUD_LE;
            else if (strcmp(w[1], "binary_compressed") == 0) {
                snprintf(why, whylen, "line %d: DATA binary_compressed is not "
                         "supported (save it as binary or ascii)", line);
                return MPB_EUNSUPPORTED;
            } else {
                snprintf(why, whylen, "line %d: DATA '%s' is none of ascii, binary",
                         line, w[1]);
                return MPB_EPARSE;
            }
            break;
        } else {
            snprintf(why, whylen, "line %d: unknown header line '%s'", line, k);
            return MPB_EPARSE;
        }
    }
    if (nf < 0 || !have_size || !have_type) {
        snprintf(why, whylen, "line %d: the header needs FIELDS, SIZE and TYPE", line);
        return MPB_EPARSE;
    }
    if (points < 0) {
        if (width < 0) {
            snprintf(why, whylen, "line %d: the header gives neither POINTS nor WIDTH",
                     line);
            return MPB_EPARSE;
        }
        points = width * height > MPB_CLOUD_MAX_POINTS ? MPB_CLOUD_MAX_POINTS + 1
                                                       : width * height;
    }
    int have[3] = {0, 0, 0};
    size_t off = 0;
    int tok = 0;
    for (int i = 0; i < nf; i++) {
        int k = strcmp(names[i], "x") == 0 ? 0 : strcmp(names[i], "y") == 0 ? 1
                : strcmp(names[i], "z") == 0 ? 2 : -1;
        if (k >= 0) {
            int t = -1;
            if (type[i] == 'F')
                t = size[i] == 4 ? MPB__CT_F32 : size[i] == 8 ? MPB__CT_F64 : -1;
            else if (size[i] == 1 || size[i] == 2 || size[i] == 4)
                t = (type[i] == 'I' ? MPB__CT_I8 : MPB__CT_U8) +
                    2 * (size[i] == 2 ? 1 : size[i] == 4 ? 2 : 0);
            if (t < 0 || count[i] != 1) {
                snprintf(why, whylen, "line %d: field %s of type %c, size %ld, count "
                         "%ld is not supported", line, names[i], type[i], size[i],
                         count[i]);
                return MPB_EUNSUPPORTED;
            }
            have[k] = 1;
            L->type[k] = t;
            L->off[k] = off;
            L->tok[k] = tok;
        }
        off += (size_t)(size[i] * count[i]);
        tok += (int)count[i];
    }
    if (!have[0] || !have[1] || !have[2]) {
        snprintf(why, whylen, "line %d: FIELDS lacks x, y or z", line);
        return MPB_EPARSE;
    }
    L->n = points;
    L->record = off;
    L->nvalues = tok;
    L->body = (size_t)(p - bytes);
    L->body_line = line + 1;
    return MPB_OK;
}
