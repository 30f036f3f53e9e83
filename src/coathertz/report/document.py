"""The report documents: a self-contained HTML page (figures embedded) and a Markdown summary.

Both open with the claims table (each claim, our number, the paper's bound, holds / does not
hold), then the regression result against a baseline if one was given, provenance and run
times, and one section per study (its claim, its figures, the methods' pairwise differences,
any failed cases).
"""

from __future__ import annotations

import base64
import html
import math
from collections.abc import Sequence
from pathlib import Path
from typing import Any

INCONCLUSIVE = "inconclusive (within numerical error)"
VERDICT_STYLE = {"holds": "#d8f0d8", "does not hold": "#f6d0d0", INCONCLUSIVE: "#f8ecc0",
                 "observed": "#eeeeee", "n/a": "#ffffff"}
#: Verdicts in counting order, with singular and plural phrasing.
_PHRASES = (("holds", "holds", "hold"), ("does not hold", "does not hold", "do not hold"),
            (INCONCLUSIVE, "is inconclusive (within numerical error)",
             "are inconclusive (within numerical error)"),
            ("observed", "observation", "observations"),
            ("n/a", "could not be computed", "could not be computed"))
COUNTS_NOTE = ("results: one per case and method; solved now: in this run; reused: taken from the result "
               "store, where an earlier run stored the same case with the same method, settings and "
               "code version")


def _num(v: float, unit: str) -> str:
    if not math.isfinite(v):
        return "—"
    return f"{v:.3g}{' ' + unit if unit else ''}"


def _unc(c: Any) -> str:
    u = getattr(c, "uncertainty", math.nan)
    judged = getattr(c, "judged_against", "")
    if (c.holds is None or not judged or judged.endswith("itself")) and not math.isfinite(u):
        return ""
    return "not estimated" if not math.isfinite(u) else f"± {u:.2g}{' ' + c.unit if c.unit else ''}"


def verdict_counts(verdicts: Sequence[str]) -> str:
    """``"26 hold, 1 does not hold, 3 are inconclusive (within numerical error), 43 observations"``:
    every verdict class present, each count agreeing in number."""
    parts = []
    for key, one, many in _PHRASES:
        n = sum(1 for v in verdicts if v == key)
        if n:
            parts.append(f"{n} {one if n == 1 else many}")
    other = len([v for v in verdicts if v not in {k for k, _, _ in _PHRASES}])
    if other:
        parts.append(f"{other} other")
    return ", ".join(parts) + f" ({len(verdicts)} claim{'s' if len(verdicts) != 1 else ''})"


def cases_phrase(r: Any) -> str:
    """``"72 cases (quick resolution)"``: the set a study ran on in this run."""
    n = len(r.extra.get("cases", {})) or len({x["case"] for x in r.rows})
    return f"{n} case{'s' if n != 1 else ''} at the {r.resolution} resolution"


def claims_rows(results: Sequence[Any]) -> list[dict]:
    rows = []
    for r in results:
        for c in r.claims:
            rows.append({"study": r.name, "id": c.id, "claim": c.text, "value": _num(c.value, c.unit),
                         "uncertainty": _unc(c), "bound": c.bound, "verdict": c.verdict,
                         "judged": getattr(c, "judged_against", ""), "detail": c.detail})
    return rows


def _md_escape(s: str) -> str:
    return s.replace("|", "\\|").replace("\n", " ")


def markdown(results: Sequence[Any], provenance: dict, figures: dict[str, list[Path]], outdir: Path,
             drift: Sequence[Any] | None = None, notes: Sequence[str] = ()) -> str:
    """Markdown summary (figures linked, not embedded)."""
    lines = ["# coathertz verification report", ""]
    verdicts = [row["verdict"] for row in claims_rows(results)]
    lines.append(f"Resolution **{provenance.get('resolution')}**, {provenance.get('date')}; "
                 + verdict_counts(verdicts) + ".")
    lines += ["", "## Claims", "", CLAIMS_NOTE, "",
              "| study | claim | ours | uncertainty | paper | verdict | judged against | detail |",
              "|---|---|---|---|---|---|---|---|"]
    for row in claims_rows(results):
        lines.append("| " + " | ".join(_md_escape(str(row[k])) for k in
                                        ("study", "claim", "value", "uncertainty", "bound", "verdict",
                                         "judged", "detail")) + " |")
    if drift is not None:
        lines += ["", "## Regression against the baseline", ""]
        moved = [d for d in drift if d.is_drift]
        lines.append("No drift beyond tolerances." if not moved else f"**{len(moved)} claim(s) moved:**")
        lines += [f"- {_md_escape(d.describe())}" for d in drift]
    lines += ["", "## Provenance", ""]
    lines += [f"- {k}: {v}" for k, v in provenance.items() if k != "notes"]
    lines += [f"- note: {n}" for n in notes]
    lines += ["", "## Run time per study", "", COUNTS_NOTE + ".", "",
              "| study | cases | results solved now / reused | methods | wall time |",
              "|---|---|---|---|---|"]
    for r in results:
        lines.append(f"| {r.name} | {len({x['case'] for x in r.rows})} | {r.computed} / {r.reused} | "
                     f"{', '.join(r.methods)} | {r.wall_time:.1f} s |")
    for r in results:
        lines += ["", f"## {r.title} ({cases_phrase(r)})", "", f"*Paper:* {r.claim}", ""]
        lines += [f"- *{m}* {_md_escape(why)}" for m, why in sorted(getattr(r, "skipped", {}).items())]
        for p in figures.get(r.name, []):
            if p.suffix == ".png":
                lines.append(f"![{p.stem}]({p.relative_to(outdir).as_posix()})")
        summ = r.extra.get("pairwise", [])
        if summ:
            lines += ["", "Cross-checks (each method against the case's reference):", "",
                      "| methods | quantity | cases | max abs diff | mean diff |", "|---|---|---|---|---|"]
            lines += [f"| {s['pair']} | {s['quantity']} | {s['n']} | {s['max_abs']:.3g} % "
                      f"| {s['mean']:.3g} % |" for s in summ]
        sbs = r.extra.get("side_by_side", [])
        if sbs:
            cols = [k for k in sbs[0] if k != "case"]
            lines += ["", "Cases solved by every method (bars):", "",
                      "| case | " + " | ".join(cols) + " |", "|---" * (len(cols) + 1) + "|"]
            lines += ["| " + s["case"] + " | " + " | ".join(f"{s[c]:.5g}" for c in cols) + " |" for s in sbs]
        if r.failures:
            lines += ["", f"{len(r.failures)} failed case(s):"]
            lines += [f"- {f['case']} ({f['method']}): {_md_escape(str(f['error']))[:200]}"
                      for f in r.failures[:20]]
    return "\n".join(lines) + "\n"


def _img(path: Path) -> str:
    data = base64.b64encode(path.read_bytes()).decode()
    return f'<img src="data:image/png;base64,{data}" alt="{html.escape(path.stem)}">'


CLAIMS_NOTE = ("Each figure is computed against the case's reference: of the methods that solved a case, the"
               " one of highest reference rank (named under 'judged against'). Its uncertainty is the "
               'reference solved again at refined settings where a study asks for it and the method offers '
               'them (a convergence estimate), else the spread between the methods that solved the same '
               'cases (conservative where the reference is the more accurate method). A claim is '
               "'inconclusive (within numerical error)' when our number lies within that uncertainty of the "
               "paper's bound.")

CSS = """
body { font-family: system-ui, sans-serif; max-width: 1250px; margin: 1em auto; padding: 0 1em; color: #222; }
table { border-collapse: collapse; margin: 0.6em 0; font-size: 0.86em; display: block; max-width: 100%;
        overflow-x: auto; }
td { overflow-wrap: break-word; }
th, td { border: 1px solid #bbb; padding: 3px 6px; vertical-align: top; }
th { background: #f0f0f0; }
img { max-width: 100%; display: block; margin: 0.5em 0; }
.small { font-size: 0.85em; color: #555; }
pre { white-space: pre-wrap; background: #f7f7f7; padding: 0.5em; font-size: 0.8em; }
"""


def html_page(results: Sequence[Any], provenance: dict, figures: dict[str, list[Path]],
              drift: Sequence[Any] | None = None, notes: Sequence[str] = (),
              docs: dict[str, str] | None = None) -> str:
    """Self-contained HTML page: every PNG embedded as base64."""
    e = html.escape
    out = ["<!DOCTYPE html><html><head><meta charset='utf-8'><title>coathertz verification report</title>",
           f"<style>{CSS}</style></head><body>", "<h1>coathertz verification report</h1>",
           f"<p class='small'>resolution <b>{e(str(provenance.get('resolution')))}</b>, "
           f"{e(str(provenance.get('date')))}, coathertz {e(str(provenance.get('version')))}, "
           f"commit {e(str(provenance.get('git_short', provenance.get('git_commit'))))}</p>",
           f"<p>{e(verdict_counts([row['verdict'] for row in claims_rows(results)]))}.</p>",
           # first screen: one line per study with its verdicts and a link to its section
           "<h2>Headline</h2><table class='headline'><tr><th>study</th><th>verdicts</th></tr>"
           + "".join(f"<tr><td><a href='#{e(r.name)}'>{e(r.title)}</a></td>"
                     f"<td>{e(verdict_counts([c.verdict for c in r.claims]))}</td></tr>" for r in results)
           + "</table>",
           f"<h2>Claims</h2><p class='small'>{e(CLAIMS_NOTE)}</p>"
           "<table class='claims'><tr><th>study</th><th>claim</th><th>ours</th><th>uncertainty</th>"
           "<th>paper</th>"
           "<th>verdict</th><th>judged against</th><th>detail</th></tr>"]
    for row in claims_rows(results):
        bg = VERDICT_STYLE.get(row["verdict"], "#fff")
        out.append(f"<tr><td>{e(row['study'])}</td><td>{e(row['claim'])}</td><td>{e(row['value'])}</td>"
                   f"<td>{e(row['uncertainty'])}</td><td>{e(row['bound'])}</td>"
                   f"<td style='background:{bg}'>{e(row['verdict'])}</td><td>{e(row['judged'])}</td>"
                   f"<td class='small'>{e(row['detail'])}</td></tr>")
    out.append("</table>")
    if drift is not None:
        moved = [d for d in drift if d.is_drift]
        out.append("<h2>Regression against the baseline</h2>")
        verdict = "No drift beyond tolerances." if not moved else f"<b>{len(moved)} claim(s) moved</b>"
        out.append(f"<p>{verdict}</p><ul>" + "".join(f"<li>{e(d.describe())}</li>" for d in drift) + "</ul>")
    out.append("<h2>Provenance</h2><table>")
    out += [f"<tr><th>{e(k)}</th><td>{e(str(v))}</td></tr>" for k, v in provenance.items()]
    out += [f"<tr><th>note</th><td>{e(n)}</td></tr>" for n in notes]
    out.append(f"</table><h2>Run time per study</h2><p class='small'>{e(COUNTS_NOTE)}.</p>"
               "<table><tr><th>study</th><th>cases</th>"
               "<th>results solved now / reused</th><th>methods</th><th>wall time</th>"
               "<th>solver time by method</th></tr>")
    for r in results:
        mt = ", ".join(f"{k}: {v:.1f} s" for k, v in sorted(r.method_time.items()))
        out.append(f"<tr><td>{e(r.name)}</td><td>{len({x['case'] for x in r.rows})}</td>"
                   f"<td>{r.computed} / {r.reused}</td><td>{e(', '.join(r.methods))}</td>"
                   f"<td>{r.wall_time:.1f} s</td><td>{e(mt)}</td></tr>")
    out.append("</table>")
    for r in results:
        out.append(f"<h2 id='{e(r.name)}'>{e(r.title)} ({e(cases_phrase(r))})</h2>"
                   f"<p><i>Paper:</i> {e(r.claim)}</p>")
        skipped = getattr(r, "skipped", {})
        if skipped:
            out.append("<ul class='small'>" + "".join(f"<li><b>{e(m)}</b> {e(why)}</li>"
                                                      for m, why in sorted(skipped.items())) + "</ul>")
        if docs and docs.get(r.name):
            out.append("<details><summary>What is run and compared</summary>"
                       f"<pre>{e(docs[r.name])}</pre></details>")
        for p in figures.get(r.name, []):
            if p.suffix == ".png":
                out.append(_img(p))
        summ = r.extra.get("pairwise", [])
        if summ:
            out.append("<p>Cross-checks: each method against the case's reference (difference in %; the "
                       "largest is the claims' numerical uncertainty):</p>"
                       "<table><tr><th>methods</th><th>quantity</th><th>cases</th><th>max |diff|</th>"
                       "<th>mean diff</th></tr>")
            out += [f"<tr><td>{e(s['pair'])}</td><td>{e(s['quantity'])}</td><td>{s['n']}</td>"
                    f"<td>{s['max_abs']:.3g} %</td><td>{s['mean']:.3g} %</td></tr>" for s in summ]
            out.append("</table>")
        sbs = r.extra.get("side_by_side", [])
        if sbs:
            cols = [k for k in sbs[0] if k != "case"]
            out.append("<p>Cases solved by every method (bars = ratios to the eq (7) normalisers):</p>"
                       "<table><tr><th>case</th>" + "".join(f"<th>{e(c)}</th>" for c in cols) + "</tr>")
            out += ["<tr><td>" + e(s["case"]) + "</td>" + "".join(f"<td>{s[c]:.5g}</td>" for c in cols)
                    + "</tr>" for s in sbs]
            out.append("</table>")
        if r.failures:
            out.append(f"<p>{len(r.failures)} failed case(s):</p><ul>")
            out += [f"<li>{e(f['case'])} ({e(f['method'])}): {e(str(f['error'])[:300])}</li>"
                    for f in r.failures[:30]]
            out.append("</ul>")
    out.append("</body></html>")
    return "\n".join(out)
