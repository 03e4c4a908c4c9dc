"""Tests of the traction-separation laws (dhfield.bem.laws)."""
from __future__ import annotations

import numpy as np
import pytest
from scipy import integrate

from dhfield.bem.laws import DugdaleLaw, ExponentialLaw, cell_fraction_below, law_from_name

#: Closed forms in double precision.
RTOL_CLOSED_FORM = 1e-14
#: scipy.integrate.quad on a smooth integrand asked for 1e-12 relative.
RTOL_QUAD = 1e-10
#: Brute-force sub-sampling of a cell on a 1000 x 1000 midpoint lattice: the area of a
#: half-plane cut is resolved to ~1/1000 of a cell (boundary cells, half of them cut).
ATOL_SUBSAMPLE = 2e-3


def test_dugdale_stress_and_work():
    law = DugdaleLaw(2.0, 0.25)
    np.testing.assert_array_equal(law.stress([0.0, 0.1, 0.2499, 0.25, 1.0]), [2.0, 2.0, 2.0, 0.0, 0.0])
    assert law.work_of_adhesion == pytest.approx(0.5, rel=RTOL_CLOSED_FORM)
    # Maugis: h0 = dgamma/sigma0
    assert DugdaleLaw.from_work_of_adhesion(4.0, 0.05).range == pytest.approx(0.0125, rel=RTOL_CLOSED_FORM)
    # energy still to be paid is the integral of the stress beyond h
    assert law.energy(0.1) == pytest.approx(2.0 * 0.15, rel=RTOL_CLOSED_FORM)


def test_exponential_work_by_quadrature():
    law = ExponentialLaw.from_work_of_adhesion(3.0, 0.6)
    work, _ = integrate.quad(law.stress, 0.0, np.inf, epsabs=0.0, epsrel=1e-12)
    assert work == pytest.approx(0.6, rel=RTOL_QUAD)
    assert law.work_of_adhesion == pytest.approx(0.6, rel=RTOL_CLOSED_FORM)
    assert float(law.stress(0.0)) == pytest.approx(3.0, rel=RTOL_CLOSED_FORM)
    tail, _ = integrate.quad(law.stress, 0.3, np.inf, epsabs=0.0, epsrel=1e-12)
    assert float(law.energy(0.3)) == pytest.approx(tail, rel=RTOL_QUAD)


def test_law_from_name_and_bad_input():
    assert isinstance(law_from_name("dugdale", 1.0), DugdaleLaw)
    assert isinstance(law_from_name("exponential", 1.0), ExponentialLaw)
    with pytest.raises(ValueError, match="law must be one of"):
        law_from_name("lj", 1.0)
    with pytest.raises(ValueError, match="max_stress"):
        DugdaleLaw(-1.0, 1.0)
    with pytest.raises(ValueError, match="range"):
        ExponentialLaw(1.0, 0.0)


@pytest.mark.parametrize("gx,gy,excess", [(1.0, 0.3, 0.1), (0.2, 0.9, -0.35), (0.5, 0.5, 0.0),
                                         (1.0, 0.0, 0.2), (0.7, 0.2, 0.44), (0.7, 0.2, -0.5)])
def test_cell_fraction_matches_subsampling(gx, gy, excess):
    # unit cell [-1/2, 1/2]^2, field f = f_c + gx x + gy y, threshold - f_c = excess
    m = 1000
    t = (np.arange(m) + 0.5) / m - 0.5
    x, y = np.meshgrid(t, t, indexing="ij")
    brute = float(np.mean(gx * x + gy * y < excess))
    exact = float(cell_fraction_below(excess, abs(gx), abs(gy)))
    assert exact == pytest.approx(brute, abs=ATOL_SUBSAMPLE)


def test_cell_fraction_limits_and_symmetry():
    s = np.linspace(-2.0, 2.0, 101)
    f = cell_fraction_below(s, 1.3, 0.4)
    g = cell_fraction_below(-s, 1.3, 0.4)
    np.testing.assert_allclose(f + g, 1.0, rtol=0, atol=RTOL_CLOSED_FORM)   # F(s) + F(-s) = 1
    assert np.all(np.diff(f) >= 0)                                          # monotone
    assert f[0] == 0.0 and f[-1] == 1.0
    # zero spread: a step
    np.testing.assert_array_equal(cell_fraction_below([-1e-9, 0.0, 1e-9], 0.0, 0.0), [0.0, 0.5, 1.0])
