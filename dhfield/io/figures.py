"""What every dhfield figure shares: PNG, SVG and PDF files, model names, SI prefixes, SI axes.

* :func:`figure_paths`, :func:`save_figure` and :func:`write_figure`: a figure written as PNG,
  SVG and PDF side by side, all checked before any is written, atomically;
* :data:`MODEL_LABELS` and :func:`model_label`: the readable name of each model slug, for
  titles and legends (the report uses the same table);
* :func:`si_prefix`: a scale and prefixed unit for axis labels;
* :func:`crossed_cylinders_si`: the crossing angle, peak adhesive stress and load unit of
  two equal crossed cylinders at given (beta0, mu), for maps in SI units (Eqs. 3-6, 34, 35).
"""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from ..analysis.compare import RECOMMENDED_MODEL
from . import atomic_path, check_writable

__all__ = ["RECOMMENDED_MODEL", "MODEL_LABELS", "model_label", "SI_PREFIXES", "si_prefix", "crossed_cylinders_si", "figure_paths",
           "save_figure", "write_figure"]

#: Readable name of each model slug (``--model`` names of :mod:`dhfield.analysis.compare`, the adhesive
#: BEM of a sweep, and the closures of the report's periphery section).
MODEL_LABELS = {
    "hertz": "Hertz",
    "jkr": "JKR",
    "dmt": "DMT",
    "md": "Maugis–Dugdale",
    "maugis-dugdale": "Maugis–Dugdale",
    "dh-circular": "DH circular",
    "dh-elliptic": "DH elliptic (paper)",
    "dh-elliptic-jkr-beta": "DH elliptic, β from JKR",
    "dh-elliptic-ray-average": "DH elliptic, ray average",
    "dh-elliptic-two-axis": "DH elliptic, two axes",
    "jkr-elliptic": "JKR elliptical (JG05)",
    "jkr-elliptic-energy": "JKR elliptical (energy)",
    "md-elliptic": "MD elliptical (recommended)",
    "bem-adhesive": "adhesive BEM",
    "bem": "BEM",
    "recommended": "recommended",
}


def model_label(slug) -> str:
    """Return the readable name of a model slug (the slug itself when the table has none).

    Parameters
    ----------
    slug : str
        A model name such as ``"dh-elliptic-two-axis"``.

    Returns
    -------
    str
        Its name in titles and legends, e.g. ``"DH elliptic, two axes"``.
    """
    return MODEL_LABELS.get(str(slug), str(slug))


#: ``(scale, prefix)`` of the SI prefixes of :func:`si_prefix`, smallest first.
SI_PREFIXES = ((1e-12, "p"), (1e-9, "n"), (1e-6, "µ"), (1e-3, "m"), (1.0, ""), (1e3, "k"), (1e6, "M"),
             (1e9, "G"))


def si_prefix(magnitude, unit, *, prefixes=SI_PREFIXES):
    """Return ``(scale, label)`` that puts ``magnitude`` [unit] between 1 and 1000 in a prefixed unit.

    Parameters
    ----------
    magnitude : float
        A typical value (its absolute value is used) [unit].
    unit : str
        The SI unit without prefix, e.g. ``"N"``.
    prefixes : tuple of (float, str), default :data:`SI_PREFIXES`
        The ``(scale, prefix)`` pairs allowed, smallest first; magnitudes below the first
        take the first.

    Returns
    -------
    (float, str)
        Divide values by the scale to plot them in the prefixed unit, e.g. ``(1e-3, "mN")``.
    """
    m = abs(float(magnitude))
    if not math.isfinite(m) or m == 0.0:
        return 1.0, unit
    scale, p = prefixes[0]
    for s, name in prefixes:
        if m >= s:
            scale, p = s, name
    return scale, f"{p}{unit}"


def crossed_cylinders_si(beta0, mu, *, youngs_modulus_1, poisson_ratio_1, cylinder_radius, work_of_adhesion,
                         youngs_modulus_2=None, poisson_ratio_2=None, skew_angle_deg=None):
    """Return the SI quantities of two equal crossed cylinders at Hertz ellipticity ``beta0`` and Tabor ``mu``.

    Parameters
    ----------
    beta0 : array_like or None
        Hertz ellipticity b/a in (0, 1] [-] (Eq. 9); None when ``skew_angle_deg`` is given.
    mu : array_like
        Tabor parameter [-] (Eq. 35), broadcast with ``beta0``.
    youngs_modulus_1, poisson_ratio_1 : float
        Young's modulus [Pa] and Poisson's ratio [-] of body 1.
    cylinder_radius : float
        Radius R_c of both cylinders [m].
    work_of_adhesion : float
        Delta gamma [J m^-2].
    youngs_modulus_2, poisson_ratio_2 : float, optional
        Body 2 (default: body 1).
    skew_angle_deg : array_like, optional
        The crossing angle in (0, 90] [deg] instead of ``beta0``.

    Returns
    -------
    dict
        ``skew_angle_deg`` (crossing angle [deg]), ``max_adhesive_stress`` (sigma0 [Pa]) and
        ``load_unit`` (2 pi R dgamma / sin theta [N], which turns W* into a force), arrays
        broadcast over ``beta0`` and ``mu``.

    Raises
    ------
    ValueError
        Naming the material or geometry parameter that is not positive and finite (or a
        Poisson's ratio outside (-1, 0.5]).

    Notes
    -----
    theta from beta0 by Eqs. (3)-(4) and (9) (:func:`dhfield.core.geometry.skew_angle`);
    R' = R_c/(1 - cos theta), R'' = R_c/(1 + cos theta) (Eqs. 3-4), R = sqrt(R' R'') (Eq. 5),
    E* by Eq. (6); Eq. (35) inverted, sigma0 = mu (E*^2 dgamma/R)^(1/3); Eq. (34) inverted,
    W = W* 2 pi R dgamma / sin theta.
    """
    from ..core import geometry

    e2 = youngs_modulus_1 if youngs_modulus_2 is None else youngs_modulus_2
    nu2 = poisson_ratio_1 if poisson_ratio_2 is None else poisson_ratio_2
    for name, value in (("youngs_modulus", youngs_modulus_1), ("youngs_modulus_2", e2),
                        ("cylinder_radius", cylinder_radius), ("work_of_adhesion", work_of_adhesion)):
        if not (isinstance(value, (int, float, np.floating)) and math.isfinite(value) and value > 0):
            raise ValueError(f"{name} must be a positive finite number; got {value!r}")
    for name, value in (("poisson_ratio", poisson_ratio_1), ("poisson_ratio_2", nu2)):
        if not (isinstance(value, (int, float, np.floating)) and -1.0 < value <= 0.5):
            raise ValueError(f"{name} must be in (-1, 0.5]; got {value!r}")
    if skew_angle_deg is not None:
        theta, mu = np.broadcast_arrays(np.deg2rad(np.asarray(skew_angle_deg, float)), np.asarray(mu, float))
        theta = np.clip(theta, float(geometry.skew_angle(1e-4)), 0.5 * np.pi)
    else:
        beta0, mu = np.broadcast_arrays(np.asarray(beta0, float), np.asarray(mu, float))
        theta = np.asarray(geometry.skew_angle(np.clip(beta0, 1e-4, 1.0)), float)  # Eqs. (3)-(4), (9)
    r1, r2 = geometry.principal_radii(cylinder_radius, theta)  # Eqs. (3)-(4)
    r = geometry.effective_radius(r1, r2)  # Eq. (5)
    e_star = geometry.reduced_modulus(youngs_modulus_1, poisson_ratio_1, e2, nu2)  # Eq. (6)
    sigma0 = mu * np.cbrt(e_star**2 * work_of_adhesion / r)  # Eq. (35)
    load_unit = 2.0 * np.pi * r * work_of_adhesion / np.sin(theta)  # Eq. (34)
    return {"skew_angle_deg": np.rad2deg(theta), "max_adhesive_stress": sigma0, "load_unit": load_unit}


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


def write_figure(build, path, dpi):
    """Check the three paths of ``path``, build the figure and write it as PNG, SVG and PDF, atomically.

    Parameters
    ----------
    build : callable
        ``build()`` returns the :class:`matplotlib.figure.Figure`; called after the paths are
        checked, with matplotlib on its ``Agg`` backend.  The figure is closed afterwards.
    path : path-like
        PNG file (:func:`figure_paths`).
    dpi : int
        PNG resolution [dots per inch].

    Returns
    -------
    tuple of Path
        The PNG, SVG and PDF paths of :func:`figure_paths`, written.
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    paths = figure_paths(path)
    fig = build()
    try:
        save_figure(fig, paths, dpi)
    finally:
        plt.close(fig)
    return paths
