"""verification.study_extended: what the record of a part stopped at its hard timeout says of each case.

The part's case store (:class:`dhfield.sweep.store.CaseStore`) holds ``<key>.nc`` for a finished case and
``<key>.failed.nc`` for one that raised, and nothing for a case not finished; the line of each case must say
which, and never call a case it holds nothing of "attempted".  A fabricated timeout record and store
(no solve, no timing).
"""
import json

from dhfield.sweep import engine
from dhfield.sweep.store import CaseStore, output_paths
from verification import study_extended as se


def _timed_out_part(work_dir, name="trial"):
    """A part of 2 beta0 x 1 mu x 2 levels stopped at its timeout: one case finished, one failed, two nothing."""
    rec = {"part": name, "beta0": [0.5, 1.0], "mu": [10.0], "levels": [1, 2], "timeout_s": 600.0, "wall_s": 600.2,
           "cpu_s": 590.0, "command": f"dhfield sweep {name}.toml --workers 1", "commit": "abc1234",
           "stopped": "2026-11-26T14:00:00Z", "load_average": [2.0, 2.0, 2.0]}
    (work_dir / f"{name}.timeout.json").write_text(json.dumps(rec))
    store = CaseStore(output_paths(work_dir / f"{name}.nc")[1], "fingerprint")
    # keys: adhesive__<beta0 index>_<mu index>_<level index>_<law index>, as the engine writes them
    store.write("adhesive__00000_00000_00000_00000", engine._case_dataset({"W_star": -0.65}, "ok", ""))
    store.write("adhesive__00001_00000_00001_00000",
                engine._case_dataset({"W_star": float("nan")}, "failed", "RuntimeError: refused before solving"))


def test_timeout_record_says_what_each_case_reached(tmp_path):
    _timed_out_part(tmp_path)
    lines = se._attempts(tmp_path)
    assert set(lines) == {(0.5, 10.0, 1), (0.5, 10.0, 2), (1.0, 10.0, 1), (1.0, 10.0, 2)}
    assert lines[(0.5, 10.0, 1)].startswith("finished (status ok) in the case store trial.nc.cases/")
    assert "build reads the case from the store" in lines[(0.5, 10.0, 1)]
    assert lines[(1.0, 10.0, 2)].startswith("failed in part trial (RuntimeError: refused before solving)")
    for key in ((0.5, 10.0, 2), (1.0, 10.0, 1)):
        line = lines[key]
        assert line.startswith("not finished when part trial stopped at its hard timeout of 600 s")
        assert "2 of the part's 4 cases had ended" in line and "running at the stop or was not reached" in line
    for line in lines.values():
        assert "attempted" not in line and "commit abc1234" in line and "\n" not in line


def test_no_timeout_record_no_lines(tmp_path):
    assert se._attempts(tmp_path) == {}


def test_part_config_carries_the_time_allowed(tmp_path):
    """A part's TOML is a valid sweep; --max-seconds gives its [bem] max_seconds without changing its fingerprint
    (a part rerun with more time resumes its case store)."""
    from dhfield.sweep import load_config

    plain, longer = tmp_path / "a.toml", tmp_path / "b.toml"
    plain.write_text(se.part_config("high-mu-level2"))
    longer.write_text(se.part_config("high-mu-level2", 4000))
    a, b = load_config(plain), load_config(longer)
    assert a.max_seconds is None and b.max_seconds == 4000.0
    assert a.axes["grid_level"] == (2,) and a.fingerprint() == b.fingerprint()


def test_build_reads_the_cases_a_timed_out_part_finished(tmp_path, monkeypatch):
    """A part stopped at its timeout writes no sweep output; its finished cases come from its case store,
    the failed and unfinished ones do not."""
    monkeypatch.setitem(se.PARTS, "trial", ((0.5, 1.0), (10.0,), (1, 2)))
    _timed_out_part(tmp_path)
    cases = se._sweep_cases(tmp_path)
    assert set(cases) == {(0.5, 10.0)} and set(cases[(0.5, 10.0)]) == {1}
    case = cases[(0.5, 10.0)][1]
    assert case["W_star"] == -0.65 and case["status"] == "ok" and "case store trial.nc.cases/" in case["source"]
    (tmp_path / "trial.timeout.json").unlink()          # no timeout record: the store is not read
    assert se._sweep_cases(tmp_path) == {}


def test_build_lists_under_not_run_only_the_cases_not_run():
    """A stopped part's record has a line for each of its cases; a finished one is not listed as not run."""
    attempts = {(0.1, 10.0, 1): "not finished when part p stopped", (0.3, 10.0, 1): "finished (status ok) in the store"}
    lines = se._not_run_lines([(0.1, 10.0, 1)], attempts)
    assert lines[0] == "not run (1): beta0 0.1 mu 10 level 1"
    assert lines[1] == "  beta0 0.1 mu 10 level 1: not finished when part p stopped"
    assert lines[2].startswith("cases held, with what the timeout record of a stopped part says of them (1)")
    assert lines[3] == "  beta0 0.3 mu 10 level 1: finished (status ok) in the store"
    assert se._not_run_lines([], {}) == ["not run (0): none"]


def test_build_keeps_the_sweep_cases_the_previous_build_holds(tmp_path, monkeypatch):
    """A later session's work dir lacks the parts earlier sessions ran: a rebuild keeps their cases as the
    previous build holds them, and a part in the work dir replaces the same case."""
    import shutil

    import numpy as np
    import xarray as xr

    out = tmp_path / "extended.nc"
    shutil.copy(se.DEFAULT_OUT, out)
    work = tmp_path / "work"
    work.mkdir()
    monkeypatch.setitem(se.PARTS, "trial", ((0.5, 1.0), (10.0,), (1, 2)))
    _timed_out_part(work)                                   # beta0 0.5, mu 10, level 1: W* = -0.65, ok
    assert se.build(work, out) == 0
    with xr.open_dataset(se.DEFAULT_OUT) as before, xr.open_dataset(out) as after:
        swept = np.char.startswith(before["source"].values.astype(str), "dhfield sweep")
        assert swept.sum() >= 30
        replaced = dict(beta0=0.5, mu=10.0, level=1)
        keep = swept.copy()
        keep[list(before["beta0"].values).index(0.5), list(before["mu"].values).index(10.0), 0] = False
        for name in ("W_star", "W_star_error", "nx", "cpu_seconds"):
            np.testing.assert_array_equal(after[name].values[keep], before[name].values[keep])
        np.testing.assert_array_equal(after["status"].values[keep], before["status"].values[keep])
        assert all(se._HELD in s for s in after["source"].values[keep])
        assert float(after["W_star"].sel(replaced)) == -0.65
        assert "part trial" in str(after["source"].sel(replaced).values)
        assert se._HELD not in str(after["source"].sel(replaced).values)


def test_a_case_answered_carries_the_solver_note_as_its_message(tmp_path, monkeypatch):
    """An answer has no sweep message; the build keeps the solver's note instead (here the widest edge's, which
    the report's level-2 sentence reads), while a case that is not an answer keeps the sweep's reason."""
    from dhfield.analysis.bem_start import WIDEST_EDGE_NOTE

    monkeypatch.setitem(se.PARTS, "trial", ((0.5, 1.0), (10.0,), (1, 2)))
    _timed_out_part(tmp_path)
    store = CaseStore(output_paths(tmp_path / "trial.nc")[1], "fingerprint")
    case = engine._case_dataset({"W_star": -0.66}, "ok", "")
    case.attrs["case_note"] = WIDEST_EDGE_NOTE
    store.write("adhesive__00000_00000_00001_00000", case)           # beta0 0.5, mu 10, level 2
    cases = se._sweep_cases(tmp_path)[(0.5, 10.0)]
    assert cases[2]["message"] == WIDEST_EDGE_NOTE and cases[2]["W_star"] == -0.66
    assert cases[1]["message"] == ""                                   # level 1: an answer without a note
