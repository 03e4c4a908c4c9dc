"""Self-consistent adhesive normal contact on the elastic half-space (DC-FFT BEM): one state.

This is the ground truth the analytic closures are checked against: a
free-boundary (non-periodic) boundary-element solver for the adhesive normal
contact of two elastic bodies with an arbitrary initial gap z(x, y), under
displacement control, with a Dugdale (Maugis) or an exponential traction law
(:mod:`dhfield.bem.laws`).

Problem
-------
Unknowns are the repulsive (contact) pressure ``p >= 0`` and the adhesive
stress ``s`` per cell.  With the DC-FFT operator K (:mod:`dhfield.bem.operator`)
and the approach delta,

.. math::

    h = z - \\delta + K(p - s) \\ge 0, \\quad p \\ge 0, \\quad p\\,h = 0,
    \\qquad s = \\sigma(h),

the traction law acting over the whole surface (also inside the contact, where
h = 0 and s = sigma0, as in Maugis' model).  The total pressure is ``p - s``
and the load ``W = sum (p - s) dx dy``.

Algorithm
---------
* **An adhesive state** is solved by the semismooth Newton (primal-dual active-set) method of
  :mod:`dhfield.bem.newton`, the project's one adhesive solver, with one start protocol
  (:func:`solve_problem`): Newton from the route's start (the converged neighbour, or the same
  approach on a coarser grid), else nested iteration from the coarsest grid of the domain
  (:func:`nested_solve`).  Before 2026-12-02 it was a fixed point (Polonsky-Keer CG inside,
  Anderson-mixed cohesive zone outside) with a sub-cell zone edge; docs/theory/bem.rst keeps
  why it was replaced.
* **The non-adhesive contact** (and the contact pressure of a cold start with a given adhesive
  stress, :func:`solve_contact_pressure`) is solved by the Polonsky-Keer constrained conjugate
  gradient (displacement control: the gradient is the gap on the active set; cells that overlap
  are added, cells that go tensile are released and conjugacy is reset; Polonsky & Keer 1999).
* **Stable discrete edge**: a discrete state is energy-stable only if the spectral radius of
  ``|d sigma/dh| K`` is below 1, and for a ring of edge cells K sums to ~(2/pi) ln(c/dx) dx/E*.
  The Dugdale edge is therefore a ramp in the gap at least
  ``EDGE_WIDTH_FACTOR (1 + (2/pi) ln n) sigma0 dx/E*`` wide (capped at 2 h0, symmetric about h0
  so the work of adhesion is unchanged; it vanishes like dx ln(1/dx)).  Grids that would need
  more than 2 h0 are flagged ``resolved=False``: in the paper's units that is roughly
  dx > 2/(kappa_n mu^2), i.e. mu = 5 needs n >~ 512.
* **Symmetry**: when z is even in x and y (and nx, ny are even) the solver
  works on the quadrant ``x > 0, y > 0`` with the operator's symmetry mode
  (a quarter of the unknowns, the same discrete sum); the returned state is
  always on the full grid.


Units
-----
Any consistent units: lengths (z, delta, grid cells), stresses (E*, the law's
sigma0) and forces (load = stress x area).  :func:`adhesive_pull_off` uses the
paper's (R = E* = Delta gamma = 1, Eqs. 32-35).


References
----------
.. [1] I. A. Polonsky, L. M. Keer (1999) A numerical method for solving rough
   contact problems based on the multi-level multi-summation and conjugate
   gradient techniques. Wear 231:206-219. doi:10.1016/S0043-1648(99)00113-1
.. [2] D. Maugis (1992) Adhesion of spheres: the JKR-DMT transition using a
   Dugdale model. J. Colloid Interface Sci. 150:243-269.
   doi:10.1016/0021-9797(92)90288-C
.. [3] M. Hintermueller, K. Ito, K. Kunisch (2002) The primal-dual active set strategy as
   a semismooth Newton method. SIAM J. Optim. 13:865-888. doi:10.1137/S1052623401383558
.. [4] N. H. M. Zini et al. (2018) Tribol. Lett. 66:30. doi:10.1007/s11249-017-0976-8
"""
from __future__ import annotations

import functools
import math
from dataclasses import dataclass, replace
from typing import NamedTuple

import numpy as np
from scipy.fft import next_fast_len

from ..core.validation import check_finite, check_positive
from .backend import array_module, to_host
from .laws import DugdaleLaw, cell_fraction_below, check_law
from .operator import MIN_CELLS, Grid, get_operator, influence_coefficients, quadrant, unfold_quadrant
from .state import ContactState

__all__ = ["solve_adhesive", "AdhesiveProblem", "edge_width_ratio", "Prediction", "solve_problem", "secant_prediction",
           "DEFAULT_TOL", "DEFAULT_MAX_ITER", "solve_contact_pressure", "ContactPressureSolution",
           "assemble_state", "extrapolated_start", "nested_solve", "coarser_problem", "start_traction", "state_options",
           "newton_contact_state"]

#: Default solver tolerance: an adhesive state's ``max |min(h/h0, p/sigma0)|``
#: (:attr:`dhfield.bem.newton.SolverOptions.tol`), or the non-adhesive contact's complementarity
#: error relative to |delta| [-].
DEFAULT_TOL = 1e-6
#: Default cap on the conjugate-gradient iterations of a non-adhesive state, and on the GMRES
#: iterations of each linear solve of an adhesive one (at most ``SolverOptions.max_krylov``).
DEFAULT_MAX_ITER = 20000
#: Smallest width (in gap) of the Dugdale edge's ramp, as a multiple of
#: kappa_n sigma0 dx/E* with kappa_n = 1 + (2/pi) ln n (n cells per axis): the cell
#: fraction is taken over at least this gap spread.  Energy stability of a discrete
#: state needs the spectral radius of |d sigma/dh| K below 1; for a ring of edge cells
#: K sums to ~(2/pi) ln(c/dx) dx/E*, so an edge narrower than that makes every discrete
#: state unstable (lattice trapping: no converged state, jumps).  The regularisation is
#: symmetric about h0 (the work of adhesion is unchanged) and vanishes like dx ln(1/dx).
#: It is capped at 2 h0; a grid that would need more is under-resolved
#: (``resolved=False`` in the results: the process zone c - a is not resolved, expect
#: unconverged states), which needs roughly dx < 2 E* h0/(kappa_n sigma0), i.e.
#: dx < 2/(kappa_n mu^2) in the paper's units.
EDGE_WIDTH_FACTOR = 1.25
#: Evenness tolerance for the automatic symmetry mode (relative to max |z|).
_EVEN_RTOL = 1e-12


# ============================================================================ helpers
def _is_even_even(z):
    nx, ny = z.shape
    if nx % 2 or ny % 2:
        return False
    tol = _EVEN_RTOL * max(float(np.max(np.abs(z))), 1e-300)
    return bool(np.max(np.abs(z - z[::-1, :])) <= tol and np.max(np.abs(z - z[:, ::-1])) <= tol)


def edge_width_ratio(grid, law, reduced_modulus=1.0) -> float:
    """How far a grid is from resolving a traction law's edge: resolved iff <= 1 [-].

    Parameters
    ----------
    grid : Grid
        The cell grid (cells dx x dy, nx x ny).
    law : DugdaleLaw or ExponentialLaw
        The traction law (sigma0, range).
    reduced_modulus : float
        E* [stress].

    Returns
    -------
    float
        Dugdale: the edge width wanted, ``kappa sigma0 sqrt(dx dy)/E*`` with
        ``kappa = EDGE_WIDTH_FACTOR (1 + (2/pi) ln sqrt(nx ny))``, per its cap 2 h0
        (:data:`EDGE_WIDTH_FACTOR`).  A smooth law: its steepest slope sigma0/rho times
        the edge cells' compliance ``kappa sqrt(dx dy)/E*`` (the same criterion: the
        smeared Dugdale edge has the slope sigma0/(2 h0)).

    Notes
    -----
    The ratio falls like ln(n)/n as the cells shrink; in the paper's units (sigma0 = mu,
    h0 = 1/mu) it is ``kappa mu^2 sqrt(dx dy)/2`` for the Dugdale law, so a case at mu needs
    cells ``sqrt(dx dy) <= 2/(kappa mu^2)`` (:func:`dhfield.analysis.bem_start.required_cells`).
    """
    want = _edge_compliance(grid, float(reduced_modulus)) * law.max_stress
    return want / (2.0 * law.range) if isinstance(law, DugdaleLaw) else want / law.range


def _edge_compliance(grid, reduced_modulus):
    """kappa sqrt(dx dy)/E*: the compliance of a ring of edge cells (see EDGE_WIDTH_FACTOR)."""
    kappa = EDGE_WIDTH_FACTOR * (1.0 + 2.0 / math.pi * math.log(math.sqrt(grid.nx * grid.ny)))
    return kappa * math.sqrt(grid.dx * grid.dy) / reduced_modulus


class AdhesiveProblem:
    """Working arrays of one (grid, z, law) problem: full grid or even-even quadrant.

    Parameters
    ----------
    initial_gap : array_like, shape (nx, ny)
        Initial gap z(x, y) at the cell centres of ``grid`` [length].
    grid : Grid
        The full cell grid.
    law : DugdaleLaw, ExponentialLaw or None
        Traction-separation law; None for non-adhesive contact.
    symmetric : bool or None
        Work on the even-even quadrant; None: when z is even in x and y and nx, ny are even.
    threads : int or None
        FFTW threads (None: :func:`dhfield.bem.operator.default_threads`).
    reduced_modulus : float
        E* [stress].
    backend : str, optional
        Array backend of the working arrays (:mod:`dhfield.bem.backend`); default
        ``$DHFIELD_BEM_BACKEND`` or ``"fftw"``.  The working arrays (``z``, and those of the
        solve) are the backend's; :meth:`to_full` returns numpy arrays.

    Raises
    ------
    ValueError
        If ``grid`` is not a :class:`Grid`, ``initial_gap`` is not finite or not of the grid's
        shape, ``law`` is not a traction law, or ``symmetric=True`` for an uneven problem.
    """

    def __init__(self, initial_gap, grid, law, symmetric, threads, reduced_modulus, *, backend=None):
        if not isinstance(grid, Grid):
            raise ValueError(f"grid must be a dhfield.bem.Grid; got {type(grid).__name__}")
        z = check_finite("initial_gap", initial_gap, "initial gap z(x, y), length")
        if z.shape != grid.shape:
            raise ValueError(f"initial_gap must have the grid shape {grid.shape}; got {z.shape}")
        self.law = check_law(law)
        even = _is_even_even(z)
        if symmetric is None:
            symmetric = even
        elif symmetric and not even:
            raise ValueError("symmetric=True needs even nx, ny and an initial_gap even in x and in y")
        self.symmetric = bool(symmetric)
        self.grid = grid
        self.op = get_operator(grid, reduced_modulus, symmetric=self.symmetric, threads=threads, backend=backend)
        self._built_with = (threads, float(reduced_modulus), backend)      # (coarser_problem)
        self.xp = self.op.xp
        self.z = self.work_array(quadrant(z) if self.symmetric else z)
        self.z_full = z
        # self-influence K00 (centre of a loaded cell), for the cold-start pressure
        e = float(reduced_modulus)
        dx, dy = grid.dx, grid.dy
        d = math.hypot(dx, dy)
        self.k0 = (dx * math.log((dy + d) / (d - dy)) + dy * math.log((dx + d) / (d - dx))) / (math.pi * e)
        self.weight = (4.0 if self.symmetric else 1.0) * grid.dx * grid.dy
        # smallest edge width of the Dugdale zone (see EDGE_WIDTH_FACTOR)
        self.min_spread = 0.0
        self.widest_spread = 0.0      # the Dugdale edge's cap 2 h0 (0 for other laws)
        self.resolved = True
        self.edge_width_ratio = 0.0
        if self.law is not None:
            ratio = edge_width_ratio(grid, self.law, e)
            self.resolved = ratio <= 1.0
        if isinstance(self.law, DugdaleLaw):
            # wanted edge width per its cap 2 h0 (the located search's gate reads it)
            self.edge_width_ratio = ratio
            # at most 2 h0: the smeared edge stays within h >= 0 and keeps the work of adhesion
            want = _edge_compliance(grid, e) * self.law.max_stress
            self.widest_spread = 2.0 * self.law.range
            self.min_spread = min(want, self.widest_spread)

    def work_array(self, a):
        """Return an array as a contiguous float array of the working backend (moved there if need be).

        Parameters
        ----------
        a : array_like
            Field on the working grid.

        Returns
        -------
        array
            ``a`` as an array of ``self.xp`` (no copy when it already is one).
        """
        return self.xp.ascontiguousarray(self.xp.asarray(a, dtype=float))

    def to_full(self, q):
        """Return a working-grid field on the full grid, on the host.

        Parameters
        ----------
        q : array
            Field on the working grid (the quadrant in symmetric mode).

        Returns
        -------
        ndarray
            The field on the full grid as a numpy array (unfolded in symmetric mode, else
            ``q`` itself on the fftw and numpy backends).
        """
        q = to_host(q)
        return unfold_quadrant(q) if self.symmetric else q

    def to_work(self, f):
        """Return a full-grid field on the working grid.

        Parameters
        ----------
        f : ndarray, shape (nx, ny)
            Field on the full grid.

        Returns
        -------
        array
            Its quadrant in symmetric mode (a copy), else ``f`` as a contiguous array, on the
            working backend.
        """
        f = to_host(f)
        return self.xp.ascontiguousarray(self.xp.asarray(quadrant(f) if self.symmetric else f))

    def gradient_spreads(self, h):
        """Compute the gap's variation across each cell, for the sub-cell Dugdale edge.

        Central differences, mirrored at the symmetry axes in symmetric mode; spreads below
        the smallest edge width ``min_spread`` are scaled up to it.

        Parameters
        ----------
        h : ndarray
            Gap on the working grid [length].

        Returns
        -------
        sx : ndarray
            The variation ``|dh/dx| dx`` along x per cell [length].
        sy : ndarray
            The variation ``|dh/dy| dy`` along y per cell [length].
        """
        if self.symmetric:
            # central differences; at the symmetry axes (index 0) the mirror image h[-1] = h[0],
            # one-sided at the outer edge (slices instead of padded copies: the same values)
            sx = np.empty_like(h)
            sy = np.empty_like(h)
            np.subtract(h[2:], h[:-2], out=sx[1:-1])
            np.subtract(h[1], h[0], out=sx[0])
            np.subtract(h[-1], h[-2], out=sx[-1])
            np.subtract(h[:, 2:], h[:, :-2], out=sy[:, 1:-1])
            np.subtract(h[:, 1], h[:, 0], out=sy[:, 0])
            np.subtract(h[:, -1], h[:, -2], out=sy[:, -1])
            np.abs(sx, out=sx)
            np.abs(sy, out=sy)
            sx[:-1] *= 0.5
            sy[:, :-1] *= 0.5
        else:
            gx, gy = np.gradient(h)
            sx, sy = np.abs(gx), np.abs(gy)
        if self.min_spread > 0.0:
            # spreads below min_spread are scaled up to it (factor 1 elsewhere: unchanged);
            # a flat cell gets it along x.  Whole-array operations: no boolean gathers.
            tot = sx + sy
            f = np.divide(self.min_spread, np.maximum(tot, 1e-300))
            np.maximum(f, 1.0, out=f)
            sx *= f
            sy *= f
            flat = tot == 0.0
            np.copyto(sx, self.min_spread, where=flat)
            np.copyto(sy, 0.0, where=flat)
        return sx, sy

    def stress_from_gap(self, h, contact):
        """Compute the adhesive stress per cell for the gap h (the fixed-point map).

        Parameters
        ----------
        h : ndarray
            Gap on the working grid [length].
        contact : ndarray of bool
            Cells in contact (full adhesive stress for the Dugdale law).

        Returns
        -------
        ndarray
            Tensile stress per cell, in [0, sigma0]: sigma0 times the sub-cell zone fraction
            (Dugdale), or sigma(max(h, 0)) for a smooth law [stress].
        """
        law = self.law
        if isinstance(law, DugdaleLaw):
            sx, sy = self.gradient_spreads(h)
            chi = cell_fraction_below(law.range - h, sx, sy)
            chi[contact] = 1.0
            return law.max_stress * chi
        return law.stress(np.maximum(h, 0.0))

    def stress_of_state(self, state):
        """Compute the adhesive stress of a solved state, to start the fixed point from.

        Parameters
        ----------
        state : ContactState
            A solved state on this problem's grid.

        Returns
        -------
        ndarray
            Stress on the working grid: sigma0 times the state's contact U zone fraction
            (Dugdale), or sigma(h) of its gap for a smooth law [stress].
        """
        law = self.law
        if isinstance(law, DugdaleLaw):
            return law.max_stress * self.to_work(state.adhesive_zone)
        return law.stress(np.maximum(self.to_work(state.gap), 0.0))

    def zone_fraction(self, h, contact):
        """Compute the fraction of each cell in contact U zone (h below the law's zone gap).

        Parameters
        ----------
        h : ndarray
            Gap on the working grid [length].
        contact : ndarray of bool
            Cells in contact (fraction 1).

        Returns
        -------
        ndarray
            Fraction in [0, 1] per cell of the working grid [-].
        """
        sx, sy = self.gradient_spreads(h)
        chi = cell_fraction_below(self.law.zone_gap - h, sx, sy)
        chi[contact] = 1.0
        return chi


def _complementarity(h, active):
    """max of |h| on the active set and of max(-h, 0) off it."""
    if h.size == 0:
        return 0.0
    v = np.where(active, np.abs(h), -h)
    return max(float(v.max()), 0.0)


def _dot(a, b):
    """Inner product without BLAS (a threaded BLAS ddot is very slow on a loaded machine)."""
    return float(np.einsum("ij,ij->", a, b))


#: Largest number of direct-sum terms (cells whose pressure a Polonsky-Keer step changes
#: beyond the CG update, i.e. released or newly loaded, times their 4 mirror images in
#: symmetric mode) for which the gap is corrected by adding influence coefficients instead
#: of a new convolution.  One term is two passes over the working grid; a convolution
#: costs ~7x (N = 256) to ~25x (N = 512) one term (symmetric quadrant).
DIRECT_CORRECTION_TERMS = 16


@functools.lru_cache(maxsize=4)
def _extended_kernel(grid, reduced_modulus):
    """Influence coefficients for every signed offset, ``E[u + nx - 1, v + ny - 1] = K[|u|, |v|]``."""
    k = influence_coefficients(grid, reduced_modulus)[:grid.nx, :grid.ny]
    k = np.concatenate([k[:0:-1], k], axis=0)
    return np.ascontiguousarray(np.concatenate([k[:, :0:-1], k], axis=1))


@functools.lru_cache(maxsize=4)
def _backend_kernel(grid, reduced_modulus, backend):
    """:func:`_extended_kernel` as an array of the backend (a copy on the GPU)."""
    ext = _extended_kernel(grid, reduced_modulus)
    return ext if backend in ("fftw", "numpy") else array_module(backend)[0].asarray(ext)


def _add_point_loads(op, h, cells, amounts):
    """h += K(amounts at cells) by direct summation (4 mirror images in symmetric mode)."""
    ext = _backend_kernel(op.grid, op.reduced_modulus, op.backend)
    nx, ny = op.grid.shape
    mx, my = h.shape
    cells = tuple(to_host(c).tolist() for c in cells)
    for (i, j), a in zip(zip(*cells), to_host(amounts).tolist()):
        if op.symmetric:
            rows = (slice(nx - 1 - i, nx - 1 - i + mx), slice(nx + i, nx + i + mx))
            cols = (slice(ny - 1 - j, ny - 1 - j + my), slice(ny + j, ny + j + my))
            for r in rows:
                for c in cols:
                    h += a * ext[r, c]
        else:
            h += a * ext[nx - 1 - i:2 * nx - 1 - i, ny - 1 - j:2 * ny - 1 - j]


#: Smallest grid (cells per axis) of the nested cold start of :func:`solve_contact_pressure`.
NESTED_COLD_MIN_N = 64


def _nested_cold_start(op, g0, scale, tol, max_iter, k0):
    """Pressure of the same contact problem on the grid half as fine (recursively), or None.

    The gap is restricted by 2 x 2 cell averages and the coarse pressure prolonged as
    piecewise constant: a cold start whose smooth error is gone (Hertz N = 512: ~50 fine CG
    iterations instead of 74, the coarse ones costing ~1/5 each).
    """
    grid = op.grid
    if min(grid.nx, grid.ny) < 2 * NESTED_COLD_MIN_N or grid.nx % 4 or grid.ny % 4:
        return None, 0
    coarse = Grid(grid.nx // 2, grid.ny // 2, 2.0 * grid.dx, 2.0 * grid.dy)
    cop = get_operator(coarse, op.reduced_modulus, symmetric=op.symmetric, threads=op.threads, backend=op.backend)
    gc = 0.25 * (g0[0::2, 0::2] + g0[1::2, 0::2] + g0[0::2, 1::2] + g0[1::2, 1::2])
    # the self-influence of a cell scales with its size
    pc, _, it, _ = solve_contact_pressure(cop, gc, np.zeros_like(gc), scale, tol, max_iter, 2.0 * k0)
    return np.repeat(np.repeat(pc, 2, axis=0), 2, axis=1), it


#: The CG runs on the box of cells that can touch when that box (rounded up to an
#: FFT-friendly size) holds at most this fraction of the working cells: below it the
#: smaller transforms and vectors outweigh the two working-grid convolutions that
#: frame the cropped solve (Hertz N = 512: box 0.13 of the cells, ~6x faster).
CROP_MAX_FRACTION = 0.5
#: Cells added around the box of negative free gap (rounding of the free gap's convolution).
CROP_MARGIN = 2
#: With an adhesive stress the bound above covers the cohesive zone; the CG then runs on a
#: box around the warm start's contact (p > 0 or h < 0) plus this many cells (the edge
#: moves by about a cell between outer iterations), checked afterwards on the whole grid
#: (sphere N = 256, lambda = 1 and 3: 1 whole-grid completion in 477 box solves).
ACTIVE_BOX_MARGIN = 2
#: ... when that box holds at most this fraction of the working cells: a box solve costs
#: two whole-grid convolutions (gap, completion) plus ~9 on the box, against ~9 on the
#: whole grid (sphere N = 256: ~30 % less CPU on the path with boxes of 0.5-0.6 of the quadrant).
ACTIVE_BOX_MAX_FRACTION = 0.8


def _crop_size(cells, available):
    """Smallest even 5-smooth size >= cells (FFT-friendly on the doubled DC-FFT grid), capped at ``available``.

    Even 5-smooth numbers are twice the 5-smooth ones (``scipy.fft.next_fast_len`` for real transforms).
    """
    k = 2 * next_fast_len(-(-int(cells) // 2), real=True)
    return k if k < available else available


def _box(op, mask, margin, max_fraction):
    """(operator, index box) around the cells of ``mask`` plus ``margin`` cells, or None.

    The box is rounded up to FFT-friendly sizes; None when ``mask`` is empty or the box
    holds more than ``max_fraction`` of the working cells.  In symmetric mode the box
    is the quadrant's corner at the origin, i.e. a centred sub-grid.
    """
    rows = np.flatnonzero(mask.any(axis=1))
    if rows.size == 0:
        return None
    cols = np.flatnonzero(mask.any(axis=0))
    mx, my = mask.shape
    grid = op.grid
    if op.symmetric:
        kx = _crop_size(int(rows[-1]) + 1 + margin, mx)
        ky = _crop_size(int(cols[-1]) + 1 + margin, my)
        i0 = j0 = 0
        sub = (2 * kx, 2 * ky)
    else:
        kx = _crop_size(int(rows[-1] - rows[0]) + 1 + 2 * margin, mx)
        ky = _crop_size(int(cols[-1] - cols[0]) + 1 + 2 * margin, my)
        i0 = min(max(int(rows[0]) - margin, 0), mx - kx)
        j0 = min(max(int(cols[0]) - margin, 0), my - ky)
        sub = (kx, ky)
    if kx * ky > max_fraction * mx * my or min(sub) < MIN_CELLS:
        return None
    sub_op = get_operator(Grid(sub[0], sub[1], grid.dx, grid.dy), op.reduced_modulus,
                          symmetric=op.symmetric, threads=op.threads, backend=op.backend)
    return sub_op, (slice(i0, i0 + kx), slice(j0, j0 + ky))


def _contact_box(op, free_gap):
    """(operator, index box) of the cells that can touch, or None when cropping does not pay.

    Every influence coefficient is positive (Love's solution), so for p >= 0 the gap
    ``free_gap + K p >= free_gap``: no cell with a non-negative free gap ever touches.
    The contact problem restricted to the box of cells with a negative free gap is
    therefore the same discrete problem (the operator is translation invariant: the box's
    own DC-FFT operator applies the same influence coefficients).  In symmetric mode the
    box is the quadrant's corner at the origin, i.e. a centred sub-grid.
    """
    return _box(op, free_gap < 0.0, CROP_MARGIN, CROP_MAX_FRACTION)


class ContactPressureSolution(NamedTuple):
    """Result of :func:`solve_contact_pressure` (working arrays of the operator's shape).

    Parameters
    ----------
    pressure : ndarray
        Repulsive pressure p >= 0 [stress].
    gap : ndarray
        Gap h = g0 + K(p - stress) [length].
    iterations : int
        CG iterations, on every grid (coarse and box ones included).
    error : float
        Complementarity error / scale [-].
    """

    pressure: np.ndarray     #: repulsive pressure p >= 0 [stress]
    gap: np.ndarray          #: gap h = g0 + K(p - stress) [length]
    iterations: int          #: CG iterations, on every grid (coarse and box ones included)
    error: float             #: complementarity error / scale [-]


def solve_contact_pressure(op, free_gap, pressure, scale, tol, max_iter, self_influence,
                           stress=None) -> ContactPressureSolution:
    """Repulsive pressure of the contact problem with a known tensile stress (Polonsky-Keer CG).

    Solves, on the working grid of ``op`` (the quadrant in symmetric mode),

    .. math:: h = g_0 + K(p - s) \\ge 0, \\quad p \\ge 0, \\quad p\\,h = 0,

    i.e. min 1/2 p.Kp + (g0 - K s).p over p >= 0, by the constrained conjugate gradient
    of Polonsky & Keer (1999) under displacement control.  Without a stress the CG runs
    on the box of cells with ``g0 < 0`` when that box is small (:func:`_contact_box`:
    every influence coefficient is positive, so no other cell can touch; the same
    discrete problem), and the gap is completed on the working grid by one convolution.
    With an adhesive stress the bound ``g0 - K s`` is negative over about the whole
    cohesive zone (at lambda = 3, N = 256: the whole quadrant), so the CG runs
    instead on a box around the warm start's contact and is checked on the whole grid
    (:func:`_active_box_cg`).  A cold start without stress begins from the same problem
    on the grid half as fine (:func:`_nested_cold_start`).

    Parameters
    ----------
    op : HalfSpaceOperator
        The DC-FFT operator K of the working grid.
    free_gap : ndarray
        The free gap g0 = z - delta on the working grid [length].
    pressure : ndarray
        Warm start p (clipped at 0; zeros for a cold start) [stress].
    scale : float
        Gap scale of the complementarity error (e.g. h0 or |delta|) [length].
    tol : float
        Tolerance on the complementarity error / scale [-].
    max_iter : int
        Cap on the CG iterations.
    self_influence : float
        K00, the displacement of a cell under its own unit pressure (cold starts)
        [length/stress].
    stress : ndarray, optional
        Known tensile (adhesive) stress s on the working grid [stress].

    Returns
    -------
    ContactPressureSolution
        Pressure, gap, iterations and the complementarity error / scale.
    """
    return ContactPressureSolution(*_contact_pressure(op, free_gap, pressure, scale, tol, max_iter,
                                                      self_influence, stress))


def _contact_pressure(op, g0, p, scale, tol, max_iter, k0, stress):
    """The body of :func:`solve_contact_pressure`: (p, h, iterations, error)."""
    xp = op.xp
    p = xp.array(p, dtype=float, copy=True)
    np.maximum(p, 0.0, out=p)
    if stress is not None:
        return _active_box_cg(op, g0, p, scale, tol, max_iter, k0, stress)
    box = _contact_box(op, g0)
    if box is None:
        return _constrained_cg(op, g0, p, scale, tol, max_iter, k0, stress)
    sub_op, sl = box
    pc, _, it, _ = _constrained_cg(sub_op, xp.ascontiguousarray(g0[sl]), xp.ascontiguousarray(p[sl]),
                                   scale, tol, max_iter, k0, None, exact_gap=False)
    p = np.zeros_like(g0)
    p[sl] = pc
    h = g0 + op(p)
    return p, h, it, _complementarity(h, p > 0) / scale


def _active_box_cg(op, g0, p, scale, tol, max_iter, k0, stress):
    """The CG with a known stress, on a box around the warm start's contact when that pays.

    The box holds every cell of the warm start with p > 0 or h < 0, plus
    ``ACTIVE_BOX_MARGIN`` cells.  p vanishes outside it, so on the box K p is the box's
    own convolution and the free gap there is ``h - K_box p``.  The solution is checked on
    the whole grid (one convolution); if a cell outside the box overlaps, the CG goes on
    over the whole grid from there, so the result is always the whole-grid problem's.
    """
    if not np.any(p > 0):
        return _constrained_cg(op, g0, p, scale, tol, max_iter, k0, stress)
    h = g0 + op(p - stress)
    box = _box(op, (p > 0) | (h < 0.0), ACTIVE_BOX_MARGIN, ACTIVE_BOX_MAX_FRACTION)
    if box is None:
        return _constrained_cg(op, g0, p, scale, tol, max_iter, k0, stress, h=h)
    sub_op, sl = box
    pb = op.xp.ascontiguousarray(p[sl])
    hb = op.xp.ascontiguousarray(h[sl])
    pc, _, it, _ = _constrained_cg(sub_op, hb - sub_op(pb), pb.copy(), scale, tol, max_iter, k0, None,
                                   h=hb.copy(), exact_gap=False)   # (p is updated in place)
    dp = np.zeros_like(p)
    dp[sl] = pc - pb
    p[sl] = pc
    h += op(dp)
    err = _complementarity(h, p > 0) / scale
    if err <= tol:
        return p, h, it, err
    # a cell outside the box touches: finish on the whole grid
    p, h, it2, err = _constrained_cg(op, g0, p, scale, tol, max(max_iter - it, 1), k0, stress, h=h)
    return p, h, it + it2, err


def _constrained_cg(op, g0, p, scale, tol, max_iter, k0, stress, h=None, exact_gap=True):
    """The Polonsky-Keer iteration for ``h = g0 + K(p - stress)`` on ``op``'s grid (p >= 0, owned).

    ``h``: the gap of ``p`` if already known (a cold start, p = 0, without stress starts
    from the coarser grid, :func:`_nested_cold_start`); ``exact_gap``: end with a
    fresh convolution of the gap (False when the caller completes the gap itself: the
    box solves, whose returned gap is discarded).
    """

    def gap(p):
        return g0 + op(p if stress is None else p - stress)

    coarse_it = 0
    if np.any(p > 0):
        h = gap(p) if h is None else h
    else:
        h = gap(p) if stress is not None else g0.copy()
        neg = h < 0
        if not np.any(neg):
            return p, h, 0, 0.0          # empty active set: linear, done
        pc = None
        if stress is None:               # cold start of a contact problem: from the coarser grid
            pc, coarse_it = _nested_cold_start(op, g0, scale, tol, max_iter, k0)
        if pc is not None and np.any(pc > 0):
            p = pc
        else:
            p[neg] = -h[neg] / k0        # cold start: local (Jacobi) estimate
        h = gap(p)
    t = np.zeros_like(p)
    r = np.empty_like(p)
    kt = np.empty_like(p)
    g_old = 1.0
    conj = False
    it = 0
    since_full = 0
    active = p > 0
    err = _complementarity(h, active) / scale
    while err > tol and it < max_iter:
        it += 1
        np.multiply(h, active, out=r)
        g = _dot(r, r)
        if conj and g_old > 0.0:
            t *= g / g_old
            t += r
        else:
            t[...] = r
        g_old = g
        op(t, out=kt)
        den = _dot(kt, t)
        if not den > 0.0:
            break
        tau = _dot(h, t) / den
        p -= tau * t
        released = p < 0.0
        any_rel = bool(released.any())
        if any_rel:
            rel_cells = np.nonzero(released)
            rel_amounts = -p[rel_cells]
            p[released] = 0.0
        overlap = (~active) & (h < 0.0)
        any_ol = bool(overlap.any())
        if any_ol:
            ol_cells = np.nonzero(overlap)
            ol_amounts = -tau * h[ol_cells]
            p[ol_cells] += ol_amounts
        conj = not any_ol
        since_full += 1
        n_changed = (rel_amounts.size if any_rel else 0) + (ol_amounts.size if any_ol else 0)
        if since_full >= 25 or n_changed * (4 if op.symmetric else 1) > DIRECT_CORRECTION_TERMS:
            h = gap(p)
            since_full = 0
        else:
            # the CG step is linear; cells clipped at zero or newly loaded are few: add them directly
            h -= tau * kt
            if any_rel:
                _add_point_loads(op, h, rel_cells, rel_amounts)
            if any_ol:
                _add_point_loads(op, h, ol_cells, ol_amounts)
        active = p > 0
        err = _complementarity(h, active) / scale
    if since_full and exact_gap:
        h = gap(p)
        err = _complementarity(h, p > 0) / scale
    return p, h, it + coarse_it, err   # CG iterations on every grid (coarse ones are cheaper)


# ============================================================================ solver
def solve_adhesive(initial_gap, grid, approach, law, *, guess=None, tol=DEFAULT_TOL,
                   max_iter=DEFAULT_MAX_ITER, symmetric=None, threads=None,
                   reduced_modulus=1.0) -> ContactState:
    """Adhesive normal contact at a given approach (displacement control), by BEM.

    Parameters
    ----------
    initial_gap : array_like, shape (nx, ny)
        Initial gap z(x, y) >= its minimum at the cell centres of ``grid``
        (e.g. x^2/(2R') + y^2/(2R'') for the crossed cylinders, Eq. 2) [length].
    grid : dhfield.bem.Grid
        Cell grid; the domain must contain the whole cohesive zone (the load is
        the integral over the grid; nothing acts outside it).
    approach : float
        Approach of distant points delta [length]; ``h = z - delta + omega``.
    law : DugdaleLaw, ExponentialLaw or None
        Traction-separation law (:mod:`dhfield.bem.laws`); None for non-adhesive
        (Hertz-type) contact.
    guess : ContactState, optional
        Warm start (a state on the same grid, e.g. the previous state of a path).
        Along a path always warm-start: the adhesive states are multistable.
    tol : float, default DEFAULT_TOL
        Tolerance [-]: ``max |min(h/h0, p/sigma0)|`` of an adhesive state, or the
        complementarity error relative to |delta| and max z without adhesion.
    max_iter : int, default DEFAULT_MAX_ITER
        Cap on the conjugate-gradient iterations without adhesion, or on the GMRES
        iterations of each linear solve of an adhesive state.
    symmetric : bool, optional
        Solve on the even-even quadrant (default: when z is even in x and y and
        nx, ny are even).
    threads : int, optional
        FFTW threads.
    reduced_modulus : float, default 1
        E* [stress].

    Returns
    -------
    ContactState
        On the full grid, with ``converged``, ``iterations``, ``residual``.  An
        unconverged state is returned flagged, never silently.

    Raises
    ------
    ValueError
        If an argument is out of range (naming it): a non-finite gap or approach, a grid
        or gap shape mismatch, ``tol <= 0``, ``max_iter < 1``, or a guess on another grid.

    Notes
    -----
    See the module docstring for the algorithm: the semismooth Newton solve of
    :mod:`dhfield.bem.newton` from ``guess``, else by nested iteration from the coarsest
    grid (:func:`solve_problem`); without a law the Polonsky-Keer CG.
    """
    prob = AdhesiveProblem(initial_gap, grid, law, symmetric, threads, reduced_modulus)
    delta = float(check_finite("approach", approach, "approach of distant points, length"))
    tol = float(check_positive("tol", tol, "solver tolerance, dimensionless"))
    if int(max_iter) < 1:
        raise ValueError(f"max_iter must be an integer >= 1; got {max_iter!r}")
    if guess is not None and not (isinstance(guess, ContactState) and guess.grid == grid):
        raise ValueError("guess must be a ContactState on the same grid")
    return solve_problem(prob, delta, guess, tol, int(max_iter))


def solve_problem(prob, delta, guess, tol, max_iter):
    """Solve a prepared problem at one approach (the body of :func:`solve_adhesive`).

    An adhesive state is solved by the semismooth Newton method of :mod:`dhfield.bem.newton`
    (the project's one adhesive solver), with one start protocol: Newton from ``guess`` (the
    converged neighbour of a path, or the same approach on a coarser grid, as the route
    supplies it); when there is none, or Newton from it does not converge, nested iteration
    from the coarsest grid of this domain (:func:`nested_solve`).  An analytic start (a
    :class:`Prediction` with a zone and no contact pressure) is not a solved state: it goes to
    nested iteration at once, sigma0 on its zone (on the sphere at lambda = 1, N = 64, Newton
    from it ran 60 iterations unconverged before nested iteration solved it in 4 per level).
    Without a law the
    non-adhesive contact is solved by the Polonsky-Keer conjugate gradient.

    Parameters
    ----------
    prob : AdhesiveProblem
        The problem's working arrays.
    delta : float
        Approach of distant points [length].
    guess : ContactState, Prediction or None
        Warm start: a solved state on the same grid, an extrapolated prediction, or None
        for a cold start.
    tol : float
        Tolerance [-]: the non-adhesive contact's complementarity error (relative to |delta|
        and max z); an adhesive state's ``max |min(h/h0, p/sigma0)|``
        (:attr:`dhfield.bem.newton.SolverOptions.tol`).
    max_iter : int
        Cap on the conjugate-gradient iterations (non-adhesive contact), or on the GMRES
        iterations of each linear solve of an adhesive state (at most
        :data:`dhfield.bem.newton.NESTED_OPTIONS` ``.max_krylov``).

    Returns
    -------
    ContactState
        On the full grid, flagged ``converged=False`` when the tolerance was not met
        (``iterations``: CG or GMRES iterations; ``outer_iterations``: Newton iterations).
    """
    law = prob.law
    if law is None:
        zd = prob.z - delta
        scale = max(abs(delta), float(np.max(np.abs(prob.z))) * 1e-3, 1e-300)
        if isinstance(guess, Prediction):
            p = prob.work_array(guess.pressure).copy()
        elif guess is not None and guess.repulsive_pressure is not None:
            p = prob.to_work(guess.repulsive_pressure).copy()
        else:
            p = np.zeros_like(prob.z)
        p, h, it, err = solve_contact_pressure(prob.op, zd, p, scale, tol, max_iter, prob.k0)
        return assemble_state(prob, delta, p, np.zeros_like(p), h, it, err, err <= tol, 1)
    from .newton import solve_state

    options = state_options(tol, max_iter)
    st = None
    gmres = newton = 0
    if guess is not None and not _zone_only(guess):
        st = solve_state(prob, delta, start_traction(prob, guess), options)
        gmres, newton = st.krylov_iterations, st.newton_iterations
    if st is None or not st.converged:
        st = nested_solve(prob, delta, _zone_mask(prob, delta, guess), options)
        gmres, newton = gmres + st.krylov_iterations, newton + st.newton_iterations
    return newton_contact_state(prob, delta, st, gmres, newton)


def state_options(tol, max_iter):
    """The Newton options of every adhesive state :func:`solve_problem` solves.

    Parameters
    ----------
    tol : float
        Tolerance [-] (:attr:`dhfield.bem.newton.SolverOptions.tol`).
    max_iter : int
        Cap on the GMRES iterations of each linear solve [-].

    Returns
    -------
    dhfield.bem.newton.SolverOptions
        :data:`dhfield.bem.newton.NESTED_OPTIONS` with ``tol`` and ``max_krylov`` =
        ``min(max_iter, NESTED_OPTIONS.max_krylov)``.
    """
    from .newton import NESTED_OPTIONS

    return replace(NESTED_OPTIONS, tol=float(tol), max_krylov=min(int(max_iter), NESTED_OPTIONS.max_krylov))


def start_traction(prob, guess):
    """The total traction (positive in compression) a warm start gives the Newton solve.

    Parameters
    ----------
    prob : AdhesiveProblem
        The problem.
    guess : ContactState or Prediction
        A solved state on the problem's grid (its pressure ``p - s``), or a prediction
        (repulsive pressure and adhesive stress on the working grid).

    Returns
    -------
    ndarray
        The traction q on the working grid [stress].
    """
    if isinstance(guess, Prediction):
        return prob.work_array(guess.pressure) - prob.work_array(guess.stress)
    return prob.to_work(guess.pressure)


def _zone_only(guess):
    """True for an analytic start: a :class:`Prediction` with a zone and no contact pressure (not a solved state)."""
    return isinstance(guess, Prediction) and not np.any(guess.pressure)


def _zone_mask(prob, delta, guess):
    """The full-grid cells of the adhesive zone a cold start spreads sigma0 over.

    The guess's contact U cohesive zone when it has one, else the rigid gap's cells below
    the law's zone gap (``z - delta < zone_gap``).
    """
    if isinstance(guess, Prediction):
        m = prob.to_full(np.asarray(guess.stress)) > 0.5 * prob.law.max_stress
    elif guess is not None:
        m = guess.adhesive_zone > 0.5
    else:
        m = None
    if m is None or not m.any():
        m = prob.z_full - delta < prob.law.zone_gap
    return m


def coarser_problem(prob, k) -> "AdhesiveProblem":
    """The same problem on the grid with ``k`` x ``k`` cells merged (same domain, law and symmetry).

    The initial gap of a coarse cell is the mean of its ``k x k`` cells' (the cell-centre
    samples of a smooth gap, averaged: a start's problem, not an answer's).

    Parameters
    ----------
    prob : AdhesiveProblem
        The problem.
    k : int
        Cells merged per axis; both cell counts must be multiples of ``k`` (of ``2 k`` in
        symmetric mode) [-].

    Returns
    -------
    AdhesiveProblem
        On ``(nx/k) x (ny/k)`` cells.
    """
    g = prob.grid
    k = int(k)
    m = 2 * k if prob.symmetric else k
    if k < 1 or g.nx % m or g.ny % m:
        raise ValueError(f"k must divide the cell counts {g.nx} x {g.ny} (times 2 in symmetric mode); got {k!r}")
    z = prob.z_full.reshape(g.nx // k, k, g.ny // k, k).mean(axis=(1, 3))
    threads, e, backend = prob._built_with
    return AdhesiveProblem(z, Grid(g.nx // k, g.ny // k, g.dx * k, g.dy * k), prob.law, prob.symmetric, threads, e,
                           backend=backend)


def nested_solve(prob, delta, zone, options):
    """Solve an adhesive state by nested iteration from sigma0 on ``zone`` on the coarsest grid.

    The grids halve the cells per axis down to at least
    :data:`dhfield.bem.ladder.NESTED_MIN_CELLS` per axis (:func:`dhfield.bem.ladder.nested_levels`);
    the coarsest starts from the adhesive stress sigma0 on ``zone`` and the contact
    pressure it implies (:func:`dhfield.bem.newton.cold_start`), each state is prolonged to
    start the next (:func:`dhfield.bem.newton.solve_state_nested`).

    Parameters
    ----------
    prob : AdhesiveProblem
        The problem (the finest grid).
    delta : float
        Approach [length].
    zone : ndarray of bool, shape (nx, ny)
        Full-grid cells of the start's adhesive zone.
    options : SolverOptions
        Options of the finest grid.

    Returns
    -------
    NewtonResult
        The finest grid's state.
    """
    from .ladder import nested_levels
    from .newton import cold_start_on, solve_state_nested

    nx, ny = prob.grid.nx, prob.grid.ny
    levels = nested_levels(nx, ny)
    while levels > 1 and (nx % (2 ** levels) or ny % (2 ** levels)):
        levels -= 1
    ladder = [coarser_problem(prob, 2 ** j) for j in range(levels - 1, 0, -1)] + [prob]
    k = 2 ** (levels - 1)
    coarse_zone = zone.reshape(nx // k, k, ny // k, k).mean(axis=(1, 3)) >= 0.5
    return solve_state_nested(ladder, float(delta), cold_start_on(ladder[0], float(delta), coarse_zone),
                              options).state


def newton_contact_state(prob, delta, state, gmres, newton) -> ContactState:
    """The full-grid :class:`ContactState` of a Newton state of ``prob``.

    Parameters
    ----------
    prob : AdhesiveProblem
        The problem it solves.
    delta : float
        Its approach [length].
    state : NewtonResult
        The state (:func:`dhfield.bem.newton.solve_state`).
    gmres, newton : int
        GMRES and Newton iterations spent on it (recorded as ``iterations`` and
        ``outer_iterations``).

    Returns
    -------
    ContactState
        Repulsive pressure ``q + sigma(h)`` on the contact cells (zero elsewhere), the adhesive
        stress ``sigma(h)`` of the grid's ramped law (sigma0 on the contact), the gap.
    """
    from .newton import ramp_stress

    s = ramp_stress(prob, state.gap)
    p = np.where(state.contact, state.traction + s, 0.0)
    st = assemble_state(prob, delta, p, s, state.gap, gmres, state.residual, state.converged, newton)
    if isinstance(prob.law, DugdaleLaw):
        # the cohesive fraction of the ramped law itself (sigma/sigma0 off the contact), so that the
        # state's adhesive force sigma0 x (contact U zone area) is the integral of its stress
        st = replace(st, cohesive=np.where(st.contact, 0.0, prob.to_full(s) / prob.law.max_stress))
    return st


@dataclass
class Prediction:
    """Warm start extrapolated along a path (working arrays: repulsive pressure, stress).

    Parameters
    ----------
    pressure : ndarray
        Repulsive pressure on the working grid, >= 0 [stress].
    stress : ndarray
        Adhesive (tensile) stress on the working grid, in [0, sigma0] [stress].
    """

    pressure: np.ndarray
    stress: np.ndarray


def secant_prediction(prob, prev, last, delta):
    """Predict the warm start at ``delta`` from the last two states of a path.

    Parameters
    ----------
    prob : AdhesiveProblem
        The problem both states solve.
    prev, last : ContactState or None
        The two previous states of the path, in order.
    delta : float
        Next approach [length].

    Returns
    -------
    Prediction or ContactState or None
        The secant extrapolation (:func:`extrapolated_start`) when both states converged on
        the same branch (both in contact or both not) and the step ratio t is in (0, 1.5];
        else ``last``.
    """
    if prev is None or last is None or not (prev.converged and last.converged):
        return last
    if prev.in_contact != last.in_contact or prev.approach == last.approach:
        return last
    t = (delta - last.approach) / (last.approach - prev.approach)
    if not 0.0 < t <= 1.5:
        return last
    return extrapolated_start(prob, prev, last, t)


def extrapolated_start(prob, prev, last, t) -> Prediction:
    """Extrapolate a warm start ``last + t (last - prev)`` from two solved states.

    Parameters
    ----------
    prob : AdhesiveProblem
        The (adhesive) problem both states solve.
    prev, last : ContactState
        Two solved states on the problem's grid, with repulsive pressures.
    t : float
        Extrapolation factor [-].

    Returns
    -------
    Prediction
        Pressure clipped at >= 0 and stress clipped to [0, sigma0], on the working grid.
    """
    s1, s0 = prob.stress_of_state(last), prob.stress_of_state(prev)
    p1, p0 = prob.to_work(last.repulsive_pressure), prob.to_work(prev.repulsive_pressure)
    stress = np.clip(s1 + t * (s1 - s0), 0.0, prob.law.max_stress)
    pressure = np.maximum(p1 + t * (p1 - p0), 0.0)
    return Prediction(pressure, stress)


def assemble_state(prob, delta, p, s, h, iterations, residual, converged, outer):
    """Build the full-grid :class:`ContactState` from a solve's working arrays.

    Parameters
    ----------
    prob : AdhesiveProblem
        The problem solved.
    delta : float
        Approach of distant points [length].
    p : ndarray
        Repulsive pressure on the working grid [stress].
    s : ndarray
        Adhesive stress on the working grid [stress].
    h : ndarray
        Gap on the working grid [length].
    iterations : int
        Total inner iterations.
    residual : float
        Final residual [-].
    converged : bool
        Whether both tolerances were met.
    outer : int
        Outer (fixed-point) iterations.

    Returns
    -------
    ContactState
        Pressure ``p - s``, load ``sum(p - s)`` times the cell area (four times in
        symmetric mode), contact ``p > 0`` and the cohesive fraction outside it.
    """
    contact_w = p > 0
    law = prob.law
    if law is None:
        coh = np.zeros_like(p)
    else:
        coh = prob.zone_fraction(h, contact_w)
        coh[contact_w] = 0.0
    load = float(np.sum(p - s)) * prob.weight
    full = prob.to_full
    return ContactState(
        grid=prob.grid, pressure=full(p - s), gap=full(h), approach=float(delta), load=load,
        contact=full(contact_w), cohesive=full(coh), law=law, converged=bool(converged),
        iterations=int(iterations), residual=float(residual), outer_iterations=int(outer),
        repulsive_pressure=full(p), resolved=bool(prob.resolved))
