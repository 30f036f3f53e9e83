"""Figures rendered in forked processes (:func:`coathertz.figstyle.saving`): the same bytes as in
one process, SVG only on request, a failed render named, no render process left behind."""

from __future__ import annotations

import os
import time
from pathlib import Path

import pytest

from coathertz.errors import CoatHertzError
from coathertz.figstyle import figure, plain_power, save, saving


def _draw(label: str):
    fig, axes = figure(2)
    for k, ax in enumerate(axes[0]):
        ax.plot([0, 1, 2], [k, 1 - k, 2 * k], label=label)
        ax.set_xlabel("x [m]")
        ax.set_title(label)
    return fig


@pytest.fixture
def forks(monkeypatch):
    """The pids of the render processes forked during a test."""
    pids: list[int] = []
    real_fork = os.fork

    def fork():
        pid = real_fork()
        if pid:
            pids.append(pid)
        return pid

    monkeypatch.setattr(os, "fork", fork)
    return pids


def _all_collected(pids: list[int]) -> bool:
    """Every one of ``pids`` has exited and been waited for (none running, none a zombie)."""
    for pid in pids:
        try:
            os.waitpid(pid, os.WNOHANG)
        except ChildProcessError:
            continue
        return False
    return True


def test_forked_renders_equal_serial_ones(tmp_path, forks):
    serial = save(_draw("serial"), tmp_path / "one", "f")
    with saving(jobs=2):
        forked = [save(_draw("serial"), tmp_path / "two", f"f{i}")[0] for i in range(3)]
    assert [p.suffix for p in serial] == [".png"]
    for p in forked:
        assert p.read_bytes() == serial[0].read_bytes(), p
    assert len(forks) == 3 and _all_collected(forks)


@pytest.mark.parametrize("engine", ["tight", "constrained"])
def test_one_pass_png_equals_savefig(tmp_path, engine):
    """A figure with a layout engine is written from one drawing pass (``_write_png_drawn``):
    the same pixels as matplotlib's ``savefig`` at the same resolution, which draws it twice."""
    import numpy as np
    from PIL import Image

    from coathertz.figstyle import PNG_DPI

    def draw():
        fig = _draw("one pass")
        fig.set_layout_engine(engine)
        im = fig.axes[1].pcolormesh([[0.0, 1.0], [2.0, 3.0]])
        fig.colorbar(im, ax=fig.axes[1], label="error [%]")
        fig.suptitle("a long title that the figure wraps to its width " * 3, fontsize=10)
        return fig

    ours = save(draw(), tmp_path, "ours")[0]
    ref = draw()
    ref._suptitle.set_wrap(True)
    ref.savefig(tmp_path / "ref.png", dpi=PNG_DPI)
    with Image.open(ours) as a, Image.open(tmp_path / "ref.png") as b:
        assert a.mode == "RGB" and b.mode == "RGBA"  # opaque: written without the alpha channel
        assert a.info["dpi"] == pytest.approx(b.info["dpi"]) and a.info["Software"] == b.info["Software"]
        theirs = np.asarray(b)
        assert (theirs[..., 3] == 255).all()
        assert np.array_equal(np.asarray(a), theirs[..., :3])  # the same pixels


def test_svg_only_on_request(tmp_path):
    with saving(("png", "svg"), jobs=2):
        paths = save(_draw("svg"), tmp_path, "g")
    assert [p.suffix for p in paths] == [".png", ".svg"]
    assert all(p.stat().st_size > 5000 for p in paths)
    assert paths[1].read_text().lstrip().startswith("<?xml")


def test_failed_render_is_named(tmp_path, capfd, forks):
    fig = _draw("ok")
    fig.axes[0].set_title(r"$\frac{1}{$")  # mathtext that fails only when drawn
    with pytest.raises(CoatHertzError, match=r"could not render figure.*broken"):
        with saving(jobs=2):
            save(fig, tmp_path, "broken")
            save(_draw("fine"), tmp_path, "fine")
    assert (tmp_path / "fine.png").stat().st_size > 5000
    assert len(forks) == 2 and _all_collected(forks)


def test_bad_format_is_refused():
    with pytest.raises(CoatHertzError, match="png, svg"):
        with saving(("pdf",)):
            pass


class _Result:
    """The parts of a study result that plot_study reads."""

    def __init__(self, value: float):
        self.name, self.value, self.extra = "toy", value, {}

    def to_json(self) -> dict:
        return {"name": self.name, "value": self.value, "wall_time": time.perf_counter()}


class _Study:
    GENERIC_FIGURES = False

    @classmethod
    def plot(cls, result, outdir):
        with (Path(outdir) / "calls.txt").open("a") as fh:  # drawn in a render process: counted on disk
            fh.write("drawn\n")
        return save(_draw(f"value {result.value}"), outdir, "toy")


def _calls(folder) -> int:
    return len((folder / "calls.txt").read_text().splitlines())


def test_unchanged_figures_are_not_redrawn(tmp_path):
    from coathertz.report import plot_study

    for value, drawn in ((1.0, 1), (1.0, 1), (2.0, 2)):  # same numbers: kept; new numbers: redrawn
        with saving(jobs=2):
            paths = plot_study(_Result(value), _Study, tmp_path)
        assert _calls(tmp_path) == drawn and paths[0].stat().st_size > 5000
    paths[0].unlink()  # a figure gone from disk is drawn again
    with saving(jobs=2):
        plot_study(_Result(2.0), _Study, tmp_path)
    assert _calls(tmp_path) == 3 and paths[0].is_file()


def test_study_figures_are_built_in_the_render_process(tmp_path):
    """Within a saving block the study's figures are built and written by a render process: this
    process runs none of ``plot``, and learns the written paths when the block ends."""
    from coathertz.report import plot_study

    class Where(_Study):
        @classmethod
        def plot(cls, result, outdir):
            (Path(outdir) / "pid.txt").write_text(str(os.getpid()))
            return [*save(_draw("a"), outdir, "toy_a"), *save(_draw("b"), outdir, "toy_b")]

    with saving(jobs=2):
        paths = plot_study(_Result(3.0), Where, tmp_path)
        assert paths == [] or len(paths) == 2  # filled when its process ends
    assert [p.name for p in paths] == ["toy_a.png", "toy_b.png"]
    assert all(p.stat().st_size > 5000 for p in paths)
    assert int((tmp_path / "pid.txt").read_text()) != os.getpid()


def test_failed_render_leaves_no_record(tmp_path, capfd):
    from coathertz.report import FIGURE_KEYS, plot_study

    class Broken(_Study):
        @classmethod
        def plot(cls, result, outdir):
            fig = _draw("x")
            fig.axes[0].set_title(r"$\frac{1}{$")
            return save(fig, outdir, "toy")

    with pytest.raises(CoatHertzError), saving(jobs=2):
        plot_study(_Result(5.0), Broken, tmp_path)
    assert "toy" not in (tmp_path / FIGURE_KEYS).read_text()
    assert "coathertz: figure toy: ValueError" in capfd.readouterr().err  # the figure, not the study


def test_tight_layout_measures_each_panel_once(tmp_path, monkeypatch):
    """The engine :func:`~coathertz.figstyle.save` lays a tight figure out with gives matplotlib's
    tight layout's subplot parameters exactly, measuring each panel once instead of twice."""
    from matplotlib.axes import Axes

    from coathertz.figstyle import _tight_once

    calls = []
    real = Axes.get_tightbbox

    def counted(self, *args, **kwargs):
        calls.append(self)
        return real(self, *args, **kwargs)

    monkeypatch.setattr(Axes, "get_tightbbox", counted)
    params = []
    for once in (False, True):
        fig = _draw("layout")
        fig.axes[0].set_yscale("log")
        fig.axes[0].set_ylim(1e-3, 10)
        fig.suptitle("a title", fontsize=10)
        fig.set_layout_engine("tight", pad=0.5)
        if once:
            _tight_once(fig)
        calls.clear()
        fig.get_layout_engine().execute(fig)
        sp = fig.subplotpars
        params.append(((sp.left, sp.right, sp.bottom, sp.top, sp.wspace, sp.hspace), len(calls)))
        assert fig.get_layout_engine().get()["pad"] == 0.5
    (theirs, n_theirs), (ours, n_ours) = params
    assert ours == theirs  # exactly: the same boxes, the same arithmetic
    assert (n_theirs, n_ours) == (4, 2)
    assert "get_tightbbox" not in vars(fig.axes[0])  # the panels are left as they were


@pytest.mark.parametrize(("math", "plain"), [
    (r"$\mathdefault{10^{-1}}$", "10⁻¹"),
    (r"$\mathdefault{10^{12}}$", "10¹²"),
    (r"$\mathdefault{-10^{0}}$", "\N{MINUS SIGN}10⁰"),
    (r"$\mathdefault{0}$", "0"),
    (r"$\mathdefault{2\times10^{-3}}$", "2×10⁻³"),
    (r"$\alpha_\delta$", r"$\alpha_\delta$"),  # not a tick label of a log axis: unchanged
    ("", ""),
])
def test_plain_power_labels(math, plain):
    from coathertz.figstyle import plain_power

    assert plain_power(math) == plain


def test_log_axes_are_labelled_in_plain_text(tmp_path):
    """A saved figure's log and symmetric-log axes label the same ticks as matplotlib's default,
    in plain text (no mathtext)."""
    fig = _draw("log")
    fig.axes[0].set_yscale("log")
    fig.axes[0].set_ylim(1e-3, 10)
    fig.axes[1].set_yscale("symlog", linthresh=0.1)
    fig.axes[1].set_ylim(-10, 10)
    fig.set_layout_engine("tight")
    save(fig, tmp_path, "log")
    for ax, want in zip(fig.axes, (["10⁻³", "10⁻²", "10⁻¹", "10⁰", "10¹"],
                                   ["\N{MINUS SIGN}10¹", "\N{MINUS SIGN}10⁰", "\N{MINUS SIGN}10⁻¹",
                                    "0", "10⁻¹", "10⁰", "10¹"]), strict=True):
        got = [t.get_text() for t in ax.get_yticklabels() if ax.get_ylim()[0] <= t.get_position()[1]
               <= ax.get_ylim()[1]]
        assert got == want, got


def test_log_axes_make_only_the_ticks_in_view(tmp_path):
    """A saved figure's log axes draw the same ticks as matplotlib's default locator, having made
    Tick objects for those in view only (not for the decades beyond both ends)."""
    drawn, made = [], []
    for ours in (False, True):
        fig = _draw("log")
        fig.axes[0].set_xscale("log")
        fig.axes[0].set_xlim(0.013, 3.1)
        fig.set_layout_engine("tight")
        if ours:
            save(fig, tmp_path, "log")
        else:
            fig.canvas.draw()
        axis = fig.axes[0].xaxis
        drawn.append([(t.get_loc(), t.label1.get_text()) for t in axis._update_ticks()])
        made.append(len(axis.majorTicks) + len(axis.minorTicks))
    assert drawn[1] == [(loc, plain_power(s)) for loc, s in drawn[0]]
    # 0.1 and 1; 0.02-0.09, 0.2-0.9, 2 and 3
    assert len(drawn[0]) == 20 and made[0] > 20 and made[1] == 20, (drawn, made)


def _rich(label: str, engine: bool = True):
    """A figure with what the render process's caches keep: text of several sizes and fonts,
    mathtext, log ticks (many: ticks copied from the first), ticks changed after they were made,
    markers (plain, open, rotated), a colour bar, a legend; without ``engine`` a third panel
    sharing the first's y-axis and no layout engine (cropped: two drawing passes)."""
    from matplotlib.markers import MarkerStyle

    fig, axes = figure(2 if engine else 3, sharey=not engine)
    ax0, ax1 = axes[0][:2]
    if not engine:
        ax2 = axes[0][2]
        ax2.plot([0.5, 2.0, 7.0], [1.0, 3.0, 2.0], "s-", ms=3, label="shared")
        ax2.get_xticklabels()  # ticks made before the parameters change
        ax2.tick_params(axis="x", labelrotation=40, labelsize=6, direction="in", length=6)
        ax2.set_xlabel("t [s]")
    x = [1e-2, 1e-1, 1.0, 10.0]
    ax0.plot(x, [1.0, 2.0, 4.0, 3.0], "o", mfc="none", ms=7, label=r"$\delta/\delta_{0s}$")
    ax0.plot(x, [2.0, 1.0, 3.0, 5.0], marker=MarkerStyle("^").rotated(deg=30), ls="none", label="rotated")
    ax0.set_xscale("log")
    ax0.set_xlabel(r"$H = h/a_{0s}$")
    ax0.set_ylabel("p [MPa]", fontsize=7)
    ax0.legend(fontsize=7, title=label, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    im = ax1.pcolormesh([[0.0, 1.0], [2.0, 3.0]])
    fig.colorbar(im, ax=ax1, label="error [%]")
    ax1.set_title(label, fontsize=9, fontweight="bold")
    if engine:
        # wrapped: by bisection (plain text), word by word (with mathtext)
        math = r"with $\nu_s = 0.3$ in it" if label == "second" else ""
        fig.suptitle(f"{label}: a title that wraps " * 4 + math, fontsize=10)
        fig.set_layout_engine("tight")
    else:
        fig.suptitle(f"{label}: cropped", fontsize=10)
    return fig


def test_render_process_caches_keep_the_pixels(tmp_path):
    """Figures built and written in one render process (whose text and marker caches serve all
    of them, :func:`~coathertz.figstyle._render_process_caches`) are byte-for-byte those written
    here without the caches."""
    from coathertz.figstyle import draw_elsewhere

    # the third repeats the first's strings: cache hits; the fourth has no layout engine
    labels = [("first", True), ("second", True), ("first", True), ("first", False)]
    serial = [save(_rich(*s), tmp_path / "one", f"f{i}")[0] for i, s in enumerate(labels)]
    with saving(jobs=2):
        forked = draw_elsewhere("rich", lambda: [save(_rich(*s), tmp_path / "two", f"f{i}")[0]
                                                 for i, s in enumerate(labels)])
    assert [p.name for p in forked] == [p.name for p in serial]
    for a, b in zip(serial, forked, strict=True):
        assert a.read_bytes() == b.read_bytes(), b


def test_render_caches_only_on_checked_matplotlib():
    """The caches replace private parts of matplotlib: used only on the releases the pixel test
    above was run on, any patch level; another release draws with matplotlib as it is."""
    from coathertz.figstyle import CACHED_MATPLOTLIB, caches_apply

    for release in CACHED_MATPLOTLIB:
        assert caches_apply(release + ".0") and caches_apply(release + ".7rc1")
    assert not caches_apply("3.7.5")
    assert not caches_apply("99.0.0")
