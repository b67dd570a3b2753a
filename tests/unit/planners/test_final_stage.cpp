// test_final_stage.cpp - mpb-planner-ompl's last check before it answers
// (planners/ompl/final_stage.h): a stage that passes a coarse motion check
// but fails at the verifier's step is dropped, and the answer ends with
// the last stage that passes, as mpbenchd would judge it.
//
// The planar world of test_verify.c: two unit links of radius 0.05 from
// the origin, j1 in [-3, 3], j2 in [-2.5, 2.5], and a circle of radius
// 0.1 at (1.5, 0). With j2 = 0 the arm collides iff |j1| <= 0.1002; for
// j1 in [-2, -0.5] and [0.5, 2] it is free.
#include <cstdio>
#include <string>
#include <vector>

#include "final_stage.h"
#include "mpbench/mpbench.h"

namespace {

int failures = 0;

void expect(bool ok, const char *what)
{
    std::printf("%s - %s\n", ok ? "ok" : "not ok", what);
    if (!ok)
        failures++;
}

}  // namespace

int main()
{
    mpb_world *w = nullptr;
    char err[200];
    if (mpb_world_open("planar", "link_radius 0.05\njoint j1 -3 3 1\njoint j2 -2.5 2.5 1\n",
                       "planar", "circle 1.5 0 0.1\n", &w, err, sizeof err) != MPB_OK) {
        std::printf("not ok - mpb_world_open: %s\n", err);
        return 1;
    }
    // Free at both ends, through the circle in between (j1 = 0).
    const std::vector<double> through = {-0.5, 0, 0.5, 0};
    const std::vector<double> around = {-1, 0, -2, 0, -1.5, 0};
    const std::vector<double> short_cut = {-1, 0, -1.5, 0};
    std::string why;

    // Sampled (verification: sampled), a step of 2 rad checks the ends
    // alone; certified, the default, proves or refuses the whole segment.
    mpb_world_set_verification(w, MPB_VERIFY_SAMPLED);
    expect(mpb_ompl::stage_valid(w, through, 2, 2.0, nullptr),
           "a segment checked at its ends alone (step 2 rad) passes the circle unseen");
    mpb_world_set_verification(w, MPB_VERIFY_CERTIFIED);
    expect(!mpb_ompl::stage_valid(w, through, 2, 2.0, nullptr),
           "... certified, whatever the step, it collides");
    expect(!mpb_ompl::stage_valid(w, through, 2, 0.01, &why),
           "... at the verifier's step (0.01 rad) it collides");
    expect(why.find("segment 0 collides") != std::string::npos,
           "... and the reason is the verifier's own line");
    expect(mpb_ompl::stage_valid(w, around, 2, 0.01, nullptr), "a path that keeps away is valid");
    expect(!mpb_ompl::stage_valid(w, {-1, 0, -3.5, 0}, 2, 0.01, nullptr),
           "a waypoint past a joint limit is not");

    const std::vector<std::string> names = {"raw", "shortcut", "smoothed"};
    std::string dropped;
    int last = mpb_ompl::last_valid_stage(w, {around, short_cut, through}, names, 2, 0.01,
                                          &dropped);
    expect(last == 1, "a smoothed stage through the circle: the answer ends with the shortcut");
    expect(dropped.find("smoothed: segment 0 collides") == 0,
           "... and the dropped stage is named with its reason");

    dropped.clear();
    last = mpb_ompl::last_valid_stage(w, {around, through, through}, names, 2, 0.01, &dropped);
    expect(last == 0, "both simplified stages invalid: the answer ends with the raw path");
    expect(dropped.find("smoothed") != std::string::npos &&
               dropped.find("shortcut") != std::string::npos,
           "... both named");

    dropped.clear();
    last = mpb_ompl::last_valid_stage(w, {around, short_cut, around}, names, 2, 0.01, &dropped);
    expect(last == 2 && dropped.empty(), "all valid: all are sent, none named");

    last = mpb_ompl::last_valid_stage(w, {through}, names, 2, 0.01, nullptr);
    expect(last == -1, "no valid stage: -1");

    mpb_world_close(w);
    return failures == 0 ? 0 : 1;
}
