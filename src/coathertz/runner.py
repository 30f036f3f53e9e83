"""Run (case, method) tasks through one runner, storing each result as it finishes.

Backends
--------
* ``serial``: in this process (tests; the closed form, which is faster than a process hop).
* local processes (default, ``workers=2``): :class:`concurrent.futures.ProcessPoolExecutor`.
* ``dask.distributed`` (optional extra ``coathertz[dask]``): ``scheduler="tcp://host:8786"`` or a
  ``distributed.Client``; tasks are submitted to the cluster, results stored as they arrive.

Every task is first looked up in the :class:`~coathertz.store.ResultStore`; only missing ones
run. Tasks of one method are sent in chunks (``chunk_size``; methods with a ``solve_many``
batch entry point, such as the FFT solver, get several cases per chunk so that they share grids
and warm starts); a chunk's results are written to the store the moment it returns, one row per
case. An interrupted run (Ctrl-C, a killed process) therefore loses at most the chunks in
flight, and a rerun picks up where it stopped. Failures of single cases (a solver that did not
converge, a case a method rejects) are stored as errors and reported, not raised.

Every result passes :func:`coathertz.validity.check` (``meta["validity"]`` where a/R > 0.1); the
run then issues one :class:`~coathertz.errors.ModelValidityWarning` that counts them.

Worker processes die with their parent: on Linux the kernel kills them when the parent dies
(``prctl(PR_SET_PDEATHSIG, SIGKILL)``), elsewhere a watchdog thread in each worker notices
that its parent is gone within a second; they also drop their inherited copy of the store
lock, so a killed run never leaves a store locked or open.
"""

from __future__ import annotations

import functools
import itertools
import multiprocessing
import os
import signal
import sys
import threading
import time
import traceback
import warnings
from collections.abc import Callable, Iterable, Mapping, Sequence
from concurrent.futures import FIRST_COMPLETED, Future, ProcessPoolExecutor, wait
from dataclasses import dataclass, field
from typing import Any

from coathertz.case import ContactCase
from coathertz.errors import CoatHertzError, ModelValidityWarning
from coathertz.methods import Method
from coathertz.store import ResultStore, StoredResult, case_key, settings_key

DEFAULT_WORKERS = 2


class RunInterrupted(KeyboardInterrupt):
    """Raised by :func:`run_tasks` when ``stop_after`` results have been stored (tests)."""


@dataclass(frozen=True)
class Task:
    """Solve ``case`` with ``method``."""

    case: ContactCase
    method: Method

    @functools.cached_property
    def key(self) -> tuple[str, str, str]:
        """(case key, method name, settings key): one method may run with several settings.
        Computed once per task (two hashes of JSON texts; a run asks about six times per task)."""
        return case_key(self.case), self.method.name, settings_key(self.method.settings())


@dataclass
class RunOutcome:
    """What :func:`run_tasks` did: results by ``(case_key, method, settings_key)`` and counts."""

    results: dict[tuple[str, str, str], StoredResult] = field(default_factory=dict)
    reused: int = 0
    computed: int = 0
    failed: int = 0
    wall_time: float = 0.0
    method_time: dict[str, float] = field(default_factory=dict)

    def get(self, case: ContactCase, method: str | Method) -> StoredResult | None:
        """Result of ``case`` by ``method`` (a Method, or a name if only one setting ran)."""
        if not isinstance(method, str):
            return self.results.get(Task(case, method).key)
        ck = case_key(case)
        return next((sr for k, sr in self.results.items() if k[0] == ck and k[1] == method), None)


def solve_chunk(method: Method, cases: Sequence[ContactCase]) -> list[tuple[dict | None, str | None]]:
    """Solve ``cases`` with ``method`` (batch entry point if there is one); never raises.

    Returns ``(scalars, None)`` or ``(None, error message)`` per case; each result has passed
    :func:`coathertz.validity.check` (without a warning: :func:`run_tasks` issues one per run).
    """
    from coathertz.validity import check

    out: list[tuple[dict | None, str | None]] = []
    many = getattr(method, "solve_many", None)
    if many is not None and len(cases) > 1:
        try:
            return [(check(c, r, warn=False).scalars(), None)
                    for c, r in zip(cases, many(list(cases)), strict=True)]
        except Exception:  # one bad case spoils the batch: redo case by case
            pass
    for c in cases:
        try:
            out.append((check(c, method.solve(c), warn=False).scalars(), None))
        except Exception as exc:
            out.append((None, f"{type(exc).__name__}: {exc}"))
    return out


#: Seconds between two progress lines when stderr is not a terminal (a log file, CI).
PROGRESS_INTERVAL = 5.0
#: Seconds between two redraws of the progress line on a terminal.
PROGRESS_REDRAW = 0.5
#: Seconds of recent history over which the ETA measures the rate of solver time done.
PROGRESS_WINDOW = 15.0
#: Per-case solver time [s] assumed for a method's cost class until one of its cases has
#: finished (then its measured mean replaces it); the quick fig-3 study on 2 cores (AMD EPYC)
#: measured 2.5 ms (closed form), 28 ms (axisym), 0.2 s (FFT) and 2 s (FE) per case.
COST_PRIOR = {"cheap": 3e-3, "moderate": 0.1, "expensive": 2.0}


def _duration(seconds: float) -> str:
    s = round(seconds)
    if s < 60:
        return f"{s} s"
    if s < 3600:
        return f"{s // 60} min {s % 60:02d} s"
    return f"{s // 3600} h {s % 3600 // 60:02d} min"


class Progress:
    """Progress of one :func:`run_tasks` call on stderr: cases done, rate, elapsed time and an
    ETA weighted by each method's measured cost per case.

    The ETA is the cost left over the recent rate of solver time done (:meth:`eta`), the cost of
    a case being its method's mean measured solver time per case (:data:`COST_PRIOR` by cost
    class for a method none of whose cases has finished yet). The count-based ETA of a
    progress bar assumes every case costs the same; with FE cases 1000 times the cost of
    closed-form ones it is off by the mix.

    On a terminal the line is redrawn in place (a carriage return) and erased at the end; otherwise (a log
    file) one line is written every :data:`PROGRESS_INTERVAL` seconds.
    """

    def __init__(self, pending: Mapping[str, int], desc: str, *, enabled: bool = True,
                 stream: Any = None, tty: bool | None = None,
                 interval: float | None = None, clock: Callable[[], float] = time.monotonic) -> None:
        from coathertz.methods import method_info

        self.total = dict(pending)
        self.done = dict.fromkeys(pending, 0)
        self.spent = dict.fromkeys(pending, 0.0)
        self.prior = {m: COST_PRIOR.get(method_info(m).cost, COST_PRIOR["expensive"]) for m in pending}
        self.desc, self.enabled = desc, enabled
        self.stream = sys.stderr if stream is None else stream
        self.tty = bool(getattr(self.stream, "isatty", lambda: False)()) if tty is None else tty
        self.interval = (PROGRESS_REDRAW if self.tty else PROGRESS_INTERVAL) if interval is None else interval
        self.clock = clock
        self.t0 = self.last = clock()
        self.samples: list[tuple[float, float]] = [(self.t0, 0.0)]  # (time, solver seconds done)
        self._width = 0

    def cost(self, method: str) -> float:
        """Mean measured seconds per case of ``method`` (its class prior before the first)."""
        n = self.done.get(method, 0)
        return self.spent[method] / n if n else self.prior.get(method, COST_PRIOR["expensive"])

    def eta(self) -> float | None:
        """Seconds left (None before the first case has finished): the cost left over the
        rate at which solver time was done in the last :data:`PROGRESS_WINDOW` seconds (the
        rate changes when the run passes from cases solved in this process to worker pools)."""
        now = self.clock()
        while len(self.samples) > 1 and now - self.samples[1][0] >= PROGRESS_WINDOW:
            self.samples.pop(0)
        t_then, spent_then = self.samples[0]
        rate = (sum(self.spent.values()) - spent_then) / (now - t_then) if now > t_then else 0.0
        if rate <= 0:
            return None
        return sum((self.total[m] - self.done[m]) * self.cost(m) for m in self.total) / rate

    def line(self) -> str:
        n, total = sum(self.done.values()), sum(self.total.values())
        elapsed = self.clock() - self.t0
        rate = n / elapsed if elapsed > 0 else 0.0
        eta = self.eta()
        left = "" if eta is None or n == total else f", about {_duration(eta)} left"
        return (f"{self.desc}: {n}/{total} cases done, {rate:.3g} cases/s, elapsed "
                f"{_duration(elapsed)}{left}")

    def update(self, method: str, n: int = 1, seconds: float = 0.0) -> None:
        """``n`` cases of ``method`` finished, taking ``seconds`` together."""
        if method not in self.total:
            self.total[method], self.done[method], self.spent[method] = n, 0, 0.0
            self.prior[method] = COST_PRIOR["expensive"]
        self.done[method] += n
        self.spent[method] += seconds
        now = self.clock()
        self.samples.append((now, sum(self.spent.values())))
        if self.enabled and now - self.last >= self.interval:
            self.last = now
            self._write(self.line())

    def _write(self, text: str) -> None:
        try:
            if self.tty:
                self.stream.write("\r" + text.ljust(self._width))
                self._width = len(text)
            else:
                self.stream.write(text + "\n")
            self.stream.flush()
        except (OSError, ValueError):  # a closed stderr must not stop the run
            self.enabled = False

    def close(self) -> None:
        if self.enabled and self.tty and self._width:
            self._write(" " * self._width)
            self.stream.write("\r")


def _case_seconds(scalars: dict | None, fallback: float) -> float:
    """The solver's own time for one case (``meta["wall_time"]``, measured in the worker), else
    ``fallback`` (the chunk's time from submission to result, queueing included)."""
    t = ((scalars or {}).get("meta") or {}).get("wall_time")
    return float(t) if isinstance(t, int | float) and 0 <= t < float("inf") else fallback


def _stored(tasks: Iterable[Task], store: ResultStore) -> dict[tuple[str, str, str], StoredResult]:
    """The stored results of ``tasks`` (one query per method), by task key."""
    by_method: dict[int, list[Task]] = {}
    for t in tasks:
        by_method.setdefault(id(t.method), []).append(t)
    out: dict[tuple[str, str, str], StoredResult] = {}
    for ts in by_method.values():
        m = ts[0].method
        found = store.get_many([t.case for t in ts], m.name, m.settings())
        out.update({t.key: found[t.key[0]] for t in ts if t.key[0] in found})
    return out


def _chunks(tasks: list[Task], chunk_size: int | None) -> list[tuple[Method, list[ContactCase]]]:
    by_method: dict[tuple[str, int], list[Task]] = {}
    methods: dict[tuple[str, int], Method] = {}
    for t in tasks:
        k = (t.method.name, id(t.method))
        by_method.setdefault(k, []).append(t)
        methods[k] = t.method
    out = []
    for k, ts in by_method.items():
        m = methods[k]
        size = chunk_size or (8 if hasattr(m, "solve_many") else 1)
        for s in range(0, len(ts), size):
            out.append((m, [t.case for t in ts[s : s + size]]))
    return out


def _dask_client(scheduler: Any):
    try:
        from distributed import Client
    except ImportError as exc:
        raise CoatHertzError(
            "--scheduler needs dask.distributed: pip install 'coathertz[dask]'"
        ) from exc
    if isinstance(scheduler, str):
        try:
            return Client(scheduler), True
        except (OSError, ValueError, TypeError) as exc:
            raise CoatHertzError(f"--scheduler {scheduler!r}: cannot connect to a dask scheduler "
                                 f"there ({exc})") from None
    return scheduler, False


def run_tasks(
    tasks: Iterable[Task],
    store: ResultStore,
    *,
    workers: int = DEFAULT_WORKERS,
    scheduler: Any = None,
    progress: bool = True,
    chunk_size: int | None = None,
    inline: Sequence[str] | None = None,
    retry_errors: bool = False,
    stop_after: int | None = None,
    desc: str = "cases",
    ahead: Callable[[], Iterable[Task]] | None = None,
) -> RunOutcome:
    """Run every task not yet in ``store``; store each result as soon as it is available.

    Parameters
    ----------
    tasks
        (case, method) pairs; duplicates are solved once.
    store
        Result store; finished results are reused, new ones written one by one.
    workers
        Local worker processes; ``workers <= 1`` runs everything in this process.
    scheduler
        ``dask.distributed`` scheduler address (``tcp://...``) or ``Client``; overrides
        ``workers``.
    chunk_size
        Cases per submitted chunk (default 8 for methods with ``solve_many``, else 1).
    inline
        Method names always run in this process; default: the methods that declare
        ``inline = True`` (a closed form: cheaper than a hop to a worker).
    retry_errors
        Rerun cases whose stored result is an error.
    stop_after
        Raise :class:`RunInterrupted` after this many new results are stored (for tests of
        interruption and resume).
    ahead
        The tasks of the *next* call (on the open :class:`worker_pool` only): once this call's
        own chunks are all submitted, the free slots start those not stored yet, so that the
        workers keep solving while this process analyses and draws (see ``_Ahead``). The
        next call adopts them. Called at most once.
    """
    t_start = time.perf_counter()
    outcome = RunOutcome()
    unique: dict[tuple[str, str], Task] = {}
    for t in tasks:
        unique.setdefault(t.key, t)
    pending: list[Task] = []
    found = _stored(unique.values(), store)
    for t in unique.values():
        sr = found.get(t.key)
        if sr is not None and (sr.ok or not retry_errors):
            outcome.results[t.key] = sr
            outcome.reused += 1
        else:
            pending.append(t)
    adopted, handed = _AHEAD.adopt(pending)
    if adopted or handed:
        covered = {Task(c, m).key for m, cs in [*((m, cs) for m, cs, _ in adopted.values()), *handed]
                   for c in cs}
        pending = [t for t in pending if t.key not in covered]
    own = {t.key for t in unique.values()}
    if not pending and not adopted and not handed:
        # nothing to solve here (every result stored): the next call's cases start now, on the
        # workers, while this process analyses and draws
        _start_ahead(ahead, store, own, chunk_size, workers, scheduler)
        outcome.wall_time = time.perf_counter() - t_start
        return outcome

    counts: dict[str, int] = {}
    for t in pending:
        counts[t.method.name] = counts.get(t.method.name, 0) + 1
    for m, cs in [*((m, cs) for m, cs, _ in adopted.values()), *handed]:
        counts[m.name] = counts.get(m.name, 0) + len(cs)
    bar = Progress(counts, desc, enabled=progress)
    stored = 0
    outside: list[str] = []

    def record(method: Method, cases: Sequence[ContactCase], res: list, dt: float) -> None:
        nonlocal stored
        for c, (scalars, err) in zip(cases, res, strict=True):
            store.put(c, method.name, method.settings(), scalars, err)
            sr = store.get(c, method.name, method.settings())
            assert sr is not None
            outcome.results[Task(c, method).key] = sr
            if err is None:
                outcome.computed += 1
            else:
                outcome.failed += 1
            if scalars is not None and (scalars.get("meta") or {}).get("validity"):
                outside.append(f"{method.name}: {c.label or c.describe()}")
            stored += 1
            bar.update(method.name, 1, _case_seconds(scalars, dt / len(cases)))
            if stop_after is not None and stored >= stop_after:
                raise RunInterrupted(f"stopped after {stored} results (stop_after)")
        outcome.method_time[method.name] = outcome.method_time.get(method.name, 0.0) + dt

    try:
        if inline is None:
            inline = {t.method.name for t in pending if getattr(t.method, "inline", False)}
        local = [t for t in pending if t.method.name in inline]
        remote = [t for t in pending if t.method.name not in inline]
        if scheduler is None and workers <= 1:
            local, remote = local + remote, []
        local_chunks = _chunks(local, chunk_size)
        if (remote or adopted or handed) and scheduler is None:
            # the workers start first; this process solves its own (inline) chunks meanwhile
            later = None if ahead is None else (lambda: _AHEAD.plan(ahead, store, own, chunk_size))
            _run_processes(handed + _chunks(remote, chunk_size), workers, record, adopted, later,
                           local_chunks)
        else:
            if not remote:  # nothing for the workers from this call: the next call's cases start now
                _start_ahead(ahead, store, own, chunk_size, workers, scheduler)
            for m, cs in local_chunks:
                t0 = time.perf_counter()
                res = solve_chunk(m, cs)
                record(m, cs, res, time.perf_counter() - t0)
            if remote:
                _run_dask(_chunks(remote, chunk_size), scheduler, record)
    finally:
        bar.close()
        outcome.wall_time = time.perf_counter() - t_start
        if outside:
            warnings.warn(
                f"{len(outside)} result(s) lie outside the model's assumptions (a/R > 0.1; "
                f"meta['validity'] says why), e.g. {outside[0]}", ModelValidityWarning, stacklevel=2)
    return outcome


def _mp_context():
    methods = multiprocessing.get_all_start_methods()
    return multiprocessing.get_context("fork" if "fork" in methods else "spawn")


#: Seconds between two checks of the parent by a worker's watchdog thread.
WATCHDOG_INTERVAL = 0.5


def _set_parent_death_signal() -> bool:
    """Ask the Linux kernel to SIGKILL this process when its parent dies (``prctl``)."""
    if not sys.platform.startswith("linux"):
        return False
    try:
        import ctypes

        libc = ctypes.CDLL(None, use_errno=True)
        PR_SET_PDEATHSIG = 1
        return libc.prctl(PR_SET_PDEATHSIG, signal.SIGKILL, 0, 0, 0) == 0
    except (OSError, AttributeError):  # pragma: no cover
        return False


def _watch_parent(parent: int) -> None:
    while True:
        if os.getppid() != parent:
            os._exit(1)
        time.sleep(WATCHDOG_INTERVAL)


def worker_init(parent: int) -> None:
    """Initializer of the worker processes: die with the parent ``parent`` (pid).

    Sets the parent-death signal (Linux) and starts a watchdog thread (everywhere) that exits
    the worker as soon as it is re-parented; closes the inherited store-lock descriptors.
    """
    from coathertz.store import HELD_LOCK_FDS

    for fd in list(HELD_LOCK_FDS):
        try:
            os.close(fd)
        except OSError:
            pass
    HELD_LOCK_FDS.clear()
    # Ctrl-C reaches the whole process group: the parent stops the run and terminates the
    # workers; a worker handling SIGINT itself would print its traceback ("Process ForkProcess-N:")
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    # terminated by the parent (an interrupted run): die quietly, not by a handler inherited from it
    signal.signal(signal.SIGTERM, signal.SIG_DFL)
    _set_parent_death_signal()
    if os.getppid() != parent:  # the parent died before the signal was armed
        os._exit(1)
    threading.Thread(target=_watch_parent, args=(parent,), daemon=True, name="parent-watchdog").start()


#: The pool of :func:`worker_pool` while one is open: (executor, its number of workers).
_POOL: tuple[ProcessPoolExecutor, int] | None = None


#: Chunks of the next calls' work kept running ahead per worker (a chunk is 8 FFT cases or one
#: FE case, about a second): enough to keep every worker busy between two results.
AHEAD_PER_WORKER = 3
#: Chunks started ahead per worker at most, finished ones that no call has adopted yet included:
#: what the workers may solve while this process analyses and draws (a minute of work and more;
#: the results held are a few kB a case); an interrupted run stores the finished ones
#: (``_Ahead.salvage``).
AHEAD_HELD_PER_WORKER = 100
#: Seconds between two checks of the feeder thread when no chunk has finished.
FEED_INTERVAL = 0.25


class _Ahead:
    """Work of the next :func:`run_tasks` calls started early on the shared pool.

    ``queued`` chunks wait for a free slot; ``running`` maps a submitted chunk's future to its
    (method, cases), until a call adopts it. :meth:`adopt` hands a call the futures of its own
    tasks (it records their results as if it had submitted them) and takes back its queued ones.

    While a :class:`worker_pool` block is open, a feeder thread (:meth:`start`) submits queued
    chunks as earlier ones finish, so that the workers go on solving while this process is busy
    elsewhere (a study's analysis, its figures): at most :data:`AHEAD_PER_WORKER` chunks per
    worker running, :data:`AHEAD_HELD_PER_WORKER` started and not yet adopted. It holds back
    while a call submits its own chunks (``paused``), which come first. What is never adopted is
    dropped with the pool; on an interrupt the finished chunks are stored first
    (:meth:`salvage`)."""

    def __init__(self) -> None:
        self.queued: list[tuple[Method, list[ContactCase]]] = []
        self.running: dict[Future, tuple[Method, list[ContactCase]]] = {}
        self.paused = False
        self._lock = threading.RLock()
        self._wake = threading.Event()
        self._stop = threading.Event()
        self._thread: threading.Thread | None = None
        self._pool: tuple[ProcessPoolExecutor, int] | None = None

    def clear(self) -> None:
        with self._lock:
            for f in self.running:
                f.cancel()
            self.queued.clear()
            self.running.clear()

    def plan(self, ahead: Callable[[], Iterable[Any]], store: ResultStore, own: set,
             chunk_size: int | None) -> None:
        """Queue the tasks of ``ahead()`` that are neither this call's (``own``), nor stored, nor
        already ahead, nor run in this process (``inline`` methods). ``ahead()`` gives tasks, or
        groups of tasks (one per later call; may be a generator), each chunked on its own and
        queued as soon as it is planned (the feeder starts it while the next group is planned)."""
        with self._lock:
            held = [*self.queued, *self.running.values()]
        taken = set(own) | {Task(c, m).key for m, cs in held for c in cs}
        items = iter(ahead())
        first = next(items, None)
        if first is None:
            return
        groups = [[first, *items]] if isinstance(first, Task) else itertools.chain([first], items)
        for group in groups:  # chunked group by group (a study's cases with each other)
            todo: dict[tuple, Task] = {}
            for t in group:
                if t.key not in taken and not getattr(t.method, "inline", False):
                    todo.setdefault(t.key, t)
            taken |= set(todo)
            found = _stored(todo.values(), store)
            chunks = _chunks([t for t in todo.values() if t.key not in found], chunk_size)
            with self._lock:
                self.queued += chunks
            self._wake.set()

    def top_up(self, ex: ProcessPoolExecutor, workers: int) -> None:
        """Submit queued chunks while fewer than ``AHEAD_PER_WORKER * workers`` run and fewer
        than ``AHEAD_HELD_PER_WORKER * workers`` are held (running or finished, not adopted)."""
        with self._lock:
            busy = sum(not f.done() for f in self.running)
            while (self.queued and busy < AHEAD_PER_WORKER * workers
                   and len(self.running) < AHEAD_HELD_PER_WORKER * workers):
                m, cs = self.queued.pop(0)
                f = ex.submit(solve_chunk, m, cs)
                self.running[f] = (m, cs)
                busy += 1
                f.add_done_callback(lambda _f: self._wake.set())

    def adopt(self, pending: Sequence[Task]) -> tuple[dict[Future, tuple[Method, list[ContactCase], float]],
                                                      list[tuple[Method, list[ContactCase]]]]:
        """The chunks that hold any of ``pending``, taken from here: the running ones (with
        their submit time for :func:`run_tasks`'s records) and the queued ones, which the caller
        submits as they are (so that a case is solved with the same chunk, hence the same warm
        starts, whatever the timing: the numbers of a run do not depend on how fast it went)."""
        with self._lock:
            if not (self.queued or self.running):
                return {}, []
            want = {t.key for t in pending}

            def mine(cs: list[ContactCase], m: Method) -> bool:
                return any(Task(c, m).key in want for c in cs)

            queued = [(m, cs) for m, cs in self.queued if mine(cs, m)]
            self.queued = [(m, cs) for m, cs in self.queued if not mine(cs, m)]
            got = {f: (m, cs, time.perf_counter()) for f, (m, cs) in self.running.items() if mine(cs, m)}
            for f in got:
                del self.running[f]
        self._wake.set()  # slots freed
        return got, queued

    def salvage(self, store: ResultStore) -> int:
        """Store the results of the chunks started ahead that have finished and that no call
        adopted (an interrupted run keeps them); returns the number of results stored."""
        with self._lock:
            done = [(f, m, cs) for f, (m, cs) in self.running.items()
                    if f.done() and not f.cancelled() and f.exception() is None]
        n = 0
        for f, m, cs in done:
            for c, (scalars, err) in zip(cs, f.result(), strict=True):
                store.put(c, m.name, m.settings(), scalars, err)
                n += 1
        return n

    def wake(self) -> None:
        """Let the feeder thread look for free slots now."""
        self._wake.set()

    def start(self, ex: ProcessPoolExecutor, workers: int) -> None:
        """Start the feeder thread for the pool ``ex`` (a :class:`worker_pool` block)."""
        self.stop()
        self._pool = (ex, workers)
        self._stop.clear()
        self._thread = threading.Thread(target=self._feed, daemon=True, name="ahead-feeder")
        self._thread.start()

    def stop(self) -> None:
        """Stop the feeder thread (it submits nothing more)."""
        if self._thread is not None:
            self._stop.set()
            self._wake.set()
            self._thread.join(timeout=5.0)
        self._thread, self._pool = None, None

    def _feed(self) -> None:
        while not self._stop.is_set():
            self._wake.wait(FEED_INTERVAL)
            self._wake.clear()
            if self._stop.is_set() or self.paused or self._pool is None:
                continue
            ex, n = self._pool
            if getattr(ex, "_broken", False):
                return
            try:
                self.top_up(ex, n)
            except RuntimeError:  # the pool shut down under us (an interrupted run)
                return


_AHEAD = _Ahead()


def _new_pool(workers: int) -> ProcessPoolExecutor:
    return ProcessPoolExecutor(max_workers=workers, mp_context=_mp_context(),
                               initializer=worker_init, initargs=(os.getpid(),))


def _drop_pending(ex: ProcessPoolExecutor) -> None:
    """Cancel the work items of ``ex`` not yet running and take them off its list.

    When a worker dies, the executor's thread marks every listed item's future failed
    (``terminate_broken``); CPython 3.11 does so without checking whether the future was already
    cancelled, and the ``InvalidStateError`` it then raises is printed as a thread traceback on
    an interrupted run (seen in about 3 of 4 interrupts on a loaded machine)."""
    items = getattr(ex, "_pending_work_items", None)
    if not items:
        return
    for work_id, item in list(items.items()):
        if item.future.cancel() or item.future.cancelled():
            items.pop(work_id, None)


def _kill_pool(ex: ProcessPoolExecutor) -> None:
    """Terminate the workers of ``ex`` at once (an interrupted run does not wait for the cases in
    flight: an FE case can take minutes) and shut it down."""
    _AHEAD.clear()
    _drop_pending(ex)
    procs = list((getattr(ex, "_processes", None) or {}).values())
    for p in procs:
        p.terminate()  # SIGTERM: a worker dies at once (worker_init leaves its default action)
    for p in procs:
        p.join(timeout=5.0)
    # then wait for the executor's own thread: left running, it closes its wake-up pipe while the
    # interpreter's exit hook of concurrent.futures still writes to it ("Bad file descriptor")
    ex.shutdown(wait=not any(p.is_alive() for p in procs), cancel_futures=True)


class worker_pool:  # a context manager, named like the function it reads as
    """One pool of ``workers`` local processes for every :func:`run_tasks` call in the block
    (``with worker_pool(2): ...`` around the studies of a run): the workers are started once,
    not per call, and keep what they cached (quadrature tables, FFT plans) from one call to the
    next, and the next calls' work started ahead (``run_tasks(..., ahead=...)``) is fed to them
    while this process does other things. Calls asking for a different number of workers get
    their own pool. Leaving the block by an exception terminates the workers, after storing in
    ``store`` (where given) what they finished ahead; leaving it normally waits for them to exit.
    """

    def __init__(self, workers: int, store: ResultStore | None = None):
        self.workers = max(1, min(int(workers), os.cpu_count() or 1))
        self.store = store
        self._outer: tuple[ProcessPoolExecutor, int] | None = None
        self._ex: ProcessPoolExecutor | None = None

    def __enter__(self) -> worker_pool:
        global _POOL
        self._outer, self._ex = _POOL, _new_pool(self.workers)
        _POOL = (self._ex, self.workers)
        _AHEAD.start(self._ex, self.workers)
        return self

    def __exit__(self, kind, exc, tb) -> None:
        global _POOL
        _AHEAD.stop()
        _POOL = self._outer
        if self._ex is None:  # pragma: no cover - __enter__ failed
            _AHEAD.clear()
            return
        if kind is not None and self.store is not None:
            try:  # the cases finished ahead are kept: a rerun does not solve them again
                _AHEAD.salvage(self.store)
            except Exception:  # a store that cannot take them: they are solved again
                pass
        _AHEAD.clear()  # work started for a call that did not come
        if kind is None:
            self._ex.shutdown(wait=True)
        else:
            _kill_pool(self._ex)
        if self._outer is not None:  # an enclosing block's feeder goes on
            _AHEAD.start(*self._outer)


def _start_ahead(ahead: Callable[[], Iterable[Task]] | None, store: ResultStore, own: set,
                 chunk_size: int | None, workers: int, scheduler: Any) -> None:
    """Start the next call's work (``ahead``) on the open :class:`worker_pool` now: for a call
    that gives the workers nothing (every result stored, or only inline methods), so that they
    solve while this process goes on (its inline cases, the study's analysis and figures)."""
    if ahead is None or scheduler is not None or workers <= 1 or _POOL is None:
        return
    ex, n = _POOL
    if getattr(ex, "_broken", False):
        return
    try:
        _AHEAD.plan(ahead, store, own, chunk_size)
    except Exception:  # the next call plans again and reports it
        _AHEAD.queued.clear()
        return
    _AHEAD.top_up(ex, n)


def _run_processes(chunks: list, workers: int, record: Callable,
                   adopted: Mapping[Future, tuple] | None = None,
                   later: Callable[[], None] | None = None,
                   local: Sequence[tuple[Method, list[ContactCase]]] = ()) -> None:
    """Run ``chunks`` on local processes and ``record`` each result; ``adopted``: futures already
    running (started ahead), recorded like the others; ``later``: queues the next call's work
    (``_Ahead``), started in the slots this call's chunks leave free at its end; ``local``:
    chunks solved in this process once the workers have theirs (inline methods, such as the
    closed form), between which finished chunks are recorded and the workers fed."""
    workers = max(1, min(workers, max(len(chunks), 1), os.cpu_count() or 1))
    # the pool of an open worker_pool block, unless a worker of it died (a broken pool)
    shared = _POOL is not None and _POOL[1] >= workers and not getattr(_POOL[0], "_broken", False)
    ex = _POOL[0] if shared else _new_pool(workers)  # type: ignore[index]
    futures: dict[Future, tuple[Method, list, float]] = dict(adopted or {})
    it = iter(chunks)
    clean = False
    ahead = shared and later is not None
    started_ahead = False
    _AHEAD.paused = shared  # this call's own chunks first
    try:
        # keep at most 2 * workers chunks submitted: an interrupt then loses little work
        for m, cs in it:
            futures[ex.submit(solve_chunk, m, cs)] = (m, cs, time.perf_counter())
            if len(futures) >= 2 * workers:
                break

        def collect(f: Future) -> None:
            nonlocal started_ahead
            m, cs, t0 = futures.pop(f)
            try:
                res = f.result()
            except Exception as exc:  # worker died: record the failure per case
                msg = f"{type(exc).__name__}: {exc}\n{traceback.format_exc(limit=2)}"
                res = [(None, msg)] * len(cs)
            record(m, cs, res, time.perf_counter() - t0)
            nxt = next(it, None)
            if nxt is not None:
                futures[ex.submit(solve_chunk, *nxt)] = (nxt[0], nxt[1], time.perf_counter())
            elif shared and _AHEAD.paused:  # this call's chunks are all out: the feeder goes on
                _AHEAD.paused = False
                _AHEAD.wake()
            if nxt is None and ahead:  # the next call's chunks fill the free slots
                if not started_ahead:
                    started_ahead = True
                    try:
                        later()  # type: ignore[misc]
                    except Exception:  # the next call plans again and reports it
                        _AHEAD.queued.clear()
                _AHEAD.top_up(ex, _POOL[1])  # type: ignore[index]

        for m, cs in local:  # this process's own chunks while the workers solve theirs
            t0 = time.perf_counter()
            record(m, cs, solve_chunk(m, cs), time.perf_counter() - t0)
            for f in [f for f in futures if f.done()]:
                collect(f)
        while futures:
            done, _ = wait(list(futures), return_when=FIRST_COMPLETED)
            for f in done:
                collect(f)
        clean = True
    finally:
        _AHEAD.paused = False
        for f in futures:
            f.cancel()
        if not clean:  # interrupted: do not wait for chunks in flight (an FE case can take minutes)
            _kill_pool(ex)
        elif not shared:
            ex.shutdown(wait=True)


def _run_dask(chunks: list, scheduler: Any, record: Callable) -> None:
    from distributed import as_completed

    client, own = _dask_client(scheduler)
    futs, meta = [], {}
    try:
        for m, cs in chunks:
            f = client.submit(solve_chunk, m, cs, pure=False)
            futs.append(f)
            meta[f.key] = (m, cs, time.perf_counter())
        for f in as_completed(futs):
            m, cs, t0 = meta[f.key]
            try:
                res = f.result()
            except Exception as exc:
                res = [(None, f"{type(exc).__name__}: {exc}")] * len(cs)
            record(m, cs, res, time.perf_counter() - t0)
    finally:
        client.cancel(futs)
        if own:
            client.close()
