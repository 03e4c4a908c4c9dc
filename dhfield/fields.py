"""Hertz and double-Hertz fields on a Cartesian grid, and their BEM cross-check.

The analytic model gives the pressure (Eqs. 7, 16, 22), the surface displacement
(Eqs. 13-15, 21, 26) and the gap (Eq. 27) at any point.  This module samples the
pressure on a :class:`dhfield.bem.Grid`, computes the displacement numerically
with the DC-FFT operator of :mod:`dhfield.bem`, and compares numerical and
analytic displacement and gap over the whole field: in the contact ellipse, in
the adhesive annulus and outside, on the Cartesian grid and, by interpolation,
on a polar (r, theta_p) grid.

Conventions are those of :mod:`dhfield.hertz` and :mod:`dhfield.bem`: arrays
``[i, j]`` with axis 0 along x (the major axis a), pressure positive in
compression, displacement positive into the bodies, ``h = z - delta + omega``.

Pressure sampling
-----------------
``sampling="average"`` (the default) assigns each cell the exact mean of the
semi-ellipsoidal pressure over the cell, from the closed-form volume under the
unit hemisphere (see :func:`hemisphere_volume`); ``sampling="centre"`` takes the
value at the cell centre.  Measured with ``verification/convergence_bem.py``
(Hertz ellipse a = 1, beta = 0.7, R = E* = 1, domain [-2a, 2a]^2 of N x N cells,
errors of the BEM displacement at the cell centres relative to max |omega|):

=====  ================  ================  ================  ================
N      L-inf, average    L-inf, centre     RMS, average      RMS, centre
=====  ================  ================  ================  ================
128    7.33e-04          1.53e-03          1.09e-04          9.96e-05
256    2.81e-04 (1.38)   4.78e-04 (1.68)   2.99e-05 (1.87)   2.36e-05 (2.08)
512    1.05e-04 (1.42)   2.57e-04 (0.89)   8.04e-06 (1.90)   7.27e-06 (1.70)
1024   3.86e-05 (1.45)   6.18e-05 (2.06)   2.13e-06 (1.92)   1.87e-06 (1.96)
2048   1.41e-05 (1.46)   3.78e-05 (0.71)   5.65e-07 (1.92)   6.72e-07 (1.48)
=====  ================  ================  ================  ================

(observed orders between successive grids in brackets).  The RMS errors of the
two samplings are alike (second order, set by the smooth interior), but the
maximum error, which sits in the cells cut by the contact edge, is 1.5-4 times
smaller with cell averages and converges regularly, while centre samples
mis-state the load of the edge cells by O(h^1.5) at a position-dependent rate
and converge erratically.  Hence the default ``"average"``.

Neither sampling reaches order 2 in L-infinity: a piecewise-constant pressure
differs from the square-root edge of Eq. (7) by O(h^1/2) in the edge cells,
which changes the displacement at nearby cell centres by O(h^3/2).  The
whole-grid L-infinity order therefore approaches 1.5 from below (1.47 between
N = 2048 and 4096, ``convergence_bem.py --nmax 4096``).  Away from the edges
(cells more than 0.1 a from them) the order is 2.0.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy import ndimage

from . import bem, double_hertz, hertz, model
from ._memory import check_memory
from ._validation import check_ellipticity, check_positive

__all__ = [
    "SAMPLINGS",
    "hemisphere_volume",
    "ellipsoid_cell_average",
    "ellipsoid_pressure",
    "hertz_pressure",
    "dh_pressure",
    "numerical_displacement",
    "region_masks",
    "compare",
    "polar_grid",
    "to_polar",
    "observed_orders",
    "refinement_study",
    "FieldCase",
    "hertz_case",
    "dh_case",
    "annulus_identity",
    "adhesive_state",
    "model_case",
    "analytic_fields",
    "CASE_BYTES_PER_CELL",
    "check_case_memory",
]

SAMPLINGS = ("average", "centre")


# --------------------------------------------------------------------------- sampling
def _hemisphere_volume_quadrant(x, y):
    """V(X, Y) for 0 <= X, Y (clamped to the unit disk internally)."""
    x = np.minimum(x, 1.0)
    y = np.minimum(y, 1.0)
    outside = x * x + y * y > 1.0
    # beyond the circle the inner integral saturates at (pi/4)(1 - x^2): split at x0 = sqrt(1 - Y^2)
    x0 = np.sqrt(np.maximum(1.0 - y * y, 0.0))
    xi = np.where(outside, x0, x)
    s = np.sqrt(np.maximum(1.0 - xi * xi - y * y, 0.0))
    # arcsin(x/sqrt(1-y^2)) = atan2(x, S) etc.: written with the one shared S, the three angle
    # terms' sensitivities to S cancel at the circle (dF/dS = O(S^2)), so rounding of S near the
    # edge does not reach V (the arcsin form loses ~sqrt(eps) there).
    ax = np.arctan2(xi, s)
    ay = np.arctan2(y, s)
    at = np.arctan2(xi * y, s)
    v = (2.0 * xi * y * s + y * (3.0 - y * y) * ax + xi * (3.0 - xi * xi) * ay - 2.0 * at) / 6.0
    g = lambda t: t - t**3 / 3.0  # noqa: E731 - integral of (1 - t^2)
    return v + np.where(outside, 0.25 * np.pi * (g(x) - g(x0)), 0.0)


def hemisphere_volume(x, y):
    """Compute the volume under the unit hemisphere over ``[0, x] x [0, y]`` (signed) [-].

    ``V(x, y) = int_0^x int_0^y sqrt(max(1 - s^2 - t^2, 0)) dt ds``, odd in x and y.

    Parameters
    ----------
    x, y : array_like
        Upper limits of the integral, in units of the hemisphere's radius [-].

    Returns
    -------
    ndarray
        The signed volume ``V(x, y)`` [-], broadcast over ``x`` and ``y``.

    Notes
    -----
    Inside the unit disk (``S = sqrt(1 - x^2 - y^2)``)

    .. math::

        6V = 2xyS + y(3 - y^2)\\arcsin\\frac{x}{\\sqrt{1-y^2}}
             + x(3 - x^2)\\arcsin\\frac{y}{\\sqrt{1-x^2}} - 2\\arctan\\frac{xy}{S},

    derived by integrating ``sqrt(1 - x^2 - y^2)`` in y, then in x by parts
    (``d/dx atan(xy/S) = y/((1 - x^2) S)``).  Beyond the circle the integral over y
    saturates at ``(pi/4)(1 - x^2)``, which is added from ``x0 = sqrt(1 - y^2)`` on.
    ``V(1, 1) = pi/6``.  The three angles are evaluated as ``atan2(x, S)``,
    ``atan2(y, S)`` and ``atan2(xy, S)`` with one shared S: their sensitivities to
    S then cancel at the circle, whereas the arcsin form loses about sqrt(eps)
    there (visible as 1e-7 errors in cell averages).  The tests check V against adaptive quadrature.
    """
    x = np.asarray(x, dtype=float)
    y = np.asarray(y, dtype=float)
    return np.sign(x) * np.sign(y) * _hemisphere_volume_quadrant(np.abs(x), np.abs(y))


def ellipsoid_cell_average(grid: bem.Grid, semi_major, semi_minor, peak_pressure):
    """Compute the cell averages of the semi-ellipsoidal pressure of Eq. (7) [Pa].

    The mean of ``Po sqrt(1 - (x/a)^2 - (y/b)^2)`` over each cell, exactly (up to
    rounding), from :func:`hemisphere_volume` at the scaled cell corners.

    Parameters
    ----------
    grid : dhfield.bem.Grid
        The cell grid [m].
    semi_major, semi_minor : float
        Semi-axes a and b of the pressure ellipse [m].
    peak_pressure : float
        Peak pressure Po [Pa].

    Returns
    -------
    ndarray
        The cell means [Pa], shape ``(nx, ny)``.
    """
    a = float(check_positive("semi_major", semi_major, "m"))
    b = float(check_positive("semi_minor", semi_minor, "m"))
    # only the positive quadrant is computed; the field is even in x and y
    xe = grid.x_edges / a
    ye = grid.y_edges / b
    v = hemisphere_volume(xe[:, None], ye[None, :])
    cell = v[1:, 1:] - v[:-1, 1:] - v[1:, :-1] + v[:-1, :-1]
    return peak_pressure * a * b / (grid.dx * grid.dy) * cell  # Eq. (7), cell means


def ellipsoid_pressure(grid: bem.Grid, semi_major, semi_minor, peak_pressure, sampling="average"):
    """Sample the semi-ellipsoidal pressure of Eq. (7) on the grid [Pa].

    Parameters
    ----------
    grid : dhfield.bem.Grid
        The cell grid [m].
    semi_major, semi_minor : float
        Semi-axes a and b of the pressure ellipse [m].
    peak_pressure : float
        Peak pressure Po [Pa].
    sampling : {"average", "centre"}
        Cell means (default) or centre values.

    Returns
    -------
    ndarray
        The pressure [Pa], shape ``grid.shape``.
    """
    if sampling not in SAMPLINGS:
        raise ValueError(f"sampling must be one of {SAMPLINGS}; got {sampling!r}")
    if sampling == "average":
        return ellipsoid_cell_average(grid, semi_major, semi_minor, peak_pressure)
    x, y = grid.mesh()
    return hertz.pressure(x, y, semi_major, semi_minor, peak_pressure)  # Eq. (7)


def hertz_pressure(grid: bem.Grid, semi_major, beta, effective_radius=1.0, reduced_modulus=1.0,
                   sampling="average"):
    """Sample the Hertz pressure of the contact ellipse (Eqs. 7, 8) on the grid [Pa].

    Parameters
    ----------
    grid : dhfield.bem.Grid
        The cell grid [m].
    semi_major : float
        Contact semi-major axis a [m].
    beta : float
        Ellipticity b/a [-].
    effective_radius, reduced_modulus : float
        R [m] and E* [Pa].
    sampling : {"average", "centre"}
        Cell means (default) or centre values.

    Returns
    -------
    ndarray
        The pressure [Pa], shape ``grid.shape``.
    """
    a = check_positive("semi_major", semi_major, "m")
    beta = check_ellipticity("beta", beta)
    po = hertz.max_pressure(a, beta, effective_radius, reduced_modulus)  # Eq. (8)
    return ellipsoid_pressure(grid, a, beta * a, po, sampling)  # Eq. (7)


def dh_pressure(grid: bem.Grid, semi_major, adhesive_semi_major, beta, scaling, effective_radius=1.0,
                reduced_modulus=1.0, sampling="average"):
    """Sample the total DH pressure ``(1 + v) H_ab - v H_cd`` (Eqs. 16, 20, 22) on the grid [Pa].

    Cell averages are exact because the field is linear in the two Hertz pressures.

    Parameters
    ----------
    grid : dhfield.bem.Grid
        The cell grid [m].
    semi_major : float
        Contact semi-major axis a [m].
    adhesive_semi_major : float
        Adhesive semi-major axis c [m].
    beta : float
        Common ellipticity b/a = d/c [-].
    scaling : float
        Scaling factor v of the DH pressure [-].
    effective_radius : float, default 1.0
        R [m].
    reduced_modulus : float, default 1.0
        E* [Pa].
    sampling : {"average", "centre"}
        Cell means (default) or centre values.

    Returns
    -------
    ndarray
        The pressure [Pa], shape ``grid.shape``.

    See Also
    --------
    dhfield.double_hertz.pressure : The same field at arbitrary points.
    """
    a, c, beta, v, r, e = double_hertz.check_parameters(semi_major, adhesive_semi_major, beta, scaling,
                                                        effective_radius, reduced_modulus)
    po_ab = hertz.max_pressure(a, beta, r, e)  # Eq. (8)
    po_cd = hertz.max_pressure(c, beta, r, e)  # Eq. (20)
    h_ab = ellipsoid_pressure(grid, a, beta * a, po_ab, sampling)  # Eq. (7)
    h_cd = ellipsoid_pressure(grid, c, beta * c, po_cd, sampling)  # Eq. (16)
    return (1.0 + v) * h_ab - v * h_cd  # Eq. (22)


def numerical_displacement(pressure, grid: bem.Grid, reduced_modulus=1.0, *, symmetric=True,
                           threads=None):
    """Compute the BEM surface displacement of a gridded pressure at the cell centres [m].

    Parameters
    ----------
    pressure : array_like
        Gridded pressure [Pa], shape ``grid.shape``.
    grid : dhfield.bem.Grid
        The cell grid [m].
    reduced_modulus : float, default 1.0
        E* [Pa].
    symmetric : bool, default True
        Transform only the quadrant (every field of this module is even in x and
        y; used when the grid has even nx, ny).
    threads : int, optional
        FFT worker threads.

    Returns
    -------
    ndarray
        The displacement [m], shape ``grid.shape``.
    """
    p = np.asarray(pressure, dtype=float)
    if p.shape != grid.shape:
        raise ValueError(f"pressure must have the grid shape {grid.shape}; got {p.shape}")
    if symmetric and grid.is_even:
        op = bem.get_operator(grid, reduced_modulus, symmetric=True, threads=threads)
        return bem.unfold_quadrant(op(bem.quadrant(p)))
    return bem.get_operator(grid, reduced_modulus, threads=threads)(p)


# --------------------------------------------------------------------------- comparison
def region_masks(x, y, semi_major, beta, adhesive_semi_major=None):
    """Compute boolean masks of the contact ellipse, the adhesive annulus and the outside.

    Parameters
    ----------
    x, y : array_like
        Points [m] (e.g. ``grid.mesh()``).
    semi_major : float
        Contact semi-major axis a [m].
    beta : float
        Common ellipticity [-].
    adhesive_semi_major : float, optional
        Adhesive semi-major axis c [m]; without it the annulus is empty.

    Returns
    -------
    dict
        ``{"contact": ..., "annulus": ..., "outside": ...}``; points on an ellipse
        belong to the inner region.
    """
    x = np.asarray(x, dtype=float)
    y = np.asarray(y, dtype=float)
    rho_ab = (x / semi_major) ** 2 + (y / (beta * semi_major)) ** 2
    contact = rho_ab <= 1.0
    if adhesive_semi_major is None:
        return {"contact": contact, "annulus": np.zeros_like(contact), "outside": ~contact}
    c = adhesive_semi_major
    inside_cd = (x / c) ** 2 + (y / (beta * c)) ** 2 <= 1.0
    return {"contact": contact, "annulus": inside_cd & ~contact, "outside": ~inside_cd}


def compare(numerical, analytic, masks=None, scale=None) -> dict:
    """Compute error statistics of ``numerical - analytic``, overall and per region.

    Parameters
    ----------
    numerical, analytic : array_like
        Same shape.
    masks : dict of str -> bool array, optional
        Regions (e.g. from :func:`region_masks`); "all" is always added.
    scale : float, optional
        Normalisation of the relative errors; default ``max|analytic|``.

    Returns
    -------
    dict
        ``{region: {"max": max|e|, "rms": sqrt(mean e^2), "rel_max": max|e|/scale,
        "rel_rms": rms/scale, "count": n}}``; NaN entries for empty regions.
    """
    num = np.asarray(numerical, dtype=float)
    ana = np.asarray(analytic, dtype=float)
    if num.shape != ana.shape:
        raise ValueError(f"numerical and analytic must have the same shape; got {num.shape} and {ana.shape}")
    err = num - ana
    if scale is None:
        scale = float(np.max(np.abs(ana)))
    regions = {"all": np.ones(err.shape, dtype=bool)}
    regions.update(masks or {})
    out = {}
    for name, m in regions.items():
        m = np.asarray(m, dtype=bool)
        if m.shape != err.shape:
            raise ValueError(f"mask {name!r} must have shape {err.shape}; got {m.shape}")
        e = err[m]
        if e.size == 0:
            mx = rms = float("nan")
        else:
            mx = float(np.max(np.abs(e)))
            rms = float(np.sqrt(np.mean(e * e)))
        out[name] = {"max": mx, "rms": rms, "rel_max": mx / scale, "rel_rms": rms / scale,
                     "count": int(e.size)}
    return out


# --------------------------------------------------------------------------- polar
def polar_grid(r_max, n_r=200, n_theta=91, theta_max=0.5 * np.pi):
    """Return radii ``[0, r_max]`` [m] and angles ``theta_p in [0, theta_max]`` [rad].

    Parameters
    ----------
    r_max : float
        Largest radius [m].
    n_r : int, default 200
        Number of radii.
    n_theta : int, default 91
        Number of angles.
    theta_max : float, default pi/2
        Largest angle [rad].

    Returns
    -------
    r : ndarray
        1-D radii [m].
    theta_p : ndarray
        1-D angles [rad].
    """
    r_max = float(check_positive("r_max", r_max, "m"))
    return np.linspace(0.0, r_max, int(n_r)), np.linspace(0.0, float(theta_max), int(n_theta))


def to_polar(field, grid: bem.Grid, r, theta_p, order=3):
    """Interpolate a cell-centred Cartesian field onto polar points ``(r, theta_p)``.

    Parameters
    ----------
    field : array_like
        Shape ``grid.shape``.
    grid : dhfield.bem.Grid
        The grid the field lives on.
    r, theta_p : array_like
        1-D radii [m] and polar angles from the x axis [rad]; the result has
        shape ``(len(r), len(theta_p))``.
    order : int, default 3
        Spline order of :func:`scipy.ndimage.map_coordinates`.

    Returns
    -------
    ndarray
        The field at ``x = r cos theta_p, y = r sin theta_p``; NaN outside the
        hull of the cell centres.

    Notes
    -----
    The spline's boundary condition (``mode="reflect"``) perturbs it near the
    domain edge by an amount that decays like 0.27^k at k cells from the edge.
    """
    f = np.asarray(field, dtype=float)
    if f.shape != grid.shape:
        raise ValueError(f"field must have the grid shape {grid.shape}; got {f.shape}")
    r = np.asarray(r, dtype=float)
    t = np.asarray(theta_p, dtype=float)
    x = r[:, None] * np.cos(t)[None, :]
    y = r[:, None] * np.sin(t)[None, :]
    fi = (x - grid.x[0]) / grid.dx
    fj = (y - grid.y[0]) / grid.dy
    out = ndimage.map_coordinates(f, [fi, fj], order=order, mode="reflect")
    inside = (fi >= 0) & (fi <= grid.nx - 1) & (fj >= 0) & (fj <= grid.ny - 1)
    return np.where(inside, out, np.nan)


# --------------------------------------------------------------------------- refinement
def observed_orders(h, err):
    """Compute the observed orders ``log(e_i/e_{i+1})/log(h_i/h_{i+1})`` between successive grids.

    Parameters
    ----------
    h : array_like
        Cell sizes of the grids [m].
    err : array_like
        Errors on those grids (any consistent unit).

    Returns
    -------
    ndarray
        The ``len(h) - 1`` observed orders [-].
    """
    h = np.asarray(h, dtype=float)
    e = np.asarray(err, dtype=float)
    return np.log(e[:-1] / e[1:]) / np.log(h[:-1] / h[1:])


def refinement_study(error_of_n, ns):
    """Run a grid-refinement study.

    Parameters
    ----------
    error_of_n : callable
        ``error_of_n(n) -> (h, error)`` for ``n`` cells per axis.
    ns : sequence of int
        Increasing resolutions.

    Returns
    -------
    dict
        ``n``, ``h``, ``error`` (arrays), ``order`` (between successive grids,
        NaN-padded in front) and ``fitted_order`` (least-squares slope of
        log error against log h).
    """
    ns = [int(n) for n in ns]
    hs, errs = zip(*(error_of_n(n) for n in ns))
    hs = np.asarray(hs, dtype=float)
    errs = np.asarray(errs, dtype=float)
    orders = np.concatenate([[np.nan], observed_orders(hs, errs)])
    fitted = float(np.polyfit(np.log(hs), np.log(errs), 1)[0]) if len(ns) > 1 else float("nan")
    return {"n": np.asarray(ns), "h": hs, "error": errs, "order": orders, "fitted_order": fitted}


# --------------------------------------------------------------------------- cases
@dataclass
class FieldCase:
    """All fields of one case on one grid (arrays of shape ``grid.shape``).

    Parameters
    ----------
    grid : dhfield.bem.Grid
        The cell grid [m].
    parameters : dict
        Every input parameter (for provenance).
    pressure : ndarray
        Gridded pressure fed to the BEM [Pa].
    pressure_exact : ndarray
        The analytic pressure at the cell centres [Pa].
    displacement_analytic, displacement_numerical : ndarray
        Surface displacements [m].
    gap_analytic, gap_numerical : ndarray
        Gaps [m]; the numerical gap uses the analytic approach.
    masks : dict
        Region masks (:func:`region_masks`).
    approach : float
        The approach delta [m].
    """

    grid: bem.Grid
    parameters: dict
    pressure: np.ndarray
    pressure_exact: np.ndarray
    displacement_analytic: np.ndarray
    displacement_numerical: np.ndarray
    gap_analytic: np.ndarray
    gap_numerical: np.ndarray
    masks: dict
    approach: float

    def displacement_errors(self) -> dict:
        """Compare the displacements, relative to max |analytic displacement|.

        Returns
        -------
        dict
            :func:`compare`'s statistics per region.
        """
        return compare(self.displacement_numerical, self.displacement_analytic, self.masks)

    def gap_errors(self) -> dict:
        """Compare the gaps, relative to max |analytic displacement|.

        Returns
        -------
        dict
            :func:`compare`'s statistics per region.
        """
        scale = float(np.max(np.abs(self.displacement_analytic)))
        return compare(self.gap_numerical, self.gap_analytic, self.masks, scale=scale)


def _shape_z(x, y, beta, effective_radius):
    r1, r2 = hertz.principal_radii_from_ellipticity(beta, effective_radius)
    return x**2 / (2.0 * r1) + y**2 / (2.0 * r2)  # Eq. (2)


#: Peak memory of one field case per grid cell, from its computation to its netCDF file [bytes].
#: Measured peak RSS above the imports: 139 B/cell at n = 1024 and 130 B/cell at n = 2048
#: (``dhfield field``, ru_maxrss); 160 leaves a 20 % margin.
CASE_BYTES_PER_CELL = 160


def check_case_memory(n, ny=None) -> None:
    """Refuse an ``n`` x ``ny`` field case that would not fit in memory, before allocating it.

    The estimate is ``CASE_BYTES_PER_CELL * n * ny``; the limit is 80 % of the
    memory available now (:func:`dhfield._memory.memory_limit`).

    Parameters
    ----------
    n : int
        Cells along x (and along y unless ``ny`` is given) [-].
    ny : int, optional
        Cells along y [-].

    Raises
    ------
    ValueError
        Naming ``n`` (and ``ny``), the estimate and the limit.
    """
    from .bem.operator import MIN_CELLS

    for name, value in (("n", n), ("ny", ny)):  # name the input the user gave (Grid says nx)
        try:
            ok = value is None or (not isinstance(value, bool) and int(value) == value and value >= MIN_CELLS)
        except (TypeError, ValueError, OverflowError):
            ok = False
        if not ok:
            raise ValueError(f"{name} must be an integer >= {MIN_CELLS} (cells per axis); got {value!r}")
    grid = bem.Grid(n, n if ny is None else ny, 1.0, 1.0)  # validates the cell counts; allocates nothing
    what = f"n={grid.nx}" + (f", ny={grid.ny}" if grid.ny != grid.nx else "") + \
        f" (a {grid.nx} x {grid.ny} grid, about {CASE_BYTES_PER_CELL} bytes per cell)"
    check_memory(CASE_BYTES_PER_CELL * float(grid.nx) * float(grid.ny), what)


def hertz_case(n, semi_major=1.0, beta=1.0, *, half_width=None, effective_radius=1.0,
               reduced_modulus=1.0, sampling="average", symmetric=True, threads=None, ny=None) -> FieldCase:
    """Compute the Hertz contact ellipse's fields on an ``n`` x ``ny`` grid over ``[-L, L]^2``.

    Parameters
    ----------
    n : int
        Cells along x (and y unless ``ny`` is given) [-].
    semi_major : float, default 1.0
        Contact semi-major axis a [m].
    beta : float, default 1.0
        Ellipticity b/a [-].
    half_width : float, optional
        Half-width L of the domain [m]; default ``2 a``.
    effective_radius : float, default 1.0
        R [m].
    reduced_modulus : float, default 1.0
        E* [Pa].
    sampling : {"average", "centre"}
        Cell means (default) or centre values of the pressure.
    symmetric : bool, default True
        Transform only the quadrant.
    threads : int, optional
        FFT worker threads.
    ny : int, optional
        Cells along y [-].

    Returns
    -------
    FieldCase
        All fields of the case.
    """
    a = float(check_positive("semi_major", semi_major, "m"))
    beta = float(check_ellipticity("beta", beta))
    L = 2.0 * a if half_width is None else half_width
    grid = bem.Grid.centered(n, L, ny=ny)
    check_case_memory(grid.nx, grid.ny)
    x, y = grid.mesh()
    po = hertz.max_pressure(a, beta, effective_radius, reduced_modulus)  # Eq. (8)
    p = ellipsoid_pressure(grid, a, beta * a, po, sampling)
    w_num = numerical_displacement(p, grid, reduced_modulus, symmetric=symmetric, threads=threads)
    w_ana = hertz.surface_displacement(x, y, a, beta * a, po, reduced_modulus)  # Eq. (13)
    delta = float(hertz.approach(a, beta, effective_radius, reduced_modulus))  # Eq. (14a)
    z = _shape_z(x, y, beta, effective_radius)
    params = dict(model="hertz", n=grid.nx, ny=grid.ny, semi_major=a, beta=beta, half_width=float(L),
                  effective_radius=float(effective_radius), reduced_modulus=float(reduced_modulus),
                  sampling=sampling, symmetric=bool(symmetric))
    return FieldCase(grid, params, p, hertz.pressure(x, y, a, beta * a, po), w_ana, w_num,
                     z - delta + w_ana, z - delta + w_num, region_masks(x, y, a, beta), delta)


def dh_case(n, semi_major, adhesive_semi_major, beta, scaling, *, half_width=None, effective_radius=1.0,
            reduced_modulus=1.0, sampling="average", symmetric=True, threads=None, ny=None,
            extra_parameters=None) -> FieldCase:
    """Compute the extended DH contact's fields on an ``n`` x ``ny`` grid over ``[-L, L]^2``.

    The numerical gap is ``z - delta + omega_BEM`` with the analytic approach
    ``delta = (1 + v) delta_ab - v delta_cd``.

    Parameters
    ----------
    n : int
        Cells along x (and y unless ``ny`` is given) [-].
    semi_major : float
        Contact semi-major axis a [m].
    adhesive_semi_major : float
        Adhesive semi-major axis c [m].
    beta : float
        Common ellipticity [-].
    scaling : float
        Scaling factor v [-].
    half_width : float, optional
        Half-width L of the domain [m]; default ``1.5 c``.
    effective_radius : float, default 1.0
        R [m].
    reduced_modulus : float, default 1.0
        E* [Pa].
    sampling : {"average", "centre"}
        Cell means (default) or centre values of the pressure.
    symmetric : bool, default True
        Transform only the quadrant.
    threads : int, optional
        FFT worker threads.
    ny : int, optional
        Cells along y [-].
    extra_parameters : dict, optional
        Recorded in :attr:`FieldCase.parameters` as well.

    Returns
    -------
    FieldCase
        All fields of the case.
    """
    a, c, beta, v, r, e = double_hertz.check_parameters(semi_major, adhesive_semi_major, beta, scaling,
                                                        effective_radius, reduced_modulus)
    a, c, beta, v, r, e = (float(t) for t in (a, c, beta, v, r, e))
    L = 1.5 * c if half_width is None else half_width
    grid = bem.Grid.centered(n, L, ny=ny)
    check_case_memory(grid.nx, grid.ny)
    x, y = grid.mesh()
    p = dh_pressure(grid, a, c, beta, v, r, e, sampling)  # Eq. (22)
    w_num = numerical_displacement(p, grid, e, symmetric=symmetric, threads=threads)
    w_ana = double_hertz.surface_displacement(x, y, a, c, beta, v, r, e)  # Eq. (26)
    delta = float(double_hertz.approach(a, c, beta, v, r, e))
    z = _shape_z(x, y, beta, r)
    params = dict(model="double_hertz", n=grid.nx, ny=grid.ny, semi_major=a, adhesive_semi_major=c,
                  beta=beta, scaling=v, half_width=float(L), effective_radius=r, reduced_modulus=e,
                  sampling=sampling, symmetric=bool(symmetric))
    params.update(extra_parameters or {})
    return FieldCase(grid, params, p, double_hertz.pressure(x, y, a, c, beta, v, r, e), w_ana, w_num,
                     z - delta + w_ana, z - delta + w_num,  # Eq. (27)
                     region_masks(x, y, a, beta, c), delta)


def annulus_identity(case: FieldCase, n_theta=91, n_r=64):
    """Check h_BEM = (1 + v) h_Hertz in the adhesive annulus along every theta_p.

    The numerical gap is interpolated (cubic splines) onto rays
    ``theta_p in [0, pi/2]`` at ``n_r`` radii strictly between ``r_ab(theta_p)``
    and ``r_cd(theta_p)`` (Eqs. A1, A2), and compared with ``(1 + v)`` times the
    analytic Hertz gap of the contact ellipse (:func:`dhfield.hertz.gap`).

    Parameters
    ----------
    case : FieldCase
        A DH case (:func:`dh_case` or :func:`model_case`).
    n_theta : int, default 91
        Number of rays [-].
    n_r : int, default 64
        Radii per ray [-].

    Returns
    -------
    dict
        ``theta_p`` [rad]; ``max_error`` per ray [m]; ``rel_error`` per ray
        (divided by the largest ``(1 + v) h_H`` in the annulus); ``worst``.
    """
    prm = case.parameters
    a, c, beta, v = prm["semi_major"], prm["adhesive_semi_major"], prm["beta"], prm["scaling"]
    r_, e_ = prm["effective_radius"], prm["reduced_modulus"]
    theta = np.linspace(0.0, 0.5 * np.pi, int(n_theta))
    ct, st = np.cos(theta), np.sin(theta)
    b, d = beta * a, beta * c
    r_ab = a * b / np.sqrt((b * ct) ** 2 + (a * st) ** 2)  # Eq. (A1)
    r_cd = c * d / np.sqrt((d * ct) ** 2 + (c * st) ** 2)  # Eq. (A2)
    s = (np.arange(n_r) + 0.5) / n_r
    rr = r_ab[None, :] + s[:, None] * (r_cd - r_ab)[None, :]
    x, y = rr * ct[None, :], rr * st[None, :]
    g = case.grid
    fi = (x - g.x[0]) / g.dx
    fj = (y - g.y[0]) / g.dy
    h_num = ndimage.map_coordinates(case.gap_numerical, [fi, fj], order=3, mode="reflect")
    h_ref = (1.0 + v) * hertz.gap(x, y, a, beta, r_, e_)
    err = np.max(np.abs(h_num - h_ref), axis=0)
    scale = float(np.max(np.abs(h_ref)))
    return {"theta_p": theta, "max_error": err, "rel_error": err / scale, "worst": float(np.max(err / scale)),
            "scale": scale}


def adhesive_state(a_star, *, beta0, mu):
    """Solve for the nondimensional DH state ``(c*, v)`` at contact size ``a*`` (Eqs. 24, 31, 35).

    A scalar wrapper of :func:`dhfield.model.solve_adhesive_axis`.

    Parameters
    ----------
    a_star : float
        Contact semi-major axis a/c_r [-].
    beta0 : float
        Ellipticity of both ellipses (Eqs. 17-19) [-].
    mu : float
        Tabor parameter, Eq. (35) [-].

    Returns
    -------
    c_star : float
        Adhesive semi-major axis c/c_r [-].
    v : float
        Scaling factor [-].
    """
    c, v = model.solve_adhesive_axis(np.atleast_1d(np.asarray(a_star, dtype=float)), mu=mu, beta0=beta0)
    return float(np.ravel(c)[0]), float(np.ravel(v)[0])


def model_case(n, beta0, mu, a_star, *, half_width=None, sampling="average", symmetric=True,
               threads=None) -> FieldCase:
    """Compute the nondimensional DH case (R = E* = Delta gamma = 1) of :mod:`dhfield.model` on a grid.

    Solves for ``c*`` and ``v`` (:func:`adhesive_state`) and returns :func:`dh_case`
    with ``beta0``, ``mu``, ``a_star`` recorded in the parameters.

    Parameters
    ----------
    n : int
        Cells per axis [-].
    beta0 : float
        Ellipticity of both ellipses [-].
    mu : float
        Tabor parameter, Eq. (35) [-].
    a_star : float
        Contact semi-major axis a/c_r [-].
    half_width : float, optional
        Half-width of the domain [c_r]; default ``1.5 c*``.
    sampling : {"average", "centre"}
        Cell means (default) or centre values of the pressure.
    symmetric : bool, default True
        Transform only the quadrant.
    threads : int, optional
        FFT worker threads.

    Returns
    -------
    FieldCase
        All fields of the case, lengths in c_r and pressures in E* c_r/R.
    """
    c, v = adhesive_state(a_star, mu=mu, beta0=beta0)
    return dh_case(n, float(a_star), c, float(beta0), v, half_width=half_width, sampling=sampling,
                   symmetric=symmetric, threads=threads,
                   extra_parameters=dict(beta0=float(beta0), mu=float(mu), a_star=float(a_star),
                                         c_star=c, units="nondimensional: lengths in c_r = (R^2 dgamma/E*)^(1/3), "
                                               "pressures in E* c_r/R (Eqs. 32-35)"))


def analytic_fields(case: FieldCase, x, y) -> dict:
    """Evaluate the analytic pressure, displacement and gap of ``case`` at arbitrary points.

    Parameters
    ----------
    case : FieldCase
        A Hertz or DH case.
    x, y : array_like
        The points [m].

    Returns
    -------
    dict
        ``{"pressure": ..., "displacement": ..., "gap": ...}`` (Eqs. 7/22,
        13/26, 27) evaluated with the case's parameters [Pa], [m], [m].
    """
    prm = case.parameters
    a, beta = prm["semi_major"], prm["beta"]
    r, e = prm["effective_radius"], prm["reduced_modulus"]
    x = np.asarray(x, dtype=float)
    y = np.asarray(y, dtype=float)
    if prm["model"] == "hertz":
        po = hertz.max_pressure(a, beta, r, e)  # Eq. (8)
        return {"pressure": hertz.pressure(x, y, a, beta * a, po),  # Eq. (7)
                "displacement": hertz.surface_displacement(x, y, a, beta * a, po, e),  # Eq. (13)
                "gap": hertz.gap(x, y, a, beta, r, e)}
    c, v = prm["adhesive_semi_major"], prm["scaling"]
    return {"pressure": double_hertz.pressure(x, y, a, c, beta, v, r, e),  # Eq. (22)
            "displacement": double_hertz.surface_displacement(x, y, a, c, beta, v, r, e),  # Eq. (26)
            "gap": double_hertz.gap(x, y, a, c, beta, v, r, e)}  # Eq. (27)
