"""Tests of the netCDF output of a field case (dhfield.io.field) and the ``field`` CLI."""
from __future__ import annotations

import os
import pickle
import subprocess
import sys
import textwrap

import numpy as np
import pytest

from dhfield import PAPER_DOI
from dhfield.analysis import field_metrics, fields
from dhfield.io import read_netcdf
from dhfield.io.field import FIELD_VARIABLES, field_dataset, write_field

CASE = dict(beta0=0.9, mu=1.0, a_star=1.2)
N = 32
#: Polar gap difference on 32^2 cells: discretisation (4e-3 of max |omega| on the grid) plus
#: cubic-spline interpolation across the h ~ (r - r_ab)^1.5 edge; measured 1.6e-2.
RTOL_POLAR_GAP_32 = 0.03

_READER = textwrap.dedent("""
    import pickle, sys
    from dhfield.io import read_netcdf
    ds = read_netcdf(sys.argv[1])
    out = {"attrs": dict(ds.attrs),
           "vars": {k: (v.dims, v.values, dict(v.attrs)) for k, v in ds.variables.items()}}
    with open(sys.argv[2], "wb") as fh:
        pickle.dump(out, fh)
""")


@pytest.fixture(scope="module")
def case():
    return fields.model_case(N, **CASE)


def _same(a, b) -> bool:
    a, b = np.asarray(a), np.asarray(b)
    if a.dtype.kind in "fc":
        return a.shape == b.shape and np.array_equal(a, b, equal_nan=True)
    return a.shape == b.shape and np.array_equal(a, b)


def test_round_trip_in_a_fresh_process(case, tmp_path):
    ds = field_dataset(case)
    path = write_field(case, tmp_path / "case.nc")
    dump = tmp_path / "dump.pickle"
    res = subprocess.run([sys.executable, "-c", _READER, str(path), str(dump)], capture_output=True, text=True,
                         timeout=120, env=dict(os.environ))
    assert res.returncode == 0, res.stderr
    with open(dump, "rb") as fh:
        back = pickle.load(fh)
    # every variable and coordinate: identical values, dims and attributes
    assert set(back["vars"]) == set(ds.variables)
    for name, var in ds.variables.items():
        dims, values, attrs = back["vars"][name]
        assert dims == var.dims, name
        assert _same(values, var.values), name
        assert set(attrs) == set(var.attrs), name
        for k, v in var.attrs.items():
            assert _same(attrs[k], v), (name, k)
    # global attributes (history timestamp included)
    on_disk = read_netcdf(path).attrs
    assert set(back["attrs"]) == set(on_disk)
    for k in on_disk:
        assert _same(back["attrs"][k], on_disk[k]), k
    for k, v in ds.attrs.items():
        if k != "history":
            assert _same(back["attrs"][k], v), k


def test_cf_metadata_and_every_parameter(case):
    ds = field_dataset(case)
    for name in ds.variables:
        if name == "region":
            assert "flag_meanings" in ds[name].attrs
            continue
        assert ds[name].attrs.get("units") is not None, name
        assert ds[name].attrs.get("long_name"), name
    for name in FIELD_VARIABLES:
        assert ds[name].dims == ("y", "x")   # rows y, columns x: ds.gap_numerical.plot() the right way up
    assert ds.attrs["Conventions"].startswith("CF-")
    assert ds.attrs["source"].startswith("dhfield ")
    assert PAPER_DOI in ds.attrs["references"]
    assert "created by dhfield" in ds.attrs["history"]
    for key, value in dict(CASE, n=N, sampling="average", adhesive_semi_major=case.parameters["adhesive_semi_major"],
                           scaling=case.parameters["scaling"], half_width=case.parameters["half_width"]).items():
        assert ds.attrs[f"param_{key}"] == value, key
    assert ds.attrs["param_length_scale"].startswith("c_r")
    # nondimensional case: lengths in units of c_r
    assert ds["x"].attrs["units"] == "1"
    # differences are analytic minus numerical
    assert np.array_equal(ds["gap_difference"].values, (case.gap_analytic - case.gap_numerical).T)


def test_polar_variables_match_the_cartesian_ones(case):
    ds = field_dataset(case, n_r=41, n_theta=19)
    assert ds["gap_numerical_polar"].dims == ("r", "theta_p")
    assert ds["theta_p"].values[-1] == pytest.approx(np.pi / 2)
    # analytic and numerical gaps agree to the discretisation error on the polar grid too
    scale = np.abs(case.displacement_analytic).max()
    assert np.nanmax(np.abs(ds["gap_difference_polar"].values)) <= RTOL_POLAR_GAP_32 * scale
    # the annulus identity per ray is stored on the same theta_p coordinate
    ident = field_metrics.annulus_identity(case, n_theta=19)
    assert np.array_equal(ds["annulus_identity_error"].values, ident["rel_error"])


def test_write_field_of_a_model_case(tmp_path):
    out = write_field(fields.model_case(16, CASE["beta0"], CASE["mu"], CASE["a_star"]), tmp_path / "c.nc",
                      polar=False)
    ds = read_netcdf(out)
    assert ds.sizes["x"] == 16 and "gap_numerical_polar" not in ds
    assert sorted(p.name for p in tmp_path.iterdir()) == ["c.nc"]


def test_bad_output_paths_leave_nothing_behind(tmp_path):
    case = fields.model_case(16, 0.9, 1.0, 1.2)
    before = sorted(tmp_path.iterdir())
    with pytest.raises(ValueError, match="output path"):
        write_field(case, tmp_path / "missing" / "c.nc")
    with pytest.raises(ValueError, match="output path"):
        write_field(case, tmp_path)
    blocker = tmp_path / "file"
    blocker.write_text("keep")
    with pytest.raises(ValueError, match="output path"):
        write_field(case, blocker / "c.nc")
    assert sorted(tmp_path.iterdir()) == sorted(before + [blocker])


def test_bad_parameters_are_named_before_anything_is_solved():
    for kwargs, name in [(dict(beta0=1.5), "beta0"), (dict(mu=-1.0), "mu"), (dict(a_star=0.0), "a_star"),
                         (dict(n=7), "n")]:
        args = dict(CASE, n=16)
        args.update(kwargs)
        with pytest.raises(ValueError, match=name):
            fields.model_case(args["n"], args["beta0"], args["mu"], args["a_star"])


def test_cli_field(tmp_path, capsys):
    cli = pytest.importorskip("dhfield.cli")
    os.chdir(tmp_path)
    status = cli.main(["field", "--beta0", "0.9", "--mu", "1", "--a-star", "1.2", "--n", "16", "--out", "case.nc"])
    assert status == 0
    assert "wrote case.nc" in capsys.readouterr().out
    ds = read_netcdf(tmp_path / "case.nc")
    assert ds.attrs["param_beta0"] == 0.9 and ds.sizes["x"] == 16
    status = cli.main(["field", "--beta0", "0.9", "--mu", "1", "--a-star", "1.2", "--n", "4", "--out", "bad.nc"])
    assert status == 2
    assert "n must be an integer >= 8" in capsys.readouterr().err
    assert not (tmp_path / "bad.nc").exists()


def test_si_hertz_case_in_metres_and_pascals(tmp_path):
    case = fields.hertz_case(16, 2e-4, 0.8, effective_radius=0.05, reduced_modulus=2e9)
    ds = read_netcdf(write_field(case, tmp_path / "hertz.nc"))
    assert ds["x"].attrs["units"] == "m" and ds["r"].attrs["units"] == "m"
    assert ds["pressure"].attrs["units"] == "Pa" and ds["gap_numerical"].attrs["units"] == "m"
    assert ds.attrs["param_model"] == "hertz" and ds.attrs["param_reduced_modulus"] == 2e9
    assert "annulus_identity_error" not in ds and "param_length_scale" not in ds.attrs
    assert set(np.unique(ds["region"].values)) == {0, 2}


def test_metadata_from_the_schema_and_cf_rules(case, tmp_path):
    from dhfield.core import schema
    from dhfield.io.field import REGIONS

    ds = field_dataset(case, n_r=9, n_theta=5)
    for name, (quantity, qualifier) in FIELD_VARIABLES.items():
        ref = schema.attrs(quantity, nondimensional=True)
        assert ds[name].attrs["units"] == ref["units"] == "1"
        assert ds[name].attrs["long_name"] == f"{ref['long_name']}, {qualifier}"
    assert ds["x"].attrs["long_name"] == schema.attrs("x", nondimensional=True)["long_name"]
    assert ds["theta_p"].attrs["units"] == "rad"
    assert ds["region"].attrs["flag_meanings"] == " ".join(REGIONS) and "units" not in ds["region"].attrs
    assert set(np.unique(ds["region"].values)) <= {0, 1, 2}
    back = read_netcdf(write_field(case, tmp_path / "c.nc", n_r=9, n_theta=5))
    for name in ("x", "y", "r", "theta_p"):
        assert "axis" not in back[name].attrs and "_FillValue" not in back[name].encoding, name
