"""``dhfield cycle`` and ``--machine-stiffness`` of ``pulloff``/``curve``: CLI equals API, one-line errors."""
import json

import numpy as np
import pytest

from dhfield import compliance
from dhfield.cli import main

PDMS = ["--youngs-modulus", "1.8e6", "--poisson-ratio", "0.49", "--cylinder-radius", "3e-3",
        "--skew-angle-deg", "90", "--work-of-adhesion", "0.05", "--adhesive-stress", "3e4"]
#: JSON round-trips doubles exactly; the CLI calls the same function
TOL_CLI_API = 1e-12


def _json(capsys, argv):
    rc = main(argv)
    out = capsys.readouterr()
    assert rc == 0, out.err
    return json.loads(out.out)


def test_cycle_json_equals_api(capsys):
    rec = _json(capsys, ["cycle", "--model", "jkr", "--beta0", "1", "--mu", "5", "--machine-stiffness", "1",
                         "--json"])
    api = compliance.loading_cycle("jkr", mu=5.0, beta0=1.0, machine_stiffness=1.0)
    for k in ("jump_in_W_star", "jump_out_W_star", "energy_lost_star", "separation_delta_star"):
        assert rec[k] == pytest.approx(api[k], rel=TOL_CLI_API)
    assert rec["units"]["energy_lost_star"] == "1"


def test_cycle_si_and_plot(capsys, tmp_path):
    png = tmp_path / "cycle.png"
    rec = _json(capsys, ["cycle", "--model", "md", *PDMS, "--machine-stiffness", "50", "--json"])
    assert rec["units"]["energy_lost"] == "J" and rec["energy_lost"] > 0
    assert rec["machine_stiffness"] == 50.0
    rc = main(["cycle", "--model", "md", *PDMS, "--plot", str(png)])
    assert rc == 0 and png.stat().st_size > 10_000


def test_cycle_load_control_plot_runs(capsys, tmp_path):
    png = tmp_path / "k0.png"
    assert main(["cycle", "--model", "jkr", "--beta0", "1", "--mu", "5", "--machine-stiffness", "0",
                 "--plot", str(png)]) == 0
    assert "inf" in capsys.readouterr().out


@pytest.mark.parametrize("argv, match", [
    (["cycle", "--model", "jkr", "--beta0", "1", "--mu", "5", "--machine-stiffness", "-1"], "machine-stiffness"),
    (["cycle", "--model", "jkr", "--beta0", "1", "--mu", "5", "--machine-stiffness", "inf"], "machine-stiffness"),
    (["cycle", "--model", "jkr", "--beta0", "1", "--mu", "5", "--plot", "x.pdf"], "plot"),
    (["pulloff", "--model", "jkr", "--beta0", "1", "--mu", "5", "--machine-stiffness", "nan"], "machine_stiffness"),
    (["pulloff", "--model", "jkr", "--beta0", "1", "--mu", "5", "--machine-stiffness", "1", "--control",
      "displacement"], "control"),
    (["curve", "--model", "jkr", "--beta0", "1", "--mu", "5", "--machine-stiffness", "0"], "machine_stiffness"),
])
def test_bad_input_one_line_exit_2(capsys, argv, match):
    assert main(argv) == 2
    err = capsys.readouterr().err.strip()
    assert err.count("\n") == 0 and match in err


def test_pulloff_machine_stiffness(capsys):
    rec = _json(capsys, ["pulloff", "--model", "jkr", "--beta0", "1", "--mu", "5", "--machine-stiffness", "0.3",
                         "--json"])
    assert rec["control"] == "spring"
    assert rec["W_star"] == pytest.approx(compliance.pull_off_under_spring("jkr", mu=5.0, beta0=1.0, machine_stiffness=0.3)["W_star"],
                                          rel=TOL_CLI_API)
    si = _json(capsys, ["pulloff", "--model", "jkr", *PDMS, "--machine-stiffness", "1e-9", "--json"])
    assert si["force"] == pytest.approx(-1.5 * np.pi * si["effective_radius"] * 0.05, rel=1e-6)  # K -> 0: JKR


def test_curve_machine_stiffness(capsys):
    rec = _json(capsys, ["curve", "--model", "jkr", "--beta0", "1", "--mu", "5", "--n", "5",
                         "--machine-stiffness", "2", "--json"])
    np.testing.assert_allclose(rec["machine_displacement"],
                               np.array(rec["delta_star"]) + np.array(rec["W_star"]) / 2.0, rtol=1e-14)
    si = _json(capsys, ["curve", "--model", "jkr", *PDMS, "--n", "4", "--machine-stiffness", "50", "--json"])
    np.testing.assert_allclose(si["machine_displacement"], np.array(si["approach"]) + np.array(si["force"]) / 50.0,
                               rtol=1e-14)
    assert si["units"]["machine_displacement"] == "m"
