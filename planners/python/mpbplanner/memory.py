"""memory.py - a run's peak memory and memory limit, as the C kit does
them (docs/protocol.md, "Memory").

Around solve() alone: the process's peak resident size (VmHWM) is reset
by writing "5" to /proc/self/clear_refs and read after, in MB; with a
request's memory_limit above 0, RLIMIT_DATA is lowered to the process's
data size (VmData) plus that many MB for the solve and restored after,
so that an allocation past it raises MemoryError. Where the reset is not
available the peak is the process's since it started; where
/proc/self/status is not, it is NaN (not measured).
"""
from __future__ import annotations

import math
from typing import Optional

try:
    import resource
except ImportError:             # not POSIX: no limit
    resource = None


def _status_kb(key: str) -> Optional[int]:
    try:
        with open("/proc/self/status", encoding="ascii",
                  errors="replace") as f:
            for line in f:
                if line.startswith(key + ":"):
                    return int(line.split()[1])
    except (OSError, ValueError, IndexError):
        pass
    return None


class Watch:
    """with Watch(limit_mb) as w: solve ...; then w.peak_mb, w.note."""

    def __init__(self, limit_mb: float) -> None:
        self.limit_mb = limit_mb if limit_mb and limit_mb > 0 and \
            math.isfinite(limit_mb) else 0.0
        self.old = None
        self.reset = False
        self.peak_mb = math.nan
        self.note = ""          # why the limit was not set, if it was not

    def __enter__(self) -> Watch:
        try:
            with open("/proc/self/clear_refs", "w", encoding="ascii") as f:
                f.write("5")
            self.reset = True
        except OSError:
            pass
        if self.limit_mb > 0:
            data_kb = _status_kb("VmData")
            if resource is None or data_kb is None:
                self.note = (f"memory_limit {self.limit_mb:g} MB not "
                             f"enforced: cannot read the process's data size")
                return self
            try:
                self.old = resource.getrlimit(resource.RLIMIT_DATA)
                want = int((data_kb / 1024.0 + self.limit_mb) * 1048576)
                hard = self.old[1]
                if hard != resource.RLIM_INFINITY and want > hard:
                    want = hard
                resource.setrlimit(resource.RLIMIT_DATA, (want, hard))
            except (OSError, ValueError) as e:
                self.old = None
                self.note = (f"memory_limit {self.limit_mb:g} MB not "
                             f"enforced: setrlimit(RLIMIT_DATA): {e}")
        return self

    def __exit__(self, *exc: object) -> bool:
        if self.old is not None:
            resource.setrlimit(resource.RLIMIT_DATA, self.old)
            self.old = None
        hwm = _status_kb("VmHWM")
        self.peak_mb = hwm / 1024.0 if hwm else math.nan
        return False
