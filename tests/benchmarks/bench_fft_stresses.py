"""Benchmark of the FFT stress field (a script, not a timed test): issue 18's performance goals.

On one core (BLAS and scipy.fft pinned to one thread), CPU time (``time.process_time``, the
fastest of ``--repeat`` runs, so that a loaded shared machine inflates it least) and peak memory:

1. the full tensor (6 components) on 128^2 at 64 depths (goal <= 1 s), pressure and sliding
   (mu = 0.3) on a coated body (a = 0.1 mm, h = 0.2 a, domain 4a, pad 4, depths geometric from
   0.001 a to 3 a), in double and single precision; also the normal load alone;
2. 256^2 at 128 depths into one preallocated float64 array (403 MB; goal: peak < 2 GB);
   the depths are computed one at a time, so the working memory beyond the result is one
   depth's spectra.

Peak memory is ``tracemalloc``'s traced peak (numpy's buffers included) of each run, and the
process's ``ru_maxrss`` at the end. With ``--old REV`` the module as of git revision ``REV``
(default: the first parent of the commit that made it fast) is timed in the same run on the
same inputs (part 1 only; its field is compared with the new one).

Usage: ``python tests/benchmarks/bench_fft_stresses.py [--quick] [--repeat N] [--old REV]``.
"""

from __future__ import annotations

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
os.environ.setdefault("OMP_NUM_THREADS", "1")

import argparse
import importlib.util
import platform
import resource
import subprocess
import sys
import tempfile
import time
import tracemalloc
from pathlib import Path

import numpy as np

from coathertz.fft.frf import Layer
from coathertz.fft.grid import Grid
from coathertz.fft.stresses import CoatedStressFRF, stresses_surface
from coathertz.materials import Material

A = 1e-4  # contact radius [m]
OLD_REV = "96b7277"  # main before the stack stresses and the speed work


def inputs(n: int, n_depths: int):
    g = Grid(n, n, 4 * A / n, 4 * A / n)
    X, Y = np.meshgrid(g.x, g.y)
    p = 1e9 * np.sqrt(np.clip(1 - (X**2 + Y**2) / A**2, 0, None))
    frf = CoatedStressFRF(Layer(Material(E=300e9, nu=0.25), Material(E=200e9, nu=0.3)), 0.2 * A)
    depths = np.geomspace(1e-3 * A, 3 * A, n_depths)
    return g, p, frf, depths


def timed(fn, repeat: int) -> tuple[float, float, object]:
    """Fastest CPU time [s] of ``repeat`` calls, peak traced memory [MB] of one, and its result."""
    best = np.inf
    for _ in range(repeat):
        t0 = time.process_time()
        out = fn()
        best = min(best, time.process_time() - t0)
        del out
    tracemalloc.start()
    out = fn()
    _, peak = tracemalloc.get_traced_memory()
    tracemalloc.stop()
    return best, peak / 1e6, out


def load_old(rev: str):
    """The stress module as of git revision ``rev`` (None if git or the revision is missing)."""
    root = Path(__file__).resolve().parents[2]
    try:
        src = subprocess.run(["git", "-C", str(root), "show", f"{rev}:src/coathertz/fft/stresses.py"],
                             check=True, capture_output=True, text=True).stdout
    except (OSError, subprocess.CalledProcessError):
        return None
    path = Path(tempfile.mkdtemp()) / "old_fft_stresses.py"
    path.write_text(src)
    spec = importlib.util.spec_from_file_location("old_fft_stresses", path)
    mod = importlib.util.module_from_spec(spec)
    sys.modules["old_fft_stresses"] = mod
    spec.loader.exec_module(mod)
    return mod


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="part 1 only")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--old", default=OLD_REV, help="git revision of the old module ('' for none)")
    args = ap.parse_args()
    print(f"machine: {platform.machine()}, {os.cpu_count()} CPUs, load average "
          f"{os.getloadavg()[0]:.1f}, python {platform.python_version()}, numpy {np.__version__}")
    g, p, frf, depths = inputs(128, 64)
    kw = {"p": p, "qx": 0.3 * p}
    old = load_old(args.old) if args.old else None
    ref = None
    if old is not None:
        frf_old = old.CoatedStressFRF(frf.layer, frf.h)  # the old module's own responses
        t, m, ref = timed(lambda: old.stresses_surface(g, depths, frf_old, **kw), args.repeat)
        print(f"128^2 x 64 depths, pressure + sliding, old ({args.old}): {t:.2f} s CPU, "
              f"peak traced {m:.0f} MB")
    for prec in ("double", "single"):
        t, m, out = timed(lambda prec=prec: stresses_surface(g, depths, frf, precision=prec, **kw),
                          args.repeat)
        diff = "" if ref is None else f", max |new - old| {np.abs(out - ref).max() / 1e9:.1e} p0"
        print(f"128^2 x 64 depths, pressure + sliding, {prec}: {t:.2f} s CPU (goal <= 1 s), "
              f"peak traced {m:.0f} MB (result {out.nbytes / 1e6:.0f} MB){diff}")
    t, m, out = timed(lambda: stresses_surface(g, depths, frf, p=p), args.repeat)
    print(f"128^2 x 64 depths, pressure only, double: {t:.2f} s CPU, peak traced {m:.0f} MB")
    if not args.quick:
        g2, p2, frf2, depths2 = inputs(256, 128)
        result = np.empty((depths2.size, 6, 256, 256))
        for prec in ("double", "single"):
            t, m, _ = timed(lambda prec=prec: stresses_surface(
                g2, depths2, frf2, p=p2, qx=0.3 * p2, precision=prec, out=result), 1)
            print(f"256^2 x 128 depths, pressure + sliding, {prec}: {t:.2f} s CPU, peak traced "
                  f"{m:.0f} MB beyond the {result.nbytes / 1e6:.0f} MB result (goal: total < 2000 MB)")
    rss = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1e3
    print(f"process peak resident memory (ru_maxrss): {rss:.0f} MB")


if __name__ == "__main__":
    main()
