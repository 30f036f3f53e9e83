"""Figures rendered in forked processes (:func:`coathertz.figstyle.saving`): the same bytes as in
one process, SVG only on request, a failed render named, no render process left behind."""

from __future__ import annotations

import os

import pytest

from coathertz.errors import CoatHertzError
from coathertz.figstyle import figure, save, saving


def _draw(label: str):
    fig, axes = figure(2)
    for k, ax in enumerate(axes[0]):
        ax.plot([0, 1, 2], [k, 1 - k, 2 * k], label=label)
        ax.set_xlabel("x [m]")
        ax.set_title(label)
    return fig


def _no_children_left() -> bool:
    """No child process of this one, running or finished-but-not-collected."""
    try:
        os.waitpid(-1, os.WNOHANG)  # returns when a child exists (running or a zombie)
    except ChildProcessError:
        return True
    return False


def test_forked_renders_equal_serial_ones(tmp_path):
    serial = save(_draw("serial"), tmp_path / "one", "f")
    with saving(jobs=2):
        forked = [save(_draw("serial"), tmp_path / "two", f"f{i}")[0] for i in range(3)]
    assert [p.suffix for p in serial] == [".png"]
    for p in forked:
        assert p.read_bytes() == serial[0].read_bytes(), p
    assert _no_children_left()


def test_svg_only_on_request(tmp_path):
    with saving(("png", "svg"), jobs=2):
        paths = save(_draw("svg"), tmp_path, "g")
    assert [p.suffix for p in paths] == [".png", ".svg"]
    assert all(p.stat().st_size > 5000 for p in paths)
    assert paths[1].read_text().lstrip().startswith("<?xml")


def test_failed_render_is_named(tmp_path, capfd):
    fig = _draw("ok")
    fig.axes[0].set_title(r"$\frac{1}{$")  # mathtext that fails only when drawn
    with pytest.raises(CoatHertzError, match=r"could not render figure.*broken"):
        with saving(jobs=2):
            save(fig, tmp_path, "broken")
            save(_draw("fine"), tmp_path, "fine")
    assert (tmp_path / "fine.png").stat().st_size > 5000
    assert _no_children_left()


def test_bad_format_is_refused():
    with pytest.raises(CoatHertzError, match="png, svg"):
        with saving(("pdf",)):
            pass
