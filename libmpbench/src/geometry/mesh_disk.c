/*
 * mesh_disk.c - meshes as assimp read them, kept in the cache on disk
 * (mesh_cache.h, disk_cache.h), so that only the first process on a
 * machine pays for parsing a robot's mesh files.
 *
 * The key is this file's format version, what the reader says about
 * itself (assimp's version and the steps it runs), the file name's
 * extension (assimp picks its importer by it), the scale's bits and every
 * byte of the file: a file changed by one byte, read at another scale or
 * by another assimp is another entry. The payload is the mesh: its counts,
 * then its vertices (doubles) and triangles (int32), in the writer's byte
 * order (the file's header tells the other one apart). A payload whose
 * lengths do not add up, or whose mesh fails mpb__mesh_check(), is a miss.
 */
#include <pthread.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "mpbench/mpbench.h"
#include "geometry/disk_cache.h"
#include "geometry/mesh_cache.h"
#include "geometry/mesh.h"

#define MESH_DISK_VERSION 1u

static const mpb__disk_kind mesh_kind = {"mesh", "MPBMESH1", MESH_DISK_VERSION};

static pthread_mutex_t mu = PTHREAD_MUTEX_INITIALIZER;
static long loads;

int mpb__mesh_disk_key(const char *path, const double scale[3],
                       const char *reader, mpb__mesh_disk_id *id)
{
    memset(id, 0, sizeof *id);
    size_t n = 0;
    char *bytes = mpb_read_file(path, 0, &n);
    if (!bytes)
        return MPB_ENOTFOUND;
    const char *slash = strrchr(path, '/');
    const char *dot = strrchr(slash ? slash : path, '.');
    const char *ext = dot ? dot : "";
    uint32_t version = MESH_DISK_VERSION;
    size_t rl = strlen(reader) + 1, el = strlen(ext) + 1;
    size_t len = sizeof version + rl + el + 3 * sizeof(double) + n;
    unsigned char *key = malloc(len);
    if (!key) {
        free(bytes);
        return MPB_ENOMEM;
    }
    unsigned char *p = key;
    memcpy(p, &version, sizeof version);
    p += sizeof version;
    memcpy(p, reader, rl);
    p += rl;
    memcpy(p, ext, el);
    p += el;
    memcpy(p, scale, 3 * sizeof(double));
    p += 3 * sizeof(double);
    memcpy(p, bytes, n);
    free(bytes);
    mpb__disk_cache_hash(key, len, id->hash);
    id->key_len = len;
    free(key);
    return MPB_OK;
}

mpb_mesh *mpb__mesh_disk_get(const mpb__mesh_disk_id *id)
{
    unsigned char *payload = NULL;
    size_t len = 0;
    if (mpb__disk_cache_read(&mesh_kind, id->hash, id->key_len, &payload,
                             &len) != MPB_OK)
        return NULL;
    int32_t nv = -1, nt = -1;
    mpb_mesh *m = NULL;
    if (len >= 8) {
        memcpy(&nv, payload, 4);
        memcpy(&nt, payload + 4, 4);
    }
    if (nv >= 0 && nt > 0 && nv <= INT32_MAX / 3 && nt <= INT32_MAX / 3 &&
        len == 8 + (size_t)nv * 3 * sizeof(double) + (size_t)nt * 3 * sizeof(int32_t) &&
        (m = mpb__mesh_create(nv, nt))) {
        size_t vb = (size_t)nv * 3 * sizeof(double);
        memcpy(m->vertices, payload + 8, vb);
        memcpy(m->triangles, payload + 8 + vb, (size_t)nt * 3 * sizeof(int32_t));
        if (mpb__mesh_check(m, NULL, 0) != MPB_OK) {
            mpb__mesh_destroy(m);
            m = NULL;
        }
    }
    free(payload);
    if (m) {
        pthread_mutex_lock(&mu);
        loads++;
        pthread_mutex_unlock(&mu);
    }
    return m;
}

void mpb__mesh_disk_put(const mpb__mesh_disk_id *id, const mpb_mesh *m)
{
    size_t vb = (size_t)m->num_vertices * 3 * sizeof(double);
    size_t tb = (size_t)m->num_triangles * 3 * sizeof(int32_t);
    unsigned char *payload = malloc(8 + vb + tb);
    if (!payload)
        return;
    int32_t nv = m->num_vertices, nt = m->num_triangles;
    memcpy(payload, &nv, 4);
    memcpy(payload + 4, &nt, 4);
    memcpy(payload + 8, m->vertices, vb);
    memcpy(payload + 8 + vb, m->triangles, tb);
    (void)mpb__disk_cache_write(&mesh_kind, id->hash, id->key_len, payload,
                                8 + vb + tb);
    free(payload);
}

long mpb__mesh_disk_loads(void)
{
    pthread_mutex_lock(&mu);
    long n = loads;
    pthread_mutex_unlock(&mu);
    return n;
}
