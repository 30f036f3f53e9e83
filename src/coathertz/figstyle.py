"""Plot helpers shared by the studies' figures and the report's: figure creation, saving,
colours, series, and each method's marker and legend label (from the method registry).

This module sits below both :mod:`coathertz.verification` and :mod:`coathertz.report` (it imports
neither), so the report can import the study framework at module level without a cycle.
The rules these helpers serve are in ``docs/style-figures.md``.
"""

from __future__ import annotations

import contextlib
import functools
import gc
import math
import os
import re
import signal
import sys
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

__all__ = ["DEFAULT_FORMATS", "active_formats", "after_renders", "colour", "draw_elsewhere", "figure",
           "method_handles", "method_style", "save", "saving", "series"]


#: The formats :func:`save` writes unless a :func:`~coathertz.figstyle.saving` block says
#: otherwise. PNG is what the report embeds; SVG (vector copies for papers) is opt-in
#: (``coathertz verify --svg``): it costs as much again as the PNG.
DEFAULT_FORMATS: tuple[str, ...] = ("png",)

#: Resolution of the PNG figures [dots per inch].
PNG_DPI = 150


@dataclass
class _Saving:
    """State of a :func:`~coathertz.figstyle.saving` block: the formats and the running render processes."""

    formats: tuple[str, ...]
    jobs: int
    running: dict[int, str] = field(default_factory=dict)  # pid -> figure name
    failed: list[str] = field(default_factory=list)
    after: list = field(default_factory=list)  # callables to run once every render succeeded
    # pid -> (read end of the pipe the process writes its files' paths to, the list to fill)
    written: dict[int, tuple[int, list[Path]]] = field(default_factory=dict)

    def reap(self, block: bool) -> None:
        """Collect this block's finished render processes; with ``block``, wait for the oldest.
        (Only its own children are waited for: a worker pool of the caller is left alone.)"""
        for pid in list(self.running):
            if block and pid in self.written:  # its paths first: it cannot end while the pipe is full
                self._read_paths(pid)
            done, status = os.waitpid(pid, 0 if block else os.WNOHANG)
            if done == 0:
                continue
            name = self.running.pop(pid)
            if pid in self.written:
                self._read_paths(pid)
            if os.waitstatus_to_exitcode(status) != 0:
                self.failed.append(name)
            if block:
                return

    def _read_paths(self, pid: int) -> None:
        """Read to its end the pipe of a :func:`draw_elsewhere` process (one path a line) into
        its list, and close it."""
        fd, paths = self.written.pop(pid)
        with os.fdopen(fd, "rb") as fh:
            paths.extend(Path(line) for line in fh.read().decode().splitlines() if line)

    def stop(self) -> None:
        """Kill and collect every render process still running (the block is being left early)."""
        for pid in self.running:
            with contextlib.suppress(ProcessLookupError):
                os.kill(pid, signal.SIGKILL)
        for pid in list(self.running):
            with contextlib.suppress(ChildProcessError):
                os.waitpid(pid, 0)
        for fd, _ in self.written.values():
            os.close(fd)
        self.written.clear()
        self.running.clear()

    def fork(self, name: str, work: Callable[[], None]) -> int | None:
        """Fork a render process named ``name`` that runs ``work()`` and leaves without any
        cleanup (exit status 1, with one line naming ``name`` and the error, if it raised);
        first wait while ``jobs + QUEUED_RENDERS`` are running. Returns the child's pid in this
        process; never returns in the child."""
        while len(self.running) >= self.jobs + QUEUED_RENDERS:
            self.reap(block=True)
        sys.stdout.flush()
        sys.stderr.flush()
        pid = os.fork()
        if pid == 0:
            code = 1
            try:
                global _WRITING
                _WRITING = None
                gc.disable()  # short-lived: a collection would only copy the parent's pages (fork)
                signal.signal(signal.SIGINT, signal.SIG_DFL)
                _render_process_caches()
                work()
                code = 0
            except BaseException as exc:  # one line, the parent names the figure again and raises
                name = _WRITING or name  # the figure being written, in a study's render process
                print(f"coathertz: figure {name}: {type(exc).__name__}: {exc}", file=sys.stderr, flush=True)
            finally:
                os._exit(code)
        self.running[pid] = name
        return pid


_SAVING: _Saving | None = None
_WRITING: str | None = None  # the figure :func:`save` is writing in this process (for its error line)
#: A token of the drawing pass :func:`_write` is in (None outside one): within a pass nothing but
#: matplotlib's drawing runs, so what it computes twice from equal inputs may be kept.
_DRAWING: object | None = None

#: Render processes allowed beyond ``jobs`` before :func:`save` waits for one: the caller goes on
#: with its next study or figure while the operating system shares the CPUs between them.
QUEUED_RENDERS = 2


def _cpus() -> int:
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:  # pragma: no cover - not Linux
        return os.cpu_count() or 1


@contextlib.contextmanager
def saving(formats: Sequence[str] = DEFAULT_FORMATS, jobs: int | None = None):
    """Within this block :func:`save` writes ``formats`` and renders each figure in a forked
    process, up to ``jobs + QUEUED_RENDERS`` at once (``jobs`` default: the CPUs this process may
    use), while the caller goes on with its work. Leaving the block waits for every render; a
    render that failed raises :class:`~coathertz.errors.CoatHertzError` naming the figure.
    Where ``os.fork`` does not exist or ``jobs == 1``, figures are rendered in this process."""
    global _SAVING
    from coathertz.errors import CoatHertzError

    bad = [f for f in formats if f not in ("png", "svg")]
    if bad or not formats:
        raise CoatHertzError(f"figure formats must be among png, svg; got {list(formats)}")
    jobs = _cpus() if jobs is None else max(1, int(jobs))
    if not hasattr(os, "fork"):  # pragma: no cover - not POSIX
        jobs = 1
    outer, _SAVING = _SAVING, _Saving(tuple(formats), jobs)
    state = _SAVING
    try:
        yield state
        while state.running:
            state.reap(block=True)
    except BaseException:
        state.stop()
        raise
    finally:
        _SAVING = outer
    if state.failed:
        raise CoatHertzError(f"could not render figure(s) {', '.join(sorted(state.failed))} "
                             "(the reason is printed above)")
    for fn in state.after:
        fn()


def after_renders(fn) -> None:
    """Call ``fn()`` once every figure saved so far is on disk: at the end of the enclosing
    :func:`~coathertz.figstyle.saving` block if all its renders succeeded (never otherwise), or
    now outside one."""
    if _SAVING is None:
        fn()
    else:
        _SAVING.after.append(fn)


def active_formats() -> tuple[str, ...]:
    """The formats :func:`save` writes here and now (those of the enclosing
    :func:`~coathertz.figstyle.saving` block)."""
    return _SAVING.formats if _SAVING is not None else DEFAULT_FORMATS


def _write(fig, paths: Sequence[Path]) -> None:
    """Write ``fig`` to ``paths``. A figure with a layout engine is laid out as it is drawn, with
    its title wrapped to its width, and written as laid out; one without is cropped to its
    drawn content (``bbox_inches="tight"``, a second drawing pass)."""
    import matplotlib
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    engine = fig.get_layout_engine() is not None
    _prepare(fig)
    title = getattr(fig, "_suptitle", None)  # matplotlib keeps the suptitle's Text here
    if engine and title is not None:
        title.set_wrap(True)
    global _DRAWING
    try:
        with matplotlib.rc_context({"svg.hashsalt": "coathertz"}):
            for p in paths:
                _DRAWING = object()  # a new drawing pass (no code of ours runs until it ends)
                svg = p.suffix == ".svg"
                if engine and not svg and isinstance(fig.canvas, FigureCanvasAgg):
                    _write_png_drawn(fig, p)
                    continue
                fig.savefig(p, dpi=None if svg else PNG_DPI, bbox_inches=None if engine else "tight",
                            metadata={"Date": None} if svg else None)
    finally:
        _DRAWING = None


_SUPERSCRIPT = str.maketrans("0123456789-", "⁰¹²³⁴⁵⁶⁷⁸⁹⁻")
_MATH_POWER = re.compile(r"(\d+)\^\{(-?\d+)\}")


def plain_power(label: str) -> str:
    r"""A log axis' mathtext tick label (``$\mathdefault{-2\times10^{-3}}$``) as plain text with
    unicode superscripts and signs (``−2×10⁻³``); any other label unchanged.

    Matplotlib parses every mathtext label when it is first drawn (about 12 ms of CPU a string),
    and each figure is drawn in its own process, so the log axes' decade labels cost tenths of a
    second a figure; plain text draws the same number without the parser."""
    if not (label.startswith("$\\mathdefault{") and label.endswith("}$")):
        return label
    inner = label[len("$\\mathdefault{"):-2].replace("\\times", "×")
    inner = _MATH_POWER.sub(lambda m: m[1] + m[2].translate(_SUPERSCRIPT), inner)
    if any(c in inner for c in "\\^{}$"):
        return label
    return inner.replace("-", "\N{MINUS SIGN}", 1) if inner.startswith("-") else inner


def _plain_log_labels(fig) -> None:
    """Let every log (and symmetric-log) axis of ``fig`` that labels its ticks with matplotlib's
    mathtext powers write them as plain text (:func:`plain_power`); same numbers, same places."""
    from matplotlib.ticker import LogFormatterSciNotation

    for ax in fig.axes:
        for axis in (ax.xaxis, ax.yaxis):
            for fmt in (axis.get_major_formatter(), axis.get_minor_formatter()):
                if type(fmt) is LogFormatterSciNotation:  # the default of log and symlog axes
                    fmt.__class__ = _plain_log_formatter_class()  # keeps its settings


@functools.cache
def _plain_log_formatter_class():
    from matplotlib.ticker import LogFormatterSciNotation

    class PlainLogFormatter(LogFormatterSciNotation):
        """:class:`~matplotlib.ticker.LogFormatterSciNotation` writing plain text
        (:func:`plain_power`)."""

        def __call__(self, x, pos=None) -> str:
            return plain_power(super().__call__(x, pos))

    return PlainLogFormatter


def _log_ticks_in_view(fig) -> None:
    """Let every log axis of ``fig`` with matplotlib's ``LogLocator`` return only the ticks in
    its view: matplotlib makes a tick (two marks, a grid line, two labels) for every location its
    locator returns, whole decades beyond both ends included (a third of the minor ticks of the
    report's log axes), and then draws only those in view. The ticks drawn are the same."""
    from matplotlib.ticker import LogLocator

    for ax in fig.axes:
        for axis in (ax.xaxis, ax.yaxis):
            for loc in (axis.get_major_locator(), axis.get_minor_locator()):
                if type(loc) is LogLocator:
                    loc.__class__ = _in_view_log_locator_class()  # keeps its settings


@functools.cache
def _in_view_log_locator_class():
    from matplotlib.ticker import LogLocator

    class InViewLogLocator(LogLocator):
        """:class:`~matplotlib.ticker.LogLocator` leaving out the ticks beyond its axis' view
        (see :func:`_log_ticks_in_view`)."""

        def __call__(self):
            locs = super().__call__()
            axis = self.axis
            if axis is None or len(locs) == 0:
                return locs
            # the axis keeps ticks within 1e-10 of the view's span (in the scale's coordinates);
            # a wider margin keeps a superset, so the same ticks are drawn
            lo, hi = sorted(axis.get_transform().transform(axis.get_view_interval()))
            with np.errstate(all="ignore"):
                t = axis.get_transform().transform(np.asarray(locs, dtype=float))
            margin = 1e-6 * (hi - lo)
            keep = (t >= lo - margin) & (t <= hi + margin)
            return np.asarray(locs)[keep] if np.isfinite(t).all() else locs

    return InViewLogLocator


def _tight_once(fig) -> None:
    """Give a figure laid out by matplotlib's tight layout engine an equal engine that measures
    each panel once per layout instead of twice.

    Matplotlib's tight layout (``rect`` given, as it always is for the engine) runs its subplot
    adjustment twice, and each run measures every panel's tight bounding box (ticks, tick labels,
    axis labels: most of the layout's cost). Nothing moves between the two runs (the subplot
    parameters are applied only after the second), so the second run's boxes equal the first's;
    this engine keeps them for the second run. The subplot parameters, hence the pixels, are
    those of ``TightLayoutEngine``."""
    from matplotlib.layout_engine import TightLayoutEngine

    engine = fig.get_layout_engine()
    if type(engine) is TightLayoutEngine:
        fig.set_layout_engine(_tight_once_engine_class()(**engine.get()))


@functools.cache
def _tight_once_engine_class():
    from matplotlib.layout_engine import TightLayoutEngine

    class TightOnceEngine(TightLayoutEngine):
        """:class:`~matplotlib.layout_engine.TightLayoutEngine` measuring each panel once per
        layout (see :func:`_tight_once`)."""

        def execute(self, fig) -> None:
            patched = []
            for ax in fig.axes:
                if "get_tightbbox" in vars(ax):
                    continue
                measured: dict = {}

                def get_tightbbox(renderer=None, *args, _ax=ax, _measured=measured, **kwargs):
                    if args or set(kwargs) - {"for_layout_only"}:
                        return type(_ax).get_tightbbox(_ax, renderer, *args, **kwargs)
                    key = (id(renderer), bool(kwargs.get("for_layout_only")))
                    if key not in _measured:
                        _measured[key] = type(_ax).get_tightbbox(_ax, renderer, **kwargs)
                    return _measured[key]

                ax.get_tightbbox = get_tightbbox
                patched.append(ax)
            try:
                super().execute(fig)
            finally:
                for ax in patched:
                    del ax.get_tightbbox

    return TightOnceEngine


def _prepare(fig) -> None:
    """Make ``fig`` cheaper to draw, its pixels read the same: one measurement per panel in the
    tight layout (:func:`_tight_once`), plain-text log tick labels (:func:`_plain_log_labels`),
    log ticks made only in view (:func:`_log_ticks_in_view`)."""
    _tight_once(fig)
    _plain_log_labels(fig)
    _log_ticks_in_view(fig)


#: The matplotlib releases (major.minor) on which the render processes' caches
#: (:func:`_render_process_caches`) were checked to leave every pixel as it was
#: (``tests/verification/test_figure_saving.py``). They replace private parts of matplotlib
#: (its text layout and tick making): on any other release the render processes
#: draw with matplotlib as it is, slower but safe. Add a release here only after that test
#: passed on it.
CACHED_MATPLOTLIB = ("3.11",)


def caches_apply(version: str) -> bool:
    """Whether the render processes' caches are used with matplotlib ``version`` (a release of
    :data:`CACHED_MATPLOTLIB`, any patch level)."""
    return ".".join(version.split(".")[:2]) in CACHED_MATPLOTLIB


def _render_process_caches() -> None:
    """In a render process (a process of ours alone, which only draws figures and exits), let
    matplotlib keep what it measures of text and markers for every figure instead of measuring
    it again; the pixels are the same (``tests/verification/test_figure_saving.py``).

    1. The height metrics of a font (the ascent, descent and line gap every text line is laid
       out with: a font look-up and two font tables read for every text drawn or measured) are
       kept per font properties and resolution: the Agg renderer gets the method
       ``_get_font_height_metrics`` matplotlib's text layout asks a renderer for first
       (``matplotlib.text.Text._get_layout``), computing what the layout computes without it.
    2. The width, height and descent of a string (matplotlib keeps them per renderer, and each
       figure has a renderer of its own) are kept for the process, per string, font properties,
       math flag and resolution: the Agg renderer's measure depends on nothing else.
    3. Mathtext is parsed once per string, resolution and font for the process (matplotlib
       keeps the parses per renderer).
    4. A marker copied from another (every new tick copies the first tick's lines) is copied
       with its transforms, not deep-copied with its paths (which no marker changes).
    5. Within one drawing pass (:data:`_DRAWING`: the layout engine's measuring, then the
       painting), an axis' ticks (locations, labels, which are in view) are computed once per
       view and place of its panel (:func:`_ticks_key`), not at every request (about 11 per
       axis: its bounding box, its spines', its label's and title's places, its siblings'),
       and a text's layout once per string, font, angle and alignment.
    6. A new tick is a copy of the axis' first (:func:`_copied_tick`) instead of one built from
       the rcParams (matplotlib then copies the first tick's properties to it either way).
    7. A wrapped text (the figures' titles) finds its line ends by bisection
       (:func:`_wrapped_text`)."""
    import matplotlib.text
    from matplotlib.axis import Axis
    from matplotlib.backends.backend_agg import RendererAgg
    from matplotlib.font_manager import fontManager, get_font
    from matplotlib.markers import MarkerStyle
    from matplotlib.mathtext import MathTextParser

    if getattr(RendererAgg, "_coathertz_caches", False) or not caches_apply(matplotlib.__version__):
        return
    heights: dict = {}

    def _get_font_height_metrics(self, prop):
        key = (hash(prop), self.dpi)  # FontProperties compare by this hash
        if key not in heights:
            out = (None, None, None)
            font = get_font(fontManager._find_fonts_by_props(prop))
            for table_name, linegap_key, ascent_key, descent_key in (
                    ("OS/2", "sTypoLineGap", "sTypoAscender", "sTypoDescender"),
                    ("hhea", "lineGap", "ascent", "descent")):
                table = font.get_sfnt_table(table_name)
                if table is None:
                    continue
                fontsize = prop.get_size_in_points()
                units_per_em = font.get_sfnt_table("head")["unitsPerEm"]
                scale = 1 / units_per_em * fontsize * self.dpi / 72  # as matplotlib's layout
                out = (table[ascent_key] * scale, -table[descent_key] * scale, table[linegap_key] * scale)
                break
            heights[key] = out
        return heights[key]

    metrics: dict = {}
    measured = matplotlib.text._get_text_metrics_with_cache

    def text_metrics(renderer, text, fontprop, ismath, dpi):
        if type(renderer) is not RendererAgg:
            return measured(renderer, text, fontprop, ismath, dpi)
        key = (text, hash(fontprop), ismath, dpi, renderer.dpi)
        if key not in metrics:
            metrics[key] = renderer.get_text_width_height_descent(text, fontprop, ismath)
        return metrics[key]

    parser = MathTextParser("path")  # what each renderer makes for itself
    init = RendererAgg.__init__

    def __init__(self, *args, **kwargs):
        init(self, *args, **kwargs)
        self.mathtext_parser = parser  # its parses kept per string, resolution and font

    set_marker = MarkerStyle._set_marker

    def _set_marker(self, marker):
        if not isinstance(marker, MarkerStyle):
            return set_marker(self, marker)
        state = dict(marker.__dict__)
        for k in ("_transform", "_alt_transform", "_user_transform"):
            if state.get(k) is not None:
                state[k] = state[k].frozen()  # a copy of its own (``rotated`` changes it in place)
        self.__dict__ = state
        return None

    update_ticks = Axis._update_ticks

    def _update_ticks(self):
        if _DRAWING is None:
            return update_ticks(self)
        key = _ticks_key(self)
        kept = self.__dict__.get("_coathertz_ticks")
        if kept is None or kept[0] != key:
            ticks = update_ticks(self)
            kept = self._coathertz_ticks = (_ticks_key(self), ticks)  # its new ticks counted
        return list(kept[1])

    Axis._update_ticks = _update_ticks
    get_tick = Axis._get_tick

    def _get_tick(self, major):
        ticks = self.__dict__.get("majorTicks" if major else "minorTicks")
        if ticks and type(ticks[0]) is getattr(self, "_tick_class", None):
            return _copied_tick(ticks[0])
        return get_tick(self, major)

    Axis._get_tick = _get_tick
    get_layout = matplotlib.text.Text._get_layout

    def _get_layout(self, renderer):
        if _DRAWING is None or self._wrap or getattr(self, "_transform_rotates_text", False):  # by its place
            return get_layout(self, renderer)
        key = (_DRAWING, id(renderer), getattr(renderer, "dpi", None), self._text, hash(self._fontproperties),
               self._rotation, self._rotation_mode, self._horizontalalignment, self._verticalalignment,
               self._multialignment, self._linespacing, self._usetex, getattr(self, "_parse_math", True))
        kept = self.__dict__.get("_coathertz_layout")
        if kept is None or kept[0] != key:
            kept = self._coathertz_layout = (key, get_layout(self, renderer))
        return kept[1]

    matplotlib.text.Text._get_layout = _get_layout
    matplotlib.text.Text._get_wrapped_text = _wrapped_text
    RendererAgg._get_font_height_metrics = _get_font_height_metrics
    RendererAgg.__init__ = __init__
    matplotlib.text._get_text_metrics_with_cache = text_metrics
    MarkerStyle._set_marker = _set_marker
    RendererAgg._coathertz_caches = True


def _copied_tick(tick):
    """A copy of ``tick`` (a :class:`~matplotlib.axis.Tick` and its two marks, grid line and two
    labels) sharing nothing its owner may change: each artist's attributes copied, each its own
    callbacks, font properties and markers (see :func:`_render_process_caches`)."""
    from matplotlib.cbook import CallbackRegistry
    from matplotlib.markers import MarkerStyle

    def copied(artist):
        new = object.__new__(type(artist))
        new.__dict__.update(artist.__dict__)
        new._callbacks = CallbackRegistry(signals=["pchanged"])
        return new

    new = copied(tick)
    for name in ("tick1line", "tick2line", "gridline"):
        line = copied(getattr(tick, name))
        line._marker = MarkerStyle(line._marker)
        setattr(new, name, line)
    for name in ("label1", "label2"):
        label = copied(getattr(tick, name))
        label._fontproperties = label._fontproperties.copy()
        setattr(new, name, label)
    return new


def _wrapped_text(text) -> str:
    """:meth:`matplotlib.text.Text._get_wrapped_text` (a wrapped text's lines, each as many
    words as fit the figure's width) finding each line's end by bisection (about 5 widths
    measured a line instead of one per word: each a new string to lay out) where the words'
    widths grow with their number (a line without mathtext); the same lines.
    Lines with ``$`` are measured word by word, as matplotlib does (a word that opens or closes
    mathtext can make the longer string the narrower)."""
    if not text.get_wrap() or text.get_usetex():
        return text.get_text()
    line_width = text._get_wrap_line_width()
    lines = []
    for unwrapped in text.get_text().split("\n"):
        words = unwrapped.split(" ")
        monotonic = "$" not in unwrapped
        while words:
            if len(words) == 1:
                lines.append(words.pop(0))
                continue
            if monotonic:  # the first i in [2, n] whose i words are too wide, else n + 1
                lo, hi = 2, len(words) + 1
                while lo < hi:
                    mid = (lo + hi) // 2
                    if text._get_rendered_text_width(" ".join(words[:mid])) > line_width:
                        hi = mid
                    else:
                        lo = mid + 1
                end = lo - 1
            else:
                end = len(words)
                for i in range(2, len(words) + 1):
                    if text._get_rendered_text_width(" ".join(words[:i])) > line_width:
                        end = i - 1
                        break
            lines.append(" ".join(words[:end]))
            words = words[end:]
    return "\n".join(lines)


def _ticks_key(axis) -> tuple:
    """What the ticks an axis draws depend on within one drawing pass (see
    :func:`_render_process_caches`): the pass, its view, its panel's place and size in pixels (at
    the figure's resolution; a locator may choose its number of ticks by the length of the axis),
    its locators and formatters, and how many ticks it has made."""
    major, minor = axis.major, axis.minor
    return (_DRAWING, *axis.get_view_interval(), *axis.axes.bbox.bounds,
            id(major.locator), id(major.formatter), id(minor.locator), id(minor.formatter),
            len(axis.majorTicks), len(axis.minorTicks))


#: zlib level of the PNG files: 3 writes the report's opaque RGB figures in about 60 % of the
#: time of matplotlib's 6 (RGBA), the files about 5 % smaller (no alpha channel).
PNG_COMPRESSION = 3


def _write_png_drawn(fig, path: Path) -> None:
    """Write the PNG of a figure with a layout engine from one drawing pass.

    ``savefig`` draws such a figure twice: once with the renderer switched off, to run the
    layout engine, then again to paint. Drawing the canvas runs the engine itself at the start
    of the pass, so one pass gives the same pixels as ``savefig(path, dpi=PNG_DPI)``
    (``tests/verification/test_figure_saving.py``), at about three quarters of the CPU time. An
    opaque figure (every report figure) is written as RGB, without the alpha channel, at zlib
    level :data:`PNG_COMPRESSION`; the PNG keeps matplotlib's resolution and software tags."""
    import matplotlib
    from PIL import Image
    from PIL.PngImagePlugin import PngInfo

    fig.set_dpi(PNG_DPI)
    fig.canvas.draw()
    image = Image.fromarray(np.asarray(fig.canvas.buffer_rgba()))
    if image.getchannel("A").getextrema() == (255, 255):  # opaque: RGB (PIL drops alpha fastest)
        image = image.convert("RGB")
    info = PngInfo()
    info.add_text("Software", f"Matplotlib version{matplotlib.__version__}, https://matplotlib.org/")
    image.save(path, format="png", dpi=(PNG_DPI, PNG_DPI), pnginfo=info, compress_level=PNG_COMPRESSION)


def save(fig, outdir: str | Path, name: str) -> list[Path]:
    """Save ``fig`` as ``outdir/name.png`` (150 dpi), and ``.svg`` where a
    :func:`~coathertz.figstyle.saving` block asks for it; close it. Byte-for-byte reproducible: no
    date in the SVG, fixed SVG ids (a rerun with equal numbers leaves a published report
    unchanged). Inside a :func:`~coathertz.figstyle.saving` block with more than one job the files
    are complete only when the block ends."""
    import matplotlib.pyplot as plt

    outdir = Path(outdir)
    outdir.mkdir(parents=True, exist_ok=True)
    state = _SAVING
    paths = [outdir / f"{name}.{ext}" for ext in (state.formats if state else DEFAULT_FORMATS)]
    if state is None or state.jobs == 1:
        global _WRITING
        _WRITING = name  # left set if it raises: a render process's error line names it
        _write(fig, paths)
        _WRITING = None
        plt.close(fig)
        return paths
    state.fork(name, lambda: _write(fig, paths))
    plt.close(fig)
    state.reap(block=False)
    return paths


@functools.cache
def _warm_up() -> None:
    """Draw, once in this process, a small figure with what the report's figures have (a tight
    layout, mathtext, log and linear ticks, a legend, a colour bar, text of several sizes), so
    that every render process forked afterwards starts with matplotlib's one-time work done (the
    mathtext grammar, the fonts loaded, the tick machinery): about 0.3 CPU-s each, once here.
    The modules the figures use that nothing imports before (pyplot, contours, triangulations,
    PIL's image plug-ins) are imported here too: about 0.1 CPU-s each render process."""
    import matplotlib

    matplotlib.use("Agg", force=False)
    import contourpy  # noqa: F401
    import matplotlib.pyplot
    import matplotlib.tri
    from PIL import Image

    Image.preinit()  # the plug-ins PIL imports at its first save
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    fig = Figure(figsize=(4.0, 3.0), dpi=PNG_DPI)
    FigureCanvasAgg(fig)
    ax, ax2 = fig.subplots(1, 2)
    ax.plot([1e-2, 1.0, 10.0], [1.0, 2.0, 3.0], "o", mfc="none", ms=4, label=r"$\delta_{0s}^*$")
    ax.set_xscale("log")
    ax.set_xlabel(r"$H = h/a_{0s}$")
    ax.set_ylabel("p [MPa]", fontsize=7)
    ax.legend(fontsize=7)
    fig.colorbar(ax2.pcolormesh([[0.0, 1.0], [2.0, 3.0]]), ax=ax2, label="error [%]")
    ax2.set_title("x", fontsize=9)
    fig.suptitle("warm-up", fontsize=10)
    fig.set_layout_engine("tight")
    _prepare(fig)
    fig.canvas.draw()


def draw_elsewhere(name: str, draw: Callable[[], Iterable[Path]]) -> list[Path]:
    """Run ``draw()``, which builds figures, saves them (:func:`save`) and returns their paths, in
    a forked render process of the enclosing :func:`~coathertz.figstyle.saving` block (one with
    more than one job): this process goes on at once, and building the figures costs it nothing.
    Inside the render process each figure is written as it is saved (the process's text, font
    and tick caches serve all of them).

    Returns the list of ``draw()``'s paths: at once outside such a block; within one, a list
    filled when the render process ends (complete at the end of the block, like the files).
    ``draw`` must not change anything this process reads later: it runs in a copy of it."""
    state = _SAVING
    if state is None or state.jobs == 1:
        return list(draw())
    _warm_up()
    paths: list[Path] = []
    read, write = os.pipe()

    def work() -> None:
        global _SAVING
        os.close(read)
        _SAVING = _Saving(state.formats, 1)  # in this process, each figure written as saved
        drawn = [str(p) for p in draw()]
        for fn in _SAVING.after:
            fn()
        with os.fdopen(write, "wb") as fh:
            fh.write("".join(p + "\n" for p in drawn).encode())

    pid = state.fork(name, work)
    os.close(write)
    state.written[pid] = (read, paths)
    state.reap(block=False)
    return paths


def figure(ncols: int, nrows: int = 1, width: float = 4.2, height: float = 3.4, sharey: bool = False,
           sharex: bool | str = False):
    """A grid of ``nrows`` x ``ncols`` panels (``axes[row, col]``); ``sharey`` for panels comparing
    the same quantity, ``sharex`` (``True`` or ``"col"``) for rows of panels over the same
    abscissa: only the bottom row labels its ticks (docs/style-figures.md)."""
    import matplotlib

    matplotlib.use("Agg", force=False)
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(nrows, ncols, figsize=(width * ncols, height * nrows), squeeze=False,
                             sharey=sharey, sharex=sharex)
    return fig, axes


def colour(i: int, n: int):
    import matplotlib

    return matplotlib.colormaps["viridis"](i / max(n - 1, 1))


def series(rows: Sequence[dict], method: str, key: str, value: float, x: str, y: str):
    """(x, y) arrays of ``rows`` of ``method`` with ``row[key] == value``, sorted by x."""
    sel = sorted((r[x], r[y]) for r in rows if r["method"] == method and math.isclose(r[key], value))
    if not sel:
        return np.array([]), np.array([])
    xs, ys = zip(*sel, strict=True)
    return np.array(xs), np.array(ys)


def method_style(name: str, colour: Any = None) -> dict[str, Any]:
    """Matplotlib keywords for a method's markers: its registered marker; the reference-ranked
    methods filled and small, lower-ranked ones open and larger (so both show where they overlap)."""
    from coathertz.methods import method_info

    info = method_info(name)
    filled = info.reference_rank >= 20
    kw: dict[str, Any] = {"marker": info.marker if info.marker not in ("-", "") else "None",
                          "ms": 4 if filled else 7, "ls": "none"}
    if colour is not None:
        kw["color"] = colour
        kw["mfc"] = colour if filled else "none"
    elif not filled:
        kw["mfc"] = "none"
    return kw


def method_handles(names: Iterable[str], closed_form_line: bool = True) -> list:
    """Legend handles, one per method, in black: the closed form as a line, the others as their
    registered markers, labelled with their registered labels."""
    from matplotlib.lines import Line2D

    from coathertz.methods import method_info, rank_order

    out = []
    for n in rank_order(set(names)):
        info = method_info(n)
        if info.reference_rank <= 0:
            if closed_form_line:
                out.append(Line2D([], [], color="k", lw=1.2, label=info.label))
            continue
        out.append(Line2D([], [], label=info.label, **method_style(n, "k")))
    return out
