"""Dimensional front end: unit neutrality, geometry of crossed cylinders, every model in SI, broadcasting."""
import numpy as np
import pytest
from numpy.testing import assert_allclose

from dhfield.analysis import dimensional as dim
from dhfield.models import dh_elliptic_fields as dh
from dhfield.core import geometry
from dhfield.models import jkr_elliptic
from dhfield.core.schema import (LOAD_CURVE_HEADER_KEYS, LOAD_CURVE_SI_KEYS, PULL_OFF_SI_KEYS,
                                 PULL_OFF_TRUST_KEYS)

# PDMS-like crossed fibres: E = 2 MPa, nu = 0.5, Rc = 1 mm, 60 deg, dgamma = 0.05 J/m^2, sigma0 = 0.5 MPa.
SI = dict(youngs_modulus_1=2e6, poisson_ratio_1=0.5, youngs_modulus_2=2e6, poisson_ratio_2=0.5,
          cylinder_radius=1e-3, skew_angle=np.pi / 3, work_of_adhesion=0.05, max_adhesive_stress=5e5)
# The worked example of issue 10: PDMS cylinders R = 5 mm crossed at 60 deg, dgamma = 40 mJ/m^2.
PDMS = dict(SI, cylinder_radius=5e-3, work_of_adhesion=0.04)
#: unit conversion only: the same floating-point operations up to scale factors
TOL_UNITS = 1e-10
#: two independent SI paths (dimensional.pull_off_force vs jkr_elliptic.pull_off_force) of one closed form
TOL_SAME_FORM = 1e-12
#: the two-axis closure against elliptical JKR at mu = 19.5: the closure tends to the JKR limit as mu grows
#: (within 0.3 % at mu = 10 and 0.03 % at mu = 30 over beta0 = 0.3-0.99, dhfield.analysis.compare docstring)
TOL_JKR_LIMIT = 1e-3
#: cheap models for the loops (the closures cost ~1 s a point and are tested in test_compare)
CHEAP = ("dh-elliptic", "dh-circular", "jkr", "dmt", "md", "jkr-elliptic")


def test_unit_neutrality():
    # The same contact in (mm, N, MPa): 1 MPa = 1 N/mm^2, 1 J/m^2 = 1e-3 N/mm.
    mm = dict(youngs_modulus_1=2.0, poisson_ratio_1=0.5, youngs_modulus_2=2.0, poisson_ratio_2=0.5,
              cylinder_radius=1.0, skew_angle=np.pi / 3, work_of_adhesion=0.05e-3, max_adhesive_stress=0.5)
    p_si, p_mm = dim.contact_parameters(**SI), dim.contact_parameters(**mm)
    assert p_si.mu == pytest.approx(p_mm.mu, rel=1e-12)
    assert p_si.beta0 == pytest.approx(p_mm.beta0, rel=1e-12)
    for model in CHEAP:
        f_si = dim.pull_off_force(p_si, model=model, check_closure=False)
        f_mm = dim.pull_off_force(p_mm, model=model, check_closure=False)
        assert f_si["force"] == pytest.approx(f_mm["force"], rel=TOL_UNITS)  # both in newtons
        for k in ("semi_major", "semi_minor", "approach"):
            assert f_si[k] == pytest.approx(f_mm[k] * 1e-3, rel=TOL_UNITS, abs=1e-30), (model, k)


def test_every_model_same_keys_in_si():
    p = dim.contact_parameters(**SI)
    for model in CHEAP:
        rec = dim.pull_off_force(p, model=model, check_closure=False)
        assert tuple(rec) == PULL_OFF_SI_KEYS + PULL_OFF_TRUST_KEYS, model
        assert rec["force"] < 0 and rec["model"] == model


def test_backward_compatible_call():
    rec = dim.pull_off_force(dim.contact_parameters(**SI), check_closure=False)
    assert rec["model"] == "md-elliptic"  # the default since issue 20 (compare.DEFAULT_MODEL)
    assert {"force", "semi_major", "adhesive_semi_major", "approach", "mu", "beta0"} <= set(rec)


def test_si_curve_consistent_with_field_functions():
    p = dim.contact_parameters(**SI)
    c = dim.load_curve_si(p, n=15, model="dh-elliptic")  # the DH field functions: the paper's model
    assert tuple(c) == LOAD_CURVE_HEADER_KEYS + LOAD_CURVE_SI_KEYS
    w = dh.load(c["semi_major"], c["adhesive_semi_major"], p.beta0, c["v"], p.effective_radius,
                p.reduced_modulus)
    assert_allclose(c["force"], w, rtol=1e-11)
    s0 = dh.max_adhesive_stress(c["semi_major"], c["adhesive_semi_major"], p.beta0, c["v"],
                                p.effective_radius, p.reduced_modulus)
    assert_allclose(s0, SI["max_adhesive_stress"], rtol=1e-11)
    d = dh.approach(c["semi_major"], c["adhesive_semi_major"], p.beta0, c["v"], p.effective_radius,
                    p.reduced_modulus)
    assert_allclose(c["approach"], d, rtol=1e-11, atol=1e-20)


@pytest.mark.parametrize("model", ["md-elliptic", "dh-elliptic", "jkr-elliptic", "jkr"])
def test_si_curve_over_loads(model):
    p = dim.contact_parameters(**SI)
    f_po = dim.pull_off_force(p, model=model, check_closure=False)["force"]
    force = np.linspace(f_po, -2 * f_po, 5)
    c = dim.load_curve_si(p, model=model, force=force)
    assert_allclose(c["force"], force, rtol=1e-9, atol=1e-9 * abs(f_po))
    by_size = dim.load_curve_si(p, c["semi_major"], model=model)
    assert_allclose(by_size["force"], c["force"], rtol=1e-12, atol=1e-15 * abs(f_po))
    with pytest.raises(ValueError, match="force"):
        dim.load_curve_si(p, c["semi_major"], model=model, force=force)


def test_pdms_example():
    """Issue 10: E = 2 MPa, nu = 0.5, R = 5 mm, 60 deg, dgamma = 40 mJ/m^2, sigma0 = 0.5 MPa."""
    p = dim.contact_parameters(**PDMS)
    assert p.beta0 == pytest.approx(0.4826, abs=5e-5)  # issue 10 quotes beta0 = 0.48, mu = 22
    assert p.mu == pytest.approx(21.65, abs=5e-3)
    jkr = dim.pull_off_force(p, model="jkr-elliptic")
    ref = jkr_elliptic.pull_off_force(p.effective_radius, p.reduced_modulus, 0.04, beta0=p.beta0)
    assert jkr["force"] == pytest.approx(ref, rel=TOL_SAME_FORM)
    paper = dim.pull_off_force(p, model="dh-elliptic")
    assert paper["force"] > 0.8 * jkr["force"]  # the paper's model: ~30 % less adhesion here
    assert "md-elliptic" in paper["warning"]  # its reference since issue 20 (the two-axis closure before)
    # the closures accept mu <= 20 (dhfield.models.dh_elliptic_closure.CLOSURE_MU_RANGE): the same contact at sigma0 = 0.45 MPa
    q = dim.contact_parameters(**{**PDMS, "max_adhesive_stress": 4.5e5})
    two = dim.pull_off_force(q, model="dh-elliptic-two-axis")
    assert two["force"] == pytest.approx(jkr["force"], rel=TOL_JKR_LIMIT)  # JKR: independent of sigma0
    assert two["warning"] == ""
    assert dim.pull_off_force(q, model="dh-elliptic", check_closure=True)["warning"].startswith(
        "dh-elliptic pull-off departs")


def test_broadcasting_and_scalars():
    skew = np.radians([45.0, 60.0, 90.0])
    p = dim.contact_parameters(**{**SI, "skew_angle": skew})
    assert np.shape(p.mu) == (3,) and np.shape(p.load_unit) == (3,)
    rec = dim.pull_off_force(p, model="jkr-elliptic")
    for k in ("force", "semi_major", "semi_minor", "approach", "beta0", "mu", "work_of_adhesion"):
        assert np.shape(rec[k]) == (3,), k
    one = dim.pull_off_force(dim.contact_parameters(**{**SI, "skew_angle": skew[1]}), model="jkr-elliptic")
    assert np.ndim(one["force"]) == 0 and np.ndim(one["mu"]) == 0
    assert_allclose(rec["force"][1], one["force"], rtol=1e-14)


def test_perpendicular_cylinders_are_circular_jkr_like():
    p = dim.contact_parameters(**{**SI, "skew_angle": np.pi / 2})
    assert p.beta0 == pytest.approx(1.0, abs=1e-12)
    assert p.effective_radius == pytest.approx(1e-3)


def test_crossed_cylinder_radii_limits():
    theta = np.radians([10.0, 30.0, 60.0, 89.0, 90.0])
    assert_allclose(dim.crossed_cylinder_radii(2e-3, 2e-3, theta), geometry.principal_radii(2e-3, theta),
                    rtol=1e-13)  # Eqs. (3)-(4)
    assert_allclose(dim.crossed_cylinder_radii(2e-3, 5e-3, np.pi / 2), (5e-3, 2e-3), rtol=1e-15)
    assert_allclose(dim.crossed_cylinder_radii(5e-3, 2e-3, np.pi / 2), (5e-3, 2e-3), rtol=1e-15)


def test_crossed_cylinder_radii_eigenvalues():
    """Independent check: 1/R', 1/R'' are the eigenvalues of the gap's curvature tensor
    sum_i e_i e_i^T / R_i, e_i the in-plane normals of the cylinder axes at angle theta."""
    rng = np.random.default_rng(20261123)
    for r1, r2, th in zip(rng.uniform(1e-4, 1e-2, 20), rng.uniform(1e-4, 1e-2, 20), rng.uniform(0.05, np.pi / 2, 20)):
        e1, e2 = np.array([1.0, 0.0]), np.array([np.cos(th), np.sin(th)])
        k = np.outer(e1, e1) / r1 + np.outer(e2, e2) / r2
        lo, hi = np.linalg.eigvalsh(k)
        assert_allclose(dim.crossed_cylinder_radii(r1, r2, th), (1 / lo, 1 / hi), rtol=1e-10)


def test_principal_radii_any_order():
    a = dim.contact_parameters_from_principal_radii(2e6, 0.5, 2e6, 0.5, 3e-3, 1e-3, 0.05, 5e5)
    b = dim.contact_parameters_from_principal_radii(2e6, 0.5, 2e6, 0.5, 1e-3, 3e-3, 0.05, 5e5)
    assert a == b and a.r_major == 3e-3
    c = dim.contact_parameters(**SI)
    d = dim.contact_parameters_from_principal_radii(2e6, 0.5, 2e6, 0.5, c.r_major, c.r_minor, 0.05, 5e5)
    assert d.mu == pytest.approx(c.mu, rel=1e-15) and d.sin_skew == pytest.approx(c.sin_skew, rel=1e-12)


@pytest.mark.parametrize("key, value", [("work_of_adhesion", -1.0), ("max_adhesive_stress", 0.0),
                                        ("skew_angle", 0.0), ("cylinder_radius", np.nan),
                                        ("poisson_ratio_1", 0.6), ("youngs_modulus_2", -1.0)])
def test_bad_input(key, value):
    with pytest.raises(ValueError, match=key):
        dim.contact_parameters(**{**SI, key: value})


def test_bad_model():
    with pytest.raises(ValueError, match="model"):
        dim.pull_off_force(dim.contact_parameters(**SI), model="hertz")
    with pytest.raises(ValueError, match="radius_2"):
        dim.crossed_cylinder_radii(1e-3, 0.0, 1.0)


PDMS = dict(youngs_modulus_1=2e6, poisson_ratio_1=0.5, youngs_modulus_2=2e6, poisson_ratio_2=0.5,
            cylinder_radius=5e-3, skew_angle=np.pi / 3, work_of_adhesion=0.04, max_adhesive_stress=5e5)


@pytest.mark.parametrize("key, value, words", [
    ("both_moduli", 1e308, "youngs_modulus"), ("youngs_modulus_1", 1e-308, "youngs_modulus"),
    ("youngs_modulus_2", 1e-308, "youngs_modulus"), ("work_of_adhesion", 1e308, "work_of_adhesion"),
    ("cylinder_radius", 1e308, "cylinder_radius")])
def test_extreme_si_inputs_are_named_without_runtime_warnings(key, value, words):
    # Issue 9 (hostile-input campaign): these printed numpy RuntimeWarnings and then blamed
    # max_adhesive_stress with a range of [inf, inf] Pa, or r_major, which the user never gave.
    import warnings

    # One rigid body (E1 = 1e308) is a valid input; both rigid is not.
    kwargs = {**PDMS, "youngs_modulus_1": value, "youngs_modulus_2": value} if key == "both_moduli" \
        else {**PDMS, key: value}
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        with pytest.raises(ValueError, match=words):
            dim.contact_parameters(**kwargs)
