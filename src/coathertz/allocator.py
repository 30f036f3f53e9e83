"""The C allocator's settings for a whole run (glibc's ``mallopt``).

The solvers allocate and free arrays of 0.1–30 MB thousands of times per run (FFT work arrays,
FE element matrices, figure buffers). By default glibc serves each from fresh ``mmap`` pages or
gives the top of its heap back to the kernel as soon as 128 KiB are free, so every new array
faults its pages in again, zero-filled by the kernel. Keeping freed memory
in the process (a higher trim threshold and top padding, and the heap for arrays up to 64 MiB)
removes about 28 % of the page faults of the quick verification run (1.23 M → 0.90 M) and about
1.2 s of its system time (2 cores, five runs each way; its user time varied from run to run by
more than any difference). The cost is memory a process keeps after a peak: at most about
:data:`TRIM_THRESHOLD` per process above what it holds.

Arrays larger than :data:`MMAP_THRESHOLD` still come from ``mmap`` and go back at once. Where the
C library is not glibc (macOS, musl) nothing changes.
"""

from __future__ import annotations

import ctypes
import sys

#: Blocks at least this large [bytes] are mapped on their own (glibc ``M_MMAP_THRESHOLD``).
MMAP_THRESHOLD = 64 * 2**20
#: Free memory at the top of the heap kept before it is returned [bytes] (``M_TRIM_THRESHOLD``).
TRIM_THRESHOLD = 256 * 2**20
#: Extra memory asked of the kernel whenever the heap grows [bytes] (``M_TOP_PAD``).
TOP_PAD = 64 * 2**20

_M_TRIM_THRESHOLD, _M_TOP_PAD, _M_MMAP_THRESHOLD = -1, -2, -3
_DONE: list[bool] = []


def keep_freed_memory() -> bool:
    """Apply the settings above to this process (and the processes it forks later); once per
    process. Returns whether glibc accepted them."""
    if _DONE:
        return _DONE[0]
    ok = False
    if sys.platform.startswith("linux"):
        try:
            libc = ctypes.CDLL(None)
            mallopt = libc.mallopt
            mallopt.argtypes, mallopt.restype = [ctypes.c_int, ctypes.c_int], ctypes.c_int
            ok = all(mallopt(param, value) == 1 for param, value in (
                (_M_MMAP_THRESHOLD, MMAP_THRESHOLD), (_M_TRIM_THRESHOLD, TRIM_THRESHOLD),
                (_M_TOP_PAD, TOP_PAD)))
        except (OSError, AttributeError):  # not glibc
            ok = False
    _DONE.append(ok)
    return ok
