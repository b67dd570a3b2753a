/*
 * wrist_cache.h - private to libmpbench and its tests: the wrist tables'
 * cache on disk, so that only the first process on a machine pays for
 * building them (wrist_table.h). wrist_cache.c also keeps the
 * process-wide cache in front of it: mpb__wrist_table_get() and the
 * counts of wrist_table.h.
 *
 * A file holds one table's bytes (its payload, mpb__wrist_table_encode())
 * under the hash of its key: everything the table is computed from (the
 * pair's kinematics, both links' shapes with every mesh vertex and
 * triangle, the build's parameters, MPB__WRIST_CACHE_VERSION). The files
 * are disk_cache.h's, kind "wrist" ($MPB_CACHE_DIR/wrist, else
 * $XDG_CACHE_HOME/mpbench/wrist, else $HOME/.cache/mpbench/wrist), magic
 * "MPBWRIST": checked, checksummed, written atomically. Nothing here
 * fails a world: a miss means build, a failed write means the next
 * process builds too.
 */
#ifndef MPB_WRIST_CACHE_H
#define MPB_WRIST_CACHE_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* The file format; part of every key too. Bump it when the payload's
 * layout or the way a table is built changes. */
#define MPB__WRIST_CACHE_VERSION 1

/* A key's hash: 32 hex digits and a NUL. */
#define MPB__WRIST_HASH_SIZE 33
void mpb__wrist_cache_hash(const void *key, size_t len,
                           char out[MPB__WRIST_HASH_SIZE]);

/*
 * The cache's directory into buf (n bytes), created when create is 1.
 * MPB_OK; MPB_ENOTFOUND when there is no HOME to fall back on, the path
 * does not fit, or (create) it cannot be made.
 */
int mpb__wrist_cache_dir(char *buf, size_t n, int create);

/*
 * The payload stored for a key of hash `hash` and length key_len: MPB_OK
 * with *payload (malloc()ed, the caller frees) and *len; MPB_ENOTFOUND if
 * there is none or the file fails any check; MPB_ENOMEM.
 */
int mpb__wrist_cache_read(const char *hash, size_t key_len,
                          unsigned char **payload, size_t *len);

/* Store a payload under the key: MPB_OK, or an error the caller may
 * ignore (MPB_ENOTFOUND: no directory; MPB_EIO; MPB_ENOMEM). */
int mpb__wrist_cache_write(const char *hash, size_t key_len,
                           const void *payload, size_t len);

#ifdef __cplusplus
}
#endif

#endif /* MPB_WRIST_CACHE_H */
