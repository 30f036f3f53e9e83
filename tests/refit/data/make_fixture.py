"""Regenerate the small fixture sweep and its data file from the shipped sweep.

Usage (repository root)::

    python tests/refit/data/make_fixture.py
    coathertz fit-alpha --sweep tests/refit/data/small_sweep.json --out tests/refit/data/small_refit.json
"""

from __future__ import annotations

from importlib import resources
from pathlib import Path

import numpy as np

from coathertz.cli.fit_alpha import export_sweep, load_sweep

SIZES = {("elastic", "train"): 150, ("elastic", "valid"): 40, ("rigid", "train"): 80,
         ("rigid", "valid"): 20, ("ellipse", "train"): 80, ("ellipse", "valid"): 20}


def main() -> None:
    src = Path(str(resources.files("coathertz") / "data" / "alpha_refit_sweep.json"))
    cols, prov = load_sweep(src)
    rng = np.random.default_rng(0)
    cfg, which = np.asarray(cols["config"]), np.asarray(cols["set"])
    keep = []
    for (c, w), n in SIZES.items():
        idx = np.flatnonzero((cfg == c) & (which == w))
        keep += sorted(rng.choice(idx, size=min(n, idx.size), replace=False).tolist())
    small = {k: [v[i] for i in keep] for k, v in cols.items()}
    sizes = {f"{c}/{w}": n for (c, w), n in SIZES.items()}
    prov = {**prov, "fixture": f"subset of {src.name}: {sizes}"}
    export_sweep(Path(__file__).parent / "small_sweep.json", small, prov)


if __name__ == "__main__":
    main()
