"""Load-curve and pull-off Datasets and tables: schema metadata, canonical dims, round trips, atomic writes."""
import json
import os

import numpy as np
import pandas as pd
import pytest

from dhfield.models import dh_elliptic as model
from dhfield.core import schema
from dhfield.io import read_netcdf
from dhfield.io.curves import CURVE_VARIABLES, load_curve_dataset, pull_off_dataset, write_load_curve
from dhfield.io.table import read_table, sidecar_path, write_table


def test_every_variable_takes_its_metadata_from_the_schema():
    ds = load_curve_dataset(model.load_curve(mu=1.0, beta0=0.9, n=5))
    assert tuple(ds.data_vars) == schema.LOAD_CURVE_KEYS
    for name in CURVE_VARIABLES:
        assert ds[name].attrs == schema.attrs(name, nondimensional=True), name
    assert ds["point"].attrs["units"] == "1"
    for key in ("Conventions", "source", "references", "history", "param_mu", "param_beta0", "param_model"):
        assert key in ds.attrs


def test_si_curve_has_si_units():
    n = 4
    curve = {k: np.linspace(1.0, 2.0, n) for k in schema.LOAD_CURVE_SI_KEYS}
    curve.update(model="dh-elliptic", beta0=0.5, mu=2.0, sin_skew=0.8)
    ds = load_curve_dataset(curve)
    assert tuple(ds.data_vars) == schema.LOAD_CURVE_SI_KEYS
    assert ds["force"].attrs["units"] == "N" and ds["semi_major"].attrs["units"] == "m"
    assert ds["approach"].attrs["units"] == "m" and ds.attrs["param_sin_skew"] == 0.8


def test_si_and_ellipticity_records_write_their_own_groups(tmp_path):
    """The one load-curve type (issue 16): an SI record writes the SI columns, the paper's model's
    record its header and free ellipticity as attributes."""
    from dhfield.analysis import dimensional

    p = dimensional.contact_parameters(1e6, 0.5, 1e6, 0.5, 0.01, 1.2, 0.05, 2e5)
    ds = load_curve_dataset(dimensional.load_curve_si(p, n=4, model="jkr"))
    assert tuple(ds.data_vars) == schema.LOAD_CURVE_SI_KEYS and ds["force"].attrs["units"] == "N"
    assert ds.attrs["param_model"] == "jkr" and ds.attrs["param_geometry"] == "circle"
    ds = load_curve_dataset(model.load_curve(mu=1.0, beta0=0.9, ellipticity=0.85, n=4))
    assert tuple(ds.data_vars) == schema.LOAD_CURVE_KEYS
    assert ds.attrs["param_ellipticity"] == 0.85 and ds.attrs["param_model"] == "dh-elliptic"


def test_round_trip_values_and_attrs(tmp_path):
    curve = model.load_curve(mu=2.0, beta0=0.8, n=9)
    path = write_load_curve(curve, tmp_path / "x.nc")
    ds = read_netcdf(path)
    ref = load_curve_dataset(curve)
    for name in list(CURVE_VARIABLES) + ["point"]:
        np.testing.assert_array_equal(ds[name].values, ref[name].values)
        assert ds[name].attrs == ref[name].attrs, name
    assert "_FillValue" not in ds["point"].encoding
    assert ds.attrs["param_beta0"] == 0.8


def test_csv_opens_with_pandas_defaults_and_has_a_sidecar(tmp_path):
    curve = model.load_curve(mu=2.0, beta0=0.8, n=7)
    path = write_load_curve(curve, tmp_path / "x.csv")
    frame = pd.read_csv(path)  # no arguments: plain header row, one row per point
    assert list(frame.columns) == list(CURVE_VARIABLES)
    for name in CURVE_VARIABLES:
        # repr() round trip: bit-identical floats
        np.testing.assert_array_equal(frame[name].to_numpy(), np.asarray(getattr(curve, name)))
    meta = json.loads(sidecar_path(path).read_text())
    for name in CURVE_VARIABLES:
        assert meta["columns"][name] == schema.attrs(name, nondimensional=True)
    assert meta["attributes"]["param_mu"] == 2.0 and "doi:" in meta["attributes"]["references"]
    frame2, meta2 = read_table(path, required=CURVE_VARIABLES)
    assert meta2 == meta and len(frame2) == 7
    assert sorted(p.name for p in tmp_path.iterdir()) == ["x.csv", "x.csv.json"]


def test_table_keeps_nan_and_strings(tmp_path):
    path = write_table({"model": ["jkr", "dmt"], "c_star": [np.nan, 1.5]}, tmp_path / "t.csv", title="t")
    frame = pd.read_csv(path)
    assert frame["model"].tolist() == ["jkr", "dmt"]
    assert np.isnan(frame["c_star"][0]) and frame["c_star"][1] == 1.5
    columns = json.loads(sidecar_path(path).read_text())["columns"]
    assert "units" not in columns["model"] and columns["c_star"]["units"] == "1"


def test_table_rejects_ragged_columns_and_unknown_names(tmp_path):
    with pytest.raises(ValueError, match="one length"):
        write_table({"a_star": [1.0, 2.0], "W_star": [1.0]}, tmp_path / "t.csv", title="t")
    with pytest.raises(ValueError, match="name must be one of"):
        write_table({"not_a_variable": [1.0]}, tmp_path / "t.csv", title="t")
    assert list(tmp_path.iterdir()) == []


def test_pull_off_dataset_is_on_beta0_mu():
    mu, beta0 = np.array([0.5, 1.0, 5.0]), np.array([0.8, 0.9])
    p = model.pull_off(mu=mu[:, None], beta0=beta0[None, :])
    ds = pull_off_dataset({"W_star": p.W_star, "a_star_displacement_control": p.a_star}, beta0=beta0, mu=mu)
    assert ds["W_star"].dims == schema.GRID_DIMS and ds["W_star"].shape == (2, 3)
    # transposed, not reshaped: the value at (beta0=0.8, mu=5) is that point's pull-off
    assert ds["W_star"].sel(beta0=0.8, mu=5.0).item() == model.pull_off(mu=5.0, beta0=0.8).W_star
    assert ds["W_star"].attrs["units"] == "1" and "at pull-off" in ds["W_star"].attrs["long_name"]
    assert "displacement control" in ds["a_star_displacement_control"].attrs["long_name"]
    same = pull_off_dataset({"W_star": p.W_star.T}, beta0=beta0, mu=mu, input_dims=("beta0", "mu"))
    np.testing.assert_array_equal(same["W_star"].values, ds["W_star"].values)
    with pytest.raises(ValueError, match="input_dims"):
        pull_off_dataset({"W_star": p.W_star}, beta0=beta0, mu=mu, input_dims=("mu", "x"))


def test_unknown_suffix_is_an_error(tmp_path):
    with pytest.raises(ValueError, match=r"\.nc or \.csv"):
        write_load_curve(model.load_curve(mu=1.0, beta0=0.9, n=3), tmp_path / "x.txt")
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize("name", ["x.nc", "x.csv"])
def test_written_files_get_default_permissions(tmp_path, name):
    path = write_load_curve(model.load_curve(mu=1.0, beta0=0.9, n=3), tmp_path / name)
    umask = os.umask(0)
    os.umask(umask)
    for p in [path] + ([sidecar_path(path)] if name.endswith(".csv") else []):
        assert (p.stat().st_mode & 0o777) == (0o666 & ~umask)


def test_failed_csv_write_leaves_nothing_and_keeps_the_old_file(tmp_path, monkeypatch):
    path = write_load_curve(model.load_curve(mu=1.0, beta0=0.9, n=3), tmp_path / "x.csv")
    before = {p.name: p.read_bytes() for p in tmp_path.iterdir()}

    def boom(*args, **kwargs):
        raise OSError("disk full")

    monkeypatch.setattr(json, "dump", boom)
    with pytest.raises(OSError, match="disk full"):
        write_load_curve(model.load_curve(mu=2.0, beta0=0.9, n=5), path)
    assert {p.name: p.read_bytes() for p in tmp_path.iterdir()} == before


@pytest.mark.parametrize("content, match", [
    ("a,b\n1,2\n", "no column 'force'"),
    ("force,semi_major\n1,nan\n", "column 'semi_major'.*not a finite number"),
    ("force,semi_major\n1,abc\n", "column 'semi_major'.*'abc'"),
    ("force,semi_major\n", "no data rows"),
    ("", "not a readable CSV"),
])
def test_bad_tables_name_the_file_and_column(tmp_path, content, match):
    path = tmp_path / "d.csv"
    path.write_text(content)
    with pytest.raises(ValueError, match=match) as err:
        read_table(path, required=("force", "semi_major"))
    assert "d.csv" in str(err.value) and "\n" not in str(err.value)


def test_pull_off_dataset_beta0_and_mu_are_keyword_only():
    """(beta0, mu) is GRID_DIMS' order, (mu, beta0) was the old one: a positional grid would swap them silently."""
    with pytest.raises(TypeError, match="positional"):
        pull_off_dataset([1.0], [0.9], {"W_star": [[1.0]]})
