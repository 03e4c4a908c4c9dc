"""The standard maps of a sweep: files written, values drawn, bad input."""
from __future__ import annotations

import numpy as np
import pytest
from matplotlib.figure import Figure

from dhfield import plotting
from dhfield.cli import main
from dhfield.sweep import config_from_mapping, run_sweep

#: The closed-form models are evaluated to rounding.
CLOSED_FORM_RTOL = 1e-14


@pytest.fixture(scope="module")
def sweep(tmp_path_factory):
    d = tmp_path_factory.mktemp("plot")
    cfg = config_from_mapping({"axes": {"beta0": [0.5, 0.75, 1.0], "mu": {"geomspace": [0.1, 10, 4]}},
                               "sweep": {"models": ["jkr", "dmt", "jkr-elliptic"]}})
    return run_sweep(cfg, out=d / "s.nc", scheduler="synchronous", progress=False)


def test_error_map_draws_the_relative_difference(sweep):
    ax = Figure().add_subplot()
    plotting.error_map(sweep.dataset, "dmt", "jkr", ax)
    drawn = np.asarray(ax.collections[0].get_array())
    # DMT W* = -1, JKR W* = -3/4 (closed forms): (W_dmt - W_jkr)/|W_jkr| = -1/3 everywhere.
    np.testing.assert_allclose(drawn, -1.0 / 3.0, rtol=CLOSED_FORM_RTOL)
    assert drawn.size == 3 * 4


def test_pull_off_and_ellipticity_maps(sweep):
    ax = Figure().add_subplot()
    plotting.pull_off_map(sweep.dataset, "jkr", ax)
    np.testing.assert_array_equal(np.asarray(ax.collections[0].get_array()), -0.75)
    ax = Figure().add_subplot()
    plotting.ellipticity_map(sweep.dataset, "jkr-elliptic", ax)
    ell = np.asarray(ax.collections[0].get_array()).reshape(3, 4)
    assert ell[-1] == pytest.approx(1.0, rel=CLOSED_FORM_RTOL)  # circle at beta0 = 1
    assert np.all(ell[0] < ell[-1])  # the contact stays elliptical at pull-off for beta0 < 1
    assert ax.get_xscale() == "log"


def test_cli_writes_png_and_svg(sweep, tmp_path, capsys):
    assert main(["plot", str(sweep.path), "--out", str(tmp_path), "--reference", "jkr"]) == 0
    names = sorted(p.name for p in tmp_path.iterdir())
    assert names == sorted(f"s_{kind}.{fmt}" for kind in ("pull_off", "error", "ellipticity")
                           for fmt in ("png", "svg"))
    assert (tmp_path / "s_error.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert "<svg" in (tmp_path / "s_error.svg").read_text()[:2000]
    assert capsys.readouterr().out.count("wrote ") == 6


def test_default_reference_is_the_papers_model():
    import xarray as xr

    ds = xr.Dataset(coords={"model": ["md", "dh-elliptic"]})
    assert plotting.default_reference(ds) == "dh-elliptic"
    ds = xr.Dataset(coords={"model": ["md", "dh-elliptic", "bem-adhesive"]})
    assert plotting.default_reference(ds) == "bem-adhesive"


@pytest.mark.parametrize("extra, words", [(["--reference", "hertz"], "reference"), ([], None)])
def test_cli_bad_input(sweep, tmp_path, capsys, extra, words):
    if words is None:  # a file that is not a sweep
        bad = tmp_path / "x.nc"
        bad.write_text("not netcdf")
        argv, words = ["plot", str(bad)], "not a readable netCDF"
    else:
        argv = ["plot", str(sweep.path), "--out", str(tmp_path), *extra]
    assert main(argv) == 2
    err = capsys.readouterr().err.strip()
    assert words in err and "\n" not in err
    assert not list(tmp_path.glob("*.png"))
