"""Figure of the pull-off force against the crossing angle for one material (``dhfield force-vs-angle``).

Two panels sharing the crossing angle (:class:`dhfield.analysis.force_vs_angle.ForceVsAngle`):

* the pull-off force of every model [N, with an SI prefix], the tensile magnitude -W, the
  recommended model drawn first in the legend and on top, in black and thickest, with its
  estimated error band (:mod:`dhfield.analysis.model_error`) shaded where a stored BEM case checks it,
  and the stored BEM pull-offs that lie on the material's path, in newtons, with their stated
  errors;
* the material's Tabor parameter mu against the angle, over the stored BEM cases (each at the
  angle of its beta0) and the box they span: the cases on the path are those the upper panel
  shows.  A stored W* off the path is the pull-off of another contact, so it is shown here, on
  the nondimensional axes, and not converted into a force the material does not have.

Every other model has its own combination of colour, line style and marker
(:func:`model_styles`), distinct for up to 140 models.
"""
from __future__ import annotations

import numpy as np

from ..analysis.compare import RECOMMENDED_MODEL
from .figures import model_label, si_prefix, write_figure

__all__ = ["COLOURS", "LINE_STYLES", "MARKERS", "model_styles", "force_vs_angle_figure", "write_force_vs_angle_plot"]

#: Colours of the models other than the recommended one (matplotlib's tab10).
COLOURS = ("#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b", "#e377c2", "#7f7f7f",
           "#bcbd22", "#17becf")
#: Line styles, cycled with the colours: 4 styles against 10 colours and 7 markers.
LINE_STYLES = ("--", "-.", ":", (0, (5, 1, 1, 1, 1, 1)))
#: Markers, cycled with the colours and line styles.
MARKERS = ("o", "s", "^", "v", "D", "P", "X")
#: Style of the recommended model: drawn on top, black and thickest.
_RECOMMENDED_STYLE = {"color": "black", "linestyle": "-", "marker": None, "linewidth": 2.8, "zorder": 10}


def model_styles(models):
    """Return a distinct line style for each model, the recommended one black, solid and thickest.

    Parameters
    ----------
    models : sequence of str
        Model names.

    Returns
    -------
    dict
        Model -> keyword arguments of :meth:`matplotlib.axes.Axes.plot` (``color``, ``linestyle``,
        ``marker``, ``linewidth``, ``zorder``).  The i-th other model takes colour i mod 10, line
        style i mod 4 and marker i mod 7: no two of the first 140 share all three.
    """
    out, i = {}, 0
    for name in models:
        if name == RECOMMENDED_MODEL:
            out[name] = dict(_RECOMMENDED_STYLE)
            continue
        out[name] = {"color": COLOURS[i % len(COLOURS)], "linestyle": LINE_STYLES[i % len(LINE_STYLES)],
                     "marker": MARKERS[i % len(MARKERS)], "linewidth": 1.4, "zorder": 3}
        i += 1
    return out


def _quantity(value, unit, symbol):
    scale, label = si_prefix(value, unit)
    return f"{symbol} = {value / scale:.3g} {label}"


def _answered_label(table, name):
    """The legend label of a model: its name, and the angles it answered at where not all."""
    f, at = table.force[name], table.evaluated[name]
    ok = at & np.isfinite(f)
    label = model_label(name)
    if not np.any(ok):
        return f"{label} (no answer here)"
    if np.all(ok[at]):
        return label
    th = table.skew_angle_deg[ok]
    return f"{label} ({th.min():.0f}–{th.max():.0f}° only)"


def force_vs_angle_figure(table):
    """Draw the pull-off force of every model against the crossing angle, and the BEM cases' map.

    Parameters
    ----------
    table : dhfield.analysis.force_vs_angle.ForceVsAngle
        From :func:`dhfield.analysis.force_vs_angle.pull_off_force_vs_angle`.

    Returns
    -------
    matplotlib.figure.Figure
        Upper panel: -W [N, prefixed] of every model; lower panel: mu against the angle.
    """
    import matplotlib.pyplot as plt

    th = table.skew_angle_deg
    finite = np.concatenate([np.abs(f[np.isfinite(f)]) for f in table.force.values()] + [np.zeros(0)])
    scale, unit = si_prefix(np.median(finite) if finite.size else 1.0, "N")
    fig, (ax, ax_mu) = plt.subplots(2, 1, figsize=(11.5, 8.6), sharex=True,
                                    gridspec_kw={"height_ratios": (3.0, 1.35), "hspace": 0.08})
    styles = model_styles(table.models)
    rec = table.recommended_model
    for name in table.models:  # the recommended model first
        f, at = table.force[name], table.evaluated[name]
        ok = at & np.isfinite(f)
        st = styles[name]
        every = max(1, int(ok.sum()) // 9) if at.all() else 1
        ax.plot(th[ok], -f[ok] / scale, label=_answered_label(table, name), markevery=every, markersize=5,
                **st)
    # the recommended model's error band, where a stored BEM case checks it
    e = table.recommended_error
    band = np.isfinite(e) & np.isfinite(table.force[rec])
    f_rec = -table.force[rec] / scale
    if np.any(band):
        ax.fill_between(th, f_rec * (1 - e), f_rec * (1 + e), where=band, color="black", alpha=0.18, lw=0,
                        zorder=2, label=f"{model_label(rec)}: estimated error vs BEM")
    else:
        ax.text(0.99, 0.98, f"{model_label(rec)}: no error band; no stored BEM case\nchecks these points "
                f"(μ {np.nanmin(table.mu):.3g}–{np.nanmax(table.mu):.3g} here)", transform=ax.transAxes,
                fontsize=8, color="0.25", va="top", ha="right")
    bem = table.bem
    if len(bem):
        ax.errorbar(np.minimum(bem.skew_angle_deg, 90.0), -bem.force / scale, yerr=bem.force_error / scale,
                    fmt="D", color="red", mec="black", ms=7, capsize=3, zorder=12,
                    label="adhesive BEM, stored (on this path)")
    ax.set_ylabel(f"pull-off force −W (tensile) [{unit}]")
    inp = table.inputs
    title = ", ".join([_quantity(inp["youngs_modulus_1"], "Pa", "E"), f"ν = {inp['poisson_ratio_1']:g}",
                       _quantity(inp["cylinder_radius"], "m", "R_c"),
                       _quantity(inp["work_of_adhesion"], "J/m²", "Δγ"),
                       _quantity(inp["max_adhesive_stress"], "Pa", "σ0")])
    if inp["youngs_modulus_2"] != inp["youngs_modulus_1"] or inp["poisson_ratio_2"] != inp["poisson_ratio_1"]:
        title += ", body 2: " + _quantity(inp["youngs_modulus_2"], "Pa", "E2") + f", ν2 = {inp['poisson_ratio_2']:g}"
    ax.set_title(f"Pull-off force of two equal crossed cylinders against their crossing angle\n{title}",
                 fontsize=10)
    ax.grid(True, alpha=0.3)
    ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=8, frameon=False)

    # lower panel: the material's path through (angle, mu) over the stored BEM cases
    st = table.stored
    box_th = (float(np.min(st.skew_angle_deg)), 90.0)
    box_mu = (float(np.min(st.mu)), float(np.max(st.mu)))
    ax_mu.fill_between(box_th, box_mu[0], box_mu[1], color="tab:green", alpha=0.12, lw=0,
                       label="box of the stored BEM cases")
    ax_mu.plot(np.minimum(st.skew_angle_deg, 90.0), st.mu, "o", mfc="none", mec="0.45", ms=5,
               label=f"stored BEM case ({len(st)})")
    ax_mu.plot(th, table.mu, "-", color="black", lw=2, label="this material's μ (Eq. 35)")
    if len(bem):
        ax_mu.plot(np.minimum(bem.skew_angle_deg, 90.0), bem.mu, "D", color="red", mec="black", ms=7,
                   label=f"on the path ({len(bem)})")
    ax_mu.set_yscale("log")
    lo = min(box_mu[0], float(np.nanmin(table.mu)))
    hi = max(box_mu[1], float(np.nanmax(table.mu)))
    ax_mu.set_ylim(lo / 1.6, hi * 1.6)
    ax_mu.set_ylabel("Tabor parameter μ")
    ax_mu.set_xlabel("crossing angle θ [deg]  (β0 from Eqs. 3-4, 9)")
    ax_mu.grid(True, which="both", alpha=0.25)
    ax_mu.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=8, frameon=False)
    ax_mu.set_xlim(th[0] - 1.0, th[-1] + 1.0)
    fig.subplots_adjust(left=0.08, right=0.70, top=0.92, bottom=0.08)
    return fig


def write_force_vs_angle_plot(table, path, dpi=150):
    """Write :func:`force_vs_angle_figure` as PNG, SVG and PDF, atomically.

    Parameters
    ----------
    table : dhfield.analysis.force_vs_angle.ForceVsAngle
        The table to draw.
    path : path-like
        The PNG file; the SVG and PDF go beside it (:func:`dhfield.io.figures.figure_paths`).
    dpi : int, default 150
        PNG resolution [dots per inch].

    Returns
    -------
    tuple of Path
        The PNG, SVG and PDF paths, written.
    """
    return write_figure(lambda: force_vs_angle_figure(table), path, dpi)
