"""Report section: the theta_p dependence, Eq. (30) and the equal-beta test (issue 5).

Along every ray theta_p of the adhesive annulus, at the pull-off point of the
paper's model (Zini et al. 2018, doi:10.1007/s11249-017-0976-8) for
beta0 in {0.8, 0.9, 0.99} and mu in {0.5, 1, 2, 5}: the maximum adhesive stress
sigma0(theta_p), the zone width, the edge separation, the ray work of adhesion
Delta gamma(theta_p) (Eq. 31 on every ray) and the sigma-h curves; Eq. (30) as
printed, by area and by Green's theorem; the spread of the cohesive law across
theta_p and two alternative closures (:mod:`dhfield.models.dh_elliptic_closure`); and the ray work
from the BEM gap field (:mod:`dhfield.analysis.fields`) against the analytic one.

``python -m verification.sec_periphery`` prints the tables (full resolution);
``--quick`` the quick ones.
"""
from __future__ import annotations

import sys
import time
from pathlib import Path

import numpy as np

from verification._api import Figure, Section, check_ge, check_le, save_figure
from verification._style import QUICK_DPI, REPORT_DPI, figsize, legend_below, model_label, rel_diff_label

TITLE = "θp dependence, Eq. (30) and the equal-β test"

BETA0 = (0.8, 0.9, 0.99)
MU = (0.5, 1.0, 2.0, 5.0)

#: issue 5: the two evaluations of Eq. (30) on the analytic fields agree to 1e-6 (rel. to 4 Δγ(0))
TOL_EQ30 = 1e-6
#: Green's form: the curved edges (h = 0, σ = 0) vanish; rounding of closed forms
TOL_EDGES = 1e-12
#: ray quadrature (graded Gauss) vs dhfield.models.dh_elliptic_adhesion (a separate implementation), exponential rule
TOL_RAY = 1e-11
#: β0 = 1 against Greenwood & Johnson (1998) closed form and θp independence: rounding
TOL_CIRCLE = 1e-12
#: equal β: σ0(θp) is v Po_cd √(1 − a²/c²) on every ray (closed form): rounding
TOL_SIGMA0 = 1e-12
#: closures at β0 = 1 vs the paper's pull-off: both solves to 1e-12, minimum located to 1e-8 in a*
TOL_CLOSURE_CIRCLE = 1e-9
#: two-axis closure: the contact condition by superposition of the two Hertz displacements (Eq. 13)
TOL_CONTACT = 1e-12
#: issue 5: BEM vs analytic Δγ(θp) at N = 1024 (relative, max over θp)
TOL_BEM = 1e-3
#: quick mode (N = 256, one case): O(dx^1.5) BEM + interpolation error, measured 9.6e-4 at μ = 1, β0 = 0.8
TOL_BEM_QUICK = 2e-3
#: μ = 5: the BEM gap error converges like dx^1.5 (measured orders 1.34-1.59); demand >= 1.2
MIN_ORDER_MU5 = 1.2
#: Eq. (30) as an area sum of the BEM field (central differences; σ's √ edge): measured 3e-4 at N = 1024
TOL_EQ30_GRID = 5e-3
#: quick mode, N = 256: measured 9.3e-3 (same O(dx^1.5) behaviour, coarser grid)
TOL_EQ30_GRID_QUICK = 2e-2

_COLORS = {0.5: "tab:blue", 1.0: "tab:green", 2.0: "tab:orange", 5.0: "tab:red"}
_STYLES = {0.8: "-", 0.9: "--", 0.99: ":"}


def _settings(quick):
    if quick:
        return dict(n_theta=31, n_law=65, dpi=QUICK_DPI, closure_beta=(0.8,), closure_mu=(1.0, 5.0),
                    bem_cases=((0.8, 1.0),), bem_n=(128, 256), curve_n=25)
    return dict(n_theta=91, n_law=129, dpi=REPORT_DPI, closure_beta=BETA0, closure_mu=MU,
                bem_cases=tuple((b, m) for b in BETA0 for m in MU), bem_n=(512, 1024), curve_n=60)


def _plt():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt




# --------------------------------------------------------------------------- computations
def compute(quick=False, progress=print):
    """All numbers of the section (no files).  Returns a dict of results."""
    from dhfield.models import (dh_elliptic_closure as closure, dh_elliptic as model, dh_elliptic_periphery as
                                periphery)
    from dhfield.analysis import compare, eq30

    cfg = _settings(quick)
    mu, beta0 = np.array(MU), np.array(BETA0)
    th = np.linspace(0.0, 0.5 * np.pi, cfg["n_theta"])
    po = model.pull_off(mu=mu[None, :], beta0=beta0[:, None])
    prof = periphery.periphery_at_pull_off(po, th)
    law_theta = np.deg2rad([0.0, 30.0, 60.0, 90.0])
    law = periphery.cohesive_law(po.a_star, po.c_star, po.ellipticity, po.v, law_theta, n_points=cfg["n_law"])
    progress(f"ray quantities at pull-off, {beta0.size} × {mu.size} (β0, μ) × {th.size} rays")
    area = eq30.eq30_area(po.a_star, po.c_star, po.ellipticity, po.v)
    bnd = eq30.eq30_boundary(po.a_star, po.c_star, po.ellipticity, po.v)
    mean = eq30.periphery_work_of_adhesion(po.a_star, po.c_star, po.ellipticity, po.v)
    mean_angle = eq30.periphery_work_of_adhesion(po.a_star, po.c_star, po.ellipticity, po.v, weight="angle")
    progress("Eq. (30): polar area integral and Green's boundary form")
    spread = closure.equal_beta_spread(beta0=beta0[:, None], mu=mu[None, :], n_theta=31)
    progress("equal-β spread of Δγ(θp) and of the σ–h curves")
    cb, cm = np.array(cfg["closure_beta"]), np.array(cfg["closure_mu"])
    closures = {}
    for name in closure.CLOSURES:
        t0 = time.perf_counter()
        closures[name] = closure.state_at_pull_off(beta0=cb[:, None], mu=cm[None, :], closure=name)
        progress(f"closure '{name}': pull-off on {cb.size} × {cm.size} (β0, μ) "
                 f"({time.perf_counter() - t0:.1f} s)")
    ref = compare.compare(mu=cm[None, :], beta0=cb[:, None], models=["jkr-elliptic", "dh-circular"])
    return dict(cfg=cfg, mu=mu, beta0=beta0, theta=th, pull_off=po, profile=prof, law=law, law_theta=law_theta,
                eq30_area=area, eq30_boundary=bnd, mean_work=mean, mean_work_angle=mean_angle, spread=spread,
                closure_beta=cb, closure_mu=cm, closures=closures,
                jkr_elliptic=np.broadcast_to(ref["jkr-elliptic"]["W_star"], (cb.size, cm.size)),
                dh_circular=np.broadcast_to(ref["dh-circular"]["W_star"], (cb.size, cm.size)))


def bem_comparison(cases, ns, progress=print, theta=None):
    """Δγ(θp) from the BEM gap (dhfield.analysis.fields.dh_case) vs analytic, per case and N.

    Returns a list of dicts (beta0, mu, n, error, profile, analytic, order) and the
    Eq. (30) area sum on the finest BEM field of the first case.  The cases run as
    tasks of the sweep engine (:func:`dhfield.sweep.map_cases`; the refinements of
    one case stay in one task), on the scheduler of ``$DHFIELD_SCHEDULER``
    (``report.py --scheduler``), serially in this process by default.
    """
    from dhfield.sweep import map_cases

    theta = np.linspace(0.0, 0.5 * np.pi, 19) if theta is None else theta
    results = map_cases(_bem_case, [(b0, m, tuple(ns), theta, i == 0) for i, (b0, m) in enumerate(cases)])
    out = []
    eq30_grid = None
    for recs, grid_sum in results:
        for rec in recs:
            progress(f"BEM Δγ(θp): β0 = {rec['beta0']:g}, μ = {rec['mu']:g}, N = {rec['n']}: max rel. error "
                     f"{rec['max_error']:.2e} ({rec.pop('seconds'):.1f} s)")
        out.extend(recs)
        eq30_grid = grid_sum if eq30_grid is None else eq30_grid
    return out, eq30_grid


def _bem_case(b0, m, ns, theta, with_eq30):
    """One case of :func:`bem_comparison` at every N (a task of the sweep engine)."""
    from dhfield.models import (dh_elliptic_fields as double_hertz, dh_elliptic as model,
                                dh_elliptic_periphery as periphery)
    from dhfield.analysis import eq30, fields

    out = []
    eq30_grid = None
    po = model.pull_off(mu=m, beta0=b0)
    a, c, v = float(po.a_star), float(po.c_star), float(po.v)
    ref = periphery.periphery(a, c, b0, v, theta)
    errs = []
    for n in ns:
        t0 = time.perf_counter()
        case = fields.dh_case(n, a, c, b0, v, half_width=1.05 * c)
        g = case.grid
        prof = periphery.periphery_from_gap_grid(g.x, g.y, case.gap_numerical, (a, c, b0, v), theta)
        err = np.abs(prof.work_of_adhesion / ref.work_of_adhesion - 1.0)
        errs.append(float(err.max()))
        # the two sources apart: spline of the analytic gap sampled on the same grid (interpolation only),
        # and the BEM gap with the analytic gap as interpolation trend (BEM only)
        interp = periphery.periphery_from_gap_grid(g.x, g.y, case.gap_analytic, (a, c, b0, v), theta)
        xx, yy = g.mesh()
        known = {"grid": case.gap_analytic}

        def trend(px, py, a=a, c=c, b0=b0, v=v, known=known, shape=xx.shape):
            if np.shape(px) == shape and np.array_equal(px, xx) and np.array_equal(py, yy):
                return known["grid"]
            return double_hertz.gap(px, py, a, c, b0, v)

        bem_only = periphery.periphery_from_gap_grid(g.x, g.y, case.gap_numerical, (a, c, b0, v), theta,
                                                     trend=trend)
        rel = (lambda p: float(np.max(np.abs(p.work_of_adhesion / ref.work_of_adhesion - 1.0))))
        rec = dict(beta0=b0, mu=m, n=n, error=err, max_error=float(err.max()), profile=prof, analytic=ref,
                   state=(a, c, b0, v), half_width=1.05 * c, zone_cells=float((c - a) / g.dx),
                   interp_error=rel(interp), bem_error=rel(bem_only))
        out.append(rec)
        if with_eq30 and n == ns[-1]:
            x, y = g.x, g.y
            s = eq30.adhesive_stress_extended(xx, yy, c, b0, v)
            eq30_grid = dict(value=eq30.eq30_cartesian(x, y, s, case.gap_numerical),
                             boundary=eq30.eq30_boundary_from_grid(x, y, case.gap_numerical, a, c, b0, v),
                             exact=float(eq30.eq30_area(a, c, b0, v)), beta0=b0, mu=m, n=n)
        rec["seconds"] = time.perf_counter() - t0
    order = float(np.log(errs[0] / errs[-1]) / np.log(ns[-1] / ns[0])) if len(ns) > 1 else float("nan")
    for rec in out:
        rec["order"] = order
    return out, eq30_grid


# --------------------------------------------------------------------------- tables
def ratio_table(res):
    """Δγ(π/2)/Δγ(0) at pull-off, β0 × μ (Markdown)."""
    w = res["profile"].work_of_adhesion
    lines = ["| β0 \\ μ | " + " | ".join(f"{m:g}" for m in res["mu"]) + " |",
             "|---|" + "---|" * res["mu"].size]
    for i, b in enumerate(res["beta0"]):
        lines.append(f"| {b:g} | " + " | ".join(f"{w[i, j, -1] / w[i, j, 0]:.4f}" for j in range(res["mu"].size))
                     + " |")
    return "\n".join(lines)


def spread_table(res):
    """The equal-β test: spreads of Δγ and of the σ–h curves (Markdown)."""
    s = res["spread"]
    prof = res["profile"]
    lines = ["| β0 | μ | Δγ(π/2)/Δγ(0) | (max − min)/mean of Δγ | mean Δγ (r_ab² weights) | "
             "σ–h curves: max ∫abs(Δσ)dh / Δγ(0) | σ–h curves: max abs(Δσ)/σ0 | h(r_cd): minor/major | "
             "σ0(π/2)/σ0(0) |", "|---|---|---|---|---|---|---|---|---|"]
    s0 = prof.max_adhesive_stress
    for i, b in enumerate(res["beta0"]):
        for j, m in enumerate(res["mu"]):
            lines.append(f"| {b:g} | {m:g} | {s.work_ratio[i, j]:.4f} | {s.work_spread[i, j]:.4f} | "
                         f"{s.mean_work[i, j]:.4f} | {s.law_spread[i, j]:.4f} | {s.law_sup_spread[i, j]:.3f} | "
                         f"{s.separation_ratio[i, j]:.4f} | {s0[i, j, -1] / s0[i, j, 0]:.12f} |")
    return "\n".join(lines)


def eq30_table(res):
    """Eq. (30) by area and by boundary, next to Δγ(0), Δγ(π/2) and the periphery mean (Markdown)."""
    w = res["profile"].work_of_adhesion
    bnd = res["eq30_boundary"]
    lines = ["| β0 | μ | Eq. (30), area | Eq. (30), boundary | abs(area − boundary)/(4Δγ(0)) | "
             "4[Δγ(0) − Δγ(π/2)] | Δγ(0) (Eq. 31, imposed) | Δγ(π/2) | mean Δγ, r_ab² weights | "
             "mean Δγ, uniform in θp |", "|---|---|---|---|---|---|---|---|---|---|"]
    for i, b in enumerate(res["beta0"]):
        for j, m in enumerate(res["mu"]):
            a_, b_ = res["eq30_area"][i, j], bnd.total[i, j]
            lines.append(f"| {b:g} | {m:g} | {a_:.10f} | {b_:.10f} | {abs(a_ - b_) / (4 * w[i, j, 0]):.1e} | "
                         f"{4 * (w[i, j, 0] - w[i, j, -1]):.10f} | {w[i, j, 0]:.6f} | {w[i, j, -1]:.6f} | "
                         f"{res['mean_work'][i, j]:.6f} | {res['mean_work_angle'][i, j]:.6f} |")
    return "\n".join(lines)


def closure_table(res):
    """Pull-off W* of the paper's closure and the alternatives (Markdown)."""
    cl = res["closures"]
    p, r, t = cl["paper"], cl["ray_average"], cl["two_axis"]
    lines = ["| β0 | μ | W* paper (Eq. 31 on θp = 0) | W* ray average | shift | W* two axes | shift | "
             "β_ab, β_cd (two axes) | σ0(π/2)/μ (two axes) | W* elliptical JKR (JG05) | W* DH circular |",
             "|---|---|---|---|---|---|---|---|---|---|---|"]
    for i, b in enumerate(res["closure_beta"]):
        for j, m in enumerate(res["closure_mu"]):
            wp = p.W_star[i, j]
            lines.append(
                f"| {b:g} | {m:g} | {wp:.5f} | {r.W_star[i, j]:.5f} | {100 * (r.W_star[i, j] / wp - 1):+.2f} % | "
                f"{t.W_star[i, j]:.5f} | {100 * (t.W_star[i, j] / wp - 1):+.2f} % | "
                f"{t.beta_contact[i, j]:.4f}, {t.beta_adhesive[i, j]:.4f} | {t.sigma0_minor[i, j] / m:.4f} | "
                f"{res['jkr_elliptic'][i, j]:.5f} | {res['dh_circular'][i, j]:.5f} |")
    return "\n".join(lines)


def bem_table(recs):
    lines = ["| β0 | μ | N | cells across the zone (major axis) | max over θp of abs(Δγ_BEM/Δγ − 1) | "
             "observed order | interpolation only (analytic gap on the grid) | BEM only (analytic trend) |",
             "|---|---|---|---|---|---|---|---|"]
    for r in recs:
        lines.append(f"| {r['beta0']:g} | {r['mu']:g} | {r['n']} | {r['zone_cells']:.0f} | {r['max_error']:.2e} | "
                     f"{r['order']:.2f} | {r['interp_error']:.2e} | {r['bem_error']:.2e} |")
    return "\n".join(lines)


# --------------------------------------------------------------------------- checks
def _checks(res):
    from dhfield.models import (dh_elliptic_adhesion as adhesion, dh_elliptic_closure as closure, hertz,
                                dh_elliptic as model, dh_elliptic_periphery as periphery)
    from dhfield.analysis import eq30
    from dhfield.core.geometry import radius_ratio

    out = []
    po, prof = res["pull_off"], res["profile"]
    w = prof.work_of_adhesion
    bnd = res["eq30_boundary"]
    rel = np.abs(res["eq30_area"] - bnd.total) / (4 * w[..., 0])
    out.append(check_le("Eq. (30): polar area integral vs Green's boundary form, 12 pull-off states, "
                        "max abs(area − boundary)/(4Δγ(0))", rel.max(), TOL_EQ30,
                        "two independent quadratures of the analytic fields (Eq. 30 as printed; Green's theorem)"))
    edges = np.maximum(np.abs(bnd.inner_edge), np.abs(bnd.outer_edge)) / (4 * w[..., 0])
    out.append(check_le("Eq. (30), Green's form: contribution of the contact edge (h = 0) and adhesive edge "
                        "(σ = 0), evaluated from the fields, max rel.", edges.max(), TOL_EDGES,
                        "Green's theorem: h = 0 on the contact edge, σ = 0 on the adhesive edge (Eqs. 23, 27); only the rays θp = 0, π/2 survive"))
    th = res["theta"]
    ref = adhesion.work_of_adhesion(po.a_star[..., None], po.c_star[..., None], po.ellipticity[..., None],
                                    po.v[..., None], theta=th)
    out.append(check_le("Δγ(θp) of dhfield.models.dh_elliptic_periphery vs dhfield.models.dh_elliptic_adhesion.work_of_adhesion (separate code), "
                        "all rays and pull-off states, max rel. difference", np.max(np.abs(w / ref - 1)), TOL_RAY,
                        "two implementations of Eq. (31) on every ray"))
    out.append(check_le("Δγ(θp = 0) = 1 at pull-off (Eq. 31 imposed by the model), max abs. error",
                        np.max(np.abs(w[..., 0] - 1)), TOL_RAY, "dhfield.models.dh_elliptic solve"))
    s0 = prof.max_adhesive_stress
    out.append(check_le("equal β: σ0(θp) = μ on every ray (Eqs. 24, 35), max rel. deviation",
                        np.max(np.abs(s0 / res["mu"][None, :, None] - 1)), TOL_SIGMA0,
                        "closed form: r_ab/r_cd = a/c on every ray when b/a = d/c"))
    # beta0 = 1: theta-independence and the GJ98 closed form
    po1 = model.pull_off(mu=res["mu"], beta0=1.0)
    prof1 = periphery.periphery_at_pull_off(po1, th)
    gj = po1.v * (1 + po1.v) * 2 / (3 * np.pi) * (po1.c_star - po1.a_star) ** 2 * (po1.c_star + 2 * po1.a_star)
    err = max(np.max(np.abs(prof1.work_of_adhesion / gj[:, None] - 1)),
              np.max(np.abs(prof1.edge_separation / prof1.edge_separation[:, :1] - 1)),
              np.max(np.abs(prof1.zone_width / prof1.zone_width[:, :1] - 1)))
    out.append(check_le("β0 = 1: Δγ(θp) vs Greenwood–Johnson (1998) closed form v(1+v)(2/3π)(c−a)²(c+2a); "
                        "edge separation and zone width independent of θp; max rel. error", err, TOL_CIRCLE,
                        "GJ98 closed form (R = E* = 1), circular symmetry"))
    i30_1 = eq30.eq30_area(po1.a_star, po1.c_star, 1.0, po1.v)
    out.append(check_le("β0 = 1: Eq. (30) vanishes although Δγ = 1, max abs(Eq. 30)", np.max(np.abs(i30_1)),
                        TOL_CIRCLE, "Green's form: 4[Δγ(0) − Δγ(π/2)] = 0 by symmetry"))
    wc = [abs(closure.pull_off_closure(beta0=1.0, mu=m, closure=name).W_star / model.pull_off(mu=m, beta0=1.0).W_star - 1)
          for name in ("ray_average", "two_axis") for m in (0.5, 5.0)]
    out.append(check_le("alternative closures at β0 = 1 (μ = 0.5, 5) vs the paper's pull-off W*, max rel.",
                        max(wc), TOL_CLOSURE_CIRCLE, "reduction to the paper's model at the circle"))
    t = res["closures"]["two_axis"]
    worst = 0.0
    r1 = np.sqrt(radius_ratio(res["closure_beta"]))[:, None] * np.ones(t.W_star.shape)
    for idx in np.ndindex(t.W_star.shape):
        a, b, c, d = t.a_star[idx], t.b_star[idx], t.c_star[idx], t.d_star[idx]
        A, B = t.contact_amplitude[idx], t.adhesive_amplitude[idx]
        ang = np.linspace(0, 2 * np.pi, 9)
        x, y = 0.9 * a * np.cos(ang), 0.9 * b * np.sin(ang)

        def om(xx, yy):
            return hertz.surface_displacement(xx, yy, a, b, A) - hertz.surface_displacement(xx, yy, c, d, B)

        h = x**2 / (2 * r1[idx]) + y**2 * r1[idx] / 2 + om(x, y) - om(0.0, 0.0)
        worst = max(worst, float(np.max(np.abs(h))))
    out.append(check_le("two-axis closure at pull-off: gap inside the contact ellipse by superposition of the "
                        "two Hertz displacements (Eq. 13), max abs(h) (c_r²/R)", worst, TOL_CONTACT,
                        "contact condition h = 0 (Eq. 27) kept exactly with β_cd ≠ β_ab"))
    dev = max(np.max(np.abs(t.work_major - 1)), np.max(np.abs(t.work_minor - 1)))
    out.append(check_le("two-axis closure at pull-off: Δγ(0) = Δγ(π/2) = 1, max abs. error", dev, 1e-11,
                        "closure solve tolerance 1e-12 on log Δγ"))
    return out


# --------------------------------------------------------------------------- figures
def _fig_rays(res, outdir, dpi):
    plt = _plt()
    prof = res["profile"]
    deg = np.rad2deg(res["theta"])
    fig, axs = plt.subplots(2, 2, figsize=figsize(2, 0.74), sharex=True)
    panels = [(prof.work_of_adhesion, "Δγ(θp)/Δγ(0) (Eq. 31)", False),
              (prof.max_adhesive_stress, "σ0(θp)/σ0(0) (Eq. 24)", True),
              (prof.zone_width, "(r_cd − r_ab)(θp)/(r_cd − r_ab)(0)", True),
              (prof.edge_separation, "h(r_cd, θp)/h(r_cd, 0) (Eq. 27)", True)]
    for ax, (q, lab, norm) in zip(axs.ravel(), panels):
        for i, b in enumerate(res["beta0"]):
            for j, m in enumerate(res["mu"]):
                y = q[i, j] / q[i, j, 0] if norm else q[i, j]
                ax.plot(deg, y, _STYLES[b], color=_COLORS[m], lw=1.3,
                        label=f"β0 = {b:g}, μ = {m:g}" if ax is axs[0, 0] else None)
        ax.set_ylabel(lab)
        ax.grid(alpha=0.3)
    for ax in axs[1]:
        ax.set_xlabel("ray angle θp (deg), 0 = major axis")
    axs[0, 1].set_ylim(0.99, 1.01)
    handles, labels = axs[0, 0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="lower center", ncol=4, frameon=False)  # 12 entries: under the panels
    fig.suptitle("Elliptical DH at pull-off (load control): quantities along every ray")
    fig.tight_layout(rect=(0, 0.13, 1, 1))
    cap = ("Along every ray θp of the adhesive annulus at the load-controlled pull-off of the paper's model "
           "(Eqs. 17–19, 24, 31, 35; rays r_ab ≤ r ≤ r_cd of Eqs. A1–A2): the ray work of adhesion "
           "Δγ(θp) = ∫σ dh (Eq. 31 evaluated on every ray), σ0(θp) (Eq. 24 on the ray: flat, equal β), the zone "
           "width and the edge separation h(r_cd) (Eq. 27), the last two relative to θp = 0. Colour: μ; line "
           "style: β0 = 0.8 solid, 0.9 dashed, 0.99 dotted.")
    return Figure(save_figure(fig, outdir / "periphery_rays_pull_off.png", dpi), cap)


def _fig_laws(res, outdir, dpi):
    plt = _plt()
    law = res["law"]
    fig, axs = plt.subplots(1, 4, figsize=figsize(2, 0.33), sharey=True)
    cols = ["k", "tab:blue", "tab:orange", "tab:red"]
    i = 0  # beta0 = 0.8
    for j, (ax, m) in enumerate(zip(axs, res["mu"])):
        h0 = law.separation[i, j, 0, -1]
        s0 = law.stress[i, j, 0, 0]
        for k, tt in enumerate(res["law_theta"]):
            ax.plot(law.separation[i, j, k] / h0, law.stress[i, j, k] / s0, color=cols[k],
                    label=f"θp = {np.rad2deg(tt):.0f}°")
        ax.set_title(f"β0 = {res['beta0'][i]:g}, μ = {m:g}")
        ax.set_xlabel("h / h(r_cd, θp = 0)")
        ax.grid(alpha=0.3)
    axs[0].set_ylabel("σ / σ0")
    axs[0].legend()
    fig.tight_layout()
    cap = ("The cohesive law each ray sees: σ (Eq. 23) against the gap h (Eq. 27) along rays θp = 0°, 30°, 60°, "
           "90°, at pull-off, β0 = 0.8. Equal β gives the same σ0 on every ray but a shorter law (smaller edge "
           "separation) towards the minor axis, so the area under it, Δγ(θp) (Eq. 31 on the ray), falls.")
    return Figure(save_figure(fig, outdir / "periphery_sigma_h_laws.png", dpi), cap)


def _fig_curves(res, outdir, dpi, n):
    from dhfield.models import dh_elliptic as model, dh_elliptic_periphery as periphery

    plt = _plt()
    fig, ax = plt.subplots(figsize=figsize(1))
    a = np.linspace(0.1, 3.0, n)
    curves = {}
    th = np.linspace(0.0, 0.5 * np.pi, 19)
    for b in res["beta0"]:
        for m in (1.0, 5.0):
            lc = model.load_curve(beta0=b, mu=m, a_star=a)
            pr = periphery.periphery_along_curve(lc, th)
            ratio = pr.work_of_adhesion[:, -1] / pr.work_of_adhesion[:, 0]
            curves[(float(b), m)] = (lc, pr)
            ax.plot(lc.W_star, ratio, _STYLES[b], color=_COLORS[m], label=f"β0 = {b:g}, μ = {m:g}")
    ax.set_xlabel("W* (Eq. 34)")
    ax.set_ylabel("Δγ(π/2) / Δγ(0)")
    ax.set_xlim(-1, 2.6)
    ax.grid(alpha=0.3)
    legend_below(fig, ncol=2)
    cap = ("Ratio of the ray works of adhesion on the minor and major axes (Eq. 31 on θp = π/2 and 0) along the "
           "load curves of the paper's model (Figs. 4–5 states, a* ∈ [0.1, 3]), μ = 1 and 5.")
    return Figure(save_figure(fig, outdir / "periphery_ratio_load_curves.png", dpi), cap), curves


def _fig_closures(res, outdir, dpi):
    plt = _plt()
    cl = res["closures"]
    n_panels = len(res["closure_beta"])
    fig, axs = plt.subplots(1, n_panels, figsize=figsize(1, 0.85) if n_panels == 1 else figsize(2, 0.4),
                            squeeze=False)
    for i, (ax, b) in enumerate(zip(axs[0], res["closure_beta"])):
        m = res["closure_mu"]
        ax.plot(m, cl["paper"].W_star[i], "o-", color="k", label=model_label("dh-elliptic") + ", Δγ on θp = 0")
        ax.plot(m, cl["ray_average"].W_star[i], "s--", color="tab:blue", label=model_label("dh-elliptic-ray-average"))
        ax.plot(m, cl["two_axis"].W_star[i], "^-.", color="tab:red", label=model_label("dh-elliptic-two-axis") + ", β_cd ≠ β_ab")
        ax.plot(m, res["jkr_elliptic"][i], "x:", color="0.4", label=model_label("jkr-elliptic"))
        ax.set_xscale("log")
        ax.set_xticks(m)
        ax.set_xticklabels([f"{x:g}" for x in m])
        ax.minorticks_off()
        ax.set_xlabel("μ (Eq. 35)")
        ax.set_title(f"β0 = {b:g}")
        ax.grid(alpha=0.3)
    axs[0, 0].set_ylabel("W*max (Eq. 34)")
    legend_below(fig, ncol=1 if n_panels == 1 else 2)
    cap = ("Load-controlled pull-off W*max (Eq. 34, as in Fig. 9a) of the paper's closure (Eqs. 17–19, 31) and of "
           "two alternatives: Δγ = 1 imposed on the periphery average, and on both axes with β_cd ≠ β_ab and "
           "the contact condition kept exactly; elliptical JKR (Johnson & Greenwood 2005) for reference.")
    return Figure(save_figure(fig, outdir / "closure_pull_off.png", dpi), cap)


def _fig_bem(recs, outdir, dpi):
    plt = _plt()
    nmax = max(r["n"] for r in recs)
    fig, ax = plt.subplots(figsize=figsize(1))
    for r in recs:
        if r["n"] != nmax:
            continue
        # the report's sign convention, model/BEM − 1 (the check's |BEM/model − 1| differs by O(error²))
        err = np.abs(r["analytic"].work_of_adhesion / r["profile"].work_of_adhesion - 1.0)
        ax.semilogy(np.rad2deg(r["profile"].theta), np.maximum(err, 1e-12), _STYLES[r["beta0"]],
                    color=_COLORS[r["mu"]], label=f"β0 = {r['beta0']:g}, μ = {r['mu']:g}")
    ax.axhline(TOL_BEM, color="k", lw=0.8)
    ax.set_xlabel("θp (deg)")
    ax.set_ylabel(rel_diff_label("Δγ(θp)", "analytic", "BEM", percent=False, absolute=True))
    ax.grid(alpha=0.3)
    ax.legend(ncol=2)
    fig.tight_layout()
    cap = (f"Ray work of adhesion (Eq. 31 on every ray) from the DC-FFT BEM gap (dhfield.bem/fields, N = {nmax}, "
           "domain 2.1c, cell-averaged DH pressure of Eq. 22) against the analytic fields, at pull-off. The gap is "
           "interpolated along each ray with a bicubic spline and integrated by parts against the analytic σ "
           "(Eq. 23). Horizontal line: the 1e-3 target.")
    return Figure(save_figure(fig, outdir / "periphery_bem_vs_analytic.png", dpi), cap)


# --------------------------------------------------------------------------- text
def _text(res, recs, eq30_grid, quick):
    w = res["profile"].work_of_adhesion
    ratio = w[..., -1] / w[..., 0]
    cl = res["closures"]
    shift_r = cl["ray_average"].W_star / cl["paper"].W_star - 1
    shift_t = cl["two_axis"].W_star / cl["paper"].W_star - 1
    jkr = res["jkr_elliptic"]
    gap_p = np.abs(cl["paper"].W_star / jkr - 1)
    gap_t = np.abs(cl["two_axis"].W_star / jkr - 1)
    imu5 = list(res["closure_mu"]).index(5.0) if 5.0 in res["closure_mu"] else None
    parts = []
    parts.append(
        "**What varies around the periphery.** With equal ellipticities (Eq. 17) the maximum adhesive stress is "
        "the same on every ray (σ0(θp) = μ to rounding: last column of the equal-β table), the zone width scales "
        "exactly like r_ab(θp), but the work the fields do along a ray, Δγ(θp) = ∫σ dh (Eq. 31 on that ray), "
        "falls monotonically from the major axis, where the model imposes Δγ = 1, to the minor axis. At "
        f"pull-off, Δγ(π/2)/Δγ(0) is {ratio[0].max():.3f}–{ratio[0].min():.3f} at β0 = 0.8, "
        f"{ratio[1].max():.3f}–{ratio[1].min():.3f} at β0 = 0.9 and {ratio[2].max():.4f}–{ratio[2].min():.4f} "
        "at β0 = 0.99, decreasing with μ; for the narrow JKR-like zone (μ = 5) it is close to β0 itself "
        f"({', '.join(f'{x:.4f}' for x in ratio[:, -1])}). The σ–h curves have the same start σ0 but end at a "
        "smaller separation on the minor axis (h(r_cd) minor/major ≈ the same ratio), so no single cohesive "
        "law describes the annulus.")
    parts.append(
        "**What it means for the equal-β assumption.** The paper's model is a consistent adhesive contact only "
        "on the major axis. Everywhere else the fields release less than the material's work of adhesion: "
        f"the periphery average (weights r_ab², the area a self-similar advance of the contact edge sweeps) is "
        f"{res['mean_work'][0].max():.3f}–{res['mean_work'][0].min():.3f} Δγ at β0 = 0.8 and "
        f"{res['mean_work'][1].max():.3f}–{res['mean_work'][1].min():.3f} at 0.9, i.e. a contact in which the "
        "whole periphery must satisfy Δγ is under-adhered by "
        f"{100 * (1 - res['mean_work'][0].max()):.0f}–{100 * (1 - res['mean_work'][0].min()):.0f} % (β0 = 0.8) and "
        f"{100 * (1 - res['mean_work'][1].max()):.0f}–{100 * (1 - res['mean_work'][1].min()):.0f} % (β0 = 0.9). "
        f"At β0 = 0.99 the spread (max − min)/mean is {100 * res['spread'].work_spread[2].max():.2f} % at most. "
        "The assumption β_cd = β_ab = β0 is therefore adequate for nearly "
        "circular contacts only, as the paper itself suspected from Fig. 8; the table shows by how much it "
        "fails, and that the failure grows towards the JKR side (larger μ).")
    parts.append(
        "**Eq. (30) is not the work of adhesion (erratum).** Its integrand σ_r h_θ − σ_θ h_r is the Jacobian "
        "∂(σ, h)/∂(r, θp); by Green's theorem the quarter-annulus integral is ∮σ dh around the boundary. On the "
        "contact edge h ≡ 0 (dh = 0 along it), on the adhesive edge σ = 0, and the two axes remain, run in "
        "opposite directions: **Eq. (30) = 4[Δγ(0) − Δγ(π/2)]**. Both evaluations agree to "
        f"{np.max(np.abs(res['eq30_area'] - res['eq30_boundary'].total) / (4 * w[..., 0])):.0e}. At the paper's own "
        f"pull-off points Eq. (30) gives {res['eq30_area'].min():.3f}–{res['eq30_area'].max():.3f} where Δγ = 1 is "
        "imposed, it vanishes at the circle, and it vanishes identically for any field with one cohesive law "
        "σ = f(h): it measures the *inconsistency* of the cohesive law between the axes, not an energy per "
        "unit area. (The dr dθp measure without the factor r is not the problem: the Jacobian is coordinate-"
        "free, ∂(σ,h)/∂(r,θ) dr dθ = ∂(σ,h)/∂(x,y) dx dy.) The factor 4 does not hold either: the integrand is "
        "odd in x and in y, so over the whole annulus the integral is exactly 0. The formula that is the work of "
        "adhesion is the "
        "line integral across the zone, Δγ(θp) = ∫_{r_ab}^{r_cd} σ ∂h/∂r dr, on every ray; for the DH fields, "
        "which are not consistent, a single number must be chosen — θp = 0 (the paper), or the periphery "
        "average Δγ̄ = ∫Δγ(θp) r_ab² dθp / ∫r_ab² dθp (`dhfield.analysis.eq30.periphery_work_of_adhesion`).")
    if imu5 is not None and 0.8 in res["closure_beta"]:
        i8 = list(res["closure_beta"]).index(0.8)
        t = cl["two_axis"]
        cb = np.asarray(res["closure_beta"])[:, None]
        circ = bool(np.all(t.beta_contact > cb) and np.all(t.beta_adhesive > t.beta_contact))
        dh_jkr = abs(res["dh_circular"][i8, imu5] / -0.75 - 1)
        parts.append(
            "**Alternative closures and the pull-off force.** Imposing Δγ = 1 on the periphery average (equal β "
            "kept), or on both axes with β_cd ≠ β_ab (the contact condition then fixes both Hertz amplitudes: "
            "two fields with different ellipticities can only reproduce the geometry's curvature ratio R′/R″ if "
            "both ellipticities move to the same side of β0, the adhesive one further"
            + (" — here both become more circular, β0 < β_ab < β_cd" if circ else "") + "), makes pull-off more "
            "tensile by "
            f"{100 * min(shift_r[i8].min(), shift_t[i8].min()):.1f} to {100 * max(shift_r[i8].max(), shift_t[i8].max()):.1f} % "
            f"at β0 = 0.8 (μ = {res['closure_mu'].min():g}–{res['closure_mu'].max():g}). At μ = 5 the two-axis "
            f"closure is {100 * gap_t[i8, imu5]:.1f} % from elliptical JKR and the ray-average closure "
            f"{100 * abs(cl['ray_average'].W_star[i8, imu5] / jkr[i8, imu5] - 1):.1f} % (it keeps the paper's "
            f"pressure form, equal β), against {100 * gap_p[i8, imu5]:.1f} % "
            f"for the paper's closure — comparable to the {100 * dh_jkr:.1f} % by which circular DH differs from "
            "circular JKR at μ = 5. The price of the two-axis closure is a non-uniform σ0: μ is imposed on "
            "the major axis and the minor axis carries "
            f"{100 * ((t.sigma0_minor / res['closure_mu']).min() - 1):.1f}–"
            f"{100 * ((t.sigma0_minor / res['closure_mu']).max() - 1):.1f} % more (σ0(π/2)/μ in the table). The "
            "deviation of the paper's Fig. 9a at β0 = 0.8 and 0.9 is thus mostly due to imposing Δγ on θp = 0 "
            "only, not to the DH pressure form.")
    if recs:
        nmax = max(r["n"] for r in recs)
        fin = [r for r in recs if r["n"] == nmax]
        ok = [r for r in fin if r["mu"] <= 2.0]
        bad = [r for r in fin if r["mu"] > 2.0]
        txt = (f"**BEM vs analytic Δγ(θp).** N = {nmax}{' (quick mode: coarse grid, looser tolerance)' if quick else ''}: "
               f"max relative difference over θp {min(r['max_error'] for r in fin):.1e}–"
               f"{max(r['max_error'] for r in fin):.1e}.")
        if ok and bad:
            txt += (f" The 1e-3 target is met for μ ≤ 2 (≤ {max(r['max_error'] for r in ok):.1e}) and **not "
                    f"reached at μ = 5** ({min(r['max_error'] for r in bad):.1e}–{max(r['max_error'] for r in bad):.1e}): "
                    f"there the zone spans only ~{min(r['zone_cells'] for r in bad):.0f} cells across the major "
                    "axis, and the error, O(dx^1.5) from the square-root edges, converges at the observed order "
                    f"{min(r['order'] for r in bad):.2f}–{max(r['order'] for r in bad):.2f}; 1e-3 would need "
                    f"N ≈ {max(nmax * (r['max_error'] / TOL_BEM) ** (1 / r['order']) for r in bad):.0f}. The two "
                    "error sources are of the same size there: the spline of the analytic gap sampled on the "
                    f"same grid alone gives {min(r['interp_error'] for r in bad):.1e}–"
                    f"{max(r['interp_error'] for r in bad):.1e} (the s^(3/2) kinks of h at both zone edges), the "
                    "BEM gap with the analytic gap as interpolation trend "
                    f"{min(r['bem_error'] for r in bad):.1e}–{max(r['bem_error'] for r in bad):.1e}; it is the "
                    "resolution of the narrow zone, not the ray quadrature.")
        parts.append(txt)
    if eq30_grid:
        parts.append(
            f"**Eq. (30) on the BEM field** (β0 = {eq30_grid['beta0']:g}, μ = {eq30_grid['mu']:g}, N = "
            f"{eq30_grid['n']}): area sum of central differences {eq30_grid['value']:.5f}, Green's form from the "
            f"gridded gap {eq30_grid['boundary']:.5f}, analytic {eq30_grid['exact']:.5f}.")
    return "\n\n".join(parts)


# --------------------------------------------------------------------------- verdict
def verdict_lines(res, recs):
    """The section's conclusions for the report's lead (Markdown lines; every number computed here).

    Returns
    -------
    verdict, guide : list of str
    """
    from dhfield.analysis import eq30
    from dhfield.models import dh_elliptic as model
    from dhfield.core.geometry import skew_angle

    def rng(x, fmt):
        lo, hi = float(np.min(x)), float(np.max(x))
        return f"{lo:{fmt}}" if f"{lo:{fmt}}" == f"{hi:{fmt}}" else f"{lo:{fmt}}–{hi:{fmt}}"

    def pct(x, digits=1):
        return f"{100 * x:.{digits}f} %"

    w = res["profile"].work_of_adhesion
    ratio = w[..., -1] / w[..., 0]
    cl, jkr = res["closures"], res["jkr_elliptic"]
    cb, cm = list(res["closure_beta"]), list(res["closure_mu"])
    shift_t = cl["two_axis"].W_star / cl["paper"].W_star - 1
    shift_r = cl["ray_average"].W_star / cl["paper"].W_star - 1
    gap = {k: np.abs(cl[k].W_star / jkr - 1) for k in ("paper", "two_axis", "ray_average")}
    deg = np.rad2deg(skew_angle(np.asarray(cb, float)))
    verdict = []
    if 5.0 in cm:
        j = cm.index(5.0)
        betas = ", ".join(f"{b:g}" for b in cb)
        verdict.append(
            "**Imposing Δγ around the periphery, not only on θp = 0, closes the gap.** At μ = 5 and β0 = "
            f"{betas} the two-axis closure (`dh-elliptic-two-axis`: Δγ on both axes, β_cd ≠ β_ab) is within "
            f"{pct(gap['two_axis'][:, j].max(), 2)} of elliptical JKR and the ray-average closure "
            f"(`dh-elliptic-ray-average`: Δγ on the periphery average, equal β) within "
            f"{pct(gap['ray_average'][:, j].max(), 2)}, against {rng(100 * gap['paper'][:, j], '.1f')} % for the "
            f"paper's closure. Over β0 = {betas} and μ = {', '.join(f'{m:g}' for m in cm)} both make the "
            f"pull-off {rng(100 * np.concatenate([shift_t.ravel(), shift_r.ravel()]), '.1f')} % more tensile "
            "than the paper's closure (Eq. 34).")
    big = [(b, m) for i, b in enumerate(cb) for k, m in enumerate(cm) if abs(shift_t[i, k]) > 0.02]
    small = [(b, m) for i, b in enumerate(cb) for k, m in enumerate(cm) if abs(shift_t[i, k]) <= 0.02]
    where = []
    if big:
        where.append("by more than 2 % at (β0, μ) = " + ", ".join(f"({b:g}, {m:g})" for b, m in big))
    if small:
        where.append("within 2 % at " + ", ".join(f"({b:g}, {m:g})" for b, m in small))
    verdict.append(
        "**Range.** The paper's closure departs from the two-axis closure " + "; ".join(where) + ". In skew "
        "angle: β0 = " + ", ".join(f"{b:g} is θ_skew = {d:.1f}°" for b, d in zip(cb, deg)) + " (Eq. 3), so "
        "the paper's validated range β0 ≥ 0.8 covers crossing angles of about 80–90° only.")
    circle = model.pull_off(mu=res["mu"], beta0=1.0)
    i30_circle = np.abs(eq30.eq30_area(circle.a_star, circle.c_star, 1.0, circle.v))
    agree = np.max(np.abs(res["eq30_area"] - res["eq30_boundary"].total) / (4 * w[..., 0]))
    verdict.append(
        "**Eq. (30) is not the work of adhesion.** By Green's theorem it equals 4[Δγ(0) − Δγ(π/2)], the "
        f"difference of the ray works between the axes (area and boundary forms agree to {agree:.0e} of 4Δγ): "
        f"it vanishes at the circle (abs(Eq. 30) ≤ {i30_circle.max():.0e} at β0 = 1, where Δγ = 1), and at the "
        f"paper's own pull-off points (β0 = {', '.join(f'{b:g}' for b in res['beta0'])}, μ = "
        f"{', '.join(f'{m:g}' for m in res['mu'])}) it gives {rng(res['eq30_area'], '.3f')} where Δγ = 1 is "
        "imposed.")
    per_beta = "; ".join(f"{rng(ratio[i], '.3f' if b < 0.95 else '.4f')} at β0 = {b:g}"
                         for i, b in enumerate(res["beta0"]))
    verdict.append(
        "**Equal β gives no single cohesive law around the periphery.** At pull-off the ray work of adhesion "
        f"on the minor axis over that on the major axis, Δγ(π/2)/Δγ(0) (Eq. 31 on each ray), is {per_beta} "
        f"(μ = {res['mu'].min():g}–{res['mu'].max():g}), while σ0 is the same on every ray: the minor axis "
        f"releases up to {pct(1 - ratio.min(), 0)} less than the work of adhesion the model imposes.")
    if recs:
        nmax = max(r["n"] for r in recs)
        fin = [r for r in recs if r["n"] == nmax]
        wide = [r["max_error"] for r in fin if r["mu"] <= 2.0]
        narrow = [r["max_error"] for r in fin if r["mu"] > 2.0]
        verdict.append(
            f"The ray works are confirmed on the boundary-element field (DC-FFT, N = {nmax}, {len(fin)} pull-off "
            "state(s)): max over θp of abs(Δγ_BEM/Δγ − 1) = "
            + (f"{rng(wide, '.1e')} for μ ≤ 2" if wide else "")
            + ("; " if wide and narrow else "")
            + (f"{rng(narrow, '.1e')} for μ = 5, where the narrow zone spans few cells" if narrow else "") + ".")
    guide = []
    if 5.0 in cm:
        j = cm.index(5.0)
        s0 = cl["two_axis"].sigma0_minor / np.asarray(cm)[None, :]
        from dhfield.analysis.compare import PAPER_MODEL, RECOMMENDED_MODEL

        guide.append(
            f"**The paper's pressure form on elliptical contacts, β0 < 0.99 (θ_skew below about "
            f"{np.rad2deg(skew_angle(0.99)):.1f}°):** for a pull-off force use the recommended `{RECOMMENDED_MODEL}` "
            "(the default); of the double-Hertz closures, `dh-elliptic-two-axis` (by name) is within "
            f"{pct(gap['two_axis'][:, j].max(), 2)} of elliptical JKR at μ = 5 for β0 = "
            f"{', '.join(f'{b:g}' for b in cb)}; it keeps the contact condition exactly, at the price of a σ0 up "
            f"to {pct(s0.max() - 1)} above μ on the minor axis. The paper's `{PAPER_MODEL}`, available by name, is "
            f"{rng(100 * np.abs(shift_t[np.asarray(cb) < 0.99]), '.1f')} % weaker than the two-axis closure at "
            f"β0 = {', '.join(f'{b:g}' for b in cb if b < 0.99)} (it warns where it departs from "
            f"`{RECOMMENDED_MODEL}` by more than 2 %).")
        guide.append(
            "**The paper's pressure form with a fair work of adhesion:** `dh-elliptic-ray-average` keeps one "
            f"β and one σ0 on every ray and is within {pct(gap['ray_average'][:, j].max(), 2)} of elliptical "
            "JKR at μ = 5.")
    return verdict, guide


# --------------------------------------------------------------------------- datasets
def _datasets(res, recs, outdir):
    from dhfield.io import periphery as iop

    out = []
    ds = iop.pull_off_periphery_dataset(res["pull_off"], res["profile"], res["law"], beta0=res["beta0"], mu=res["mu"])
    out.append(iop.write_dataset(ds, outdir / "periphery_pull_off.nc"))
    ds = iop.equal_beta_dataset(_sub_spread(res), res["closures"], beta0=res["closure_beta"],
                                mu=res["closure_mu"])
    out.append(iop.write_dataset(ds, outdir / "equal_beta_closures.nc"))
    ds = iop.eq30_dataset(res["eq30_area"], res["eq30_boundary"].total,
                          res["profile"].work_of_adhesion[..., 0], res["profile"].work_of_adhesion[..., -1],
                          res["mean_work"], beta0=res["beta0"], mu=res["mu"])
    out.append(iop.write_dataset(ds, outdir / "eq30.nc"))
    if recs:
        nmax = max(r["n"] for r in recs)
        r = next(r for r in recs if r["n"] == nmax)
        a, c, b0, v = r["state"]
        ds = iop.grid_periphery_dataset(r["profile"].theta, r["analytic"], {"bem": r["profile"]},
                                        beta0=b0, mu=r["mu"], n=nmax, semi_major=a, adhesive_semi_major=c,
                                        scaling=v, half_width=r["half_width"], sampling="average",
                                        method="parts")
        out.append(iop.write_dataset(ds, outdir / "periphery_bem.nc"))
    return out


def _sub_spread(res):
    """The spread restricted to the closure grid (same β0, μ subset)."""
    from dhfield.models.dh_elliptic_closure import EqualBetaSpread

    ib = [list(res["beta0"]).index(b) for b in res["closure_beta"]]
    im = [list(res["mu"]).index(m) for m in res["closure_mu"]]
    return EqualBetaSpread(**{k: np.asarray(v)[np.ix_(ib, im)] for k, v in res["spread"].as_dict().items()})


# --------------------------------------------------------------------------- entry point
def run(outdir: Path, quick: bool, progress) -> Section:
    """Build the section: figures, tables, checks and netCDF files under ``outdir``."""
    outdir = Path(outdir)
    outdir.mkdir(parents=True, exist_ok=True)
    res = compute(quick, progress)
    cfg = res["cfg"]
    checks = _checks(res)
    progress("checks: Eq. (30), limits, closures")
    recs, eq30_grid = bem_comparison(cfg["bem_cases"], cfg["bem_n"], progress)
    nmax = cfg["bem_n"][-1]
    fin = [r for r in recs if r["n"] == nmax]
    if quick:
        checks.append(check_le(f"BEM vs analytic Δγ(θp), QUICK: N = {nmax}, β0 = 0.8, μ = 1, max rel. over θp",
                               max(r["max_error"] for r in fin), TOL_BEM_QUICK,
                               "analytic Eq. (31); quick-mode grid, not the N = 1024 target"))
    else:
        wide = [r for r in fin if r["mu"] <= 2.0]
        checks.append(check_le(f"BEM vs analytic Δγ(θp) at N = {nmax}, μ ≤ 2 (9 pull-off states), max rel. over "
                               "θp", max(r["max_error"] for r in wide), TOL_BEM,
                               "analytic Eq. (31) on every ray; target 1e-3"))
        narrow = [r for r in fin if r["mu"] > 2.0]
        if narrow:
            checks.append(check_ge("BEM vs analytic Δγ(θp), μ = 5 (target 1e-3 not reached at N = 1024, see "
                                   "text): observed convergence order N = 512 → 1024, min over β0",
                                   min(r["order"] for r in narrow), MIN_ORDER_MU5,
                                   "O(dx^1.5) BEM error of the square-root pressure edges"))
    if eq30_grid:
        checks.append(check_le(f"Eq. (30) as an area sum of the BEM field (N = {eq30_grid['n']}, central "
                               f"differences{', QUICK' if quick else ''}) vs the analytic area integral, rel.",
                               abs(eq30_grid["value"] / eq30_grid["exact"] - 1),
                               TOL_EQ30_GRID_QUICK if quick else TOL_EQ30_GRID,
                               "dhfield.analysis.eq30.eq30_area (analytic fields)"))
    figures = [_fig_rays(res, outdir, cfg["dpi"]), _fig_laws(res, outdir, cfg["dpi"])]
    fig, curves = _fig_curves(res, outdir, cfg["dpi"], cfg["curve_n"])
    figures += [fig, _fig_closures(res, outdir, cfg["dpi"]), _fig_bem(recs, outdir, cfg["dpi"])]
    progress("figures")
    datasets = _datasets(res, recs, outdir)
    from dhfield.io import periphery as iop

    ds = iop.load_curve_periphery_dataset({k: v[0] for k, v in curves.items()},
                                          {k: v[1] for k, v in curves.items()}, beta0=res["beta0"], mu=[1.0, 5.0])
    datasets.append(iop.write_dataset(ds, outdir / "periphery_load_curves.nc"))
    progress("netCDF")
    tables = [
        "**Δγ(π/2)/Δγ(0) at pull-off** (load control; Eq. 31 on the minor over the major axis):\n\n" + ratio_table(res),
        "**The equal-β test** (spread across θp at pull-off; σ–h curves on 31 rays):\n\n" + spread_table(res),
        "**Eq. (30) as printed vs the ray works** (pull-off states; Eq. 30 = 4[Δγ(0) − Δγ(π/2)]):\n\n"
        + eq30_table(res),
        "**Pull-off with alternative closures** (load control; shift relative to the paper's closure):\n\n"
        + closure_table(res),
        f"**BEM vs analytic Δγ(θp)**{' (QUICK: coarse grids)' if quick else ''}:\n\n" + bem_table(recs),
    ]
    verdict, guide = verdict_lines(res, recs)
    return Section(title=TITLE, text=_text(res, recs, eq30_grid, quick), checks=checks, figures=figures,
                   tables=tables, datasets=datasets, verdict=verdict, guide=guide)


def main(argv=None):
    """Print the section's tables: ``python -m verification.sec_periphery [--quick] [--bem]``."""
    argv = sys.argv[1:] if argv is None else argv
    quick = "--quick" in argv
    res = compute(quick, progress=lambda m: print(f"# {m}", file=sys.stderr))
    print("## Δγ(π/2)/Δγ(0) at pull-off\n\n" + ratio_table(res) + "\n")
    print("## Equal-β test\n\n" + spread_table(res) + "\n")
    print("## Eq. (30)\n\n" + eq30_table(res) + "\n")
    print("## Closures\n\n" + closure_table(res) + "\n")
    if "--bem" in argv:
        cfg = res["cfg"]
        recs, g = bem_comparison(cfg["bem_cases"], cfg["bem_n"],
                                 progress=lambda m: print(f"# {m}", file=sys.stderr))
        print("## BEM vs analytic\n\n" + bem_table(recs) + "\n")
        print(f"Eq. (30) on the BEM field: {g}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
