"""dhfield.analysis.adhesion_map: the elliptical adhesion map against its reference (limits, shapes, refusals).

Provenance of the limits:

* beta0 = 1 (90 deg): the reference is Maugis-Dugdale on the sphere by construction
  (dhfield.models.md_elliptic: W* = -1 + (W*_JKR + 1) g, g from MD, GVG(1) = -3/4 exactly).
* mu -> 0: DMT, W = -2 pi R dgamma (Derjaguin), is the limit of MD (Maugis 1992), of the
  reference and of the circular double-Hertz model (Greenwood & Johnson 1998); the elliptical
  JKR models do not depend on mu, and the paper's elliptical double-Hertz model imposes
  dgamma on the major axis only (Eq. 31), so off the circle it does not reach DMT.
* mu -> infinity: the reference's JKR limit is GVG (Giudici, Vella & Griffiths 2025).
"""
from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from dhfield.analysis import adhesion_map as am
from dhfield.analysis import compare
from dhfield.core.validation import TABOR_RANGE

#: TABOR_RANGE's documented promise: at mu = 1e-6 every model is at its DMT limit to < 1e-3 relative.
DMT_TOL = 1e-3
#: Round-off of the reference's identity at the circle (a few operations on O(1) numbers).
EXACT = 1e-12
ANGLES = np.array([10.0, 20.0, 30.0, 45.0, 60.0, 90.0])


@pytest.fixture(scope="module")
def limits():
    """The six map models at the ends of the accepted mu range (cheap: 6 x 4 points)."""
    return am.adhesion_map(ANGLES, [TABOR_RANGE[0], 0.3, 1.0, 1e4])


def test_reference_is_the_registered_recommended_model():
    # the map's reference is the library's default model under its registered name, labelled as the
    # figures label it, and listed once even when the caller names it again
    from dhfield.io.figures import MODEL_LABELS as FIGURE_LABELS

    assert am.REFERENCE_MODEL == "md-elliptic" == compare.DEFAULT_MODEL
    assert am.REFERENCE_MODEL in compare.MODEL_NAMES
    assert am.MODEL_LABELS[am.REFERENCE_MODEL] == FIGURE_LABELS["md-elliptic"] == "MD elliptical (recommended)"
    assert len(set(am.MAP_MODEL_NAMES)) == len(am.MAP_MODEL_NAMES)
    r = am.adhesion_map([60.0], [1.0], models=("dmt", "md-elliptic", "dmt"))
    assert r.models == ("md-elliptic", "dmt")
    with pytest.raises(ValueError, match="models") as exc:
        am.adhesion_map([60.0], [1.0], models=("no-such-model",))
    assert str(exc.value).count("md-elliptic") == 1


def test_shapes_types_and_order(limits):
    r = limits
    assert r.models == am.MAP_MODEL_NAMES and r.models[0] == am.REFERENCE_MODEL == r.reference
    n = (len(am.MAP_MODEL_NAMES), ANGLES.size, 4)
    for arr in (r.force, r.deviation, r.status):
        assert arr.shape == n
    assert r.status.dtype == np.int8
    assert r.reference_force.shape == r.validated.shape == n[1:]
    assert r.beta0.shape == ANGLES.shape and np.all(np.diff(r.beta0) > 0)
    np.testing.assert_array_equal(r.deviation[0], 0.0)  # the reference against itself
    assert "validated against the BEM only" in r.reference_note and set(r.notes) == set(r.models)


def test_crossing_angle_to_beta0():
    # the issue's own pairs (60 deg: the PDMS case beta0 = 0.4826; 30 deg: 0.1806) and the circle at 90 deg
    r = am.adhesion_map([30.0, 60.0, 90.0], [1.0], models=("dmt",))
    np.testing.assert_allclose(r.beta0, [0.1806, 0.4826, 1.0], atol=5e-5)


def test_ninety_degrees_is_md_on_the_sphere(limits):
    i = limits.index("md")
    np.testing.assert_allclose(limits.deviation[i, -1], 0.0, atol=EXACT)


def test_dmt_limit(limits):
    r = limits
    # reference, MD and DMT at DMT (W/(pi R dgamma) = -2) at every angle
    np.testing.assert_allclose(r.reference_force[:, 0], -2.0, rtol=DMT_TOL)
    for m in ("md", "dmt"):
        np.testing.assert_allclose(r.deviation[r.index(m), :, 0], 0.0, atol=DMT_TOL)
    np.testing.assert_array_equal(r.force[r.index("dmt")], -2.0)  # closed form, any mu
    # the paper's model reaches DMT on the circle only (dgamma on the major axis, Eq. 31)
    dh = r.deviation[r.index("dh-elliptic"), :, 0]
    assert abs(dh[-1]) < DMT_TOL
    assert np.all(dh[ANGLES <= 60] < -0.1)
    # the elliptical JKR models do not depend on mu; GVG on the circle is JKR: 1.5/2 of DMT
    for m in ("jkr-elliptic", "jkr-elliptic-energy"):
        f = r.force[r.index(m)]
        np.testing.assert_array_equal(f, f[:, :1] * np.ones_like(f))
    np.testing.assert_allclose(r.deviation[r.index("jkr-elliptic-energy"), -1, 0], -0.25, atol=DMT_TOL)


def test_jkr_limit_is_gvg(limits):
    # recommended - GVG = (1 - g)(W*_DMT,ell - W*_GVG), 1 - g = 3 (W_MD/W_JKR - 1) on the sphere and
    # |W*_DMT,ell - W*_GVG|/|W*_GVG| = 2/|F_GVG| - 1 <= 1 for every angle >= 10 deg (F_GVG <= -1.33):
    # bounded by 3 x the sphere's MD-JKR gap, 4x to cover the second order of the ratio
    md = compare.pull_off("md", beta0=1.0, mu=1e4)["W_star"]
    gap = abs(md / compare.pull_off("jkr", beta0=1.0, mu=1e4)["W_star"] - 1.0)
    assert gap < 1e-6
    dev = limits.deviation[limits.index("jkr-elliptic-energy"), :, -1]
    assert np.all(np.abs(dev) <= 4 * gap + EXACT)


def test_validated_region_marks_the_ground_truth_extent(limits):
    # beta0 >= 0.1 is 18.8 deg and above (both stored ground truths: 0.1-0.3 and 0.5-1); mu 0.3 and 1
    # inside, 1e-6 and 1e4 outside
    v = limits.validated
    expected = np.zeros_like(v)
    expected[ANGLES >= 18.8, 1:3] = True
    np.testing.assert_array_equal(v, expected)
    r = am.adhesion_map([30.0, 90.0], [1.0, 10.0], models=("dmt",), validated_beta0=(0.1, 1.0),
                        validated_mu=(0.1, 10.0))
    assert r.validated.all() and "in [0.1, 10]" in r.reference_note


def test_warnings_are_recorded_not_raised(limits):
    s = limits.status[limits.index("dmt")]
    # DMT is validated for beta0 = 1, mu <= 0.09 (compare.VALIDITY_RANGES): answered there, warned elsewhere
    assert s[-1, 0] == 0
    assert np.all(s[:-1] == 1) and np.all(s[:, 1:] == 1)
    assert "validated for" in limits.notes["dmt"]
    assert limits.notes[am.REFERENCE_MODEL] == ""


def test_refusals_are_recorded_not_raised():
    # the closures refuse beta0 < 0.3 (crossing below ~44 deg): no answer there, an answer at 60 deg
    r = am.adhesion_map([30.0, 60.0], [1.0], models=("dh-elliptic-two-axis",))
    i = r.index("dh-elliptic-two-axis")
    assert r.status[i, 0, 0] == am.STATUS_MEANINGS.index("refused") and np.isnan(r.force[i, 0, 0])
    assert r.status[i, 1, 0] <= 1 and np.isfinite(r.deviation[i, 1, 0])
    assert "refused 1 of 2 points" in r.notes["dh-elliptic-two-axis"] and "beta0" in r.notes["dh-elliptic-two-axis"]
    assert r.fraction_answered()["dh-elliptic-two-axis"] == 0.5
    assert not r.within(1.0)[i, 0, 0]  # no answer is never 'within'


def test_fractions(limits):
    f1, f5 = limits.fraction_within(0.01), limits.fraction_within(0.05)
    assert f1[am.REFERENCE_MODEL] == f5[am.REFERENCE_MODEL] == 1.0
    for m in limits.models:
        assert 0.0 <= f1[m] <= f5[m] <= 1.0
    assert all(v == 1.0 for v in limits.fraction_answered().values())


def test_default_grid():
    a, m = am.map_grid(5, 9)
    np.testing.assert_allclose(a, [10, 30, 50, 70, 90])
    np.testing.assert_allclose(m, np.geomspace(0.01, 100, 9))


@pytest.mark.parametrize("kwargs, name", [
    (dict(crossing_angle_deg=[0.0, 45.0]), "crossing_angle_deg"),
    (dict(crossing_angle_deg=[45.0, 95.0]), "crossing_angle_deg"),
    (dict(crossing_angle_deg=[60.0, 45.0]), "crossing_angle_deg"),
    (dict(crossing_angle_deg=[[45.0]]), "crossing_angle_deg"),
    (dict(mu=[0.0, 1.0]), "mu"),
    (dict(mu=[1.0, np.nan]), "mu"),
    (dict(mu=[2.0, 1.0]), "mu"),
    (dict(models=("no-such-model",)), "models"),
    (dict(models=()), "models"),
    (dict(validated_beta0=(1.0, 0.5)), "validated_beta0"),
    (dict(validated_mu=(0.3,)), "validated_mu"),
])
def test_bad_input_names_the_parameter(kwargs, name):
    args = dict(crossing_angle_deg=[45.0], mu=[1.0], models=("dmt",))
    with pytest.raises(ValueError, match=name):
        am.adhesion_map(**{**args, **kwargs})


@pytest.mark.parametrize("args, name", [((1, 5), "n_angle"), ((5, 2.5), "n_mu"), ((5, True), "n_mu")])
def test_bad_grid_names_the_parameter(args, name):
    with pytest.raises(ValueError, match=name):
        am.map_grid(*args)


def test_bad_tolerance_and_model(limits):
    with pytest.raises(ValueError, match="tolerance"):
        limits.within(-0.01)
    with pytest.raises(ValueError, match="model"):
        limits.index("jkr")


@settings(max_examples=15, deadline=None)
@given(angle=st.floats(10.0, 90.0), log_mu=st.floats(-2.0, 2.0))
def test_every_map_model_answers_in_the_domain(angle, log_mu):
    # crossing angle 10-90 deg x mu 0.01-100: every model of the map answers (possibly warned), with a
    # pull-off between DMT (-2, the rigid limit) and zero
    r = am.adhesion_map([angle], [10.0 ** log_mu])
    assert np.all(r.status <= 1)
    assert np.all((r.force >= -2.0 - EXACT) & (r.force < 0.0))


def test_recommended_pull_off_is_the_reference_of_the_map():
    # the one adapter that names the recommended model: W* = -s + (W*_GVG + s) g(mu_e) (Eq. T1),
    # g = (W*_MD + 1)/(1/4) from MD on the sphere at mu_e = mu s^(1/4) (Eq. T0) and GVG's elliptical JKR
    # (built here from those two models), and the map's reference column is its force 2 W*/s (Eq. 34)
    from dhfield.models import jkr_elliptic_energy, maugis_dugdale
    from dhfield.core.geometry import sin_skew_angle

    r = am.adhesion_map([30.0, 60.0, 90.0], [0.1, 1.0, 10.0], models=("dmt",))
    b, m = np.meshgrid(r.beta0, r.mu, indexing="ij")
    w = am.recommended_pull_off(beta0=b, mu=m)
    s = sin_skew_angle(b)
    g = (maugis_dugdale.pull_off_nondimensional(beta0=1.0, mu=m * s ** 0.25).W_star + 1.0) / 0.25
    expected = -s + (jkr_elliptic_energy.pull_off_nondimensional(beta0=b, mu=1.0).W_star + s) * g
    np.testing.assert_allclose(w, expected, rtol=1e-12)
    np.testing.assert_allclose(2.0 * w / s, r.reference_force, rtol=EXACT)
    assert w.shape == b.shape
