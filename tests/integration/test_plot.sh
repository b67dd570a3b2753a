#!/bin/sh
# mpb plot on a real benchmark's database (the demo's scene, OMPL and null
# planners, 3 runs per query, run over LCM in a private network namespace):
# the expected images (the performance profiles too), each a real PNG or
# a well-formed SVG that names the planners and says what the database
# says; and one-line errors for an
# unknown scene, an experiment without finished runs, a missing database
# and a missing gnuplot. A second experiment, left unfinished (its OMPL
# planner never comes), has scenes whose names differ only in non-ASCII
# characters or punctuation: a file of their own for each.
set -u
. "$MPB_SOURCE/tests/integration/lib.sh"
mpb_enter_netns "$0" "$@"

work=$(mktemp -d)
trap 'mpb_stop_all; rm -rf "$work"' EXIT
DB=$work/demo.db
mpb=$MPB_BUILD/tools/mpb
planar=$MPB_SOURCE/scenes/planar

sed -e "s|runs: 10 |runs: 3 |" -e "s|\.\./planar/|$planar/|" \
    "$MPB_SOURCE/scenes/experiments/demo.yaml" >"$work/demo.yaml"
mpb_spawn "$work/null.log" "$MPB_BUILD/planners/null/mpb-planner-null"
mpb_spawn "$work/ompl.log" "$MPB_BUILD/planners/ompl/mpb-planner-ompl"
mpb_timeout 120 "$MPB_BUILD/daemon/mpbenchd" -d "$DB" "$work/demo.yaml" \
    >"$work/daemon.log" 2>&1
check "the benchmark completes" eq $? 0
mpb_stop_all

# Odd names: 台所 and 倉庫 give the same file name part, as do "a b" and
# "a_b"; "a_b-3" is what "a b" (scene 3) becomes then. The null planner's
# 30 runs finish; the OMPL configuration's 18 never do.
sed "s|PLANAR|$planar|" >"$work/names.yaml" <<'END'
experiment:
  name: "names 'odd' ü"
  runs: 3
  time_limit: 1.0
robot:
  format: planar
  file: PLANAR/arm3.robot
scenes:
  - name: "台所"
    format: planar
    file: PLANAR/pillars.scene
    queries:
      - {name: q, start: [0, 0, 0], goal: [-1.2, 1.5, 1.0], tolerance: 0.01}
  - name: "倉庫"
    format: planar
    file: PLANAR/pillars.scene
    queries:
      - {name: q, start: [0, 0, 0], goal: [2.6, 0, 0], tolerance: 0.01}
  - name: "a b"
    format: planar
    file: PLANAR/pillars.scene
    queries:
      - {name: q, start: [0, 0, 0], goal: [2.6, 0, 0], tolerance: 0.01}
  - name: "a_b"
    format: planar
    file: PLANAR/pillars.scene
    queries:
      - {name: q, start: [0, 0, 0], goal: [2.6, 0, 0], tolerance: 0.01}
  - name: "a_b-3"
    format: planar
    file: PLANAR/pillars.scene
    queries:
      - {name: q, start: [0, 0, 0], goal: [2.6, 0, 0], tolerance: 0.01}
  - name: "Säule \"x\" | `echo hi` 'q' \\ 100% & $HOME @x {y}^z_w, a scene whose name goes on and on past the width of any plot title, with more words"
    format: planar
    file: PLANAR/pillars.scene
    queries:
      - {name: q, start: [0, 0, 0], goal: [2.6, 0, 0], tolerance: 0.01}
planners:
  - planner: null
    algorithms: [straight_line]
  - planner: null
    algorithms: [straight_line]
    name: "zwei ü"
    runs: 2
  - planner: ompl
    algorithms: [RRTConnect]
END
NAMES=$work/names.db
mpb_spawn "$work/null2.log" "$MPB_BUILD/planners/null/mpb-planner-null"
"$MPB_BUILD/daemon/mpbenchd" -d "$NAMES" "$work/names.yaml" >"$work/names.log" 2>&1 &
daemon=$!
mpb_wait_count "$NAMES" 30 30 "SELECT count(*) FROM runs WHERE state = 'done'"
kill -TERM $daemon
wait $daemon
check "the second experiment stops with 30 runs done and 18 not" \
    test "$(sqlite3 "$NAMES" "SELECT count(*) FROM runs WHERE state = 'done'"):$(sqlite3 "$NAMES" "SELECT count(*) FROM runs WHERE state != 'done'")" = 30:18
mpb_stop_all

# ---- PNG (the default) ------------------------------------------------------
"$mpb" plot -o "$work/png" "$DB" >"$work/png.out" 2>"$work/png.err"
check "mpb plot exits 0" eq $? 0
cat "$work/png.err"
kinds="time success path_length smoothness clearance ee_path_length"
for k in $kinds; do
    f=$work/png/plot-pillars-$k.png
    check "it writes and names plot-pillars-$k.png" grep -qx "$f" "$work/png.out"
    check "... a PNG file" \
        test "$(head -c 8 "$f" | od -An -tx1 | tr -d ' \n')" = 89504e470d0a1a0a
    check "... of a real picture's size" test "$(stat -c %s "$f")" -gt 8000
done
# The success against the time budget of the one problem set (the scene).
f=$work/png/plot-budget-pillars.png
check "it writes and names plot-budget-pillars.png" grep -qx "$f" "$work/png.out"
check "... a PNG file of a real picture's size" test "$(stat -c %s "$f")" -gt 8000
check "it writes and names budget.csv" grep -qx "$work/png/budget.csv" "$work/png.out"
for c in $(sqlite3 "$DB" "SELECT name FROM planner_configs"); do
    n=$(sqlite3 "$DB" "SELECT count(*) FROM results WHERE planner = '$c'")
    ok=$(sqlite3 "$DB" "SELECT sum(success) FROM results WHERE planner = '$c'")
    last=$(grep "^\"pillars\",\"$c\",verified," "$work/png/budget.csv" | tail -n 1)
    check "budget.csv: $c's verified curve ends at its $ok of $n runs" \
        python3 -c "import sys; f = sys.argv[1].split(','); sys.exit(not (f[-1] == sys.argv[3] and abs(float(f[-2]) - int(sys.argv[2]) / int(sys.argv[3])) < 1e-8))" "$last" "$ok" "$n"
    slowest=$(sqlite3 "$DB" "SELECT printf('%.9g', max(time_total)) FROM results WHERE planner = '$c' AND success = 1")
    check "... at the time of its slowest success" \
        test "$(echo "$last" | cut -d, -f4)" = "$slowest"
done
# The performance profiles of that set (values: unit/test_plot_profile).
f=$work/png/plot-profile-pillars.png
check "it writes and names plot-profile-pillars.png" grep -qx "$f" "$work/png.out"
check "... a PNG file of a real picture's size" test "$(stat -c %s "$f")" -gt 8000
check "it writes and names profile.csv" grep -qx "$work/png/profile.csv" "$work/png.out"
check "... over the scene's 2 queries, for time and path length" test \
    "$(sed 1d "$work/png/profile.csv" | cut -d, -f1,2,6 | sort -u | tr '\n' ' ')" = \
    '"pillars",path_length,2 "pillars",time,2 '
check "it writes nothing else" eq "$(ls "$work/png" | wc -l)" 10
check "... and names nothing else" eq "$(wc -l <"$work/png.out")" 10

# ---- SVG ----------------------------------------------------------------------
"$mpb" plot --format svg --scene pillars -o "$work/svg" "$DB" >"$work/svg.out"
check "--format svg exits 0" eq $? 0
check "... writes six SVG files and no PNG" \
    test "$(ls "$work/svg" | grep -c '\.svg$'):$(ls "$work/svg" | grep -c '\.png$')" = 6:0
for f in "$work"/svg/*.svg; do
    check "$(basename "$f") is well-formed XML" \
        python3 -c "import sys, xml.etree.ElementTree as E; E.parse(sys.argv[1])" "$f"
done
svg_text() {
    python3 -c "import sys, xml.etree.ElementTree as E
print('\n'.join(''.join(t.itertext()) for t in E.parse(sys.argv[1]).iter() if t.tag.endswith('text')))" "$1"
}
svg_text "$work/svg/plot-pillars-success.svg" >"$work/success.txt"
svg_text "$work/svg/plot-pillars-time.svg" >"$work/time.txt"
svg_text "$work/svg/plot-pillars-path_length.svg" >"$work/length.txt"
for c in $(sqlite3 "$DB" "SELECT name FROM planner_configs"); do
    check "the success chart names $c" grep -qx "$c" "$work/success.txt"
    n=$(sqlite3 "$DB" "SELECT count(*) FROM results WHERE planner = '$c'")
    ok=$(sqlite3 "$DB" "SELECT sum(success) FROM results WHERE planner = '$c'")
    check "... with its $ok of $n successes" grep -qx "$ok of $n" "$work/success.txt"
    check "the time plot counts its $n runs" grep -qx "$n runs" "$work/time.txt"
    check "the path length plot counts its $ok successful runs" \
        grep -qx "$ok successful runs" "$work/length.txt"
done
check "the path length plot keys the OMPL stages" \
    sh -c "grep -qx raw '$work/length.txt' && grep -qx shortcut '$work/length.txt' && grep -qx smoothed '$work/length.txt'"
check "the time plot says its unit" grep -q "planning time .*(s" "$work/time.txt"
check "... and draws the experiment's time limit" \
    grep -qx "time limit $(printf %g "$(sqlite3 "$DB" 'SELECT time_limit FROM experiments')") s" "$work/time.txt"
check "the titles name the scene and the experiment" \
    grep -q "scene pillars, 2 queries pooled (experiment demo)" "$work/success.txt"

# ---- boxes -----------------------------------------------------------------------
# The script mpb gives gnuplot, through a gnuplot that keeps a copy.
mkdir "$work/bin"
printf '#!/bin/sh\ntee "$GP_SCRIPT" | exec %s "$@"\n' "$(command -v gnuplot)" >"$work/bin/gnuplot"
chmod +x "$work/bin/gnuplot"
GP_SCRIPT=$work/demo.gp PATH=$work/bin:$PATH "$mpb" plot -o "$work/gp" "$DB" >/dev/null
GP_SCRIPT=$work/names.gp PATH=$work/bin:$PATH "$mpb" plot -o "$work/gp" "$NAMES" >/dev/null
# Each plot's datablocks: $bC_K the values of configuration C, stage K (one
# a line); $qC_K its box: x q1 low high q3 median. Checked against type-7
# quartiles (Python's statistics.quantiles, method 'inclusive', as R's and
# numpy's default) and whiskers at the furthest value within 1.5 IQR.
boxes_check() {
    python3 - "$@" <<'END'
import re, statistics, sys
script, mode = open(sys.argv[1]).read(), sys.argv[2]
plots = script.split('\nreset\n')
boxes = small = 0
bad = []
for plot in plots:
    blocks = dict(re.findall(r'^\$(\w+) << EOD\n(.*?)^EOD$', plot, re.M | re.S))
    for name, text in blocks.items():
        if not name.startswith('b'):
            continue
        v = sorted(float(x) for x in text.split())
        q = blocks.get('q' + name[1:])
        if len(v) < 3:
            small += 1
            if q is not None:
                bad.append((name, 'a box of %d values' % len(v)))
            continue
        if q is None or not re.search(r'\$q%s using 1:2:3:4:5 with candlesticks' % name[1:], plot):
            bad.append((name, 'no box drawn'))
            continue
        boxes += 1
        x, q1, lo, hi, q3, med = (float(t) for t in q.split())
        e1, e2, e3 = statistics.quantiles(v, n=4, method='inclusive')
        iqr = e3 - e1
        elo = min(t for t in v if t >= e1 - 1.5 * iqr)
        ehi = max(t for t in v if t <= e3 + 1.5 * iqr)
        for got, want in ((q1, e1), (med, e2), (q3, e3), (lo, elo), (hi, ehi)):
            if abs(got - want) > 1e-9 * max(1, abs(want)):
                bad.append((name, got, want))
if mode == 'boxes':
    print('%d boxes checked' % boxes)
    sys.exit(1 if bad or boxes == 0 else 0)
print('%d series of 1 or 2 values' % small)
sys.exit(1 if bad or small == 0 else 0)
END
}
check "every box is type-7 quartiles and median, whiskers at 1.5 IQR" \
    boxes_check "$work/demo.gp" boxes
check "... for 3 values too (null planner, 3 runs per scene)" \
    boxes_check "$work/names.gp" boxes
check "... and 1 or 2 values are only dots" boxes_check "$work/names.gp" small
sqlite3 "$DB" "SELECT time_total FROM runs WHERE state = 'done'" >"$work/times.txt"
check "the time plot's values are the database's" python3 - "$work/demo.gp" "$work/times.txt" <<'END'
import re, sys
plot = [p for p in open(sys.argv[1]).read().split('\nreset\n') if 'plot-pillars-time.png' in p][0]
got = sorted(float(x) for name, text in re.findall(r'^\$(\w+) << EOD\n(.*?)^EOD$', plot, re.M | re.S)
             if name.startswith('b') for x in text.split())
want = sorted(float(x) for x in open(sys.argv[2]).read().split())
sys.exit(0 if len(got) == len(want) and all(abs(a - b) <= 1e-12 * max(1, abs(b)) for a, b in zip(got, want)) else 1)
END

# ---- names that clash in file names ---------------------------------------------
"$mpb" plot --format both -o "$work/names" "$NAMES" >"$work/names.out" 2>"$work/names.err"
check "mpb plot of the odd names exits 0" eq $? 0
check "... prints no path twice" eq "$(sort "$work/names.out" | uniq -d | wc -l)" 0
check "... and writes as many files as it prints paths" \
    eq "$(ls "$work/names" | wc -l)" "$(wc -l <"$work/names.out")"
check "... a time plot for each of the 6 scenes" \
    eq "$(grep -c -- '-time\.svg$' "$work/names.out")" 6
for f in __-1 __-2 a_b-3 a_b-4 a_b-3-5; do
    check "a scene whose file name another one has takes its id: plot-$f-time" \
        grep -qx "$work/names/plot-$f-time.svg" "$work/names.out"
done
svg_text "$work/names/plot-__-1-success.svg" >"$work/names1.txt"
svg_text "$work/names/plot-__-2-success.svg" >"$work/names2.txt"
check "scene 1 (台所) has its own success chart: 3 of 3" grep -qx "3 of 3" "$work/names1.txt"
check "... and scene 2 (倉庫) its own: 0 of 3" grep -qx "0 of 3" "$work/names2.txt"
"$mpb" plot --scene "a b" --format svg -o "$work/names-ab" "$NAMES" >"$work/names-ab.out"
check "... with nothing on stderr (no 'empty y range' for a straight path's smoothness, all 0)" \
    test ! -s "$work/names.err"
svg_text "$work/names/plot-__-1-time.svg" >"$work/names1-time.txt"
check "an unfinished experiment's plots say so: the time plot" \
    grep -q "UNFINISHED: 3 more runs not finished yet" "$work/names1-time.txt"
check "... the success chart" \
    grep -q "UNFINISHED: 3 more runs not finished yet" "$work/names1.txt"
check "... where a configuration has no finished run" \
    grep -qx "no finished run" "$work/names1.txt"
check "... and a path metric's plot" \
    grep -q "UNFINISHED: 3 more runs" "$work/names/plot-__-1-smoothness.svg"
check "a finished experiment's plots do not" \
    sh -c "! grep -q UNFINISHED '$work'/svg/*.svg"
check "--scene keeps the scene's file name" \
    grep -qx "$work/names-ab/plot-a_b-3-time.svg" "$work/names-ab.out"

# ---- names as they are, in lines that fit -------------------------------------
# The SVG's text: each name as the database has it (UTF-8, quotes,
# backquotes, backslash, $ and @ untouched), titles broken into lines of at
# most 95 characters (800 px) that, joined, give the whole title.
title_has() {
    python3 - "$@" <<'END'
import sys, xml.etree.ElementTree as E
texts = [''.join(t.itertext()) for t in E.parse(sys.argv[1]).iter()
         if t.tag.endswith('text')]
joined = ' '.join(texts)
long = [t for t in texts if len(t) > 95]
missing = [w for w in sys.argv[2:] if w not in joined]
if long or missing:
    print('too long:', long, 'missing:', missing)
    sys.exit(1)
END
}
long_name=$(sqlite3 "$NAMES" "SELECT name FROM scenes WHERE id = 6")
check "the long name's success chart names it whole, in lines that fit" \
    title_has "$(ls "$work"/names/plot-S_ule*-success.svg)" \
    "scene $long_name, 1 query pooled (experiment names 'odd' ü)"
check "scene 台所's titles name it, its configurations keep their ü" \
    title_has "$work/names/plot-__-1-time.svg" "scene 台所, 1 query pooled" \
    "null/straight_line#zwei ü"
check "the demo's smoothness title fits too" \
    title_has "$work/svg/plot-pillars-smoothness.svg" "Smoothness"
# A PNG draws 台 only when a font has it (else '?': pango would draw a box
# many times the text's size across the image).
GP_SCRIPT=$work/png.gp PATH=$work/bin:$PATH \
    "$mpb" plot --scene 台所 -o "$work/names-png" "$NAMES" >/dev/null
if [ -n "$(fc-list ':charset=53f0' family 2>/dev/null)" ]; then kitchen=台所; else kitchen='??'; fi
check "the PNG's title shows 台所 as $kitchen, as the fonts allow" \
    grep -q "^set title 'Planning time per run - scene $kitchen, 1 query" "$work/png.gp"
check "... and its ü as ü" grep -q "'null/straight_line#zwei ü'" "$work/png.gp"

# ---- errors -------------------------------------------------------------------
"$mpb" plot --scene kitchen -o "$work/none" "$DB" >/dev/null 2>"$work/scene.err"
check "an unknown scene exits 1" eq $? 1
check "... naming it and the scenes there are" \
    grep -qx "mpb plot: experiment 'demo' in $DB has no scene 'kitchen' (its scenes: pillars)" "$work/scene.err"

# An experiment whose runs never finished: the daemon stopped before any
# planner came.
"$MPB_BUILD/daemon/mpbenchd" -d "$work/empty.db" "$work/demo.yaml" >/dev/null 2>&1 &
daemon=$!
mpb_wait_count "$work/empty.db" 1 10 'SELECT count(*) FROM runs'
kill -TERM $daemon
wait $daemon
"$mpb" plot -o "$work/none" "$work/empty.db" >"$work/empty.out" 2>"$work/empty.err"
check "a database without finished runs exits 1" eq $? 1
check "... saying so in one line" \
    grep -qx "mpb plot: experiment 'demo' (id 1) in $work/empty.db has no finished runs to plot" "$work/empty.err"
check "... writing nothing" test ! -e "$work/none"

"$mpb" plot "$work/missing.db" >/dev/null 2>"$work/missing.err"
check "a missing database exits 1 naming it" \
    grep -qx "mpb plot: cannot open $work/missing.db: No such file or directory" "$work/missing.err"

PATH=/nonexistent "$mpb" plot -o "$work/nognuplot" "$DB" >/dev/null 2>"$work/nognuplot.err"
check "without gnuplot it exits 1" eq $? 1
check "... saying what to install" grep -q "^mpb plot: gnuplot not found on PATH" "$work/nognuplot.err"
check "... in that one line, no shell's 'not found' before it" \
    eq "$(wc -l <"$work/nognuplot.err")" 1

"$mpb" plot --format gif "$DB" >/dev/null 2>&1
check "an unknown format is a usage error" eq $? 2
"$mpb" plot --help | grep -q "box plot"
check "--help describes the plots" eq $? 0

mpb_finish
