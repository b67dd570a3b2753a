"""node.py - the protocol of docs/protocol.md, spoken with the PyPI `lcm`
package and the generated Python types.

One thread (the caller's) plans; another runs LCM: it takes requests into a
queue, acknowledges them, announces the planner every heartbeat, and
re-sends each result until the daemon acknowledges it. A request seen
before is never planned twice: it is answered with the result already
made, or only acknowledged while planning.

Reusable for any planner in Python (docs/writing-a-planner.md):

    Node(name, algorithms, url).serve(solve)

with solve(req) -> plan_result_t. A result whose time_total solve() left
at 0 gets the time solve() took, by the node's clock. As the C kit does,
the node answers a
request for an algorithm it does not offer with INVALID_REQUEST without
calling solve(), and an exception in solve() with FAILED and the
exception in the result's message, and goes on serving.
"""
import hashlib
import hmac
import os
import queue
import re
import socket
import sys
import threading
import time
import traceback

import lcm
from mpb import plan_request_t, plan_result_t, planner_announce_t, run_ack_t

ANNOUNCE = "MPB_ANNOUNCE"
ACK = "MPB_ACK"
RESULT = "MPB_RESULT"
HEARTBEAT_S = 0.5
RESEND_S = 0.2
TAG_BYTES = 32
PLANNER_ID_MAX = 96
MESSAGE_MAX = 1000          # characters of an exception kept in a message


def name_error(name):
    """Why name cannot name a planner family (the C kit's rule), or None."""
    if not 1 <= len(name) <= 32:
        return "planner name must be 1 to 32 characters"
    if not re.fullmatch(r"[A-Za-z0-9_.-]+", name):
        return (f"planner name '{name}' may hold only letters, digits "
                "and '_' '.' '-'")
    return None


def planner_id(name, host, pid):
    """name@host:pid, with the host's other characters as '-' and the host
    shortened so that the id fits in PLANNER_ID_MAX characters."""
    host = re.sub(r"[^A-Za-z0-9_.-]", "-", host) or "localhost"
    room = PLANNER_ID_MAX - len(name) - 2 - len(str(pid))
    return f"{name}@{host[:room]}:{pid}"


class Auth:
    """The optional shared secret (docs/protocol.md, "Authentication"): an
    HMAC-SHA-512-256 tag after each message, keyed with the BLAKE2b-256 hash
    of the secret file, over the channel, a NUL byte and the encoding."""

    def __init__(self, path):
        with open(path, "rb") as f:
            self.key = hashlib.blake2b(f.read(), digest_size=32).digest()

    def tag(self, channel, data):
        mac = hmac.new(self.key, channel.encode() + b"\0" + data, hashlib.sha512)
        return mac.digest()[:TAG_BYTES]

    def seal(self, channel, data):
        return data + self.tag(channel, data)

    def open(self, channel, data):
        """The message without its tag, or None if the tag is wrong."""
        if len(data) < TAG_BYTES:
            return None
        body, tag = data[:-TAG_BYTES], data[-TAG_BYTES:]
        return body if hmac.compare_digest(tag, self.tag(channel, body)) else None


class Node:
    """A planner process on the network: name is its family (what
    experiment files name), algorithms the names it offers, url LCM's URL
    ("" for LCM's default), auth an Auth or None. Raises ValueError for a
    name the C kit would refuse too."""

    def __init__(self, name, algorithms, url, auth=None, verbose=False):
        error = name_error(name)
        if error:
            raise ValueError(error)
        self.host = socket.gethostname()
        self.planner_id = planner_id(name, self.host, os.getpid())
        self.lc = lcm.LCM(url) if url else lcm.LCM()
        self.name, self.algorithms = name, algorithms
        self.auth, self.verbose = auth, verbose
        self.requests = queue.Queue()
        self.lock = threading.Lock()
        self.seen = {}           # run id -> None while planning, else result bytes
        self.unacked = {}        # run id -> next time to re-send its result
        self.active = []
        self.stopping = False
        self.lc.subscribe("MPB_REQUEST_" + self.planner_id, self._on_request)
        # The daemon acknowledges our results on a channel of our own.
        self.lc.subscribe(ACK + "_" + self.planner_id, self._on_ack)

    def log(self, text):
        if self.verbose:
            print(f"mpb-planner-python: {text}", file=sys.stderr, flush=True)

    # ---- sending ---------------------------------------------------------

    def _publish(self, channel, data):
        self.lc.publish(channel, self.auth.seal(channel, data) if self.auth else data)

    def _announce(self):
        a = planner_announce_t()
        a.utime = int(time.time() * 1e6)
        a.planner_id, a.name, a.host = self.planner_id, self.name, self.host
        a.pid, a.language, a.version = os.getpid(), "python", "0.1.0"
        a.heartbeat_ms = int(HEARTBEAT_S * 1000)
        a.algorithms, a.num_algorithms = list(self.algorithms), len(self.algorithms)
        a.capacity = 1
        with self.lock:
            a.active_runs = list(self.active)
        a.num_active = len(a.active_runs)
        self._publish(ANNOUNCE, a.encode())

    def _ack(self, run_id, kind):
        k = run_ack_t()
        k.utime = int(time.time() * 1e6)
        k.run_id, k.sender_id, k.kind = run_id, self.planner_id, kind
        self._publish(ACK, k.encode())

    # ---- receiving (LCM thread) -------------------------------------------

    def _unseal(self, channel, data):
        if self.auth is None:
            return data
        body = self.auth.open(channel, data)
        if body is None:
            self.log(f"dropped a message on {channel} without a valid tag")
        return body

    def _on_request(self, channel, data):
        data = self._unseal(channel, data)
        if data is None:
            return
        try:
            req = plan_request_t.decode(data)
        except Exception as e:      # a malformed message must not stop us
            self.log(f"dropped a malformed request: {e}")
            return
        if req.planner_id != self.planner_id:
            return
        with self.lock:
            # Earlier results the daemon has stored ride on the request.
            for run_id in req.stored:
                self.unacked.pop(run_id, None)
            known = req.run_id in self.seen
            result = self.seen.get(req.run_id)
            if not known:
                self.seen[req.run_id] = None
        if not known:
            self._ack(req.run_id, run_ack_t.REQUEST_RECEIVED)
            self.requests.put(req)
        elif result is None:
            self._ack(req.run_id, run_ack_t.REQUEST_RECEIVED)
        else:
            self._publish(RESULT, result)

    def _on_ack(self, channel, data):
        data = self._unseal(channel, data)
        if data is None:
            return
        try:
            k = run_ack_t.decode(data)
        except Exception:
            return
        if k.kind in (run_ack_t.RESULT_STORED, run_ack_t.RESULT_REJECTED):
            with self.lock:
                self.unacked.pop(k.run_id, None)

    def _lcm_loop(self):
        next_announce = 0.0
        while not self.stopping:
            now = time.monotonic()
            if now >= next_announce:
                self._announce()
                next_announce = now + HEARTBEAT_S
            with self.lock:
                due = [r for r, t in self.unacked.items() if t <= now]
                for r in due:
                    self.unacked[r] = now + RESEND_S
                resend = [self.seen[r] for r in due]
            for data in resend:
                self._publish(RESULT, data)
            self.lc.handle_timeout(50)

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
            try:
                res = solve(req)
            except Exception as e:      # the planner's bug: say so, go on
                print(f"mpb-planner-python: run {req.run_id[:8]}: solve() "
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
        res.utime = int(time.time() * 1e6)
        res.run_id, res.planner_id = req.run_id, self.planner_id
        try:
            return res, res.encode()
        except Exception as e:          # e.g. num_stages != len(stages)
            res = self._failed(plan_result_t.FAILED, f"the result of solve() "
                               f"cannot be encoded: {type(e).__name__}: {e}")
            res.utime = int(time.time() * 1e6)
            res.run_id, res.planner_id = req.run_id, self.planner_id
            return res, res.encode()

    def serve(self, solve):
        """Answer requests with solve(req) -> plan_result_t until stop()."""
        t = threading.Thread(target=self._lcm_loop, daemon=True)
        t.start()
        while not self.stopping:
            try:
                req = self.requests.get(timeout=0.2)
            except queue.Empty:
                continue
            with self.lock:
                self.active = [req.run_id]
            self.log(f"run {req.run_id[:8]}: {req.algorithm}, "
                     f"{req.time_limit:g} s")
            res, data = self._answer(solve, req)
            with self.lock:
                self.active = []
                self.seen[req.run_id] = data
                self.unacked[req.run_id] = time.monotonic() + RESEND_S
            self._publish(RESULT, data)
            self.log(f"run {req.run_id[:8]}: status {res.status}, "
                     f"{res.time_total:.3f} s")
        t.join(timeout=1.0)

    def stop(self):
        self.stopping = True
