"""Option values the parser reads as nothing, flagged fits, and messages in the user's units (issue 42)."""
from __future__ import annotations

import pytest

from dhfield.cli import main


@pytest.fixture(autouse=True)
def _private_env(tmp_path, monkeypatch):
    monkeypatch.setenv("DHFIELD_CACHE", str(tmp_path / "cache"))
    monkeypatch.setenv("DHFIELD_THREADS", "1")
    monkeypatch.delenv("DHFIELD_DEBUG", raising=False)
    monkeypatch.chdir(tmp_path)


def _run(capsys, argv):
    code = main(argv)
    out, err = capsys.readouterr()
    return code, out, err


# ------------------------------------------------------------------ finding 11: "--opt=--" is an empty list
@pytest.mark.parametrize("argv, option", [
    (["pulloff", "--beta0=--", "--mu", "1"], "--beta0"),
    (["pulloff", "--beta0", "0.9", "--mu=--"], "--mu"),
    (["compare", "--beta0=--", "--mu", "1"], "--beta0"),
    (["solve", "--beta0=--", "--mu", "1", "--n", "32"], "--beta0"),
    (["field", "--beta0=--", "--mu", "1", "--a-star", "1.2", "--n", "16", "--out", "f.nc"], "--beta0"),
    (["curve", "--beta0=--", "--mu", "1"], "--beta0"),
    (["periphery", "--beta0=--", "--mu", "1"], "--beta0"),
    (["sweep", "--beta0=--", "--mu", "1", "--models", "jkr", "--out", "s.nc"], "--beta0"),
    (["sweep", "--beta0", "0.9", "--mu", "1", "--models=--", "--out", "s.nc"], "--models"),
    (["cycle", "--beta0", "1", "--mu", "1", "--machine-stiffness=--", "--json"], "--machine-stiffness"),
    (["fit", "--pull-off-force=--", "--adhesive-stress", "1"], "--pull-off-force"),
])
def test_an_option_given_as_double_dash_is_refused_by_name(capsys, argv, option):
    code, out, err = _run(capsys, argv)
    assert code == 2 and out == "" and err.count("\n") == 1, (code, out, err)
    assert err.startswith(f"dhfield: error: {argv[0]}: argument {option}") and "expected a value" in err, err


@pytest.mark.parametrize("kw, name", [({"beta0": [], "mu": 1.0}, "beta0"), ({"beta0": 0.9, "mu": []}, "mu"),
                                      ({"beta0": (), "mu": ()}, "mu")])
def test_compare_refuses_empty_arrays_by_name(kw, name):
    from dhfield import compare

    with pytest.raises(ValueError, match=f"^{name} must contain at least one value"):
        compare.pull_off("md-elliptic", **kw)
    with pytest.raises(ValueError, match=f"^{name} must contain at least one value"):
        compare.compare(**kw)
