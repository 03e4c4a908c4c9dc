"""``dhfield cycle`` and ``--machine-stiffness`` of ``pulloff``/``curve``: CLI equals API, one-line errors."""
import json

import numpy as np
import pytest

from dhfield.analysis import spring as compliance
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


# ============================================================================ cycle --model bem (issue 17)
#: The sphere at lambda = 1 (mu = 0.887) on N = 64.  The BEM cycle against MD's
#: (python -m verification.bem_spring --cycle --n 64 --lam 1 --k 1, and the rigid machine): jump in
#: +0.04 %, jump out -0.22 %, energy lost +0.11 % at K* = 1; jump out +0.52 % rigid.  2 % is ~4x the
#: worst (N = 64 puts ~10 cells across the Dugdale zone; the 1 % target at N = 256 is the
#: verification script's) and still catches a wrong spring term of the energy (W_o^2 - W_i^2)/(2K*),
#: 0.12 of 0.89 here.
BEM_MU, BEM_N, BEM_RTOL = 0.887, "64", 0.02


def test_bem_cycle_matches_md_and_plots(capsys, tmp_path):
    png = tmp_path / "bem_cycle.png"
    rc = main(["cycle", "--model", "bem", "--beta0", "1", "--mu", str(BEM_MU), "--n", BEM_N,
               "--machine-stiffness", "1", "--json", "--plot", str(png)])
    out = capsys.readouterr()
    assert rc == 0, out.err
    rec = json.loads(out.out)   # one JSON object: no "wrote" line after it
    ref = compliance.loading_cycle("md", beta0=1.0, mu=BEM_MU, machine_stiffness=1.0)
    assert rec["model"] == "bem" and rec["resolved"] and rec["n"] == 64
    for key, err in (("jump_in_W_star", "jump_in_W_star_error"), ("jump_out_W_star", "jump_out_W_star_error"),
                     ("energy_lost_star", "energy_lost_error_star")):
        assert rec[key] == pytest.approx(ref[key], rel=BEM_RTOL), key
        assert abs(rec[key] - ref[key]) <= rec[err] + 2e-3, key   # + the N = 64 lattice jaggedness
    # the force-free approach ends where the central gap reaches the Dugdale range: delta* = -1/mu (exact)
    assert rec["jump_in_start_delta_star"] == pytest.approx(ref["jump_in_start_delta_star"], rel=1e-12)
    assert rec["separation_delta_star"] == pytest.approx(rec["jump_out_delta_star"] + rec["jump_out_W_star"],
                                                         rel=1e-12)
    assert rec["units"]["energy_lost_star"] == "1" and rec["units"]["elapsed"] == "s"
    assert png.stat().st_size > 10_000


def test_bem_cycle_si_rigid_machine(capsys):
    """SI flags: K [N/m] -> K* as compliance.stiffness_star; the forces are W* x the load unit; against
    MD's SI cycle within BEM_RTOL (a rigid machine: the displacement-control jump out)."""
    from dhfield.analysis import dimensional

    sphere = ["--youngs-modulus", "1.8e6", "--poisson-ratio", "0.49", "--principal-radii", "3e-3", "3e-3",
              "--work-of-adhesion", "0.05", "--adhesive-stress", "2.5e4"]   # mu = 0.874
    rec = _json(capsys, ["cycle", "--model", "bem", *sphere, "--n", BEM_N, "--json"])
    params = dimensional.contact_parameters_from_principal_radii(1.8e6, 0.49, 1.8e6, 0.49, 3e-3, 3e-3, 0.05, 2.5e4)
    ref = compliance.loading_cycle_si(params, None, model="md")
    assert rec["jump_out_force"] == pytest.approx(rec["jump_out_W_star"] * float(params.load_unit), rel=1e-14)
    for key in ("jump_in_force", "jump_out_force", "energy_lost"):
        assert rec[key] == pytest.approx(ref[key], rel=BEM_RTOL), key
    assert rec["units"]["jump_out_force"] == "N" and rec["units"]["energy_lost"] == "J"


@pytest.mark.parametrize("argv, match", [
    (["--model", "bem", "--machine-stiffness", "0"], "machine-stiffness"),
    (["--model", "md", "--n", "64"], "--n"),
    (["--model", "bem", "--n", "15"], "n"),
])
def test_bem_cycle_bad_input(capsys, argv, match):
    assert main(["cycle", "--beta0", "1", "--mu", "1", *argv]) == 2
    err = capsys.readouterr().err.strip()
    assert err.count("\n") == 0 and match in err


@pytest.mark.parametrize("suffix", [".csv", ".nc"])
def test_curve_out_keeps_machine_displacement(capsys, tmp_path, suffix):
    """Issue 17: `curve --machine-stiffness K --out` dropped the machine_displacement column."""
    import xarray as xr

    from dhfield.io.table import read_table

    out = tmp_path / f"curve{suffix}"
    assert main(["curve", "--model", "jkr", *PDMS, "--n", "4", "--machine-stiffness", "50", "--out", str(out)]) == 0
    capsys.readouterr()
    printed = _json(capsys, ["curve", "--model", "jkr", *PDMS, "--n", "4", "--machine-stiffness", "50", "--json"])
    if suffix == ".nc":
        ds = xr.open_dataset(out)
        got, unit, k = ds["machine_displacement"].values, ds["machine_displacement"].attrs["units"], \
            ds.attrs["param_machine_stiffness"]
        ds.close()
    else:
        frame, meta = read_table(out)
        got, unit = frame["machine_displacement"].to_numpy(), meta["columns"]["machine_displacement"]["units"]
        k = meta["attributes"]["param_machine_stiffness"]
    np.testing.assert_array_equal(got, printed["machine_displacement"])
    assert unit == "m" and k == 50.0
