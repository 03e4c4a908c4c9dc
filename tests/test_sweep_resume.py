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
