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


# --- CLI: `dhfield compare` and `dhfield pulloff --model` -----------------------------------

def test_cli_compare_json_and_netcdf(tmp_path, capsys):
    import json

    from dhfield.cli import main
    from dhfield.io import read_netcdf

    out = tmp_path / "cmp.nc"
    assert main(["compare", "--beta0", "0.9", "--mu", "5", "--json", "--out", str(out)]) == 0
    payload = json.loads(capsys.readouterr().out)
    names = [r["model"] for r in payload["models"]]
    assert names == list(compare.MODELS)
    ref = compare.compare(5.0, 0.9)
    for r in payload["models"]:
        assert r["W_star"] == pytest.approx(float(ref[r["model"]]["W_star"]), rel=1e-15)
    ds = read_netcdf(out)
    assert list(ds["model"].values) == names
    assert_allclose(ds["W_star"].values, [float(ref[n]["W_star"]) for n in names], rtol=1e-15)
    assert ds.attrs["param_beta0"] == 0.9


@pytest.mark.parametrize("name", sorted(compare.MODELS))
def test_cli_pulloff_model(name, capsys):
    import json

    from dhfield.cli import main

    assert main(["pulloff", "--beta0", "0.9", "--mu", "2", "--model", name, "--json"]) == 0
    rec = json.loads(capsys.readouterr().out)
    assert rec["model"] == name
    assert rec["W_star"] == pytest.approx(float(compare.pull_off(name, 2.0, 0.9)["W_star"]), rel=1e-15)


def test_cli_bad_input(capsys, tmp_path):
    from dhfield.cli import main

    assert main(["pulloff", "--beta0", "0.9", "--mu", "2", "--model", "hertz"]) == 2
    assert main(["compare", "--beta0", "1.5", "--mu", "2"]) == 2
    assert "beta0" in capsys.readouterr().err
    assert main(["compare", "--beta0", "0.9", "--mu", "2", "--out", str(tmp_path / "x.txt")]) == 2
    assert main(["compare", "--beta0", "0.9", "--mu", "-2"]) == 2
