#!/bin/sh
# A URDF robot's meshes as mpbenchd finds them: in the folders of
# MPB_MESH_PATH, of ROS_PACKAGE_PATH, then beside the URDF; not found, one
# line naming the variables and the folders tried.
set -u
. "$MPB_SOURCE/tests/integration/lib.sh"

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
daemon=$MPB_BUILD/daemon/mpbenchd
data=$MPB_SOURCE/tests/support/data/meshes

# experiment FILE URDF
experiment() {
    cat >"$1" <<EOT
experiment: {name: meshes, runs: 1, time_limit: 1}
robot: {format: urdf, file: $2, joints: [j]}
scenes:
  - name: empty
    format: moveit-scene
    text: "(empty)\n.\n"
    queries:
      - {name: q, start: [0], goal: [0.5]}
planners:
  - {planner: null, algorithms: [straight_line]}
EOT
}
unset MPB_MESH_PATH ROS_PACKAGE_PATH

# Beside the URDF (mesh_pkg/ is in its folder).
experiment "$work/beside.yaml" "$data/mesh_arm.urdf"
check "a package beside the URDF is found" \
    sh -c "'$daemon' --check '$work/beside.yaml' >/dev/null 2>&1"

# The URDF elsewhere: found through either variable, else named.
cp "$data/mesh_arm.urdf" "$work/arm.urdf"
experiment "$work/apart.yaml" "$work/arm.urdf"
check "through MPB_MESH_PATH" \
    sh -c "MPB_MESH_PATH=/nowhere:$data '$daemon' --check '$work/apart.yaml' >/dev/null 2>&1"
check "through ROS_PACKAGE_PATH, a folder that is the package" \
    sh -c "ROS_PACKAGE_PATH=$data/mesh_pkg '$daemon' --check '$work/apart.yaml' >/dev/null 2>&1"
out=$(MPB_MESH_PATH=/nowhere "$daemon" --check "$work/apart.yaml" 2>&1)
check "not found: refused" test $? -ne 0
check "... in one line" eq "$(printf '%s\n' "$out" | wc -l)" 1
check "... naming the mesh, the variables and the folders" sh -c \
    "printf '%s' \"\$1\" | grep -q \"mesh 'package://mesh_pkg/meshes/cube.stl': not found .*looked in MPB_MESH_PATH (/nowhere) and ROS_PACKAGE_PATH (not set) and the URDF's folder ($work/)\"" _ "$out"

mpb_finish
