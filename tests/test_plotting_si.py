"""The sweep maps fit for a paper (issue 17): SI axes, shared colour scales, the sign convention,
the trusted reference, readable names, PDF.  Closed-form sweeps (JKR W* = -3/4, DMT W* = -1); the SI
conversion itself is checked in test_io_figures."""
from __future__ import annotations

import numpy as np
import pytest
from matplotlib.figure import Figure

from dhfield.io import sweep_maps as plotting
from dhfield.cli import main
from dhfield.io.figures import crossed_cylinders_si, model_label

#: The PDMS crossed cylinders of issue 17.
PDMS = dict(youngs_modulus_1=1.8e6, poisson_ratio_1=0.49, cylinder_radius=3e-3, work_of_adhesion=0.05)


def _sweep(models=("jkr", "dmt"), beta0=(0.5, 0.75, 1.0), mu=(0.3, 1.0, 3.0, 10.0), values=None):
    import xarray as xr

    beta0, mu = np.asarray(beta0, float), np.asarray(mu, float)
    values = values or {"jkr": -0.75, "dmt": -1.0}
    w = np.stack([np.full((beta0.size, mu.size), values.get(m, -0.8)) for m in models])
    ell = np.stack([np.tile(beta0[:, None], (1, mu.size)) for _ in models])
    return xr.Dataset({"W_star": (("model", "beta0", "mu"), w), "ellipticity": (("model", "beta0", "mu"), ell)},
                      coords={"model": list(models), "beta0": beta0, "mu": mu})


def test_si_pull_off_map_is_the_force_on_angle_and_sigma0_axes():
    ds = _sweep()
    ax = Figure().add_subplot()
    mesh = plotting.pull_off_map(ds, "jkr", ax, si=PDMS, force_scale=1e-3)
    drawn = np.asarray(mesh.get_array()).reshape(3, 4)
    unit = crossed_cylinders_si(ds["beta0"].values[:, None], ds["mu"].values[None, :], **PDMS)["load_unit"]
    np.testing.assert_allclose(drawn, -0.75 * unit / 1e-3, rtol=1e-12)  # W = W* x load unit (Eq. 34), in mN
    assert "[mN]" in ax.figure.axes[-1].get_ylabel()  # the colour bar
    assert "σ0 [kPa]" in ax.get_xlabel() and "angle" in ax.get_ylabel() and ax.get_xscale() == "log"
    corners = mesh.get_coordinates()
    assert corners[..., 1].max() == pytest.approx(90.0)  # beta0 = 1: perpendicular cylinders


def test_si_needs_a_whole_material():
    with pytest.raises(ValueError, match="cylinder_radius"):
        plotting.pull_off_map(_sweep(), "jkr", Figure().add_subplot(),
                              si={k: v for k, v in PDMS.items() if k != "cylinder_radius"})
    with pytest.raises(ValueError, match="poisson_ratio"):
        plotting.pull_off_map(_sweep(), "jkr", Figure().add_subplot(), si={**PDMS, "poisson_ratio_1": 0.7})


def test_cli_si_flags(tmp_path, capsys):
    nc = tmp_path / "s.nc"
    _sweep().to_netcdf(nc)
    assert main(["plot", str(nc), "--out", str(tmp_path / "si"), "--youngs-modulus", "1.8e6"]) == 2
    err = capsys.readouterr().err.strip()
    assert "--poisson-ratio" in err and "--cylinder-radius" in err and "\n" not in err
    assert not (tmp_path / "si").exists()
    assert main(["plot", str(nc), "--out", str(tmp_path / "si"), "--youngs-modulus", "1.8e6", "--poisson-ratio",
                 "0.49", "--cylinder-radius", "3e-3", "--work-of-adhesion", "0.05", "--reference", "jkr"]) == 0
    names = sorted(p.name for p in (tmp_path / "si").iterdir())
    assert names == sorted(f"s_{k}.{f}" for k in ("pull_off", "error", "ellipticity") for f in ("png", "svg", "pdf"))


def test_panels_of_one_figure_share_one_colour_scale():
    ds = _sweep(models=("jkr", "dmt", "md"), values={"jkr": -0.75, "dmt": -1.0, "md": -0.9})
    figs = plotting._figures(ds, ["jkr", "dmt", "md"], "jkr", None)
    for fig in figs:
        meshes = [c for ax in fig.axes if ax.get_label() != "<colorbar>" for c in ax.collections]
        assert len(meshes) == len(fig.axes) - 1
        assert len({m.get_clim() for m in meshes}) == 1  # one range for every panel
        assert len([ax for ax in fig.axes if ax.get_label() == "<colorbar>"]) == 1  # one colour bar
    lo, hi = figs[0].axes[0].collections[0].get_clim()
    assert (lo, hi) == (-1.0, -0.75)  # the pull-off range over all models
    lo, hi = figs[1].axes[0].collections[0].get_clim()
    assert hi == -lo == pytest.approx(100.0 / 3.0)  # DMT vs JKR: 100 (-1/(-3/4) - 1), symmetric about 0


def test_error_map_states_the_reports_sign_convention():
    ax = Figure().add_subplot()
    plotting.error_map(_sweep(), "dmt", "jkr", ax)
    assert ax.figure.axes[-1].get_ylabel() == "W*max: model/JKR − 1 [%]"
    assert ax.get_title() == "DMT"


def test_titles_are_readable_names_and_reference_is_the_trusted_model():
    import xarray as xr

    ax = Figure().add_subplot()
    plotting.pull_off_map(_sweep(models=("jkr", "dmt")), "jkr", ax)
    assert ax.get_title() == "JKR" == model_label("jkr")
    ds = xr.Dataset(coords={"model": ["md", "dh-elliptic", "jkr-elliptic", "dh-elliptic-two-axis"]})
    assert plotting.default_reference(ds) == "dh-elliptic-two-axis"  # not the paper's model, which it distrusts
    ds = xr.Dataset(coords={"model": ["md", "dh-elliptic", "jkr-elliptic"]})
    assert plotting.default_reference(ds) == "jkr-elliptic"


def test_swept_mu_values_are_the_log_ticks():
    ax = Figure().add_subplot()
    plotting.pull_off_map(_sweep(), "jkr", ax)
    assert list(ax.get_xticks()) == [0.3, 1.0, 3.0, 10.0]
    assert [t.get_text() for t in ax.get_xticklabels()] == ["0.3", "1", "3", "10"]
