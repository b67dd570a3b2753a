/*
 * base64.h - RFC 4648 base64 (with '=' padding), for binary data inside
 * the library's text formats (an octree in a .scene); not part of the API.
 */
#ifndef MPB_BASE64_H
#define MPB_BASE64_H

#include <stddef.h>

/* The encoding of n bytes, in lines of at most 76 characters each ended
 * by '\n', NUL-terminated, into *out (the caller frees it). MPB_OK or
 * MPB_ENOMEM. */
int mpb__base64_encode(const void *data, size_t n, char **out, size_t *outlen);

/* Decode len characters at s (no whitespace; a multiple of 4, the last
 * group padded) into out, which holds at least 3 * len / 4 bytes;
 * *n gets the bytes written. 0 on success; else -1 - the index of the
 * first bad character (or of the group that is short). */
long mpb__base64_decode(const char *s, size_t len, unsigned char *out, size_t *n);

#endif /* MPB_BASE64_H */
