"""verification.jkr_limit: the numerical JKR limit (BEM W*(mu) extrapolated to mu -> infinity).

Provenance:

* Maugis-Dugdale on the sphere (Maugis 1992, dhfield.models.maugis_dugdale) tends to JKR (1971),
  W* = -3/4 in load control; sampled at the stored study's mu it is the test signal of the
  extrapolation (every fit of the family must return -3/4).
* Synthetic data built exactly of one form (transition weight, or a series in 1/mu^2) must be
  extrapolated exactly (round-off).
* The stored BEM (data/adhesive_ground_truth.nc) on the sphere must extrapolate to -3/4 within
  the stated error; GVG (Giudici, Vella & Griffiths 2025) is the energy-minimising elliptical JKR.
"""
from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from dhfield.models import maugis_dugdale as md
from verification import jkr_limit as jl

DATASET = Path(__file__).resolve().parent.parent / "data" / "adhesive_ground_truth.nc"
#: mu of the stored study (data/adhesive_ground_truth.nc)
STUDY_MU = np.array([0.3, 0.5, 1.0, 2.0, 5.0])
#: The truncation of the 1/mu^2 series through mu = 2, 5 on MD is 0.042 % (its next term, ~1/mu^4):
#: every member of the family must be within 0.05 % on the sphere.
TOL_FAMILY = 5e-4
#: Round-off of a least-squares or 3x3 solve on O(1) numbers.
EXACT = 1e-12


def test_md_at_the_study_mu_extrapolates_to_jkr():
    w = md.pull_off_nondimensional(beta0=1.0, mu=STUDY_MU).W_star
    lim = jl.extrapolate_jkr_limit(STUDY_MU, w, 1.0)
    assert lim.mu_used == (1.0, 2.0, 5.0)  # the JKR side only (mu >= 1), the three largest
    # the transition form is MD's own weight: exact on the sphere
    assert abs(lim.w_inf - jl.W_STAR_JKR_SPHERE) < EXACT
    for label, v in lim.estimates.items():
        assert abs(v / jl.W_STAR_JKR_SPHERE - 1) < TOL_FAMILY, label
    # the series members are genuine extrapolations (not the identity): they differ from -3/4
    series = [v for k, v in lim.estimates.items() if k.startswith("1/mu")]
    assert len(series) == 2 and all(abs(v + 0.75) > 1e-6 for v in series)
    # the stated error covers the truth
    assert abs(lim.w_inf + 0.75) <= lim.error and lim.bem_error == 0.0


def test_md_approaches_jkr_as_one_over_mu_squared():
    # the form the series assumes: (W*_MD + 3/4) mu^2 tends to a constant (local slope -2 in log-log)
    mu = np.array([50.0, 100.0, 200.0])
    d = md.pull_off_nondimensional(beta0=1.0, mu=mu).W_star + 0.75
    slope = np.diff(np.log(np.abs(d))) / np.diff(np.log(mu))
    np.testing.assert_allclose(slope, -2.0, atol=2e-3)


@pytest.mark.parametrize("w_inf, s", [(-0.6531, 0.8775), (-0.41, 0.5), (-0.75, 1.0)])
def test_synthetic_transition_form_is_recovered_exactly(w_inf, s):
    g = jl.sphere_transition_weight(STUDY_MU)
    w = -s + (w_inf + s) * g
    lim = jl.extrapolate_jkr_limit(STUDY_MU, w, s)
    assert abs(lim.w_inf - w_inf) < EXACT
    for k, v in lim.estimates.items():
        if k.startswith("g,"):
            assert abs(v - w_inf) < EXACT, k


def test_series_limit_is_exact_on_a_series():
    mu = np.array([1.0, 2.0, 5.0])
    w = -0.7 + 0.03 / mu**2 - 0.01 / mu**4
    assert abs(jl.series_limit(mu, w, 3) + 0.7) < EXACT
    assert abs(jl.series_limit(mu[1:], -0.7 + 0.03 / mu[1:] ** 2, 2) + 0.7) < EXACT


def test_bem_uncertainty_enters_over_g():
    w = md.pull_off_nondimensional(beta0=1.0, mu=STUDY_MU).W_star
    unc = np.full(STUDY_MU.shape, 1e-3)
    lim = jl.extrapolate_jkr_limit(STUDY_MU, w, 1.0, unc)
    assert lim.bem_error == pytest.approx(1e-3 / jl.sphere_transition_weight(5.0), rel=EXACT)
    assert lim.error == pytest.approx(lim.fit_spread + lim.bem_error, rel=EXACT)


def test_nan_and_low_mu_are_skipped():
    w = md.pull_off_nondimensional(beta0=1.0, mu=STUDY_MU).W_star
    w[-1] = np.nan
    lim = jl.extrapolate_jkr_limit(STUDY_MU, w, 1.0)
    assert lim.mu_used == (1.0, 2.0)


@pytest.mark.parametrize("kwargs, match", [
    (dict(mu=[0.3, 0.5], w_star=[-0.9, -0.85], sin_skew=1.0), "mu must include"),
    (dict(mu=[1.0, 2.0], w_star=[-0.8, -0.76], sin_skew=0.0), "sin_skew"),
    (dict(mu=[1.0, 2.0], w_star=[-0.8, -0.76], sin_skew=1.5), "sin_skew"),
])
def test_bad_input_names_the_parameter(kwargs, match):
    with pytest.raises(ValueError, match=match):
        jl.extrapolate_jkr_limit(**kwargs)


@pytest.fixture(scope="module")
def rows():
    pytest.importorskip("xarray")
    if not DATASET.is_file():
        pytest.skip("no stored ground truth")
    return jl.bem_jkr_limits(DATASET)


def test_stored_bem_sphere_extrapolates_to_jkr(rows):
    sph = [r for r in rows if r["beta0"] == 1.0][0]["limit"]
    assert abs(sph.w_inf + 0.75) <= sph.error
    assert sph.error / 0.75 < 0.005  # an error estimate small enough to judge the JKR models


def test_stored_bem_limit_covers_gvg_and_excludes_jg_at_beta0_half(rows):
    assert [r["beta0"] for r in rows][0] == 0.5
    for r in rows:
        assert r["gvg_z"] <= 1.0, r["beta0"]
    # at beta0 = 0.5 JG's fixed-shape JKR is 2.5 % weaker than GVG: the BEM tells them apart
    assert rows[0]["jg_z"] > 3.0


def test_ladder_uncertainty_is_finite_where_two_levels_exist(rows):
    import xarray as xr

    with xr.open_dataset(DATASET) as ds:
        rel = jl.ladder_uncertainty(ds.load())
    assert np.isfinite(rel[-1]) and 0.0 < rel[-1] < 0.01
