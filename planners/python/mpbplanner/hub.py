"""hub.py - LCM through lcm-java's TCP hub (tcpq://HOST:PORT) with
libmpbench's own hub link (mpbench/link.h), for the Python kit: the subset
of lcm.LCM that node.py uses (subscribe, publish, handle_timeout).

The binding's own tcpq provider, like liblcm's, allocates whatever length
a frame claims and publishes without a lock. libmpbench's link, which the
C daemon and planners use, checks every length before reading it, sends
frames whole under a lock and connects again while the hub is away
(link.h says how); it hands each message to a memq:// instance of liblcm,
whose handlers run here in handle_timeout(), on the caller's thread.
"""
from __future__ import annotations

import ctypes
from ctypes import (CFUNCTYPE, POINTER, Structure, byref, c_char_p, c_int,
                    c_int64, c_long, c_uint, c_uint32, c_void_p)
from typing import Callable, Dict, Optional, Sequence

from .libmpbench import Functions, path

Handler = Callable[[str, bytes], None]


class _RecvBuf(Structure):
    """liblcm's lcm_recv_buf_t."""
    _fields_ = [("data", c_void_p), ("data_size", c_uint32),
                ("recv_utime", c_int64), ("lcm", c_void_p)]


class _Stats(Structure):
    """link.h's mpb_hub_stats."""
    _fields_ = [("is_hub", c_int), ("connected", c_int), ("connects", c_long),
                ("oversized", c_long), ("overflowed", c_long),
                ("malformed", c_long), ("retry_s", ctypes.c_double)]


_HANDLER = CFUNCTYPE(None, POINTER(_RecvBuf), c_char_p, c_void_p)

_c = Functions(
    mpb_lcm_create=(c_void_p, c_char_p, POINTER(c_char_p), c_int,
                            POINTER(c_int)),
    mpb_lcm_destroy=(None, c_void_p),
    mpb_lcm_publish=(c_int, c_void_p, c_char_p, c_char_p, c_uint),
    mpb_lcm_hub_stats=(None, c_void_p, POINTER(_Stats)),
    mpb_lcm_hub_wait=(c_int, c_void_p, ctypes.c_double),
    lcm_subscribe=(c_void_p, c_void_p, c_char_p, _HANDLER, c_void_p),
    lcm_handle_timeout=(c_int, c_void_p, c_int),
)


def is_hub(url: Optional[str]) -> bool:
    """Whether url names a hub: tcpq://... (mpb_lcm_url_is_hub())."""
    return bool(url) and url.startswith("tcpq://")


class HubLCM:
    """A hub link for url, subscribed at the hub to channels (every
    message the process wants must be on one: the hub relays no other).
    ValueError for a URL that is not tcpq://HOST:PORT."""

    def __init__(self, url: str, channels: Sequence[str]) -> None:
        self.channels = list(channels)
        names = (c_char_p * max(len(self.channels), 1))(
            *[c.encode() for c in self.channels])
        try:
            create = _c.mpb_lcm_create
        except OSError as e:
            raise ValueError(f"cannot load libmpbench ({path()}), whose "
                             f"hub link reaches {url}: {e}") from e
        self._lcm = create(url.encode(), names, len(self.channels), None)
        if not self._lcm:
            raise ValueError(f"{url}: a hub's URL is tcpq://HOST:PORT")
        # The C callbacks, kept alive as long as the instance.
        self._callbacks: Dict[str, object] = {}
        # The link connects in the background: a moment for it, as the C
        # kit gives it, so the first announcement is not lost.
        _c.mpb_lcm_hub_wait(self._lcm, 2.0)

    def subscribe(self, channel: str, handler: Handler) -> None:
        """Call handler(channel, data) for each message on channel (one of
        those given at creation) in handle_timeout()."""
        if channel not in self.channels:
            raise ValueError(f"channel {channel} was not given to the hub "
                             f"link at its creation")

        def on_message(rbuf, name, _user):
            buf = rbuf.contents
            handler(name.decode(errors="replace"),
                    ctypes.string_at(buf.data, buf.data_size))

        callback = _HANDLER(on_message)
        self._callbacks[channel] = callback
        # liblcm matches a subscription as a regular expression: the
        # channel's own characters, anchored, match it alone but for '.'.
        if not _c.lcm_subscribe(self._lcm, channel.encode(), callback, None):
            raise ValueError(f"cannot subscribe to {channel}")

    def publish(self, channel: str, data: bytes) -> None:
        """Send data on channel through the hub, one frame under the
        link's lock (safe from any thread); dropped, as a datagram may
        be, while the hub is away or past the bounds of lcm_filter.h."""
        data = bytes(data)
        _c.mpb_lcm_publish(self._lcm, channel.encode(), data, len(data))

    def handle_timeout(self, ms: int) -> int:
        """Hand out a message waiting, or one arriving within ms
        milliseconds, to its handler: >0 if one was, 0 if none came, <0
        on an error (lcm_handle_timeout())."""
        return int(_c.lcm_handle_timeout(self._lcm, int(ms)))

    def stats(self) -> _Stats:
        """What the link has seen (mpb_lcm_hub_stats())."""
        out = _Stats()
        _c.mpb_lcm_hub_stats(self._lcm, byref(out))
        return out

    @property
    def connects(self) -> int:
        """Connections made, the first included: the node re-sends its
        unacknowledged results when this grows."""
        return int(self.stats().connects)

    def close(self) -> None:
        """Stop the link and free it; no other thread may be using it."""
        if self._lcm:
            _c.mpb_lcm_destroy(self._lcm)
            self._lcm = None
