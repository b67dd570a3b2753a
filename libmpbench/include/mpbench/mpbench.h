/*
 * mpbench.h - the public API of libmpbench, the motion-planner benchmarking
 * library. Include this one header; it includes the others.
 *
 * Conventions, written down once:
 *   - Every name is prefixed mpb_ (types, functions) or MPB_ (macros).
 *   - Functions that can fail return an int: 0 (MPB_OK) on success, a
 *     negative MPB_E... code on failure. mpb_strerror() names a code; the
 *     handle's own errmsg function (e.g. mpb_store_errmsg()) gives the detail.
 *     Functions that answer a question and cannot fail return the answer:
 *     mpb_x_num_...() a count, mpb_x_is_...() 1 or 0, a lookup an index
 *     or -1 when there is none; each says so, as does any other exception
 *     (mpb_auth_check() returns its verdict).
 *   - Objects are handles with one release function each. A handle read
 *     from a source (a file, a text, a key) is made by mpb_x_open...() and
 *     released by mpb_x_close(); one made empty or from numbers, to be
 *     filled by the caller, by mpb_x_create...() and mpb_x_destroy().
 *     Releasing NULL does nothing.
 *   - Who frees returned memory is stated at each function. A pointer an
 *     accessor returns (mpb_x_get_...(), a name) is owned by the handle and
 *     lives until the handle is released; names of codes and types are
 *     static.
 *   - The library never prints and never exits.
 */
#ifndef MPBENCH_H
#define MPBENCH_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

#define MPB_VERSION_MAJOR 0
#define MPB_VERSION_MINOR 1
#define MPB_VERSION_PATCH 0
#define MPB_VERSION_STRING "0.1.0"

/*
 * The error codes: name, value, meaning. One list generates the enum and
 * mpb_strerror(), so the two cannot drift apart.
 */
#define MPB_ERRNO_MAP(X)                                          \
    X(OK,          0,   "success")                                \
    X(ERROR,      -1,   "unspecified error")                      \
    X(NOMEM,      -2,   "out of memory")                          \
    X(INVAL,      -3,   "invalid argument")                       \
    X(IO,         -4,   "input/output error")                     \
    X(PARSE,      -5,   "malformed input")                        \
    X(DB,         -6,   "database error")                         \
    X(NOTFOUND,   -7,   "not found")                              \
    X(EXISTS,     -8,   "already exists")                         \
    X(LCM,        -9,   "LCM error")                              \
    X(UNSUPPORTED,-10,  "unsupported format or feature")          \
    X(REJECTED,   -11,  "message rejected")                       \
    X(BUSY,       -12,  "in use by another process")

typedef enum mpb_errno {
#define MPB__ERRNO_ENUM(name, value, text) MPB_E##name = (value),
    MPB_ERRNO_MAP(MPB__ERRNO_ENUM)
#undef MPB__ERRNO_ENUM
} mpb_errno;

#define MPB_OK MPB_EOK

/* A static English description of an error code; never NULL. */
const char *mpb_strerror(int code);

/* The symbolic name of an error code ("MPB_EPARSE"); never NULL. */
const char *mpb_err_name(int code);

/*
 * Read the whole file at path into a newly allocated buffer: its bytes,
 * then a NUL, so that a text file reads as a string (a NUL inside is the
 * caller's to refuse). Its length without the NUL goes into *len when len
 * is not NULL. A file of more than max bytes is refused (max 0: no limit).
 * Returns the buffer, which the caller frees with free(); or NULL with
 * errno set: fopen()'s reason, EISDIR for a folder, EFBIG for a file over
 * max, ENOMEM, or EIO for a read error.
 */
char *mpb_read_file(const char *path, size_t max, size_t *len);

#ifdef __cplusplus
}
#endif

#include "mpbench/metrics.h"
#include "mpbench/stats.h"
#include "mpbench/store.h"
#include "mpbench/proto.h"
#include "mpbench/world.h"
#include "mpbench/verify.h"
#include "mpbench/outcome.h"
#include "mpbench/wire.h"
#include "mpbench/auth.h"
#include "mpbench/lcm_filter.h"
#include "mpbench/link.h"
#include "mpbench/pose.h"
#include "mpbench/mesh.h"
#include "mpbench/collision.h"
#include "mpbench/octree.h"
#include "mpbench/cloud.h"
#include "mpbench/scene.h"
#include "mpbench/sense.h"
#include "mpbench/robot.h"
#include "mpbench/srdf.h"
#include "mpbench/bodies.h"
#include "mpbench/ompl_log.h"

#endif /* MPBENCH_H */
