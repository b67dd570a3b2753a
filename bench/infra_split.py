"""infra_split.py - bench/infra.sh's breakdown of the daemon's wall time
from an lcm-logger log of the run and its database.

    python3 infra_split.py TYPES LOG DB MODE ROUND

TYPES is the build's lcmtypes/python. With one planner, every run's
request and result are in the log (the logger's receive time, Unix us;
re-sends after the first copy are not counted), and the database has its
time_total, world_setup_time, verify_time and finished (Unix s). A run
the logger missed (unlogged=N) is placed by the database alone. Then,
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
                req.setdefault(plan_request_t.decode(event.data).attempt_id, t)
            elif event.channel == "MPB_RESULT":
                res.setdefault(plan_result_t.decode(event.data).attempt_id, t)
        except ValueError:
            pass        # another type on the channel: not ours
    rows = sqlite3.connect(db).execute(
        "SELECT attempt_id, time_total, coalesce(world_setup_time, 0),"
        " coalesce(verify_time, 0), finished, finished - wall_time"
        " FROM runs WHERE state = 'done' AND time_total IS NOT NULL").fetchall()
    # A run whose request or result the logger missed (a datagram dropped
    # under load): sent when the database says (finished - wall_time),
    # answered as soon as it was planned; its way counts as the daemon's.
    runs = sorted((req.get(u, sent), res.get(u, req.get(u, sent) + tau + setup),
                   tau, setup, ver, fin)
                  for u, tau, setup, ver, fin, sent in rows)
    unlogged = sum(1 for r in rows if r[0] not in req or r[0] not in res)
    if len(runs) < 2:
        print("infra_split.py: %d runs in %s" % (len(runs), db), file=sys.stderr)
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
          "verify_beside=%.4f first_setup_s=%.3f unlogged=%d"
          % (mode, rnd, len(runs), wall, tau, 1 - tau / wall, setup / wall,
             planner / wall, daemon / wall, tail / wall,
             sum(r[4] for r in runs) / wall, runs[0][3], unlogged))
    return 0


if __name__ == "__main__":
    sys.exit(main())
