"""The analytic-versus-BEM field cases (dhfield.analysis.fields); the sampling, metrics, polar resampling and
refinement helpers have their own test modules."""
from __future__ import annotations

import numpy as np
import pytest

from dhfield import bem
from dhfield.analysis import field_sampling, fields
from dhfield.models import dh_elliptic as model

# --- tolerances -------------------------------------------------------------------
#: Gap inside the contact (beta0 = 0.9, mu = 1, a* = 1.2, 256^2 cells): measured 7.4e-4 (absolute, nondimensional units).
ATOL_CONTACT_GAP_256 = 1.5e-3
#: Symmetry mode vs full grid (issue 4: 1e-12).
RTOL_SYMMETRY = 1e-12
#: SI vs nondimensional: the same floating-point operations up to scaled inputs (rounding);
#: pressures pass through fewer operations than the FFT'd displacements.
RTOL_UNITS_PRESSURE = 1e-12
RTOL_UNITS_FIELD = 1e-11

CASE = dict(beta0=0.9, mu=1.0, a_star=1.2)


@pytest.fixture(scope="module")
def dh256():
    return fields.model_case(256, CASE["beta0"], CASE["mu"], CASE["a_star"])


# --- BEM cross-check ----------------------------------------------------------------


def test_numerical_gap_vanishes_in_the_contact(dh256):
    err = dh256.gap_errors()
    assert np.max(np.abs(dh256.gap_numerical[dh256.masks["contact"]])) <= ATOL_CONTACT_GAP_256
    assert err["contact"]["count"] > 0 and err["annulus"]["count"] > 0 and err["outside"]["count"] > 0


def test_symmetric_and_full_cases_agree():
    full = fields.hertz_case(48, 1.0, 0.8, symmetric=False)
    sym = fields.hertz_case(48, 1.0, 0.8, symmetric=True)
    scale = np.abs(full.displacement_numerical).max()
    assert np.max(np.abs(full.displacement_numerical - sym.displacement_numerical)) <= RTOL_SYMMETRY * scale


def test_bad_input():
    grid = bem.Grid.centered(16, 2.0)
    with pytest.raises(ValueError, match="pressure"):
        field_sampling.numerical_displacement(np.ones((16, 15)), grid)
    with pytest.raises(ValueError, match="semi_major"):
        field_sampling.hertz_pressure(grid, -1.0, 0.5)
    with pytest.raises(ValueError, match="beta"):
        fields.hertz_case(16, 1.0, 1.5)
    with pytest.raises(ValueError, match="n"):
        fields.hertz_case(4, 1.0, 0.5)
    with pytest.raises(ValueError, match="adhesive_semi_major"):
        fields.dh_case(16, 1.0, 0.5, 0.9, 1.0)


def test_unit_neutrality_si_vs_nondimensional():
    # the same Hertz problem in SI (a = 0.2 mm, R = 5 cm, E* = 2 GPa) and in R = E* = a = 1 units:
    # pressures scale with E* a/R, displacements and gaps with a^2/R
    a, r, e, beta = 2e-4, 0.05, 2e9, 0.75
    si = fields.hertz_case(32, a, beta, effective_radius=r, reduced_modulus=e)
    nd = fields.hertz_case(32, 1.0, beta)
    p_s, u_s = e * a / r, a * a / r
    assert np.allclose(si.pressure / p_s, nd.pressure, rtol=RTOL_UNITS_PRESSURE,
                       atol=RTOL_UNITS_PRESSURE * nd.pressure.max())
    for name in ("displacement_numerical", "displacement_analytic", "gap_numerical", "gap_analytic"):
        ref = getattr(nd, name)
        assert np.allclose(getattr(si, name) / u_s, ref, rtol=RTOL_UNITS_FIELD,
                           atol=RTOL_UNITS_FIELD * np.abs(ref).max()), name


def test_adhesive_state_takes_beta0_and_mu_by_keyword():
    """(mu, beta0) was the old positional order: a positional call would swap them silently."""
    with pytest.raises(TypeError, match="positional"):
        fields.adhesive_state(1.0, 1.0, 0.9)
    c, v = fields.adhesive_state(1.0, beta0=0.9, mu=1.0)
    assert (c, v) == tuple(float(t) for t in model.solve_adhesive_axis(1.0, beta0=0.9, mu=1.0))
