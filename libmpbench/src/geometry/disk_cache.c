/*
 * disk_cache.c - the files of the caches on disk (disk_cache.h): where
 * they live, their header and checksum, atomic writes.
 */
#include <errno.h>
#include <fcntl.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include <sodium.h>

#include "mpbench/mpbench.h"
#include "geometry/disk_cache.h"

/*
 * A file: this header, then the payload. Numbers in the writer's byte
 * order, which the byte-order mark tells apart from the other one.
 *   0  magic (the kind's)   8 bytes
 *   8  byte-order mark      uint32 0x01020304
 *  12  format version       uint32
 *  16  key length           uint64
 *  24  payload length       uint64
 *  32  key hash             32 hex digits
 *  64  payload checksum     32 hex digits (BLAKE2b-128 of the payload)
 */
#define HEADER 96
#define BOM 0x01020304u
#define MAX_PAYLOAD (64u << 20)     /* far above a wrist table (40 KB) or
                                       a robot's mesh (1 MB) */

static const char hexdigits[] = "0123456789abcdef";

void mpb__disk_cache_hash(const void *key, size_t len,
                          char out[MPB__DISK_HASH_SIZE])
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

int mpb__disk_cache_dir(const mpb__disk_kind *kind, char *buf, size_t n,
                        int create)
{
    const char *d;
    int len;
    if ((d = env_dir("MPB_CACHE_DIR")))
        len = snprintf(buf, n, "%s/%s", d, kind->dir);
    else if ((d = env_dir("XDG_CACHE_HOME")))
        len = snprintf(buf, n, "%s/mpbench/%s", d, kind->dir);
    else if ((d = env_dir("HOME")))
        len = snprintf(buf, n, "%s/.cache/mpbench/%s", d, kind->dir);
    else
        return MPB_ENOTFOUND;
    if (len < 0 || (size_t)len >= n)
        return MPB_ENOTFOUND;
    return create ? make_dirs(buf) : MPB_OK;
}

/* The file for a hash, into buf (4096 bytes). */
static int file_path(const mpb__disk_kind *kind, const char *hash, int create,
                     char *buf)
{
    char dir[4000];
    int rc = mpb__disk_cache_dir(kind, dir, sizeof dir, create);
    if (rc != MPB_OK)
        return rc;
    snprintf(buf, 4096, "%s/%.32s.tbl", dir, hash);
    return MPB_OK;
}

static void checksum(const void *data, size_t len, char out[MPB__DISK_HASH_SIZE])
{
    mpb__disk_cache_hash(data, len, out);
}

static void header(const mpb__disk_kind *kind, unsigned char h[HEADER],
                   const char *hash, size_t key_len, const void *payload,
                   size_t len)
{
    uint32_t bom = BOM, version = kind->version;
    uint64_t kl = key_len, pl = len;
    char sum[MPB__DISK_HASH_SIZE];
    checksum(payload, len, sum);
    memcpy(h, kind->magic, 8);
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

int mpb__disk_cache_read(const mpb__disk_kind *kind, const char *hash,
                         size_t key_len, unsigned char **payload, size_t *len)
{
    char path[4096];
    *payload = NULL;
    *len = 0;
    if (file_path(kind, hash, 0, path) != MPB_OK)
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
    if (memcmp(h, kind->magic, 8) != 0 || bom != BOM ||
        version != kind->version || kl != key_len ||
        memcmp(h + 32, hash, 32) != 0 || pl != (uint64_t)(st.st_size - HEADER))
        goto done;
    if (!(p = malloc(pl ? (size_t)pl : 1))) {
        rc = MPB_ENOMEM;
        goto done;
    }
    char sum[MPB__DISK_HASH_SIZE];
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

int mpb__disk_cache_write(const mpb__disk_kind *kind, const char *hash,
                          size_t key_len, const void *payload, size_t len)
{
    char path[4096], tmp[4200];
    if (len > MAX_PAYLOAD)
        return MPB_EINVAL;
    int rc = file_path(kind, hash, 1, path);
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
    header(kind, h, hash, key_len, payload, len);
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
