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
* **Inner problem** (convex): for a given adhesive stress s, the non-adhesive
  contact with the modified gap ``g0 = z - delta - K s``, solved for the
  pressure by the Polonsky-Keer constrained conjugate gradient (displacement
  control: the gradient is the gap on the active set; cells that overlap are
  added, cells that go tensile are released and conjugacy is reset; Polonsky &
  Keer 1999).  The pressure is the unknown, so no inverse of the non-periodic
  operator is needed.  An empty active set (no contact) is the linear case
  ``h = g0``, returned at once.
* **Outer problem**: a fixed point on the adhesive stress, accelerated by
  Anderson mixing (type II, memory 6), warm-started from the previous state
  of a path.  For the Dugdale law the unknown is the cell fraction chi in the
  zone h < h0, so ``s = sigma0 chi``.
* **Sub-cell zone edge** (Dugdale): a cell-wise law pins the zone edge to the
  cell boundaries (lattice trapping: jagged load curves, pull-off biased
  towards stronger adhesion).  Here chi of a cell is the exact area fraction
  of the cell where the *linearly interpolated* gap is below h0
  (:func:`dhfield.bem.laws.cell_fraction_below`, with the central-difference
  gradient of h), so the edge moves continuously through the cells and the
  fixed-point map is continuous.  Contact cells have chi = 1.
* **Stable discrete edge** (found here): a discrete state is energy-stable
  only if the spectral radius of ``|d sigma/dh| K`` is below 1, and for a
  ring of edge cells K sums to ~(2/pi) ln(c/dx) dx/E*.  With the bare sub-cell
  fraction the edge's gap spread |grad h| dx can be smaller than
  sigma0 (2/pi) ln(c/dx) dx/E* (lambda >~ 2): then no discrete state is
  stable, the outer iteration wanders and the path jumps (lattice trapping in
  another guise; damping cannot cure it).  The fraction is therefore taken
  over a gap spread of at least ``EDGE_WIDTH_FACTOR (1 + (2/pi) ln n) sigma0 dx/E*``
  (capped at 2 h0, symmetric about h0 so the work of adhesion is unchanged;
  it vanishes like dx ln(1/dx)).  Grids that would need more than 2 h0 are
  flagged ``resolved=False``: in the paper's units that is roughly
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
.. [3] H. F. Walker, P. Ni (2011) Anderson acceleration for fixed-point
   iterations. SIAM J. Numer. Anal. 49:1715-1735. doi:10.1137/10078356X
.. [4] N. H. M. Zini et al. (2018) Tribol. Lett. 66:30. doi:10.1007/s11249-017-0976-8
"""
from __future__ import annotations

import functools
import math
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np
from scipy.fft import next_fast_len

from ..core.validation import check_finite, check_optional_count, check_positive
from .backend import array_module, namespace_of, to_host
from .laws import DugdaleLaw, cell_fraction_below, check_law
from .operator import MIN_CELLS, Grid, get_operator, influence_coefficients, quadrant, unfold_quadrant
from .state import ContactState

__all__ = ["solve_adhesive", "AdhesiveProblem", "edge_width_ratio", "Prediction", "solve_problem", "secant_prediction",
           "DEFAULT_TOL", "DEFAULT_MAX_ITER", "solve_contact_pressure", "ContactPressureSolution",
           "AndersonMixing", "assemble_state", "STRETCH_ANDERSON_MEMORY", "extrapolated_start", "stretch_step", "StretchStep"]

#: Default solver tolerance: complementarity error of the contact problem relative to
#: the law's range (or |delta| without adhesion), and largest change of the zone
#: fraction between outer iterations [-].
DEFAULT_TOL = 1e-6
#: Default cap on the inner (conjugate-gradient) iterations of one state.
DEFAULT_MAX_ITER = 20000
#: Cap on outer (zone) iterations of one state.
MAX_OUTER = 300
#: Smallest width (in gap) of the sub-cell Dugdale edge, as a multiple of
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
#: Inner tolerance per outer iteration = INNER_FACTOR x the last outer residual.
INNER_FACTOR = 0.1
#: A state whose outer residual has not reached a new minimum for this many outer
#: iterations has stalled: its best iterate is returned (flagged unless within tol).
STALL_OUTER = 60
#: Outer iterations between Anderson restarts.
ANDERSON_RESTART = 40
#: Anderson memory (number of previous iterates mixed).
ANDERSON_MEMORY = 6
#: Anderson memory of the high-mu route's states started from an external start (the lower-mu
#: start, or the route's own states on the grid half as fine;
#: :data:`dhfield.bem.pull_off.PREDICTED_STRETCH_EVERY` says where), mixed without the periodic
#: restarts (only a stretch step restarts it).  Their residual sits in a ring of ~5000 edge cells
#: whose undulations are many slow modes, more than 6 differences span (docs/theory/bem.rst,
#: 'Measurements behind the solver's constants').
STRETCH_ANDERSON_MEMORY = 30
#: Stretch step (:func:`stretch_step`): finite-difference increment of the stretch factors [-].
STRETCH_INCREMENT = 2e-3
#: Stretch step: largest change of a stretch factor per Broyden step [-].
STRETCH_MAX_STEP = 1e-2
#: Stretch step: Broyden updates after the finite-difference Jacobian (each one inner solve).
STRETCH_BROYDEN_STEPS = 5
#: Stretch step: taken only when the state stalls, i.e. when the best outer residual of the last
#: half of the ``stretch_every`` window is above this fraction of the best of its first half.
#: A converging state gains nothing from a stretch step, which costs CG iterations
#: (docs/theory/bem.rst).
STRETCH_STALL_RATIO = 0.5
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

    ``relaxed_edge=True`` (Dugdale only) widens the sub-cell edge to what discrete stability
    wants even beyond its cap 2 h0 (:data:`EDGE_WIDTH_FACTOR`), so that a grid too coarse for
    the law still has stable, converging states: they solve a smeared law and serve only as
    warm starts of a finer grid (``resolved`` stays False).  ``widest_edge=True`` (Dugdale only)
    spreads the edge over its cap 2 h0 whatever the grid wants (:meth:`with_widest_edge`): the
    same work of adhesion, a smaller fixed-point gain at the edge, so that a state whose own
    edge stalls converges there and then starts the state of the grid's own edge
    (:meth:`dhfield.bem.branch.Branch.widest_edge_guess`).

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
    relaxed_edge : bool, default False
        Widen the Dugdale edge beyond its cap 2 h0 (see above).
    backend : str, optional
        Array backend of the working arrays (:mod:`dhfield.bem.backend`); default
        ``$DHFIELD_BEM_BACKEND`` or ``"fftw"``.  The working arrays (``z``, and those of the
        solve) are the backend's; :meth:`to_full` returns numpy arrays.
    widest_edge : bool, default False
        Spread the Dugdale edge over its cap 2 h0 (see above): a warm start's law, or, by
        choice (:attr:`dhfield.analysis.bem_start.AdhesiveOptions.widest_edge`), the law of a
        high-mu refinement that keeps level 1's law (a stress ramp over gaps 0 to 2 h0).

    Raises
    ------
    ValueError
        If ``grid`` is not a :class:`Grid`, ``initial_gap`` is not finite or not of the grid's
        shape, ``law`` is not a traction law, or ``symmetric=True`` for an uneven problem.
    """

    def __init__(self, initial_gap, grid, law, symmetric, threads, reduced_modulus, *, relaxed_edge=False,
                 backend=None, widest_edge=False):
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
        self._built_with = (threads, float(reduced_modulus), backend)      # (with_widest_edge)
        self.widest_edge = bool(widest_edge)
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
            # relaxed_edge: the edge as wide as stability wants, beyond 2 h0 (a different law near the
            # edge, and resolved = False: only a warm start for a finer grid, never an answer)
            self.min_spread = want if relaxed_edge else min(want, self.widest_spread)
            if self.widest_edge:
                self.min_spread = max(self.min_spread, self.widest_spread)

    def with_widest_edge(self) -> "AdhesiveProblem":
        """The same problem (gap, grid, law, symmetry) with the Dugdale edge spread over its cap 2 h0.

        A state that stalls with the grid's own edge can converge with the wide edge and then
        start the grid's own state (docs/theory/bem.rst, 'The adhesive solver').

        Returns
        -------
        AdhesiveProblem
            ``widest_edge=True``; its states are warm starts, not answers of this problem
            (unless this problem has ``widest_edge=True`` already).

        Raises
        ------
        ValueError
            If the problem's law is not a Dugdale law.
        """
        if not isinstance(self.law, DugdaleLaw):
            raise ValueError(f"with_widest_edge needs a Dugdale law; got {type(self.law).__name__}")
        threads, e, backend = self._built_with
        return AdhesiveProblem(self.z_full, self.grid, self.law, self.symmetric, threads, e, backend=backend,
                               widest_edge=True)

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


class AndersonMixing:
    """Anderson mixing (type II) for x = F(x); residual f = F(x) - x.

    Parameters
    ----------
    memory : int, default ANDERSON_MEMORY
        Number of past differences kept [-].
    """

    def __init__(self, memory=ANDERSON_MEMORY):
        self.m = memory
        self.reset()

    def reset(self):
        """Forget the stored history (the next step is a plain fixed-point step)."""
        self.dx = None
        self.df = None
        self.gram = None         # df df^T of the stored differences, kept up to date row by row
        self.count = 0
        self.x_prev = self.f_prev = None

    def step(self, x, f):
        """Return the next iterate from the current one and its residual.

        Parameters
        ----------
        x : ndarray
            Current iterate.
        f : ndarray
            Its residual F(x) - x, of the shape of ``x``.

        Returns
        -------
        ndarray
            The mixed iterate, of the shape of ``x`` (``x + f`` without history, or after
            a singular least-squares system, which also resets the history).
        """
        xf, ff = x.ravel(), f.ravel()
        xp = namespace_of(xf)
        if self.dx is None:
            self.dx = xp.empty((self.m, xf.size))
            self.df = xp.empty((self.m, xf.size))
            self.gram = xp.zeros((self.m, self.m))
        if self.x_prev is not None:
            k = self.count % self.m
            np.subtract(xf, self.x_prev, out=self.dx[k])
            np.subtract(ff, self.f_prev, out=self.df[k])
            self.count += 1
            # only slot k changed: its row and column of the Gram matrix (m dot products a step, not
            # m^2; memory 30 on 1.6e6 cells, 1 thread: 0.05 s against 0.12 s for the whole product)
            row = self.df[:min(self.count, self.m)] @ self.df[k]
            self.gram[k, :row.size] = row
            self.gram[:row.size, k] = row
        self.x_prev, self.f_prev = xf.copy(), ff.copy()
        new = xf + ff
        n = min(self.count, self.m)
        if n:
            dfm = self.df[:n]
            dxm = self.dx[:n]
            # small normal equations (n x n), Tikhonov-regularised relative to their scale
            gram = self.gram[:n, :n]
            reg = 1e-12 * max(float(np.trace(gram)), 1e-300)
            try:
                gamma = xp.linalg.solve(gram + reg * xp.eye(n), dfm @ ff)
            except np.linalg.LinAlgError:
                gamma = None
            if gamma is None or not bool(xp.all(xp.isfinite(gamma))):   # (CuPy does not raise)
                self.reset()
                return new.reshape(x.shape)
            new -= gamma @ dxm + gamma @ dfm
        return new.reshape(x.shape)


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
        Tolerance on the complementarity error (relative to the law's range,
        or to |delta| and max z without adhesion) and on the largest change of
        the zone fraction (Dugdale) or of the stress relative to sigma0
        (exponential) between outer iterations [-].
    max_iter : int, default DEFAULT_MAX_ITER
        Cap on the total inner conjugate-gradient iterations.
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
    See the module docstring for the algorithm: Polonsky-Keer CG for the
    repulsive pressure inside an Anderson-accelerated fixed point on the
    adhesive stress, with the sub-cell Dugdale zone edge.
    """
    prob = AdhesiveProblem(initial_gap, grid, law, symmetric, threads, reduced_modulus)
    delta = float(check_finite("approach", approach, "approach of distant points, length"))
    tol = float(check_positive("tol", tol, "solver tolerance, dimensionless"))
    if int(max_iter) < 1:
        raise ValueError(f"max_iter must be an integer >= 1; got {max_iter!r}")
    if guess is not None and not (isinstance(guess, ContactState) and guess.grid == grid):
        raise ValueError("guess must be a ContactState on the same grid")
    return solve_problem(prob, delta, guess, tol, int(max_iter))


def solve_problem(prob, delta, guess, tol, max_iter, *, stretch_every=None, anderson_memory=None, give_up_after=None):
    """Solve a prepared problem at one approach (the body of :func:`solve_adhesive`).

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
        Tolerance, as in :func:`solve_adhesive` [-].
    max_iter : int
        Cap on the total inner conjugate-gradient iterations.
    stretch_every : int, optional
        Dugdale law only: every this many outer iterations of a state not yet converged, a
        stretch step (:func:`stretch_step`) instead of an Anderson step when the state stalls
        (``STRETCH_STALL_RATIO``), and Anderson's history restarts.  None (default): Anderson
        steps only.
    anderson_memory : int, optional
        Anderson memory, mixed without periodic restarts (a stretch step still restarts it);
        None (default): ``ANDERSON_MEMORY``, restarted every ``ANDERSON_RESTART`` outer
        iterations.
    give_up_after : int, optional
        Stop early, flagged, once the best outer residual of the last half of this many outer
        iterations is above ``STRETCH_STALL_RATIO`` times the best of the first half (a start
        that stopped converging; a race of starts, :meth:`dhfield.bem.branch.Branch.race`, then
        tries the next).  None (default): only the ``STALL_OUTER`` and ``MAX_OUTER`` limits.

    Returns
    -------
    ContactState
        On the full grid; when the iterations run out, the best iterate, flagged
        ``converged=False``.
    """
    law = prob.law
    op = prob.op
    zd = prob.z - delta
    if law is None:
        scale = max(abs(delta), float(np.max(np.abs(prob.z))) * 1e-3, 1e-300)
    else:
        scale = law.range
    # gap error -> zone-fraction error: a Dugdale cell's fraction moves by dh/spread, so the
    # inner (gap) tolerances are scaled by spread/h0 (<= 1): at N = 1024 an inner error of
    # 1e-7 h0 moved the fraction by 4e-6 and the outer residual could not reach 1e-6.
    gain = min(1.0, prob.min_spread / scale) if (law is not None and prob.min_spread > 0.0) else 1.0
    inner_tol = 0.1 * tol * gain
    if isinstance(guess, Prediction):
        p = prob.work_array(guess.pressure).copy()
    elif guess is not None and guess.repulsive_pressure is not None:
        p = prob.to_work(guess.repulsive_pressure).copy()
    else:
        p = np.zeros_like(prob.z)
    total_it = 0
    if law is None:
        # no outer loop to feed: the contact problem itself is solved to tol (converged iff err <= tol)
        p, h, it, err = solve_contact_pressure(op, zd, p, scale, tol, max_iter, prob.k0)
        total_it += it
        s = np.zeros_like(p)
        converged = err <= tol
        return assemble_state(prob, delta, p, s, h, total_it, err, converged, 1)
    sigma0 = law.max_stress
    # initial adhesive stress
    if isinstance(guess, Prediction):
        s = prob.work_array(guess.stress).copy()
    elif guess is not None:
        s = prob.stress_of_state(guess)
    else:
        h_rigid = zd.copy()
        s = prob.stress_from_gap(np.maximum(h_rigid, 0.0), h_rigid <= 0)
    anderson_memory = check_optional_count("anderson_memory", anderson_memory)
    give_up_after = check_optional_count("give_up_after", give_up_after, "outer iterations")
    acc = AndersonMixing() if anderson_memory is None else AndersonMixing(anderson_memory)
    restart = ANDERSON_RESTART if anderson_memory is None else 0
    res = np.inf
    err = np.inf
    outer = 0
    h = None
    best = None
    best_outer = 0
    history = []
    while outer < MAX_OUTER and total_it < max_iter and outer - best_outer <= STALL_OUTER:
        outer += 1
        # inexact inner solves: tighten with the outer residual (Anderson tolerates it), in units
        # of the zone fraction (gain): a looser inner solve feeds the fixed point noise larger
        # than its residual (at N = 1024 the contact set flipped by 3 % every iteration)
        itol = gain * (1e-3 if not np.isfinite(res) else min(max(INNER_FACTOR * res, 0.1 * tol), 1e-2))
        p, h, it, err = solve_contact_pressure(op, zd, p, scale, itol, max_iter - total_it, prob.k0, stress=s)
        total_it += it
        f = prob.stress_from_gap(h, p > 0) - s
        res = float(np.max(np.abs(f))) / sigma0
        if best is None or res < best[0]:
            best = (res, s.copy(), p.copy(), h.copy(), err)
            best_outer = outer
        if res <= tol and err <= tol:
            if err <= inner_tol or itol <= inner_tol:
                break
        history.append(res)
        if give_up_after and outer >= give_up_after and _stalled(history, give_up_after):
            res, s, p, h, err = best             # this start stopped converging: the best iterate, flagged
            break
        if (stretch_every and outer % stretch_every == 0 and isinstance(law, DugdaleLaw)
                and _stalled(history, stretch_every)):
            step = stretch_step(prob, delta, p, s, itol, max(max_iter - total_it, 1))
            p, s = step.pressure, step.stress
            total_it += step.iterations
            acc.reset()
            continue
        s = np.clip(acc.step(s, f), 0.0, sigma0)
        if restart and outer % restart == 0:
            acc.reset()
    else:
        # out of iterations: report the best iterate, flagged
        res, s, p, h, err = best
    converged = res <= tol and err <= tol
    return assemble_state(prob, delta, p, s, h, total_it, max(res, err), converged, outer)


def _stalled(history, window) -> bool:
    """True when the best residual of the last half of ``window`` outer iterations is above
    ``STRETCH_STALL_RATIO`` times the best of its first half (a state that stopped converging)."""
    half = window // 2
    if len(history) < 2 * half or half < 1:
        return False
    return min(history[-half:]) > STRETCH_STALL_RATIO * min(history[-2 * half:-half])


class StretchStep(NamedTuple):
    """Result of :func:`stretch_step` (working arrays of the problem's working grid).

    Parameters
    ----------
    pressure : ndarray
        Repulsive pressure solved for the stretched stress [stress].
    stress : ndarray
        The stretched adhesive stress, in [0, sigma0] [stress].
    factors : tuple of float
        Stretch factors (sx, sy) along x and y of the stress returned [-].
    iterations : int
        Inner CG iterations spent on the search [-].
    """

    pressure: np.ndarray     #: repulsive pressure solved for the stretched stress [stress]
    stress: np.ndarray       #: the stretched adhesive stress, in [0, sigma0] [stress]
    factors: tuple           #: stretch factors (sx, sy) [-]
    iterations: int          #: inner CG iterations spent [-]


def _working_axes(prob):
    """Cell-centre x and y coordinates of the working grid (the quadrant x, y > 0 in symmetric mode)."""
    g = prob.grid
    if prob.symmetric:
        return g.x[g.nx // 2:], g.y[g.ny // 2:]
    return g.x, g.y


def _stretched(prob, f, sx, sy):
    """A working-grid field stretched about the centre, f(x, y) -> f(x/sx, y/sy) (bilinear, edges held)."""
    if prob.xp is np:
        from scipy.ndimage import map_coordinates
    else:
        from cupyx.scipy.ndimage import map_coordinates

    g = prob.grid
    x, y = _working_axes(prob)
    i = (x / sx - x[0]) / g.dx
    j = (y / sy - y[0]) / g.dy
    ii, jj = np.meshgrid(i, j, indexing="ij")
    return map_coordinates(f, prob.xp.asarray(np.stack([ii, jj])), order=1, mode="nearest")


def stretch_step(prob, delta, pressure, stress, itol, max_iter) -> StretchStep:
    """Move the whole Dugdale zone edge at once: stretch the state along x and y (a Broyden search).

    The outer fixed point moves the zone edge by a fraction of a cell per iteration: a cold
    state whose zone is a few cells too large or too small creeps towards the solution and
    stalls, trapped by the lattice (at mu = 10 with a zone-fraction residual of 4e-4 to 1e-2
    after 300 outer iterations; docs/theory/bem.rst).  This step
    stretches the stress and pressure about the centre by factors (sx, sy) chosen so that the
    residual of the stretched state has no net second moments along x and y,

    .. math:: r_x = \\frac{\\sum_i f_i x_i^2}{\\langle x^2 \\rangle_s}, \\quad
              r_y = \\frac{\\sum_i f_i y_i^2}{\\langle y^2 \\rangle_s}, \\qquad
              f = \\chi(h) - s/\\sigma_0,

    i.e. so that it no longer asks for a larger or smaller zone along either axis, by a
    finite-difference Jacobian (``STRETCH_INCREMENT``) and up to ``STRETCH_BROYDEN_STEPS``
    Broyden updates (each factor moving by at most ``STRETCH_MAX_STEP`` a step).  Each
    evaluation is one inner contact solve.  The best evaluation (smallest |r_x| + |r_y|)
    is returned; the unstretched state is among them, so the step never makes the
    moments worse.

    Parameters
    ----------
    prob : AdhesiveProblem
        The problem, with a Dugdale law.
    delta : float
        Approach of distant points [length].
    pressure, stress : ndarray
        The current iterate on the working grid: repulsive pressure (the inner solve's) and
        the adhesive stress it was solved with [stress].
    itol : float
        Tolerance of the inner solves [-].
    max_iter : int
        Cap on the inner CG iterations of each solve.

    Returns
    -------
    StretchStep
        The stretched stress, its solved pressure, the factors and the CG iterations spent.
    """
    law = prob.law
    sigma0, scale = law.max_stress, law.range
    zd = prob.z - delta
    x, y = _working_axes(prob)
    x2, y2 = prob.xp.asarray((x * x)[:, None]), prob.xp.asarray((y * y)[None, :])
    w = stress / sigma0
    total = max(float(w.sum()), 1e-300)
    mx = max(float((w * x2).sum()) / total, 1e-300)
    my = max(float((w * y2).sum()) / total, 1e-300)
    spent = 0

    def moments(v):
        nonlocal spent
        if v[0] == 1.0 and v[1] == 1.0:
            st, p0 = stress, pressure
        else:
            st = np.clip(_stretched(prob, stress, v[0], v[1]), 0.0, sigma0)
            p0 = np.maximum(_stretched(prob, pressure, v[0], v[1]), 0.0)
        p, h, it, _ = solve_contact_pressure(prob.op, zd, p0, scale, itol, max_iter, prob.k0, stress=st)
        spent += it
        f = (prob.stress_from_gap(h, p > 0) - st) / sigma0
        return np.array([float((f * x2).sum()) / mx, float((f * y2).sum()) / my]), st, p

    v = np.ones(2)
    r, st, p = moments(v)
    best = (float(np.abs(r).sum()), st, p, (1.0, 1.0))
    jac = np.empty((2, 2))
    for k in range(2):
        e = v.copy()
        e[k] += STRETCH_INCREMENT
        jac[:, k] = (moments(e)[0] - r) / STRETCH_INCREMENT
    for _ in range(STRETCH_BROYDEN_STEPS):
        try:
            dv = -np.linalg.solve(jac, r)
        except np.linalg.LinAlgError:
            break
        dv = np.clip(dv, -STRETCH_MAX_STEP, STRETCH_MAX_STEP)
        v = v + dv
        r_new, st, p = moments(v)
        if float(np.abs(r_new).sum()) < best[0]:
            best = (float(np.abs(r_new).sum()), st, p, (float(v[0]), float(v[1])))
        jac += np.outer((r_new - r) - jac @ dv, dv) / float(dv @ dv)
        r = r_new
        if float(np.abs(dv).max()) < 0.05 * STRETCH_INCREMENT:
            break
    return StretchStep(pressure=best[2], stress=best[1], factors=best[3], iterations=spent)


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
