// world_cache.cpp - the worlds mpb-planner-ompl keeps between requests.
#include <cstring>

#include "world_cache.h"

namespace mpb_ompl {
namespace {

void close(CachedWorld &c)
{
    mpb_world_close(c.world);
    mpb_robot_close(c.robot);
}

// A hash names the text; without one, the text names itself.
std::string part(const char *format, const char *hash, const char *text)
{
    std::string s = format != nullptr ? format : "";
    s += ':';
    if (hash != nullptr && hash[0] != '\0')
        s += hash;
    else
        s += std::string("text:") + (text != nullptr ? text : "");
    return s;
}

}  // namespace

// The robot of a urdf world in the request's joint order, for IK and goal
// regions. The world keeps its own robot private (its format may have
// none); parsing the URDF once more per cached world costs milliseconds.
mpb_robot *cached_robot(CachedWorld &c, const mpb_plan_request_t *req, std::string &err)
{
    if (c.robot != nullptr)
        return c.robot;
    if (req->robot_format == nullptr || std::strcmp(req->robot_format, "urdf") != 0) {
        err = "pose-region goals need a urdf robot";
        return nullptr;
    }
    char msg[256] = "";
    if (mpb_robot_open_urdf_joints(req->robot, req->joint_names, req->num_joints,
                                   &c.robot, msg, sizeof msg) != MPB_OK ||
        mpb_request_hold(req, nullptr, c.robot, msg, sizeof msg) != MPB_OK) {
        err = msg;
        return nullptr;
    }
    return c.robot;
}

WorldCache::~WorldCache()
{
    for (CachedWorld &c : list_)
        close(c);
}

CachedWorld *WorldCache::get(const mpb_plan_request_t *req, const mpb_solve_limits *lim,
                             std::string &err, bool *built)
{
    *built = false;
    std::string key = part(req->robot_format, req->robot_hash, req->robot) +
                      '\n' + part(req->scene_format, req->scene_hash, req->scene);
    for (int j = 0; j < req->num_joints; j++)
        key += std::string("\n") + req->joint_names[j];
    for (auto it = list_.begin(); it != list_.end(); ++it)
        if (it->key == key) {
            list_.splice(list_.begin(), list_, it);
            return &list_.front();
        }
    mpb_world *w = nullptr;
    char msg[256] = "";
    mpb_solve_setting_up(lim);
    int rc = mpb_world_open_group(req->robot_format, req->robot,
                                  req->scene_format, req->scene,
                                  req->joint_names, req->num_joints, &w,
                                  msg, sizeof msg);
    mpb_solve_planning(lim);
    if (rc != MPB_OK || w == nullptr) {
        err = msg[0] != '\0' ? msg : mpb_strerror(rc);
        return nullptr;
    }
    *built = true;
    list_.push_front(CachedWorld{key, w, nullptr});
    while (list_.size() > kSize) {
        close(list_.back());
        list_.pop_back();
    }
    return &list_.front();
}

}  // namespace mpb_ompl
