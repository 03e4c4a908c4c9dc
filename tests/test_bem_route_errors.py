"""Every BEM route states an error that holds, checks resolution, and advises its own analytic value (issue 42).

References are Maugis-Dugdale on the sphere (beta0 = 1): the load and displacement-control pull-offs of
:func:`dhfield.models.maugis_dugdale.pull_off_nondimensional` and the jump under a spring along the MD curve
(:func:`dhfield.analysis.spring.pull_off_under_spring`, model 'md').  The whole study (60+ cases, every route)
is ``verification/bem_stated_error.py``; here the cases the issue names.
"""
import json
import math

import pytest

from dhfield.analysis import spring as compliance
from dhfield.models import maugis_dugdale
from dhfield.analysis.bem_start import GridPlan, adhesive_pull_off, plan_grid
from dhfield.bem.operator import Grid
from dhfield.cli import main
from dhfield.cli.solve import EXIT_UNRESOLVABLE, EXIT_UNCONVERGED, EXIT_UNRESOLVED
from dhfield.core.progress import PROGRESS_PREFIX


def _solve_json(argv, capsys):
    rc = main(["solve", *argv, "--json"])
    captured = capsys.readouterr()
    return rc, json.loads(captured.out), captured.err


# ------------------------------------------------------------------ finding 2: the spring's resolution check
@pytest.mark.parametrize("k", ["0", "0.1"])
def test_spring_route_applies_the_resolution_check(k, capsys):
    """mu = 2 at n = 32: the grid does not resolve the Dugdale edge.  Load control exits 4; so must the spring
    (it said resolved, W* = -0.7724 +- 0.0021 at K* = 0, 4x its error from MD's -0.7641), with ``converged``."""
    rc, rec, err = _solve_json(["--beta0", "1", "--mu", "2", "--n", "32", "--machine-stiffness", k], capsys)
    # unresolved, and (the Newton solve finds no stable discrete edge there) possibly unconverged too:
    # either way flagged, never exit 0
    assert rc == (EXIT_UNRESOLVED if rec["converged"] else EXIT_UNCONVERGED)
    assert rec["resolved"] is False and rec["W_star_error"] is None      # inf prints as null: no error bound
    assert "converged" in rec and isinstance(rec["converged"], bool)
    # one line says why (the progress lines of the states solved, issue 40, are not part of the verdict)
    verdict = [line for line in err.strip().splitlines() if not line.startswith(PROGRESS_PREFIX)]
    assert "traction law's edge" in rec["note"] and len(verdict) == 1


def test_spring_answer_lies_within_its_stated_error(capsys):
    """A resolved spring case (mu = 1, n = 64, K* = 1) exits 0 within its stated error of MD under the spring."""
    rc, rec, _ = _solve_json(["--beta0", "1", "--mu", "1", "--n", "64", "--machine-stiffness", "1"], capsys)
    ref = float(compliance.pull_off_under_spring("md", beta0=1.0, mu=1.0, machine_stiffness=1.0)["W_star"])
    assert rec["resolved"] and rec["converged"] and rc == 0
    assert abs(rec["W_star"] - ref) <= rec["W_star_error"]


# ------------------------------------------------------------------ finding 3: displacement-control errors
@pytest.mark.parametrize("mu, n", [(0.3, 48), (0.3, 64), (1.0, 32)])
def test_displacement_control_answer_lies_within_its_stated_error(mu, n):
    """The issue's cases outside their stated error (2.15x at mu = 0.3, n = 48; 1.3x at mu = 1, n = 32).

    An answer lies within its stated error of MD, or is flagged: at mu = 0.3, n = 48 the coarser
    check grid (24 cells) finds no pull-off, so no error is stated (``resolved`` False)."""
    res = adhesive_pull_off(beta0=1.0, mu=mu, n=n, control="displacement", threads=1)
    ref = float(maugis_dugdale.pull_off_nondimensional(1.0, mu, control="displacement").W_star)
    assert res.converged
    assert (not res.resolved and res.W_star_error == math.inf) if n == 48 else res.resolved
    assert abs(res.W_star - ref) <= res.W_star_error


def test_ladder_error_is_first_order_richardson_with_its_safety():
    """|W(n) - W(n_c)| / (n/n_c - 1) is the error of W(n) for an error ~ 1/n; the bound is twice it."""
    from dhfield.bem.pull_off import ladder_cells, ladder_error, route_error

    w_exact, c = -0.4, 0.3                     # W(n) = W_exact + c/n: the error of W(64) is c/64
    w = {n: w_exact + c / n for n in (32, 48, 64)}
    for n_c in (32, 48):
        est = ladder_error(w[64], w[n_c], 64, n_c)
        assert est == pytest.approx(2.0 * c / 64)
    assert ladder_error(w[64], float("nan"), 64, 32) == math.inf
    assert ladder_cells(64) == (32, 48) and ladder_cells(10) == (8,) and ladder_cells(8) == ()
    g = Grid.centered(64, 2.0)
    # without a coarser value there is no estimate; the floor counts the zone's width only (a* = 0: loss of contact)
    assert route_error(1e-3, -0.4, (0.0, 0.0, 0.5, 0.5), g, w_coarse=float("nan"), n_coarse=32) == math.inf
    assert math.isfinite(route_error(1e-3, -0.4, (0.0, 0.0, 0.5, 0.5), g, w_coarse=-0.41, n_coarse=32))


# ------------------------------------------------------------------ finding 4: the refusal's advice per route
def _refusal(argv, capsys, command="solve"):
    rc = main([command, *argv])
    err = capsys.readouterr().err.strip().splitlines()
    assert rc == EXIT_UNRESOLVABLE and len(err) == 1
    return err[0]


def test_refusal_advises_the_displacement_control_value(capsys):
    ref = float(maugis_dugdale.pull_off_nondimensional(1.0, 5.0, control="displacement").W_star)    # -0.4172
    load = float(maugis_dugdale.pull_off_nondimensional(1.0, 5.0, control="load").W_star)           # -0.7525
    line = _refusal(["--beta0", "1", "--mu", "5", "--n", "32", "--control", "displacement"], capsys)
    assert f"W* = {ref:.4f} under displacement control" in line and f"{load:.4f}" not in line


def test_refusal_advises_the_spring_value(capsys):
    ref = float(compliance.pull_off_under_spring("md", beta0=1.0, mu=5.0, machine_stiffness=1.0)["W_star"])  # -0.5544
    line = _refusal(["--beta0", "1", "--mu", "5", "--n", "32", "--machine-stiffness", "1"], capsys)
    assert f"W* = {ref:.4f} under a machine spring K* = 1" in line and "-0.7525" not in line


@pytest.mark.parametrize("k, control", [(None, "displacement"), (1.0, "spring")])
def test_cycle_refusal_advises_the_jump_out_of_its_machine(k, control, capsys):
    """``cycle --model bem``: a rigid machine jumps out at the displacement-control pull-off, a spring at its own."""
    argv = ["--model", "bem", "--beta0", "1", "--mu", "5", "--n", "32"] + ([] if k is None else
                                                                           ["--machine-stiffness", str(k)])
    line = _refusal(argv, capsys, command="cycle")
    if k is None:
        ref = float(maugis_dugdale.pull_off_nondimensional(1.0, 5.0, control="displacement").W_star)
    else:
        ref = float(compliance.pull_off_under_spring("md", beta0=1.0, mu=5.0, machine_stiffness=k)["W_star"])
    assert f"W* = {ref:.4f}" in line and "-0.7525" not in line


def test_plan_names_the_route_and_says_when_no_analytic_value_exists():
    from dhfield.analysis.bem_start import analytic_pull_off

    plan = plan_grid(beta0=1.0, mu=5.0, n=32, control="spring", machine_stiffness=1.0)
    assert plan.control == "spring" and plan.machine_stiffness_star == 1.0
    assert plan.analytic_W_star == pytest.approx(analytic_pull_off(beta0=1.0, mu=5.0, control="spring",
                                                                   machine_stiffness=1.0))
    none = GridPlan(**{**plan.__dict__, "analytic_W_star": float("nan")})
    assert "no analytic W* exists for a machine spring K* = 1" in none.message()
    with pytest.raises(ValueError, match="machine_stiffness"):
        plan_grid(beta0=1.0, mu=1.0, n=32, control="load", machine_stiffness=1.0)
    with pytest.raises(ValueError, match="control"):
        analytic_pull_off(beta0=1.0, mu=1.0, control="spring-ish")
