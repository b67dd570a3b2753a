/*
 * robot_urdf.cpp - the C++ bridge to urdfdom: parses URDF text and copies
 * the model into the plain C structs of robot_urdf.h. Catches every
 * exception; urdfdom's console messages are captured, not printed.
 */
#include "model/robot_urdf.h"

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <map>
#include <mutex>
#include <new>
#include <string>
#include <vector>

#include <console_bridge/console.h>
#include <tinyxml.h>
#include <urdf_parser/urdf_parser.h>

#include "core/cxx_guard.h"
#include "core/errbuf.h"
#include "mpbench/mpbench.h"

namespace {

/* Collects what urdfdom logs while a parse runs. */
class Capture : public console_bridge::OutputHandler {
public:
    std::vector<std::string> errors;
    void log(const std::string &text, console_bridge::LogLevel level,
             const char *, int) override
    {
        if (level >= console_bridge::CONSOLE_BRIDGE_LOG_ERROR)
            errors.push_back(text);
    }
};

/*
 * console_bridge keeps one global handler: swap ours in for the parse,
 * under a lock, and put the previous one back even if the parse throws.
 */
std::mutex capture_lock;

class CaptureScope {
public:
    explicit CaptureScope(Capture *c) : guard_(capture_lock)
    {
        level_ = console_bridge::getLogLevel();
        if (level_ > console_bridge::CONSOLE_BRIDGE_LOG_ERROR)
            console_bridge::setLogLevel(console_bridge::CONSOLE_BRIDGE_LOG_ERROR);
        console_bridge::useOutputHandler(c);
    }
    ~CaptureScope()
    {
        console_bridge::restorePreviousOutputHandler();
        console_bridge::setLogLevel(level_);
    }
    CaptureScope(const CaptureScope &) = delete;
    CaptureScope &operator=(const CaptureScope &) = delete;

private:
    std::lock_guard<std::mutex> guard_;
    console_bridge::LogLevel level_;
};

/* One line: the messages joined with "; ", newlines and tabs as spaces. */
std::string join_one_line(const std::vector<std::string> &msgs)
{
    std::string s;
    for (const std::string &m : msgs) {
        if (!s.empty())
            s += "; ";
        s += m;
    }
    for (char &c : s)
        if (c == '\n' || c == '\r' || c == '\t')
            c = ' ';
    while (!s.empty() && s.back() == ' ')
        s.pop_back();
    return s;
}

char *dup_string(const std::string &s)
{
    char *p = static_cast<char *>(std::malloc(s.size() + 1));
    if (!p)
        throw std::bad_alloc();
    std::memcpy(p, s.c_str(), s.size() + 1);
    return p;
}

/*
 * Where the text first stops being UTF-8, or false if it never does.
 * TinyXML 2.6 trusts a lead byte's length: a multi-byte sequence cut
 * short by the end of the text makes it read past the terminator, so
 * nothing reaches it unchecked.
 */
bool find_bad_utf8(const char *text, int *line, int *col)
{
    const unsigned char *p = reinterpret_cast<const unsigned char *>(text);
    *line = 1;
    *col = 1;
    while (*p) {
        int len = *p < 0x80 ? 1 : (*p & 0xE0) == 0xC0 ? 2
                : (*p & 0xF0) == 0xE0 ? 3 : (*p & 0xF8) == 0xF0 ? 4 : 0;
        if (len == 0 || (len == 2 && *p < 0xC2) || (len == 4 && *p > 0xF4))
            return true;
        for (int k = 1; k < len; k++)
            if ((p[k] & 0xC0) != 0x80)     /* also stops at the terminator */
                return true;
        /* Overlong three- and four-byte forms, surrogates, past U+10FFFF. */
        if ((len == 3 && ((*p == 0xE0 && p[1] < 0xA0)
                          || (*p == 0xED && p[1] > 0x9F)))
            || (len == 4 && ((*p == 0xF0 && p[1] < 0x90)
                             || (*p == 0xF4 && p[1] > 0x8F))))
            return true;
        if (*p == '\n') {
            (*line)++;
            *col = 1;
        } else {
            (*col)++;
        }
        p += len;
    }
    return false;
}

/* Deeper than any robot needs; TinyXML recurses once per level and a
 * hundred thousand levels overflow the stack. */
const int XML_DEPTH_MAX = 1000;

/* Past "<!--...-->", "<?...?>", "<![CDATA[...]]>" or "<!...>" at p. */
const char *skip_markup(const char *p)
{
    const char *end = "";
    if (std::strncmp(p, "<!--", 4) == 0)
        end = "-->";
    else if (std::strncmp(p, "<![CDATA[", 9) == 0)
        end = "]]>";
    else if (p[1] == '?')
        end = "?>";
    const char *q = *end ? std::strstr(p, end) : std::strchr(p, '>');
    return q ? q + std::strlen(*end ? end : ">") : p + std::strlen(p);
}

/* True if elements nest deeper than XML_DEPTH_MAX, by a scan of the tags
 * (quoted attribute values may hold '>'). */
bool too_deep(const char *p)
{
    int depth = 0;
    while ((p = std::strchr(p, '<')) != nullptr) {
        if (p[1] == '!' || p[1] == '?') {
            p = skip_markup(p);
            continue;
        }
        bool closing = p[1] == '/';
        char quote = 0;
        for (p++; *p && (quote || *p != '>'); p++)
            if (*p == '"' || *p == '\'') {
                if (!quote)
                    quote = *p;
                else if (quote == *p)
                    quote = 0;
            }
        bool empty = p[-1] == '/';
        if (closing)
            depth--;
        else if (!empty && ++depth > XML_DEPTH_MAX)
            return true;
        if (!*p)
            break;
    }
    return false;
}

void to_pose(const urdf::Pose &in, mpb_pose *out)
{
    mpb_pose_identity(out);
    mpb_pose_set_quat(out, in.rotation.x, in.rotation.y, in.rotation.z,
                      in.rotation.w);
    out->t[0] = in.position.x;
    out->t[1] = in.position.y;
    out->t[2] = in.position.z;
}

mpb_joint_type to_type(int t)
{
    switch (t) {
    case urdf::Joint::REVOLUTE:   return MPB_JOINT_REVOLUTE;
    case urdf::Joint::CONTINUOUS: return MPB_JOINT_CONTINUOUS;
    case urdf::Joint::PRISMATIC:  return MPB_JOINT_PRISMATIC;
    case urdf::Joint::FLOATING:   return MPB_JOINT_FLOATING;
    case urdf::Joint::PLANAR:     return MPB_JOINT_PLANAR;
    default:                      return MPB_JOINT_FIXED;
    }
}

/* Copy one geometry; false (with err) for one urdfdom should not produce. */
bool to_geom(const urdf::Collision &c, const std::string &link,
             mpb__urdf_geom *g, char *err, size_t errlen)
{
    std::memset(g, 0, sizeof *g);
    to_pose(c.origin, &g->origin);
    g->mesh_scale[0] = g->mesh_scale[1] = g->mesh_scale[2] = 1.0;
    if (!c.name.empty())
        g->name = dup_string(c.name);
    const urdf::Geometry *geo = c.geometry.get();
    if (!geo) {
        mpb__set_err(err, errlen, "link '%.80s': collision without geometry",
                     link.c_str());
        return false;
    }
    switch (geo->type) {
    case urdf::Geometry::BOX: {
        const urdf::Box *b = static_cast<const urdf::Box *>(geo);
        g->type = MPB_SHAPE_BOX;
        g->dims[0] = b->dim.x;
        g->dims[1] = b->dim.y;
        g->dims[2] = b->dim.z;
        break;
    }
    case urdf::Geometry::SPHERE:
        g->type = MPB_SHAPE_SPHERE;
        g->dims[0] = static_cast<const urdf::Sphere *>(geo)->radius;
        break;
    case urdf::Geometry::CYLINDER: {
        const urdf::Cylinder *cy = static_cast<const urdf::Cylinder *>(geo);
        g->type = MPB_SHAPE_CYLINDER;
        g->dims[0] = cy->radius;
        g->dims[1] = cy->length;
        break;
    }
    case urdf::Geometry::MESH: {
        const urdf::Mesh *m = static_cast<const urdf::Mesh *>(geo);
        g->type = MPB_SHAPE_MESH;
        g->mesh_uri = dup_string(m->filename);
        g->mesh_scale[0] = m->scale.x;
        g->mesh_scale[1] = m->scale.y;
        g->mesh_scale[2] = m->scale.z;
        break;
    }
    default:
        mpb__set_err(err, errlen, "link '%.80s': unknown collision geometry",
                     link.c_str());
        return false;
    }
    return true;
}

/*
 * A link holds its children by shared_ptr, so joints that form a loop keep
 * urdfdom's model alive after its last owner lets go. Cutting every link's
 * children when the model is done frees it whatever its shape.
 */
struct ModelCycleBreaker {
    urdf::ModelInterfaceSharedPtr model;
    ~ModelCycleBreaker()
    {
        for (auto &kv : model->links_) {
            kv.second->child_links.clear();
            kv.second->child_joints.clear();
        }
    }
};

/*
 * urdfdom links a child under every joint that names it and does not look
 * for loops, so a link with two parent joints would be copied twice and a
 * loop would make the walk below endless. Refuse both here.
 */
bool check_tree(const urdf::ModelInterface &model, char *err, size_t errlen)
{
    std::map<std::string, std::string> parent_of;   /* child -> parent */
    std::map<std::string, std::string> joint_of;    /* child -> joint */
    for (const auto &kv : model.joints_) {
        const urdf::Joint &j = *kv.second;
        if (j.parent_link_name == j.child_link_name) {
            mpb__set_err(err, errlen, "the joints form a loop at link '%.80s'",
                         j.child_link_name.c_str());
            return false;
        }
        auto seen = joint_of.find(j.child_link_name);
        if (seen != joint_of.end()) {
            mpb__set_err(err, errlen, "link '%.80s' has two parent joints "
                         "('%.80s' and '%.80s')", j.child_link_name.c_str(),
                         seen->second.c_str(), j.name.c_str());
            return false;
        }
        joint_of[j.child_link_name] = j.name;
        parent_of[j.child_link_name] = j.parent_link_name;
    }
    /* Each link has one parent at most: walk up from each, 1 marking the
     * links on this walk, 2 those already known to reach a root. */
    std::map<std::string, int> mark;
    for (const auto &kv : parent_of) {
        std::vector<std::string> path;
        std::string at = kv.first;
        while (mark[at] == 0) {
            mark[at] = 1;
            path.push_back(at);
            auto up = parent_of.find(at);
            if (up == parent_of.end())
                break;
            at = up->second;
        }
        if (mark[at] == 1 && parent_of.count(at)) {
            mpb__set_err(err, errlen, "the joints form a loop at link '%.80s'",
                         at.c_str());
            return false;
        }
        for (const std::string &l : path)
            mark[l] = 2;
    }
    return true;
}

/* Depth-first from the root, parents before children; a stack of its own,
 * as a deep chain must not exhaust the C stack. */
void collect(const urdf::LinkConstSharedPtr &root,
             std::vector<urdf::LinkConstSharedPtr> &order,
             std::vector<int> &parents)
{
    std::vector<std::pair<urdf::LinkConstSharedPtr, int>> todo;
    todo.emplace_back(root, -1);
    while (!todo.empty()) {
        urdf::LinkConstSharedPtr link = todo.back().first;
        int parent = todo.back().second;
        todo.pop_back();
        int me = static_cast<int>(order.size());
        order.push_back(link);
        parents.push_back(parent);
        /* Reversed, so the first child comes off the stack first. */
        for (auto c = link->child_links.rbegin(); c != link->child_links.rend();
             ++c)
            todo.emplace_back(*c, me);
    }
}

int fill(const urdf::ModelInterface &model, mpb__urdf_model *m, char *err,
         size_t errlen)
{
    urdf::LinkConstSharedPtr root = model.getRoot();
    if (!root) {
        mpb__set_err(err, errlen, "no root link");
        return MPB_EPARSE;
    }
    if (!check_tree(model, err, errlen))
        return MPB_EPARSE;
    std::vector<urdf::LinkConstSharedPtr> order;
    std::vector<int> parents;
    collect(root, order, parents);

    m->name = dup_string(model.getName());
    m->links = static_cast<mpb__urdf_link *>(
        std::calloc(order.size(), sizeof *m->links));
    if (!m->links)
        throw std::bad_alloc();
    m->num_links = static_cast<int>(order.size());

    for (size_t i = 0; i < order.size(); i++) {
        const urdf::Link &ul = *order[i];
        mpb__urdf_link *l = &m->links[i];
        l->name = dup_string(ul.name);
        l->parent = parents[i];
        mpb_pose_identity(&l->origin);
        l->type = MPB_JOINT_FIXED;
        l->axis[0] = 1.0;
        if (ul.parent_joint) {
            const urdf::Joint &j = *ul.parent_joint;
            l->joint = dup_string(j.name);
            l->type = to_type(j.type);
            to_pose(j.parent_to_joint_origin_transform, &l->origin);
            l->axis[0] = j.axis.x;
            l->axis[1] = j.axis.y;
            l->axis[2] = j.axis.z;
            if (j.limits) {
                l->has_limits = 1;
                l->lo = j.limits->lower;
                l->hi = j.limits->upper;
                l->max_velocity = j.limits->velocity;
            }
            if (j.mimic) {
                l->mimic = dup_string(j.mimic->joint_name);
                l->mimic_multiplier = j.mimic->multiplier;
                l->mimic_offset = j.mimic->offset;
            }
        }
        std::vector<urdf::CollisionSharedPtr> cs = ul.collision_array;
        if (cs.empty() && ul.collision)
            cs.push_back(ul.collision);
        if (!cs.empty()) {
            l->geoms = static_cast<mpb__urdf_geom *>(
                std::calloc(cs.size(), sizeof *l->geoms));
            if (!l->geoms)
                throw std::bad_alloc();
            for (size_t k = 0; k < cs.size(); k++) {
                l->num_geoms = static_cast<int>(k + 1);
                if (!cs[k] || !to_geom(*cs[k], ul.name, &l->geoms[k], err,
                                       errlen)) {
                    if (!cs[k])
                        mpb__set_err(err, errlen, "link '%.80s': empty collision",
                                     ul.name.c_str());
                    return MPB_EPARSE;
                }
            }
        }
    }
    return MPB_OK;
}

} // namespace

/* The line and column (1-based, in characters) of position p of text. */
void place_of(const char *text, const char *p, int *line, int *col)
{
    *line = 1;
    *col = 1;
    for (const char *c = text; c < p; c++) {
        if (*c == '\n') {
            ++*line;
            *col = 1;
        } else if ((*c & 0xC0) != 0x80) {
            ++*col;
        }
    }
}

/* A <!DOCTYPE ...> with an internal subset ("[ ... ]"): TinyXML ends the
 * declaration at the subset's first '>' and then finds no root element,
 * so urdfdom would say "Could not find the 'robot' element". */
const char *internal_dtd(const char *text)
{
    const char *d = std::strstr(text, "<!DOCTYPE");
    if (!d)
        return nullptr;
    const char *open = std::strchr(d, '['), *close = std::strchr(d, '>');
    return open && !(close && close < open) ? d : nullptr;
}

/* See robot_urdf.h. */
extern "C" int mpb__xml_precheck(const char *text, char *err, size_t errlen)
{
    const char *s = text;
    while (*s == ' ' || *s == '\t' || *s == '\r' || *s == '\n')
        s++;
    if (*s == '\0') {
        mpb__set_err(err, errlen, "empty document");
        return MPB_EPARSE;
    }
    if (*s != '<') {
        mpb__set_err(err, errlen, "not XML (the text does not begin with '<')");
        return MPB_EPARSE;
    }

    int line, col;
    if (find_bad_utf8(text, &line, &col)) {
        mpb__set_err(err, errlen, "line %d, column %d: not UTF-8", line, col);
        return MPB_EPARSE;
    }

    if (too_deep(text)) {
        mpb__set_err(err, errlen, "XML nested too deeply (more than %d levels)",
                     XML_DEPTH_MAX);
        return MPB_EPARSE;
    }

    if (const char *d = internal_dtd(text)) {
        place_of(text, d, &line, &col);
        mpb__set_err(err, errlen, "line %d, column %d: a <!DOCTYPE> with an "
                     "internal DTD ([...]) is not read: remove it", line, col);
        return MPB_EPARSE;
    }
    return MPB_OK;
}

extern "C" int mpb__urdf_parse(const char *text, mpb__urdf_model *m,
                               char *err, size_t errlen)
{
    mpb__set_err(err, errlen, "%s", "");
    if (!m)
        return MPB_EINVAL;
    std::memset(m, 0, sizeof *m);
    if (!text)
        return MPB_EINVAL;
    int rc = mpb__xml_precheck(text, err, errlen);
    if (rc != MPB_OK)
        return rc;

    static const mpb__cxx_guard says = {"", "", MPB_EPARSE,
                                        "unknown exception from urdfdom",
                                        MPB_EPARSE};
    rc = mpb__cxx_guarded(err, errlen, says, [&]() -> int {
        /* urdfdom parses with TinyXML but passes on only its message;
         * parse once more ourselves for the line and column. */
        TiXmlDocument xml;
        xml.Parse(text, nullptr, TIXML_ENCODING_UTF8);
        if (xml.Error()) {
            mpb__set_err(err, errlen, "line %d, column %d: not well-formed XML: %s",
                         xml.ErrorRow(), xml.ErrorCol(), xml.ErrorDesc());
            return MPB_EPARSE;
        }
        Capture cap;
        urdf::ModelInterfaceSharedPtr model;
        {
            CaptureScope scope(&cap);
            try {
                model = urdf::parseURDF(text);
            } catch (const std::bad_alloc &) {
                throw;
            } catch (const std::exception &e) {
                cap.errors.push_back(e.what());
            }
        }
        if (!cap.errors.empty() || !model) {
            std::string msg = join_one_line(cap.errors);
            if (msg.empty())
                msg = "urdfdom could not parse it";
            /* tinyxml's own messages all begin "Error ": say it is XML. */
            if (msg.compare(0, 6, "Error ") == 0)
                msg = "not well-formed XML: " + msg;
            mpb__set_err(err, errlen, "%s", msg.c_str());
            return MPB_EPARSE;
        }
        ModelCycleBreaker breaker{model};
        return fill(*model, m, err, errlen);
    });
    if (rc != MPB_OK)
        mpb__urdf_model_clear(m);
    return rc;
}

extern "C" void mpb__urdf_model_clear(mpb__urdf_model *m)
{
    if (!m)
        return;
    for (int i = 0; i < m->num_links && m->links; i++) {
        mpb__urdf_link *l = &m->links[i];
        std::free(l->name);
        std::free(l->joint);
        std::free(l->mimic);
        for (int k = 0; k < l->num_geoms; k++) {
            std::free(l->geoms[k].mesh_uri);
            std::free(l->geoms[k].name);
        }
        std::free(l->geoms);
    }
    std::free(m->links);
    std::free(m->name);
    std::memset(m, 0, sizeof *m);
}
