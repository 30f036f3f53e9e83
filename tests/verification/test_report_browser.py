"""the HTML report in a real browser (headless Chromium from the system packages).

Every image decodes, nothing overflows the page horizontally, no console error or failed
resource; a screenshot is kept in the test's tmp_path. Runs where ``chromium`` (or
``chromium-browser`` / ``google-chrome``) is installed, e.g. ``apt-get install chromium``;
skips with that reason otherwise.
"""

from __future__ import annotations

import json
import re
import shutil
import subprocess
from pathlib import Path

import pytest

BROWSER = next((b for b in ("chromium", "chromium-browser", "google-chrome") if shutil.which(b)), None)
pytestmark = [pytest.mark.browser,
              pytest.mark.skipif(BROWSER is None, reason="no headless Chromium installed "
                                 "(apt-get install chromium) to test the HTML report in")]
PUBLISHED = Path(__file__).resolve().parents[2] / "reports" / "published" / "quick" / "index.html"
WIDTH = 1100

#: Injected first in <head>: records script errors, failed resources and console.error calls.
PROBE_HEAD = """<script>window.__errs = [];
window.addEventListener('error', e => window.__errs.push(String(e.message || (e.target && (e.target.src ||
  e.target.href)) || 'error')), true);
const __ce = console.error; console.error = (...a) => { window.__errs.push('console.error: ' + a.join(' '));
  __ce(...a); };</script>"""
#: Injected last in <body>: after load, writes what it found into <pre id="__check">.
PROBE_BODY = """<script>window.addEventListener('load', () => {
  const imgs = [...document.images];
  const bad = imgs.filter(i => !(i.complete && i.naturalWidth > 0)).map(i => i.alt);
  const vw = document.documentElement.clientWidth;
  const wide = [...document.querySelectorAll('body *')].filter(el => {
    const r = el.getBoundingClientRect();
    let p = el.parentElement;  // inside a horizontally scrolling box is fine
    while (p && p !== document.body) { if (getComputedStyle(p).overflowX === 'auto') return false;
      p = p.parentElement; }
    return r.right > vw + 1; }).map(el => el.tagName + (el.id ? '#' + el.id : '')).slice(0, 10);
  const pre = document.createElement('pre'); pre.id = '__check';
  pre.textContent = JSON.stringify({images: imgs.length, bad, wide, errs: window.__errs,
    scroll: document.documentElement.scrollWidth, vw});
  document.body.appendChild(pre); });</script>"""


def _chromium(*args: str, timeout: float = 120) -> subprocess.CompletedProcess:
    cmd = [BROWSER, "--headless", "--no-sandbox", "--disable-gpu", "--hide-scrollbars",
           "--virtual-time-budget=10000", f"--window-size={WIDTH},1000", *args]
    return subprocess.run(cmd, capture_output=True, text=True, timeout=timeout, check=False)


def check_page(html: Path, shots: Path) -> dict:
    """Open ``html`` (with the probes injected into a copy) and return what the probes found; keep a
    screenshot of the original page in ``shots``."""
    text = html.read_text()
    probed = shots / f"{html.parent.name}_probed.html"
    probed.write_text(text.replace("<head>", "<head>" + PROBE_HEAD, 1)
                      .replace("</body>", PROBE_BODY + "</body>"))
    dom = _chromium("--dump-dom", probed.as_uri())
    m = re.search(r'<pre id="__check">(.*?)</pre>', dom.stdout, re.S)
    assert m, f"no probe output; chromium stderr: {dom.stderr[-2000:]}"
    found = json.loads(m.group(1).replace("&quot;", '"').replace("&amp;", "&").replace("&lt;", "<")
                       .replace("&gt;", ">"))
    shot = shots / f"{html.parent.name}.png"
    _chromium(f"--screenshot={shot}", html.as_uri())
    found["screenshot"] = shot
    return found


def _assert_clean(found: dict) -> None:
    assert found["images"] >= 3, found
    assert not found["bad"], f"images that did not load: {found['bad']}"
    assert not found["errs"], f"console errors / failed resources: {found['errs']}"
    assert found["scroll"] <= found["vw"] + 1, f"page overflows horizontally: {found}"
    assert not found["wide"], f"elements overflow the page: {found['wide']}"
    assert found["screenshot"].stat().st_size > 10_000


def test_fresh_report_in_browser(tmp_path):
    from coathertz.cli import main

    out = tmp_path / "fresh"
    assert main(["verify", "--tiny", "--study", "fig3", "--study", "section6", "--method",
                 "closed-form", "--method", "fft", "--no-progress", "--workers", "1", "--out", str(out)]) == 0
    _assert_clean(check_page(out / "index.html", tmp_path))


@pytest.mark.skipif(not PUBLISHED.exists(), reason="no published report in this checkout")
def test_published_report_in_browser(tmp_path):
    _assert_clean(check_page(PUBLISHED, tmp_path))
