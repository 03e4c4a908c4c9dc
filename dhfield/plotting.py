"""The standard maps of a sweep (matplotlib, at the edge of the library).

Input is the Dataset of :func:`dhfield.sweep.run_sweep` (or the file it wrote),
with the pull-off variables on ``(model, beta0 | skew_angle_deg, mu[, n, law])``:

* :func:`pull_off_map` -- W*max(mu, beta0) of one model (the paper's Fig. 9
  quantity, Eq. 34, over the whole parameter plane);
* :func:`error_map` -- the relative difference of one model's W*max from a
  reference model's;
* :func:`ellipticity_map` -- the contact ellipticity b/a at pull-off;
* :func:`standard_maps` -- all of them for every model, as PNG and SVG.

The numpy core never imports this module; matplotlib is used through
:class:`matplotlib.figure.Figure` only (no pyplot state, no display needed).
"""
from __future__ import annotations

from pathlib import Path

import numpy as np

__all__ = ["pull_off_map", "error_map", "ellipticity_map", "standard_maps", "default_reference",
           "FORMATS"]

#: File formats written by :func:`standard_maps`.
FORMATS = ("png", "svg")


def _ell_dim(ds):
    return "skew_angle_deg" if "skew_angle_deg" in ds.dims else "beta0"


def _plane(da):
    """Select a 2-D (ellipticity, mu) plane: the finest BEM grid and the first cohesive law."""
    if "n" in da.dims:
        da = da.isel(n=-1)
    if "law" in da.dims:
        da = da.isel(law=0)
    return da


def _check(ds, model, name="model"):
    if "W_star" not in ds or "model" not in ds.dims:
        raise ValueError("sweep must hold the pull_off quantity (variables W_star on the dimension model)")
    models = [str(m) for m in ds["model"].values]
    if model not in models:
        raise ValueError(f"{name} must be one of the sweep's models {models}; got {model!r}")


def _draw(ax, da, ds, title, label, cmap="viridis", symmetric=False):
    ell = _ell_dim(ds)
    z = np.asarray(_plane(da).transpose(ell, "mu").values, dtype=float)
    x = np.asarray(ds["mu"].values, float)
    y = np.asarray(ds[ell].values, float)
    kw = {}
    if symmetric:
        lim = np.nanmax(np.abs(z)) if np.isfinite(z).any() else 1.0
        kw = dict(vmin=-lim, vmax=lim)
    if x.size > 1 and y.size > 1:
        mesh = ax.pcolormesh(x, y, z, shading="nearest", cmap=cmap, **kw)
    else:  # one row or column: a line plot is the honest picture
        mesh = None
        if y.size == 1:
            ax.plot(x, z[0], "o-")
        else:
            ax.plot(y, z[:, 0], "o-")
    if x.size > 1 and np.all(x > 0) and x.max() / x.min() > 20:
        ax.set_xscale("log")
    ax.set_xlabel("Tabor parameter mu (Eq. 35)")
    ax.set_ylabel("skew angle [deg]" if ell == "skew_angle_deg" else "beta0 = b/a (Eq. 9)")
    ax.set_title(title, fontsize=9)
    if mesh is not None:
        ax.figure.colorbar(mesh, ax=ax, label=label)


def pull_off_map(ds, model, ax):
    """Draw W*max(mu, beta0) of ``model`` (Eq. 34, negative: tensile) on ``ax``.

    Parameters
    ----------
    ds : xarray.Dataset
        A sweep holding the pull_off quantity (``W_star``, ``ellipticity`` on ``model``).
    model : str
        A model of ``ds["model"]``.
    ax : matplotlib.axes.Axes
        Where to draw (a colour bar is added next to it).
    """
    _check(ds, model)
    _draw(ax, ds["W_star"].sel(model=model), ds, f"{model}: W*max (Eq. 34)", "W*max")


def error_map(ds, model, reference, ax):
    """Draw the relative difference of W*max between ``model`` and ``reference`` on ``ax``.

    The difference is (W*max_model - W*max_reference)/abs(W*max_reference).

    Parameters
    ----------
    ds : xarray.Dataset
        A sweep holding the pull_off quantity (``W_star``, ``ellipticity`` on ``model``).
    model : str
        A model of ``ds["model"]``.
    reference : str
        The reference model, also in ``ds["model"]``.
    ax : matplotlib.axes.Axes
        Where to draw (a colour bar is added next to it).
    """
    _check(ds, model)
    _check(ds, reference, "reference")
    w = ds["W_star"]
    rel = (w.sel(model=model) - w.sel(model=reference)) / np.abs(w.sel(model=reference))
    _draw(ax, rel, ds, f"{model} vs {reference}: relative W*max difference", "relative difference",
          cmap="RdBu_r", symmetric=True)


def ellipticity_map(ds, model, ax):
    """Draw the contact ellipticity b/a at pull-off of ``model`` on ``ax``.

    Parameters
    ----------
    ds : xarray.Dataset
        A sweep holding the pull_off quantity (``W_star``, ``ellipticity`` on ``model``).
    model : str
        A model of ``ds["model"]``.
    ax : matplotlib.axes.Axes
        Where to draw (a colour bar is added next to it).
    """
    _check(ds, model)
    _draw(ax, ds["ellipticity"].sel(model=model), ds, f"{model}: ellipticity b/a at pull-off",
          "b/a at pull-off", cmap="magma")


def default_reference(ds) -> str:
    """Reference of the error maps: the adhesive BEM ground truth if swept, else the paper's model.

    Parameters
    ----------
    ds : xarray.Dataset
        A sweep with a ``model`` coordinate.

    Returns
    -------
    str
        ``"bem-adhesive"`` or ``"dh-elliptic"`` when swept, else the first model.
    """
    models = [str(m) for m in ds["model"].values]
    for name in ("bem-adhesive", "dh-elliptic"):
        if name in models:
            return name
    return models[0]


def _grid_figure(n_panels):
    from matplotlib.figure import Figure

    cols = min(3, max(1, n_panels))
    rows = int(np.ceil(n_panels / cols))
    fig = Figure(figsize=(4.6 * cols, 3.6 * rows), layout="constrained")
    axes = [fig.add_subplot(rows, cols, i + 1) for i in range(n_panels)]
    return fig, axes


def _save(fig, stem: Path) -> list:
    from .io import atomic_path

    paths = []
    for fmt in FORMATS:
        p = stem.with_name(f"{stem.name}.{fmt}")
        with atomic_path(p) as tmp:
            fig.savefig(tmp, format=fmt, dpi=110)
        paths.append(p)
    return paths


def standard_maps(ds, out_dir, *, reference=None, stem="sweep") -> list:
    """Write the standard maps of a sweep as PNG and SVG; return the paths.

    Parameters
    ----------
    ds : xarray.Dataset or path
        A sweep Dataset (or its netCDF file) holding the pull_off quantity.
    out_dir : path
        Existing directory for ``<stem>_pull_off``, ``<stem>_error`` (when there
        are two models or more) and ``<stem>_ellipticity``, each ``.png`` and ``.svg``.
    reference : str, optional
        Reference model of the error maps (default :func:`default_reference`).
    stem : str, default "sweep"
        Start of the file names.

    Returns
    -------
    list of pathlib.Path
        The files written.
    """
    if not hasattr(ds, "data_vars"):
        from .io import read_netcdf

        ds = read_netcdf(ds)
    out_dir = Path(out_dir)
    if not out_dir.is_dir():
        raise ValueError(f"out (output directory) must be an existing directory; got {str(out_dir)!r}")
    if "W_star" not in ds or "model" not in ds.dims:
        raise ValueError("sweep must hold the pull_off quantity (variables W_star on the dimension model)")
    models = [str(m) for m in ds["model"].values]
    ref = default_reference(ds) if reference is None else reference
    _check(ds, ref, "reference")
    written = []
    fig, axes = _grid_figure(len(models))
    for ax, m in zip(axes, models):
        pull_off_map(ds, m, ax)
    written += _save(fig, out_dir / f"{stem}_pull_off")
    others = [m for m in models if m != ref]
    if others:
        fig, axes = _grid_figure(len(others))
        for ax, m in zip(axes, others):
            error_map(ds, m, ref, ax)
        written += _save(fig, out_dir / f"{stem}_error")
    fig, axes = _grid_figure(len(models))
    for ax, m in zip(axes, models):
        ellipticity_map(ds, m, ax)
    written += _save(fig, out_dir / f"{stem}_ellipticity")
    return written
