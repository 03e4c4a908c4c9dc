"""Every analytic model by the name it has on the command line (``--model``).

:data:`MODELS` maps each name to the model's nondimensional pull-off, and :data:`CURVES`
to its load curve where it has one; :mod:`dhfield.analysis.compare` puts the validity
warnings and the error against the BEM ground truth on top.  The recommended model,
:data:`RECOMMENDED_MODEL`, is the default wherever a model is chosen.
"""
from __future__ import annotations

import numpy as np

from . import (dh_circular, dh_elliptic, dh_elliptic_closure, dmt, jkr, jkr_elliptic,
               jkr_elliptic_energy, maugis_dugdale, md_elliptic)
from ..core.geometry import sin_skew_angle
from ..core.schema import LOAD_CURVE_KEYS

__all__ = ["MODELS", "MODEL_NAMES", "CURVE_MODEL_NAMES", "CIRCULAR_MODEL_NAMES", "DEFAULT_MODEL",
           "RECOMMENDED_MODEL", "PAPER_MODEL", "ABSENT_KEYS", "CURVES"]

_NAN = float("nan")
#: The recommended model (:mod:`dhfield.models.md_elliptic`), the default everywhere a model is chosen:
#: the Python API (:func:`pull_off`, :func:`load_curve`, ``dhfield.pull_off``,
#: :func:`dhfield.analysis.dimensional.pull_off_force`), the command line, the report and the docs read it from
#: here (``tests/test_one_default.py`` checks them).  The paper's model stays available by name,
#: ``model="dh-elliptic"``.
RECOMMENDED_MODEL = md_elliptic.MODEL_NAME
#: The default model of every function and command that takes one: :data:`RECOMMENDED_MODEL`.
DEFAULT_MODEL = RECOMMENDED_MODEL
#: The paper's model (Zini et al. 2018), available by this name everywhere a model is chosen.
PAPER_MODEL = "dh-elliptic"


def _dh_elliptic_jkr_beta(beta0, mu, *, control="load"):
    """The paper's second assumption (Fig. 9b): the paper's model at beta = beta_JKR(pull-off)."""
    beta_jkr = jkr_elliptic.pull_off_nondimensional(beta0, mu, control=control).ellipticity
    return dh_elliptic.pull_off_nondimensional(beta0, mu, control=control, ellipticity=beta_jkr).replace(
        model="dh-elliptic-jkr-beta")


#: name -> the model's pull-off, ``f(beta0, mu, *, control) -> dhfield.core.records.PullOff`` on validated
#: inputs (see the module docstring); :func:`pull_off` adds the validity warnings.
MODELS = {
    "md-elliptic": md_elliptic.pull_off_nondimensional,
    "dh-elliptic": dh_elliptic.pull_off_nondimensional,
    "dh-elliptic-two-axis": dh_elliptic_closure.pull_off_two_axis,
    "dh-elliptic-ray-average": dh_elliptic_closure.pull_off_ray_average,
    "dh-elliptic-jkr-beta": _dh_elliptic_jkr_beta,
    "dh-circular": dh_circular.pull_off_nondimensional,
    "jkr": jkr.pull_off_nondimensional,
    "dmt": dmt.pull_off_nondimensional,
    "md": maugis_dugdale.pull_off_nondimensional,
    "jkr-elliptic": jkr_elliptic.pull_off_nondimensional,
    "jkr-elliptic-energy": jkr_elliptic_energy.pull_off_nondimensional,
}
MODEL_NAMES = tuple(MODELS)
#: Models of a circular contact (R = sqrt(R'R''), sin(theta_skew) = 1 in Eq. 34), whatever beta0.
CIRCULAR_MODEL_NAMES = ("dh-circular", "jkr", "dmt", "md")


#: name -> the keys of :data:`dhfield.core.schema.PULL_OFF_KEYS` that are NaN in every pull-off of the model (it
#: has no such quantity: no adhesive zone, no double-Hertz factor ``v``); ``dhfield pulloff`` leaves them
#: out of its text output (with their SI keys).  ``tests/test_registry.py`` checks the table against
#: the models' records.
ABSENT_KEYS = {
    "md-elliptic": ("c_star", "d_star", "v", "adhesive_ellipticity"),
    "dh-elliptic": (),
    "dh-elliptic-two-axis": ("v",),
    "dh-elliptic-ray-average": ("v",),
    "dh-elliptic-jkr-beta": (),
    "dh-circular": (),
    "jkr": ("c_star", "d_star", "v", "adhesive_ellipticity"),
    "dmt": ("c_star", "d_star", "v", "adhesive_ellipticity"),
    "md": ("v",),
    "jkr-elliptic": ("c_star", "d_star", "v", "adhesive_ellipticity"),
    "jkr-elliptic-energy": ("c_star", "d_star", "v", "adhesive_ellipticity"),
}


# --------------------------------------------------------------------------- load curves
def _curve_paper(a, mu, beta0):
    c = dh_elliptic.load_curve(mu=mu, beta0=beta0, a_star=a, checked=False)  # validated by compare.load_curve
    return {k: c[k] for k in LOAD_CURVE_KEYS}


def _curve_closure(solver):
    def curve(a, mu, beta0):
        st = solver(a, beta0=beta0, mu=mu)
        return {"a_star": st.a_star, "b_star": st.b_star, "c_star": st.c_star, "d_star": st.d_star,
                "v": np.full(np.shape(st.a_star), _NAN), "W_star": st.W_star, "delta_star": st.delta_star}
    return curve


def _curve_circle(module, with_stress):
    # the public SI curve with R = E* = dgamma = 1: lengths in c_r, load in 2 pi R dgamma, sigma0 = mu
    def curve(a, mu, beta0):
        args = (a, 1.0, 1.0, 1.0) + ((mu,) if with_stress else ())
        c = module.load_curve(*args)
        a = np.asarray(c.semi_major, float)
        return {"a_star": a, "b_star": a, "c_star": np.full(a.shape, _NAN), "d_star": np.full(a.shape, _NAN),
                "v": np.full(a.shape, _NAN), "W_star": np.asarray(c.force) / (2 * np.pi),  # Eq. (34), sin = 1
                "delta_star": np.asarray(c.approach, float)}
    return curve


def _curve_jkr_elliptic(a, mu, beta0, module=jkr_elliptic):
    c = module.load_curve(a, 1.0, 1.0, 1.0, beta0=beta0)
    shape = np.shape(c.semi_major)
    return {"a_star": np.asarray(c.semi_major, float), "b_star": np.asarray(c.semi_minor, float),
            "c_star": np.full(shape, _NAN), "d_star": np.full(shape, _NAN), "v": np.full(shape, _NAN),
            "W_star": np.asarray(c.force) * sin_skew_angle(beta0, checked=False) / (2 * np.pi),  # Eq. (34)
            "delta_star": np.asarray(c.approach, float)}


def _curve_recommended(a, mu, beta0):
    c = md_elliptic.load_curve_nondimensional(a, beta0, mu, checked=False)  # validated by load_curve
    nan = np.full(np.shape(c["a_star"]), _NAN)
    return {"a_star": c["a_star"], "b_star": c["b_star"], "c_star": nan, "d_star": nan, "v": nan,
            "W_star": c["W_star"], "delta_star": c["delta_star"]}


#: name -> (a*, mu, beta0) -> dict of the curve arrays, for the models that have a load curve.
CURVES = {
    "md-elliptic": _curve_recommended,
    "dh-elliptic": _curve_paper,
    "dh-elliptic-two-axis": _curve_closure(dh_elliptic_closure.solve_two_axis),
    "dh-elliptic-ray-average": _curve_closure(dh_elliptic_closure.solve_ray_average),
    "dh-circular": _curve_circle(dh_circular, True),
    "jkr": _curve_circle(jkr, False),
    "dmt": _curve_circle(dmt, False),
    "md": _curve_circle(maugis_dugdale, True),
    "jkr-elliptic": _curve_jkr_elliptic,
    "jkr-elliptic-energy": lambda a, mu, beta0: _curve_jkr_elliptic(a, mu, beta0, jkr_elliptic_energy),
}
#: Models with a load curve.  ``dh-elliptic-jkr-beta`` has none: its ellipticity is defined
#: at pull-off only.
CURVE_MODEL_NAMES = tuple(n for n in MODEL_NAMES if n in CURVES)
