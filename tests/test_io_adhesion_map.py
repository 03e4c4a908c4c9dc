"""dhfield.io.adhesion_map: the adhesion map's Dataset, its atomic netCDF file and the round trip."""
from __future__ import annotations

import numpy as np
import pytest

from dhfield.analysis import adhesion_map as am
from dhfield.core import schema
from dhfield.io.adhesion_map import adhesion_map_dataset, read_adhesion_map, write_adhesion_map


@pytest.fixture(scope="module")
def small():
    # 3 angles x 3 mu, the six map models and one that refuses 30 deg (beta0 < 0.3)
    return am.adhesion_map([30.0, 60.0, 90.0], [0.1, 1.0, 10.0],
                           models=am.MAP_MODEL_NAMES + ("dh-elliptic-two-axis",))


def test_dataset_metadata_from_the_schema(small):
    ds = adhesion_map_dataset(small, command="pytest")
    assert tuple(ds["force_pi_r_dgamma"].dims) == ("model", "skew_angle_deg", "mu")
    for v in ("force_pi_r_dgamma", "relative_deviation", "skew_angle_deg", "mu", "beta0"):
        want = schema.attrs(v)
        assert ds[v].attrs["units"] == want["units"]
        assert ds[v].attrs["long_name"].startswith(want["long_name"])
    assert ds["skew_angle_deg"].attrs["units"] == "degree"
    assert ds["model_status"].attrs["flag_meanings"].split() == list(am.STATUS_MEANINGS)
    # every output says the reference is the recommended model md-elliptic, validated against the BEM only
    # in part
    assert "validated against the BEM only" in ds.attrs["reference_note"]
    assert ds["relative_deviation"].attrs["comment"] == ds.attrs["reference_note"]
    assert ds.attrs["reference_model"] == am.REFERENCE_MODEL and ds.attrs["param_command"] == "pytest"
    assert "Giudici" in ds.attrs["model_labels"] and "md-elliptic: MD elliptical (recommended)" in ds.attrs["model_labels"]
    assert "md-elliptic" in ds.attrs["reference_note"] and "elliptic-transition" not in str(ds.attrs)


def test_round_trip(small, tmp_path):
    p = write_adhesion_map(small, tmp_path / "map.nc")
    back = read_adhesion_map(p)
    for f in ("crossing_angle_deg", "mu", "beta0", "force", "deviation", "status", "reference_force",
              "validated"):
        np.testing.assert_array_equal(getattr(back, f), getattr(small, f), err_msg=f)
    assert back.models == small.models and back.notes == small.notes
    assert back.validated_beta0 == small.validated_beta0 and back.validated_mu == small.validated_mu
    assert back.reference_note == small.reference_note
    i = back.index("dh-elliptic-two-axis")
    assert back.status[i, 0, 0] == am.STATUS_MEANINGS.index("refused") and np.isnan(back.force[i, 0, 0])


def test_write_is_atomic_and_checked(small, tmp_path):
    with pytest.raises(ValueError, match="out"):
        write_adhesion_map(small, tmp_path / "no_such_dir" / "map.nc")
    assert list(tmp_path.iterdir()) == []  # nothing left behind
    with pytest.raises(ValueError, match="result"):
        adhesion_map_dataset({"force": 1})


def test_read_rejects_other_files(tmp_path):
    import xarray as xr

    from dhfield.io import write_netcdf

    p = write_netcdf(xr.Dataset({"x": ("mu", np.ones(2))}), tmp_path / "other.nc")
    with pytest.raises(ValueError, match="path"):
        read_adhesion_map(p)


def test_cf_compliance(small, tmp_path):
    # the writers' rule (tests/test_cf_compliance.py): no CF 1.10 error from the IOOS compliance checker
    from compliance_checker import runner as checker

    p = write_adhesion_map(small, tmp_path / "map.nc")
    cs = checker.CheckSuite()
    cs.load_all_available_checkers()
    ds = cs.load_dataset(str(p))
    try:
        results, _ = cs.run_all(ds, ["cf:1.10"], skip_checks=[])["cf:1.10"]
    finally:
        ds.close()
    bad = []

    def walk(rs):
        for r in rs:
            if r.weight == 3 and r.value is not None:
                v = r.value
                if not (v[0] == v[1] if isinstance(v, tuple) else bool(v)):
                    bad.append((r.name, r.msgs))
            walk(r.children or [])

    walk(results)
    assert bad == []
