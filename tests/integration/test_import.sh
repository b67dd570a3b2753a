#!/bin/sh
# `mpb import` on a log written by OMPL 1.5's own ompl::tools::Benchmark:
# the runs arrive, reports read them, and exported again for Planner Arena
# they keep OMPL's conventions: the experiments and runs columns where
# Planner Arena looks, the status enum, booleans as 0/1, and per planner
# the same run count and the same averages as the log itself says (worked
# out here from the log's text, not through mpbench). A broken log adds
# nothing and says where it broke.
set -u
. "$MPB_SOURCE/tests/integration/lib.sh"

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mpb=$MPB_BUILD/tools/mpb
DB=$work/imported.db

"$MPB_BUILD/tests/mpb-test-ompl-log" "$work/wall.log" 6 0.05
check "OMPL's Benchmark wrote a log" test -s "$work/wall.log"

out=$("$mpb" import -d "$DB" "$work/wall.log")
check "mpb import succeeds" eq $? 0
echo "# $out"

# Per planner: runs, mean time, mean solved, read from the log's text.
cat >"$work/means.py" <<'EOT'
import sys
lines = open(sys.argv[1]).read().split("\n")
i = next(k for k, l in enumerate(lines) if l.endswith(" planners"))
n = int(lines[i].split()[0]); i += 1
for _ in range(n):
    name = lines[i]; i += 1
    c = int(lines[i].split()[0]); i += 1 + c
    p = int(lines[i].split()[0]); i += 1
    props = [lines[i + k].rsplit(" ", 1)[0] for k in range(p)]; i += p
    r = int(lines[i].split()[0]); i += 1
    rows = [[v.strip() for v in lines[i + k].split(";")][:p] for k in range(r)]
    i += r
    while lines[i] != ".":
        i += 1
    i += 1
    col = lambda key: [float(row[props.index(key)]) for row in rows]
    t, s = col("time"), col("solved")
    print("%s|%d|%.9g|%.9g" % (name.replace("geometric_", ""), r,
                               sum(t) / r, sum(s) / r))
EOT
python3 "$work/means.py" "$work/wall.log" | sort >"$work/log.means"
check "the log has three planners" eq "$(wc -l <"$work/log.means")" 3

check "every run is in the database" \
    eq "$(q "SELECT count(*) FROM runs WHERE state = 'done'")" \
       "$(awk -F'|' '{n += $2} END {print n}' "$work/log.means")"
check "mpb report reads the imported experiment" \
    sh -c "'$mpb' report '$DB' | grep -q 'ompl/RRTConnect'"

"$mpb" export --planner-arena "$DB" "$work/arena.db" >/dev/null
check "export for Planner Arena succeeds" eq $? 0
A=$work/arena.db
check "experiments: the first twelve columns, in Planner Arena's order" \
    test "$(sqlite3 "$A" "SELECT group_concat(name, ',') FROM
              (SELECT name FROM pragma_table_info('experiments') ORDER BY cid LIMIT 12)")" \
    = "id,name,totaltime,timelimit,memorylimit,runcount,version,hostname,cpuinfo,date,seed,setup"
# An imported log goes out as the log said (docs/planner-arena.md): its
# planners' names, its run properties as columns in its order.
first=$(sed -n '/ properties for each run$/{n;p;q}' "$work/wall.log" | sed 's/ [A-Z]*$//; s/ /_/g')
check "runs: id, experimentid, plannerid, then the log's properties ($first first)" \
    test "$(sqlite3 "$A" "SELECT group_concat(name, ',') FROM
              (SELECT name FROM pragma_table_info('runs') ORDER BY cid LIMIT 4)")" \
    = "id,experimentid,plannerid,$first"
check "the status enum is there" \
    ge "$(sqlite3 "$A" "SELECT count(*) FROM enums WHERE name = 'status'")" 7
check "booleans are the integers 0 and 1" \
    eq "$(sqlite3 "$A" "SELECT count(*) FROM runs WHERE typeof(solved) != 'integer'
                        OR solved NOT IN (0, 1)")" 0
sqlite3 "$A" "SELECT p.name, count(*), printf('%.9g', avg(r.time)),
                     printf('%.9g', avg(r.solved))
                FROM runs r JOIN plannerConfigs p ON p.id = r.plannerid
               GROUP BY p.name" | sed 's/^geometric_//' | sort >"$work/arena.means"
check "per planner, the same runs and averages as the log" \
    cmp -s "$work/log.means" "$work/arena.means"
[ $FAILS -eq 0 ] || { echo "# log:"; cat "$work/log.means"; echo "# arena:"; cat "$work/arena.means"; }

# OMPL's "memory REAL" (MB) is the run's memory (runs.memory), and
# Planner Arena's "memory" again, every run's to the last digit printed.
cat >"$work/memory.py" <<'EOT'
import sys
lines = open(sys.argv[1]).read().split("\n")
i = next(k for k, l in enumerate(lines) if l.endswith(" planners"))
out = []
n = int(lines[i].split()[0]); i += 1
for _ in range(n):
    i += 1                                  # the planner's name
    c = int(lines[i].split()[0]); i += 1 + c
    p = int(lines[i].split()[0]); i += 1
    props = [lines[i + k].rsplit(" ", 1)[0] for k in range(p)]; i += p
    r = int(lines[i].split()[0]); i += 1
    m = props.index("memory")
    out += ["%.9g" % float(lines[i + k].split(";")[m]) for k in range(r)]
    i += r
    while lines[i] != ".":
        i += 1
    i += 1
print(len(out), ",".join(sorted(out)))
EOT
log_memory=$(python3 "$work/memory.py" "$work/wall.log")
mem_of() { sqlite3 "$1" "SELECT count(memory) || ' ' || group_concat(m, ',') FROM
                          (SELECT printf('%.9g', memory) AS m, memory FROM $2 ORDER BY m)"; }
check "import -d: every run's memory is the log's (${log_memory%% *} runs)" \
    test "$(mem_of "$DB" runs)" = "$log_memory"
check "... and not a planner value as well" \
    eq "$(q "SELECT count(*) FROM planner_values WHERE name = 'memory'")" 0
check "export --planner-arena: memory again, the log's" \
    test "$(mem_of "$A" runs)" = "$log_memory"

# Straight into Planner Arena (mpb import -p), as OMPL's script writes it:
# the planners keep the log's names, and the rows are the log's.
"$mpb" import -p "$work/direct.db" "$work/wall.log" >/dev/null
check "mpb import -p succeeds" eq $? 0
D=$work/direct.db
check "direct: experiments' first twelve columns in Planner Arena's order" \
    test "$(sqlite3 "$D" "SELECT group_concat(name, ',') FROM
              (SELECT name FROM pragma_table_info('experiments') ORDER BY cid LIMIT 12)")" \
    = "id,name,totaltime,timelimit,memorylimit,runcount,version,hostname,cpuinfo,date,seed,setup"
check "direct: booleans are the integers 0 and 1" \
    eq "$(sqlite3 "$D" "SELECT count(*) FROM runs WHERE typeof(solved) != 'integer'
                        OR solved NOT IN (0, 1)")" 0
check "direct: the status enum is there" \
    ge "$(sqlite3 "$D" "SELECT count(*) FROM enums WHERE name = 'status'")" 7
sqlite3 "$D" "SELECT p.name, count(*), printf('%.9g', avg(r.time)),
                     printf('%.9g', avg(r.solved))
                FROM runs r JOIN plannerConfigs p ON p.id = r.plannerid
               GROUP BY p.name" | sed 's/^geometric_//' | sort >"$work/direct.means"
check "direct: per planner, the same runs and averages as the log" \
    cmp -s "$work/log.means" "$work/direct.means"
# Every value of every run, as OMPL's script stores the log's text: it
# binds the text and SQLite's REAL affinity converts it (SQLite 3.40 reads
# "0.814637" as 0.8146370000000001, not as float() or strtod do): the
# reader's own conversion must give the very same doubles. Debian's
# python3, for the SQLite mpbench links.
cat >"$work/values.py" <<'EOT'
import math, sqlite3, sys
lines = open(sys.argv[1]).read().split("\n")
db = sqlite3.connect(sys.argv[2])
i = next(k for k, l in enumerate(lines) if l.endswith(" planners"))
n = int(lines[i].split()[0]); i += 1
cells = bad = 0
for _ in range(n):
    name = lines[i]; i += 1
    c = int(lines[i].split()[0]); i += 1 + c
    p = int(lines[i].split()[0]); i += 1
    cols = [lines[i + k].rsplit(" ", 1)[0].replace(" ", "_") for k in range(p)]
    i += p
    r = int(lines[i].split()[0]); i += 1
    got = db.execute("SELECT %s FROM runs JOIN plannerConfigs c ON c.id = plannerid"
                     " WHERE c.name = ? ORDER BY runs.id"
                     % ",".join('runs."%s"' % k for k in cols), (name,)).fetchall()
    for k in range(r):
        for v, x in zip([v.strip() for v in lines[i + k].split(";")][:p], got[k]):
            want = {"true": 1.0, "false": 0.0}.get(v) if v in ("true", "false") \
                else db.execute("SELECT CAST(? AS REAL)", (v,)).fetchone()[0] \
                if v and v not in ("nan", "inf", "-inf") else None
            if want is not None and not math.isfinite(want):
                want = None
            cells += 1
            bad += (x is None) != (want is None) or (x is not None and float(x) != want)
    i += r
    while lines[i] != ".":
        i += 1
    i += 1
print(cells, bad)
EOT
set -- $(/usr/bin/python3 "$work/values.py" "$work/wall.log" "$D")
check "direct: every value is the log's, to the last bit ($1 values)" \
    test "${1:-0}" -gt 0 -a "${2:-1}" -eq 0
"$mpb" import -p "$work/direct.db" "$work/wall.log" >/dev/null 2>&1
check "direct: an existing Planner Arena database is not overwritten" test $? -eq 1
check "direct: ... and still holds one experiment" \
    eq "$(sqlite3 "$D" "SELECT count(*) FROM experiments")" 1
# Progress: OMPL's Benchmark lists the sample's properties sorted, "time"
# among them; each goes to its own column, as the script puts it. Every
# run of the log gets one sample: 0.5 for "time", 7 for the rest.
awk '/ progress properties for each run$/ {
         print; q = $1
         for (k = 0; k < q; k++) {getline; print; name[k] = $0; sub(/ [A-Z]+$/, "", name[k])}
         getline; print; n = $1
         for (r = 0; r < n; r++) {
             getline; s = ""
             for (k = 0; k < q; k++) s = s (name[k] == "time" ? "0.5" : "7") ","
             print s ";"
         }
         next
     }
     {print}' "$work/wall.log" >"$work/progress.log"
samples=$(grep -Ec '^(7|0\.5),.*;$' "$work/progress.log")
"$mpb" import -p "$work/progress.db" "$work/progress.log" >/dev/null
check "direct: progress, each value in its own column ($samples samples)" \
    test "$samples" -gt 0 -a "$(sqlite3 "$work/progress.db" \
        "SELECT count(*), sum(time = 0.5), sum(best_cost = 7) FROM progress")" \
        = "$samples|$samples|$samples"
# A write that fails half-way (a column name SQLite refuses): no
# database, and no temporary file beside it.
sed 's/^time REAL$/ti"me REAL/' "$work/wall.log" >"$work/badcol.log"
"$mpb" import -p "$work/half.db" "$work/badcol.log" >/dev/null 2>&1
check "direct: a failed write fails" test $? -eq 1
check "direct: ... and leaves no file behind" \
    test -z "$(ls "$work" | grep '^half\.db')"

# Round trip through OMPL's format: the exported log imports to the same
# (tau_r is the log's "time"; tau_t adds its simplification time).
# Its planners come back as mpbench/ompl/NAME, the log being mpbench's;
# its setup block holds the imported log, whose "|>>>" must not end it.
"$mpb" export --ompl-log "$DB" "$work/logs" >/dev/null
"$mpb" import -d "$work/again.db" "$work"/logs/*.log >/dev/null
check "the exported OMPL log imports again" eq $? 0
sqlite3 "$work/again.db" "SELECT c.name, count(*), printf('%.9g', avg(r.time_raw)),
                                 printf('%.9g', avg(r.success))
                            FROM runs r JOIN planner_configs c ON c.id = r.planner_config_id
                           GROUP BY c.name" | sed 's/^.*\///' | sort >"$work/again.means"
check "... with the same runs and averages" cmp -s "$work/log.means" "$work/again.means"
check "... and the same memory, run by run" \
    test "$(mem_of "$work/again.db" runs)" = "$log_memory"
# mpbench's own experiment properties, query and mpbench_experiment, are
# the log's once imported, and exported again as they were.
want=$(sed -n 's/^query VARCHAR(512) = //p; s/^mpbench_experiment INTEGER = //p' \
           "$work"/logs/*.log | paste -sd'|')
# Imported second, the log's experiment has another id than it says.
"$mpb" import -d "$work/again2.db" "$work/wall.log" "$work"/logs/*.log >/dev/null
"$mpb" export --planner-arena -e 2 "$work/again2.db" "$work/again-pa.db" >/dev/null
check "query and mpbench_experiment are kept through import -d ($want)" \
    test -n "$want" -a "$(sqlite3 "$work/again-pa.db" \
        "SELECT query || '|' || mpbench_experiment FROM experiments")" = "$want"
rm -rf "$work/logs2"
"$mpb" export --ompl-log -e 2 "$work/again2.db" "$work/logs2" >/dev/null
check "... and in the log exported again" test "$(sed -n \
    's/^query VARCHAR(512) = //p; s/^mpbench_experiment INTEGER = //p' \
    "$work"/logs2/*.log | paste -sd'|')" = "$want"

# A log cut short, and a file that is no log: one line naming where, and
# nothing added to the database.
before=$(q "SELECT count(*) FROM experiments")
head -n "$(( $(wc -l <"$work/wall.log") - 4 ))" "$work/wall.log" >"$work/cut.log"
err=$("$mpb" import -d "$DB" "$work/cut.log" 2>&1)
check "a truncated log fails" test $? -eq 1
check "... in one line naming the file and line" \
    sh -c "printf '%s\n' \"\$1\" | grep -Eq '^mpb import: .*cut.log:[0-9]+: '" _ "$err"
echo "# $err"
printf 'OMPL version 1.5.2\nExperiment x\nRunning on h\nStarting at d\n<<<|\n' >"$work/bad.log"
err=$("$mpb" import -d "$DB" "$work/bad.log" 2>&1)
check "a log without its block end fails in one line" \
    eq "$(printf '%s\n' "$err" | wc -l)" 1
echo "# $err"
check "nothing was added by the broken logs" \
    eq "$(q "SELECT count(*) FROM experiments")" "$before"

# Every log is checked before a database is created or opened.
err=$("$mpb" import -d "$work/new.db" "$work/wall.log" "$work/missing.log" 2>&1)
check "a missing log fails" test $? -eq 1
check "... in one line" eq "$(printf '%s\n' "$err" | wc -l)" 1
check "... and no database is created" test ! -e "$work/new.db"
echo "# $err"
"$mpb" import -d "$DB" "$work/wall.log" "$work/cut.log" >/dev/null 2>&1
check "a good log before a broken one is not imported either" \
    eq "$(q "SELECT count(*) FROM experiments")" "$before"
err=$("$mpb" import -p "$work/part.db" "$work/wall.log" "$work/wall.log" "$work/cut.log" "$work/missing.log" 2>&1)
check "-p: good logs before broken ones fail" test $? -eq 1
check "... each broken one said, once" \
    test "$(printf '%s\n' "$err" | grep -c 'cut.log:[0-9]*: ')$(printf '%s\n' "$err" | grep -c 'cannot read .*missing.log')$(printf '%s\n' "$err" | wc -l)" = 112
check "... and no database appears, nor a file beside it" \
    test -z "$(ls "$work" | grep '^part\.db')"
sed 's/^3 planners$/2 planners/' "$work/wall.log" >"$work/fewer.log"
for to in "-d $work/fewer.db" "-p $work/fewer-pa.db"; do
    err=$("$mpb" import $to "$work/fewer.log" 2>&1)
    check "a planner count too small fails (${to%% *})" \
        sh -c "printf '%s\n' \"\$1\" | grep -q 'fewer.log:[0-9]*: text after the last planner'" _ "$err"
done
check "... and writes no database" test ! -e "$work/fewer.db" -a ! -e "$work/fewer-pa.db"
# A log OMPL wrote with no planner added: nothing to import, no database.
sed -n '1,/^[0-9]* planners$/p' "$work/wall.log" | sed 's/^3 planners$/0 planners/' \
    >"$work/none.log"
for to in "-d $work/none.db" "-p $work/none-pa.db"; do
    err=$("$mpb" import $to "$work/none.log" 2>&1)
    check "a log without runs fails (${to%% *})" test $? -eq 1
    check "... saying so" test "$err" = \
        "mpb import: $work/none.log: no runs in the log (0 planners): nothing to import"
done
check "... and writes no database" test ! -e "$work/none.db" -a ! -e "$work/none-pa.db"
err=$("$mpb" import -p "$work/direct.db" "$work/wall.log" "$work/wall.log" 2>&1)
check "an existing Planner Arena database is said once" \
    eq "$(printf '%s\n' "$err" | grep -c exists)" 1

# OMPL's statuses past the ones mpbench has: 0 (unknown), 8 (abort) and
# 9 (infeasible) are mpbench's "failed", and the log's own number is kept
# (a planner value) and exported again as it was.
cat >"$work/st.log" <<'EOT'
OMPL version 1.5.2
Experiment st
0 experiment properties
Running on h
Starting at 2026-01-01 00:00:00
<<<|
|>>>
<<<|
|>>>
1 is the random seed
1 seconds per run
1024 MB per run
4 runs per planner
1 seconds spent to collect the data
1 enum type
status|Unknown status|Invalid start|Invalid goal|Unrecognized goal type|Timeout|Approximate solution|Exact solution|Crash|Abort|Infeasible
1 planners
geometric_RRT
0 common properties
7 properties for each run
simplified correct solution strict BOOLEAN
simplified solution segments INTEGER
solution difference REAL
solution segments INTEGER
solved BOOLEAN
status ENUM
time REAL
4 runs
; ; ; ; 0; 0; 0.5; 
; ; ; ; 0; 8; 0.5; 
; ; ; ; 0; 9; 0.5; 
1; 3; 0.25; 7; 1; 6; 0.5; 
.
EOT
"$mpb" import -d "$work/st.db" "$work/st.log" >/dev/null
check "statuses 0, 8, 9 are failed, 6 solved" \
    test "$(sqlite3 "$work/st.db" "SELECT group_concat(status, ',') FROM
              (SELECT status FROM runs ORDER BY repetition)")" = "failed,failed,failed,solved"
"$mpb" export --planner-arena "$work/st.db" "$work/st-pa.db" >/dev/null
check "... and are exported as the log's own numbers" \
    test "$(sqlite3 "$work/st-pa.db" "SELECT group_concat(status, ',') FROM
              (SELECT status FROM runs ORDER BY id)")" = "0,8,9,6"

# The path properties mpbench has no stage metric for are kept as the
# planner's values, as every other property (and as the log's own cells
# the ones mpbench's success is made of).
check "unmapped solution ... and simplified ... properties are kept" \
    test "$(sqlite3 "$work/st.db" "SELECT group_concat(name || '=' || value, ',') FROM
              (SELECT name, value FROM planner_values WHERE name NOT IN
                 ('status', 'solved') ORDER BY name)")" \
    = "simplified correct solution strict=1.0,solution difference=0.25"

# Exported again, an imported run's segments are the log's.
check "solution segments and simplified solution segments are exported" \
    test "$(sqlite3 "$work/st-pa.db" "SELECT group_concat(coalesce(solution_segments, '-')
              || '/' || coalesce(simplified_solution_segments, '-'), ',') FROM
              (SELECT * FROM runs ORDER BY id)")" = "-/-,-/-,-/-,7/3"

# -p writes what OMPL's script would: the version line "OMPL version "
# (no number) as "OMPL version", and the settings as "line\n;" each.
"$mpb" import -p "$work/wall-pa.db" "$work/wall.log" >/dev/null
check "-p: a version without a number is the script's 'OMPL version'" \
    test "$(sqlite3 "$work/wall-pa.db" "SELECT version FROM experiments")" = "OMPL version"
want=$(awk '/ common properties$/ {n = $1; s = ""
                for (k = 0; k < n; k++) {getline; s = s $0 "|;"}
                print s; exit}' "$work/wall.log")
check "-p: plannerConfigs.settings in the script's form" \
    test "$(sqlite3 "$work/wall-pa.db" "SELECT replace(settings, char(10), '|')
              FROM plannerConfigs ORDER BY id LIMIT 1")" = "$want"
"$mpb" import -p "$work/st-pa2.db" "$work/st.log" >/dev/null
check "-p: no common properties, empty settings; a version kept" \
    test "$(sqlite3 "$work/st-pa2.db" "SELECT quote(settings), version
              FROM plannerConfigs, experiments")" = "''|OMPL 1.5.2"

# The setup block as the script keeps it: every line as it is, its
# blanks too (OMPL writes "  - signature: 2 1 2 " with a trailing one).
python3 -c '
import sqlite3, sys
lines = open(sys.argv[1]).read().split("\n")
i = lines.index("<<<|") + 1
want = ""
while not lines[i].startswith("|>>>"):
    want += lines[i] + "\n"; i += 1
got = sqlite3.connect(sys.argv[2]).execute("SELECT setup FROM experiments").fetchone()[0]
sys.exit(0 if got == want and want.count(" \n") > 0 else 1)
' "$work/wall.log" "$work/wall-pa.db"
check "-p: the setup block is the log's, blanks and all" test $? -eq 0

mpb_finish
