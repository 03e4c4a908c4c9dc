"""Comparison Dataset (dhfield.io.compare): schema metadata, CF flags, round trip of values and attrs."""
import numpy as np
import pytest

from dhfield.analysis import compare
from dhfield.core import schema
from dhfield.io import read_netcdf, write_netcdf
from dhfield.io.compare import COMPARISON_VARIABLES, GEOMETRIES, comparison_dataset

MODELS = ("dh-elliptic", "dh-circular", "jkr", "jkr-elliptic")


@pytest.fixture(scope="module")
def records():
    return compare.compare(mu=2.0, beta0=0.9, models=MODELS, check_closure=False)


def test_variables_follow_the_record_schema(records):
    ds = comparison_dataset(records)
    numeric = [k for k in schema.PULL_OFF_KEYS if k in ds.data_vars and k not in ("geometry", "at_zero_contact",
                                                                                   "warning")]
    assert tuple(numeric) == COMPARISON_VARIABLES
    for k in COMPARISON_VARIABLES:
        assert ds[k].attrs["units"] == "1" and ds[k].attrs["long_name"].startswith(schema.VARIABLES[k].long_name)
        np.testing.assert_array_equal(ds[k].values, [float(records[m][k]) for m in MODELS])
    assert list(ds["model"].values) == list(MODELS) and "units" not in ds["model"].attrs


def test_geometry_is_a_flag_variable(records):
    ds = comparison_dataset(records)
    g = ds["geometry"]
    assert g.attrs["flag_meanings"] == " ".join(GEOMETRIES) and list(g.attrs["flag_values"]) == [0, 1]
    decoded = [GEOMETRIES[c] for c in g.values]
    assert decoded == [records[m]["geometry"] for m in MODELS] == ["ellipse", "circle", "circle", "ellipse"]
    assert "units" not in g.attrs


def test_round_trip_values_and_attrs(records, tmp_path):
    ds = comparison_dataset(records)
    back = read_netcdf(write_netcdf(ds, tmp_path / "c.nc"))
    assert set(back.variables) == set(ds.variables)
    for name in ds.variables:
        if ds[name].dtype.kind == "f":
            np.testing.assert_array_equal(back[name].values, ds[name].values)
        else:
            assert list(back[name].values) == list(ds[name].values), name
        assert set(back[name].attrs) == set(ds[name].attrs), name
        for key, value in ds[name].attrs.items():
            assert np.array_equal(back[name].attrs[key], value), (name, key)
    assert back.attrs["param_control"] == "load" and back.attrs["param_mu"] == 2.0


def test_no_records_is_an_error():
    with pytest.raises(ValueError, match="records"):
        comparison_dataset({})
