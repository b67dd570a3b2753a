/*
 * srdf_tinyxml.cpp - the C++ bridge that reads an SRDF's
 * <disable_collisions> pairs with TinyXML into srdf.h's plain structs.
 * Catches every exception.
 */
#include "srdf.h"

#include <cstdlib>
#include <cstring>
#include <exception>
#include <new>

#include <tinyxml.h>

#include "errbuf.h"
#include "robot_urdf.h"
#include "mpbench/mpbench.h"

namespace {

char *dup_or_throw(const char *s)
{
    char *d = strdup(s ? s : "");
    if (!d)
        throw std::bad_alloc();
    return d;
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
    int n = 0;
    for (const TiXmlElement *e = root->FirstChildElement("disable_collisions");
         e; e = e->NextSiblingElement("disable_collisions"))
        n++;
    if (n == 0)
        return MPB_OK;
    s->pairs = static_cast<mpb__srdf_pair *>(std::calloc((size_t)n, sizeof *s->pairs));
    if (!s->pairs)
        throw std::bad_alloc();
    for (const TiXmlElement *e = root->FirstChildElement("disable_collisions");
         e; e = e->NextSiblingElement("disable_collisions")) {
        const char *a = e->Attribute("link1"), *b = e->Attribute("link2");
        if (!a || !*a || !b || !*b) {
            mpb__set_err(err, errlen, "line %d: disable_collisions has no %s",
                         e->Row(), !a || !*a ? "link1" : "link2");
            return MPB_EPARSE;
        }
        mpb__srdf_pair *p = &s->pairs[s->num_pairs++];
        p->line = e->Row();
        p->link1 = dup_or_throw(a);
        p->link2 = dup_or_throw(b);
        p->reason = dup_or_throw(e->Attribute("reason"));
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
    int rc;
    try {
        rc = parse(text, s, err, errlen);
    } catch (const std::bad_alloc &) {
        mpb__set_err(err, errlen, "out of memory");
        rc = MPB_ENOMEM;
    } catch (const std::exception &e) {
        mpb__set_err(err, errlen, "%s", e.what());
        rc = MPB_EPARSE;
    } catch (...) {
        mpb__set_err(err, errlen, "unknown exception while reading the SRDF");
        rc = MPB_EPARSE;
    }
    if (rc != MPB_OK)
        mpb__srdf_clear(s);
    return rc;
}

extern "C" void mpb__srdf_clear(mpb__srdf *s)
{
    if (!s)
        return;
    for (int i = 0; i < s->num_pairs; i++) {
        std::free(s->pairs[i].link1);
        std::free(s->pairs[i].link2);
        std::free(s->pairs[i].reason);
    }
    std::free(s->pairs);
    std::memset(s, 0, sizeof *s);
}
