/*
 * wrist_cache.c - the wrist tables' cache on disk (wrist_cache.h): where
 * it lives, the file's header and checksum, atomic writes.
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
#include "geometry/wrist_cache.h"

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

/* Read all of fd's n bytes: 0, or -1. */
static int read_all(int fd, unsigned char *p, size_t n)
{
    while (n > 0) {
        ssize_t r = read(fd, p, n);
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
    if (sodium_init() < 0 || file_path(hash, 0, path) != MPB_OK)
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
        st.st_size > HEADER + (off_t)MAX_PAYLOAD || read_all(fd, h, HEADER) != 0)
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
    if (read_all(fd, p, (size_t)pl) != 0)
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

/* Write all n bytes: 0, or -1. */
static int write_all(int fd, const unsigned char *p, size_t n)
{
    while (n > 0) {
        ssize_t r = write(fd, p, n);
        if (r < 0 && errno == EINTR)
            continue;
        if (r <= 0)
            return -1;
        p += r;
        n -= (size_t)r;
    }
    return 0;
}

int mpb__wrist_cache_write(const char *hash, size_t key_len,
                           const void *payload, size_t len)
{
    char path[4096], tmp[4200];
    if (len > MAX_PAYLOAD || sodium_init() < 0)
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
    rc = write_all(fd, h, HEADER) == 0 && write_all(fd, payload, len) == 0
             ? MPB_OK : MPB_EIO;
    if (close(fd) != 0)
        rc = MPB_EIO;
    if (rc == MPB_OK && rename(tmp, path) != 0)
        rc = MPB_EIO;
    if (rc != MPB_OK)
        unlink(tmp);
    return rc;
}
