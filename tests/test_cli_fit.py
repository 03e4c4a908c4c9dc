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
    code, out, err = _run(capsys, ["fit", "--pull-off-force", "-0.80e-3", "-0.83e-3", "-0.78e-3", *ISSUE,
                                   "--model", "dh-elliptic", "--json"])
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
    (["--pull-off-force", "-1e-3", "-1.1e-3", *ISSUE, "--adhesive-stress-std", "-1e4"], "--adhesive-stress-std must"),
    (["--pull-off-force", "-1e-3", "-1.1e-3", *ISSUE, "--skew-angle-deg-std", "nan"], "--skew-angle-deg-std must"),
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


@pytest.mark.parametrize("model", ["dh-elliptic", None])
def test_curve_fit_with_the_paper_model_warns(capsys, tmp_path, model):
    # issue 17: 'fit --data' with the then-default paper's model printed nothing on stderr (beta0 = 0.48 at
    # 60 degrees); it warns now.  The default is the recommended md-elliptic since issue 20, validated
    # everywhere: silent (None below).
    from dhfield.analysis import dimensional as dim

    p = dim.contact_parameters(2e6, 0.5, 2e6, 0.5, 5e-3, math.pi / 3, 0.04, 2.5e4)
    a = p.length_unit * np.linspace(0.3, 3.0, 12)
    w = dim.load_curve_si(p, semi_major=a, model=model or "md-elliptic")["force"]
    (tmp_path / "d.csv").write_text("force,semi_major\n" + "".join(f"{x!r},{y!r}\n" for x, y in zip(map(float, w), map(float, a))))
    code, out, err = _run(capsys, ["fit", "--data", str(tmp_path / "d.csv"), "--youngs-modulus", "2e6",
                                   "--poisson-ratio", "0.5", "--cylinder-radius", "5e-3", "--skew-angle-deg", "60",
                                   "--json"] + (["--model", model] if model else []))
    assert code == 0, err
    rec = json.loads(out)
    if model:
        assert "dh-elliptic is validated for" in rec["warning"]
        assert err == f"dhfield: warning: {rec['warning']}\n"
    else:
        assert rec["model"] == "md-elliptic" and rec["warning"] == "" and err == ""
        assert rec["work_of_adhesion"] == pytest.approx(0.04, rel=1e-6)  # its own synthetic curve back


# ------------------------------------------------------------------------- data files: units, degenerate data
PDMS = ["--youngs-modulus", "1.8e6", "--poisson-ratio", "0.49", "--cylinder-radius", "3e-3", "--skew-angle-deg", "60"]


@pytest.fixture(scope="module")
def curve():
    """The MD load curve [N], [m] of the issue's PDMS contact (dgamma = 50 mJ/m^2, sigma0 = 0.1 MPa), 15 points."""
    from dhfield.analysis import dimensional as dim

    p = dim.contact_parameters(1.8e6, 0.49, 1.8e6, 0.49, 3e-3, math.pi / 3, 0.05, 1e5)
    a = p.length_unit * np.linspace(0.3, 3.0, 15)
    c = dim.load_curve_si(p, semi_major=a, model="md")
    return p, np.asarray(c["force"], float), a, np.asarray(c["approach"], float)


def _write(path, header, *columns):
    rows = zip(*(map(float, c) for c in columns))
    path.write_text(",".join(header) + "\n" + "".join(",".join(repr(v) for v in r) + "\n" for r in rows),
                    encoding="utf-8")
    return str(path)


def test_units_in_the_header_are_converted(curve, tmp_path):
    from dhfield.io.fit import read_curve_data

    p, w, a, d = curve
    path = _write(tmp_path / "u.csv", ["load [mN]", "contact_size (\u00b5m)", "approach [nm]"], 1e3 * w, 1e6 * a,
                  1e9 * d)
    got = read_curve_data(path, p)
    # one multiplication by the unit's factor: rounding only (a few ulp)
    np.testing.assert_allclose(got["force"], w, rtol=1e-15)
    np.testing.assert_allclose(got["semi_major"], a, rtol=1e-15)
    np.testing.assert_allclose(got["approach"], d, rtol=1e-15)


def test_cli_fit_reads_units_from_the_header(curve, capsys, tmp_path):
    p, w, a, _ = curve
    si = _write(tmp_path / "si.csv", ["load", "contact_size"], w, a)
    mn = _write(tmp_path / "mn.csv", ["load [mN]", "contact_size [um]"], 1e3 * w, 1e6 * a)
    recs = []
    for path in (si, mn):
        code, out, err = _run(capsys, ["fit", "--data", path, *PDMS, "--model", "md", "--json"])
        assert code == 0, err
        recs.append(json.loads(out))
    # the same data in other units: the same fit (the least squares stop at xtol = 1e-14)
    assert recs[1]["work_of_adhesion"] == pytest.approx(recs[0]["work_of_adhesion"], rel=1e-8)
    assert recs[0]["work_of_adhesion"] == pytest.approx(0.05, rel=1e-8)


@pytest.mark.parametrize("scale, header, looks", [
    ((1e3, 1e6), ["load", "contact_size"], "these look like mN (column 'load') and um (column 'contact_size'); "
                                           "columns without a unit in the header are expected in N and m"),
    ((1e3, 1e3), ["force", "semi_major"], "these look like mN (column 'force') and mm (column 'semi_major')"),
    ((1e6, 1.0), ["force", "semi_major"], "these look like uN (column 'force')"),
    ((1e15, 1e6), ["force", "semi_major [um]"], "implausible magnitudes in SI units"),
])
def test_implausible_magnitudes_name_the_likely_unit(curve, capsys, tmp_path, scale, header, looks):
    # issue 17: a CSV in mN and um gave "a_star must be in [1e-06, 1e+06] ...; got 2044713.87"
    _, w, a, _ = curve
    path = _write(tmp_path / "d.csv", header, scale[0] * w, scale[1] * a)
    code, out, err = _run(capsys, ["fit", "--data", path, *PDMS])
    assert code == 2 and out == "" and err.count("\n") == 1 and "d.csv" in err
    assert looks in err, err


def test_unknown_unit_is_one_line(curve, capsys, tmp_path):
    _, w, a, _ = curve
    path = _write(tmp_path / "d.csv", ["force [kg]", "semi_major"], w, a)
    code, out, err = _run(capsys, ["fit", "--data", path, *PDMS])
    assert code == 2 and err.count("\n") == 1 and "column 'force [kg]': unknown force unit 'kg'" in err


def test_all_zero_forces_name_the_file_and_column(curve, capsys, tmp_path):
    import warnings

    # issue 18 item 14: four scipy RuntimeWarnings, then "array must not contain infs or NaNs"
    _, _, a, _ = curve
    path = _write(tmp_path / "zero.csv", ["force", "semi_major"], np.zeros(a.size), a)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        code, out, err = _run(capsys, ["fit", "--data", path, *PDMS])
    assert code == 2 and out == "" and err.count("\n") == 1, err
    assert "zero.csv" in err and "column 'force': every load is 0" in err


def test_copies_of_one_row_are_one_line(curve, capsys, tmp_path):
    # issue 18 item 3: five copies of one row gave a confident fit (+- 4.6e-10)
    _, w, a, _ = curve
    path = _write(tmp_path / "five.csv", ["force", "semi_major"], np.full(5, w[7]), np.full(5, a[7]))
    code, out, err = _run(capsys, ["fit", "--data", path, *PDMS])
    assert code == 2 and err.count("\n") == 1 and "fewer distinct points than the 2 parameters" in err
