"""hostile_frames.py - hostile clients of an LCM TCP hub (tcpq://): each
connects to the hub at HOST PORT and sends one kind of bad input, on the
channels given (those mpbench processes subscribe to), then goes.

usage: python3 hostile_frames.py HOST PORT CHANNEL...
       python3 hostile_frames.py --serve PORT SECONDS

Kinds: frames claiming a 4 GiB (0xffffffff) or 2 GiB channel or payload;
a frame cut short; a stream of random bytes; a real 17 MiB message (over
MPB_LCM_MESSAGE_MAX, which the hub relays whole); a channel name with a
NUL in it; small malformed messages. Prints one line per kind sent.
"""
import os
import random
import socket
import struct
import sys
import time

MAGIC_CLIENT, VERSION, PUBLISH, SUBSCRIBE = 0x287617FB, 0x0100, 1, 2
MAGIC_SERVER = 0x287617FA


def client(host, port):
    s = socket.create_connection((host, port), 5)
    s.sendall(struct.pack(">II", MAGIC_CLIENT, VERSION))
    s.recv(8)
    return s


def frame(channel, data, data_len=None, channel_len=None):
    c = channel.encode() if isinstance(channel, str) else channel
    return (struct.pack(">II", PUBLISH, len(c) if channel_len is None else channel_len)
            + c + struct.pack(">I", len(data) if data_len is None else data_len)
            + data)


def send_then_close(host, port, what, payload):
    try:
        s = client(host, port)
        s.sendall(payload)
        time.sleep(0.05)
        s.close()
    except OSError as e:          # the hub may drop us: that is its right
        print(f"{what}: the hub closed the connection ({e})")
        return
    print(f"sent {what}")


def main():
    host, port, channels = sys.argv[1], int(sys.argv[2]), sys.argv[3:]
    rnd = random.Random(38)
    for ch in channels:
        send_then_close(host, port, f"a 4 GiB payload claim on {ch}",
                        frame(ch, b"x" * 16, data_len=0xFFFFFFFF))
        send_then_close(host, port, f"a 2 GiB payload claim on {ch}",
                        frame(ch, b"x" * 16, data_len=0x7FFFFFF0))
        send_then_close(host, port, f"a 4 GiB channel claim on {ch}",
                        frame(ch, b"", channel_len=0xFFFFFFFF))
        send_then_close(host, port, f"a frame cut short on {ch}",
                        frame(ch, b"y" * 100)[:40])
        send_then_close(host, port, f"a NUL inside the channel {ch}",
                        frame(ch.encode() + b"\0x", b"z" * 30))
        for n in (0, 1, 7, 64, 300):
            send_then_close(host, port, f"{n} random bytes as a message on {ch}",
                            frame(ch, bytes(rnd.getrandbits(8) for _ in range(n))))
        # Over the bound, relayed whole by the hub to every subscriber.
        send_then_close(host, port, f"a 17 MiB message on {ch}",
                        frame(ch, os.urandom(1024) * (17 * 1024)))
    send_then_close(host, port, "64 KiB of random bytes",
                    bytes(rnd.getrandbits(8) for _ in range(65536)))
    send_then_close(host, port, "a subscription that is no regular expression",
                    struct.pack(">II", SUBSCRIBE, 3) + b"(*[")


def serve(port, seconds):
    """A hostile hub: to each client that connects, one bad answer in turn
    (a frame claiming 4 GiB of payload, then 2 GiB sent slowly in part,
    a 4 GiB channel, a type that is no message, random bytes), then close.
    The clients must survive, within bounded memory, and come back."""
    srv = socket.socket()
    srv.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
    srv.bind(("127.0.0.1", port))
    srv.listen(16)
    srv.settimeout(0.5)
    rnd = random.Random(7)
    bad = [
        frame("MPB_RESULT", b"x" * 4096, data_len=0xFFFFFFFF),
        frame("MPB_RESULT", b"x" * 65536, data_len=0x7FFFFFF0),
        frame("MPB_RESULT", b"", channel_len=0xFFFFFFFF) + b"y" * 4096,
        struct.pack(">II", 7, 12) + b"not a frame",
        bytes(rnd.getrandbits(8) for _ in range(4096)),
    ]
    end, served = time.monotonic() + seconds, 0
    while time.monotonic() < end:
        try:
            c, _ = srv.accept()
        except socket.timeout:
            continue
        try:
            c.settimeout(1)
            c.sendall(struct.pack(">II", MAGIC_SERVER, VERSION))
            time.sleep(0.05)
            c.sendall(bad[served % len(bad)])
            time.sleep(0.1)
        except OSError:
            pass
        c.close()
        served += 1
    print(f"served {served} connections")


if __name__ == "__main__":
    if sys.argv[1] == "--serve":
        serve(int(sys.argv[2]), float(sys.argv[3]))
    else:
        main()
