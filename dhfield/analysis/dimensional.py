"""Dimensional front end: materials and contact geometry in SI units, every model.

The nondimensional models (:mod:`dhfield.analysis.compare`) are scaled back with

* lengths in the contact plane: c_r = (R^2 dgamma/E*)^(1/3)          (Eq. 33)
* approach: c_r^2/R
* stresses: E* c_r/R = (E*^2 dgamma/R)^(1/3), so sigma0 = mu times it (Eq. 35)
* load: W = 2 pi R dgamma W*/sin(theta_skew)                          (Eq. 34)

with R = sqrt(R'R'') (Eq. 5) and sin(theta_skew) that of the Hertz ellipticity
beta0 of the geometry (:func:`dhfield.core.geometry.sin_skew_angle`), 1 for the
circular models: the same factor the nondimensional models divide by, so that
the force in newtons does not depend on the convention.

Geometry
--------
Three ways to give the undeformed gap z = x^2/(2R') + y^2/(2R''):

* two equal cylinders of radius R_c crossed at theta_skew (Eqs. 3-4):
  :func:`contact_parameters`;
* two cylinders of radii R1, R2 crossed at theta_skew:
  :func:`crossed_cylinder_radii`, then :func:`contact_parameters_from_principal_radii`;
* any paraboloid, by its principal relative radii R', R'':
  :func:`contact_parameters_from_principal_radii`.

Paper note: for equal cylinders R = R_c/sin(theta_skew), so Eq. (34) may also be
written W = 2 pi R_c dgamma W*/sin^2(theta_skew).  dhfield follows Eq. (34) as
printed, consistently with Eq. (36).

Every function broadcasts over arrays; a scalar in gives a scalar out.

Plausibility
------------
Inputs are SI.  A modulus, radius, work of adhesion or adhesive stress far outside the
range of real contacts (:data:`PLAUSIBLE_SI_RANGES`: E in [1 kPa, 1 TPa], a radius in
[1 nm, 1 m], Delta gamma <= 10 J m^-2, sigma0 <= 100 GPa) is computed as given and warned
with :class:`dhfield.analysis.validity.ImplausibleInputWarning` ("did you mean MPa, mm or mJ?"):
1.8 for a PDMS modulus of 1.8 MPa, or 3 for a 3 mm radius, would otherwise give a force
off by orders of magnitude without a word.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..core import units as units
from . import compare
from ..core import geometry
from ..core.validation import ELLIPTICITY_RANGE, TABOR_RANGE, check_interval, check_positive
from ..core.records import load_curve_record
from .validity import ImplausibleInputWarning, warn_record

__all__ = ["ContactParameters", "contact_parameters", "contact_parameters_from_principal_radii",
           "crossed_cylinder_radii", "load_curve_si", "pull_off_force", "pull_off_record_si",
           "PLAUSIBLE_SI_RANGES", "check_plausible_si"]

_s = units.scalar_or_array

#: quantity -> (smallest, largest plausible value [SI unit], SI unit, the unit a value outside was most
#: likely meant in).  Far outside every real contact: soft gels have E ~ 1 kPa, diamond ~ 1 TPa; a
#: contact radius from a molecule (1 nm) to a boulder (1 m); Delta gamma of solids below ~ 10 J m^-2 and
#: sigma0 below the ideal strength of solids, ~ 100 GPa.
PLAUSIBLE_SI_RANGES = {
    "youngs_modulus": (1e3, 1e12, "Pa", "MPa"),
    "radius": (1e-9, 1.0, "m", "mm"),
    "work_of_adhesion": (0.0, 10.0, "J m^-2", "mJ m^-2"),
    "max_adhesive_stress": (0.0, 1e11, "Pa", "MPa"),
}


def check_plausible_si(stacklevel=2, **inputs):
    """Warn where SI inputs lie far outside the range of real contacts (a unit slip, most likely).

    Parameters
    ----------
    stacklevel : int
        As for :func:`warnings.warn`, counted from the caller of this function.
    **inputs : array_like
        ``name=value`` pairs, each name starting with a key of :data:`PLAUSIBLE_SI_RANGES`
        (``youngs_modulus_1``, ``cylinder_radius`` is a ``radius`` ...); values in SI units.

    Warns
    -----
    dhfield.analysis.validity.ImplausibleInputWarning
        One warning naming every implausible input, its value and the unit it was
        probably meant in ("did you mean MPa, mm or mJ?").  The inputs are used as given.
    """
    import warnings

    said = []
    for name, value in inputs.items():
        key = next(k for k in PLAUSIBLE_SI_RANGES if k in name)
        lo, hi, unit, meant = PLAUSIBLE_SI_RANGES[key]
        v = np.asarray(value, dtype=float)
        low, high = v < lo, v > hi
        if np.any(low):
            said.append(f"{name} = {float(v[low].flat[0]):.4g} {unit} is below {lo:g} {unit}")
        if np.any(high):
            said.append(f"{name} = {float(v[high].flat[0]):.4g} {unit} is above {hi:g} {unit}")
        if np.any(low | high):
            said[-1] += f" (did you mean {meant}?)"
    if said:
        warnings.warn("implausible SI input: " + "; ".join(said) + "; inputs are in SI units (Pa, m, J m^-2); "
                      "the result is computed as given", ImplausibleInputWarning, stacklevel=stacklevel + 1)


@dataclass(frozen=True)
class ContactParameters:
    """Derived parameters of an adhesive elliptical contact (SI); floats or arrays.

    Parameters
    ----------
    reduced_modulus : float or ndarray
        E* [Pa] (Eq. 6).
    r_major, r_minor : float or ndarray
        Principal relative radii R' >= R'' [m] (Eqs. 3-4).
    effective_radius : float or ndarray
        R [m] (Eq. 5).
    beta0 : float or ndarray
        Hertz ellipticity [-] (Eq. 9).
    sin_skew : float or ndarray
        The sin(theta_skew) of beta0 [-].
    mu : float or ndarray
        Tabor parameter [-] (Eq. 35).
    length_unit : float or ndarray
        The length scale c_r [m] (Eq. 33).
    approach_unit : float or ndarray
        The approach scale c_r^2/R [m].
    load_unit : float or ndarray
        The load scale 2 pi R dgamma / sin(theta_skew) [N] (Eq. 34).
    work_of_adhesion : float or ndarray
        Delta gamma [J m^-2].
    max_adhesive_stress : float or ndarray
        The peak adhesive stress sigma0 [Pa].
    """
    reduced_modulus: float
    r_major: float
    r_minor: float
    effective_radius: float
    beta0: float
    sin_skew: float
    mu: float
    length_unit: float
    approach_unit: float
    load_unit: float
    work_of_adhesion: float = float("nan")
    max_adhesive_stress: float = float("nan")


#: The smallest crossing angle of the models' domain, beta0 >= 1e-4 [rad].
_SKEW_ANGLE_MIN = float(geometry.skew_angle(ELLIPTICITY_RANGE[0], checked=False))


def _reduced_modulus(e1, nu1, e2, nu2):
    e1 = check_positive("youngs_modulus_1", e1, "Pa")
    e2 = check_positive("youngs_modulus_2", e2, "Pa")
    nu1 = check_interval("poisson_ratio_1", nu1, -1.0, 0.5, what="Poisson's ratio")
    nu2 = check_interval("poisson_ratio_2", nu2, -1.0, 0.5, what="Poisson's ratio")
    return geometry.reduced_modulus(e1, nu1, e2, nu2, checked=False)  # Eq. (6)


def crossed_cylinder_radii(radius_1, radius_2, skew_angle):
    """Compute the principal relative radii R' >= R'' of two cylinders crossed at an angle.

    Parameters
    ----------
    radius_1, radius_2 : array_like
        Radii of the two cylinders, > 0 [m].
    skew_angle : array_like
        Angle theta_skew between the cylinder axes, in (0, pi/2] [rad].

    Returns
    -------
    r_major : ndarray or float
        R' [m].
    r_minor : ndarray or float
        R'' <= R' [m].

    Notes
    -----
    Johnson (1985) [1]_, Sec. 4.2, Eqs. (4.2)-(4.3), with 1/R1'' = 1/R2'' = 0 for
    cylinders and A = 1/(2R'), B = 1/(2R''):

    .. math::

        \\frac{1}{R'} + \\frac{1}{R''} = \\frac{1}{R_1} + \\frac{1}{R_2}, \\qquad
        \\frac{1}{R''} - \\frac{1}{R'} = \\sqrt{\\frac{1}{R_1^2} + \\frac{1}{R_2^2}
            + \\frac{2\\cos 2\\theta}{R_1 R_2}}

    For R1 = R2 = R_c this is the paper's Eqs. (3)-(4), R' = R_c/(1 - cos theta),
    R'' = R_c/(1 + cos theta); at theta = pi/2, R' = max(R1, R2), R'' = min(R1, R2).

    References
    ----------
    .. [1] K. L. Johnson, Contact Mechanics, Cambridge University Press (1985),
       doi:10.1017/CBO9781139171731
    """
    k1 = 1.0 / check_positive("radius_1", radius_1, "m")
    k2 = 1.0 / check_positive("radius_2", radius_2, "m")
    th = check_interval("skew_angle", skew_angle, 0.0, np.pi / 2, what="rad")
    total = k1 + k2  # Johnson (4.2): 2(A + B)
    diff = np.sqrt(np.maximum(k1 * k1 + k2 * k2 + 2.0 * k1 * k2 * np.cos(2.0 * th), 0.0))  # (4.3): 2(B - A)
    with np.errstate(divide="ignore"):
        r_major = 2.0 / (total - diff)  # 1/R' = 2A; infinite for parallel equal cylinders
    r_minor = 2.0 / (total + diff)  # 1/R'' = 2B
    return _s(r_major), _s(r_minor)


def contact_parameters_from_principal_radii(youngs_modulus_1, poisson_ratio_1, youngs_modulus_2,
                                            poisson_ratio_2, r_major, r_minor, work_of_adhesion,
                                            max_adhesive_stress):
    """Compute the nondimensional groups and scales of a contact of principal relative radii R', R''.

    Parameters
    ----------
    youngs_modulus_1 : array_like
        Young's modulus E1 > 0 of the first body [Pa].
    poisson_ratio_1 : array_like
        Poisson's ratio of the first body, in (-1, 0.5] [-].
    youngs_modulus_2 : array_like
        Young's modulus E2 > 0 of the second body [Pa].
    poisson_ratio_2 : array_like
        Poisson's ratio of the second body, in (-1, 0.5] [-].
    r_major, r_minor : array_like
        Principal relative radii R', R'' > 0 of the gap z = x^2/(2R') + y^2/(2R'')
        [m]; given in either order (the larger is R').
    work_of_adhesion : array_like
        Delta gamma > 0 [J m^-2].
    max_adhesive_stress : array_like
        Peak adhesive stress sigma0 > 0 [Pa].

    Returns
    -------
    ContactParameters
        Floats for scalar inputs, arrays broadcast over all inputs otherwise.

    Warns
    -----
    dhfield.analysis.validity.ImplausibleInputWarning
        Where an input lies outside :data:`PLAUSIBLE_SI_RANGES` (:func:`check_plausible_si`).
    """
    return _contact_parameters(youngs_modulus_1, poisson_ratio_1, youngs_modulus_2, poisson_ratio_2, r_major, r_minor,
                               work_of_adhesion, max_adhesive_stress, None)


def _contact_parameters(youngs_modulus_1, poisson_ratio_1, youngs_modulus_2, poisson_ratio_2, r_major, r_minor,
                        work_of_adhesion, max_adhesive_stress, input_radius):
    """:func:`contact_parameters_from_principal_radii`; ``input_radius``: the (name, value) of the radius the
    user gave (checked for plausibility instead of the smaller principal radius), or None."""
    e_star = _reduced_modulus(youngs_modulus_1, poisson_ratio_1, youngs_modulus_2, poisson_ratio_2)
    r1 = check_positive("r_major", r_major, "m")
    r2 = check_positive("r_minor", r_minor, "m")
    w = check_positive("work_of_adhesion", work_of_adhesion, "J m^-2")
    s0 = check_positive("max_adhesive_stress", max_adhesive_stress, "Pa")
    r1, r2 = np.maximum(r1, r2), np.minimum(r1, r2)

    with np.errstate(over="ignore"):
        ratio = r1 / r2
    if not np.all(np.isfinite(ratio)):
        raise ValueError(f"r_major/r_minor must be finite (principal radii of one contact); got R' = {float(np.max(r1)):g}, "
                         f"R'' = {float(np.min(r2)):g}")
    # validated above: the radii (> 0, a finite ratio >= 1), E*, dgamma and sigma0
    r = geometry.effective_radius(r1, r2, checked=False)  # Eq. (5)
    beta0 = geometry.ellipticity_from_radius_ratio(ratio, checked=False)  # Eq. (9)
    sin_skew = geometry.sin_skew_angle(beta0, checked=False)
    e_star, r1, r2, r, beta0, sin_skew, w, s0 = np.broadcast_arrays(e_star, r1, r2, r, beta0, sin_skew, w, s0)
    mu = units.tabor_parameter(s0, r, e_star, w, checked=False)  # Eq. (35)
    _check_model_domain(ratio, beta0, mu, s0)
    # valid, but perhaps in the wrong units.  The smaller principal radius R'' is within a factor 2 of
    # the cylinders' (Johnson 4.2-4.3); R' grows without bound as the crossing angle closes.
    name, radius = input_radius if input_radius is not None else ("radius R'' (r_minor)", r2)
    moduli = {"youngs_modulus_1": youngs_modulus_1}
    if not np.array_equal(youngs_modulus_2, youngs_modulus_1):  # one material: one message
        moduli["youngs_modulus_2"] = youngs_modulus_2
    check_plausible_si(stacklevel=3, **moduli, **{name: radius}, work_of_adhesion=w, max_adhesive_stress=s0)
    return ContactParameters(
        _s(e_star), _s(r1), _s(r2), _s(r), _s(beta0), _s(sin_skew), _s(mu),
        _s(units.length_unit(r, e_star, w, checked=False)),  # Eq. (33)
        _s(units.approach_unit(r, e_star, w, checked=False)),
        _s(units.load_unit(r, w, sin_skew, checked=False)),  # Eq. (34)
        _s(w), _s(s0))


def _check_model_domain(ratio, beta0, mu, s0):
    """Name the SI input behind a beta0 or mu outside the models' domain."""
    if np.any(beta0 < ELLIPTICITY_RANGE[0]):
        raise ValueError(f"r_major/r_minor must be at most {float(geometry.radius_ratio(ELLIPTICITY_RANGE[0])):.6g} "
                         f"(beta0 >= {ELLIPTICITY_RANGE[0]:g}; longer contacts are line contacts); "
                         f"got {float(np.max(ratio)):.6g}")
    lo, hi = TABOR_RANGE
    bad = (mu < lo) | (mu > hi)
    if np.any(bad):
        with np.errstate(divide="ignore", invalid="ignore"):
            scale = np.broadcast_to(s0 / mu, np.shape(bad))[bad].flat[0]  # sigma0 per unit mu [Pa]
        if not (np.isfinite(scale) and 0.0 < scale < np.inf and np.isfinite(hi * scale) and lo * scale > 0.0):
            # No sigma0 can help: E*, the work of adhesion or the radii are themselves extreme.
            raise ValueError(f"youngs_modulus, work_of_adhesion and the radii give a Tabor parameter mu "
                             f"(Eq. (35)) outside [{lo:g}, {hi:g}] for every max_adhesive_stress; got mu = "
                             f"{float(np.broadcast_to(mu, np.shape(bad))[bad].flat[0]):.6g} "
                             f"(check the inputs' units: Pa, J m^-2, m)")
        raise ValueError(f"max_adhesive_stress must be in [{lo * scale:.6g}, {hi * scale:.6g}] Pa here "
                         f"(Tabor parameter mu of Eq. (35) in [{lo:g}, {hi:g}]); "
                         f"got {float(np.broadcast_to(s0, np.shape(bad))[bad].flat[0])!r}")


def contact_parameters(youngs_modulus_1, poisson_ratio_1, youngs_modulus_2, poisson_ratio_2,
                       cylinder_radius, skew_angle, work_of_adhesion, max_adhesive_stress):
    """Compute the nondimensional groups and scales of two equal crossed cylinders.

    Parameters
    ----------
    youngs_modulus_1 : array_like
        Young's modulus E1 > 0 of the first body [Pa].
    poisson_ratio_1 : array_like
        Poisson's ratio of the first body, in (-1, 0.5] [-].
    youngs_modulus_2 : array_like
        Young's modulus E2 > 0 of the second body [Pa].
    poisson_ratio_2 : array_like
        Poisson's ratio of the second body, in (-1, 0.5] [-].
    cylinder_radius : array_like
        Radius R_c of both cylinders [m].
    skew_angle : array_like
        Crossing angle theta_skew in (0, pi/2] [rad].
    work_of_adhesion : array_like
        Delta gamma > 0 [J m^-2].
    max_adhesive_stress : array_like
        Peak adhesive stress sigma0 > 0 [Pa].

    Returns
    -------
    ContactParameters
        Floats for scalar inputs, arrays broadcast over all inputs otherwise.

    Warns
    -----
    dhfield.analysis.validity.ImplausibleInputWarning
        Where an input lies outside :data:`PLAUSIBLE_SI_RANGES` (:func:`check_plausible_si`).
    """
    th_min = _SKEW_ANGLE_MIN
    th = check_interval("skew_angle", skew_angle, th_min, np.pi / 2, low_open=False,
                        what=f"rad; below {th_min:.4g} rad the contact is a line contact, "
                             f"beta0 < {ELLIPTICITY_RANGE[0]:g}")
    rc = check_positive("cylinder_radius", cylinder_radius, "m")
    with np.errstate(divide="ignore"):  # R' = inf for a vanishing angle: rejected below, by name
        r1, r2 = geometry.principal_radii(rc, th, checked=False)  # Eqs. (3)-(4)
    if not np.all(np.isfinite(r1)):
        raise ValueError(f"cylinder_radius must be finite after Eq. (3), R' = R_c/(1 - cos theta_skew) < "
                         f"{np.finfo(float).max:.4g} m; got {float(np.max(cylinder_radius))!r}")
    return _contact_parameters(youngs_modulus_1, poisson_ratio_1, youngs_modulus_2, poisson_ratio_2, r1, r2,
                               work_of_adhesion, max_adhesive_stress, ("cylinder_radius", rc))


def _si_inputs(params):
    return {"work_of_adhesion": params.work_of_adhesion, "max_adhesive_stress": params.max_adhesive_stress,
            "reduced_modulus": params.reduced_modulus, "r_major": params.r_major, "r_minor": params.r_minor,
            "effective_radius": params.effective_radius}


def pull_off_force(params: ContactParameters, model=compare.DEFAULT_MODEL, control="load", *,
                   check_closure=True, warn=True):
    """Pull-off of a contact in SI units, for any model.

    Parameters
    ----------
    params : ContactParameters
        From :func:`contact_parameters` or :func:`contact_parameters_from_principal_radii`
        (scalars or arrays).
    model : str
        One of :data:`dhfield.analysis.compare.MODEL_NAMES`; default the recommended ``md-elliptic``
        (:data:`dhfield.analysis.compare.DEFAULT_MODEL`).
    control : {'load', 'displacement'}
        Loading mode.

    Returns
    -------
    dhfield.core.records.PullOff
        The keys of :data:`dhfield.core.schema.PULL_OFF_SI_KEYS`, in that order, for
        every model: ``force`` [N] (negative: tensile), ``semi_major``,
        ``semi_minor``, ``adhesive_semi_major``, ``adhesive_semi_minor``,
        ``approach`` [m] (NaN where the model has no such quantity), the SI
        inputs, and the nondimensional record of the model.

    Other Parameters
    ----------------
    check_closure : bool
        For ``dh-elliptic``: compare with the recommended model and fill ``warning``
        (:func:`dhfield.analysis.compare.pull_off`).
    warn : bool
        Also raise a non-empty ``warning`` as a Python warning (as :func:`dhfield.analysis.compare.pull_off`);
        False leaves it in the record only.

    Warns
    -----
    dhfield.analysis.validity.OutsideVerifiedDomainWarning
        Where the record's ``warning`` is not empty (with ``warn``).
    """
    rec = compare.pull_off(model, mu=params.mu, beta0=params.beta0, control=control, check_closure=check_closure,
                           warn=False)
    if warn:
        warn_record(rec, stacklevel=2)  # pointing at the caller of this function
    return pull_off_record_si(rec, params)


def pull_off_record_si(rec, params: ContactParameters):
    """A nondimensional pull-off record of :mod:`dhfield.analysis.compare` in SI units.

    Parameters
    ----------
    rec : dhfield.core.records.PullOff
        From :func:`dhfield.analysis.compare.pull_off` or :func:`dhfield.analysis.compare.compare`, at
        ``params.mu`` and ``params.beta0``.
    params : ContactParameters
        The contact the record was computed for.

    Returns
    -------
    dhfield.core.records.PullOff
        The keys of :data:`dhfield.core.schema.PULL_OFF_SI_KEYS` (see :func:`pull_off_force`).

    Notes
    -----
    Inverts Eqs. (32)-(34): W = W* 2 pi R dgamma/sin(theta_skew), a = a* c_r,
    delta = delta* c_r^2/R, with the record's own sin(theta_skew)
    (:func:`dhfield.core.units.pull_off_si`, the one conversion of every model).
    """
    return units.pull_off_si(rec, _si_inputs(params))


def load_curve_si(params: ContactParameters, semi_major=None, n=200, *, model=compare.DEFAULT_MODEL,
                  force=None):
    """Load curve of a contact in SI units, over contact sizes or over loads.

    Parameters
    ----------
    params : ContactParameters
        From :func:`contact_parameters` (scalar parameters).
    semi_major : array_like, optional
        Contact semi-major axes a > 0 [m]; default ``n`` points of the model's
        default grid.
    n : int
        Number of points of the default grid.
    model : str
        One of :data:`dhfield.analysis.compare.CURVE_MODEL_NAMES`; default the recommended
        ``md-elliptic``.
    force : array_like, optional
        Loads W [N] (positive compressive), each at least the pull-off force:
        the curve is then evaluated on its stable branch at these loads
        (:func:`dhfield.analysis.compare.load_curve_at_load`).  Give ``semi_major`` or
        ``force``, not both.

    Returns
    -------
    dhfield.core.records.LoadCurve
        The SI curve: the scalar keys of :data:`dhfield.core.schema.LOAD_CURVE_HEADER_KEYS`, then the
        arrays of :data:`dhfield.core.schema.LOAD_CURVE_SI_KEYS`: ``semi_major``,
        ``semi_minor``, ``adhesive_semi_major``, ``adhesive_semi_minor`` [m], ``v``
        [-], ``force`` W [N] (positive compressive), ``approach`` delta [m].
    """
    if semi_major is not None and force is not None:
        raise ValueError("semi_major and force are alternatives: give one of them, not both")
    if np.ndim(params.mu) or np.ndim(params.beta0):
        raise ValueError("params of a load curve must be scalars; got array-valued ContactParameters")
    lu = params.length_unit
    if force is not None:
        f = np.asarray(force, dtype=float)
        sin_skew = 1.0 if model in compare.CIRCULAR_MODEL_NAMES else params.sin_skew
        unit = units.load_unit(params.effective_radius, params.work_of_adhesion, sin_skew)  # Eq. (34)
        if model in compare.CURVE_MODEL_NAMES and f.size and np.all(np.isfinite(f)):
            # the stable branch starts at the pull-off: say so in newtons (the caller's unit), not in W*
            w_po = float(compare.MODELS[model](np.asarray(params.beta0), np.asarray(params.mu),
                                               control="load")["W_star"]) * float(unit)
            if float(np.min(f)) < w_po:
                raise ValueError(f"force must be at least the pull-off force {w_po:.6g} N of {model} (the stable "
                                 f"branch starts there); got min {float(np.min(f)):.6g} N")
        c = compare.load_curve_at_load(model, mu=params.mu, beta0=params.beta0, w_star=f / unit)
    else:
        a_star = None if semi_major is None else check_positive("semi_major", semi_major, "m") / lu
        c = compare.load_curve(model, mu=params.mu, beta0=params.beta0, a_star=a_star, n=n)
    unit = units.load_unit(params.effective_radius, params.work_of_adhesion, c["sin_skew"])
    arrays = {
        "semi_major": c["a_star"] * lu, "semi_minor": c["b_star"] * lu,  # Eq. (32)
        "adhesive_semi_major": c["c_star"] * lu, "adhesive_semi_minor": c["d_star"] * lu,
        "v": c["v"], "force": c["W_star"] * unit,  # Eq. (34)
        "approach": c["delta_star"] * params.approach_unit,
    }
    return load_curve_record(c.model, c.beta0, c.mu, arrays, sin_skew=c.sin_skew, geometry=c.geometry)
