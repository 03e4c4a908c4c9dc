"""Every kind of netCDF file dhfield writes passes the IOOS compliance-checker (cf:1.10) with zero errors.

Issue 9, item 10.  Each writer is fed a small case (n = 8-16 cells, a few grid points) and its
file is checked in-process; the rules the issue names (no ``_FillValue`` on coordinates, no
``axis`` that reads x/y as longitude/latitude, flags on categorical variables, units on every
numeric variable) are also asserted directly, so that a checker upgrade cannot hide them.  A
negative control shows that the checker, as run here, does report such an error.
"""
from __future__ import annotations

import math
from types import SimpleNamespace

import netCDF4
import numpy as np
import pytest
import xarray as xr

from dhfield.analysis import compare, fields
from dhfield.models import dh_elliptic as model, dh_elliptic_periphery as periphery
from dhfield.core import schema
from dhfield.analysis import dimensional as dim
from dhfield.io import write_netcdf
from dhfield.io import curves as io_curves
from dhfield.io import periphery as io_periphery
from dhfield.io.compare import comparison_dataset
from dhfield.io.field import write_field

from compliance_checker import runner as checker  # the 'test' extra of pyproject.toml installs it

#: The checker's high-priority results are the "Errors" of its report (weight 3).
ERROR_WEIGHT = 3
THETA = np.linspace(0.0, 0.5 * np.pi, 4)


@pytest.fixture(scope="module")
def suite():
    cs = checker.CheckSuite()
    cs.load_all_available_checkers()
    return cs


def cf_errors(suite, path) -> list:
    """The failed high-priority (error) results of ``cf:1.10`` for ``path``, as (name, messages)."""
    ds = suite.load_dataset(str(path))
    try:
        results, _exceptions = suite.run_all(ds, ["cf:1.10"], skip_checks=[])["cf:1.10"]
    finally:
        ds.close()
    bad = []

    def walk(rs):
        for r in rs:
            if r.weight == ERROR_WEIGHT and r.value is not None:
                v = r.value
                ok = v[0] == v[1] if isinstance(v, tuple) else bool(v)
                if not ok:
                    bad.append((r.name, r.msgs))
            walk(r.children or [])

    walk(results)
    return bad


def _write(ds, path):
    return write_netcdf(ds, path)


def _curve_nd(tmp):
    return io_curves.write_load_curve(model.load_curve(mu=1.0, beta0=0.9, n=5), tmp / "curve.nc")


def _curve_si(tmp):
    p = dim.contact_parameters(2e6, 0.5, 2e6, 0.5, 5e-3, math.pi / 3, 0.04, 2.5e4)
    return io_curves.write_load_curve(dim.load_curve_si(p, n=5), tmp / "curve_si.nc")


def _pull_off_grid(tmp):
    mu, beta0 = np.array([0.5, 2.0]), np.array([0.8, 0.9, 1.0])
    p = model.pull_off(mu=mu[:, None], beta0=beta0[None, :])
    return _write(io_curves.pull_off_dataset({"W_star": p.W_star, "a_star_load": p.a_star}, beta0=beta0, mu=mu),
                  tmp / "pull_off.nc")


def _compare(tmp):
    recs = compare.compare(mu=2.0, beta0=0.9, models=("dh-elliptic", "dh-circular", "jkr", "md", "jkr-elliptic"),
                           check_closure=False)
    return _write(comparison_dataset(recs), tmp / "compare.nc")


def _field(tmp):
    return write_field(fields.model_case(16, 0.9, 1.0, 1.2), tmp / "field.nc", n_r=9, n_theta=5)


def _periphery(tmp):
    mu, beta0 = np.array([[1.0]]), np.array([[0.85]])
    po = model.pull_off(mu=mu, beta0=beta0)
    prof = periphery.periphery_at_pull_off(po, THETA)
    law = periphery.cohesive_law(po.a_star, po.c_star, po.ellipticity, po.v, THETA[[0, -1]], n_points=5)
    ds = io_periphery.pull_off_periphery_dataset(po, prof, law, beta0=beta0[:, 0], mu=mu[0])
    return io_periphery.write_dataset(ds, tmp / "periphery.nc")


def _equal_beta(tmp):
    # the writer only reads the arrays; synthetic ones (shape (beta0, mu)) keep the test fast
    shape = (2, 3)
    rng = np.random.default_rng(9)
    spread = SimpleNamespace(**{k: rng.random(shape) for k in (
        "work_ratio", "work_spread", "mean_work", "law_spread", "law_sup_spread", "separation_ratio",
        "width_ratio")})
    state = SimpleNamespace(**{k: rng.random(shape) for k in (
        "W_star", "a_star", "c_star", "beta_contact", "beta_adhesive", "work_major", "work_minor",
        "sigma0_minor")})
    ds = io_periphery.equal_beta_dataset(spread, {"paper": state, "two_axis": state}, beta0=[0.8, 0.9],
                                      mu=[0.5, 1.0, 2.0])
    return io_periphery.write_dataset(ds, tmp / "equal_beta.nc")


def _eq30(tmp):
    a = np.ones((2, 3))
    ds = io_periphery.eq30_dataset(a, a, a, a, a, beta0=[0.8, 0.9], mu=[0.5, 1.0, 2.0])
    return io_periphery.write_dataset(ds, tmp / "eq30.nc")


def _load_curve_periphery(tmp):
    lc = model.load_curve(beta0=0.9, mu=1.0, a_star=[0.5, 1.0])
    pr = periphery.periphery_along_curve(lc, THETA)
    ds = io_periphery.load_curve_periphery_dataset({(0.9, 1.0): lc}, {(0.9, 1.0): pr}, beta0=[0.9], mu=[1.0])
    return io_periphery.write_dataset(ds, tmp / "lc_periphery.nc")


def _grid_periphery(tmp):
    prof = SimpleNamespace(work_of_adhesion=np.ones(4), edge_separation=np.ones(4), contact_edge_gap=np.zeros(4))
    ds = io_periphery.grid_periphery_dataset(THETA, prof, {"bem": prof}, n=16)
    return io_periphery.write_dataset(ds, tmp / "grid_periphery.nc")


def _solution(tmp):
    from dhfield.bem import adhesive_pull_off
    from dhfield.io.solution import write_solution

    return write_solution(adhesive_pull_off(mu=1.0, beta0=0.9, n=8), tmp / "solution.nc")


def _sweep(tmp):
    from dhfield.sweep import config_from_mapping, run_sweep

    cfg = config_from_mapping({"axes": {"beta0": [0.8, 1.0], "mu": [0.5, 2.0]},
                               "sweep": {"models": ["dh-elliptic", "jkr"]}})
    return run_sweep(cfg, out=tmp / "sweep.nc", scheduler="synchronous", progress=False).path


WRITERS = {
    "load curve (nondimensional)": _curve_nd, "load curve (SI)": _curve_si, "pull-off grid": _pull_off_grid,
    "comparison": _compare, "field": _field, "periphery": _periphery, "equal-beta": _equal_beta,
    "eq30": _eq30, "load-curve periphery": _load_curve_periphery, "grid periphery": _grid_periphery,
    "BEM solution": _solution, "sweep": _sweep,
}


@pytest.fixture(scope="module")
def written(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("cf")
    return {name: make(tmp) for name, make in WRITERS.items()}


@pytest.mark.parametrize("name", list(WRITERS))
def test_compliance_checker_reports_no_error(suite, written, name):
    assert cf_errors(suite, written[name]) == []


@pytest.mark.parametrize("name", list(WRITERS))
def test_the_issue_rules_directly(written, name):
    with netCDF4.Dataset(written[name]) as nc:
        for vname, var in nc.variables.items():
            attrs = var.ncattrs()
            if vname in nc.dimensions:  # coordinate variable
                assert "_FillValue" not in attrs, (name, vname)
                assert "axis" not in attrs, (name, vname)
            categorical = "flag_values" in attrs
            if categorical:
                assert "flag_meanings" in attrs and len(var.flag_meanings.split()) == len(var.flag_values)
            if var.dtype == str or var.dtype.kind in "SU" or categorical:
                assert "units" not in attrs, (name, vname)  # labels and codes have no unit
            else:
                assert "units" in attrs and "long_name" in attrs, (name, vname)
                if vname in schema.VARIABLES:
                    assert var.units in (schema.units(vname), "1"), (name, vname)


def test_dimensions_are_in_the_canonical_order(written):
    for name in ("pull-off grid", "periphery", "equal-beta", "eq30", "sweep"):
        ds = xr.open_dataset(written[name])
        for v in ds.variables.values():
            assert v.dims == schema.order_dims(v.dims), (name, v.name, v.dims)
        ds.close()


def test_the_checker_does_catch_a_fill_value_on_a_coordinate(suite, tmp_path):
    # negative control: the rule of issue 9 item 10, written with xarray's defaults (no finalize)
    ds = xr.Dataset({"v": ("x", np.ones(3), {"units": "1", "long_name": "v"})},
                    coords={"x": ("x", np.arange(3.0), {"units": "m", "long_name": "x"})},
                    attrs={"Conventions": "CF-1.10"})
    ds.to_netcdf(tmp_path / "bad.nc", engine="netcdf4")
    errors = cf_errors(suite, tmp_path / "bad.nc")
    assert any("_FillValue" in " ".join(msgs) for _, msgs in errors), errors
