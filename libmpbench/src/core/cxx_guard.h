/*
 * cxx_guard.h - the C++ bridges' guard at their extern "C" fronts: run
 * the body, and turn any exception into an MPB_E... code and one line in
 * (err, errlen); not part of the API. C++ only.
 */
#ifndef MPB_CXX_GUARD_H
#define MPB_CXX_GUARD_H

#ifndef __cplusplus
#error "core/cxx_guard.h is for the C++ bridges"
#endif

#include <cstddef>
#include <exception>
#include <new>

#include "core/errbuf.h"
#include "mpbench/mpbench.h"

/* What the guard says, and returns, for each kind of exception. */
struct mpb__cxx_guard {
    const char *prefix;     /* before every message ("mesh 'x': "), or "" */
    const char *library;    /* before a std::exception's text ("FCL: "), or "" */
    int         what_rc;    /* returned for a std::exception */
    const char *unknown;    /* the message for anything else */
    int         unknown_rc; /* returned for anything else */
};

/*
 * body()'s result (MPB_OK or an MPB_E... code); if it throws instead:
 * MPB_ENOMEM and "PREFIXout of memory" for std::bad_alloc, g.what_rc and
 * "PREFIXLIBRARYwhat()" for another std::exception, g.unknown_rc and
 * "PREFIXUNKNOWN" for anything else. err may be NULL.
 */
template <class Body>
int mpb__cxx_guarded(char *err, std::size_t errlen, const mpb__cxx_guard &g,
                     Body body)
{
    try {
        return body();
    } catch (const std::bad_alloc &) {
        mpb__set_err(err, errlen, "%sout of memory", g.prefix);
        return MPB_ENOMEM;
    } catch (const std::exception &e) {
        mpb__set_err(err, errlen, "%s%s%s", g.prefix, g.library, e.what());
        return g.what_rc;
    } catch (...) {
        mpb__set_err(err, errlen, "%s%s", g.prefix, g.unknown);
        return g.unknown_rc;
    }
}

#endif /* MPB_CXX_GUARD_H */
