#!/bin/sh
# An experiment whose scene names a point cloud (a wall of points, as a
# 2 cm octree) runs with tools/run_benchmark.sh: the real daemon, OMPL's
# planner and the verifier all take the wall from the scene text the
# daemon made, the planner's paths go round it and are certified free
# of its cells; a path straight through it (the null planner's) is
# refused as a collision with the octree's object.
set -u
. "$MPB_SOURCE/tests/integration/lib.sh"

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
DB=$work/octree.db

mpb_ball_robot "$work/ball.urdf"
# The wall: points every 1 cm at x = 0.5, y -0.3 .. 0.3, z 0 .. 0.8.
awk 'BEGIN { n = 0; for (y = -30; y <= 30; y++) for (z = 0; z <= 80; z++) n++;
             print "ply\nformat ascii 1.0\nelement vertex " n;
             print "property float x\nproperty float y\nproperty float z\nend_header";
             for (y = -30; y <= 30; y++) for (z = 0; z <= 80; z++)
                 printf "0.5 %.2f %.2f\n", y / 100, z / 100 }' >"$work/wall.ply"
printf 'wall\n.\ncloud wall file wall.ply voxel 0.02\n' >"$work/wall.scene"
cat >"$work/wall.yaml" <<EOT
experiment: {name: octree-wall, runs: 3, time_limit: 5, seed: 1}
robot: {format: urdf, file: ball.urdf, joints: [x, y, z]}
scenes:
  - name: wall
    format: moveit-scene
    file: wall.scene
    queries:
      - {name: across, start: [0.2, 0, 0.4], goal: [0.8, 0, 0.4]}
planners:
  - {planner: ompl, algorithms: [RRTConnect]}
  - {planner: null, algorithms: [straight_line]}
EOT

out=$(MPB_BUILD=$MPB_BUILD mpb_timeout 200 sh "$MPB_SOURCE/tools/run_benchmark.sh" \
      -d "$DB" -p ompl,null -l "$work/logs" "$work/wall.yaml" 2>&1)
check "run_benchmark.sh runs the experiment" eq $? 0
check "the stored scene holds the wall's octree, not its file name" \
    eq "$(q "SELECT count(*) FROM scenes WHERE scene LIKE '%octree wall binary 0.02 %'")" 1
check "OMPL's three runs are solved and verified, round the wall" \
    eq "$(q "SELECT count(*) FROM results WHERE planner LIKE 'ompl/%' AND success = 1")" 3
check "... certified free of its cells" \
    eq "$(q "SELECT count(*) FROM stages WHERE verification = 'certified' AND valid = 1")" \
       "$(q "SELECT count(*) FROM stages WHERE valid = 1")"
check "... and some stage was checked at all" \
    test "$(q "SELECT count(*) FROM stages WHERE valid = 1")" -gt 0
check "the straight line through the wall is refused as a collision" \
    eq "$(q "SELECT count(*) FROM results WHERE planner LIKE 'null/%' AND success = 0
             AND verdict = 'collision'")" 3
[ "$(q "SELECT count(*) FROM results WHERE success = 1")" = 3 ] ||
    { printf '%s\n' "$out"; cat "$work"/logs/*.log 2>/dev/null | tail -30; }
mpb_finish
