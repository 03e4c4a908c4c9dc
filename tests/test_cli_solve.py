"""``dhfield solve``: JSON keys, netCDF output, input validation, reported non-convergence."""
import json
import math
import re

import numpy as np
import pytest

from dhfield.analysis import compare
from dhfield.cli import main
from dhfield.cli.solve import EXIT_UNCONVERGED, EXIT_UNRESOLVABLE
from dhfield.io.solution import read_solution
from dhfield.core.schema import PULL_OFF_KEYS, PULL_OFF_SOLVER_KEYS
from dhfield.core.progress import PROGRESS_PREFIX

#: N = 32 is a smoke-test grid (about 6 cells across the Dugdale zone at mu = 1); the
#: accuracy targets (1 % of MD at N = 256) belong to tests/test_bem_adhesive.py.  At
#: N = 32 the sphere is within 0.1 % of MD (measured), so 3 % leaves room and still
#: catches a wrong normalisation (Eq. 34) or sign.
COARSE_MD_RTOL = 0.03


def test_solve_json_and_netcdf(tmp_path, capsys):
    out = tmp_path / "run.nc"
    rc = main(["solve", "--beta0", "1", "--mu", "1", "--n", "32", "--json", "--out", str(out)])
    captured = capsys.readouterr()
    rec = json.loads(captured.out)
    # the BEM's pull-off record, JSON-ready: the keys of every model's record, then its solver group
    assert tuple(rec) == PULL_OFF_KEYS + PULL_OFF_SOLVER_KEYS + ("units",)
    assert rec["model"] == "bem" and rec["v"] is None   # v (NaN: no DH factor) prints as null
    assert rc == (0 if rec["converged"] else EXIT_UNCONVERGED)
    if rc or rec["failures"]:  # a failure, or a note on states beyond the pull-off: one line naming the case
        assert len(captured.err.strip().splitlines()) == 1 and "beta0=1, mu=1, n=32" in captured.err
    md = compare.pull_off("md", mu=1.0, beta0=1.0)["W_star"]  # Maugis-Dugdale at lambda = 1.1272 mu
    assert rec["W_star"] == pytest.approx(md, rel=COARSE_MD_RTOL)
    assert rec["ellipticity"] == pytest.approx(1.0, abs=1e-12)
    assert rec["adhesive_ellipticity"] == pytest.approx(1.0, abs=1e-12)
    assert rec["search"] == "bracket"     # the default 'located' needs N >= 128: the fallback is reported
    ds = read_solution(out)
    assert ds.attrs["search"] == "bracket"
    assert float(ds["W_star_pull_off"]) == rec["W_star"]
    assert ds.attrs["param_beta0"] == 1.0 and ds.attrs["param_law"] == "dugdale"


def test_solve_reports_non_convergence(monkeypatch, capsys):
    """A path whose states cannot converge (one Newton iteration each) exits 3 with one line."""
    import dataclasses

    import dhfield.bem.newton

    monkeypatch.setattr(dhfield.bem.newton, "NESTED_OPTIONS",
                        dataclasses.replace(dhfield.bem.newton.NESTED_OPTIONS, max_newton=1))
    rc = main(["solve", "--beta0", "0.8", "--mu", "1", "--n", "16", "--json"])
    err = [ln for ln in capsys.readouterr().err.strip().splitlines() if not ln.startswith(PROGRESS_PREFIX)]
    assert rc == EXIT_UNCONVERGED
    assert len(err) == 1 and "did not converge" in err[0] and "beta0=0.8, mu=1, n=16" in err[0]


@pytest.mark.parametrize("argv, word", [
    (["--beta0", "1.5", "--mu", "1"], "beta0"),
    (["--beta0", "0.8", "--mu", "-1"], "mu"),
    (["--beta0", "0.8", "--mu", "1", "--n", "15"], "n"),
    (["--beta0", "0.8", "--mu", "1", "--law", "lj"], "law"),
    (["--beta0", "0.8", "--mu", "1", "--search", "gauss"], "search"),
    (["--beta0", "1", "--mu", "2", "--n", "64", "--law", "exponential", "--search", "newton"], "search"),
    (["--beta0", "1", "--mu", "2", "--n", "64", "--control", "displacement", "--search", "newton"], "search"),
    (["--beta0", "0.8", "--mu", "1", "--out", "/nonexistent-dir/x.nc"], "out"),
    (["--beta0", "1", "--mu", "1", "--machine-stiffness", "-1"], "machine-stiffness"),
    (["--beta0", "1", "--mu", "1", "--machine-stiffness", "inf"], "machine-stiffness"),
    (["--beta0", "1", "--mu", "1", "--machine-stiffness", "1", "--control", "displacement"], "control"),
    (["--beta0", "1", "--mu", "1", "--machine-stiffness", "1", "--search", "march"], "search"),
    (["--beta0", "1", "--mu", "1", "--machine-stiffness", "1", "--plot", "x.png"], "plot"),
    (["--beta0", "1", "--mu", "2", "--n", "64", "--law", "exponential", "--search", "predicted"], "search"),
])
def test_solve_bad_input(argv, word, capsys):
    assert main(["solve", *argv]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and word in err[0]


def test_help_documents_exit_status(capsys):
    with pytest.raises(SystemExit):
        main(["solve", "--help"])
    assert f"{EXIT_UNCONVERGED} a state of the path up to the pull-off did not converge" in " ".join(
        capsys.readouterr().out.split())


def test_solve_flags_an_unresolved_pull_off(tmp_path, capsys):
    """Issue 18 item 1: an unresolved pull-off used to print converged = True and exit 0.  On the
    sphere at mu = 0.3, N = 8 the contact covers the centre cells only (resolved = False; W* =
    -0.93 where MD gives -0.89): the CLI must print and store resolved = false and exit 4."""
    from dhfield.cli.solve import EXIT_UNRESOLVED

    out = tmp_path / "unresolved.nc"
    rc = main(["solve", "--beta0", "1", "--mu", "0.3", "--n", "8", "--json", "--out", str(out)])
    captured = capsys.readouterr()
    rec = json.loads(captured.out)
    assert rec["resolved"] is False
    assert rc == EXIT_UNRESOLVED != 0
    assert "unresolved" in captured.err and "beta0=1, mu=0.3, n=8" in captured.err
    ds = read_solution(out)
    assert ds.attrs["resolved"] == 0 and int(ds["resolved"]) == 0
    assert int(ds["converged_pull_off"]) == int(rec["converged"])
    rc = main(["solve", "--beta0", "1", "--mu", "0.3", "--n", "8"])
    text = capsys.readouterr().out
    assert rc == EXIT_UNRESOLVED and "resolved = False" in text


def test_solve_refuses_a_grid_far_too_coarse(tmp_path, capsys):
    """Issue 18 item 1: at mu = 8, N = 32 on the sphere the CLI printed W* = -2.44 (MD: -0.75),
    converged, exit 0.  The Dugdale edge wants 17x its cap there: refused before solving, one line,
    nothing written, exit 5."""
    from dhfield.cli.solve import EXIT_UNRESOLVABLE

    out = tmp_path / "refused.nc"
    rc = main(["solve", "--beta0", "1", "--mu", "8", "--n", "32", "--json", "--out", str(out)])
    captured = capsys.readouterr()
    assert rc == EXIT_UNRESOLVABLE and captured.out == "" and not out.exists()
    err = captured.err.strip().splitlines()
    assert len(err) == 1 and "too coarse" in err[0] and "analytic W*" in err[0]


def test_solve_resolved_case_exits_zero_and_says_so(tmp_path, capsys):
    out = tmp_path / "ok.nc"
    rc = main(["solve", "--beta0", "1", "--mu", "1", "--n", "32", "--out", str(out)])
    text = capsys.readouterr().out
    assert "resolved = True" in text
    ds = read_solution(out)
    assert ds.attrs["resolved"] == 1 and int(ds["resolved"]) == 1
    assert rc in (0, EXIT_UNCONVERGED)


def test_solve_predicted_search_on_an_explicit_grid_is_within_its_error_of_maugis_dugdale(capsys):
    # --search predicted with --n: the high-mu route refined on the caller's grid (here mu = 2, N = 128,
    # resolved, where the route is cheap); MD (Maugis 1992) is exact on the sphere
    from dhfield.models import maugis_dugdale

    rc = main(["solve", "--beta0", "1", "--mu", "2", "--n", "128", "--search", "predicted", "--json"])
    rec = json.loads(capsys.readouterr().out)
    md = float(maugis_dugdale.pull_off_nondimensional(1.0, 2.0, control="load").W_star)
    assert rc == 0 and rec["converged"] and rec["n"] == 128
    assert abs(rec["W_star"] - md) <= rec["W_star_error"]


def test_solve_too_large_for_memory_is_refused_before_allocating(monkeypatch, capsys):
    """Issue 18 item 11: `solve --n 8192` ran past 90 s at >= 5.5 GB with no output.  It is now
    refused at once, in one line with the estimate and the limit: the library's own check (issue 42 finding 6),
    PATH_BYTES_PER_CELL (550 B/cell) x 8192^2 = 34.4 GiB against 80 % of 16 GiB."""
    import dhfield.core.memory
    import dhfield.bem
    from dhfield.analysis.bem_start import PATH_BYTES_PER_CELL

    def forbidden(*a, **k):
        raise AssertionError("solved before checking the memory")

    monkeypatch.setattr(dhfield.bem, "adhesive_pull_off", forbidden)
    monkeypatch.setattr(dhfield.core.memory, "available_memory", lambda: 16 * 2**30)
    assert main(["solve", "--beta0", "1", "--mu", "1", "--n", "8192"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    estimate = f"{PATH_BYTES_PER_CELL * 8192**2 / 2**30:.3g} GiB"
    assert len(err) == 1 and "n=8192" in err[0] and estimate in err[0] and "12.8 GiB" in err[0], (estimate, err)


def test_solve_json_has_units(capsys):
    """Issue 18 item 14: `solve --json` had no units entry (pulloff, curve, compare have one)."""
    main(["solve", "--beta0", "1", "--mu", "1", "--n", "32", "--json"])
    rec = json.loads(capsys.readouterr().out)
    assert rec["units"]["W_star"] == "1" and rec["units"]["elapsed"] == "s"
    assert {k for k, v in rec.items() if isinstance(v, (int, float)) and k != "units"} <= set(rec["units"])


def test_help_opens_with_what_solve_does(capsys):
    """Issue 17: `solve --help` opened with "Displacement-controlled loading/unloading path" although
    load control is the default."""
    with pytest.raises(SystemExit):
        main(["solve", "--help"])
    text = " ".join(capsys.readouterr().out.split())
    desc = text.split("options:")[0].split("]", 1)[-1] if "options:" in text else text
    assert "Pull-off of the adhesive elliptical contact" in desc and "load control (the default)" in desc
    assert not desc.strip().startswith("Displacement")


def test_progress_lines_off_a_terminal(monkeypatch, capsys):
    """Issue 40: progress goes to stderr also when it is not a terminal, one line per state with the
    elapsed time and an ETA, in W* for nondimensional input (the terminal's redrawn line of issue 17
    is off: the lines replace it); --quiet writes none."""
    import dhfield.bem

    seen = {}
    real = dhfield.bem.adhesive_pull_off

    def spy(*a, **k):
        seen["progress"] = k.get("progress")
        return real(*a, **k)

    monkeypatch.setattr(dhfield.bem, "adhesive_pull_off", spy)
    monkeypatch.setattr("sys.stderr.isatty", lambda: False, raising=False)
    assert main(["solve", "--beta0", "1", "--mu", "1", "--n", "32", "--json"]) == 0
    out = capsys.readouterr()
    lines = [ln for ln in out.err.splitlines() if ln.startswith(PROGRESS_PREFIX)]
    assert seen["progress"] is False          # no redrawn terminal line: the lines say it
    assert lines[0].startswith(PROGRESS_PREFIX + "solving beta0=1, mu=1, n=32")
    states = [ln for ln in lines if " state " in ln]
    rec = json.loads(out.out)
    assert len(states) == rec["n_steps"] >= 3    # one line per state (no coarser grid at N = 32)
    assert all(re.search(r"W\* = [-+]\d\.\d{5}; elapsed \d+\.\d s, ETA ~\d+\.\d s$", ln) for ln in states), states
    assert main(["solve", "--beta0", "1", "--mu", "1", "--n", "32", "--json", "--quiet"]) == 0
    assert PROGRESS_PREFIX not in capsys.readouterr().err


def test_a_refinement_is_announced_and_the_eta_counts_the_new_grid():
    """The Newton route's refinements (a finer answer's grid while the stated error is above its target)
    are said on a progress line, and the ETA then counts the states expected on the new grid."""
    import io

    from dhfield.bem.branch import answer_grid_changed, state_reporter
    from dhfield.core.progress import EXPECTED_STATES, SolveProgress

    stream = io.StringIO()
    rep = SolveProgress(1.0, "W*", (64, 64), "newton", stream=stream)
    rep.cells_done, rep.answer_states = 10 * 64 * 64, EXPECTED_STATES["newton"]   # the first answer grid done
    with state_reporter(rep):
        answer_grid_changed((128, 128), "stated error 1.00% above the target 0.20%")
    assert rep.answer_grid == (128, 128) and rep.answer_states == 0
    line = stream.getvalue().strip()
    assert line.startswith(PROGRESS_PREFIX + "refining: the answer's grid is now 128 x 128 (stated error 1.00%")
    # the ETA: the states expected on the new grid, each at the seconds per cell so far times its cells
    per_cell = rep.elapsed() / rep.cells_done
    assert rep.eta() == pytest.approx(EXPECTED_STATES["newton"] * 128 * 128 * per_cell, rel=0.5)
    answer_grid_changed((256, 256))            # outside a reporter's block: nothing to tell, no error


def test_the_eta_takes_the_cost_per_cell_of_the_finest_grid_so_far(monkeypatch):
    """A state on a finer grid needs more iterations: the ETA's seconds per cell are at least those of
    the last state on the finest grid solved so far (here 20 s for 64 x 64 after 0.01 s for 16 x 16)."""
    import io
    from types import SimpleNamespace

    import dhfield.core.progress as progress

    clock = [100.0]
    monkeypatch.setattr(progress.time, "perf_counter", lambda: clock[0])
    rep = progress.SolveProgress(1.0, "W*", (64, 64), "newton", stream=io.StringIO())

    def state(n):
        return SimpleNamespace(grid=SimpleNamespace(nx=n, ny=n), load=-1.0, converged=True)

    clock[0] += 0.01
    rep("coarse", 0, state(16), "refine")
    clock[0] += 20.0
    rep("answer", 1, state(64), "refine")
    left = progress.EXPECTED_STATES["newton"] - 1
    assert rep.eta() == pytest.approx(left * 64 * 64 * (20.0 / (64 * 64)), rel=1e-12)   # not 20.01 s / 4352 cells


def test_progress_in_newtons_for_si_input(capsys):
    """SI input: each state's load in N, W* times the load unit 2 pi R dgamma/sin theta_skew (Eq. 34)."""
    from dhfield.analysis.dimensional import contact_parameters

    args = ["--youngs-modulus", "2e6", "--poisson-ratio", "0.5", "--cylinder-radius", "5e-3", "--skew-angle-deg",
            "60", "--work-of-adhesion", "0.04", "--adhesive-stress", "2.31e4"]
    assert main(["solve", *args, "--n", "32", "--json"]) == 0
    out = capsys.readouterr()
    rec = json.loads(out.out)
    states = [ln for ln in out.err.splitlines() if ln.startswith(PROGRESS_PREFIX) and " state " in ln]
    forces = [float(re.search(r"W = ([-+][0-9.e+-]+) N;", ln).group(1)) for ln in states]
    assert len(forces) == rec["n_steps"]
    # the pull-off is the lowest load of the states solved, in N
    assert min(forces) == pytest.approx(rec["force"], rel=1e-4)
    p = contact_parameters(2e6, 0.5, 2e6, 0.5, 5e-3, math.radians(60), 0.04, 2.31e4)
    assert rec["force"] == pytest.approx(rec["W_star"] * 2 * math.pi * float(p.effective_radius) * 0.04
                                         / float(p.sin_skew), rel=1e-12)


def test_max_seconds_stops_and_says_what_was_reached(capsys):
    """--max-seconds stops the solve after the state that crosses it: exit 6, one line with the states
    reached and the analytic value, nothing on stdout and no file written."""
    from dhfield.cli.solve import EXIT_TIME_LIMIT

    rc = main(["solve", "--beta0", "1", "--mu", "1", "--n", "64", "--max-seconds", "1e-6", "--json"])
    out = capsys.readouterr()
    err = [ln for ln in out.err.strip().splitlines() if not ln.startswith(PROGRESS_PREFIX)]
    assert rc == EXIT_TIME_LIMIT == 6 and out.out == ""
    # the timer stops it within the first state: nothing reached
    assert len(err) == 1 and "stopped at --max-seconds 1e-06 s" in err[0] and "0 states in" in err[0]
    assert "no state solved yet" in err[0] and "not a pull-off" in err[0] and "analytic W* = -0.79" in err[0]
    assert main(["solve", "--beta0", "1", "--mu", "1", "--max-seconds", "0"]) == 2
    assert "max-seconds" in capsys.readouterr().err


def test_time_limit_after_a_state_names_the_lowest_load():
    """Without the timer (or between states) the reporter stops after the state past the limit and says
    the lowest load reached on the answer's grid, in the result's unit."""
    import io
    from types import SimpleNamespace

    from dhfield.core.progress import SolveProgress, SolveTimeLimit

    def state(load, n):
        return SimpleNamespace(load=load, converged=True, grid=SimpleNamespace(nx=n, ny=n))

    stream = io.StringIO()
    rep = SolveProgress(0.5, "N", (64, 64), "located", max_seconds=1e9, stream=stream, header="solving x")
    rep("path", 0, state(-3.0, 32), "unloading")
    rep("located N=64", 0, state(-2.0, 64), "unloading")
    rep.max_seconds = 0.0
    with pytest.raises(SolveTimeLimit, match=r"3 states in .*the lowest W = -1 N on the 64 x 64 grid"):
        rep("located N=64", 1, state(-1.5, 64), "unloading")
    lines = stream.getvalue().splitlines()
    assert lines[0] == PROGRESS_PREFIX + "solving x" and len(lines) == 4
    assert "state 1 on 32 x 32 (path, unloading): W = -1.5 N;" in lines[1]


def test_refusal_quotes_the_analytic_force_in_newtons(capsys):
    """A refused SI case names the analytic pull-off in N (W* times 2 pi R dgamma/sin theta_skew, Eq. 34)."""
    from dhfield.analysis.compare import pull_off
    from dhfield.analysis.dimensional import contact_parameters

    args = ["--youngs-modulus", "2e6", "--poisson-ratio", "0.5", "--cylinder-radius", "5e-3", "--skew-angle-deg",
            "60", "--work-of-adhesion", "0.04", "--adhesive-stress", "2e5"]
    assert main(["solve", *args, "--n", "8"]) == EXIT_UNRESOLVABLE
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "too coarse" in err[0]
    p = contact_parameters(2e6, 0.5, 2e6, 0.5, 5e-3, math.radians(60), 0.04, 2e5)
    w = float(pull_off(beta0=float(p.beta0), mu=float(p.mu), warn=False).W_star)
    force = w * 2 * math.pi * float(p.effective_radius) * 0.04 / float(p.sin_skew)
    got = float(re.search(r"a force of ([-0-9.e+]+) N", err[0]).group(1))
    assert got == pytest.approx(force, rel=1e-5)


# --------------------------------------------------------------------------- SI inputs and outputs (issue 17)
#: The README's PDMS cylinders (E = 2 MPa, nu = 0.5, R_c = 5 mm, 60 deg, dgamma = 0.04 J/m^2) at
#: sigma0 = 23.1 kPa, mu = 1.0003: a Dugdale zone of several cells even at N = 32.
PDMS_SI = ["--youngs-modulus", "2e6", "--poisson-ratio", "0.5", "--cylinder-radius", "5e-3",
           "--skew-angle-deg", "60", "--work-of-adhesion", "0.04", "--adhesive-stress", "2.31e4"]


def test_solve_si_round_trip(tmp_path, capsys):
    """SI in -> the same W* as the nondimensional call at the (beta0, mu) of the contact, and SI out
    by closed forms written here without dhfield.analysis.dimensional: equal cylinders crossed at theta have
    R'R'' = R_c^2/sin^2(theta) (Eqs. 3-5), so R = R_c/sin(theta); E* = E/(2(1 - nu^2)) (Eq. 6);
    W = W* 2 pi R dgamma/sin(theta) (Eq. 34), a = a* c_r with c_r = (R^2 dgamma/E*)^(1/3) (Eqs. 32-33),
    delta = delta* c_r^2/R.  rel 1e-12: the same floats through a different order of operations."""
    import math

    out = tmp_path / "si.nc"
    rc = main(["solve", *PDMS_SI, "--n", "32", "--json", "--out", str(out)])
    si = json.loads(capsys.readouterr().out)
    assert rc in (0, EXIT_UNCONVERGED)
    rc2 = main(["solve", "--beta0", repr(si["beta0"]), "--mu", repr(si["mu"]), "--n", "32", "--json"])
    nd = json.loads(capsys.readouterr().out)
    assert rc2 == rc
    for key in ("W_star", "a_star", "b_star", "c_star", "d_star", "delta_star"):
        assert si[key] == pytest.approx(nd[key], rel=1e-12, abs=0.0), key
    theta, rc_, dgamma, e, nu = math.radians(60.0), 5e-3, 0.04, 2e6, 0.5
    r = rc_ / math.sin(theta)
    e_star = e / (2.0 * (1.0 - nu * nu))
    c_r = (r * r * dgamma / e_star) ** (1.0 / 3.0)
    assert si["force"] == pytest.approx(si["W_star"] * 2.0 * math.pi * r * dgamma / math.sin(theta), rel=1e-12)
    assert si["semi_major"] == pytest.approx(si["a_star"] * c_r, rel=1e-12)
    assert si["adhesive_semi_minor"] == pytest.approx(si["d_star"] * c_r, rel=1e-12)
    assert si["approach"] == pytest.approx(si["delta_star"] * c_r * c_r / r, rel=1e-12)
    assert si["mu"] == pytest.approx(2.31e4 * (r / (e_star ** 2 * dgamma)) ** (1.0 / 3.0), rel=1e-12)  # Eq. (35)
    assert si["units"]["force"] == "N" and si["units"]["semi_major"] == "m" and si["units"]["W_star"] == "1"
    assert si["units"]["max_adhesive_stress"] == "Pa" and si["units"]["approach"] == "m"
    ds = read_solution(out)
    assert float(ds["force_pull_off"]) == si["force"] and ds["force_pull_off"].attrs["units"] == "N"
    assert float(ds["semi_major_pull_off"]) == si["semi_major"] and ds["approach_pull_off"].attrs["units"] == "m"
    assert float(ds["W_star_pull_off"]) == si["W_star"]
    # text output: the SI line beside the nondimensional ones
    main(["solve", *PDMS_SI, "--n", "32"])
    text = capsys.readouterr().out
    assert "W* = " in text and f"force = {si['force']:.6g} N" in text and " m  approach = " in text


@pytest.mark.parametrize("extra, word", [
    (["--beta0", "0.8"], "either --beta0/--mu or physical inputs"),
    (["--adhesive-stress", "1e-3"], "max_adhesive_stress"),          # mu = 4e-8, below the models' range
    (["--youngs-modulus", "0"], "youngs_modulus_1 must be in (0, inf)"),
    (["--skew-angle-deg", "120"], "skew-angle-deg"),
    (["--plot", "figure.svg"], "plot"),
])
def test_solve_bad_si_input(extra, word, capsys, tmp_path, monkeypatch):
    import dhfield.bem

    monkeypatch.chdir(tmp_path)
    monkeypatch.setattr(dhfield.bem, "adhesive_pull_off", lambda *a, **k: pytest.fail("solved a bad input"))
    argv = list(PDMS_SI)
    for flag, value in zip(extra[::2], extra[1::2]):
        if flag in argv:
            argv[argv.index(flag) + 1] = value
        else:
            argv += [flag, value]
    assert main(["solve", *argv, "--n", "32"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and word in err[0], err


def test_solve_incomplete_si_input(capsys):
    assert main(["solve", *PDMS_SI[:-2], "--n", "32"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "--adhesive-stress" in err[0]


def test_solve_plot_writes_png_svg_pdf(tmp_path, capsys):
    """The figure code runs end to end from the command line (N = 32: cheap), SI axes."""
    png = tmp_path / "solve.png"
    rc = main(["solve", *PDMS_SI, "--n", "32", "--plot", str(png)])
    assert rc in (0, EXIT_UNCONVERGED)
    assert f"wrote {png}" in capsys.readouterr().out
    for suffix in (".png", ".svg", ".pdf"):
        assert png.with_suffix(suffix).stat().st_size > 1000
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_solve_refuses_a_grid_far_too_coarse_in_one_line_before_solving(capsys):
    # issue 20: --n 512 at mu = 11.4 (60 deg) printed W* = nan after 110 s; the edge wants 3x its cap there
    from dhfield.cli.solve import EXIT_UNRESOLVABLE

    rc = main(["solve", "--beta0", "0.4826", "--mu", "11.4", "--n", "512"])
    err = capsys.readouterr().err.strip().splitlines()
    assert rc == EXIT_UNRESOLVABLE
    assert len(err) == 1 and "n=512 is too coarse" in err[0] and "needs n >=" in err[0] and "W* = -0.64" in err[0]


def test_solve_without_n_refuses_a_case_beyond_memory(monkeypatch, capsys):
    from dhfield.analysis import bem_start as adhesive_start
    from dhfield.cli.solve import EXIT_UNRESOLVABLE

    monkeypatch.setattr(adhesive_start, "memory_limit", lambda: 1024)
    rc = main(["solve", "--beta0", "0.8", "--mu", "1"])
    err = capsys.readouterr().err.strip().splitlines()
    assert rc == EXIT_UNRESOLVABLE and len(err) == 1 and "GiB available" in err[0] and "analytic W*" in err[0]


# ============================================================================ --machine-stiffness (issue 17)
#: The sphere at lambda = 1.1272 mu = 1 (mu = 0.887) on N = 64: the BEM's discretisation error there,
#: measured against MD under the same spring (python -m verification.bem_spring --n 64 --lam 1), is
#: +0.06 % at K* = 0, +0.23 % at K* = 1 and +0.5 % for a rigid machine; 2 % is 3x the worst and still
#: catches a wrong spring weight (K* = 1 vs K* = 0 moves W* by 27 %) or load normalisation (Eq. 34).
SPRING_MU, SPRING_N, SPRING_RTOL = 0.887, "64", 0.02
#: A sphere of the same mu in SI: PDMS (E = 1.8 MPa, nu = 0.49), R = 3 mm, dgamma = 50 mJ/m^2,
#: sigma0 = 25 kPa (mu = 0.874), under a spring of 50 N/m (K* = 0.093).
SPHERE_SI = ["--youngs-modulus", "1.8e6", "--poisson-ratio", "0.49", "--principal-radii", "3e-3", "3e-3",
             "--work-of-adhesion", "0.05", "--adhesive-stress", "2.5e4"]


def test_solve_under_a_spring_matches_md_under_the_same_spring(tmp_path, capsys):
    """BEM vs Maugis-Dugdale (dhfield.analysis.spring, Maugis 1992 + Maugis & Barquins 1978's jump
    dW/d(delta) = -K) on the sphere at K* = 1: within the stated fit error plus the lattice
    jaggedness of N = 64 (2e-3, tests/test_bem_spring.py), and within SPRING_RTOL."""
    from dhfield.analysis import spring as compliance

    out = tmp_path / "spring.nc"
    rc = main(["solve", "--beta0", "1", "--mu", str(SPRING_MU), "--n", SPRING_N, "--machine-stiffness", "1",
               "--json", "--out", str(out)])
    rec = json.loads(capsys.readouterr().out)
    assert rc == 0 and rec["control"] == "spring" and rec["resolved"] and rec["machine_stiffness_star"] == 1.0
    md = float(compliance.pull_off_under_spring("md", beta0=1.0, mu=SPRING_MU, machine_stiffness=1.0)["W_star"])
    assert abs(rec["W_star"] - md) <= rec["W_star_error"] + 2e-3
    assert rec["W_star"] == pytest.approx(md, rel=SPRING_RTOL)
    assert rec["separation_delta_star"] == pytest.approx(rec["delta_star"] + rec["W_star"] / 1.0, rel=1e-14)
    assert rec["units"]["machine_stiffness_star"] == "1" and rec["units"]["W_star"] == "1"
    ds = read_solution(out)
    assert float(ds["W_star_pull_off"]) == rec["W_star"] and ds.attrs["param_control"] == "spring"
    assert float(ds["machine_stiffness"]) == 1.0 and ds["machine_stiffness"].attrs["units"] == "1"
    assert ds["W_star_branch"].size == rec["branch_states"]
    np.testing.assert_allclose(ds["machine_displacement_branch"], ds["delta_star_branch"] + ds["W_star_branch"],
                               rtol=1e-14)


def test_solve_under_a_spring_in_si(tmp_path, capsys):
    """K in N/m -> K* by Eqs. (33)-(34) (compliance.stiffness_star), force = W* x the load unit, and
    the force against MD's under the same spring (dhfield pulloff --model md) within SPRING_RTOL."""
    from dhfield.analysis import spring as compliance, dimensional

    out = tmp_path / "spring_si.nc"
    rc = main(["solve", *SPHERE_SI, "--n", SPRING_N, "--machine-stiffness", "50", "--json", "--out", str(out)])
    rec = json.loads(capsys.readouterr().out)
    assert rc == 0 and rec["resolved"]
    params = dimensional.contact_parameters_from_principal_radii(1.8e6, 0.49, 1.8e6, 0.49, 3e-3, 3e-3, 0.05, 2.5e4)
    k_star = float(compliance.stiffness_star(50.0, params.effective_radius, params.reduced_modulus, 0.05))
    assert rec["machine_stiffness_star"] == pytest.approx(k_star, rel=1e-14) and rec["machine_stiffness"] == 50.0
    assert rec["force"] == pytest.approx(rec["W_star"] * float(params.load_unit), rel=1e-14)
    md = compliance.pull_off_force_under_spring(params, 50.0, model="md")
    assert rec["force"] == pytest.approx(md["force"], rel=SPRING_RTOL)
    assert rec["units"]["force"] == "N" and rec["units"]["machine_stiffness"] == "N m-1"
    assert rec["units"]["separation_approach"] == "m"
    ds = read_solution(out)
    assert float(ds["force_pull_off"]) == rec["force"] and ds["force_pull_off"].attrs["units"] == "N"
    assert float(ds["machine_stiffness_si"]) == 50.0 and ds["machine_stiffness_si"].attrs["units"] == "N m-1"
    assert ds.attrs["param_machine_stiffness"] == 50.0
    main(["solve", *SPHERE_SI, "--n", SPRING_N, "--machine-stiffness", "50"])
    text = capsys.readouterr().out
    assert "machine spring K* = " in text and f"force = {rec['force']:.6g} N" in text and "(K = 50 N/m)" in text


def test_out_and_plot_are_one_set_an_interrupt_while_plotting_keeps_the_old_files(tmp_path, monkeypatch, capsys):
    """Issue 42 finding 9: Ctrl-C while plotting left a new --out file beside the old images, and the CLI
    said "no output was written"."""
    from dhfield.cli import main
    from dhfield.io import solve_plot

    old = {}
    for name in ("t.nc", "t.png", "t.svg", "t.pdf"):
        (tmp_path / name).write_bytes(f"old {name}".encode())
        old[name] = f"old {name}".encode()

    def interrupted(*args, **kwargs):   # Ctrl-C while the figure is drawn
        raise KeyboardInterrupt

    monkeypatch.setattr(solve_plot, "solve_figure", interrupted)
    status = main(["solve", "--beta0", "1", "--mu", "1", "--n", "16", "--out", str(tmp_path / "t.nc"),
                   "--plot", str(tmp_path / "t.png")])
    err = capsys.readouterr().err.strip().splitlines()
    assert status == 130 and err[-1] == "dhfield: interrupted (SIGINT); no output was written", err
    assert {name: (tmp_path / name).read_bytes() for name in old} == old
    assert not list(tmp_path.glob(".*.part"))
