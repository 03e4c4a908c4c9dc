"""The registry of models by name (dhfield.models.registry): its tables, every pull-off the minimum
of the model's load curve, and the circular models at beta0 = 1 against their closed forms.

Closed forms, in the paper's units (W* = W/(2 pi R dgamma) at beta0 = 1, a* = a/c_r with
c_r^3 = R^2 dgamma/E*, delta* = delta R/c_r^2; Eqs. 32-35):

* JKR under load control: W = -(3/2) pi R dgamma at a^3 = 3 pi dgamma R^2/(2K), K = 4E*/3, so
  W* = -3/4 and a*^3 = 9 pi/8; delta = a^2/R - sqrt(2 pi dgamma a/E*), so delta* = a*^2 - sqrt(2 pi a*).
* JKR under displacement control (the minimum of delta): d(delta)/da = 0 at a^3 = pi dgamma R^2/(8E*),
  a*^3 = pi/8, where W = -(5/6) pi R dgamma, W* = -5/12.
* DMT: W = -2 pi R dgamma at zero contact, W* = -1, a* = delta* = 0, under either control (delta =
  a^2/R is least at a = 0).
"""
import math

import numpy as np
import pytest
from numpy.testing import assert_allclose

from dhfield.core.schema import LOAD_CURVE_KEYS, PULL_OFF_KEYS
from dhfield.models import registry

#: the closures cost about 1 s a point (pull-off) and 0.05 s a curve point: checked on fewer points
CLOSURES = ("dh-elliptic-two-axis", "dh-elliptic-ray-average")
#: numeric keys of a nondimensional pull-off record that a model may lack (ABSENT_KEYS)
NONDIM = ("W_star", "a_star", "b_star", "c_star", "d_star", "v", "delta_star", "ellipticity",
          "adhesive_ellipticity")
#: the closed forms are evaluated in double precision; the models reach them through root finds
#: and elliptic integrals at the circle, each to ~1e-12 relative
TOL_CLOSED_FORM = 1e-9
#: the pull-off search locates a* to rtol 1e-8; W* is quadratic at its minimum, so W* to ~1e-15 plus
#: the rounding of W* itself
TOL_PULL_OFF_W = 1e-12
#: spacing of the dense a* grid of the load curves
GRID_STEP = 2e-3
#: the point (beta0, mu) of the single-point checks: an ellipse in the transition regime
BETA0, MU = 0.7, 1.0


def _pull_off(name, beta0, mu, control="load"):
    return registry.MODELS[name](np.float64(beta0), np.float64(mu), control=control)


# --------------------------------------------------------------------------- the tables
def test_registry_names():
    assert set(registry.MODELS) == {"md-elliptic", "dh-elliptic", "dh-elliptic-two-axis", "dh-elliptic-ray-average",
                                    "dh-elliptic-jkr-beta", "dh-circular", "jkr", "dmt", "md", "jkr-elliptic",
                                    "jkr-elliptic-energy"}
    assert registry.MODEL_NAMES == tuple(registry.MODELS)
    # issue 20: the recommended model is the default and the first column of compare
    assert registry.MODEL_NAMES[0] == registry.DEFAULT_MODEL == registry.RECOMMENDED_MODEL == "md-elliptic"
    assert registry.PAPER_MODEL == "dh-elliptic" != registry.RECOMMENDED_MODEL
    assert set(registry.CIRCULAR_MODEL_NAMES) <= set(registry.MODEL_NAMES)


def test_curve_model_names_are_the_models_with_a_curve():
    assert set(registry.CURVE_MODEL_NAMES) <= set(registry.MODEL_NAMES)
    assert registry.CURVE_MODEL_NAMES == tuple(n for n in registry.MODEL_NAMES if n in registry.CURVES)
    assert set(registry.CURVES) == set(registry.CURVE_MODEL_NAMES)
    # the JKR-beta variant's ellipticity is defined at pull-off only
    assert set(registry.CURVE_MODEL_NAMES) == set(registry.MODEL_NAMES) - {"dh-elliptic-jkr-beta"}


@pytest.mark.parametrize("name", registry.MODEL_NAMES)
@pytest.mark.parametrize("control", ["load", "displacement"])
def test_every_name_has_a_pull_off(name, control):
    rec = _pull_off(name, BETA0, MU, control)
    assert tuple(rec) == PULL_OFF_KEYS
    assert rec["model"] == name and rec["control"] == control
    assert np.isfinite(rec["W_star"]) and rec["W_star"] < 0
    assert rec["geometry"] == ("circle" if name in registry.CIRCULAR_MODEL_NAMES else "ellipse")


def test_absent_keys_are_nan_in_every_pull_off_and_the_others_finite():
    """ABSENT_KEYS: per model, exactly the keys that are NaN, at every point of a spread of (beta0, mu)
    and under both controls; every other numeric key is finite there."""
    assert tuple(registry.ABSENT_KEYS) == registry.MODEL_NAMES
    b = np.array([0.3, 0.5, 0.8, 0.95, 1.0, 0.5, 0.9, BETA0])
    m = np.array([0.3, 1.0, 5.0, 2.0, 0.5, 20.0, 0.1, MU])
    for name in registry.MODEL_NAMES:
        absent = set(registry.ABSENT_KEYS[name])
        assert absent <= set(NONDIM), name
        pick = [0, 2, 7] if name in CLOSURES else slice(None)
        for control in ("load", "displacement"):
            rec = registry.MODELS[name](b[pick], m[pick], control=control)
            for k in NONDIM:
                values = np.asarray(rec[k], float)
                if k in absent:
                    assert np.all(np.isnan(values)), (name, control, k)
                else:
                    assert np.all(np.isfinite(values)), (name, control, k)


# --------------------------------------------------------------------------- pull-off = curve minimum
def _dense_grid():
    # a* = 1e-6 (the smallest accepted contact) and then a uniform grid
    return np.concatenate([[1e-6], np.arange(GRID_STEP, 4.0, GRID_STEP)])


def _window_grid(centre, half_width=0.05):
    # a grid on multiples of GRID_STEP, so that it does not contain the pull-off's a* itself
    lo = math.floor((centre - half_width) / GRID_STEP) * GRID_STEP
    return np.arange(max(lo, GRID_STEP), centre + half_width, GRID_STEP)


@pytest.mark.parametrize("name", registry.CURVE_MODEL_NAMES)
def test_load_control_pull_off_is_the_minimum_of_the_curve(name):
    """The load-control pull-off W* is the least load of the model's own curve W*(a*).

    On a grid of spacing h, the grid point nearest the minimiser a*_0 lies within h/2 of it, so the
    grid's least load exceeds W*(a*_0) by at most W'' (h/2)^2 / 2 = W'' h^2/8 (Taylor; W'' from the
    second difference at the grid minimum, doubled for its variation over one step), and it is
    never below W*(a*_0).  A smooth curve with one minimum has its minimiser between the
    neighbours of the grid minimum: |a*_grid - a*_0| < h.  The closures' curves are checked on a
    window of +-0.05 around the pull-off (on multiples of h, not through a*_0) and on a coarse
    grid of the whole range.
    """
    rec = _pull_off(name, BETA0, MU)
    w0, a0 = float(rec["W_star"]), float(rec["a_star"])
    if name in CLOSURES:
        a = _window_grid(a0)
        coarse = np.asarray(registry.CURVES[name](np.arange(0.1, 4.0, 0.1), MU, BETA0)["W_star"], float)
        assert np.all(coarse >= w0 - TOL_PULL_OFF_W), name
    else:
        a = _dense_grid()
    curve = registry.CURVES[name](a, MU, BETA0)
    assert set(LOAD_CURVE_KEYS) <= set(curve)
    w = np.asarray(curve["W_star"], float)
    assert np.all(np.isfinite(w)), name
    i = int(np.argmin(w))
    assert np.all(w >= w0 - TOL_PULL_OFF_W), (name, w.min() - w0)
    if i == 0:
        # the minimum at zero contact (DMT): W* rises from a* = 0 (convexly), so the rise over the
        # first point [0, a_0] is at most the slope over the first step times a_0
        assert rec["at_zero_contact"] and a0 == 0.0
        assert w[0] - w0 <= (w[1] - w[0]) / (a[1] - a[0]) * a[0] + TOL_PULL_OFF_W
        return
    assert 0 < i < a.size - 1, f"{name}: the curve's minimum at the end of the grid"
    h = a[i + 1] - a[i]
    second = (w[i - 1] - 2.0 * w[i] + w[i + 1]) / h**2
    assert second > 0, name
    assert w[i] - w0 <= 2.0 * second * h**2 / 8.0 + TOL_PULL_OFF_W, (name, w[i] - w0)
    assert abs(a[i] - a0) < h, (name, a[i], a0)


# --------------------------------------------------------------------------- the circle's closed forms
JKR = {"load": (-0.75, (9 * math.pi / 8) ** (1 / 3)), "displacement": (-5 / 12, (math.pi / 8) ** (1 / 3))}


@pytest.mark.parametrize("name", ["jkr", "jkr-elliptic", "jkr-elliptic-energy"])
@pytest.mark.parametrize("control", ["load", "displacement"])
def test_jkr_models_at_the_circle_are_the_jkr_closed_form(name, control):
    w, a = JKR[control]
    for mu in (0.3, 5.0):   # JKR has no adhesive stress: mu does not enter
        rec = _pull_off(name, 1.0, mu, control)
        assert_allclose(rec["W_star"], w, rtol=TOL_CLOSED_FORM, err_msg=name)
        assert_allclose(rec["a_star"], a, rtol=TOL_CLOSED_FORM, err_msg=name)
        assert_allclose(rec["b_star"], a, rtol=TOL_CLOSED_FORM, err_msg=name)
        assert_allclose(rec["delta_star"], a**2 - math.sqrt(2 * math.pi * a), rtol=TOL_CLOSED_FORM, err_msg=name)


@pytest.mark.parametrize("control", ["load", "displacement"])
def test_dmt_is_the_dmt_closed_form(control):
    for beta0, mu in ((1.0, 0.3), (BETA0, MU)):   # a circular model: beta0 enters through sin_skew only
        rec = _pull_off("dmt", beta0, mu, control)
        assert rec["W_star"] == pytest.approx(-1.0, rel=TOL_CLOSED_FORM)
        assert rec["a_star"] == 0.0 and rec["delta_star"] == 0.0 and rec["at_zero_contact"]
