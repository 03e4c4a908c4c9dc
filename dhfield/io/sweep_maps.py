"""The standard maps of a sweep (matplotlib, at the edge of the library).

Input is the Dataset of :func:`dhfield.sweep.run_sweep` (or the file it wrote),
with the pull-off variables on ``(model, beta0 | skew_angle_deg, mu[, n, law])``:

* :func:`pull_off_map` -- W*max(mu, beta0) of one model (the paper's Fig. 9
  quantity, Eq. 34, over the whole parameter plane);
* :func:`error_map` -- the relative difference of one model's W*max from a
  reference model's, ``model/ref − 1`` in percent (the report's convention);
* :func:`ellipticity_map` -- the contact ellipticity b/a at pull-off;
* :func:`standard_maps` -- all of them for every model, as PNG, SVG and PDF, panels
  that show the same quantity on one shared colour scale.

Each map takes ``si``, the material of two equal crossed cylinders
(:data:`SI_KEYS`): the axes are then the crossing angle [deg] and the peak
adhesive stress sigma0 [Pa], and the pull-off is a force [N] (Eqs. 34-35 inverted,
:func:`dhfield.io.figures.crossed_cylinders_si`).

The numpy core never imports this module; matplotlib is used through
:class:`matplotlib.figure.Figure` only (no pyplot state, no display needed).
"""
from __future__ import annotations

from pathlib import Path

import numpy as np

from .figures import RECOMMENDED_MODEL, crossed_cylinders_si, model_label, si_prefix

__all__ = ["pull_off_map", "error_map", "ellipticity_map", "standard_maps", "default_reference",
           "check_sweep", "cell_edges", "output_paths", "FORMATS", "MAX_CELLS_PER_AXIS", "REFERENCE_ORDER",
           "SI_KEYS", "FONT_PT"]

#: File formats written by :func:`standard_maps`.
FORMATS = ("png", "svg", "pdf")

#: Most cells drawn along each axis of a map: a larger sweep is shown at evenly spaced rows and
#: columns (a note in the title says so).  A 1000 x 1000 map took 81 s and wrote 190 MB SVGs;
#: with at most 400 x 400 cells, drawn as an embedded raster in SVG, every file stays small.
MAX_CELLS_PER_AXIS = 400
#: Valid range of each ellipticity axis: cell edges are clipped to it (beta0 cells must not run to 1.05).
_AXIS_RANGE = {"beta0": (0.0, 1.0), "skew_angle_deg": (0.0, 90.0)}
#: Reference of the error maps, the most trusted swept model first: the adhesive BEM (ground
#: truth), the recommended model (:data:`dhfield.analysis.compare.RECOMMENDED_MODEL`, within 0.46 % of every
#: stored BEM case), the two-axis closure, the elliptical JKR limits (GVG, then JG), then the
#: paper's model.
REFERENCE_ORDER = ("bem-adhesive", RECOMMENDED_MODEL, "dh-elliptic-two-axis", "jkr-elliptic-energy", "jkr-elliptic",
                   "dh-elliptic")
#: Keys of ``si`` (the material of two equal crossed cylinders, SI units); the ``*_2`` are optional.
SI_KEYS = ("youngs_modulus_1", "poisson_ratio_1", "youngs_modulus_2", "poisson_ratio_2", "cylinder_radius",
           "work_of_adhesion")
#: Font size of the maps [pt]: panels are drawn at print size (3.3 in wide), so this is the size on paper.
FONT_PT = 8.0
_PANEL_IN = (3.3, 2.7)
_RC = {"font.size": FONT_PT, "axes.titlesize": FONT_PT + 0.5, "axes.labelsize": FONT_PT,
       "xtick.labelsize": FONT_PT, "ytick.labelsize": FONT_PT, "figure.titlesize": FONT_PT + 1,
       "legend.fontsize": FONT_PT}


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


def _plane_values(da, ds):
    """(x = mu, y = ellipticity axis, z, note): the sorted plane, thinned to MAX_CELLS_PER_AXIS."""
    ell = _ell_dim(ds)
    plane = _plane(da).transpose(ell, "mu").sortby(ell).sortby("mu")
    iy, ix = _thin(plane.sizes[ell]), _thin(plane.sizes["mu"])
    note = ""
    if iy.size < plane.sizes[ell] or ix.size < plane.sizes["mu"]:
        note = f"\n({ix.size} x {iy.size} of {plane.sizes['mu']} x {plane.sizes[ell]} points shown)"
    plane = plane.isel({ell: iy, "mu": ix})
    return (np.asarray(plane["mu"].values, float), np.asarray(plane[ell].values, float),
            np.asarray(plane.values, dtype=float), note)


def _log_mu(x):
    return bool(x.size > 1 and np.all(x > 0) and x.max() / x.min() > 20)


def _si(si, ell, mu, ell_values):
    """SI quantities (crossing angle, sigma0, load unit) at the points (ell_values, mu)."""
    kw = {k: v for k, v in dict(si).items() if v is not None}
    unknown = sorted(set(kw) - set(SI_KEYS))
    if unknown:
        raise ValueError(f"si must hold only {', '.join(SI_KEYS)}; got {', '.join(unknown)}")
    missing = [k for k in SI_KEYS if not k.endswith("_2") and k not in kw]
    if missing:
        raise ValueError(f"si needs {', '.join(missing)}")
    if ell == "skew_angle_deg":
        return crossed_cylinders_si(None, mu, skew_angle_deg=ell_values, **kw)
    return crossed_cylinders_si(ell_values, mu, **kw)


def _tidy_log_axis(axis, lo, hi, centres=None):
    """Ticks of a log axis whose labels never overlap: the swept values when few, else 1-2-5 or decades."""
    from matplotlib.ticker import FixedLocator, FuncFormatter, LogLocator, NullFormatter, NullLocator

    fmt = FuncFormatter(lambda v, _pos: f"{v:g}" if 1e-3 <= abs(v) < 1e5 else f"{v:.0e}".replace("e+0", "e")
                        .replace("e-0", "e-"))
    if centres is not None and 1 < len(centres) <= 6:
        axis.set_major_locator(FixedLocator(list(centres)))
        axis.set_minor_locator(NullLocator())
    elif hi / lo <= 1e3:
        axis.set_major_locator(LogLocator(base=10.0, subs=(1.0, 2.0, 5.0) if hi / lo > 10 else (1.0, 2.0, 3.0, 5.0),
                                          numticks=12))
        axis.set_minor_locator(LogLocator(base=10.0, subs=tuple(range(2, 10)), numticks=12))
    else:
        axis.set_major_locator(LogLocator(base=10.0, subs=(1.0,), numticks=7))
        axis.set_minor_locator(LogLocator(base=10.0, subs=tuple(range(2, 10)), numticks=12))
    axis.set_major_formatter(fmt)
    axis.set_minor_formatter(NullFormatter())


def _draw(ax, da, ds, title, *, cmap="viridis", vmin=None, vmax=None, si=None, scale=None, label=""):
    """Draw one map; return the colour mesh (None for a line plot)."""
    ell = _ell_dim(ds)
    x, y, z, note = _plane_values(da, ds)
    log = _log_mu(x)
    if scale is not None:  # values in SI at each cell (the load unit varies with the angle)
        z = z * scale(x, y)
    mesh = None
    if x.size > 1 and y.size > 1:
        xe = cell_edges(x, log)
        ye = cell_edges(y, limits=_AXIS_RANGE.get(ell))
        if si is not None:
            ye = np.clip(ye, 1e-4 if ell == "beta0" else 1e-2, None)
            if not log and xe[0] <= 0:
                xe[0] = 0.5 * x[0]
            q = _si(si, ell, xe[None, :], ye[:, None])
            s0, s0_label = si_prefix(np.nanmax(q["max_adhesive_stress"]), "Pa")
            mesh = ax.pcolormesh(q["max_adhesive_stress"] / s0, q["skew_angle_deg"], z, shading="flat", cmap=cmap,
                                 vmin=vmin, vmax=vmax, rasterized=True)
        else:
            mesh = ax.pcolormesh(xe, ye, z, shading="flat", cmap=cmap, vmin=vmin, vmax=vmax, rasterized=True)
    else:  # one row or column: a line plot is the honest picture
        if si is not None:
            raise ValueError("si maps need at least two values on each axis of the sweep")
        if y.size == 1:
            ax.plot(x, z[0], "o-")
        else:
            ax.plot(y, z[:, 0], "o-")
        ax.set_ylabel(label)
    if not np.isfinite(z).any():
        ax.text(0.5, 0.5, "no values\n(every case failed)", transform=ax.transAxes, ha="center", va="center")
    if log:
        ax.set_xscale("log")
        lo, hi = ax.get_xlim()
        _tidy_log_axis(ax.xaxis, lo, hi, None if si is not None else x)
    if si is not None:
        ax.set_xlabel(f"peak adhesive stress σ0 [{s0_label}]")
        ax.set_ylabel("crossing angle θ [deg]")
    else:
        ax.set_xlabel("Tabor parameter μ (Eq. 35)")
        ax.set_ylabel("crossing angle θ [deg]" if ell == "skew_angle_deg" else "β0 = b/a (Eq. 9)")
    ax.set_title(title + note)
    return mesh


def _si_load(si, ds):
    """The cell-wise factor W*max -> W [N] (Eq. 34 inverted), or None without ``si``."""
    if si is None:
        return None
    ell = _ell_dim(ds)
    return lambda x, y: _si(si, ell, x[None, :], y[:, None])["load_unit"]


def _single_colorbar(ax, mesh, label):
    if mesh is not None:
        ax.figure.colorbar(mesh, ax=ax, label=label)


def pull_off_map(ds, model, ax, *, si=None, vmin=None, vmax=None, colorbar=True, force_scale=None):
    """Draw W*max(mu, beta0) of ``model`` (Eq. 34, negative: tensile) on ``ax``.

    Parameters
    ----------
    ds : xarray.Dataset
        A sweep holding the pull_off quantity (``W_star``, ``ellipticity`` on ``model``).
    model : str
        A model of ``ds["model"]``.
    ax : matplotlib.axes.Axes
        Where to draw.
    si : dict, optional
        Material of equal crossed cylinders (:data:`SI_KEYS`): the pull-off force W [N] against
        crossing angle and sigma0.
    vmin, vmax : float, optional
        Colour range (in the plotted unit); the default is this map's own range.
    colorbar : bool, default True
        Add a colour bar next to ``ax`` (:func:`standard_maps` draws one for all panels).
    force_scale : float, optional
        With ``si``: the force unit [N] of the colours (default: a prefix chosen from the values).

    Returns
    -------
    matplotlib.collections.QuadMesh or None
        The colour mesh (None for a one-row sweep, drawn as a line).
    """
    _check(ds, model)
    da = ds["W_star"].sel(model=model)
    label = "pull-off load W*max (Eq. 34)"
    scale = None
    if si is not None:
        load = _si_load(si, ds)
        if force_scale is None:
            x, y, z, _ = _plane_values(da, ds)
            force_scale = si_prefix(np.nanmax(np.abs(z * load(x, y))) if np.isfinite(z).any() else 1.0, "N")[0]
        scale = lambda x, y: load(x, y) / force_scale  # noqa: E731 - a one-line unit conversion
        label = f"pull-off force W [{si_prefix(force_scale, 'N')[1]}]"
    mesh = _draw(ax, da, ds, model_label(model), vmin=vmin, vmax=vmax, si=si, scale=scale, label=label)
    if colorbar:
        _single_colorbar(ax, mesh, label + ", tensile < 0")
    return mesh


def _relative_difference(ds, model, reference):
    w = ds["W_star"]
    return 100.0 * (w.sel(model=model) / w.sel(model=reference) - 1.0)


def error_map(ds, model, reference, ax, *, si=None, vmin=None, vmax=None, colorbar=True):
    """Draw the relative difference of W*max between ``model`` and ``reference`` on ``ax``, in percent.

    The difference is ``100 (W*max_model / W*max_reference − 1)``, the report's sign
    convention: positive where the model's pull-off is the stronger (both are negative).

    Parameters
    ----------
    ds : xarray.Dataset
        A sweep holding the pull_off quantity (``W_star``, ``ellipticity`` on ``model``).
    model : str
        A model of ``ds["model"]``.
    reference : str
        The reference model, also in ``ds["model"]``.
    ax : matplotlib.axes.Axes
        Where to draw.
    si : dict, optional
        Material of equal crossed cylinders (:data:`SI_KEYS`): SI axes.
    vmin, vmax : float, optional
        Colour range [%]; the default is symmetric about zero over this map.
    colorbar : bool, default True
        Add a colour bar next to ``ax``.

    Returns
    -------
    matplotlib.collections.QuadMesh or None
        The colour mesh (None for a one-row sweep, drawn as a line).
    """
    _check(ds, model)
    _check(ds, reference, "reference")
    rel = _relative_difference(ds, model, reference)
    if vmin is None or vmax is None:
        z = np.asarray(rel.values, float)
        lim = float(np.nanmax(np.abs(z))) if np.isfinite(z).any() else 1.0
        vmin, vmax = -(lim or 1.0), (lim or 1.0)
    label = f"W*max: model/{model_label(reference)} − 1 [%]"
    mesh = _draw(ax, rel, ds, model_label(model), cmap="RdBu_r", vmin=vmin, vmax=vmax, si=si, label=label)
    if colorbar:
        _single_colorbar(ax, mesh, label)
    return mesh


def ellipticity_map(ds, model, ax, *, si=None, vmin=None, vmax=None, colorbar=True):
    """Draw the contact ellipticity b/a at pull-off of ``model`` on ``ax``.

    Parameters
    ----------
    ds : xarray.Dataset
        A sweep holding the pull_off quantity (``W_star``, ``ellipticity`` on ``model``).
    model : str
        A model of ``ds["model"]``.
    ax : matplotlib.axes.Axes
        Where to draw.
    si : dict, optional
        Material of equal crossed cylinders (:data:`SI_KEYS`): SI axes.
    vmin, vmax : float, optional
        Colour range; the default is this map's own range.
    colorbar : bool, default True
        Add a colour bar next to ``ax``.

    Returns
    -------
    matplotlib.collections.QuadMesh or None
        The colour mesh (None for a one-row sweep, drawn as a line).
    """
    _check(ds, model)
    label = "contact ellipticity b/a at pull-off"
    mesh = _draw(ax, ds["ellipticity"].sel(model=model), ds, model_label(model), cmap="magma", vmin=vmin,
                 vmax=vmax, si=si, label=label)
    if colorbar:
        _single_colorbar(ax, mesh, label)
    return mesh


def default_reference(ds) -> str:
    """Reference of the error maps: the most trusted model of :data:`REFERENCE_ORDER` that was swept.

    Parameters
    ----------
    ds : xarray.Dataset
        A sweep with a ``model`` coordinate.

    Returns
    -------
    str
        ``"bem-adhesive"`` (the ground truth) if swept, else the recommended model, then
        the others of :data:`REFERENCE_ORDER` in turn, else the first model.
    """
    models = [str(m) for m in ds["model"].values]
    for name in REFERENCE_ORDER:
        if name in models:
            return name
    return models[0]


def _grid_figure(n_panels):
    from matplotlib.figure import Figure

    cols = 2 if n_panels == 4 else min(3, max(1, n_panels))
    rows = int(np.ceil(n_panels / cols))
    fig = Figure(figsize=(_PANEL_IN[0] * cols + 0.9, _PANEL_IN[1] * rows + 0.45), layout="constrained")
    axes = [fig.add_subplot(rows, cols, i + 1) for i in range(n_panels)]
    return fig, axes


def _render(fig) -> dict:
    """The figure as bytes in every format of :data:`FORMATS` (nothing written yet), without dates."""
    import io

    meta = {"svg": {"Date": None}, "pdf": {"CreationDate": None}}
    out = {}
    for fmt in FORMATS:
        buf = io.BytesIO()
        fig.savefig(buf, format=fmt, dpi=150, metadata=meta.get(fmt))
        out[fmt] = buf.getvalue()
    return out


def _shared_limits(planes, centred=False):
    """(vmin, vmax) over every finite value of ``planes``; symmetric about 0 when ``centred``."""
    vals = np.concatenate([np.asarray(p, float).ravel() for p in planes]) if planes else np.array([])
    vals = vals[np.isfinite(vals)]
    if vals.size == 0:
        return (-1.0, 1.0) if centred else (0.0, 1.0)
    if centred:
        m = float(np.max(np.abs(vals))) or 1.0
        return -m, m
    lo, hi = float(vals.min()), float(vals.max())
    return (lo, hi) if hi > lo else (lo - 0.5 * (abs(lo) or 1.0), hi + 0.5 * (abs(hi) or 1.0))


def _material_note(si) -> str:
    def pre(v, unit):
        k, lab = si_prefix(v, unit)
        return f"{v / k:.3g} {lab}"

    e2 = si.get("youngs_modulus_2")
    body = f"E = {pre(si['youngs_modulus_1'], 'Pa')}, ν = {si['poisson_ratio_1']:g}"
    if e2 is not None and e2 != si["youngs_modulus_1"]:
        body += f"; E2 = {pre(e2, 'Pa')}, ν2 = {si.get('poisson_ratio_2') or si['poisson_ratio_1']:g}"
    return (f"crossed cylinders R_c = {pre(si['cylinder_radius'], 'm')}, {body}, "
            f"Δγ = {pre(si['work_of_adhesion'], 'J/m²')}")


def _figures(ds, models, ref, si):
    """The standard figures of a sweep (pull-off, error, ellipticity), panels on shared colour scales."""
    import matplotlib

    figs = []
    with matplotlib.rc_context(_RC):
        tail = f"\n{_material_note(si)}" if si is not None else ""
        fig, axes = _grid_figure(len(models))
        if si is not None:
            load = _si_load(si, ds)
            planes = [_plane_values(ds["W_star"].sel(model=m), ds) for m in models]
            planes = [z * load(x, y) for x, y, z, _ in planes]
            big = max((float(np.nanmax(np.abs(z))) for z in planes if np.isfinite(z).any()), default=1.0)
            fscale, flabel = si_prefix(big, "N")
            lims = _shared_limits([z / fscale for z in planes])
            label, kw = f"pull-off force W [{flabel}], tensile < 0", {"si": si, "force_scale": fscale}
        else:
            lims = _shared_limits([_plane_values(ds["W_star"].sel(model=m), ds)[2] for m in models])
            label, kw = "pull-off load W*max (Eq. 34), tensile < 0", {}
        meshes = [pull_off_map(ds, m, ax, vmin=lims[0], vmax=lims[1], colorbar=False, **kw)
                  for ax, m in zip(axes, models)]
        _shared_colorbar(fig, axes, meshes, label)
        fig.suptitle(("Pull-off force of each model" if si is not None else "Pull-off load of each model") + tail)
        figs.append(fig)
        others = [m for m in models if m != ref]
        if others:
            fig, axes = _grid_figure(len(others))
            lims = _shared_limits([_plane_values(_relative_difference(ds, m, ref), ds)[2] for m in others],
                                  centred=True)
            meshes = [error_map(ds, m, ref, ax, si=si, vmin=lims[0], vmax=lims[1], colorbar=False)
                      for ax, m in zip(axes, others)]
            _shared_colorbar(fig, axes, meshes, f"W*max: model/ref − 1 [%]\n(ref = {model_label(ref)})")
            fig.suptitle(f"Pull-off against {model_label(ref)}: model/ref − 1, > 0 where the model's pull-off "
                         "is stronger" + tail)
            figs.append(fig)
        if "ellipticity" in ds:
            fig, axes = _grid_figure(len(models))
            lims = _shared_limits([_plane_values(ds["ellipticity"].sel(model=m), ds)[2] for m in models])
            meshes = [ellipticity_map(ds, m, ax, si=si, vmin=lims[0], vmax=lims[1], colorbar=False)
                      for ax, m in zip(axes, models)]
            _shared_colorbar(fig, axes, meshes, "contact ellipticity b/a at pull-off")
            fig.suptitle("Contact ellipticity b/a at pull-off" + tail)
            figs.append(fig)
    return figs


def _shared_colorbar(fig, axes, meshes, label):
    mesh = next((m for m in meshes if m is not None), None)
    if mesh is not None:
        fig.colorbar(mesh, ax=axes, label=label, shrink=0.9 if len(axes) > 3 else 1.0)


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


def standard_maps(ds, out_dir, *, reference=None, stem="sweep", si=None) -> list:
    """Write the standard maps of a sweep as PNG, SVG and PDF; return the paths.

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
        models or more) and ``<stem>_ellipticity``, each ``.png``, ``.svg`` and
        ``.pdf``; created (with its parents) if it does not exist.
    reference : str, optional
        Reference model of the error maps (default :func:`default_reference`).
    stem : str, default "sweep"
        Start of the file names.
    si : dict, optional
        Material of two equal crossed cylinders (:data:`SI_KEYS`, SI units): the maps
        are drawn against crossing angle [deg] and sigma0 [Pa], the pull-off as a force.

    Returns
    -------
    list of pathlib.Path
        The files written.

    Notes
    -----
    Panels of one figure show the same quantity on one colour scale (one colour bar);
    the error maps are ``model/ref − 1`` [%] against :func:`default_reference`.
    """
    from . import atomic_files, atomic_path, validate_output_path

    if not hasattr(ds, "data_vars"):
        from . import read_netcdf

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
    if si is not None:  # the material checked before anything is created
        ell = _ell_dim(ds)
        _si(si, ell, np.asarray(ds["mu"].values, float)[:1], np.asarray(ds[ell].values, float)[:1])
    if not out_dir.is_dir():
        try:
            out_dir.mkdir(parents=True)
        except OSError as exc:
            raise ValueError(f"out (output directory) {str(out_dir)!r} cannot be created ({exc.strerror})") \
                from None
    for p in paths:
        validate_output_path(p, None, "out")
    rendered = [_render(fig) for fig in _figures(ds, models, ref, si)]
    data = [r[fmt] for r in rendered for fmt in FORMATS]
    with atomic_files():   # every map as one set: all moved into place, or none (an interrupt keeps the old)
        for p, blob in zip(paths, data):
            with atomic_path(p) as tmp:
                tmp.write_bytes(blob)
    return paths
