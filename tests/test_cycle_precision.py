"""``dhfield cycle``: the energy lost with the jump-in convention's spread, printed to the digits it supports."""
from __future__ import annotations

import math

import numpy as np
import pytest

from dhfield.analysis import compare, spring as compliance
from dhfield.cli import main

# the PDMS contact of issue 40 at 60 degrees: beta0 = 0.4826, mu = 11.40
PDMS_60 = ["--youngs-modulus", "1.8e6", "--poisson-ratio", "0.49", "--cylinder-radius", "3e-3",
           "--skew-angle-deg", "60", "--work-of-adhesion", "0.045", "--adhesive-stress", "3e5"]


def _loading_branch_work(model, mu, beta0, delta_1, delta_2, n=40001):
    """int W* d(delta*) along the stable (loading) branch between the states at delta_1 and delta_2,
    by the trapezoid rule on a fine grid of contact sizes (independent of compliance's quadrature)."""
    a_out = float(compare.pull_off(model, mu=mu, beta0=beta0, control="displacement", warn=False)["a_star"])
    a = np.linspace(a_out, 20.0, 20001)
    c = compare.load_curve(model, mu=mu, beta0=beta0, a_star=a)
    d = np.asarray(c["delta_star"])
    assert np.all(np.diff(d) > 0)  # the stable branch: delta rises with a
    a1, a2 = np.interp([delta_1, delta_2], d, a)
    grid = np.linspace(a1, a2, n)
    c = compare.load_curve(model, mu=mu, beta0=beta0, a_star=grid)
    return float(np.trapezoid(np.asarray(c["W_star"]), np.asarray(c["delta_star"])))


def test_convention_spread_is_the_work_between_the_two_landings():
    # rigid machine: the contact lands at delta_s; the two conventions (contact-curve end, Dugdale
    # range -1/mu) differ by the work along the loading branch between their landing states
    mu, beta0 = 11.400482908952114, 0.48262778112325216
    rec = compliance.loading_cycle("md-elliptic", mu=mu, beta0=beta0)
    end = rec["jump_in_start_delta_star"]
    expected = abs(_loading_branch_work("md-elliptic", mu, beta0, end, -1.0 / mu))
    assert rec["energy_lost_convention_star"] == pytest.approx(expected, rel=1e-5)
    assert rec["energy_lost_uncertainty_star"] == pytest.approx(
        rec["energy_lost_error_star"] + rec["energy_lost_convention_star"], rel=1e-12)


def test_physical_jump_in_has_no_convention_spread():
    rec = compliance.loading_cycle("jkr", mu=2.0, beta0=1.0)
    assert rec["energy_lost_convention_star"] == 0.0
    assert rec["energy_lost_uncertainty_star"] == rec["energy_lost_error_star"]


def _lines(out):
    return {line.split()[0]: line.split()[1:] for line in out.splitlines() if line.strip()}


def test_cli_prints_the_energy_to_the_digits_its_uncertainty_supports(capsys):
    # issue 40: "7.257e-09 +- 4.8e-18 J" -- the float noise of the quadrature was the only uncertainty
    code = main(["cycle", *PDMS_60])
    out, err = capsys.readouterr()
    assert code == 0, err
    lines = _lines(out)
    value_text, unit = lines["energy_lost"]
    u = float(lines["energy_lost_uncertainty"][0])
    conv, quad = float(lines["energy_lost_convention"][0]), float(lines["energy_lost_error"][0])
    assert unit == "J" and u >= conv > 1e3 * quad  # the convention, not float noise, sets the precision
    mantissa = value_text.split("e")[0].replace("-", "").replace(".", "").lstrip("0")
    value = float(value_text)
    assert len(mantissa) == math.floor(math.log10(abs(value))) - math.floor(math.log10(u)) + 2  # 2nd digit of u
    assert lines["energy_lost_star"][0] == "0.810"


@pytest.mark.parametrize("value, uncertainty, text", [
    (1.566931205e-09, 1.84e-10, "1.57e-09"), (0.8101828563, 0.095, "0.810"), (-0.5, 0.02, "-0.500"),
    (1234.5, 5.0, "1234.5"), (12.3456, float("nan"), "12.35 (uncertainty unknown)"), (2.0, 0.0, "2"),
])
def test_round_to_uncertainty(value, uncertainty, text):
    from dhfield.io.cycle import round_to_uncertainty

    assert round_to_uncertainty(value, uncertainty) == text
