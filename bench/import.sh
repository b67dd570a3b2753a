#!/bin/sh
# bench/import.sh - issue 7, item 6: an OMPL benchmark log of at least
# 50,000 runs into a Planner Arena database: `mpb import -p` (straight
# into it), and `mpb import -d` + `mpb export --planner-arena` (through an
# mpbench database), against OMPL's own ompl_benchmark_statistics.py, on
# the same log, on this machine, in the same run. Prints the time of each
# (-p and the script: the median of MPB_IMPORT_REPS, default 5, taken in
# turns; through a database: of 3), the ratios, and whether the databases
# hold the same rows, cell by cell (tests/tools/same_database.py).
#
#   bench/import.sh [RUNS]            (default 50000)
#
# The log is written by OMPL 1.5's ompl::tools::Benchmark (the test helper
# mpb-test-ompl-log), its runs repeated until there are RUNS of them.
# OMPL's script is not part of mpbench: OMPL_STATS names it, or else
# bench/ompl_peer.sh takes it from Debian's source package of the
# installed OMPL (that needs the network); without it only mpbench's side
# is timed. MPB_BUILD is the build tree.
set -eu
root=$(cd "$(dirname "$0")/.." && pwd)
. "$root/tools/usage.sh"
mpb_no_options "$@"
BUILD=${MPB_BUILD:-$root/build}
RUNS=${1:-50000}
mpb=$BUILD/tools/mpb
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

cmake --build "$BUILD" --target mpb mpb-test-ompl-log >/dev/null
"$BUILD/tests/mpb-test-ompl-log" "$work/base.log" 100 0.01

# Repeat each planner's run lines (and progress lines) k times.
python3 - "$work/base.log" "$work/big.log" "$RUNS" <<'EOF'
import math, sys
lines = open(sys.argv[1]).read().split("\n")
i = next(k for k, l in enumerate(lines) if l.endswith(" planners"))
planners = int(lines[i].split()[0])
out, j, blocks = lines[:i + 1], i + 1, []
for _ in range(planners):
    b = {"head": [lines[j]]}; j += 1
    c = int(lines[j].split()[0]); b["head"] += lines[j:j + 1 + c]; j += 1 + c
    p = int(lines[j].split()[0]); b["head"] += lines[j:j + 1 + p]; j += 1 + p
    n = int(lines[j].split()[0]); b["runs"] = lines[j + 1:j + 1 + n]; j += 1 + n
    b["prog_head"], b["prog"] = [], []
    if lines[j] != ".":
        q = int(lines[j].split()[0]); b["prog_head"] = lines[j:j + 1 + q]; j += 1 + q
        j += 1; b["prog"] = lines[j:j + n]; j += n
    j += 1
    blocks.append(b)
total = sum(len(b["runs"]) for b in blocks)
k = math.ceil(int(sys.argv[3]) / total)
for b in blocks:
    n = len(b["runs"]) * k
    out += b["head"] + ["%d runs" % n] + b["runs"] * k
    if b["prog_head"]:
        out += b["prog_head"] + ["%d runs" % n] + b["prog"] * k
    out.append(".")
open(sys.argv[2], "w").write("\n".join(out) + "\n")
print("log: %d runs (%d written by OMPL's Benchmark, x%d), %.1f MB"
      % (total * k, total, k, sum(len(l) + 1 for l in out) / 1e6))
EOF

now() { date +%s.%N; }
median() { printf '%s\n' "$@" | sort -g | awk '{v[NR] = $1} END {print v[int((NR + 1) / 2)]}'; }

time_mpb() {
    rm -f "$work/mpb.db"* "$work/arena.db"
    t0=$(now)
    "$mpb" import -d "$work/mpb.db" "$work/big.log" >/dev/null
    "$mpb" export --planner-arena "$work/mpb.db" "$work/arena.db" >/dev/null
    t1=$(now)
    echo "$t1 - $t0" | bc
}
time_direct() {
    rm -f "$work/direct.db"
    t0=$(now)
    "$mpb" import -p "$work/direct.db" "$work/big.log" >/dev/null
    t1=$(now)
    echo "$t1 - $t0" | bc
}
time_ompl() {
    rm -f "$work/ompl.db"
    t0=$(now)
    python3 "$OMPL_STATS" -d "$work/ompl.db" "$work/big.log" >/dev/null 2>&1
    t1=$(now)
    echo "$t1 - $t0" | bc
}

# mpb import -p and the script in turns, REPS times each, so that a load
# that comes and goes weighs on both alike: the medians, and the median of
# the ratios of each pair.
REPS=${MPB_IMPORT_REPS:-5}
have_ompl=0
[ -n "${OMPL_STATS:-}" ] || OMPL_STATS=$(MPB_BUILD=$BUILD sh "$root/bench/ompl_peer.sh") || true
[ -n "${OMPL_STATS:-}" ] && [ -f "$OMPL_STATS" ] && have_ompl=1
ds= os= rs=
i=0
while [ $i -lt "$REPS" ]; do
    x=$(time_direct)
    ds="$ds $x"
    if [ $have_ompl = 1 ]; then
        y=$(time_ompl)
        os="$os $y"
        rs="$rs $(echo "scale=3; $y / $x" | bc)"
    fi
    i=$((i + 1))
done
d=$(median $ds)
echo "mpb import -p (straight into Planner Arena): $d s (median of $REPS:$ds)"
m=$(median "$(time_mpb)" "$(time_mpb)" "$(time_mpb)")
echo "mpb import -d + export --planner-arena: $m s"
if [ $have_ompl = 0 ]; then
    echo "no ompl_benchmark_statistics.py (OMPL_STATS, bench/ompl_peer.sh): OMPL's side not timed"
    echo "RESULT import runs=$RUNS direct_s=$d mpb_s=$m"
    exit 0
fi
o=$(median $os)
echo "ompl_benchmark_statistics.py:          $o s (median of $REPS:$os)"
ratio=$(echo "scale=2; $o / $d" | bc)
ratio_db=$(echo "scale=2; $o / $m" | bc)
paired=$(median $rs)
echo "ratio per pair (script / mpb import -p):$rs, median ${paired}x"
echo "ratio (OMPL's script / mpb import -p): ${ratio}x"
echo "ratio (OMPL's script / mpb import -d + export): ${ratio_db}x"

# The same rows, every cell with its type (tests/tools/same_database.py):
# -p's database is the script's, every table. The one made through an
# mpbench database is told apart (same_via_db): its experiments, runs and
# progress, property by property and by value (its planners are named
# mpbench's way, its planners' own numbers are reals).
same_db() { python3 "$root/tests/tools/same_database.py" "$@" >"$work/same.out"; }
if same_db "$work/ompl.db" "$work/direct.db"; then
    same=yes
    echo "same rows (-p): yes, every cell of every table"
else
    same=no
    echo "same rows (-p): NO"; head -n 21 "$work/same.out"
fi
if same_db --properties --values "$work/ompl.db" "$work/arena.db"; then
    same_db=yes
    echo "same experiments, runs and progress (-d + export): yes"
else
    same_db=no
    echo "same experiments, runs and progress (-d + export): NO"; head -n 21 "$work/same.out"
fi
echo "RESULT import runs=$RUNS direct_s=$d mpb_s=$m ompl_s=$o ratio=$ratio paired_ratio=$paired ratio_via_db=$ratio_db same_rows=$same same_via_db=$same_db"
