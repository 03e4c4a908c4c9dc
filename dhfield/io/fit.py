"""Input and output of the fits (:mod:`dhfield.analysis.fit`): the measured load curve, the residual plot.

:func:`read_curve_data` reads a measured load curve from CSV; :func:`write_residual_plot`
draws a :class:`dhfield.analysis.fit.CurveFit` (matplotlib at the edge, imported on use).
:func:`read_joint_data` reads data at several crossing angles (a ``skew_angle_deg`` column),
and :func:`write_joint_plot` draws a :class:`dhfield.analysis.fit.JointFit`.
"""
from __future__ import annotations

import math
import re
from pathlib import Path

import numpy as np

from .figures import model_label, si_prefix, write_figure

__all__ = ["read_curve_data", "write_residual_plot", "residual_figure", "format_with_uncertainty", "DATA_COLUMNS",
           "FORCE_UNITS", "LENGTH_UNITS", "MAX_DATA_ROWS", "ANGLE_COLUMNS", "ANGLE_UNITS", "has_angle_column",
           "read_joint_data", "joint_figure", "write_joint_plot"]

#: Most data rows of a measured load curve (:func:`read_curve_data`); a larger file is refused, naming
#: it and its row count, before anything is fitted.
MAX_DATA_ROWS = 1_000_000

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
    params : dhfield.analysis.dimensional.ContactParameters, optional
        The contact: columns without a unit are checked against it (Notes).

    Returns
    -------
    dict
        ``force``, ``semi_major`` and (if present) ``approach``: float arrays [N], [m], [m].

    Raises
    ------
    ValueError
        One line naming the file (and the column): more than :data:`MAX_DATA_ROWS`
        rows, a column missing, not numeric,
        an unknown unit, forces zero in every row, or (with ``params``)
        magnitudes that look like another unit -- the message names it.

    Notes
    -----
    Checks of columns without a unit (a unit in the header is taken as given):

    * contact semi-major axes below the larger principal radius R' (Hertz
      theory needs a << R');
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
    if len(frame) > MAX_DATA_ROWS:
        raise ValueError(f"{where} has {len(frame)} data rows; a load curve may have at most {MAX_DATA_ROWS} "
                         "(MAX_DATA_ROWS): thin the data or fit it in parts")
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
    if not np.max(np.abs(a)) < float(params.r_major):
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
    facts = (f"contact sizes up to {a_max:.3g} m against a largest radius of curvature of "
             f"{float(params.r_major):.3g} m" if a_max >= float(params.r_major) else
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


#: SI prefixes of :func:`format_with_uncertainty`, by power of ten.
_SI_PREFIXES = {-15: "f", -12: "p", -9: "n", -6: "\u00b5", -3: "m", 0: "", 3: "k", 6: "M", 9: "G", 12: "T"}


def format_with_uncertainty(value, stderr, unit) -> str:
    """``value ± stderr`` with an SI prefix and the precision the standard error allows.

    The standard error is rounded to two significant digits and the value to the
    same decimal place; the prefix is the power of 1000 of the value, e.g.
    ``format_with_uncertainty(7.941e4, 2e4, "Pa")`` gives ``"79 ± 20 kPa"``.
    A NaN or infinite standard error prints the value to 4 significant digits
    and ``(no s.e.)``.

    Parameters
    ----------
    value, stderr : float
        The estimate and its standard error, in ``unit``.
    unit : str
        SI unit without prefix (``"Pa"``, ``"J/m²"``, ``"N"``).

    Returns
    -------
    str
        The value with its uncertainty and unit.
    """
    value, stderr = float(value), float(stderr)
    if not math.isfinite(value):
        return f"{value} {unit}"
    exp3 = 0 if value == 0 else 3 * math.floor(math.log10(abs(value)) / 3)
    exp3 = min(max(exp3, min(_SI_PREFIXES)), max(_SI_PREFIXES))
    v, prefix = value / 10.0 ** exp3, _SI_PREFIXES[exp3]
    if not (math.isfinite(stderr) and stderr > 0):
        return f"{v:.4g} {prefix}{unit} (no s.e.)"
    s = stderr / 10.0 ** exp3
    place = 1 - math.floor(math.log10(s))  # decimal place of the second significant digit of s
    s_r = round(s, place)
    if s_r >= 10.0 ** (2 - place):  # rounding carried into a third digit (e.g. 99.6 -> 100)
        place -= 1
        s_r = round(s, place)
    v_r = round(v, place)
    decimals = max(place, 0)
    return f"{v_r:.{decimals}f} \u00b1 {s_r:.{decimals}f} {prefix}{unit}"


def _format_interval(interval, value, stderr, unit) -> str:
    """``[lo, hi] unit`` with the SI prefix and decimal places of :func:`format_with_uncertainty`."""
    lo, hi = (float(x) for x in interval)
    if not (math.isfinite(lo) and math.isfinite(hi)):
        return "(none)"
    text = format_with_uncertainty(value, stderr, unit)  # "v ± s prefix-unit": reuse its decimals and prefix
    number, rest = text.split(" \u00b1 ")
    decimals = len(number.split(".")[1]) if "." in number else 0
    prefixed = rest.split(" ", 1)[1]
    exp3 = 0 if value == 0 else 3 * math.floor(math.log10(abs(value)) / 3)  # as format_with_uncertainty
    factor = 10.0 ** -min(max(exp3, min(_SI_PREFIXES)), max(_SI_PREFIXES))
    return f"[{lo * factor:.{decimals}f}, {hi * factor:.{decimals}f}] {prefixed}"


def _three_digits(x) -> str:
    """Three significant digits without an exponent between 1e-3 and 1e6 (9610, not 9.61e+03)."""
    x = float(x)
    return f"{float(f'{x:.3g}'):g}" if 1e-3 <= abs(x) < 1e6 else f"{x:.3g}"


def residual_figure(fit, *, n=200):
    """Draw the figure of :func:`write_residual_plot` (data, smooth fitted curve, residuals).

    Parameters
    ----------
    fit : dhfield.analysis.fit.CurveFit
        The fit.
    n : int, default 200
        Points of the smooth fitted curve.

    Returns
    -------
    matplotlib.figure.Figure
        The figure.
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    a_curve, w_curve, d_curve = fit.model_curve(n)
    a_scale, a_unit = si_prefix(np.nanmax(np.abs(fit.contact_size)), "m")
    a_data = np.asarray(fit.contact_size) / a_scale
    with_approach = fit.approach is not None
    cols = 2 if with_approach else 1
    fig, axes = plt.subplots(2, cols, figsize=(5.2 * cols, 5.6), sharex=True, squeeze=False,
                             gridspec_kw={"height_ratios": (2.2, 1.0)})
    blocks = [("load W", "load residual", "N", fit.load, w_curve, fit.load_residuals, "o", "C0")]
    if with_approach:
        blocks.append(("approach δ", "approach residual", "m", fit.approach, d_curve, fit.approach_residuals,
                       "s", "C2"))
    for k, (label, res_label, unit, data, curve, residuals, marker, colour) in enumerate(blocks):
        scale, prefixed = si_prefix(np.nanmax(np.abs(data)), unit)
        r_scale, r_prefixed = si_prefix(np.nanmax(np.abs(residuals)), unit)  # residuals: their own prefix
        ax = axes[0, k]
        ax.plot(a_data, np.asarray(data) / scale, marker, ms=4.5, color=colour, label="data", zorder=3)
        ax.plot(np.asarray(a_curve) / a_scale, np.asarray(curve) / scale, "-", lw=1.6, color="C1",
                label=f"{model_label(fit.model)}, fitted")
        ax.set_ylabel(f"{label} [{prefixed}]")
        ax.legend(fontsize=9, loc="best", frameon=False)
        ax.grid(alpha=0.25)
        ax = axes[1, k]
        ax.axhline(0.0, color="0.5", lw=0.8)
        ax.plot(a_data, np.asarray(residuals) / r_scale, marker, ms=4.5, color=colour)
        ax.set_ylabel(f"{res_label} [{r_prefixed}]")
        ax.set_xlabel(f"contact semi-major axis a [{a_unit}]")
        ax.grid(alpha=0.25)
    title = (f"Δγ = {format_with_uncertainty(fit.work_of_adhesion, fit.work_of_adhesion_stderr, 'J/m²')},  "
             f"σ₀ = {format_with_uncertainty(fit.max_adhesive_stress, fit.max_adhesive_stress_stderr, 'Pa')}"
             f"\n(± 1 s.e.; μ = {_three_digits(fit.mu)}, β₀ = {_three_digits(fit.beta0)})")
    fig.suptitle(title, fontsize=10)
    notes = [m for m in (("not identifiable: see the fit's message" if not fit.success else ""),
                         ("model outside its validated range: see the fit's warning" if fit.warning else "")) if m]
    if notes:
        fig.text(0.5, 0.005, "; ".join(notes), ha="center", va="bottom", fontsize=8, color="C3")
    fig.tight_layout(rect=(0, 0.03 if notes else 0, 1, 1))
    return fig


def write_residual_plot(fit, path, *, dpi=150) -> tuple[Path, Path, Path]:
    """Write the data, the fitted curve and the residuals of ``fit`` as PNG, SVG and PDF.

    The model is drawn as a smooth curve over the measured range of contact sizes
    (:meth:`dhfield.analysis.fit.CurveFit.model_curve`), the estimates in the title with SI
    prefixes and the precision their standard errors allow
    (:func:`format_with_uncertainty`); with approaches, a second column.

    Parameters
    ----------
    fit : dhfield.analysis.fit.CurveFit
        The fit.
    path : path-like
        PNG file to write; the SVG and PDF are the same path with suffixes
        ``.svg`` and ``.pdf``.  All three are checked before any is written, and
        written atomically.
    dpi : int
        Resolution of the PNG.

    Returns
    -------
    (Path, Path, Path)
        The PNG, SVG and PDF paths.
    """
    return write_figure(lambda: residual_figure(fit), path, dpi)


#: Accepted names of the crossing-angle column of :func:`read_joint_data` (degrees unless the header says ``[rad]``).
ANGLE_COLUMNS = ("skew_angle_deg", "skew_angle", "crossing_angle_deg", "crossing_angle")
#: Units accepted in the crossing-angle header: unit -> factor to degrees.
ANGLE_UNITS = {"deg": 1.0, "\u00b0": 1.0, "rad": 180.0 / math.pi}


def _angle_column(frame):
    """(column, factor to degrees) of the crossing-angle column of ``frame``, or None."""
    for col in frame.columns:
        base, unit = _split_header(col)
        if base in ANGLE_COLUMNS:
            return col, unit
    return None


def has_angle_column(path) -> bool:
    """Whether a CSV file has a crossing-angle column (:data:`ANGLE_COLUMNS`).

    Parameters
    ----------
    path : path-like
        CSV file with a header row.

    Returns
    -------
    bool
        True when one of its columns is named in :data:`ANGLE_COLUMNS`.
    """
    from .table import read_table

    frame, _ = read_table(path)
    return _angle_column(frame) is not None


def read_joint_data(path) -> dict:
    """Data at several crossing angles from a CSV file, in SI units and degrees.

    Parameters
    ----------
    path : path-like
        CSV with a header row: ``skew_angle_deg`` (or another name of :data:`ANGLE_COLUMNS`;
        degrees, or radians with ``[rad]`` in the header), ``force`` (or ``load``) and optionally
        ``semi_major`` (or ``contact_size``).  Without a contact size each row is a pull-off force
        (negative); with it, a point of a load curve.  Units in the headers as for
        :func:`read_curve_data` (:data:`FORCE_UNITS`, :data:`LENGTH_UNITS`).

    Returns
    -------
    dict
        ``skew_angle_deg`` [deg], ``force`` [N] and (if present) ``semi_major`` [m]: float arrays.

    Raises
    ------
    ValueError
        One line naming the file and the column: more than :data:`MAX_DATA_ROWS` rows, a
        column missing or not numeric, an unknown unit, an ``approach`` column (not fitted
        jointly), or an angle outside (0, 90] degrees.
    """
    from .table import read_table

    frame, _ = read_table(path)
    where = f"data file {str(path)!r}"
    if len(frame) > MAX_DATA_ROWS:
        raise ValueError(f"{where} has {len(frame)} data rows; a joint fit may have at most {MAX_DATA_ROWS} "
                         "(MAX_DATA_ROWS): thin the data")
    found = _angle_column(frame)
    if found is None:
        raise ValueError(f"{where} has no crossing-angle column ({', '.join(ANGLE_COLUMNS)}); "
                         f"columns: {', '.join(map(str, frame.columns))}")
    angle_col, angle_unit = found
    if angle_unit is not None and angle_unit not in ANGLE_UNITS:
        raise ValueError(f"{where}, column {angle_col!r}: unknown angle unit {angle_unit!r}; use one of "
                         f"{', '.join(ANGLE_UNITS)}")
    cols, factors = {"skew_angle_deg": angle_col}, {"skew_angle_deg": ANGLE_UNITS.get(angle_unit, 1.0)}
    headers = [_split_header(c) for c in frame.columns]
    for name in ("force", "semi_major", "approach"):
        hit = [(col, unit) for col, (base, unit) in zip(frame.columns, headers) if base in DATA_COLUMNS[name]]
        if not hit:
            if name == "force":
                raise ValueError(f"{where} has no column 'force' (or load); columns: "
                                 f"{', '.join(map(str, frame.columns))}")
            continue
        col, unit = hit[0]
        if name == "approach":
            raise ValueError(f"{where}, column {col!r}: approaches are not fitted jointly over angles; "
                             "remove the column (or fit each angle with its own --data file)")
        cols[name] = col
        kind, table = _QUANTITY_UNITS[name]
        if unit is not None and unit not in table:
            raise ValueError(f"{where}, column {col!r}: unknown {kind} unit {unit!r}; use one of {', '.join(table)}")
        factors[name] = table.get(unit, 1.0) if unit is not None else 1.0
    frame, _ = read_table(path, required=tuple(cols.values()))
    out = {name: frame[col].to_numpy(dtype=float) * factors[name] for name, col in cols.items()}
    angles = out["skew_angle_deg"]
    bad = ~((angles > 0.0) & (angles <= 90.0))
    if np.any(bad):
        raise ValueError(f"{where}, column {angle_col!r}: a crossing angle must be in (0, 90] degrees; got "
                         f"{float(angles[bad][0]):g} in row {int(np.flatnonzero(bad)[0]) + 1}")
    if "semi_major" not in out and not np.all(out["force"] < 0.0):
        k = int(np.flatnonzero(~(out["force"] < 0.0))[0])
        raise ValueError(f"{where}, column {cols['force']!r}: without a contact-size column each row is a pull-off "
                         f"force, which must be negative (tensile); got {float(out['force'][k]):g} in row {k + 1}")
    return out


def joint_figure(fit, *, n=120):
    """Draw the figure of :func:`write_joint_plot`.

    Parameters
    ----------
    fit : dhfield.analysis.fit.JointFit
        The fit.
    n : int, default 120
        Points of each smooth model curve.

    Returns
    -------
    matplotlib.figure.Figure
        The figure.
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    angles = np.asarray(fit.skew_angle_deg)
    fig, axes = plt.subplots(2, 1, figsize=(6.0, 6.2), sharex=True, gridspec_kw={"height_ratios": (2.2, 1.0)})
    f_scale, f_unit = si_prefix(np.nanmax(np.abs(fit.force)), "N")
    label = f"{model_label(fit.model)}, fitted"
    if fit.kind == "pull_off":
        lo, hi = float(np.min(angles)), float(np.max(angles))
        pad = 0.05 * (hi - lo) if hi > lo else 2.0
        grid = np.linspace(max(lo - pad, 1e-3), min(hi + pad, 90.0), n)
        axes[0].plot(angles, fit.force / f_scale, "o", ms=4.5, color="C0", label="data", zorder=3)
        axes[0].plot(grid, fit.model_pull_off(grid) / f_scale, "-", lw=1.6, color="C1", label=label)
        axes[0].set_ylabel(f"pull-off force [{f_unit}]")
        residuals = 100.0 * (fit.force - fit.force_fitted) / np.abs(fit.force_fitted)
        axes[1].plot(angles, residuals, "o", ms=4.5, color="C0")
        axes[1].set_ylabel("residual [% of model]")
        axes[1].set_xlabel("crossing angle θ [deg]")
    else:
        a_scale, a_unit = si_prefix(np.nanmax(fit.contact_size), "m")
        residuals = fit.force - fit.force_fitted
        r_scale, r_unit = si_prefix(np.nanmax(np.abs(residuals)), "N")
        for k, a in enumerate(fit.angles):
            rows = angles == a
            colour = f"C{k % 10}"
            axes[0].plot(fit.contact_size[rows] / a_scale, fit.force[rows] / f_scale, "o", ms=4.5, color=colour,
                         label=f"data, {a:g}°", zorder=3)
            a_curve, w_curve = fit.model_curve(a, n)
            axes[0].plot(a_curve / a_scale, w_curve / f_scale, "-", lw=1.4, color=colour)
            axes[1].plot(fit.contact_size[rows] / a_scale, residuals[rows] / r_scale, "o", ms=4.5, color=colour)
        axes[0].plot([], [], "-", color="0.3", label=label)
        axes[0].set_ylabel(f"load W [{f_unit}]")
        axes[1].set_ylabel(f"load residual [{r_unit}]")
        axes[1].set_xlabel(f"contact semi-major axis a [{a_unit}]")
    axes[1].axhline(0.0, color="0.5", lw=0.8)
    for ax in axes:
        ax.grid(alpha=0.25)
    axes[0].legend(fontsize=8, loc="best", frameon=False)
    parts = [f"Δγ = {format_with_uncertainty(fit.work_of_adhesion, fit.work_of_adhesion_stderr, 'J/m²')}"]
    if "max_adhesive_stress" in fit.fitted:
        parts.append(f"σ₀ = {format_with_uncertainty(fit.max_adhesive_stress, fit.max_adhesive_stress_stderr, 'Pa')}")
    else:
        parts.append(f"σ₀ = {format_with_uncertainty(fit.max_adhesive_stress, math.nan, 'Pa')}"
                     .replace("(no s.e.)", "(fixed)"))
    interval = _format_interval(fit.work_of_adhesion_interval, fit.work_of_adhesion, fit.work_of_adhesion_stderr,
                                "J/m²")
    fig.suptitle(",  ".join(parts) + f"\n(± 1 standard error; 95 % interval of Δγ {interval}; "
                 f"{len(fit.angles)} angles, {fit.force.size} rows)", fontsize=9.5)
    notes = [m for m in (("not identifiable: see the fit's message" if not fit.success else ""),
                         ("outside the model's validated or verified range: see the fit's warning"
                          if fit.warning else "")) if m]
    if notes:
        fig.text(0.5, 0.005, "; ".join(notes), ha="center", va="bottom", fontsize=8, color="C3")
    fig.tight_layout(rect=(0, 0.03 if notes else 0, 1, 1))
    return fig


def write_joint_plot(fit, path, *, dpi=150) -> tuple[Path, Path, Path]:
    """Write the data of a joint fit against the fitted model as PNG, SVG and PDF.

    Pull-off forces: the data and the fitted pull-off force against the crossing angle, one
    smooth curve over the angles; load curves: load against contact size, one colour and one
    fitted curve per angle.  Residuals below; the estimates in the title with the precision
    their standard errors allow (:func:`format_with_uncertainty`).

    Parameters
    ----------
    fit : dhfield.analysis.fit.JointFit
        The fit.
    path : path-like
        PNG file to write; the SVG and PDF take the same path with suffixes ``.svg`` and
        ``.pdf``.  All three are checked before any is written, and written atomically.
    dpi : int
        Resolution of the PNG.

    Returns
    -------
    (Path, Path, Path)
        The PNG, SVG and PDF paths.
    """
    return write_figure(lambda: joint_figure(fit), path, dpi)
