"""infra_split.py - bench/infra.sh's breakdown of the daemon's wall time
from an lcm-logger log of the run and its database.

    python3 infra_split.py TYPES LOG DB MODE ROUND

TYPES is the build's lcmtypes/python. With one planner, every run's
request and result are in the log (the logger's receive time, Unix us;
re-sends after the first copy are not counted), and the database has its
time_total, world_setup_time, verify_time and finished (Unix s). Then,
over the runs in the order of their requests:

    wall   = last result stored - first request published
           = sum(time_total) + setup + planner + daemon + tail

  setup    sum(world_setup_time): the planner opening each scene's world
  planner  sum(result published - request published - time_total -
           world_setup_time): the messages' way there and back and the
           planner kit's untimed work
  daemon   sum(next request published - result published): the loop
           handing the result over and sending the next request
  tail     last result stored - its publication: its verification, and
           whatever verification was still waiting for the worker

and verify_beside = sum(verify_time) / wall (above 1: the worker could
not keep up). Prints one RESULT line, shares of wall.
"""
import sqlite3
import sys


def main():
    if len(sys.argv) != 6:
        print(__doc__.strip(), file=sys.stderr)
        return 2
    types, log, db, mode, rnd = sys.argv[1:]
    sys.path.insert(0, types)
    import lcm
    from mpb import plan_request_t, plan_result_t

    req, res = {}, {}
    for event in lcm.EventLog(log, "r"):
        t = event.timestamp / 1e6
        try:
            if event.channel.startswith("MPB_REQUEST"):
                req.setdefault(plan_request_t.decode(event.data).run_id, t)
            elif event.channel == "MPB_RESULT":
                res.setdefault(plan_result_t.decode(event.data).run_id, t)
        except ValueError:
            pass        # another type on the channel: not ours
    rows = sqlite3.connect(db).execute(
        "SELECT run_uid, time_total, coalesce(world_setup_time, 0),"
        " coalesce(verify_time, 0), finished FROM runs WHERE state = 'done'"
        " AND time_total IS NOT NULL").fetchall()
    runs = sorted((req[u], res[u], tau, setup, ver, fin)
                  for u, tau, setup, ver, fin in rows if u in req and u in res)
    if len(runs) < 2 or len(runs) != len(rows):
        print("infra_split.py: %d of %d runs found in %s" % (len(runs), len(rows), log),
              file=sys.stderr)
        return 1
    last = max(r[5] for r in runs)
    wall = last - runs[0][0]
    tau = sum(r[2] for r in runs)
    setup = sum(r[3] for r in runs)
    planner = sum(r[1] - r[0] - r[2] - r[3] for r in runs)
    daemon = sum(runs[i + 1][0] - runs[i][1] for i in range(len(runs) - 1))
    tail = last - runs[-1][1]
    print("RESULT infra verification=%s round=%s runs=%d wall_s=%.3f tau_s=%.3f "
          "share=%.4f setup=%.4f planner=%.4f daemon=%.4f tail=%.4f "
          "verify_beside=%.4f first_setup_s=%.3f"
          % (mode, rnd, len(runs), wall, tau, 1 - tau / wall, setup / wall,
             planner / wall, daemon / wall, tail / wall,
             sum(r[4] for r in runs) / wall, runs[0][3]))
    return 0


if __name__ == "__main__":
    sys.exit(main())
