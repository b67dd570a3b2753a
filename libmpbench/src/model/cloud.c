/*
 * cloud.c - a point cloud's points (PLY or PCD, cloud_ply.c and
 * cloud_pcd.c read the headers), checked one by one, into an octree or
 * an array.
 */
#include "mpbench/mpbench.h"
#include "mpbench/cloud.h"
#include "core/errbuf.h"
#include "core/number.h"
#include "core/readfile.h"
#include "core/words.h"
#include "model/cloud_internal.h"

#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

size_t mpb__cloud_type_size(int type)
{
    static const size_t S[] = {1, 1, 2, 2, 4, 4, 4, 8};
    return type >= 0 && type <= MPB__CT_F64 ? S[type] : 0;
}

int mpb__cloud_words(const char *b, const char *e, char *w, int rows,
                     size_t cols)
{
    mpb__word at[MPB__CLOUD_WORDS_MAX];
    if (rows > MPB__CLOUD_WORDS_MAX)
        rows = MPB__CLOUD_WORDS_MAX;
    int n = mpb__split_words(b, e, at, rows);
    for (int i = 0; i < n && i < rows; i++) {
        size_t k = (size_t)at[i].len < cols - 1 ? (size_t)at[i].len : cols - 1;
        memcpy(w + (size_t)i * cols, at[i].p, k);
        w[(size_t)i * cols + k] = '\0';
    }
    return n;
}

int mpb__cloud_count(const char *w, long *v)
{
    char *e;
    errno = 0;
    long long x = strtoll(w, &e, 10);
    if (e == w || *e || errno || x < 0)
        return 0;
    *v = x > MPB_CLOUD_MAX_POINTS ? MPB_CLOUD_MAX_POINTS + 1 : (long)x;
    return 1;
}

static double value_at(const unsigned char *p, int type, int big)
{
    unsigned char b[8];
    size_t n = mpb__cloud_type_size(type);
    for (size_t i = 0; i < n; i++)
        b[i] = big ? p[n - 1 - i] : p[i];
    switch (type) {
    case MPB__CT_I8:  return (double)(int8_t)b[0];
    case MPB__CT_U8:  return (double)b[0];
    case MPB__CT_I16: { int16_t v; memcpy(&v, b, 2); return v; }
    case MPB__CT_U16: { uint16_t v; memcpy(&v, b, 2); return v; }
    case MPB__CT_I32: { int32_t v; memcpy(&v, b, 4); return v; }
    case MPB__CT_U32: { uint32_t v; memcpy(&v, b, 4); return v; }
    case MPB__CT_F32: { float v; memcpy(&v, b, 4); return v; }
    default:          { double v; memcpy(&v, b, 8); return v; }
    }
}

static const char *const AXIS[] = {"x", "y", "z"};

int mpb_cloud_read(const void *bytes, size_t len, const char *name,
                   mpb_cloud_point_fn fn, void *ctx, long *count,
                   char *err, size_t errlen)
{
    if (err && errlen)
        err[0] = '\0';
    if (count)
        *count = 0;
    if ((!bytes && len > 0) || !fn)
        return MPB_EINVAL;
    if (!name)
        name = "cloud";
    const char *s = bytes;
    mpb__cloud_layout L;
    char why[200];
    int rc = len >= 4 && memcmp(s, "ply", 3) == 0 && (s[3] == '\n' || s[3] == '\r')
                 ? mpb__ply_header(s, len, &L, why, sizeof why)
                 : mpb__pcd_header(s, len, &L, why, sizeof why);
    if (rc != MPB_OK) {
        mpb__set_err(err, errlen, "%s: %s", name, why);
        return rc;
    }
    if (L.n > MPB_CLOUD_MAX_POINTS) {
        mpb__set_err(err, errlen, "%s: line %d: more than %ld points", name,
                     L.body_line - 1, MPB_CLOUD_MAX_POINTS);
        return MPB_EPARSE;
    }
    size_t left = len - L.body;
    const unsigned char *d = (const unsigned char *)s + L.body;
    /* the header's count against what the file can hold, before anything
       is read: an absurd count fails here */
    if (L.format != MPB__CLOUD_ASCII) {
        if (L.skip_bytes > left || (L.record > 0 &&
                                    (size_t)L.n > (left - L.skip_bytes) / L.record)) {
            mpb__set_err(err, errlen, "%s: line %d: the header says %ld %s of %zu "
                         "bytes, but the file holds %zu bytes of data: truncated or a "
                         "wrong count", name, L.body_line - 1, L.n, L.unit == NULL ? "" : L.unit,
                         L.record, left);
            return MPB_EPARSE;
        }
        d += L.skip_bytes;
        for (long i = 0; i < L.n; i++) {
            const unsigned char *r = d + (size_t)i * L.record;
            double p[3];
            for (int k = 0; k < 3; k++) {
                p[k] = value_at(r + L.off[k], L.type[k], L.format == MPB__CLOUD_BE);
                if (!isfinite(p[k])) {
                    mpb__set_err(err, errlen, "%s: %s %ld (data byte %zu): %s is not "
                                 "finite", name, L.unit, i,
                                 L.body + L.skip_bytes + (size_t)i * L.record + L.off[k],
                                 AXIS[k]);
                    return MPB_EPARSE;
                }
            }
            char msg[160] = "";
            if ((rc = fn(ctx, i, p, msg, sizeof msg)) != MPB_OK) {
                mpb__set_err(err, errlen, "%s: %s %ld: %s", name, L.unit, i,
                             msg[0] ? msg : mpb_strerror(rc));
                return rc;
            }
        }
        if (count)
            *count = L.n;
        return MPB_OK;
    }
    /* ASCII: each point (or skipped element) on a line of its own */
    if ((size_t)(L.n + L.skip_lines) > left / 2 + 1) {
        mpb__set_err(err, errlen, "%s: line %d: the header says %ld %s, but the "
                     "file holds %zu bytes of data: truncated or a wrong count", name,
                     L.body_line - 1, L.n, L.unit, left);
        return MPB_EPARSE;
    }
    const char *p = (const char *)d, *end = s + len;
    int line = L.body_line;
    for (long i = 0; i < L.skip_lines; i++, line++) {
        const char *e = memchr(p, '\n', (size_t)(end - p));
        if (!e) {
            mpb__set_err(err, errlen, "%s: line %d: the file ends inside the "
                         "elements before the points", name, line);
            return MPB_EPARSE;
        }
        p = e + 1;
    }
    for (long i = 0; i < L.n; i++, line++) {
        const char *e = p < end ? memchr(p, '\n', (size_t)(end - p)) : NULL;
        if (!e)
            e = end;
        if (p >= end) {
            mpb__set_err(err, errlen, "%s: line %d: the file ends at %s %ld of %ld: "
                         "truncated", name, line, L.unit, i, L.n);
            return MPB_EPARSE;
        }
        double pt[3];
        int tok = 0, got = 0;
        const char *q = p;
        while (q < e) {
            while (q < e && (*q == ' ' || *q == '\t' || *q == '\r'))
                q++;
            if (q >= e)
                break;
            const char *b = q;
            while (q < e && *q != ' ' && *q != '\t' && *q != '\r')
                q++;
            for (int k = 0; k < 3; k++)
                if (L.tok[k] == tok) {
                    double v;
                    if (!mpb__number(b, (int)(q - b), &v) && !(q - b == 3 &&
                        (memcmp(b, "nan", 3) == 0 || memcmp(b, "NaN", 3) == 0))) {
                        mpb__set_err(err, errlen, "%s: %s %ld (line %d): %s is not a "
                                     "number: '%.*s'", name, L.unit, i, line, AXIS[k],
                                     (int)(q - b > 30 ? 30 : q - b), b);
                        return MPB_EPARSE;
                    }
                    if (q - b == 3 && (b[0] == 'n' || b[0] == 'N'))
                        v = NAN;
                    if (!isfinite(v)) {
                        mpb__set_err(err, errlen, "%s: %s %ld (line %d): %s is not "
                                     "finite", name, L.unit, i, line, AXIS[k]);
                        return MPB_EPARSE;
                    }
                    pt[k] = v;
                    got++;
                }
            tok++;
        }
        if (got < 3 || tok < L.nvalues) {
            mpb__set_err(err, errlen, "%s: %s %ld (line %d): %d numbers, the header "
                         "says %d", name, L.unit, i, line, tok, L.nvalues);
            return MPB_EPARSE;
        }
        char msg[160] = "";
        if ((rc = fn(ctx, i, pt, msg, sizeof msg)) != MPB_OK) {
            mpb__set_err(err, errlen, "%s: %s %ld (line %d): %s", name, L.unit, i,
                         line, msg[0] ? msg : mpb_strerror(rc));
            return rc;
        }
        p = e < end ? e + 1 : end;
    }
    if (count)
        *count = L.n;
    return MPB_OK;
}

/* ---- into an octree, into an array -------------------------------------- */

static int to_octree(void *ctx, long i, const double p[3], char *msg, size_t msglen)
{
    (void)i;
    mpb_octree *o = ctx;
    int rc = mpb_octree_add_point(o, p);
    if (rc == MPB_EINVAL) {
        snprintf(msg, msglen, "(%g, %g, %g) is beyond the octree's reach (%g m at "
                 "this voxel size)", p[0], p[1], p[2],
                 mpb_octree_resolution(o) * (double)(1u << (MPB_OCTREE_DEPTH - 1)));
        return MPB_EPARSE;
    }
    if (rc == MPB_EPARSE)
        snprintf(msg, msglen, "more than %d occupied cells at this voxel size",
                 MPB_OCTREE_MAX_CELLS);
    return rc;
}

int mpb_cloud_load_octree(const char *path, double voxel, mpb_octree **out,
                          char *err, size_t errlen)
{
    if (!path || !out)
        return MPB_EINVAL;
    *out = NULL;
    mpb_octree *o;
    int rc = mpb_octree_create(voxel, &o);
    if (rc == MPB_EINVAL) {
        mpb__set_err(err, errlen, "%s: voxel size %g is outside %g .. %g m", path,
                     voxel, MPB_OCTREE_MIN_RESOLUTION, MPB_OCTREE_MAX_RESOLUTION);
        return rc;
    }
    if (rc != MPB_OK)
        return rc;
    char *buf;
    size_t len;
    if ((rc = mpb__read_file(path, MPB_CLOUD_MAX_BYTES, &buf, &len, err, errlen)) != MPB_OK) {
        mpb_octree_destroy(o);
        return rc;
    }
    rc = mpb_cloud_read(buf, len, path, to_octree, o, NULL, err, errlen);
    free(buf);
    if (rc == MPB_OK && (rc = mpb_octree_num_cells(o)) >= 0)
        rc = MPB_OK;
    else if (rc == MPB_EPARSE && err && errlen && !err[0])
        mpb__set_err(err, errlen, "%s: more than %d occupied cells at this voxel size",
                     path, MPB_OCTREE_MAX_CELLS);
    if (rc != MPB_OK) {
        mpb_octree_destroy(o);
        return rc;
    }
    *out = o;
    return MPB_OK;
}

typedef struct arr {
    double *xyz;
    long    n, cap, max;
} arr;

static int to_array(void *ctx, long i, const double p[3], char *msg, size_t msglen)
{
    (void)i;
    arr *a = ctx;
    if (a->n >= a->max) {
        snprintf(msg, msglen, "more than %ld points", a->max);
        return MPB_EPARSE;
    }
    if (a->n == a->cap) {
        long cap = a->cap ? 2 * a->cap : 256;
        double *q = realloc(a->xyz, (size_t)cap * 3 * sizeof *q);
        if (!q)
            return MPB_ENOMEM;
        a->xyz = q;
        a->cap = cap;
    }
    memcpy(a->xyz + 3 * a->n, p, 3 * sizeof *p);
    a->n++;
    return MPB_OK;
}

int mpb_cloud_load_points(const char *path, long max, double **xyz, long *n,
                          char *err, size_t errlen)
{
    if (!path || !xyz || !n || max < 0)
        return MPB_EINVAL;
    *xyz = NULL;
    *n = 0;
    char *buf;
    size_t len;
    int rc = mpb__read_file(path, MPB_CLOUD_MAX_BYTES, &buf, &len, err, errlen);
    if (rc != MPB_OK)
        return rc;
    arr a = {.max = max};
    rc = mpb_cloud_read(buf, len, path, to_array, &a, NULL, err, errlen);
    free(buf);
    if (rc != MPB_OK) {
        free(a.xyz);
        return rc;
    }
    *xyz = a.xyz;
    *n = a.n;
    return MPB_OK;
}
