"""The allocator settings (``coathertz.allocator``): freed arrays are reused, not faulted in again."""

from __future__ import annotations

import platform
import subprocess
import sys
import textwrap

import pytest

PROBE = textwrap.dedent("""
    import resource, sys
    import numpy as np
    from coathertz.allocator import keep_freed_memory
    ok = keep_freed_memory()
    a = np.ones(4 * 2**20); del a  # 32 MiB, below MMAP_THRESHOLD: the heap grows once
    f0 = resource.getrusage(resource.RUSAGE_SELF).ru_minflt
    for _ in range(5):
        a = np.ones(4 * 2**20); del a
    print(ok, resource.getrusage(resource.RUSAGE_SELF).ru_minflt - f0)
""")


@pytest.mark.skipif(not sys.platform.startswith("linux") or platform.libc_ver()[0] != "glibc",
                    reason="mallopt settings exist on glibc only")
def test_freed_arrays_are_reused_without_page_faults():
    """Five 32 MiB arrays allocated and freed after a first one: with the settings applied they
    reuse its memory (a few faults at most, for small objects), where each would otherwise fault
    up to its 8192 pages in again (glibc's defaults give memory back at every free)."""
    out = subprocess.run([sys.executable, "-c", PROBE], capture_output=True, text=True, check=True)
    ok, faults = out.stdout.split()
    assert ok == "True"
    assert int(faults) <= 64, f"{faults} page faults for 5 reused 32 MiB arrays (5 x 8192 if none is)"
