"""hub.py - LCM through lcm-java's TCP hub (tcpq://HOST:PORT), as
libmpbench's hub link does it (libmpbench/include/mpbench/hub.h), for the
Python kit: the subset of lcm.LCM that node.py uses (subscribe, publish,
handle_timeout).

The binding's own tcpq provider, like liblcm's, allocates whatever length a
frame claims and publishes without a lock. Here a frame's lengths are
checked before anything is read into memory (a channel over 63 bytes or a
message over 16 MiB is read past and dropped), frames go out whole under a
lock, and a lost connection is made again every RETRY_S, subscribing
again. Reading happens in handle_timeout(), on the caller's thread.
"""
import select
import socket
import struct
import threading
import time

MAGIC_SERVER = 0x287617FA
MAGIC_CLIENT = 0x287617FB
VERSION = 0x0100
PUBLISH, SUBSCRIBE = 1, 2
CHANNEL_MAX = 63
MESSAGE_MAX = 16 << 20
RETRY_S = 0.5
CONNECT_S = 2.0


def is_hub(url):
    return bool(url) and url.startswith("tcpq://")


def _regex(channel):
    """A Java regular expression matching channel alone."""
    return "".join(c if c.isascii() and (c.isalnum() or c == "_") else "\\" + c
                   for c in channel)


class HubLCM:
    def __init__(self, url):
        where = url[len("tcpq://"):].split("?")[0].split("/")[0]
        host, _, port = where.partition(":")
        self.host = host or "127.0.0.1"
        self.port = int(port) if port else 7700
        if not 0 < self.port < 65536:
            raise ValueError(f"{url}: a hub's URL is tcpq://HOST:PORT")
        self.handlers = {}
        self.sock = None
        self.lock = threading.Lock()    # one frame at a time; guards sock
        self.next_try = 0.0
        self.inbuf = bytearray()
        self.skip = 0                   # bytes of a dropped frame to pass
        self.pending_drop = False       # then its data's length, and that
        self.dropped = 0
        self.connects = 0               # connections made (for re-sends)

    # ---- the connection ----------------------------------------------------

    def _connect(self):
        now = time.monotonic()
        if now < self.next_try:
            return None
        self.next_try = now + RETRY_S
        try:
            s = socket.create_connection((self.host, self.port), CONNECT_S)
            s.settimeout(CONNECT_S)
            s.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
            s.sendall(struct.pack(">II", MAGIC_CLIENT, VERSION))
            hello = b""
            while len(hello) < 8:
                part = s.recv(8 - len(hello))
                if not part:
                    raise OSError("hub closed")
                hello += part
            if struct.unpack(">I", hello[:4])[0] != MAGIC_SERVER:
                raise OSError("not an LCM hub")
            for channel in self.handlers:
                name = _regex(channel).encode()
                s.sendall(struct.pack(">II", SUBSCRIBE, len(name)) + name)
            s.settimeout(None)
        except OSError:
            return None
        self.inbuf, self.skip, self.pending_drop = bytearray(), 0, False
        with self.lock:
            self.sock = s
        self.connects += 1
        return s

    def _drop(self):
        with self.lock:
            s, self.sock = self.sock, None
        if s is not None:
            s.close()

    # ---- the lcm.LCM subset ------------------------------------------------

    def subscribe(self, channel, handler):
        self.handlers[channel] = handler
        with self.lock:
            s = self.sock
        if s is not None:
            name = _regex(channel).encode()
            self.publish_raw(struct.pack(">II", SUBSCRIBE, len(name)) + name)

    def publish_raw(self, frame):
        with self.lock:
            if self.sock is None:
                return
            try:
                self.sock.sendall(frame)
            except OSError:
                # Half a frame makes the stream unreadable: end it; the
                # reader makes a new connection.
                try:
                    self.sock.shutdown(socket.SHUT_RDWR)
                except OSError:
                    pass

    def publish(self, channel, data):
        name = channel.encode()
        if len(name) > CHANNEL_MAX or len(data) > MESSAGE_MAX:
            return
        self.publish_raw(struct.pack(">II", PUBLISH, len(name)) + name +
                         struct.pack(">I", len(data)) + bytes(data))

    def handle_timeout(self, ms):
        """Read what the hub sent within ms milliseconds, and hand every
        whole message to its handler; 0 if none."""
        with self.lock:
            s = self.sock
        if s is None and (s := self._connect()) is None:
            time.sleep(ms / 1000.0)
            return 0
        ready, _, _ = select.select([s], [], [], ms / 1000.0)
        if not ready:
            return 0
        try:
            part = s.recv(1 << 16)
            # Acknowledge at once: the hub writes a frame's words one by
            # one with Nagle's algorithm on (hub.h in libmpbench).
            s.setsockopt(socket.IPPROTO_TCP, socket.TCP_QUICKACK, 1)
        except OSError:
            part = b""
        if not part:
            self._drop()
            return 0
        self.inbuf += part
        return self._dispatch()

    def _dispatch(self):
        """Hand out every whole message in inbuf. The buffer never holds
        more than one message's header and at most MESSAGE_MAX bytes of
        data (and one read): larger claims are read past in skip."""
        handled = 0
        buf = self.inbuf
        while True:
            if self.skip:
                n = min(self.skip, len(buf))
                self.skip -= n
                del buf[:n]
                if self.skip:
                    break
            if self.pending_drop:           # a name read past: its length
                if len(buf) < 4:
                    break
                self.skip = struct.unpack_from(">I", buf)[0]
                del buf[:4]
                self.pending_drop = False
                self.dropped += 1
                continue
            if len(buf) < 8:
                break
            kind, clen = struct.unpack_from(">II", buf)
            if kind != PUBLISH:
                self._drop()                # not a message: the stream is lost
                buf.clear()
                break
            if clen > CHANNEL_MAX:
                del buf[:8]
                self.skip, self.pending_drop = clen, True
                continue
            head = 8 + clen + 4
            if len(buf) < head:
                break
            dlen = struct.unpack_from(">I", buf, 8 + clen)[0]
            if dlen > MESSAGE_MAX:
                del buf[:head]
                self.skip = dlen
                self.dropped += 1
                continue
            if len(buf) < head + dlen:
                break
            channel = bytes(buf[8:8 + clen])
            data = bytes(buf[head:head + dlen])
            del buf[:head + dlen]
            try:
                name = channel.decode()
            except UnicodeDecodeError:
                continue
            handler = self.handlers.get(name)
            if handler is not None:
                handler(name, data)
                handled += 1
        return handled
