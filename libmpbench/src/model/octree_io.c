/*
 * octree_io.c - OctoMap's formats: the binary stream (two bits a child:
 * 01 occupied leaf, 10 free leaf, 11 inner node, 00 unknown; depth
 * first), the full stream of an "OcTree" (a float log-odds and a byte of
 * child bits a node, depth first), and the .bt and .ot files' headers.
 * Read with the depth and the cell count bounded, so that corrupt data
 * fails with its byte instead of recursing or allocating without end.
 */
#include "mpbench/mpbench.h"
#include "mpbench/octree.h"
#include "core/errbuf.h"
#include "core/readfile.h"
#include "model/octree_internal.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define BT_HEAD "# Octomap OcTree binary file"
#define OT_HEAD "# Octomap OcTree file"
/* The largest octree file read (bytes): 2^20 x 64 */
#define MAX_FILE ((size_t)1 << 30)

typedef struct rd {
    const unsigned char *p;
    size_t               len, at;
    mpb_octree          *o;
    int                  rc;
    char                 why[160];
} rd;

static int rd_fail(rd *r, int rc, const char *what)
{
    if (r->rc == MPB_OK) {
        r->rc = rc;
        snprintf(r->why, sizeof r->why, "data byte %zu: %s", r->at, what);
    }
    return r->rc;
}

static int rd_push(rd *r, uint64_t code, int level)
{
    int rc = mpb__octree_push(r->o, code, level);
    if (rc == MPB_EPARSE || (rc == MPB_OK && r->o->num_cells > MPB_OCTREE_MAX_CELLS)) {
        char m[120];
        snprintf(m, sizeof m, "more than %d occupied cells", MPB_OCTREE_MAX_CELLS);
        return rd_fail(r, MPB_EPARSE, m);
    }
    if (rc != MPB_OK)
        return rd_fail(r, rc, "out of memory");
    return MPB_OK;
}

/* A node of level `level` (its children level - 1) whose lower corner
 * has code `base`, in the binary stream. */
static int read_binary_node(rd *r, int level, uint64_t base)
{
    if (r->len - r->at < 2)
        return rd_fail(r, MPB_EPARSE, "truncated: the tree needs more bytes");
    unsigned bits = (unsigned)r->p[r->at] | (unsigned)r->p[r->at + 1] << 8;
    r->at += 2;
    uint64_t step = (uint64_t)1 << (3 * (level - 1));
    int inner[8];
    for (int i = 0; i < 8; i++) {
        unsigned b = bits >> (2 * i) & 3u;   /* bit 2i: low, 2i+1: high */
        inner[i] = b == 3u;
        if (b == 2u && rd_push(r, base + (uint64_t)i * step, level - 1) != MPB_OK)
            return r->rc;
        if (inner[i] && level - 1 == 0) {
            r->at -= 2;
            return rd_fail(r, MPB_EPARSE, "corrupt: a leaf cell has children "
                           "(deeper than OctoMap's 16 levels)");
        }
    }
    for (int i = 0; i < 8; i++)
        if (inner[i] && read_binary_node(r, level - 1, base + (uint64_t)i * step) != MPB_OK)
            return r->rc;
    return MPB_OK;
}

/* A node of the full stream: its log-odds, its child bits, its
 * children. */
static int read_full_node(rd *r, int level, uint64_t base)
{
    if (r->len - r->at < 5)
        return rd_fail(r, MPB_EPARSE, "truncated: the tree needs more bytes");
    float v;
    memcpy(&v, r->p + r->at, sizeof v);
    if (!isfinite(v))
        return rd_fail(r, MPB_EPARSE, "corrupt: a log-odds value is not finite");
    unsigned kids = r->p[r->at + 4];
    if (kids != 0 && level == 0)
        return rd_fail(r, MPB_EPARSE, "corrupt: a leaf cell has children "
                       "(deeper than OctoMap's 16 levels)");
    r->at += 5;
    if (kids == 0) {
        if (v >= 0.0f && level < MPB_OCTREE_DEPTH)
            return rd_push(r, base, level);
        if (v >= 0.0f)
            return rd_fail(r, MPB_EPARSE, "the whole root cube is occupied");
        return MPB_OK;
    }
    uint64_t step = (uint64_t)1 << (3 * (level - 1));
    for (int i = 0; i < 8; i++)
        if ((kids >> i & 1u) && read_full_node(r, level - 1, base + (uint64_t)i * step) != MPB_OK)
            return r->rc;
    return MPB_OK;
}

static void name_err(char *err, size_t errlen, const char *name, const char *why)
{
    if (name)
        mpb__set_err(err, errlen, "%s: %s", name, why);
    else
        mpb__set_err(err, errlen, "octree: %s", why);
}

int mpb_octree_create_from_stream(const void *data, size_t len, double resolution,
                                  int binary, const char *name, mpb_octree **out,
                                  char *err, size_t errlen)
{
    if (err && errlen)
        err[0] = '\0';
    if (!out || (!data && len > 0))
        return MPB_EINVAL;
    *out = NULL;
    mpb_octree *o;
    int rc = mpb_octree_create(resolution, &o);
    if (rc == MPB_EINVAL) {
        char m[160];
        snprintf(m, sizeof m, "resolution %g is outside %g .. %g m", resolution,
                 MPB_OCTREE_MIN_RESOLUTION, MPB_OCTREE_MAX_RESOLUTION);
        name_err(err, errlen, name, m);
        return rc;
    }
    if (rc != MPB_OK)
        return rc;
    rd r = {.p = data, .len = len, .o = o, .rc = MPB_OK};
    if (len > 0) {
        if (binary)
            read_binary_node(&r, MPB_OCTREE_DEPTH, 0);
        else
            read_full_node(&r, MPB_OCTREE_DEPTH, 0);
        if (r.rc == MPB_OK && r.at < len) {
            char m[80];
            snprintf(m, sizeof m, "corrupt: %zu bytes after the tree", len - r.at);
            rd_fail(&r, MPB_EPARSE, m);
        }
        if (r.rc == MPB_OK && (rc = mpb__octree_normalise(o)) != MPB_OK)
            rd_fail(&r, rc, rc == MPB_ENOMEM ? "out of memory" : "too many cells");
    }
    if (r.rc != MPB_OK) {
        name_err(err, errlen, name, r.why);
        mpb_octree_destroy(o);
        return r.rc;
    }
    *out = o;
    return MPB_OK;
}

/* One header line [b, e) (no newline). */
static int header_line(const char *b, const char *e, const char *word)
{
    size_t n = strlen(word);
    return (size_t)(e - b) >= n && memcmp(b, word, n) == 0 &&
           ((size_t)(e - b) == n || b[n] == ' ' || b[n] == '\t' || b[n] == '\r');
}

int mpb_octree_create_from_bytes(const void *bytes, size_t len, const char *name,
                                 mpb_octree **out, char *err, size_t errlen)
{
    if (err && errlen)
        err[0] = '\0';
    if (!out || (!bytes && len > 0))
        return MPB_EINVAL;
    *out = NULL;
    const char *s = bytes, *end = s + len;
    const char *nl = memchr(s, '\n', len);
    if (!nl) {
        name_err(err, errlen, name, "line 1: not an OctoMap file (no header line)");
        return MPB_EPARSE;
    }
    const char *e1 = nl > s && nl[-1] == '\r' ? nl - 1 : nl;
    int binary;
    if ((size_t)(e1 - s) == strlen(BT_HEAD) && memcmp(s, BT_HEAD, strlen(BT_HEAD)) == 0)
        binary = 1;
    else if ((size_t)(e1 - s) == strlen(OT_HEAD) && memcmp(s, OT_HEAD, strlen(OT_HEAD)) == 0)
        binary = 0;
    else {
        name_err(err, errlen, name, "line 1: not an OctoMap file (expected '"
                 BT_HEAD "' or '" OT_HEAD "')");
        return MPB_EPARSE;
    }
    double res = NAN;
    int line = 1, have_id = 0;
    const char *p = nl + 1;
    char m[200];
    for (;;) {
        line++;
        if (p >= end) {
            snprintf(m, sizeof m, "line %d: the header ends before its 'data' line", line);
            name_err(err, errlen, name, m);
            return MPB_EPARSE;
        }
        const char *e = memchr(p, '\n', (size_t)(end - p));
        if (!e) {
            snprintf(m, sizeof m, "line %d: the header ends before its 'data' line", line);
            name_err(err, errlen, name, m);
            return MPB_EPARSE;
        }
        const char *b = p;
        p = e + 1;
        while (b < e && (*b == ' ' || *b == '\t'))
            b++;
        if (b == e || *b == '#' || (e - b == 1 && *b == '\r'))
            continue;
        if (header_line(b, e, "data"))
            break;
        if (header_line(b, e, "id")) {
            const char *v = b + 2;
            while (v < e && (*v == ' ' || *v == '\t'))
                v++;
            const char *ve = e;
            while (ve > v && (ve[-1] == '\r' || ve[-1] == ' '))
                ve--;
            if (ve - v != 6 || memcmp(v, "OcTree", 6) != 0) {
                snprintf(m, sizeof m, "line %d: tree type '%.*s' is not supported "
                         "(only OcTree)", line, (int)(ve - v > 40 ? 40 : ve - v), v);
                name_err(err, errlen, name, m);
                return MPB_EUNSUPPORTED;
            }
            have_id = 1;
        } else if (header_line(b, e, "res")) {
            char num[64];
            size_t n = (size_t)(e - b - 3);
            if (n >= sizeof num)
                n = sizeof num - 1;
            memcpy(num, b + 3, n);
            num[n] = '\0';
            char *q;
            res = strtod(num, &q);
            while (*q == ' ' || *q == '\t' || *q == '\r')
                q++;
            if (q == num || *q) {
                snprintf(m, sizeof m, "line %d: res needs a number", line);
                name_err(err, errlen, name, m);
                return MPB_EPARSE;
            }
            if (!(res >= MPB_OCTREE_MIN_RESOLUTION && res <= MPB_OCTREE_MAX_RESOLUTION)) {
                snprintf(m, sizeof m, "line %d: resolution %g is outside %g .. %g m",
                         line, res, MPB_OCTREE_MIN_RESOLUTION, MPB_OCTREE_MAX_RESOLUTION);
                name_err(err, errlen, name, m);
                return MPB_EPARSE;
            }
        } else if (!header_line(b, e, "size")) {
            snprintf(m, sizeof m, "line %d: unknown header line '%.*s'", line,
                     (int)(e - b > 40 ? 40 : e - b), b);
            name_err(err, errlen, name, m);
            return MPB_EPARSE;
        }
    }
    (void)have_id;              /* OctoMap's oldest files have none */
    if (isnan(res)) {
        snprintf(m, sizeof m, "line %d: the header has no 'res' line", line);
        name_err(err, errlen, name, m);
        return MPB_EPARSE;
    }
    return mpb_octree_create_from_stream(p, (size_t)(end - p), res, binary, name, out, err, errlen);
}

int mpb_octree_create_from_file(const char *path, mpb_octree **out, char *err, size_t errlen)
{
    if (!path || !out)
        return MPB_EINVAL;
    *out = NULL;
    char *buf;
    size_t len;
    int rc = mpb__read_file(path, MAX_FILE, &buf, &len, err, errlen);
    if (rc != MPB_OK)
        return rc;
    rc = mpb_octree_create_from_bytes(buf, len, path, out, err, errlen);
    free(buf);
    return rc;
}

/* ---- writing ------------------------------------------------------------ */

typedef struct wr {
    unsigned char *p;
    size_t         len, cap;
    int            oom;
} wr;

static void put(wr *w, const void *b, size_t n)
{
    if (w->oom)
        return;
    if (w->len + n > w->cap) {
        size_t cap = w->cap ? w->cap : 256;
        while (cap < w->len + n)
            cap *= 2;
        unsigned char *q = realloc(w->p, cap);
        if (!q) {
            w->oom = 1;
            return;
        }
        w->p = q;
        w->cap = cap;
    }
    memcpy(w->p + w->len, b, n);
    w->len += n;
}

/* The node of `level` at `base`, over cells [*i, end) (sorted): those in
 * its span are its. */
static void write_node(wr *w, const mpb_octree *o, size_t *i, int level, uint64_t base)
{
    uint64_t step = (uint64_t)1 << (3 * (level - 1));
    unsigned bits = 0;
    int inner[8] = {0};
    size_t j = *i;
    for (int c = 0; c < 8; c++) {
        uint64_t lo = base + (uint64_t)c * step, hi = lo + step;
        if (j < o->num_cells && o->cells[j].code == lo && o->cells[j].level == level - 1) {
            bits |= 2u << (2 * c);       /* occupied leaf: 01 (high bit) */
            j++;
            continue;
        }
        if (j < o->num_cells && o->cells[j].code < hi) {
            bits |= 3u << (2 * c);
            inner[c] = 1;
            while (j < o->num_cells && o->cells[j].code < hi)
                j++;
        }
    }
    unsigned char b[2] = {(unsigned char)(bits & 0xff), (unsigned char)(bits >> 8)};
    put(w, b, 2);
    for (int c = 0; c < 8; c++)
        if (inner[c])
            write_node(w, o, i, level - 1, base + (uint64_t)c * step);
        else if (bits >> (2 * c) & 3u)
            (*i)++;
}

/* The number of nodes write_node() makes (OctoMap's "size"): every node
 * written, root included, and every occupied leaf. */
static size_t count_nodes(const mpb_octree *o)
{
    /* each cell is a leaf; each distinct ancestor prefix an inner node */
    size_t n = 0;
    for (int l = 1; l <= MPB_OCTREE_DEPTH; l++) {
        uint64_t prev = UINT64_MAX;
        for (size_t i = 0; i < o->num_cells; i++) {
            if (o->cells[i].level >= l)
                continue;
            uint64_t a = o->cells[i].code >> (3 * l);
            if (a != prev)
                n++;
            prev = a;
        }
    }
    return n + o->num_cells;
}

int mpb_octree_write(mpb_octree *o, int header, unsigned char **data, size_t *len)
{
    if (!o || !data || !len)
        return MPB_EINVAL;
    *data = NULL;
    *len = 0;
    int rc = mpb__octree_normalise(o);
    if (rc != MPB_OK)
        return rc;
    wr w = {0};
    if (header) {
        char h[256];
        int n = snprintf(h, sizeof h, BT_HEAD "\n# written by mpbench\nid OcTree\n"
                         "size %zu\nres %.17g\ndata\n",
                         o->num_cells ? count_nodes(o) : (size_t)0, o->res);
        put(&w, h, (size_t)n);
    }
    if (o->num_cells > 0) {
        size_t i = 0;
        write_node(&w, o, &i, MPB_OCTREE_DEPTH, 0);
    }
    if (w.oom) {
        free(w.p);
        return MPB_ENOMEM;
    }
    if (!w.p)                    /* an empty tree with no header */
        w.p = malloc(1);
    if (!w.p)
        return MPB_ENOMEM;
    *data = w.p;
    *len = w.len;
    return MPB_OK;
}
