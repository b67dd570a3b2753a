"""stall_client.py - a hub client that subscribes to every channel and
never reads (tests/integration/test_hub_stalled.sh): once its socket's
buffers are full, lcm-java's hub blocks relaying to it.

    python3 stall_client.py HOST PORT SECONDS

Connects, greets the hub, subscribes to ".*", then sleeps SECONDS (at most
600) without reading, and exits."""
import socket
import struct
import sys
import time

MAGIC_SERVER, MAGIC_CLIENT, VERSION, SUBSCRIBE = 0x287617FA, 0x287617FB, 0x0100, 2

host, port, secs = sys.argv[1], int(sys.argv[2]), min(float(sys.argv[3]), 600)
s = socket.socket(socket.AF_INET, socket.SOCK_STREAM)
s.setsockopt(socket.SOL_SOCKET, socket.SO_RCVBUF, 4096)   # fills soonest
s.connect((host, port))
s.sendall(struct.pack(">II", MAGIC_CLIENT, VERSION))
hello = b""
while len(hello) < 8:
    hello += s.recv(8 - len(hello))
assert struct.unpack(">I", hello[:4])[0] == MAGIC_SERVER
s.sendall(struct.pack(">II", SUBSCRIBE, 2) + b".*")
print("subscribed, not reading", flush=True)
time.sleep(secs)
