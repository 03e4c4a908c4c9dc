"""Where the adhesive BEM starts, chosen from the analytic models; the BEM pull-off in the paper's units.

The BEM engine (:mod:`dhfield.bem`) is the ground truth the analytic models are
judged against, so it imports none of them: it takes its start as an argument
(:class:`dhfield.bem.pull_off.UnloadingStart`).  This module chooses that start
from the models:

* the domain, from the DH model's cohesive zone at the start of unloading
  (:func:`dhfield.models.dh_elliptic.load_curve`);
* the range of the unloading path, from the DH model's pull-offs in both controls
  (:func:`dhfield.models.dh_elliptic.pull_off`);
* the cold start of the bracket search, from the two-axis closure's load-control
  pull-off for beta0 < 1 (``dh-elliptic-two-axis``, :func:`dhfield.analysis.compare.pull_off`),
  the DH model's at beta0 = 1.

The grid: :func:`plan_grid` chooses the cells a case needs from the law's edge
(:func:`dhfield.bem.solver.edge_width_ratio` <= 1, i.e. ``sqrt(dx dy) <= 2/(kappa mu^2)``)
and the expected zone width (:func:`expected_zone_width`, 0.785/mu^2) -- n x n cells for
beta0 >= SHAPED_CELLS_MAX_BETA0, about square cells below (nx x ny, :func:`shaped_cells_y`,
also on the predicted route below:
n x n cells stretched along x put the Dugdale edge at a slender contact's tips near
instability, and waste cells along y) -- estimates its memory
and time, and names the analytic value to use instead
(:func:`dhfield.models.md_elliptic.pull_off_nondimensional`); :func:`adhesive_pull_off`
without ``n`` uses it and refuses, before solving, a case beyond the memory or the time
allowed (:class:`UnresolvableCaseError`).  Where the grid half as fine cannot hold the
Dugdale edge, the path routes search the minimum on this grid from the analytic pull-off
(the bracket search); at mu >= :data:`PREDICTED_MIN_MU` only fine lattice samples around
GVG's pull-off are solved, on a domain holding its zone (:func:`predicted_start`, :func:`dhfield.bem.pull_off.predicted_path`).

:func:`adhesive_pull_off` and :func:`refine_pull_off`, the user-facing BEM
pull-offs, set the problem up here and run :func:`dhfield.bem.pull_off.solve_pull_off`
and :func:`dhfield.bem.pull_off.refine` on it; :mod:`dhfield.bem` forwards their
names, so ``from dhfield.bem import adhesive_pull_off`` keeps working.
"""
from __future__ import annotations

import functools
import math
from dataclasses import dataclass, replace

import numpy as np

from ..models import dh_elliptic
from ..core.memory import memory_limit
from ..core.validation import check_count, check_ellipticity, check_positive
from ..bem.laws import law_from_name
from ..bem.operator import Grid
from ..bem.ladder import NEWTON_SEARCH
from ..bem.path import PathOptions
from ..bem.pull_off import (DEFAULT_STEPS, DOMAIN_MARGIN, MAX_CELLS, MAX_STEPS, NESTED_MIN_N,
                            NondimensionalProblem, UnloadingStart, check_bem_pull_off, check_cells,
                            paper_problem, refine, solve_pull_off)
from ..core.records import PullOff
from ..bem.solver import DEFAULT_MAX_ITER, DEFAULT_TOL, edge_width_ratio

__all__ = ["unloading_start", "nondimensional_problem", "adhesive_pull_off", "refine_pull_off", "GridPlan",
           "plan_grid", "analytic_pull_off", "UnresolvableCaseError", "expected_zone_width", "AUTO_MIN_CELLS", "DEFAULT_MAX_SECONDS",
           "UNSTABLE_EDGE_RATIO", "AdhesiveOptions", "SHAPED_CELLS_MAX_BETA0",
           "AUTO_MIN_CELLS_Y", "AUTO_CONTACT_CELLS", "shaped_cells_y", "predicted_start", "predicted_problem",
           "PREDICTED_MIN_MU", "PREDICTED_SEARCH", "takes_predicted_route",
           "newton_problem", "newton_grids", "takes_newton_route",
           "pull_off_cost", "check_grid_memory", "WIDEST_EDGE_NOTE", "WIDEST_EDGE_MARK"]


def unloading_start(*, beta0, mu, n_steps=DEFAULT_STEPS, margin=DOMAIN_MARGIN) -> UnloadingStart:
    """Choose where the BEM's unloading path starts at (mu, beta0), from the analytic models (an input, not a result).

    Parameters
    ----------
    beta0 : float
        Initial (Hertz) ellipticity in (0, 1] [-].
    mu : float
        Tabor parameter of Eq. (35), > 0 [-].
    n_steps : int, default DEFAULT_STEPS
        Unloading steps from the start of unloading to the expected jump (4 to 1e6) [-].
    margin : float, default DOMAIN_MARGIN
        Domain half-width per expected zone semi-axis, > 1 (the zone must lie inside the grid) [-].

    Returns
    -------
    UnloadingStart
        Domain half-widths [c_r], ``approach_max`` and the unloading step [c_r^2/R], and the
        bracket search's cold start (approach [c_r^2/R] and zone semi-axes (c, d) [c_r]).

    Raises
    ------
    ValueError
        If ``mu``, ``beta0``, ``n_steps`` or ``margin`` is out of range (naming it).

    Notes
    -----
    The analytic DH model gives the expected pull-off (a_po, delta_po).  Unloading
    starts at a* = 1.1 a_po + 0.15 (a state on the stable branch, above pull-off), whose DH
    approach is ``approach_max`` and whose adhesive semi-axis c* sets the domain:
    half-widths ``margin c*`` along x and ``margin c* beta0^(3/4)`` along y (the
    adhesive ellipse is rounder than the contact ellipse).  The step takes the
    path in ``n_steps`` from ``approach_max`` to 20 % beyond the analytic
    displacement-control pull-off.  The bracket search's cold start is the
    two-axis closure's pull-off for beta0 < 1 (:func:`_two_axis_start`), whose zone
    is close to the BEM's; the DH zone (d = beta0 c) is not, and a cold start from it
    need not converge.
    """
    mu = float(check_positive("mu", mu, "transition parameter of Eq. (35), dimensionless"))
    beta0 = float(check_ellipticity("beta0", beta0))
    n_steps = check_count("n_steps", n_steps, 4, MAX_STEPS, "unloading steps")
    return _start(mu, beta0, n_steps, _check_margin(margin))


def _check_margin(margin) -> float:
    """``margin`` as a domain half-width per zone semi-axis: a number > 1 (ValueError naming it otherwise).

    The largest cohesive zone of the path (at the start of unloading) must lie inside the
    grid: with margin <= 1 the domain cuts it and the pull-off is that of another problem.
    """
    margin = float(check_positive("margin", margin, "domain half-width per zone semi-axis"))
    if not margin > 1.0:
        raise ValueError("margin must be > 1 (domain half-width per semi-axis of the largest cohesive zone "
                         f"of the path, which must lie inside the grid); got {margin!r}")
    return margin


def _start(mu, beta0, n_steps, margin) -> UnloadingStart:
    """:func:`unloading_start` of checked inputs."""
    po = dh_elliptic.pull_off(mu=mu, beta0=beta0)
    pod = dh_elliptic.pull_off(mu=mu, beta0=beta0, control="displacement")
    a_start = 1.1 * float(po.a_star) + 0.15
    cur = dh_elliptic.load_curve(mu=mu, beta0=beta0, a_star=[a_start])
    c_start = float(cur.c_star[0])
    d_max = float(cur.delta_star[0])
    d_end = float(pod.delta_star) - 0.2 * (d_max - float(pod.delta_star))
    # the cold start of the bracket search: the analytic load-control pull-off state
    start = _two_axis_start(mu, beta0) if beta0 < 1.0 else None
    half_x, half_y = margin * c_start, margin * c_start * beta0 ** 0.75
    if start is None and beta0 < 1.0 and mu >= SLENDER_START_MIN_MU:
        # slender (the two-axis closure refuses beta0 < 0.3): GVG's pull-off ellipse plus the zone
        start = _gvg_start(mu, beta0)
        half_x = max(half_x, SLENDER_DOMAIN_MARGIN * start[1][0])
        half_y = max(half_y, SLENDER_DOMAIN_MARGIN * start[1][1])
    if start is None:
        at_po = dh_elliptic.load_curve(mu=mu, beta0=beta0, a_star=[max(float(po.a_star), 1e-3 * a_start)])
        start = (float(po.delta_star), (float(at_po.c_star[0]), float(at_po.d_star[0])))
    return UnloadingStart(half_x, half_y, d_max, (d_max - d_end) / int(n_steps), start[0], start[1])


#: Smallest mu at which slender contacts (no two-axis start) start from GVG's JKR pull-off ellipse.
SLENDER_START_MIN_MU = 2.0
#: Domain half-width per semi-axis of that start's zone (GVG's contact plus the expected zone):
#: the paper's zone is too small a domain for a slender contact, whose BEM contact outgrows it.
SLENDER_DOMAIN_MARGIN = 1.3


def _gvg_start(mu, beta0):
    """(approach, (c, d)) of GVG's JKR load-control pull-off (:mod:`dhfield.models.jkr_elliptic_energy`), the
    contact semi-axes widened by :func:`expected_zone_width`: the cold start of slender contacts."""
    from ..models import jkr_elliptic_energy

    rec = jkr_elliptic_energy.pull_off_nondimensional(beta0, mu, control="load")
    w = expected_zone_width(mu)
    return float(rec["delta_star"]), (float(rec["a_star"]) + w, float(rec["b_star"]) + w)


@functools.lru_cache(maxsize=64)
def _two_axis_start(mu, beta0):
    """(approach, (c, d)) at the load-control pull-off of the two-axis closure, or None if it fails.

    The paper's closure keeps d = beta0 c; the BEM's adhesive ellipse is rounder.  The
    two-axis closure (beta_cd free) is within 0.8 % of the BEM's pull-off approach and 0.4 %
    of its c, d at beta0 = 0.5, mu = 5, close enough for a cold start that converges
    (docs/theory/bem.rst, 'Measurements behind the solver's constants').
    """
    from . import compare

    try:
        rec = compare.pull_off("dh-elliptic-two-axis", mu=mu, beta0=beta0, control="load", warn=False)
        out = (float(rec["delta_star"]), (float(rec["c_star"]), float(rec["d_star"])))
    except (ValueError, ArithmeticError):
        return None
    return out if np.all(np.isfinite([out[0], *out[1]])) and min(out[1]) > 0 else None


def nondimensional_problem(*, beta0, mu, n, law="dugdale", n_steps=DEFAULT_STEPS,
                           margin=DOMAIN_MARGIN, ny=None) -> NondimensionalProblem:
    """Set up the grid, initial gap, law and path range of the paper's problem at (mu, beta0).

    The start comes from the analytic models (:func:`unloading_start`).

    Parameters
    ----------
    beta0 : float
        Initial (Hertz) ellipticity in (0, 1] [-].
    mu : float
        Tabor parameter of Eq. (35), > 0 [-].
    n : int
        Cells along x (and along y unless ``ny`` is given), even, 8 to 65536 [-].
    law : {'dugdale', 'exponential'}, default 'dugdale'
        Traction law, as in :func:`dhfield.bem.pull_off.paper_problem`.
    n_steps : int, default DEFAULT_STEPS
        Unloading steps (4 to 1e6) [-], as in :func:`unloading_start`.
    margin : float, default DOMAIN_MARGIN
        Domain half-width per expected zone semi-axis, > 1 [-], as in :func:`unloading_start`.
    ny : int, optional
        Cells along y, even, 8 to 65536 [-]; default ``n`` (e.g. :attr:`GridPlan.ny_needed`
        for cells shaped to a slender contact).

    Returns
    -------
    NondimensionalProblem
        :func:`dhfield.bem.pull_off.paper_problem` with the start of :func:`unloading_start`.

    Raises
    ------
    ValueError
        If an argument is out of range (naming it).
    """
    mu = float(check_positive("mu", mu, "transition parameter of Eq. (35), dimensionless"))
    beta0 = float(check_ellipticity("beta0", beta0))
    n = check_cells(n)
    ny = None if ny is None else check_cells(ny, "ny")
    check_grid_memory(n, ny)
    n_steps = check_count("n_steps", n_steps, 4, MAX_STEPS, "unloading steps")
    start = _start(mu, beta0, n_steps, _check_margin(margin))
    return paper_problem(mu=mu, beta0=beta0, n=n, start=start, law=law, ny=ny)


# ============================================================================ the grid a case needs
#: Fewest cells per axis of an automatic grid: N = 256 is within 1 % of Maugis-Dugdale on the
#: sphere at mu <= 3 (tests/test_cli_solve.py, data/adhesive_ground_truth.nc).
AUTO_MIN_CELLS = 256
#: Fewest cells across the expected Dugdale zone c - a (:func:`expected_zone_width`) along x
#: of an automatic grid (the resolved flag wants >= ZONE_MIN_CELLS = 1 at pull-off; the edge
#: criterion below gives ~2 at mu >= 5, so this rarely binds).
AUTO_ZONE_CELLS = 2.0
#: Memory of one load-control pull-off per cell of the full grid [bytes]: measured with the
#: former fixed-point solver (its operator, CG and Anderson arrays and the states a path holds;
#: docs/theory/bem.rst, 'Measurements behind the solver's constants').  It still bounds the
#: Newton route: ``dhfield solve --beta0 0.047 --mu 5`` peaked at 748 MB with 4848 x 480 cells as
#: its largest grid, 320 bytes per cell with the interpreter's own.
PATH_BYTES_PER_CELL = 550.0
#: Wall time per cell of the full grid and per iteration [s] (median of the stored ground truth
#: on a shared 2-core machine, in conjugate-gradient iterations of the former fixed point;
#: docs/theory/bem.rst).
SECONDS_PER_CELL_ITERATION = 6e-8
#: Iterations of one pull-off at a resolved grid (3000-9300 CG iterations at mu = 5).  With the two
#: constants above the time estimate is a rough one (a factor 2-3 either way on a loaded machine).
PULL_OFF_ITERATIONS = 6000
#: Default time a pull-off with an automatic grid may be estimated to take before it is refused [s].
DEFAULT_MAX_SECONDS = 1800.0


def pull_off_cost(nx, ny) -> tuple:
    """Estimated memory [bytes] and time [s] of one load-control pull-off on ``nx`` x ``ny`` cells.

    ``PATH_BYTES_PER_CELL nx ny`` and ``SECONDS_PER_CELL_ITERATION nx ny PULL_OFF_ITERATIONS``
    (constants fitted to stored solves, docs/theory/bem.rst): the estimates of :func:`plan_grid` and
    :func:`dhfield.sweep.tasks.automatic_grid`.

    Parameters
    ----------
    nx, ny : int
        Cells along x and y of the full grid [-].

    Returns
    -------
    memory_bytes : float
        Estimated peak memory [bytes].
    seconds : float
        Estimated wall time [s] (a factor 2-3 either way on a loaded machine).
    """
    cells = float(nx) * float(ny)
    return PATH_BYTES_PER_CELL * cells, SECONDS_PER_CELL_ITERATION * cells * PULL_OFF_ITERATIONS


def check_grid_memory(nx, ny=None) -> None:
    """Refuse a BEM grid whose pull-off would not fit the memory available, before anything is allocated.

    Every route that sets up an adhesive BEM problem on a given grid (:func:`nondimensional_problem`,
    :func:`predicted_problem`; so :func:`adhesive_pull_off` with ``n``, the unloading branch of
    :mod:`dhfield.analysis.bem_spring`, the adhesive cases of :mod:`dhfield.sweep`, ``dhfield solve``
    and ``dhfield cycle``) calls it first.  The estimate is :func:`pull_off_cost`'s; the limit is
    :func:`dhfield.core.memory.memory_limit` (80 % of the memory available now; none when unknown).

    Parameters
    ----------
    nx : int
        Cells along x [-].
    ny : int, optional
        Cells along y [-]; default ``nx``.

    Raises
    ------
    ValueError
        One line naming ``n``, the estimated memory and the limit.
    """
    from ..core.memory import check_memory

    nx = int(nx)
    ny = nx if ny is None else int(ny)
    cells = f"{nx}" if ny == nx else f"{nx} x {ny}"
    check_memory(pull_off_cost(nx, ny)[0], f"n={cells} (a {nx} x {ny} grid of the adhesive BEM, about "
                 f"{PATH_BYTES_PER_CELL:.0f} bytes per cell)")


#: An explicit grid whose ``edge_width_ratio`` exceeds this has no stable discrete state: its
#: states do not converge (they do at 1.10-1.18, not at 2.1-3.8; docs/theory/bem.rst).
#: :func:`plan_grid` says so.
UNSTABLE_EDGE_RATIO = 2.0


def expected_zone_width(mu) -> float:
    """Estimate the width c - a of the Dugdale zone on the JKR side [c_r].

    Parameters
    ----------
    mu : float
        Tabor parameter of Eq. (35), > 0 [-].

    Returns
    -------
    float
        ``(pi/8) 2 E* dgamma/sigma0^2 = 0.785/mu^2`` with R = E* = dgamma = 1 (sigma0 = mu)
        [c_r].

    Notes
    -----
    An upper bound on the BEM's zone width, close on the JKR side (mu >= 5; within 10 % of
    the stored BEM at mu = 5, docs/theory/bem.rst).
    """
    return math.pi / 8.0 * 2.0 / float(mu) ** 2


def _fft_sizes(low=AUTO_MIN_CELLS, a_min=4):
    """Even cell counts with small prime factors (2^a 3^b 5^c, a >= a_min: multiples of 16), low to MAX_CELLS."""
    out = set()
    for a in range(a_min, 17):
        for b in range(0, 4):
            for c in range(0, 3):
                n = 2 ** a * 3 ** b * 5 ** c
                if low <= n <= MAX_CELLS:
                    out.add(n)
    return sorted(out)


#: Below this beta0 an automatic grid has as many cells along y as make them about square
#: (``dy <= dx``; :func:`shaped_cells_y`) instead of n x n cells stretched along x: the
#: Dugdale zone is about as wide on both axes, so square cells resolve it with fewer cells
#: (2.5x fewer at beta0 = 0.1806, mu = 5; docs/theory/bem.rst).  At beta0 >= 0.45 the
#: automatic grids are n x n (the saving there is small).
SHAPED_CELLS_MAX_BETA0 = 0.45
#: Fewest cells along y of a shaped automatic grid (the nested grids 2x, 4x coarser keep a few).
AUTO_MIN_CELLS_Y = 64
#: Fewest cells across each expected contact semi-axis at pull-off (the DH model's a*, b*,
#: :func:`dhfield.models.dh_elliptic.pull_off`) of a shaped automatic grid, along x and along y.  On the DMT
#: side the contact at pull-off is small inside a wide zone.  The DH model's b* is 20-45 %
#: below the BEM's at beta0 = 0.18-0.3, mu = 0.1-5, so 5 cells on it are ~7 on the BEM's, a
#: discretisation error estimate (DISCRETISATION_ERROR_PER_CELL / cells) below 1 %.  It binds
#: only at mu <~ 0.5.
AUTO_CONTACT_CELLS = 5.0


def shaped_cells_y(n, half_width_x, half_width_y, max_dy=None) -> int:
    """Choose the cells along y that make the cells about square on the domain ``2 half_width_x x 2 half_width_y``.

    Parameters
    ----------
    n : int
        Cells along x (an automatic size, a multiple of 16) [-].
    half_width_x, half_width_y : float
        Domain half-widths [c_r].
    max_dy : float, optional
        Largest cell size along y wanted besides ``dx`` (e.g. to resolve the contact's
        minor semi-axis) [c_r].

    Returns
    -------
    int
        The smallest 2^a 3^b 5^c >= AUTO_MIN_CELLS_Y with ``dy <= min(dx, max_dy)`` and divisible by the
        largest power of 2, k, that divides ``n`` with ``n/k >= NESTED_MIN_N``: every coarser
        grid of the nested and located searches (``n/2, n/4, ... >= NESTED_MIN_N`` along x)
        then halves y exactly too, and keeps >= AUTO_MIN_CELLS_Y/k cells along it [-].
    """
    n = int(n)
    q = 1
    while n % (2 * q) == 0 and n // (2 * q) >= NESTED_MIN_N:
        q *= 2
    a_min = q.bit_length() - 1
    dy = 2.0 * float(half_width_x) / n if max_dy is None else min(2.0 * float(half_width_x) / n, float(max_dy))
    want = 2.0 * float(half_width_y) / dy
    return next(k for k in _fft_sizes(max(AUTO_MIN_CELLS_Y, q), a_min) if k >= want * (1.0 - 1e-12))


@dataclass(frozen=True)
class GridPlan:
    """The grid a BEM pull-off needs at (mu, beta0), its cost, and the analytic value to use instead.

    Parameters
    ----------
    mu : float
        Tabor parameter of the case, Eq. (35) [-].
    beta0 : float
        Initial ellipticity of the case [-].
    n : int
        Cells along x asked for (the automatic choice when none was given) [-].
    n_needed : int
        Fewest cells along x (from the FFT-friendly sizes) that resolve the law's edge
        (``edge_width_ratio <= 1``) with >= AUTO_ZONE_CELLS cells across the expected zone
        along x and y [-].
    edge_width_ratio : float
        :func:`dhfield.bem.solver.edge_width_ratio` of the grid of ``n`` (x ``ny``) (resolved iff <= 1) [-].
    memory_bytes : float
        Estimated memory of the pull-off on the grid of ``n_needed`` x ``ny_needed`` [bytes].
    seconds : float
        Estimated wall time of the pull-off on that grid [s].
    memory_limit : float or None
        The memory one computation may claim now [bytes] (None: unknown, no limit).
    max_seconds : float
        The time allowed [s].
    analytic_W_star : float
        The best analytic value of the route asked (``control``, ``machine_stiffness_star``):
        :func:`dhfield.models.md_elliptic.pull_off_nondimensional` (GVG x the sphere's MD/JKR
        transition; load control within 0.46 % of the 57 stored BEM cases, beta0 0.1-1,
        mu 0.1-10) under load or displacement control, and its jump out under the machine
        spring (:func:`dhfield.analysis.spring.pull_off_under_spring`, model
        :data:`dhfield.analysis.compare.DEFAULT_MODEL`) [-].
    ny : int, optional
        Cells along y of the grid of ``n`` [-]; default ``n``.
    ny_needed : int, optional
        Cells along y of the automatic grid [-]: ``n_needed`` for beta0 >=
        :data:`SHAPED_CELLS_MAX_BETA0`, else about square cells (:func:`shaped_cells_y`);
        default ``n_needed``.
    predicted : bool, default False
        True when ``n_needed`` is planned on the domain of the predicted route
        (:func:`predicted_start`: only states near the pull-off are solved, so the domain
        holds GVG's pull-off zone instead of the zone at the start of unloading).
    control : {'load', 'displacement', 'spring'}, default 'load'
        The route ``analytic_W_star`` is the pull-off of.
    machine_stiffness_star : float, optional
        K* of the machine spring [-] (paper's units, :func:`dhfield.analysis.spring.stiffness_star`),
        with ``control='spring'``; None otherwise.
    """

    mu: float
    beta0: float
    n: int
    n_needed: int
    edge_width_ratio: float
    memory_bytes: float
    seconds: float
    memory_limit: float | None
    max_seconds: float
    analytic_W_star: float
    ny: int | None = None
    ny_needed: int | None = None
    predicted: bool = False
    control: str = "load"
    machine_stiffness_star: float | None = None

    def __post_init__(self):
        if self.ny is None:
            object.__setattr__(self, "ny", self.n)
        if self.ny_needed is None:
            object.__setattr__(self, "ny_needed", self.n_needed)

    @property
    def affordable(self) -> bool:
        """True when the grid of ``n_needed`` fits the memory and the time allowed."""
        fits = self.memory_limit is None or self.memory_bytes <= self.memory_limit
        return fits and self.seconds <= self.max_seconds

    @property
    def too_coarse(self) -> bool:
        """True when the grid of ``n`` is far too coarse for the law's edge (> UNSTABLE_EDGE_RATIO)."""
        return self.edge_width_ratio > UNSTABLE_EDGE_RATIO

    @property
    def resolved(self) -> bool:
        """True when the grid of ``n`` resolves the law's edge."""
        return self.edge_width_ratio <= 1.0

    def reason(self) -> str:
        """Say why the case cannot be solved as asked.

        Returns
        -------
        str
            The reasons (too coarse an ``n``, memory, time), joined by "; "; empty when the
            case can be solved.
        """
        why = []
        if self.too_coarse:
            why.append(f"n={self.n} is too coarse for the Dugdale edge at mu={self.mu:g} (it wants "
                       f"{self.edge_width_ratio:.2f}x its cap 2 h0: no stable discrete state, no convergence)")
        if self.memory_limit is not None and self.memory_bytes > self.memory_limit:
            why.append(f"n={self._needed()} needs ~{self.memory_bytes / 2**30:.3g} GiB, more than the "
                       f"{self.memory_limit / 2**30:.3g} GiB available")
        if self.seconds > self.max_seconds:
            why.append(f"n={self._needed()} would take ~{self.seconds:.0f} s, more than the "
                       f"{self.max_seconds:.0f} s allowed")
        return "; ".join(why)

    def _needed(self) -> str:
        """The automatic grid: ``n_needed``, and ``x ny_needed`` when not square."""
        return f"{self.n_needed}" + (f" x {self.ny_needed}" if self.ny_needed != self.n_needed else "")

    def message(self) -> str:
        """Describe the plan in one line.

        Returns
        -------
        str
            The case, why it cannot be solved (:meth:`reason`), the N it needs with its
            memory and time, and the analytic W* of the route asked to use instead (or that
            there is none).
        """
        return (f"beta0={self.beta0:g}, mu={self.mu:g}: {self.reason() or 'can be solved'}; a resolved BEM "
                f"needs n >= {self._needed()} (~{self.memory_bytes / 2**30:.2g} GiB, ~{self.seconds / 60:.0f} min "
                f"estimated); {self.advice()}")

    def route(self) -> str:
        """Name the route the plan is for.

        Returns
        -------
        str
            'load control', 'displacement control' or 'a machine spring K* = ...'.
        """
        if self.control == "spring":
            return f"a machine spring K* = {self.machine_stiffness_star:.6g}"
        return f"{self.control} control"

    def advice(self) -> str:
        """Say which analytic value to use instead of the BEM, for the route asked.

        Returns
        -------
        str
            The analytic W* of :attr:`analytic_W_star` and its model, named with the route; where
            it is not finite, that no analytic value exists for that route.
        """
        if not math.isfinite(self.analytic_W_star):
            return f"no analytic W* exists for {self.route()} at this case"
        return (f"use the analytic W* = {self.analytic_W_star:.4f} under {self.route()} (md-elliptic: "
                "GVG x the sphere's MD/JKR transition) instead")


class UnresolvableCaseError(RuntimeError):
    """A BEM pull-off that cannot be resolved within the memory or time available, refused before solving.

    Parameters
    ----------
    plan : GridPlan
        The case, the N it needs, its estimated memory [bytes] and time [s], and the best
        analytic value (``plan.analytic_W_star``).

    Attributes
    ----------
    plan : GridPlan
        The plan given.
    n_needed : int
        Shortcut to ``plan.n_needed`` [-].
    memory_bytes : float
        Shortcut to ``plan.memory_bytes`` [bytes].
    seconds : float
        Shortcut to ``plan.seconds`` [s].
    analytic_W_star : float
        Shortcut to ``plan.analytic_W_star`` [-].
    """

    def __init__(self, plan: GridPlan):
        self.plan = plan
        self.n_needed = plan.n_needed
        self.memory_bytes = plan.memory_bytes
        self.seconds = plan.seconds
        self.analytic_W_star = plan.analytic_W_star
        super().__init__(plan.message())


def plan_grid(*, beta0, mu, n=None, law="dugdale", margin=DOMAIN_MARGIN,
              max_seconds=DEFAULT_MAX_SECONDS, ny=None, predicted=None, control="load",
              machine_stiffness=None) -> GridPlan:
    """Plan the grid a BEM pull-off at (mu, beta0) needs, its estimated cost, and the analytic fall-back.

    Parameters
    ----------
    beta0 : float
        Initial (Hertz) ellipticity in (0, 1] [-].
    mu : float
        Tabor parameter of Eq. (35), > 0 [-].
    n : int, optional
        Cells along x asked for [-]; default: the automatic choice ``n_needed``.
    law : {'dugdale', 'exponential'}, default 'dugdale'
        Traction law (sigma0 = mu, Delta gamma = 1).
    margin : float, default DOMAIN_MARGIN
        As in :func:`unloading_start` (the domain) [-].
    max_seconds : float, default DEFAULT_MAX_SECONDS
        Time allowed [s] (:attr:`GridPlan.affordable`).
    ny : int, optional
        Cells along y of the grid of ``n`` [-]; default ``n`` (``ny_needed`` when ``n`` is
        not given either).
    predicted : bool, optional
        Plan the automatic grid on the predicted route's domain (:func:`predicted_start`);
        default: for the Dugdale law at mu >= :data:`PREDICTED_MIN_MU` when ``n`` is not given
        (the load-control route :func:`adhesive_pull_off` then takes, :func:`takes_predicted_route`).
    control : {'load', 'displacement', 'spring'}, default 'load'
        The route whose analytic pull-off the plan names (:attr:`GridPlan.analytic_W_star`).
    machine_stiffness : float, optional
        K* >= 0 of the machine spring [-] (paper's units), required with ``control='spring'``
        and refused otherwise.

    Returns
    -------
    GridPlan
        The case, ``n`` and ``n_needed``, the edge ratio of the grid of ``n``, the estimated
        memory and time of the grid of ``n_needed``, the limits, and the analytic W* of the
        route asked.

    Raises
    ------
    ValueError
        If an argument is out of range (naming it).

    Notes
    -----
    The domain is :func:`unloading_start`'s.  For beta0 >= :data:`SHAPED_CELLS_MAX_BETA0` the
    grid has n x n cells over it (rectangular cells for beta0 < 1); below, n along x and
    ``ny = shaped_cells_y(n, ...)`` along y, about square cells (the Dugdale zone is about
    as wide along both axes, so it is resolved along both with fewer cells: 2.5x fewer at
    beta0 = 0.18, mu = 5; 4.6x at beta0 = 0.1).  ``n_needed`` is the smallest size of
    2^a 3^b 5^c (a multiple of 16, at least :data:`AUTO_MIN_CELLS`) whose
    :func:`dhfield.bem.solver.edge_width_ratio` is <= 1 (resolved: in the paper's units
    ``sqrt(dx dy) <= 2/(kappa mu^2)``) and whose cells number >= :data:`AUTO_ZONE_CELLS`
    across :func:`expected_zone_width` along x and along y (for shaped grids also >=
    :data:`AUTO_CONTACT_CELLS` across the DH model's contact semi-axes at pull-off, along x
    and y: the binding criterion on the DMT side, mu <~ 0.5).  Both fall like 1/mu^2, so N
    grows like mu^2 (ln-corrected): ~512 at mu = 5, ~1440 at mu = 10 for beta0 = 0.5.
    Memory ``PATH_BYTES_PER_CELL nx ny`` and time
    ``SECONDS_PER_CELL_ITERATION nx ny PULL_OFF_ITERATIONS`` (constants fitted to stored
    solves; the solver works on the quadrant, which these include).
    """
    mu = float(check_positive("mu", mu, "transition parameter of Eq. (35), dimensionless"))
    beta0 = float(check_ellipticity("beta0", beta0))
    max_seconds = float(check_positive("max_seconds", max_seconds, "time allowed, s"))
    w_star = analytic_pull_off(beta0=beta0, mu=mu, control=control, machine_stiffness=machine_stiffness)
    if predicted is None:
        predicted = takes_predicted_route(beta0=beta0, mu=mu, n=n, law=law)
    predicted = bool(predicted)
    margin = _check_margin(margin)
    start = (predicted_start(mu=mu, beta0=beta0, n_steps=DEFAULT_STEPS, margin=margin) if predicted
             else _start(mu, beta0, DEFAULT_STEPS, margin))
    law_obj = law_from_name(law, mu, 1.0)
    zone = expected_zone_width(mu)

    shaped = beta0 < SHAPED_CELLS_MAX_BETA0
    if shaped:                  # the contact at pull-off must be resolved along both axes
        po = dh_elliptic.pull_off(mu=mu, beta0=beta0)
        contact_dx, contact_dy = (float(po.a_star) / AUTO_CONTACT_CELLS, float(po.b_star) / AUTO_CONTACT_CELLS)

    def cells_y(k):
        return shaped_cells_y(k, start.half_width_x, start.half_width_y, contact_dy) if shaped else k

    def grid(k, k_y=None):
        return Grid.centered(k, start.half_width_x, ny=cells_y(k) if k_y is None else k_y,
                             half_width_y=start.half_width_y)

    def good(k):
        g = grid(k)
        fine = edge_width_ratio(g, law_obj) <= 1.0 and zone / max(g.dx, g.dy) >= AUTO_ZONE_CELLS
        return fine and (not shaped or g.dx <= contact_dx)

    sizes = _fft_sizes()
    n_needed = next((k for k in sizes if good(k)), None)
    if n_needed is None:        # beyond MAX_CELLS: extrapolate (N grows like mu^2)
        g = grid(MAX_CELLS)
        n_needed = int(2 * math.ceil(MAX_CELLS * max(edge_width_ratio(g, law_obj),
                                                     AUTO_ZONE_CELLS * max(g.dx, g.dy) / zone) / 2))
        ny_needed = int(2 * math.ceil(n_needed * g.ny / MAX_CELLS / 2))
    else:
        ny_needed = cells_y(n_needed)
    if n is None:
        n, ny = n_needed, (ny_needed if ny is None else check_cells(ny, "ny"))
    else:
        n = check_cells(n)
        ny = n if ny is None else check_cells(ny, "ny")
    memory_bytes, seconds = pull_off_cost(n_needed, ny_needed)
    return GridPlan(mu, beta0, int(n), int(n_needed), float(edge_width_ratio(grid(n, ny), law_obj)),
                    memory_bytes, seconds, memory_limit(), max_seconds, w_star, int(ny), int(ny_needed), predicted,
                    control, None if machine_stiffness is None else float(machine_stiffness))


def analytic_pull_off(*, beta0, mu, control="load", machine_stiffness=None) -> float:
    """The analytic W* to use where the BEM cannot answer, for the route asked [-].

    Parameters
    ----------
    beta0 : float
        Initial (Hertz) ellipticity in (0, 1] [-].
    mu : float
        Tabor parameter of Eq. (35), > 0 [-].
    control : {'load', 'displacement', 'spring'}, default 'load'
        The route: the minimum of the load, the minimum of the approach, or the jump out
        under a machine spring.
    machine_stiffness : float, optional
        K* >= 0 of the spring [-] (paper's units, :func:`dhfield.analysis.spring.stiffness_star`);
        required with ``control='spring'``, refused otherwise.

    Returns
    -------
    float
        :func:`dhfield.models.md_elliptic.pull_off_nondimensional` under ``control`` (load or
        displacement), or the jump out of that model's curve under the spring
        (:func:`dhfield.analysis.spring.pull_off_under_spring`); NaN where the model gives no finite
        value (the plan then says no analytic value exists for the route).

    Raises
    ------
    ValueError
        If ``control`` is unknown, or ``machine_stiffness`` is missing or out of range for it.
    """
    from ..models import md_elliptic

    if control not in ("load", "displacement", "spring"):
        raise ValueError(f"control must be one of ('load', 'displacement', 'spring') (loading mode); got {control!r}")
    if (control == "spring") != (machine_stiffness is not None):
        raise ValueError("machine_stiffness goes with control='spring' and only with it (K* of the machine "
                         f"spring, paper's units); got control={control!r}, machine_stiffness={machine_stiffness!r}")
    if control == "spring":
        from .compare import DEFAULT_MODEL
        from .spring import check_machine_stiffness, pull_off_under_spring

        k = float(check_machine_stiffness("machine_stiffness", machine_stiffness))
        w = pull_off_under_spring(DEFAULT_MODEL, beta0=beta0, mu=mu, machine_stiffness=k)["W_star"]
    else:
        w = md_elliptic.pull_off_nondimensional(beta0, mu, control=control).W_star
    w = float(np.asarray(w, float))
    return w if math.isfinite(w) else float("nan")


@dataclass(frozen=True)
class AdhesiveOptions:
    """Numerical settings of :func:`adhesive_pull_off` (the defaults are the tested ones).

    Parameters
    ----------
    n_steps : int, default DEFAULT_STEPS
        Unloading steps (4 to 1e6) [-]; see :func:`unloading_start`.
    refine_levels : int, default 2
        Refinements of the pull-off bracket (0-20) [-]; see :class:`dhfield.bem.path.PathOptions`.
    tol : float, optional
        Solver tolerance [-]; see :class:`dhfield.bem.path.PathOptions`.  Default (None):
        ``DEFAULT_TOL`` on every route.
    max_iter : int, default DEFAULT_MAX_ITER
        Iteration cap per state [-]; see :class:`dhfield.bem.path.PathOptions`.
    margin : float, default DOMAIN_MARGIN
        Domain half-width per expected zone semi-axis, > 1 [-]; see :func:`unloading_start`.
    keep_states : bool, default False
        Keep every state of the path; see :class:`dhfield.bem.path.PathOptions`.
    max_seconds : float, default DEFAULT_MAX_SECONDS
        Automatic n only: the estimated time allowed [s] (:func:`plan_grid`).
    nested : bool, optional
        Bracket search only: start every state from the same approach solved
        on a grid half as fine (:class:`dhfield.bem.pull_off.NestedWarmStart`).
        Default (None): when ``n >= 2 * NESTED_MIN_N``.
    """

    n_steps: int = DEFAULT_STEPS
    refine_levels: int = 2
    tol: float | None = None
    max_iter: int = DEFAULT_MAX_ITER
    margin: float = DOMAIN_MARGIN
    keep_states: bool = False
    max_seconds: float = DEFAULT_MAX_SECONDS
    nested: bool | None = None


def adhesive_pull_off(*, beta0, mu, n=None, ny=None, law="dugdale", control="load", search=None,
                      threads=None, progress=None, options=None) -> PullOff:
    """Compute the BEM pull-off of the adhesive crossed-cylinder (elliptical) contact, paper units.

    Parameters
    ----------
    beta0 : float
        Initial ellipticity (Hertz b/a of the geometry) in (0, 1] [-].
    mu : float
        Tabor parameter, Eq. (35), > 0 [-] (sigma0 = mu, Delta gamma = 1).
    n : int, optional
        Cells along x (even; and along y unless ``ny`` is given) [-].  Default: chosen from
        the expected zone width and the law's edge (:func:`plan_grid`, ``n_needed`` x
        ``ny_needed``: about square cells below beta0 = SHAPED_CELLS_MAX_BETA0), refused with
        :class:`UnresolvableCaseError` before anything is solved when that grid does not fit
        the memory available or ``options.max_seconds``.
    ny : int, optional
        Cells along y (even) [-]; default ``n``, or the automatic ``ny_needed`` when ``n``
        is not given.
    law : {'dugdale', 'exponential'}
        Traction law (:mod:`dhfield.bem.laws`).
    control : {'load', 'displacement'}
        Load control: the minimum of the unloading load.  Displacement control:
        the jump, the minimum of the approach along the branch (its fold, or
        the loss of contact; :mod:`dhfield.bem.continuation`).
    search : {'newton', 'located', 'bracket', 'march', 'predicted'}, optional
        Load control only (the route taken is the record's ``search``).  Default (None):
        'newton' for the Dugdale law's load-control pull-off on the automatic grid with the
        default path settings (:func:`takes_newton_route`), else 'located'.
        'newton': the semismooth Newton state solve on two grids
        (:func:`dhfield.bem.ladder.ladder_pull_off`; Dugdale law only): the answer's grid holds
        at least the planned (or given) cells, the check grid three quarters of them with the
        Dugdale edge resolved, and the stated error is the grid ladder's; on the automatic
        grid, finer grids follow while it exceeds :data:`LADDER_TARGET_ERROR`.
        'predicted': the high-mu route (:func:`dhfield.bem.pull_off.predicted_path`: lattice samples around
        GVG's pull-off) on its own domain,
        also on an explicit ``n`` x ``ny`` grid (no lattice retry there); Dugdale law only.
        'located' takes it by itself on automatic grids at mu >= :data:`PREDICTED_MIN_MU`
        (:func:`takes_predicted_route`); asking for it on an explicit grid makes a refined
        grid of the same route and domain (``dhfield sweep``'s grid levels at those mu).
        'located' (the default of the other cases) is 'bracket' with the minimum located on coarser
        grids first (below).  'bracket': cold-start at the analytic
        pull-off approach from its cohesive zone (:func:`unloading_start`) and
        bracket the load minimum there (a handful of states;
        :func:`dhfield.bem.path.bracket_search`).  'march': unload from
        ``approach_max`` in uniform steps to the jump and refine the minimum's
        bracket (~5x more states, same pull-off).  'located': the minimum is
        located on the grids 2x, 4x, ... coarser (the bracket search on the
        coarsest resolved one; three samples of the approach lattice
        ``approach_max - j approach_step/2`` around the coarser level's minimum
        on every finer one), and on this grid only those lattice samples and at
        most one parabola vertex (none with ``options.refine_levels=0``) are solved,
        each from the same approach on the grid half as fine: 3-4 fine states
        instead of 4-6 at N = 256, the same pull-off to the
        jaggedness of the discrete load curve (~5e-4).  Falls back to 'bracket'
        (keeping the coarse states) when ``n < 2 NESTED_MIN_N``, when the grid
        half as fine is too coarse for the Dugdale edge
        (:data:`dhfield.bem.pull_off.LOCATE_MAX_EDGE_RATIO`), when the located
        minimum is not interior, or when a fine state does not converge.
    threads : int, optional
        FFTW threads; see :class:`dhfield.bem.path.PathOptions`.
    progress : bool, optional
        Progress line on stderr; see :class:`dhfield.bem.path.PathOptions`.
    options : AdhesiveOptions, optional
        Numerical settings (steps, refinements, tolerance, iteration cap, domain margin,
        kept states, time allowed, nested warm starts); default ``AdhesiveOptions()``.

    Returns
    -------
    dhfield.core.records.PullOff
        The one pull-off record of every model, with ``model='bem'`` and its solver group
        (:func:`dhfield.bem.pull_off.pull_off_result` lists the BEM's fields): W* in the
        normalisation of Eq. (34) with sin(theta_skew) of beta0, like every other model of
        :mod:`dhfield.analysis.compare`; semi-axes in c_r; the whole path in ``path``.

    Raises
    ------
    UnresolvableCaseError
        Automatic n only: the grid the case needs exceeds the memory or the time allowed;
        the exception carries that N, its estimated memory and time, and the analytic
        W* to use instead (one-line message).
    ValueError
        If an argument is out of its range (naming it), e.g. an unknown ``search`` or
        ``control``.

    Notes
    -----
    With R = E* = Delta gamma = 1 (Eqs. 32-35): the initial gap is Eq. (2) with
    R' R'' = 1, the law has sigma0 = mu and range 1/mu, and

    .. math:: W^* = \\frac{W \\sin\\theta_{skew}}{2\\pi R\\Delta\\gamma}

    (Eq. 34).  The domain and the path come from :func:`nondimensional_problem`.
    """
    from ..bem.pull_off import SEARCHES

    if options is None:
        options = AdhesiveOptions()
    elif not isinstance(options, AdhesiveOptions):
        raise ValueError(f"options must be an AdhesiveOptions (numerical settings); got {type(options).__name__}")
    n_steps, refine_levels, tol, max_iter = options.n_steps, options.refine_levels, options.tol, options.max_iter
    margin, keep_states, max_seconds = options.margin, options.keep_states, options.max_seconds
    nested = options.nested

    for name, value in (("mu", mu), ("beta0", beta0)):  # one case per call: scalars only
        if np.ndim(value) != 0:
            raise ValueError(f"{name} must be a scalar (one BEM case per call); got an array of shape "
                             f"{np.shape(value)}")
    if search is None:       # the default route (takes_newton_route)
        search = NEWTON_SEARCH if takes_newton_route(law=law, control=control, n=n, options=options) else "located"
    if search not in SEARCHES + (PREDICTED_SEARCH, NEWTON_SEARCH):
        raise ValueError(f"search must be one of {SEARCHES + (PREDICTED_SEARCH, NEWTON_SEARCH)} (load-control "
                         f"path); got {search!r}")
    if control not in ("load", "displacement"):
        raise ValueError(f"control must be one of ('load', 'displacement') (loading mode); got {control!r}")
    if search == NEWTON_SEARCH:
        if not (law == "dugdale" and control == "load"):
            raise ValueError(f"search='newton' needs law='dugdale' and control='load' (the Newton pull-off); got "
                             f"law={law!r}, control={control!r}")
        return _newton_pull_off(beta0=beta0, mu=mu, n=n, ny=ny, threads=threads, margin=margin,
                                max_seconds=max_seconds)
    if search == PREDICTED_SEARCH and not (law == "dugdale" and control == "load" and nested is None):
        raise ValueError("search='predicted' needs law='dugdale', control='load', and options.nested None (the "
                         f"predicted route has no nested starts); got law={law!r}, control={control!r}, "
                         f"nested={nested!r}")
    options = PathOptions(refine_levels=refine_levels, tol=DEFAULT_TOL if tol is None else tol,
                          max_iter=max_iter, threads=threads, keep_states=keep_states, progress=progress)
    if n is None:
        coarse_route = control == "load" and search == "located" and nested is None and law == "dugdale"
        predicted = takes_predicted_route(beta0=beta0, mu=mu, law=law, control=control, search=search, nested=nested)
        plan = plan_grid(mu=mu, beta0=beta0, law=law, margin=margin, max_seconds=max_seconds, predicted=predicted,
                         control=control)
        if not plan.affordable:
            raise UnresolvableCaseError(plan)
        n = plan.n_needed
        ny = plan.ny_needed if ny is None else ny
        if plan.predicted:
            # high mu: the grid half as fine cannot hold the Dugdale edge; only fine lattice
            # samples around GVG's pull-off, on a domain holding its zone (nx x ny cells)
            prob = predicted_problem(mu=mu, beta0=beta0, n=n, n_steps=n_steps, margin=margin, ny=ny)
            return _predicted_pull_off(prob, options)
        bracket_here = coarse_route and n % 4 == 0 and ny % 4 == 0 and not _half_grid_locates(plan, law, margin)
    elif search == PREDICTED_SEARCH:
        # the route on the caller's grid (a refined grid of the same route and domain)
        prob = predicted_problem(mu=mu, beta0=beta0, n=n, n_steps=n_steps, margin=margin, ny=ny)
        return _predicted_pull_off(prob, options)
    else:
        bracket_here = False
    prob = nondimensional_problem(mu=mu, beta0=beta0, n=n, law=law, n_steps=n_steps, margin=margin, ny=ny)
    if bracket_here and prob.has_cold_start:
        # the grid half as fine cannot hold the Dugdale edge (LOCATE_MAX_EDGE_RATIO): the bracket
        # search on this grid from the analytic pull-off, each state by nested iteration where its
        # neighbour does not start it (dhfield.bem.solver.solve_problem)
        search = "bracket"
    res = solve_pull_off(prob, control=control, search=search, nested=nested, options=options)
    if control == "displacement":
        res = _ladder_checked(prob, res, n_steps=n_steps, margin=margin, options=options)
    return res


def _newton_pull_off(*, beta0, mu, n, ny, threads, margin, max_seconds) -> PullOff:
    """The load-control Dugdale pull-off by :func:`dhfield.bem.ladder.ladder_pull_off`, as a record.

    The answer's grid has at least the planned cells (:func:`plan_grid`, or ``n`` x ``ny``) and
    its check grid resolves the Dugdale edge with the margin (:func:`dhfield.bem.ladder.ladder_grids`);
    on an automatic grid, finer grids follow while the stated error exceeds
    :data:`LADDER_TARGET_ERROR` (at most :data:`LADDER_REFINEMENTS`, each within the memory);
    the domain and the first approach are the predicted route's (:func:`predicted_problem`), or
    the analytic models' (:func:`nondimensional_problem`) where the predicted zone does not fit.
    """
    from ..bem import ladder

    automatic = n is None
    if automatic:
        plan = plan_grid(mu=mu, beta0=beta0, law="dugdale", margin=margin, max_seconds=max_seconds,
                         control="load")
        if not plan.affordable:
            raise UnresolvableCaseError(plan)
        n, ny = plan.n_needed, plan.ny_needed
    ny = n if ny is None else ny
    prob = newton_problem(mu=mu, beta0=beta0, n=n, ny=ny, margin=margin)
    (nc, _), (nf, nyf) = newton_grids(prob)
    check_grid_memory(nf, nyf)
    fine = prob.on_cells(nf, nyf)
    res = ladder.ladder_pull_off(fine, nc, threads=1 if threads is None else threads,
                                 target_error=LADDER_TARGET_ERROR, max_refinements=LADDER_REFINEMENTS if automatic else 0,
                                 grid_check=check_grid_memory, max_seconds=max_seconds)
    return ladder.pull_off_record(res)


def newton_grids(problem) -> tuple:
    """The check grid and the answer's grid of the Newton route on ``problem``'s domain (before refinement).

    Parameters
    ----------
    problem : NondimensionalProblem
        The route's problem (:func:`newton_problem`); its grid is the smallest answer's grid.

    Returns
    -------
    ((int, int), (int, int))
        Cells (nx, ny) of the check grid and of the answer's grid
        (:func:`dhfield.bem.ladder.ladder_grids`, rounded by :func:`dhfield.bem.ladder.nested_cells`
        so that their nested levels reach ~16 cells per axis).
    """
    from ..bem import ladder

    nc, nf = ladder.ladder_grids(problem)
    return ladder.nested_cells(problem, nc), ladder.nested_cells(problem, nf)


#: The Newton route refines its grids (each 4/3 times the last's cells per axis) until the stated
#: error is at most this [-] ...
LADDER_TARGET_ERROR = 2e-3
#: ... at most this many times, each within the memory and the time allowed (``max_seconds``) [-].
#: With at most 2 (before 2026-12-02, and the pre-check grid counted as one), beta0 = 0.047 at
#: mu = 2 and 3 stopped at stated errors of 1.4 % and 1.3 % after a few seconds.
LADDER_REFINEMENTS = 4


def _ladder_checked(prob, res, *, n_steps, margin, options) -> PullOff:
    """The displacement-control pull-off ``res`` on ``prob`` with the grid's error from a coarser grid.

    The same route on the first of :func:`dhfield.bem.pull_off.ladder_cells` (half, then three
    quarters of the cells per axis) over the same domain whose edge ratio is at most
    :data:`dhfield.bem.pull_off.LOCATE_MAX_EDGE_RATIO` (its states converge); its W* gives the
    stated error (:func:`dhfield.bem.pull_off.route_error`).  Where there is no such grid, or its
    pull-off is not converged, there is no estimate: the record is then unresolved (infinite ``W_star_error``).  An unresolved
    ``res`` is returned as it is.
    """
    from ..bem.pull_off import LOCATE_MAX_EDGE_RATIO, ladder_cells, pull_off_result

    if not res.resolved:          # not an answer whatever its error: no grid half as fine to solve
        return res
    n, ny = prob.grid.nx, prob.grid.ny
    w_c, n_c, elapsed = float("nan"), 0, 0.0
    for n_c, ny_c in zip(ladder_cells(n), ladder_cells(ny)):
        coarse = nondimensional_problem(mu=prob.mu, beta0=prob.beta0, n=n_c, law=prob.law.name, n_steps=n_steps,
                                        margin=margin, ny=ny_c)
        if edge_width_ratio(coarse.grid, coarse.law) <= LOCATE_MAX_EDGE_RATIO:
            got = solve_pull_off(coarse, control="displacement", options=replace(options, progress=False))
            elapsed = got.elapsed
            if got.converged and np.isfinite(got.W_star):
                w_c = float(got.W_star)
            break
    out = pull_off_result(prob, n, res.path, res.search, coarse=(w_c, n_c), options=options)
    return replace(out, elapsed=res.elapsed + elapsed)


#: Smallest mu at which an automatic grid of the path routes whose half grid cannot hold the
#: Dugdale edge solves only fine lattice samples around GVG's pull-off (:func:`_predicted_pull_off`)
#: instead of the bracket search (docs/theory/bem.rst, 'Measurements behind the solver's constants').
PREDICTED_MIN_MU = 7.5
#: The ``search`` of :func:`adhesive_pull_off` that asks for the predicted route, also on an explicit
#: grid (the refined grid levels of ``dhfield sweep`` at mu >= PREDICTED_MIN_MU).
PREDICTED_SEARCH = "predicted"

#: The note of a stored record solved with the Dugdale edge at its widest (the option
#: ``AdhesiveOptions.widest_edge``, removed 2026-12-02: the cases of
#: ``data/adhesive_ground_truth_extended.nc`` that used it carry this note in their message);
#: it ends with :data:`WIDEST_EDGE_MARK`, which readers of those files look for.
WIDEST_EDGE_NOTE = "Dugdale edge held at its cap 2 h0 on the grid of the answer (options.widest_edge)"
#: What a stored record's note or message carries when it was solved with the widest edge.
WIDEST_EDGE_MARK = "(options.widest_edge)"


def takes_newton_route(*, law="dugdale", control="load", n=None, search=None, options=None) -> bool:
    """Tell whether :func:`adhesive_pull_off` solves a case by the Newton route (``search='newton'``).

    The Newton route (:func:`dhfield.bem.ladder.ladder_pull_off`) is the default of the Dugdale
    law's load-control pull-off on the automatic grid: no ``n``, no ``search``, and none of the
    settings only the path routes read (:class:`AdhesiveOptions`' ``n_steps``, ``refine_levels``,
    ``tol``, ``max_iter``, ``keep_states``, ``nested`` at their defaults;
    ``margin`` and ``max_seconds`` apply to both).  Any other case takes the path routes
    (``search='located'`` and its predicted route at high mu), as does an explicit ``search``
    other than ``'newton'``.  :func:`adhesive_pull_off`, the command line and the sweep share
    this rule.

    Parameters
    ----------
    law : {'dugdale', 'exponential'}, default 'dugdale'
        Traction law.
    control : {'load', 'displacement'}, default 'load'
        Loading mode.
    n : int, optional
        Cells along x asked for (None: the automatic grid).
    search : str, optional
        The search asked for (None: the default route).
    options : AdhesiveOptions, optional
        Numerical settings.

    Returns
    -------
    bool
        True where the case is solved by the Newton route.
    """
    if search is not None:
        return search == NEWTON_SEARCH
    opts = AdhesiveOptions() if options is None else options
    path_settings = replace(opts, margin=DOMAIN_MARGIN, max_seconds=DEFAULT_MAX_SECONDS) != AdhesiveOptions()
    return bool(law == "dugdale" and control == "load" and n is None and not path_settings)


def takes_predicted_route(*, beta0, mu, n=None, law="dugdale", control="load", search="located", nested=None) -> bool:
    """Tell whether :func:`adhesive_pull_off` solves a case by the predicted route.

    The route solves fine lattice samples around GVG's pull-off only
    (:func:`dhfield.bem.pull_off.predicted_path`).

    :func:`adhesive_pull_off`, :func:`plan_grid` (its default) and the command line share this
    rule, so that a plan is made on the domain the solve will use.

    Parameters
    ----------
    beta0 : float
        Initial (Hertz) ellipticity in (0, 1] [-].
    mu : float
        Tabor parameter of Eq. (35), > 0 [-].
    n : int, optional
        Cells along x asked for; by default the route is taken by automatic grids only (``n`` None).
    law : {'dugdale', 'exponential'}, default 'dugdale'
        Traction law.
    control : {'load', 'displacement'}, default 'load'
        Loading mode.
    search : str, default 'located'
        Load-control search of :func:`adhesive_pull_off`; ``'predicted'`` (:data:`PREDICTED_SEARCH`)
        asks for the route on any grid and at any mu.
    nested : bool, optional
        :attr:`AdhesiveOptions.nested`; the route needs the default (None).

    Returns
    -------
    bool
        True for an automatic grid under the default load-control search with the Dugdale law
        at mu >= :data:`PREDICTED_MIN_MU`, at every beta0 (slender contacts on shaped nx x ny
        grids too).
    """
    if search == PREDICTED_SEARCH:      # asked for (adhesive_pull_off refuses it with another law or control)
        return bool(law == "dugdale" and control == "load" and nested is None)
    return bool(n is None and law == "dugdale" and control == "load" and search == "located" and nested is None
                and float(mu) >= PREDICTED_MIN_MU)


def predicted_start(*, beta0, mu, n_steps=DEFAULT_STEPS, margin=DOMAIN_MARGIN) -> UnloadingStart:
    """The start of the predicted route: GVG's pull-off, on a domain holding its zone.

    Parameters
    ----------
    beta0 : float
        Initial (Hertz) ellipticity in (0, 1] [-].
    mu : float
        Tabor parameter of Eq. (35), > 0 [-].
    n_steps : int, default DEFAULT_STEPS
        Unloading steps, as in :func:`unloading_start` (the approach lattice) [-].
    margin : float, default DOMAIN_MARGIN
        Domain half-width per semi-axis of the cold start's zone, > 1 [-].

    Returns
    -------
    UnloadingStart
        :func:`unloading_start`'s path range (``approach_max``, ``approach_step``: the same
        approach lattice), with GVG's load-control pull-off corrected by the sphere's MD as
        the cold start (:func:`_gvg_md_start`: its approach, its contact ellipse widened by
        the MD zone) and half-widths ``margin`` times that zone's semi-axes (never wider than
        :func:`unloading_start`'s).

    Notes
    -----
    Only states near the pull-off are solved (:func:`dhfield.bem.pull_off.predicted_path`),
    so the domain need not hold the zone at the start of unloading, and the edge is resolved
    with fewer cells (at beta0 = 0.4826, mu = 10: N = 1280 instead of 1440).  The zone grows
    by ~1.5 % per lattice sample above the pull-off, so ``margin`` = 1.15 holds about ten
    samples above it (the search adds at most ``LOCATE_MAX_EXTEND`` = 6).
    """
    mu = float(check_positive("mu", mu, "transition parameter of Eq. (35), dimensionless"))
    beta0 = float(check_ellipticity("beta0", beta0))
    margin = _check_margin(margin)
    base = _start(mu, beta0, n_steps, margin)
    approach, zone = _gvg_md_start(mu, beta0)
    return replace(base, half_width_x=min(base.half_width_x, margin * zone[0]),
                   half_width_y=min(base.half_width_y, margin * zone[1]), approach=approach, zone=zone)


def _gvg_md_start(mu, beta0):
    """(approach, (c, d)) of GVG's JKR load-control pull-off corrected to finite mu by the sphere's MD.

    The contact semi-axes of :mod:`dhfield.models.jkr_elliptic_energy` times the sphere's
    a_MD/a_JKR at pull-off, widened by the sphere's MD zone width c_MD - a_MD
    (:mod:`dhfield.models.maugis_dugdale`), at GVG's approach plus the sphere's
    delta_MD - delta_JKR.  Only a start (any converging start gives the same state): on the
    sphere at mu = 5 the BEM's pull-off contact (N = 256: a* = 1.510, c* = 1.539) is within
    0.4 cell of it (a = 1.504, c = 1.534) and 1.1 cells from GVG's widened by
    :func:`expected_zone_width` (c = 1.555); the edge's creep from a start a cell off costs
    most of the outer iterations of a cold state.
    """
    from ..models import jkr_elliptic_energy, maugis_dugdale

    gvg = jkr_elliptic_energy.pull_off_nondimensional(beta0, mu, control="load")
    jkr = jkr_elliptic_energy.pull_off_nondimensional(1.0, mu, control="load")
    md = maugis_dugdale.pull_off_nondimensional(1.0, mu, control="load")
    ratio = float(md.a_star) / float(jkr["a_star"])
    w = float(md.c_star) - float(md.a_star)
    approach = float(gvg["delta_star"]) + float(md.delta_star) - float(jkr["delta_star"])
    return approach, (ratio * float(gvg["a_star"]) + w, ratio * float(gvg["b_star"]) + w)


def predicted_problem(*, beta0, mu, n, n_steps=DEFAULT_STEPS, margin=DOMAIN_MARGIN, ny=None) -> NondimensionalProblem:
    """The paper's problem (Dugdale law) on the predicted route's domain with its start (:func:`predicted_start`).

    Parameters
    ----------
    beta0 : float
        Initial (Hertz) ellipticity in (0, 1] [-].
    mu : float
        Tabor parameter of Eq. (35), > 0 [-].
    n : int
        Cells per axis, even, 8 to 65536 [-].
    n_steps : int, default DEFAULT_STEPS
        Unloading steps (4 to 1e6) [-].
    margin : float, default DOMAIN_MARGIN
        As in :func:`predicted_start` [-].
    ny : int, optional
        Cells along y (even, 8 to 65536) [-]; default ``n``.

    Returns
    -------
    NondimensionalProblem
        :func:`dhfield.bem.pull_off.paper_problem` with :func:`predicted_start`.
    """
    n = check_cells(n)
    ny = n if ny is None else check_cells(ny, "ny")
    check_grid_memory(n, ny)
    n_steps = check_count("n_steps", n_steps, 4, MAX_STEPS, "unloading steps")
    return paper_problem(mu=mu, beta0=beta0, n=n, ny=ny,
                         start=predicted_start(mu=mu, beta0=beta0, n_steps=n_steps, margin=margin))


def newton_problem(*, beta0, mu, n, ny=None, margin=DOMAIN_MARGIN) -> NondimensionalProblem:
    """The paper's problem (Dugdale law) on the Newton route's domain, with its cold start.

    The domain holds both analytic estimates of the pull-off's cohesive zone with the margin:
    the predicted route's (:func:`predicted_start`: GVG's contact widened by the sphere's MD
    zone, close to the BEM's at mu >= 5) and the analytic models' (:func:`unloading_start`:
    the zone of the slender and low-mu contacts, whose zone is elongated with the contact and
    which the predicted estimate undercuts, e.g. c = 2.77 against the BEM's 3.29 at
    beta0 = 0.5, mu = 0.3).  Its half-widths are ``margin`` times the larger semi-axis of the
    two per axis, never wider than :func:`unloading_start`'s domain.  The cold start is the
    predicted route's where its zone lies inside that domain, else the models'.

    Parameters
    ----------
    beta0 : float
        Hertz ellipticity b/a in (0, 1] (Eq. 9) [-].
    mu : float
        Tabor parameter of Eq. (35), > 0 [-].
    n : int
        Cells along x (even, 8 to 65536) [-].
    ny : int, optional
        Cells along y [-]; default ``n``.
    margin : float, default DOMAIN_MARGIN
        Domain half-width per zone semi-axis, > 1 [-].

    Returns
    -------
    NondimensionalProblem
        :func:`dhfield.bem.pull_off.paper_problem` on that domain with that start.
    """
    mu = float(check_positive("mu", mu, "transition parameter of Eq. (35), dimensionless"))
    beta0 = float(check_ellipticity("beta0", beta0))
    margin = _check_margin(margin)
    n = check_cells(n)
    ny = n if ny is None else check_cells(ny, "ny")
    check_grid_memory(n, ny)
    base = _start(mu, beta0, DEFAULT_STEPS, margin)
    approach, zone = _gvg_md_start(mu, beta0)
    half_x = min(base.half_width_x, margin * max(zone[0], base.zone[0]))
    half_y = min(base.half_width_y, margin * max(zone[1], base.zone[1]))
    start = replace(base, half_width_x=half_x, half_width_y=half_y)
    if zone[0] < half_x and zone[1] < half_y:
        start = replace(start, approach=approach, zone=zone)
    return paper_problem(mu=mu, beta0=beta0, n=n, ny=ny, start=start)


def _predicted_pull_off(prob, options, *, tol=None) -> PullOff:
    """Load-control pull-off at high mu from fine lattice samples around the problem's cold start.

    ``prob`` from :func:`predicted_problem`: its cold start is GVG's load-control pull-off
    (corrected by the sphere's MD), which at high mu lies within a lattice step of the BEM's;
    :func:`dhfield.bem.pull_off.predicted_path` solves the samples around it, to ``tol`` (default
    ``options.tol``).  When that
    fails the record says so (``converged`` False) and its ``note`` names why and the analytic W*
    to use instead (:func:`dhfield.models.md_elliptic.pull_off_nondimensional`).  No other route
    is tried (:data:`PREDICTED_MIN_MU`).

    The first state starts from GVG's zone, each other from its nearest solved neighbour, and
    a state that does not converge from its start by nested iteration from the coarsest grid
    (:func:`dhfield.bem.solver.solve_problem`).
    """
    from ..models import md_elliptic
    from ..bem.pull_off import predicted_path, pull_off_result

    options = options.checked()
    if tol is not None:
        options = replace(options, tol=tol)
    path = predicted_path(prob, options)
    res = pull_off_result(prob, prob.grid.nx, path, PREDICTED_SEARCH, options=options)   # the route, named as asked for
    if res.converged:
        return res
    w = float(md_elliptic.pull_off_nondimensional(prob.beta0, prob.mu).W_star)
    return replace(res, note="; ".join(filter(None, (res.note, f"use the analytic W* = {w:.4f} "
                                                                "(md-elliptic) instead"))))


def _half_grid_locates(plan, law, margin) -> bool:
    """True when the grid half as fine as ``plan.n_needed`` passes the located search's edge gate."""
    from ..bem.pull_off import LOCATE_MAX_EDGE_RATIO

    start = _start(plan.mu, plan.beta0, DEFAULT_STEPS, _check_margin(margin))
    half = Grid.centered(plan.n_needed // 2, start.half_width_x, ny=plan.ny_needed // 2,
                         half_width_y=start.half_width_y)
    return edge_width_ratio(half, law_from_name(law, plan.mu, 1.0)) <= LOCATE_MAX_EDGE_RATIO


def refine_pull_off(coarse, n, *, refine_factor=4, window=3, threads=None, progress=None,
                    options=None) -> PullOff:
    """Compute the load-control pull-off on a finer grid, started from a coarser solution.

    The fine states sit on the finest approach lattice of the full path set by
    ``options.n_steps``, ``options.refine_levels`` and ``refine_factor``
    (:func:`adhesive_pull_off`), so that the fine pull-off equals the full fine path's
    wherever both bracket the same samples.

    Parameters
    ----------
    coarse : dhfield.core.records.PullOff
        A BEM pull-off of the same (mu, beta0, law) on a coarser grid (load
        control), e.g. from :func:`adhesive_pull_off` at N = 256 or from a
        previous call of this function.
    n : int
        Cells per axis of the fine grid (even, > ``coarse.n``) [-].
    refine_factor : int, default 4
        Step division per refinement (2-100) [-].
    window : int, default 3
        Half-width of the window of fine states around the coarse pull-off, in
        finest path steps (extended while the fine minimum sits on its edge) [-].
    threads : int, optional
        FFTW threads; see :class:`dhfield.bem.path.PathOptions`.
    progress : bool, optional
        Progress line on stderr; see :class:`dhfield.bem.path.PathOptions`.
    options : AdhesiveOptions, optional
        Numerical settings, as for :func:`adhesive_pull_off`; used here: ``n_steps`` (unloading
        steps of the full path), ``refine_levels`` (refinements of its pull-off bracket),
        ``tol``, ``max_iter`` and ``keep_states``; default ``AdhesiveOptions()``.

    Returns
    -------
    dhfield.core.records.PullOff
        As :func:`adhesive_pull_off` (``search='refine'``), with ``path.phase == 'refine'`` for every
        state (:func:`dhfield.bem.pull_off.refine`).

    Raises
    ------
    ValueError
        If ``coarse`` is not a BEM :class:`~dhfield.core.records.PullOff`, ``n`` is not
        above ``coarse.n``, or another argument is out of range (naming it).
    """
    check_bem_pull_off("coarse", coarse)
    n = check_count("n", n, 8, 2 ** 16, "cells per axis")
    if n <= coarse.n:
        raise ValueError(f"n must be an integer > coarse.n = {coarse.n} (cells per axis); got {n!r}")
    window = check_count("window", window, 1, MAX_STEPS, "finest path steps")
    if options is None:
        options = AdhesiveOptions()
    elif not isinstance(options, AdhesiveOptions):
        raise ValueError(f"options must be an AdhesiveOptions (numerical settings); got {type(options).__name__}")
    path_options = PathOptions(refine_levels=options.refine_levels, refine_factor=refine_factor,
                               tol=DEFAULT_TOL if options.tol is None else options.tol,
                               max_iter=options.max_iter, threads=threads, keep_states=options.keep_states,
                               progress=progress).checked()
    prob = nondimensional_problem(mu=coarse.mu, beta0=coarse.beta0, n=n, law=coarse.law, n_steps=options.n_steps)
    return refine(prob, coarse, window=window, options=path_options)

