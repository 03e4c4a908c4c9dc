"""Atomic writes under signals and failures (issue 9, items 3, 4, 6, 9).

The signal tests run a child Python and send it a real signal while it writes
(or computes), then check that it ended promptly, removed its temporary file
and left no output.
"""
from __future__ import annotations

import os
import signal
import stat
import subprocess
import sys
import textwrap
import time
from pathlib import Path

import numpy as np
import pytest

from dhfield import io as dio

#: Seconds a child may take to import dhfield and build its data on a loaded 2-core machine.
START_TIMEOUT = 120
#: Seconds an interrupted child may take to stop: one 16 MiB slab and the cleanup take well under 1 s;
#: the old code never stopped (deadlock on xarray's lock), so any finite bound separates them.
STOP_TIMEOUT = 20
#: Size of the temporary file at which the child is surely writing data, not only the header [bytes].
WRITING_BYTES = 2 * 2**20

_WRITER = textwrap.dedent("""
    import sys
    import numpy as np
    import xarray as xr
    from dhfield.io import write_netcdf
    n = 1024
    ds = xr.Dataset({f"v{i}": (("x", "y"), np.full((n, n), float(i))) for i in range(8)},
                    coords={"x": np.arange(n) * 1.0, "y": np.arange(n) * 1.0})
    print("ready", flush=True)
    write_netcdf(ds, sys.argv[1])
    print("done", flush=True)
""")


def _default_signals():
    # a child of a non-interactive shell may inherit SIGINT ignored, and one of `nohup` SIGHUP
    # ignored (dhfield.io rightly keeps an ignored signal ignored): give it the defaults
    signal.signal(signal.SIGINT, signal.SIG_DFL)
    signal.signal(signal.SIGHUP, signal.SIG_DFL)


def _wait_for(predicate, timeout, proc):
    t0 = time.monotonic()
    while not predicate():
        if proc.poll() is not None or time.monotonic() - t0 > timeout:
            return False
        time.sleep(0.01)
    return True


def _parts(d: Path):
    return sorted(p.name for p in d.iterdir() if p.name.endswith(".part"))


@pytest.mark.parametrize("signame", ["SIGINT", "SIGTERM", "SIGHUP"])
def test_signal_during_netcdf_write_stops_promptly_and_leaves_nothing(tmp_path, signame):
    """Issue 9 item 3: SIGINT hung on xarray's lock; SIGTERM/SIGHUP left the .part behind."""
    target = tmp_path / "t.nc"
    proc = subprocess.Popen([sys.executable, "-c", _WRITER, str(target)], stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True, preexec_fn=_default_signals)
    try:
        assert proc.stdout.readline().strip() == "ready"

        def writing():
            return any(p.stat().st_size > WRITING_BYTES for p in tmp_path.glob(".t.nc.*.part"))

        assert _wait_for(writing, START_TIMEOUT, proc), "the child never started writing"
        proc.send_signal(getattr(signal, signame))
        try:
            out, err = proc.communicate(timeout=STOP_TIMEOUT)
        except subprocess.TimeoutExpired:
            pytest.fail(f"{signame} during the netCDF write: no exit within {STOP_TIMEOUT} s (hang)")
    finally:
        if proc.poll() is None:
            proc.kill()
            proc.communicate()
    assert "done" not in out
    assert proc.returncode == -getattr(signal, signame)  # re-delivered: the default action ended it
    assert _parts(tmp_path) == [] and not target.exists()


def test_sigint_during_computation_is_one_line_and_130(tmp_path):
    """Issue 9 item 6: Ctrl-C during a computation printed a KeyboardInterrupt traceback."""
    target = tmp_path / "f.nc"
    proc = subprocess.Popen([sys.executable, "-m", "dhfield.cli", "field", "--beta0", "0.9", "--mu", "1",
                             "--a-star", "1.2", "--n", "1024", "--out", str(target)],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, preexec_fn=_default_signals,
                            env=dict(os.environ, DHFIELD_CACHE=str(tmp_path / "cache")))
    maps = Path(f"/proc/{proc.pid}/maps")
    try:
        if not maps.parent.exists():
            proc.kill()
            pytest.skip("needs /proc to see when the child is computing")

        def computing():  # the FFT library is loaded inside `field`'s run(), after parsing
            try:
                return "pyfftw" in maps.read_text()
            except OSError:
                return False

        assert _wait_for(computing, START_TIMEOUT, proc), "the child never started computing"
        time.sleep(0.3)
        proc.send_signal(signal.SIGINT)
        out, err = proc.communicate(timeout=STOP_TIMEOUT)
    finally:
        if proc.poll() is None:
            proc.kill()
            proc.communicate()
    assert proc.returncode == 130, err
    lines = err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("dhfield: interrupted"), err
    assert not target.exists() and _parts(tmp_path) == []


_DISK_FULL = textwrap.dedent("""
    import resource, signal, sys
    signal.signal(signal.SIGXFSZ, signal.SIG_IGN)  # writes past the limit fail with EFBIG instead
    resource.setrlimit(resource.RLIMIT_FSIZE, (int(sys.argv[1]), int(sys.argv[1])))
    from dhfield.cli import main
    sys.exit(main(sys.argv[2:]))
""")


def test_disk_full_during_netcdf_write_is_one_line(tmp_path):
    """Issue 9 item 6: a full disk during a netCDF write gave ~50 lines ending `NetCDF: HDF error`.

    The file-size limit (RLIMIT_FSIZE) makes every write past 256 kB fail the way a full disk does.
    """
    target = tmp_path / "f.nc"
    res = subprocess.run([sys.executable, "-c", _DISK_FULL, str(256 * 1024), "field", "--beta0", "0.9", "--mu", "1",
                          "--a-star", "1.2", "--n", "32", "--out", str(target)], capture_output=True, text=True,
                         timeout=START_TIMEOUT, env=dict(os.environ, DHFIELD_CACHE=str(tmp_path / "cache")))
    lines = res.stderr.strip().splitlines()
    assert res.returncode == 2, res.stderr
    assert len(lines) == 1 and lines[0].startswith("dhfield: error: could not write the netCDF file"), res.stderr
    assert not target.exists() and _parts(tmp_path) == []


def test_failed_write_keeps_the_previous_file_and_its_mode(tmp_path):
    target = tmp_path / "c.nc"
    target.write_bytes(b"previous")
    os.chmod(target, 0o640)
    with pytest.raises(RuntimeError, match="boom"):
        with dio.atomic_path(target) as tmp:
            tmp.write_bytes(b"partial")
            raise RuntimeError("boom")
    assert target.read_bytes() == b"previous" and _parts(tmp_path) == []
    with dio.atomic_path(target) as tmp:
        tmp.write_bytes(b"new")
    assert target.read_bytes() == b"new"
    assert stat.S_IMODE(target.stat().st_mode) == 0o640  # the replaced file's mode is kept


def test_new_file_gets_umask_permissions(tmp_path):
    old = os.umask(0o027)
    try:
        with dio.atomic_path(tmp_path / "n.csv") as tmp:
            tmp.write_text("x")
    finally:
        os.umask(old)
    assert stat.S_IMODE((tmp_path / "n.csv").stat().st_mode) == 0o640


def test_longest_file_name_can_be_written(tmp_path):
    """Issue 9 item 9: names of 241-255 bytes failed because the temporary name was longer."""
    name_max = os.pathconf(tmp_path, "PC_NAME_MAX")
    target = tmp_path / ("a" * (name_max - 3) + ".nc")
    with dio.atomic_path(target) as tmp:
        assert len(tmp.name) <= 58   # .<32 characters>.<pid>-<8 characters>.part
        tmp.write_bytes(b"ok")
    assert target.read_bytes() == b"ok"
    with pytest.raises(ValueError, match=f"at most {name_max} bytes"):
        dio.validate_output_path(tmp_path / ("a" * (name_max - 2) + ".nc"))


def test_netcdf_round_trip_of_the_writer(tmp_path, rng):
    """The netCDF4 writer keeps values, dtypes, attributes, strings and booleans."""
    import xarray as xr

    ds = xr.Dataset(
        {"p": (("x", "y"), rng.random((40, 3)), {"units": "Pa", "long_name": "pressure"}),
         "flag": (("x",), (np.arange(40) % 3).astype(np.int8), {"flag_values": np.array([0, 1, 2], np.int8),
                                                              "flag_meanings": "a b c"}),
         "ok": (("y",), np.array([True, False, True])),
         "label": (("m",), np.array(["dh-elliptic", "jkr"])),
         "scalar": ((), 2.5)},
        coords={"x": ("x", np.linspace(0, 1, 40), {"units": "m"}), "y": np.arange(3.0), "m": ["a", "b"]},
        attrs={"title": "t", "param_n": 3, "param_flag": 1, "vector": np.array([1.0, 2.0])})
    ds["p"][0, 0] = np.nan
    path = dio.write_netcdf(ds, tmp_path / "r.nc")
    back = dio.read_netcdf(path)
    # dimensions in the canonical order of dhfield.core.schema.DIM_ORDER (y before x: rows y, columns x)
    assert back["p"].dims == ("y", "x")
    np.testing.assert_array_equal(back["p"].transpose("x", "y").values, ds["p"].values)  # NaN in the same place
    np.testing.assert_array_equal(back["flag"].values, ds["flag"].values)
    assert back["flag"].dtype == np.int8 and back["ok"].dtype == bool
    assert list(back["label"].values) == ["dh-elliptic", "jkr"] and float(back["scalar"]) == 2.5
    assert back["p"].attrs["units"] == "Pa" and back.attrs["param_n"] == 3
    np.testing.assert_array_equal(back.attrs["vector"], [1.0, 2.0])
    import netCDF4

    with netCDF4.Dataset(path) as nc:
        for coord in ("x", "y"):
            assert "_FillValue" not in nc[coord].ncattrs()  # CF: coordinates have no missing values


def test_unreadable_input_is_one_line_value_error(tmp_path):
    bad = tmp_path / "bad.nc"
    bad.write_bytes(b"not netcdf\n" * 10)
    for path, word in ((bad, "not a readable netCDF file"), (tmp_path / "missing.nc", "does not exist"),
                       (tmp_path, "not a file")):
        with pytest.raises(ValueError, match=word) as info:
            dio.read_netcdf(path)
        assert "\n" not in str(info.value)


def test_full_disk_message_gives_real_sizes(tmp_path, monkeypatch):
    """Issue 18 item 14: a full disk said "needs about 0.0 MiB and the device has 0.0 MiB free"."""
    import collections
    import shutil

    import numpy as np
    import xarray as xr

    usage = collections.namedtuple("usage", "total used free")
    monkeypatch.setattr(shutil, "disk_usage", lambda p: usage(10**9, 10**9 - 100, 100))
    ds = xr.Dataset({"v": ("x", np.zeros(64))})  # 512 bytes of data
    with pytest.raises(OSError) as err:
        dio.write_netcdf(ds, tmp_path / "x.nc")
    msg = str(err.value)
    assert "512 B" in msg and "100 B free" in msg and "0.0 MiB" not in msg
    assert not (tmp_path / "x.nc").exists()


def test_non_utf8_netcdf_name_is_refused_in_one_line(tmp_path):
    """Issue 18 item 14: a non-UTF-8 --out gave "'utf-8' codec can't encode character" after computing."""
    import os

    bad = os.fsdecode(os.fsencode(str(tmp_path)) + b"/\xff.nc")
    with pytest.raises(ValueError, match="UTF-8"):
        dio.validate_output_path(bad, (".nc",))
    dio.validate_output_path(os.fsdecode(os.fsencode(str(tmp_path)) + b"/\xff.csv"), (".csv",))  # CSV is fine


def test_git_commit_names_the_checkout():
    """One provenance helper (dhfield.io.git_commit) for the report, the study and the library: a
    hash of the requested length, marked when tracked files differ from it; never raises."""
    import re

    from dhfield.io import git_commit

    full, short = git_commit(), git_commit(short=12, paths=("dhfield/bem",))
    if full == "unavailable":  # not a git checkout (an installed copy)
        pytest.skip("not run from a git checkout")
    assert re.fullmatch(r"[0-9a-f]{40}( \(uncommitted changes\))?", full)
    assert re.fullmatch(r"[0-9a-f]{12}( \(uncommitted changes in dhfield/bem\))?", short)
    assert full.startswith(short[:12])


# --------------------------------------------------------------------------- issue 42: files written as a set, stale parts
def test_csv_and_its_sidecar_are_committed_together_under_sigint(tmp_path, monkeypatch, default_sigint):
    """Issue 42 finding 9: Ctrl-C right after X.csv.json was renamed left the new sidecar beside the old CSV."""
    from dhfield.io.table import write_table

    target = tmp_path / "x.csv"
    write_table({"a_star": [1.0]}, target, title="old")
    old = (target.read_bytes(), (tmp_path / "x.csv.json").read_bytes())
    real_replace = os.replace
    calls = []

    def replace_then_sigint(src, dst):   # the signal lands between the two renames
        real_replace(src, dst)
        calls.append(dst)
        if len(calls) == 1:
            os.kill(os.getpid(), signal.SIGINT)

    monkeypatch.setattr(dio.os, "replace", replace_then_sigint)
    with pytest.raises(KeyboardInterrupt):
        write_table({"a_star": [2.0]}, target, title="new")
    monkeypatch.undo()
    new = (target.read_bytes(), (tmp_path / "x.csv.json").read_bytes())
    assert new[0] != old[0] and new[1] != old[1], "both files new (the interrupt waited for the set)"
    assert b'"new"' in new[1] and _parts(tmp_path) == []


def test_a_set_interrupted_before_its_commit_keeps_every_old_file(tmp_path):
    """Issue 42 finding 9: files written together are moved into place together, or not at all."""
    (tmp_path / "a.nc").write_bytes(b"old a")
    (tmp_path / "b.png").write_bytes(b"old b")
    before = len(dio.written_files())
    with pytest.raises(KeyboardInterrupt):
        with dio.atomic_files():
            with dio.atomic_path(tmp_path / "a.nc") as tmp:
                tmp.write_bytes(b"new a")
            raise KeyboardInterrupt   # e.g. Ctrl-C while the figure is drawn
    assert (tmp_path / "a.nc").read_bytes() == b"old a" and (tmp_path / "b.png").read_bytes() == b"old b"
    assert _parts(tmp_path) == [] and len(dio.written_files()) == before


def test_stale_part_of_a_killed_writer_is_removed_by_the_next_write(tmp_path):
    """Issue 42 finding 10: hidden .part files of a SIGKILLed writer were never cleaned up."""
    proc = subprocess.Popen([sys.executable, "-c", textwrap.dedent("""
        import os, sys, time
        from dhfield.io import atomic_path
        with atomic_path(sys.argv[1]) as tmp:
            tmp.write_bytes(b"partial")
            print("writing", flush=True)
            time.sleep(600)
    """), str(tmp_path / "t.nc")], stdout=subprocess.PIPE, text=True)
    try:
        assert proc.stdout.readline().strip() == "writing"
        assert len(_parts(tmp_path)) == 1
        live = tmp_path / _parts(tmp_path)[0]
        with dio.atomic_path(tmp_path / "t.nc") as tmp:   # the writer still runs: its file is kept
            tmp.write_bytes(b"first")
        assert live.exists()
    finally:
        proc.kill()
        proc.wait()
    with dio.atomic_path(tmp_path / "t.nc") as tmp:      # it was killed: its file goes
        tmp.write_bytes(b"second")
    assert _parts(tmp_path) == [] and (tmp_path / "t.nc").read_bytes() == b"second"


def test_new_csv_does_not_overwrite_an_existing_sidecar(tmp_path):
    """Issue 42 finding 10: ``--out X.csv`` silently replaced an X.csv.json of another table."""
    from dhfield.io.table import write_table

    side = tmp_path / "x.csv.json"
    side.write_text('{"columns": {}}\n')
    with pytest.raises(ValueError, match="does not exist but its JSON sidecar"):
        write_table({"a_star": [1.0]}, tmp_path / "x.csv", title="t")
    assert side.read_text() == '{"columns": {}}\n' and not (tmp_path / "x.csv").exists()
    (tmp_path / "x.csv").write_text("a_star\n0\n")   # with its CSV it is replaced, as the CSV is
    write_table({"a_star": [1.0]}, tmp_path / "x.csv", title="t")
    assert '"a_star"' in side.read_text()
