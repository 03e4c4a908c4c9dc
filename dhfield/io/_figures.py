"""Figures written as PNG, SVG and PDF side by side, all checked before any is written, atomically."""
from __future__ import annotations

from pathlib import Path

from . import atomic_path, check_writable


def figure_paths(path):
    """Return the PNG, SVG and PDF paths of a figure, each checked writable before anything is drawn.

    Parameters
    ----------
    path : path-like
        The PNG file; the SVG and PDF are the same path with suffixes ``.svg`` and ``.pdf``.

    Returns
    -------
    (Path, Path, Path)
        The PNG, SVG and PDF paths.

    Raises
    ------
    ValueError
        If ``path`` is not a ``.png`` path, or one of the three cannot be written.
    """
    png = Path(path)
    if png.suffix.lower() != ".png":
        raise ValueError(f"plot must be a .png file path (an .svg and a .pdf are written beside it); "
                         f"got {str(png)!r}")
    paths = (png, png.with_suffix(".svg"), png.with_suffix(".pdf"))
    for out in paths:  # all three checked before any is written
        check_writable(out, "plot")
    return paths


def save_figure(fig, paths, dpi):
    """Write ``fig`` to the PNG, SVG and PDF of :func:`figure_paths`, atomically, without dates.

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        The figure.
    paths : (Path, Path, Path)
        The PNG, SVG and PDF paths.
    dpi : int
        Resolution of the PNG.
    """
    png, svg, pdf = paths
    with atomic_path(png) as tmp_png, atomic_path(svg) as tmp_svg, atomic_path(pdf) as tmp_pdf:
        fig.savefig(tmp_png, format="png", dpi=dpi)
        fig.savefig(tmp_svg, format="svg", metadata={"Date": None})
        fig.savefig(tmp_pdf, format="pdf", metadata={"CreationDate": None})
