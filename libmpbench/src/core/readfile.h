/*
 * readfile.h - a whole file into memory for the library's loaders, with
 * their one-line messages; not part of the API (mpb_read_file() is).
 */
#ifndef MPB_READFILE_H
#define MPB_READFILE_H

#include <stddef.h>

/*
 * mpb_read_file() with its failure said as an error code and one line in
 * err: MPB_OK with *text (NUL-terminated, the caller frees it) and *len;
 * or *text NULL and MPB_EIO ("PATH: cannot open: REASON", "PATH: larger
 * than MAX bytes", "PATH: read error") or MPB_ENOMEM ("PATH: out of
 * memory").
 */
int mpb__read_file(const char *path, size_t max, char **text, size_t *len,
                   char *err, size_t errlen);

#endif /* MPB_READFILE_H */
