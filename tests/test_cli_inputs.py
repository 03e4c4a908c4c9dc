"""Option values the parser reads as nothing, flagged fits, and messages in the user's units (issue 42)."""
from __future__ import annotations

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
    from dhfield import compare

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

    from dhfield import dimensional as dim

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
