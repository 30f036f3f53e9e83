"""BLAS thread limits, shared by every part that runs small dense algebra.

Threaded BLAS on small products (the exact method's Galerkin systems, the FE contact's Schur
complement, the refit's per-block matrix products) only adds wake-up and contention costs on
the 2-core machines this suite runs on (measured: an exact-method case 480 ms with the default
threads against 17 ms with one; the FE's 173 x 173 Schur inverse 80-150 ms against 1 ms when the
other core is busy). Once numpy is loaded only ``threadpoolctl`` can limit its BLAS threads from
inside the process; without it (it is a declared dependency) the limits are no-ops.
"""

from __future__ import annotations

import contextlib
import math

_STATE: list = []  # [ThreadpoolController of the BLAS libraries, their default thread count]


def blas_threads(n: int | None) -> contextlib.AbstractContextManager:
    """Run a block with BLAS limited to ``n`` threads (``None``: the libraries' default, e.g. a
    sparse factorisation inside a block limited to one). The controller is built once per
    process."""
    if not _STATE:
        try:
            from threadpoolctl import ThreadpoolController
        except ImportError:  # pragma: no cover - declared dependency
            return contextlib.nullcontext()
        import scipy.linalg  # noqa: F401 - load scipy's BLAS before the controller looks for it

        ctl = ThreadpoolController().select(user_api="blas")
        _STATE.extend([ctl, max([c["num_threads"] for c in ctl.info()], default=1)])
    ctl, default = _STATE
    return ctl.limit(limits=default if n is None else n)


def norm2(x) -> float:
    """Euclidean norm of a vector without BLAS. OpenBLAS threads ``ddot`` (and so
    ``np.linalg.norm``) beyond 10k entries, and each such call leaves its second thread spinning for
    about 0.11 s (measured: 0.11 CPU-s during a 0.3 s sleep after one norm of 28.7k entries, none
    after this one); in the elastic-plastic Newton loop, which takes several norms of the whole
    out-of-balance force per iteration, that kept the other core busy (20 of 50 CPU-s on the
    delta/delta_c = 200 path of ``tests/benchmarks/bench_plastic.py``)."""
    import numpy as np

    return math.sqrt(float(np.einsum("i,i->", x, x)))
