// final_stage.cpp - each stage checked at the verifier's step before it is
// sent (final_stage.h).

#include "final_stage.h"

namespace mpb_ompl {

bool stage_valid(mpb_world *w, const std::vector<double> &path, int num_joints,
                 double resolution, std::string *why)
{
    if (num_joints <= 0 || path.empty() || path.size() % static_cast<size_t>(num_joints) != 0) {
        if (why != nullptr)
            *why = "no waypoints";
        return false;
    }
    const int n = static_cast<int>(path.size() / static_cast<size_t>(num_joints));
    // Start and goal are the path's own ends: only what lies between them
    // is in question here (the planner's goal test stands for the goal).
    mpb_goal goal{};
    goal.kind = MPB_GOAL_JOINTS;
    goal.joints = path.data() + static_cast<size_t>(n - 1) * static_cast<size_t>(num_joints);
    goal.joint_tolerance = 0.0;
    mpb_verdict v{};
    int rc = mpb_verify_path(w, path.data(), 0.0, &goal, path.data(), n, num_joints,
                             resolution, &v);
    if (rc == MPB_OK && v.code == MPB_VERDICT_VALID)
        return true;
    if (why != nullptr)
        *why = v.detail[0] != '\0' ? v.detail : mpb_verdict_name(v.code);
    return false;
}

int last_valid_stage(mpb_world *w, const std::vector<std::vector<double>> &stages,
                     const std::vector<std::string> &names, int num_joints,
                     double resolution, std::string *dropped)
{
    for (int i = static_cast<int>(stages.size()) - 1; i >= 0; i--) {
        std::string why;
        if (stage_valid(w, stages[static_cast<size_t>(i)], num_joints, resolution, &why))
            return i;
        if (dropped != nullptr) {
            std::string name = static_cast<size_t>(i) < names.size()
                                   ? names[static_cast<size_t>(i)] : std::to_string(i);
            *dropped += (dropped->empty() ? "" : "; ") + name + ": " + why;
        }
    }
    return -1;
}

}  // namespace mpb_ompl
