/*
 * srdf.c - an SRDF read against its URDF (mpbench/srdf.h): each group's
 * joints by MoveIt's rules and whether mpbench can plan it, group states,
 * virtual and passive joints, end effectors and disabled pairs checked by
 * name. The XML itself is read by the C++ bridge srdf_tinyxml.cpp.
 *
 * A joint is known by an id: a URDF joint by its child link's index
 * (1 .. num_links-1), virtual joint v by num_links + v.
 */
#include "mpbench/mpbench.h"
#include "mpbench/srdf.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/errbuf.h"
#include "model/robot_urdf.h"
#include "model/srdf_xml.h"

#define NAME_SHOWN 80           /* characters of a name in errors */

typedef struct group_info {
    mpb_srdf_group pub;
    unsigned char *in;          /* per joint id: in the group */
    unsigned char *named;       /* per joint id: named by a <joint> of the
                                   group or of a subgroup */
    int            done;
    char          *why;         /* why mpbench cannot plan it, or NULL */
} group_info;

struct mpb_srdf {
    mpb__srdf               raw;
    mpb__urdf_model        *owned;  /* when mpb_srdf_open() parsed the URDF */
    const mpb__urdf_model  *m;
    int                     num_ids;
    group_info             *groups;
    mpb_srdf_state         *states;
    mpb_srdf_virtual_joint *vjoints;
    mpb_srdf_end_effector  *eefs;
    int                     num_skipped;  /* pairs naming unknown links */
    char                   *skipped;      /* the line saying so, or NULL */
};

/* ---- names --------------------------------------------------------------- */

static int find_link(const mpb__urdf_model *m, const char *name)
{
    for (int i = 0; i < m->num_links; i++)
        if (strcmp(m->links[i].name, name) == 0)
            return i;
    return -1;
}

/* The id of the joint of that name (URDF first, then virtual), or -1. */
static int find_joint(const mpb_srdf *s, const char *name)
{
    const mpb__urdf_model *m = s->m;
    for (int i = 1; i < m->num_links; i++)
        if (m->links[i].joint && strcmp(m->links[i].joint, name) == 0)
            return i;
    for (int v = 0; v < s->raw.num_vjoints; v++)
        if (strcmp(s->raw.vjoints[v].name, name) == 0)
            return m->num_links + v;
    return -1;
}

static const char *joint_name(const mpb_srdf *s, int id)
{
    return id < s->m->num_links ? s->m->links[id].joint
                                : s->raw.vjoints[id - s->m->num_links].name;
}

static int is_ancestor(const mpb__urdf_model *m, int a, int b)
{
    for (int i = b; i >= 0; i = m->links[i].parent)
        if (i == a)
            return 1;
    return 0;
}

static int is_active_type(mpb_joint_type t)
{
    return t == MPB_JOINT_REVOLUTE || t == MPB_JOINT_CONTINUOUS
        || t == MPB_JOINT_PRISMATIC;
}

int mpb_srdf_is_passive(const mpb_srdf *s, const char *joint)
{
    for (int i = 0; s && joint && i < s->raw.num_passive; i++)
        if (strcmp(s->raw.passive[i].name, joint) == 0)
            return s->raw.passive[i].line;
    return 0;
}

/* ---- groups --------------------------------------------------------------- */

/* The joints of the path between links base and tip, into in[]. */
static void add_path(const mpb__urdf_model *m, int base, int tip,
                     unsigned char *in)
{
    int c = base;
    while (!is_ancestor(m, c, tip))     /* the link both lie below */
        c = m->links[c].parent;
    for (int i = tip; i != c; i = m->links[i].parent)
        in[i] = 1;
    for (int i = base; i != c; i = m->links[i].parent)
        in[i] = 1;
}

static char *dup_printf(const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 1, 2)))
#endif
    ;

static char *dup_printf(const char *fmt, ...)
{
    char buf[2048];
    va_list ap;
    va_start(ap, fmt);
    mpb__set_err_v(buf, sizeof buf, fmt, ap);
    va_end(ap);
    return strdup(buf);
}

/* Why group g cannot be planned, or NULL if it can: into G->why. */
static int judge(mpb_srdf *s, group_info *G)
{
    const mpb__urdf_model *m = s->m;
    const char *name = G->pub.name;
    for (int id = 1; id < s->num_ids && !G->why; id++) {
        if (!G->named[id])
            continue;
        const char *j = joint_name(s, id);
        int pl = mpb_srdf_is_passive(s, j);
        if (id >= m->num_links)
            G->why = dup_printf("group '%.*s' names virtual joint '%.*s', which "
                                "mpbench holds at the identity; it cannot be "
                                "planned", NAME_SHOWN, name, NAME_SHOWN, j);
        else if (pl)
            G->why = dup_printf("group '%.*s' names joint '%.*s', which is "
                                "passive (srdf line %d); a passive joint is "
                                "never planned", NAME_SHOWN, name, NAME_SHOWN,
                                j, pl);
        else if (m->links[id].mimic && is_active_type(m->links[id].type))
            G->why = dup_printf("group '%.*s' names joint '%.*s', which mimics "
                                "'%.*s' and follows it; a mimic joint cannot "
                                "be planned", NAME_SHOWN, name, NAME_SHOWN, j,
                                NAME_SHOWN, m->links[id].mimic);
        else
            continue;
        return G->why ? MPB_OK : MPB_ENOMEM;
    }
    if (G->pub.num_active == 0) {
        G->why = dup_printf("group '%.*s' has no joint to plan: its joints are "
                            "fixed, mimic, passive or virtual", NAME_SHOWN, name);
        return G->why ? MPB_OK : MPB_ENOMEM;
    }
    for (int k = 1; k < G->pub.num_active; k++) {
        int a = find_joint(s, G->pub.active[k - 1]);
        int b = find_joint(s, G->pub.active[k]);
        if (!is_ancestor(m, a, m->links[b].parent)) {
            G->why = dup_printf("group '%.*s' is not a serial chain: its joints "
                                "'%.*s' and '%.*s' are on different branches; "
                                "mpbench plans one chain of joints, each below "
                                "the one before", NAME_SHOWN, name, NAME_SHOWN,
                                G->pub.active[k - 1], NAME_SHOWN,
                                G->pub.active[k]);
            return G->why ? MPB_OK : MPB_ENOMEM;
        }
    }
    return MPB_OK;
}

/* The joints of group g, its subgroups first (the SRDF has no cycles). */
static int group_joints(mpb_srdf *s, int g, char *err, size_t errlen)
{
    const mpb__urdf_model *m = s->m;
    const mpb__srdf_group *rg = &s->raw.groups[g];
    group_info *G = &s->groups[g];
    if (G->done)
        return MPB_OK;
    G->done = 1;
    G->pub.name = rg->name;
    G->pub.line = rg->line;
    G->in = calloc((size_t)s->num_ids, 1);
    G->named = calloc((size_t)s->num_ids, 1);
    G->pub.subgroups = calloc((size_t)rg->num_elems + 1, sizeof(char *));
    if (!G->in || !G->named || !G->pub.subgroups)
        return MPB_ENOMEM;
    const char **subs = (const char **)G->pub.subgroups;
    for (int k = 0; k < rg->num_elems; k++) {
        const mpb__srdf_elem *e = &rg->elems[k];
        int id, l, b, rc;
        switch (e->kind) {
        case MPB__SRDF_JOINT:
            if ((id = find_joint(s, e->name)) < 0) {
                mpb__set_err(err, errlen, "line %d: group '%.*s' names joint "
                             "'%.*s', which is not a joint of the URDF", e->line,
                             NAME_SHOWN, rg->name, NAME_SHOWN, e->name);
                return MPB_EPARSE;
            }
            G->in[id] = G->named[id] = 1;
            break;
        case MPB__SRDF_LINK:
            if ((l = find_link(m, e->name)) < 0) {
                mpb__set_err(err, errlen, "line %d: group '%.*s' names link "
                             "'%.*s', which is not a link of the URDF", e->line,
                             NAME_SHOWN, rg->name, NAME_SHOWN, e->name);
                return MPB_EPARSE;
            }
            if (l > 0)
                G->in[l] = 1;
            else        /* the root: the virtual joints above it */
                for (int v = 0; v < s->raw.num_vjoints; v++)
                    G->in[m->num_links + v] = 1;
            break;
        case MPB__SRDF_CHAIN:
            l = find_link(m, e->name);
            b = find_link(m, e->tip);
            if (l < 0 || b < 0) {
                mpb__set_err(err, errlen, "line %d: group '%.*s': chain names "
                             "%s link '%.*s', which is not a link of the URDF",
                             e->line, NAME_SHOWN, rg->name,
                             l < 0 ? "base" : "tip", NAME_SHOWN,
                             l < 0 ? e->name : e->tip);
                return MPB_EPARSE;
            }
            add_path(m, l, b, G->in);
            if (!G->pub.chain_base) {
                G->pub.chain_base = m->links[l].name;
                G->pub.chain_tip = m->links[b].name;
            }
            break;
        case MPB__SRDF_GROUP:
            id = mpb__srdf_find_group(&s->raw, e->name);
            if ((rc = group_joints(s, id, err, errlen)) != MPB_OK)
                return rc;
            for (int i = 0; i < s->num_ids; i++) {
                G->in[i] |= s->groups[id].in[i];
                G->named[i] |= s->groups[id].named[i];
            }
            subs[G->pub.num_subgroups++] = s->groups[id].pub.name;
            break;
        }
    }
    int n = 0;
    for (int i = 0; i < s->num_ids; i++)
        n += G->in[i];
    if (n == 0) {
        mpb__set_err(err, errlen, "line %d: group '%.*s' has no joints",
                     rg->line, NAME_SHOWN, rg->name);
        return MPB_EPARSE;
    }
    const char **joints = calloc((size_t)n, sizeof *joints);
    const char **active = calloc((size_t)n, sizeof *active);
    G->pub.joints = joints;
    G->pub.active = active;
    if (!joints || !active)
        return MPB_ENOMEM;
    /* Virtual joints first: they sit above the root. */
    for (int id = m->num_links; id < s->num_ids; id++)
        if (G->in[id])
            joints[G->pub.num_joints++] = joint_name(s, id);
    for (int id = 1; id < m->num_links; id++) {
        if (!G->in[id])
            continue;
        const mpb__urdf_link *ul = &m->links[id];
        joints[G->pub.num_joints++] = ul->joint;
        if (is_active_type(ul->type) && !ul->mimic &&
            !mpb_srdf_is_passive(s, ul->joint))
            active[G->pub.num_active++] = ul->joint;
    }
    return judge(s, G);
}

/* ---- checks by name -------------------------------------------------------- */

static int check_vjoints(mpb_srdf *s, char *err, size_t errlen)
{
    const mpb__urdf_model *m = s->m;
    for (int v = 0; v < s->raw.num_vjoints; v++) {
        const mpb__srdf_vjoint *V = &s->raw.vjoints[v];
        int l = find_link(m, V->child_link);
        if (l < 0) {
            mpb__set_err(err, errlen, "line %d: virtual_joint '%.*s' has "
                         "child_link '%.*s', which is not a link of the URDF",
                         V->line, NAME_SHOWN, V->name, NAME_SHOWN, V->child_link);
            return MPB_EPARSE;
        }
        if (l != 0) {
            mpb__set_err(err, errlen, "line %d: virtual_joint '%.*s' attaches "
                         "to '%.*s', which is not the URDF's root link '%.*s'",
                         V->line, NAME_SHOWN, V->name, NAME_SHOWN, V->child_link,
                         NAME_SHOWN, m->links[0].name);
            return MPB_EPARSE;
        }
        int clash = find_joint(s, V->name);
        if (clash >= 0 && clash < m->num_links) {
            mpb__set_err(err, errlen, "line %d: virtual_joint '%.*s' has the "
                         "name of a joint of the URDF", V->line, NAME_SHOWN,
                         V->name);
            return MPB_EPARSE;
        }
        s->vjoints[v] = (mpb_srdf_virtual_joint){V->name, V->type,
                                                 V->parent_frame, V->child_link,
                                                 V->line};
    }
    for (int i = 0; i < s->raw.num_passive; i++)
        if (find_joint(s, s->raw.passive[i].name) < 0) {
            mpb__set_err(err, errlen, "line %d: passive_joint '%.*s' is not a "
                         "joint of the URDF", s->raw.passive[i].line, NAME_SHOWN,
                         s->raw.passive[i].name);
            return MPB_EPARSE;
        }
    return MPB_OK;
}

/* The joint id a group state's value is for: a joint's name, or a
 * virtual joint's variable ("virtual_joint/trans_x"). */
static int state_joint(const mpb_srdf *s, const char *name)
{
    int id = find_joint(s, name);
    if (id >= 0)
        return id;
    const char *slash = strchr(name, '/');
    for (int v = 0; slash && v < s->raw.num_vjoints; v++)
        if (strlen(s->raw.vjoints[v].name) == (size_t)(slash - name) &&
            strncmp(s->raw.vjoints[v].name, name, (size_t)(slash - name)) == 0)
            return s->m->num_links + v;
    return -1;
}

static int check_states(mpb_srdf *s, char *err, size_t errlen)
{
    for (int i = 0; i < s->raw.num_states; i++) {
        const mpb__srdf_state *S = &s->raw.states[i];
        int g = mpb__srdf_find_group(&s->raw, S->group);
        if (g < 0) {
            mpb__set_err(err, errlen, "line %d: group_state '%.*s' is for group "
                         "'%.*s', which is no group of the SRDF", S->line,
                         NAME_SHOWN, S->name, NAME_SHOWN, S->group);
            return MPB_EPARSE;
        }
        const char **joints = calloc((size_t)S->num_values + 1, sizeof *joints);
        double *values = calloc((size_t)S->num_values + 1, sizeof *values);
        s->states[i] = (mpb_srdf_state){S->name, S->group, S->line,
                                        S->num_values, joints, values};
        if (!joints || !values)
            return MPB_ENOMEM;
        for (int k = 0; k < S->num_values; k++) {
            const mpb__srdf_value *V = &S->values[k];
            int id = state_joint(s, V->joint);
            if (id < 0) {
                mpb__set_err(err, errlen, "line %d: group_state '%.*s' gives "
                             "joint '%.*s', which is not a joint of the URDF",
                             V->line, NAME_SHOWN, S->name, NAME_SHOWN, V->joint);
                return MPB_EPARSE;
            }
            if (!s->groups[g].in[id]) {
                mpb__set_err(err, errlen, "line %d: group_state '%.*s' gives "
                             "joint '%.*s', which is not in group '%.*s'",
                             V->line, NAME_SHOWN, S->name, NAME_SHOWN, V->joint,
                             NAME_SHOWN, S->group);
                return MPB_EPARSE;
            }
            joints[k] = V->joint;
            values[k] = V->value;
        }
    }
    return MPB_OK;
}

static int check_eefs(mpb_srdf *s, char *err, size_t errlen)
{
    for (int i = 0; i < s->raw.num_eefs; i++) {
        const mpb__srdf_eef *E = &s->raw.eefs[i];
        /* What names what, and which file ought to have it. */
        const char *bad = NULL, *what = NULL, *kind = "group", *file = "SRDF";
        if (mpb__srdf_find_group(&s->raw, E->group) < 0)
            bad = E->group, what = "group";
        else if (find_link(s->m, E->parent_link) < 0)
            bad = E->parent_link, what = "parent_link", kind = "link",
            file = "URDF";
        else if (E->parent_group &&
                 mpb__srdf_find_group(&s->raw, E->parent_group) < 0)
            bad = E->parent_group, what = "parent_group";
        if (bad) {
            mpb__set_err(err, errlen, "line %d: end_effector '%.*s' has %s "
                         "'%.*s', which is not a %s of the %s", E->line,
                         NAME_SHOWN, E->name, what, NAME_SHOWN, bad, kind, file);
            return MPB_EPARSE;
        }
        s->eefs[i] = (mpb_srdf_end_effector){E->name, E->group, E->parent_link,
                                             E->parent_group, E->line};
    }
    return MPB_OK;
}

/*
 * <disable_collisions> pairs that name a link the URDF lacks: skipped, as
 * MoveIt does (it warns and goes on; VAMP's Baxter and Fetch SRDFs name
 * links their URDFs leave out). One line says how many and which.
 */
#define SKIPPED_SHOWN 3         /* pairs named in the line */

/* Add name to the list "a, b" in names (cap bytes) unless there; "..."
 * once it is full. */
static void add_name(char *names, size_t cap, const char *name)
{
    size_t used = strlen(names), n = strlen(name);
    for (const char *p = names; *p;) {
        size_t k = strcspn(p, ",");
        if (k == n && strncmp(p, name, n) == 0)
            return;
        p += k + (p[k] == ',' ? 2 : 0);
    }
    if (used >= 3 && strcmp(names + used - 3, "...") == 0)
        return;
    if (used + n + 8 < cap)
        snprintf(names + used, cap - used, "%s%s", used ? ", " : "", name);
    else
        snprintf(names + used, cap - used, "%s...", used ? ", " : "");
}

static int check_pairs(mpb_srdf *s)
{
    char buf[1024], names[512] = "";
    size_t used = 0;
    for (int i = 0; i < s->raw.num_pairs; i++) {
        const mpb__srdf_pair *p = &s->raw.pairs[i];
        int a = find_link(s->m, p->link1), b = find_link(s->m, p->link2);
        if (a >= 0 && b >= 0)
            continue;
        char shown[NAME_SHOWN + 1];
        if (a < 0) {
            snprintf(shown, sizeof shown, "%s", p->link1);
            add_name(names, sizeof names, shown);
        }
        if (b < 0) {
            snprintf(shown, sizeof shown, "%s", p->link2);
            add_name(names, sizeof names, shown);
        }
        if (s->num_skipped++ >= SKIPPED_SHOWN || used >= sizeof buf)
            continue;
        const char *missing = a < 0 ? p->link1 : p->link2;
        used += (size_t)snprintf(buf + used, sizeof buf - used,
                                 "%sline %d (%.*s, %.*s: no link '%.*s'%s)",
                                 s->num_skipped > 1 ? ", " : "", p->line,
                                 NAME_SHOWN, p->link1, NAME_SHOWN, p->link2,
                                 NAME_SHOWN, missing,
                                 a < 0 && b < 0 ? " nor the other" : "");
    }
    if (s->num_skipped == 0)
        return MPB_OK;
    char more[64] = "";
    if (s->num_skipped > SKIPPED_SHOWN)
        snprintf(more, sizeof more, " and %d more",
                 s->num_skipped - SKIPPED_SHOWN);
    s->skipped = dup_printf("%d of %d disable_collisions pairs name links the "
                            "URDF lacks and are skipped, as MoveIt does: %s%s; "
                            "the names: %s", s->num_skipped, s->raw.num_pairs,
                            buf, more, names);
    return s->skipped ? MPB_OK : MPB_ENOMEM;
}

/* ---- the handle ----------------------------------------------------------- */

/* mpb__srdf_bind_robot() for a model of the URDF. */
static int bind(mpb__srdf *raw, const mpb__urdf_model *m, mpb_srdf **out,
                char *err, size_t errlen)
{
    mpb__set_err(err, errlen, "%s", "");
    *out = NULL;
    mpb_srdf *s = calloc(1, sizeof *s);
    if (!s) {
        mpb__srdf_clear(raw);
        mpb__set_err(err, errlen, "out of memory");
        return MPB_ENOMEM;
    }
    s->raw = *raw;
    memset(raw, 0, sizeof *raw);
    s->m = m;
    s->num_ids = m->num_links + s->raw.num_vjoints;
    s->groups = calloc((size_t)s->raw.num_groups + 1, sizeof *s->groups);
    s->states = calloc((size_t)s->raw.num_states + 1, sizeof *s->states);
    s->vjoints = calloc((size_t)s->raw.num_vjoints + 1, sizeof *s->vjoints);
    s->eefs = calloc((size_t)s->raw.num_eefs + 1, sizeof *s->eefs);
    int rc = MPB_ENOMEM;
    if (s->groups && s->states && s->vjoints && s->eefs)
        rc = check_vjoints(s, err, errlen);
    for (int g = 0; rc == MPB_OK && g < s->raw.num_groups; g++)
        rc = group_joints(s, g, err, errlen);
    if (rc == MPB_OK)
        rc = check_states(s, err, errlen);
    if (rc == MPB_OK)
        rc = check_eefs(s, err, errlen);
    if (rc == MPB_OK)
        rc = check_pairs(s);
    if (rc != MPB_OK) {
        if (rc == MPB_ENOMEM)
            mpb__set_err(err, errlen, "out of memory");
        mpb_srdf_close(s);
        return rc;
    }
    *out = s;
    return MPB_OK;
}

int mpb__srdf_bind_robot(mpb__srdf *raw, const mpb_robot *r, mpb_srdf **out,
                         char *err, size_t errlen)
{
    return bind(raw, mpb__robot_model(r), out, err, errlen);
}

const mpb__srdf *mpb__srdf_raw(const mpb_srdf *s)
{
    return s ? &s->raw : NULL;
}

int mpb_srdf_open(const char *urdf_text, const char *srdf_text,
                  mpb_srdf **out, char *err, size_t errlen)
{
    char why[512];
    mpb__srdf raw;
    mpb__set_err(err, errlen, "%s", "");
    if (out)
        *out = NULL;
    if (!urdf_text || !srdf_text || !out) {
        mpb__set_err(err, errlen, "srdf: the URDF and SRDF texts and out are "
                     "required");
        return MPB_EINVAL;
    }
    mpb__urdf_model *m = calloc(1, sizeof *m);
    if (!m) {
        mpb__set_err(err, errlen, "out of memory");
        return MPB_ENOMEM;
    }
    int rc = mpb__urdf_parse(urdf_text, m, why, sizeof why);
    if (rc != MPB_OK) {
        mpb__set_err(err, errlen, "urdf: %s", why);
        free(m);
        return rc;
    }
    if ((rc = mpb__srdf_parse(srdf_text, &raw, why, sizeof why)) == MPB_OK)
        rc = bind(&raw, m, out, why, sizeof why);
    if (rc != MPB_OK) {
        mpb__set_err(err, errlen, "srdf %s", why);
        mpb__urdf_model_clear(m);
        free(m);
        return rc;
    }
    (*out)->owned = m;
    return MPB_OK;
}

void mpb_srdf_close(mpb_srdf *s)
{
    if (!s)
        return;
    for (int g = 0; s->groups && g < s->raw.num_groups; g++) {
        group_info *G = &s->groups[g];
        free(G->in);
        free(G->named);
        free(G->why);
        free((void *)G->pub.joints);
        free((void *)G->pub.active);
        free((void *)G->pub.subgroups);
    }
    for (int i = 0; s->states && i < s->raw.num_states; i++) {
        free((void *)s->states[i].joints);
        free((void *)s->states[i].values);
    }
    free(s->groups);
    free(s->states);
    free(s->vjoints);
    free(s->eefs);
    free(s->skipped);
    mpb__srdf_clear(&s->raw);
    if (s->owned) {
        mpb__urdf_model_clear(s->owned);
        free(s->owned);
    }
    free(s);
}

const char *mpb_srdf_robot_name(const mpb_srdf *s)
{
    return s && s->raw.robot_name ? s->raw.robot_name : "";
}

int mpb_srdf_num_skipped_pairs(const mpb_srdf *s)
{
    return s ? s->num_skipped : 0;
}

const char *mpb_srdf_skipped_pairs(const mpb_srdf *s)
{
    return s ? s->skipped : NULL;
}

int mpb_srdf_num_groups(const mpb_srdf *s)
{
    return s ? s->raw.num_groups : 0;
}

const mpb_srdf_group *mpb_srdf_get_group(const mpb_srdf *s, int i)
{
    return s && i >= 0 && i < s->raw.num_groups ? &s->groups[i].pub : NULL;
}

int mpb_srdf_group_index(const mpb_srdf *s, const char *name)
{
    int g = s ? mpb__srdf_find_group(&s->raw, name) : -1;
    return g >= 0 ? g : MPB_ENOTFOUND;
}

int mpb_srdf_group_check(const mpb_srdf *s, int i, char *err, size_t errlen)
{
    mpb__set_err(err, errlen, "%s", "");
    if (!s || i < 0 || i >= s->raw.num_groups)
        return MPB_EINVAL;
    if (s->groups[i].why) {
        mpb__set_err(err, errlen, "%s", s->groups[i].why);
        return MPB_EUNSUPPORTED;
    }
    return MPB_OK;
}

int mpb_srdf_num_states(const mpb_srdf *s)
{
    return s ? s->raw.num_states : 0;
}

const mpb_srdf_state *mpb_srdf_get_state(const mpb_srdf *s, int i)
{
    return s && i >= 0 && i < s->raw.num_states ? &s->states[i] : NULL;
}

int mpb_srdf_state_values(const mpb_srdf *s, int i, const char *name,
                          double *q, char *err, size_t errlen)
{
    mpb__set_err(err, errlen, "%s", "");
    if (!s || i < 0 || i >= s->raw.num_groups || !name || !q)
        return MPB_EINVAL;
    const mpb_srdf_group *G = &s->groups[i].pub;
    const mpb_srdf_state *other = NULL;
    for (int k = 0; k < s->raw.num_states; k++) {
        const mpb_srdf_state *S = &s->states[k];
        if (strcmp(S->name, name) != 0)
            continue;
        if (strcmp(S->group, G->name) != 0) {
            other = S;
            continue;
        }
        for (int j = 0; j < G->num_active; j++) {
            int v = 0;
            while (v < S->num_values && strcmp(S->joints[v], G->active[j]) != 0)
                v++;
            if (v == S->num_values) {
                mpb__set_err(err, errlen, "group_state '%.*s' (srdf line %d) has "
                             "no value for joint '%.*s'", NAME_SHOWN, name,
                             S->line, NAME_SHOWN, G->active[j]);
                return MPB_EINVAL;
            }
            q[j] = S->values[v];
        }
        return MPB_OK;
    }
    if (other) {
        mpb__set_err(err, errlen, "group_state '%.*s' is for group '%.*s', not "
                     "'%.*s'", NAME_SHOWN, name, NAME_SHOWN, other->group,
                     NAME_SHOWN, G->name);
        return MPB_EINVAL;
    }
    char have[256] = "";
    size_t used = 0;
    for (int k = 0; k < s->raw.num_states && used < sizeof have; k++)
        if (strcmp(s->states[k].group, G->name) == 0)
            used += (size_t)snprintf(have + used, sizeof have - used, "%s%s",
                                     used ? ", " : "", s->states[k].name);
    mpb__set_err(err, errlen, "group '%.*s' has no group_state '%.*s' (%s%s)",
                 NAME_SHOWN, G->name, NAME_SHOWN, name,
                 used ? "it has " : "it has none", have);
    return MPB_ENOTFOUND;
}

int mpb_srdf_num_virtual_joints(const mpb_srdf *s)
{
    return s ? s->raw.num_vjoints : 0;
}

const mpb_srdf_virtual_joint *mpb_srdf_get_virtual_joint(const mpb_srdf *s,
                                                         int i)
{
    return s && i >= 0 && i < s->raw.num_vjoints ? &s->vjoints[i] : NULL;
}

int mpb_srdf_num_passive_joints(const mpb_srdf *s)
{
    return s ? s->raw.num_passive : 0;
}

const char *mpb_srdf_passive_joint(const mpb_srdf *s, int i, int *line)
{
    if (!s || i < 0 || i >= s->raw.num_passive)
        return NULL;
    if (line)
        *line = s->raw.passive[i].line;
    return s->raw.passive[i].name;
}

int mpb_srdf_num_end_effectors(const mpb_srdf *s)
{
    return s ? s->raw.num_eefs : 0;
}

const mpb_srdf_end_effector *mpb_srdf_get_end_effector(const mpb_srdf *s,
                                                       int i)
{
    return s && i >= 0 && i < s->raw.num_eefs ? &s->eefs[i] : NULL;
}
