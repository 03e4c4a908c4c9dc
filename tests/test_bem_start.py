"""The start of the adhesive BEM chosen from the analytic models (dhfield.analysis.bem_start).

The start itself is judged by the BEM states it leads to (tests/test_bem_pull_off.py);
here: that it is the analytic models' numbers, and that a domain too small for the
contact is refused before anything is solved.
"""
from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pytest

from dhfield.analysis import bem_start as adhesive_start, compare
from dhfield.models import dh_elliptic as model
from dhfield.analysis.bem_start import AdhesiveOptions
from dhfield.bem.solver import DEFAULT_TOL

#: The start is copied from the closure's pull-off record: only round-off can differ.
RTOL_SAME_NUMBER = 1e-12


def test_cold_start_is_the_two_axis_pull_off_for_an_ellipse_and_the_dh_one_for_the_sphere():
    """The fix of beta0 = 0.5, mu = 5 (issue 8): the bracket search cold-starts from the two-axis
    closure's pull-off state, whose adhesive ellipse is rounder than beta0 (like the BEM's), not
    from the paper's zone d = beta0 c (48 cells short along y at N = 512: no convergence)."""
    start = adhesive_start.unloading_start(mu=5.0, beta0=0.5)
    ref = compare.pull_off("dh-elliptic-two-axis", mu=5.0, beta0=0.5, control="load")
    c, d = start.zone
    assert start.approach == pytest.approx(float(ref["delta_star"]), rel=RTOL_SAME_NUMBER)
    assert (c, d) == pytest.approx((float(ref["c_star"]), float(ref["d_star"])), rel=RTOL_SAME_NUMBER)
    assert d / c > 0.5 + 0.05                      # rounder than beta0 (two-axis: 0.596)
    sphere = adhesive_start.unloading_start(mu=5.0, beta0=1.0)
    assert sphere.approach == float(model.pull_off(mu=5.0, beta0=1.0).delta_star)
    assert sphere.zone[0] == sphere.zone[1]


@pytest.mark.parametrize("margin", [0.1, 0.3, 1.0])
def test_domain_too_small_for_the_contact_is_refused_before_solving(margin):
    # issue 18: margin = 0.3 gave W* = -0.261 and 0.1 gave -0.029 (about -0.79): the domain cut the zone
    with pytest.raises(ValueError, match=r"^margin must be > 1"):
        adhesive_start.adhesive_pull_off(mu=1.0, beta0=0.9, n=64, options=AdhesiveOptions(margin=margin))
    with pytest.raises(ValueError, match=r"^margin must be > 1"):
        adhesive_start.unloading_start(mu=1.0, beta0=0.9, margin=margin)


def test_the_bem_facade_forwards_the_convenience_functions():
    from dhfield import bem

    assert bem.adhesive_pull_off is adhesive_start.adhesive_pull_off
    assert bem.refine_pull_off is adhesive_start.refine_pull_off
    assert bem.nondimensional_problem is adhesive_start.nondimensional_problem


# ============================================================================ the grid a case needs (issue 20)
def _paper_edge_ratio(mu, n, start):
    """kappa mu^2 sqrt(dx dy)/2 of an n x n grid over the start's domain: the Dugdale edge width wanted,
    EDGE_WIDTH_FACTOR (1 + (2/pi) ln n) sigma0 sqrt(dx dy)/E*, per its cap 2 h0 (sigma0 = mu, h0 = 1/mu)."""
    import math

    from dhfield.bem.solver import EDGE_WIDTH_FACTOR

    dx, dy = 2 * start.half_width_x / n, 2 * start.half_width_y / n
    kappa = EDGE_WIDTH_FACTOR * (1 + 2 / math.pi * math.log(n))
    return kappa * mu * mu * math.sqrt(dx * dy) / 2


@pytest.mark.parametrize("mu, beta0", [(5.0, 0.5), (10.0, 0.4826), (5.0, 1.0), (2.0, 0.8)])
def test_automatic_grid_is_the_smallest_that_resolves_the_dugdale_edge(mu, beta0):
    plan = adhesive_start.plan_grid(mu=mu, beta0=beta0)
    # the domain of the route the automatic grid takes (high mu: the predicted route's, GVG's zone)
    start = (adhesive_start.predicted_start if plan.predicted else adhesive_start.unloading_start)(mu=mu, beta0=beta0)
    assert plan.predicted == (mu >= adhesive_start.PREDICTED_MIN_MU)
    assert plan.n == plan.n_needed and plan.n_needed >= adhesive_start.AUTO_MIN_CELLS
    # the edge criterion, written out in the paper's units (independent of the solver's code)
    assert plan.edge_width_ratio == pytest.approx(_paper_edge_ratio(mu, plan.n, start), rel=1e-12)
    assert plan.resolved and plan.edge_width_ratio <= 1.0
    smaller = [k for k in adhesive_start._fft_sizes() if k < plan.n_needed]
    if smaller:   # the next smaller size fails the edge or the zone-cell criterion
        k = smaller[-1]
        zone_cells = adhesive_start.expected_zone_width(mu) / (2 * start.half_width_x / k)
        assert _paper_edge_ratio(mu, k, start) > 1.0 or zone_cells < adhesive_start.AUTO_ZONE_CELLS


def test_automatic_grid_grows_like_mu_squared():
    # both criteria scale as 1/mu^2 (ln-corrected by kappa): 2x mu -> ~4x cells per axis, less the ln
    n5, n10 = (adhesive_start.plan_grid(mu=mu, beta0=0.4826).n_needed for mu in (5.0, 10.0))
    assert 2.5 < n10 / n5 <= 4.5


def test_expected_zone_width_matches_the_stored_bem_on_the_jkr_side():
    # (pi/8) 2 E* dgamma/sigma0^2 = 0.785/mu^2; the stored BEM at mu = 5 (data/adhesive_ground_truth.nc,
    # finest converged N per case) has c* - a* = 0.029-0.031 and d* - b* = 0.029-0.030: within 10 %
    from pathlib import Path

    import numpy as np
    import xarray as xr

    with xr.open_dataset(Path(__file__).resolve().parent.parent / "data" / "adhesive_ground_truth.nc") as ds:
        at5 = ds.sel(mu=5.0)
        widths = np.concatenate([(at5.c_star - at5.a_star).values.ravel(), (at5.d_star - at5.b_star).values.ravel()])
        ns = np.concatenate([np.broadcast_to(at5.n.values, at5.c_star.shape).ravel()] * 2)
    widths = widths[np.isfinite(widths) & (ns >= 256)]
    assert widths.size >= 10
    np.testing.assert_allclose(widths, adhesive_start.expected_zone_width(5.0), rtol=0.10)


def test_case_beyond_time_is_refused_before_solving_with_the_analytic_value(monkeypatch):
    from dhfield.models import md_elliptic as elliptic_transition

    calls = []
    monkeypatch.setattr(adhesive_start, "solve_pull_off", lambda *a, **k: calls.append(a))
    with pytest.raises(adhesive_start.UnresolvableCaseError) as info:
        adhesive_start.adhesive_pull_off(mu=10.0, beta0=0.4826, options=AdhesiveOptions(max_seconds=1.0))
    err = info.value
    assert not calls                                              # nothing solved
    assert err.n_needed == adhesive_start.plan_grid(mu=10.0, beta0=0.4826).n_needed
    assert err.seconds > 1.0 and err.memory_bytes > 0.0
    ref = float(elliptic_transition.pull_off_nondimensional(0.4826, 10.0).W_star)
    assert err.analytic_W_star == pytest.approx(ref, rel=RTOL_SAME_NUMBER)
    msg = str(err)
    assert "\n" not in msg and f"n >= {err.n_needed}" in msg and f"{ref:.4f}" in msg and "1 s allowed" in msg


def test_case_beyond_memory_is_refused(monkeypatch):
    monkeypatch.setattr(adhesive_start, "memory_limit", lambda: 1024)
    plan = adhesive_start.plan_grid(mu=5.0, beta0=0.5)
    assert not plan.affordable and "GiB available" in plan.reason()
    with pytest.raises(adhesive_start.UnresolvableCaseError, match="GiB available"):
        adhesive_start.adhesive_pull_off(mu=5.0, beta0=0.5)


def test_explicit_grid_far_too_coarse_is_named():
    # the case: N = 512 at mu = 11.4 wants ~3x the edge's cap (no stable discrete state)
    plan = adhesive_start.plan_grid(mu=11.4, beta0=0.4826, n=512)
    assert plan.n == 512 and plan.too_coarse and plan.n_needed > 512
    assert "n=512 is too coarse for the Dugdale edge" in plan.reason()
    assert not adhesive_start.plan_grid(mu=1.0, beta0=0.9, n=64).too_coarse


def test_automatic_grid_on_the_sphere_at_mu_5_is_within_1_percent_of_maugis_dugdale():
    # mu = 5 (lambda = 5.64): the grid half as fine (N = 160) cannot hold the Dugdale edge, so the located
    # route is the bracket search on this grid (each state by the Newton solve); MD (Maugis 1992) is the
    # closed form on the sphere; 1 % is the BEM's stated accuracy where resolved (DMT_BOUND_SLACK; measured +0.04 %)
    from dhfield.models import maugis_dugdale

    plan = adhesive_start.plan_grid(mu=5.0, beta0=1.0)
    assert not adhesive_start._half_grid_locates(plan, "dugdale", adhesive_start.DOMAIN_MARGIN)
    res = adhesive_start.adhesive_pull_off(search="located", mu=5.0, beta0=1.0, progress=False)
    md = float(maugis_dugdale.pull_off_nondimensional(1.0, 5.0, control="load").W_star)
    assert res.n == plan.n_needed and res.converged and res.resolved
    assert res.W_star == pytest.approx(md, rel=0.01)


def test_slender_contact_starts_from_the_gvg_ellipse_and_its_domain_holds_it():
    # beta0 = 0.1806 (30 deg): the two-axis closure refuses beta0 < 0.3 and the paper's zone (2.34 x 0.42)
    # is far inside GVG's contact (2.79 x 0.74); the start is GVG's pull-off ellipse widened by the zone
    from dhfield.models import jkr_elliptic_energy

    start = adhesive_start.unloading_start(mu=5.0, beta0=0.1806)
    gvg = jkr_elliptic_energy.pull_off_nondimensional(0.1806, 5.0, control="load")
    w = adhesive_start.expected_zone_width(5.0)
    assert start.approach == pytest.approx(float(gvg["delta_star"]), rel=RTOL_SAME_NUMBER)
    assert start.zone == pytest.approx((float(gvg["a_star"]) + w, float(gvg["b_star"]) + w), rel=RTOL_SAME_NUMBER)
    margin = adhesive_start.SLENDER_DOMAIN_MARGIN
    assert start.half_width_x >= margin * start.zone[0] * (1 - 1e-12)
    assert start.half_width_y >= margin * start.zone[1] * (1 - 1e-12)


@pytest.mark.parametrize("kwargs, name", [({"max_iter": 0}, "max_iter"), ({"mu": np.array([1.0])}, "mu"),
                                          ({"beta0": np.array([0.9, 0.8])}, "beta0")])
def test_bad_counts_and_arrays_are_named_errors(kwargs, name):
    """Issue 18 item 13: max_iter = 0 and an array mu raised TypeError from inside the solver."""
    args = {"mu": 1.0, "beta0": 0.9, **kwargs}
    with pytest.raises(ValueError, match=name):
        adhesive_start.adhesive_pull_off(mu=args["mu"], beta0=args["beta0"], n=16,
                                         options=AdhesiveOptions(**{k: v for k, v in kwargs.items()
                                                                    if k not in ("mu", "beta0")}))


def test_adhesive_pull_off_takes_beta0_and_mu_by_keyword():
    """(mu, beta0) was the old positional order: a positional call would swap them silently."""
    with pytest.raises(TypeError, match="positional"):
        adhesive_start.adhesive_pull_off(1.0, 0.9, 16)


# ======================================================================== cells shaped to slender contacts (issue 20)
def _paper_edge_ratio_xy(mu, nx, ny, start):
    """As :func:`_paper_edge_ratio` on an nx x ny grid: kappa = EDGE_WIDTH_FACTOR (1 + (2/pi) ln sqrt(nx ny))."""
    import math

    from dhfield.bem.solver import EDGE_WIDTH_FACTOR

    dx, dy = 2 * start.half_width_x / nx, 2 * start.half_width_y / ny
    kappa = EDGE_WIDTH_FACTOR * (1 + 2 / math.pi * math.log(math.sqrt(nx * ny)))
    return kappa * mu * mu * math.sqrt(dx * dy) / 2


@pytest.mark.parametrize("mu, beta0", [(5.0, 0.1806), (5.0, 0.1), (10.0, 0.1806), (1.0, 0.3), (5.0, 0.05)])
def test_slender_automatic_grid_has_about_square_cells_resolving_the_zone_on_both_axes(mu, beta0):
    plan = adhesive_start.plan_grid(mu=mu, beta0=beta0)
    # at mu >= PREDICTED_MIN_MU the plan is made on the predicted route's domain
    start = (adhesive_start.predicted_start if plan.predicted else adhesive_start.unloading_start)(mu=mu, beta0=beta0)
    nx, ny = plan.n_needed, plan.ny_needed
    assert (plan.n, plan.ny) == (nx, ny) and ny < nx
    dx, dy = 2 * start.half_width_x / nx, 2 * start.half_width_y / ny
    # dy <= dx, and about square: 2^a 3^b 5^c multiples of 32 are at most ~20 % apart above 256
    # (640, 768; 1200, 1440), so dy >= dx/1.25 unless the 64-cell floor binds
    assert dy <= dx * (1 + 1e-12)
    assert ny == adhesive_start.AUTO_MIN_CELLS_Y or dy >= dx / 1.25
    assert plan.edge_width_ratio == pytest.approx(_paper_edge_ratio_xy(mu, nx, ny, start), rel=1e-12)
    zone = adhesive_start.expected_zone_width(mu)
    assert plan.edge_width_ratio <= 1.0 and min(zone / dx, zone / dy) >= adhesive_start.AUTO_ZONE_CELLS
    smaller = [k for k in adhesive_start._fft_sizes() if k < nx]
    if smaller:   # the next smaller size along x (with its own ny) fails the edge or a zone criterion
        k = smaller[-1]
        ky = adhesive_start.shaped_cells_y(k, start.half_width_x, start.half_width_y)
        kdx, kdy = 2 * start.half_width_x / k, 2 * start.half_width_y / ky
        assert _paper_edge_ratio_xy(mu, k, ky, start) > 1.0 or zone / max(kdx, kdy) < adhesive_start.AUTO_ZONE_CELLS


@pytest.mark.parametrize("mu, beta0", [(5.0, 0.5), (10.0, 0.4826), (5.0, 1.0), (1.0, 0.45)])
def test_automatic_grid_stays_n_by_n_from_the_shaping_threshold_up(mu, beta0):
    plan = adhesive_start.plan_grid(mu=mu, beta0=beta0)
    assert plan.ny_needed == plan.n_needed and plan.ny == plan.n


def test_slender_grid_coarsens_exactly_for_the_nested_searches():
    # every coarser grid of the located/nested searches (n/2, n/4, ... along x) must halve y exactly and
    # keep the domain (Grid(n/k, ny/k, k dx, k dy)); shaped_cells_y makes ny divisible by n's power of 2
    for mu, beta0 in [(5.0, 0.1806), (10.0, 0.1806), (5.0, 0.1), (7.0, 0.25)]:
        plan = adhesive_start.plan_grid(mu=mu, beta0=beta0)
        nd = adhesive_start.nondimensional_problem(mu=mu, beta0=beta0, n=plan.n_needed, ny=plan.ny_needed)
        assert nd.grid.shape == (plan.n_needed, plan.ny_needed)
        k = 2
        while plan.n_needed // k >= 64 and plan.n_needed % k == 0:
            c = nd.coarser(plan.n_needed // k)
            assert c.grid.ny * k == plan.ny_needed
            assert c.grid.nx * c.grid.dx == pytest.approx(nd.grid.nx * nd.grid.dx, rel=1e-12)
            assert c.grid.ny * c.grid.dy == pytest.approx(nd.grid.ny * nd.grid.dy, rel=1e-12)
            k *= 2


def test_nx_by_ny_problem_has_the_crossed_cylinder_gap_of_eq_2():
    # z = x^2/(2R') + y^2/(2R'') with R' = sqrt(rho), R'' = 1/sqrt(rho) (Eq. 2, R'R'' = 1), on the cell centres
    import math

    from dhfield.core import geometry

    nd = adhesive_start.nondimensional_problem(mu=5.0, beta0=0.1806, n=96, ny=32)
    g = nd.grid
    assert g.shape == (96, 32)
    rho = float(geometry.radius_ratio(0.1806))
    x = (np.arange(96) - 47.5) * g.dx
    y = (np.arange(32) - 15.5) * g.dy
    z = x[:, None] ** 2 / (2 * math.sqrt(rho)) + y[None, :] ** 2 * math.sqrt(rho) / 2
    np.testing.assert_allclose(nd.initial_gap, z, rtol=1e-13, atol=1e-15)


@pytest.mark.parametrize("ny", [7, 31, 0, 2.5])
def test_bad_ny_is_named(ny):
    with pytest.raises(ValueError, match=r"^ny must be"):
        adhesive_start.nondimensional_problem(mu=1.0, beta0=0.3, n=64, ny=ny)
    with pytest.raises(ValueError, match=r"^ny must be"):
        adhesive_start.plan_grid(mu=1.0, beta0=0.3, n=64, ny=ny)


def test_shaped_and_stretched_grids_give_the_same_slender_pull_off_within_their_stated_errors():
    # beta0 = 0.1806 (30 deg), mu = 1: the automatic grid (256 x 72, about square cells) and 256 x 256
    # cells stretched 3.6x along x are two discretisations of one problem (independent routes to the
    # same pull-off); each must be converged, resolved, and within the sum of their stated errors
    shaped = adhesive_start.adhesive_pull_off(search="located", mu=1.0, beta0=0.1806, progress=False)
    g = shaped.path.pull_off_state.grid
    assert g.ny < g.nx and 0.8 < g.dy / g.dx <= 1.0
    stretched = adhesive_start.adhesive_pull_off(mu=1.0, beta0=0.1806, n=g.nx, progress=False)
    assert stretched.path.pull_off_state.grid.shape == (g.nx, g.nx)
    for res in (shaped, stretched):
        assert res.converged and res.resolved and np.isfinite(res.W_star_error)
    assert abs(shaped.W_star - stretched.W_star) <= shaped.W_star_error + stretched.W_star_error
    # and both lie between the DMT limit -sin(theta) and the JKR limit (GVG) of Eq. (34)
    from dhfield.models import jkr_elliptic_energy

    from dhfield.core.geometry import sin_skew_angle

    gvg = float(jkr_elliptic_energy.pull_off_nondimensional(0.1806, 1.0, control="load")["W_star"])
    for res in (shaped, stretched):
        assert -float(sin_skew_angle(0.1806)) < res.W_star < gvg


@pytest.mark.parametrize("mu, beta0", [(0.1, 0.1806), (0.3, 0.1806), (0.1, 0.3)])
def test_slender_automatic_grid_resolves_the_small_dmt_side_contact(mu, beta0):
    # on the DMT side the pull-off contact is small inside a wide zone (beta0 = 0.1806, mu = 0.1: the BEM's
    # b* = 0.093 spanned one square cell of 256 x 72): >= AUTO_CONTACT_CELLS cells across the DH model's a*, b*
    plan = adhesive_start.plan_grid(mu=mu, beta0=beta0)
    start = adhesive_start.unloading_start(mu=mu, beta0=beta0)
    po = model.pull_off(mu=mu, beta0=beta0)
    dx, dy = 2 * start.half_width_x / plan.n_needed, 2 * start.half_width_y / plan.ny_needed
    assert float(po.a_star) / dx >= adhesive_start.AUTO_CONTACT_CELLS
    assert float(po.b_star) / dy >= adhesive_start.AUTO_CONTACT_CELLS
    assert dy <= dx * (1 + 1e-12)


def test_high_mu_automatic_grid_takes_the_predicted_route(monkeypatch):
    # mu >= PREDICTED_MIN_MU with a half grid that cannot hold the Dugdale edge: fine lattice samples
    # around GVG's pull-off; nothing solved here
    calls = []
    answer = SimpleNamespace(converged=True)
    monkeypatch.setattr(adhesive_start, "_predicted_pull_off",
                        lambda prob, opts, tol=None:
                        calls.append((prob.grid.nx, tol, opts.tol)) or answer)
    assert adhesive_start.adhesive_pull_off(search="located", mu=10.0, beta0=0.4826) is answer
    plan = adhesive_start.plan_grid(mu=10.0, beta0=0.4826)
    # its states to the one default tolerance unless a tol is given
    assert calls == [(plan.n_needed, None, DEFAULT_TOL)] and plan.predicted
    opts = adhesive_start.AdhesiveOptions(tol=2e-6)
    assert adhesive_start.adhesive_pull_off(search="located", mu=10.0, beta0=0.4826, options=opts) is answer
    assert calls[-1][1:] == (None, 2e-6)                          # the tolerance given, through the options
    # its domain holds GVG's pull-off zone only: N = 1280 instead of 1440 on the unloading path's domain
    assert plan.n_needed < adhesive_start.plan_grid(mu=10.0, beta0=0.4826, predicted=False).n_needed
    assert adhesive_start.PREDICTED_MIN_MU > 5.0                  # mu = 5 keeps the bracket search


def test_predicted_search_on_an_explicit_grid_is_that_route_on_that_grid(monkeypatch):
    # a refined grid level of the predicted route: the same route and domain on the caller's n x ny cells
    calls = []
    answer = SimpleNamespace(converged=False)
    monkeypatch.setattr(adhesive_start, "_predicted_pull_off",
                        lambda prob, opts, tol=None: calls.append((prob, tol)) or answer)
    assert adhesive_start.adhesive_pull_off(mu=10.0, beta0=0.5, n=96, ny=64, search="predicted") is answer
    prob, tol = calls[0]
    ref = adhesive_start.predicted_problem(mu=10.0, beta0=0.5, n=96, ny=64)
    assert (prob.grid, tol) == (ref.grid, None)                      # options.tol; no lattice retry on it
    assert len(calls) == 1
    for n in (None, 96):
        with pytest.raises(ValueError, match="options.nested None"):
            adhesive_start.adhesive_pull_off(mu=10.0, beta0=0.5, n=n, search="predicted",
                                             options=adhesive_start.AdhesiveOptions(nested=True))
    with pytest.raises(ValueError, match="search='predicted' needs law='dugdale'"):
        adhesive_start.adhesive_pull_off(mu=10.0, beta0=0.5, n=96, law="exponential", search="predicted")
    with pytest.raises(ValueError, match="search must be one of .*'predicted'"):
        adhesive_start.adhesive_pull_off(mu=10.0, beta0=0.5, n=96, search="guess")


def test_predicted_route_on_the_sphere_is_within_its_stated_error_of_maugis_dugdale():
    # the predicted route on a small resolved grid (mu = 2, N = 128: lambda = 2.26): MD (Maugis 1992) is
    # exact on the sphere; the answer must lie within its own stated error (search + grid) of it
    from dhfield.models import maugis_dugdale
    from dhfield.bem.path import PathOptions

    prob = adhesive_start.predicted_problem(mu=2.0, beta0=1.0, n=128)
    res = adhesive_start._predicted_pull_off(prob, PathOptions(progress=False))
    md = float(maugis_dugdale.pull_off_nondimensional(1.0, 2.0, control="load").W_star)
    assert res.search == "predicted" and res.converged and res.resolved      # the route it took
    assert 3 <= res.n_steps <= 4                                  # three samples (+ at most one vertex)
    assert abs(res.W_star - md) <= res.W_star_error


def test_predicted_route_that_fails_says_so_and_tries_no_other_route(monkeypatch):
    # a cap of one Newton iteration per state cannot converge the cold state: the record must say so
    # (converged and resolved False, no error bound), name the analytic W* to use instead, and try
    # no other route
    import dataclasses

    import dhfield.bem.newton
    from dhfield.models import md_elliptic as elliptic_transition
    from dhfield.bem.path import PathOptions

    monkeypatch.setattr(dhfield.bem.newton, "NESTED_OPTIONS",
                        dataclasses.replace(dhfield.bem.newton.NESTED_OPTIONS, max_newton=1))
    monkeypatch.setattr(adhesive_start, "solve_pull_off",
                        lambda *a, **k: (_ for _ in ()).throw(AssertionError("another route was tried")))
    prob = adhesive_start.predicted_problem(mu=2.0, beta0=1.0, n=128)
    res = adhesive_start._predicted_pull_off(prob, PathOptions(progress=False))
    assert not res.converged and not res.resolved and res.W_star_error == float("inf")
    assert len(res.failures) == res.n_steps == 1
    w = float(elliptic_transition.pull_off_nondimensional(1.0, 2.0).W_star)
    assert "cold state" in res.note and f"analytic W* = {w:.4f}" in res.note


@pytest.mark.parametrize("call", [lambda: adhesive_start.unloading_start(1.0, 0.9),
                                  lambda: adhesive_start.nondimensional_problem(1.0, 0.9, 16),
                                  lambda: adhesive_start.plan_grid(1.0, 0.9),
                                  lambda: adhesive_start.predicted_start(1.0, 0.9),
                                  lambda: adhesive_start.predicted_problem(1.0, 0.9, 16)])
def test_start_and_plan_take_beta0_and_mu_by_keyword(call):
    """(mu, beta0) was the old positional order: a positional call would swap them silently (issue 16)."""
    with pytest.raises(TypeError, match="positional"):
        call()


def test_one_route_rule_for_the_plan_and_the_solve():
    """plan_grid's default and adhesive_pull_off decide the predicted route by one rule
    (takes_predicted_route), so a caller planning for another route (displacement control, another
    search, an explicit n, the spring's unloading branch) plans on the unloading path's domain."""
    assert adhesive_start.takes_predicted_route(beta0=0.4826, mu=10.0)
    assert adhesive_start.plan_grid(beta0=0.4826, mu=10.0).predicted
    for kw in (dict(control="displacement"), dict(search="bracket"), dict(n=1440), dict(law="exponential"),
               dict(nested=True)):
        assert not adhesive_start.takes_predicted_route(beta0=0.4826, mu=10.0, **kw), kw
    assert adhesive_start.takes_predicted_route(beta0=0.3, mu=10.0)         # shaped grids too (nx x ny)
    assert not adhesive_start.takes_predicted_route(beta0=0.4826, mu=5.0)   # below PREDICTED_MIN_MU


def test_every_bem_route_refuses_an_unaffordable_grid_before_allocating(monkeypatch):
    """Issue 42 finding 6: the memory check lived in ``dhfield solve`` only; the library, the spring's
    unloading branch and the sweep's cases allocated an unaffordable n (the sweep: 6.4 GB, headed for OOM)."""
    from dhfield.core import memory as _memory
    from dhfield.analysis.bem_spring import bem_unloading_branch

    def allocated(*args, **kwargs):
        raise AssertionError("the problem was set up (its arrays allocated) before the memory check")

    monkeypatch.setattr(_memory, "available_memory", lambda: 2**20)   # 0.8 MiB may be claimed
    monkeypatch.setattr(adhesive_start, "paper_problem", allocated)
    msg = r"n=64 \(a 64 x 64 grid of the adhesive BEM.* needs an estimated .* more than the limit"
    with pytest.raises(ValueError, match=msg):   # 64^2 cells x 550 B = 2.1 MiB
        adhesive_start.adhesive_pull_off(beta0=1.0, mu=1.0, n=64)
    with pytest.raises(ValueError, match=msg):
        adhesive_start.adhesive_pull_off(beta0=1.0, mu=1.0, n=64, control="displacement")
    with pytest.raises(ValueError, match=msg):
        bem_unloading_branch(beta0=1.0, mu=1.0, n=64)
    with pytest.raises(ValueError, match=r"n=64 x 32 \(a 64 x 32 grid"):
        adhesive_start.predicted_problem(beta0=1.0, mu=10.0, n=64, ny=32)
