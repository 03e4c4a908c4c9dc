"""Sweep configuration: TOML and flag forms, and every bad input rejected before work starts."""
from __future__ import annotations

import numpy as np
import pytest

from dhfield.cli import main
from dhfield.sweep import config_from_mapping, engine, load_config
from dhfield.sweep.config import axis_values, check_scheduler_address

#: cos(pi/2) is 6e-17 in floating point, so beta0 at 90 degrees is 1 to a few ulp.
CIRCLE_ATOL = 1e-15

GOOD = {"axes": {"beta0": [0.8, 0.9, 1.0], "mu": {"geomspace": [0.1, 10, 5]}},
        "sweep": {"models": ["dh-elliptic", "md"], "chunk_points": 8}}


def test_mapping_round_trip():
    cfg = config_from_mapping(GOOD)
    assert cfg.axes["beta0"] == (0.8, 0.9, 1.0)
    np.testing.assert_array_equal(cfg.axes["mu"], np.geomspace(0.1, 10, 5))
    assert cfg.models == ("dh-elliptic", "md") and cfg.quantities == ("pull_off",)
    again = config_from_mapping(cfg.as_dict())
    assert again == cfg and again.fingerprint() == cfg.fingerprint()


def test_fingerprint_ignores_where_and_how_it_runs():
    base = config_from_mapping(GOOD)
    moved = config_from_mapping({**GOOD, "run": {"workers": 2, "out": "elsewhere.nc"}})
    assert moved.fingerprint() == base.fingerprint()
    other = config_from_mapping({**GOOD, "sweep": {"models": ["md"]}})
    assert other.fingerprint() != base.fingerprint()


def test_toml_file(tmp_path):
    path = tmp_path / "s.toml"
    path.write_text('[sweep]\nquantities = ["bem_field"]\n[axes]\nskew_angle_deg = {linspace = [45, 90, 3]}\n'
                    'mu = [1.0]\na_star = [1.0]\nn = [64]\n[bem]\nhalf_width = 3.0\n')
    cfg = load_config(path)
    assert cfg.ellipticity_axis == "skew_angle_deg"
    assert cfg.beta0[-1] == pytest.approx(1.0, abs=CIRCLE_ATOL)  # 90 degrees: the circle (Eqs. 3-4)
    assert np.all(np.diff(cfg.beta0) > 0)
    assert cfg.half_width == 3.0


@pytest.mark.parametrize("mapping, words", [
    ({**GOOD, "extra": {}}, "unknown config key 'extra'"),
    ({**GOOD, "sweep": {"modles": ["md"]}}, "sweep.modles"),
    ({"axes": {"beta0": [0.9], "mu": [1.0], "theta": [1.0]}}, "axes.theta"),
    ({"axes": {"beta0": [], "mu": [1.0]}}, "axes.beta0 must not be empty"),
    ({"axes": {"beta0": [0.9], "mu": {"geomspace": [0.1, 1, 0]}}}, "axes.mu.geomspace num"),
    ({"axes": {"beta0": [0.9, 1.5], "mu": [1.0]}}, "axes.beta0"),
    ({"axes": {"beta0": [0.9], "mu": [0.0]}}, "axes.mu"),
    ({"axes": {"beta0": [0.9], "mu": [float("nan")]}}, "axes.mu"),
    ({"axes": {"beta0": [0.9], "mu": [1.0, 1.0]}}, "distinct"),
    ({"axes": {"skew_angle_deg": [120.0], "mu": [1.0]}}, "axes.skew_angle_deg"),
    ({"axes": {"beta0": [0.9], "skew_angle_deg": [60.0], "mu": [1.0]}}, "not both"),
    ({"axes": {"beta0": [0.9]}}, "axes must include mu"),
    ({"axes": {"beta0": [0.9], "mu": [1.0], "a_star": [1.0], "n": [33]}, "sweep": {"quantities": ["bem_field"]}},
     "axes.n"),
    ({"axes": {"beta0": [0.9], "mu": [1.0], "n": [64]}, "sweep": {"quantities": ["bem_field"]}},
     "axes.a_star is needed"),
    ({"axes": {"beta0": [0.9], "mu": [1.0], "a_star": [1.0]}}, "not used"),
    ({**GOOD, "sweep": {"quantities": ["pull_off", "bem_field"]},
      "axes": {"beta0": [0.9], "mu": [1.0], "a_star": [1.0], "n": [64]}}, "axes.a_star cannot be swept"),
    ({**GOOD, "sweep": {"models": ["nope"]}}, "sweep.models"),
    ({**GOOD, "sweep": {"quantities": ["everything"]}}, "sweep.quantities"),
    ({**GOOD, "sweep": {"control": "force"}}, "sweep.control"),
    ({**GOOD, "sweep": {"chunk_points": 0}}, "sweep.chunk_points"),
    ({**GOOD, "bem": {"half_width": -1.0}}, "bem.half_width"),
    ({**GOOD, "run": {"workers": 0}}, "run.workers"),
    ({**GOOD, "run": {"scheduler": "localhost"}}, "scheduler"),
    ({"axes": {"beta0": {"linspace": [0.1, 1]}, "mu": [1.0]}}, "axes.beta0.linspace"),
])
def test_bad_config_names_the_key(mapping, words):
    with pytest.raises(ValueError, match=words.replace("(", r"\(").replace(".", r"\.")) as exc:
        config_from_mapping(mapping)
    assert "\n" not in str(exc.value)


def test_axis_spec_forms():
    assert axis_values("mu", 2.0) == (2.0,)
    assert axis_values("n", [64, 128]) == (64, 128)
    np.testing.assert_allclose(axis_values("beta0", {"linspace": [0.5, 1, 3]}), [0.5, 0.75, 1.0])


def test_scheduler_address_form():
    assert check_scheduler_address("tcp://127.0.0.1:8786") == "tcp://127.0.0.1:8786"
    with pytest.raises(ValueError, match="scheduler"):
        check_scheduler_address("127.0.0.1:8786")


def test_unreachable_scheduler(monkeypatch):
    monkeypatch.setattr(engine, "CONNECT_TIMEOUT", 0.5)
    with pytest.raises(ValueError, match="unreachable"):
        engine.connect("tcp://127.0.0.1:9")  # discard port: nothing listens on loopback


def _cli_fails_before_work(tmp_path, capsys, argv):
    out = tmp_path / "s.nc"
    assert main(["sweep", *argv, "--out", str(out), "--quiet"]) == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith("dhfield: error:") and "\n" not in err and "Traceback" not in err
    assert not out.exists() and not (tmp_path / "s.nc.cases").exists()  # no work started
    return err


@pytest.mark.parametrize("toml, words", [
    ('[axes]\nbeta0 = [0.9]\nmu = [1.0]\n[sweep]\nfoo = 1\n', "sweep.foo"),
    ('[axes]\nbeta0 = [0.9]\nmu = [-1.0]\n', "axes.mu"),
    ('[axes]\nbeta0 = []\nmu = [1.0]\n', "empty"),
    ('[axes\nbeta0 = [0.9]\n', "not valid TOML"),
])
def test_cli_bad_config_file(tmp_path, capsys, toml, words):
    cfg = tmp_path / "bad.toml"
    cfg.write_text(toml)
    assert words in _cli_fails_before_work(tmp_path, capsys, [str(cfg)])


def test_cli_bad_flags(tmp_path, capsys):
    assert "axes.beta0" in _cli_fails_before_work(tmp_path, capsys, ["--beta0", "0", "--mu", "1"])
    assert "linspace" in _cli_fails_before_work(tmp_path, capsys, ["--beta0", "0.9", "--beta0-linspace", "0.5", "1",
                                                                   "3", "--mu", "1"])
    assert "sweep.models" in _cli_fails_before_work(tmp_path, capsys, ["--beta0", "0.9", "--mu", "1",
                                                                       "--models", "hertz"])
    assert "--workers" in _cli_fails_before_work(tmp_path, capsys, ["--beta0", "0.9", "--mu", "1",
                                                                     "--workers", "0"])
    # issue 9 (hostile-input campaign): an absurd worker count overflowed inside dask ("internal error").
    assert "--workers" in _cli_fails_before_work(tmp_path, capsys, ["--beta0", "0.9", "--mu", "1",
                                                                     "--workers", "99999999999"])


def test_cli_unreachable_scheduler(tmp_path, capsys, monkeypatch):
    monkeypatch.setattr(engine, "CONNECT_TIMEOUT", 0.5)
    err = _cli_fails_before_work(tmp_path, capsys, ["--beta0", "0.9", "--mu", "1", "--scheduler",
                                                    "tcp://127.0.0.1:9"])
    assert "unreachable" in err
