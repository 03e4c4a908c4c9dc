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
           "check_sweep", "cell_edges", "output_paths", "FORMATS", "MAX_CELLS_PER_AXIS"]

#: File formats written by :func:`standard_maps`.
FORMATS = ("png", "svg")


#: Most cells drawn along each axis of a map: a larger sweep is shown at evenly spaced rows and
#: columns (a note in the title says so).  A 1000 x 1000 map took 81 s and wrote 190 MB SVGs;
#: with at most 400 x 400 cells, drawn as an embedded raster in SVG, every file stays small.
MAX_CELLS_PER_AXIS = 400
#: Valid range of each ellipticity axis: cell edges are clipped to it (beta0 cells must not run to 1.05).
_AXIS_RANGE = {"beta0": (0.0, 1.0), "skew_angle_deg": (0.0, 90.0)}


def _ell_dim(ds):
    return "skew_angle_deg" if "skew_angle_deg" in ds.dims else "beta0"


def _plane(da):
    """Select a 2-D (ellipticity, mu) plane: the finest BEM grid and the first cohesive law."""
    if "n" in da.dims:
        da = da.isel(n=-1)
    if "law" in da.dims:
        da = da.isel(law=0)
    return da


def _numeric(ds, name, what):
    if not np.issubdtype(ds[name].dtype, np.number) or np.issubdtype(ds[name].dtype, np.complexfloating):
        raise ValueError(f"sweep variable {name} ({what}) must be real numbers; got dtype {ds[name].dtype} "
                         "(not a file written by 'dhfield sweep'?)")


def check_sweep(ds) -> list:
    """Check that ``ds`` is a sweep :func:`standard_maps` can draw; return its model names.

    Parameters
    ----------
    ds : xarray.Dataset
        A sweep written by ``dhfield sweep`` (``W_star`` on (model, beta0 or skew angle, mu)).

    Returns
    -------
    list of str
        The model names of the sweep, in its order.

    Raises
    ------
    ValueError
        One line, if ``W_star`` or the axes are missing or not real numbers, if a model
        name appears twice, or if an axis value is not finite.
    """
    if "W_star" not in ds or "model" not in ds.dims:
        raise ValueError("sweep must hold the pull_off quantity (variables W_star on the dimension model)")
    _numeric(ds, "W_star", "the pull-off force")
    ell = _ell_dim(ds)
    for dim in (ell, "mu"):
        if dim not in ds["W_star"].dims or dim not in ds.coords:
            raise ValueError(f"sweep variable W_star must lie on the dimensions (model, {ell}, mu); "
                             f"got {ds['W_star'].dims}")
        _numeric(ds, dim, "an axis")
        if not np.all(np.isfinite(np.asarray(ds[dim].values, float))):
            raise ValueError(f"sweep axis {dim} must hold finite values; got {ds[dim].values}")
    if "ellipticity" in ds:
        _numeric(ds, "ellipticity", "the contact ellipticity")
    models = [str(m) for m in ds["model"].values]
    dup = sorted({m for m in models if models.count(m) > 1})
    if dup:
        raise ValueError(f"sweep models must be distinct; {', '.join(dup)} appear(s) more than once in "
                         f"{models}")
    return models


def _check(ds, model, name="model"):
    models = check_sweep(ds)
    if model not in models:
        raise ValueError(f"{name} must be one of the sweep's models {models}; got {model!r}")


def _thin(n):
    """Indices of at most MAX_CELLS_PER_AXIS evenly spaced rows out of ``n`` (all if fewer)."""
    if n <= MAX_CELLS_PER_AXIS:
        return np.arange(n)
    return np.unique(np.round(np.linspace(0, n - 1, MAX_CELLS_PER_AXIS)).astype(int))


def cell_edges(centres, log=False, limits=None):
    """Return the edges of the cells around sorted centres: midpoints, geometric ones on a log axis.

    Parameters
    ----------
    centres : array_like
        Sorted cell centres (positive when ``log``).
    log : bool, optional
        Whether the axis is logarithmic.
    limits : tuple of float, optional
        ``(low, high)``: the outer edges are clipped to this valid range of the axis.

    Returns
    -------
    numpy.ndarray
        ``len(centres) + 1`` cell edges.

    Notes
    -----
    On a log axis the edge between x_i and x_i+1 is sqrt(x_i x_i+1), the midpoint in
    log x, and the outer edges mirror it (x_0^2/edge_1); linear midpoints would put the
    first cell's left edge at or below zero, off a log axis (mu = 0.3 disappeared next to
    1, 3, 10).
    """
    x = np.asarray(centres, float)
    if x.size == 1:
        w = 0.5 * abs(x[0]) or 0.5
        e = np.array([x[0] / 2.0, x[0] * 2.0]) if log else np.array([x[0] - w, x[0] + w])
    elif log:
        mid = np.sqrt(x[:-1] * x[1:])
        e = np.concatenate([[x[0] ** 2 / mid[0]], mid, [x[-1] ** 2 / mid[-1]]])
    else:
        mid = 0.5 * (x[:-1] + x[1:])
        e = np.concatenate([[2.0 * x[0] - mid[0]], mid, [2.0 * x[-1] - mid[-1]]])
    if limits is not None:
        e[0], e[-1] = max(e[0], min(limits[0], x[0])), min(e[-1], max(limits[1], x[-1]))
    return e


def _draw(ax, da, ds, title, label, cmap="viridis", symmetric=False):
    ell = _ell_dim(ds)
    plane = _plane(da).transpose(ell, "mu").sortby(ell).sortby("mu")
    iy, ix = _thin(plane.sizes[ell]), _thin(plane.sizes["mu"])
    thinned = iy.size < plane.sizes[ell] or ix.size < plane.sizes["mu"]
    if thinned:
        title += f"\n({ix.size} x {iy.size} of {plane.sizes['mu']} x {plane.sizes[ell]} points shown)"
    plane = plane.isel({ell: iy, "mu": ix})
    z = np.asarray(plane.values, dtype=float)
    x = np.asarray(plane["mu"].values, float)
    y = np.asarray(plane[ell].values, float)
    kw = {}
    if symmetric:
        lim = np.nanmax(np.abs(z)) if np.isfinite(z).any() else 1.0
        kw = dict(vmin=-lim, vmax=lim)
    log = bool(x.size > 1 and np.all(x > 0) and x.max() / x.min() > 20)
    if x.size > 1 and y.size > 1:
        mesh = ax.pcolormesh(cell_edges(x, log), cell_edges(y, limits=_AXIS_RANGE.get(ell)), z,
                             shading="flat", cmap=cmap, rasterized=True, **kw)
    else:  # one row or column: a line plot is the honest picture
        mesh = None
        if y.size == 1:
            ax.plot(x, z[0], "o-")
        else:
            ax.plot(y, z[:, 0], "o-")
    if log:
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
    _draw(ax, rel, ds, f"{model} vs {reference}: relative W*max difference",
          "(W*model - W*ref)/|W*ref|", cmap="RdBu_r", symmetric=True)


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


def _render(fig) -> dict:
    """The figure as bytes in every format of :data:`FORMATS` (nothing written yet)."""
    import io

    out = {}
    for fmt in FORMATS:
        buf = io.BytesIO()
        fig.savefig(buf, format=fmt, dpi=110)
        out[fmt] = buf.getvalue()
    return out


def output_paths(ds, out_dir, *, reference=None, stem="sweep") -> list:
    """List the files :func:`standard_maps` writes for ``ds``, in order (nothing is checked or written).

    Parameters
    ----------
    ds : xarray.Dataset
        The sweep (see :func:`check_sweep`).
    out_dir : str or pathlib.Path
        The output directory.
    reference : str, optional
        The reference model of the error map (default: :func:`default_reference`).
    stem : str, optional
        The file name stem.

    Returns
    -------
    list of pathlib.Path
        The output paths.
    """
    models = check_sweep(ds)
    ref = default_reference(ds) if reference is None else reference
    kinds = ["pull_off"] + (["error"] if [m for m in models if m != ref] else [])
    kinds += ["ellipticity"] if "ellipticity" in ds else []
    return [Path(out_dir) / f"{stem}_{kind}.{fmt}" for kind in kinds for fmt in FORMATS]


def standard_maps(ds, out_dir, *, reference=None, stem="sweep") -> list:
    """Write the standard maps of a sweep as PNG and SVG; return the paths.

    Every output is checked (:func:`dhfield.io.validate_output_path`) and every
    figure drawn before the first file is written, so a bad target (a symbolic
    link, a directory, a read-only file) leaves all files as they were.  Maps of
    more than :data:`MAX_CELLS_PER_AXIS` points along an axis are drawn at evenly
    spaced points (said in the title); the colour mesh is rasterised in SVG.

    Parameters
    ----------
    ds : xarray.Dataset or path
        A sweep Dataset (or its netCDF file) holding the pull_off quantity.
    out_dir : path
        Directory for ``<stem>_pull_off``, ``<stem>_error`` (when there are two
        models or more) and ``<stem>_ellipticity``, each ``.png`` and ``.svg``;
        created (with its parents) if it does not exist.
    reference : str, optional
        Reference model of the error maps (default :func:`default_reference`).
    stem : str, default "sweep"
        Start of the file names.

    Returns
    -------
    list of pathlib.Path
        The files written.
    """
    from .io import atomic_path, validate_output_path

    if not hasattr(ds, "data_vars"):
        from .io import read_netcdf

        ds = read_netcdf(ds)
    out_dir = Path(out_dir)
    if not str(out_dir).strip():
        raise ValueError("out (output directory) must be a non-empty path")
    if out_dir.exists() and not out_dir.is_dir():
        raise ValueError(f"out (output directory) must be a directory; {str(out_dir)!r} is a file")
    models = check_sweep(ds)
    ref = default_reference(ds) if reference is None else reference
    _check(ds, ref, "reference")
    paths = output_paths(ds, out_dir, reference=ref, stem=stem)
    if not out_dir.is_dir():
        try:
            out_dir.mkdir(parents=True)
        except OSError as exc:
            raise ValueError(f"out (output directory) {str(out_dir)!r} cannot be created ({exc.strerror})") \
                from None
    for p in paths:
        validate_output_path(p, None, "out")
    rendered = []
    fig, axes = _grid_figure(len(models))
    for ax, m in zip(axes, models):
        pull_off_map(ds, m, ax)
    rendered.append(_render(fig))
    others = [m for m in models if m != ref]
    if others:
        fig, axes = _grid_figure(len(others))
        for ax, m in zip(axes, others):
            error_map(ds, m, ref, ax)
        rendered.append(_render(fig))
    if "ellipticity" in ds:
        fig, axes = _grid_figure(len(models))
        for ax, m in zip(axes, models):
            ellipticity_map(ds, m, ax)
        rendered.append(_render(fig))
    data = [r[fmt] for r in rendered for fmt in FORMATS]
    for p, blob in zip(paths, data):
        with atomic_path(p) as tmp:
            tmp.write_bytes(blob)
    return paths
