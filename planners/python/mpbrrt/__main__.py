"""mpb-planner-python: an mpbench planner written in Python.

RRT-Connect in joint space with a shortcut stage, collision checks by
libmpbench (through ctypes), messages by the PyPI `lcm` package. A worked
example for docs/writing-a-planner.md as much as a planner.
"""
import argparse
import signal
import sys

from mpbplanner.auth import Auth, AuthError
from mpbplanner.node import Node, name_error
from mpbplanner.request import WorldCache

from .solve import solve

ALGORITHMS = ["RRTConnect"]


class _Parser(argparse.ArgumentParser):
    """A bad command line in one line, as the other mpbench programs say
    it (argparse prints the usage too)."""

    def error(self, message):
        print(f"{self.prog}: {message} (try --help)", file=sys.stderr)
        sys.exit(2)


def main(argv=None):
    ap = _Parser(
        prog="mpb-planner-python",
        description="An mpbench planner in Python: answers plan requests "
                    "from mpbenchd with RRT-Connect (stages raw and "
                    "shortcut). Params: range (rad, default 0.5), "
                    "resolution (rad, default 0.005), allocate (MB held "
                    "while planning, for tests of memory_limit; default 0).",
        epilog="Stops on SIGINT or SIGTERM. Protocol: docs/protocol.md; "
               "how it is written: docs/writing-a-planner.md.")
    ap.add_argument("-u", "--lcm-url", default="",
                    help="LCM URL (default: LCM's, udpm://239.255.76.67:7667?ttl=0)")
    ap.add_argument("-s", "--secret-file", metavar="FILE",
                    help="sign and check every message with this shared "
                         "secret, as mpbenchd --secret-file does")
    ap.add_argument("-n", "--name", default="python",
                    help="planner family announced (default: python)")
    ap.add_argument("-v", "--verbose", action="store_true",
                    help="log each run to stderr")
    args = ap.parse_args(argv)
    error = name_error(args.name)
    if error:
        print(f"mpb-planner-python: {error} (see --help)", file=sys.stderr)
        return 2

    try:
        auth = Auth(args.secret_file) if args.secret_file else None
    except AuthError as e:      # libmpbench's line, naming the file
        print(f"mpb-planner-python: {e}", file=sys.stderr)
        return 1
    try:
        node = Node(args.name, ALGORITHMS, args.lcm_url, auth, args.verbose,
                    {a: "sampling" for a in ALGORITHMS})
    except Exception as e:
        print(f"mpb-planner-python: cannot start LCM: {e}", file=sys.stderr)
        return 1
    signal.signal(signal.SIGTERM, lambda *_: node.stop())
    signal.signal(signal.SIGINT, lambda *_: node.stop())
    cache = WorldCache()
    node.log(f"{node.planner_id} ready: {', '.join(ALGORITHMS)}")
    node.serve(lambda req, limits: solve(req, cache, limits))
    return 0


if __name__ == "__main__":
    sys.exit(main())
