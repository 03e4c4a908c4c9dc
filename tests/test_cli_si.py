"""The SI command line (``pulloff``/``curve`` with physical inputs), one record schema, the warning line."""
import json
import math

import numpy as np
import pytest

from dhfield.analysis import compare
from dhfield.analysis import dimensional as dim
from dhfield.cli import main
from dhfield.core.schema import (LOAD_CURVE_HEADER_KEYS, LOAD_CURVE_SI_KEYS, PULL_OFF_KEYS, PULL_OFF_SI_KEYS,
                                 PULL_OFF_TRUST_KEYS)

#: issue 10's worked example: PDMS cylinders (E = 2 MPa, nu = 0.5, R = 5 mm) crossed at 60 deg,
#: dgamma = 40 mJ/m^2, sigma0 = 0.5 MPa
PDMS_ARGS = ["--youngs-modulus", "2e6", "--poisson-ratio", "0.5", "--cylinder-radius", "5e-3",
             "--skew-angle-deg", "60", "--work-of-adhesion", "0.04", "--adhesive-stress", "0.5e6"]
#: CLI and API: the same computation; JSON round-trips doubles exactly (issue 10: "to 1e-12")
TOL_CLI_API = 1e-12


def _run(capsys, argv):
    rc = main(argv)
    out = capsys.readouterr()
    return rc, out.out, out.err


def _json(capsys, argv):
    rc, out, err = _run(capsys, argv)
    assert rc == 0, err
    return json.loads(out), err


def test_pdms_one_command_equals_api(capsys):
    # issue 10's worked example is about the paper's model (the default then): named explicitly
    rec, err = _json(capsys, ["pulloff", *PDMS_ARGS, "--model", "dh-elliptic", "--json"])
    p = dim.contact_parameters(2e6, 0.5, 2e6, 0.5, 5e-3, math.radians(60), 0.04, 0.5e6)
    api = dim.pull_off_force(p, model="dh-elliptic")
    assert rec["force"] == pytest.approx(float(api["force"]), rel=TOL_CLI_API)
    for k in ("semi_major", "semi_minor", "adhesive_semi_major", "adhesive_semi_minor", "approach",
              "beta0", "mu", "sin_skew"):
        assert rec[k] == pytest.approx(float(api[k]), rel=TOL_CLI_API), k
    assert list(rec)[:-1] == list(PULL_OFF_SI_KEYS + PULL_OFF_TRUST_KEYS) and list(rec)[-1] == "units"
    assert rec["units"]["force"] == "N" and rec["units"]["semi_major"] == "m"
    assert rec["sin_skew"] == pytest.approx(math.sin(math.radians(60)), rel=1e-12)
    # the paper's model warns in one line on stderr (against the recommended model since issue 20)
    lines = [ln for ln in err.splitlines() if ln]
    assert len(lines) == 1 and lines[0].startswith("dhfield: warning:") and "md-elliptic" in lines[0]
    assert rec["warning"] in lines[0]


def test_pdms_two_axis_no_warning(capsys):
    # sigma0 = 0.45 MPa (mu = 19.5): inside the closures' accepted mu <= 30 (dhfield.models.dh_elliptic_closure.CLOSURE_MU_RANGE)
    args = PDMS_ARGS[:-1] + ["0.45e6"]
    rec, err = _json(capsys, ["pulloff", *args, "--model", "dh-elliptic-two-axis", "--json"])
    assert err == "" and rec["warning"] == ""
    assert rec["model"] == "dh-elliptic-two-axis" and rec["v"] is None  # n/a is null, not missing


def test_no_warning_near_the_circle(capsys):
    rec, err = _json(capsys, ["pulloff", "--beta0", "0.99", "--mu", "1", "--json"])
    assert err == "" and rec["warning"] == ""


def test_every_model_same_keys(capsys):
    """Schema test (issue 10): every model's --json has the same keys, in the same order."""
    keys = set()
    for name in compare.MODEL_NAMES:
        rec, _ = _json(capsys, ["pulloff", "--beta0", "0.9", "--mu", "1", "--model", name, "--json"])
        assert list(rec) == list(PULL_OFF_KEYS + PULL_OFF_TRUST_KEYS) + ["units"], name
        keys.add(tuple(rec))
    assert len(keys) == 1
    for name in ("jkr", "md", "jkr-elliptic"):  # SI: the same, with the SI keys
        rec, _ = _json(capsys, ["pulloff", *PDMS_ARGS, "--model", name, "--json"])
        assert list(rec) == list(PULL_OFF_SI_KEYS + PULL_OFF_TRUST_KEYS) + ["units"], name


def test_geometry_flags_agree(capsys):
    base = ["pulloff", "--model", "jkr-elliptic", "--json", "--youngs-modulus", "2e6", "--poisson-ratio", "0.5",
            "--work-of-adhesion", "0.04", "--adhesive-stress", "0.5e6"]
    equal, _ = _json(capsys, base + ["--cylinder-radius", "5e-3", "--skew-angle-deg", "60"])
    radii, _ = _json(capsys, base + ["--radii", "5e-3", "5e-3", "--skew-angle-deg", "60"])
    assert radii["force"] == pytest.approx(equal["force"], rel=1e-13)
    # unequal cylinders at 90 deg: R' = R1, R'' = R2, in either order
    crossed, _ = _json(capsys, base + ["--radii", "2e-3", "5e-3", "--skew-angle-deg", "90"])
    principal, _ = _json(capsys, base + ["--principal-radii", "5e-3", "2e-3"])
    assert crossed["force"] == pytest.approx(principal["force"], rel=1e-13)
    assert (crossed["r_major"], crossed["r_minor"]) == pytest.approx((5e-3, 2e-3), rel=1e-15)
    # the second body defaults to the first
    second, _ = _json(capsys, base + ["--principal-radii", "5e-3", "2e-3", "--youngs-modulus-2", "2e6",
                                      "--poisson-ratio-2", "0.5"])
    assert second["force"] == principal["force"]


def test_si_unit_neutrality_through_the_cli(capsys):
    """The same contact in mm, N and MPa: force in N unchanged, lengths in mm."""
    si, _ = _json(capsys, ["pulloff", *PDMS_ARGS, "--model", "md", "--json"])
    mm, _ = _json(capsys, ["pulloff", "--model", "md", "--json", "--youngs-modulus", "2", "--poisson-ratio", "0.5",
                           "--cylinder-radius", "5", "--skew-angle-deg", "60", "--work-of-adhesion", "0.04e-3",
                           "--adhesive-stress", "0.5"])
    assert mm["force"] == pytest.approx(si["force"], rel=1e-10)
    assert mm["semi_major"] * 1e-3 == pytest.approx(si["semi_major"], rel=1e-10)


@pytest.mark.parametrize("argv, needle", [
    (["pulloff", "--beta0", "0.5", *PDMS_ARGS], "not both"),
    (["pulloff", "--mu", "2"], "--beta0"),
    (["pulloff", *PDMS_ARGS[:-2]], "--adhesive-stress"),
    (["pulloff", *PDMS_ARGS, "--principal-radii", "1", "2"], "exactly one"),
    (["pulloff", *[a for a in PDMS_ARGS if a not in ("--skew-angle-deg", "60")]], "--skew-angle-deg"),
    (["pulloff", *PDMS_ARGS[:7], "120", *PDMS_ARGS[8:]], "skew-angle-deg"),
    (["pulloff", *PDMS_ARGS[:3], "0.7", *PDMS_ARGS[4:]], "poisson_ratio"),
    (["curve", "--beta0", "0.9", "--mu", "1", "--load-min", "1", "--load-max", "2"], "physical inputs"),
    (["curve", *PDMS_ARGS, "--load-min=-1", "--load-max", "1"], "pull-off"),
    (["curve", *PDMS_ARGS, "--load-min", "1"], "--load-max"),
    (["curve", "--beta0", "0.9", "--mu", "1", "--model", "dh-elliptic-jkr-beta"], "model"),
])
def test_bad_input_one_line(capsys, argv, needle):
    rc, out, err = _run(capsys, argv)
    assert rc == 2 and out == ""
    assert len(err.strip().splitlines()) == 1 and "Traceback" not in err
    assert needle in err


def test_curve_json_nondimensional(capsys):
    rec, _ = _json(capsys, ["curve", "--beta0", "0.8", "--mu", "2", "--model", "jkr-elliptic", "--n", "5", "--json"])
    ref = compare.load_curve("jkr-elliptic", mu=2.0, beta0=0.8, n=5)
    assert list(rec)[:-1] == list(ref)
    np.testing.assert_allclose(rec["W_star"], ref["W_star"], rtol=1e-15)


def test_curve_si_over_loads(capsys):
    rec, _ = _json(capsys, ["curve", *PDMS_ARGS, "--load-min=-5e-4", "--load-max", "1e-3", "--n", "4", "--json"])
    assert list(rec)[:-1] == list(LOAD_CURVE_HEADER_KEYS + LOAD_CURVE_SI_KEYS)
    np.testing.assert_allclose(rec["force"], np.linspace(-5e-4, 1e-3, 4), rtol=1e-9, atol=1e-15)
    assert rec["units"]["force"] == "N" and rec["units"]["semi_major"] == "m"
    size, _ = _json(capsys, ["curve", *PDMS_ARGS, "--semi-major-min", "2e-4", "--semi-major-max", "4e-4", "--n", "3",
                             "--json"])
    np.testing.assert_allclose(size["semi_major"], [2e-4, 3e-4, 4e-4], rtol=1e-15)


def test_curve_si_writes_netcdf(tmp_path, capsys):
    from dhfield.io import read_netcdf

    out = tmp_path / "si.nc"
    rc, _, err = _run(capsys, ["curve", *PDMS_ARGS, "--model", "jkr", "--n", "5", "--out", str(out)])
    assert rc == 0, err
    ds = read_netcdf(out)
    assert ds["force"].attrs["units"] == "N" and ds["semi_major"].attrs["units"] == "m"


def test_compare_si_equals_pulloff_si(capsys):
    """`compare` with physical inputs: every model in SI, the same record as `pulloff --model`."""
    payload, err = _json(capsys, ["compare", *PDMS_ARGS, "--json"])
    assert [r["model"] for r in payload["models"]] == list(compare.MODEL_NAMES)
    assert all(list(r) == list(PULL_OFF_SI_KEYS + PULL_OFF_TRUST_KEYS) for r in payload["models"])
    assert payload["units"]["force"] == "N"
    assert len([ln for ln in err.splitlines() if ln]) == 2  # dh-elliptic's line, then one for the others
    by_name = {r["model"]: r for r in payload["models"]}
    p = dim.contact_parameters(2e6, 0.5, 2e6, 0.5, 5e-3, math.radians(60), 0.04, 0.5e6)
    for name in ("jkr-elliptic", "md", "dmt"):
        api = dim.pull_off_force(p, model=name)
        assert by_name[name]["force"] == pytest.approx(float(api["force"]), rel=TOL_CLI_API), name


@pytest.mark.parametrize("inputs, header", [
    (["--beta0", "0.8", "--mu", "1"], ("[Eq. 34]", "[c_r]", "[c_r]", "[c_r]", "[c_r]", "[1]", "[c_r^2/R]")),
    (PDMS_ARGS, ("[N]", "[m]", "[m]", "[m]", "[m]", "[Eq. 34]")),
])
def test_compare_table_says_its_units(capsys, inputs, header):
    """Issue 17: the compare table had no units header.  A 'units' row under the column names (SI
    units with physical inputs); nondimensionally also a line naming the paper's scales."""
    rc, out, _ = _run(capsys, ["compare", *inputs])
    lines = out.splitlines()
    assert rc == 0
    row = next(line for line in lines if line.startswith("units"))
    # one label per column, in column order; then the departure from the recommended model and the error, in %
    assert row.split()[1:] == " ".join(header).split() + ["[%]", "[%]"]
    assert lines.index(row) == next(i for i, line in enumerate(lines) if line.startswith("model")) + 1
    assert ("c_r = (R^2 dgamma/E*)^(1/3)" in out) == (inputs[0] == "--beta0")


def test_pulloff_text_has_no_rounding_noise(capsys):
    """Issue 17: the text output printed sin_skew 0.49999999999999994 at 30 deg (repr of a float one
    ulp from sin 30 deg = 1/2).  Now 10 significant digits, as curve, cycle and fit."""
    argv = [*PDMS_ARGS[:-4], "--work-of-adhesion", "0.04", "--adhesive-stress", "0.5e6", "--model", "jkr-elliptic"]
    argv[argv.index("--skew-angle-deg") + 1] = "30"
    rc, out, _ = _run(capsys, ["pulloff", *argv])
    row = {line.split()[0]: line.split()[1] for line in out.splitlines() if len(line.split()) > 1}
    assert rc == 0 and row["sin_skew"] == "0.5"
    numbers = [v for v in row.values() if v.lstrip("-")[:1].isdigit()]
    assert numbers and all(len(v.lstrip("-0.").replace(".", "").split("e")[0]) <= 10 for v in numbers), numbers
