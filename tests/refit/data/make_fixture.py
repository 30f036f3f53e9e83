"""Regenerate the small fixture sweep and its data file from the shipped sweep.

Usage (repository root)::

    python tests/refit/data/make_fixture.py
    coathertz fit-alpha --sweep tests/refit/data/small_sweep.json --out tests/refit/data/small_refit.json

The fixture keeps every fourth node of the shipped training grids (elastic 9 x 5 x 5 of
33 x 17 x 17, rigid 17 x 9 of 65 x 33), a random subset of the validation and ellipse rows,
and carries smaller fit settings (``provenance.fit_settings``) that the fit-alpha command uses.
"""

from __future__ import annotations

from importlib import resources
from pathlib import Path

import numpy as np

from coathertz.cli.fit_alpha import export_sweep, load_sweep
from coathertz.closedform.refit.model import t_nu
from coathertz.closedform.refit.reduced import s_coordinate
from coathertz.fitalpha.fit import FitSettings
from coathertz.fitalpha.sweep import REDUCED_BOX, RIGID_BOX, lobatto

SIZES = {("elastic", "valid"): 60, ("rigid", "valid"): 40, ("ellipse", "train"): 80, ("ellipse", "valid"): 20}
SETTINGS = {
    "elastic": FitSettings((6, 4, 2), ((2, 2),), reweight=0),
    "rigid": FitSettings((8, 6), (), reweight=0),
    "ellipse": FitSettings((4, 3, 2), ((2, 2),), reweight=0),
    "corrected_elastic": FitSettings((8, 4, 4), ((8, 4),), ridge=1e-10, reweight=0),
    "corrected_rigid": FitSettings((12, 6), (), ridge=1e-10, reweight=0),
}


def _on(x, nodes, tol=1e-7) -> np.ndarray:
    return np.min(np.abs(np.asarray(x, dtype=float)[:, None] - nodes[None, :]), axis=1) < tol


def main() -> None:
    src = Path(str(resources.files("coathertz") / "data" / "alpha_refit_sweep.json.gz"))
    cols, prov = load_sweep(src)
    rng = np.random.default_rng(0)
    cfg, which = np.asarray(cols["config"]), np.asarray(cols["set"])
    H, E = np.log10(np.asarray(cols["H"], float)), np.log10(np.asarray(cols["E"], float))
    nu_c, nu_s = np.asarray(cols["nu_c"], float), np.asarray(cols["nu_s"], float)
    el = (cfg == "elastic") & (which == "train") & _on(H, lobatto(9, *REDUCED_BOX["log10_H"])) \
        & _on(E, lobatto(5, *REDUCED_BOX["log10_E"])) & _on(s_coordinate(10**E, nu_c, nu_s), lobatto(5, 0, 1))
    t_nodes = lobatto(9, float(t_nu(0.5)), float(t_nu(0.0)))
    rg = (cfg == "rigid") & (which == "train") & _on(H, lobatto(17, *RIGID_BOX["log10_H"])) \
        & _on(t_nu(nu_c), t_nodes, 1e-6)
    keep = np.flatnonzero(el | rg).tolist()
    for (c, w), n in SIZES.items():
        idx = np.flatnonzero((cfg == c) & (which == w))
        keep += sorted(rng.choice(idx, size=min(n, idx.size), replace=False).tolist())
    small = {k: [v[i] for i in keep] for k, v in cols.items()}
    sizes = {"elastic/train": int(el.sum()), "rigid/train": int(rg.sum()),
             **{f"{c}/{w}": n for (c, w), n in SIZES.items()}}
    prov = {**prov, "fixture": f"subset of {src.name}: {sizes}",
            "fit_settings": {k: s.to_dict() for k, s in SETTINGS.items()}}
    export_sweep(Path(__file__).parent / "small_sweep.json", small, prov)
    print(sizes)


if __name__ == "__main__":
    main()
