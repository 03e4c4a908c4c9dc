"""verification.study_newton: the recompute's dataset says of each stored case what was found, and its table judges it.

Fabricated case records (no solve): an answer within the stored truth's error, an answer outside it,
an unconverged one, a failed process and a case not run.  The table's verdict is |new - stored| <= the
sum of both stated errors; anything else, or a case that is not an answer, makes it exit 1.
"""
import json

import numpy as np
import pytest
import xarray as xr

from verification import study_newton as sn

CASES = [(1.0, 1.0, -0.7928, 1e-4), (0.5, 1.0, -0.6926, 1e-4), (1.0, 10.0, -0.7507, 7e-3),
         (0.5, 10.0, -0.6535, 6e-3), (0.1, 10.0, -0.2255, 2e-3)]


def _record(beta0, mu, w, err, converged=True, resolved=True):
    return {"beta0": beta0, "mu": mu, "W_star": w, "W_star_error": err, "a_star": 1.0, "b_star": 1.0,
            "c_star": 1.1, "d_star": 1.1, "delta_star": -0.8, "converged": converged, "resolved": resolved,
            "nx": 256, "ny": 256, "states": 9, "gmres": 600, "wall_seconds": 2.0, "cpu_seconds": 1.5,
            "peak_rss_gib": 0.2, "note": "", "commit": "abc1234", "command": "dhfield solve ...",
            "finished": "2026-12-02T06:00:00Z"}


@pytest.fixture
def work(tmp_path, monkeypatch):
    monkeypatch.setattr(sn, "stored_cases", lambda path=None: list(CASES))
    recs = [_record(1.0, 1.0, -0.79285, 2e-4),                       # |dev| 5e-5 <= 2e-4 + 1e-4: agrees
            _record(0.5, 1.0, -0.6940, 2e-4),                        # |dev| 1.4e-3 > 3e-4: does not
            _record(1.0, 10.0, -0.7508, np.inf, converged=False, resolved=False),
            {"beta0": 0.5, "mu": 10.0, "error": "MemoryError", "wall_seconds": 3.0, "command": "c", "finished": "f"}]
    for r in recs:
        (tmp_path / f"case_b{r['beta0']:g}_m{r['mu']:g}.json").write_text(json.dumps(r))
    return tmp_path


def test_build_keeps_every_case_and_says_what_became_of_it(work):
    ds = sn.build(work, work / "out.nc")
    assert ds.sel(beta0=1.0, mu=1.0)["status"].item() == "ok"
    assert ds.sel(beta0=1.0, mu=10.0)["status"].item() == "not_converged"
    assert ds.sel(beta0=0.5, mu=10.0)["status"].item() == "failed"
    assert ds.sel(beta0=0.5, mu=10.0)["note"].item() == "MemoryError"
    assert ds.sel(beta0=0.1, mu=10.0)["status"].item() == "not run"
    assert ds.sel(beta0=0.1, mu=1.0)["status"].item() == "absent"          # not a stored case
    assert float(ds.sel(beta0=0.5, mu=1.0)["W_star_stored"]) == -0.6926
    with xr.open_dataset(work / "out.nc") as back:                          # written, with units and names
        assert back["cpu_seconds"].attrs["units"] == "s" and "long_name" in back["W_star"].attrs
        assert back.attrs["build_command"].startswith("python -m verification.study_newton")


def test_table_judges_by_both_stated_errors_and_flags_the_rest(work, capsys):
    sn.build(work, work / "out.nc")
    assert sn.table(work / "out.nc") == 1
    out = capsys.readouterr().out
    rows = {line.split()[0] + " " + line.split()[1]: line for line in out.splitlines()[1:-1]}
    assert rows["1 1"].endswith("yes") and rows["0.5 1"].endswith("NO")
    assert "not_converged" in rows["1 10"] and "failed" in rows["0.5 10"] and "not run" in rows["0.1 10"]
    assert "cases not answered or not agreeing: 4" in out


def test_run_skips_the_cases_already_recorded(work, monkeypatch):
    calls = []
    monkeypatch.setattr(sn.subprocess, "run", lambda cmd, **kw: calls.append(cmd))
    sn.run(work, mus={1.0})                       # both mu = 1 cases are recorded: nothing solved
    assert calls == []
