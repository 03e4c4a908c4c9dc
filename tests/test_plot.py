"""The standard maps of a sweep: files written, values drawn, bad input."""
from __future__ import annotations

import numpy as np
import pytest
from matplotlib.figure import Figure

from dhfield.io import sweep_maps as plotting
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
    # DMT W* = -1, JKR W* = -3/4 (closed forms): the report's convention, model/ref - 1 in percent,
    # is 100 (-1/(-3/4) - 1) = +100/3 everywhere (positive: DMT's pull-off is the stronger).
    np.testing.assert_allclose(drawn, 100.0 / 3.0, rtol=CLOSED_FORM_RTOL)
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


def test_cli_writes_png_svg_and_pdf(sweep, tmp_path, capsys):
    assert main(["plot", str(sweep.path), "--out", str(tmp_path), "--reference", "jkr"]) == 0
    names = sorted(p.name for p in tmp_path.iterdir())
    assert names == sorted(f"s_{kind}.{fmt}" for kind in ("pull_off", "error", "ellipticity")
                           for fmt in ("png", "svg", "pdf"))
    assert (tmp_path / "s_error.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert "<svg" in (tmp_path / "s_error.svg").read_text()[:2000]
    assert (tmp_path / "s_error.pdf").read_bytes()[:5] == b"%PDF-"
    assert capsys.readouterr().out.count("wrote ") == 9


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


def _synthetic(n_ell, n_mu, models=("jkr", "dmt"), mu=None):
    """A sweep-shaped Dataset with closed-form values (JKR -3/4, DMT -1), no computation."""
    import xarray as xr

    mu = np.geomspace(0.1, 10, n_mu) if mu is None else np.asarray(mu, float)
    beta0 = np.linspace(0.2, 1.0, n_ell)
    w = np.stack([np.full((n_ell, mu.size), -0.75 if m == "jkr" else -1.0) for m in models])
    return xr.Dataset({"W_star": (("model", "beta0", "mu"), w), "ellipticity": (("model", "beta0", "mu"), 0 * w + 1)},
                      coords={"model": list(models), "beta0": beta0, "mu": mu})


def test_plot_checks_every_output_before_writing_any(sweep, tmp_path, capsys):
    """Issue 18 item 6: with s_error.svg a directory, plot replaced three other files and then
    exited 2, leaving old and new mixed.  Now it refuses before writing anything."""
    old = {}
    for kind in ("pull_off", "ellipticity"):
        for fmt in ("png", "svg"):
            p = tmp_path / f"s_{kind}.{fmt}"
            p.write_bytes(b"old")
            old[p] = b"old"
    (tmp_path / "s_error.png").write_bytes(b"old")
    old[tmp_path / "s_error.png"] = b"old"
    (tmp_path / "s_error.svg").mkdir()
    assert main(["plot", str(sweep.path), "--out", str(tmp_path), "--reference", "jkr"]) == 2
    err = capsys.readouterr().err.strip()
    assert "\n" not in err and "s_error.svg" in err
    for p, content in old.items():
        assert p.read_bytes() == content, p
    assert not list(tmp_path.glob(".*.part"))


def test_plot_creates_its_output_directory(sweep, tmp_path, capsys):
    """Issue 17: `dhfield plot --out maps2` refused a directory that did not exist yet."""
    out = tmp_path / "maps2" / "deeper"
    assert main(["plot", str(sweep.path), "--out", str(out), "--reference", "jkr"]) == 0
    assert len(list(out.glob("s_*.png"))) == 3


def test_log_axis_cells_keep_the_smallest_mu():
    """Issue 17: `--mu 0.3 1 3 10` hid the mu = 0.3 column (linear midpoints on a log axis put its
    left edge below zero).  The edges are now geometric midpoints: every column has positive width."""
    ax = Figure().add_subplot()
    plotting.pull_off_map(_synthetic(3, 4, mu=[0.3, 1, 3, 10]), "jkr", ax)
    assert ax.get_xscale() == "log"
    edges = plotting.cell_edges([0.3, 1, 3, 10], log=True)
    assert np.all(edges > 0) and np.all(np.diff(np.log(edges)) > 0)
    # geometric midpoints: sqrt(0.3 x 1), and the outer edge mirrors it in log x
    assert edges[1] == pytest.approx(np.sqrt(0.3)) and edges[0] == pytest.approx(0.3 ** 2 / np.sqrt(0.3))
    coords = ax.collections[0].get_coordinates()
    assert coords[..., 0].min() == pytest.approx(edges[0])
    # beta0 cells stop at the axis' range (they ran to 1.05)
    assert coords[..., 1].max() == pytest.approx(1.0)


def test_large_sweep_is_thinned_and_svg_bounded(tmp_path):
    """Issue 18 item 10: a 1000 x 1000 sweep took 81 s and wrote 190 MB SVGs.  At most
    MAX_CELLS_PER_AXIS points per axis are drawn (said in the title), the mesh is a raster in SVG."""
    ds = _synthetic(1000, 1000)
    paths = plotting.standard_maps(ds, tmp_path, reference="jkr", stem="big")
    svg = [p for p in paths if p.suffix == ".svg"]
    assert svg and max(p.stat().st_size for p in svg) < 2 * 2**20
    ax = Figure().add_subplot()
    plotting.pull_off_map(ds, "jkr", ax)
    assert np.asarray(ax.collections[0].get_array()).size <= plotting.MAX_CELLS_PER_AXIS ** 2
    assert "points shown" in ax.get_title()


def test_string_w_star_and_duplicate_models_are_clean_errors(tmp_path, capsys):
    """Issue 18 items 13, 14: a W_star of strings gave UFuncTypeError, duplicate model names an
    xarray transpose error.  Both are one line naming the problem, exit 2."""
    ds = _synthetic(3, 4)
    bad = ds.assign(W_star=ds["W_star"].astype(str))
    bad.to_netcdf(tmp_path / "str.nc")
    assert main(["plot", str(tmp_path / "str.nc"), "--out", str(tmp_path)]) == 2
    err = capsys.readouterr().err.strip()
    assert "\n" not in err and "W_star" in err and "real numbers" in err
    dup = _synthetic(3, 4, models=("jkr", "jkr"))
    dup.to_netcdf(tmp_path / "dup.nc")
    assert main(["plot", str(tmp_path / "dup.nc"), "--out", str(tmp_path)]) == 2
    err = capsys.readouterr().err.strip()
    assert "\n" not in err and "distinct" in err and "jkr" in err
    assert not list(tmp_path.glob("*.png"))


def test_plot_writes_its_maps_as_one_set_under_sigint(sweep, tmp_path, monkeypatch, default_sigint):
    """Issue 42 finding 9: files written together are moved into place together; a signal between two
    renames waits for the set (before, the maps of one run were left beside those of the previous one)."""
    import os
    import signal

    from dhfield import io as dio

    assert main(["plot", str(sweep.path), "--out", str(tmp_path), "--reference", "jkr"]) == 0
    old = {p: p.read_bytes() for p in tmp_path.iterdir()}
    for p in old:   # mark every file, so that old and new tell apart
        p.write_bytes(b"old")
    real, calls = os.replace, []

    def replace_then_sigint(src, dst):
        real(src, dst)
        calls.append(dst)
        if len(calls) == 1:
            os.kill(os.getpid(), signal.SIGINT)

    monkeypatch.setattr(dio.os, "replace", replace_then_sigint)
    with pytest.raises(KeyboardInterrupt):
        plotting.standard_maps(sweep.path, tmp_path, reference="jkr", stem=sweep.path.stem)
    monkeypatch.undo()
    states = {p.name: p.read_bytes() == b"old" for p in old}
    assert len(set(states.values())) == 1, states
    assert not list(tmp_path.glob(".*.part"))
