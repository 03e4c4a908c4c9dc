"""Hertz and double-Hertz fields on a Cartesian grid, and their BEM cross-check.

The analytic model gives the pressure (Eqs. 7, 16, 22), the surface displacement
(Eqs. 13-15, 21, 26) and the gap (Eq. 27) at any point.  This module samples the
pressure on a :class:`dhfield.bem.Grid`, computes the displacement numerically
with the DC-FFT operator of :mod:`dhfield.bem`, and compares numerical and
analytic displacement and gap over the whole field: in the contact ellipse, in
the adhesive annulus and outside, on the Cartesian grid and, by interpolation,
on a polar (r, theta_p) grid.

Conventions are those of :mod:`dhfield.models.hertz` and :mod:`dhfield.bem`: arrays
``[i, j]`` with axis 0 along x (the major axis a), pressure positive in
compression, displacement positive into the bodies, ``h = z - delta + omega``.

The pressure sampling is :mod:`dhfield.analysis.field_sampling`; the error metrics
:mod:`dhfield.analysis.field_metrics`; the polar resampling :mod:`dhfield.analysis.polar`.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .. import bem
from ..models import dh_elliptic_fields, hertz, dh_elliptic
from ..core.memory import check_memory
from ..core.validation import check_ellipticity, check_positive
from .field_metrics import compare, region_masks
from .field_sampling import dh_pressure, ellipsoid_pressure, numerical_displacement

__all__ = ["FieldCase", "hertz_case", "dh_case", "adhesive_state", "model_case", "analytic_fields",
           "CASE_BYTES_PER_CELL", "check_case_memory"]


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
#: The peak RSS above the imports is 139 B/cell at n = 1024 and 130 B/cell at n = 2048
#: (``dhfield field``, ru_maxrss); 160 leaves a 20 % margin.
CASE_BYTES_PER_CELL = 160


def check_case_memory(n, ny=None) -> None:
    """Refuse an ``n`` x ``ny`` field case that would not fit in memory, before allocating it.

    The estimate is ``CASE_BYTES_PER_CELL * n * ny``; the limit is 80 % of the
    memory available now (:func:`dhfield.core.memory.memory_limit`).

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
    from ..bem.operator import MIN_CELLS

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
            reduced_modulus=1.0, sampling="average", threads=None) -> FieldCase:
    """Compute the extended DH contact's fields on an ``n`` x ``n`` grid over ``[-L, L]^2``.

    The numerical gap is ``z - delta + omega_BEM`` with the analytic approach
    ``delta = (1 + v) delta_ab - v delta_cd``.  The pressure is symmetric in both
    axes: on an even grid only the quadrant is transformed (as ``symmetric=True``
    in :func:`hertz_case`, whose test compares it with the full transform).

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
    threads : int, optional
        FFT worker threads.

    Returns
    -------
    FieldCase
        All fields of the case.
    """
    a, c, beta, v, r, e = dh_elliptic_fields.check_parameters(semi_major, adhesive_semi_major, beta, scaling,
                                                        effective_radius, reduced_modulus)
    a, c, beta, v, r, e = (float(t) for t in (a, c, beta, v, r, e))
    L = 1.5 * c if half_width is None else half_width
    grid = bem.Grid.centered(n, L)
    check_case_memory(grid.nx, grid.ny)
    x, y = grid.mesh()
    p = dh_pressure(grid, a, c, beta, v, r, e, sampling)  # Eq. (22)
    w_num = numerical_displacement(p, grid, e, symmetric=True, threads=threads)
    w_ana = dh_elliptic_fields.surface_displacement(x, y, a, c, beta, v, r, e)  # Eq. (26)
    delta = float(dh_elliptic_fields.approach(a, c, beta, v, r, e))
    z = _shape_z(x, y, beta, r)
    params = dict(model="double_hertz", n=grid.nx, ny=grid.ny, semi_major=a, adhesive_semi_major=c,
                  beta=beta, scaling=v, half_width=float(L), effective_radius=r, reduced_modulus=e,
                  sampling=sampling, symmetric=True)
    return FieldCase(grid, params, p, dh_elliptic_fields.pressure(x, y, a, c, beta, v, r, e), w_ana, w_num,
                     z - delta + w_ana, z - delta + w_num,  # Eq. (27)
                     region_masks(x, y, a, beta, c), delta)


def adhesive_state(a_star, *, beta0, mu):
    """Solve for the nondimensional DH state ``(c*, v)`` at contact size ``a*`` (Eqs. 24, 31, 35).

    A scalar wrapper of :func:`dhfield.models.dh_elliptic.solve_adhesive_axis`.

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
    c, v = dh_elliptic.solve_adhesive_axis(np.atleast_1d(np.asarray(a_star, dtype=float)), mu=mu, beta0=beta0)
    return float(np.ravel(c)[0]), float(np.ravel(v)[0])


def model_case(n, beta0, mu, a_star, *, half_width=None, sampling="average", threads=None) -> FieldCase:
    """Compute the nondimensional DH case (R = E* = Delta gamma = 1) of :mod:`dhfield.models.dh_elliptic` on a grid.

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
    threads : int, optional
        FFT worker threads.

    Returns
    -------
    FieldCase
        All fields of the case, lengths in c_r and pressures in E* c_r/R.
    """
    check_case_memory(n)  # n named, and the memory checked, before anything is solved
    c, v = adhesive_state(a_star, mu=mu, beta0=beta0)
    case = dh_case(n, float(a_star), c, float(beta0), v, half_width=half_width, sampling=sampling, threads=threads)
    case.parameters.update(beta0=float(beta0), mu=float(mu), a_star=float(a_star), c_star=c,
                           units="nondimensional: lengths in c_r = (R^2 dgamma/E*)^(1/3), pressures in E* c_r/R "
                                 "(Eqs. 32-35)")
    return case


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
    return {"pressure": dh_elliptic_fields.pressure(x, y, a, c, beta, v, r, e),  # Eq. (22)
            "displacement": dh_elliptic_fields.surface_displacement(x, y, a, c, beta, v, r, e),  # Eq. (26)
            "gap": dh_elliptic_fields.gap(x, y, a, c, beta, v, r, e)}  # Eq. (27)
