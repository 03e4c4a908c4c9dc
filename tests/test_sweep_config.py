"""Sweep configuration: TOML and flag forms, and every bad input rejected before work starts."""
from __future__ import annotations

import types

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

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


# --- issue 18, items 7, 8, 9, 13, 14: TOML values, scheduler peers ------------------------------------
_AXES = '[axes]\nbeta0 = [0.9]\nmu = [1.0]\n'


def _deep(depth):
    return _AXES + "[run]\nout = " + "[" * depth + "]" * depth + "\n"


@pytest.mark.parametrize("toml, words", [
    (_AXES + '[run]\nout = ""\n', "run.out"),               # item 7: wrote sweep.nc and cases/ into the cwd
    (_AXES + '[run]\nout = "  "\n', "run.out"),
    (_AXES + '[run]\nworkers = 99999\n', "run.workers"),     # item 9: spawned the workers, --workers is refused
    (_deep(5000), "too deeply"),                              # item 13: internal error RecursionError
    ('[axes]\nbeta0 = [0.9]\nmu = {linspace = [0.1, 1, 1e300]}\n', "num"),   # item 14: numpy's size error
    ('[axes]\nbeta0 = [0.9]\nmu = {linspace = [0.1, 1, inf]}\n', "num"),
    ('[axes]\nbeta0 = [0.9]\nmu = {linspace = [0.1, 1, nan]}\n', "num"),
    (_AXES + '[run]\nscheduler = "tls://127.0.0.1:8786"\n', "tls://"),
])
def test_cli_bad_toml_values(tmp_path, capsys, toml, words, monkeypatch):
    monkeypatch.chdir(tmp_path)
    cfg = tmp_path / "bad.toml"
    cfg.write_text(toml)
    assert words in _cli_fails_before_work(tmp_path, capsys, [str(cfg)])
    assert main(["sweep", str(cfg), "--quiet"]) == 2           # without --out: run.out is the output
    err = capsys.readouterr().err.strip()
    assert words in err and "\n" not in err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["bad.toml"]   # nothing written in the cwd


def test_toml_workers_bound_equals_the_cli_bound():
    from dhfield.sweep.config import max_workers

    config_from_mapping({**GOOD, "run": {"workers": max_workers()}})
    with pytest.raises(ValueError, match=f"1..{max_workers()}"):
        config_from_mapping({**GOOD, "run": {"workers": max_workers() + 1}})


def test_toml_with_a_byte_order_mark_is_read(tmp_path):
    """Item 14: a UTF-8 BOM (Notepad writes one) gave "Invalid statement"."""
    cfg = tmp_path / "bom.toml"
    cfg.write_bytes(b"\xef\xbb\xbf" + _AXES.encode())
    assert load_config(cfg).axes["mu"] == (1.0,)
    cfg.write_bytes(b"\xff\xfe" + _AXES.encode("utf-16-le"))
    with pytest.raises(ValueError, match="UTF-8"):
        load_config(cfg)


@pytest.mark.parametrize("address", ["tls://127.0.0.1:8786", "ucx://127.0.0.1:8786", "ws://127.0.0.1:8786",
                                     "wss://h:1", "inproc://x", "tcp://127.0.0.1:99999", "tcp://a b:1"])
def test_unsupported_scheduler_addresses_are_one_line(tmp_path, capsys, address):
    """Item 13: tls/ucx/ws gave internal errors, inproc://x 'not enough values to unpack'."""
    err = _cli_fails_before_work(tmp_path, capsys, ["--beta0", "0.9", "--mu", "1", "--scheduler", address])
    assert "scheduler" in err


def _peer(behaviour):
    """A listener on 127.0.0.1 that behaves like a non-scheduler; returns (address, stop)."""
    import socket
    import threading

    srv = socket.socket()
    srv.bind(("127.0.0.1", 0))
    srv.listen(4)
    stop = threading.Event()
    conns = []

    def serve():
        srv.settimeout(0.1)
        while not stop.is_set():
            try:
                c, _ = srv.accept()
            except OSError:
                continue
            conns.append(c)
            if behaviour == "garbage":
                c.sendall(b"\xff" * 64)          # announces 2^64 - 1 bytes
            elif behaviour == "close":
                c.close()
            # "silent" and "http" (an HTTP server waits for a request) send nothing

    t = threading.Thread(target=serve, daemon=True)
    t.start()

    def close():
        stop.set()
        t.join()
        for c in conns:
            c.close()
        srv.close()

    return f"tcp://127.0.0.1:{srv.getsockname()[1]}", close


@pytest.mark.parametrize("behaviour, words", [("silent", "no dask handshake within"),
                                              ("garbage", "is not a dask scheduler"),
                                              ("close", "closed the connection")])
def test_scheduler_peer_that_is_not_one_fails_in_time(tmp_path, capsys, monkeypatch, behaviour, words):
    """Item 8: a silent listener or an HTTP server kept `sweep --scheduler` waiting past 120 s;
    a garbage peer made it allocate 6.46 EiB.  Now: one line within CONNECT_TIMEOUT."""
    import time

    monkeypatch.setattr(engine, "CONNECT_TIMEOUT", 0.5)
    address, close = _peer(behaviour)
    try:
        t0 = time.monotonic()
        err = _cli_fails_before_work(tmp_path, capsys, ["--beta0", "0.9", "--mu", "1", "--workers", "1",
                                                        "--scheduler", address])
        assert time.monotonic() - t0 < 10  # a hang guard, not a timing test
    finally:
        close()
    assert words in err and address in err


# --- [bem] max_seconds / --max-seconds: the time allowed per adhesive case (issue 20) ------------------------
_ADHESIVE_TOML = '[sweep]\nquantities = ["adhesive"]\n[axes]\nbeta0 = [0.5]\nmu = [10.0]\ngrid_level = [1, 2]\n'


def test_max_seconds_from_toml(tmp_path):
    """Parsed as a float [s]; absent: None (the library's default); round-trips; not in the fingerprint
    (it decides only whether a case is refused, so a rerun with more time resumes the same store)."""
    path = tmp_path / "t.toml"
    path.write_text(_ADHESIVE_TOML + "[bem]\nmax_seconds = 3600\n")
    cfg = load_config(path)
    assert cfg.max_seconds == 3600.0 and type(cfg.max_seconds) is float
    assert config_from_mapping(cfg.as_dict()) == cfg
    path.write_text(_ADHESIVE_TOML)
    default = load_config(path)
    assert default.max_seconds is None and "max_seconds" not in default.as_dict()["bem"]
    assert default.fingerprint() == cfg.fingerprint()


@pytest.mark.parametrize("value", [0, 0.0, -1, -3600.0, float("nan"), float("inf"), "3600", "1h", True, [3600]])
def test_bad_max_seconds_names_the_key(value):
    mapping = {"axes": {"beta0": [0.5], "mu": [10.0], "grid_level": [2]}, "sweep": {"quantities": ["adhesive"]},
               "bem": {"max_seconds": value}}
    with pytest.raises(ValueError, match=r"bem\.max_seconds must be a finite number > 0") as exc:
        config_from_mapping(mapping)
    assert "\n" not in str(exc.value)


@pytest.mark.parametrize("toml", ["max_seconds = 0\n", "max_seconds = -5\n", "max_seconds = nan\n",
                                  'max_seconds = "long"\n'])
def test_cli_bad_max_seconds_in_toml(tmp_path, capsys, toml):
    cfg = tmp_path / "bad.toml"
    cfg.write_text(_ADHESIVE_TOML + "[bem]\n" + toml)
    msg = _cli_fails_before_work(tmp_path, capsys, [str(cfg)])
    assert "bem.max_seconds" in msg and "--max-seconds" not in msg      # typed in the file, not as a flag


def test_cli_bad_max_seconds_flag(tmp_path, capsys):
    axes = ["--beta0", "0.5", "--mu", "10", "--grid-level", "2", "--quantities", "adhesive"]
    for value in ("0", "-1", "nan", "inf"):
        assert "--max-seconds (bem.max_seconds) must be" in _cli_fails_before_work(tmp_path, capsys,
                                                                                   [*axes, "--max-seconds", value])
    assert "--max-seconds" in _cli_fails_before_work(tmp_path, capsys, [*axes, "--max-seconds", "1h"])
    cfg = tmp_path / "t.toml"
    cfg.write_text(_ADHESIVE_TOML)
    assert "--max-seconds (bem.max_seconds) must be" in _cli_fails_before_work(tmp_path, capsys,
                                                                               [str(cfg), "--max-seconds", "0"])


def test_cli_max_seconds_flag_reaches_the_config(tmp_path, monkeypatch):
    """The flag form sets [bem] max_seconds; with a config file it overrides the file's (the only [bem] key that
    may: the others change results); another flag of the config's tables is still refused."""
    import dhfield.sweep as sweep_pkg

    seen = []

    def fake_run_sweep(config, **kw):
        seen.append(config)
        return types.SimpleNamespace(path=kw["out"], computed=[], reused=[], failed=[], flagged=[], warned=0)

    monkeypatch.setattr(sweep_pkg, "run_sweep", fake_run_sweep)
    axes = ["--beta0", "0.5", "--mu", "10", "--grid-level", "1", "2", "--quantities", "adhesive"]
    out = str(tmp_path / "s.nc")
    assert main(["sweep", *axes, "--max-seconds", "3600", "--out", out, "--quiet"]) == 0
    assert seen[-1].max_seconds == 3600.0 and seen[-1].axes["grid_level"] == (1, 2)
    assert main(["sweep", *axes, "--out", out, "--quiet"]) == 0
    assert seen[-1].max_seconds is None
    cfg = tmp_path / "t.toml"
    cfg.write_text(_ADHESIVE_TOML + "[bem]\nmax_seconds = 600\n")
    assert main(["sweep", str(cfg), "--out", out, "--quiet"]) == 0
    assert seen[-1].max_seconds == 600.0
    assert main(["sweep", str(cfg), "--max-seconds", "5400", "--out", out, "--quiet"]) == 0
    assert seen[-1].max_seconds == 5400.0 and seen[-1].fingerprint() == seen[-2].fingerprint()
    assert main(["sweep", str(cfg), "--half-width", "3", "--out", out, "--quiet"]) == 2
    assert len(seen) == 4


@settings(max_examples=60, deadline=None)
@given(st.one_of(st.integers(-10**6, 10**6), st.floats(allow_nan=True, allow_infinity=True), st.booleans(),
                 st.text(max_size=5), st.none()))
def test_max_seconds_domain(value):
    """Accepted iff a finite number > 0 (None: the library's default); anything else one line naming the key."""
    mapping = {"axes": {"beta0": [0.5], "mu": [1.0], "grid_level": [1]}, "sweep": {"quantities": ["adhesive"]},
               "bem": {"max_seconds": value}}
    ok = value is None or (not isinstance(value, (bool, str)) and np.isfinite(value) and value > 0)
    if ok:
        assert config_from_mapping(mapping).max_seconds == (None if value is None else float(value))
    else:
        with pytest.raises(ValueError, match=r"bem\.max_seconds") as exc:
            config_from_mapping(mapping)
        assert "\n" not in str(exc.value)


@pytest.mark.parametrize("flags, named", [
    (["--mu", "1", "--half-width", "-1"], "--half-width (bem.half_width) must be"),
    (["--mu", "1", "--beta0", "2"], "--beta0 (axes.beta0) must be"),
    (["--mu-geomspace", "-1", "10", "5"], "--mu-geomspace (axes.mu.geomspace) start/stop"),
])
def test_cli_error_names_the_flag_that_was_typed(tmp_path, capsys, flags, named):
    """A bad value given as a flag is named by the flag, then by its config key."""
    axes = ["--beta0", "0.5", "--grid-level", "1", "--quantities", "adhesive"]
    assert named in _cli_fails_before_work(tmp_path, capsys, [*axes, *flags])


# --- [bem] widest_edge and base_lattice: removed (2026-12-02) with the path routes' rescue layers ---------------
@pytest.mark.parametrize("key, value", [("widest_edge", True), ("widest_edge", False), ("base_lattice", 1),
                                        ("base_lattice", 0)])
def test_removed_bem_keys_are_refused_with_the_reason(key, value):
    mapping = {"axes": {"beta0": [0.5], "mu": [10.0], "grid_level": [2]}, "sweep": {"quantities": ["adhesive"]},
               "bem": {key: value}}
    with pytest.raises(ValueError, match=rf"config key 'bem\.{key}' was removed on 2026-12-02 .*delete the key"):
        config_from_mapping(mapping)


def test_removed_bem_key_exits_2_with_one_line(tmp_path, capsys):
    from dhfield.cli import main

    path = tmp_path / "old.toml"
    path.write_text(_ADHESIVE_TOML + "[bem]\nbase_lattice = 1\n")
    assert main(["sweep", str(path), "--out", str(tmp_path / "o.nc"), "--quiet"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "bem.base_lattice" in err[0] and "removed" in err[0], err


def test_adhesive_sweeps_name_their_route_in_the_fingerprint():
    """A store of the path routes' answers (before the Newton route was the default) is not resumed."""
    from dhfield.sweep.config import ADHESIVE_ROUTE

    adhesive = config_from_mapping({"axes": {"beta0": [0.5], "mu": [1.0], "grid_level": [1]},
                                    "sweep": {"quantities": ["adhesive"]}})
    payload = {"axes": {k: list(v) for k, v in adhesive.axes.items()}, "quantities": ["adhesive"],
               "models": list(adhesive.models), "control": "load", "chunk_points": adhesive.chunk_points,
               "half_width": None, "sampling": "average"}
    import hashlib
    import json

    before = hashlib.sha256(json.dumps(payload, sort_keys=True).encode()).hexdigest()[:16]   # the old rule
    assert adhesive.fingerprint() != before and ADHESIVE_ROUTE == "newton"
    payload["adhesive_route"] = ADHESIVE_ROUTE
    assert adhesive.fingerprint() == hashlib.sha256(json.dumps(payload, sort_keys=True).encode()).hexdigest()[:16]


def test_config_imports_nothing_from_tasks():
    """The imports between the sweep's config and tasks go one way (tasks -> config): no cycle."""
    import ast
    import inspect

    from dhfield.sweep import config as config_module

    tree = ast.parse(inspect.getsource(config_module))
    imported = {node.module for node in ast.walk(tree) if isinstance(node, ast.ImportFrom) and node.level == 1}
    assert "tasks" not in imported, "dhfield.sweep.config imports from .tasks: the config <-> tasks cycle is back"
    assert config_module.cohesive_laws()[0] == config_module.cohesive_default()
