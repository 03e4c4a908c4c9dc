"""Residual plot of a load-curve fit (:func:`dhfield.fit.fit_curve`): matplotlib at the edge."""
from __future__ import annotations

from pathlib import Path

import numpy as np

from . import atomic_path, check_writable

__all__ = ["write_residual_plot"]


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
