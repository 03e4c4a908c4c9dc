"""Figure of an adhesive BEM pull-off (``dhfield solve --plot``): matplotlib at the edge.

Three panels of a BEM pull-off (:class:`dhfield.core.records.PullOff` with its path):

* the contact and the cohesive (adhesive) zone of the pull-off state, with the
  ellipses of semi-axes (a, b) and (c, d) fitted from the second moments of the
  masks (:meth:`dhfield.bem.ContactState.contact_semi_axes`);
* the total pressure of that state (compressive positive; the Dugdale traction
  -sigma0 is negative), on a colour scale centred on zero;
* the load-approach path of the result (:class:`dhfield.bem.UnloadingPath`: the
  states solved on this grid, the pull-off marked), over the load curve of the
  analytic ``dh-elliptic-two-axis`` model for reference.

With the contact's :class:`dhfield.analysis.dimensional.ContactParameters` the axes are in
SI units with prefixes (Eqs. 32-35 inverted), else in the paper's units.
"""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from .figures import SI_PREFIXES, model_label, si_prefix, write_figure

__all__ = ["solve_figure", "write_solve_plot", "REFERENCE_MODEL"]

#: Analytic model drawn under the BEM path: the elliptical double-Hertz model with the
#: two-axis closure, the one that agrees with the BEM across mu (README, model choice).
REFERENCE_MODEL = "dh-elliptic-two-axis"

#: SI prefixes of this figure's axes: those of :func:`si_prefix` from nano up (no pico).
_PREFIXES = tuple(p for p in SI_PREFIXES if p[0] >= 1e-9)


def _prefix(magnitude: float, unit: str) -> tuple[float, str]:
    """(scale, label) that puts ``magnitude`` [unit] between 1 and 1000 in a prefixed unit (nano up)."""
    return si_prefix(magnitude, unit, prefixes=_PREFIXES)


def _scales(result, params):
    """Scales and labels of length, approach, stress and load, SI (with params) or paper's units."""
    from ..core.geometry import sin_skew_angle

    sin_skew = float(sin_skew_angle(result.beta0))
    if params is None:
        return {"length": (1.0, "c_r"), "approach": (1.0, "c_r²/R"), "stress": (1.0, "E*c_r/R"),
                "load": (sin_skew / (2.0 * math.pi), None), "si": False}
    from .solution import stress_unit

    lu, au = float(params.length_unit), float(params.approach_unit)
    su = stress_unit(params)
    fu = float(params.effective_radius * params.work_of_adhesion)  # the path's load is in R dgamma
    st = result.path.pull_off_state
    ls, ll = _prefix(result.c_star * lu, "m")
    as_, al = _prefix(np.nanmax(np.abs(result.path.approach)) * au, "m")
    ss, sl = _prefix(np.nanmax(np.abs(st.pressure)) * su, "Pa")
    fs, fl = _prefix(abs(result.path.pull_off_load) * fu, "N")
    return {"length": (lu / ls, ll), "approach": (au / as_, al), "stress": (su / ss, sl),
            "load": (fu / fs, fl), "si": True}


def _stress_unit(params) -> float:
    """The paper's stress unit E* c_r/R [Pa] (pressures of the state are in it)."""
    from .solution import stress_unit

    return stress_unit(params)


def _two_sided_ticks(lo: float, hi: float) -> np.ndarray:
    """Colour-bar ticks of a scale centred on zero: nice ticks on each side, zero included."""
    from matplotlib.ticker import MaxNLocator

    neg = MaxNLocator(nbins=4).tick_values(lo, 0.0) if lo < 0 else np.array([0.0])
    pos = MaxNLocator(nbins=3).tick_values(0.0, hi) if hi > 0 else np.array([0.0])
    ticks = np.unique(np.concatenate([neg, pos]))
    return ticks[(ticks >= lo) & (ticks <= hi)]


def _ellipses(ax, result, k, colour_ab="k", colour_cd="k"):
    from matplotlib.patches import Ellipse

    ax.add_patch(Ellipse((0, 0), 2 * result.a_star * k, 2 * result.b_star * k, fill=False, ec=colour_ab, lw=1.4,
                         ls="-", label="fitted contact ellipse (a, b)"))
    ax.add_patch(Ellipse((0, 0), 2 * result.c_star * k, 2 * result.d_star * k, fill=False, ec=colour_cd, lw=1.4,
                         ls="--", label="fitted adhesive ellipse (c, d)"))


def _zoom(ax, result, k):
    c = max(result.c_star, result.a_star) * k
    d = max(result.d_star, result.b_star) * k
    ax.set_xlim(-1.25 * c, 1.25 * c)
    ax.set_ylim(-(1.25 * d + 0.1 * c), 1.25 * d + 0.1 * c)
    ax.set_aspect("equal")


def solve_figure(result, params=None):
    """The matplotlib figure of :func:`write_solve_plot` (map, pressure, path).

    Parameters
    ----------
    result : dhfield.core.records.PullOff
        The pull-off, with its path and the state at pull-off.
    params : dhfield.analysis.dimensional.ContactParameters, optional
        The contact solved (same beta0 and mu): SI axes.  Without it the paper's units.

    Returns
    -------
    matplotlib.figure.Figure
        The figure (close it with ``matplotlib.pyplot.close``).
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.colors import ListedColormap, TwoSlopeNorm
    from matplotlib.ticker import FormatStrFormatter

    from .solution import REGIONS, region_codes

    sc = _scales(result, params)
    si = sc["si"]
    lk, ll = sc["length"]
    st = result.path.pull_off_state
    g = st.grid
    x, y = np.asarray(g.x) * lk, np.asarray(g.y) * lk
    fig = plt.figure(figsize=(9.0, 7.6), layout="constrained")
    gs = fig.add_gridspec(2, 2, height_ratios=(1.0, 1.05), width_ratios=(1.0, 1.2))
    axes = [fig.add_subplot(gs[0, 0]), fig.add_subplot(gs[0, 1]), fig.add_subplot(gs[1, :])]

    # (a) contact and cohesive zone, fitted ellipses
    ax = axes[0]
    region = region_codes(st).T  # (y, x)
    colours = {"contact": "#3b6fb6", "cohesive_zone": "#f2a541", "outside": "#ffffff"}
    cmap = ListedColormap([colours[r] for r in REGIONS])
    ax.pcolormesh(x, y, region, cmap=cmap, vmin=-0.5, vmax=len(REGIONS) - 0.5, shading="nearest",
                  rasterized=True)
    _ellipses(ax, result, lk)
    ax.set_title("contact and adhesive zone at pull-off\nfitted ellipses: solid (a, b), dashed (c, d)",
                 fontsize=10)
    _zoom(ax, result, lk)
    lo_y, hi_y = ax.get_ylim()
    ax.set_ylim(lo_y, hi_y + 0.3 * (hi_y - lo_y))  # room for the zone's label above the ellipses
    ax.text(0.0, 0.0, "contact", ha="center", va="center", color="white", fontsize=10)
    zone = "cohesive zone (Dugdale)" if result.law == "dugdale" else "cohesive zone"
    ax.annotate(zone, xy=(0.0, 0.5 * (result.b_star + result.d_star) * lk),
                xytext=(0.0, hi_y + 0.12 * (hi_y - lo_y)), ha="center", va="center", fontsize=9,
                arrowprops=dict(arrowstyle="-|>", color="0.2", lw=1.0))
    ax.set_xlabel(f"x (major axis) [{ll}]")
    ax.set_ylabel(f"y (minor axis) [{ll}]")

    # (b) pressure, centred on zero
    ax = axes[1]
    sk, sl = sc["stress"]
    p = np.asarray(st.pressure).T * sk
    lo, hi = float(np.min(p)), float(np.max(p))
    norm = TwoSlopeNorm(vmin=min(lo, -1e-12 * max(hi, 1.0)), vcenter=0.0, vmax=max(hi, 1e-12 * max(-lo, 1.0)))
    im = ax.pcolormesh(x, y, p, cmap="RdBu_r", norm=norm, shading="nearest", rasterized=True)
    _ellipses(ax, result, lk, "0.15", "0.15")
    _zoom(ax, result, lk)
    cb = fig.colorbar(im, ax=ax, shrink=0.85, pad=0.02)
    cb.set_ticks(_two_sided_ticks(norm.vmin, norm.vmax))  # TwoSlopeNorm alone may label one side only
    cb.ax.yaxis.set_major_formatter(FormatStrFormatter("%g"))
    s0 = (f"−σ0 = −{float(params.max_adhesive_stress) * sk / _stress_unit(params):.3g} {sl}" if si
          else f"−σ0 = −μ = −{result.mu:.3g}")
    cb.set_label(f"pressure p [{sl}], compressive > 0\n(cohesive zone: {s0})", fontsize=9)
    ax.set_xlabel(f"x (major axis) [{ll}]")
    ax.set_title("pressure at pull-off", fontsize=10)

    # (c) load-approach path
    ax = axes[2]
    ak, al = sc["approach"]
    fk, fl = sc["load"]
    path = result.path
    _reference_curve(ax, result, ak, fk)
    d = np.asarray(path.approach, float) * ak
    w = np.asarray(path.load, float) * fk
    ok = np.asarray(path.converged, bool)
    phases = np.asarray([str(q) for q in path.phase])
    jump = phases == "jump"  # re-solved from separation after the branch ended: W = 0
    sel = ok & ~jump
    ax.plot(d[sel], w[sel], "o", ms=5, color="C0", mfc="none", mew=1.4,
            label=f"BEM states, N = {result.n} (loading, unloading, refinement)")
    if np.any(ok & jump):
        ax.plot(d[ok & jump], w[ok & jump], "o", ms=5, color="C2", mfc="none", mew=1.4,
                label="BEM, after the jump out: separated (W = 0)")
    if np.any(~ok):
        ax.plot(d[~ok], w[~ok], "x", ms=6, color="C3", label="BEM: unconverged (excluded)")
    ax.plot([path.pull_off_approach * ak], [path.pull_off_load * fk], "*", ms=13, color="C3", mec="k", mew=0.6,
            label="pull-off", zorder=5)
    ax.set_xlabel(f"approach δ [{al}]" if si else "approach δ* = δR/c_r²  (Eq. 33)")
    ax.set_ylabel(f"force W [{fl}]  (compressive > 0)" if si else "load W* = W sin θ/(2πRΔγ)  (Eq. 34)")
    ax.legend(fontsize=9, loc="upper right", framealpha=0.9)
    ax.grid(alpha=0.25)
    ax.set_title(f"load–approach path ({result.control} control)", fontsize=10)

    flag = "" if (result.converged and getattr(result, "resolved", True)) else \
        "   [NOT " + ("converged" if not result.converged else "resolved") + ": not an answer]"
    if si:
        wu, wl = _prefix(result.W_star * float(params.load_unit), "N")
        lq, lql = _prefix(result.c_star * float(params.length_unit), "m")
        head = (f"BEM pull-off W = {result.W_star * float(params.load_unit) / wu:.4g} {wl} (W* = {result.W_star:.4g}); "
                f"a, b = {result.a_star * params.length_unit / lq:.3g}, {result.b_star * params.length_unit / lq:.3g}"
                f" {lql}; c, d = {result.c_star * params.length_unit / lq:.3g}, "
                f"{result.d_star * params.length_unit / lq:.3g} {lql}")
        sub = (f"E* = {params.reduced_modulus / 1e6:.3g} MPa, R = {params.effective_radius * 1e3:.3g} mm, "
               f"Δγ = {params.work_of_adhesion:.3g} J/m², σ0 = {params.max_adhesive_stress / 1e3:.3g} kPa  →  "
               f"β0 = {result.beta0:.3g}, μ = {result.mu:.3g}; {result.law}, N = {result.n}")
    else:
        head = (f"BEM pull-off W* = {result.W_star:.4g}; a*, b* = {result.a_star:.3g}, {result.b_star:.3g}; "
                f"c*, d* = {result.c_star:.3g}, {result.d_star:.3g}")
        sub = f"β0 = {result.beta0:.3g}, μ = {result.mu:.3g};  {result.law}, N = {result.n}, {result.control} control"
    fig.suptitle(head + flag + "\n" + sub, fontsize=10.5)
    return fig


def _reference_curve(ax, result, ak, fk):
    """The analytic load curve of :data:`REFERENCE_MODEL` (Dugdale law only), in the path's units."""
    if result.law != "dugdale":
        return
    from ..analysis import compare
    from ..core.geometry import sin_skew_angle

    try:
        c = compare.load_curve(REFERENCE_MODEL, mu=result.mu, beta0=result.beta0)
    except (ValueError, RuntimeError, ArithmeticError):  # no reference curve here: the BEM states alone
        return
    load = np.asarray(c["W_star"], float) * 2.0 * math.pi / float(sin_skew_angle(result.beta0))  # Eq. (34)
    delta = np.asarray(c["delta_star"], float)
    ok = np.isfinite(load) & np.isfinite(delta)
    d_bem = np.asarray(result.path.approach, float)
    top = max(float(np.nanmax(d_bem)), result.delta_star) if d_bem.size else result.delta_star
    span = max(top - float(np.nanmin(delta[ok])), 1e-12)
    ok &= delta <= top + 0.6 * span  # the unloading end of the curve, where the BEM path lies
    ax.plot(delta[ok] * ak, load[ok] * fk, "-", color="0.55", lw=1.3,
            label=f"{model_label(REFERENCE_MODEL)} (analytic)")


def write_solve_plot(result, path, *, params=None, dpi=150) -> tuple[Path, Path, Path]:
    """Write the figure of a BEM pull-off as PNG, SVG and PDF (all atomically).

    Parameters
    ----------
    result : dhfield.core.records.PullOff
        The pull-off, with its path and the state at pull-off.
    path : path-like
        PNG file; the SVG and PDF are the same path with suffixes ``.svg`` and
        ``.pdf``.  All three are checked before any is written.
    params : dhfield.analysis.dimensional.ContactParameters, optional
        The contact solved: SI axes (else the paper's units).
    dpi : int
        Resolution of the PNG.

    Returns
    -------
    (Path, Path, Path)
        The PNG, SVG and PDF paths.
    """
    return write_figure(lambda: solve_figure(result, params), path, dpi)
