"""Input and output of the fits (:mod:`dhfield.fit`): the measured load curve, the residual plot.

:func:`read_curve_data` reads a measured load curve from CSV; :func:`write_residual_plot`
draws a :class:`dhfield.fit.CurveFit` (matplotlib at the edge, imported on use).
"""
from __future__ import annotations

from pathlib import Path

import numpy as np

from . import atomic_path, check_writable

__all__ = ["read_curve_data", "write_residual_plot", "DATA_COLUMNS"]

#: Columns of a measured load curve: schema name -> accepted column names.
DATA_COLUMNS = {"force": ("force", "load"), "semi_major": ("semi_major", "contact_size"),
                "approach": ("approach",)}


def read_curve_data(path, params=None) -> dict:
    """A measured load curve from a CSV file, in SI units.

    Parameters
    ----------
    path : path-like
        CSV with a header row: ``force`` (or ``load``) [N], ``semi_major`` (or
        ``contact_size``) [m], optionally ``approach`` [m].
    params : dhfield.dimensional.ContactParameters, optional
        The contact, for the plausibility checks of the magnitudes.

    Returns
    -------
    dict
        ``force``, ``semi_major`` and (if present) ``approach``: float arrays [N], [m], [m].

    Raises
    ------
    ValueError
        One line naming the file and the column.
    """
    from .table import read_table

    frame, _ = read_table(path)
    cols = {}
    for name, aliases in DATA_COLUMNS.items():
        found = [a for a in aliases if a in frame.columns]
        if found:
            cols[name] = found[0]
        elif name != "approach":
            raise ValueError(f"data file {str(path)!r} has no column {name!r} (or {', '.join(aliases[1:])}); "
                             f"columns: {', '.join(map(str, frame.columns))}")
    frame, _ = read_table(path, required=tuple(cols.values()))
    return {name: frame[col].to_numpy(dtype=float) for name, col in cols.items()}


def write_residual_plot(fit, path, *, dpi=120) -> tuple[Path, Path]:
    """Write the data, the fitted curve and the residuals of ``fit`` as PNG and SVG.

    Parameters
    ----------
    fit : dhfield.fit.CurveFit
    path : path-like
        PNG file to write; the SVG is the same path with suffix ``.svg``.  Both
        are written atomically.
    dpi : int
        Resolution of the PNG.

    Returns
    -------
    (Path, Path)
        The PNG and SVG paths.
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    png = Path(path)
    if png.suffix.lower() != ".png":
        raise ValueError(f"plot must be a .png file path (an .svg is written beside it); got {str(png)!r}")
    svg = png.with_suffix(".svg")
    check_writable(png, "plot")
    a_mm = 1e3 * np.asarray(fit.contact_size)
    order = np.argsort(a_mm)
    rows = 2 if fit.approach is None else 3
    fig, axes = plt.subplots(rows, 1, figsize=(6.0, 2.4 * rows + 0.6), sharex=True)
    ax = axes[0]
    ax.plot(a_mm, 1e3 * np.asarray(fit.load), "o", ms=4, label="data")
    ax.plot(a_mm[order], 1e3 * np.asarray(fit.load_fitted)[order], "-", label=f"{fit.model} fit")
    ax.set_ylabel("load W [mN]")
    ax.set_title(f"Δγ = {fit.work_of_adhesion:.4g} ± {fit.work_of_adhesion_stderr:.2g} J/m², "
                 f"σ₀ = {fit.max_adhesive_stress:.4g} ± {fit.max_adhesive_stress_stderr:.2g} Pa (±1 s.e.)", fontsize=9)
    ax.legend(fontsize=8, loc="best")
    ax = axes[1]
    ax.axhline(0.0, color="0.6", lw=0.8)
    ax.plot(a_mm, 1e3 * np.asarray(fit.load_residuals), "o", ms=4)
    ax.set_ylabel("load residual [mN]")
    if fit.approach is not None:
        ax = axes[2]
        ax.axhline(0.0, color="0.6", lw=0.8)
        ax.plot(a_mm, 1e6 * np.asarray(fit.approach_residuals), "s", ms=4, color="C2")
        ax.set_ylabel("approach residual [µm]")
    axes[-1].set_xlabel("contact semi-major axis a [mm]")
    fig.tight_layout()
    try:
        with atomic_path(png) as tmp_png, atomic_path(svg) as tmp_svg:
            fig.savefig(tmp_png, format="png", dpi=dpi)
            fig.savefig(tmp_svg, format="svg", metadata={"Date": None})
    finally:
        plt.close(fig)
    return png, svg
