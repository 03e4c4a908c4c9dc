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
    # mu = 5 (lambda = 5.64): the grid half as fine (N = 160) cannot hold the Dugdale edge, so the states
    # start from it with the edge relaxed (RelaxedWarmStart); MD (Maugis 1992) is the closed form on the
    # sphere; 1 % is the BEM's stated accuracy where resolved (DMT_BOUND_SLACK; measured +0.04 %)
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
    # around GVG's pull-off (the relaxed half grid's states stall at mu = 10); nothing solved here
    calls = []
    answer = SimpleNamespace(converged=True)
    monkeypatch.setattr(adhesive_start, "_predicted_pull_off",
                        lambda prob, opts, tol=None, start="cold":
                        calls.append((prob.grid.nx, tol, opts.tol)) or answer)
    # (the start of its states: test_predicted_route_trapped_on_its_lattice_is_solved_once_more_on_the_next)
    monkeypatch.setattr(adhesive_start, "_relaxed_pull_off", lambda prob, opts: "r")
    assert adhesive_start.adhesive_pull_off(search="located", mu=10.0, beta0=0.4826) is answer
    plan = adhesive_start.plan_grid(mu=10.0, beta0=0.4826)
    # its states to PREDICTED_TOL unless a tol is given; the fall-back (relaxed) keeps DEFAULT_TOL
    assert calls == [(plan.n_needed, adhesive_start.PREDICTED_TOL, DEFAULT_TOL)] and plan.predicted
    opts = adhesive_start.AdhesiveOptions(tol=2e-6)
    assert adhesive_start.adhesive_pull_off(search="located", mu=10.0, beta0=0.4826, options=opts) is answer
    assert calls[-1][1:] == (2e-6, 2e-6)
    # its domain holds GVG's pull-off zone only: N = 1280 instead of 1440 on the unloading path's domain
    assert plan.n_needed < adhesive_start.plan_grid(mu=10.0, beta0=0.4826, predicted=False).n_needed
    assert adhesive_start.PREDICTED_MIN_MU > 5.0                  # mu = 5 keeps the relaxed route (measured)


def test_predicted_search_on_an_explicit_grid_is_that_route_on_that_grid(monkeypatch):
    # a refined grid level of the predicted route: the same route and domain on the caller's n x ny cells
    calls = []
    answer = SimpleNamespace(converged=False)
    monkeypatch.setattr(adhesive_start, "_predicted_pull_off",
                        lambda prob, opts, tol=None, start="cold": calls.append((prob, tol, start)) or answer)
    assert adhesive_start.adhesive_pull_off(mu=10.0, beta0=0.5, n=96, ny=64, search="predicted") is answer
    prob, tol, start = calls[0]
    ref = adhesive_start.predicted_problem(mu=10.0, beta0=0.5, n=96, ny=64)
    assert (prob.grid, tol) == (ref.grid, adhesive_start.PREDICTED_TOL)        # no lattice retry on it
    assert len(calls) == 1
    # 96 x 64 at mu = 10: the grid half as fine does not hold the edge even at mu/2, so GVG's cold start
    assert start == "cold" and not adhesive_start.lower_mu_start_possible(ref)
    with pytest.raises(ValueError, match="options.nested=True needs a grid whose half holds"):
        adhesive_start.adhesive_pull_off(mu=10.0, beta0=0.5, n=96, ny=64, search="predicted",
                                         options=adhesive_start.AdhesiveOptions(nested=True))
    # where the half grid serves: the route's own states there (it holds the edge at mu and takes the
    # lower-mu start itself: a refined level) by default, else the lower-mu start (128 cells: the half
    # grid, 64, is the nested starts' smallest), the cold start with nested=False
    calls.clear()
    adhesive_start.adhesive_pull_off(mu=2.0, beta0=1.0, n=256, search="predicted")
    adhesive_start.adhesive_pull_off(mu=2.0, beta0=1.0, n=128, search="predicted")
    adhesive_start.adhesive_pull_off(mu=2.0, beta0=1.0, n=128, search="predicted",
                                     options=adhesive_start.AdhesiveOptions(nested=False))
    assert [c[2] for c in calls] == ["coarse-route", "lower-mu", "cold"]
    with pytest.raises(ValueError, match="options.nested None on the automatic grid"):
        adhesive_start.adhesive_pull_off(mu=10.0, beta0=0.5, search="predicted",
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


def test_lower_mu_start_is_possible_where_the_half_grid_holds_the_edge_at_half_mu():
    # the automatic grid of the predicted route holds the edge at mu (ratio <= 1) and its half grid does
    # not (~1.8 measured): at mu/2 the ratio (~ mu^2) is 4x smaller, so the half grid holds it
    from dhfield.bem.laws import law_from_name
    from dhfield.bem.solver import edge_width_ratio

    for beta0 in (1.0, 0.5, 0.1):
        plan = adhesive_start.plan_grid(mu=10.0, beta0=beta0, predicted=True, max_seconds=1e9)
        level1 = adhesive_start.predicted_problem(mu=10.0, beta0=beta0, n=plan.n_needed, ny=plan.ny_needed)
        half = level1.coarser(plan.n_needed // 2)
        assert edge_width_ratio(level1.grid, level1.law) <= 1.0 < edge_width_ratio(half.grid, half.law)
        low = edge_width_ratio(half.grid, law_from_name("dugdale", 5.0, 1.0))
        assert low == pytest.approx(edge_width_ratio(half.grid, half.law) / 4) and low <= 1.0
        assert adhesive_start.lower_mu_start_possible(level1)
        # level 2 (twice the cells): its half grid is level 1
        fine = adhesive_start.predicted_problem(mu=10.0, beta0=beta0, n=2 * plan.n_needed, ny=2 * plan.ny_needed)
        assert fine.coarser(plan.n_needed).grid == level1.grid and adhesive_start.lower_mu_start_possible(fine)
    # cells not multiples of 4, or a grid whose half is far too coarse even at mu/2: not possible
    assert not adhesive_start.lower_mu_start_possible(adhesive_start.predicted_problem(mu=2.0, beta0=1.0, n=130))
    assert not adhesive_start.lower_mu_start_possible(adhesive_start.predicted_problem(mu=10.0, beta0=0.5, n=96,
                                                                                       ny=64))


def test_coarse_route_start_is_possible_on_the_refined_levels_of_the_mu_10_cases():
    # level 2 (twice the cells per axis of the automatic grid): its half grid is level 1, which holds the
    # edge at mu and takes the lower-mu start itself; level 1's own half grid does not hold the edge
    for beta0 in (1.0, 0.5, 0.1):
        plan = adhesive_start.plan_grid(mu=10.0, beta0=beta0, predicted=True, max_seconds=1e9)
        level1 = adhesive_start.predicted_problem(mu=10.0, beta0=beta0, n=plan.n_needed, ny=plan.ny_needed)
        fine = adhesive_start.predicted_problem(mu=10.0, beta0=beta0, n=2 * plan.n_needed, ny=2 * plan.ny_needed)
        assert adhesive_start.coarse_route_start_possible(fine)
        assert not adhesive_start.coarse_route_start_possible(level1)
    # cells not multiples of 8, or a half grid too small for its own lower-mu start (64 = NESTED_MIN_N)
    for n in (260, 128):
        assert not adhesive_start.coarse_route_start_possible(adhesive_start.predicted_problem(mu=2.0, beta0=1.0, n=n))
    assert adhesive_start.coarse_route_start_possible(adhesive_start.predicted_problem(mu=2.0, beta0=1.0, n=256))


def test_coarse_route_start_is_within_its_stated_error_of_maugis_dugdale():
    # the sphere at mu = 2 on 256^2: the first state starts from the same approach at mu = 2 solved on
    # 128^2 by the route (itself from mu = 1 on 64^2); MD (exact on the sphere) must lie within the
    # answer's stated error of it
    from dhfield.models import maugis_dugdale
    from dhfield.bem.path import PathOptions
    from dhfield.bem.pull_off import CoarseRouteWarmStart

    prob = adhesive_start.predicted_problem(mu=2.0, beta0=1.0, n=256)
    res = adhesive_start._predicted_pull_off(prob, PathOptions(progress=False), start="coarse-route")
    md = float(maugis_dugdale.pull_off_nondimensional(1.0, 2.0, control="load").W_star)
    assert res.converged and res.resolved and res.path.coarse_states > 0
    assert abs(res.W_star - md) <= res.W_star_error
    ws = CoarseRouteWarmStart(prob, tol=1e-4, max_iter=10 ** 6)
    d = prob.pull_off_approach
    coarse = ws.coarse_state(d)
    assert coarse.converged and coarse.grid.nx == 128 and coarse.law == prob.law   # the same mu, half the cells
    assert ws.coarse_state(d) is coarse and ws.states_solved >= 2                  # once; and its lower-mu start
    guess = ws(d)
    assert guess.grid == prob.grid and guess.law == prob.law
    # the race's last start: the fine grid's own lower-mu start (mu = 1 on 128^2), counted with the rest
    before = ws.states_solved
    alt = ws.alternative(d)
    assert alt.grid == prob.grid and alt.law == prob.law and ws.states_solved > before
    with pytest.raises(ValueError, match="multiples of 8"):
        CoarseRouteWarmStart(adhesive_start.predicted_problem(mu=2.0, beta0=1.0, n=132), tol=1e-4, max_iter=10)


@pytest.mark.parametrize("every", [False, True])
def test_predicted_route_starts_the_first_or_every_state_from_the_external_start(every):
    # a lower-mu start that counts what it is asked: without starts_every_state only the first state
    # (the later ones from their neighbours), with it every state of the route
    from dhfield.bem.path import PathOptions
    from dhfield.bem.pull_off import LowerMuWarmStart, predicted_path

    class Counting(LowerMuWarmStart):
        starts_every_state = every

        def coarse_state(self, approach):
            asked.append(approach)
            return super().coarse_state(approach)

    asked = []
    prob = adhesive_start.predicted_problem(mu=2.0, beta0=1.0, n=128)
    path = predicted_path(prob, PathOptions(progress=False).checked(),
                          warm_start=Counting(prob, tol=1e-4, max_iter=10 ** 6))
    solved = sorted(set(path.approach.tolist()))
    assert path.pull_off_converged and len(solved) >= 3
    assert sorted(set(asked)) == (solved if every else [path.approach[0]])


@pytest.mark.parametrize("failures, expected", [
    # the lower-mu start fails: solved again cold, with the full budget (no give-up window)
    (1, [("ContactState", None), ("Prediction", None)]),
    # cold fails too: the same state solved with the Dugdale edge at its widest
    # (Branch.widest_edge_guess), which then starts the grid's own state, with the full budget
    (2, [("ContactState", None), ("Prediction", None), ("wide", None), ("ContactState", None)]),
])
def test_predicted_route_races_a_lost_first_state_external_then_cold_then_wide_edge(monkeypatch, failures,
                                                                                     expected):
    # the route's first state from a lower-mu start; its first `failures` solves on the grid are
    # reported unconverged; the route converges from the next start of the race
    import dataclasses

    from dhfield.bem import branch as branch_module
    from dhfield.bem.path import PathOptions
    from dhfield.bem.pull_off import LowerMuWarmStart, predicted_path

    calls = []
    real = branch_module.solve_problem

    def failing(p, approach, start, *args, **kwargs):
        st = real(p, approach, start, *args, **kwargs)
        if p.grid.nx != prob.grid.nx:               # the lower-mu start's own states (grid half as fine)
            return st
        calls.append(("wide" if p.widest_edge else type(start).__name__, kwargs.get("give_up_after")))
        own = [c for c in calls if c[0] != "wide"]               # the grid's own states solved so far
        return dataclasses.replace(st, converged=False) if not p.widest_edge and len(own) <= failures else st

    prob = adhesive_start.predicted_problem(mu=2.0, beta0=1.0, n=128)
    warm = LowerMuWarmStart(prob, tol=1e-4, max_iter=10 ** 6)
    monkeypatch.setattr(branch_module, "solve_problem", failing)
    path = predicted_path(prob, PathOptions(progress=False).checked(), warm_start=warm)
    assert path.pull_off_converged
    assert calls[:len(expected)] == expected


def test_predicted_route_that_fails_says_so_and_tries_no_other_route(monkeypatch):
    # an iteration cap of 5 CG iterations cannot converge the cold state: the record must say so
    # (converged and resolved False, no error bound), name the analytic W* to use instead, and not
    # fall back on the relaxed route (whose states stall at the mu this route serves)
    from dhfield.models import md_elliptic as elliptic_transition
    from dhfield.bem.path import PathOptions

    def relaxed(*args, **kwargs):
        raise AssertionError("the relaxed route was tried")

    monkeypatch.setattr(adhesive_start, "_relaxed_pull_off", relaxed)
    prob = adhesive_start.predicted_problem(mu=2.0, beta0=1.0, n=128)
    res = adhesive_start._predicted_pull_off(prob, PathOptions(progress=False, max_iter=5))
    assert not res.converged and not res.resolved and res.W_star_error == float("inf")
    assert len(res.failures) == res.n_steps == 1
    w = float(elliptic_transition.pull_off_nondimensional(1.0, 2.0).W_star)
    assert "cold state" in res.note and f"analytic W* = {w:.4f}" in res.note


def test_next_lattice_is_the_next_automatic_size_that_fits():
    sizes = adhesive_start._fft_sizes()
    for n in (1200, 1280, 512):
        nxt = adhesive_start.next_lattice(n, max_seconds=1e9)
        assert nxt == min(k for k in sizes if k > n) and nxt % 16 == 0
    # the retry's time estimate (plan_grid's constants) must fit the time allowed
    cells = 1280.0 ** 2
    est = adhesive_start.SECONDS_PER_CELL_ITERATION * cells * adhesive_start.PULL_OFF_ITERATIONS
    assert adhesive_start.next_lattice(1200, max_seconds=est * 0.99) is None
    assert adhesive_start.next_lattice(1200, max_seconds=est * 1.01) == 1280
    with pytest.raises(ValueError, match="max_seconds"):
        adhesive_start.next_lattice(1200, max_seconds=0)
    # a shaped lattice keeps its cells' shape: 2560 x 480 -> 2880 x 540, whose estimate must fit
    est = adhesive_start.SECONDS_PER_CELL_ITERATION * 2880.0 * 540.0 * adhesive_start.PULL_OFF_ITERATIONS
    assert adhesive_start.next_lattice(2560, max_seconds=est * 1.01, ny=480) == 2880
    assert adhesive_start.next_lattice(2560, max_seconds=est * 0.99, ny=480) is None


def test_next_lattice_grid_keeps_the_cells_shape():
    # the retry of a shaped lattice: nx the next size, ny scaled as nx and even (2560 x 480 -> 2880 x 540;
    # 1920 x 800 -> 2048 x 854, beta0 = 0.3's level-1 lattices at mu = 10: 800 * 2048/1920 = 853.3, up to even)
    assert adhesive_start.next_lattice_grid(2560, 480, 1e9) == (2880, 540)
    assert adhesive_start.next_lattice_grid(1920, 800, 1e9) == (2048, 854)
    assert adhesive_start.next_lattice_grid(1200, 1200, 1e9) == (1280, 1280)
    assert adhesive_start.next_lattice_grid(1200, 1200, 1e-3) is None          # nothing fits in a millisecond
    with pytest.raises(ValueError, match="ny"):
        adhesive_start.next_lattice_grid(1200, 0, 1e9)


def test_predicted_route_trapped_on_its_lattice_is_solved_once_more_on_the_next(monkeypatch):
    # the records are real BEM answers of a small sphere (mu = 2, N = 128): unconverged (5 CG
    # iterations) and converged; the route's first tries are made to return the first
    from dhfield.bem.path import PathOptions

    small = adhesive_start.predicted_problem(mu=2.0, beta0=1.0, n=128)
    failed = adhesive_start._predicted_pull_off(small, PathOptions(progress=False, max_iter=5))
    good = adhesive_start._predicted_pull_off(small, PathOptions(progress=False))
    assert not failed.converged and good.converged
    calls = []

    def route(fails):
        def run(prob, opts, tol=None, start="cold"):
            calls.append((prob.grid.nx, start))
            return failed if len(calls) <= fails else good
        return run

    n = adhesive_start.plan_grid(mu=10.0, beta0=0.4826).n_needed
    n_next = adhesive_start.next_lattice(n)
    prob = adhesive_start.predicted_problem(mu=10.0, beta0=0.4826, n=n)
    assert adhesive_start.lower_mu_start_possible(prob)
    # GVG's start fails, the lower-mu start on the same lattice answers
    monkeypatch.setattr(adhesive_start, "_predicted_pull_off", route(1))
    res = adhesive_start.adhesive_pull_off(search="located", mu=10.0, beta0=0.4826)
    assert calls == [(n, "cold"), (n, "lower-mu")]
    assert res.converged and res.W_star == good.W_star
    assert "from GVG's start did not converge" in res.note
    assert "solved again from the lower-mu start (mu = 5 on the grid half as fine)" in res.note
    assert res.elapsed == pytest.approx(failed.elapsed + good.elapsed)
    # both fail on the first lattice: once more on the next, from GVG's start
    calls.clear()
    monkeypatch.setattr(adhesive_start, "_predicted_pull_off", route(2))
    res = adhesive_start.adhesive_pull_off(search="located", mu=10.0, beta0=0.4826)
    assert calls == [(n, "cold"), (n, "lower-mu"), (n_next, "cold")]
    assert res.converged and res.W_star == good.W_star
    assert f"N = {n} lattice" in res.note and f"N = {n_next}" in res.note and "lower-mu start" in res.note
    assert res.elapsed == pytest.approx(2 * failed.elapsed + good.elapsed)
    # the same order on a slender contact
    calls.clear()
    monkeypatch.setattr(adhesive_start, "_predicted_pull_off", route(1))
    adhesive_start.adhesive_pull_off(search="located", mu=10.0, beta0=0.1)
    n_slender = adhesive_start.plan_grid(mu=10.0, beta0=0.1).n_needed
    assert calls == [(n_slender, "cold"), (n_slender, "lower-mu")]
    # a converged first try is the answer; failed ones with no affordable next lattice are reported
    calls.clear()
    monkeypatch.setattr(adhesive_start, "_predicted_pull_off", route(0))
    assert adhesive_start.adhesive_pull_off(search="located", mu=10.0, beta0=0.4826) is good and calls == [(n, "cold")]
    monkeypatch.setattr(adhesive_start, "_predicted_pull_off", lambda prob, opts, tol=None, start="cold": failed)
    monkeypatch.setattr(adhesive_start, "next_lattice", lambda n, max_seconds, ny=None: None)
    res = adhesive_start.adhesive_pull_off(search="located", mu=10.0, beta0=0.4826)
    assert not res.converged and res.W_star_error == float("inf") and "lower-mu start" in res.note


def test_lower_mu_start_from_the_half_grid_agrees_with_the_cold_route():
    # the sphere at mu = 2 on 128^2: each state starts from mu = 1 at the same approach on 64^2 (solved by
    # nested starts); the converged answer must not depend on the start (to its stated error), and MD
    # (exact on the sphere) must lie within that error of it
    from dhfield.models import maugis_dugdale
    from dhfield.bem.path import PathOptions
    from dhfield.bem.pull_off import LowerMuWarmStart

    prob = adhesive_start.predicted_problem(mu=2.0, beta0=1.0, n=128)
    assert adhesive_start.lower_mu_start_possible(prob)
    low = adhesive_start._predicted_pull_off(prob, PathOptions(progress=False), start="lower-mu")
    cold = adhesive_start._predicted_pull_off(prob, PathOptions(progress=False), start="cold")
    md = float(maugis_dugdale.pull_off_nondimensional(1.0, 2.0, control="load").W_star)
    assert low.converged and low.resolved and low.path.coarse_states > 0
    assert abs(low.W_star - cold.W_star) <= low.W_star_error and abs(low.W_star - md) <= low.W_star_error
    ws = LowerMuWarmStart(prob, tol=1e-4, max_iter=10 ** 6)
    guess = ws(prob.pull_off_approach)
    assert ws.mu == 1.0 and guess.law == prob.law and guess.grid == prob.grid   # the fine law, the fine grid
    with pytest.raises(ValueError, match="mu_ratio"):
        LowerMuWarmStart(prob, tol=1e-4, max_iter=100, mu_ratio=1.0)
    with pytest.raises(ValueError, match="start must be one of"):
        adhesive_start._predicted_pull_off(prob, PathOptions(progress=False), start="warm")


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
