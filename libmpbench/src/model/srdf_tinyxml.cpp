/*
 * srdf_tinyxml.cpp - the C++ bridge that reads an SRDF with TinyXML into
 * srdf_xml.h's plain structs: groups, group states, virtual and passive
 * joints, end effectors, disabled collision pairs. Catches every
 * exception.
 */
#include "model/srdf_xml.h"

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <new>
#include <string>
#include <vector>

#include <tinyxml.h>

#include "core/cxx_guard.h"
#include "core/errbuf.h"
#include "model/robot_urdf.h"
#include "mpbench/mpbench.h"

namespace {

/* A fault in the SRDF: the message is already in err. */
struct Refused {};

char *dup_or_throw(const char *s)
{
    char *d = strdup(s ? s : "");
    if (!d)
        throw std::bad_alloc();
    return d;
}

template <typename T>
T *alloc_array(size_t n)
{
    T *a = static_cast<T *>(std::calloc(n > 0 ? n : 1, sizeof(T)));
    if (!a)
        throw std::bad_alloc();
    return a;
}

class Reader {
public:
    Reader(mpb__srdf *s, char *err, size_t errlen)
        : s_(s), err_(err), errlen_(errlen) {}

    /* The attribute, which must be there and not empty. */
    const char *need(const TiXmlElement *e, const char *attr)
    {
        const char *v = e->Attribute(attr);
        if (!v || !*v) {
            mpb__set_err(err_, errlen_, "line %d: %s has no %s", e->Row(),
                         e->Value(), attr);
            throw Refused();
        }
        return v;
    }

    void group(const TiXmlElement *g)
    {
        const char *name = need(g, "name");
        int prior = mpb__srdf_find_group(s_, name);
        if (prior >= 0) {
            mpb__set_err(err_, errlen_, "line %d: group '%.80s' is defined "
                         "twice (first at line %d)", g->Row(), name,
                         s_->groups[prior].line);
            throw Refused();
        }
        mpb__srdf_group *G = &s_->groups[s_->num_groups++];
        G->name = dup_or_throw(name);
        G->line = g->Row();
        size_t n = 0;
        for (const TiXmlElement *e = g->FirstChildElement(); e;
             e = e->NextSiblingElement())
            n++;
        G->elems = alloc_array<mpb__srdf_elem>(n);
        for (const TiXmlElement *e = g->FirstChildElement(); e;
             e = e->NextSiblingElement()) {
            std::string v = e->Value();
            mpb__srdf_elem el = {};
            el.line = e->Row();
            if (v == "joint") {
                el.kind = MPB__SRDF_JOINT;
                el.name = dup_or_throw(need(e, "name"));
            } else if (v == "link") {
                el.kind = MPB__SRDF_LINK;
                el.name = dup_or_throw(need(e, "name"));
            } else if (v == "chain") {
                el.kind = MPB__SRDF_CHAIN;
                const char *base = need(e, "base_link"), *tip = need(e, "tip_link");
                el.name = dup_or_throw(base);
                el.tip = dup_or_throw(tip);
            } else if (v == "group") {
                el.kind = MPB__SRDF_GROUP;
                el.name = dup_or_throw(need(e, "name"));
            } else {
                continue;       /* MoveIt reads only these four */
            }
            G->elems[G->num_elems++] = el;
        }
    }

    void state(const TiXmlElement *e)
    {
        const char *name = need(e, "name"), *group = need(e, "group");
        for (int i = 0; i < s_->num_states; i++)
            if (std::strcmp(s_->states[i].name, name) == 0 &&
                std::strcmp(s_->states[i].group, group) == 0) {
                mpb__set_err(err_, errlen_, "line %d: group_state '%.80s' of "
                             "group '%.80s' is defined twice (first at line %d)",
                             e->Row(), name, group, s_->states[i].line);
                throw Refused();
            }
        mpb__srdf_state *S = &s_->states[s_->num_states++];
        S->name = dup_or_throw(name);
        S->group = dup_or_throw(group);
        S->line = e->Row();
        size_t n = 0;
        for (const TiXmlElement *j = e->FirstChildElement("joint"); j;
             j = j->NextSiblingElement("joint"))
            n++;
        S->values = alloc_array<mpb__srdf_value>(n);
        for (const TiXmlElement *j = e->FirstChildElement("joint"); j;
             j = j->NextSiblingElement("joint")) {
            const char *jn = need(j, "name"), *val = need(j, "value");
            char *end = nullptr;
            double v = std::strtod(val, &end);
            while (end && (*end == ' ' || *end == '\t'))
                end++;
            if (end == val || !end || *end || !std::isfinite(v)) {
                mpb__set_err(err_, errlen_, "line %d: group_state '%.80s': "
                             "joint '%.80s' has value '%.40s', not a number "
                             "(a multi-variable joint's values are not read)",
                             j->Row(), name, jn, val);
                throw Refused();
            }
            for (int k = 0; k < S->num_values; k++)
                if (std::strcmp(S->values[k].joint, jn) == 0) {
                    mpb__set_err(err_, errlen_, "line %d: group_state '%.80s' "
                                 "gives joint '%.80s' twice", j->Row(), name, jn);
                    throw Refused();
                }
            mpb__srdf_value *V = &S->values[S->num_values++];
            V->joint = dup_or_throw(jn);
            V->value = v;
            V->line = j->Row();
        }
    }

    void vjoint(const TiXmlElement *e)
    {
        const char *name = need(e, "name"), *type = need(e, "type");
        const char *parent = need(e, "parent_frame"), *child = need(e, "child_link");
        if (std::strcmp(type, "fixed") != 0 && std::strcmp(type, "floating") != 0 &&
            std::strcmp(type, "planar") != 0) {
            mpb__set_err(err_, errlen_, "line %d: virtual_joint '%.80s' has type "
                         "'%.40s'; it must be fixed, floating or planar",
                         e->Row(), name, type);
            throw Refused();
        }
        for (int i = 0; i < s_->num_vjoints; i++)
            if (std::strcmp(s_->vjoints[i].name, name) == 0) {
                mpb__set_err(err_, errlen_, "line %d: virtual_joint '%.80s' is "
                             "defined twice (first at line %d)", e->Row(), name,
                             s_->vjoints[i].line);
                throw Refused();
            }
        mpb__srdf_vjoint *V = &s_->vjoints[s_->num_vjoints++];
        V->name = dup_or_throw(name);
        V->type = dup_or_throw(type);
        V->parent_frame = dup_or_throw(parent);
        V->child_link = dup_or_throw(child);
        V->line = e->Row();
    }

    void passive(const TiXmlElement *e)
    {
        mpb__srdf_passive *P = &s_->passive[s_->num_passive++];
        P->name = dup_or_throw(need(e, "name"));
        P->line = e->Row();
    }

    void eef(const TiXmlElement *e)
    {
        const char *name = need(e, "name"), *group = need(e, "group");
        const char *link = need(e, "parent_link");
        const char *pg = e->Attribute("parent_group");
        mpb__srdf_eef *E = &s_->eefs[s_->num_eefs++];
        E->name = dup_or_throw(name);
        E->group = dup_or_throw(group);
        E->parent_link = dup_or_throw(link);
        E->parent_group = pg && *pg ? dup_or_throw(pg) : nullptr;
        E->line = e->Row();
    }

    void pair(const TiXmlElement *e)
    {
        const char *a = need(e, "link1"), *b = need(e, "link2");
        mpb__srdf_pair *p = &s_->pairs[s_->num_pairs++];
        p->line = e->Row();
        p->link1 = dup_or_throw(a);
        p->link2 = dup_or_throw(b);
        p->reason = dup_or_throw(e->Attribute("reason"));
    }

    /* Every <group name=> inside a group names a group; no group may
     * contain itself, directly or through others. */
    void check_subgroups()
    {
        for (int g = 0; g < s_->num_groups; g++)
            for (int k = 0; k < s_->groups[g].num_elems; k++) {
                const mpb__srdf_elem *el = &s_->groups[g].elems[k];
                if (el->kind == MPB__SRDF_GROUP &&
                    mpb__srdf_find_group(s_, el->name) < 0) {
                    mpb__set_err(err_, errlen_, "line %d: group '%.80s' names "
                                 "subgroup '%.80s', which is no group of the "
                                 "SRDF", el->line, s_->groups[g].name, el->name);
                    throw Refused();
                }
            }
        /* Depth-first from each group; a group met again on the current
         * path is a cycle. */
        std::vector<int> mark(static_cast<size_t>(s_->num_groups), 0);
        for (int g = 0; g < s_->num_groups; g++) {
            std::vector<int> path;
            visit(g, mark, path);
        }
    }

private:
    void visit(int g, std::vector<int> &mark, std::vector<int> &path)
    {
        if (mark[static_cast<size_t>(g)] == 2)
            return;
        path.push_back(g);
        mark[static_cast<size_t>(g)] = 1;
        const mpb__srdf_group *G = &s_->groups[g];
        for (int k = 0; k < G->num_elems; k++) {
            if (G->elems[k].kind != MPB__SRDF_GROUP)
                continue;
            int sub = mpb__srdf_find_group(s_, G->elems[k].name);
            if (mark[static_cast<size_t>(sub)] == 1) {
                std::string cycle;
                size_t at = 0;
                while (path[at] != sub)
                    at++;
                for (size_t i = at; i < path.size(); i++)
                    cycle += std::string(s_->groups[path[i]].name) + " -> ";
                cycle += s_->groups[sub].name;
                mpb__set_err(err_, errlen_, "line %d: group '%.80s' contains "
                             "itself through its subgroups (%.200s)",
                             G->elems[k].line, s_->groups[sub].name,
                             cycle.c_str());
                throw Refused();
            }
            visit(sub, mark, path);
        }
        mark[static_cast<size_t>(g)] = 2;
        path.pop_back();
    }

    mpb__srdf *s_;
    char *err_;
    size_t errlen_;
};

size_t count(const TiXmlElement *root, const char *name)
{
    size_t n = 0;
    for (const TiXmlElement *e = root->FirstChildElement(name); e;
         e = e->NextSiblingElement(name))
        n++;
    return n;
}

int parse(const char *text, mpb__srdf *s, char *err, size_t errlen)
{
    int rc = mpb__xml_precheck(text, err, errlen);
    if (rc != MPB_OK)
        return rc;
    TiXmlDocument xml;
    xml.Parse(text, nullptr, TIXML_ENCODING_UTF8);
    if (xml.Error()) {
        mpb__set_err(err, errlen, "line %d, column %d: not well-formed XML: %s",
                     xml.ErrorRow(), xml.ErrorCol(), xml.ErrorDesc());
        return MPB_EPARSE;
    }
    const TiXmlElement *root = xml.RootElement();
    if (!root) {
        mpb__set_err(err, errlen, "no root element");
        return MPB_EPARSE;
    }
    if (std::strcmp(root->Value(), "robot") != 0) {
        mpb__set_err(err, errlen, "line %d: the root element is <%.40s>, not "
                     "<robot>", root->Row(), root->Value());
        return MPB_EPARSE;
    }
    s->robot_name = dup_or_throw(root->Attribute("name"));
    s->pairs = alloc_array<mpb__srdf_pair>(count(root, "disable_collisions"));
    s->groups = alloc_array<mpb__srdf_group>(count(root, "group"));
    s->states = alloc_array<mpb__srdf_state>(count(root, "group_state"));
    s->vjoints = alloc_array<mpb__srdf_vjoint>(count(root, "virtual_joint"));
    s->passive = alloc_array<mpb__srdf_passive>(count(root, "passive_joint"));
    s->eefs = alloc_array<mpb__srdf_eef>(count(root, "end_effector"));
    Reader r(s, err, errlen);
    try {
        for (const TiXmlElement *e = root->FirstChildElement(); e;
             e = e->NextSiblingElement()) {
            std::string v = e->Value();
            if (v == "group")
                r.group(e);
            else if (v == "group_state")
                r.state(e);
            else if (v == "virtual_joint")
                r.vjoint(e);
            else if (v == "passive_joint")
                r.passive(e);
            else if (v == "end_effector")
                r.eef(e);
            else if (v == "disable_collisions")
                r.pair(e);
        }
        r.check_subgroups();
    } catch (const Refused &) {
        return MPB_EPARSE;
    }
    return MPB_OK;
}

} // namespace

extern "C" int mpb__srdf_parse(const char *text, mpb__srdf *s, char *err,
                               size_t errlen)
{
    mpb__set_err(err, errlen, "%s", "");
    if (!s)
        return MPB_EINVAL;
    std::memset(s, 0, sizeof *s);
    if (!text)
        return MPB_EINVAL;
    static const mpb__cxx_guard says = {
        "", "", MPB_EPARSE, "unknown exception while reading the SRDF",
        MPB_EPARSE};
    int rc = mpb__cxx_guarded(err, errlen, says,
                              [&] { return parse(text, s, err, errlen); });
    if (rc != MPB_OK)
        mpb__srdf_clear(s);
    return rc;
}

extern "C" int mpb__srdf_find_group(const mpb__srdf *s, const char *name)
{
    for (int i = 0; s && name && i < s->num_groups; i++)
        if (s->groups[i].name && std::strcmp(s->groups[i].name, name) == 0)
            return i;
    return -1;
}

extern "C" void mpb__srdf_clear(mpb__srdf *s)
{
    if (!s)
        return;
    std::free(s->robot_name);
    for (int i = 0; i < s->num_pairs; i++) {
        std::free(s->pairs[i].link1);
        std::free(s->pairs[i].link2);
        std::free(s->pairs[i].reason);
    }
    std::free(s->pairs);
    for (int i = 0; i < s->num_groups; i++) {
        for (int k = 0; k < s->groups[i].num_elems; k++) {
            std::free(s->groups[i].elems[k].name);
            std::free(s->groups[i].elems[k].tip);
        }
        std::free(s->groups[i].elems);
        std::free(s->groups[i].name);
    }
    std::free(s->groups);
    for (int i = 0; i < s->num_states; i++) {
        for (int k = 0; k < s->states[i].num_values; k++)
            std::free(s->states[i].values[k].joint);
        std::free(s->states[i].values);
        std::free(s->states[i].name);
        std::free(s->states[i].group);
    }
    std::free(s->states);
    for (int i = 0; i < s->num_vjoints; i++) {
        std::free(s->vjoints[i].name);
        std::free(s->vjoints[i].type);
        std::free(s->vjoints[i].parent_frame);
        std::free(s->vjoints[i].child_link);
    }
    std::free(s->vjoints);
    for (int i = 0; i < s->num_passive; i++)
        std::free(s->passive[i].name);
    std::free(s->passive);
    for (int i = 0; i < s->num_eefs; i++) {
        std::free(s->eefs[i].name);
        std::free(s->eefs[i].group);
        std::free(s->eefs[i].parent_link);
        std::free(s->eefs[i].parent_group);
    }
    std::free(s->eefs);
    std::memset(s, 0, sizeof *s);
}
