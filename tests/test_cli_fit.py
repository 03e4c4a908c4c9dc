"""``dhfield fit`` on the command line: replicates, uncertainty flags, warnings, data files with units."""
from __future__ import annotations

import json
import math

import numpy as np

import pytest

from dhfield.cli import main


def _run(capsys, argv):
    code = main(argv)
    out, err = capsys.readouterr()
    return code, out, err


@pytest.mark.parametrize("argv, where", [(["fit", "--bogus"], ""), (["fit", "--model", "hertz"], "fit: ")])
def test_usage_error_prefix_is_not_doubled(capsys, argv, where):
    # issue 17: "dhfield: error: dhfield: unrecognized arguments: ..." (main and argparse both named the program)
    code, out, err = _run(capsys, argv)
    assert code == 2 and out == "" and err.count("\n") == 1
    assert err.startswith(f"dhfield: error: {where}") and "dhfield: error: dhfield" not in err, err


ISSUE = ["--youngs-modulus", "1.8e6", "--poisson-ratio", "0.49", "--cylinder-radius", "3e-3",
         "--skew-angle-deg", "60", "--adhesive-stress", "3e5"]


def test_replicate_forces_give_a_standard_error(capsys):
    # issue 17's must-show command: three replicates, the paper's model (which warns here, mu ~ 9.7)
    code, out, err = _run(capsys, ["fit", "--pull-off-force", "-0.80e-3", "-0.83e-3", "-0.78e-3", *ISSUE, "--json"])
    assert code == 0, err
    rec = json.loads(out)
    assert rec["n_replicates"] == 3 and rec["forces"] == [-0.80e-3, -0.83e-3, -0.78e-3]
    w, se = rec["work_of_adhesion"], rec["work_of_adhesion_stderr"]
    assert 0 < rec["replicate_stderr"] < se < 0.1 * w
    assert rec["work_of_adhesion_ci95"][0] < w < rec["work_of_adhesion_ci95"][1]
    assert rec["units"]["work_of_adhesion_stderr"] == "J m-2" and rec["units"]["forces"] == "N"
    assert rec["warning"] and err.startswith("dhfield: warning: ")


def test_input_uncertainty_flags_propagate(capsys):
    # JKR: dgamma = -F sin(theta)/(1.5 pi R_c): the contribution of R_c is dgamma std(R_c)/R_c (closed form)
    argv = ["fit", "--pull-off-force", "-0.80e-3", "-0.83e-3", "-0.78e-3", *ISSUE, "--model", "jkr",
            "--cylinder-radius-std", "0.1e-3", "--adhesive-stress-std", "0.5e5", "--youngs-modulus-std", "0.1e6",
            "--json"]
    code, out, err = _run(capsys, argv)
    assert code == 0, err
    rec = json.loads(out)
    c = rec["input_contributions"]
    assert c["cylinder_radius"] == pytest.approx(rec["work_of_adhesion"] * 0.1e-3 / 3e-3, rel=1e-5)
    assert c["adhesive_stress"] < 1e-10 and c["youngs_modulus"] < 1e-10  # JKR does not depend on them
    assert rec["input_stderr"] == pytest.approx(c["cylinder_radius"], rel=1e-6)
    assert rec["work_of_adhesion_stderr"] > rec["replicate_stderr"]


@pytest.mark.parametrize("argv, match", [
    (["--pull-off-force", "-1e-3", "-1.1e-3", *ISSUE, "--radii-std", "1e-4", "1e-4"], "--radii-std needs --radii"),
    (["--data", "d.csv", *ISSUE, "--adhesive-stress-std", "1e4"], "goes with --pull-off-force"),
])
def test_uncertainty_flag_misuse_is_one_line(capsys, tmp_path, monkeypatch, argv, match):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "d.csv").write_text("force,semi_major\n1e-3,1e-4\n2e-3,2e-4\n3e-3,3e-4\n")
    code, out, err = _run(capsys, ["fit", *argv])
    assert code == 2 and out == "" and err.count("\n") == 1 and match in err, err


def test_pull_off_fit_warns_exactly_like_pulloff(capsys):
    # issue 18 item 5: jkr at mu ~ 0.045 printed no warning in fit, while pulloff warns for the same state
    argv = ["--youngs-modulus", "1.8e6", "--poisson-ratio", "0.49", "--principal-radii", "3e-3", "3e-3"]
    code, out, err = _run(capsys, ["fit", "--pull-off-force", "-1e-3", *argv, "--adhesive-stress", "3e3",
                                   "--model", "jkr", "--json"])
    assert code == 0, err
    rec = json.loads(out)
    assert rec["mu"] < 0.1 and "jkr is validated for" in rec["warning"]
    fit_err = err
    code, out, err = _run(capsys, ["pulloff", *argv, "--model", "jkr", "--adhesive-stress", "3e3",
                                   "--work-of-adhesion", repr(rec["work_of_adhesion"]), "--json"])
    assert code == 0 and err == fit_err and json.loads(out)["warning"] == rec["warning"]


def test_curve_fit_with_the_default_model_warns(capsys, tmp_path):
    # issue 17: 'fit --data' with the default model printed nothing on stderr (beta0 = 0.48 at 60 degrees)
    from dhfield import dimensional as dim

    p = dim.contact_parameters(2e6, 0.5, 2e6, 0.5, 5e-3, math.pi / 3, 0.04, 2.5e4)
    a = p.length_unit * np.linspace(0.3, 3.0, 12)
    w = dim.load_curve_si(p, semi_major=a)["force"]
    (tmp_path / "d.csv").write_text("force,semi_major\n" + "".join(f"{x!r},{y!r}\n" for x, y in zip(map(float, w), map(float, a))))
    code, out, err = _run(capsys, ["fit", "--data", str(tmp_path / "d.csv"), "--youngs-modulus", "2e6",
                                   "--poisson-ratio", "0.5", "--cylinder-radius", "5e-3", "--skew-angle-deg", "60",
                                   "--json"])
    assert code == 0, err
    rec = json.loads(out)
    assert "dh-elliptic is validated for" in rec["warning"]
    assert err == f"dhfield: warning: {rec['warning']}\n"
