"""Verification reports: figures, error maps, HTML and Markdown documents, regression.

:func:`write_report` takes the study results of a run and writes, into one folder, the
studies' figures (PNG and SVG), the E x H error maps and pairwise-difference plots,
``index.html`` (self-contained), ``summary.md``, ``results.json`` (claims and tidy rows),
``baseline.json`` (for ``coathertz verify --baseline``) and ``rows/<study>.csv``.

The report imports only public names: the study framework's (:mod:`coathertz.verification`),
the registry's (:mod:`coathertz.methods`) and its own modules.
"""

from __future__ import annotations

import contextlib
import csv
import dataclasses
import inspect
import json
from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from coathertz.jsonsafe import to_jsonable as json_safe
from coathertz.report.baseline import Drift, baseline_dict, compare, write_baseline
from coathertz.report.document import html_page, markdown
from coathertz.verification import crosscheck_summary, group_by_case

__all__ = ["FIGURE_KEYS", "Drift", "ReportFiles", "compare", "figure_key", "plot_study", "write_report"]


@dataclass
class ReportFiles:
    html: Path
    markdown: Path
    results: Path
    baseline: Path
    figures: dict[str, list[Path]] = field(default_factory=dict)
    drift: list[Drift] | None = None

    @property
    def drifted(self) -> list[Drift]:
        return [d for d in (self.drift or []) if d.is_drift]


def _write_csv(path: Path, rows: Sequence[dict]) -> None:
    if not rows:
        return
    cols: list[str] = []
    for r in rows:
        cols += [k for k in r if k not in cols]
    with path.open("w", newline="") as fh:
        w = csv.DictWriter(fh, cols)
        w.writeheader()
        w.writerows(rows)


BARS = (("a_bar", "a"), ("p_bar", "p"), ("delta_bar", "delta"))


def side_by_side(rows: Sequence[dict], methods: Sequence[str], limit: int = 60) -> list[dict]:
    """The bars of every case that all the study's registered ``methods`` solved, one row per case,
    methods in rank order (reference first)."""
    from coathertz.methods import rank_order

    names = rank_order(methods)
    if len(names) < 2:
        return []
    out = []
    for cid, ms in group_by_case(rows).items():
        if all(m in ms for m in names):
            out.append({"case": cid, **{f"{q}:{m}": ms[m][k] for k, q in BARS for m in names}})
    return out[:limit]


#: Fields of a study result that do not reach its figures (timings and counts of this run).
_NOT_DRAWN = ("wall_time", "method_time", "computed", "reused", "workers")

#: The file in a figure folder that records which drawing each study's figures are.
FIGURE_KEYS = ".figure-keys.json"


def _drawn(result: Any) -> dict:
    """What a study's figures are drawn from: its JSON form (``to_json``) less the timings and
    counts of this run. A dataclass result is read field by field, without the deep copy of
    every row that ``dataclasses.asdict`` makes (a third of the time of :func:`figure_key`);
    its claims keep their verdicts."""
    if not dataclasses.is_dataclass(result):
        return {k: v for k, v in result.to_json().items() if k not in _NOT_DRAWN}
    d = {f.name: getattr(result, f.name) for f in dataclasses.fields(result) if f.name not in _NOT_DRAWN}
    if "claims" in d:
        d["claims"] = [{**dataclasses.asdict(c), "verdict": c.verdict} for c in d["claims"]]
    return d


def _key_default(obj: Any) -> Any:
    """JSON form of what :func:`~coathertz.jsonsafe.to_jsonable` leaves (a dataclass nested in
    a result's ``extra``: its fields, arrays in full)."""
    if dataclasses.is_dataclass(obj) and not isinstance(obj, type):
        return json_safe(dataclasses.asdict(obj))
    return str(obj)


def figure_key(result: Any, module: Any | None, formats: Sequence[str]) -> str:
    """A hash of everything a study's figures are drawn from: the result (less its timings), the
    source of the study module and of the plotting code, matplotlib's version and the formats."""
    import hashlib

    import matplotlib

    from coathertz import figstyle
    from coathertz.report import figures as report_figures

    h = hashlib.sha256(json.dumps(json_safe(_drawn(result)), sort_keys=True, default=_key_default).encode())
    for mod in (module, figstyle, report_figures):
        if mod is not None:
            with contextlib.suppress(OSError, TypeError):
                h.update(inspect.getsource(mod).encode())
    h.update(f"{matplotlib.__version__} {sorted(formats)}".encode())
    return h.hexdigest()


def plot_study(result: Any, module: Any | None, figdir: str | Path) -> list[Path]:
    """Draw the figures of one study result: the study module's own (``module.plot``) and the
    report's E x H error maps and pairwise plots, unless the module sets ``GENERIC_FIGURES =
    False``. Also stores the cross-check summaries the pages show in ``result.extra``. Inside a
    :func:`coathertz.figstyle.saving` block the figures are built and rendered in the background,
    in a process of their own (:func:`coathertz.figstyle.draw_elsewhere`), and the list returned
    is complete, like the files, when the block ends.

    Figures drawn from the same numbers by the same code (:func:`figure_key`, recorded in
    ``figdir/.figure-keys.json``) and still on disk are not drawn again."""
    from coathertz.figstyle import active_formats, after_renders, draw_elsewhere
    from coathertz.methods import method_names
    from coathertz.report.figures import error_heatmaps, pairwise_plot

    figdir = Path(figdir)
    generic = getattr(module, "GENERIC_FIGURES", True)  # studies re-using another's cases opt out
    if generic:
        result.extra["pairwise"] = crosscheck_summary(result.crosscheck)
        registered = set(method_names())
        result.extra["side_by_side"] = side_by_side(result.rows,
                                                    [m for m in result.methods if m in registered])
    key = figure_key(result, module, active_formats())
    keys_path = figdir / FIGURE_KEYS
    try:
        keys = json.loads(keys_path.read_text())
    except (OSError, ValueError):
        keys = {}
    old = keys.get(result.name, {})
    if old.get("key") == key and old.get("files") and all((figdir / f).is_file() for f in old["files"]):
        return [figdir / f for f in old["files"]]

    def draw() -> list[Path]:
        drawn: list[Path] = list(module.plot(result, figdir)) if module is not None else []
        if generic:
            drawn += error_heatmaps(result, figdir)
            drawn += pairwise_plot(result, figdir)
        return drawn

    # built and written in a render process of its own (in a saving block), this one goes on
    paths = draw_elsewhere(result.name, draw)

    def record() -> None:  # only once the files are complete
        try:
            now = json.loads(keys_path.read_text())
        except (OSError, ValueError):
            now = {}
        now[result.name] = {"key": key, "files": [p.name for p in paths]}
        keys_path.write_text(json.dumps(now, indent=1, sort_keys=True))

    keys.pop(result.name, None)  # redrawn: the old record no longer holds until then
    figdir.mkdir(parents=True, exist_ok=True)
    keys_path.write_text(json.dumps(keys, indent=1, sort_keys=True))
    after_renders(record)
    return paths


def write_report(
    results: Sequence[Any],
    outdir: str | Path,
    provenance: dict,
    modules: dict[str, Any] | None = None,
    baseline: dict | None = None,
    notes: Sequence[str] = (),
    svg: bool = False,
    jobs: int | None = None,
    figures: dict[str, list[Path]] | None = None,
) -> ReportFiles:
    """Write the full report of ``results`` (study results) into ``outdir``.

    ``figures`` are the studies' figure files where they were already drawn (by
    :func:`plot_study` into ``outdir/figures``, as ``coathertz verify`` does while the next study
    runs); otherwise they are drawn here: PNG (what the pages embed), with SVG copies if ``svg``,
    rendered by up to ``jobs`` processes at once (default: the CPUs this process may use).
    """
    from coathertz.figstyle import saving

    out = Path(outdir)
    figdir = out / "figures"
    figdir.mkdir(parents=True, exist_ok=True)
    (out / "rows").mkdir(exist_ok=True)
    mods = modules or {}
    docs = {r.name: inspect.getdoc(mods[r.name]) or "" for r in results if r.name in mods}
    if figures is None:
        figures = {}
        with saving(("png", "svg") if svg else ("png",), jobs):  # every render done at the end
            for r in results:
                figures[r.name] = plot_study(r, mods.get(r.name), figdir)
    for r in results:
        _write_csv(out / "rows" / f"{r.name}.csv", r.rows)
        _write_csv(out / "rows" / f"{r.name}_errors.csv", r.errors)
    current = baseline_dict(results, provenance)
    drift = compare(baseline, current) if baseline is not None else None
    results_path = out / "results.json"
    results_path.write_text(json.dumps(json_safe({"provenance": provenance,
                                                   "studies": [r.to_json() for r in results]}), indent=1))
    base_path = write_baseline(out / "baseline.json", results, provenance)
    md = out / "summary.md"
    md.write_text(markdown(results, provenance, figures, out, drift, notes))
    page = out / "index.html"
    page.write_text(html_page(results, provenance, figures, drift, notes, docs))
    return ReportFiles(page, md, results_path, base_path, figures, drift)
