/*
 * wrist_cache.c - the wrist tables' caches (wrist_cache.h): the key, the
 * process-wide cache, and the one on disk (its files: disk_cache.c).
 */
#include <pthread.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "mpbench/mpbench.h"
#include "core/grow.h"
#include "geometry/disk_cache.h"
#include "geometry/wrist_cache.h"
#include "geometry/wrist_table.h"

static const mpb__disk_kind wrist_kind = {"wrist", "MPBWRIST",
                                          MPB__WRIST_CACHE_VERSION};

void mpb__wrist_cache_hash(const void *key, size_t len,
                           char out[MPB__WRIST_HASH_SIZE])
{
    mpb__disk_cache_hash(key, len, out);
}

int mpb__wrist_cache_dir(char *buf, size_t n, int create)
{
    return mpb__disk_cache_dir(&wrist_kind, buf, n, create);
}

int mpb__wrist_cache_read(const char *hash, size_t key_len,
                          unsigned char **payload, size_t *len)
{
    return mpb__disk_cache_read(&wrist_kind, hash, key_len, payload, len);
}

int mpb__wrist_cache_write(const char *hash, size_t key_len,
                           const void *payload, size_t len)
{
    return mpb__disk_cache_write(&wrist_kind, hash, key_len, payload, len);
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
