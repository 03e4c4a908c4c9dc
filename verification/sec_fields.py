"""Report section: the full 2-D field, analytic vs DC-FFT boundary elements (issue 4).

The paper evaluates its fields only along theta_p = 0.  Here the pressure of the
extended DH model (Eqs. 16, 20, 22) is put on a Cartesian grid, its surface
displacement is computed independently with the DC-FFT half-space operator of
:mod:`dhfield.bem` (Love's exact influence coefficients, Liu, Wang & Liu 2000), and
compared with the analytic displacement (Eqs. 13-15, 26) and gap (Eq. 27) over the
whole surface and on polar rays (r, theta_p).

Checks (each with its tolerance and reason):

* the operator against closed forms (Love's centre value of a loaded cell) and the
  symmetry (DCT) mode against the full grid (issue: 1e-12);
* accuracy: relative L-infinity displacement error vs Eq. (13) at N = 512 and
  N = 1024 (issue: 1e-3, 3e-4), Hertz ellipse a = 1, beta = 0.7 on [-2a, 2a]^2,
  cell-averaged pressure; observed orders of the RMS error and of the L-infinity
  error away from the edges (issue: >= 1.5); the whole-grid L-infinity order is
  reported against its theoretical ceiling 1.5 (square-root pressure edge);
* the annulus identity: in the adhesive annulus the numerical gap equals
  (1 + v) times the Hertz gap (hertz.gap, Eqs. 2, 13, 14a) along every theta_p in
  [0, pi/2], to the discretisation error, and that error falls with refinement;
* the numerical gap vanishes in the contact ellipse to the discretisation error.
"""
from __future__ import annotations

import math
import time
from pathlib import Path

import numpy as np

from verification._api import Figure, Section, check_ge, check_le, save_figure
from verification._style import QUICK_DPI, REPORT_DPI, figsize, legend_below, shared_limits

TITLE = "Full-field verification: analytic DH fields vs DC-FFT boundary elements (2-D, all θp)"

#: The case of the CLI example and of the maps (nondimensional, R = E* = dgamma = 1).
CASE = dict(beta0=0.9, mu=1.0, a_star=1.2)
#: The paper's Fig. 3 ellipticity (nearly circular), same mu and a*.
CASE_FIG3 = dict(beta0=0.99, mu=1.0, a_star=1.2)
#: Hertz ellipse of the accuracy study (same as verification/convergence_bem.py).
HERTZ = dict(semi_major=1.0, beta=0.7)

#: Issue 4 targets: relative L-inf displacement error at these N, and the observed order.
TARGET_LINF = {512: 1e-3, 1024: 3e-4}
TARGET_ORDER = 1.5
#: Whole-grid L-inf order: a piecewise-constant pressure misses the square-root edge of Eq. (7)
#: by O(h^1/2) in the edge cells, so the displacement near the edge converges at O(h^1.5) at best;
#: measured 1.38-1.46 for N = 128...2048.  The bound guards against a regression, not the target.
MIN_ORDER_LINF_EDGE = 1.3
#: Symmetry mode vs full grid: issue 4 asks for 1e-12.
TOL_SYMMETRY = 1e-12
#: Love's closed form at the centre of a square cell: double-precision rounding.
TOL_CLOSED_FORM = 1e-14
#: Annulus identity, worst relative error over theta_p (relative to max (1+v) h_H in the annulus):
#: measured 6.1e-3 (N = 64), 2.3e-3 (128), 7.9e-4 (256), 2.4e-4 (512); the bound is
#: C h^1.5 with C twice the measured constant (discretisation of the square-root edges and
#: cubic-spline interpolation onto the rays).
def tol_annulus(n):
    return 2.0 * 6.1e-3 * (64.0 / n) ** 1.5


#: Gap in the contact ellipse (nondimensional): measured 5.5e-3 (N = 64) ... 2.7e-4 (512), O(h^1.5).
def tol_contact_gap(n):
    return 2.0 * 5.5e-3 * (64.0 / n) ** 1.5


#: Off-edge band of the accuracy study (cells at least this far from the ellipse edge) [a].
EDGE_BAND = 0.1


def _settings(quick):
    if quick:
        return dict(n_case=64, ns=(128, 256, 512), dpi=QUICK_DPI, n_theta=46)
    return dict(n_case=512, ns=(128, 256, 512, 1024, 2048), dpi=REPORT_DPI, n_theta=91)




def _ellipse(ax, a, beta, **kw):
    t = np.linspace(0, 2 * np.pi, 361)
    ax.plot(a * np.cos(t), beta * a * np.sin(t), **kw)


# --------------------------------------------------------------------------- figures


def _fig_maps(case, path, dpi):
    import matplotlib.pyplot as plt

    prm = case.parameters
    g = case.grid
    ext = [g.x_edges[0], g.x_edges[-1], g.y_edges[0], g.y_edges[-1]]
    panels = [
        (case.pressure, "pressure p (Eq. 22, cell averages)", "RdBu_r", True),
        (case.gap_numerical, "gap h from the BEM displacement", "viridis", False),
        (case.displacement_analytic - case.displacement_numerical,
         "ω: Eq. (26) − BEM", "RdBu_r", True),
        (case.gap_analytic - case.gap_numerical, "h: Eq. (27) − BEM", "RdBu_r", True),
    ]
    cbar_labels = ("p (units Po_ab)", "h (units c_r²/R)", "analytic − BEM (units c_r²/R)",
                   "analytic − BEM (units c_r²/R)")
    fig, axes = plt.subplots(2, 2, figsize=figsize(2, 0.84), constrained_layout=True)
    # the two difference maps compare the same kind of quantity (units c_r²/R): one colour range
    diff_lim = shared_limits([panels[2][0], panels[3][0]], centred=True)
    for k, (ax, (f, title, cmap, centred)) in enumerate(zip(axes.ravel(), panels)):
        kw = {}
        if k >= 2:
            kw = dict(vmin=diff_lim[0], vmax=diff_lim[1])
        elif centred:
            m = float(np.max(np.abs(f)))
            kw = dict(vmin=-m, vmax=m)
        im = ax.imshow(f.T, origin="lower", extent=ext, cmap=cmap, aspect="equal", **kw)
        _ellipse(ax, prm["semi_major"], prm["beta"], color="k", lw=0.8)
        _ellipse(ax, prm["adhesive_semi_major"], prm["beta"], color="k", lw=0.8, ls="--")
        ax.set_title(title)
        ax.set_xlabel("x / c_r")
        ax.set_ylabel("y / c_r")
        fig.colorbar(im, ax=ax, shrink=0.85, label=cbar_labels[k])
    fig.suptitle(f"β0 = {prm['beta0']:g}, μ = {prm['mu']:g}, a* = {prm['a_star']:g} "
                 f"(c* = {prm['adhesive_semi_major']:.4f}, v = {prm['scaling']:.4f}), {g.nx}×{g.ny} cells")
    return save_figure(fig, path, dpi)


def _fig_profiles(cases, path, dpi):
    """Fig. 3a/3b style: pressure and displacement (and gap) along theta_p = 0."""
    import matplotlib.pyplot as plt

    from dhfield.analysis import fields

    fig, axes = plt.subplots(1, 3, figsize=figsize(2, 0.4), constrained_layout=True)
    for case, color in zip(cases, ("tab:blue", "tab:red")):
        prm = case.parameters
        a = prm["semi_major"]
        g = case.grid
        j = g.ny // 2  # the row just above the x axis: y = dy/2
        xs = g.x[g.nx // 2:]
        r = np.linspace(0.0, xs[-1], 600)
        ana = fields.analytic_fields(case, r, np.zeros_like(r))
        ana_row = fields.analytic_fields(case, xs, np.full_like(xs, g.y[j]))
        po = float(__import__("dhfield").hertz.max_pressure(a, prm["beta"]))
        lab = f"β0 = {prm['beta0']:g}"
        axes[0].plot(r / a, ana["pressure"] / po, color=color, label=f"{lab}, analytic (Eqs. 22, 26, 27)")
        axes[0].plot(xs / a, case.pressure[g.nx // 2:, j] / po, ".", ms=3, color=color,
                     label=f"{lab}, BEM (cells at y = Δy/2)")
        axes[1].plot(r / a, ana["displacement"], color=color, label=None)
        axes[1].plot(xs / a, case.displacement_numerical[g.nx // 2:, j], ".", ms=3, color=color,
                     label=None)
        axes[2].plot(r / a, ana["gap"], color=color, label=None)
        axes[2].plot(xs / a, case.gap_numerical[g.nx // 2:, j], ".", ms=3, color=color, label=None)
        del ana_row
        for ax in axes:
            ax.axvline(1.0, color="0.6", lw=0.6)
            ax.axvline(prm["adhesive_semi_major"] / a, color=color, lw=0.6, ls="--")
    axes[0].set_ylabel("P / Po_ab")
    axes[1].set_ylabel("ω (units c_r²/R)")
    axes[2].set_ylabel("gap h (units c_r²/R)")
    for ax, t in zip(axes, ("(a) pressure, cf. Fig. 3a", "(b) displacement, cf. Fig. 3b", "(c) gap")):
        ax.set_xlabel("r / a along θp = 0")
        ax.set_title(t)
    legend_below(fig, ncol=2)
    return save_figure(fig, path, dpi)


def _fig_annulus(results, path, dpi):
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=figsize(1), constrained_layout=True)
    for n, res in sorted(results.items()):
        ax.semilogy(np.degrees(res["theta_p"]), res["rel_error"], label=f"N = {n}")
        ax.axhline(tol_annulus(n), ls=":", lw=0.8, color=ax.lines[-1].get_color())
    ax.set_xlabel("θp [deg]")
    ax.set_ylabel("|h_BEM − (1+v)h_H| / max (1+v)h_H")
    ax.set_title("Annulus identity h = (1+v)h_H (Eq. 27)")
    from matplotlib.lines import Line2D

    handles = ax.get_legend_handles_labels()[0] + [Line2D([], [], color="0.4", ls=":", lw=0.8,
                                                          label="tolerance at that N")]
    legend_below(fig, handles, [h.get_label() for h in handles], ncol=3)  # in the axes it hid a tolerance line
    return save_figure(fig, path, dpi)


def _fig_convergence(arr, path, dpi):
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=figsize(1), constrained_layout=True)
    n, h = arr[:, 0], arr[:, 1]
    ax.loglog(n, arr[:, 2], "o-", label="rel. L∞, whole grid")
    ax.loglog(n, arr[:, 3], "s-", label=f"rel. L∞, > {EDGE_BAND} a from the edge")
    ax.loglog(n, arr[:, 4], "^-", label="rel. RMS")
    for order, ls in ((1.5, ":"), (2.0, "--")):
        ax.loglog(n, arr[0, 2] * (h / h[0]) ** order, ls, color="0.5", lw=0.8, label=f"slope {order}")
    for nt, tol in TARGET_LINF.items():
        if nt <= n.max():
            ax.plot([nt], [tol], "kx")
    ax.set_xticks(n, [str(int(v)) for v in n])
    ax.minorticks_off()
    ax.set_xlabel("N (cells per axis)")
    ax.set_ylabel("error / max |ω|")
    ax.set_title("BEM vs Eq. (13), β = 0.7 (×: targets)")
    legend_below(fig, ncol=2)
    return save_figure(fig, path, dpi)


# --------------------------------------------------------------------------- run
def _hertz_refinement_row(n):
    """(N, h, rel. L-inf, rel. L-inf off the edge, rel. RMS) of the Hertz case on N x N cells
    (a row of :func:`verification.convergence_bem.study`, as one task of the sweep engine)."""
    from dhfield.analysis import fields
    from verification.convergence_bem import errors

    case = fields.hertz_case(n, HERTZ["semi_major"], HERTZ["beta"])
    return (n, case.grid.dx, *errors(case))



def run(outdir: Path, quick: bool, progress) -> Section:
    """Build the full-field section (see module docstring).

    Parameters
    ----------
    outdir : Path
        Directory for this section's figures and netCDF files.
    quick : bool
        Small grids (a few seconds).
    progress : callable
        ``progress(message)``.

    Returns
    -------
    Section
    """
    import matplotlib

    matplotlib.use("Agg")

    from dhfield import bem
    from dhfield.analysis import field_metrics, field_sampling, fields
    from dhfield.core import refinement
    from dhfield.io.field import write_field
    from dhfield.sweep import map_cases
    from verification.convergence_bem import format_table

    outdir = Path(outdir)
    outdir.mkdir(parents=True, exist_ok=True)
    cfg = _settings(quick)
    checks, figures, datasets, tables = [], [], [], []
    t0 = time.perf_counter()

    # ---- the operator: closed form and symmetry mode
    u_c = float(bem.love_influence(0.0, 0.0, 0.5, 0.5))
    ref = 4.0 / math.pi * math.log(1.0 + math.sqrt(2.0))
    checks.append(check_le("Love: centre of a unit square cell, u E*/(p Δ) vs (4/π) ln(1+√2)",
                           abs(u_c / ref - 1.0), TOL_CLOSED_FORM, "closed form (Johnson 1985, §3.2)"))
    n = cfg["n_case"]
    case = fields.model_case(n, **CASE)
    full = field_sampling.numerical_displacement(case.pressure, case.grid, symmetric=False)
    sym_err = float(np.max(np.abs(full - case.displacement_numerical)) / np.max(np.abs(full)))
    checks.append(check_le(f"symmetry (DCT quadrant) mode vs full grid, DH case, N = {n}", sym_err, TOL_SYMMETRY,
                           "same discrete convolution, required to 1e-12"))
    progress(f"DH case N = {n}: c* = {case.parameters['adhesive_semi_major']:.6f}, "
             f"v = {case.parameters['scaling']:.6f}")

    # ---- accuracy and convergence (Hertz ellipse, cell averages)
    # one sweep-engine task per N (report.py --scheduler runs them in parallel; serial by default)
    arr = np.array(map_cases(_hertz_refinement_row, [(m,) for m in cfg["ns"]]))
    orders = np.array([np.concatenate([[np.nan], refinement.observed_orders(arr[:, 1], arr[:, k])])
                       for k in (2, 3, 4)]).T
    progress(f"refinement study N = {cfg['ns']}")
    tables.append("**Accuracy of the BEM against Eq. (13)**: Hertz ellipse a = 1, β = 0.7 (R = E* = 1), "
                  "domain [−2a, 2a]², N × N cells, pressure by exact cell averages; errors at the cell centres "
                  "relative to max |ω| (observed orders between successive grids).\n\n" + format_table(arr, orders))
    for nt, tol in TARGET_LINF.items():
        if nt in arr[:, 0]:
            e = float(arr[arr[:, 0] == nt, 2][0])
            checks.append(check_le(f"rel. L∞ displacement error vs Eq. (13), N = {nt}, whole grid", e, tol,
                                   "Eq. (13) closed form (Hertz ellipse β = 0.7 on [−2a, 2a]², cell averages); target"))
    step = f"N = {int(arr[-2, 0])} → {int(arr[-1, 0])}"
    checks.append(check_ge(f"observed order, rel. RMS displacement error, {step}", orders[-1, 2], TARGET_ORDER,
                           "Eq. (13) closed form; second order expected in the smooth interior"))
    checks.append(check_ge(f"observed order, rel. L∞ error > {EDGE_BAND} a from the edge, {step}", orders[-1, 1],
                           TARGET_ORDER, "Eq. (13) closed form; second order expected away from the edge"))
    fitted = float(np.polyfit(np.log(arr[:, 1]), np.log(arr[:, 2]), 1)[0])
    checks.append(check_ge(f"observed order, rel. L∞ error on the whole grid (fit over N = {cfg['ns'][0]}…"
                           f"{cfg['ns'][-1]})", fitted, MIN_ORDER_LINF_EDGE,
                           "ceiling 1.5 for piecewise-constant pressure with a square-root edge; the target 1.5 "
                           "is approached from below, not reached"))
    figures.append(Figure(_fig_convergence(arr, outdir / "fields_convergence.png", cfg["dpi"]),
                          "Convergence of the DC-FFT displacement to the analytic Hertz displacement, Eq. (13) "
                          "(Eqs. 13–15 with the root l of Eq. 12b outside the ellipse)."))

    # ---- annulus identity and contact gap
    results = {}
    for m in (n // 2, n):
        c_m = case if m == n else fields.model_case(m, **CASE)
        results[m] = field_metrics.annulus_identity(c_m, n_theta=cfg["n_theta"])
        checks.append(check_le(f"annulus identity h_BEM = (1+v) h_H, worst ray of θp ∈ [0°, 90°], N = {m}",
                               results[m]["worst"], tol_annulus(m),
                               "Eq. (27) rearranged: h = (1+v) h_H in the annulus (README, Notes on the paper); tolerance 2× the measured C h^1.5"))
        gap_in = float(np.max(np.abs(c_m.gap_numerical[c_m.masks["contact"]])))
        checks.append(check_le(f"numerical gap in the contact ellipse, max |h_BEM|, N = {m}", gap_in,
                               tol_contact_gap(m), "contact condition of Eqs. (13a), (26a); 2× measured C h^1.5"))
    ratio = results[n // 2]["worst"] / results[n]["worst"]
    checks.append(check_ge(f"annulus identity error falls with refinement, N = {n // 2} → {n} (ratio)", ratio,
                           2.0 ** 1.2, "discretisation error O(h^1.5): ratio 2.8 expected, ≥ 2^1.2 required"))
    figures.append(Figure(_fig_annulus(results, outdir / "fields_annulus_identity.png", cfg["dpi"]),
                          "Annulus identity along every ray θp: the BEM gap vs (1+v) times the Hertz gap "
                          "(Eq. 27 with Eqs. 2, 13b, 14a); dotted lines are the tolerances."))
    progress("annulus identity")

    # ---- maps, profiles, datasets
    figures.append(Figure(_fig_maps(case, outdir / "fields_maps.png", cfg["dpi"]),
                          "Maps of the DH pressure (Eqs. 16, 20, 22), the BEM gap, and analytic-minus-numerical "
                          "displacement (Eq. 26) and gap (Eq. 27); solid: contact ellipse, dashed: adhesive "
                          "ellipse (Eqs. A1, A2)."))
    case99 = fields.model_case(n, **CASE_FIG3)
    figures.append(Figure(_fig_profiles([case99, case], outdir / "fields_profiles.png", cfg["dpi"]),
                          "Profiles along θp = 0 in the style of the paper's Fig. 3a (pressure, Eqs. 8, 20, 22) "
                          "and Fig. 3b (surface displacement, Eq. 26), plus the gap (Eq. 27); lines analytic, "
                          "dots BEM / cell averages on the row y = Δy/2."))
    for c_, tag in ((case, "beta0_0.9"), (case99, "beta0_0.99")):
        p = write_field(c_, outdir / f"field_{tag}_mu1_astar1.2_N{n}.nc")
        datasets.append(p)
    progress("maps, profiles and datasets")

    err = case.displacement_errors()
    gerr = case.gap_errors()
    rows = ["| region | cells | ω rel. max | ω rel. RMS | h rel. max | h rel. RMS |",
            "|:--|--:|--:|--:|--:|--:|"]
    for region in ("contact", "annulus", "outside", "all"):
        e, g = err[region], gerr[region]
        rows.append(f"| {region} | {e['count']} | {e['rel_max']:.2e} | {e['rel_rms']:.2e} | {g['rel_max']:.2e} | "
                    f"{g['rel_rms']:.2e} |")
    tables.append(f"**DH case β0 = {CASE['beta0']}, μ = {CASE['mu']}, a* = {CASE['a_star']}, N = {n}**: "
                  "analytic vs BEM by region, relative to max |ω|.\n\n" + "\n".join(rows))

    text = (
        "The paper solves the line θp = 0 only. Here the DH pressure is laid on an N × N grid (exact cell "
        "averages of the two semi-ellipsoids), its displacement is computed by the DC-FFT boundary-element "
        "operator (Love's influence coefficients, zero-padded 2N grid, even–even DCT mode), and compared with "
        "Eqs. (13)–(15), (26) and (27) everywhere: in the contact ellipse, in the adhesive annulus and outside, "
        "and on polar rays. The whole-grid L∞ error converges at order ≈ 1.45, the ceiling 1.5 of a "
        "piecewise-constant pressure with a square-root edge being approached from below; away from the edges "
        "and in RMS the order is ≈ 2. "
        f"Nondimensional units R = E* = Δγ = 1 (lengths in c_r). Section time {time.perf_counter() - t0:.1f} s.")
    verdict = [f"The DC-FFT boundary elements reproduce the analytic DH fields over the whole surface, not only "
               f"on θp = 0: displacement error against Eq. (13) {float(arr[-1, 2]):.1e} of max ω at N = "
               f"{int(arr[-1, 0])} (observed order {fitted:.2f} in L∞, {float(orders[-1, 2]):.2f} in RMS); the "
               f"annulus identity h = (1+v) h_H (Eq. 27) holds to {results[n]['worst']:.1e} at N = {n}."]
    return Section(title=TITLE, text=text, checks=checks, figures=figures, tables=tables, datasets=datasets,
                   verdict=verdict)
