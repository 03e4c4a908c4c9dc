"""Figure of a loading-unloading cycle (:func:`dhfield.analysis.spring.cycle_path`): matplotlib at the edge.

:func:`round_to_uncertainty` prints the energy lost to the digits its stated uncertainty (the
quadrature's and the jump-in convention's, :mod:`dhfield.analysis.spring`) supports.
"""
from __future__ import annotations

from pathlib import Path

import numpy as np

from .figures import figure_paths, model_label, save_figure

__all__ = ["write_cycle_plot", "round_to_uncertainty"]


def write_cycle_plot(path_data, path, *, force_unit=None, approach_unit=None, dpi=130) -> Path:
    """Draw force against approach with both jumps marked and the energy lost shaded.

    Parameters
    ----------
    path_data : dict
        From :func:`dhfield.analysis.spring.cycle_path`.
    path : path-like
        PNG file to write; an SVG and a PDF are written beside it (same path, suffixes
        ``.svg`` and ``.pdf``), all three checked first and written atomically.
    force_unit, approach_unit : float, optional
        SI scales [N] and [m] of W* and delta* (both or neither); the axes are then
        in mN and um, else nondimensional (Eq. 34 and c_r^2/R).
    dpi : int
        Resolution of the PNG.

    Returns
    -------
    Path
        The PNG written.
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    paths = figure_paths(path)
    png = paths[0]
    rec = path_data["record"]
    si = force_unit is not None
    fs = 1e3 * force_unit if si else 1.0  # mN
    ds = 1e6 * approach_unit if si else 1.0  # um
    fl = "force W [mN] (compressive > 0)" if si else "load W* = W sin(θ)/(2πRΔγ)  (Eq. 34)"
    dl = "approach δ [µm]" if si else "approach δ* = δR/c_r²"

    fig, ax = plt.subplots(figsize=(6.4, 4.6))
    bd, bw = path_data["branch"]
    ld, lw = path_data["loop"]
    finite = np.all(np.isfinite(ld))
    if finite:
        ax.fill(ld * ds, lw * fs, color="C1", alpha=0.25, lw=0, label="energy lost per cycle")
    ax.plot(bd * ds, bw * fs, "-", color="C0", lw=1.8, label="equilibrium curve (stable under the machine)")
    ad, aw = path_data["approach"]
    lo = min(float(np.min(bd)), float(ad[0]))
    sep = rec["separation_delta_star"]
    left = lo if np.isfinite(sep) else lo - 0.3 * (float(np.max(bd)) - lo)
    ax.plot(np.array([left, ad[1]]) * ds, aw * fs, "-", color="0.35", lw=1.4, label="separated, W = 0")
    jd, jw = path_data["jump_in"]
    ax.annotate("", xy=(jd[1] * ds, jw[1] * fs), xytext=(jd[0] * ds, jw[0] * fs),
                arrowprops=dict(arrowstyle="-|>", color="C2", lw=1.8))
    ax.plot(jd * ds, jw * fs, "o", color="C2", ms=5, label="jump in (approach)")
    od, ow = path_data["jump_out"]
    if not np.isfinite(od[1]):  # load control: the contact flies off at constant load
        od = np.array([od[0], left])
        ow = np.array([ow[0], ow[0]])
    ax.annotate("", xy=(od[1] * ds, ow[1] * fs), xytext=(od[0] * ds, ow[0] * fs),
                arrowprops=dict(arrowstyle="-|>", color="C3", lw=1.8))
    ax.plot(od[:1] * ds, ow[:1] * fs, "s", color="C3", ms=6, label="jump out (retraction)")
    ax.axhline(0.0, color="0.75", lw=0.6, zorder=0)
    ax.set_xlabel(dl)
    ax.set_ylabel(fl)
    k = rec["machine_stiffness_star"]
    machine = ("rigid machine (displacement control)" if not np.isfinite(k) else
               "load control (K = 0)" if k == 0 else
               f"machine stiffness K = {rec['machine_stiffness']:.3g} N/m" if si and "machine_stiffness" in rec
               else f"machine stiffness K* = {k:.3g}")
    if not np.isfinite(rec["energy_lost_star"]):
        energy = "energy lost: infinite (K = 0)"
    elif si:
        u = rec.get("energy_lost_uncertainty", float("nan"))
        energy = f"energy lost {round_to_uncertainty(rec['energy_lost'] * 1e9, u * 1e9)} ± {u * 1e9:.2g} nJ"
    else:
        u = rec.get("energy_lost_uncertainty_star", float("nan"))
        energy = f"energy lost U* = {round_to_uncertainty(rec['energy_lost_star'], u)} ± {u:.2g}"
    out = rec["jump_out_W_star"] * fs
    inn = rec["jump_in_W_star"] * fs
    inn = 0.0 if abs(inn) < 1e-12 * max(1.0, abs(out)) else inn  # rounding of a zero-load landing
    unit = " mN" if si else ""
    ax.set_title(f"{model_label(rec['model'])}: β0 = {rec['beta0']:.3g}, μ = {rec['mu']:.3g}; {machine}\n"
                 f"jump in at W = {inn:.4g}{unit}, jump out at W = {out:.4g}{unit}; {energy}", fontsize=9)
    handles, labels = ax.get_legend_handles_labels()  # below the axes: inside, it hid the curve's minimum
    fig.legend(handles, labels, fontsize=8, loc="lower center", ncol=2, frameon=False)
    fig.set_size_inches(6.4, 5.2)
    fig.tight_layout(rect=(0, 0.13, 1, 1))
    try:
        save_figure(fig, paths, dpi)
    finally:
        plt.close(fig)
    return png


def round_to_uncertainty(value, uncertainty) -> str:
    """Print ``value`` to the digits ``uncertainty`` supports: the decimal place of its second significant digit.

    Parameters
    ----------
    value : float
        The value.
    uncertainty : float
        Its stated uncertainty, >= 0, same unit.  0: ``value`` to 10 significant digits; NaN:
        4 significant digits and ``(uncertainty unknown)``.

    Returns
    -------
    str
        E.g. ``round_to_uncertainty(1.566931205e-09, 1.84e-10)`` gives ``"1.57e-09"`` and
        ``round_to_uncertainty(0.8101828563, 0.095)`` gives ``"0.810"``; a value below the
        uncertainty's first digit keeps one significant digit.
    """
    import math

    value, uncertainty = float(value), float(uncertainty)
    if not math.isfinite(value):
        return str(value)
    if not math.isfinite(uncertainty):
        return f"{value:.4g} (uncertainty unknown)"
    if uncertainty <= 0.0 or value == 0.0:
        return f"{value:.10g}"
    place = math.floor(math.log10(uncertainty)) - 1          # power of ten of the 2nd significant digit
    digits = math.floor(math.log10(abs(value))) - place + 1  # significant digits of value to that place
    digits = min(max(digits, 1), 10)
    if abs(math.log10(abs(value))) >= 4:
        return f"{value:.{digits - 1}e}"
    last = math.floor(math.log10(abs(value))) - digits + 1  # power of ten of the last digit kept
    return f"{round(value, -last):.{max(-last, 0)}f}"
