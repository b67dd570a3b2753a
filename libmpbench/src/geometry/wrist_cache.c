/*
 * wrist_cache.c - the wrist tables' caches (wrist_cache.h): the key, the
 * process-wide cache, and the one on disk: where it lives, the file's
 * header and checksum, atomic writes.
 */
#include <errno.h>
#include <fcntl.h>
#include <pthread.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include <sodium.h>

#include "mpbench/mpbench.h"
#include "core/grow.h"
#include "geometry/wrist_cache.h"
#include "geometry/wrist_table.h"

/*
 * A file: this header, then the payload. Numbers in the writer's byte
 * order, which the byte-order mark tells apart from the other one.
 *   0  magic "MPBWRIST"     8 bytes
 *   8  byte-order mark      uint32 0x01020304
 *  12  format version       uint32
 *  16  key length           uint64
 *  24  payload length       uint64
 *  32  key hash             32 hex digits
 *  64  payload checksum     32 hex digits (BLAKE2b-128 of the payload)
 */
#define HEADER 96
#define MAGIC "MPBWRIST"
#define BOM 0x01020304u
#define MAX_PAYLOAD (64u << 20)     /* far above any table's (40 KB) */

static const char hexdigits[] = "0123456789abcdef";

void mpb__wrist_cache_hash(const void *key, size_t len,
                           char out[MPB__WRIST_HASH_SIZE])
{
    unsigned char raw[16];
    /* libsodium wants it before any use (idempotent, thread-safe). It
     * fails only without a random source, which BLAKE2b does not need:
     * the hash is the same either way. */
    int ready = sodium_init();
    (void)ready;
    crypto_generichash(raw, sizeof raw, key, len, NULL, 0);
    for (int i = 0; i < 16; i++) {
        out[2 * i] = hexdigits[raw[i] >> 4];
        out[2 * i + 1] = hexdigits[raw[i] & 15];
    }
    out[32] = '\0';
}

/* An absolute path from the environment, or NULL. */
static const char *env_dir(const char *name)
{
    const char *v = getenv(name);
    return v && v[0] == '/' ? v : NULL;
}

/* mkdir -p, the last components private to the user. */
static int make_dirs(char *path)
{
    for (char *p = path + 1;; p++) {
        if (*p != '/' && *p != '\0')
            continue;
        char c = *p;
        *p = '\0';
        int rc = mkdir(path, 0700);
        *p = c;
        if (rc != 0 && errno != EEXIST)
            return MPB_ENOTFOUND;
        if (c == '\0')
            break;
    }
    struct stat st;
    return stat(path, &st) == 0 && S_ISDIR(st.st_mode) ? MPB_OK : MPB_ENOTFOUND;
}

int mpb__wrist_cache_dir(char *buf, size_t n, int create)
{
    const char *d;
    int len;
    if ((d = env_dir("MPB_CACHE_DIR")))
        len = snprintf(buf, n, "%s/wrist", d);
    else if ((d = env_dir("XDG_CACHE_HOME")))
        len = snprintf(buf, n, "%s/mpbench/wrist", d);
    else if ((d = env_dir("HOME")))
        len = snprintf(buf, n, "%s/.cache/mpbench/wrist", d);
    else
        return MPB_ENOTFOUND;
    if (len < 0 || (size_t)len >= n)
        return MPB_ENOTFOUND;
    return create ? make_dirs(buf) : MPB_OK;
}

/* The file for a hash, into buf (4096 bytes). */
static int file_path(const char *hash, int create, char *buf)
{
    char dir[4000];
    int rc = mpb__wrist_cache_dir(dir, sizeof dir, create);
    if (rc != MPB_OK)
        return rc;
    snprintf(buf, 4096, "%s/%.32s.tbl", dir, hash);
    return MPB_OK;
}

static void checksum(const void *data, size_t len, char out[MPB__WRIST_HASH_SIZE])
{
    mpb__wrist_cache_hash(data, len, out);
}

static void header(unsigned char h[HEADER], const char *hash, size_t key_len,
                   const void *payload, size_t len)
{
    uint32_t bom = BOM, version = MPB__WRIST_CACHE_VERSION;
    uint64_t kl = key_len, pl = len;
    char sum[MPB__WRIST_HASH_SIZE];
    checksum(payload, len, sum);
    memcpy(h, MAGIC, 8);
    memcpy(h + 8, &bom, 4);
    memcpy(h + 12, &version, 4);
    memcpy(h + 16, &kl, 8);
    memcpy(h + 24, &pl, 8);
    memcpy(h + 32, hash, 32);
    memcpy(h + 64, sum, 32);
}

/* Read (writing 0) or write all n bytes at p: 0, or -1. */
static int io_all(int fd, unsigned char *p, size_t n, int writing)
{
    while (n > 0) {
        ssize_t r = writing ? write(fd, p, n) : read(fd, p, n);
        if (r < 0 && errno == EINTR)
            continue;
        if (r <= 0)
            return -1;
        p += r;
        n -= (size_t)r;
    }
    return 0;
}

int mpb__wrist_cache_read(const char *hash, size_t key_len,
                          unsigned char **payload, size_t *len)
{
    char path[4096];
    *payload = NULL;
    *len = 0;
    if (file_path(hash, 0, path) != MPB_OK)
        return MPB_ENOTFOUND;
    int fd = open(path, O_RDONLY | O_CLOEXEC);
    if (fd < 0)
        return MPB_ENOTFOUND;
    struct stat st;
    unsigned char h[HEADER], *p = NULL;
    int rc = MPB_ENOTFOUND;
    uint32_t bom, version;
    uint64_t kl, pl;
    if (fstat(fd, &st) != 0 || !S_ISREG(st.st_mode) || st.st_size < HEADER ||
        st.st_size > HEADER + (off_t)MAX_PAYLOAD || io_all(fd, h, HEADER, 0) != 0)
        goto done;
    memcpy(&bom, h + 8, 4);
    memcpy(&version, h + 12, 4);
    memcpy(&kl, h + 16, 8);
    memcpy(&pl, h + 24, 8);
    if (memcmp(h, MAGIC, 8) != 0 || bom != BOM ||
        version != MPB__WRIST_CACHE_VERSION || kl != key_len ||
        memcmp(h + 32, hash, 32) != 0 || pl != (uint64_t)(st.st_size - HEADER))
        goto done;
    if (!(p = malloc(pl ? (size_t)pl : 1))) {
        rc = MPB_ENOMEM;
        goto done;
    }
    char sum[MPB__WRIST_HASH_SIZE];
    if (io_all(fd, p, (size_t)pl, 0) != 0)
        goto done;
    checksum(p, (size_t)pl, sum);
    if (memcmp(h + 64, sum, 32) != 0)
        goto done;
    *payload = p;
    *len = (size_t)pl;
    p = NULL;
    rc = MPB_OK;
done:
    free(p);
    close(fd);
    return rc;
}

int mpb__wrist_cache_write(const char *hash, size_t key_len,
                           const void *payload, size_t len)
{
    char path[4096], tmp[4200];
    if (len > MAX_PAYLOAD)
        return MPB_EINVAL;
    int rc = file_path(hash, 1, path);
    if (rc != MPB_OK)
        return rc;
    /* A private name in the same directory, so that rename() is atomic;
     * a writer that dies leaves only a dot file behind. */
    char *slash = strrchr(path, '/');
    snprintf(tmp, sizeof tmp, "%.*s/.%.32s.XXXXXX", (int)(slash - path), path,
             hash);
    int fd = mkstemp(tmp);
    if (fd < 0)
        return MPB_EIO;
    unsigned char h[HEADER];
    header(h, hash, key_len, payload, len);
    rc = io_all(fd, h, HEADER, 1) == 0 &&
         io_all(fd, (unsigned char *)payload, len, 1) == 0 ? MPB_OK : MPB_EIO;
    if (close(fd) != 0)
        rc = MPB_EIO;
    if (rc == MPB_OK && rename(tmp, path) != 0)
        rc = MPB_EIO;
    if (rc != MPB_OK)
        unlink(tmp);
    return rc;
}

/* ---- in process -------------------------------------------------------- */

/* What determines a table, as bytes: the parameters, the kinematics, both
 * sides' shapes with their meshes' vertices and triangles. */
typedef struct keybuf {
    unsigned char *p;
    int            len, cap, failed;
} keybuf;

static void put(keybuf *k, const void *data, size_t n)
{
    if (k->failed || n > (size_t)(INT32_MAX / 2) - (size_t)k->len ||
        mpb__grow((void **)&k->p, &k->cap, k->len + (int)n, 1) != MPB_OK) {
        k->failed = 1;
        return;
    }
    memcpy(k->p + k->len, data, n);
    k->len += (int)n;
}

static int make_key(const mpb__wrist_spec *s, keybuf *k)
{
    double params[5] = {0, 0, 0, 0, MPB__WRIST_CACHE_VERSION};
    mpb__wrist_get_params(params);
    int n = s->num_joints;
    put(k, params, sizeof params);
    put(k, &n, sizeof n);
    put(k, s->fixed, (size_t)(n + 1) * sizeof s->fixed[0]);
    put(k, s->axis, (size_t)n * sizeof s->axis[0]);
    put(k, s->lo, (size_t)n * sizeof s->lo[0]);
    put(k, s->hi, (size_t)n * sizeof s->hi[0]);
    for (int side = 0; side < 2; side++) {
        const mpb__wrist_side *sd = &s->side[side];
        put(k, &sd->num_shapes, sizeof sd->num_shapes);
        for (int i = 0; i < sd->num_shapes; i++) {
            const mpb_geometry *g = &sd->geoms[i];
            int type = (int)g->type;
            put(k, &type, sizeof type);
            put(k, g->dims, sizeof g->dims);
            put(k, &sd->offsets[i], sizeof sd->offsets[i]);
            if (g->type != MPB_SHAPE_MESH)
                continue;
            put(k, &g->mesh->num_vertices, sizeof g->mesh->num_vertices);
            put(k, &g->mesh->num_triangles, sizeof g->mesh->num_triangles);
            put(k, g->mesh->vertices, 3 * sizeof(double) *
                (size_t)g->mesh->num_vertices);
            put(k, g->mesh->triangles, 3 * sizeof(int32_t) *
                (size_t)g->mesh->num_triangles);
        }
    }
    return k->failed ? MPB_ENOMEM : MPB_OK;
}

/* Kept for the life of the process: a planner opens a world per scene,
 * one after the other, and each must find the tables of the last. */
typedef struct entry {
    unsigned char          *key;
    int                     len;
    const mpb__wrist_table *table;
    struct entry           *next;
} entry;

static pthread_mutex_t cache_mu = PTHREAD_MUTEX_INITIALIZER;
static entry *cache;
static long builds, loads;

/* The table for the key k of spec from the disk cache, else built (and
 * *built = 1) and stored there if it can be. */
static int from_disk(const mpb__wrist_spec *spec, const keybuf *k,
                     mpb__wrist_table **out, int *built)
{
    char hash[MPB__WRIST_HASH_SIZE];
    unsigned char *payload = NULL;
    size_t len = 0;
    mpb__wrist_cache_hash(k->p, (size_t)k->len, hash);
    int rc = mpb__wrist_cache_read(hash, (size_t)k->len, &payload, &len);
    if (rc == MPB_OK) {
        rc = mpb__wrist_table_decode(spec, payload, len, out);
        free(payload);
        if (rc != MPB_EPARSE) {
            *built = 0;
            return rc;
        }
    } else if (rc == MPB_ENOMEM) {
        return rc;
    }
    *built = 1;
    if ((rc = mpb__wrist_table_build(spec, out)) != MPB_OK)
        return rc;
    if ((payload = mpb__wrist_table_encode(*out, &len)))
        (void)mpb__wrist_cache_write(hash, (size_t)k->len, payload, len);
    free(payload);
    return MPB_OK;
}

static const mpb__wrist_table *lookup(const keybuf *k)
{
    for (entry *e = cache; e; e = e->next)
        if (e->len == k->len && memcmp(e->key, k->p, (size_t)k->len) == 0)
            return e->table;
    return NULL;
}

int mpb__wrist_table_get(const mpb__wrist_spec *spec,
                         const mpb__wrist_table **out)
{
    keybuf k = {0};
    int rc = make_key(spec, &k);
    if (rc != MPB_OK) {
        free(k.p);
        return rc;
    }
    pthread_mutex_lock(&cache_mu);
    *out = lookup(&k);
    pthread_mutex_unlock(&cache_mu);
    if (*out) {
        free(k.p);
        return MPB_OK;
    }
    /* Read or built outside the lock; two threads may both make one
     * table, and the first into the cache is kept. */
    mpb__wrist_table *t = NULL;
    entry *e = malloc(sizeof *e);
    int built = 0;
    rc = e ? from_disk(spec, &k, &t, &built) : MPB_ENOMEM;
    if (rc != MPB_OK) {
        free(e);
        free(k.p);
        return rc;
    }
    pthread_mutex_lock(&cache_mu);
    builds += built;
    loads += !built;
    *out = lookup(&k);
    if (!*out) {
        e->key = k.p;
        e->len = k.len;
        e->table = *out = t;
        e->next = cache;
        cache = e;
        e = NULL;
        t = NULL;
        k.p = NULL;
    }
    pthread_mutex_unlock(&cache_mu);
    mpb__wrist_table_free(t);
    free(e);
    free(k.p);
    return MPB_OK;
}

long mpb__wrist_builds(void)
{
    pthread_mutex_lock(&cache_mu);
    long n = builds;
    pthread_mutex_unlock(&cache_mu);
    return n;
}

long mpb__wrist_loads(void)
{
    pthread_mutex_lock(&cache_mu);
    long n = loads;
    pthread_mutex_unlock(&cache_mu);
    return n;
}

void mpb__wrist_forget(void)
{
    pthread_mutex_lock(&cache_mu);
    while (cache) {
        entry *e = cache;
        cache = e->next;
        mpb__wrist_table_free((mpb__wrist_table *)e->table);
        free(e->key);
        free(e);
    }
    pthread_mutex_unlock(&cache_mu);
}
