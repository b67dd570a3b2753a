/*
 * parse_cache.h - private to libmpbench and its tests: URDF and SRDF texts
 * parsed once per process.
 *
 * A planner opens one world per scene, and every world of an experiment
 * carries the same robot text: parsing it again with TinyXML and urdfdom
 * was most of what a later world cost (MotionBenchMaker's Panda: 0.8 of
 * 1.3 ms). Here the last few texts parsed are kept with what they parsed
 * to, keyed by the whole text (compared byte for byte, never by a hash
 * alone), and a caller gets its own deep copy: a text that differs by one
 * byte is parsed anew, and nothing a caller does to its copy reaches the
 * cache. Only successful parses are kept. Thread-safe.
 * mpb__urdf_parse_cached() (robot_urdf.h) and mpb__srdf_parse_cached()
 * (srdf_xml.h) are its entries; this header is for its tests.
 */
#ifndef MPB_PARSE_CACHE_H
#define MPB_PARSE_CACHE_H

#include <stddef.h>

#include "model/robot_urdf.h"
#include "model/srdf_xml.h"

#ifdef __cplusplus
extern "C" {
#endif

/* A deep copy of *from into *to (zeroed first): MPB_OK or MPB_ENOMEM, on
 * which *to holds nothing to free. */
int mpb__urdf_model_copy(const mpb__urdf_model *from, mpb__urdf_model *to);
int mpb__srdf_copy(const mpb__srdf *from, mpb__srdf *to);

/* For tests and measurements: the texts parsed (cache misses) since the
 * process began, URDF and SRDF together; and emptying the cache. */
long mpb__parse_cache_parses(void);
void mpb__parse_cache_forget(void);

#ifdef __cplusplus
}
#endif

#endif /* MPB_PARSE_CACHE_H */
