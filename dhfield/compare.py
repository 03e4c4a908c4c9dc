"""All comparison models behind one interface, on the axes of the paper's Figs. 8-9.

Every entry of :data:`MODELS` is a callable ``(mu, beta0, control="load") -> dict``
returning the pull-off in the paper's normalisation (Eqs. 32-35):

``model, beta0, mu, control, W_star, a_star, c_star, v, delta_star, ellipticity,
sin_skew, geometry``

* ``W_star = W sin(theta_skew)/(2 pi R dgamma)`` (Eq. 34), with sin(theta_skew) of
  beta0 for the elliptical models and 1 for the circular ones (``sin_skew`` says
  which); R = sqrt(R'R'').
* ``a_star`` is the contact semi-major axis (the radius for the circle) in
  c_r = (R^2 dgamma/E*)^(1/3); ``delta_star`` the approach in c_r^2/R.
* ``c_star`` (outer edge of the adhesive zone) and ``v`` (DH factor) are NaN where
  the model has none (JKR, DMT, elliptical JKR; ``v`` for MD).
* ``ellipticity`` is the contact b/a at pull-off (1 for the circle).
* mu is the paper's Eq. (35); MD is evaluated at lambda = 1.1272 mu
  (:mod:`dhfield.transition`, same sigma0).  JKR, DMT and elliptical JKR do not
  depend on mu.

Models
------
``dh-elliptic``           the paper's model, beta = beta0 throughout (Eq. 19) — :mod:`dhfield.model`
``dh-elliptic-jkr-beta``  the paper's second assumption (Fig. 9): beta_(pull-off) = beta_JKR(pull-off)
``dh-circular``           Greenwood & Johnson (1998) — :mod:`dhfield.dh_circular`
``jkr``, ``dmt``          :mod:`dhfield.jkr`, :mod:`dhfield.dmt`
``md``                    Maugis (1992) — :mod:`dhfield.maugis_dugdale`
``jkr-elliptic``          Johnson & Greenwood (2005) — :mod:`dhfield.jkr_elliptic`

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

This is :func:`dhfield.model.pull_off` with ``ellipticity=beta_JKR``; at beta0 = 1
it is the paper's model (beta_JKR = 1).
"""
from __future__ import annotations

import numpy as np

from . import dh_circular, dmt, jkr, jkr_elliptic, maugis_dugdale
from ._adhesion import approach_unit, check_control, check_material, length_unit, load_unit
from ._validation import check_ellipticity, check_positive
from .geometry import sin_skew_angle

__all__ = ["MODELS", "MODEL_NAMES", "compare", "pull_off", "to_dimensional"]

_NAN = float("nan")


def _check(mu, beta0, control):
    mu = check_positive("mu", mu, "transition parameter of Eq. (35), dimensionless")
    beta0 = check_ellipticity("beta0", beta0)
    check_control(control)
    return np.broadcast_arrays(mu, beta0)


def _record(name, mu, beta0, control, st, ellipticity, sin_skew, geometry):
    shape = np.broadcast_shapes(mu.shape, beta0.shape)

    def arr(x):
        out = np.broadcast_to(np.asarray(x, dtype=float), shape).copy()
        return out[()] if out.ndim == 0 else out

    return {"model": name, "beta0": arr(beta0), "mu": arr(mu), "control": control,
            "W_star": arr(st["W_star"]), "a_star": arr(st["a_star"]),
            "c_star": arr(st.get("c_star", _NAN)), "v": arr(st.get("v", _NAN)),
            "delta_star": arr(st["delta_star"]), "ellipticity": arr(ellipticity),
            "sin_skew": arr(sin_skew), "geometry": geometry}


def _from_model(res):
    return {"W_star": res.W_star, "a_star": res.a_star, "c_star": res.c_star, "v": res.v,
            "delta_star": res.delta_star}


def _dh_elliptic(mu, beta0, control="load"):
    from .model import pull_off as dh_pull_off

    mu, beta0 = _check(mu, beta0, control)
    res = dh_pull_off(mu, beta0, control=control)
    return _record("dh-elliptic", mu, beta0, control, _from_model(res), beta0, sin_skew_angle(beta0),
                   "ellipse")


def _dh_elliptic_jkr_beta(mu, beta0, control="load"):
    from .model import pull_off as dh_pull_off

    mu, beta0 = _check(mu, beta0, control)
    beta_jkr = jkr_elliptic._pull_off(beta0, control)["beta"]
    res = dh_pull_off(mu, beta0, control=control, ellipticity=beta_jkr)
    return _record("dh-elliptic-jkr-beta", mu, beta0, control, _from_model(res), beta_jkr,
                   sin_skew_angle(beta0), "ellipse")


def _dh_circular(mu, beta0, control="load"):
    mu, beta0 = _check(mu, beta0, control)
    return _record("dh-circular", mu, beta0, control, dh_circular._pull_off(mu, control), 1.0, 1.0,
                   "circle")


def _jkr(mu, beta0, control="load"):
    mu, beta0 = _check(mu, beta0, control)
    return _record("jkr", mu, beta0, control, jkr._pull_off(control), 1.0, 1.0, "circle")


def _dmt(mu, beta0, control="load"):
    mu, beta0 = _check(mu, beta0, control)
    return _record("dmt", mu, beta0, control, dmt._pull_off(control), 1.0, 1.0, "circle")


def _md(mu, beta0, control="load"):
    mu, beta0 = _check(mu, beta0, control)
    return _record("md", mu, beta0, control, maugis_dugdale._pull_off(mu, control), 1.0, 1.0,
                   "circle")


def _jkr_elliptic(mu, beta0, control="load"):
    mu, beta0 = _check(mu, beta0, control)
    st = jkr_elliptic._pull_off(beta0, control)
    return _record("jkr-elliptic", mu, beta0, control, st, st["beta"], sin_skew_angle(beta0), "ellipse")


#: name -> callable (mu, beta0, control="load") -> dict (see the module docstring)
MODELS = {
    "dh-elliptic": _dh_elliptic,
    "dh-elliptic-jkr-beta": _dh_elliptic_jkr_beta,
    "dh-circular": _dh_circular,
    "jkr": _jkr,
    "dmt": _dmt,
    "md": _md,
    "jkr-elliptic": _jkr_elliptic,
}
MODEL_NAMES = tuple(MODELS)


def pull_off(model, mu, beta0, control="load"):
    """Pull-off of one model, in the paper's normalisation (Eq. 34).

    Parameters
    ----------
    model : str
        One of :data:`MODEL_NAMES`.
    mu : array_like
        Transition parameter of Eq. (35), > 0 [-].
    beta0 : array_like
        Hertz ellipticity b/a of the geometry, in (0, 1] [-].
    control : {'load', 'displacement'}
        Loading mode.

    Returns
    -------
    dict
        See the module docstring.
    """
    if model not in MODELS:
        raise ValueError(f"model must be one of {MODEL_NAMES}; got {model!r}")
    return MODELS[model](mu, beta0, control)


def compare(mu, beta0, control="load", models=None):
    """Pull-off of every model side by side, on the axes of Fig. 9.

    All models apply to any beta0: the circular ones (dh-circular, jkr, dmt, md)
    are the beta0 -> 1 references the paper plots in Fig. 9a, evaluated with
    R = sqrt(R'R'') and sin(theta_skew) = 1 (``geometry`` = 'circle').

    Returns
    -------
    dict
        model name -> record (see the module docstring).
    """
    names = MODEL_NAMES if models is None else tuple(models)
    return {name: pull_off(name, mu, beta0, control) for name in names}


def to_dimensional(record, effective_radius, reduced_modulus, work_of_adhesion):
    """SI values of a record: ``load`` [N], ``semi_major`` and ``adhesive_semi_major`` [m],
    ``approach`` [m].

    Parameters
    ----------
    record : dict
        A record from :data:`MODELS`.
    effective_radius, reduced_modulus, work_of_adhesion : array_like
        R = sqrt(R'R'') [m], E* [Pa], dgamma [J/m^2].

    Notes
    -----
    Inverts Eqs. (32)-(34): W = W* 2 pi R dgamma/sin(theta_skew), a = a* c_r,
    delta = delta* c_r^2/R.
    """
    r, e, w = check_material(effective_radius, reduced_modulus, work_of_adhesion)
    cr = length_unit(r, e, w)
    return {"model": record["model"],
            "load": record["W_star"] * load_unit(r, w, record["sin_skew"]),  # Eq. (34)
            "semi_major": record["a_star"] * cr,  # Eq. (32)
            "adhesive_semi_major": record["c_star"] * cr,
            "approach": record["delta_star"] * approach_unit(r, e, w)}
