/*
 * robot_urdf.h - private: the URDF model as plain C structs, filled by the
 * C++ bridge robot_urdf.cpp (urdfdom) and turned into an mpb_robot by
 * robot.c. Every pointer here is malloc'd; mpb__urdf_model_clear() frees
 * them all.
 */
#ifndef MPB_ROBOT_URDF_H
#define MPB_ROBOT_URDF_H

#include <stddef.h>

#include "mpbench/robot.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct mpb__urdf_geom {
    mpb_shape_type type;        /* BOX, SPHERE, CYLINDER, MESH */
    double         dims[4];
    char          *mesh_uri;    /* MESH only */
    double         mesh_scale[3];
    mpb_pose       origin;
    char          *name;        /* NULL if none */
} mpb__urdf_geom;

typedef struct mpb__urdf_link {
    char          *name;
    int            parent;      /* link index, -1 for the root */
    /* The joint from the parent (unused at the root). */
    char          *joint;
    mpb_joint_type type;
    mpb_pose       origin;      /* parent frame -> joint frame */
    double         axis[3];     /* as written (urdfdom's default 1 0 0) */
    int            has_limits;
    double         lo, hi, max_velocity;
    char          *mimic;       /* <mimic joint=>: the joint it follows,
                                   or NULL */
    double         mimic_multiplier, mimic_offset; /* value = m * leader + o */
    int            num_geoms;
    mpb__urdf_geom *geoms;
} mpb__urdf_link;

typedef struct mpb__urdf_model {
    char           *name;
    int             num_links;  /* depth-first from the root: parents first */
    mpb__urdf_link *links;
} mpb__urdf_model;

/*
 * Parse URDF text into *m (zeroed first). MPB_OK; MPB_EPARSE with one line
 * in err (no prefix: "link 'a' is not unique"); MPB_ENOMEM. On failure *m
 * holds nothing to free.
 */
int mpb__urdf_parse(const char *text, mpb__urdf_model *m, char *err,
                    size_t errlen);

/*
 * mpb__urdf_parse() through the process's cache of parsed texts
 * (parse_cache.h): the same results and errors, the text parsed once.
 */
int mpb__urdf_parse_cached(const char *text, mpb__urdf_model *m, char *err,
                           size_t errlen);

/*
 * What TinyXML is not trusted with, checked before it parses an XML text
 * (URDF or SRDF): MPB_OK, or MPB_EPARSE with one line in err ("empty
 * document", "not XML ...", "line 3, column 7: not UTF-8", "XML nested
 * too deeply ...", "line 2, column 1: a <!DOCTYPE> with an internal DTD
 * ([...]) is not read: remove it").
 */
int mpb__xml_precheck(const char *text, char *err, size_t errlen);

/* Free everything *m holds and zero it. */
void mpb__urdf_model_clear(mpb__urdf_model *m);

/* The model a robot was built from (robot.c); owned by the robot. */
const mpb__urdf_model *mpb__robot_model(const mpb_robot *r);

#ifdef __cplusplus
}
#endif

#endif /* MPB_ROBOT_URDF_H */
