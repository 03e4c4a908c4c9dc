"""Hertz and double-Hertz pressures sampled on a BEM grid, and the displacement the BEM gives for them.

The analytic model gives the pressure (Eqs. 7, 16, 22) at any point; this module puts
it on a :class:`dhfield.bem.Grid` (cell means or centre values) and computes its
surface displacement with the DC-FFT operator of :mod:`dhfield.bem`.  The cases of
:mod:`dhfield.analysis.fields` are built on it.

Pressure sampling
-----------------
``sampling="average"`` (the default) assigns each cell the exact mean of the
semi-ellipsoidal pressure over the cell, from the closed-form volume under the
unit hemisphere (see :func:`hemisphere_volume`); ``sampling="centre"`` takes the
value at the cell centre.  The RMS errors of the displacement of the two
samplings are alike (second order, set by the smooth interior), but the
maximum error, which sits in the cells cut by the contact edge, is 1.5-4 times
smaller with cell averages and converges regularly, while centre samples
mis-state the load of the edge cells by O(h^1.5) at a position-dependent rate
and converge erratically.  Hence the default ``"average"``: on a Hertz ellipse
(beta = 0.7) its maximum error relative to max |omega| is 2.8e-4 at N = 256 and
1.4e-5 at N = 2048 (``verification/convergence_bem.py``; the table is in
docs/theory/bem.rst, 'Measurements behind the solver's constants').

Neither sampling reaches order 2 in L-infinity: a piecewise-constant pressure
differs from the square-root edge of Eq. (7) by O(h^1/2) in the edge cells,
which changes the displacement at nearby cell centres by O(h^3/2).  The
whole-grid L-infinity order therefore approaches 1.5 from below (1.47 between
N = 2048 and 4096, ``convergence_bem.py --nmax 4096``).  Away from the edges
(cells more than 0.1 a from them) the order is 2.0.
"""
from __future__ import annotations

import numpy as np

from .. import bem
from ..models import dh_elliptic_fields, hertz
from ..core.validation import check_ellipticity, check_positive

__all__ = ["SAMPLINGS", "hemisphere_volume", "ellipsoid_cell_average", "ellipsoid_pressure", "hertz_pressure",
           "dh_pressure", "numerical_displacement"]

#: The two ways of putting a pressure on the grid: cell means (default) and centre values.
SAMPLINGS = ("average", "centre")


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
    dhfield.models.dh_elliptic_fields.pressure : The same field at arbitrary points.
    """
    a, c, beta, v, r, e = dh_elliptic_fields.check_parameters(semi_major, adhesive_semi_major, beta, scaling,
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
