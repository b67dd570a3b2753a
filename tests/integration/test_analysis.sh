#!/bin/sh
# The runs for analysing them yourself (docs/analysis.md) on a real
# benchmark's database (the demo's arm, OMPL and null planners over LCM in
# a private network namespace; one scene put in a problem set by `set:`,
# one in its default set): scenes.problem_set as the file says, `mpb
# export --runs-csv` writing the run_summary view, docs/analysis.md's
# pandas example run as it is written, with .venv's python, giving the
# numbers of `mpb report`, and the export of a database made before the
# view, read-only.
set -u
. "$MPB_SOURCE/tests/integration/lib.sh"
mpb_enter_netns "$0" "$@"

work=$(mktemp -d)
trap 'mpb_stop_all; rm -rf "$work"' EXIT
DB=$work/demo.db
mpb=$MPB_BUILD/tools/mpb
planar=$MPB_SOURCE/scenes/planar
python=$MPB_SOURCE/.venv/bin/python3

sed "s|PLANAR|$planar|" >"$work/demo.yaml" <<'END'
experiment: {name: analysis, runs: 3, time_limit: 1.0, seed: 7}
robot: {format: planar, file: PLANAR/arm3.robot}
scenes:
  - name: pillars
    set: shelves
    format: planar
    file: PLANAR/pillars.scene
    queries:
      - {name: over, start: [0, 0, 0], goal: [2.6, 0, 0], tolerance: 0.01}
      - {name: fold, start: [0, 0, 0], goal: [-1.2, 1.5, 1.0], tolerance: 0.01}
  - name: "walls, high/1"
    format: planar
    file: PLANAR/pillars.scene
    queries:
      - {name: fold, start: [0, 0, 0], goal: [-1.2, 1.5, 1.0], tolerance: 0.01}
planners:
  - {planner: ompl, algorithms: [RRTConnect]}
  - {planner: null, algorithms: [straight_line], runs: 1}
END
mpb_spawn "$work/null.log" "$MPB_BUILD/planners/null/mpb-planner-null"
mpb_spawn "$work/ompl.log" "$MPB_BUILD/planners/ompl/mpb-planner-ompl"
mpb_timeout 120 "$MPB_BUILD/daemon/mpbenchd" -d "$DB" "$work/demo.yaml" \
    >"$work/daemon.log" 2>&1
check "the benchmark completes" eq $? 0
mpb_stop_all

check "set: puts its scene in that problem set, the other is in its default" \
    test "$(sqlite3 "$DB" "SELECT group_concat(name || '=' || problem_set, ';') FROM scenes")" = \
    "pillars=shelves;walls, high/1=walls, high"

done_runs=$(sqlite3 "$DB" "SELECT count(*) FROM runs WHERE state = 'done'")
out=$("$mpb" export --runs-csv "$DB" "$work/runs.csv")
check "mpb export --runs-csv exits 0" eq $? 0
check "... saying how many runs it wrote" test "$out" = "$work/runs.csv: $done_runs runs"
check "... a header and one row per finished run" \
    eq "$(wc -l <"$work/runs.csv")" $((done_runs + 1))
check "... the header naming run_summary's columns" test \
    "$(head -n 1 "$work/runs.csv")" = "$(sqlite3 -header -csv "$DB" 'SELECT * FROM run_summary LIMIT 1' | head -n 1)"
check "... the same rows to standard output" \
    sh -c "'$mpb' export --runs-csv '$DB' - | cmp -s - '$work/runs.csv'"
"$python" - "$work/runs.csv" "$DB" <<'END'
import csv, sqlite3, sys
rows = list(csv.DictReader(open(sys.argv[1], newline="")))
db = sqlite3.connect(sys.argv[2])
want = {r[0]: r[1:] for r in db.execute(
    "SELECT run, problem_set, scene, planner, verified, time_total FROM run_summary")}
bad = [r["run"] for r in rows
       if (r["problem_set"], r["scene"], r["planner"], int(r["verified"]),
           float(r["time_total"])) != tuple(want[int(r["run"])])]
sys.exit(1 if bad or len(rows) != len(want) else 0)
END
check "... each row as the view has it, quoted names and exact times read back" eq $? 0

# docs/analysis.md's example, as written there, then its numbers beside
# mpb report's time_total means.
sed -n '/^```python$/,/^```$/p' "$MPB_SOURCE/docs/analysis.md" | \
    sed -n '2,/^```$/p' | sed '$d' >"$work/example.py"
check "docs/analysis.md has the three-line example" eq "$(wc -l <"$work/example.py")" 3
"$mpb" report --format csv "$DB" >"$work/report.csv"
check "mpb report --format csv exits 0" eq $? 0
cat >>"$work/example.py" <<'END'
import csv, sys
report = [r for r in csv.DictReader(open(sys.argv[1], newline=""))
          if r["metric"] == "time_total" and r["mean"] != ""]
for r in report:
    ours = times[(r["scene"], r["planner"])]
    print(r["scene"], r["planner"], r["mean"], repr(ours))
    if abs(ours - float(r["mean"])) > 1e-12 * abs(ours):
        sys.exit(1)
print(len(report), "means agree")
END
(cd "$work" && "$python" example.py report.csv) >"$work/example.out" 2>&1
check "the example runs with .venv's pandas and gives mpb report's means" eq $? 0
cat "$work/example.out"
check "... for each scene and planner that has successes" \
    grep -qx "$(grep -c ',time_total,s,[0-9]' "$work/report.csv") means agree" "$work/example.out"

"$mpb" export --runs-csv "$DB" "$work/runs.csv" >/dev/null 2>"$work/exists.err"
check "an existing CSV is left alone: exit 1" eq $? 1
check "... saying so in one line" \
    grep -qx "mpb export: $work/runs.csv exists (--force replaces it)" "$work/exists.err"
"$mpb" export --runs-csv -e 9 "$DB" "$work/none.csv" 2>"$work/none.err"
check "an unknown experiment is an error" eq $? 1
check "... in one line, writing nothing" sh -c \
    "grep -qx 'mpb export: $DB: no experiment 9' '$work/none.err' && ! test -e '$work/none.csv' && ! test -e '$work/none.csv.part'"

# A database made before run_summary and scenes.problem_set, read-only:
# the same rows, each scene in its default set.
cp "$DB" "$work/old.db"
sqlite3 "$work/old.db" "DROP VIEW run_summary; ALTER TABLE scenes DROP COLUMN problem_set"
chmod a-w "$work/old.db"
"$mpb" export --runs-csv "$work/old.db" - >"$work/old.csv"
check "an older database is exported read-only" eq $? 0
check "... the same rows, pillars in its default set (its name), the other as before" test \
    "$(sed 's/,pillars,pillars,/,shelves,pillars,/' "$work/old.csv")" = "$(cat "$work/runs.csv")"
check "... which the file had in it" grep -q ',pillars,pillars,' "$work/old.csv"

mpb_finish
