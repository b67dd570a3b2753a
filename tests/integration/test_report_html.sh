#!/bin/sh
# mpb report --format html: one self-contained page of an experiment (a
# planar one: the null planner, whose line over the pillar fails, beside
# OMPL's RRTConnect and RRT): the paper's table with each configuration,
# the plots of mpb plot inlined as SVG, the findings, and every failed
# run linked to its mpb view page. Written with -o, the page has those
# views beside it (views/run-ID.html), one per link; written to stdout, it
# says how to make them. Opened in headless Chromium: the plots show, and
# the first link opens a drawn 3-D view. Every number of every table, read
# from the page Chromium renders, is the number of mpb report --format
# json, rounded as the page prints it; a page with one number off fails
# that check. Without gnuplot the page is still written and says why it
# has no plots.
#
# MPB_REPORT_SCREENSHOT=FILE keeps the screenshot of the page there (how
# docs/images/report-html.png is made); MPB_KEEP=1 keeps the work folder.
set -u
. "$MPB_SOURCE/tests/integration/lib.sh"
mpb_enter_netns "$0" "$@"

work=$(mktemp -d)
trap 'mpb_stop_all; [ -n "${MPB_KEEP:-}" ] || rm -rf "$work"' EXIT
DB=$work/report.db
mpb=$MPB_BUILD/tools/mpb
export MPB_WEB_MODULES="$MPB_SOURCE/.cache/web/node_modules"

MPB_QUERIES='{name: a, start: [0, 0, 0], goal: [0.3, -0.2, 0.1], tolerance: 0.01}
{name: over_the_pillar, start: [0, 0, 0], goal: [2.6, 0, 0], tolerance: 0.01}' \
    mpb_planar_experiment "$work/exp.yaml" "name: html-report, runs: 3, time_limit: 2" \
    "{planner: null, algorithms: [straight_line]}" \
    "{planner: ompl, algorithms: [RRTConnect, RRT]}"
mpb_spawn "$work/null.log" "$MPB_BUILD/planners/null/mpb-planner-null"
mpb_spawn "$work/ompl.log" "$MPB_BUILD/planners/ompl/mpb-planner-ompl"
mpb_timeout 120 "$MPB_BUILD/daemon/mpbenchd" -d "$DB" "$work/exp.yaml" >"$work/daemon.log" 2>&1
check "the experiment completes" eq $? 0

mkdir "$work/site" "$work/tmp"
TMPDIR=$work/tmp "$mpb" report --format html -o "$work/site/report.html" "$DB" \
    >"$work/report.out" 2>"$work/report.err"
check "mpb report --format html -o FILE writes the page" eq $? 0
check "... saying nothing on stdout or stderr" \
    test ! -s "$work/report.out" -a ! -s "$work/report.err"
page=$work/site/report.html
check "... and nothing else beside it but views/" \
    test "$(ls "$work/site")" = "$(printf 'report.html\nviews')"
for c in null/straight_line ompl/RRTConnect ompl/RRT; do
    check "... the table has a column for $c" grep -q "<th>$c</th>" "$page"
done
# The columns grouped by approach: OMPL's (sampling) first, then the null
# planner's, which declares none.
check "... the success rates of the text report" \
    grep -q '<tr><td>s_r (%)</td><td>100.0</td><td>100.0</td><td>50.0</td></tr>' "$page"
check "... and its claims: the null planner's refused over the pillar" \
    grep -q '<tr><td>refused claims</td><td>0</td><td>0</td><td>3</td></tr>' "$page"
check "... six plots inlined as SVG (time, success, four path metrics)" \
    test "$(grep -c '^<svg' "$page")" = 6
check "... and no file of theirs left behind" test -z "$(ls "$work/tmp")"
failed=$(q "SELECT group_concat(id, ' ') FROM runs WHERE success = 0")
check "three runs failed (the null planner's over the pillar)" \
    test "$(echo $failed | wc -w)" = 3
for id in $failed; do
    check "... run $id is linked to its view" grep -q "href=\"views/run-$id.html\"" "$page"
    check "... which is written beside the page" \
        grep -q "^<!DOCTYPE html>" "$work/site/views/run-$id.html"
done
check "... no successful run is" \
    test "$(grep -o 'href="views/run-[0-9]*.html"' "$page" | wc -l)" = 3
check "... and views/ holds those three pages only" \
    test "$(ls "$work/site/views" | wc -l)" = 3
check "... the findings are there" grep -q 'What the tables say' "$page"
check "... with the paired tests' part" grep -q 'no significant difference' "$page"
# At the top: the table over all problems, the budget curves (one plot:
# one set; a solid and a dotted curve per configuration), the matrix.
check "... the table over all problems first" \
    test "$(grep -n -m1 '<h2>' "$page" | cut -d: -f2-)" = '<h2>All problems</h2>'
check "... its median row" grep -q '<tr><td>tau_t (median, s)</td>' "$page"
check "... one budget plot of six curves" \
    test "$(grep -c '<svg class="budget"' "$page")" = 1 -a \
         "$(grep -c '<path class="curve' "$page")" = 6
check "... and the comparison matrix" grep -q '<table class="matrix">' "$page"
check "... the scene's detail after them, open (no sets to fold under)" \
    grep -q '^<details open><summary>scene ' "$page"

# To stdout, the same page, saying how to make the views.
TMPDIR=$work/tmp "$mpb" report --format html "$DB" >"$work/stdout.html" 2>"$work/stdout.err"
check "mpb report --format html to stdout" eq $? 0
check "... links the same runs" test "$(grep -o 'href="views/run-[0-9]*.html"' "$work/stdout.html")" = \
    "$(grep -o 'href="views/run-[0-9]*.html"' "$page")"
check "... and says how to make their views" \
    grep -q 'id="make-views".*mpb report --format html -o report.html' "$work/stdout.html"
check "... which the page written with -o does not" test "$(grep -c make-views "$page")" = 0

# A failed run with no stages (as when a planner returns no path) has no
# view to draw: no link, and its row says why.
first=${failed%% *}
sqlite3 "$DB" ".backup '$work/nostages.db'" &&
    sqlite3 "$work/nostages.db" "DELETE FROM stages WHERE run_id = $first"
mkdir "$work/nostages"
"$mpb" report --format html -o "$work/nostages/report.html" "$work/nostages.db" \
    >"$work/nostages.out" 2>&1
check "a report whose failed run $first has no stages is written" eq $? 0
check "... saying nothing" test ! -s "$work/nostages.out"
check "... that run not linked" \
    test "$(grep -c "href=\"views/run-$first.html\"" "$work/nostages/report.html")" = 0
check "... its row saying why" \
    grep -q "^<tr><td>$first</td>.*(no view: no stages to draw" "$work/nostages/report.html"
check "... the other two linked, their views written" \
    test "$(grep -o 'href="views/run-[0-9]*.html"' "$work/nostages/report.html" | wc -l)" = 2 \
    -a "$(ls "$work/nostages/views" | wc -l)" = 2

# A report that cannot be written, or whose views cannot be drawn: one
# line, exit 1, no page left.
"$mpb" report --format html -o "$work/missing/report.html" "$DB" >"$work/bad.out" 2>"$work/bad.err"
check "-o into a missing folder fails" eq $? 1
check "... with one line" test "$(wc -l <"$work/bad.err")" = 1
MPB_THREE_JS=/nonexistent "$mpb" report --format html -o "$work/nothree.html" "$DB" \
    >"$work/bad.out" 2>"$work/bad.err"
check "-o without three.js for the views fails" eq $? 1
check "... with one line naming it" grep -q 'cannot read three.js at /nonexistent' "$work/bad.err"
check "... that line only" test "$(wc -l <"$work/bad.err")" = 1
check "... leaving no page" test ! -e "$work/nothree.html" -a ! -e "$work/nothree.html.tmp"
"$mpb" report --format json -o "$work/report-o.json" "$DB" >"$work/json.out"
check "-o writes the other formats too" eq $? 0
"$mpb" report --format json "$DB" >"$work/report.json"
check "mpb report --format json writes the same numbers as JSON" eq $? 0
check "... the same with -o FILE" cmp -s "$work/report.json" "$work/report-o.json"
node "$MPB_SOURCE/tests/integration/report_html_check.js" "$page" 6 "$work/report.json" \
    "$work/report.png" >"$work/check.out" 2>&1
status=$?
sed 's/^/    /' "$work/check.out"
check "headless Chromium: the report and its first link pass every check" eq $status 0
if [ -n "${MPB_REPORT_SCREENSHOT:-}" ] && [ -f "$work/report.png" ]; then
    cp "$work/report.png" "$MPB_REPORT_SCREENSHOT"
fi
check "... its tables checked against the JSON" \
    grep -q '^ok - every number of every table is the JSON' "$work/check.out"

# One number off, the last digit of its first cell (before any exponent)
# changed: the check must see it.
# The scene's table: the last tau_t row (the one over all problems is
# first, the same numbers).
last=$(grep -n '^<tr><td>tau_t (Mean, s)</td>' "$page" | tail -1 | cut -d: -f1)
awk -v last="$last" 'NR == last {
        i = index($0, "</td><td>") + 8; rest = substr($0, i + 1)
        cell = substr(rest, 1, index(rest, "</td>") - 1)
        k = match(cell, /[0-9](e[-+][0-9]+)?$/); d = substr(cell, k, 1)
        $0 = substr($0, 1, i + k - 1) ((d + 1) % 10) substr(rest, k + 1)
        done = 1
    } { print }' "$page" >"$work/site/perturbed.html"
check "a page with one number of tau_t changed" \
    test "$(diff "$page" "$work/site/perturbed.html" | grep -c '^>')" = 1
node "$MPB_SOURCE/tests/integration/report_html_check.js" "$work/site/perturbed.html" 6 \
    "$work/report.json" >"$work/perturbed.out" 2>&1
status=$?
sed 's/^/    /' "$work/perturbed.out"
check "... fails the check" test $status -ne 0
check "... on that number" \
    grep -q "^not ok - every number of every table.*tau_t (Mean, s), ompl/RRTConnect: the page" \
    "$work/perturbed.out"

# Without gnuplot: the page, saying why there are no plots.
PATH=/nonexistent "$mpb" report --format html "$DB" >"$work/noplot.html" 2>"$work/noplot.err"
check "without gnuplot the page is still written" eq $? 0
check "... without mpb plot's plots" test "$(grep -c '^<svg' "$work/noplot.html")" = 0
check "... but with the budget curves, which need no gnuplot" \
    test "$(grep -c '<path class="curve' "$work/noplot.html")" = 6
check "... saying why" grep -q 'No plots: mpb plot did not draw them' "$work/noplot.html"
check "... and mpb plot's own line on stderr" grep -q 'gnuplot' "$work/noplot.err"

mpb_finish
