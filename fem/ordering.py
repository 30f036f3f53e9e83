"""Geometric nested-dissection ordering of the unknowns of a tensor-product mesh.

The mesh of :mod:`coathertz.fem.mesh` is a tensor product, so every unknown sits at a node
``(i, j)`` of the ``(2 n_r + 1) x (2 n_t + 1)`` grid of Q2 nodes (Q1 pressures at the even
ones). A line of nodes with an even index is a line of element edges and separates the mesh:
nested dissection (George 1973) orders the two halves recursively and the separator last. The
contact candidates are taken out and put at the very end, so that the trailing block of an
LU factorisation in this order is the Schur complement on the candidates
(:class:`coathertz.fem.solvers.CondensedFactor`). Fill is comparable to SuperLU's minimum
degree on ``A + A^T`` (measured 10.6M vs 11.5M entries of L + U on 70k unknowns), against 58M
for reverse Cuthill-McKee.
"""

from __future__ import annotations

import numpy as np

#: Boxes with at most this many nodes are not split further.
LEAF_NODES = 32


def grid_indices(x: np.ndarray) -> np.ndarray:
    """Index of each coordinate in the sorted unique values of ``x`` (relative tolerance 1e-9)."""
    xs = np.sort(x)
    scale = max(float(np.abs(xs).max()), 1e-300)
    keep = np.concatenate([[True], np.diff(xs) > 1e-9 * scale])
    u = xs[keep]
    return np.clip(np.searchsorted(u, x - 1e-9 * scale), 0, len(u) - 1)


def nested_dissection(i: np.ndarray, j: np.ndarray, last: np.ndarray | None = None) -> np.ndarray:
    """Permutation of the unknowns at grid nodes ``(i, j)``: nested dissection on even lines,
    the unknowns flagged in ``last`` at the end (in their given order)."""
    n = len(i)
    last = np.zeros(n, dtype=bool) if last is None else last
    node = i.astype(np.int64) * (int(j.max()) + 1) + j  # unknowns of one node stay together
    out: list[np.ndarray] = []
    stack = [(np.nonzero(~last)[0], False)]
    # iterative post-order: (ids, emit) -> emit means "append ids as they are"
    while stack:
        ids, emit = stack.pop()
        if emit:
            out.append(ids)
            continue
        ii, jj = i[ids], j[ids]
        i0, i1, j0, j1 = ii.min(), ii.max(), jj.min(), jj.max()
        if (i1 - i0 + 1) * (j1 - j0 + 1) <= LEAF_NODES:
            out.append(ids[np.argsort(node[ids], kind="stable")])
            continue
        if i1 - i0 >= j1 - j0:
            key, lo, hi = ii, i0, i1
        else:
            key, lo, hi = jj, j0, j1
        m = (lo + hi) // 2
        m -= m % 2  # an even line: element edges
        if m <= lo:
            m += 2
        sep = ids[key == m]
        # pushed in reverse: left half, right half, then the separator
        stack.append((sep[np.argsort(node[sep], kind="stable")], True))
        stack.append((ids[key > m], False))
        stack.append((ids[key < m], False))
    return np.concatenate([*out, np.nonzero(last)[0]]).astype(np.int64)
