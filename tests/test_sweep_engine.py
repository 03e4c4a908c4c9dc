"""Sweep engine: values against closed forms and the single-case functions, schedulers, failures."""
from __future__ import annotations

import numpy as np
import pytest

from dhfield.analysis import compare
from dhfield.core import schema
from dhfield.core.geometry import ellipticity_from_skew_angle
from dhfield.sweep import config_from_mapping, engine, run_sweep, tasks

#: The analytic pull-off of a block equals the one-call evaluation to rounding: the
#: quadrature's panel count follows the smallest adhesive-zone scale of the batch, so
#: blocks and the whole grid differ in the last digits only (solve tolerance 1e-14).
BLOCK_RTOL = 1e-10

SMALL = {"axes": {"beta0": [0.6, 1.0], "mu": {"geomspace": [0.2, 5, 3]}},
         "sweep": {"models": ["dh-elliptic", "md", "jkr", "dmt"], "chunk_points": 3}}
#: Forward BEM cases on one fixed grid (one operator per worker).
BEM = {"axes": {"beta0": [0.8], "mu": [1.0], "a_star": [0.9, 1.2], "n": [32]},
       "sweep": {"quantities": ["bem_field"]}, "bem": {"half_width": 3.0}}


def _values(ds):
    """Every data variable, for bit-for-bit comparison (attrs such as history excluded)."""
    return {k: ds[k].values for k in ds.data_vars}


def _assert_bit_identical(a, b):
    va, vb = _values(a), _values(b)
    assert va.keys() == vb.keys()
    for k in va:
        if va[k].dtype.kind == "f":
            np.testing.assert_array_equal(va[k], vb[k], err_msg=k)  # NaN == NaN here, bits otherwise
        else:
            assert (va[k] == vb[k]).all(), k


@pytest.fixture(scope="module")
def serial(tmp_path_factory):
    d = tmp_path_factory.mktemp("serial")
    return (run_sweep(config_from_mapping(SMALL), out=d / "s.nc", scheduler="synchronous", progress=False),
            run_sweep(config_from_mapping(BEM), out=d / "b.nc", scheduler="synchronous", progress=False))


def test_closed_forms(serial):
    w = serial[0].dataset["W_star"]
    # JKR: W_max = -3/2 pi R dgamma (Johnson, Kendall & Roberts 1971); DMT: -2 pi R dgamma (Derjaguin,
    # Muller & Toporov 1975); in W* = W/(2 pi R dgamma) (Eq. 34 with sin = 1): -3/4 and -1.
    assert np.all(w.sel(model="jkr").values == -0.75)
    np.testing.assert_allclose(w.sel(model="dmt").values, -1.0, rtol=1e-15)


def test_matches_single_case_functions(serial):
    ds = serial[0].dataset
    mu, b0 = np.meshgrid(ds["mu"].values, ds["beta0"].values)
    for model in ("dh-elliptic", "md"):
        ref = compare.pull_off(model, mu=mu, beta0=b0, check_closure=False)
        for k in tasks.PULL_OFF_FIELDS:
            np.testing.assert_allclose(ds[k].sel(model=model).values, ref[k], rtol=BLOCK_RTOL, err_msg=k)


def test_dataset_layout_and_metadata(serial):
    ds = serial[0].dataset
    assert ds["W_star"].dims == ("model", "beta0", "mu")  # schema.DIM_ORDER
    for k in tasks.PULL_OFF_FIELDS:
        assert ds[k].attrs["units"] == schema.attrs(k, nondimensional=True)["units"]
        assert ds[k].attrs["long_name"] == schema.attrs(k, nondimensional=True)["long_name"]
    assert (ds["status"].values == 0).all()
    assert "doi:10.1007/s11249-017-0976-8" in ds.attrs["references"]
    for c in ds.coords:
        assert ds[c].encoding.get("_FillValue", None) is None


def test_bem_field_cases_match_single_case(serial):
    from dhfield.analysis.fields import model_case

    ds = serial[1].dataset
    assert ds["bem_displacement_error"].dims == ("beta0", "mu", "a_star", "n")
    case = model_case(32, 0.8, 1.0, 1.2, half_width=3.0, threads=1)
    assert ds["bem_displacement_error"].sel(a_star=1.2).item() == case.displacement_errors()["all"]["rel_max"]
    assert (ds["bem_field_status"].values == 0).all()


def test_skew_angle_axis(tmp_path):
    cfg = config_from_mapping({"axes": {"skew_angle_deg": [40.0, 90.0], "mu": [1.0]},
                               "sweep": {"models": ["jkr-elliptic"]}})
    ds = run_sweep(cfg, out=tmp_path / "k.nc", scheduler="synchronous", progress=False).dataset
    assert ds["W_star"].dims == ("model", "skew_angle_deg", "mu")
    np.testing.assert_array_equal(ds["beta0"].values, ellipticity_from_skew_angle(np.radians([40.0, 90.0])))


def _worker_threads():
    import os

    from threadpoolctl import threadpool_info

    return os.getpid(), {i["internal_api"]: i["num_threads"] for i in threadpool_info()}


def test_same_bits_on_every_scheduler(serial, tmp_path):
    """Serial, local processes and a dask.distributed LocalCluster on loopback agree bit for bit."""
    from distributed import LocalCluster

    import os

    from dask.callbacks import Callback

    env = {k: os.environ.get(k) for k in engine.SINGLE_THREAD_ENV}
    in_flight = [0, 0]  # now, most

    def pretask(key, dsk, state):
        in_flight[0] += 1
        in_flight[1] = max(in_flight)

    def posttask(key, result, dsk, state, worker_id):
        in_flight[0] -= 1

    with engine.connect("processes", workers=2) as pool:  # one pool of 2 worker processes for both sweeps
        assert pool.start(wait=False) == 0.0  # spawned, starting in the background
        assert pool.start() > 0.0 and pool.start() == 0.0  # every worker up before the sweeps, once
        with Callback(pretask=pretask, posttask=posttask):
            procs = [run_sweep(config_from_mapping(c), out=tmp_path / f"p{i}.nc", scheduler=pool, progress=False)
                     for i, c in enumerate((SMALL, BEM))]
        threads = [pool.pool.submit(_worker_threads).result() for _ in range(4)]
    # Tasks go out one per free worker (SMALL has 8 pull-off blocks), never in batches to one worker.
    assert in_flight[1] == 2
    # Each local worker runs one BLAS/OpenMP thread; this process's environment is untouched.
    assert all(t and set(t.values()) == {1} for _, t in threads), threads
    assert {k: os.environ.get(k) for k in engine.SINGLE_THREAD_ENV} == env
    with LocalCluster(n_workers=2, threads_per_worker=1, processes=False, protocol="tcp", host="127.0.0.1",
                      dashboard_address=None) as cluster:
        assert cluster.scheduler_address.startswith("tcp://127.0.0.1:")
        dist = [run_sweep(config_from_mapping(c), out=tmp_path / f"d{i}.nc", scheduler=cluster.scheduler_address,
                          progress=False) for i, c in enumerate((SMALL, BEM))]
    for s, p, d in zip(serial, procs, dist):
        _assert_bit_identical(s.dataset, p.dataset)
        _assert_bit_identical(s.dataset, d.dataset)


def test_failed_case_is_recorded_and_retried(tmp_path, monkeypatch):
    real = engine.bem_field_case

    def flaky(**params):
        if params["a_star"] == 1.2:
            raise FloatingPointError("injected failure")
        return real(**params)

    monkeypatch.setattr(engine, "bem_field_case", flaky)
    cfg = config_from_mapping(BEM)
    first = run_sweep(cfg, out=tmp_path / "f.nc", scheduler="synchronous", progress=False)
    ds = first.dataset
    bad = ds.sel(a_star=1.2, beta0=0.8, mu=1.0, n=32)
    assert int(bad["bem_field_status"]) == engine._STATUS["failed"]
    assert "FloatingPointError: injected failure" in str(bad["bem_field_message"].values)
    assert np.isnan(float(bad["bem_displacement_error"]))
    good = ds.sel(a_star=0.9, beta0=0.8, mu=1.0, n=32)
    assert int(good["bem_field_status"]) == 0 and np.isfinite(float(good["bem_displacement_error"]))
    assert len(first.failed) == 1
    monkeypatch.setattr(engine, "bem_field_case", real)
    second = run_sweep(cfg, out=tmp_path / "f.nc", scheduler="synchronous", progress=False)
    assert second.failed == [] and second.computed == first.failed  # only the failed case is redone
    assert (second.dataset["bem_field_status"].values == 0).all()


def test_pluggable_adhesive_ground_truth(tmp_path, monkeypatch):
    """The adhesive quantity goes on the model dimension; a non-converged case keeps its message."""

    class Result:
        def __init__(self, mu, beta0):
            self.W_star, self.a_star, self.c_star, self.beta_ab = -mu * beta0, 1.0, 2.0, beta0
            self.b_star, self.d_star, self.beta_cd = beta0, 2.0 * mu, mu  # distinct per case
            self.delta_star, self.iterations = -0.5, 7
            self.converged = mu < 2.0
            self.message = "" if self.converged else "stalled"

    def fake_solver(mu, beta0, n, *, law, control, threads):
        return Result(mu, beta0)

    monkeypatch.setattr(tasks, "adhesive_solver", lambda name="default": fake_solver)
    monkeypatch.setattr(engine, "adhesive_solver", lambda name="default": fake_solver)
    cfg = config_from_mapping({"axes": {"beta0": [0.9], "mu": [1.0, 3.0], "n": [32, 64]},
                               "sweep": {"quantities": ["pull_off", "adhesive"], "models": ["jkr"]}})
    ds = run_sweep(cfg, out=tmp_path / "a.nc", scheduler="synchronous", progress=False).dataset
    assert list(ds["model"].values) == ["jkr", tasks.ADHESIVE_MODEL]
    assert ds["W_star"].dims == ("model", "beta0", "mu", "n", "law")
    adh = ds.sel(model=tasks.ADHESIVE_MODEL, beta0=0.9, n=64).isel(law=0)
    np.testing.assert_array_equal(adh["W_star"].values, [-0.9, -2.7])
    assert list(adh["status"].values) == [0, engine._STATUS["not_converged"]]
    assert str(ds["adhesive_message"].sel(beta0=0.9, mu=3.0, n=64).isel(law=0).values) == "stalled"
    assert (ds["W_star"].sel(model="jkr").values == -0.75).all()  # analytic models broadcast over n, law
    assert (ds["warning"].sel(model="jkr").values != "").all()  # jkr is validated at beta0 = 1 only
    assert (ds["warning"].sel(model=tasks.ADHESIVE_MODEL).values == "").all()
    # The BEM-only outputs of `dhfield solve --json` are in the sweep too (same names and metadata).
    np.testing.assert_array_equal(adh["b_star"].values, [0.9, 0.9])
    np.testing.assert_array_equal(adh["d_star"].values, [2.0, 6.0])
    np.testing.assert_array_equal(adh["beta_cd"].values, [1.0, 3.0])
    np.testing.assert_array_equal(adh["beta_ab"].values, [0.9, 0.9])
    assert ds["beta_cd"].attrs["long_name"] == schema.attrs("beta_cd", nondimensional=True)["long_name"]


def test_progress_bar_with_eta():
    import io

    out = io.StringIO()
    bar = engine.Progress(4, True, stream=out)
    for _ in range(4):
        bar.advance()
    bar.close()
    text = out.getvalue()
    assert "4/4 100%" in text and "ETA" in text and text.endswith("\n")
    quiet = io.StringIO()
    bar = engine.Progress(4, False, stream=quiet)
    bar.advance(4)
    bar.close()
    assert quiet.getvalue() == ""


def test_map_cases_keeps_order():
    assert engine.map_cases(divmod, [(7, 2), (9, 4), (1, 1)], scheduler="synchronous") == [(3, 1), (2, 1), (1, 0)]


#: The JKR load curve is a closed form evaluated to rounding.
JKR_CURVE_RTOL = 1e-12


def test_load_curves(tmp_path):
    cfg = config_from_mapping({"axes": {"beta0": [0.8, 1.0], "mu": [0.5, 2.0]},
                               "sweep": {"quantities": ["load_curve"], "models": ["jkr", "md"],
                                         "curve_a_star": [0.1, 2.0], "curve_points": 12}})
    ds = run_sweep(cfg, out=tmp_path / "c.nc", scheduler="synchronous", progress=False).dataset
    assert ds["curve_W_star"].dims == ("model", "beta0", "mu", "point")
    a = ds["curve_a_star"].values
    np.testing.assert_array_equal(a, np.linspace(0.1, 2.0, 12))
    # JKR (Johnson, Kendall & Roberts 1971) with R = E* = dgamma = 1: W = 4a^3/3 - sqrt(8 pi a^3),
    # W* = W/(2 pi) (Eq. 34, circle).
    jkr = (4.0 * a**3 / 3.0 - np.sqrt(8.0 * np.pi * a**3)) / (2.0 * np.pi)
    for b in (0.8, 1.0):
        np.testing.assert_allclose(ds["curve_W_star"].sel(model="jkr", beta0=b, mu=2.0).values, jkr,
                                   rtol=JKR_CURVE_RTOL)
    ref = compare.load_curve("md", mu=0.5, beta0=0.8, a_star=a)
    np.testing.assert_array_equal(ds["curve_W_star"].sel(model="md", beta0=0.8, mu=0.5).values, ref["W_star"])
    assert (ds["load_curve_status"].values == 0).all()


def test_costliest_tasks_start_first(tmp_path, monkeypatch):
    """Longest-processing-time order: tasks start in decreasing expected cost (grid order breaks ties)."""
    calls = []

    class Result:
        W_star = a_star = c_star = beta_ab = b_star = d_star = beta_cd = delta_star = iterations = 1.0
        converged, message = True, ""

    def recording_solver(mu, beta0, n, *, law, control, threads):
        calls.append((mu, beta0, n))
        return Result()

    monkeypatch.setattr(tasks, "adhesive_solver", lambda name="default": recording_solver)
    monkeypatch.setattr(engine, "adhesive_solver", lambda name="default": recording_solver)
    cfg = config_from_mapping({"axes": {"beta0": [0.8, 1.0], "mu": [0.3, 2.0, 1.0], "n": [32, 64]},
                               "sweep": {"quantities": ["adhesive"]}})
    run_sweep(cfg, out=tmp_path / "o.nc", scheduler="synchronous", progress=False)
    expected = [tasks.expected_seconds("adhesive", {"mu": m, "beta0": b, "n": n}) for m, b, n in calls]
    assert len(calls) == 12
    assert expected == sorted(expected, reverse=True)
    assert calls[0] == (2.0, 0.8, 64) and calls[-1] == (0.3, 1.0, 32)


def test_case_files_record_their_wall_time(serial):
    from dhfield.io import read_netcdf
    from dhfield.sweep.store import output_paths

    _, store_dir = output_paths(serial[1].path)
    for p in store_dir.glob("bem_field__*.nc"):
        seconds = read_netcdf(p).attrs["seconds"]
        assert 0.0 < seconds < 600.0
    assert "seconds" not in serial[1].dataset.attrs


def test_unresolved_adhesive_case_is_not_stored_ok(tmp_path, capsys):
    """Issue 18 item 1: `dhfield sweep --beta0 1 --mu 8 --n 32 --quantities adhesive` stored
    W* = -2.44 with status 0 although the solver flags the case resolved = False (the Dugdale
    zone is narrower than a cell).  It must be stored with status "unresolved" and the CLI
    must say so and exit non-zero, also under --quiet."""
    from dhfield.cli import main
    from dhfield.cli.sweep import EXIT_FLAGGED

    out = tmp_path / "adh.nc"
    rc = main(["sweep", "--beta0", "1", "--mu", "8", "--n", "32", "--quantities", "adhesive", "--workers", "1",
               "--out", str(out), "--quiet"])
    err = capsys.readouterr().err
    assert rc == EXIT_FLAGGED
    assert "1 flagged" in err
    import xarray as xr

    with xr.open_dataset(out) as ds:
        st = int(ds["status"].sel(model=tasks.ADHESIVE_MODEL).values.item())
        msg = str(ds["adhesive_message"].values.item())
    assert st == engine._STATUS["unresolved"] != 0
    assert "resolve" in msg


def test_quiet_sweep_with_failed_cases_says_so(tmp_path, capsys, monkeypatch):
    """Issue 18 item 14: `sweep --quiet` with failed cases exited 1 with nothing on stderr."""
    from dhfield.cli import main

    def broken(*a, **k):
        raise RuntimeError("boom")

    monkeypatch.setattr(engine, "pull_off_block", broken)
    rc = main(["sweep", "--beta0", "0.9", "--mu", "1", "--workers", "1", "--out", str(tmp_path / "f.nc"),
               "--quiet"])
    err = capsys.readouterr().err.strip()
    assert rc == 1 and "1 failed" in err and "\n" not in err


def test_sweep_keeps_each_records_validity_warning(tmp_path, capsys):
    """Issue 17: md at beta0 = 0.5 and jkr-elliptic at mu = 0.3 were stored with status 0 and no
    warning.  Each point carries its record's warning (compare.pull_off), also when a rerun reads
    the blocks back from the store, and the command says how many points are warned."""
    from dhfield.cli import main

    cfg = config_from_mapping({"axes": {"beta0": [0.5, 1.0], "mu": [0.3, 20.0]},
                               "sweep": {"models": ["md", "jkr-elliptic"], "chunk_points": 2}})
    first = run_sweep(cfg, out=tmp_path / "w.nc", scheduler="synchronous", progress=False)
    again = run_sweep(cfg, out=tmp_path / "w.nc", scheduler="synchronous", progress=False)
    assert again.computed == [] and again.reused
    for res in (first, again):
        ds = res.dataset
        assert ds["warning"].dims == ("model", "beta0", "mu")
        assert ds["warning"].attrs["long_name"] == schema.attrs("warning")["long_name"]
        assert (ds["status"].values == 0).all()  # answered: the warning says how far to trust it
        for model in ("md", "jkr-elliptic"):
            for b in (0.5, 1.0):
                for m in (0.3, 20.0):
                    rec = compare.pull_off(model, beta0=b, mu=m, check_closure=False)
                    assert str(ds["warning"].sel(model=model, beta0=b, mu=m).values) == rec["warning"]
        assert "md is validated" in str(ds["warning"].sel(model="md", beta0=0.5, mu=20.0).values)
        assert "mu = 0.3" in str(ds["warning"].sel(model="jkr-elliptic", beta0=1.0, mu=0.3).values)
        assert res.warned == 4  # md at beta0 = 0.5 (two mu), jkr-elliptic at mu = 0.3 (two beta0)
    rc = main(["sweep", "--beta0", "0.5", "--mu", "20", "--models", "md", "--workers", "1",
               "--out", str(tmp_path / "cli.nc")])
    assert rc == 0
    assert "1 pull-off point(s) outside their model's validated range" in capsys.readouterr().err


@pytest.mark.parametrize("converged, status, grid_advice", [(False, "not_converged", False),
                                                             (True, "unresolved", True)])
def test_adhesive_message_advises_a_finer_grid_only_for_a_converged_unresolved_case(tmp_path, monkeypatch,
                                                                                   converged, status, grid_advice):
    """A case that did not converge keeps the solver's own reason (at mu = 10: trapped lattices, the analytic W*);
    "increase n" is the advice for a converged path on a grid too coarse for its zone only."""
    fields = engine._FIELDS["adhesive"]

    def solver(**params):
        rec = {k: float("nan") for k in fields}
        rec.update({k: "" for k in engine._TEXT_FIELDS.get("adhesive", ())})
        rec.update(converged=converged, resolved=False, message="the solver's reason")
        return rec

    monkeypatch.setattr(engine, "adhesive_case", solver)
    out = engine._run_cases("adhesive", [("adhesive__00000_00000_00000_00000", {})], tmp_path / "store", "fp")
    rec, st, message, computed = out["adhesive__00000_00000_00000_00000"]
    assert st == status and computed and message.startswith("the solver's reason")
    assert (engine.UNRESOLVED_MESSAGE in message) == grid_advice
