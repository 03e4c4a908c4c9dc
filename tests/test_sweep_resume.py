"""A sweep SIGKILLed midway resumes: complete, identical, and no finished case recomputed."""
from __future__ import annotations

import os
import signal
import subprocess
import sys
import time

import numpy as np

from dhfield.sweep import config_from_mapping, load_config, run_sweep
from dhfield.sweep.store import output_paths

#: Forward BEM cases of one (beta0, mu) state family on one fixed grid: one load path,
#: so one task that writes each case as it finishes (N = 128: ~0.1 s a case).
CONFIG = """\
[sweep]
quantities = ["bem_field"]
[axes]
beta0 = [0.8]
mu = [1.0]
a_star = [0.6, 0.7, 0.8, 0.9, 1.0, 1.1, 1.2, 1.3, 1.4, 1.5, 1.6, 1.7, 1.8, 1.9]
n = [128]
[bem]
half_width = 4.0
"""
#: Seconds to wait for the first finished cases of the sweep being killed (interpreter
#: start-up included, on a loaded 2-core machine).
START_TIMEOUT = 120.0
#: Finished cases before the kill: enough to show they are reused.
KILL_AFTER = 3


def _finished(store_dir):
    return {p.name: (p.stat().st_ino, p.stat().st_mtime_ns)
            for p in store_dir.glob("bem_field__*.nc") if not p.name.endswith(".failed.nc")}


def test_kill_and_resume(tmp_path):
    cfg_path = tmp_path / "s.toml"
    cfg_path.write_text(CONFIG)
    out = tmp_path / "killed.nc"
    final, store_dir = output_paths(out)
    cmd = [sys.executable, "-c", "import sys; from dhfield.cli import main; sys.exit(main(sys.argv[1:]))",
           "sweep", str(cfg_path), "--workers", "1", "--quiet", "--out", str(out)]
    proc = subprocess.Popen(cmd, start_new_session=True, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    try:
        deadline = time.monotonic() + START_TIMEOUT
        while len(_finished(store_dir)) < KILL_AFTER:
            assert proc.poll() is None, proc.stderr.read().decode()
            assert time.monotonic() < deadline, "the sweep did not start in time"
            time.sleep(0.01)
        os.killpg(proc.pid, signal.SIGKILL)  # the whole process group, workers included
    finally:
        proc.wait(timeout=30)
    assert proc.returncode == -signal.SIGKILL
    done = _finished(store_dir)
    n_cases = len(load_config(cfg_path).axes["a_star"])
    assert KILL_AFTER <= len(done) < n_cases, "the sweep must be killed midway"
    assert not final.exists()
    # A case being written at the kill survives at most as a hidden temporary (.<name>.*.part,
    # dhfield.io.atomic_path), never as <key>.nc, so it is not taken for a finished case.

    resumed = run_sweep(load_config(cfg_path), out=out, scheduler="synchronous", progress=False)
    assert sorted(f"{k}.nc" for k in resumed.reused) == sorted(done)
    assert len(resumed.computed) == n_cases - len(done)
    for name, stamp in done.items():  # finished cases were read, not rewritten
        p = store_dir / name
        assert (p.stat().st_ino, p.stat().st_mtime_ns) == stamp

    whole = run_sweep(config_from_mapping(load_config(cfg_path).as_dict()), out=tmp_path / "whole.nc",
                      scheduler="synchronous", progress=False)
    a, b = resumed.dataset, whole.dataset
    assert (a["bem_field_status"].values == 0).all()
    for k in a.data_vars:
        if a[k].dtype.kind == "f":
            np.testing.assert_array_equal(a[k].values, b[k].values, err_msg=k)
    # The file on disk is the consolidated, complete sweep.
    from dhfield.io import read_netcdf

    on_disk = read_netcdf(final)
    np.testing.assert_array_equal(on_disk["bem_displacement_error"].values, a["bem_displacement_error"].values)


def test_rerun_of_a_finished_sweep_computes_nothing(tmp_path):
    cfg = config_from_mapping({"axes": {"beta0": [0.7, 1.0], "mu": [0.5, 2.0]},
                               "sweep": {"models": ["md", "jkr-elliptic"], "chunk_points": 2}})
    first = run_sweep(cfg, out=tmp_path / "r.nc", scheduler="synchronous", progress=False)
    second = run_sweep(cfg, out=tmp_path / "r.nc", scheduler="synchronous", progress=False)
    assert second.computed == [] and second.reused == first.computed
    np.testing.assert_array_equal(first.dataset["W_star"].values, second.dataset["W_star"].values)


def test_store_of_another_config_is_refused(tmp_path):
    import pytest

    cfg = config_from_mapping({"axes": {"beta0": [1.0], "mu": [1.0]}, "sweep": {"models": ["jkr"]}})
    run_sweep(cfg, out=tmp_path / "x.nc", scheduler="synchronous", progress=False)
    other = config_from_mapping({"axes": {"beta0": [0.9], "mu": [1.0]}, "sweep": {"models": ["jkr"]}})
    with pytest.raises(ValueError, match="different sweep config"):
        run_sweep(other, out=tmp_path / "x.nc", scheduler="synchronous", progress=False)


# --------------------------------------------------------------------------- issue 42: stores that cannot mix configs
def _md_sweep(tmp_path, mu, out="x.nc", **run):
    cfg = config_from_mapping({"axes": {"beta0": [0.9, 1.0], "mu": list(mu)}, "sweep": {"models": ["md"]}})
    return run_sweep(cfg, out=tmp_path / out, scheduler="synchronous", progress=False, **run)


def _md_values(beta0, mu):
    """Maugis-Dugdale W* computed directly (not through a sweep) at every (beta0, mu)."""
    import warnings

    from dhfield.analysis.compare import pull_off

    with warnings.catch_warnings():   # beta0 = 0.9 is outside md's validated range: the same value all the same
        warnings.simplefilter("ignore")
        return np.array([[float(pull_off("md", beta0=b, mu=m).W_star) for m in mu] for b in beta0])


def test_store_without_manifest_does_not_lend_its_cases_to_another_config(tmp_path):
    """Issue 42 finding 1: with manifest.json deleted, the mu = 5, 10 sweep reused the mu = 0.5, 1 case."""
    import pytest

    _md_sweep(tmp_path, [0.5, 1.0])
    (tmp_path / "x.nc.cases" / "manifest.json").unlink()
    with pytest.raises(ValueError, match="has no manifest.json and holds case files .1 of another sweep config"):
        _md_sweep(tmp_path, [5.0, 10.0])
    # the same config finds its own cases again (their fingerprint and coordinates match)
    again = _md_sweep(tmp_path, [0.5, 1.0])
    assert again.computed == [] and len(again.reused) == 1
    np.testing.assert_allclose(again.dataset["W_star"].sel(model="md").values, _md_values([0.9, 1.0], [0.5, 1.0]),
                               rtol=1e-12)


def test_a_case_file_of_another_config_is_computed_again(tmp_path):
    """Issue 42 finding 1: a case is reused only if its fingerprint and coordinates match, not by its key."""
    import shutil

    _md_sweep(tmp_path, [0.5, 1.0], out="a.nc")
    _md_sweep(tmp_path, [5.0, 10.0], out="b.nc")
    (key,) = [p.name for p in (tmp_path / "b.nc.cases").glob("pull_off__*.nc")]
    shutil.copyfile(tmp_path / "a.nc.cases" / key, tmp_path / "b.nc.cases" / key)   # the same key, the wrong case
    res = _md_sweep(tmp_path, [5.0, 10.0], out="b.nc")
    assert res.computed == [key[:-3]] and res.reused == []
    np.testing.assert_allclose(res.dataset["W_star"].sel(model="md").values, _md_values([0.9, 1.0], [5.0, 10.0]),
                               rtol=1e-12)


def test_a_case_store_that_is_a_symbolic_link_is_refused(tmp_path):
    """Issue 42 finding 10: the case store was written through a symbolic link."""
    import pytest

    real = tmp_path / "real"
    real.mkdir()
    (tmp_path / "x.nc.cases").symlink_to(real)
    with pytest.raises(ValueError, match="case store must not be a symbolic link"):
        _md_sweep(tmp_path, [1.0])
    (tmp_path / "d").symlink_to(real)
    with pytest.raises(ValueError, match="must not be a symbolic link"):
        _md_sweep(tmp_path, [1.0], out="d")
    assert list(real.iterdir()) == [] and not (tmp_path / "x.nc").exists()


def test_out_with_another_suffix_is_refused_not_made_a_directory(tmp_path):
    """Issue 42 finding 10: ``sweep --out x.txt`` silently created a directory."""
    from dhfield.cli import main

    assert main(["sweep", "--beta0", "1", "--mu", "1", "--models", "md", "--workers", "1", "--quiet",
                 "--out", str(tmp_path / "x.txt")]) == 2
    assert not (tmp_path / "x.txt").exists()
    (tmp_path / "runs.d").mkdir()   # an existing directory is an output directory whatever its name
    assert main(["sweep", "--beta0", "1", "--mu", "1", "--models", "md", "--workers", "1", "--quiet",
                 "--out", str(tmp_path / "runs.d")]) == 0
    assert (tmp_path / "runs.d" / "sweep.nc").is_file()


def test_interrupted_sweep_says_how_many_cases_are_stored(tmp_path, monkeypatch, capsys):
    """Issue 42 finding 9: an interrupted sweep said "no output was written" after storing resumable cases."""
    from dhfield.cli import main
    from dhfield.sweep import engine

    def interrupted(*args, **kwargs):   # Ctrl-C once every case is stored, before the consolidated file
        raise KeyboardInterrupt

    monkeypatch.setattr(engine, "_consolidate", interrupted)
    argv = ["sweep", "--beta0", "0.9", "1", "--mu", "0.5", "1", "--models", "md", "jkr", "--chunk-points", "1",
            "--workers", "1", "--quiet", "--out", str(tmp_path / "s.nc")]
    assert main(argv) == 130
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "no output was written" not in err[0], err
    assert "8 finished case(s) are stored in" in err[0] and "8 of them by this run" in err[0], err
    assert "was not written" in err[0] and "to resume" in err[0], err
    monkeypatch.undo()
    res = run_sweep(config_from_mapping({"axes": {"beta0": [0.9, 1.0], "mu": [0.5, 1.0]},
                                         "sweep": {"models": ["md", "jkr"], "chunk_points": 1}}),
                    out=tmp_path / "s.nc", scheduler="synchronous", progress=False)
    assert res.computed == [] and len(res.reused) == 8


def test_adhesive_sweep_refuses_an_unaffordable_n_before_anything(tmp_path, monkeypatch):
    """Issue 42 finding 6: a sweep with n = [8192] started allocating; solve refused it at once."""
    import pytest

    from dhfield.core import memory as _memory

    monkeypatch.setattr(_memory, "available_memory", lambda: 50 * 2**20)   # 40 MiB may be claimed
    cfg = config_from_mapping({"axes": {"beta0": [1.0], "mu": [1.0, 2.0], "n": [256]},
                               "sweep": {"quantities": ["adhesive"]}})   # 256^2 x 550 B = 34 MiB a case
    with pytest.raises(ValueError, match=r"axes.n = 256 .*2 cases at once.* fewer workers"):
        run_sweep(cfg, out=tmp_path / "a.nc", scheduler="processes", workers=2, progress=False)
    monkeypatch.setattr(_memory, "available_memory", lambda: 20 * 2**20)
    with pytest.raises(ValueError, match=r"axes.n = 256 \(the adhesive BEM on a 256 x 256 grid\) needs"):
        run_sweep(cfg, out=tmp_path / "a.nc", scheduler="synchronous", progress=False)
    assert list(tmp_path.iterdir()) == []   # refused before the store, the workers or any case
