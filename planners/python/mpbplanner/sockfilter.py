"""sockfilter.py - the kernel filter of libmpbench's lcm_filter.h on the
receive socket the PyPI `lcm` binding makes for itself.

The binding's receive thread trusts the headers of what arrives: two
datagrams (a filler, then a short message whose channel name has no NUL)
hand the planner a 4294967295-byte message. The C processes attach a
classic BPF program that drops malformed datagrams (and the channels they
do not want) to their LCM socket; this attaches the same program, made by
libmpbench, to the one UDP socket on the URL's port that appears while
the binding's LCM instance is made.
"""
from __future__ import annotations

import ctypes
from ctypes import POINTER, c_char_p, c_int
from typing import Optional, Sequence, Set, Tuple

import lcm

from .libmpbench import library

SOCKETS_MAX = 64


def _library() -> Optional[ctypes.CDLL]:
    try:
        lib = library()
    except OSError:
        return None
    lib.mpb_lcm_sockets.restype = c_int
    lib.mpb_lcm_sockets.argtypes = [c_char_p, POINTER(c_int), c_int]
    lib.mpb_lcm_filter_socket.restype = c_int
    lib.mpb_lcm_filter_socket.argtypes = [c_int, POINTER(c_char_p), c_int]
    return lib


def _sockets(lib: ctypes.CDLL, url: Optional[str]) -> Set[int]:
    fds = (c_int * SOCKETS_MAX)()
    n = lib.mpb_lcm_sockets(url.encode() if url else None, fds, SOCKETS_MAX)
    return set(fds[:n])


def filtered_lcm(url: Optional[str],
                 channels: Sequence[str]) -> Tuple[lcm.LCM, bool]:
    """lcm.LCM(url) ("" or None: LCM's default), and whether its receive
    socket now drops malformed datagrams and every short message on a
    channel not in channels (at most 8 names; [] keeps every channel)."""
    lib = _library()
    before = _sockets(lib, url) if lib else set()
    lc = lcm.LCM(url) if url else lcm.LCM()
    if lib is None:
        return lc, False
    lc.fileno()                 # sets up the receive socket now
    new = _sockets(lib, url) - before
    if len(new) != 1:
        return lc, False
    names = (c_char_p * max(len(channels), 1))(*[c.encode() for c in channels])
    return lc, lib.mpb_lcm_filter_socket(new.pop(), names, len(channels)) == 0
