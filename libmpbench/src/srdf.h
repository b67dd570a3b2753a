/*
 * srdf.h - private: the part of a robot's SRDF (MoveIt's Semantic Robot
 * Description Format) that mpbench reads, its <disable_collisions> pairs,
 * as plain C, filled by the C++ bridge srdf_tinyxml.cpp (TinyXML, the
 * reader urdfdom uses). Every pointer here is malloc'd;
 * mpb__srdf_clear() frees them all.
 */
#ifndef MPB_SRDF_H
#define MPB_SRDF_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct mpb__srdf_pair {
    char *link1, *link2;
    char *reason;               /* as written; "" if absent */
    int   line;                 /* of the element, from 1 */
} mpb__srdf_pair;

typedef struct mpb__srdf {
    int             num_pairs;
    mpb__srdf_pair *pairs;      /* in file order */
} mpb__srdf;

/*
 * Parse SRDF text into *s (zeroed first): the root element must be
 * <robot>; each <disable_collisions> under it needs link1 and link2. Other
 * elements (groups, group states, virtual and passive joints, end
 * effectors) are skipped. MPB_OK; MPB_EPARSE with one line in err naming
 * the line ("line 7: disable_collisions has no link2", "line 12, column
 * 3: not well-formed XML: ..."); MPB_ENOMEM. On failure *s holds nothing
 * to free.
 */
int mpb__srdf_parse(const char *text, mpb__srdf *s, char *err, size_t errlen);

/* Free everything *s holds and zero it; NULL does nothing. */
void mpb__srdf_clear(mpb__srdf *s);

#ifdef __cplusplus
}
#endif

#endif /* MPB_SRDF_H */
