"""``coathertz verify`` end to end at the tiny resolution: report files, baseline regression."""

from __future__ import annotations

import json

import pytest

from coathertz.cli import main
from coathertz.report.baseline import compare

ARGS = ["verify", "--tiny", "--study", "fig3", "--study", "section6", "--method", "closed-form",
        "--method", "fft", "--no-progress", "--workers", "1"]


@pytest.fixture(scope="module")
def report(tmp_path_factory):
    out = tmp_path_factory.mktemp("report")
    assert main([*ARGS, "--out", str(out)]) == 0
    return out


def test_report_files(report):
    html = (report / "index.html").read_text()
    md = (report / "summary.md").read_text()
    assert html.index("<h2>Headline</h2>") < html.index("<h2>Claims</h2>") < html.index("<h2>Provenance</h2>")
    # the first screen links every study's section
    assert "<a href='#fig3'>" in html and "<h2 id='fig3'>" in html
    assert html.count("data:image/png;base64,") >= 3  # self-contained
    assert "src=\"figures/" not in html
    assert md.splitlines()[0].startswith("# coathertz verification report")
    assert md.index("## Claims") < md.index("## Provenance")
    for key in ("version", "git_commit", "date", "resolution: tiny", "machine", "total_run_time"):
        assert key in md
    for name in ("fig3.png", "fig3_errmap_fft.png", "section6.png"):
        assert (report / "figures" / name).stat().st_size > 5000
    assert not (report / "figures" / "fig3_pairwise.png").exists()  # one numerical method: no cross-check
    results = json.loads((report / "results.json").read_text())
    assert [s["name"] for s in results["studies"]] == ["fig3", "section6"]
    assert (report / "rows" / "fig3.csv").read_text().startswith("case,")
    assert (report / "store.csv").exists() and (report / "store.sqlite").exists()


def test_rerun_reuses_and_matches_baseline(report, capsys):
    assert main([*ARGS, "--out", str(report), "--baseline", str(report / "baseline.json")]) == 0
    out = capsys.readouterr().out
    assert "no drift" in out
    assert "(0 solved now" in out  # everything reused from the store


def test_drift_beyond_tolerance_exits_nonzero(report, tmp_path, capsys):
    base = json.loads((report / "baseline.json").read_text())
    base["claims"]["fig3-max-err"]["value"] += 1.0
    path = tmp_path / "moved.json"
    path.write_text(json.dumps(base))
    assert main([*ARGS, "--out", str(tmp_path / "r"), "--store", str(report / "store.sqlite"),
                 "--baseline", str(path)]) == 1
    out = capsys.readouterr().out
    assert "fig3-max-err" in out and "moved" in out
    assert "Regression against the baseline" in (tmp_path / "r" / "summary.md").read_text()


def test_compare_kinds():
    def b(claims):
        return {"studies": {"s": "quick"}, "claims": {k: {"study": "s", "value": v, "tol": 0.1, "holds": h,
                                                          "text": k} for k, (v, h) in claims.items()}}
    old = b({"a": (1.0, True), "b": (2.0, True), "c": ("nan", None), "gone": (1.0, True)})
    new = b({"a": (1.05, True), "b": (2.0, False), "c": ("nan", None), "fresh": (3.0, None)})
    kinds = {d.claim: d.kind for d in compare(old, new)}
    assert kinds == {"b": "verdict", "gone": "missing", "fresh": "new"}
    new["claims"]["a"]["value"] = 1.2
    assert {d.claim: d.kind for d in compare(old, new)}["a"] == "moved"


def test_bad_arguments(tmp_path):
    out = tmp_path / "never"
    assert main(["verify", "--study", "nope", "--out", str(out)]) == 2
    assert main(["verify", "--method", "nope", "--study", "fig3", "--out", str(out)]) == 2
    assert main(["verify", "--workers", "0", "--out", str(out)]) == 2
    assert not out.exists()  # nothing written for bad input


def test_list(capsys):
    assert main(["verify", "--list"]) == 0
    out = capsys.readouterr().out
    assert "study  fig3" in out and "method fft" in out


def test_cli_interrupted_midway_then_resumed(tmp_path):
    """SIGINT to a running ``coathertz verify``: exit 130, finished results kept; the rerun reuses
    exactly those and computes the rest."""
    import signal
    import subprocess
    import sys
    import time

    from coathertz.store import ResultStore
    from coathertz.verification import get_study

    out = tmp_path / "r"
    args = ["verify", "--quick", "--study", "fig3", "--method", "closed-form", "--method", "fft",
            "--no-progress", "--workers", "2", "--out", str(out)]
    # Ctrl-C's default action in the child whatever the launcher left: a suite started in the
    # background by a non-interactive shell (``bash .ci/run &``) ignores SIGINT, and a Python
    # started with SIGINT ignored keeps ignoring it (this test then failed with exit status 0)
    proc = subprocess.Popen([sys.executable, "-m", "coathertz.cli", *args],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                            preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))
    db = out / "store.sqlite"
    n_cf = len(get_study("fig3").cases("quick"))
    try:
        deadline = time.time() + 90
        while time.time() < deadline and proc.poll() is None:
            if db.exists():
                with ResultStore(db) as st:
                    if st.count(method="fft") >= 16:
                        break
            time.sleep(0.02)
        proc.send_signal(signal.SIGINT)
        _, err = proc.communicate(timeout=60)
    finally:
        if proc.poll() is None:
            proc.kill()
    assert proc.returncode == 130, err
    assert "run the same command again to resume" in err
    with ResultStore(db) as st:
        done = st.count()
    assert n_cf + 16 <= done < 2 * n_cf
    # rerun in a fresh process too (the store key holds the code version, computed per process)
    rerun = subprocess.run([sys.executable, "-m", "coathertz.cli", *args], capture_output=True, text=True,
                           timeout=120, check=True)
    line = next(x for x in rerun.stdout.splitlines() if x.startswith("fig3"))
    n_refine = sum(sc.refine for sc in get_study("fig3").cases("quick"))  # FFT at 2n, solved after the rest
    assert f"({2 * n_cf - done + n_refine} solved now, {done} reused from the store)" in line


def test_verdict_counts_agree_in_number_and_cover_every_class():
    from coathertz.report.document import verdict_counts

    v = ["holds", "does not hold", "inconclusive (within numerical error)", "observed", "observed", "n/a"]
    text = verdict_counts(v)
    assert text == ("1 holds, 1 does not hold, 1 is inconclusive (within numerical error), 2 observations, "
                    "1 could not be computed (6 claims)")
    assert verdict_counts(["holds"] * 2 + ["does not hold"] * 18) == "2 hold, 18 do not hold (20 claims)"


def test_a_verdict_that_becomes_inconclusive_is_drift():
    def b(verdict, holds):
        claim = {"study": "s", "value": 1.0, "tol": 0.1, "holds": holds, "verdict": verdict, "text": "c"}
        return {"studies": {"s": "quick"}, "claims": {"c": claim}}
    drift = compare(b("does not hold", False), b("inconclusive (within numerical error)", False))
    assert [d.kind for d in drift] == ["verdict"]
    assert "does not hold -> inconclusive" in drift[0].describe()
