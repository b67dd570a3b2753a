"""replay_log.py - test tool: publish again what an lcm-logger log
recorded, as an attacker on the network could.

    python3 replay_log.py LOG REGEX [SPEED]

Publishes, in order and with the gaps between them as recorded (divided by
SPEED, default 1), every message of LOG whose channel matches REGEX (the
whole channel name), byte for byte; then prints how many on each channel
("MPB_STATUS 12"), one line each, sorted by channel.
"""
import re
import sys
import time

import lcm


def main():
    if len(sys.argv) not in (3, 4):
        print(__doc__.strip(), file=sys.stderr)
        return 2
    log, pattern = sys.argv[1], re.compile(sys.argv[2])
    speed = float(sys.argv[3]) if len(sys.argv) == 4 else 1.0
    lc = lcm.LCM()
    counts = {}
    first = start = None
    for event in lcm.EventLog(log, "r"):
        if not pattern.fullmatch(event.channel):
            continue
        if first is None:
            first, start = event.timestamp, time.monotonic()
        due = start + (event.timestamp - first) / 1e6 / speed
        wait = due - time.monotonic()
        if wait > 0:
            time.sleep(wait)
        lc.publish(event.channel, event.data)
        counts[event.channel] = counts.get(event.channel, 0) + 1
    for channel in sorted(counts):
        print(channel, counts[channel])
    return 0


if __name__ == "__main__":
    sys.exit(main())
