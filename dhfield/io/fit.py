"""Input and output of the fits (:mod:`dhfield.fit`): the measured load curve, the residual plot.

:func:`read_curve_data` reads a measured load curve from CSV; :func:`write_residual_plot`
draws a :class:`dhfield.fit.CurveFit` (matplotlib at the edge, imported on use).
"""
from __future__ import annotations

import math
import re
from pathlib import Path

import numpy as np

from . import atomic_path, check_writable

__all__ = ["read_curve_data", "write_residual_plot", "DATA_COLUMNS", "FORCE_UNITS", "LENGTH_UNITS"]

#: Columns of a measured load curve: schema name -> accepted column names.
DATA_COLUMNS = {"force": ("force", "load"), "semi_major": ("semi_major", "contact_size"),
                "approach": ("approach",)}
#: Units accepted in a column header (``load [mN]`` or ``load (mN)``): unit -> factor to SI.
#: Case matters (mN is not MN); the micro sign may be u, the micro sign or the Greek mu.
FORCE_UNITS = {"N": 1.0, "kN": 1e3, "mN": 1e-3, "uN": 1e-6, "\u00b5N": 1e-6, "\u03bcN": 1e-6, "nN": 1e-9}
LENGTH_UNITS = {"m": 1.0, "cm": 1e-2, "mm": 1e-3, "um": 1e-6, "\u00b5m": 1e-6, "\u03bcm": 1e-6,
                "micron": 1e-6, "nm": 1e-9}
_QUANTITY_UNITS = {"force": ("force", FORCE_UNITS), "semi_major": ("length", LENGTH_UNITS),
                   "approach": ("length", LENGTH_UNITS)}
#: The units :func:`read_curve_data` proposes for a column without one (one per decade of 1e3).
_GUESSES = {"force": ("N", "mN", "uN", "nN"), "semi_major": ("m", "mm", "um", "nm"),
            "approach": ("m", "mm", "um", "nm")}
#: Plausible ratio of the largest compressive load to the Hertz load 4E*a^3/(3R) at its contact
#: size: adhesion lowers the load below Hertz's (ratio < 1, near 0 close to zero load), an
#: ellipse's Hertz load differs from the circle's by a factor below 2; a unit slip is >= 1e3.
_HERTZ_LOAD_RATIO = (1e-5, 1e2)
#: Plausible work of adhesion [J m^-2] of the most tensile load W_min, dgamma ~ -W_min/(1.75 pi R)
#: (between JKR's 1.5 pi R dgamma and DMT's 2 pi R dgamma): from liquids-wetted polymers (1e-4) to
#: clean metals (a few J m^-2); a unit slip moves it by 1e3.
_WORK_RANGE = (1e-4, 10.0)
#: Typical work of adhesion [J m^-2] (van der Waals solids): ranks the units that pass.
_TYPICAL_WORK = 0.05
#: Plausible ratio of the largest |approach| to a^2/R (Hertz: 1; JKR at pull-off: about 1/3).
_HERTZ_APPROACH_RATIO = (1e-3, 1e2)
_HEADER = re.compile(r"^\s*(?P<name>[^\[\]()]*?)\s*(?:\[\s*(?P<u1>[^\]]*?)\s*\]|\(\s*(?P<u2>[^)]*?)\s*\))\s*$")


def _split_header(column):
    """(name, unit or None) of a header such as ``load [mN]``, ``load (mN)`` or ``load``."""
    m = _HEADER.match(str(column))
    if m is None:
        return str(column).strip().lower(), None
    return m.group("name").lower(), m.group("u1") if m.group("u1") is not None else m.group("u2")


def read_curve_data(path, params=None) -> dict:
    """A measured load curve from a CSV file, in SI units.

    Parameters
    ----------
    path : path-like
        CSV with a header row: ``force`` (or ``load``), ``semi_major`` (or
        ``contact_size``), optionally ``approach``.  A header may carry a unit
        in brackets or parentheses, ``load [mN]``, ``contact_size (um)``: forces
        in :data:`FORCE_UNITS`, lengths in :data:`LENGTH_UNITS`; without one,
        forces are in N and lengths in m.
    params : dhfield.dimensional.ContactParameters, optional
        The contact: columns without a unit are checked against it (Notes).

    Returns
    -------
    dict
        ``force``, ``semi_major`` and (if present) ``approach``: float arrays [N], [m], [m].

    Raises
    ------
    ValueError
        One line naming the file and the column: a column missing, not numeric,
        an unknown unit, forces zero in every row, or (with ``params``)
        magnitudes that look like another unit -- the message names it.

    Notes
    -----
    Checks of columns without a unit (a unit in the header is taken as given):

    * contact sizes below the smaller principal radius R'' (Hertz theory needs
      a << R);
    * the most tensile load W_min: the work of adhesion it implies,
      :math:`-W_{min}/(1.75 \\pi R)` (between JKR's and DMT's pull-off), in
      :data:`_WORK_RANGE`;
    * the largest compressive load W against the Hertz load
      :math:`W_H = 4E^*a^3/(3R)` at its contact size: W/W_H in
      :data:`_HERTZ_LOAD_RATIO` (adhesion only lowers it);
    * the largest |approach| against :math:`a^2/R`: in :data:`_HERTZ_APPROACH_RATIO`.

    Where SI fails them, the units of :data:`_GUESSES` are tried (all
    combinations) and the one that passes with the most typical values
    (dgamma nearest 0.05 J/m^2, W/W_H nearest 1) is named in the message.
    The checks catch the slips of 1e3 between the units of the tables; an
    explicit unit in the header skips them.
    """
    from .table import read_table

    frame, _ = read_table(path)
    where = f"data file {str(path)!r}"
    cols, col_units = {}, {}
    headers = [_split_header(c) for c in frame.columns]
    for name, aliases in DATA_COLUMNS.items():
        found = [(col, unit) for col, (base, unit) in zip(frame.columns, headers) if base in aliases]
        if found:
            cols[name], col_units[name] = found[0]
        elif name != "approach":
            raise ValueError(f"{where} has no column {name!r} (or {', '.join(aliases[1:])}); "
                             f"columns: {', '.join(map(str, frame.columns))}")
    factors = {}
    for name, unit in col_units.items():
        if unit is None:
            continue
        kind, table = _QUANTITY_UNITS[name]
        if unit not in table:
            raise ValueError(f"{where}, column {cols[name]!r}: unknown {kind} unit {unit!r}; "
                             f"use one of {', '.join(table)}")
        factors[name] = table[unit]
    frame, _ = read_table(path, required=tuple(cols.values()))
    raw = {name: frame[col].to_numpy(dtype=float) for name, col in cols.items()}
    if not np.any(raw["force"] != 0.0):
        raise ValueError(f"{where}, column {cols['force']!r}: every load is 0; a load curve needs the "
                         "measured loads (compressive positive, pull-off negative)")
    if params is not None:
        _check_magnitudes(raw, factors, cols, params, where)
    return {name: values * factors.get(name, 1.0) for name, values in raw.items()}


def _plausible(raw, f, params):
    """(passes, score) of the data read with the factors ``f`` (see read_curve_data's Notes).

    The score (lower: more typical) is |log10(dgamma/0.05)| + |log10(W/W_H)|/2.
    """
    a = raw["semi_major"] * f["semi_major"]
    w = raw["force"] * f["force"]
    r, e = float(params.effective_radius), float(params.reduced_modulus)
    if not np.max(np.abs(a)) < float(params.r_minor):
        return False, math.inf
    score = 0.0
    if np.min(w) < 0.0:
        work = -float(np.min(w)) / (1.75 * math.pi * r)  # between JKR (1.5 pi R) and DMT (2 pi R)
        if not _WORK_RANGE[0] <= work <= _WORK_RANGE[1]:
            return False, math.inf
        score += abs(math.log10(work / _TYPICAL_WORK))
    k = int(np.argmax(w))
    if w[k] > 0.0:
        ratio = w[k] / (4.0 * e * a[k] ** 3 / (3.0 * r))  # Hertz: W = 4 E* a^3/(3R)
        if not _HERTZ_LOAD_RATIO[0] <= ratio <= _HERTZ_LOAD_RATIO[1]:
            return False, math.inf
        score += abs(math.log10(ratio)) / 2
    if "approach" in raw:
        d = np.max(np.abs(raw["approach"])) * f["approach"]
        q = d / (np.max(a) ** 2 / r)
        if d > 0.0 and not _HERTZ_APPROACH_RATIO[0] <= q <= _HERTZ_APPROACH_RATIO[1]:
            return False, math.inf
    return True, score


def _check_magnitudes(raw, factors, cols, params, where):
    import itertools

    free = [name for name in raw if name not in factors]
    if not free:
        return
    si = {name: factors.get(name, 1.0) for name in raw}
    ok, _ = _plausible(raw, si, params)
    if ok:
        return
    best = None
    for combo in itertools.product(*(_GUESSES[name] for name in free)):
        f = dict(si)
        for name, unit in zip(free, combo):
            f[name] = _QUANTITY_UNITS[name][1][unit]
        passes, score = _plausible(raw, f, params)
        if passes:
            if best is None or score < best[0]:
                best = (score, combo)
    a_max = float(np.max(np.abs(raw["semi_major"]))) * si["semi_major"]
    facts = (f"contact sizes up to {a_max:.3g} m against a radius of curvature of "
             f"{float(params.r_minor):.3g} m" if a_max >= float(params.r_minor) else
             "a work of adhesion -W_min/(1.75 pi R) outside [1e-4, 10] J/m^2, or loads, contact sizes and "
             "approaches off Hertz's W = 4E*a^3/(3R), delta = a^2/R by orders of magnitude")
    if best is None:
        raise ValueError(f"{where}: implausible magnitudes in SI units ({facts}); columns without a unit in "
                         "the header are read in N and m: check the values, or write the units in the header, "
                         "e.g. 'force [mN]', 'semi_major [um]'")
    guess = [(cols[name], unit) for name, unit in zip(free, best[1]) if _QUANTITY_UNITS[name][1][unit] != 1.0]
    parts = [f"{unit} (column {col!r})" for col, unit in guess]
    looks = parts[0] if len(parts) == 1 else ", ".join(parts[:-1]) + " and " + parts[-1]
    example = ", ".join(f"'{_split_header(col)[0]} [{unit}]'" for col, unit in guess)
    raise ValueError(f"{where}: these look like {looks}; columns without a unit in the header are expected "
                     f"in N and m ({facts}): write the units in the header, e.g. {example}")


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
