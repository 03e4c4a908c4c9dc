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
:func:`approach_unit` and :func:`load_unit`.
"""
from __future__ import annotations

import numpy as np

from .validation import check_control, check_interval, check_positive, check_tabor
from .records import load_curve_record, pull_off_record_si


def check_material(effective_radius, reduced_modulus, work_of_adhesion):
    """Validate R [m], E* [Pa], dgamma [J/m^2]; return them as float arrays."""
    r = check_positive("effective_radius", effective_radius, "m")
    e = check_positive("reduced_modulus", reduced_modulus, "Pa")
    w = check_positive("work_of_adhesion", work_of_adhesion, "J/m^2")
    return r, e, w


def check_contact_size(name, value):
    """Validate a (nondimensional or SI) contact radius: finite and >= 0."""
    return check_interval(name, value, 0.0, np.inf, low_open=False, high_open=True,
                          what="contact radius, >= 0")


def length_unit(effective_radius, reduced_modulus, work_of_adhesion, *, checked=True):
    """c_r = (R^2 dgamma/E*)^(1/3), Eq. (33) [m]; ``checked=False`` on R, E*, dgamma validated already."""
    args = (effective_radius, reduced_modulus, work_of_adhesion)
    return _length(*(check_material(*args) if checked else args))


def approach_unit(effective_radius, reduced_modulus, work_of_adhesion, *, checked=True):
    """c_r^2/R = (R dgamma^2/E*^2)^(1/3) [m], the unit of delta*; ``checked=False`` on validated inputs."""
    args = (effective_radius, reduced_modulus, work_of_adhesion)
    return _approach(*(check_material(*args) if checked else args))


def load_unit(effective_radius, work_of_adhesion, sin_skew=1.0, *, checked=True):
    """2 pi R dgamma / sin(theta_skew), Eq. (34) [N]; sin_skew = 1 for the circle; ``checked=False`` on
    validated R, dgamma."""
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

    ``rec`` is a :class:`dhfield.core.records.PullOff`; ``inputs`` maps :data:`SI_INPUT_KEYS` to
    validated values (R, E*, dgamma, sigma0 or NaN, R', R'').  W = W* 2 pi R dgamma/sin(theta_skew)
    with the record's own sin(theta_skew) (Eq. 34), a = a* c_r and c = c* c_r (Eqs. 32-33),
    delta = delta* c_r^2/R.  Returns a :class:`dhfield.core.records.PullOff` (its SI group).
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
    """The SI inputs of :func:`pull_off_si` from validated R, E*, dgamma (and sigma0, R'/R''):
    R' = R sqrt(rho), R'' = R/sqrt(rho) (Eq. 5), both R for the circle."""
    sq = np.sqrt(np.asarray(radius_ratio, dtype=float))
    return {"work_of_adhesion": w, "max_adhesive_stress": np.asarray(max_adhesive_stress, dtype=float),
            "reduced_modulus": e, "r_major": r * sq, "r_minor": r / sq, "effective_radius": r}


def pull_off_si_of(core, inputs, *, control, beta0=1.0, mu=float("nan")):
    """The SI pull-off record of a model: its nondimensional core ``core(beta0, mu, control=...)``
    (a :class:`dhfield.core.records.PullOff`) over the broadcast shape of the inputs, then
    :func:`pull_off_si`.  ``mu`` NaN for the models that have none (JKR, DMT, elliptical JKR)."""
    shape = np.broadcast_shapes(*(np.shape(v) for v in inputs.values()), np.shape(beta0), np.shape(mu))
    rec = core(np.broadcast_to(np.asarray(beta0, dtype=float), shape), np.asarray(mu, dtype=float),
               control=control)
    return pull_off_si(rec, inputs)


def si_curve(model, arrays, *, mu=float("nan"), beta0=1.0, sin_skew=1.0, geometry="circle", ellipticity=None):
    """The SI :class:`dhfield.core.records.LoadCurve` of a model's SI ``load_curve``.

    ``arrays`` holds ``semi_major``, ``force``, ``approach`` [SI] and, where the model has them,
    ``semi_minor``, ``adhesive_semi_major``, ``adhesive_semi_minor`` [m] and ``v`` [-]; they are
    broadcast to one shape (that of the contact sizes and the material inputs together).
    ``mu`` NaN for the models that have none (JKR, DMT, elliptical JKR); ``beta0`` and
    ``sin_skew`` 1 for the circle.
    """
    values = np.broadcast_arrays(*(np.asarray(v, dtype=float) for v in arrays.values()))
    return load_curve_record(model, beta0, mu, dict(zip(arrays, values)), sin_skew=sin_skew, geometry=geometry,
                             ellipticity=ellipticity)


def si_circular_load_curve(model, core, contact_radius, effective_radius, reduced_modulus, work_of_adhesion,
                           max_adhesive_stress=None, *, zone=False, dh_factor=False):
    """The SI load curve of a circular model from its nondimensional core (inputs validated here).

    ``core(a_star)`` (or ``core(a_star, mu)`` where the model has a Tabor parameter, i.e. where
    ``max_adhesive_stress`` is given) returns the model's nondimensional curve over a/c_r
    (``W_star``, ``delta_star``, and ``c_star``, ``v`` where the model has them).
    W = W* 2 pi R dgamma (Eq. 34, sin_skew = 1), delta = delta* c_r^2/R and, with ``zone``, the
    adhesive radius c = c* c_r (Eqs. 32-33); ``dh_factor`` carries the DH factor v.
    Returns :func:`si_curve`'s record.
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


def si_pull_off(core, effective_radius, reduced_modulus, work_of_adhesion, max_adhesive_stress=None, *,
                control="load", radius_ratio=1.0, beta0=1.0, check_mu=False):
    """The SI pull-off record of a model from its nondimensional core (inputs validated here).

    Checks ``control``, R, E*, dgamma (and sigma0 where given: then mu of Eq. (35) is passed to
    the core, and checked against the Tabor range with ``check_mu``), evaluates
    ``core(beta0, mu, control=...)`` over the broadcast shape of the inputs and converts it with
    :func:`pull_off_si`; ``radius_ratio`` R'/R'' and ``beta0`` 1 for the circle.
    """
    check_control(control)
    r, e, w = check_material(effective_radius, reduced_modulus, work_of_adhesion)
    if max_adhesive_stress is None:
        return pull_off_si_of(core, si_inputs(r, e, w, radius_ratio=radius_ratio), control=control, beta0=beta0)
    mu = tabor_parameter(max_adhesive_stress, r, e, w)
    if check_mu:
        check_tabor("mu", mu)
    s0 = np.asarray(max_adhesive_stress, dtype=float)
    return pull_off_si_of(core, si_inputs(r, e, w, s0, radius_ratio), control=control, beta0=beta0, mu=mu)


def tabor_parameter(max_adhesive_stress, effective_radius, reduced_modulus, work_of_adhesion, *, checked=True):
    """mu = sigma0 (R/(E*^2 dgamma))^(1/3), Eq. (35) [-]; ``checked=False`` on inputs validated already."""
    if checked:
        s = check_positive("max_adhesive_stress", max_adhesive_stress, "Pa")
        r, e, w = check_material(effective_radius, reduced_modulus, work_of_adhesion)
    else:
        s, r, e, w = max_adhesive_stress, effective_radius, reduced_modulus, work_of_adhesion
    with np.errstate(over="ignore", under="ignore", divide="ignore"):
        # extreme but finite inputs give 0 or inf here; the caller's range check names the input
        return s * np.cbrt(r / (e * e * w))  # Eq. (35)


def scalar_or_array(x):
    """Return a 0-d array as a Python-float-like numpy scalar, otherwise the array."""
    x = np.asarray(x, dtype=float)
    return x[()] if x.ndim == 0 else x
