"""peers_summary.py - the tables of docs/results-peers.md from a database
of the peers' experiments (mbm-panda-peers*.yaml).

Per planner and problem set (the query name before '/'): runs finished,
claimed (the planner answered SOLVED), verified (mpbench's success),
claimed but refused, time_total median and 95th percentile and path
length and smoothness medians over verified runs. Then every refused
claim by verdict: which link touched which object, in which stage, and
how deep in configuration space: the verifier's colliding segment sampled
again at 400 points with libmpbench's world (the kit's World), giving the
length in rad of the stretch in collision.

    MPB_LIBMPBENCH=build/libmpbench/libmpbench.so MPB_MESH_PATH=... \\
      .cache/peers/ompl2/bin/python3 bench/peers_summary.py DB [--no-depth]
"""
import math
import re
import sqlite3
import struct
import sys
from collections import Counter, defaultdict


def pct(xs, p):
    if not xs:
        return math.nan
    xs = sorted(xs)
    k = (len(xs) - 1) * p
    lo, hi = math.floor(k), math.ceil(k)
    return xs[lo] + (xs[hi] - xs[lo]) * (k - lo)


def fmt(x, d=3):
    return "-" if x is None or (isinstance(x, float) and math.isnan(x)) \
        else f"{x:.{d}f}"


def main(argv):
    db = sqlite3.connect(argv[1])
    depth = "--no-depth" not in argv
    rows = db.execute("""
        SELECT r.run, r.planner, r.query, r.status, r.success, r.verdict,
               r.message, r.time_total, r.path_length, r.smoothness,
               r.final_stage
        FROM results r ORDER BY r.planner, r.query""").fetchall()
    planners = []
    per = defaultdict(list)
    for row in rows:
        if row[1] not in planners:
            planners.append(row[1])
        per[(row[1], row[2].split("/")[0])].append(row)
        per[(row[1], "all")].append(row)
    sets = sorted({row[2].split("/")[0] for row in rows}) + ["all"]

    print("| planner | set | runs | claimed | verified | refused | "
          "time median (s) | time p95 (s) | path length median (rad) | "
          "smoothness median (rad^2) |")
    print("|---|---|---:|---:|---:|---:|---:|---:|---:|---:|")
    for p in planners:
        for s in sets:
            rs = per.get((p, s), [])
            if not rs:
                continue
            claimed = sum(1 for r in rs if r[3] == "solved")
            ok = [r for r in rs if r[4] == 1]
            refused = sum(1 for r in rs if r[3] == "solved" and r[4] != 1)
            t = [r[7] for r in ok if r[7] is not None]
            lp = [r[8] for r in ok if r[8] is not None]
            sm = [r[9] for r in ok if r[9] is not None]
            name = f"**{s}**" if s == "all" else s
            print(f"| {p} | {name} | {len(rs)} | {claimed} | {len(ok)} | "
                  f"{refused} | {fmt(pct(t, .5))} | {fmt(pct(t, .95))} | "
                  f"{fmt(pct(lp, .5), 2)} | {fmt(pct(sm, .5), 3)} |")

    # Every refused claim: stage verdicts of the run.
    print()
    print("Refused claims by verdict (the final stage's) and by the stage "
          "where each run's path first failed:")
    print()
    print("| planner | refused | verdicts | stages failed (first) | "
          "touching pairs (most frequent) |")
    print("|---|---:|---|---|---|")
    details = []
    for p in planners:
        rs = [r for r in per[(p, "all")] if r[3] == "solved" and r[4] != 1]
        if not rs:
            continue
        verdicts = Counter(r[5] for r in rs)
        pairs = Counter()
        first_bad = Counter()
        for r in rs:
            m = re.search(r"(\S+) touches (scene object \S+|\S+)", r[6] or "")
            if m:
                pairs[f"{m.group(1)} / {m.group(2).replace('scene object ', '')}"] += 1
            st = db.execute("SELECT name, valid FROM stages WHERE run_id = ? "
                            "ORDER BY idx", (r[0],)).fetchall()
            bad = [n for n, v in st if not v]
            first_bad[bad[0] if bad else "none"] += 1
            details.append(r)
        print(f"| {p} | {len(rs)} | "
              + ", ".join(f"{k} {v}" for k, v in verdicts.most_common())
              + " | " + ", ".join(f"{k} {v}" for k, v in first_bad.most_common())
              + " | " + ", ".join(f"{k} ({v})" for k, v in pairs.most_common(4))
              + " |")

    if not depth:
        return 0
    from mpbplanner.world import World
    print()
    print("How deep: each refused collision's segment sampled at 400 points "
          "with libmpbench's world; the stretch in collision (rad of joint "
          "motion) and its share of the segment:")
    print()
    print("| planner | refused for collision | stretch median (rad) | "
          "stretch max (rad) | share median |")
    print("|---|---:|---:|---:|---:|")
    worlds = {}
    stretch = defaultdict(list)
    for r in details:
        if r[5] != "collision":
            continue
        m = re.search(r"final stage (\d+) .* segment (\d+) collides", r[6] or "")
        if not m:
            continue
        idx, seg = int(m.group(1)), int(m.group(2))
        sc = db.execute("""SELECT s.id, s.robot_format, s.robot, s.scene_format,
                                  s.scene, q.joint_names
                           FROM runs u JOIN queries q ON q.id = u.query_id
                           JOIN scenes s ON s.id = q.scene_id
                           WHERE u.id = ?""", (r[0],)).fetchone()
        if sc[0] not in worlds:
            for w in worlds.values():
                w.close()
            worlds.clear()
            worlds[sc[0]] = World(sc[1], sc[2], sc[3], sc[4], sc[5].split())
        w = worlds[sc[0]]
        nw, nj, blob = db.execute(
            "SELECT num_waypoints, num_joints, waypoints FROM stages "
            "WHERE run_id = ? AND idx = ?", (r[0], idx)).fetchone()
        vals = struct.unpack(f"<{nw * nj}d", blob)
        a, b = vals[seg * nj:(seg + 1) * nj], vals[(seg + 1) * nj:(seg + 2) * nj]
        seglen = math.sqrt(sum((y - x) ** 2 for x, y in zip(a, b)))
        n = 400
        hit = sum(0 if w.free([x + (y - x) * k / n for x, y in zip(a, b)])
                  else 1 for k in range(n + 1))
        stretch[r[1]].append((seglen * hit / (n + 1), hit / (n + 1)))
    for p in planners:
        xs = stretch.get(p)
        if not xs:
            continue
        print(f"| {p} | {len(xs)} | {fmt(pct([x for x, _ in xs], .5), 4)} | "
              f"{fmt(max(x for x, _ in xs), 4)} | "
              f"{fmt(100 * pct([f for _, f in xs], .5), 1)}% |")
    return 0


if __name__ == "__main__":
    if len(sys.argv) < 2:
        print("usage: peers_summary.py DB [--no-depth]", file=sys.stderr)
        sys.exit(2)
    sys.exit(main(sys.argv))
