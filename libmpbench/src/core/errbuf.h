/*
 * errbuf.h - messages into a caller's buffer (err, errlen), as the
 * library's parsers, providers and C++ bridges report them; not part of
 * the API.
 */
#ifndef MPB_ERRBUF_H
#define MPB_ERRBUF_H

#include <stdarg.h>
#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/*
 * printf into err, if err is not NULL and errlen not 0, truncated to fit
 * and on one line: the line breaks that quoted input or a C++ library's
 * exception text may hold become spaces.
 */
void mpb__set_err(char *err, size_t errlen, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

/* The same with a va_list. */
void mpb__set_err_v(char *err, size_t errlen, const char *fmt, va_list ap)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 0)))
#endif
    ;

#ifdef __cplusplus
}
#endif

#endif /* MPB_ERRBUF_H */
