#!/bin/sh
# bench/view.sh - how `mpb view` copes with large inputs (docs/performance.md):
# a PR2 run of 10,000 waypoints in a scene of 1,000 objects (boxes,
# cylinders, spheres and small meshes around the kitchen), written with
# `mpb view` and opened in headless Chromium (tests/integration/
# view_check.js, which also checks the page). Prints the times and sizes;
# nothing here is pass/fail on time.
#
#   bench/view.sh [BUILD]     (default build/; root, for the network namespace)
set -eu
src=$(cd "$(dirname "$0")/.." && pwd)
. "$src/tools/usage.sh"
mpb_no_options "$@"
build=$(cd "${1:-$src/build}" && pwd)
if [ -z "${MPB_IN_NETNS:-}" ]; then
    export MPB_IN_NETNS=1
    exec unshare -n sh "$0" "$build"
fi
ip link set lo up
ip route add 224.0.0.0/4 dev lo
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
export MPB_WEB_MODULES="$src/.cache/web/node_modules"

# A real run first (the null planner's straight line), then the database
# made large: the scene with 1,000 objects more, the stage of 10,000
# waypoints along the same line, its verdict moved to the segment where
# the line's collision now is.
joints="[r_shoulder_pan_joint, r_shoulder_lift_joint, r_upper_arm_roll_joint, r_elbow_flex_joint, r_forearm_roll_joint, r_wrist_flex_joint, r_wrist_roll_joint]"
cat >"$work/exp.yaml" <<EOF
experiment: {name: view-bench, runs: 1, time_limit: 5}
robot: {format: urdf, file: $src/scenes/robots/pr2_right_arm.urdf, joints: $joints}
scenes:
  - {name: kitchen, format: moveit-scene, file: $src/scenes/paper/kitchen.scene,
     queries: [{name: q, start: [0, 0, 0, -1, 0, -1, 0], goal: [-1.2, 1.1, -1.5, -1.9, 0, -0.6, 0], tolerance: 0.01}]}
planners:
  - {planner: null, algorithms: [straight_line]}
EOF
"$build/planners/null/mpb-planner-null" >/dev/null 2>&1 &
planner=$!
"$build/daemon/mpbenchd" -d "$work/big.db" "$work/exp.yaml" >/dev/null 2>&1
kill $planner
python3 - "$work/big.db" <<'EOF'
import math, random, sqlite3, struct, sys
db = sqlite3.connect(sys.argv[1])
random.seed(29)
(scene,) = db.execute("SELECT scene FROM scenes").fetchone()
body = scene.rstrip().rstrip(".").rstrip()
objects = []
for k in range(1000):
    # a ring of shelves' worth of clutter, 2 to 6 m from the robot
    r, a = random.uniform(2, 6), random.uniform(0, 2 * math.pi)
    x, y, z = r * math.cos(a), r * math.sin(a), random.uniform(0, 2)
    kind = k % 4
    shape = ["box 0.2 0.3 0.4", "cylinder 0.1 0.5", "sphere 0.15",
             "mesh 4 4\n0 0 0\n0.3 0 0\n0 0.3 0\n0 0 0.3\n0 1 2\n0 1 3\n0 2 3\n1 2 3"][kind]
    objects.append("* clutter %d\n%.3f %.3f %.3f\n0 0 0 1\n1\n%s\n0 0 0\n0 0 0 1\n0.6 0.6 0.7 1\n0"
                   % (k, x, y, z, shape))
db.execute("UPDATE scenes SET scene = ?", (body + "\n" + "\n".join(objects) + "\n.\n",))
a = [0, 0, 0, -1, 0, -1, 0]
b = [-1.2, 1.1, -1.5, -1.9, 0, -0.6, 0]
n = 10000
wp = []
for i in range(n):
    wp += [a[j] + i / (n - 1) * (b[j] - a[j]) for j in range(7)]
(detail,) = db.execute("SELECT verdict_detail FROM stages").fetchone()
at = float(detail.split("s=")[1].split()[0])
seg = int(at * (n - 1))
db.execute("UPDATE stages SET num_waypoints = ?, waypoints = ?, verdict_segment = ?,"
           " verdict_detail = ?", (n, struct.pack("<%dd" % len(wp), *wp), seg,
           "segment %d collides (the line of %s)" % (seg, detail)))
db.commit()
EOF
detail=$(sqlite3 "$work/big.db" "SELECT verdict_detail FROM stages")
t0=$(date +%s.%N)
"$build/tools/mpb" view "$work/big.db" 1 -o "$work/big.html" >/dev/null
t1=$(date +%s.%N)
size=$(wc -c <"$work/big.html")
echo "mpb view: 10,000 waypoints, 1,000 objects more: $(awk "BEGIN { printf \"%.2f\", $t1 - $t0 }") s, $((size / 1024)) KiB"
node "$src/tests/integration/view_check.js" "$work/big.html" "$detail" "$work/big.png"
