"""Joint fit over crossing angles: dhfield.analysis.fit.fit_joint and ``dhfield fit --data`` with an angle column."""
from __future__ import annotations

import json
import math
import warnings

import numpy as np
import pytest

from dhfield.analysis import compare
from dhfield.analysis import dimensional as dim
from dhfield.cli import main

# the PDMS contact of issue 40: two 3 mm cylinders, E = 1.8 MPa, nu = 0.49
MATERIAL = dict(youngs_modulus_1=1.8e6, poisson_ratio_1=0.49, youngs_modulus_2=1.8e6, poisson_ratio_2=0.49,
                cylinder_radius=3e-3)
WORK, STRESS = 0.045, 3e5
CLI_INPUTS = ["--youngs-modulus", "1.8e6", "--poisson-ratio", "0.49", "--cylinder-radius", "3e-3"]
ANGLES = (20.0, 40.0, 60.0, 90.0)


def contact_at(angle_deg):
    return dim.contact_parameters(**MATERIAL, skew_angle=math.radians(angle_deg), work_of_adhesion=WORK,
                                  max_adhesive_stress=STRESS)


def _synthetic(seed=40, replicates=5, noise=0.03):
    """4 angles x 5 replicate pull-off forces of the recommended model, times 1 + 0.03 z (seeded)."""
    angles = np.repeat(ANGLES, replicates)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        exact = {a: float(dim.pull_off_force(contact_at(a), compare.RECOMMENDED_MODEL)["force"]) for a in ANGLES}
    rng = np.random.default_rng(seed)
    return angles, np.array([exact[a] for a in angles]) * (1.0 + noise * rng.standard_normal(angles.size))


def _write(path, header, rows):
    path.write_text(header + "\n" + "\n".join(",".join(f"{x:.12g}" for x in row) for row in rows) + "\n")
    return str(path)


def test_cli_joint_fit_recovers_work_of_adhesion_within_two_standard_errors(tmp_path, capsys):
    # issue 40's must-show: 4 angles x 5 replicates, recommended model, 3 % seeded noise, a plot
    angles, forces = _synthetic()
    csv = _write(tmp_path / "po.csv", "skew_angle_deg,force [mN]", zip(angles, forces * 1e3))
    png = tmp_path / "fit.png"
    code = main(["fit", "--data", csv, *CLI_INPUTS, "--adhesive-stress", "3e5", "--plot", str(png), "--json"])
    out, err = capsys.readouterr()
    assert code == 0, err
    rec = json.loads(out)
    assert rec["model"] == compare.RECOMMENDED_MODEL and rec["kind"] == "pull_off"
    assert rec["n_points"] == 20 and rec["skew_angles_deg"] == list(ANGLES) and rec["dof"] == 19
    w, se, (lo, hi) = rec["work_of_adhesion"], rec["work_of_adhesion_stderr"], rec["work_of_adhesion_ci95"]
    assert abs(w - WORK) <= 2.0 * se
    assert 0.0 < se < 0.01 * w  # 3 % noise over 20 rows: about 0.03/sqrt(20) = 0.7 %
    # the interval is t-based (t(0.975, 19) = 2.093), the standard error is not inflated
    from scipy import stats
    assert (hi - lo) / 2 == pytest.approx(stats.t.ppf(0.975, 19) * se, rel=1e-9)
    assert rec["units"]["work_of_adhesion_stderr"] == "J m-2" and rec["units"]["skew_angles_deg"] == "deg"
    # mu changes with the angle (R = sqrt(R'R'') does), the material does not
    assert len(set(round(m, 6) for m in rec["mu"])) == 4
    for suffix in (".png", ".svg", ".pdf"):
        assert png.with_suffix(suffix).stat().st_size > 0


def test_joint_estimate_is_the_replicate_mean_and_stderr_is_s_over_sqrt_n():
    # independent: each force inverted on its own (fit_work_of_adhesion, one root per row); on the JKR
    # side d ln|F|/d ln dgamma is 1 to within 1e-3, so the least-squares estimate in ln dgamma is the
    # mean of the 20 ln dgamma_i and its standard error s/sqrt(n) of them
    from dhfield.analysis.fit import fit_joint, fit_work_of_adhesion

    angles, forces = _synthetic()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        res = fit_joint(forces, angles, contact_at, max_adhesive_stress=STRESS)
        logs = np.log([fit_work_of_adhesion(f, contact_at(a), max_adhesive_stress=STRESS).work_of_adhesion
                       for a, f in zip(angles, forces)])
    mean = math.exp(float(np.mean(logs)))
    plain = mean * float(np.std(logs, ddof=1)) / math.sqrt(logs.size)
    assert res.work_of_adhesion == pytest.approx(mean, rel=1e-5)
    assert res.work_of_adhesion_stderr == pytest.approx(plain, rel=1e-3)
    assert res.fitted == ("work_of_adhesion",) and res.success


def test_joint_load_curves_recover_both_parameters():
    # noiseless load curves at three angles: dgamma and sigma0 back to rounding from a start 1.5 x off
    from dhfield.analysis.fit import fit_joint

    angles, sizes, loads = [], [], []
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for a in (30.0, 60.0, 90.0):
            p = contact_at(a)
            c = dim.load_curve_si(p, n=200)
            a_min = float(np.asarray(c["semi_major"])[np.argmin(np.asarray(c["force"]))])  # pull-off size
            pts = np.linspace(0.9 * a_min, 3.0 * a_min, 4)
            angles += [a] * 4
            sizes += list(pts)
            loads += list(np.asarray(dim.load_curve_si(p, semi_major=pts)["force"]))
        res = fit_joint(loads, angles, contact_at, contact_size=sizes, initial=(0.03, 2e5))
    assert res.kind == "load_curve" and res.success, res.message
    assert res.work_of_adhesion == pytest.approx(WORK, rel=1e-8)
    assert res.max_adhesive_stress == pytest.approx(STRESS, rel=1e-7)
    a, w = res.model_curve(60.0, 5)
    assert a.size == 5 and np.all(np.isfinite(w))


def test_sigma0_from_pull_off_on_the_jkr_side_is_flagged_not_identifiable(tmp_path, capsys):
    # mu 11-16: the pull-off force barely depends on sigma0; without --adhesive-stress the fit is flagged
    angles, forces = _synthetic()
    csv = _write(tmp_path / "po.csv", "skew_angle_deg,force", zip(angles, forces))
    code = main(["fit", "--data", csv, *CLI_INPUTS, "--json"])
    out, err = capsys.readouterr()
    assert code == 3
    rec = json.loads(out)
    assert "max_adhesive_stress" in rec["not_identifiable"] and rec["max_adhesive_stress"] is None
    assert "dhfield: fit is not an answer: " in err and "--adhesive-stress" in err


@pytest.mark.parametrize("header, rows, extra, needle", [
    ("skew_angle_deg,force", [(120.0, -1e-3), (60.0, -1e-3)], [], "(0, 90] degrees"),
    ("skew_angle_deg,force", [(60.0, 1e-3), (60.0, -1e-3)], [], "must be negative"),
    ("skew_angle [grad],force", [(60.0, -1e-3), (30.0, -1e-3)], [], "unknown angle unit"),
    ("skew_angle_deg,force", [(60.0, -1e-3), (30.0, -1e-3)], ["--skew-angle-deg", "60"], "--skew-angle-deg goes"),
])
def test_bad_joint_input_is_one_line_exit_2(tmp_path, capsys, header, rows, extra, needle):
    csv = _write(tmp_path / "bad.csv", header, rows)
    code = main(["fit", "--data", csv, *CLI_INPUTS, "--adhesive-stress", "3e5", *extra])
    out, err = capsys.readouterr()
    assert code == 2 and out == "" and err.count("\n") == 1, err
    assert needle in err
