"""Dimensional front end: unit neutrality and consistency with the SI field functions."""
import numpy as np
import pytest

from dhfield import dimensional as dim
from dhfield import double_hertz as dh

# PDMS-like crossed fibres: E = 2 MPa, nu = 0.5, Rc = 1 mm, 60 deg, dgamma = 0.05 J/m^2, sigma0 = 0.5 MPa.
SI = dict(youngs_modulus_1=2e6, poisson_ratio_1=0.5, youngs_modulus_2=2e6, poisson_ratio_2=0.5,
          cylinder_radius=1e-3, skew_angle=np.pi / 3, work_of_adhesion=0.05, max_adhesive_stress=5e5)


def test_unit_neutrality():
    # The same contact in (mm, mN, kPa): E in kPa = mN/mm^2 * 1e-3... use (mm, N, MPa): 1 MPa = 1 N/mm^2,
    # 1 J/m^2 = 1e-3 N/mm.
    mm = dict(youngs_modulus_1=2.0, poisson_ratio_1=0.5, youngs_modulus_2=2.0, poisson_ratio_2=0.5,
              cylinder_radius=1.0, skew_angle=np.pi / 3, work_of_adhesion=0.05e-3, max_adhesive_stress=0.5)
    p_si, p_mm = dim.contact_parameters(**SI), dim.contact_parameters(**mm)
    assert p_si.mu == pytest.approx(p_mm.mu, rel=1e-12)
    assert p_si.beta0 == pytest.approx(p_mm.beta0, rel=1e-12)
    f_si, f_mm = dim.pull_off_force(p_si), dim.pull_off_force(p_mm)
    assert f_si["force"] == pytest.approx(f_mm["force"], rel=1e-10)  # both in newtons
    assert f_si["semi_major"] == pytest.approx(f_mm["semi_major"] * 1e-3, rel=1e-10)


def test_si_curve_consistent_with_field_functions():
    p = dim.contact_parameters(**SI)
    c = dim.load_curve_si(p, n=15)
    w = dh.load(c["semi_major"], c["adhesive_semi_major"], p.beta0, c["scaling"], p.effective_radius,
                p.reduced_modulus)
    np.testing.assert_allclose(c["load"], w, rtol=1e-11)
    s0 = dh.max_adhesive_stress(c["semi_major"], c["adhesive_semi_major"], p.beta0, c["scaling"],
                                p.effective_radius, p.reduced_modulus)
    np.testing.assert_allclose(s0, SI["max_adhesive_stress"], rtol=1e-11)
    d = dh.approach(c["semi_major"], c["adhesive_semi_major"], p.beta0, c["scaling"], p.effective_radius,
                    p.reduced_modulus)
    np.testing.assert_allclose(c["approach"], d, rtol=1e-11, atol=1e-20)


def test_perpendicular_cylinders_are_circular_jkr_like():
    p = dim.contact_parameters(**{**SI, "skew_angle": np.pi / 2})
    assert p.beta0 == pytest.approx(1.0, abs=1e-12)
    assert p.effective_radius == pytest.approx(1e-3)


@pytest.mark.parametrize("key, value", [("work_of_adhesion", -1.0), ("max_adhesive_stress", 0.0),
                                        ("skew_angle", 0.0), ("cylinder_radius", np.nan),
                                        ("poisson_ratio_1", 0.6)])
def test_bad_input(key, value):
    name = {"poisson_ratio_1": "nu1"}.get(key, key)
    with pytest.raises(ValueError, match=name):
        dim.contact_parameters(**{**SI, key: value})
