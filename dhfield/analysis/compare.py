"""All comparison models behind one interface, on the axes of the paper's Figs. 8-9.

Every model is reached by name (:data:`MODEL_NAMES`) through :func:`pull_off`,
:func:`compare`, :func:`load_curve` and :func:`load_curve_at_load`; the SI front
end (:mod:`dhfield.analysis.dimensional`) and the command line (``--model``) take the same
names.  Every pull-off record has the keys of :data:`dhfield.core.schema.PULL_OFF_KEYS`,
in that order, for every model, in the paper's normalisation (Eqs. 32-35):

* ``W_star = W sin(theta_skew)/(2 pi R dgamma)`` (Eq. 34), with sin(theta_skew) of
  beta0 for the elliptical models and 1 for the circular ones (``sin_skew`` says
  which); R = sqrt(R'R'').  Positive compressive: pull-off is negative.
* ``a_star``, ``b_star`` are the contact semi-axes (the radius for the circle) in
  c_r = (R^2 dgamma/E*)^(1/3); ``c_star``, ``d_star`` the adhesive-zone semi-axes,
  NaN where the model has none (JKR, DMT, elliptical JKR); ``delta_star`` the
  approach in c_r^2/R.
* ``v`` is the double-Hertz factor of Eq. (22), NaN outside the equal-beta DH
  models (the closures have two independent amplitudes, MD has none).
* ``ellipticity`` b/a and ``adhesive_ellipticity`` d/c at pull-off.
* ``at_zero_contact``: the pull-off is reached as the contact vanishes.
* ``warning``: empty, except outside the model's validated range
  (:data:`VALIDITY_RANGES`; for the recommended model the box of the stored BEM ground
  truth) and, for ``dh-elliptic``, where its pull-off departs from the recommended model
  by more than :data:`WARNING_THRESHOLD` (2 %).  :func:`pull_off` also raises a
  non-empty one as a Python warning, :class:`dhfield.analysis.validity.OutsideVerifiedDomainWarning`.
* mu is the paper's Eq. (35); MD is evaluated at lambda = 1.1272 mu
  (:mod:`dhfield.core.transition`, same sigma0).  JKR, DMT and elliptical JKR do not
  depend on mu.

Models
------
``md-elliptic``
    the recommended model and the default (:data:`RECOMMENDED_MODEL`, the one place that
    names it; every default of the API, the command line, the report and the docs is read
    from there): the sphere's Maugis-Dugdale transition
    carried over to the ellipse between the elliptical DMT (mu -> 0) and the
    energy-minimising elliptical JKR of GVG (mu -> infinity), MD exactly at beta0 = 1;
    within 0.46 % of every stored BEM case — :mod:`dhfield.models.md_elliptic`.
    Named for what it approximates, the elliptical contact with a Dugdale
    (Maugis-Dugdale) law, and apart from the paper's double-Hertz ``dh-elliptic``
    and the two elliptical JKR limits ``jkr-elliptic`` (JG) and ``jkr-elliptic-energy`` (GVG)
``dh-elliptic``
    the paper's model, beta = beta0 throughout, dgamma on the major axis
    (Eqs. 17-19, 31) — :mod:`dhfield.models.dh_elliptic`; to reproduce the paper
``dh-elliptic-two-axis``
    dgamma = 1 on both axes, beta_cd != beta_ab, contact condition exact —
    :func:`dhfield.models.dh_elliptic_closure.pull_off_two_axis`
``dh-elliptic-ray-average``
    equal beta, dgamma = 1 on the periphery average — :func:`dhfield.models.dh_elliptic_closure.pull_off_ray_average`
``dh-elliptic-jkr-beta``
    the paper's second assumption (Fig. 9): beta_(pull-off) = beta_JKR(pull-off)
``dh-circular``
    Greenwood & Johnson (1998) — :mod:`dhfield.models.dh_circular`
``jkr``, ``dmt``
    :mod:`dhfield.models.jkr`, :mod:`dhfield.models.dmt`
``md``
    Maugis (1992) — :mod:`dhfield.models.maugis_dugdale`
``jkr-elliptic``
    Johnson & Greenwood (2005) — :mod:`dhfield.models.jkr_elliptic`
``jkr-elliptic-energy``
    Giudici, Vella & Griffiths (2025), energy minimised over both semi-axes —
    :mod:`dhfield.models.jkr_elliptic_energy`

Every model except ``dh-elliptic-jkr-beta`` (whose ellipticity is defined at
pull-off only) has a load curve (:data:`CURVE_MODEL_NAMES`).

Which model to use when
-----------------------
* **md-elliptic** (the default) for any elliptical or circular contact, crossing
  angles 10-90 deg (beta0 down to 0.047 and below) and any mu: within 0.46 % of every
  stored BEM case (beta0 0.1-1, mu 0.1-10, load control;
  ``python -m verification.elliptic_transition``), exactly DMT as mu -> 0, GVG as
  mu -> infinity and MD at beta0 = 1; under 1 ms per point vectorised.  Outside the
  box of the stored BEM cases (:data:`dhfield.analysis.validity.BEM_VERIFIED_BETA0`,
  :data:`dhfield.analysis.validity.BEM_VERIFIED_MU`) it answers and warns that no BEM case checked
  the point.
* **dh-elliptic** (the paper's) to reproduce the paper.  It under-predicts the
  adhesion increasingly as the contact gets more elliptical and mu larger (table
  below); its records carry a ``warning`` where its pull-off departs from
  ``md-elliptic`` by more than :data:`WARNING_THRESHOLD`.
* **dh-elliptic-two-axis**, **dh-elliptic-ray-average**: the closures of the paper's
  model (dgamma imposed on both axes, or on the periphery average), for comparison;
  about 200 ms per point, beta0 >= 0.3 and mu <= 30 (:mod:`dhfield.models.dh_elliptic_closure`).  The
  two-axis closure tends to elliptical JKR (JG) at high mu.
* **jkr-elliptic-energy** (GVG) for mu >= 10, the exact-energy JKR limit, the one the
  recommended model and the BEM reach as mu -> infinity;
  **jkr-elliptic** (Johnson & Greenwood 2005) to compare with it: JG fixes the contact
  shape by one condition and under-predicts the adhesion of slender contacts (the
  BEM at beta0 = 0.5, mu = 5 is 2.9 % stronger than JG, within 0.4 % of GVG).
* **dh-circular, md, jkr, dmt** for beta0 = 1 (perpendicular equal cylinders or
  spheres); at beta0 < 1 they are the circle of the same R = sqrt(R'R'').
* **dh-elliptic-jkr-beta** only to reproduce the paper's Fig. 9b.

Pull-off W* of the paper's closure and of the alternatives relative to the two-axis
closure, W*_model/W*_two-axis - 1 (load control; ranges over mu = 0.1, 0.3, 1, 3, 10,
30, computed with :func:`pull_off` on that grid; negative: less adhesion than the
two-axis closure):

===========  ==========================  ==========================  ==========================
beta0        dh-elliptic                 dh-elliptic-ray-average     jkr-elliptic
===========  ==========================  ==========================  ==========================
0.99         -0.3 % to -0.5 %            < 0.01 %                    -0.02 % (mu 30) .. -23 % (mu 0.1)
0.95         -1.3 % (mu 0.1) to -2.5 %   < 0.03 %
0.9          -2.7 % to -5.2 %            < 0.1 %
0.8          -5.5 % to -10.7 %           -0.2 % to +0.2 %
0.5          -16 % to -30 %              -1.4 % to +1.9 %
0.3          -25 % to -47 %              -3.9 % to +5.8 %            -0.03 % (mu 30) .. -30 % (mu 0.1)
===========  ==========================  ==========================  ==========================

The JKR-beta variant
--------------------
The paper (Sec. 3, Fig. 9) makes "the ellipticity ratios of both contact and
adhesive ellipses ... equal [to] the ellipticity ratio of the contact area obtained
from the JKR elliptical model", keeping Eq. (18) at pull-off.  It does not say
what else changes.  Here:

* **beta_JKR replaces beta** for the shapes of both ellipses (d/c = b/a = beta_JKR)
  *and* for the Hertz relations Eqs. (8), (11), (20) that tie Po_ab, Po_cd and
  the load to the semi-axes.  Those relations are only geometry-consistent (the
  contact condition holds inside each ellipse) for the curvature ratio whose Hertz
  ellipticity is beta; mixing beta_JKR shapes with beta0 pressures would violate
  the contact condition inside the ellipse.
* **beta0 is kept** for the load normalisation sin(theta_skew) of Eq. (34) and
  for R = sqrt(R'R''): the cylinders, and so the axes of Fig. 9, are unchanged,
  and the variant's W*max is directly comparable with elliptical JKR, whose W*
  also carries sin(theta_skew(beta0)).
* beta_JKR is taken under the same control mode as the pull-off requested.

This is :func:`dhfield.models.dh_elliptic.pull_off` with ``ellipticity=beta_JKR``; at beta0 = 1
it is the paper's model (beta_JKR = 1).
"""
from __future__ import annotations

import numpy as np

from ..core.validation import check_contact_size_star, check_count, check_grid_point
from ..core.geometry import sin_skew_angle
from ..models.dh_elliptic import DEFAULT_A_STAR, MAX_CURVE_POINTS
from .model_error import departure_warning as _disagreement, with_model_error
from ..models.registry import (ABSENT_KEYS, CIRCULAR_MODEL_NAMES, CURVE_MODEL_NAMES, DEFAULT_MODEL, MODEL_NAMES,
                               MODELS, PAPER_MODEL, RECOMMENDED_MODEL, CURVES)
from ..core.records import PullOff, broadcast_field, load_curve_record, pull_off_record
from ..core.schema import LOAD_CURVE_KEYS, PULL_OFF_KEYS, PULL_OFF_TRUST_KEYS

from .validity import (JKR_PROXY_MU, VALIDITY_RANGES, WARNING_THRESHOLD, closure_departure, departure_warning,
                       join_warnings, validity_message, validity_table, warn_record)

__all__ = ["MODELS", "MODEL_NAMES", "CURVE_MODEL_NAMES", "CIRCULAR_MODEL_NAMES", "DEFAULT_MODEL", "RECOMMENDED_MODEL",
           "PAPER_MODEL", "ABSENT_KEYS", "compare", "departure_from_recommended",
           "load_curve", "load_curve_at_load", "pull_off",
           # the validity policy, from dhfield.analysis.validity
           "WARNING_THRESHOLD", "JKR_PROXY_MU", "VALIDITY_RANGES", "closure_departure", "validity_message",
           "validity_table"]

_NAN = float("nan")
def _check(mu, beta0, control):
    beta0, mu = check_grid_point(beta0, mu, control)  # _validation.TABOR_RANGE: every model's accepted domain
    return mu, beta0


def _warned(rec, warning=""):
    """``rec`` with its validity warning (:mod:`dhfield.analysis.validity`) joined to ``warning``."""
    return rec.replace(warning=broadcast_field(join_warnings(warning, validity_message(rec.model, rec.mu, rec.beta0)),
                                    np.shape(rec.W_star), object))


def _pull_off(name, beta0, mu, control, *, check_closure=True, reference=None):
    """Pull-off record of a model on validated inputs, with its warnings."""
    rec = MODELS[name](beta0, mu, control=control)
    warning = ""
    if name == "dh-elliptic" and check_closure:
        # its departure from the recommended model (reference: its W* where the caller has it)
        warning = departure_warning(rec.W_star, mu, beta0, control, reference)
    return with_model_error(_warned(rec, warning))


def _failed(name, beta0, mu, control, exc):
    """The NaN record of a model that refused (beta0, mu) or failed to converge there, saying why."""
    shape = np.broadcast_shapes(np.shape(beta0), np.shape(mu))
    nan = np.full(shape, _NAN)
    st = {"W_star": nan, "a_star": nan, "b_star": nan, "c_star": nan, "delta_star": nan, "ellipticity": nan,
          "at_zero_contact": np.zeros(shape, bool)}
    circle = name in CIRCULAR_MODEL_NAMES
    return with_model_error(_warned(pull_off_record(name, beta0, mu, st, control=control,
                                                    sin_skew=1.0 if circle else sin_skew_angle(beta0),
                                                    geometry="circle" if circle else "ellipse"),
                                    f"{name} failed: {exc}"))


def _pull_off_pointwise(name, beta0, mu, control, **kwargs):
    """Pull-off of a model over arrays, point by point: NaN and the reason where it refuses a point."""
    b, m = np.broadcast_arrays(beta0, mu)
    recs = []
    for bi, mi in zip(b.ravel(), m.ravel()):
        try:
            recs.append(_pull_off(name, bi, mi, control, **kwargs))
        except (ValueError, RuntimeError) as exc:
            recs.append(_failed(name, bi, mi, control, exc))
    text = {"model", "control", "geometry"}
    dtypes = {"warning": object, "at_zero_contact": bool, "bem_verified": bool}
    return PullOff(**{k: recs[0][k] if k in text else
                      np.array([r[k] for r in recs], dtype=dtypes.get(k, float)).reshape(b.shape)
                      for k in PULL_OFF_KEYS + PULL_OFF_TRUST_KEYS})


def _pull_off_guarded(name, beta0, mu, control, **kwargs):
    """:func:`_pull_off`; where the model refuses (part of) the inputs, NaN and the reason at those points."""
    try:
        return _pull_off(name, beta0, mu, control, **kwargs)
    except (ValueError, RuntimeError) as exc:
        if np.broadcast(beta0, mu).ndim == 0:
            return _failed(name, beta0, mu, control, exc)
        return _pull_off_pointwise(name, beta0, mu, control, **{k: v for k, v in kwargs.items()
                                                                  if k != "reference"})


def _check_model(model):
    if model not in MODELS:
        raise ValueError(f"model must be one of {', '.join(MODEL_NAMES)}; got {model!r}")
    return model


def pull_off(model=DEFAULT_MODEL, *, beta0, mu, control="load", check_closure=True, warn=True):
    """Compute the pull-off of one model, in the paper's normalisation (Eq. 34).

    Parameters
    ----------
    model : str
        One of :data:`MODEL_NAMES`; default the recommended model (:data:`DEFAULT_MODEL`).
        ``"dh-elliptic"`` is the paper's model.
    beta0 : array_like
        Hertz ellipticity b/a of the geometry, in (0, 1] [-] (keyword-only, as ``mu``).
    mu : array_like
        Transition parameter of Eq. (35), > 0 [-].
    control : {'load', 'displacement'}
        Loading mode.

    Returns
    -------
    dhfield.core.records.PullOff
        The record of every model: the keys of :data:`dhfield.core.schema.PULL_OFF_KEYS`,
        in that order, then the trust group :data:`dhfield.core.schema.PULL_OFF_TRUST_KEYS`
        (``model_error``, the estimated relative error of W* against the BEM ground
        truth, and ``bem_verified``; :mod:`dhfield.analysis.model_error`), as attributes or a
        mapping; NaN where a quantity does not apply (module docstring).  Arrays
        broadcast over ``mu`` and ``beta0``; scalars in give scalars out.  Over arrays,
        a point the model refuses (a narrower domain of its own, such as the closures'
        beta0 >= 0.3) or fails to converge at gets NaN values and the reason in
        ``warning``, and the other points their answers.

    Other Parameters
    ----------------
    check_closure : bool
        For ``dh-elliptic`` only: also evaluate the recommended model ``md-elliptic``
        (about 1 ms per point) and fill ``warning`` where the paper's pull-off departs
        from it by more than :data:`WARNING_THRESHOLD`.  The departure from the two-axis
        closure (about 200 ms per point) is :func:`dhfield.analysis.validity.closure_departure`.
        False leaves ``warning`` empty of this check.
    warn : bool
        Also raise a non-empty ``warning`` as a Python warning,
        :class:`dhfield.analysis.validity.OutsideVerifiedDomainWarning` (one per call).  False leaves it
        in the record only (for callers that report it themselves).

    Raises
    ------
    ValueError
        For invalid ``mu``, ``beta0`` or ``control`` (every model's domain), and for a
        scalar point the model refuses.

    Warns
    -----
    dhfield.analysis.validity.OutsideVerifiedDomainWarning
        Where the record's ``warning`` is not empty (with ``warn``).
    """
    _check_model(model)
    mu, beta0 = _check(mu, beta0, control)
    if np.broadcast(beta0, mu).ndim == 0:
        rec = _pull_off(model, beta0, mu, control, check_closure=check_closure)
    else:
        rec = _pull_off_guarded(model, beta0, mu, control, check_closure=check_closure)
    if warn:
        warn_record(rec, stacklevel=2)
    return rec


def compare(*, beta0, mu, control="load", models=None, check_closure=True):
    """Compute the pull-off of every model side by side, on the axes of Fig. 9.

    All models apply to any beta0: the circular ones (dh-circular, jkr, dmt, md)
    are the beta0 -> 1 references the paper plots in Fig. 9a, evaluated with
    R = sqrt(R'R'') and sin(theta_skew) = 1 (``geometry`` = 'circle').

    Parameters
    ----------
    beta0 : array_like
        Hertz ellipticity b/a of the geometry, in (0, 1] [-] (keyword-only, as every
        parameter).
    mu : array_like
        Transition parameter of Eq. (35), > 0 [-].
    control : {'load', 'displacement'}
        Loading mode.
    models : sequence of str, optional
        Names of :data:`MODEL_NAMES`; default all.
    check_closure : bool
        As in :func:`pull_off`.

    Returns
    -------
    dict
        Model name -> record (see :func:`pull_off`), with the trust group.  The
        recommended model is evaluated once and also serves the warning of
        ``dh-elliptic``.  A model that refuses the inputs (a narrower domain of its
        own) or fails to converge gets NaN values and says why in ``warning`` (point
        by point over arrays); invalid ``mu``, ``beta0`` or ``control`` raise
        ValueError as in :func:`pull_off`.  Where the recommended model is among
        ``models`` and answers, every other model whose W* departs from it by more than
        :data:`WARNING_THRESHOLD` says so in ``warning``
        (:func:`dhfield.analysis.model_error.departure_warning`).
    """
    names = MODEL_NAMES if models is None else tuple(_check_model(m) for m in models)
    mu, beta0 = _check(mu, beta0, control)  # bad input is an error for every model

    # a model that refuses these inputs (a narrower domain of its own) or fails to converge gets a NaN record
    # that says why (point by point over arrays), instead of taking the other models down with it
    out = {}
    reference = shown = None
    if RECOMMENDED_MODEL in names:
        shown = _pull_off_guarded(RECOMMENDED_MODEL, beta0, mu, control)
        reference = None if np.all(np.isnan(shown.W_star)) else shown.W_star
    for name in names:
        if name == "dh-elliptic":
            out[name] = _pull_off(name, beta0, mu, control, check_closure=check_closure, reference=reference)
        elif name == RECOMMENDED_MODEL:
            out[name] = shown
        else:
            rec = _pull_off_guarded(name, beta0, mu, control)
            if reference is not None:  # its departure from the recommended model, where above the threshold
                rec = rec.replace(warning=broadcast_field(
                    join_warnings(rec.warning, _disagreement(name, rec.W_star, reference, rec.model_error)),
                    np.shape(rec.W_star), object))
            out[name] = rec
    return out


def departure_from_recommended(records):
    """Relative departure of each model's pull-off from the recommended model's.

    Parameters
    ----------
    records : dict
        Model name -> pull-off record, as from :func:`compare`; must hold
        :data:`RECOMMENDED_MODEL`.

    Returns
    -------
    dict
        Model name -> W*_model / W*_recommended - 1 [-] (0 for the recommended model;
        NaN where either gave no answer).  Positive: more adhesion than the recommended
        model.
    """
    if RECOMMENDED_MODEL not in records:
        raise ValueError(f"records must hold the recommended model {RECOMMENDED_MODEL}; got {', '.join(records)}")
    ref = np.asarray(records[RECOMMENDED_MODEL]["W_star"], float)
    with np.errstate(invalid="ignore", divide="ignore"):
        out = {name: np.asarray(r["W_star"], float) / ref - 1.0 for name, r in records.items()}
    return {name: v[()] if v.ndim == 0 else v for name, v in out.items()}




def _check_curve_model(model):
    _check_model(model)
    if model not in CURVES:
        raise ValueError(f"model must be one with a load curve ({', '.join(CURVE_MODEL_NAMES)}); got "
                         f"{model!r}, whose ellipticity is defined at pull-off only")
    return model


def _curve_arrays(model, a_star, mu, beta0):
    st = CURVES[model](a_star, mu, beta0)
    return {k: np.asarray(st[k], float) for k in LOAD_CURVE_KEYS}


def _curve_record(model, mu, beta0, arrays):
    circle = model in CIRCULAR_MODEL_NAMES
    sin_skew = 1.0 if circle else float(sin_skew_angle(beta0, checked=False))  # beta0 validated by the caller
    return load_curve_record(model, beta0, mu, arrays, sin_skew=sin_skew, geometry="circle" if circle else "ellipse")


def load_curve(model=DEFAULT_MODEL, *, beta0, mu, a_star=None, n=200):
    """Load curve of one model at given contact semi-major axes (nondimensional).

    Parameters
    ----------
    model : str
        One of :data:`CURVE_MODEL_NAMES`; default the recommended model (:data:`DEFAULT_MODEL`).
    beta0 : float
        Hertz ellipticity of the geometry, in (0, 1] [-].
    mu : float
        Tabor parameter of Eq. (35), > 0 [-].
    a_star : array_like, optional
        Contact semi-major axes a/c_r > 0 (Eq. 32) [-]; default ``n`` points
        evenly spaced over :data:`dhfield.models.dh_elliptic.DEFAULT_A_STAR`.
    n : int
        Number of points of the default grid (>= 2).

    Returns
    -------
    dhfield.core.records.LoadCurve
        The record of every model's curve: the scalar keys of
        :data:`dhfield.core.schema.LOAD_CURVE_HEADER_KEYS`, then the
        arrays of :data:`dhfield.core.schema.LOAD_CURVE_KEYS` (NaN where a model has no
        such quantity: ``c_star``, ``d_star`` outside the DH models, ``v`` outside the
        paper's and the circular DH models where the DH factor is not reported).
    """
    _check_curve_model(model)
    mu, beta0 = (float(x) for x in _check_scalar(mu, beta0))
    if a_star is None:
        n = check_count("n", n, 2, MAX_CURVE_POINTS, "number of curve points")
        a_star = np.linspace(*DEFAULT_A_STAR, n)
    a_star = np.atleast_1d(check_contact_size_star("a_star", a_star))
    if a_star.size > MAX_CURVE_POINTS:
        raise ValueError(f"a_star must have at most {MAX_CURVE_POINTS} points; got {a_star.size}")
    return _curve_record(model, mu, beta0, _curve_arrays(model, a_star, mu, beta0))


def _check_scalar(mu, beta0):
    mu, beta0 = _check(mu, beta0, "load")
    if mu.ndim or beta0.ndim:
        raise ValueError("mu and beta0 of a load curve must be scalars; got arrays of shape "
                         f"{np.shape(mu)} and {np.shape(beta0)}")
    return mu, beta0


def load_curve_at_load(model, *, beta0, mu, w_star):
    """Load curve of one model at given loads, on its stable branch under load control.

    Parameters
    ----------
    model : str
        One of :data:`CURVE_MODEL_NAMES`.
    beta0, mu : float
        Hertz ellipticity of the geometry and Tabor parameter (Eq. 35) [-].
    w_star : array_like
        Loads W* = W sin(theta_skew)/(2 pi R dgamma) (Eq. 34) [-], each at least the
        pull-off load of the model (the stable branch starts there).

    Returns
    -------
    dhfield.core.records.LoadCurve
        As :func:`load_curve`, at the contact sizes whose load is ``w_star``.

    Notes
    -----
    Under load control the pull-off is the last minimum of W*(a*) seen from high
    load, so W* rises monotonically for a* above it; each a* is the root of
    W*(a*) = w_star bracketed there (:func:`scipy.optimize.elementwise.find_root`,
    relative tolerance :data:`_ROOT_RTOL`).
    """
    from scipy.optimize import elementwise

    _check_curve_model(model)
    mu, beta0 = (float(x) for x in _check_scalar(mu, beta0))
    w = np.atleast_1d(np.asarray(w_star, dtype=float))
    if not np.all(np.isfinite(w)):
        raise ValueError(f"load must be finite; got {w_star!r}")
    po = MODELS[model](np.asarray(beta0), np.asarray(mu), control="load")
    w_po, a_po = float(po["W_star"]), float(po["a_star"])
    if np.any(w < w_po):
        raise ValueError(f"load must be at least the pull-off load W* = {w_po:.6g} of {model} "
                         f"(the stable branch starts there); got min {w.min():.6g}")
    lo = max(a_po, 1e-6)
    hi = max(2.0 * lo, 1.0)

    def f(a, target):
        return _curve_arrays(model, a, mu, beta0)["W_star"] - target

    for _ in range(60):
        if f(np.array([hi]), 0.0)[0] >= w.max():
            break
        hi *= 2.0
    else:
        raise ValueError(f"load must be below the largest load this model reaches; got {w.max():.6g}")
    flo = f(np.full(w.shape, lo), w)
    a = np.full(w.shape, lo)
    inside = flo < 0
    if np.any(inside):
        res = elementwise.find_root(f, (np.full(int(inside.sum()), lo), np.full(int(inside.sum()), hi)),
                                    args=(w[inside],), tolerances=dict(xrtol=_ROOT_RTOL, xatol=0.0))
        a[inside] = res.x
    return _curve_record(model, mu, beta0, _curve_arrays(model, a, mu, beta0))


#: Relative tolerance on a* of the load inversion (well below plotting or fitting needs).
_ROOT_RTOL = 1e-12
