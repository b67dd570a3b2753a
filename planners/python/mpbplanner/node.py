"""node.py - the protocol of docs/protocol.md, spoken with the PyPI `lcm`
package and the generated Python types.

One thread (the caller's) plans; another runs LCM: it takes requests into a
queue, acknowledges them, announces the planner every heartbeat, and
re-sends each result until the daemon acknowledges it. A request seen
before is never planned twice: it is answered with the result already
made, or only acknowledged while planning. Through a hub it also tells a
stalled hub, as the C kit does: each heartbeat goes to the node itself
too, and with none back for ECHO_MAX_S while connected it says so in one
line and holds its results until one is back (one line more).

Reusable for any planner in Python (docs/writing-a-planner.md):

    Node(name, algorithms, url).serve(solve)

with solve(req, limits) -> plan_result_t (limits.py: the run's deadline
and the node's stop flag; a solve(req) is called without). A result whose time_total solve() left
at 0 gets the time solve() took, by the node's clock; one whose memory
solve() left at 0 gets the process's peak resident memory during solve()
(MB), and a request's memory_limit is enforced around solve(), a
MemoryError answered with MEMORY (memory.py). As the C kit does,
the node answers a
request for an algorithm it does not offer with INVALID_REQUEST without
calling solve(), an exception in solve() with FAILED and the
exception in the result's message, and a result too large to send (over
16 MiB encoded) with FAILED saying so, and goes on serving.
"""
from __future__ import annotations

import hashlib
import os
import queue
import re
import socket
import sys
import threading
import time
import traceback
from typing import Any, Callable, Mapping, Optional, Sequence

from mpb import (daemon_status_t, plan_request_t, plan_result_t,
                 planner_announce_t, run_ack_t)
from mpb import (plan_request_v1_t, plan_result_v2_t, planner_announce_v2_t,
                 run_ack_v1_t)

from .auth import TRAILER_BYTES, Auth, AuthError  # noqa: F401 (the kit's API)
from .limits import Limits, takes_limits
from .hub import HubLCM, is_hub
from .memory import Watch
from .sockfilter import filtered_lcm

# The channels of libmpbench's list of messages (mpbench/messages.h),
# which tests/python/test_kit.py checks these against.
ANNOUNCE = "MPB_ANNOUNCE"
REQUEST_PREFIX = "MPB_REQUEST_"
ACK = "MPB_ACK"
RESULT = "MPB_RESULT"
HEARTBEAT_S = 0.5
RESEND_S = 0.2              # a result's first re-send; the wait doubles
RESEND_MAX_S = 2.0          # to this, until the daemon acknowledges it
STATUS = "MPB_STATUS"
ECHO_MAX_S = 5.0            # through a hub, no heartbeat back this long
                            # while connected: the hub is stalled (the C
                            # kit's MPB__ECHO_MAX_S, the daemon's too)
PLANNER_ID_MAX = 51         # MPB_REQUEST_<id> within LCM's 63 characters
MESSAGE_MAX = 1000          # characters of an exception kept in a message
LCM_MESSAGE_MAX = 16 << 20  # MPB_LCM_MESSAGE_MAX (lcm_filter.h): every
                            # mpbench socket drops a larger message
# What Limits.setting_up() and planning() say, as run_ack_t kinds.
_PHASES = {"setting_up": run_ack_t.SETTING_UP,
           "planning": run_ack_t.PLANNING}


# A test's switch, never a user's: MPB_KIT_LAYOUT=before-attempt-id makes
# the kit speak as planners built before attempt_id did (docs/protocol.md,
# "Older layouts"), every message it sends under the older layout's
# fingerprint and only messages under it taken (the bytes are today's), so
# that tests/integration/test_old_planner.sh shows today's daemon serving
# such planners.
_OLDER = {plan_request_t: plan_request_v1_t, plan_result_t: plan_result_v2_t,
          planner_announce_t: planner_announce_v2_t, run_ack_t: run_ack_v1_t}
_SPEAK_OLDER = os.environ.get("MPB_KIT_LAYOUT") == "before-attempt-id"


def _encode(msg: Any) -> bytes:
    """msg's encoding, in the layout the kit speaks."""
    data = msg.encode()
    older = _OLDER.get(type(msg)) if _SPEAK_OLDER else None
    return older._get_packed_fingerprint() + data[8:] if older else data


def _decode(cls: Any, data: bytes) -> Any:
    """A message of type cls from data, in the layout the kit speaks."""
    older = _OLDER.get(cls) if _SPEAK_OLDER else None
    if older:
        if data[:8] != older._get_packed_fingerprint():
            raise ValueError(f"not {older.__name__}")
        data = cls._get_packed_fingerprint() + data[8:]
    return cls.decode(data)


def name_error(name: str) -> Optional[str]:
    """Why name cannot name a planner family (the C kit's rule), or None."""
    if not 1 <= len(name) <= 32:
        return "planner name must be 1 to 32 characters"
    if not re.fullmatch(r"[A-Za-z0-9_.-]+", name):
        return (f"planner name '{name}' may hold only letters, digits "
                "and '_' '.' '-'")
    return None


def planner_id(name: str, host: str, pid: int) -> str:
    """name@host:pid within PLANNER_ID_MAX characters, as the C kit makes it
    (mpb_planner_id_make() in proto.h): the host's characters outside
    [A-Za-z0-9_.-] as '-'; a host too long keeps its first characters,
    then '-' and 8 hex digits of the BLAKE2b-128 hash of the whole host."""
    room = PLANNER_ID_MAX - len(name) - 2 - len(str(pid))
    host = host or "localhost"
    if len(host) > room:
        digest = hashlib.blake2b(host.encode(), digest_size=16).hexdigest()
        host = host[:room - 9] + "-" + digest[:8]
    host = re.sub(r"[^A-Za-z0-9_.-]", "-", host)
    return f"{name}@{host}:{pid}"


# The approaches a planner may declare per algorithm (docs/protocol.md).
APPROACHES = ("sampling", "search", "optimisation", "hybrid")


class Node:
    """A planner process on the network: name is its family (what
    experiment files name), algorithms the names it offers, url LCM's URL
    ("" for LCM's default), auth an Auth or None. approaches (optional)
    maps an algorithm to its approach, the paper's word for its kind of
    planner ("sampling", "search", "optimisation", "hybrid"), announced
    with it (docs/protocol.md); an algorithm it leaves out declares none.
    Raises ValueError for a name the C kit would refuse too, or an
    approach that is none of those words."""

    def __init__(self, name: str, algorithms: Sequence[str], url: str,
                 auth: Optional[Auth] = None, verbose: bool = False,
                 approaches: Optional[Mapping[str, str]] = None) -> None:
        approaches = dict(approaches or {})
        for algorithm, word in approaches.items():
            if word not in APPROACHES:
                raise ValueError(f"algorithm {algorithm}: approach "
                                 f"'{word}' is none of "
                                 f"{', '.join(APPROACHES)}")
        self.approaches = approaches
        error = name_error(name)
        if error:
            raise ValueError(error)
        self.host = socket.gethostname()
        self.planner_id = planner_id(name, self.host, os.getpid())
        # Its two channels (and with a secret the daemon's status, for
        # the instance to echo), and no malformed datagram (sockfilter.py).
        request = REQUEST_PREFIX + self.planner_id
        ack = self.ack_channel = ACK + "_" + self.planner_id
        # Through a hub (hub.py, libmpbench's link): no socket to
        # filter, every length checked before it is read.
        channels = [request, ack] + ([STATUS] if auth is not None else [])
        self.hub = is_hub(url)
        if self.hub:
            self.lc, filtered = HubLCM(url, channels), True
        else:
            self.lc, filtered = filtered_lcm(url, channels)
        if not filtered:
            print("mpb-planner-python: warning: LCM's receive socket has no "
                  "filter (not a udpm:// URL, or the kernel refused it): a "
                  "malformed datagram can crash this process",
                  file=sys.stderr, flush=True)
        self.name, self.algorithms = name, algorithms
        self.auth, self.verbose = auth, verbose
        self.requests = queue.Queue()
        self.lock = threading.Lock()
        self.seen = {}           # attempt id -> None while planning, else
                                 # result bytes
        self.unacked = {}        # attempt id -> (next time to re-send its
                                 # result, the wait after that)
        self.connects = 0        # the hub link's connections, last seen
        # Through a hub, the heartbeat's echo (the LCM thread's alone).
        self.echo_back = time.monotonic()   # one came back, or a
                                 # connection began whose echo is to come
        self.echo_connects = 0   # the connection echo_back is of
        self.stalled = False     # the hub relays nothing: send the echo
                                 # alone, hold the results
        self.stalled_since = 0.0
        self.relays_again = False
        self.link_said = 0       # the link's state last told: 0 none yet,
        self.link_lost = 0.0     # 1 up, 2 away (since link_lost)
        self.active = []
        self.stopping = False
        self.announce_now = False
        self.daemon = 0          # with auth: the daemon's instance to echo
        self.lc.subscribe(request, self._on_request)
        if auth is not None:     # the daemon's instance, from its status
            self.lc.subscribe(STATUS, self._on_status)
        # The daemon acknowledges our results on a channel of our own.
        self.lc.subscribe(ack, self._on_ack)

    def log(self, text: str) -> None:
        if self.verbose:
            print(f"mpb-planner-python: {text}", file=sys.stderr, flush=True)

    def warn(self, text: str) -> None:
        print(f"mpb-planner-python: {text}", file=sys.stderr, flush=True)

    # ---- sending ---------------------------------------------------------

    def _publish(self, channel, data):
        if self.auth:
            data = self.auth.seal(channel, data, self.daemon)
        self.lc.publish(channel, data)

    def _announce(self):
        if self.auth and not self.daemon:
            return                  # no daemon would believe it yet
        a = planner_announce_t()
        a.utime = int(time.time() * 1e6)
        a.planner_id, a.name, a.host = self.planner_id, self.name, self.host
        a.pid, a.language, a.version = os.getpid(), "python", "0.1.0"
        a.heartbeat_ms = int(HEARTBEAT_S * 1000)
        a.algorithms, a.num_algorithms = list(self.algorithms), len(self.algorithms)
        if self.approaches:
            a.approaches = [self.approaches.get(x, "") for x in a.algorithms]
            a.num_approaches = len(a.approaches)
        a.capacity = 1
        with self.lock:
            a.active_attempts = list(self.active)
        a.num_active = len(a.active_attempts)
        self._publish(ANNOUNCE, _encode(a))

    def _ack(self, attempt_id, kind):
        k = run_ack_t()
        k.utime = int(time.time() * 1e6)
        k.attempt_id, k.sender_id, k.kind = attempt_id, self.planner_id, kind
        self._publish(ACK, _encode(k))

    def _echo(self):
        """The heartbeat's echo, to the node itself on its acknowledgement
        channel (no run, sender_id its own id, with a secret echoing its
        own instance): the hub relays it back while it relays at all."""
        k = run_ack_t()
        k.utime = int(time.time() * 1e6)
        k.attempt_id, k.sender_id = "", self.planner_id
        k.kind = run_ack_t.REQUEST_RECEIVED
        data = _encode(k)
        if self.auth:
            data = self.auth.seal(self.ack_channel, data, self.auth.instance)
        self.lc.publish(self.ack_channel, data)

    # ---- receiving (LCM thread) -------------------------------------------

    def _unseal(self, channel, data):
        """(the message to decode, its sender's instance) if authentic and
        fresh (a request or an acknowledgement from a daemon that echoes
        this process, or the node's own echo), else (None, 0); without a
        secret the sender is 0."""
        if self.auth is None:
            return data, 0
        verdict, body, sender = self.auth.open(channel, data)
        if verdict != Auth.FRESH:
            self.log(f"dropped a message on {channel}: "
                     f"{Auth.verdict_text(verdict)}")
            return None, 0
        if channel.startswith(REQUEST_PREFIX):
            self.daemon = sender
        return body, sender

    def _on_status(self, channel, data):
        verdict, body, sender = self.auth.open(channel, data)
        if verdict not in (Auth.FRESH, Auth.UNPROVEN):
            return
        try:
            st = daemon_status_t.decode(body)
        except Exception:
            return
        if st.state in ("waiting", "running") and sender != self.daemon:
            self.daemon = sender
            self.announce_now = True

    def _on_request(self, channel, data):
        data, _ = self._unseal(channel, data)
        if data is None:
            return
        try:
            req = _decode(plan_request_t, data)
        except Exception as e:      # a malformed message must not stop us
            self.log(f"dropped a malformed request: {e}")
            return
        if req.planner_id != self.planner_id:
            return
        with self.lock:
            # Earlier results the daemon has stored ride on the request.
            for attempt_id in req.stored:
                self.unacked.pop(attempt_id, None)
            known = req.attempt_id in self.seen
            result = self.seen.get(req.attempt_id)
            if not known:
                self.seen[req.attempt_id] = None
        if not known:
            self._ack(req.attempt_id, run_ack_t.REQUEST_RECEIVED)
            self.requests.put(req)
        elif result is None:
            self._ack(req.attempt_id, run_ack_t.REQUEST_RECEIVED)
        else:
            self._publish(RESULT, result)

    def _on_ack(self, channel, data):
        data, sender = self._unseal(channel, data)
        if data is None:
            return
        try:
            k = _decode(run_ack_t, data)
        except Exception:
            return
        if k.sender_id == self.planner_id and (
                self.auth is None or sender == self.auth.instance):
            self._echo_back()
        elif k.kind in (run_ack_t.RESULT_STORED, run_ack_t.RESULT_REJECTED):
            with self.lock:
                self.unacked.pop(k.attempt_id, None)

    # ---- a stalled hub (LCM thread) ---------------------------------------

    def _echo_back(self):
        """An echo came back: the hub relays; if it was stalled, say so
        once and have every result not yet stored sent at once."""
        now = time.monotonic()
        self.echo_back = now
        if self.stalled:
            self.stalled, self.relays_again = False, True
            self.announce_now = True
            self.warn(f"the hub relays again after "
                      f"{now - self.stalled_since:.1f} s: the results it "
                      f"has not stored go again now")

    def _tell_outage(self, st, now: float) -> None:
        """A hub away (killed, restarted, out of reach) is an outage: say
        so in one line when the link goes and one when it is back, as the
        C kit and the daemon do; the results not stored go again then."""
        if st.connected and self.link_said == 2:
            self.warn(f"the hub is back after {now - self.link_lost:.1f} s "
                      f"(connection {st.connects}): the results it has not "
                      f"stored go again now")
        elif not st.connected and self.link_said != 2:
            self.link_lost = now
            what = ("lost the hub" if self.link_said == 1
                    else "cannot reach the hub yet")
            self.warn(f"{what}; trying again every {st.retry_s:.1f} s, its "
                      f"results wait meanwhile")
        self.link_said = 1 if st.connected else 2

    def _watch_link(self):
        """With nothing waiting to be handled: connected, and no echo back
        for ECHO_MAX_S, the hub is stalled. The link away is an outage
        instead, and a new connection's echo is yet to come; once stalled,
        only an echo ends it."""
        if not self.hub or self.stalled:
            return
        now, st = time.monotonic(), self.lc.stats()
        self._tell_outage(st, now)
        if not st.connected or st.connects != self.echo_connects:
            self.echo_connects, self.echo_back = st.connects, now
            return
        if now - self.echo_back <= ECHO_MAX_S:
            return
        self.stalled, self.stalled_since = True, self.echo_back
        self.warn(f"the hub is stalled: connected, but none of this "
                  f"planner's heartbeats has come back for "
                  f"{now - self.echo_back:.1f} s (a client that never reads "
                  f"blocks it, docs/topology.md); its results wait until it "
                  f"relays again")

    def _lcm_loop(self):
        next_announce = 0.0
        while not self.stopping:
            now = time.monotonic()
            if now >= next_announce or self.announce_now:
                self.announce_now = False
                if not self.stalled:    # else it would wait in the hub
                    self._announce()
                if self.hub:
                    self._echo()
                next_announce = now + HEARTBEAT_S
            # A hub link connected again: what was sent meanwhile was
            # lost, so every result not acknowledged goes again now; so
            # it does when a stalled hub relays again, and none goes
            # while it is stalled.
            connects = getattr(self.lc, "connects", 0)
            relinked, self.connects = connects != self.connects, connects
            relinked = relinked or self.relays_again
            self.relays_again = False
            with self.lock:
                due = [] if self.stalled else [
                    r for r, (t, _) in self.unacked.items()
                    if t <= now or relinked]
                for r in due:
                    wait = RESEND_S if relinked else self.unacked[r][1]
                    self.unacked[r] = (now + wait, min(2 * wait, RESEND_MAX_S))
                resend = [self.seen[r] for r in due]
            for data in resend:
                self._publish(RESULT, data)
            if self.lc.handle_timeout(50) == 0:
                self._watch_link()

    # ---- planning (caller's thread) ---------------------------------------

    def _failed(self, status, message):
        res = plan_result_t()
        res.status, res.message = status, message[:MESSAGE_MAX]
        return res

    def _answer(self, solve, req):
        """(result, its encoding): solve's, or INVALID_REQUEST for an
        algorithm not offered, or FAILED saying what went wrong in solve()."""
        if req.algorithm not in self.algorithms:
            res = self._failed(plan_result_t.INVALID_REQUEST,
                               f"algorithm '{req.algorithm}' not offered by "
                               f"this planner (offered: "
                               f"{', '.join(self.algorithms)})")
        else:
            t0 = time.monotonic()
            watch = Watch(getattr(req, "memory_limit", 0.0))
            limits = Limits(t0, req.time_limit, lambda: self.stopping,
                            lambda phase: self._ack(req.attempt_id,
                                                    _PHASES[phase]))
            try:
                with watch:
                    res = (solve(req, limits) if takes_limits(solve)
                           else solve(req))
            except MemoryError:
                # Past the request's memory_limit (RLIMIT_DATA, set by
                # Watch), or the machine's: what solve() held is freed.
                res = self._failed(plan_result_t.MEMORY, "out of memory "
                                   "(MemoryError)" + (
                                       f" under the memory_limit of "
                                       f"{watch.limit_mb:g} MB"
                                       if watch.limit_mb > 0 else ""))
            except Exception as e:      # the planner's bug: say so, go on
                print(f"mpb-planner-python: run {req.attempt_id[:8]}: solve() "
                      f"raised:\n{traceback.format_exc()}", file=sys.stderr,
                      end="", flush=True)
                res = self._failed(plan_result_t.FAILED, f"solve() raised "
                                   f"{type(e).__name__}: {e}")
            if not isinstance(res, plan_result_t):
                res = self._failed(plan_result_t.FAILED, f"solve() returned "
                                   f"{type(res).__name__}, not a plan_result_t")
            if res.time_total == 0.0:
                # solve() kept no time of its own: the kit's clock is the
                # run's tau_t, never 0 s that would win "fastest".
                res.time_total = time.monotonic() - t0
            if not res.memory > 0:
                res.memory = watch.peak_mb
            if watch.note:
                res.message = (watch.note + ("; " + res.message
                                             if res.message else ""))[
                                                 :MESSAGE_MAX]
        res.utime = int(time.time() * 1e6)
        res.attempt_id, res.planner_id = req.attempt_id, self.planner_id
        try:
            data = _encode(res)
        except Exception as e:          # e.g. num_stages != len(stages)
            res = self._failed(plan_result_t.FAILED, f"the result of solve() "
                               f"cannot be encoded: {type(e).__name__}: {e}")
        else:
            # Over the bound the daemon would never receive it: a failure
            # saying why instead, as the C kit sends.
            size = len(data) + (TRAILER_BYTES if self.auth else 0)
            if size <= LCM_MESSAGE_MAX:
                return res, data
            res = self._failed(plan_result_t.FAILED, f"result too large: "
                               f"{size} bytes, over the {LCM_MESSAGE_MAX}"
                               f"-byte (16 MiB) bound of an LCM message")
        res.utime = int(time.time() * 1e6)
        res.attempt_id, res.planner_id = req.attempt_id, self.planner_id
        return res, _encode(res)

    def serve(self, solve: Callable[..., Any]) -> None:
        """Answer requests with solve(req) -> plan_result_t until stop()."""
        t = threading.Thread(target=self._lcm_loop, daemon=True)
        t.start()
        while not self.stopping:
            try:
                req = self.requests.get(timeout=0.2)
            except queue.Empty:
                continue
            with self.lock:
                self.active = [req.attempt_id]
            self.log(f"run {req.attempt_id[:8]}: {req.algorithm}, "
                     f"{req.time_limit:g} s")
            res, data = self._answer(solve, req)
            with self.lock:
                self.active = []
                self.seen[req.attempt_id] = data
                self.unacked[req.attempt_id] = (time.monotonic() + RESEND_S,
                                            2 * RESEND_S)
            if not self.stalled:        # else it goes when the hub relays
                self._publish(RESULT, data)
            self.log(f"run {req.attempt_id[:8]}: status {res.status}, "
                     f"{res.time_total:.3f} s")
        t.join(timeout=1.0)

    def stop(self) -> None:
        """Make serve() return (after the run in hand, if any)."""
        self.stopping = True
