"""The model registry: keys, normalisation, the circle, the JKR-beta variant, bad input."""
import numpy as np
import pytest
from numpy.testing import assert_allclose

from dhfield import compare, jkr_elliptic
from dhfield.geometry import sin_skew_angle

KEYS = {"model", "beta0", "mu", "W_star", "a_star", "c_star", "v", "delta_star"}
#: issue 3: circular DH vs the elliptical DH core at beta0 = 1
TOL_CORE = 1e-9


def test_registry_names():
    assert set(compare.MODELS) == {"dh-elliptic", "dh-elliptic-jkr-beta", "dh-circular", "jkr", "dmt",
                                   "md", "jkr-elliptic"}


@pytest.mark.parametrize("name", sorted(compare.MODELS))
@pytest.mark.parametrize("control", ["load", "displacement"])
def test_every_model_returns_a_record(name, control):
    rec = compare.MODELS[name](2.0, 0.9, control)
    assert KEYS <= set(rec)
    assert rec["model"] == name and rec["control"] == control
    assert np.isfinite(rec["W_star"]) and rec["W_star"] < 0
    if name in ("jkr", "dmt", "jkr-elliptic"):
        assert np.isnan(rec["c_star"]) and np.isnan(rec["v"])
    if name == "md":
        assert np.isnan(rec["v"])


def test_vectorised_over_mu():
    mu = np.array([0.5, 1.0, 2.0, 5.0])
    for name, f in compare.MODELS.items():
        rec = f(mu, 0.9)
        assert np.shape(rec["W_star"]) == mu.shape, name
        assert_allclose(rec["W_star"][2], f(2.0, 0.9)["W_star"], rtol=1e-12, err_msg=name)


@pytest.mark.parametrize("mu", [0.5, 2.0, 5.0])
def test_circle_all_dh_variants_agree(mu):
    pytest.importorskip("dhfield.model")
    res = compare.compare(mu, 1.0)
    w = res["dh-circular"]["W_star"]
    for name in ("dh-elliptic", "dh-elliptic-jkr-beta"):
        assert_allclose(res[name]["W_star"], w, atol=TOL_CORE)
        assert_allclose(res[name]["a_star"], res["dh-circular"]["a_star"], atol=TOL_CORE)
    assert_allclose(res["jkr-elliptic"]["W_star"], -0.75, rtol=1e-14)
    assert res["md"]["W_star"] > -1 and res["md"]["W_star"] < -0.75


def test_normalisation_eq34():
    beta0 = 0.8
    res = compare.compare(5.0, beta0)
    for name, rec in res.items():
        expected = 1.0 if rec["geometry"] == "circle" else sin_skew_angle(beta0)
        assert_allclose(rec["sin_skew"], expected, rtol=1e-15, err_msg=name)
    # elliptical JKR in W*: the force ratio times -0.75 sin(theta_skew(beta0))
    f = jkr_elliptic.pull_off_force_ratio(beta0=beta0)
    assert_allclose(res["jkr-elliptic"]["W_star"], -0.75 * f * sin_skew_angle(beta0), rtol=1e-12)


def test_jkr_beta_variant_definition():
    """beta_JKR(pull-off) replaces beta for both ellipses; Eq. (34) keeps sin(theta_skew(beta0))."""
    model = pytest.importorskip("dhfield.model")
    mu, beta0 = 5.0, 0.9
    rec = compare.MODELS["dh-elliptic-jkr-beta"](mu, beta0)
    bj = jkr_elliptic.pull_off_ellipticity(beta0=beta0)
    assert_allclose(rec["ellipticity"], bj, rtol=1e-15)
    ref = model.pull_off(mu, beta0, ellipticity=bj)
    assert_allclose(rec["W_star"], ref.W_star, rtol=1e-14)
    # the normalisation: same as the paper's model evaluated at beta = beta_JKR, rescaled by
    # sin(theta_skew(beta0))/sin(theta_skew(beta_JKR))
    alone = model.pull_off(mu, bj)
    assert_allclose(rec["W_star"], alone.W_star * sin_skew_angle(beta0) / sin_skew_angle(bj), rtol=1e-10)
    # the paper's claim at mu = 5: the variant narrows the gap to elliptical JKR
    w_dh = compare.MODELS["dh-elliptic"](mu, beta0)["W_star"]
    w_jkr = compare.MODELS["jkr-elliptic"](mu, beta0)["W_star"]
    assert abs(rec["W_star"] - w_jkr) < abs(w_dh - w_jkr)


def test_dimensional():
    rec = compare.pull_off("jkr-elliptic", 1.0, 0.9)
    si = compare.to_dimensional(rec, 1e-6, 1e9, 0.05)
    assert_allclose(si["load"], jkr_elliptic.pull_off_force(1e-6, 1e9, 0.05, beta0=0.9), rtol=1e-12)
    rec = compare.pull_off("jkr", 1.0, 1.0)
    assert_allclose(compare.to_dimensional(rec, 1e-6, 1e9, 0.05)["load"], -1.5 * np.pi * 1e-6 * 0.05,
                    rtol=1e-14)


def test_bad_input():
    with pytest.raises(ValueError, match="model"):
        compare.pull_off("hertz", 1.0, 0.9)
    for name in compare.MODELS:
        with pytest.raises(ValueError, match="beta0"):
            compare.MODELS[name](1.0, 1.5)
        with pytest.raises(ValueError, match="mu"):
            compare.MODELS[name](-1.0, 0.9)
        with pytest.raises(ValueError, match="control"):
            compare.MODELS[name](1.0, 0.9, "force")
