"""Option values the parser reads as nothing, flagged fits, and messages in the user's units (issue 42)."""
from __future__ import annotations

import math

import pytest

from dhfield.cli import main


@pytest.fixture(autouse=True)
def _private_env(tmp_path, monkeypatch):
    monkeypatch.setenv("DHFIELD_CACHE", str(tmp_path / "cache"))
    monkeypatch.setenv("DHFIELD_THREADS", "1")
    monkeypatch.delenv("DHFIELD_DEBUG", raising=False)
    monkeypatch.chdir(tmp_path)


def _run(capsys, argv):
    code = main(argv)
    out, err = capsys.readouterr()
    return code, out, err


# ------------------------------------------------------------------ finding 11: "--opt=--" is an empty list
@pytest.mark.parametrize("argv, option", [
    (["pulloff", "--beta0=--", "--mu", "1"], "--beta0"),
    (["pulloff", "--beta0", "0.9", "--mu=--"], "--mu"),
    (["compare", "--beta0=--", "--mu", "1"], "--beta0"),
    (["solve", "--beta0=--", "--mu", "1", "--n", "32"], "--beta0"),
    (["field", "--beta0=--", "--mu", "1", "--a-star", "1.2", "--n", "16", "--out", "f.nc"], "--beta0"),
    (["curve", "--beta0=--", "--mu", "1"], "--beta0"),
    (["periphery", "--beta0=--", "--mu", "1"], "--beta0"),
    (["sweep", "--beta0=--", "--mu", "1", "--models", "jkr", "--out", "s.nc"], "--beta0"),
    (["sweep", "--beta0", "0.9", "--mu", "1", "--models=--", "--out", "s.nc"], "--models"),
    (["cycle", "--beta0", "1", "--mu", "1", "--machine-stiffness=--", "--json"], "--machine-stiffness"),
    (["fit", "--pull-off-force=--", "--adhesive-stress", "1"], "--pull-off-force"),
])
def test_an_option_given_as_double_dash_is_refused_by_name(capsys, argv, option):
    code, out, err = _run(capsys, argv)
    assert code == 2 and out == "" and err.count("\n") == 1, (code, out, err)
    assert err.startswith(f"dhfield: error: {argv[0]}: argument {option}") and "expected a value" in err, err


@pytest.mark.parametrize("kw, name", [({"beta0": [], "mu": 1.0}, "beta0"), ({"beta0": 0.9, "mu": []}, "mu"),
                                      ({"beta0": (), "mu": ()}, "mu")])
def test_compare_refuses_empty_arrays_by_name(kw, name):
    from dhfield.analysis import compare

    with pytest.raises(ValueError, match=f"^{name} must contain at least one value"):
        compare.pull_off("md-elliptic", **kw)
    with pytest.raises(ValueError, match=f"^{name} must contain at least one value"):
        compare.compare(**kw)


# ------------------------------------------------------------------ finding 5: a flagged fit exits non-zero
PDMS = ["--youngs-modulus", "1.8e6", "--poisson-ratio", "0.49", "--cylinder-radius", "3e-3", "--skew-angle-deg", "60"]


@pytest.fixture(scope="module")
def jkr_side_curve(tmp_path_factory):
    """A load curve deep on the JKR side (sigma0 = 1e8 Pa: mu ~ 3700), 12 points [N], [m].

    There the load curve is the JKR one, which does not depend on sigma0 (JKR has no adhesive stress):
    the data determine dgamma but not sigma0.
    """
    import math

    import numpy as np

    from dhfield.analysis import dimensional as dim

    p = dim.contact_parameters(1.8e6, 0.49, 1.8e6, 0.49, 3e-3, math.pi / 3, 0.05, 1e8)
    a = p.length_unit * np.linspace(0.5, 3.0, 12)
    w = dim.load_curve_si(p, semi_major=a, model="md-elliptic")["force"]
    path = tmp_path_factory.mktemp("jkr") / "jkr.csv"
    path.write_text("force,semi_major\n" + "".join(f"{float(x)!r},{float(y)!r}\n" for x, y in zip(w, a)))
    return str(path)


def test_a_fit_that_cannot_identify_sigma0_is_flagged(capsys, jkr_side_curve):
    import json

    from dhfield.cli.solve import EXIT_UNCONVERGED

    code, out, err = _run(capsys, ["fit", "--data", jkr_side_curve, *PDMS])
    assert code == EXIT_UNCONVERGED, (code, err)
    rows = dict(line.split(None, 1) for line in out.splitlines())
    assert rows["max_adhesive_stress"] == "not identifiable" and rows["mu"] == "not identifiable", out
    assert rows["max_adhesive_stress_stderr"] == "not identifiable"
    assert rows["work_of_adhesion"].split()[0] == "0.05"  # dgamma is determined by a JKR curve
    flagged = [ln for ln in err.splitlines() if not ln.startswith("dhfield: warning:")]
    assert flagged == [flagged[0]] and flagged[0].startswith("dhfield: fit is not an answer: max_adhesive_stress "
                                                             "not identifiable"), err

    code, out, err = _run(capsys, ["fit", "--data", jkr_side_curve, *PDMS, "--json"])
    rec = json.loads(out)
    assert code == EXIT_UNCONVERGED and rec["success"] is False
    assert rec["max_adhesive_stress"] is None and rec["mu"] is None and rec["not_identifiable"] == ["max_adhesive_stress"]
    assert rec["work_of_adhesion"] == pytest.approx(0.05, rel=1e-6)


# ------------------------------------------------------------------ finding 7: threads from the free cores
@pytest.mark.parametrize("cpus, load, threads", [
    (2, 0.0, 2),     # idle: every core
    (2, 2.4, 1),     # 2 cores already busy: one thread, not two that compete with them
    (2, 6.5, 1),     # overloaded: still at least one
    (8, 2.6, 4),     # 8 - 3 = 5 free, capped at CLI_DEFAULT_MAX_THREADS = 4
    (8, 5.2, 3),
    (1, float("nan"), 1),
])
def test_bem_commands_take_threads_from_the_free_cores(monkeypatch, cpus, load, threads):
    import os

    from dhfield.bem.operator import free_cpu_count
    from dhfield.cli._common import command_threads

    monkeypatch.delenv("DHFIELD_THREADS", raising=False)
    monkeypatch.setattr(os, "sched_getaffinity", lambda pid: set(range(cpus)), raising=False)
    monkeypatch.setattr(os, "getloadavg", lambda: (load, load, load))
    assert command_threads() == threads
    assert free_cpu_count() == max(1, cpus - (round(load) if load == load else 0))
    monkeypatch.setenv("DHFIELD_THREADS", "2")  # the override stays
    assert command_threads() == 2 and command_threads(3) == 3


def test_free_cores_without_a_load_average(monkeypatch):
    import os

    from dhfield.bem.operator import free_cpu_count

    def unavailable():
        raise OSError("no load average")

    monkeypatch.setattr(os, "sched_getaffinity", lambda pid: {0, 1, 2}, raising=False)
    monkeypatch.setattr(os, "getloadavg", unavailable)
    assert free_cpu_count() == 3


# ------------------------------------------------------------------ finding 12: messages in the user's units
SI = ["--youngs-modulus", "1e6", "--poisson-ratio", "0.5", "--cylinder-radius", "0.01", "--work-of-adhesion", "0.05",
      "--adhesive-stress", "1e6"]


def _error(capsys, argv):
    code, out, err = _run(capsys, argv)
    assert code == 2 and out == "" and err.count("\n") == 1 and err.startswith("dhfield: error: "), (code, out, err)
    return err


def test_curve_load_range_below_the_pull_off_speaks_newtons(capsys):
    from dhfield.analysis import compare, dimensional

    err = _error(capsys, ["curve", *SI, "--skew-angle-deg", "60", "--load-min=-1", "--load-max", "1"])
    assert "W*" not in err and "got min -1 N" in err and " N of md-elliptic" in err, err
    # the bound quoted is the pull-off force in newtons: W* of Eq. (34) times 2 pi R dgamma / sin(theta)
    p = dimensional.contact_parameters(1e6, 0.5, 1e6, 0.5, 0.01, math.radians(60), 0.05, 1e6)
    w_star = float(compare.pull_off("md-elliptic", beta0=p.beta0, mu=p.mu)["W_star"])
    force = w_star * 2.0 * math.pi * float(p.effective_radius) * 0.05 / float(p.sin_skew)
    assert f"pull-off force {force:.6g} N" in err, (force, err)


def test_skew_angle_bound_is_in_degrees(capsys):
    from dhfield.core import geometry

    err = _error(capsys, ["pulloff", *SI, "--skew-angle-deg", "0.0354"])
    low = math.degrees(float(geometry.skew_angle(1e-4)))  # beta0 = 1e-4, the line-contact limit
    assert f"skew-angle-deg must be in [{low:.6g}, 90] degrees" in err and "rad" not in err, err
    assert 0.0354 < low < 0.0355


@pytest.mark.parametrize("cell, shown", [("nan", "nan"), ("inf", "inf"), ("abc", "'abc'")])
def test_csv_errors_print_plain_values(capsys, tmp_path, cell, shown):
    (tmp_path / "d.csv").write_text(f"force,semi_major\n1e-3,1e-4\n{cell},2e-4\n2e-3,3e-4\n")
    err = _error(capsys, ["fit", "--data", str(tmp_path / "d.csv"), *PDMS])
    assert f"column 'force': value {shown} in data row 2 is not a finite number" in err and "np." not in err, err


def test_csv_over_the_row_limit_names_the_file_and_rows(capsys, tmp_path, monkeypatch):
    import dhfield.io.fit as io_fit

    monkeypatch.setattr(io_fit, "MAX_DATA_ROWS", 10)
    rows = "".join(f"{1e-3 * (k - 5)!r},{1e-4 * (k + 1)!r}\n" for k in range(11))
    (tmp_path / "many.csv").write_text("force,semi_major\n" + rows)
    err = _error(capsys, ["fit", "--data", str(tmp_path / "many.csv"), *PDMS])
    assert "many.csv' has 11 data rows; a load curve may have at most 10" in err and "a_star" not in err, err


def test_a_toml_integer_too_long_for_python_names_its_key(capsys, tmp_path):
    import sys

    digits = sys.get_int_max_str_digits() + 700
    (tmp_path / "c.toml").write_text('[axes]\nbeta0 = [0.9]\nmu = [1.0]\n[sweep]\nmodels = ["jkr"]\n'
                                     f"chunk_points = {'9' * digits}\n")
    err = _error(capsys, ["sweep", str(tmp_path / "c.toml"), "--out", "s.nc", "--quiet"])
    assert f"key 'sweep.chunk_points' (line 6): an integer of {digits} digits" in err, err
    assert "set_int_max_str_digits" not in err


def test_the_wisdom_cache_warning_is_one_line_without_source(capsys, tmp_path, monkeypatch):
    from dhfield.bem import _wisdom

    from dhfield.bem.operator import clear_operator_cache

    monkeypatch.setitem(_wisdom._WISDOM_STATE, "loaded", False)
    clear_operator_cache()     # a cached operator (an earlier test's 16 x 16 solve) would not load the wisdom
    cache = tmp_path / "cache"
    cache.mkdir(exist_ok=True)
    (cache / "fftw_wisdom.bin").write_bytes(b"garbage\n")
    (cache / "fftw_wisdom.bin").chmod(0o644)
    code, out, err = _run(capsys, ["solve", "--beta0", "1", "--mu", "1", "--n", "16", "--json"])
    lines = [ln for ln in err.splitlines() if "wisdom" in ln]
    assert lines == [f"dhfield: warning: ignoring the FFTW wisdom cache {str(cache / 'fftw_wisdom.bin')!r}: not a "
                     "dhfield wisdom file (bad magic); it will be rewritten"], err
    assert ".py:" not in err and "WisdomCacheWarning" not in err, err


def test_a_sweep_worker_prints_a_warning_as_one_line(monkeypatch):
    import threading
    import warnings

    from dhfield.sweep import engine

    monkeypatch.setattr(warnings, "formatwarning", warnings.formatwarning)  # restored after the test
    engine._start_worker(threading.Barrier(1), ())  # what a local worker process runs first
    # what Python's warnings.showwarning writes to the worker's stderr (the parent's stderr)
    text = warnings.formatwarning("invalid value encountered in divide", RuntimeWarning, "/x/scipy/_y.py", 7,
                                  "    return a / b")
    assert text == "dhfield: warning: invalid value encountered in divide\n"
