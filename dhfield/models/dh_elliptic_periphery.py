"""The extended DH fields around the periphery: every ray theta_p in [0, pi/2].

The paper imposes the work of adhesion on the major axis only (Eq. 31, theta_p = 0).
This module evaluates, along every ray theta_p of the adhesive annulus
r_ab(theta_p) <= r <= r_cd(theta_p) (Eqs. A1, A2),

* the maximum adhesive stress on the ray, sigma0(theta_p) (at the contact edge);
* the adhesive-zone width r_cd - r_ab;
* the separation at the zone's outer edge, h(r_cd);
* the local work of adhesion Delta gamma(theta_p) = int sigma dh (Eq. 31 on the ray);
* the sigma-h curve along the ray: the cohesive law that ray "sees",

from the analytic fields (:func:`periphery`, :func:`cohesive_law`, and the pull-off
and load-curve wrappers :func:`periphery_at_pull_off`, :func:`periphery_along_curve`),
and from a numerical gap field on a Cartesian grid, e.g. a boundary-element
(BEM) field (:func:`periphery_from_gap_grid`).

Field structure
---------------
Both the paper's model and the alternative closures of :mod:`dhfield.models.dh_elliptic_closure`
are a superposition of two semi-ellipsoidal pressures,

.. math::

    p = A\\sqrt{1 - x^2/a^2 - y^2/b^2} - B\\sqrt{1 - x^2/c^2 - y^2/d^2},

with the contact condition h = 0 inside the contact ellipse (a, b).  With equal
ellipticities (Eq. 17), A = (1 + v) Po_ab and B = v Po_cd (Eq. 22).  Whatever the
ellipticities, the contact condition fixes the curvature terms of the gap
(Eqs. 13-15), and the gap in the annulus is

.. math::

    h = \\frac{A}{E^*}\\,g(x, y), \\qquad
    g = \\frac{ab}{2}\\left[I_1(l) - I_1(0) + (I_2(0) - I_2(l))x^2 + (I_3(0) - I_3(l))y^2\\right],

with I1-I3 of Eqs. (B1)-(B3) for the contact ellipse and l its ellipsoidal root
(below Eq. 12).  For A = Po_ab this is the Hertz gap, so with Eq. (22) it is the
annulus identity h = (1 + v) h_H of :mod:`dhfield.models.dh_elliptic_fields`.  The adhesive
stress is sigma = B sqrt(1 - r^2/r_cd^2) on the ray (Eq. 23), largest at the
contact edge, so sigma0(theta_p) = B sqrt(1 - r_ab^2/r_cd^2) (Eq. 24 on the ray).

Quadrature
----------
Delta gamma(theta_p) is integrated in the ellipsoidal coordinate l = l_cd sin^2 t
of the contact ellipse with the graded Gauss rule of :mod:`dhfield.models.dh_elliptic_adhesion`,
which removes the sqrt end-point behaviour of dh/dr (inner edge) and of sigma
(outer edge) exactly; the result is exact to ~1e-13 relative (tests compare with
:func:`dhfield.models.dh_elliptic_adhesion.work_of_adhesion` and the Greenwood-Johnson closed form).

Units
-----
SI at the public boundary (lengths [m], stresses [Pa], Delta gamma [J m^-2]);
with R = E* = 1 everything is nondimensional in the units of Eqs. (32)-(35), which
is what :func:`periphery_at_pull_off` and :func:`periphery_along_curve` return.

References
----------
.. [1] Zini N.H.M. et al. (2018) Extending the double-Hertz model to allow
   modeling of an adhesive elliptical contact. Tribol. Lett. 66:30.
   doi:10.1007/s11249-017-0976-8
.. [2] Greenwood J.A., Johnson K.L. (1998) An alternative to the Maugis model of
   adhesion between elastic spheres. J. Phys. D 31:3279. doi:10.1088/0022-3727/31/22/017
"""
from __future__ import annotations

from dataclasses import dataclass, fields
from typing import NamedTuple

import numpy as np

from . import dh_elliptic_fields, hertz
from ..core.validation import check_ellipticity, check_finite, check_positive
from .dh_elliptic_rays import edge_radius as _edge_radius, ray_geometry as _rays, ray_nodes as _ray_nodes
from ..core.elliptic import ellipsoid_integrals
from ..core._docstrings import fill_doc

__all__ = [
    "DEFAULT_THETA",
    "PeripheryProfile",
    "CohesiveLaw",
    "contact_edge_radius",
    "adhesive_edge_radius",
    "periphery",
    "cohesive_law",
    "ray_average",
    "periphery_at_pull_off",
    "periphery_along_curve",
    "periphery_from_gap_grid",
    "adhesive_traction",
    "periphery_from_state",
    "periphery_two_ellipses",
    "field_parameters",
    "FieldParameters",
]

#: Default rays: 91 angles, 1 degree apart, from the major (0) to the minor (pi/2) axis.
DEFAULT_THETA = np.linspace(0.0, 0.5 * np.pi, 91)
#: Number of Gauss-Legendre nodes per panel for ray integrals of gridded fields.
GRID_NODES_PER_PANEL = 24
#: Mirrored cells added at the axes of a quadrant-only grid (even symmetry) so that
#: the bicubic spline is centred there.
_MIRROR_CELLS = 4


# --------------------------------------------------------------------------- containers
@dataclass(frozen=True)
class PeripheryProfile:
    """Quantities along the rays theta_p of the adhesive annulus.

    Every array has the broadcast shape of the contact state followed by the
    ``theta`` axis (last).

    Parameters
    ----------
    theta : ndarray
        Polar angle theta_p of each ray, 0 on the major axis [rad].
    contact_radius : ndarray
        Radius of the contact edge, r_ab(theta_p), Eq. (A1) [m].
    adhesive_radius : ndarray
        Radius of the adhesive edge, r_cd(theta_p), Eq. (A2) [m].
    zone_width : ndarray
        Width of the cohesive zone, r_cd - r_ab [m].
    max_adhesive_stress : ndarray
        The maximum adhesive stress sigma0(theta_p), the tensile stress at the contact edge (Eq. 24 on the ray) [Pa].
    edge_separation : ndarray
        Gap at the zone's outer edge, h(r_cd, theta_p) (Eq. 27) [m].
    work_of_adhesion : ndarray
        Delta gamma(theta_p) = int_{r_ab}^{r_cd} sigma dh/dr dr (Eq. 31 on the ray) [J m^-2].
    contact_edge_gap : ndarray
        Gap at the contact edge h(r_ab, theta_p): 0 for the analytic fields, the
        residual of the contact condition for a numerical field [m].
    """

    theta: np.ndarray
    contact_radius: np.ndarray
    adhesive_radius: np.ndarray
    zone_width: np.ndarray
    max_adhesive_stress: np.ndarray
    edge_separation: np.ndarray
    work_of_adhesion: np.ndarray
    contact_edge_gap: np.ndarray

    def as_dict(self):
        """The fields as a dict.

        Returns
        -------
        dict
            Field name -> array.
        """
        return {f.name: getattr(self, f.name) for f in fields(self)}


@dataclass(frozen=True)
class CohesiveLaw:
    """The sigma-h curve along each ray (the cohesive law the ray sees).

    Arrays have the state shape, then the ``theta`` axis, then the sample axis
    running from the contact edge (h = 0, sigma = sigma0(theta_p)) to the
    adhesive edge (h = h(r_cd), sigma = 0).

    Parameters
    ----------
    theta : ndarray
        Ray angle theta_p [rad].
    radius : ndarray
        Radial position r on the ray [m].
    separation : ndarray
        Gap h(r, theta_p), Eq. (27) [m].
    stress : ndarray
        Tensile adhesive stress sigma(r, theta_p), Eq. (23) [Pa].
    """

    theta: np.ndarray
    radius: np.ndarray
    separation: np.ndarray
    stress: np.ndarray


# --------------------------------------------------------------------------- geometry
def contact_edge_radius(semi_major, beta, theta):
    """The radius of the contact ellipse along the ray theta_p, Eq. (A1).

    Parameters
    ----------
    semi_major : array_like
        Contact semi-major axis a [m].
    beta : array_like
        Ellipticity b/a in (0, 1] [-].
    theta : array_like
        Ray angle theta_p, 0 on the major axis [rad].

    Returns
    -------
    ndarray
        The radius r_ab [m].

    Notes
    -----
    .. math:: r_{ab} = ab/\\sqrt{(b\\cos\\theta_p)^2 + (a\\sin\\theta_p)^2}
    """
    a = check_positive("semi_major", semi_major, "m")
    beta = check_ellipticity("beta", beta)
    th = check_finite("theta", theta, "rad")
    return _edge_radius(a, beta * a, np.cos(th) ** 2, np.sin(th) ** 2)  # Eq. (A1)


def adhesive_edge_radius(adhesive_semi_major, beta, theta):
    """The radius of the adhesive ellipse along the ray theta_p, Eq. (A2).

    Parameters
    ----------
    adhesive_semi_major : array_like
        Adhesive semi-major axis c [m].
    beta : array_like
        Ellipticity d/c in (0, 1] [-].
    theta : array_like
        Ray angle theta_p [rad].

    Returns
    -------
    ndarray
        The radius r_cd [m].

    Examples
    --------
    On the axes the radius is c and d = beta c.

    >>> import numpy as np
    >>> from dhfield.models import dh_elliptic_periphery
    >>> [round(float(dh_elliptic_periphery.adhesive_edge_radius(2.0, 0.5, t)), 12) for t in (0.0, np.pi / 2)]
    [2.0, 1.0]
    """
    c = check_positive("adhesive_semi_major", adhesive_semi_major, "m")
    beta = check_ellipticity("beta", beta)
    th = check_finite("theta", theta, "rad")
    return _edge_radius(c, beta * c, np.cos(th) ** 2, np.sin(th) ** 2)  # Eq. (A2)


# --------------------------------------------------------------------------- general core
def _gap_shape(x, y, a, b):
    """g(x, y) with h = (A/E*) g in the annulus (module docstring) [m^2 ... m]."""
    l = hertz.ellipse_root(x, y, a, b)
    i1, i2, i3 = ellipsoid_integrals(l, a, b)
    j1, j2, j3 = ellipsoid_integrals(0.0, a, b)
    return 0.5 * a * b * (i1 - j1 + (j2 - i2) * x * x + (j3 - i3) * y * y)  # Eqs. (13)-(15), (27)


@fill_doc
def periphery_two_ellipses(a, b, c, d, gap_amplitude, stress_amplitude, theta, reduced_modulus=1.0):
    """Periphery of the general two-ellipse field p = A S_ab - B S_cd, any two ellipticities.

    The core of :func:`periphery` (equal ellipticities, A and B of Eq. 22), also used by
    the closures of :mod:`dhfield.models.dh_elliptic_closure` and by :mod:`dhfield.analysis.eq30`.  An unchecked
    array core: the callers validate, and NaN inputs propagate.

    Parameters
    ----------
    a, b : array_like
        Contact semi-axes [m].
    c, d : array_like
        Adhesive semi-axes (c along a, d along b) [m].
    gap_amplitude : array_like
        A, the amplitude of the semi-ellipsoidal pressure on the contact ellipse [Pa].
    stress_amplitude : array_like
        B, the amplitude of the subtracted pressure on the adhesive ellipse [Pa].
    theta : array_like, 1-D
        Ray angles theta_p, 0 on the major axis [rad].
    %(reduced_modulus_default)s

    Returns
    -------
    PeripheryProfile
        Arrays of shape ``broadcast(a, b, c, d, A, B, E*) + theta.shape``.

    Notes
    -----
    On each ray, r_ab and r_cd from Eqs. (A1), (A2); sigma0 = B sqrt(1 - r_ab^2/r_cd^2)
    (Eq. 24 on the ray); h(r_cd) from the annulus gap (Eq. 27 with the curvature
    terms of Eqs. 13-15); Delta gamma(theta_p) = int sigma dh (Eq. 31 on the ray) by
    the graded rule of the module docstring.
    """
    a, b, c, d, gap_amplitude, stress_amplitude, reduced_modulus = np.broadcast_arrays(
        *(np.asarray(q, float) for q in (a, b, c, d, gap_amplitude, stress_amplitude, reduced_modulus)))
    a_, b_, c_, d_, th, cos2, sin2, r_ab, r_cd = _rays(a, b, c, d, theta)
    amp_h = (gap_amplitude / reduced_modulus)[..., None]
    amp_s = stress_amplitude[..., None]
    shape = np.broadcast_shapes(r_ab.shape, r_cd.shape)
    r_ab = np.broadcast_to(r_ab, shape)
    r_cd = np.broadcast_to(r_cd, shape)
    sigma0 = amp_s * np.sqrt(np.maximum(1.0 - (r_ab / r_cd) ** 2, 0.0))  # Eq. (24) on the ray
    h_edge = amp_h * _gap_shape(r_cd * np.cos(th), r_cd * np.sin(th), a_, b_)  # Eq. (27) at r_cd
    work = _ray_work(a_, b_, r_cd, th, cos2, sin2, amp_h, amp_s)
    theta_b = np.broadcast_to(th, shape)
    return PeripheryProfile(theta_b, r_ab, r_cd, r_cd - r_ab, np.broadcast_to(sigma0, shape),
                            np.broadcast_to(h_edge, shape), work, np.zeros(shape))


def _ray_work(a, b, r_cd, theta, cos2, sin2, amp_h, amp_s):
    """Delta gamma(theta_p) = int sigma dh along each ray (exact quadrature)."""
    shape = np.broadcast_shapes(a.shape, b.shape, r_cd.shape, np.shape(theta), amp_h.shape, amp_s.shape)
    a, b, r_cd, amp_h, amp_s = (np.broadcast_to(q, shape) for q in (a, b, r_cd, amp_h, amp_s))
    theta, cos2, sin2 = (np.broadcast_to(q, shape) for q in (theta, cos2, sin2))
    t, w, l, r2, dr2_dl, dl_dt, _ = _ray_nodes(a, b, r_cd, theta, cos2, sin2)
    ex = (lambda q: q[..., None])
    _, i2, i3 = ellipsoid_integrals(l, ex(a), ex(b))
    _, j2, j3 = ellipsoid_integrals(0.0, a, b)
    # dh/dl = (A/E*) (ab/2) dr^2/dl [cos^2 (I2(0) - I2(l)) + sin^2 (I3(0) - I3(l))]
    slope = 0.5 * dr2_dl * ex(a * b) * (ex(cos2) * (ex(j2) - i2) + ex(sin2) * (ex(j3) - i3))
    sigma = np.sqrt(np.maximum(1.0 - r2 / ex(r_cd) ** 2, 0.0))  # Eq. (23) / B
    return amp_h * amp_s * np.sum(w * sigma * slope * dl_dt, axis=-1)  # Eq. (31) on every ray


def _law_general(a, b, c, d, gap_amplitude, stress_amplitude, theta, n_points, reduced_modulus=1.0):
    a, b, c, d, gap_amplitude, stress_amplitude, reduced_modulus = np.broadcast_arrays(
        *(np.asarray(q, float) for q in (a, b, c, d, gap_amplitude, stress_amplitude, reduced_modulus)))
    a_, b_, c_, d_, th, cos2, sin2, r_ab, r_cd = _rays(a, b, c, d, theta)
    shape = np.broadcast_shapes(r_ab.shape, r_cd.shape)
    ex = (lambda q: np.broadcast_to(q, shape)[..., None])
    # Sample uniformly in the ellipsoidal coordinate's angle t (l = l_cd sin^2 t):
    # dense at both edges, where the law has its sqrt behaviour.
    t = np.linspace(0.0, 0.5 * np.pi, int(n_points))
    l_cd = hertz.ellipse_root(r_cd * np.cos(th), r_cd * np.sin(th), a_, b_)
    l = ex(l_cd) * np.sin(t) ** 2
    c2, s2 = ex(cos2), ex(sin2)
    r = 1.0 / np.sqrt(c2 / (ex(a_) ** 2 + l) + s2 / (ex(b_) ** 2 + l))
    r[..., -1] = ex(r_cd)[..., 0]
    x, y = r * np.sqrt(c2), r * np.sqrt(s2)
    h = ex(gap_amplitude[..., None] / reduced_modulus[..., None]) * _gap_shape(x, y, ex(a_), ex(b_))  # Eq. (27)
    sigma = ex(stress_amplitude[..., None]) * np.sqrt(np.maximum(1.0 - (r / ex(r_cd)) ** 2, 0.0))  # Eq. (23)
    return CohesiveLaw(np.broadcast_to(ex(th), r.shape), r, h, sigma)


# --------------------------------------------------------------------------- public, equal beta
@fill_doc
class FieldParameters(NamedTuple):
    """Checked DH parameters and the amplitudes of the two-ellipse field (Eq. 22).

    Parameters
    ----------
    %(dh_state)s
    effective_radius : ndarray
        R = sqrt(R'R'') [m].
    reduced_modulus : ndarray
        E* [Pa].
    gap_amplitude : ndarray
        A = (1 + v) Po_ab [Pa].
    stress_amplitude : ndarray
        B = v Po_cd [Pa].
    """

    semi_major: np.ndarray
    adhesive_semi_major: np.ndarray
    beta: np.ndarray
    scaling: np.ndarray
    effective_radius: np.ndarray
    reduced_modulus: np.ndarray
    gap_amplitude: np.ndarray
    stress_amplitude: np.ndarray


@fill_doc
def field_parameters(semi_major, adhesive_semi_major, beta, scaling, effective_radius, reduced_modulus):
    """Validate a DH state (equal ellipticities) and give its two-ellipse amplitudes, Eq. (22).

    Parameters
    ----------
    %(dh_state)s
    effective_radius : array_like
        R = sqrt(R'R'') [m].
    reduced_modulus : array_like
        E* [Pa].

    Returns
    -------
    FieldParameters
        The checked arrays and A = (1 + v) Po_ab, B = v Po_cd [Pa].

    Notes
    -----
    .. math:: A = (1+v)P_{o,ab}, \\qquad B = v P_{o,cd}  \\quad (Eq.\\ 22)

    with the Hertz peak pressures of Eqs. (8) and (20).
    """
    a, c, beta, v, r, e = dh_elliptic_fields.check_parameters(semi_major, adhesive_semi_major, beta, scaling,
                                                        effective_radius, reduced_modulus)
    po_ab = hertz.max_pressure(a, beta, r, e)  # Eq. (8)
    po_cd = hertz.max_pressure(c, beta, r, e)  # Eq. (20)
    return FieldParameters(a, c, beta, v, r, e, (1.0 + v) * po_ab, v * po_cd)  # Eq. (22): A, B


def _check_theta(theta):
    if theta is None:
        return DEFAULT_THETA.copy()
    th = check_finite("theta", theta, "rad")
    if th.ndim > 1:
        raise ValueError(f"theta must be a scalar or 1-D array of ray angles (rad); got shape {th.shape}")
    if np.any((th < 0) | (th > 0.5 * np.pi + 1e-12)):
        raise ValueError("theta must be in [0, pi/2] (ray angle theta_p, rad); got "
                         f"{th[(th < 0) | (th > 0.5 * np.pi + 1e-12)].flat[0]!r}")
    return np.atleast_1d(np.clip(th, 0.0, 0.5 * np.pi))


@fill_doc
def periphery(semi_major, adhesive_semi_major, beta, scaling, theta=None, effective_radius=1.0,
              reduced_modulus=1.0):
    """The maximum adhesive stress, zone width, edge separation and work of adhesion per ray.

    Along every ray theta_p: sigma0, r_cd - r_ab, h(r_cd) and Delta gamma.

    Parameters
    ----------
    %(dh_state)s
    theta : array_like, optional
        Ray angles in [0, pi/2], 1-D [rad]; default :data:`DEFAULT_THETA`.
    %(dh_material)s

    Returns
    -------
    PeripheryProfile
        Arrays of shape ``broadcast(state).shape + theta.shape``.

    Notes
    -----
    With equal ellipticity, sigma0(theta_p) = v Po_cd sqrt(1 - a^2/c^2) on every
    ray (r_ab/r_cd = a/c), while the zone width, the edge separation and

    .. math:: \\Delta\\gamma(\\theta_p) = \\int_{r_{ab}}^{r_{cd}}\\sigma_{ac}\\,\\frac{\\partial h}{\\partial r}\\,dr

    depend on theta_p (Eq. 31 at theta_p = 0).
    """
    a, c, beta, v, r, e, amp_a, amp_b = field_parameters(semi_major, adhesive_semi_major, beta, scaling,
                                                         effective_radius, reduced_modulus)
    th = _check_theta(theta)
    return periphery_two_ellipses(a, beta * a, c, beta * c, amp_a, amp_b, th, e)


@fill_doc
def cohesive_law(semi_major, adhesive_semi_major, beta, scaling, theta=None, n_points=65,
                 effective_radius=1.0, reduced_modulus=1.0):
    """The sigma-h curve along each ray theta_p (Eqs. 23, 27).

    Parameters
    ----------
    %(dh_state)s
    theta : array_like, optional
        Ray angles in [0, pi/2], 1-D [rad].
    n_points : int
        Samples per ray (>= 2), uniform in t with l = l_cd sin^2 t [-].
    %(dh_material)s

    Returns
    -------
    CohesiveLaw
        Radius, separation and stress of shape ``state + theta + (n_points,)``.
    """
    if int(n_points) != n_points or n_points < 2:
        raise ValueError(f"n_points must be an integer >= 2 (samples per ray); got {n_points!r}")
    a, c, beta, v, r, e, amp_a, amp_b = field_parameters(semi_major, adhesive_semi_major, beta, scaling,
                                                         effective_radius, reduced_modulus)
    th = _check_theta(theta)
    return _law_general(a, beta * a, c, beta * c, amp_a, amp_b, th, int(n_points), e)


def ray_average(values, theta, contact_radius=None, weight="area"):
    """Average of a quantity over the rays theta_p in [0, pi/2] (last axis).

    Parameters
    ----------
    values : array_like
        Quantity on the rays, e.g. Delta gamma(theta_p), last axis over ``theta``.
    theta : array_like
        Ray angles, 1-D, covering [0, pi/2] [rad].
    contact_radius : array_like, optional
        The contact radius r_ab(theta_p) on the same rays [m]; needed for ``weight="area"``.
    weight : {"area", "angle"}
        ``"angle"``: uniform in theta_p.  ``"area"``: weight r_ab^2 d(theta_p), the
        area swept by a self-similar advance of the contact edge (a -> a(1+eps)),
        i.e. the energy-release average of Griffith's balance if each ray releases
        Delta gamma(theta_p) per unit of swept area.

    Returns
    -------
    ndarray
        The weighted mean, trapezoidal rule in theta_p (all quantities here are
        even about both axes, so the rule is spectrally accurate on a uniform grid).

    Notes
    -----
    .. math:: \\overline{\\Delta\\gamma} = \\frac{\\int_0^{\\pi/2}\\Delta\\gamma(\\theta_p)\\,r_{ab}^2\\,d\\theta_p}
                                        {\\int_0^{\\pi/2} r_{ab}^2\\,d\\theta_p}
    """
    th = np.asarray(theta, float)
    vals = np.asarray(values, float)
    if weight == "angle":
        wts = np.ones_like(th)
    elif weight == "area":
        if contact_radius is None:
            raise ValueError("contact_radius is required for weight='area' (r_ab on the rays, m)")
        wts = np.asarray(contact_radius, float) ** 2
    else:
        raise ValueError(f"weight must be 'area' or 'angle'; got {weight!r}")
    wts = np.broadcast_to(wts, np.broadcast_shapes(wts.shape, vals.shape))
    return np.trapezoid(vals * wts, th, axis=-1) / np.trapezoid(wts, th, axis=-1)


# --------------------------------------------------------------------------- pull-off, load curves
def periphery_at_pull_off(pull_off, theta=None):
    """The periphery quantities at the pull-off point of the paper's model.

    Parameters
    ----------
    pull_off : dhfield.core.records.PullOff
        The pull-off record of :func:`dhfield.models.dh_elliptic.pull_off` (nondimensional, Eqs. 32-36).
    theta : array_like, optional
        Ray angles, 1-D [rad].

    Returns
    -------
    PeripheryProfile
        Nondimensional (R = E* = Delta gamma = 1): lengths in c_r (Eq. 33),
        stresses in E* c_r/R (sigma0(0) = mu), Delta gamma(0) = 1 by construction;
        shape of the record followed by ``theta``.
    """
    beta = np.asarray(pull_off.ellipticity, float)
    a = np.asarray(pull_off.a_star, float)
    # a* = 0 (DMT-side pull-off): the rays start at the centre; use a tiny contact.
    a = np.where(a > 0, a, 1e-9 * np.asarray(pull_off.c_star, float))
    return periphery(a, pull_off.c_star, beta, pull_off.v, theta)


def periphery_along_curve(curve, theta=None):
    """The periphery quantities along a load curve of the paper's model.

    Parameters
    ----------
    curve : dhfield.core.records.LoadCurve
        A nondimensional curve of the paper's model, model ``dh-elliptic``
        (:func:`dhfield.models.dh_elliptic.load_curve`, whose ``ellipticity`` is that of both ellipses,
        or :func:`dhfield.analysis.compare.load_curve`, whose ellipses have beta0).
    theta : array_like, optional
        Ray angles, 1-D [rad].

    Returns
    -------
    PeripheryProfile
        Shape ``(len(a_star), len(theta))``, nondimensional as in :func:`periphery_at_pull_off`.
    """
    if getattr(curve, "model", None) != "dh-elliptic" or not curve.nondimensional:
        raise ValueError("curve must be a nondimensional load curve of the paper's model (model 'dh-elliptic', "
                         f"dhfield.models.dh_elliptic.load_curve); got {getattr(curve, 'model', type(curve).__name__)!r}")
    ell = curve.beta0 if curve.ellipticity is None else curve.ellipticity
    return periphery(curve.a_star, curve.c_star, ell, curve.v, theta)


# --------------------------------------------------------------------------- numerical (BEM) fields
def _grid_spline(x, y, gap):
    """Bicubic spline of a gridded field; a quadrant grid is mirrored (even field)."""
    from scipy.interpolate import RectBivariateSpline

    x = check_finite("x", x, "m")
    y = check_finite("y", y, "m")
    gap = check_finite("gap", gap, "m")
    if x.ndim != 1 or y.ndim != 1 or gap.shape != (x.size, y.size):
        raise ValueError("gap must have shape (len(x), len(y)) ('ij' indexing, x first); "
                         f"got {gap.shape} for {x.size} x and {y.size} y")
    if x.size < 4 or y.size < 4 or np.any(np.diff(x) <= 0) or np.any(np.diff(y) <= 0):
        raise ValueError("x and y must be strictly increasing with at least 4 points each")
    if x[0] > 0:
        m = min(_MIRROR_CELLS, x.size)
        x = np.concatenate([-x[:m][::-1], x])
        gap = np.concatenate([gap[:m][::-1], gap], axis=0)
    if y[0] > 0:
        m = min(_MIRROR_CELLS, y.size)
        y = np.concatenate([-y[:m][::-1], y])
        gap = np.concatenate([gap[:, :m][:, ::-1], gap], axis=1)
    return RectBivariateSpline(x, y, gap, kx=3, ky=3)


def periphery_from_gap_grid(x, y, gap, state, theta=None, *, method="parts", trend=None):
    """Periphery quantities from a numerical gap field on a Cartesian grid (e.g. BEM).

    The adhesive stress is the DH stress of the given state (Eq. 23), which is the
    pressure a forward BEM is loaded with; the gap h comes from the grid,
    interpolated along each ray with a bicubic spline.

    Parameters
    ----------
    x, y : array_like
        Strictly increasing 1-D grid coordinates (cell centres) [m].  A grid that
        covers only x > 0 (or y > 0) is extended by even symmetry.
    gap : array_like
        Gap h on the grid, shape ``(len(x), len(y))`` ('ij' indexing) [m].
    state : tuple
        The (scalar) DH state that produced the field, ``(semi_major, adhesive_semi_major, beta,
        scaling)`` or ``(semi_major, adhesive_semi_major, beta, scaling, effective_radius,
        reduced_modulus)``, as :class:`dhfield.models.dh_elliptic_fields.DoubleHertzParameters`: contact
        semi-major axis a [m], adhesive semi-major axis c >= a [m], common ellipticity
        b/a = d/c (Eq. 17) [-], DH scaling factor v >= 0 [-], R = sqrt(R'R'') [m] (default 1)
        and E* [Pa] (default 1).
    theta : array_like, optional
        Ray angles, 1-D [rad].
    method : {"parts", "slope"}
        ``"parts"``: Delta gamma = -sigma0 h(r_ab) - int h (d sigma/dr) dr, which
        uses only values of the interpolated gap (integration by parts;
        sigma(r_cd) = 0).  ``"slope"``: int sigma (dh/dr) dr with the spline's
        derivative.  Identical for an exact gap.
    trend : callable, optional
        ``trend(x, y) -> gap`` [m], a known field (e.g. the analytic gap
        :func:`dhfield.models.dh_elliptic_fields.gap`) used as the interpolation trend: the
        spline interpolates ``gap - trend`` on the grid and ``trend`` is added back
        at the ray points.  The reconstruction still passes through every grid
        value; only the shape between nodes comes from the trend.  Without it the
        bicubic spline has an O(dx^1.5) error at the two edges of the zone, where
        h has s^(3/2) kinks (h = 0 inside the contact; the adhesive pressure's
        square-root edge at r_cd).

    Returns
    -------
    PeripheryProfile
        The work of adhesion, edge separation and contact-edge gap from the grid;
        radii, zone width and sigma0 from the state.

    Notes
    -----
    Both forms use the graded rule in t (l = l_cd sin^2 t) of the analytic
    evaluation, with :data:`GRID_NODES_PER_PANEL` nodes per panel.
    """
    if method not in ("parts", "slope"):
        raise ValueError(f"method must be 'parts' or 'slope'; got {method!r}")
    if not isinstance(state, tuple) or len(state) not in (4, 6):
        raise ValueError("state must be a tuple (semi_major, adhesive_semi_major, beta, scaling"
                         "[, effective_radius, reduced_modulus]); got "
                         f"{type(state).__name__} of length {len(state) if isinstance(state, tuple) else '-'}")
    a, c, beta, v, r, e, amp_a, amp_b = field_parameters(*state, *(1.0, 1.0)[:6 - len(state)])
    if np.ndim(a) or np.ndim(c) or np.ndim(beta) or np.ndim(v):
        raise ValueError("periphery_from_gap_grid takes one (scalar) DH state")
    th = _check_theta(theta)
    if trend is not None:
        xg, yg = np.meshgrid(np.asarray(x, float), np.asarray(y, float), indexing="ij")
        gap = np.asarray(gap, float) - trend(xg, yg)
    else:
        trend = (lambda xx, yy: np.zeros(np.broadcast_shapes(np.shape(xx), np.shape(yy))))
    spline = _grid_spline(x, y, gap)
    prof = periphery_two_ellipses(a, beta * a, c, beta * c, amp_a, amp_b, th, e)
    a_, b_ = a, beta * a
    r_cd = prof.adhesive_radius
    cos2, sin2 = np.cos(th) ** 2, np.sin(th) ** 2
    t, w, l, r2, dr2_dl, dl_dt, _ = _ray_nodes(np.broadcast_to(a_, th.shape), np.broadcast_to(b_, th.shape),
                                              r_cd, th, cos2, sin2, nodes=GRID_NODES_PER_PANEL)
    rr = np.sqrt(r2)
    xs, ys = rr * np.cos(th)[:, None], rr * np.sin(th)[:, None]
    q = np.maximum(1.0 - r2 / r_cd[:, None] ** 2, 0.0)
    sigma = amp_b * np.sqrt(q)  # Eq. (23)
    r_ab = prof.contact_radius
    xa, ya, xc, yc = r_ab * np.cos(th), r_ab * np.sin(th), r_cd * np.cos(th), r_cd * np.sin(th)
    h_ab = spline.ev(xa, ya) + trend(xa, ya)
    h_cd = spline.ev(xc, yc) + trend(xc, yc)
    # d sigma/dt = -B (dr^2/dl)(dl/dt) / (2 r_cd^2 sqrt(q)); sqrt(q) ~ cos t cancels dl/dt's cos t
    with np.errstate(divide="ignore"):  # weightless nodes of zero-width panels sit at q = 0
        inv_sq = np.where(q > 0, 1.0 / np.sqrt(q), 0.0)
    dsigma_dt = -amp_b * dr2_dl * dl_dt * inv_sq / (2.0 * r_cd[:, None] ** 2)

    def by_parts(h_nodes, h_inner):
        # int sigma dh = [sigma h] - int h d sigma, sigma(r_cd) = 0
        return -prof.max_adhesive_stress * h_inner - np.sum(w * h_nodes * dsigma_dt, axis=-1)

    trend_work = by_parts(trend(xs, ys), trend(xa, ya))
    if method == "parts":
        h = spline.ev(xs.ravel(), ys.ravel()).reshape(xs.shape)
        work = trend_work + by_parts(h, spline.ev(xa, ya))  # Eq. (31), by parts
    else:
        hx = spline.ev(xs.ravel(), ys.ravel(), dx=1).reshape(xs.shape)
        hy = spline.ev(xs.ravel(), ys.ravel(), dy=1).reshape(xs.shape)
        dh_dr = hx * np.cos(th)[:, None] + hy * np.sin(th)[:, None]
        dr_dt = 0.5 * dr2_dl * dl_dt / rr
        work = trend_work + np.sum(w * sigma * dh_dr * dr_dt, axis=-1)  # Eq. (31)
    return PeripheryProfile(prof.theta, prof.contact_radius, prof.adhesive_radius, prof.zone_width,
                            prof.max_adhesive_stress, h_cd, work, h_ab)


# --------------------------------------------------------------------------- BEM states
#: Samples per ray of :func:`periphery_from_state` (the traction is piecewise constant per
#: cell, so the Stieltjes sum converges like 1/samples once samples >> cells per ray).
STATE_RAY_SAMPLES = 4001


def adhesive_traction(state) -> np.ndarray:
    """Tensile adhesive stress of a BEM :class:`dhfield.bem.ContactState` per cell [Pa].

    The BEM pressure is the repulsive contact pressure minus the adhesive
    traction, so the adhesive part is ``repulsive_pressure - pressure`` when the
    state carries its repulsive part.  Otherwise it is ``-pressure`` outside the
    contact and the law's stress at zero gap (sigma0 of Eq. 24 for the Dugdale
    law, as in Maugis' model) inside it; zero without a law.

    Parameters
    ----------
    state : dhfield.bem.ContactState
        A BEM solution.

    Returns
    -------
    ndarray
        The traction per cell, >= 0, shape of ``state.pressure`` [Pa].
    """
    p = np.asarray(state.pressure, dtype=float)
    contact = np.asarray(state.contact, dtype=bool)
    rep = getattr(state, "repulsive_pressure", None)
    if rep is not None:
        return np.maximum(np.asarray(rep, dtype=float) - p, 0.0)
    if state.law is None:
        return np.zeros_like(p)
    at_contact = float(np.asarray(state.law.stress(0.0)))
    return np.where(contact, at_contact, np.maximum(-p, 0.0))


def periphery_from_state(state, theta=None, *, n_samples=STATE_RAY_SAMPLES) -> PeripheryProfile:
    """Periphery quantities of a BEM solution, from its own gap and traction fields.

    The analytic counterpart is :func:`periphery`; here nothing is assumed about
    the shape of the zone: along each ray theta_p from the centre,

    * r_ab is where the ray leaves the contact mask, r_cd where it leaves the
      cohesive zone (first cell without adhesive traction beyond r_ab);
    * Delta gamma(theta_p) = int sigma dh along the ray (Eq. 31 on the ray),
      with sigma the cell's adhesive traction (:func:`adhesive_traction`:
      piecewise constant, exactly what the BEM applied) and h the gap
      interpolated by a bicubic spline, as a Stieltjes sum over
      ``n_samples`` points;
    * sigma0(theta_p) is the traction just outside the contact, h(r_cd) the
      edge separation and h(r_ab) the contact-edge gap.

    For a self-consistent solution with one traction law, Delta gamma(theta_p)
    is the law's work of adhesion on every ray (for the Dugdale law,
    sigma0 h(r_cd) = sigma0 h0), up to the discretisation; the analytic DH
    fields are not (see :func:`periphery`).

    Parameters
    ----------
    state : dhfield.bem.ContactState
        Full-grid BEM state (any consistent units).
    theta : array_like, optional
        Ray angles in [0, pi/2], 1-D [rad]; default :data:`DEFAULT_THETA`.
    n_samples : int
        Points per ray, from the centre to 98 % of the way to the grid edge.

    Returns
    -------
    PeripheryProfile
        Every array has the ``theta`` axis only; radii [m], stresses [Pa],
        gaps [m], Delta gamma [J m^-2] (or the state's units).
    """
    th = _check_theta(theta)
    if int(n_samples) != n_samples or n_samples < 16:
        raise ValueError(f"n_samples must be an integer >= 16 (points per ray); got {n_samples!r}")
    g = state.grid
    x_e, y_e = g.x_edges, g.y_edges
    gap = np.asarray(state.gap, dtype=float)
    contact = np.asarray(state.contact, dtype=bool)
    traction = adhesive_traction(state)
    spline = _grid_spline(g.x, g.y, gap)
    c, s = np.cos(th), np.sin(th)
    with np.errstate(divide="ignore"):
        r_max = 0.98 * np.minimum(np.where(c > 1e-12, x_e[-1] / np.maximum(c, 1e-300), np.inf),
                                  np.where(s > 1e-12, y_e[-1] / np.maximum(s, 1e-300), np.inf))
    t = np.linspace(0.0, 1.0, int(n_samples))
    r = r_max[:, None] * t[None, :]
    xs, ys = r * c[:, None], r * s[:, None]

    def cell(xq, yq):
        i = np.clip(np.floor((xq - x_e[0]) / g.dx).astype(int), 0, g.nx - 1)
        j = np.clip(np.floor((yq - y_e[0]) / g.dy).astype(int), 0, g.ny - 1)
        return i, j

    h = spline.ev(xs.ravel(), ys.ravel()).reshape(xs.shape)
    i, j = cell(xs, ys)
    in_contact = contact[i, j]
    xm, ym = 0.5 * (xs[:, 1:] + xs[:, :-1]), 0.5 * (ys[:, 1:] + ys[:, :-1])
    im, jm = cell(xm, ym)
    t_mid = traction[im, jm]
    n_th = th.size
    out = {k: np.full(n_th, np.nan) for k in ("r_ab", "r_cd", "s0", "h_cd", "work", "h_ab")}
    for k in range(n_th):
        outside = np.nonzero(~in_contact[k])[0]
        k0 = int(outside[0]) if outside.size else n_samples - 1
        no_traction = np.nonzero(traction[i[k, k0:], j[k, k0:]] <= 0.0)[0]
        k1 = k0 + int(no_traction[0]) if no_traction.size else n_samples - 1
        out["r_ab"][k] = r[k, k0] if k0 > 0 else 0.0
        out["r_cd"][k] = r[k, k1]
        out["s0"][k] = traction[i[k, k0], j[k, k0]]
        out["h_ab"][k] = h[k, k0]
        out["h_cd"][k] = h[k, k1]
        m0 = max(k0 - 1, 0)  # the segment that straddles the contact edge
        out["work"][k] = np.sum(t_mid[k, m0:] * np.diff(h[k, m0:]))  # Eq. (31), Stieltjes sum of sigma dh
    return PeripheryProfile(th, out["r_ab"], out["r_cd"], out["r_cd"] - out["r_ab"], out["s0"], out["h_cd"],
                            out["work"], out["h_ab"])
