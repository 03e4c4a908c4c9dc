"""The typed state of a BEM contact solution (:class:`ContactState`).

One object carries everything a BEM solution has: the grid, the full-grid
pressure and gap fields, the approach and load, the contact and cohesive-zone
masks, the traction law and the solver's convergence record.  The adhesive
solver (:func:`dhfield.bem.solver.solve_adhesive`) returns it, and the
analysis modules (periphery, Eq. 30, I/O) accept it, so a BEM solution can be
analysed like an analytic one.

Units and signs
---------------
The state is in whatever consistent units the caller used (SI, or the paper's
nondimensional units of Eqs. 32-35 with R = E* = Delta gamma = 1, in which
lengths are in c_r, the approach in c_r^2/R and stresses in E* c_r/R).  As in
:mod:`dhfield.bem.operator`: pressure positive in compression (the adhesive
traction is negative pressure); gap ``h = z - delta + omega >= 0``; load
positive compressive (pull-off loads are negative).

Semi-axes from second moments
-----------------------------
For a uniform ellipse of semi-axes a >= b centred at the origin, the area
second moments are <x'^2> = a^2/4 and <y'^2> = b^2/4 along its principal
axes.  The semi-axes of a mask (weights w in [0, 1] per cell) are therefore

.. math:: a = 2\\sqrt{\\lambda_{max}(C)}, \\qquad b = 2\\sqrt{\\lambda_{min}(C)}

with C the weighted covariance matrix of the cell centres.  For a rasterised
ellipse the error is O(h) in the cell size h (the pixel boundary); with
fractional edge weights (the cohesive zone) it is smaller.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from .laws import DugdaleLaw, ExponentialLaw
from .operator import Grid

__all__ = ["ContactState", "mask_semi_axes"]


def mask_semi_axes(weights, grid: Grid) -> tuple[float, float]:
    """Compute the semi-axes (major, minor) of a mask from its second moments [length].

    Parameters
    ----------
    weights : array_like, shape (nx, ny)
        Cell weights in [0, 1] (a bool mask, or the fraction of each cell inside
        the region) [-].
    grid : Grid
        The cell grid.

    Returns
    -------
    (float, float)
        ``2 sqrt`` of the largest and smallest eigenvalue of the weighted
        covariance of the cell centres (the semi-axes of the uniform ellipse
        with the same second moments); (0, 0) for an empty mask.
    """
    w = np.asarray(weights, dtype=float)
    if w.shape != grid.shape:
        raise ValueError(f"weights must have the grid shape {grid.shape}; got {w.shape}")
    total = float(w.sum())
    if total <= 0.0:
        return 0.0, 0.0
    x, y = grid.x, grid.y
    wx = w.sum(axis=1)
    wy = w.sum(axis=0)
    mx = float(wx @ x) / total
    my = float(wy @ y) / total
    xc = x - mx
    yc = y - my
    cxx = float(wx @ (xc * xc)) / total
    cyy = float(wy @ (yc * yc)) / total
    cxy = float(xc @ w @ yc) / total
    half_tr = 0.5 * (cxx + cyy)
    disc = np.sqrt(max(0.25 * (cxx - cyy) ** 2 + cxy * cxy, 0.0))
    lmax = half_tr + disc
    lmin = max(half_tr - disc, 0.0)
    return 2.0 * float(np.sqrt(lmax)), 2.0 * float(np.sqrt(lmin))


@dataclass(frozen=True, eq=False)
class ContactState:
    """A BEM solution of (adhesive) normal contact on a grid.

    Parameters
    ----------
    grid : Grid
        The cell grid (full grid, even when the solver worked on a quadrant).
    pressure : ndarray, shape (nx, ny)
        Total normal pressure per cell, positive in compression; the adhesive
        traction enters as negative pressure [stress].
    gap : ndarray, shape (nx, ny)
        Gap ``h = z - delta + omega >= 0`` at the cell centres [length].
    approach : float
        Approach of distant points delta (displacement control) [length].
    load : float
        Total normal load, sum of pressure x cell area, positive compressive
        [force].
    contact : ndarray of bool, shape (nx, ny)
        Cells in contact (carrying repulsive pressure).
    cohesive : ndarray of float, shape (nx, ny)
        Fraction of each cell in the cohesive zone outside the contact, in
        [0, 1] (zero on contact cells).  For the Dugdale law this is the
        sub-cell fraction with ``0 < h < h0``; for a smooth law, the cells
        with ``h < law.zone_gap``.
    law : DugdaleLaw, ExponentialLaw or None
        The traction law (None: no adhesion).
    converged : bool
        True when both solver tolerances were met.
    iterations : int
        Total inner (conjugate-gradient) iterations spent on this state.
    residual : float
        Final residual, the larger of the complementarity error of the contact
        problem (relative to the law's range, or to |delta| without adhesion)
        and the largest change of the cohesive fraction in the last outer
        iteration [-].
    outer_iterations : int
        Outer (cohesive-zone) iterations.
    repulsive_pressure : ndarray, optional
        The repulsive (contact) part of the pressure, >= 0 [stress].
    resolved : bool
        False when the grid is too coarse for the traction law (the Dugdale
        edge, or the steepest slope of a smooth law; see
        ``dhfield.bem.solver.EDGE_WIDTH_FACTOR``): no discrete state is then
        stable, and a converged one is not the continuum's.
    """

    grid: Grid
    pressure: np.ndarray
    gap: np.ndarray
    approach: float
    load: float
    contact: np.ndarray
    cohesive: np.ndarray
    law: DugdaleLaw | ExponentialLaw | None
    converged: bool
    iterations: int
    residual: float
    outer_iterations: int = 0
    repulsive_pressure: np.ndarray | None = field(default=None, repr=False)
    resolved: bool = True

    def __post_init__(self):
        shape = self.grid.shape
        for name in ("pressure", "gap", "contact", "cohesive"):
            arr = getattr(self, name)
            if np.shape(arr) != shape:
                raise ValueError(f"{name} must have the grid shape {shape}; got {np.shape(arr)}")

    # -- masks and areas -------------------------------------------------------
    @property
    def cell_area(self) -> float:
        """Area of one cell, dx dy [length^2]."""
        return self.grid.dx * self.grid.dy

    @property
    def adhesive_zone(self) -> np.ndarray:
        """Weights of contact U cohesive zone per cell, in [0, 1]."""
        return np.clip(self.contact.astype(float) + self.cohesive, 0.0, 1.0)

    @property
    def contact_area(self) -> float:
        """Area of the contact [length^2]."""
        return float(np.count_nonzero(self.contact)) * self.cell_area

    @property
    def adhesive_area(self) -> float:
        """Area of contact U cohesive zone [length^2]."""
        return float(self.adhesive_zone.sum()) * self.cell_area

    @property
    def in_contact(self) -> bool:
        """True when at least one cell is in contact."""
        return bool(np.any(self.contact))

    # -- semi-axes -------------------------------------------------------------
    def contact_semi_axes(self) -> tuple[float, float]:
        """Return the semi-axes of the contact from its second moments.

        Returns
        -------
        (float, float)
            (a, b), major and minor semi-axes of the contact [length]; (0, 0)
            without contact.
        """
        return mask_semi_axes(self.contact, self.grid)

    def cohesive_semi_axes(self) -> tuple[float, float]:
        """Return the semi-axes of contact U cohesive zone from its second moments.

        Returns
        -------
        (float, float)
            (c, d), major and minor semi-axes of contact U cohesive zone
            [length]; (0, 0) without a zone.
        """
        return mask_semi_axes(self.adhesive_zone, self.grid)

    @property
    def beta_ab(self) -> float:
        """Contact ellipticity b/a (NaN without contact) [-]."""
        a, b = self.contact_semi_axes()
        return b / a if a > 0 else float("nan")

    @property
    def beta_cd(self) -> float:
        """Adhesive-zone ellipticity d/c (NaN without a zone) [-]."""
        c, d = self.cohesive_semi_axes()
        return d / c if c > 0 else float("nan")

    @property
    def peak_pressure(self) -> float:
        """Largest compressive pressure [stress]."""
        return float(np.max(self.pressure))

    def summary(self) -> dict:
        """Return the scalars of the state as a plain dict (no fields).

        Returns
        -------
        dict
            ``approach``, ``load``, the semi-axes ``a, b, c, d``, ``beta_ab``,
            ``beta_cd``, ``contact_area``, ``adhesive_area`` and the solver
            record (``converged``, ``iterations``, ``outer_iterations``,
            ``residual``), as Python scalars in the state's units.
        """
        a, b = self.contact_semi_axes()
        c, d = self.cohesive_semi_axes()
        return {"approach": float(self.approach), "load": float(self.load), "a": a, "b": b, "c": c,
                "d": d, "beta_ab": b / a if a > 0 else float("nan"),
                "beta_cd": d / c if c > 0 else float("nan"), "contact_area": self.contact_area,
                "adhesive_area": self.adhesive_area, "converged": bool(self.converged),
                "iterations": int(self.iterations), "outer_iterations": int(self.outer_iterations),
                "residual": float(self.residual)}
