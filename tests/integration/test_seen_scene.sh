#!/bin/sh
# Planned on what is seen, judged on what is there: a scene entry's
# `seen:` gives the planners another scene than the truth. The truth has
# a post the seen scene lacks; the seen scene has a phantom the truth
# lacks. Through the real daemon, OMPL's planner and the null planner:
# the straight line past the post succeeds on what was seen and is
# refused on the truth, the one through the phantom the reverse; OMPL's
# paths avoid the phantom (it planned on what was seen, where a straight
# line would do in the truth); the store keeps both scenes and both
# judgements, and `mpb report` sets them side by side. Run again with
# three verifier threads (each its own copy of both worlds), every
# judgement is the same.
set -u
. "$MPB_SOURCE/tests/integration/lib.sh"

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
DB=$work/seen.db

mpb_ball_robot "$work/ball.urdf"
# Posts 10 cm square, 80 cm tall, at x 0.5: the truth's at y 0.5, the
# seen scene's phantom at y -0.5.
post() {
    printf '* %s\n0.5 %s 0.4\n0 0 0 1\n1\nbox\n0.1 0.1 0.8\n0 0 0\n0 0 0 1\n0 0 0 0\n0\n' "$1" "$2"
}
{ echo truth; post post 0.5; echo .; } >"$work/truth.scene"
{ echo seen; post phantom -0.5; echo .; } >"$work/seen.scene"
cat >"$work/seen.yaml" <<EOT
experiment: {name: seen-posts, runs: 2, time_limit: 5, seed: 1}
robot: {format: urdf, file: ball.urdf, joints: [x, y, z]}
scenes:
  - name: posts
    format: moveit-scene
    file: truth.scene
    seen: {format: moveit-scene, file: seen.scene}
    queries:
      - {name: by_post, start: [0.2, 0.5, 0.4], goal: [0.8, 0.5, 0.4]}
      - {name: by_phantom, start: [0.2, -0.5, 0.4], goal: [0.8, -0.5, 0.4]}
planners:
  - {planner: ompl, algorithms: [RRTConnect]}
  - {planner: null, algorithms: [straight_line]}
EOT

out=$(MPB_BUILD=$MPB_BUILD mpb_timeout 200 sh "$MPB_SOURCE/tools/run_benchmark.sh" \
      -d "$DB" -p ompl,null -l "$work/logs" "$work/seen.yaml" 2>&1)
check "run_benchmark.sh runs the experiment" eq $? 0
check "the store keeps the truth as the scene" \
    eq "$(q "SELECT count(*) FROM scenes WHERE scene LIKE '%* post%'
             AND scene NOT LIKE '%phantom%'")" 1
check "... and what was seen beside it, with where it came from" \
    eq "$(q "SELECT count(*) FROM scenes WHERE seen LIKE '%* phantom%'
             AND seen NOT LIKE '%* post%' AND seen_how LIKE 'given: %seen.scene'")" 1
check "every finished run was judged on what was seen too" \
    eq "$(q "SELECT count(*) FROM runs WHERE seen_success IS NULL")" 0
nullrun() {
    q "SELECT r.$1 FROM runs r JOIN queries q ON q.id = r.query_id
       JOIN planner_configs c ON c.id = r.planner_config_id
       WHERE c.planner = 'null' AND q.name = '$2' GROUP BY r.$1"
}
check "the line past the post: a success on what was seen" eq "$(nullrun seen_success by_post)" 1
check "... refused on the truth, for the post" eq "$(nullrun success by_post)" 0
check "... whose verdict names the post" \
    eq "$(q "SELECT count(*) FROM stages g JOIN runs r ON r.id = g.run_id
             JOIN queries q ON q.id = r.query_id
             JOIN planner_configs c ON c.id = r.planner_config_id
             WHERE q.name = 'by_post' AND c.planner = 'null' AND r.success = 0
             AND g.verdict = 'collision' AND g.verdict_detail LIKE '%post%'")" \
       "$(q "SELECT count(*) FROM runs r JOIN queries q ON q.id = r.query_id
             JOIN planner_configs c ON c.id = r.planner_config_id
             WHERE q.name = 'by_post' AND c.planner = 'null'")"
check "the line through the phantom: a success on the truth" eq "$(nullrun success by_phantom)" 1
check "... a collision on what was seen, naming the phantom" \
    test "$(nullrun seen_verdict by_phantom)|$(q "SELECT DISTINCT seen_detail LIKE '%phantom%'
             FROM runs r JOIN queries q ON q.id = r.query_id WHERE q.name = 'by_phantom'
             AND r.seen_success = 0")" = "collision|1"
check "OMPL planned on what was seen: its paths past the phantom avoid it" \
    eq "$(q "SELECT count(*) FROM runs r JOIN queries q ON q.id = r.query_id
             JOIN planner_configs c ON c.id = r.planner_config_id
             WHERE c.planner = 'ompl' AND q.name = 'by_phantom'
             AND r.claimed_success = 1 AND r.seen_success = 1 AND r.success = 1")" 2

says() { printf '%s\n' "$1" | grep -Eq "$2"; }
report=$("$MPB_BUILD/tools/mpb" report "$DB" 2>&1)
check "mpb report sets success on the truth beside success on what was seen" \
    says "$report" "Planned on what was seen, judged on what is there"
check "... the null planner: one seen-only and one truth-only success a run" \
    says "$report" "null/straight_line +4 +2 \(50%\) +2 \(50%\) +2 +2"
# mpb verify judges every final stage again on what its planner saw.
out=$("$MPB_BUILD/tools/mpb" verify "$DB")
check "mpb verify agrees on both judgements: exit 0" eq $? 0
check "... having judged the 8 final stages again on what was seen" test -n \
    "$(printf '%s\n' "$out" | grep -x '8 final stages judged again on what their planner saw: 0 changed verdict')"
cp "$DB" "$work/tampered.db"
sqlite3 "$work/tampered.db" "UPDATE runs SET seen_verdict = 'valid' WHERE seen_verdict = 'collision'"
out=$("$MPB_BUILD/tools/mpb" verify "$work/tampered.db")
check "... and finds a stored judgement on what was seen that does not hold" \
    test "$?|$(printf '%s\n' "$out" | grep -c 'on what was seen: stored valid, now collision')" = "1|2"

# mpb view draws what the planner saw over the truth, and says how the
# run fared there.
run=$(q "SELECT r.id FROM runs r JOIN queries q ON q.id = r.query_id
         JOIN planner_configs c ON c.id = r.planner_config_id
         WHERE c.planner = 'null' AND q.name = 'by_phantom' LIMIT 1")
"$MPB_BUILD/tools/mpb" view "$DB" "$run" -o "$work/run.html" >/dev/null 2>&1
check "mpb view writes the run's page" eq $? 0
seen=$(sed -n 's/.*"seen":{"how":"\([^"]*\)","success":\([0-9-]*\),"verdict":"\([a-z_]*\)".*/\1|\2|\3/p' \
       "$work/run.html")
check "... with what was seen, how the run fared there" \
    test "${seen#given: }" = "$work/seen.scene|0|collision"
check "... and its phantom to draw" grep -q '"name":"phantom"' "$work/run.html"

# Again, with a pool of verifier threads: each judges on its own copies.
mpb_spawn "$work/ompl.log" "$MPB_BUILD/planners/ompl/mpb-planner-ompl"
mpb_spawn "$work/null.log" "$MPB_BUILD/planners/null/mpb-planner-null"
"$MPB_BUILD/daemon/mpbenchd" --verify-threads 3 -d "$work/pool.db" \
    "$work/seen.yaml" >"$work/pool.log" 2>&1 &
mpb_wait $! 120
check "three verifier threads run it too" eq $? 0
judged() {
    sqlite3 "$1" "SELECT group_concat(c.name || '/' || q.name || ':' ||
        r.success || r.seen_success || r.seen_verdict, ' ') FROM (SELECT * FROM runs
        ORDER BY query_id, planner_config_id, repetition) r
        JOIN queries q ON q.id = r.query_id
        JOIN planner_configs c ON c.id = r.planner_config_id
        WHERE c.planner = 'null'"
}
check "... and judges every null run on both scenes as one thread did" \
    test "$(judged "$DB")" = "$(judged "$work/pool.db")"
check "... the same for OMPL's runs on what was seen" \
    eq "$(sqlite3 "$work/pool.db" "SELECT count(*) FROM runs WHERE seen_success = 1
           AND planner_config_id = (SELECT id FROM planner_configs WHERE planner = 'ompl')")" 4
[ "$(q "SELECT count(*) FROM runs WHERE seen_success IS NOT NULL")" = 8 ] ||
    { printf '%s\n%s\n' "$out" "$report"; cat "$work"/logs/*.log 2>/dev/null | tail -30; }
mpb_finish
