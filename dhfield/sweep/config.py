"""Sweep configuration: one validated, immutable description of a study.

A sweep is a grid of model inputs (the *axes*) and a list of *quantities*
computed at every grid point.  It is read from a TOML file
(:func:`load_config`), from a mapping of the same shape
(:func:`config_from_mapping`), or built by the command line's flag form.
Everything is validated here, before any work starts: an unknown key, an
out-of-range value or an empty axis raises one ``ValueError`` naming the key
and its valid range.

TOML layout (every table and key optional except ``[axes]``)::

    [sweep]
    quantities = ["pull_off"]          # pull_off, load_curve, bem_field, adhesive
    models = ["dh-elliptic", "md"]     # pull_off, load_curve: any of dhfield.analysis.compare.MODEL_NAMES
    curve_a_star = [0.02, 3.0]         # load_curve: contact sizes a/c_r from, to (evenly spaced)
    curve_points = 200                 # load_curve: points per curve
    control = "load"                   # or "displacement"
    chunk_points = 2048                # analytic grid points per dask task

    [axes]                             # a list, or {linspace|geomspace = [start, stop, num]}
    beta0 = [0.8, 0.9, 1.0]            # or skew_angle_deg = {linspace = [30, 90, 7]}
    mu = {geomspace = [0.1, 10, 200]}
    a_star = [0.5, 1.0]                # bem_field: contact semi-major axis a/c_r
    n = [256]                          # bem_field, adhesive: BEM cells per side
    grid_level = [1, 2]                # adhesive (instead of n): 1 = the automatic grid, k = k x its cells per axis
    law = ["dugdale"]                  # adhesive: cohesive law

    [bem]
    half_width = 3.0                   # fixed domain half-width [c_r] (default 1.5 c* per case)
    sampling = "average"               # or "centre"
    max_seconds = 3600                 # adhesive: estimated time allowed per case [s] (default 1800 s)

    [run]
    workers = 2                        # default: every core
    scheduler = "tcp://127.0.0.1:8786" # a dask.distributed scheduler (default: local processes)
    out = "sweep.nc"

Axes and quantities
-------------------
==============  ===========================================  ==========================
axis            meaning                                      used by
==============  ===========================================  ==========================
beta0           Hertz ellipticity b/a in (0, 1] (Eq. 9)      every quantity
skew_angle_deg  crossing angle in (0, 90] degrees (replaces  every quantity
                beta0; beta0 from Eqs. 3-4)
mu              Tabor parameter > 0 (Eq. 35)                 every quantity
a_star          contact semi-major axis a/c_r > 0 (Eq. 32)   bem_field
n               BEM cells per side, even, in [16, 8192]      bem_field, adhesive
grid_level      integer in [1, 4]: 1 the adhesive BEM's      adhesive (instead of n)
                automatic grid, k: k x its cells per axis
law             cohesive law of the adhesive BEM solver      adhesive
==============  ===========================================  ==========================

The ``adhesive`` quantity takes ``n`` (explicit n x n grids) or ``grid_level``, not
both.  ``grid_level = 1`` solves each case as ``dhfield solve`` without ``--n``: on the
grid and route :func:`dhfield.analysis.bem_start.adhesive_pull_off` plans from the expected
cohesive-zone width (nx x ny with about square cells below beta0 = 0.45); for the Dugdale
law under load control that is the Newton route, which solves the answer's grid and a check
grid itself and states the error from the two.  ``grid_level = k >= 2`` solves the
explicit grid of k times the cells per axis of that plan (:func:`dhfield.sweep.tasks.automatic_grid`)
by the same route, so ``grid_level = [1, 2]`` is the convergence over N of every case in one
sweep.  The adhesive route is in the fingerprint (:data:`ADHESIVE_ROUTE`): a store of the
path routes' answers (before 2026-12-02) is not resumed.

``[bem] max_seconds`` (``--max-seconds``) is the estimated time an adhesive case may take
[s], > 0 (default :data:`dhfield.analysis.bem_start.DEFAULT_MAX_SECONDS`): a level k >= 2
whose grid is estimated to take longer is refused before solving
(:func:`dhfield.sweep.tasks.adhesive_case`), and level 1 is planned with it
(:class:`dhfield.analysis.bem_start.AdhesiveOptions`); a case that is solved is not stopped when it
runs longer than its estimate (no wall-clock limit).  It decides only whether a case is refused,
never its value, so it is not part of the config's fingerprint: a refused case is stored as
failed, and a rerun with a larger ``max_seconds`` (the flag also overrides a config file's)
resumes the same store and solves it.

``[bem] widest_edge`` and ``[bem] base_lattice`` were removed on 2026-12-02 with the path
routes' rescue layers they chose (the Dugdale edge held at 2 h0, the retry lattices): a file
that sets either is refused with a line that says so.  Stored sweep outputs that recorded them
(attributes ``param_bem_widest_edge``, ``param_bem_base_lattice``) stay readable.

``pull_off`` (analytic, every model of :data:`dhfield.analysis.compare.MODEL_NAMES`)
reports ``a_star`` (the contact size at pull-off) as an output variable, so it
cannot share a sweep with an ``a_star`` axis.  ``load_curve`` (every model of
:data:`dhfield.analysis.compare.CURVE_MODEL_NAMES`) gives ``curve_W_star``,
``curve_delta_star``, ``curve_c_star``, ``curve_v`` on the dimension ``point``
of the shared contact sizes ``curve_a_star``.
"""
from __future__ import annotations

import hashlib
import json
import math
import re
import sys
from dataclasses import dataclass
from pathlib import Path

import numpy as np

__all__ = ["SweepConfig", "QUANTITIES", "AXES", "load_config", "config_from_mapping", "axis_values",
           "check_scheduler_address", "MAX_POINTS", "MAX_GRID_LEVEL", "max_workers",
           "MAX_CONFIG_BYTES", "DEFAULT_SCHEDULER_PORT", "cohesive_laws"]

#: Quantities a sweep can compute.
QUANTITIES = ("pull_off", "load_curve", "bem_field", "adhesive")
#: Axes a sweep can span, in the canonical order of the output (:data:`dhfield.core.schema.DIM_ORDER`).
AXES = ("skew_angle_deg", "beta0", "mu", "a_star", "n", "grid_level", "law")
#: Axes each quantity depends on (other axes broadcast).
QUANTITY_AXES = {
    "pull_off": ("skew_angle_deg", "beta0", "mu"),
    "load_curve": ("skew_angle_deg", "beta0", "mu"),
    "bem_field": ("skew_angle_deg", "beta0", "mu", "a_star", "n"),
    "adhesive": ("skew_angle_deg", "beta0", "mu", "n", "grid_level", "law"),
}
#: Largest number of grid points of one sweep (guards against a typo like 1e9 points).
MAX_POINTS = 10_000_000
#: Largest BEM grid (cells per side) a sweep accepts; 8192^2 cells need ~4 GiB per worker.
MAX_BEM_CELLS = 8192
_MIN_BEM_CELLS = 16
#: Finest grid level of the adhesive quantity: k^2 times the cells of the automatic grid
#: (level 4 is 16x its cells and memory; beyond, a case would not fit a worker).
MAX_GRID_LEVEL = 4
#: The adhesive quantity's default route, in the fingerprint of every sweep that has it: the
#: Newton route (:func:`dhfield.analysis.bem_start.takes_newton_route`) replaced the path routes as
#: the default of the Dugdale law under load control, so a store of their answers is not resumed.
ADHESIVE_ROUTE = "newton"

#: ``[bem]`` keys removed, and why (a file that sets one is refused with this reason).
_REMOVED_BEM_KEYS = {
    "widest_edge": "removed on 2026-12-02 with the path routes' rescue layers (the Newton route, the default of "
                   "the adhesive quantity, solves the Dugdale law as it is); delete the key",
    "base_lattice": "removed on 2026-12-02 with the path routes' retry lattices (the Newton route solves "
                    "every grid level on k times the plan); delete the key",
}
_SAMPLINGS = ("average", "centre")
_CONTROLS = ("load", "displacement")

#: Largest TOML sweep file read [bytes]: a sweep file is a few hundred bytes; a bigger one is a mistake.
MAX_CONFIG_BYTES = 1 << 20
#: Port of a scheduler address that names none (dask.distributed's default).
DEFAULT_SCHEDULER_PORT = 8786
#: Local worker processes per CPU at most (beyond a few per core they only cost memory).
WORKERS_PER_CPU = 4


def max_workers() -> int:
    """Return the largest accepted number of local worker processes.

    The one bound of ``--workers`` and ``[run] workers``.

    Returns
    -------
    int
        :data:`WORKERS_PER_CPU` x the CPUs.
    """
    import os

    return WORKERS_PER_CPU * (os.cpu_count() or 1)


_TOP_KEYS = {"sweep", "axes", "bem", "run"}
_SWEEP_KEYS = {"quantities", "models", "control", "chunk_points", "curve_a_star", "curve_points"}
_BEM_KEYS = {"half_width", "sampling", "max_seconds"}
_RUN_KEYS = {"workers", "scheduler", "out"}
_SPACE_KEYS = ("linspace", "geomspace")


@dataclass(frozen=True)
class SweepConfig:
    """A validated sweep.

    Parameters
    ----------
    axes : dict
        Axis name -> tuple of values, in :data:`AXES` order; every axis non-empty.
    quantities : tuple of str
        Subset of :data:`QUANTITIES`.
    models : tuple of str
        Comparison models of the ``pull_off`` quantity.
    control : str, default "load"
        "load" or "displacement".
    chunk_points : int, default 2048
        Grid points per analytic dask task (bounds memory per worker).
    curve_a_star : tuple of float
        Contact sizes (from, to) of the ``load_curve`` quantity [-].
    curve_points : int
        Points per load curve.
    half_width : float or None
        Fixed BEM domain half-width [c_r]; None: 1.5 c* per case.
    sampling : str
        BEM pressure sampling ("average" or "centre").
    workers : int or None
        Local worker processes (None: every core).
    scheduler : str or None
        Address of a dask.distributed scheduler.
    out : str or None
        Output path (see :func:`dhfield.sweep.store.output_paths`).
    max_seconds : float or None
        Estimated time allowed per adhesive BEM case [s], > 0 (``[bem] max_seconds``); None:
        the library's :data:`dhfield.analysis.bem_start.DEFAULT_MAX_SECONDS`.  Not in the
        fingerprint (it decides whether a case is refused, never its value).
    """

    axes: dict
    quantities: tuple = ("pull_off",)
    models: tuple = ("md-elliptic",)
    control: str = "load"
    chunk_points: int = 2048
    curve_a_star: tuple = (0.02, 3.0)
    curve_points: int = 200
    half_width: float | None = None
    sampling: str = "average"
    workers: int | None = None
    scheduler: str | None = None
    out: str | None = None
    max_seconds: float | None = None

    def fingerprint(self) -> str:
        """Hash everything that determines the results (not workers, scheduler, out, max_seconds).

        ``max_seconds`` only decides whether an adhesive case is refused before solving (stored
        as failed, retried by the next run), never a stored value: a rerun with another one
        resumes the same store.

        Returns
        -------
        str
            16 hexadecimal digits of a SHA-256.
        """
        payload = {"axes": {k: list(v) for k, v in self.axes.items()}, "quantities": list(self.quantities),
                   "models": list(self.models), "control": self.control, "chunk_points": self.chunk_points,
                   "half_width": self.half_width, "sampling": self.sampling}
        if "adhesive" in self.quantities:   # the adhesive cases' default route (the Newton route since 2026-12-02):
            payload["adhesive_route"] = ADHESIVE_ROUTE    # a store of the path routes' answers is not resumed
        if "load_curve" in self.quantities:
            payload.update(curve_a_star=list(self.curve_a_star), curve_points=self.curve_points)
        return hashlib.sha256(json.dumps(payload, sort_keys=True).encode()).hexdigest()[:16]

    def as_dict(self) -> dict:
        """Return the TOML-shaped mapping of this config.

        Returns
        -------
        dict
            The mapping; it round-trips through :func:`config_from_mapping`.
        """
        out = {"sweep": {"quantities": list(self.quantities), "models": list(self.models),
                         "control": self.control, "chunk_points": self.chunk_points,
                         "curve_a_star": list(self.curve_a_star), "curve_points": self.curve_points},
               "axes": {k: list(v) for k, v in self.axes.items()},
               "bem": {"sampling": self.sampling}, "run": {}}
        if self.half_width is not None:
            out["bem"]["half_width"] = self.half_width
        if self.max_seconds is not None:
            out["bem"]["max_seconds"] = self.max_seconds
        for k in ("workers", "scheduler", "out"):
            if getattr(self, k) is not None:
                out["run"][k] = getattr(self, k)
        return out

    @property
    def beta0(self) -> np.ndarray:
        """Ellipticity beta0 of every point of the ellipticity axis [-] (from the skew angle if given)."""
        if "beta0" in self.axes:
            return np.asarray(self.axes["beta0"], dtype=float)
        from ..core.geometry import ellipticity_from_skew_angle

        return np.asarray(ellipticity_from_skew_angle(np.radians(self.axes["skew_angle_deg"])), dtype=float)

    @property
    def adhesive_grid_axis(self) -> str:
        """Axis of the adhesive BEM's grid: "grid_level" (the automatic grid) or "n" (explicit n x n cells)."""
        return "grid_level" if "grid_level" in self.axes else "n"

    @property
    def ellipticity_axis(self) -> str:
        """Name of the ellipticity axis: "beta0" or "skew_angle_deg"."""
        return "beta0" if "beta0" in self.axes else "skew_angle_deg"


def _fail(key, valid, got):
    raise ValueError(f"{key} must be {valid}; got {got!r}")


def _name_list(sweep, key, allowed, default):
    """``sweep[key]`` as a non-empty list of names from ``allowed`` (one name may stand alone)."""
    names = sweep.get(key, [default])
    if isinstance(names, str):
        names = [names]
    if not isinstance(names, list) or not names:
        _fail(f"sweep.{key}", f"a non-empty list from {allowed}", names)
    for name in names:
        if name not in allowed:
            _fail(f"sweep.{key}", f"names from {allowed}", name)
    return names


def _check_keys(table, allowed, where):
    if not isinstance(table, dict):
        _fail(where, "a table", table)
    unknown = sorted(set(table) - set(allowed))
    if unknown:
        name = f"{where}.{unknown[0]}" if where else unknown[0]
        raise ValueError(f"unknown config key {name!r}; valid keys{' of ' + where if where else ''}: "
                         f"{', '.join(sorted(allowed))}")


def axis_values(name: str, spec) -> tuple:
    """Expand one axis's spec into its values.

    Parameters
    ----------
    name : str
        The axis, one of :data:`AXES`.
    spec : list, float or dict
        A list, a scalar, or ``{linspace|geomspace = [a, b, n]}``.

    Returns
    -------
    tuple of float
        The axis values.

    Raises
    ------
    ValueError
        Naming ``axes.<name>``, if the axis is empty or a value is out of range.
    """
    key = f"axes.{name}"
    if isinstance(spec, dict):
        _check_keys(spec, _SPACE_KEYS, key)
        if len(spec) != 1:
            _fail(key, "one of {linspace = [start, stop, num]} or {geomspace = [start, stop, num]}", spec)
        kind, args = next(iter(spec.items()))
        if not (isinstance(args, (list, tuple)) and len(args) == 3):
            _fail(f"{key}.{kind}", "[start, stop, num]", args)
        start, stop, num = args
        if (isinstance(num, bool) or not isinstance(num, (int, float)) or not math.isfinite(num)
                or num != int(num) or not 1 <= num <= MAX_POINTS):
            _fail(f"{key}.{kind} num", f"an integer in [1, {MAX_POINTS}] (an axis must not be empty; "
                  f"a sweep has at most {MAX_POINTS} points)", num)
        for v in (start, stop):
            if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
                _fail(f"{key}.{kind} start/stop", "finite numbers", v)
        if kind == "geomspace" and (start <= 0 or stop <= 0):
            _fail(f"{key}.geomspace start/stop", "> 0", [start, stop])
        values = (np.linspace if kind == "linspace" else np.geomspace)(start, stop, int(num)).tolist()
    elif isinstance(spec, (list, tuple)):
        values = list(spec)
    else:
        values = [spec]
    if len(values) == 0:
        raise ValueError(f"{key} must not be empty (give at least one value)")
    return _check_axis(name, values)


def _check_axis(name, values):
    key = f"axes.{name}"
    if name == "law":
        laws = cohesive_laws()
        for v in values:
            if v not in laws:
                _fail(key, f"cohesive law names from {laws}", v)
        out = tuple(values)
    elif name == "n":
        out = []
        for v in values:
            if isinstance(v, bool) or not isinstance(v, (int, float)) or v != int(v) or int(v) % 2 \
                    or not _MIN_BEM_CELLS <= v <= MAX_BEM_CELLS:
                _fail(key, f"even integers in [{_MIN_BEM_CELLS}, {MAX_BEM_CELLS}] (BEM cells per side; for the "
                      "adhesive BEM's automatic grid use the grid_level axis instead)", v)
            out.append(int(v))
        out = tuple(out)
    elif name == "grid_level":
        out = []
        for v in values:
            if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v) or v != int(v) \
                    or not 1 <= v <= MAX_GRID_LEVEL:
                _fail(key, f"integers in [1, {MAX_GRID_LEVEL}] (1: the adhesive BEM's automatic grid; k: k times "
                      "its cells per axis)", v)
            out.append(int(v))
        out = tuple(out)
    else:
        from ..core.validation import CONTACT_SIZE_RANGE, ELLIPTICITY_RANGE, TABOR_RANGE

        ranges = {"beta0": (ELLIPTICITY_RANGE, "in (1e-4, 1] (ellipticity b/a)", False),
                  "mu": (TABOR_RANGE, "in [1e-6, 1e12] (Tabor parameter, Eq. 35)", True),
                  "a_star": (CONTACT_SIZE_RANGE, "in [1e-6, 1e6] (contact semi-major axis a/c_r)", True),
                  "skew_angle_deg": ((0.0, 90.0), "in (0, 90] (crossing angle in degrees)", False)}
        (lo, hi), valid, closed_low = ranges[name]
        out = []
        for v in values:
            ok = not isinstance(v, bool) and isinstance(v, (int, float)) and math.isfinite(v)
            ok = ok and (lo <= v if closed_low else lo < v) and v <= hi
            if not ok:
                _fail(key, f"numbers {valid}", v)
            out.append(float(v))
        out = tuple(out)
    if len(set(out)) != len(out):
        _fail(key, "distinct values", list(values))
    return out


def _int_at_least(key, value, low):
    if isinstance(value, bool) or not isinstance(value, int) or value < low:
        _fail(key, f"an integer >= {low}", value)
    return value


def _positive_number(key, value, valid):
    """``value`` as a float if it is None or a finite number > 0 (not a bool), else :func:`_fail`.

    ``valid`` is the text of the valid range, or a function returning it (built only on failure).
    """
    if value is None:
        return None
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value) or value <= 0:
        _fail(key, valid() if callable(valid) else valid, value)
    return float(value)


def _max_seconds_range() -> str:
    """Valid range of ``[bem] max_seconds`` (imports the solver's default only when an error is raised)."""
    from ..analysis.bem_start import DEFAULT_MAX_SECONDS

    return f"a finite number > 0 (estimated time allowed per adhesive BEM case, s; default {DEFAULT_MAX_SECONDS:g})"


_ADDRESS = re.compile(r"^tcp://(\[[0-9A-Fa-f:.]+\]|[A-Za-z0-9_.-]+)(:\d{1,5})?$")
_OTHER_PROTOCOL = re.compile(r"^([A-Za-z][A-Za-z0-9+.-]*)://")


def check_scheduler_address(address):
    """Validate the form of a dask.distributed scheduler address (``tcp://host[:port]``).

    Only plain TCP is supported: ``tls://`` (needs certificates), ``ucx://``,
    ``ws://``/``wss://`` (need optional packages) and ``inproc://`` (same process
    only) are refused in one line, as is a port outside 1..65535.

    Parameters
    ----------
    address : str or None
        The address.

    Returns
    -------
    str or None
        ``address``, unchanged.

    Raises
    ------
    ValueError
        One line naming ``scheduler``, for a malformed address.
    """
    if address is None:
        return None
    if isinstance(address, str):
        other = _OTHER_PROTOCOL.match(address)
        if other and other.group(1).lower() != "tcp":
            _fail("scheduler", f"a tcp://host:port address (dhfield sweep does not support "
                  f"{other.group(1)}:// schedulers; use tcp://, 'processes' or 'synchronous')", address)
    m = _ADDRESS.match(address) if isinstance(address, str) else None
    if m is None:
        _fail("scheduler", "a dask.distributed address such as tcp://127.0.0.1:8786", address)
    if m.group(2) is not None and not 1 <= int(m.group(2)[1:]) <= 65535:
        _fail("scheduler", "an address with a port in 1..65535", address)
    return address


def scheduler_host_port(address) -> tuple:
    """(host, port) of a ``tcp://host[:port]`` address checked by :func:`check_scheduler_address`."""
    m = _ADDRESS.match(check_scheduler_address(address))
    host = m.group(1).strip("[]")
    return host, int(m.group(2)[1:]) if m.group(2) else DEFAULT_SCHEDULER_PORT


def config_from_mapping(mapping: dict) -> SweepConfig:
    """Validate a TOML-shaped mapping (see the module docstring) into a :class:`SweepConfig`.

    Parameters
    ----------
    mapping : dict
        Tables ``sweep``, ``axes``, ``bem`` and ``run``.

    Returns
    -------
    SweepConfig
        The validated sweep.
    """
    from ..analysis.compare import DEFAULT_MODEL, MODEL_NAMES

    _check_keys(mapping, _TOP_KEYS, "")
    sweep = mapping.get("sweep", {})
    _check_keys(sweep, _SWEEP_KEYS, "sweep")
    bem = mapping.get("bem", {})
    for key in sorted(set(bem) & set(_REMOVED_BEM_KEYS)) if isinstance(bem, dict) else ():
        raise ValueError(f"config key 'bem.{key}' was {_REMOVED_BEM_KEYS[key]}")
    _check_keys(bem, _BEM_KEYS, "bem")
    run = mapping.get("run", {})
    _check_keys(run, _RUN_KEYS, "run")
    axes_in = mapping.get("axes")
    if not axes_in:
        raise ValueError("axes must be a table with at least the axes beta0 (or skew_angle_deg) and mu")
    _check_keys(axes_in, AXES, "axes")

    quantities = _name_list(sweep, "quantities", QUANTITIES, "pull_off")
    models = _name_list(sweep, "models", MODEL_NAMES, DEFAULT_MODEL)
    control = sweep.get("control", "load")
    if control not in _CONTROLS:
        _fail("sweep.control", "'load' or 'displacement'", control)
    chunk = _int_at_least("sweep.chunk_points", sweep.get("chunk_points", 2048), 1)
    curve_points = _int_at_least("sweep.curve_points", sweep.get("curve_points", 200), 2)
    if curve_points > 100_000:
        _fail("sweep.curve_points", "an integer in [2, 100000]", curve_points)
    curve_a = sweep.get("curve_a_star", [0.02, 3.0])
    if (not isinstance(curve_a, list) or len(curve_a) != 2
            or not all(isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v) and
                       1e-6 <= v <= 1e6 for v in curve_a) or curve_a[0] >= curve_a[1]):
        _fail("sweep.curve_a_star", "[from, to] with 1e-6 <= from < to <= 1e6 (contact sizes a/c_r)", curve_a)
    if "load_curve" in quantities:
        from ..analysis.compare import CURVE_MODEL_NAMES

        for m in models:
            if m not in CURVE_MODEL_NAMES:
                _fail("sweep.models", f"models with load curves {CURVE_MODEL_NAMES} (quantity load_curve)", m)

    axes = {name: axis_values(name, axes_in[name]) for name in AXES if name in axes_in}
    if "beta0" in axes and "skew_angle_deg" in axes:
        raise ValueError("axes: give beta0 or skew_angle_deg, not both (one determines the other, Eqs. 3-4)")
    if "beta0" not in axes and "skew_angle_deg" not in axes:
        raise ValueError("axes must include beta0 (or skew_angle_deg)")
    if "mu" not in axes:
        raise ValueError("axes must include mu (Tabor parameter, Eq. 35)")
    needed = {"bem_field": ("a_star", "n")}
    for q in quantities:
        for ax in needed.get(q, ()):
            if ax not in axes:
                raise ValueError(f"axes.{ax} is needed by the quantity {q!r}")
    if "grid_level" in axes and "n" in axes:
        raise ValueError("axes: give n (explicit n x n grids) or grid_level (the automatic grid and its "
                         "refinements), not both; the quantity 'bem_field' needs n: run two sweeps")
    if "adhesive" in quantities and "n" not in axes and "grid_level" not in axes:
        raise ValueError("axes.n or axes.grid_level is needed by the quantity 'adhesive' (grid_level = [1, 2]: "
                         "the automatic grid and twice its cells per axis)")
    if "adhesive" in quantities and "law" not in axes:
        axes["law"] = (cohesive_default(),)
    used = set().union(*(QUANTITY_AXES[q] for q in quantities))
    for ax in axes:
        if ax not in used:
            raise ValueError(f"axes.{ax} is not used by the quantities {quantities}; remove it")
    if "pull_off" in quantities and "a_star" in axes:
        raise ValueError("axes.a_star cannot be swept together with the quantity 'pull_off' (a_star is "
                         "also its output, the contact size at pull-off); run two sweeps")
    npts = int(np.prod([len(v) for v in axes.values()]))
    if npts > MAX_POINTS:
        _fail("axes", f"at most {MAX_POINTS} grid points in all", npts)

    half_width = _positive_number("bem.half_width", bem.get("half_width"), "a number > 0 (domain half-width in c_r)")
    sampling = bem.get("sampling", "average")
    if sampling not in _SAMPLINGS:
        _fail("bem.sampling", f"one of {_SAMPLINGS}", sampling)
    max_seconds = _positive_number("bem.max_seconds", bem.get("max_seconds"), _max_seconds_range)
    workers = run.get("workers")
    if workers is not None:
        _int_at_least("run.workers", workers, 1)
        if workers > max_workers():
            _fail("run.workers", f"an integer in 1..{max_workers()} ({WORKERS_PER_CPU} local processes per "
                  "CPU)", workers)
    scheduler = run.get("scheduler")
    if scheduler not in (None, "synchronous", "processes"):
        check_scheduler_address(scheduler)
    out = run.get("out")
    if out is not None and (not isinstance(out, str) or not out.strip() or "\x00" in out):
        _fail("run.out", "a non-empty path (an output FILE.nc or DIR)", out)
    return SweepConfig(axes=axes, quantities=tuple(dict.fromkeys(quantities)), models=tuple(dict.fromkeys(models)),
                       control=control, chunk_points=chunk,
                       curve_a_star=(float(curve_a[0]), float(curve_a[1])), curve_points=curve_points,
                       half_width=half_width, sampling=sampling, max_seconds=max_seconds, workers=workers,
                       scheduler=scheduler, out=out)


def cohesive_laws() -> tuple:
    """List the names of the cohesive laws of the adhesive BEM solver (the values of the ``law`` axis).

    Returns
    -------
    tuple of str
        The names.
    """
    try:
        from ..bem.laws import LAWS
    except ImportError:  # pragma: no cover - laws module always ships
        return ("dugdale",)
    return tuple(LAWS)


def cohesive_default() -> str:
    laws = cohesive_laws()
    return laws[0] if laws else "dugdale"


def load_config(path) -> SweepConfig:
    """Read and validate a TOML sweep file (see the module docstring).

    Parameters
    ----------
    path : str or path-like
        The TOML file.

    Returns
    -------
    SweepConfig
        The validated sweep.
    """
    try:
        import tomllib
    except ModuleNotFoundError:  # Python 3.10
        import tomli as tomllib

    p = Path(path)
    if not p.is_file():
        raise ValueError(f"config must be an existing TOML file; got {str(p)!r}")
    try:
        with open(p, "rb") as fh:
            raw = fh.read(MAX_CONFIG_BYTES + 1)
    except OSError as exc:
        raise ValueError(f"config {str(p)!r} cannot be read ({exc.strerror})") from None
    if len(raw) > MAX_CONFIG_BYTES:
        raise ValueError(f"config {str(p)!r} must be a TOML file of at most {MAX_CONFIG_BYTES} bytes")
    if raw.startswith(b"\xef\xbb\xbf"):  # a UTF-8 byte-order mark (some editors write one): not TOML, skip it
        raw = raw[3:]
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise ValueError(f"config {str(p)!r} must be UTF-8 text (TOML); byte {exc.start} is not") from None
    try:
        mapping = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise ValueError(f"config {str(p)!r} is not valid TOML: {' '.join(str(exc).split())}") from None
    except RecursionError:
        raise ValueError(f"config {str(p)!r} nests tables or arrays too deeply (a sweep file needs 3 levels)") \
            from None
    except ValueError:  # Python's limit on the digits of an integer (sys.get_int_max_str_digits)
        where = _long_integer(text)
        if where is None:
            raise
        raise ValueError(f"config {str(p)!r}, {where}: integers must have at most "
                         f"{sys.get_int_max_str_digits()} digits (no value of a sweep needs more than 20)") from None
    return config_from_mapping(mapping)


def _long_integer(text):
    """Where the first integer longer than Python converts (``sys.get_int_max_str_digits``) is in a TOML
    text: ``"key 'table.key' (line n): an integer of d digits"``, or None if there is none."""
    limit = sys.get_int_max_str_digits()
    if not limit:
        return None
    m = re.search(r"\d(?:_?\d){%d,}" % limit, text)
    if m is None:
        return None
    before = text[:m.start()]
    line_no = before.count("\n") + 1
    digits = sum(c.isdigit() for c in m.group())
    table = ""
    for line in before.splitlines():
        h = re.match(r"\s*\[\[?\s*([^\]]+?)\s*\]\]?\s*(?:#.*)?$", line)
        if h:
            table = h.group(1)
    key = re.match(r"\s*([A-Za-z0-9_.\-\"' ]+?)\s*=", before[before.rfind("\n") + 1:])
    name = ".".join(x for x in (table, key.group(1).strip() if key else "") if x)
    return f"{'key ' + repr(name) + ' ' if key else ''}(line {line_no}): an integer of {digits} digits"
