"""approaches_summary.py - the tables of docs/results-approaches.md from a
database of mbm-panda-approaches*.yaml: per planner configuration, in
approach order, runs finished, claimed (SOLVED), verified (mpbench's
success), refused claims by verdict, late, unclaimed valid paths, the
time median and 95th percentile and the path length and smoothness
medians over verified runs; then verified successes per problem set (the
scene's name before '/').

    python3 bench/approaches_summary.py DB|RUNS.csv...

Each argument is a results database or its runs as `mpb export
--runs-csv` writes them (bench/approaches_shard.sh's shards); the tables
are over all of them together.
"""
import csv
import math
import sqlite3
import sys
from collections import Counter, defaultdict

ORDER = {"sampling": 0, "search": 1, "optimisation": 2, "hybrid": 3}


def pct(xs, p):
    if not xs:
        return math.nan
    xs = sorted(xs)
    k = (len(xs) - 1) * p
    lo, hi = math.floor(k), math.ceil(k)
    return xs[lo] + (xs[hi] - xs[lo]) * (k - lo)


def fmt(x, d=2):
    return "-" if x is None or (isinstance(x, float) and math.isnan(x)) \
        else f"{x:.{d}f}"


COLUMNS = ("planner", "approach", "scene", "outcome", "verdict",
           "time_total", "path_length", "smoothness")


def number(text):
    return float(text) if text not in ("", None) else None


def read_runs(path):
    """One tuple of COLUMNS per finished run of a database or a CSV."""
    if path.endswith(".csv"):
        with open(path, newline="") as f:
            return [tuple(r[c] or "" for c in COLUMNS[:5]) +
                    tuple(number(r[c]) for c in COLUMNS[5:])
                    for r in csv.DictReader(f)]
    db = sqlite3.connect(f"file:{path}?mode=ro", uri=True)
    return db.execute(
        "SELECT planner, coalesce(approach, ''), scene, outcome, verdict, "
        "time_total, path_length, smoothness FROM results").fetchall()


def main(argv):
    if len(argv) < 2 or argv[1] in ("-h", "--help"):
        print(__doc__.strip())
        return 0 if len(argv) >= 2 else 2
    rows = [r for path in argv[1:] for r in read_runs(path)]
    by = defaultdict(list)
    for r in rows:
        by[(r[0], r[1])].append(r)
    configs = sorted(by, key=lambda k: (ORDER.get(k[1], 9), k[0]))
    print("| configuration | approach | runs | claimed | verified | refused "
          "(verdict) | late | unclaimed valid | time median / p95, verified "
          "(s) | path length median (rad) | smoothness median |")
    print("|---|---|---:|---:|---:|---|---:|---:|---|---:|---:|")
    for k in configs:
        rs = by[k]
        out = Counter(r[3] for r in rs)
        refused = Counter(r[4] for r in rs if r[3] == "refused")
        ok = [r for r in rs if r[3] == "verified"]
        t = [r[5] for r in ok if r[5] is not None]
        lengths = [r[6] for r in ok if r[6] is not None]
        smooth = [r[7] for r in ok if r[7] is not None]
        claimed = out["verified"] + out["refused"] + out["late"]
        ref = ", ".join(f"{n} {v}" for v, n in refused.most_common()) or "0"
        print(f"| {k[0]} | {k[1] or '-'} | {len(rs)} | {claimed} | "
              f"{out['verified']} | {ref if out['refused'] else '0'} | "
              f"{out['late']} | {out['unclaimed_valid']} | "
              f"{fmt(pct(t, 0.5))} / {fmt(pct(t, 0.95))} | "
              f"{fmt(pct(lengths, 0.5))} | {fmt(pct(smooth, 0.5), 3)} |")
    sets = sorted({r[2].rsplit("/", 1)[0] for r in rows})
    print()
    print("| configuration | " + " | ".join(s.replace("_panda", "")
                                            for s in sets) + " |")
    print("|---|" + "---:|" * len(sets))
    for k in configs:
        cells = []
        for s in sets:
            rs = [r for r in by[k] if r[2].rsplit("/", 1)[0] == s]
            cells.append(f"{sum(r[3] == 'verified' for r in rs)}/{len(rs)}")
        print(f"| {k[0]} | " + " | ".join(cells) + " |")


if __name__ == "__main__":
    sys.exit(main(sys.argv))
