"""The adhesive ground-truth study: resume, recorded failures, Richardson over N, the dataset reader.

A stand-in solver with a known closed-form dependence on N keeps these tests fast;
the solver itself is tested in tests/test_bem_adhesive.py.
"""
import math

import numpy as np
import pytest

from verification import study_adhesive as sa

#: W*(N) = W_INF + C N^-ORDER: Richardson over three doubling levels is exact for a pure
#: power law, so the extrapolation must return W_INF to round-off.
W_INF, C, ORDER = -0.8, 3.0, 1.5
#: Round-off of the three-level Richardson formula on O(1) values.
RICHARDSON_RTOL = 1e-12


def _stand_in(calls, fail=None, unconverged=None):
    def solver(mu, beta0, n, law, control, progress, **options):
        calls.append((beta0, mu, n))
        if fail == (beta0, mu, n):
            raise RuntimeError("unloading path has no converged contact state")
        w = W_INF * mu ** 0.1 + C * n ** -ORDER
        failures = []
        if unconverged == (beta0, mu, n):
            failures = [{"approach": 5.0, "residual": 0.3, "iterations": 300, "phase": "unloading"}]
        d = dict(W_star=w, a_star=1.0, b_star=beta0, c_star=1.5, d_star=1.5 * beta0, ellipticity=beta0,
                 adhesive_ellipticity=beta0 + 1.0 / n, delta_star=-1.0, residual=1e-7, elapsed=0.01, iterations=100,
                 n_steps=30, half_width_x=2.0, half_width_y=2.0, converged=not failures, failures=failures)
        return d        # the keys of the BEM's pull-off record (a mapping) that the study reads
    return solver


def _refs(beta0s, mus):
    shape = (len(beta0s), len(mus))
    return {m: {"W_star": np.full(shape, -0.79), "ellipticity": np.full(shape, 0.8),
                "adhesive_ellipticity": np.full(shape, 0.8)} for m in ("dh-elliptic", "md")}


def test_resume_failures_and_extrapolation(tmp_path):
    calls = []
    solver = _stand_in(calls, fail=(0.8, 2.0, 32), unconverged=(1.0, 2.0, 64))
    recs = sa.run_study([0.8, 1.0], [1.0, 2.0], [16, 32, 64], work_dir=tmp_path, solver=solver, progress=False)
    assert len(recs) == len(calls) == 12
    # resume (dhfield.sweep.store): the finished cases are read back, the one that raised is solved again
    assert sorted(p.name for p in tmp_path.glob("*.failed.nc")) == ["b0.8_m2_n32_dugdale_load.failed.nc"]
    again = sa.run_study([0.8, 1.0], [1.0, 2.0], [16, 32, 64], work_dir=tmp_path, solver=solver, progress=False)
    assert len(calls) == 13 and calls[-1] == (0.8, 2.0, 32) and len(again) == 12
    for first, back in zip(recs, again):
        if first["status"] != "failed":
            assert back == first  # every field of a record survives the store
    failed = [r for r in again if r["status"] == "failed"]
    assert len(failed) == 1 and "beta0=0.8, mu=2, n=32" in failed[0]["message"]
    assert math.isnan(failed[0]["W_star"])
    bad = [r for r in again if r["status"] == "unconverged"]
    assert len(bad) == 1 and "beta0=1, mu=2, n=64" in bad[0]["message"]

    ds = sa.ground_truth_dataset(sa.load_records(tmp_path), references=_refs([0.8, 1.0], [1.0, 2.0]))
    st = ds["status"].sel(beta0=0.8, mu=2.0, n=32)
    assert sa.STATUSES[int(st)] == "failed" and "mu=2" in str(ds["message"].sel(beta0=0.8, mu=2.0, n=32).values)
    # a complete ladder: Richardson recovers the N -> infinity limit of the power law exactly
    ext = float(ds["W_star_extrapolated"].sel(beta0=1.0, mu=1.0))
    assert ext == pytest.approx(W_INF, rel=RICHARDSON_RTOL)
    assert float(ds["W_star_order"].sel(beta0=1.0, mu=1.0)) == pytest.approx(ORDER, rel=1e-9)
    assert int(ds["W_star_levels"].sel(beta0=1.0, mu=1.0)) == 3
    # failed or unconverged levels are not used: the finest usable value, flagged by its level count
    assert int(ds["W_star_levels"].sel(beta0=0.8, mu=2.0)) == 2
    assert float(ds["W_star_extrapolated"].sel(beta0=0.8, mu=2.0)) == float(ds["W_star"].sel(beta0=0.8, mu=2.0,
                                                                                             n=64))
    assert int(ds["W_star_levels"].sel(beta0=1.0, mu=2.0)) == 2


def test_unconverged_after_pull_off_is_usable(tmp_path):
    calls = []
    rec = sa.run_case(0.9, 1.0, 32, solver=_stand_in(calls, unconverged=(0.9, 1.0, 32)))
    assert rec["status"] == "unconverged"  # approach 5.0 lies before (above) the pull-off approach -1
    solver = _stand_in(calls)

    def after(*args, **kw):
        res = dict(solver(*args, **kw))
        res.update(converged=False, failures=[{"approach": -3.0, "residual": 0.2, "iterations": 9,
                                               "phase": "unloading"}])
        return res

    rec = sa.run_case(0.9, 1.0, 32, solver=after)
    assert rec["status"] == "unconverged_after_pull_off" and "beyond the pull-off" in rec["message"]
    assert "unconverged_after_pull_off" in sa.USABLE


def test_consolidated_file_round_trip(tmp_path):
    work, out = tmp_path / "work", tmp_path / "gt.nc"
    sa.run_study([1.0], [1.0], [16, 32, 64], work_dir=work, solver=_stand_in([]), progress=False)
    path = sa.consolidate(work, out, references=_refs([1.0], [1.0]), command="test")
    ds = sa.read_ground_truth(path)
    assert ds["W_star"].attrs["units"] == "1" and "2 pi R dgamma" in ds["W_star"].attrs["long_name"]
    assert ds["elapsed"].attrs["units"] == "s"
    assert ds["status"].attrs["flag_meanings"].split() == list(sa.STATUSES)
    assert ds.attrs["param_n_ladder"] == "16 32 64" and ds.attrs["param_command"] == "test"
    assert "param_git_commit" in ds.attrs and "param_solver_tol" in ds.attrs
    assert list(ds["model"].values) == ["dh-elliptic", "md"]
    assert ds["W_star_model"].dims == ("model", "beta0", "mu")
    with pytest.raises(ValueError, match="path"):
        sa.read_ground_truth(_not_a_ground_truth(tmp_path))


def _not_a_ground_truth(tmp_path):
    import xarray as xr

    from dhfield.io import write_netcdf

    return write_netcdf(xr.Dataset({"a": ("x", np.zeros(2))}), tmp_path / "other.nc")


def test_cli_validates_before_running(tmp_path):
    with pytest.raises(SystemExit) as exc:
        sa.main(["--beta0", "1.5", "--work-dir", str(tmp_path)])
    assert exc.value.code == 2
    with pytest.raises(SystemExit):
        sa.main(["--n", "33", "--work-dir", str(tmp_path)])
    with pytest.raises(SystemExit):
        sa.main(["--out", str(tmp_path / "missing" / "x.nc"), "--work-dir", str(tmp_path)])
    assert list(tmp_path.iterdir()) == []


def test_verdict_names_the_closest_closure(tmp_path):
    """The report's verdict is computed from the stored numbers: with references placed at
    known distances from the (stand-in) ground truth, it names the closest closure and its error."""
    from verification import sec_adhesive

    sa.run_study([0.8, 1.0], [1.0], [16, 32, 64], work_dir=tmp_path, solver=_stand_in([]), progress=False)
    truth = W_INF * 1.0 ** 0.1  # stand-in ground truth at mu = 1 after extrapolation
    refs = {m: {"W_star": np.full((2, 1), truth * (1 + d)), "ellipticity": np.full((2, 1), 0.8),
                "adhesive_ellipticity": np.full((2, 1), 0.8)}
            for m, d in (("dh-elliptic", -0.20), ("dh-elliptic-two-axis", 0.013), ("md", 0.05))}
    ds = sa.ground_truth_dataset(sa.load_records(tmp_path), references=refs)
    tab = sec_adhesive.truth_table(ds)
    lines = sec_adhesive.verdict_lines(tab, "test coverage")
    assert "two-axis" in lines[0] and "1.3 %" in lines[0]
    assert any("paper's closure" in ln and "-20.0 %" in ln for ln in lines)
    # the stand-in has beta_cd - beta_ab = 1/N -> 0: shared beta after extrapolation
    assert any("share β" in ln for ln in lines)
    # the model guide recommends the same closure, with the others' worst deviations
    guide = sec_adhesive.guide_lines(tab)
    assert len(guide) == 1 and "`dh-elliptic-two-axis` — within 1.3 %" in guide[0]
    assert "`dh-elliptic` 20.0 %" in guide[0] and "all 2 cases" in guide[0]


def test_implausible_order_keeps_the_finest_value():
    """Three levels whose differences shrink too slowly (order 0.1) are noise, not convergence."""
    ns = [64, 128, 256]
    vals = [1.0, 1.0 + 0.01, 1.0 + 0.01 + 0.01 * 2 ** -0.1]
    v, q, levels = sa.extrapolate(ns, vals)
    assert levels == 1 and v == vals[-1] and q == pytest.approx(0.1, rel=1e-9)


#: The study's coarse-to-fine record and a direct refine_pull_off call run the same solves;
#: FFTW plans may change the round-off, which the fixed-point termination (tol 1e-6) can
#: amplify to ~1e-7 relative in W*.
RTOL_SAME_ROUTE = 1e-6


def test_coarse_to_fine_from_a_stored_coarse_level(tmp_path):
    """The route that made beta0 = 0.5, mu = 5 converge at N = 512 (`--n 256 512 --coarse-to-fine 256`
    with the N = 256 record already stored): the coarse level is read for the record but re-solved in
    memory as the start, and the fine record says it was refined from it."""
    from dhfield.analysis.bem_start import AdhesiveOptions
    from dhfield.bem import adhesive_pull_off, refine_pull_off

    opts = dict(n_steps=4, refine_levels=0, max_iter=sa.STUDY_MAX_ITER)
    first = sa.run_study([1.0], [1.0], [16], work_dir=tmp_path, progress=False, **opts)
    assert [r["route"] for r in first] == ["full path"]
    recs = sa.run_study([1.0], [1.0], [16, 32], work_dir=tmp_path, progress=False, coarse_to_fine=16, **opts)
    fine = next(r for r in recs if r["n"] == 32)
    assert fine["route"] == "coarse to fine from n=16" and fine["search"] == "refine"
    assert fine["status"] == "ok" and fine["converged"]
    direct = refine_pull_off(adhesive_pull_off(mu=1.0, beta0=1.0, n=16, progress=False, options=AdhesiveOptions(**opts)),
                             32, progress=False, options=AdhesiveOptions(**opts))
    assert fine["W_star"] == pytest.approx(direct.W_star, rel=RTOL_SAME_ROUTE)
    assert fine["n_steps"] == direct.n_steps


def test_report_lists_the_cases_solved_coarse_to_fine(tmp_path):
    from verification import sec_adhesive

    sa.run_study([0.5, 1.0], [5.0], [16, 32], work_dir=tmp_path, solver=_stand_in([]), progress=False)
    recs = sa.load_records(tmp_path)
    for r in recs:
        if (r["beta0"], r["n"]) == (0.5, 32):
            r.update(route="coarse to fine from n=16", search="refine")
    ds = sa.ground_truth_dataset(recs, references=_refs([0.5, 1.0], [5.0]))
    assert sec_adhesive.coarse_to_fine_cases(ds) == [(0.5, 5.0, 32, "coarse to fine from n=16")]
    assert sec_adhesive.coarse_to_fine_cases(ds.drop_vars("route")) == []

