"""Run a sweep on dask: chunked analytic maps and BEM cases as tasks, resumable.

Engine
------
* **Analytic pull-offs** (:func:`dhfield.sweep.tasks.pull_off_block`) run through
  ``xarray.apply_ufunc(..., dask="parallelized")`` on a (beta0, mu) grid chunked
  into blocks of about ``chunk_points`` points, so a worker holds one block at a
  time and memory stays bounded whatever the grid size.  Each block is a case
  of the store: it is written when it finishes and read back, not recomputed,
  by a rerun.  The chunking depends only on the config, never on the
  scheduler, so every scheduler evaluates the same blocks and gives
  bit-identical results.
* **BEM cases** (:func:`~dhfield.sweep.tasks.bem_field_case`,
  :func:`~dhfield.sweep.tasks.adhesive_case`) are ``dask.delayed`` tasks.  The
  cases of one load path (the contact sizes of one forward-BEM state family;
  the whole path of an adhesive pull-off) stay in one task.  The half-space
  operator is built inside the worker on first use and cached there
  (:func:`dhfield.bem.get_operator`): it holds a lock and is never pickled.
  An adhesive case runs on an explicit ``n`` x ``n`` grid or, on the ``grid_level``
  axis, on the library's automatic grid (level 1) or k times its cells per axis
  (:func:`~dhfield.sweep.tasks.automatic_grid`); each stores its grid (nx, ny,
  half-widths), stated error, flags, wall and CPU time, route, and provenance (the
  commit that solved it, the sweep's command line, the time it finished).  A level
  whose grid is estimated to take longer than ``[bem] max_seconds`` is refused before
  solving (status "failed", retried by the next run); the consolidated file records
  the time allowed by the run that wrote it (attribute ``param_bem_max_seconds``).
* **Costliest first.** Every BEM task carries an estimate of its cost
  (:func:`dhfield.sweep.tasks.expected_seconds`: n^2 log n, times mu^1.1 for an
  adhesive path); the task keys rank them so that dask starts the costliest
  first, and hands the rest to workers as they free up (longest-processing-time
  list scheduling, within 4/3 of the best split).  A poor estimate costs balance,
  never results: the cases are independent.
* **Schedulers.** ``"synchronous"`` (serial, in this process), ``"processes"``
  (local worker processes, the default, ``workers`` of them, default every
  core), or the address of a dask.distributed scheduler
  (``tcp://host:port``; the workers must see the output directory).  Every
  worker uses one core: local workers are spawned with one BLAS/OpenMP thread
  (:data:`SINGLE_THREAD_ENV`), a serial sweep runs under
  ``threadpoolctl.threadpool_limits(1)``, and the BEM tasks ask FFTW for one
  thread.
* **Resumable.** Cases are written to a :class:`~dhfield.sweep.store.CaseStore`
  as they finish; a case that raises is recorded with its message (status
  "failed", NaN values) and retried by the next run; a non-converged adhesive
  case is recorded with its message (status "not_converged") and kept, and so
  is one that converged on a grid too coarse for its cohesive zone (status
  "unresolved": the solver's ``resolved`` flag is false).  The
  consolidated Dataset is written atomically at the end.
"""
from __future__ import annotations

import os
import shlex
import sys
import time
import traceback
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ..core import schema
from .config import ADHESIVE_ROUTE, SweepConfig, check_scheduler_address, scheduler_host_port
from .store import CaseStore, case_coordinates, output_paths
from .tasks import (ADHESIVE_BEM_FIELDS, ADHESIVE_FIELDS, ADHESIVE_GRID_FIELDS, ADHESIVE_MODEL, ADHESIVE_TEXT_FIELDS,
                    BEM_FIELD_FIELDS, CURVE_FIELDS, PULL_OFF_FIELDS, adhesive_case, adhesive_solver, bem_field_case,
                    block_values, expected_seconds, load_curve_case, pull_off_block)

_FIELDS = {"bem_field": BEM_FIELD_FIELDS, "adhesive": ADHESIVE_FIELDS + ADHESIVE_BEM_FIELDS + ADHESIVE_GRID_FIELDS,
           "load_curve": CURVE_FIELDS}
#: Text kept per case in the case file's attributes (the adhesive case's route, note and provenance).
_TEXT_FIELDS = {"adhesive": ADHESIVE_TEXT_FIELDS + ("command",)}

__all__ = ["SweepResult", "Executor", "connect", "run_sweep", "map_cases", "Progress", "STATUS_MEANINGS",
           "CONNECT_TIMEOUT", "SCHEDULER_ENV", "WORKERS_ENV", "SINGLE_THREAD_ENV", "WORKER_START_TIMEOUT",
           "QUANTITY_MODULES", "probe_scheduler", "MAX_HANDSHAKE_BYTES", "UNRESOLVED_MESSAGE", "case_key",
           "check_output", "check_sweep_memory"]

#: Seconds to wait for a dask.distributed scheduler (connection and handshake) before reporting it.
CONNECT_TIMEOUT = 5.0
#: Largest first message accepted from a scheduler [bytes]: its handshake is a few hundred bytes
#: of msgpack; a peer announcing more is not a scheduler (a garbage peer announced 6.46 EiB).
MAX_HANDSHAKE_BYTES = 1 << 16
#: Modules the tasks of each quantity import: preloaded by the local workers of a sweep
#: (:meth:`Executor.start`), so that only what the sweep uses is imported, once, at start-up.
QUANTITY_MODULES = {"pull_off": ("dhfield.analysis.compare",), "load_curve": ("dhfield.analysis.compare",),
                    "bem_field": ("dhfield.analysis.fields",), "adhesive": ("dhfield.analysis.bem_start",)}
#: Seconds a starting local worker waits for its siblings (:meth:`Executor.start`).
WORKER_START_TIMEOUT = 300.0
#: Thread counts of the numerical libraries, set to 1 in every local worker process
#: (as dask.distributed's nanny does) and, through threadpoolctl, while a sweep runs serially.
SINGLE_THREAD_ENV = ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS", "VECLIB_MAXIMUM_THREADS",
                     "NUMEXPR_NUM_THREADS")
#: Case status codes (CF flag_values) and their meanings.
STATUS_MEANINGS = {0: "ok", 1: "not_converged", 2: "failed", 3: "unresolved"}
#: Message of an adhesive case whose path converged on a grid too coarse for its cohesive zone.
UNRESOLVED_MESSAGE = ("unresolved: the grid does not resolve the cohesive zone (resolved = false), W* is not an "
                      "answer; increase n")
_STATUS = {v: k for k, v in STATUS_MEANINGS.items()}
_LOCAL = ("synchronous", "processes")
#: Environment variables giving :func:`map_cases` its default scheduler and worker count
#: (set by ``python -m verification.report --scheduler ...``; inherited by section processes).
SCHEDULER_ENV = "DHFIELD_SCHEDULER"
WORKERS_ENV = "DHFIELD_WORKERS"


# --------------------------------------------------------------------------- progress
class Progress:
    """A one-line progress bar with ETA on ``stream`` (stderr), redrawn at most 5 times a second.

    Parameters
    ----------
    total : int
        Number of steps.
    enabled : bool
        Draw the bar (False: count silently).
    label : str, default "sweep"
        Text before the bar.
    stream : file-like, optional
        Where to draw; default ``sys.stderr``.
    """

    def __init__(self, total: int, enabled: bool, label: str = "sweep", stream=None):
        self.total, self.enabled, self.label = int(total), bool(enabled), label
        self.stream = sys.stderr if stream is None else stream
        self.done = 0
        self.start = time.monotonic()
        self._last = 0.0

    def advance(self, n: int = 1) -> None:
        """Count ``n`` more steps done and redraw if due.

        Parameters
        ----------
        n : int, default 1
            Steps done.
        """
        self.done += n
        if self.enabled and (time.monotonic() - self._last > 0.2 or self.done >= self.total):
            self._draw()

    def _draw(self):
        self._last = time.monotonic()
        elapsed = self._last - self.start
        frac = self.done / self.total if self.total else 1.0
        eta = elapsed * (1.0 - frac) / frac if frac > 0 else float("nan")
        bar = "#" * int(30 * frac)
        fmt = (lambda s: "--:--" if not np.isfinite(s) else f"{int(s) // 60}:{int(s) % 60:02d}")
        self.stream.write(f"\r{self.label} [{bar:<30s}] {self.done}/{self.total} {100 * frac:3.0f}% "
                          f"elapsed {fmt(elapsed)} ETA {fmt(eta)}")
        self.stream.flush()

    def close(self) -> None:
        """Draw the final state and end the line."""
        if self.enabled:
            self._draw()
            self.stream.write("\n")
            self.stream.flush()


# --------------------------------------------------------------------------- schedulers
@dataclass
class Executor:
    """Where tasks run: ``kind`` is "synchronous", "processes" or "distributed".

    An Executor from :func:`connect` can be passed to several :func:`run_sweep`
    calls: local worker processes are started once, on first use, and kept
    (with the operators they built) until :meth:`close`.

    Parameters
    ----------
    kind : {"synchronous", "processes", "distributed"}
        Where tasks run.
    workers : int
        Number of workers.
    client : distributed.Client, optional
        The client, for ``kind == "distributed"``.
    _own_client : bool, default False
        Internal: True when this Executor started ``client`` (and closes it).
    _pool : object, optional
        Internal: the running local process pool.
    _starting : tuple, optional
        Internal: ``(pool, futures, t0)`` of workers spawned by ``start(wait=False)``.
    """

    kind: str
    workers: int
    client: object = None
    _own_client: bool = False
    _pool: object = None
    _starting: tuple = None  # (pool, futures, t0) of workers spawned by start(wait=False)

    @property
    def pool(self):
        """The local process pool, started on first use (see :meth:`start`)."""
        if self._pool is None:
            self.start()
        return self._pool

    def start(self, preload=(), wait=True) -> float:
        """Start the local worker processes now.

        Every worker is spawned with one BLAS/OpenMP thread (:data:`SINGLE_THREAD_ENV`;
        the BEM tasks also ask FFTW for one thread), so W workers use W cores and
        one worker never secretly uses two.  Each imports the modules ``preload``
        (names, e.g. :data:`QUANTITY_MODULES` values), then waits for the others:
        when this returns, all are up, and a sweep timed afterwards excludes the
        start-up.  ``wait=False`` spawns them and returns at once (0.0), so that
        they start while this process prepares the sweep; the next ``start()``
        or use of :attr:`pool` waits for them.  Nothing to do (0.0) for the
        other kinds or when the pool is already running.

        Parameters
        ----------
        preload : sequence of str, default ()
            Modules each worker imports before it reports ready.
        wait : bool, default True
            Wait until all workers are ready.

        Returns
        -------
        float
            The seconds it took until all workers were ready [s].
        """
        if self.kind != "processes" or self._pool is not None:
            return 0.0
        if self._starting is None:
            self._starting = self._spawn(tuple(preload))
        if not wait:
            return 0.0
        pool, started, t0 = self._starting
        self._starting = None
        try:
            for f in started:
                f.result()
        except BaseException:  # Ctrl-C or a worker that died: leave no process behind
            pool.shutdown(wait=False, cancel_futures=True)
            raise
        self._pool = pool
        return time.perf_counter() - t0

    def _spawn(self, preload):
        import multiprocessing
        from concurrent.futures import ProcessPoolExecutor

        import dask

        t0 = time.perf_counter()
        ctx = multiprocessing.get_context(dask.config.get("multiprocessing.context", "spawn"))
        ready = ctx.Barrier(self.workers)
        saved = {k: os.environ.get(k) for k in SINGLE_THREAD_ENV}
        os.environ.update(dict.fromkeys(SINGLE_THREAD_ENV, "1"))  # inherited by the spawned workers
        try:
            pool = ProcessPoolExecutor(self.workers, mp_context=ctx, initializer=_start_worker,
                                       initargs=(ready, preload))
            # One submit per worker spawns them all now (a spawn pool grows on demand).
            started = [pool.submit(os.getpid) for _ in range(self.workers)]
        finally:
            for k, v in saved.items():
                if v is None:
                    os.environ.pop(k, None)
                else:
                    os.environ[k] = v
        return pool, started, t0

    def close(self):
        """Stop the worker processes and the client this Executor started."""
        if self._starting is not None:
            self._starting[0].shutdown(cancel_futures=True)
            self._starting = None
        if self._pool is not None:
            self._pool.shutdown(cancel_futures=True)
            self._pool = None
        if self._own_client and self.client is not None:
            self.client.close()
            self.client = None

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()


def _one_line_warning(message, category, filename, lineno, line=None) -> str:
    """A worker's warning as the command line prints its own: one ``dhfield: warning:`` line, without
    Python's source path and line of code (``warnings.formatwarning`` of a local worker)."""
    return f"dhfield: warning: {' '.join(str(message).split())}\n"


def _start_worker(ready, preload) -> None:
    """Initializer of a local worker process: warnings as one line (:func:`_one_line_warning`), import
    ``preload``, then wait for the other workers."""
    import importlib
    import threading
    import warnings

    warnings.formatwarning = _one_line_warning
    try:
        for name in preload:
            try:
                importlib.import_module(name)
            except ImportError:  # pragma: no cover - a missing optional solver fails in its task, with a message
                pass
        try:
            ready.wait(WORKER_START_TIMEOUT)
        except threading.BrokenBarrierError:  # a slow sibling: start anyway
            pass
    except KeyboardInterrupt:  # Ctrl-C reaches the whole process group: the parent reports it, in one line
        os._exit(130)


def connect(scheduler=None, workers=None) -> Executor:
    """Resolve the scheduler before any work starts.

    Parameters
    ----------
    scheduler : str, distributed.Client or Executor, optional
        None (local processes, or serial when ``workers == 1``), "synchronous",
        "processes", a ``tcp://host:port`` address, a connected Client, or an
        Executor (returned as is).
    workers : int, optional
        Local worker processes, >= 1 (default: every core).

    Returns
    -------
    Executor
        Where the tasks will run.

    Raises
    ------
    ValueError
        Bad ``workers`` or an unreachable scheduler (after :data:`CONNECT_TIMEOUT` s).
    """
    if workers is not None and (isinstance(workers, bool) or not isinstance(workers, int) or workers < 1):
        raise ValueError(f"workers must be an integer >= 1 (local worker processes); got {workers!r}")
    if isinstance(scheduler, Executor):
        return scheduler
    if scheduler is not None and not isinstance(scheduler, str):  # a distributed.Client
        return Executor("distributed", len(scheduler.scheduler_info()["workers"]), scheduler)
    if scheduler is None:
        w = workers or os.cpu_count() or 1
        return Executor("synchronous" if w == 1 else "processes", w)
    if scheduler in _LOCAL:
        w = 1 if scheduler == "synchronous" else (workers or os.cpu_count() or 1)
        return Executor(scheduler, w)
    check_scheduler_address(scheduler)
    probe_scheduler(scheduler)
    from distributed import Client

    try:
        client = Client(scheduler, timeout=CONNECT_TIMEOUT)
    except (OSError, TimeoutError) as exc:
        raise ValueError(f"scheduler {scheduler} is unreachable ({type(exc).__name__} after "
                         f"{CONNECT_TIMEOUT:g} s); start one with 'dask scheduler' or omit --scheduler") from None
    return Executor("distributed", len(client.scheduler_info()["workers"]), client, True)


def probe_scheduler(address: str, timeout: float | None = None) -> None:
    """Check, within ``timeout`` seconds, that a dask scheduler answers at ``address``.

    A dask.distributed scheduler sends its handshake as soon as it accepts a TCP
    connection: an 8-byte length, then frames (a frame count, the frame lengths, the
    msgpack body).  This reads that message on a plain socket with a deadline, and
    refuses a peer that sends nothing (a silent listener, an HTTP server waiting for
    a request), closes, or announces a message larger than :data:`MAX_HANDSHAKE_BYTES`
    (garbage), before :class:`distributed.Client`, whose handshake is unbounded, is
    involved.

    Parameters
    ----------
    address : str
        The scheduler's ``tcp://host:port``.
    timeout : float, optional
        Deadline [s]; default :data:`CONNECT_TIMEOUT`.

    Raises
    ------
    ValueError
        One line naming the address, when no dask scheduler answers.
    """
    import socket
    import struct

    timeout = CONNECT_TIMEOUT if timeout is None else float(timeout)
    host, port = scheduler_host_port(address)
    hint = "start one with 'dask scheduler', or omit --scheduler"

    def fail(why):
        raise ValueError(f"scheduler {address} {why}; {hint}")

    deadline = time.monotonic() + timeout
    try:
        sock = socket.create_connection((host, port), timeout=timeout)
    except (socket.timeout, TimeoutError):
        fail(f"did not accept a connection within {timeout:g} s")
    except OSError as exc:
        fail(f"is unreachable ({exc.strerror or type(exc).__name__})")

    def recv_exact(n):
        buf = bytearray()
        while len(buf) < n:
            left = deadline - time.monotonic()
            if left <= 0:
                raise TimeoutError
            sock.settimeout(left)
            chunk = sock.recv(min(n - len(buf), 65536))
            if not chunk:
                raise ConnectionError("closed")
            buf += chunk
        return bytes(buf)

    with sock:
        try:
            (total,) = struct.unpack("Q", recv_exact(8))
            if not 16 <= total <= MAX_HANDSHAKE_BYTES:
                fail(f"is not a dask scheduler: its first message announces {total} bytes, a dask handshake "
                     f"has 16 to {MAX_HANDSHAKE_BYTES}")
            body = recv_exact(total)
            (n_frames,) = struct.unpack_from("Q", body)
            lengths = struct.unpack_from(f"{n_frames}Q", body, 8) if 1 <= n_frames <= 64 and \
                8 * (n_frames + 1) <= total else None
            if lengths is None or 8 * (n_frames + 1) + sum(lengths) != total:
                fail("is not a dask scheduler: its first message is not a dask handshake")
        except (socket.timeout, TimeoutError):
            fail(f"sent no dask handshake within {timeout:g} s (is it a dask scheduler? a web server or "
                 "another service on that port answers nothing)")
        except OSError as exc:
            fail(f"closed the connection before its dask handshake ({exc.strerror or exc})")


def _output_keys(collection):
    keys = collection.__dask_keys__()
    out = []

    def walk(k):
        if isinstance(k, list):
            for x in k:
                walk(x)
        else:
            out.append(k)

    walk(keys)
    return out


def _compute(collections, executor: Executor, progress: Progress):
    import dask
    from dask.callbacks import Callback

    if executor.kind == "distributed":
        from distributed import as_completed, futures_of

        persisted = executor.client.persist(list(collections))
        for _ in as_completed(futures_of(persisted)):
            progress.advance()
        return dask.compute(*persisted, scheduler=executor.client)
    keys = set()
    for c in collections:
        keys.update(_output_keys(c))

    def posttask(key, result, dsk, state, worker_id):
        if key in keys:
            progress.advance()

    if executor.kind == "processes":
        # chunksize=1: one task per free worker at a time.  dask's multiprocessing default (6)
        # sends tasks in batches of 6 to one worker: of 8 tasks on 2 workers, 6 went to one.
        with Callback(posttask=posttask):
            return dask.compute(*collections, scheduler="processes", pool=executor.pool, chunksize=1)
    from threadpoolctl import threadpool_limits

    with threadpool_limits(1), Callback(posttask=posttask):  # serial: one core, like one worker
        return dask.compute(*collections, scheduler="synchronous")


def map_cases(fn, arguments, *, scheduler=None, workers=None, progress=False) -> list:
    """Compute ``[fn(*args) for args in arguments]`` as dask tasks on a scheduler, in order.

    For studies whose results are Python objects rather than store records (the
    report's BEM loops): one task per argument tuple, so keep the cases of one
    load path in one call of ``fn``.  ``fn`` must be importable by the workers
    (a module-level function).  Nothing is stored: use :func:`run_sweep` for
    resumable studies.

    Parameters
    ----------
    fn : callable
        A module-level function, called once per argument tuple.
    arguments : iterable of tuple
        The positional arguments of each call.
    scheduler : str, distributed.Client or Executor, optional
        See :func:`connect`; default ``$DHFIELD_SCHEDULER``, else "synchronous"
        (in this process).
    workers : int, optional
        See :func:`connect`; default ``$DHFIELD_WORKERS``.
    progress : bool
        Progress bar on stderr.

    Returns
    -------
    list
        The results, in the order of ``arguments``.
    """
    import dask

    if scheduler is None:
        scheduler = os.environ.get(SCHEDULER_ENV) or "synchronous"
    if workers is None and os.environ.get(WORKERS_ENV):
        try:
            workers = int(os.environ[WORKERS_ENV])
        except ValueError:
            raise ValueError(f"${WORKERS_ENV} must be an integer >= 1; got {os.environ[WORKERS_ENV]!r}") from None
    executor = connect(scheduler, workers)
    owned = executor is not scheduler
    tasks = [dask.delayed(fn, pure=False)(*args) for args in arguments]
    bar = Progress(len(tasks), progress)
    try:
        return list(_compute(tasks, executor, bar))
    finally:
        bar.close()
        if owned:
            executor.close()


# --------------------------------------------------------------------------- case records
#: Attributes of the per-point ``warning`` of the analytic pull-off (a string: no units).
_WARNING_ATTRS = {k: v for k, v in schema.attrs("warning").items() if k != "units"}


def _case_dataset(values: dict, status: str, message: str, dims=(), seconds=float("nan")):
    """One case record; ``seconds`` (its wall time) is kept in the case file only, never in the sweep."""
    import xarray as xr

    ds = xr.Dataset({k: (dims, np.asarray(v, dtype=float), {"units": "1"}) for k, v in values.items()})
    ds.attrs.update(status=status, message=message, seconds=float(seconds))
    return ds


def _failure(exc) -> str:
    last = traceback.extract_tb(exc.__traceback__)[-1] if exc.__traceback__ else None
    where = f" ({Path(last.filename).name}:{last.lineno})" if last else ""
    return f"{type(exc).__name__}: {exc}{where}"


def _pull_off_ufunc(mu, beta0, i_ell, i_mu, *, model, control, store_dir, fingerprint):
    """apply_ufunc kernel: one block of the analytic map, read from the store if done."""
    store = CaseStore(store_dir, fingerprint)
    key = f"pull_off__{model}__{int(i_ell.flat[0]):05d}_{int(i_mu.flat[0]):05d}"
    coordinates = case_coordinates(model=model, control=control, beta0=beta0, mu=mu)
    ds = store.load(key, coordinates)
    if ds is not None:
        return np.stack([ds[k].values for k in PULL_OFF_FIELDS], axis=-1)
    try:
        rec = pull_off_block(model, beta0=beta0, mu=mu, control=control)
        out, warnings = block_values(rec), np.asarray(rec.warning, dtype=object)
        status, message = "ok", ""
    except Exception as exc:  # noqa: BLE001 - recorded with its message, the sweep goes on
        out = np.full(mu.shape + (len(PULL_OFF_FIELDS),), np.nan)
        warnings = np.full(mu.shape, "", dtype=object)
        status, message = "failed", _failure(exc)
    ds = _case_dataset({k: out[..., i] for i, k in enumerate(PULL_OFF_FIELDS)}, status, message, ("i", "j"))
    # the records' validity warnings travel through the store (read back by _consolidate):
    # the dask kernel returns numbers only
    ds["warning"] = (("i", "j"), warnings, _WARNING_ATTRS)
    store.write(key, ds, coordinates)
    return out


def _pull_off_warnings(store, models, shape):
    """{model: object array ``shape`` of the stored pull-off blocks' warnings ("" where none)}."""
    out = {m: np.full(shape, "", dtype=object) for m in models}
    for key in store.keys():
        if not key.startswith("pull_off__"):
            continue
        _, model, idx = key.split("__")
        if model not in out:
            continue
        ds = store.read(key)
        if "warning" not in ds:  # a block stored before warnings were kept: none known
            continue
        i0, j0 = (int(t) for t in idx.split("_"))
        w = ds["warning"].values.T  # a block is (mu, ell) (_pull_off_collections' broadcast order)
        out[model][i0:i0 + w.shape[0], j0:j0 + w.shape[1]] = w
    return out


def _gather(records, fields, shape, status_shape=None):
    """Arrays of ``fields`` (NaN where no case), status codes and messages of finished cases.

    ``records`` maps a case key ``<quantity>__<i>_<j>_...`` to ``(record, status, message,
    computed)``; the indices in the key place each case.  The status and messages have
    ``status_shape`` (default ``shape``; a load curve's points share one status).
    """
    status_shape = shape if status_shape is None else status_shape
    values = {k: np.full(shape, np.nan) for k in fields}
    status = np.zeros(status_shape, dtype=np.int8)
    messages = np.full(status_shape, "", dtype=object)
    for key, (rec, st, message, _) in records.items():
        idx = tuple(int(t) for t in key.split("__")[1].split("_"))
        for k in fields:
            values[k][idx] = rec[k]
        status[idx] = _STATUS[st]
        messages[idx] = message
    return values, status, messages


def _gather_text(records, fields, shape):
    """Object arrays of ``shape`` of the text ``fields`` of finished cases ("" where none)."""
    out = {k: np.full(shape, "", dtype=object) for k in fields}
    for key, (rec, _, _, _) in records.items():
        idx = tuple(int(t) for t in key.split("__")[1].split("_"))
        for k in fields:
            out[k][idx] = str(rec.get(k, ""))
    return out


def _run_cases(quantity, cases, store_dir, fingerprint, command=""):
    """One task: the cases of one load path, in order; each written as it finishes."""
    store = CaseStore(store_dir, fingerprint)
    fields = _FIELDS[quantity]
    text_fields = _TEXT_FIELDS.get(quantity, ())
    dims = ("point",) if quantity == "load_curve" else ()
    out = {}
    for key, params in cases:
        # the time allowed decides only whether a case is refused (not in the fingerprint either)
        coordinates = case_coordinates(quantity=quantity, **{k: v for k, v in params.items() if k != "max_seconds"})
        ds = store.load(key, coordinates)
        if ds is not None:
            # A field added after the case was stored reads as NaN (the case is not recomputed).
            rec = {k: ds[k].values if k in ds else np.nan for k in fields}
            rec.update({k: str(ds.attrs.get(f"case_{k}", "")) for k in text_fields})
            out[key] = (rec, ds.attrs["status"], ds.attrs["message"], False)
            continue
        t0 = time.perf_counter()
        try:
            if quantity == "bem_field":
                rec = bem_field_case(**params)
                status, message = "ok", ""
            elif quantity == "load_curve":
                rec = load_curve_case(**params)
                status, message = "ok", ""
            else:
                rec = adhesive_case(**params)
                converged, resolved = bool(rec["converged"]), bool(rec.get("resolved", True))
                rec["converged"], rec["resolved"] = float(converged), float(resolved)
                message = rec.pop("message")
                status = "ok" if converged and resolved else "not_converged" if not converged else "unresolved"
                if converged and not resolved:   # an unconverged case has its own reason
                    message = "; ".join(m for m in (message, UNRESOLVED_MESSAGE) if m)
        except Exception as exc:  # noqa: BLE001 - recorded with its message, the sweep goes on
            shape = (len(params["a_star"]),) if dims else ()
            rec = {k: np.full(shape, np.nan) for k in fields}
            status, message = "failed", _failure(exc)
            if text_fields:
                from .tasks import _git_commit

                rec.update(commit=_git_commit(), finished=time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime()))
        seconds = time.perf_counter() - t0
        if "wall_seconds" in fields and not np.isfinite(rec["wall_seconds"]):  # a failed case: its time to fail
            rec["wall_seconds"] = seconds
        text = {k: str(rec.get(k, "")) for k in text_fields}
        if text_fields:
            text["command"] = command
        case = _case_dataset({k: rec[k] for k in fields}, status, message, dims, seconds)
        case.attrs.update({f"case_{k}": v for k, v in text.items()})
        store.write(key, case, coordinates)
        out[key] = ({**{k: np.asarray(rec[k], dtype=float) for k in fields}, **text}, status, message, True)
    return out


# --------------------------------------------------------------------------- planning
def _chunks(shape, target):
    """Chunk sizes of a 2-D (ell, mu) grid with about ``target`` points per block."""
    n_ell, n_mu = shape
    c_mu = min(n_mu, target)
    c_ell = max(1, min(n_ell, target // c_mu))
    return c_ell, c_mu


def _pull_off_collections(config: SweepConfig, store_dir, fingerprint):
    import xarray as xr

    beta0 = config.beta0
    mu = np.asarray(config.axes["mu"], dtype=float)
    c_ell, c_mu = _chunks((beta0.size, mu.size), config.chunk_points)
    g_mu = xr.DataArray(mu, dims="mu").chunk({"mu": c_mu})
    g_b = xr.DataArray(beta0, dims="ell").chunk({"ell": c_ell})
    i_mu = xr.DataArray(np.arange(mu.size), dims="mu").chunk({"mu": c_mu})
    i_b = xr.DataArray(np.arange(beta0.size), dims="ell").chunk({"ell": c_ell})
    g_mu, g_b, i_mu, i_b = xr.broadcast(g_mu, g_b, i_mu, i_b)
    out = {}
    for model in config.models:
        out[model] = xr.apply_ufunc(
            _pull_off_ufunc, g_mu, g_b, i_b, i_mu,
            kwargs=dict(model=model, control=config.control, store_dir=str(store_dir), fingerprint=fingerprint),
            output_core_dims=[["field"]], dask="parallelized", output_dtypes=[float],
            dask_gufunc_kwargs={"output_sizes": {"field": len(PULL_OFF_FIELDS)}}).transpose("ell", "mu", "field")
    return out


def _case_index(config: SweepConfig, quantity):
    """(index tuple, params) of every case of a BEM quantity, grouped by load path."""
    beta0 = config.beta0
    mu = config.axes["mu"]
    groups = []
    if quantity == "load_curve":
        a_star = np.linspace(*config.curve_a_star, config.curve_points)
        for i_m, model in enumerate(config.models):
            for ib, b in enumerate(beta0):
                groups.append([((i_m, ib, im), dict(model=model, beta0=float(b), mu=float(m), a_star=a_star))
                               for im, m in enumerate(mu)])
    elif quantity == "bem_field":
        a_star, ns = config.axes["a_star"], config.axes["n"]
        for ib, b in enumerate(beta0):
            for im, m in enumerate(mu):
                for i_n, n in enumerate(ns):
                    groups.append([((ib, im, ia, i_n), dict(beta0=float(b), mu=float(m), a_star=float(a), n=int(n),
                                                            half_width=config.half_width, sampling=config.sampling))
                                   for ia, a in enumerate(a_star)])
    else:
        grid_axis = config.adhesive_grid_axis   # "n" (explicit n x n) or "grid_level" (the automatic grid)
        grids, laws = config.axes[grid_axis], config.axes["law"]
        # the time allowed per case goes to adhesive_case only when the config sets one (None: the library's)
        allowed = {} if config.max_seconds is None else {"max_seconds": float(config.max_seconds)}
        for ib, b in enumerate(beta0):
            for im, m in enumerate(mu):
                for i_n, g in enumerate(grids):
                    for il, law in enumerate(laws):
                        groups.append([((ib, im, i_n, il), {"beta0": float(b), "mu": float(m), grid_axis: int(g),
                                                            "law": law, "control": config.control, **allowed})])
    return groups


def case_key(quantity, idx) -> str:
    """Key of a case in a sweep's case store: ``<quantity>__<i>_<j>_...`` (its indices along the axes, 5 digits).

    Parameters
    ----------
    quantity : str
        One of :data:`dhfield.sweep.config.QUANTITIES`.
    idx : sequence of int
        The case's index along each axis of the quantity, in the order of the output's dims
        (adhesive: beta0, mu, n or grid_level, law).

    Returns
    -------
    str
        The file stem under which :class:`dhfield.sweep.store.CaseStore` keeps the case.
    """
    return f"{quantity}__" + "_".join(f"{int(i):05d}" for i in idx)


# --------------------------------------------------------------------------- result
@dataclass
class SweepResult:
    """Outcome of :func:`run_sweep`.

    Parameters
    ----------
    dataset : xarray.Dataset
        The consolidated sweep (dims: the swept axes).
    path : pathlib.Path or None
        Where it was written.
    computed, reused : list of str
        Keys of the cases computed by this run and of those read back from the store.
    failed : list of str
        Keys of the cases that raised (recorded with their message).
    flagged : list of str
        Keys of the BEM cases stored with a result that is not an answer: status
        "not_converged" or "unresolved" (with their message).
    warned : int
        Number of analytic pull-off points (model, beta0, mu) whose record carries a
        validity warning (the ``warning`` variable; :mod:`dhfield.analysis.validity`).
    """

    dataset: object
    path: Path | None
    computed: list = field(default_factory=list)
    reused: list = field(default_factory=list)
    failed: list = field(default_factory=list)
    flagged: list = field(default_factory=list)
    warned: int = 0


def run_sweep(config: SweepConfig, *, out=None, scheduler=None, workers=None, progress=None) -> SweepResult:
    """Run (or resume) a sweep and write the consolidated Dataset.

    Parameters
    ----------
    config : SweepConfig
        What to sweep.
    out : path, optional
        Output (see :func:`dhfield.sweep.store.output_paths`); default ``config.out``.
    scheduler : str, distributed.Client or Executor, optional
        See :func:`connect`; default ``config.scheduler``.  An Executor is
        left running (its owner closes it); anything else is closed on return.
    workers : int, optional
        Local worker processes; default ``config.workers`` or every core.
    progress : bool, optional
        Progress bar on stderr; default: when stderr is a terminal.

    Returns
    -------
    SweepResult
        The consolidated Dataset and which cases were computed, reused, failed or flagged.
    """
    out = out if out is not None else config.out
    if out is None:
        raise ValueError("out must be given (an output .nc file or directory)")
    final, store_dir = output_paths(out)
    from ..io import SignalExit, check_writable

    check_output(out)
    check_sweep_memory(config, _concurrent_cases(scheduler if scheduler is not None else config.scheduler,
                                                 workers if workers is not None else config.workers))
    if Path(out).suffix.lower() != ".nc" and Path(out).parent.is_dir() and not Path(out).exists():
        Path(out).mkdir()
    check_writable(final)
    executor = connect(scheduler if scheduler is not None else config.scheduler,
                       workers if workers is not None else config.workers)
    owned = executor is not scheduler
    store = None
    try:
        executor.start(preload=_preload(config), wait=False)  # workers start while this process prepares
        if "adhesive" in config.quantities:
            adhesive_solver()
        fp = config.fingerprint()
        store = CaseStore(store_dir, fp, manifest={"config": config.as_dict()})
        before = len(store.keys())
        return _run(config, executor, store, final, progress)
    except (KeyboardInterrupt, SignalExit) as exc:   # what the interrupted run left behind, in its message
        exc.add_note(_interrupted_note(store, final, None if store is None else before))
        raise
    finally:
        if owned:
            executor.close()


def check_output(out) -> None:
    """Refuse an output path a sweep cannot use, before anything is created (ValueError, one line).

    ``out`` is either ``FILE.nc`` (cases in ``FILE.nc.cases/``) or a directory: an
    existing one, or a new name without a file suffix (``x.txt`` is refused rather than
    made a directory).  Symbolic links are refused for the directory and the case
    store as for every output (:func:`dhfield.io.validate_output_path`).

    Parameters
    ----------
    out : path-like
        The sweep's output path (:func:`dhfield.sweep.store.output_paths`).

    Raises
    ------
    ValueError
        Naming ``out`` and what it must be.
    """
    import os

    text = os.fspath(out)
    p = Path(text)
    if p.suffix.lower() != ".nc":
        if p.is_symlink():
            raise ValueError(f"out (output directory) must not be a symbolic link (dhfield does not write through "
                             f"links; name its target {os.path.realpath(p)!r} instead); got {text!r}")
        if p.exists() and not p.is_dir():
            raise ValueError(f"out (output path) must be FILE.nc or a directory; {text!r} exists and is not a "
                             "directory")
        if not p.exists() and p.suffix:
            raise ValueError(f"out (output path) must end in .nc (one netCDF file, cases in FILE.nc.cases/) or "
                             f"name a directory (an existing one, or a new name without a suffix); got {text!r}")
    store = output_paths(p)[1]
    if store.is_symlink():
        raise ValueError(f"out: the case store must not be a symbolic link (dhfield does not write through links; "
                         f"name its target {os.path.realpath(store)!r} instead); got {str(store)!r}")


def _concurrent_cases(scheduler, workers) -> int:
    """How many cases run at once in this machine's memory: local workers (1 serially or on a cluster)."""
    if isinstance(scheduler, Executor):
        return scheduler.workers if scheduler.kind == "processes" else 1
    if scheduler is None or scheduler == "processes":
        w = workers or os.cpu_count() or 1
        return int(w) if isinstance(w, int) and not isinstance(w, bool) and w >= 1 else 1
    return 1   # "synchronous", or a cluster's workers: each case checks its own worker's memory


def check_sweep_memory(config: SweepConfig, concurrent: int = 1) -> None:
    """Refuse a sweep whose adhesive BEM cases would not fit the memory available, before anything starts.

    The adhesive cases on an explicit ``n`` axis are planned with the solver's estimate
    (:func:`dhfield.analysis.bem_start.pull_off_cost` of the largest n), times the cases that
    run at once; the limit is :func:`dhfield.core.memory.memory_limit` (80 % of the memory
    available now).  Each case is checked again by the solver before it allocates
    (:func:`dhfield.analysis.bem_start.check_grid_memory`), and the automatic grids of the
    ``grid_level`` axis by their plan.

    Parameters
    ----------
    config : SweepConfig
        The sweep.
    concurrent : int, default 1
        Cases that run at once on this machine (local worker processes) [-].

    Raises
    ------
    ValueError
        One line naming ``axes.n``, the estimate and the limit.
    """
    if "adhesive" not in config.quantities or "n" not in config.axes:
        return
    from ..core.memory import check_memory
    from ..analysis.bem_start import pull_off_cost

    n = max(config.axes["n"])
    cases = config.beta0.size * len(config.axes["mu"]) * len(config.axes.get("law", ("",)))
    k = max(1, min(int(concurrent), cases))
    what = f"axes.n = {n} (the adhesive BEM on a {n} x {n} grid" + (f", {k} cases at once" if k > 1 else "") + ")"
    try:
        check_memory(k * pull_off_cost(n, n)[0], what)
    except ValueError as exc:
        hint = "run fewer workers (--workers, run.workers) or choose a smaller n" if k > 1 else "choose a smaller n"
        raise ValueError(f"{exc}; {hint}") from None


def _interrupted_note(store, final, before) -> str:
    """What an interrupted sweep left: the cases stored (resumable) and whether the consolidated file was written."""
    if store is None:
        return "no case was stored and the consolidated file was not written"
    try:
        stored = len(store.keys())
    except Exception:  # noqa: BLE001 - a note must not hide the interrupt
        return f"the finished cases are kept in {str(store.directory)!r}; run the same sweep again to resume"
    from ..io import written_files

    wrote = Path(final) in written_files()
    new = stored - (before or 0)
    return (f"{stored} finished case(s) are stored in {str(store.directory)!r} ({new} of them by this run); "
            + (f"{str(final)!r} was written" if wrote else f"{str(final)!r} was not written")
            + ": run the same sweep again (same config and output path) to resume")


def _preload(config) -> tuple:
    """Modules the workers of ``config``'s sweep import at start-up (:data:`QUANTITY_MODULES`)."""
    return tuple(dict.fromkeys(m for q in config.quantities for m in QUANTITY_MODULES.get(q, ())))


def _run(config, executor, store, final, progress):
    from ..io import write_netcdf

    fp = store.fingerprint
    collections, kinds = [], []
    if "pull_off" in config.quantities:
        maps = _pull_off_collections(config, store.directory, fp)
        for model, arr in maps.items():
            collections.append(arr.data)
            kinds.append(("pull_off", model))
    import dask

    command = shlex.join(sys.argv)   # provenance of each case computed by this run
    backend = os.environ.get("DHFIELD_BEM_BACKEND", "").strip()
    if backend:                      # the BEM's array backend (dhfield.bem.backend) is part of how it ran
        command = f"DHFIELD_BEM_BACKEND={shlex.quote(backend)} {command}"
    tasks = []
    for q in ("load_curve", "bem_field", "adhesive"):
        if q in config.quantities:
            for group in _case_index(config, q):
                cases = [(case_key(q, idx), params) for idx, params in group]
                cost = sum(0.0 if store.is_done(key) else expected_seconds(q, params) for key, params in cases)
                tasks.append((cost, q, cases))
    # Longest-processing-time order: dask's schedulers start ready tasks of equal standing in
    # decreasing key order, so each task's key leads with its rank by expected cost (costliest
    # first; cases finished by an earlier run cost nothing), and dask hands them to workers as
    # they free up.  Ties keep the grid order.
    by_cost = sorted(range(len(tasks)), key=lambda i: -tasks[i][0])
    rank = {i: len(tasks) - 1 - r for r, i in enumerate(by_cost)}
    for i, (_, q, cases) in enumerate(tasks):
        collections.append(dask.delayed(_run_cases, pure=False)(
            q, cases, str(store.directory), fp, command, dask_key_name=f"case-{rank[i]:07d}-{cases[0][0]}"))
        kinds.append((q, [key for key, _ in cases]))
    total = sum(len(_output_keys(c)) for c in collections)
    enabled = sys.stderr.isatty() if progress is None else bool(progress)
    executor.start(preload=_preload(config))
    bar = Progress(total, enabled)
    before = set(store.keys())
    try:
        results = _compute(collections, executor, bar)
    finally:
        bar.close()
    ds = _consolidate(config, kinds, results, store)
    after = set(store.keys())
    failed = sorted(k for k in (p.name[:-len(".failed.nc")] for p in store.directory.glob("*.failed.nc"))
                    if store.matches(k, failed=True))
    flagged = sorted(key for (kind, _), res in zip(kinds, results) if kind != "pull_off"
                     for key, (_, st, _, _) in res.items() if st in ("not_converged", "unresolved"))
    write_netcdf(ds, final)
    warned = 0
    if "warning" in ds:  # the pull-off is broadcast over the adhesive BEM's n and law: count it once
        w = ds["warning"].isel({d: 0 for d in ("n", "grid_level", "law") if d in ds["warning"].dims})
        warned = int(np.count_nonzero(w.values != ""))
    return SweepResult(ds, final, computed=sorted(after - before), reused=sorted(before), failed=failed,
                       flagged=flagged, warned=warned)


# --------------------------------------------------------------------------- consolidation
_N_ATTRS = {"long_name": "BEM cells per side", "units": "1"}
_GRID_LEVEL_ATTRS = {"long_name": "grid level of the adhesive BEM: 1 the automatic grid and route (as dhfield solve "
                     "without --n), k the explicit grid of k times its cells per axis", "units": "1"}
#: Per-case numbers of the adhesive BEM beside its outputs (:data:`ADHESIVE_GRID_FIELDS`).
_ADHESIVE_GRID_ATTRS = {
    "nx": ("BEM cells along x of the adhesive case", "1"),
    "ny": ("BEM cells along y of the adhesive case", "1"),
    "half_width_x": ("domain half-width along x of the adhesive case, in c_r", "1"),
    "half_width_y": ("domain half-width along y of the adhesive case, in c_r", "1"),
    "W_star_error": ("stated error of the adhesive BEM's W_star (search + discretisation; inf: no estimate or "
                     "not resolved)", "1"),
    "converged": ("1 when every state of the adhesive case's load path down to the pull-off converged", "1"),
    "resolved": ("1 when the adhesive case's grid resolves its cohesive zone and contact", "1"),
    "n_steps": ("states solved on the adhesive case's load path", "1"),
    "wall_seconds": ("wall time of the adhesive case (shared machines: load varies)", "s"),
    "cpu_seconds": ("CPU time of the adhesive case's process", "s"),
}
_ADHESIVE_TEXT_ATTRS = {
    "search": "route that gave the adhesive pull-off (the solver's search: located, bracket, march, predicted, ...)",
    "note": "caveats of the adhesive BEM solver on the case (empty: none)",
    "commit": "git commit of the code that solved the adhesive case",
    "finished": "UTC time the adhesive case finished",
    "solver_options": "Newton options of every state of the adhesive case, as JSON (empty: not recorded)",
    "command": "command line of the sweep run that solved the adhesive case",
}
_LAW_ATTRS = {"long_name": "cohesive law of the adhesive BEM solver"}  # a string label has no units
_BEM_ATTRS = {
    "bem_displacement_error": ("max |omega_BEM - omega_Eq26| over the grid / max |omega| (forward BEM check)", "1"),
    "bem_gap_error": ("max |h_BEM - h_Eq27| over the grid / max |omega| (forward BEM check)", "1"),
    "bem_annulus_error": ("worst relative error of h = (1 + v) h_Hertz in the adhesive annulus (Eq. 27)", "1"),
    "bem_c_star": ("adhesive semi-major axis c/c_r of the checked DH state (Eqs. 24, 31)", "1"),
    "bem_v": ("double-Hertz scaling factor v of the checked DH state (Eq. 24)", "1"),
}


def _status_attrs(what):
    return {"long_name": f"status of the {what} case",  # CF flags (section 3.5): no units
            "flag_values": np.array(list(STATUS_MEANINGS), dtype=np.int8),
            "flag_meanings": " ".join(STATUS_MEANINGS.values())}


def _consolidate(config: SweepConfig, kinds, results, store):
    import xarray as xr

    from ..io import provenance_attrs

    ell = config.ellipticity_axis
    beta0 = config.beta0
    coords = {"mu": ("mu", np.asarray(config.axes["mu"]), schema.attrs("mu"))}
    if ell == "beta0":
        coords["beta0"] = ("beta0", beta0, schema.attrs("beta0"))
    else:
        coords["skew_angle_deg"] = ("skew_angle_deg", np.asarray(config.axes["skew_angle_deg"]),
                                    schema.attrs("skew_angle_deg"))
        coords["beta0"] = ("skew_angle_deg", beta0, schema.attrs("beta0"))
    if "a_star" in config.axes:
        coords["a_star"] = ("a_star", np.asarray(config.axes["a_star"]), schema.attrs("a_star", True))
    if "n" in config.axes:
        coords["n"] = ("n", np.asarray(config.axes["n"], dtype=np.int32), _N_ATTRS)
    if "grid_level" in config.axes:
        coords["grid_level"] = ("grid_level", np.asarray(config.axes["grid_level"], dtype=np.int32),
                                _GRID_LEVEL_ATTRS)
    if "law" in config.axes:
        coords["law"] = ("law", np.asarray(config.axes["law"], dtype=object), _LAW_ATTRS)
    models = list(config.models) if {"pull_off", "load_curve"} & set(config.quantities) else []
    if "adhesive" in config.quantities:
        models.append(ADHESIVE_MODEL)
    if models:
        coords["model"] = ("model", np.asarray(models, dtype=object),
                           {k: v for k, v in schema.attrs("model").items() if k != "units"})
    n_ell, n_mu = beta0.size, len(config.axes["mu"])
    data = {}
    extra = (config.adhesive_grid_axis, "law") if "adhesive" in config.quantities else ()
    ex_shape = tuple(len(config.axes[d]) for d in extra)
    if models:
        mdims = ("model", ell, "mu") + extra
        mvars = {k: np.full((len(models), n_ell, n_mu) + ex_shape, np.nan) for k in PULL_OFF_FIELDS}
        mstatus = np.zeros((len(models), n_ell, n_mu) + ex_shape, dtype=np.int8)
    blocks_msgs = []
    cases = {q: {} for q in ("load_curve", "bem_field", "adhesive")}
    for (kind, what), res in zip(kinds, results):
        if kind == "pull_off":
            m = models.index(what)
            arr = np.asarray(res)
            for i, k in enumerate(PULL_OFF_FIELDS):
                mvars[k][m] = arr[..., i].reshape((n_ell, n_mu) + (1,) * len(extra))
        else:
            cases[kind].update(res)
    if "pull_off" in config.quantities:
        for p in sorted(store.directory.glob("pull_off__*.failed.nc")):
            key = p.name[:-len(".failed.nc")]
            if not store.matches(key, failed=True):   # a record of another config: not this sweep's
                continue
            ds = store.read(key)
            _, model, idx = key.split("__")
            i0, j0 = (int(t) for t in idx.split("_"))
            shp = ds["W_star"].shape[::-1]  # a block is (mu, ell): _pull_off_collections' broadcast order
            mstatus[models.index(model), i0:i0 + shp[0], j0:j0 + shp[1]] = _STATUS["failed"]
            blocks_msgs.append(f"{model} block {ell}[{i0}:{i0 + shp[0]}] mu[{j0}:{j0 + shp[1]}]: "
                               f"{ds.attrs['message']}")
    if "adhesive" in config.quantities:
        m = models.index(ADHESIVE_MODEL)
        adims = (ell, "mu") + extra
        ashape = (n_ell, n_mu) + ex_shape
        avars, mstatus[m], amsg = _gather(cases["adhesive"], _FIELDS["adhesive"], ashape)
        for k in ADHESIVE_FIELDS:
            if k in mvars:
                mvars[k][m] = avars[k]
        from ..core.geometry import sin_skew_angle

        mvars["sin_skew"][m] = np.asarray(sin_skew_angle(beta0), dtype=float).reshape((n_ell,) + (1,) * (
            1 + len(extra)))
        data["iterations"] = (adims, avars["iterations"], schema.attrs("iterations"))
        for k in ADHESIVE_BEM_FIELDS:
            data[k] = (adims, avars[k], schema.attrs(k, nondimensional=True))
        data["adhesive_message"] = (adims, amsg, {"long_name": "message of the adhesive BEM solve (empty: ok)"})
        for k, (ln, u) in _ADHESIVE_GRID_ATTRS.items():
            v = avars[k]
            if k in ("converged", "resolved"):  # flags: -1 where no case was stored
                v = np.where(np.isnan(v), -1, v).astype(np.int8)
            data[k] = (adims, v, {"long_name": ln, "units": u})
        for k, text in _gather_text(cases["adhesive"], _TEXT_FIELDS["adhesive"], ashape).items():
            data[f"adhesive_{k}"] = (adims, text, {"long_name": _ADHESIVE_TEXT_ATTRS[k]})
    if "load_curve" in config.quantities:
        cdims = ("model", ell, "mu", "point")
        cshape = (len(models), n_ell, n_mu, config.curve_points)
        cvars, cstatus, cmsg = _gather(cases["load_curve"], CURVE_FIELDS, cshape, cshape[:-1])
        coords["curve_a_star"] = ("point", np.linspace(*config.curve_a_star, config.curve_points),
                                  {**schema.attrs("a_star", True), "long_name": "contact semi-major axis a/c_r "
                                   "of the load-curve points"})
        for k in CURVE_FIELDS:
            attrs = schema.attrs(k, nondimensional=True)
            data[f"curve_{k}"] = (cdims, cvars[k], {**attrs, "long_name": f"{attrs['long_name']}, along the "
                                                    "load curve"})
        data["load_curve_status"] = (cdims[:-1], cstatus, _status_attrs("load-curve"))
        data["load_curve_message"] = (cdims[:-1], cmsg, {"long_name": "message of the load-curve case (empty: ok)"})
    if {"pull_off", "adhesive"} & set(config.quantities):
        for k in PULL_OFF_FIELDS:
            data[k] = (mdims, mvars[k], schema.attrs(k, nondimensional=True))
        warning = np.full(mvars["W_star"].shape, "", dtype=object)
        if "pull_off" in config.quantities:
            for model, w in _pull_off_warnings(store, config.models, (n_ell, n_mu)).items():
                warning[models.index(model)] = w.reshape((n_ell, n_mu) + (1,) * len(extra))
        data["warning"] = (mdims, warning, _WARNING_ATTRS)
        st_attrs = _status_attrs("pull-off")
        if blocks_msgs:
            st_attrs["messages"] = "; ".join(blocks_msgs)
        data["status"] = (mdims, mstatus, st_attrs)
    if "bem_field" in config.quantities:
        bdims = (ell, "mu", "a_star", "n")
        bshape = (n_ell, n_mu, len(config.axes["a_star"]), len(config.axes["n"]))
        bvars, bstatus, bmsg = _gather(cases["bem_field"], BEM_FIELD_FIELDS, bshape)
        for k, (ln, u) in _BEM_ATTRS.items():
            data[k] = (bdims, bvars[k], {"long_name": ln, "units": u})
        data["bem_field_status"] = (bdims, bstatus, _status_attrs("forward BEM"))
        data["bem_field_message"] = (bdims, bmsg, {"long_name": "message of the forward BEM case (empty: ok)"})
    ds = xr.Dataset(data, coords=coords)
    ds = ds.transpose(*schema.order_dims(ds.dims))  # one pass over every variable (no per-variable merge)
    for c in ds.coords:
        ds[c].encoding["_FillValue"] = None
    allowed = {}
    if "adhesive" in config.quantities:   # the time allowed per adhesive case by this run [s]
        from ..analysis.bem_start import DEFAULT_MAX_SECONDS

        allowed["bem_max_seconds"] = float(DEFAULT_MAX_SECONDS if config.max_seconds is None else config.max_seconds)
        allowed["bem_adhesive_route"] = ADHESIVE_ROUTE
    ds.attrs.update(provenance_attrs("dhfield sweep (Zini et al. 2018 extended double-Hertz model)",
                                     sweep_fingerprint=config.fingerprint(),
                                     sweep_quantities=" ".join(config.quantities), control=config.control,
                                     chunk_points=config.chunk_points,
                                     bem_half_width=config.half_width, bem_sampling=config.sampling, **allowed))
    return ds
