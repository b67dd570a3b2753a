"""libmpbench.py - the one libmpbench.so the kit loads through ctypes, for
its world (world.py), authentication (auth.py), hub link (hub.py) and
socket filter (sockfilter.py): $MPB_LIBMPBENCH (the launchers set it to
the build tree's), else libmpbench.so.0 from the loader's path. liblcm's
own functions (lcm_subscribe, lcm_handle_timeout) are found through it,
as libmpbench links liblcm."""
from __future__ import annotations

import ctypes
import os
from typing import Any, Optional, Tuple

_lib: Optional[ctypes.CDLL] = None


def path() -> str:
    """The library the kit loads."""
    return os.environ.get("MPB_LIBMPBENCH", "libmpbench.so.0")


def library() -> ctypes.CDLL:
    """libmpbench, loaded once; OSError if it cannot be."""
    global _lib
    if _lib is None:
        _lib = ctypes.CDLL(path())
    return _lib


def declare(name: str, restype: Any, *argtypes: Any) -> Any:
    """The library's function name, with its result and argument types."""
    f = getattr(library(), name)
    f.restype = restype
    f.argtypes = list(argtypes)
    return f


class Functions:
    """Functions of the library declared on first use, for the parts of
    the kit a planner may go without (a secret, a hub): Functions(name=
    (restype, argtype, ...), ...).name(...). OSError at the first call
    if the library cannot be loaded."""

    def __init__(self, **signatures: Tuple[Any, ...]) -> None:
        self._signatures = signatures

    def __getattr__(self, name: str) -> Any:
        if name.startswith("_") or name not in self._signatures:
            raise AttributeError(name)
        restype, *argtypes = self._signatures[name]
        f = declare(name, restype, *argtypes)
        setattr(self, name, f)
        return f
