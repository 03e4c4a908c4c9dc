"""Tests of the gridded Hertz/DH fields and their BEM cross-check (dhfield.fields)."""
from __future__ import annotations

import math

import numpy as np
import pytest
from scipy import integrate

from dhfield import bem, double_hertz, fields, hertz, model

# --- tolerances -------------------------------------------------------------------
#: hemisphere_volume vs scipy dblquad asked for 1e-13 absolute.
ATOL_VOLUME = 1e-12
#: V(1, 1) = pi/6 exactly in the closed form: a few rounding errors of O(1) terms.
ATOL_QUARTER = 1e-15
#: Sums of exact cell averages: rounding of O(N^2) corner differences of O(1) volumes.
RTOL_LOAD = 1e-11
#: Cubic splines reproduce a quadratic exactly except for the boundary condition, whose
#: effect decays like 0.27^k at k cells from the domain edge: >= 16 cells here (~1e-10).
ATOL_POLAR_QUADRATIC = 1e-8
#: Annulus identity on 256^2 cells (beta0 = 0.9, mu = 1, a* = 1.2): measured 7.9e-4 relative
#: to max (1+v) h_H; O(h^1.5) discretisation of the square-root edges plus spline interpolation.
RTOL_ANNULUS_256 = 1.5e-3
#: Gap inside the contact, same case: measured 7.4e-4 (absolute, nondimensional units).
ATOL_CONTACT_GAP_256 = 1.5e-3
#: Refinement 64 -> 128 -> 256 (Hertz ellipse, cell averages), the issue's order target; the
#: RMS and off-edge orders measured here are 1.85-1.95 (second order in the smooth interior).
MIN_ORDER = 1.5
#: The whole-grid L-inf order is capped at 1.5 by the square-root edge (see fields docstring);
#: measured 1.38-1.46 between 128 and 2048 cells; this only guards against a regression.
MIN_ORDER_LINF = 1.25
#: Analytic identity h_DH = (1+v) h_H in the annulus (both closed forms): rounding only.
RTOL_ANALYTIC_IDENTITY = 1e-10
#: Cell average vs dblquad (asked for 1e-13 absolute) divided by a cell area of ~0.014.
ATOL_CELL_AVERAGE = 1e-10
#: Error ratio between N = 64 and 128 for an O(h^1.5) error is 2.8; 2^1.2 = 2.3 leaves margin.
MIN_RATIO_ANNULUS = 2.0 ** 1.2
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


# --- sampling -----------------------------------------------------------------------
@pytest.mark.parametrize("x, y", [(0.3, 0.4), (0.9, 0.8), (1.0, 1.0), (0.2, 1.3), (-0.5, 0.7), (0.99, -0.1),
                                  (2.0, 0.05)])
def test_hemisphere_volume_matches_quadrature(x, y):
    f = lambda t, s: math.sqrt(max(1.0 - s * s - t * t, 0.0))  # noqa: E731
    sx, sy = math.copysign(1.0, x), math.copysign(1.0, y)
    ref = sx * sy * integrate.dblquad(f, 0.0, abs(x), 0.0, abs(y), epsabs=1e-13, epsrel=1e-13)[0]
    assert fields.hemisphere_volume(x, y) == pytest.approx(ref, abs=ATOL_VOLUME)


def test_hemisphere_volume_quarter_is_pi_over_6():
    assert fields.hemisphere_volume(1.0, 1.0) == pytest.approx(math.pi / 6.0, abs=ATOL_QUARTER)
    assert fields.hemisphere_volume(5.0, 3.0) == pytest.approx(math.pi / 6.0, abs=ATOL_QUARTER)


def test_cell_averages_carry_the_hertz_load():
    # sum of cell means x cell area = 2/3 pi a b Po (Eq. 10) when the grid covers the ellipse
    a, beta = 1.0, 0.6
    grid = bem.Grid.centered(50, 1.3, ny=36, half_width_y=0.9)
    p = fields.hertz_pressure(grid, a, beta)
    load = p.sum() * grid.dx * grid.dy
    assert load == pytest.approx(float(hertz.load(a, beta)), rel=RTOL_LOAD)


def test_cell_averages_carry_the_dh_load():
    a, c, beta, v = 1.2, 1.9, 0.9, 1.1
    grid = bem.Grid.centered(64, 1.05 * c)
    p = fields.dh_pressure(grid, a, c, beta, v)
    load = p.sum() * grid.dx * grid.dy
    assert load == pytest.approx(float(double_hertz.load(a, c, beta, v)), rel=RTOL_LOAD)  # Eq. (25)


def test_cell_average_of_an_edge_cell_matches_quadrature():
    a, b, po = 1.0, 0.7, 2.0
    grid = bem.Grid(10, 10, 0.13, 0.11)
    avg = fields.ellipsoid_cell_average(grid, a, b, po)
    xe, ye = grid.x_edges, grid.y_edges
    f = lambda y, x: po * math.sqrt(max(1 - (x / a) ** 2 - (y / b) ** 2, 0.0))  # noqa: E731
    for i, j in [(8, 5), (9, 7), (5, 5), (7, 8)]:
        ref = integrate.dblquad(f, xe[i], xe[i + 1], ye[j], ye[j + 1], epsabs=1e-13)[0] / (grid.dx * grid.dy)
        assert avg[i, j] == pytest.approx(ref, abs=ATOL_CELL_AVERAGE)


def test_centre_sampling_is_eq7_and_dh_is_the_superposition():
    grid = bem.Grid.centered(32, 2.5)
    x, y = grid.mesh()
    p = fields.dh_pressure(grid, 1.0, 1.8, 0.8, 0.7, sampling="centre")
    assert np.array_equal(p, double_hertz.pressure(x, y, 1.0, 1.8, 0.8, 0.7))
    with pytest.raises(ValueError, match="sampling"):
        fields.hertz_pressure(grid, 1.0, 0.8, sampling="midpoint")


# --- comparison ---------------------------------------------------------------------
def test_compare_statistics():
    ana = np.array([[1.0, 2.0], [3.0, 4.0]])
    num = ana + np.array([[0.1, -0.2], [0.0, 0.0]])
    masks = {"a": np.array([[True, True], [False, False]]), "empty": np.zeros((2, 2), bool)}
    st = fields.compare(num, ana, masks)
    assert st["all"]["max"] == pytest.approx(0.2)
    assert st["a"]["rms"] == pytest.approx(math.sqrt((0.01 + 0.04) / 2))
    assert st["a"]["rel_max"] == pytest.approx(0.2 / 4.0)
    assert math.isnan(st["empty"]["max"]) and st["empty"]["count"] == 0
    with pytest.raises(ValueError, match="same shape"):
        fields.compare(num, ana[:1])


def test_region_masks_partition_the_plane():
    grid = bem.Grid.centered(40, 2.0)
    x, y = grid.mesh()
    m = fields.region_masks(x, y, 1.0, 0.8, 1.5)
    total = m["contact"].astype(int) + m["annulus"] + m["outside"]
    assert np.all(total == 1)
    assert m["contact"][20, 20] and m["outside"][0, 0]


# --- polar resampling ---------------------------------------------------------------
def test_polar_resampling_of_a_quadratic_field():
    grid = bem.Grid.centered(64, 2.0)
    x, y = grid.mesh()
    f = 3.0 * x**2 + 2.0 * y**2 - x * y
    r, th = fields.polar_grid(1.0, 31, 19, theta_max=2 * np.pi)
    fp = fields.to_polar(f, grid, r, th)
    ref = 3.0 * (r[:, None] * np.cos(th)) ** 2 + 2.0 * (r[:, None] * np.sin(th)) ** 2 \
        - r[:, None] ** 2 * np.cos(th) * np.sin(th)
    assert fp.shape == (31, 19)
    assert np.max(np.abs(fp - ref)) <= ATOL_POLAR_QUADRATIC
    assert np.isnan(fields.to_polar(f, grid, [5.0], [0.0])).all()
    with pytest.raises(ValueError, match="field"):
        fields.to_polar(f[:10], grid, r, th)


# --- BEM cross-check ----------------------------------------------------------------
def test_refinement_order():
    def err(n):
        case = fields.hertz_case(n, 1.0, 0.7)
        e = case.displacement_numerical - case.displacement_analytic
        return case.grid.dx, np.sqrt(np.mean(e**2)) / np.abs(case.displacement_analytic).max()

    study = fields.refinement_study(err, [64, 128, 256])
    assert np.all(study["order"][1:] >= MIN_ORDER)
    assert study["fitted_order"] >= MIN_ORDER

    def err_linf(n):
        case = fields.hertz_case(n, 1.0, 0.7)
        e = case.displacement_errors()
        return case.grid.dx, e["all"]["rel_max"]

    linf = fields.refinement_study(err_linf, [128, 256])
    assert linf["fitted_order"] >= MIN_ORDER_LINF


def test_off_edge_order():
    out = []
    for n in (64, 128, 256):
        case = fields.hertz_case(n, 1.0, 0.7)
        x, y = case.grid.mesh()
        keep = np.abs(np.hypot(x, y / 0.7) - 1.0) > 0.1
        e = np.abs(case.displacement_numerical - case.displacement_analytic)[keep].max()
        out.append((case.grid.dx, e))
    h, e = np.array(out).T
    assert np.all(fields.observed_orders(h, e) >= MIN_ORDER)


def test_annulus_identity(dh256):
    res = fields.annulus_identity(dh256)
    assert res["theta_p"][0] == 0.0 and res["theta_p"][-1] == pytest.approx(np.pi / 2)
    assert res["worst"] <= RTOL_ANNULUS_256
    # the analytic DH gap (Eq. 27) is (1+v) times the Hertz gap in the annulus
    prm = dh256.parameters
    x, y = dh256.grid.mesh()
    ann = dh256.masks["annulus"]
    h_h = hertz.gap(x[ann], y[ann], prm["semi_major"], prm["beta"])
    scale = np.max(np.abs(h_h))
    assert np.max(np.abs(dh256.gap_analytic[ann] - (1 + prm["scaling"]) * h_h)) <= RTOL_ANALYTIC_IDENTITY * scale


def test_annulus_identity_converges():
    coarse = fields.annulus_identity(fields.model_case(64, **CASE))["worst"]
    fine = fields.annulus_identity(fields.model_case(128, **CASE))["worst"]
    assert coarse / fine >= MIN_RATIO_ANNULUS


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
        fields.numerical_displacement(np.ones((16, 15)), grid)
    with pytest.raises(ValueError, match="semi_major"):
        fields.hertz_pressure(grid, -1.0, 0.5)
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
