"""The paper's units (Eqs. 32-35) and the one SI wrapper of the analytic models (dhfield.core.units)."""
import math

import numpy as np
import pytest

from dhfield.core import units
from dhfield.models import (dh_circular, dmt, jkr, jkr_elliptic, jkr_elliptic_energy, maugis_dugdale,
                            md_elliptic)

R, E, W, S0 = 2.5e-3, 7.0e6, 0.04, 3.0e5
RTOL = 1e-14  # a few ulps: the closed forms below use ** (1/3), the module np.cbrt


def test_units_closed_forms():
    c_r = (R**2 * W / E) ** (1.0 / 3.0)  # Eq. (33)
    assert units.length_unit(R, E, W) == pytest.approx(c_r, rel=RTOL)
    assert units.approach_unit(R, E, W) == pytest.approx(c_r**2 / R, rel=RTOL)
    assert units.load_unit(R, W) == pytest.approx(2.0 * math.pi * R * W, rel=RTOL)  # Eq. (34), circle
    sin_skew = math.sin(math.radians(50.0))
    assert units.load_unit(R, W, sin_skew) == pytest.approx(2.0 * math.pi * R * W / sin_skew, rel=RTOL)
    mu = S0 * (R / (E**2 * W)) ** (1.0 / 3.0)  # Eq. (35)
    assert units.tabor_parameter(S0, R, E, W) == pytest.approx(mu, rel=RTOL)
    # unchecked paths give the same numbers
    assert units.length_unit(R, E, W, checked=False) == units.length_unit(R, E, W)
    assert units.tabor_parameter(S0, R, E, W, checked=False) == units.tabor_parameter(S0, R, E, W)


@pytest.mark.parametrize("which, powers", [
    # exponents of (R, E*, dgamma) in c_r, c_r^2/R, 2 pi R dgamma, mu (at fixed sigma0)
    ("R", (2 / 3, 1 / 3, 1.0, 1 / 3)),
    ("E", (-1 / 3, -2 / 3, 0.0, -2 / 3)),
    ("W", (1 / 3, 2 / 3, 1.0, -1 / 3)),
])
def test_units_scale_with_the_right_powers(which, powers):
    k = 7.3
    base = {"R": R, "E": E, "W": W}
    scaled = {**base, which: base[which] * k}

    def all_units(p):
        return (units.length_unit(p["R"], p["E"], p["W"]), units.approach_unit(p["R"], p["E"], p["W"]),
                units.load_unit(p["R"], p["W"]), units.tabor_parameter(S0, p["R"], p["E"], p["W"]))

    for u0, u1, n in zip(all_units(base), all_units(scaled), powers):
        assert u1 / u0 == pytest.approx(k**n, rel=RTOL)


@pytest.mark.parametrize("call, name", [
    (lambda: units.length_unit(-1.0, E, W), "effective_radius"),
    (lambda: units.approach_unit(R, 0.0, W), "reduced_modulus"),
    (lambda: units.length_unit(R, E, float("nan")), "work_of_adhesion"),
    (lambda: units.load_unit(R, -W), "work_of_adhesion"),
    (lambda: units.load_unit(float("inf"), W), "effective_radius"),
    (lambda: units.tabor_parameter(-1.0, R, E, W), "max_adhesive_stress"),
    (lambda: units.check_contact_size("contact_radius", -1e-6), "contact_radius"),
    (lambda: units.si_pull_off(jkr.pull_off_nondimensional, R, E, W, control="grips"), "control"),
    (lambda: units.si_pull_off(dh_circular.pull_off_nondimensional, 1.0, 1e6, 0.05, 1e18, check_mu=True), "mu"),
])
def test_bad_input_is_named(call, name):
    with pytest.raises(ValueError, match=rf"^{name} "):
        call()


def test_si_pull_off_of_jkr_is_the_closed_form():
    """JKR load control: W = -3/2 pi R dgamma, a^3 = 9 pi dgamma R^2/(8 E*) (Johnson 1985, Sec. 5.5)."""
    rec = units.si_pull_off(jkr.pull_off_nondimensional, R, E, W)
    assert rec.force == pytest.approx(-1.5 * math.pi * R * W, rel=RTOL)
    assert rec.semi_major == pytest.approx((9.0 * math.pi * W * R**2 / (8.0 * E)) ** (1.0 / 3.0), rel=RTOL)
    assert rec.r_major == rec.r_minor == R and np.isnan(rec.max_adhesive_stress)


def test_si_circular_load_curve_is_dmt_closed_form():
    """DMT: W = 4E* a^3/(3R) - 2 pi R dgamma, delta = a^2/R (Derjaguin, Muller & Toporov 1975)."""
    a = np.array([0.0, 1e-5, 4e-5])
    curve = units.si_circular_load_curve("dmt", dmt.load_curve_nondimensional, a, R, E, W)
    np.testing.assert_allclose(curve.force, 4 * E * a**3 / (3 * R) - 2 * math.pi * R * W, rtol=RTOL, atol=1e-18)
    np.testing.assert_allclose(curve.approach, a**2 / R, rtol=RTOL)


# One problem in two consistent unit systems (m, N, Pa, N/m and mm, N, N/mm^2, N/mm): every model's SI
# wrapper gives the same force in newtons.
_MM = {"R": R * 1e3, "E": E * 1e-6, "W": W * 1e-3, "S0": S0 * 1e-6}
_MODELS = [
    ("jkr", lambda R, E, W, S0: jkr.pull_off_force(R, E, W)),
    ("dmt", lambda R, E, W, S0: dmt.pull_off_force(R, E, W)),
    ("dh-circular", lambda R, E, W, S0: dh_circular.pull_off_force(R, E, W, S0)),
    ("md", lambda R, E, W, S0: maugis_dugdale.pull_off_force(R, E, W, S0, control="displacement")),
    ("jkr-elliptic", lambda R, E, W, S0: jkr_elliptic.pull_off_force(R, E, W, radius_ratio=4.0)),
    ("jkr-elliptic-energy", lambda R, E, W, S0: jkr_elliptic_energy.pull_off_force(R, E, W, beta0=0.5)),
    ("md-elliptic", lambda R, E, W, S0: md_elliptic.pull_off_force(R, E, W, S0, radius_ratio=4.0)),
]


@pytest.mark.parametrize("name, force", _MODELS, ids=[m[0] for m in _MODELS])
def test_pull_off_force_is_unit_neutral(name, force):
    f_si = force(R, E, W, S0)
    f_mm = force(_MM["R"], _MM["E"], _MM["W"], _MM["S0"])
    assert f_si < 0
    assert f_mm == pytest.approx(f_si, rel=1e-12)
