#!/bin/sh
# mpb verify --compare, mpb view and mpb report's links on the thin-wall
# case of docs/verification.md: a planar arm with zero-radius links
# swings its shoulder from -0.5045 to +0.5045 rad through a 2 mm wall
# (tests/unit/verify/test_certify.c), which the sampled check (0.01 rad) steps
# over. Stored sampled (verification: sampled), the run is valid;
# compared, the certified check newly refuses it, with its colliding
# configuration; a thick wall is a collision both ways (they agree);
# a graze 2e-6 m from a circle cannot be proved and falls back to
# sampling. Stored certified, mpb view shows the configuration the
# proof found (the verdict's s, exactly), and the HTML report links the
# refused run to that view page. The databases are only read.
set -u
. "$MPB_SOURCE/tests/integration/lib.sh"
mpb_enter_netns "$0" "$@"

work=$(mktemp -d)
trap 'mpb_stop_all; rm -rf "$work"' EXIT
mpb=$MPB_BUILD/tools/mpb
daemon=$MPB_BUILD/daemon/mpbenchd

cat >"$work/arm.robot" <<EOT
base 0 0
link_radius 0
joint shoulder -3.14159 3.14159 0.5
joint elbow    -2.8 2.8 0.4
joint wrist    -2.8 2.8 0.3
EOT
# $1: the experiment's name, $2 more of its fields
experiment() {
    cat <<EOT
experiment: {name: $1, runs: 1, time_limit: 5$2}
robot: {format: planar, file: $work/arm.robot}
scenes:
  - name: thin
    format: planar
    text: "box 0.85 0 0.25 0.001\n"
    queries:
      - {name: swing, start: [-0.5045, 0, 0], goal: [0.5045, 0, 0], tolerance: 0.001}
      - {name: away, start: [2.0, 0, 0], goal: [2.5, 0, 0], tolerance: 0.001}
  - name: thick
    format: planar
    text: "box 0.85 0 0.25 0.1\n"
    queries:
      - {name: swing, start: [-0.5045, 0, 0], goal: [0.5045, 0, 0], tolerance: 0.001}
  - name: graze
    format: planar
    text: "circle 1.300002 0 0.1\n"
    queries:
      - {name: swing, start: [-0.5045, 0, 0], goal: [0.5045, 0, 0], tolerance: 0.001}
planners:
  - {planner: null, algorithms: [straight_line]}
EOT
}
experiment sampled ", verification: sampled" >"$work/sampled.yaml"
experiment certified "" >"$work/certified.yaml"
mpb_spawn "$work/null.log" "$MPB_BUILD/planners/null/mpb-planner-null"
SDB=$work/sampled.db CDB=$work/certified.db
mpb_timeout 60 "$daemon" -d "$SDB" "$work/sampled.yaml" >"$work/sdaemon.log" 2>&1
check "the sampled experiment completes" eq $? 0
mpb_timeout 60 "$daemon" -d "$CDB" "$work/certified.yaml" >"$work/cdaemon.log" 2>&1
check "the certified experiment completes" eq $? 0
thin="SELECT r.id FROM runs r JOIN queries q ON q.id = r.query_id JOIN scenes s ON s.id = q.scene_id WHERE s.name = 'thin' AND q.name = 'swing'"
check "stored sampled, the swing through the 2 mm wall is valid" test \
    "$(sqlite3 "$SDB" "SELECT verdict || ' ' || verification FROM stages WHERE run_id = ($thin)")" = "valid sampled"
check "stored certified, it is a collision" test \
    "$(sqlite3 "$CDB" "SELECT verdict || ' ' || verification FROM stages WHERE run_id = ($thin)")" = "collision certified"

sum=$(md5sum <"$SDB")
out=$("$mpb" verify --compare "$SDB" 2>"$work/err")
status=$?
printf '%s\n' "$out" | sed 's/^/    /'
check "compared: exit 0 (no sampled collision passes the certified check)" eq $status 0
check "... nothing on stderr" test ! -s "$work/err"
check "... the counts" sh -c "printf '%s\n' \"\$1\" | tail -1 | grep -q '^experiment 1: 4 runs with stages, 4 stages verified both ways; 3 agree; 0 sampled collisions the certified check passes; 1 newly refused by the certified check; 1 fell back to sampling (CPU: certified [0-9.]* s, sampled [0-9.]* s)$'" _ "$out"
run=$(sqlite3 "$SDB" "$thin")
refused=$(printf '%s\n' "$out" | grep '^newly refused:')
check "... the newly refused stage: run, place, planner, stage, stored verdict" \
    test "${refused%%: segment*}" = "newly refused: run $run thin / swing null/straight_line stage raw (stored valid)"
# its configuration: the shoulder within 2e-3 rad of 0 (where the wall
# is), the other joints 0; what the sampled check said
s=$(printf '%s\n' "$refused" | sed -n 's/.*segment 0 at s=\([0-9.e-]*\), q = \[\([^,]*\), 0, 0\]; sampled: valid$/\1 \2/p')
check "... its segment, s and configuration" test -n "$s"
check "... the configuration is a + s (b - a), near the wall" \
    awk -v v="$s" 'BEGIN { split(v, a, " "); q = -0.5045 + a[1] * 1.009;
                           exit !(a[2] - q < 1e-12 && q - a[2] < 1e-12 &&
                                  a[2] < 2e-3 && a[2] > -2e-3) }'
check "... the graze fell back to sampling" sh -c \
    "printf '%s\n' \"\$1\" | grep -q '^fell back to sampled: run [0-9]* graze / swing null/straight_line stage raw: valid$'" _ "$out"
check "... the database is untouched" test "$(md5sum <"$SDB")" = "$sum"

# The certified database: the same comparison, whatever was stored.
out=$("$mpb" verify --compare "$CDB")
check "the certified database compares the same" sh -c \
    "printf '%s\n' \"\$1\" | grep -q '^newly refused: run [0-9]* thin / swing null/straight_line stage raw (stored collision): segment 0 at s='" _ "$out"

# mpb view: the configuration the proof found, its s the verdict's.
crun=$(sqlite3 "$CDB" "$thin")
detail=$(sqlite3 "$CDB" "SELECT verdict_detail FROM stages WHERE run_id = $crun")
ds=$(printf '%s\n' "$detail" | sed -n 's/^segment 0 collides at s=\([0-9.e-]*\) (waypoints 0-1)$/\1/p')
check "the stored verdict names its s" test -n "$ds"
"$mpb" view "$CDB" "$crun" -o "$work/thin.html" >/dev/null 2>&1
check "mpb view writes the page" eq $? 0
check "... with the certified collision at the verdict's s" \
    grep -q "\"collision\":{\"s\":$ds,\"certified\":1,\"q\":\[" "$work/thin.html"
# Stored "sampled" by a certified check whose proof found the collision
# after an earlier segment was left to sampling (run 109 of
# docs/results-mbm.md): the sampled rule finds nothing there, the proof's
# configuration is shown.
cp "$CDB" "$work/fellback.db"
sqlite3 "$work/fellback.db" "UPDATE stages SET verification = 'sampled' WHERE run_id = $crun"
"$mpb" view "$work/fellback.db" "$crun" -o "$work/fellback.html" >/dev/null 2>&1
check "... stored sampled, found by the proof: still shown" \
    grep -q "\"collision\":{\"s\":$ds,\"certified\":1,\"q\":\[" "$work/fellback.html"
# The thick wall stored certified too: found again by the proof.
thick=$(sqlite3 "$CDB" "SELECT r.id FROM runs r JOIN queries q ON q.id = r.query_id JOIN scenes s ON s.id = q.scene_id WHERE s.name = 'thick'")
"$mpb" view "$CDB" "$thick" -o "$work/thick.html" >/dev/null 2>&1
check "... the thick wall's page too, certified" \
    grep -q '"collision":{"s":[0-9.e-]*,"certified":1,"q":\[' "$work/thick.html"
# Stored sampled, the thick wall's collision is the sample's: k = 101.
sthick=$(sqlite3 "$SDB" "SELECT r.id FROM runs r JOIN queries q ON q.id = r.query_id JOIN scenes s ON s.id = q.scene_id WHERE s.name = 'thick'")
"$mpb" view "$SDB" "$sthick" -o "$work/sthick.html" >/dev/null 2>&1
ss=$(sed -n 's/.*"collision":{"s":\([0-9.e-]*\),"certified":0,"q":\[.*/\1/p' "$work/sthick.html")
check "... stored sampled, the sample's configuration" \
    awk -v s="$ss" 'BEGIN { k = s * 101; exit !(s > 0 && k - int(k + 0.5) < 1e-9 && int(k + 0.5) - k < 1e-9) }'

# The HTML report links the refused run to its view page, which shows it.
if [ -d "$MPB_SOURCE/.cache/web" ] || [ -n "${MPB_THREE_JS:-}" ]; then
    mkdir "$work/site"
    "$mpb" report --format html -o "$work/site/report.html" "$CDB" >/dev/null 2>"$work/report.err"
    check "mpb report --format html writes the page" eq $? 0
    check "... the refused run linked to its view" \
        grep -q "href=\"views/run-$crun.html\"" "$work/site/report.html"
    check "... whose page shows the certified collision" \
        grep -q "\"collision\":{\"s\":$ds,\"certified\":1," "$work/site/views/run-$crun.html"
fi

"$mpb" verify --compare --experiment 9 "$SDB" >/dev/null 2>&1
check "an unknown experiment: exit 1" eq $? 1

mpb_finish
