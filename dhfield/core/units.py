"""Shared plumbing of the comparison models (JKR, DMT, MD, DH circular, elliptical JKR).

Units
-----
Every comparison model has a private nondimensional core in the units of the
paper (Eqs. 32-35): with the equivalent radius R, the reduced modulus E* and the
work of adhesion dgamma,

* lengths in ``c_r = (R^2 dgamma/E*)^(1/3)`` (Eq. 33): ``a* = a/c_r``;
* approaches in ``c_r^2/R = (R dgamma^2/E*^2)^(1/3)``: ``delta* = delta R/c_r^2``
  (the Hertz approach a^2/R becomes a*^2);
* loads in ``2 pi R dgamma / sin(theta_skew)`` (Eq. 34): ``W* = W sin(theta_skew)/(2 pi R dgamma)``,
  with sin(theta_skew) = 1 for the circle;
* the transition parameter ``mu = sigma0 (R/(E*^2 dgamma))^(1/3)`` (Eq. 35).

With R = E* = dgamma = 1 the nondimensional lengths are the dimensional ones.
The dimensional public wrappers convert with :func:`length_unit`,
:func:`approach_unit` and :func:`load_unit`; every model's SI ``load_curve`` and
``pull_off`` go through :func:`si_circular_load_curve` (or :func:`si_curve`) and
:func:`si_pull_off`.
"""
from __future__ import annotations

import numpy as np

from .validation import check_control, check_interval, check_positive, check_tabor
from .records import load_curve_record, pull_off_record_si
from ._docstrings import fill_doc

__all__ = ["check_material", "check_contact_size", "length_unit", "approach_unit", "load_unit", "tabor_parameter",
           "SI_INPUT_KEYS", "pull_off_si", "si_inputs", "si_pull_off", "si_curve", "si_circular_load_curve",
           "scalar_or_array"]


@fill_doc
def check_material(effective_radius, reduced_modulus, work_of_adhesion):
    """Validate the material and geometry inputs R, E*, dgamma (each finite and > 0).

    Parameters
    ----------
    %(effective_radius)s
    %(reduced_modulus)s
    %(work_of_adhesion)s

    Returns
    -------
    tuple of numpy.ndarray
        R [m], E* [Pa], dgamma [J/m^2] as float arrays.

    Raises
    ------
    ValueError
        If any input is not finite and > 0; the message names it.
    """
    r = check_positive("effective_radius", effective_radius, "m")
    e = check_positive("reduced_modulus", reduced_modulus, "Pa")
    w = check_positive("work_of_adhesion", work_of_adhesion, "J/m^2")
    return r, e, w


def check_contact_size(name, value):
    """Validate a contact radius (nondimensional or SI): finite and >= 0.

    Parameters
    ----------
    name : str
        The parameter's name, as the caller spells it; it starts the error message.
    value : array_like
        The contact radius [m] or [-].

    Returns
    -------
    numpy.ndarray
        ``value`` as a float array.

    Raises
    ------
    ValueError
        If ``value`` is negative or not finite.
    """
    return check_interval(name, value, 0.0, np.inf, low_open=False, high_open=True,
                          what="contact radius, >= 0")


@fill_doc
def length_unit(effective_radius, reduced_modulus, work_of_adhesion, *, checked=True):
    """Compute the length unit c_r = (R^2 dgamma/E*)^(1/3) of Eq. (33) [m].

    Parameters
    ----------
    %(effective_radius)s
    %(reduced_modulus)s
    %(work_of_adhesion)s
    %(material_units_checked)s

    Returns
    -------
    numpy.ndarray
        The length unit c_r [m].
    """
    args = (effective_radius, reduced_modulus, work_of_adhesion)
    return _length(*(check_material(*args) if checked else args))


@fill_doc
def approach_unit(effective_radius, reduced_modulus, work_of_adhesion, *, checked=True):
    """Compute the approach unit c_r^2/R = (R dgamma^2/E*^2)^(1/3), the unit of delta* [m].

    Parameters
    ----------
    %(effective_radius)s
    %(reduced_modulus)s
    %(work_of_adhesion)s
    %(material_units_checked)s

    Returns
    -------
    numpy.ndarray
        The approach unit c_r^2/R [m].
    """
    args = (effective_radius, reduced_modulus, work_of_adhesion)
    return _approach(*(check_material(*args) if checked else args))


def load_unit(effective_radius, work_of_adhesion, sin_skew=1.0, *, checked=True):
    """Compute the load unit 2 pi R dgamma / sin(theta_skew) of Eq. (34) [N].

    Parameters
    ----------
    effective_radius : array_like
        Equivalent radius R [m].
    work_of_adhesion : array_like
        Work of adhesion dgamma [J/m^2].
    sin_skew : array_like, optional
        The sine of the skew angle theta_skew of the geometry (Eq. 34), 1 for the circle [-].
    checked : bool, optional
        Validate R and dgamma (finite, > 0); False on inputs validated already.

    Returns
    -------
    numpy.ndarray
        The load unit [N].
    """
    if not checked:
        return _load(effective_radius, work_of_adhesion, sin_skew)
    r = check_positive("effective_radius", effective_radius, "m")
    w = check_positive("work_of_adhesion", work_of_adhesion, "J/m^2")
    return _load(r, w, sin_skew)


def _length(r, e, w):
    return np.cbrt(r * r * w / e)  # Eq. (33)


def _approach(r, e, w):
    return np.cbrt(r * w * w / (e * e))


def _load(r, w, sin_skew):
    return 2.0 * np.pi * r * w / np.asarray(sin_skew, dtype=float)  # Eq. (34)


#: The SI inputs of a pull-off record (:data:`dhfield.core.schema.PULL_OFF_SI_KEYS`), in order.
SI_INPUT_KEYS = ("work_of_adhesion", "max_adhesive_stress", "reduced_modulus", "r_major", "r_minor",
                 "effective_radius")


def pull_off_si(rec, inputs):
    """Convert a nondimensional pull-off record to the one SI record (Eqs. 32-34 inverted).

    Parameters
    ----------
    rec : dhfield.core.records.PullOff
        The nondimensional pull-off record of a model (with its own ``sin_skew``).
    inputs : dict
        :data:`SI_INPUT_KEYS` mapped to validated values (:func:`si_inputs`): dgamma [J/m^2],
        sigma0 [Pa] or NaN, E* [Pa], R', R'', R [m].

    Returns
    -------
    dhfield.core.records.PullOff
        The record with its SI group: W = W* 2 pi R dgamma/sin(theta_skew) [N] (Eq. 34),
        a = a* c_r, b = b* c_r, c = c* c_r, d = d* c_r [m] (Eqs. 32-33), delta = delta* c_r^2/R [m].
    """
    r, e, w = inputs["effective_radius"], inputs["reduced_modulus"], inputs["work_of_adhesion"]
    lu, au = _length(r, e, w), _approach(r, e, w)
    si = {
        "force": rec["W_star"] * _load(r, w, rec["sin_skew"]),  # Eq. (34)
        "semi_major": rec["a_star"] * lu, "semi_minor": rec["b_star"] * lu,  # Eq. (32)
        "adhesive_semi_major": rec["c_star"] * lu, "adhesive_semi_minor": rec["d_star"] * lu,
        "approach": rec["delta_star"] * au,
    }
    return pull_off_record_si(rec, {**si, **{k: inputs[k] for k in SI_INPUT_KEYS}})


def si_inputs(r, e, w, max_adhesive_stress=float("nan"), radius_ratio=1.0):
    """Collect the SI inputs of :func:`pull_off_si` from validated R, E*, dgamma.

    Parameters
    ----------
    r : array_like
        Equivalent radius R = sqrt(R'R''), validated [m].
    e : array_like
        Reduced modulus E*, validated [Pa].
    w : array_like
        Work of adhesion dgamma, validated [J/m^2].
    max_adhesive_stress : array_like, optional
        Peak adhesive stress sigma0; NaN for the models that have none [Pa].
    radius_ratio : array_like, optional
        R'/R'' >= 1, 1 for the circle [-].

    Returns
    -------
    dict
        :data:`SI_INPUT_KEYS` mapped to their values, with R' = R sqrt(rho) and
        R'' = R/sqrt(rho) (Eq. 5) [m].
    """
    sq = np.sqrt(np.asarray(radius_ratio, dtype=float))
    return {"work_of_adhesion": w, "max_adhesive_stress": np.asarray(max_adhesive_stress, dtype=float),
            "reduced_modulus": e, "r_major": r * sq, "r_minor": r / sq, "effective_radius": r}


@fill_doc
def si_pull_off(core, effective_radius, reduced_modulus, work_of_adhesion, max_adhesive_stress=None, *,
                control="load", radius_ratio=1.0, beta0=1.0, check_mu=False):
    """Compute the SI pull-off record of a model from its nondimensional core (inputs validated here).

    The one SI ``pull_off`` of every analytic model: checks ``control``, R, E*, dgamma (and
    sigma0 where given), evaluates ``core(beta0, mu, control=control)`` over the broadcast shape
    of the inputs and converts the record with :func:`pull_off_si`.

    Parameters
    ----------
    core : callable
        The model's ``pull_off_nondimensional(beta0, mu, *, control)``, returning a
        :class:`dhfield.core.records.PullOff` in the paper's units.
    effective_radius : array_like
        Equivalent radius R = sqrt(R'R'') [m].
    reduced_modulus : array_like
        Reduced modulus E* [Pa].
    work_of_adhesion : array_like
        Work of adhesion dgamma [J/m^2].
    max_adhesive_stress : array_like, optional
        Peak adhesive stress sigma0 [Pa]; the core then gets mu of Eq. (35).  None for the
        models without one (JKR, DMT, elliptical JKR): mu is NaN.
    %(control)s
    radius_ratio : array_like, optional
        R'/R'' >= 1 of the geometry, validated; 1 for the circle [-].
    beta0 : array_like, optional
        Hertz ellipticity of the geometry, validated; 1 for the circle [-].
    check_mu : bool, optional
        Check mu against :data:`dhfield.core.validation.TABOR_RANGE`.

    Returns
    -------
    dhfield.core.records.PullOff
        The pull-off record with its SI group (:func:`pull_off_si`).

    Raises
    ------
    ValueError
        On a bad ``control``, R, E*, dgamma or sigma0 (or mu, with ``check_mu``), named.
    """
    check_control(control)
    r, e, w = check_material(effective_radius, reduced_modulus, work_of_adhesion)
    if max_adhesive_stress is None:
        mu, s0 = float("nan"), float("nan")
    else:
        mu = tabor_parameter(max_adhesive_stress, r, e, w)
        if check_mu:
            check_tabor("mu", mu)
        s0 = np.asarray(max_adhesive_stress, dtype=float)
    inputs = si_inputs(r, e, w, s0, radius_ratio)
    shape = np.broadcast_shapes(*(np.shape(v) for v in inputs.values()), np.shape(beta0), np.shape(mu))
    rec = core(np.broadcast_to(np.asarray(beta0, dtype=float), shape), np.asarray(mu, dtype=float),
               control=control)
    return pull_off_si(rec, inputs)


def si_curve(model, arrays, *, mu=float("nan"), beta0=1.0, sin_skew=1.0, geometry="circle", ellipticity=None):
    """Build the SI :class:`dhfield.core.records.LoadCurve` of a model's SI ``load_curve``.

    Parameters
    ----------
    model : str
        The model's name (as on the CLI).
    arrays : dict
        ``semi_major``, ``force``, ``approach`` [m, N, m] and, where the model has them,
        ``semi_minor``, ``adhesive_semi_major``, ``adhesive_semi_minor`` [m] and ``v`` [-];
        broadcast to one shape (that of the contact sizes and the material inputs together).
    mu : array_like, optional
        Tabor parameter of Eq. (35); NaN for the models that have none (JKR, DMT,
        elliptical JKR) [-].
    beta0 : array_like, optional
        Hertz ellipticity, 1 for the circle [-].
    sin_skew : array_like, optional
        The sine of the skew angle theta_skew of Eq. (34), 1 for the circle [-].
    geometry : {'circle', 'ellipse'}
        The contact's shape.
    ellipticity : array_like, optional
        The contact ellipticity b/a along the curve, for the elliptical models [-].

    Returns
    -------
    dhfield.core.records.LoadCurve
        The SI curve.
    """
    values = np.broadcast_arrays(*(np.asarray(v, dtype=float) for v in arrays.values()))
    return load_curve_record(model, beta0, mu, dict(zip(arrays, values)), sin_skew=sin_skew, geometry=geometry,
                             ellipticity=ellipticity)


@fill_doc
def si_circular_load_curve(model, core, contact_radius, effective_radius, reduced_modulus, work_of_adhesion,
                           max_adhesive_stress=None, *, zone=False, dh_factor=False):
    """Compute the SI load curve of a circular model from its nondimensional core (inputs validated here).

    The one SI ``load_curve`` of the circular models: a* = a/c_r (Eq. 32) into the core,
    W = W* 2 pi R dgamma (Eq. 34, sin_skew = 1), delta = delta* c_r^2/R and the adhesive
    radius c = c* c_r (Eqs. 32-33).

    Parameters
    ----------
    model : str
        The model's name (as on the CLI).
    core : callable
        The model's ``load_curve_nondimensional``: ``core(a_star)``, or ``core(a_star, mu)``
        where ``max_adhesive_stress`` is given, returning ``W_star``, ``delta_star`` and, where
        the model has them, ``c_star`` and ``v`` [-].
    %(contact_radius)s
    %(effective_radius)s
    %(reduced_modulus)s
    %(work_of_adhesion)s
    max_adhesive_stress : array_like, optional
        Peak adhesive stress sigma0 [Pa]; None for the models without one (JKR, DMT).
    zone : bool, optional
        Carry the adhesive radius c (``adhesive_semi_major`` = ``adhesive_semi_minor``).
    dh_factor : bool, optional
        Carry the DH factor ``v``.

    Returns
    -------
    dhfield.core.records.LoadCurve
        The SI curve (:func:`si_curve`); its ``mu`` is that of the inputs, Eq. (35).
    """
    a = check_contact_size("contact_radius", contact_radius)
    r, e, w = check_material(effective_radius, reduced_modulus, work_of_adhesion)
    a_star = a / _length(r, e, w)  # Eq. (32)
    if max_adhesive_stress is None:
        mu, state = float("nan"), core(a_star)
    else:
        mu = tabor_parameter(max_adhesive_stress, r, e, w)
        state = core(a_star, mu)
    arrays = {"semi_major": a}
    if zone:
        c = state["c_star"] * _length(r, e, w)  # Eq. (32)
        arrays.update(adhesive_semi_major=c, adhesive_semi_minor=c)
    if dh_factor:
        arrays["v"] = state["v"]
    arrays.update(force=state["W_star"] * _load(r, w, 1.0),  # Eq. (34)
                  approach=state["delta_star"] * _approach(r, e, w))
    return si_curve(model, arrays, mu=mu)


@fill_doc
def tabor_parameter(max_adhesive_stress, effective_radius, reduced_modulus, work_of_adhesion, *, checked=True):
    """Compute the Tabor (transition) parameter mu = sigma0 (R/(E*^2 dgamma))^(1/3) of Eq. (35) [-].

    Parameters
    ----------
    max_adhesive_stress : array_like
        Peak adhesive stress sigma0 [Pa].
    %(effective_radius)s
    %(reduced_modulus)s
    %(work_of_adhesion)s
    checked : bool, optional
        Validate the inputs (each finite and > 0); False on inputs validated already.

    Returns
    -------
    numpy.ndarray
        The Tabor parameter mu [-]; extreme but finite inputs give 0 or inf (the caller's range check names the input).
    """
    if checked:
        s = check_positive("max_adhesive_stress", max_adhesive_stress, "Pa")
        r, e, w = check_material(effective_radius, reduced_modulus, work_of_adhesion)
    else:
        s, r, e, w = max_adhesive_stress, effective_radius, reduced_modulus, work_of_adhesion
    with np.errstate(over="ignore", under="ignore", divide="ignore"):
        return s * np.cbrt(r / (e * e * w))  # Eq. (35)


def scalar_or_array(x):
    """Return a 0-d result as a numpy scalar, any other as an array.

    Parameters
    ----------
    x : array_like
        A result [any unit].

    Returns
    -------
    numpy.float64 or numpy.ndarray
        ``x`` as float: a scalar for 0-d input, else an array of its shape.
    """
    x = np.asarray(x, dtype=float)
    return x[()] if x.ndim == 0 else x
