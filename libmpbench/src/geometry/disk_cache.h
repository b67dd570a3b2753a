/*
 * disk_cache.h - private to libmpbench and its tests: the files of the
 * caches on disk (the wrist tables' of wrist_cache.h, the meshes' of
 * mesh_disk.c), one file per entry, each kind in its own directory.
 *
 * A file holds one payload under the hash of its key (everything the
 * payload is computed from). The directories are $MPB_CACHE_DIR/KIND,
 * else $XDG_CACHE_HOME/mpbench/KIND, else $HOME/.cache/mpbench/KIND (an
 * empty or relative variable counts as unset). A file is used only when
 * its header (the kind's magic and format version, byte order, key hash
 * and length, payload length) matches and its payload's checksum
 * (BLAKE2b) is right; anything else reads as a miss. Files are written
 * whole to a temporary name and renamed, so a reader never sees one half
 * written, and two processes writing the same entry leave one good copy.
 */
#ifndef MPB_DISK_CACHE_H
#define MPB_DISK_CACHE_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* One kind of entry: its directory's name, its files' magic (8 bytes)
 * and its format version (part of every key too). */
typedef struct mpb__disk_kind {
    const char *dir;
    const char *magic;
    uint32_t    version;
} mpb__disk_kind;

/* A key's hash: 32 hex digits and a NUL. */
#define MPB__DISK_HASH_SIZE 33
void mpb__disk_cache_hash(const void *key, size_t len,
                          char out[MPB__DISK_HASH_SIZE]);

/*
 * The kind's directory into buf (n bytes), created when create is 1.
 * MPB_OK; MPB_ENOTFOUND when there is no HOME to fall back on, the path
 * does not fit, or (create) it cannot be made.
 */
int mpb__disk_cache_dir(const mpb__disk_kind *kind, char *buf, size_t n,
                        int create);

/*
 * The payload stored for a key of hash `hash` and length key_len: MPB_OK
 * with *payload (malloc()ed, the caller frees) and *len; MPB_ENOTFOUND if
 * there is none or the file fails any check; MPB_ENOMEM.
 */
int mpb__disk_cache_read(const mpb__disk_kind *kind, const char *hash,
                         size_t key_len, unsigned char **payload, size_t *len);

/* Store a payload under the key: MPB_OK, or an error the caller may
 * ignore (MPB_ENOTFOUND: no directory; MPB_EIO; MPB_ENOMEM; MPB_EINVAL:
 * above 64 MB). */
int mpb__disk_cache_write(const mpb__disk_kind *kind, const char *hash,
                          size_t key_len, const void *payload, size_t len);

#ifdef __cplusplus
}
#endif

#endif /* MPB_DISK_CACHE_H */
