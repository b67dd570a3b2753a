"""test_kit_stall.py - the Python kit's watch of its hub link
(mpbplanner/node.py, docs/protocol.md "Through a hub"), with pytest: its
heartbeat's echo told apart from the daemon's acknowledgements, with and
without a secret; a stall said once, only while connected; its end said
once, with every result sent again. The link is to a port that refuses
connections, its state told to the node by the test."""
import os
import socket
import time
from types import SimpleNamespace

import pytest
from mpb import run_ack_t

from mpbplanner import node
from mpbplanner.auth import TRAILER_BYTES, Auth


@pytest.fixture
def closed_port():
    s = socket.socket()
    s.bind(("127.0.0.1", 0))
    yield s.getsockname()[1]
    s.close()


def _node(port, auth=None):
    n = node.Node("stalltest", ["a"], f"tcpq://127.0.0.1:{port}", auth)
    n.sent = []
    n.lc.publish = lambda channel, data: n.sent.append((channel, bytes(data)))
    return n


def _link(n, connected, connects=1):
    n.lc.stats = lambda: SimpleNamespace(connected=connected,
                                         connects=connects, retry_s=0.5)


def _echo(n):
    n.sent.clear()
    n._echo()
    [(channel, data)] = n.sent
    assert channel == node.ACK + "_" + n.planner_id
    return channel, data


def _stall(n, capsys):
    _link(n, 1)
    n._watch_link()                     # the connection's echo is to come
    n.echo_back -= node.ECHO_MAX_S + 1
    n._watch_link()
    assert n.stalled
    return capsys.readouterr().err


def test_a_stall_is_said_once_while_connected_and_its_end_once(
        closed_port, capsys):
    n = _node(closed_port)
    try:
        _link(n, 0)
        n.echo_back -= node.ECHO_MAX_S + 1
        n._watch_link()                 # away: an outage, not a stall
        assert not n.stalled
        err = _stall(n, capsys)
        assert err.count("the hub is stalled") == 1
        n._watch_link()
        _link(n, 1, connects=2)         # reconnected: still stalled
        n._watch_link()
        assert n.stalled and capsys.readouterr().err == ""
        n._on_ack(*_echo(n))
        assert not n.stalled and n.relays_again and n.announce_now
        assert capsys.readouterr().err.count("the hub relays again") == 1
    finally:
        n.lc.close()


def test_a_daemon_ack_is_no_echo_and_the_echo_acknowledges_nothing(
        closed_port, capsys):
    n = _node(closed_port)
    try:
        n.unacked["r1"] = (0.0, node.RESEND_S)
        _stall(n, capsys)
        n._on_ack(*_echo(n))            # the echo takes no result
        assert not n.stalled and "r1" in n.unacked
        k = run_ack_t()
        k.utime, k.attempt_id, k.sender_id = int(time.time() * 1e6), "r1", "d"
        k.kind = run_ack_t.RESULT_STORED
        _stall(n, capsys)
        n._on_ack(node.ACK + "_" + n.planner_id, k.encode())
        assert n.stalled and "r1" not in n.unacked
    finally:
        n.lc.close()


def test_with_a_secret_only_its_own_instance_echoes(closed_port, capsys,
                                                     tmp_path):
    secret = tmp_path / "secret"
    secret.write_bytes(os.urandom(32))
    n = _node(closed_port, Auth(str(secret)))
    other = Auth(str(secret))
    try:
        channel, data = _echo(n)
        # The same bytes sealed by another process holding the secret.
        forged = other.seal(channel, data[:-TRAILER_BYTES], n.auth.instance)
        _stall(n, capsys)
        n._on_ack(channel, forged)
        assert n.stalled
        n._on_ack(channel, data)
        assert not n.stalled
        _stall(n, capsys)
        n._on_ack(channel, data)        # the same echo again: a replay
        assert n.stalled
    finally:
        n.lc.close()
        other.close()
