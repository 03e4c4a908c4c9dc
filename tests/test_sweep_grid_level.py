"""The adhesive quantity of a sweep on the library's automatic grid (the ``grid_level`` axis).

Level 1 is the grid and route :func:`dhfield.analysis.bem_start.adhesive_pull_off` plans when no
``n`` is given; level k the explicit grid of k times its cells per axis.  Checked: the config
(parsing, one-line errors), the grid of each level against the library's plan (identities),
the refusal of an unaffordable level before any solve, and one cheap case end to end through
the sweep engine (convergence over the two levels within the stated errors, the flags, the
grid, the timings and the provenance stored per case, and a rerun reusing the cases).
"""
from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from dhfield.analysis.bem_start import plan_grid
from dhfield.sweep import config_from_mapping, engine, load_config, run_sweep, tasks
from dhfield.sweep.config import MAX_GRID_LEVEL

LEVELS = {"axes": {"beta0": [0.1], "mu": [1.0], "grid_level": [1, 2]}, "sweep": {"quantities": ["adhesive"]}}


def test_grid_level_axis_from_toml(tmp_path):
    path = tmp_path / "s.toml"
    path.write_text('[sweep]\nquantities = ["adhesive"]\n[axes]\nbeta0 = [0.5, 1.0]\nmu = [0.1, 3]\n'
                    'grid_level = [1, 2]\n')
    cfg = load_config(path)
    assert cfg.axes["grid_level"] == (1, 2) and all(type(v) is int for v in cfg.axes["grid_level"])
    assert cfg.adhesive_grid_axis == "grid_level" and "n" not in cfg.axes
    assert config_from_mapping(cfg.as_dict()) == cfg
    explicit = config_from_mapping({"axes": {"beta0": [0.5, 1.0], "mu": [0.1, 3.0], "n": [256, 512]},
                                    "sweep": {"quantities": ["adhesive"]}})
    assert explicit.adhesive_grid_axis == "n"
    assert explicit.fingerprint() != cfg.fingerprint()


@pytest.mark.parametrize("axes, quantities, words", [
    ({"grid_level": [0]}, ["adhesive"], "axes.grid_level must be integers in [1, 4]"),
    ({"grid_level": [MAX_GRID_LEVEL + 1]}, ["adhesive"], "axes.grid_level"),
    ({"grid_level": [1.5]}, ["adhesive"], "axes.grid_level"),
    ({"grid_level": [True]}, ["adhesive"], "axes.grid_level"),
    ({"grid_level": ["auto"]}, ["adhesive"], "axes.grid_level"),
    ({"grid_level": [1, 1]}, ["adhesive"], "distinct"),
    ({"grid_level": [1], "n": [256]}, ["adhesive"], "give n (explicit n x n grids) or grid_level"),
    ({}, ["adhesive"], "axes.n or axes.grid_level is needed by the quantity 'adhesive'"),
    ({"grid_level": [1]}, ["pull_off"], "axes.grid_level is not used"),
    ({"grid_level": [1], "n": [64], "a_star": [1.0]}, ["bem_field", "adhesive"], "not both"),
    ({"n": ["auto"]}, ["adhesive"], "use the grid_level axis instead"),
])
def test_bad_grid_level_config_is_one_line(axes, quantities, words):
    mapping = {"axes": {"beta0": [0.5], "mu": [1.0], **axes}, "sweep": {"quantities": quantities}}
    with pytest.raises(ValueError, match=words.replace("(", r"\(").replace(")", r"\)").replace(".", r"\.")
                       .replace("[", r"\[").replace("]", r"\]")) as exc:
        config_from_mapping(mapping)
    assert "\n" not in str(exc.value)


def test_levels_are_the_librarys_plan():
    """Level 1 is plan_grid's automatic grid; level 2 twice the explicit-route plan per axis."""
    plan = plan_grid(beta0=0.1806, mu=3.0)
    one, two = tasks.automatic_grid(0.1806, 3.0, 1), tasks.automatic_grid(0.1806, 3.0, 2)
    assert (one["nx"], one["ny"]) == (plan.n_needed, plan.ny_needed) and one["automatic"]
    assert (two["nx"], two["ny"]) == (2 * plan.n_needed, 2 * plan.ny_needed) and not two["automatic"]
    # At mu >= 7.5 level 1 takes the predicted route (its own domain); level 2 doubles it, same route.
    high = tasks.automatic_grid(0.5, 10.0, 1)
    assert high["predicted"] and high["nx"] == plan_grid(beta0=0.5, mu=10.0).n_needed
    two = tasks.automatic_grid(0.5, 10.0, 2)
    assert two["predicted"] and (two["nx"], two["ny"]) == (2 * high["nx"], 2 * high["ny"])
    with pytest.raises(ValueError, match="grid_level"):
        tasks.automatic_grid(0.5, 1.0, 0)


def test_refined_levels_take_the_newton_route_and_the_file_names_it(tmp_path, solver_calls, any_memory):
    """A level k >= 2 is k x the plan by level 1's route, the Newton route (search 'newton'); the file
    records the adhesive route (param_bem_adhesive_route)."""
    calls = solver_calls
    cfg = config_from_mapping({"axes": {"beta0": [0.5], "mu": [10.0], "grid_level": [2]},
                               "sweep": {"quantities": ["adhesive"]}, "bem": {"max_seconds": 1e6}})
    done = run_sweep(cfg, out=tmp_path / "r.nc", scheduler="synchronous", progress=False)
    assert done.failed == [] and len(calls) == 1
    plan = plan_grid(beta0=0.5, mu=10.0)
    assert (calls[0]["n"], calls[0]["ny"]) == (2 * plan.n_needed, 2 * plan.ny_needed)
    assert calls[0]["search"] == "newton"
    assert done.dataset.attrs["param_bem_adhesive_route"] == "newton"


def test_unaffordable_level_is_refused_before_solving(monkeypatch):
    def never(**kw):
        raise AssertionError("the solver must not be called")

    monkeypatch.setattr(tasks, "adhesive_solver", lambda name="default": never)
    with pytest.raises(RuntimeError, match=r"grid_level 4: \d+ x \d+ cells need .*use the analytic W\* = -0\.\d+"):
        tasks.adhesive_case(0.5, 10.0, grid_level=4)
    with pytest.raises(ValueError, match="give n .* or grid_level"):
        tasks.adhesive_case(0.5, 1.0)


def test_cheap_case_end_to_end(tmp_path):
    """beta0 = 0.1 (18 deg crossing), mu = 1: the Newton route on at least 256 x 64 and on 512 x 128 cells, ~5 s in all."""
    cfg = config_from_mapping(LEVELS)
    res = run_sweep(cfg, out=tmp_path / "lv.nc", scheduler="synchronous", progress=False)
    assert res.failed == [] and res.flagged == [] and len(res.computed) == 2
    ds = res.dataset.sel(beta0=0.1, mu=1.0).isel(law=0)
    assert ds["W_star"].dims == ("model", "grid_level")
    plan = plan_grid(beta0=0.1, mu=1.0)
    # the Newton route answers on at least the planned cells (level 1: refined while its stated error
    # exceeds 0.2 %; level k: k x the plan, as given)
    assert (ds["nx"].values >= [plan.n_needed, 2 * plan.n_needed]).all()
    assert (ds["ny"].values >= [plan.ny_needed, 2 * plan.ny_needed]).all()
    assert ds["nx"].values[1] == 2 * plan.n_needed
    assert (ds["converged"].values == 1).all() and (ds["resolved"].values == 1).all()
    assert (ds["status"].values == 0).all()
    w = ds["W_star"].sel(model=tasks.ADHESIVE_MODEL).values
    err = ds["W_star_error"].values
    assert np.all(np.isfinite(err)) and np.all(err > 0)
    # Convergence over N: both levels answer within their stated errors of the same pull-off.
    assert abs(w[0] - w[1]) <= err[0] + err[1]
    # Between the DMT limit -sin(theta_skew) (W* is normalised by it, Eq. 34) and zero.
    sin_skew = float(ds["sin_skew"].sel(model=tasks.ADHESIVE_MODEL)[0])
    assert np.all((-sin_skew < w) & (w < 0))
    assert np.all(ds["half_width_x"].values > ds["half_width_y"].values)   # the slender domain
    assert np.all(ds["wall_seconds"].values > 0) and np.all(ds["cpu_seconds"].values > 0)
    for k in ("adhesive_search", "adhesive_commit", "adhesive_finished", "adhesive_command"):
        assert all(str(v) for v in ds[k].values), k
    assert all(str(v).endswith("Z") for v in ds["adhesive_finished"].values)
    again = run_sweep(cfg, out=tmp_path / "lv.nc", scheduler="synchronous", progress=False)
    assert again.computed == [] and len(again.reused) == 2
    for k in ("W_star", "nx", "wall_seconds", "adhesive_commit", "adhesive_finished"):
        assert (again.dataset[k].values == res.dataset[k].values).all(), k


def test_failed_level_keeps_its_reason_and_provenance(tmp_path, monkeypatch):
    def broken(**kw):
        raise MemoryError("no room")

    monkeypatch.setattr(tasks, "adhesive_solver", lambda name="default": broken)
    monkeypatch.setattr(engine, "adhesive_solver", lambda name="default": broken)
    cfg = config_from_mapping({**LEVELS, "axes": {**LEVELS["axes"], "grid_level": [1]}})
    res = run_sweep(cfg, out=tmp_path / "f.nc", scheduler="synchronous", progress=False)
    ds = res.dataset.isel(beta0=0, mu=0, grid_level=0, law=0)
    assert len(res.failed) == 1
    assert int(ds["status"].sel(model=tasks.ADHESIVE_MODEL)) == engine._STATUS["failed"]
    assert "MemoryError: no room" in str(ds["adhesive_message"].values)
    assert np.isnan(float(ds["W_star"].sel(model=tasks.ADHESIVE_MODEL))) and float(ds["wall_seconds"]) > 0
    assert str(ds["adhesive_commit"].values) and str(ds["adhesive_finished"].values)


def test_cli_grid_level_flag(tmp_path, capsys):
    """`dhfield sweep --grid-level 1 --quantities adhesive` solves on the automatic grid; a bad level exits 2."""
    import xarray as xr

    from dhfield.cli import main

    out = tmp_path / "cli.nc"
    rc = main(["sweep", "--beta0", "0.1", "--mu", "1", "--grid-level", "1", "--quantities", "adhesive",
               "--workers", "1", "--out", str(out), "--quiet"])
    assert rc == 0
    with xr.open_dataset(out) as ds:
        assert int(ds["nx"].values.item()) >= plan_grid(beta0=0.1, mu=1.0).n_needed   # (refined by the route)
    rc = main(["sweep", "--beta0", "0.1", "--mu", "1", "--grid-level", "9", "--quantities", "adhesive",
               "--out", str(tmp_path / "bad.nc")])
    err = capsys.readouterr().err.strip()
    assert rc == 2 and "axes.grid_level" in err and len(err.splitlines()) == 1


@settings(max_examples=40, deadline=None)
@given(st.one_of(st.integers(-50, 50), st.floats(allow_nan=True, allow_infinity=True), st.booleans(), st.text()))
def test_grid_level_domain(value):
    """Accepted iff an integer (or integral number) in [1, MAX_GRID_LEVEL]; anything else one line naming the axis."""
    mapping = {"axes": {"beta0": [0.5], "mu": [1.0], "grid_level": [value]}, "sweep": {"quantities": ["adhesive"]}}
    ok = (not isinstance(value, (bool, str)) and isinstance(value, (int, float)) and np.isfinite(value)
          and value == int(value) and 1 <= value <= MAX_GRID_LEVEL)
    if ok:
        assert config_from_mapping(mapping).axes["grid_level"] == (int(value),)
    else:
        with pytest.raises(ValueError, match="axes.grid_level") as exc:
            config_from_mapping(mapping)
        assert "\n" not in str(exc.value)


# --- the time allowed per adhesive case ([bem] max_seconds, --max-seconds; issue 20) -------------------------
class _Answer:
    """A converged, resolved stub result (the solver is never run: these tests decide refusals only)."""
    W_star, converged, resolved = -0.6, True, True


def _recording_solver(calls):
    def solver(**kw):
        calls.append(kw)
        return _Answer()
    return solver


@pytest.fixture
def solver_calls(monkeypatch):
    """The keyword arguments of every adhesive solve of a sweep (tasks and engine), answered by the stub."""
    calls = []
    solver = _recording_solver(calls)
    monkeypatch.setattr(tasks, "adhesive_solver", lambda name="default": solver)
    monkeypatch.setattr(engine, "adhesive_solver", lambda name="default": solver)
    return calls


@pytest.fixture
def any_memory(monkeypatch):
    """No memory limit: the refusal is decided by the time allowed alone, on any machine."""
    from dhfield.analysis import bem_start as adhesive_start

    monkeypatch.setattr(adhesive_start, "memory_limit", lambda: None)


def test_max_seconds_decides_the_refusal_of_a_level_before_solving(monkeypatch, any_memory):
    """Issue 20: beta0 = 0.5, mu = 10 at level 2 is estimated beyond the library's default time
    (~50 min > 30 min when written).  A max_seconds above a level's estimate solves it, with the
    solver given that allowance; below, it is refused before the solver is called."""
    from dhfield.analysis.bem_start import DEFAULT_MAX_SECONDS, AdhesiveOptions

    calls = []
    monkeypatch.setattr(tasks, "adhesive_solver", lambda name="default": _recording_solver(calls))
    grid = tasks.automatic_grid(0.5, 10.0, 2)
    assert grid["max_seconds"] == DEFAULT_MAX_SECONDS and not grid["automatic"]
    estimate = grid["seconds"]
    if estimate > DEFAULT_MAX_SECONDS:   # the default refuses it (the case of the issue)
        with pytest.raises(RuntimeError, match=r"min allowed \(\[bem\] max_seconds, --max-seconds\)"):
            tasks.adhesive_case(0.5, 10.0, grid_level=2)
        assert calls == []
    with pytest.raises(RuntimeError, match="grid_level 2: .* more than the"):
        tasks.adhesive_case(0.5, 10.0, grid_level=2, max_seconds=0.5 * estimate)
    assert calls == []                                       # refused before solving
    allowed = 2.0 * estimate
    assert tasks.automatic_grid(0.5, 10.0, 2, max_seconds=allowed)["max_seconds"] == allowed
    rec = tasks.adhesive_case(0.5, 10.0, grid_level=2, max_seconds=allowed)
    assert rec["W_star"] == -0.6 and len(calls) == 1
    kw = calls[0]
    assert (kw["n"], kw["ny"]) == (grid["nx"], grid["ny"])
    assert kw["search"] == "newton"                          # level 1's route (the default), on k x its plan
    assert isinstance(kw["options"], AdhesiveOptions) and kw["options"].max_seconds == allowed
    # level 1 and an explicit n: the solver plans (and refuses) with the same allowance
    tasks.adhesive_case(0.5, 10.0, grid_level=1, max_seconds=allowed)
    tasks.adhesive_case(0.5, 1.0, 64, max_seconds=allowed)
    assert "n" not in calls[1] and calls[1]["options"].max_seconds == allowed
    assert calls[2]["n"] == 64 and calls[2]["options"].max_seconds == allowed
    assert "search" not in calls[1] and "search" not in calls[2]
    tasks.adhesive_case(0.5, 1.0, grid_level=1)              # none given: the library's default, no options
    assert "options" not in calls[3]
    for bad in (0.0, -1.0, float("nan"), float("inf")):
        with pytest.raises(ValueError, match="max_seconds"):
            tasks.adhesive_case(0.5, 1.0, grid_level=2, max_seconds=bad)
    assert len(calls) == 4


def test_a_rerun_with_more_time_solves_the_refused_level(tmp_path, solver_calls, any_memory):
    """A level refused at the default time is stored failed; the same sweep with a larger [bem] max_seconds
    (not in the fingerprint) resumes the store and solves it alone, and the file records the time allowed."""
    from dhfield.analysis.bem_start import DEFAULT_MAX_SECONDS

    calls = solver_calls
    estimate = tasks.automatic_grid(0.5, 10.0, 2)["seconds"]
    base = {"axes": {"beta0": [0.5], "mu": [10.0], "grid_level": [2]}, "sweep": {"quantities": ["adhesive"]}}
    short = config_from_mapping({**base, "bem": {"max_seconds": 0.5 * estimate}})
    first = run_sweep(short, out=tmp_path / "t.nc", scheduler="synchronous", progress=False)
    assert len(first.failed) == 1 and calls == []
    msg = str(first.dataset["adhesive_message"].values.item())
    assert "more than the" in msg and "max_seconds" in msg
    assert first.dataset.attrs["param_bem_max_seconds"] == 0.5 * estimate
    longer = config_from_mapping({**base, "bem": {"max_seconds": 2.0 * estimate}})
    assert longer.fingerprint() == short.fingerprint()
    second = run_sweep(longer, out=tmp_path / "t.nc", scheduler="synchronous", progress=False)
    assert second.failed == [] and second.computed == first.failed and len(calls) == 1
    assert calls[0]["options"].max_seconds == 2.0 * estimate
    assert float(second.dataset["W_star"].sel(model=tasks.ADHESIVE_MODEL).values.item()) == -0.6
    assert second.dataset.attrs["param_bem_max_seconds"] == 2.0 * estimate
    default = run_sweep(config_from_mapping(base), out=tmp_path / "d", scheduler="synchronous", progress=False)
    assert default.dataset.attrs["param_bem_max_seconds"] == DEFAULT_MAX_SECONDS
