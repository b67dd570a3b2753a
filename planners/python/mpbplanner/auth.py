"""auth.py - the optional shared secret (docs/protocol.md,
"Authentication") through libmpbench's own functions (mpbench/auth.h),
so that the Python kit and the C processes seal and check messages with
one piece of code.

After each message goes a trailer of this process's instance, a counter
and the instance it answers, then a tag over the channel, the message
and those bytes (auth.h says which bytes and how). A receiver believes a
sender once it echoes the receiver's instance, and drops any counter of
it had before (a replay). The library keeps the key, the counter and the
senders believed; this class only hands bytes across.
"""
from __future__ import annotations

import ctypes
from ctypes import (POINTER, Structure, byref, c_char_p, c_int, c_size_t,
                    c_uint64, c_void_p)
from typing import Optional, Tuple

from .libmpbench import Functions, path

TAG_BYTES = 32                  # MPB_AUTH_TAG_SIZE
TRAILER_BYTES = 24 + TAG_BYTES  # MPB_AUTH_TRAILER_SIZE


class AuthError(ValueError):
    """A secret the library refused (unreadable, shorter than 16 bytes);
    the message is the library's one line naming the file."""


class _Info(Structure):
    """auth.h's mpb_auth_info."""
    _fields_ = [("instance", c_uint64), ("counter", c_uint64),
                ("echo", c_uint64)]


_Trailer = ctypes.c_ubyte * TRAILER_BYTES

_c = Functions(
    mpb_auth_open=(c_int, c_char_p, POINTER(c_void_p), c_char_p, c_size_t),
    mpb_auth_close=(None, c_void_p),
    mpb_auth_instance=(c_uint64, c_void_p),
    mpb_auth_check=(c_int, c_void_p, c_char_p, c_char_p, c_size_t,
                   POINTER(c_size_t), POINTER(_Info)),
    mpb_auth_verdict_text=(c_char_p, c_int),
    mpb_auth_seal=(c_int, c_void_p, c_char_p, c_char_p, c_size_t, c_uint64,
                   _Trailer),
    mpb_auth_trailer=(None, c_void_p, c_char_p, c_char_p, c_size_t, c_uint64,
                      c_uint64, c_uint64, _Trailer),
)


class Auth:
    """A secret read from a file (mpb_auth_open()), this process's
    instance and counter, and the senders it believes. seal() is safe from
    any thread; open() is for one thread only (the node's LCM thread)."""

    # mpb_auth_verdict, as open() returns it.
    FRESH, UNPROVEN, REPLAYED, BAD_TAG = range(4)

    def __init__(self, secret: str) -> None:
        """Read the secret file at the path secret (mpb_auth_open())."""
        self._a: Optional[c_void_p] = None
        err = ctypes.create_string_buffer(512)
        handle = c_void_p()
        try:
            load = _c.mpb_auth_open
        except OSError as e:
            raise AuthError(f"cannot load libmpbench ({path()}), which "
                            f"authenticates messages: {e}") from e
        if load(secret.encode(), byref(handle), err, len(err)) != 0:
            raise AuthError(err.value.decode(errors="replace"))
        self._a = handle

    def close(self) -> None:
        """Free the library's copy of the key; the object is unusable
        after. Not done on garbage collection: another thread may be
        sealing with it (in the library, without the GIL) until exit."""
        if self._a:
            _c.mpb_auth_close(self._a)
            self._a = None

    def _handle(self) -> c_void_p:
        # Never NULL to the library, which passes every message as FRESH
        # without a secret.
        if not self._a:
            raise AuthError("the secret was closed")
        return self._a

    @property
    def instance(self) -> int:
        """This process's instance (never 0), which answers echo."""
        return int(_c.mpb_auth_instance(self._handle()))

    def seal(self, channel: str, data: bytes, echo: int = 0) -> bytes:
        """data followed by its trailer (mpb_auth_seal()): this process's
        instance, its next counter, echo (the instance of the process it
        answers, 0 for none) and the tag."""
        data = bytes(data)
        out = _Trailer()
        if _c.mpb_auth_seal(self._handle(), channel.encode(), data,
                            len(data), echo, out) != 0:
            raise AuthError("cannot seal a message: no secret or channel")
        return data + bytes(out)

    def trailer(self, channel: str, data: bytes, instance: int, counter: int,
                echo: int) -> bytes:
        """The trailer of data on channel with these fields
        (mpb_auth_trailer()): for tests and the protocol's test vector."""
        data = bytes(data)
        out = _Trailer()
        _c.mpb_auth_trailer(self._handle(), channel.encode(), data, len(data),
                            instance, counter, echo, out)
        return bytes(out)

    def open(self, channel: str,
             data: bytes) -> Tuple[int, Optional[bytes], int]:
        """(verdict, the message without its trailer or None for BAD_TAG,
        the sender's instance) of a received message (mpb_auth_check()).
        Only a FRESH or UNPROVEN message may be decoded; a FRESH one is
        remembered, so the same bytes again are REPLAYED."""
        data = bytes(data)
        size, info = c_size_t(), _Info()
        verdict = _c.mpb_auth_check(self._handle(), channel.encode(), data,
                                    len(data), byref(size), byref(info))
        if verdict == self.BAD_TAG:
            return verdict, None, 0
        return verdict, data[:size.value], int(info.instance)

    @staticmethod
    def verdict_text(verdict: int) -> str:
        """A few words on a verdict, for a log line
        (mpb_auth_verdict_text())."""
        return _c.mpb_auth_verdict_text(verdict).decode()
