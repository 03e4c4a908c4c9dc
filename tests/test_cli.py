"""The CLI: thin, one-line errors with exit status 2, atomic outputs."""
import json
import os
import subprocess
import sys

import numpy as np
import pytest

from dhfield.models import dh_elliptic as model
from dhfield.cli import main
from dhfield.io import read_netcdf

KEYS = ("beta0", "mu", "W_star", "a_star", "c_star", "v", "delta_star", "model")


def test_pulloff_json(capsys):
    # the paper's model through the CLI (the default is md-elliptic since issue 20)
    assert main(["pulloff", "--beta0", "0.9", "--mu", "1", "--model", "dh-elliptic", "--json"]) == 0
    rec = json.loads(capsys.readouterr().out)
    for k in KEYS:
        assert k in rec
    assert rec["W_star"] == pytest.approx(float(model.pull_off(mu=1.0, beta0=0.9).W_star), rel=1e-15)


def test_curve_netcdf_and_csv(tmp_path):
    nc, csv = tmp_path / "c.nc", tmp_path / "c.csv"
    paper = ["--model", "dh-elliptic"]  # compared with dhfield.models.dh_elliptic below
    assert main(["curve", "--beta0", "0.9", "--mu", "1", *paper, "--out", str(nc)]) == 0
    assert main(["curve", "--beta0", "0.9", "--mu", "1", "--n", "7", *paper, "--out", str(csv)]) == 0
    ds = read_netcdf(nc)
    ref = model.load_curve(mu=1.0, beta0=0.9)
    np.testing.assert_array_equal(ds["W_star"].values, ref.W_star)
    assert ds["W_star"].attrs["units"] == "1" and "Eq. 34" in ds["W_star"].attrs["long_name"]
    assert ds.attrs["param_mu"] == 1.0 and "10.1007/s11249-017-0976-8" in ds.attrs["references"]
    rows = [ln for ln in csv.read_text().splitlines() if not ln.startswith("#")]
    assert rows[0].split(",")[0] == "a_star" and len(rows) == 8


@pytest.mark.parametrize("argv, word", [
    (["pulloff", "--beta0", "1.5", "--mu", "1"], "beta0"),
    (["pulloff", "--beta0", "0.9", "--mu", "0"], "mu"),
    (["pulloff", "--beta0", "nan", "--mu", "1"], "beta0"),
    (["curve", "--beta0", "0.9", "--mu", "1", "--a-min", "-1"], "a_star"),
    (["curve", "--beta0", "0.9", "--mu", "inf"], "mu"),
    (["curve", "--beta0", "0.9"], "--mu"),
    (["pulloff", "--beta0", "abc", "--mu", "1"], "beta0"),
])
def test_bad_input_exits_2_with_one_line(argv, word, capsys):
    assert main(argv) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and err.startswith("dhfield: error:") and word in err


def test_unwritable_path_leaves_nothing(tmp_path, capsys):
    target = tmp_path / "missing_dir" / "c.nc"
    assert main(["curve", "--beta0", "0.9", "--mu", "1", "--out", str(target)]) == 2
    assert not target.exists()
    ro = tmp_path / "ro"
    ro.mkdir()
    os.chmod(ro, 0o500)
    try:
        if os.access(ro, os.W_OK):  # running as root: permissions are not enforced
            pytest.skip("directory permissions are not enforced for this user (root)")
        assert main(["curve", "--beta0", "0.9", "--mu", "1", "--out", str(ro / "c.nc")]) == 2
        assert list(ro.iterdir()) == []
    finally:
        os.chmod(ro, 0o700)


def test_failed_write_keeps_previous_file(tmp_path, monkeypatch):
    target = tmp_path / "c.nc"
    target.write_bytes(b"previous")
    import dhfield.io

    def boom(*a, **k):
        raise RuntimeError("NetCDF: HDF error")  # what netCDF4 raises when the disk fills up

    monkeypatch.setattr(dhfield.io, "_write_encoded", boom)
    assert main(["curve", "--beta0", "0.9", "--mu", "1", "--out", str(target)]) == 2
    assert target.read_bytes() == b"previous"
    assert [p.name for p in tmp_path.iterdir()] == ["c.nc"]  # no temporary left behind


def test_console_script_no_traceback():
    r = subprocess.run([sys.executable, "-m", "dhfield.cli", "pulloff", "--beta0", "2", "--mu", "1"],
                       capture_output=True, text=True)
    assert r.returncode == 2 and "Traceback" not in r.stderr and len(r.stderr.strip().splitlines()) == 1


def test_netcdf_round_trip_in_fresh_process(tmp_path):
    nc = tmp_path / "c.nc"
    assert main(["curve", "--beta0", "0.8", "--mu", "5", "--n", "11", "--model", "dh-elliptic", "--out", str(nc)]) == 0
    code = ("import sys, json, numpy as np; from dhfield.io import read_netcdf; ds = read_netcdf(sys.argv[1]);"
            "print(json.dumps({'W': ds['W_star'].values.tolist(), 'attrs': {k: str(v) for k, v in ds.attrs.items()}}))")
    r = subprocess.run([sys.executable, "-c", code, str(nc)], capture_output=True, text=True, check=True)
    out = json.loads(r.stdout)
    ref = model.load_curve(mu=5.0, beta0=0.8, n=11)
    assert out["W"] == ref.W_star.tolist()  # bit-identical
    ds = read_netcdf(nc)
    assert out["attrs"] == {k: str(v) for k, v in ds.attrs.items()}


def test_unreadable_file_is_a_clear_error(tmp_path):
    bad = tmp_path / "x.nc"
    bad.write_text("not netcdf")
    with pytest.raises(ValueError, match="not a readable netCDF"):
        read_netcdf(bad)


def test_periphery_subcommand(tmp_path, capsys):
    from dhfield.models.dh_elliptic_adhesion import work_of_adhesion

    nc = tmp_path / "p.nc"
    assert main(["periphery", "--beta0", "0.85", "--mu", "3", "--n-theta", "3", "--json"]) == 0
    rec = json.loads(capsys.readouterr().out)
    p = model.pull_off(mu=3.0, beta0=0.85)
    assert rec["W_star"] == pytest.approx(float(p.W_star), rel=1e-12)
    # Delta gamma on each ray from the independent Eq. (31) routine; 1 on the major axis.
    ref = work_of_adhesion(float(p.a_star), float(p.c_star), 0.85, float(p.v), np.array(rec["rays"]["theta"]))
    np.testing.assert_allclose(rec["rays"]["work_of_adhesion"], ref, rtol=1e-11)
    assert rec["rays"]["work_of_adhesion"][0] == pytest.approx(1.0, rel=1e-11)
    # issue 18 item 14: a units entry like pulloff/curve/compare/solve (paper's units; theta in rad)
    assert rec["units"]["W_star"] == "1" and rec["units"]["theta"] == "rad"
    assert set(rec["rays"]) <= set(rec["units"])
    assert main(["periphery", "--beta0", "0.85", "--mu", "3", "--out", str(nc)]) == 0
    assert read_netcdf(nc)["work_ratio"].shape == (1, 1)
    assert main(["periphery", "--beta0", "0.85", "--mu", "3", "--n-theta", "1"]) == 2


def test_closed_pipe_is_quiet():
    """Issue 17: `dhfield curve ... | head` printed "dhfield: error: [Errno 32] Broken pipe".
    The run now ends quietly with 141 (128 + SIGPIPE), like a command SIGPIPE ended."""
    import os
    import subprocess
    import sys

    from dhfield.cli import EXIT_BROKEN_PIPE

    env = {**os.environ, "PYTHONPATH": os.pathsep.join(sys.path)}
    proc = subprocess.Popen([sys.executable, "-m", "dhfield.cli", "curve", "--beta0", "0.9", "--mu", "1",
                             "--n", "20000"], stdout=subprocess.PIPE, stderr=subprocess.PIPE, env=env)
    proc.stdout.readline()
    proc.stdout.close()          # the reader goes away, as `head -1` does
    err = proc.stderr.read().decode()
    assert proc.wait(timeout=120) == EXIT_BROKEN_PIPE
    assert "Broken pipe" not in err and "Traceback" not in err and "Exception ignored" not in err
