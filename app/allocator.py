"""Keep freed numpy temporaries in the heap instead of returning them to the kernel.

glibc's allocator gives memory above its trim threshold (128 KiB) back to the kernel on
free, and large blocks come from fresh ``mmap`` pages.  The analysis allocates and frees
arrays of 10^4..10^6 elements on every slider move, so each evaluation can page-fault its
working memory back in.  zwidth's own processes (the GUI, the command line and the benchmarks)
raise both thresholds at start-up.  The analysis package itself never does this: it is a
library, and this setting belongs to the process.

Since issue 21 the chain responses keep their work arrays per thread between calls
(``analysis.chain.response``), so a library user's process no longer pays for the default
settings on the usual devices: the HBFD at 2000 frequencies runs within a few per cent of the
tuned time (it was 1.7x, about 170 page faults per evaluation; ``tests/benchmarks/bench_untuned.py``,
BENCHMARKS.md).  The tuning still pays on long chains, whose ``n x N`` work arrays of several MB
are too large to keep.
"""

from __future__ import annotations

import ctypes
import ctypes.util
import sys

__all__ = ["tune_allocator", "trim_heap"]

_M_TRIM_THRESHOLD = -1
_M_TOP_PAD = -2
_M_MMAP_THRESHOLD = -3


def _glibc(name: str) -> ctypes._CFuncPtr | None:
    """glibc's function ``name`` (Linux), or ``None`` where there is none."""
    if not sys.platform.startswith("linux"):
        return None
    try:
        return getattr(ctypes.CDLL(ctypes.util.find_library("c") or "libc.so.6"), name)
    except (OSError, AttributeError):
        return None


def tune_allocator(enable: bool = True) -> bool:
    """Raise (or, with ``enable=False``, restore) glibc's trim and mmap thresholds.

    Returns ``True`` when the settings were applied (glibc on Linux), ``False`` elsewhere.
    """
    mallopt = _glibc("mallopt")
    if mallopt is None:
        return False
    mallopt.argtypes = [ctypes.c_int, ctypes.c_int]
    mallopt.restype = ctypes.c_int
    if enable:
        ok = mallopt(_M_TRIM_THRESHOLD, 256 << 20) and mallopt(_M_TOP_PAD, 64 << 20)
        ok = ok and mallopt(_M_MMAP_THRESHOLD, 32 << 20)
    else:  # glibc defaults
        ok = mallopt(_M_TRIM_THRESHOLD, 128 << 10) and mallopt(_M_TOP_PAD, 128 << 10)
        ok = ok and mallopt(_M_MMAP_THRESHOLD, 128 << 10)
    return bool(ok)


def trim_heap() -> bool:
    """Give the heap's free memory back to the kernel now (glibc ``malloc_trim(0)``).

    With :func:`tune_allocator` the heap keeps up to 256 MB of freed memory, so the resident size
    grows to the largest transient working set and stays there.  A memory measurement that asks
    what the process still *uses* (the state-machine benchmark) trims first.  Returns ``False``
    where there is no glibc."""
    trim = _glibc("malloc_trim")
    if trim is None:
        return False
    trim.argtypes = [ctypes.c_size_t]
    trim.restype = ctypes.c_int
    trim(0)
    return True
