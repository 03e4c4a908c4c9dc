"""Elastic half-space operator: surface displacement of a gridded pressure (DC-FFT).

The operator maps a piecewise-constant normal pressure on a Cartesian grid of
rectangular cells to the normal surface displacement at the cell centres.  It
is the forward problem only (no contact solver): dhfield uses it to check the
analytic displacement and gap fields of the Hertz and double-Hertz (DH) models
(Eqs. 13, 21, 26, 27 of Zini et al. 2018) over the whole surface.

Conventions
-----------
* **Grid.**  ``nx`` x ``ny`` cells of size ``dx`` x ``dy``, centred on the
  origin: cell centres ``x_i = (i - (nx - 1)/2) dx``, ``y_j = (j - (ny - 1)/2) dy``.
  Arrays are indexed ``[i, j]`` (``'ij'`` indexing: axis 0 is x, the major
  axis of the ellipse; axis 1 is y).
* **Signs.**  Pressure is positive in compression; the displacement is the
  combined normal displacement of both bodies, positive into the bodies, as in
  Eq. (12) and :mod:`dhfield.models.hertz`, so that the gap is
  ``h = z - delta + omega``.  Tensile (adhesive) stress is negative pressure.
* **Green's function.**  Boussinesq's point-load solution for the combined
  compliance, ``omega = p dA / (pi E* rho)``, integrated exactly over each
  rectangular cell with uniform pressure (Love 1929; Johnson, *Contact
  Mechanics*, 1985, Sec. 3.2).  The influence coefficient ``K[i, j]`` is the
  displacement at offset ``(i dx, j dy)`` from the centre of a loaded cell.
  No regularisation or approximation is involved, so for piecewise-constant
  pressure the operator is exact up to rounding.
* **Convolution and padding (DC-FFT).**  Liu, Wang & Liu (Wear 2000): the
  ``(2nx - 1) x (2ny - 1)`` influence coefficients are laid out in wrap-around
  order on a ``2nx x 2ny`` array (offset ``-i`` at index ``2nx - i``; the unused
  index ``nx`` is zero), the pressure is zero-padded to the same size, and the
  first ``nx x ny`` block of the circular convolution is kept.  This is the
  exact discrete *linear* (non-periodic) convolution: no periodic images.
* **FFT normalisation.**  FFTW's transforms are unnormalised (forward
  ``sum x e^{-2 pi i k n / N}``, backward with ``+``).  The kernel is even, so its
  spectrum is real: it is computed directly as the DCT-I (``REDFT00``) of
  ``K[0..nx, 0..ny]`` (scipy.fft, once per grid), and the factor ``1/(4 nx ny)``
  of the inverse transform is folded into that stored real spectrum; no other
  scaling is applied.
* **Symmetry mode.**  For pressure fields even in x and in y (all Hertz and DH
  fields here) the operator takes the quadrant ``x > 0, y > 0``
  (``nx/2 x ny/2`` cells) and returns the displacement there.  The quadrant
  zero-padded to ``nx x ny`` is half-sample even about ``-1/2`` and the kernel
  whole-sample even, so the circular convolution is diagonalised by FFTW's
  ``REDFT10`` (DCT-II, forward) and ``REDFT01`` (DCT-III, inverse), with the
  kernel spectrum given by ``REDFT00`` (DCT-I) of ``K[0..nx, 0..ny]``.  The
  result is the same discrete sum as the full grid.
* **Pruning.**  The padded half of the input is zero and the padded half of the
  output is discarded, so the row transforms (axis 1) are done only on the
  ``nx`` (or ``nx/2``) rows that matter; the column transforms (axis 0) run in
  place over all ``2nx`` (or ``nx``) rows, the padding rows being re-zeroed
  before each forward column transform.

Performance
-----------
FFTW plans, aligned work arrays and the kernel spectrum are built once per grid
(:func:`get_operator` caches operators) and reused.  FFTW wisdom is imported
from, and saved to, ``$DHFIELD_CACHE/fftw_wisdom.bin`` (default directory
``~/.cache/dhfield``) by the private :mod:`dhfield.bem._wisdom`.
``threads`` selects FFTW threads (default ``$DHFIELD_THREADS`` or 1), an integer
in ``1 .. max_threads()`` (4 per CPU); a bad ``DHFIELD_THREADS`` is a
ValueError naming it.

References
----------
.. [1] Love A.E.H. (1929) The stress produced in a semi-infinite solid by
   pressure on part of the boundary. Phil. Trans. R. Soc. A 228:377-420.
   doi:10.1098/rsta.1929.0009
.. [2] Liu S., Wang Q., Liu G. (2000) A versatile method of discrete
   convolution and FFT (DC-FFT) for contact analyses. Wear 243:101-111.
   doi:10.1016/S0043-1648(00)00427-0
.. [3] Frigo M., Johnson S.G. (2005) The design and implementation of FFTW3.
   Proc. IEEE 93:216-231 (real-to-real transform definitions).
"""
from __future__ import annotations

import functools
import math
import operator
import os
import threading
from dataclasses import dataclass

import numpy as np
import pyfftw
import scipy.fft

from ..core.validation import check_finite, check_positive
from ._wisdom import load_wisdom, save_wisdom
from .backend import array_module, check_backend, default_backend

__all__ = [
    "MIN_CELLS",
    "Grid",
    "love_influence",
    "influence_coefficients",
    "HalfSpaceOperator",
    "ArrayHalfSpaceOperator",
    "get_operator",
    "clear_operator_cache",
    "surface_displacement",
    "quadrant",
    "unfold_quadrant",
    "THREADS_PER_CPU",
    "max_threads",
    "check_threads",
    "default_threads",
    "free_cpu_count",
    "default_planner_effort",
    "check_planner_effort",
]

#: Smallest number of cells per axis accepted by :class:`Grid`.
MIN_CELLS = 8

_PLANNER_EFFORTS = ("FFTW_ESTIMATE", "FFTW_MEASURE", "FFTW_PATIENT", "FFTW_EXHAUSTIVE")


# --------------------------------------------------------------------------- grid
def _short_repr(value, limit: int = 80) -> str:
    """``repr(value)`` on one line, at most ``limit`` characters (for error messages)."""
    text = " ".join(repr(value).split())
    return text if len(text) <= limit else text[: limit - 3] + "..."


def _check_cells(name: str, value) -> int:
    try:
        n = operator.index(value)
    except TypeError:
        raise ValueError(f"{name} must be an integer >= {MIN_CELLS} (number of cells); got {_short_repr(value)}") \
            from None
    if n < MIN_CELLS:
        raise ValueError(f"{name} must be an integer >= {MIN_CELLS} (number of cells); got {n!r}")
    return int(n)


def _check_spacing(name: str, value) -> float:
    arr = check_positive(name, value, "cell size, m or nondimensional")
    if arr.ndim != 0:
        raise ValueError(f"{name} must be a scalar (cell size); got array of shape {arr.shape}")
    return float(arr)


@dataclass(frozen=True)
class Grid:
    """A Cartesian grid of ``nx`` x ``ny`` rectangular cells centred on the origin.

    Parameters
    ----------
    nx, ny : int
        Number of cells along x and y, each >= ``MIN_CELLS`` [-].
    dx, dy : float
        Cell sizes [m] (or nondimensional lengths).
    """

    nx: int
    ny: int
    dx: float
    dy: float

    def __post_init__(self):
        object.__setattr__(self, "nx", _check_cells("nx", self.nx))
        object.__setattr__(self, "ny", _check_cells("ny", self.ny))
        object.__setattr__(self, "dx", _check_spacing("dx", self.dx))
        object.__setattr__(self, "dy", _check_spacing("dy", self.dy))

    @classmethod
    def centered(cls, n, half_width, ny=None, half_width_y=None) -> "Grid":
        """Grid covering ``[-half_width, half_width] x [-half_width_y, half_width_y]``.

        Parameters
        ----------
        n : int
            Cells along x (and along y unless ``ny`` is given) [-].
        half_width : float
            Half the domain length along x [m].
        ny : int, optional
            Cells along y [-]; default ``n``.
        half_width_y : float, optional
            Half the domain length along y [m]; default ``half_width``.
        """
        nx = _check_cells("n", n)
        ny = nx if ny is None else _check_cells("ny", ny)
        lx = _check_spacing("half_width", half_width)
        ly = lx if half_width_y is None else _check_spacing("half_width_y", half_width_y)
        return cls(nx, ny, 2.0 * lx / nx, 2.0 * ly / ny)

    @property
    def shape(self) -> tuple[int, int]:
        """Cell counts ``(nx, ny)`` of the full grid [-]."""
        return (self.nx, self.ny)

    @property
    def x(self) -> np.ndarray:
        """Cell-centre x coordinates, shape (nx,) [m]."""
        return (np.arange(self.nx) - 0.5 * (self.nx - 1)) * self.dx

    @property
    def y(self) -> np.ndarray:
        """Cell-centre y coordinates, shape (ny,) [m]."""
        return (np.arange(self.ny) - 0.5 * (self.ny - 1)) * self.dy

    @property
    def x_edges(self) -> np.ndarray:
        """Cell-edge x coordinates, shape (nx + 1,) [m]."""
        return (np.arange(self.nx + 1) - 0.5 * self.nx) * self.dx

    @property
    def y_edges(self) -> np.ndarray:
        """Cell-edge y coordinates, shape (ny + 1,) [m]."""
        return (np.arange(self.ny + 1) - 0.5 * self.ny) * self.dy

    def mesh(self) -> tuple[np.ndarray, np.ndarray]:
        """Return the cell-centre coordinates on the full grid ('ij' indexing).

        Returns
        -------
        X : ndarray, shape (nx, ny)
            The x coordinate of each cell centre [m].
        Y : ndarray, shape (nx, ny)
            The y coordinate of each cell centre [m].
        """
        return np.meshgrid(self.x, self.y, indexing="ij")

    @property
    def is_even(self) -> bool:
        """True when nx and ny are even, so that the symmetry mode applies."""
        return self.nx % 2 == 0 and self.ny % 2 == 0

    def quadrant_grid_shape(self) -> tuple[int, int]:
        """Return the shape of the ``x > 0, y > 0`` quadrant used by the symmetry mode.

        Returns
        -------
        (int, int)
            ``(nx // 2, ny // 2)`` [-].
        """
        return (self.nx // 2, self.ny // 2)


# --------------------------------------------------------------------------- Love
def _w_asinh(w, t):
    """``w * asinh(t/|w|)`` with its limit 0 at w = 0."""
    aw = np.abs(w)
    with np.errstate(divide="ignore", invalid="ignore"):
        v = w * np.arcsinh(t / aw)
    return np.where(aw > 0.0, v, 0.0)


def love_influence(x, y, half_width_x, half_width_y, reduced_modulus=1.0):
    """Surface displacement of unit uniform pressure on a rectangle (Love 1929) [m/Pa].

    Parameters
    ----------
    x, y : array_like
        Field point relative to the rectangle centre [m].
    half_width_x, half_width_y : float
        Half-sides of the loaded rectangle ``|xi| <= half_width_x``,
        ``|eta| <= half_width_y`` [m].
    reduced_modulus : float, default 1
        E* [Pa].

    Returns
    -------
    ndarray
        Combined normal displacement per unit pressure [m Pa^-1].

    Notes
    -----
    With ``X+- = x +- a``, ``Y+- = y +- b``,

    .. math::

        \\pi E^* u/p = X_+ \\ln\\frac{Y_+ + \\rho_{++}}{Y_- + \\rho_{-+}}
          + Y_+ \\ln\\frac{X_+ + \\rho_{++}}{X_- + \\rho_{+-}}
          + X_- \\ln\\frac{Y_- + \\rho_{--}}{Y_+ + \\rho_{+-}}
          + Y_- \\ln\\frac{X_- + \\rho_{--}}{X_+ + \\rho_{-+}}

    (``rho`` the distance to the corner).  Each log-ratio is evaluated as a
    difference of ``asinh(t/|w|)``, since ``ln(t + sqrt(t^2 + w^2)) =
    asinh(t/|w|) + ln|w|``; this is free of the cancellation the printed
    form suffers when ``t < 0``.  At the centre of a square cell of side Delta,
    ``u = (4 Delta/pi) ln(1 + sqrt 2) p/E*``.
    """
    x = np.asarray(x, dtype=float)
    y = np.asarray(y, dtype=float)
    a = float(half_width_x)
    b = float(half_width_y)
    xp, xm, yp, ym = x + a, x - a, y + b, y - b
    s = (_w_asinh(xp, yp) - _w_asinh(xp, ym)
         + _w_asinh(yp, xp) - _w_asinh(yp, xm)
         + _w_asinh(xm, ym) - _w_asinh(xm, yp)
         + _w_asinh(ym, xm) - _w_asinh(ym, xp))
    return s / (np.pi * reduced_modulus)


def influence_coefficients(grid: Grid, reduced_modulus=1.0) -> np.ndarray:
    """Compute the influence coefficients ``K[i, j]`` for offsets ``(i dx, j dy)`` [m/Pa].

    The kernel is even in both offsets, so ``0 <= i <= nx``, ``0 <= j <= ny``
    cover every offset; the last row and column (offset ``nx dx`` or ``ny dy``)
    never enter the discrete convolution and are set to zero.

    Parameters
    ----------
    grid : Grid
        The cell grid.
    reduced_modulus : float, default 1
        E* [Pa].

    Returns
    -------
    ndarray, shape (nx + 1, ny + 1)
        Displacement at offset ``(i dx, j dy)`` per unit pressure on one cell
        (:func:`love_influence`) [m/Pa].

    Raises
    ------
    ValueError
        If ``reduced_modulus`` is not finite and positive.
    """
    e = _check_spacing("reduced_modulus", reduced_modulus)
    ix = np.arange(grid.nx + 1)[:, None] * grid.dx
    iy = np.arange(grid.ny + 1)[None, :] * grid.dy
    k = love_influence(ix, iy, 0.5 * grid.dx, 0.5 * grid.dy, e)
    k[grid.nx, :] = 0.0
    k[:, grid.ny] = 0.0
    return k


#: Threads per CPU accepted at most: FFTW gains nothing beyond the cores; the
#: factor leaves room for hyper-threading and oversubscription experiments,
#: while a typo such as 1000000 is refused instead of spawning that many threads.
THREADS_PER_CPU = 4


def max_threads() -> int:
    """Return the largest accepted FFTW thread count.

    Returns
    -------
    int
        ``THREADS_PER_CPU * os.cpu_count()`` (``os.cpu_count()`` taken as 1
        when unknown) [-].
    """
    return THREADS_PER_CPU * (os.cpu_count() or 1)


def free_cpu_count() -> int:
    """Return the number of CPUs this process may use that other work is not already using.

    Returns
    -------
    int
        ``cpus - round(load)``, at least 1, where ``cpus`` is the number of CPUs this process
        may run on (``os.sched_getaffinity``, else ``os.cpu_count()``) and ``load`` the
        one-minute load average (``os.getloadavg``; 0 where unknown) [-].  A busy machine
        thus gets fewer FFTW threads: on 2 cores already running 2 processes, threads of
        a new one only compete with them.
    """
    try:
        cpus = len(os.sched_getaffinity(0))
    except (AttributeError, OSError):  # not on Linux
        cpus = os.cpu_count() or 1
    try:
        load = os.getloadavg()[0]
    except (AttributeError, OSError):  # not on Unix, or unavailable
        load = 0.0
    busy = round(load) if math.isfinite(load) and load > 0.0 else 0
    return max(1, cpus - busy)


def default_planner_effort() -> str:
    """Return the FFTW planner flag used when none is given.

    Returns
    -------
    str
        ``$DHFIELD_FFTW_PLANNER`` if set and not blank, else ``"FFTW_MEASURE"``.
        ``FFTW_MEASURE`` times candidate algorithms and keeps the fastest, so which
        algorithm (and so the last bits of each transform) a run gets depends on the
        machine's load while it plans; ``FFTW_ESTIMATE`` chooses without timing and is
        reproducible from run to run on one machine.  The test suite plans with it.

    Raises
    ------
    ValueError
        Naming ``DHFIELD_FFTW_PLANNER`` if it is set to anything but one of the
        planner flags ``FFTW_ESTIMATE``, ``FFTW_MEASURE``, ``FFTW_PATIENT``,
        ``FFTW_EXHAUSTIVE``.
    """
    env = os.environ.get("DHFIELD_FFTW_PLANNER", "").strip()
    if not env:
        return "FFTW_MEASURE"
    return check_planner_effort(env, "DHFIELD_FFTW_PLANNER (environment)")


def check_planner_effort(value, name: str = "planner_effort") -> str:
    """Check an FFTW planner flag.

    Parameters
    ----------
    value : str or None
        One of ``FFTW_ESTIMATE``, ``FFTW_MEASURE``, ``FFTW_PATIENT``, ``FFTW_EXHAUSTIVE``;
        None for :func:`default_planner_effort`.
    name : str, default "planner_effort"
        The name the error message gives the value.

    Returns
    -------
    str
        The flag.

    Raises
    ------
    ValueError
        If ``value`` is not one of the flags.
    """
    if value is None:
        return default_planner_effort()
    if value not in _PLANNER_EFFORTS:
        raise ValueError(f"{name} must be one of {', '.join(_PLANNER_EFFORTS)}; got {value!r}")
    return value


def check_threads(value, name: str = "threads") -> int:
    """Check an FFTW thread count.

    Parameters
    ----------
    value : int
        Thread count to check (bools are refused) [-].
    name : str, default "threads"
        Name of the parameter, used in the error message.

    Returns
    -------
    int
        ``value`` as a Python int in ``1 .. max_threads()`` [-].

    Raises
    ------
    ValueError
        Naming ``name`` and the valid range if ``value`` is not an integer in
        ``1 .. max_threads()``.
    """
    valid = f"an integer in 1..{max_threads()} (at most {THREADS_PER_CPU} per CPU)"
    if isinstance(value, bool):
        raise ValueError(f"{name} must be {valid}; got {value!r}")
    try:
        n = operator.index(value)
    except TypeError:
        raise ValueError(f"{name} must be {valid}; got {_short_repr(value)}") from None
    if not 1 <= n <= max_threads():
        raise ValueError(f"{name} must be {valid}; got {n!r}")
    return int(n)


def default_threads() -> int:
    """Return the FFTW thread count used when none is given.

    Returns
    -------
    int
        ``$DHFIELD_THREADS`` if set and not blank, else 1 [-].

    Raises
    ------
    ValueError
        Naming ``DHFIELD_THREADS`` if it is set but not an integer in
        ``1 .. max_threads()``.
    """
    env = os.environ.get("DHFIELD_THREADS")
    if env is None or env.strip() == "":
        return 1
    try:
        value = int(env.strip())
    except ValueError:
        raise ValueError(f"DHFIELD_THREADS (environment) must be an integer in 1..{max_threads()}; "
                         f"got {env!r}") from None
    return check_threads(value, "DHFIELD_THREADS (environment)")


_default_threads = default_threads  # the name used before


# --------------------------------------------------------------------------- operator
def _operator_arguments(grid, reduced_modulus, symmetric, threads):
    """Checked (grid, E*, symmetric, threads) of an operator (both implementations)."""
    if not isinstance(grid, Grid):
        raise ValueError(f"grid must be a dhfield.bem.Grid; got {type(grid).__name__}")
    e = _check_spacing("reduced_modulus", reduced_modulus)
    threads = default_threads() if threads is None else check_threads(threads)
    if symmetric and not grid.is_even:
        raise ValueError(f"symmetric mode needs even nx and ny; got nx={grid.nx}, ny={grid.ny}")
    return grid, e, bool(symmetric), threads


def _kernel_spectrum(grid, reduced_modulus, symmetric, workers):
    """(input shape, real kernel spectrum with the inverse transform's normalisation folded in).

    Full grid: the wrap-around kernel on the 2nx x 2ny grid is even (offset -i at index 2nx - i,
    K[nx, :] = K[:, ny] = 0), so its DFT is real and equals the DCT-I (REDFT00) of
    K[0..nx, 0..ny]: S[k, l] = D[min(k, 2nx - k), l] for the rfft layout (2nx, ny + 1).
    Symmetry mode: the same DCT-I is the DFT of the even kernel of period 2nx, 2ny, and
    REDFT10 followed by REDFT01 multiplies by (2 nx)(2 ny).  Both fold in 1/(4 nx ny).
    """
    nx, ny = grid.shape
    d = scipy.fft.dctn(influence_coefficients(grid, reduced_modulus), type=1, workers=workers)
    scale = 1.0 / (4.0 * nx * ny)
    if symmetric:
        return (nx // 2, ny // 2), np.multiply(d[:nx, :ny], scale)
    spectrum = np.empty((2 * nx, ny + 1))
    np.multiply(d, scale, out=spectrum[: nx + 1])
    np.multiply(d[nx - 1:0:-1], scale, out=spectrum[nx + 1:])
    return (nx, ny), spectrum


class HalfSpaceOperator:
    """DC-FFT surface-displacement operator of an elastic half-space on one grid.

    Parameters
    ----------
    grid : Grid
        The cell grid.
    reduced_modulus : float, default 1
        E* [Pa].
    symmetric : bool, default False
        If True, the operator takes and returns the quadrant ``x > 0, y > 0``
        (shape ``(nx/2, ny/2)``) of a field even in x and y; needs even nx, ny.
    threads : int, optional
        FFTW threads; default ``$DHFIELD_THREADS`` or 1.
    planner_effort : str, optional
        FFTW planner flag; default :func:`default_planner_effort`.

    Notes
    -----
    Building the operator plans the transforms (using stored wisdom when
    available) and computes the kernel spectrum once; each call then costs one
    forward and one inverse (pruned) transform, one multiplication by the real
    kernel spectrum and two copies.  Calls are serialised by a lock because the
    work arrays are shared.  Its arrays are numpy arrays (``backend = "fftw"``, ``xp = numpy``;
    :mod:`dhfield.bem.backend`).
    """

    #: Backend name (:mod:`dhfield.bem.backend`).
    backend = "fftw"
    #: Array module of the operator's input and output.
    xp = np

    def __init__(self, grid: Grid, reduced_modulus=1.0, *, symmetric=False, threads=None,
                 planner_effort=None):
        self.grid, self.reduced_modulus, self.symmetric, self.threads = _operator_arguments(
            grid, reduced_modulus, symmetric, threads)
        self.planner_effort = check_planner_effort(planner_effort)
        self._lock = threading.Lock()
        load_wisdom()
        self.input_shape, spectrum = _kernel_spectrum(self.grid, self.reduced_modulus, self.symmetric, self.threads)
        self._spectrum = pyfftw.empty_aligned(spectrum.shape, dtype="float64")
        self._spectrum[...] = spectrum
        del spectrum
        rows, cols = self.input_shape
        if self.symmetric:
            self._build(rows, cols, self.grid.nx, "float64", "FFTW_REDFT10", "FFTW_REDFT01")
        else:
            self._build(rows, cols, 2 * self.grid.nx, "complex128", None, None)
        save_wisdom()

    # -- construction ---------------------------------------------------------
    def _flags(self, *extra):
        return (self.planner_effort, *extra)

    def _build(self, rows, cols, padded_rows, dtype, fwd_kind, bwd_kind):
        """Plans and aligned work arrays shared by both modes.

        Work arrays: ``_rin`` (rows x 2 cols real input, right half zero), ``_work``
        (padded_rows x spectral columns, transformed in place; its lower half is
        re-zeroed before each forward column transform) and ``_rout``.
        """
        thr = self.threads
        spec_cols = self._spectrum.shape[1]
        self._rin = pyfftw.empty_aligned((rows, 2 * cols), dtype="float64")
        self._work = pyfftw.empty_aligned((padded_rows, spec_cols), dtype=dtype)
        self._rout = pyfftw.empty_aligned((rows, 2 * cols), dtype="float64")
        fk = {} if fwd_kind is None else {"direction": [fwd_kind]}
        bk = {"direction": "FFTW_BACKWARD"} if bwd_kind is None else {"direction": [bwd_kind]}
        self._plans = (
            pyfftw.FFTW(self._rin, self._work[:rows], axes=(1,), flags=self._flags(), threads=thr, **fk),
            pyfftw.FFTW(self._work, self._work, axes=(0,), flags=self._flags(), threads=thr, **fk),
            pyfftw.FFTW(self._work, self._work, axes=(0,), flags=self._flags(), threads=thr, **bk),
            pyfftw.FFTW(self._work[:rows], self._rout, axes=(1,), flags=self._flags("FFTW_DESTROY_INPUT"),
                        threads=thr, **bk),
        )
        # planning may scribble on the arrays: the right half of _rin must stay zero
        self._rin[...] = 0.0

    # -- evaluation -----------------------------------------------------------
    def _run(self, p, out):
        rows, cols = self.input_shape
        f_row, f_col, b_col, b_row = self._plans
        self._rin[:, :cols] = p
        f_row.execute()                      # rows of the (unpadded) input only
        self._work[rows:] = 0.0              # the zero padding, overwritten by the last call
        f_col.execute()                      # in place, all rows
        np.multiply(self._work, self._spectrum, out=self._work)
        b_col.execute()                      # in place, all rows
        b_row.execute()                      # only the rows that are kept
        out[...] = self._rout[:, :cols]

    def __call__(self, pressure, out=None) -> np.ndarray:
        """Surface displacement at the cell centres [m].

        Parameters
        ----------
        pressure : array_like
            Cell pressures [Pa], shape ``input_shape`` (``(nx, ny)``, or the
            quadrant ``(nx/2, ny/2)`` in symmetric mode).
        out : ndarray, optional
            Float64 array of shape ``input_shape`` to write the result into.

        Returns
        -------
        ndarray
            Displacement, same shape as ``pressure`` [m].
        """
        p = np.asarray(pressure, dtype=float)
        if p.shape != self.input_shape:
            what = "quadrant (nx/2, ny/2)" if self.symmetric else "grid (nx, ny)"
            raise ValueError(f"pressure must have the {what} shape {self.input_shape}; got {p.shape}")
        if not math.isfinite(float(np.add.reduce(p, axis=None))):
            check_finite("pressure", p, "Pa")
        if out is None:
            out = np.empty(self.input_shape)
        elif not (isinstance(out, np.ndarray) and out.shape == self.input_shape and out.dtype == np.float64):
            raise ValueError(f"out must be a float64 array of shape {self.input_shape}")
        with self._lock:
            self._run(p, out)
        return out

    displacement = __call__


class ArrayHalfSpaceOperator:
    """The DC-FFT operator of :class:`HalfSpaceOperator` on an array backend (numpy or CuPy).

    The same discrete sum, evaluated with the backend's ``scipy.fft``-like module instead of
    pyfftw plans: full grid, ``rfft2`` of the pressure zero-padded to ``2nx x 2ny`` times the real
    kernel spectrum, unnormalised ``irfft2``; symmetry mode, DCT-II of the quadrant zero-padded to
    ``nx x ny`` times the spectrum, DCT-III (the FFTW ``REDFT10``/``REDFT01`` pair of the module's
    Conventions).  The kernel spectrum is computed on the host (``scipy.fft.dctn``, type 1) and
    moved to the backend once.

    Parameters
    ----------
    grid : Grid
        The cell grid.
    reduced_modulus : float, default 1
        E* [Pa].
    symmetric : bool, default False
        Take and return the quadrant ``x > 0, y > 0`` of an even-even field; needs even nx, ny.
    threads : int, optional
        ``scipy.fft`` workers of the ``"numpy"`` backend (ignored by ``"cupy"``); default
        :func:`default_threads`.
    backend : {"numpy", "cupy"}, default "numpy"
        Array backend (:mod:`dhfield.bem.backend`).

    Notes
    -----
    Input and output are arrays of the backend (``xp``); a numpy input is moved to it.  Unlike
    :class:`HalfSpaceOperator` it holds no shared work arrays, so calls need no lock.
    """

    def __init__(self, grid: Grid, reduced_modulus=1.0, *, symmetric=False, threads=None, backend="numpy"):
        self.grid, self.reduced_modulus, self.symmetric, self.threads = _operator_arguments(
            grid, reduced_modulus, symmetric, threads)
        backend = check_backend(backend)
        if backend == "fftw":
            raise ValueError("backend 'fftw' is HalfSpaceOperator's; ArrayHalfSpaceOperator takes 'numpy' or 'cupy'")
        self.backend = backend
        self.xp, self._fft = array_module(backend)
        self.input_shape, spectrum = _kernel_spectrum(self.grid, self.reduced_modulus, self.symmetric, self.threads)
        self._spectrum = self.xp.asarray(spectrum)
        self._kw = {"workers": self.threads} if backend == "numpy" else {}

    def __call__(self, pressure, out=None):
        """Surface displacement at the cell centres [m].

        Parameters
        ----------
        pressure : array_like
            Cell pressures [Pa], shape ``input_shape``.
        out : array, optional
            Float64 array of the backend, of shape ``input_shape``, to write the result into.

        Returns
        -------
        array
            Displacement, same shape as ``pressure``, an array of the backend [m].
        """
        xp = self.xp
        p = xp.asarray(pressure, dtype=xp.float64)
        if p.shape != self.input_shape:
            what = "quadrant (nx/2, ny/2)" if self.symmetric else "grid (nx, ny)"
            raise ValueError(f"pressure must have the {what} shape {self.input_shape}; got {p.shape}")
        if not math.isfinite(float(p.sum())):
            raise ValueError("pressure must be finite (Pa)")
        rows, cols = self.input_shape
        nx, ny = self.grid.shape
        fft = self._fft
        if self.symmetric:
            buf = xp.zeros((nx, ny))
            buf[:rows, :cols] = p
            w = fft.dctn(buf, type=2, **self._kw)
            w *= self._spectrum
            r = fft.dctn(w, type=3, **self._kw)
        else:
            buf = xp.zeros((2 * nx, 2 * ny))
            buf[:rows, :cols] = p
            w = fft.rfft2(buf, **self._kw)
            w *= self._spectrum
            r = fft.irfft2(w, s=(2 * nx, 2 * ny), norm="forward", **self._kw)
        if out is None:
            return xp.ascontiguousarray(r[:rows, :cols])
        if out.shape != self.input_shape:
            raise ValueError(f"out must be a float64 array of shape {self.input_shape}")
        out[...] = r[:rows, :cols]
        return out

    displacement = __call__


@functools.lru_cache(maxsize=16)
def _cached_operator(grid, reduced_modulus, symmetric, threads, planner_effort, backend):
    if backend != "fftw":
        return ArrayHalfSpaceOperator(grid, reduced_modulus, symmetric=symmetric, threads=threads,
                                      backend=backend)
    return HalfSpaceOperator(grid, reduced_modulus, symmetric=symmetric, threads=threads,
                             planner_effort=planner_effort)


def get_operator(grid: Grid, reduced_modulus=1.0, *, symmetric=False, threads=None,
                 planner_effort=None, backend=None):
    """Return the cached operator for this grid (built on first use).

    Parameters
    ----------
    grid : Grid
        The full cell grid.
    reduced_modulus : float, default 1
        E* [Pa].
    symmetric : bool, default False
        Build the even-even quadrant operator (see the module's Conventions).
    threads : int, optional
        FFTW threads; default :func:`default_threads`.
    planner_effort : str, default "FFTW_MEASURE"
        FFTW planner flag, one of ``FFTW_ESTIMATE``, ``FFTW_MEASURE``,
        ``FFTW_PATIENT``, ``FFTW_EXHAUSTIVE``.
    backend : str, optional
        Array backend, one of ``"fftw"``, ``"numpy"``, ``"cupy"``
        (:mod:`dhfield.bem.backend`); default :func:`dhfield.bem.backend.default_backend`.

    Returns
    -------
    HalfSpaceOperator or ArrayHalfSpaceOperator
        The operator (``"fftw"``: :class:`HalfSpaceOperator`), shared by every call with the
        same arguments.

    Raises
    ------
    ValueError
        If ``threads``, ``reduced_modulus``, ``planner_effort`` or ``backend`` is out of
        range.
    """
    threads = default_threads() if threads is None else check_threads(threads)
    e = _check_spacing("reduced_modulus", reduced_modulus)
    planner_effort = check_planner_effort(planner_effort)
    backend = default_backend() if backend is None else check_backend(backend)
    return _cached_operator(grid, e, bool(symmetric), threads, planner_effort, backend)


def clear_operator_cache() -> None:
    """Release the operators (plans, work arrays, spectra) cached by :func:`get_operator`."""
    _cached_operator.cache_clear()


def surface_displacement(pressure, dx, dy=None, reduced_modulus=1.0, *, symmetric=False,
                         threads=None) -> np.ndarray:
    """Surface displacement of a gridded pressure on the elastic half-space [m].

    Parameters
    ----------
    pressure : array_like
        Cell pressures on the full grid, shape (nx, ny), positive in
        compression [Pa].
    dx, dy : float
        Cell sizes [m]; ``dy`` defaults to ``dx``.
    reduced_modulus : float, default 1
        E* [Pa].
    symmetric : bool, default False
        Use the even-even quadrant transform: the field must be even in x and y
        (checked to a relative 1e-12), only its quadrant ``x > 0, y > 0`` is
        transformed and the result is unfolded back to the full grid.
    threads : int, optional
        FFTW threads.

    Returns
    -------
    ndarray
        Displacement at the cell centres, shape (nx, ny) [m].
    """
    p = np.asarray(pressure, dtype=float)
    if p.ndim != 2:
        raise ValueError(f"pressure must be a 2-D array; got shape {p.shape}")
    dy = dx if dy is None else dy
    grid = Grid(p.shape[0], p.shape[1], dx, dy)
    if not symmetric:
        return get_operator(grid, reduced_modulus, threads=threads)(p)
    if not grid.is_even:
        raise ValueError(f"symmetric mode needs even nx and ny; got pressure of shape {p.shape}")
    scale = float(np.max(np.abs(p))) if p.size else 0.0
    tol = _EVEN_RTOL * scale
    if np.max(np.abs(p - p[::-1, :])) > tol or np.max(np.abs(p - p[:, ::-1])) > tol:
        raise ValueError("pressure must be even in x and in y for symmetric=True")
    op = get_operator(grid, reduced_modulus, symmetric=True, threads=threads)
    return unfold_quadrant(op(quadrant(p)))


#: Relative tolerance of the evenness check in :func:`surface_displacement` (rounding of x^2 terms).
_EVEN_RTOL = 1e-12


def quadrant(field) -> np.ndarray:
    """Return the ``x > 0, y > 0`` quadrant of a full-grid field with even nx, ny.

    Parameters
    ----------
    field : array_like, shape (..., nx, ny)
        Field on the full grid; nx and ny must be even.

    Returns
    -------
    ndarray, shape (..., nx/2, ny/2)
        A contiguous copy of the quadrant.

    Raises
    ------
    ValueError
        If nx or ny is odd.
    """
    f = np.asarray(field)
    nx, ny = f.shape[-2:]
    if nx % 2 or ny % 2:
        raise ValueError(f"field must have even dimensions for a quadrant; got shape {f.shape}")
    return np.ascontiguousarray(f[..., nx // 2:, ny // 2:])


def unfold_quadrant(q) -> np.ndarray:
    """Return the full even-even field from its ``x > 0, y > 0`` quadrant.

    Parameters
    ----------
    q : array_like, shape (..., nx/2, ny/2)
        The quadrant, as returned by :func:`quadrant`.

    Returns
    -------
    ndarray, shape (..., nx, ny)
        The field mirrored into all four quadrants (even in x and in y).
    """
    q = np.asarray(q)
    half = np.concatenate([q[..., ::-1, :], q], axis=-2)
    return np.concatenate([half[..., ::-1], half], axis=-1)
