"""Report section: the comparison models and the paper's Figs. 8-9 (issue 3).

Reproduces Fig. 8 (a* against W* at mu = 5 for beta0 = 0.8, 0.9, 0.99 with the
approximate elliptical JKR model of Johnson & Greenwood 2005), Fig. 9a (W*max
against mu for every model) and Fig. 9b (relative error of both DH assumptions
against elliptical JKR) of Zini et al. 2018 (doi:10.1007/s11249-017-0976-8), with
a generated table of W*max and the paper's qualitative statements next to it.

Checks, each against a reference that does not share the code path:

* Maugis-Dugdale: pull-off within 0.1 % of DMT (lambda = 0.01) and JKR
  (lambda = 100), both controls; whole load curves against JKR/DMT at the rates
  the physics gives (module constants);
* elliptical JKR: circular JKR at beta0 = 1 (<= 1e-10); the contact condition
  inside the ellipse and Griffith's criterion at both axis ends, by an independent
  Boussinesq quadrature of the pressure; beta -> beta0 at high load;
* circular DH (closed form) against the elliptical DH core at beta0 = 1 on whole
  load curves (<= 1e-9), and its work of adhesion against quadrature of Eq. (31);
* the mu <-> lambda mapping against the two definitions.
"""
from __future__ import annotations

from pathlib import Path

import numpy as np

from verification._api import Figure, Section, check_le, save_figure
from verification._oracles import boussinesq_displacement
from verification._style import QUICK_DPI, REPORT_DPI, figsize, legend_below, model_label, rel_diff_label

TITLE = "Comparison models (JKR, DMT, Maugis–Dugdale, circular DH, elliptical JKR): Figs. 8–9"

#: issue 3: MD pull-off within 0.1 % of DMT at lambda = 0.01 and of JKR at lambda = 100
TOL_MD_PULL_OFF = 1e-3
#: issue 3 target for whole MD load curves (Maugis units); reached at lambda = 1000 / 0.001
TOL_MD_CURVE = 1e-4
#: at lambda = 100 the MD load deviates from JKR by O(lambda^-2) terms: measured 3.1e-4
TOL_MD_CURVE_100 = 4e-4
#: at lambda = 0.01 the MD load deviates from DMT by O(lambda^1.5) on A <= 0.3: measured 1.7e-3
TOL_MD_CURVE_001 = 2e-3
#: issue 3: elliptical JKR at beta0 = 1 is circular JKR on the load curve
TOL_CIRCLE = 1e-10
#: issue 3: |beta - beta0| at W* = 100 (met for beta0 = 0.99; see the text for 0.8, 0.9)
TOL_HERTZ_BETA = 1e-3
#: Boussinesq quadrature (40 x 256 nodes after the edge substitution) of the JKR pressure
TOL_BOUSSINESQ = 1e-8
#: issue 3: circular DH vs elliptical DH core at beta0 = 1 on whole load curves
TOL_CORE = 1e-9
#: adaptive quadrature of the circular work of adhesion (quad epsrel 1e-12)
TOL_QUAD = 1e-10
#: closed-form constants in double precision
TOL_EXACT = 1e-13

MU_TABLE = (0.5, 1.0, 2.0, 5.0)
#: The models of the paper's Fig. 9 (the two-axis and ray-average closures are in sec_periphery).
FIG9_MODELS = ("dh-elliptic", "dh-elliptic-jkr-beta", "dh-circular", "jkr", "dmt", "md", "jkr-elliptic")
BETA0 = (0.8, 0.9, 0.99)
MU_FIG8 = 5.0
_COLORS = {0.8: "tab:red", 0.9: "tab:olive", 0.99: "tab:blue"}
_MODEL_STYLE = {"dh-circular": ("k", "-"), "jkr": ("0.4", ":"), "dmt": ("0.4", "-."),
                "md": ("tab:purple", "--")}


def _settings(quick):
    if quick:
        return dict(n_mu=14, n_curve=150, dpi=QUICK_DPI)
    return dict(n_mu=60, n_curve=500, dpi=REPORT_DPI)




def _plt():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


# --------------------------------------------------------------------------- checks


def _checks_md():
    from dhfield.models import maugis_dugdale as md
    from dhfield.core.transition import tabor_from_maugis

    out = []
    for control, jkr_value in (("load", -1.5), ("displacement", -5.0 / 6.0)):
        # P = W/(pi R dgamma) = 2 W* (Eq. 34, the circle); lambda = 1.1272 mu
        p_dmt = 2.0 * float(md.pull_off_nondimensional(1.0, tabor_from_maugis(0.01), control=control).W_star)
        p_jkr = 2.0 * float(md.pull_off_nondimensional(1.0, tabor_from_maugis(100.0), control=control).W_star)
        out.append(check_le(f"MD pull-off ({control} control) at λ = 0.01 vs DMT −2πRΔγ, rel. error",
                            abs(p_dmt / -2.0 - 1), TOL_MD_PULL_OFF, "DMT closed form (Derjaguin et al. 1975)"))
        out.append(check_le(f"MD pull-off ({control} control) at λ = 100 vs JKR {jkr_value:.4g} πRΔγ, "
                            "rel. error", abs(p_jkr / jkr_value - 1), TOL_MD_PULL_OFF,
                            "JKR closed form (Johnson, Kendall & Roberts 1971)"))
    a = np.concatenate([[0.0], np.geomspace(1e-4, 10, 400)])
    pj, dj = a**3 - np.sqrt(6 * a**3), a**2 - 2 / 3 * np.sqrt(6 * a)
    for lam, tol in ((100.0, TOL_MD_CURVE_100), (1000.0, TOL_MD_CURVE)):
        p, d, _ = md.load_curve_maugis_units(a, lam)
        err = np.max(np.abs(p - pj) / np.maximum(1, np.abs(pj)))
        out.append(check_le(f"MD load curve at λ = {lam:g} vs JKR, Ā ∈ [0, 10], max abs(ΔP̄)/max(1, abs(P̄))", err, tol,
                            "JKR in Maugis units P̄ = Ā³ − √(6Ā³); deviation O(λ⁻²)"))
    p, d, _ = md.load_curve_maugis_units(a, 1000.0)
    big = a >= 0.3
    out.append(check_le("MD approach at λ = 1000 vs JKR, Ā ∈ [0.3, 10], max abs(ΔΔ̄)/max(1, abs(Δ̄))",
                        np.max(np.abs(d - dj)[big] / np.maximum(1, np.abs(dj[big]))), TOL_MD_CURVE,
                        "JKR Δ̄ = Ā² − (2/3)√(6Ā); near Ā = 0 MD ends at Δ̄ = −(4/3)λx = O(1/λ)"))
    small = a <= 0.3
    for lam, tol, amax in ((0.01, TOL_MD_CURVE_001, 0.3), (0.001, TOL_MD_CURVE, 0.1)):
        sel = a <= amax
        p, d, _ = md.load_curve_maugis_units(a[sel], lam)
        out.append(check_le(f"MD load curve at λ = {lam:g} vs DMT, Ā ∈ [0, {amax:g}], max abs(ΔP̄)",
                            np.max(np.abs(p - (a[sel] ** 3 - 2))), tol,
                            "DMT P̄ = Ā³ − 2; deviation O(λ^1.5)"))
    p, d, _ = md.load_curve_maugis_units(a[small], 0.01)
    off = -8 / 3 * np.sqrt(0.01 / np.pi)
    out.append(check_le("MD approach at λ = 0.01: (Δ̄ − Ā²) vs the DMT-side offset −(8/3)√(λ/π), rel. error",
                        np.max(np.abs((d - a[small] ** 2) / off - 1)), 0.05,
                        "asymptotics of the MD equations as λ → 0 (derived); O(√λ) relative"))
    return out


def _checks_jkr_elliptic():
    from dhfield.models import jkr, jkr_elliptic as je
    from dhfield.core.geometry import radius_ratio

    out = []
    a = np.linspace(0.02, 4.0, 300)
    st, ref = je.load_curve_nondimensional(a, 1.0), jkr.load_curve_nondimensional(a)
    err = max(np.max(np.abs(st["W_star"] - ref["W_star"])), np.max(np.abs(st["delta_star"] - ref["delta_star"])))
    out.append(check_le("elliptical JKR at β0 = 1 vs circular JKR, W* and δ* on a* ∈ [0.02, 4], max abs. error",
                        err, TOL_CIRCLE, "JKR closed form"))
    worst = 0.0
    for beta0, u in ((0.8, 0.3), (0.6, 0.7), (0.95, 0.5)):
        s = je.state_at_ellipticity(beta0 + (1.0 - beta0) * u, beta0)
        r1 = np.sqrt(radius_ratio(beta0))  # R' of R = sqrt(R'R'') = 1
        for x0, y0 in ((0.0, 0.0), (0.3 * s["a_star"], 0.0), (0.0, 0.5 * s["b_star"]),
                       (0.4 * s["a_star"], -0.3 * s["b_star"])):
            refd = s["delta_star"] - x0**2 / (2 * r1) - y0**2 * r1 / 2
            worst = max(worst, abs(boussinesq_displacement(x0, y0, s["a_star"], s["b_star"], s["alpha"]) - refd)
                        / max(1.0, abs(refd)))
        al0, al1, al2 = s["alpha"]
        worst = max(worst, abs(-(al0 + al1) * np.sqrt(np.pi * s["a_star"]) / np.sqrt(2) - 1),
                    abs(-(al0 + al2) * np.sqrt(np.pi * s["b_star"]) / np.sqrt(2) - 1))
    out.append(check_le("elliptical JKR: ω = δ − Ax² − By² inside the ellipse (4 points × 3 states) and "
                        "K_I = √(2E*Δγ) at both axis ends, max rel. error", worst, TOL_BOUSSINESQ,
                        "independent Boussinesq quadrature of the pressure (α0 + α1X² + α2Y²)/√(1−X²−Y²)"))
    dev = float(je.ellipticity_at_load(100.0, beta0=0.99) - 0.99)
    out.append(check_le("elliptical JKR: β − β0 at W* = 100, β0 = 0.99", dev, TOL_HERTZ_BETA,
                        "Hertz limit (β → β0 as W* → ∞)"))
    b = np.array(BETA0)
    c4 = (je.ellipticity_at_load(1e4, beta0=b) - b) * 1e2
    c6 = (je.ellipticity_at_load(1e6, beta0=b) - b) * 1e3
    out.append(check_le("elliptical JKR: (β − β0)·√W* at W* = 1e6 vs 1e4 (β0 = 0.8, 0.9, 0.99), max rel. change",
                        np.max(np.abs(c6 / c4 - 1)), 0.02,
                        "β − β0 = C/√W* + …: the adhesive correction of JKR decays like √(8πa³)/W"))
    rho = np.array([1.02, 1.01, 1.005])
    coef = (1 - je.pull_off_force_ratio(radius_ratio=rho)) / np.log(rho) ** 2
    out.append(check_le("elliptical JKR pull-off at mild ellipticity: (1 − W/(−1.5πRΔγ))/(ln R'/R'')² "
                        "at R'/R'' = 1.02 vs 1.005, rel. change", abs(coef[0] / coef[-1] - 1), 0.02,
                        "symmetry R'/R'' → R''/R': the deviation is even in ln(R'/R'')"))
    return out, {float(bb): (float(x), float(y)) for bb, x, y in zip(b, je.ellipticity_at_load(100.0, beta0=b) - b, c6)}


def _checks_dh_circular():
    from scipy import integrate

    from dhfield.models import dh_circular, dh_elliptic as model

    out = []
    worst = 0.0
    a = np.linspace(*model.DEFAULT_A_STAR, 200)
    for mu in MU_TABLE:
        ref = model.load_curve(mu=mu, beta0=1.0, a_star=a)
        st = dh_circular.load_curve_nondimensional(a, mu)
        for key in ("W_star", "c_star", "v", "delta_star"):
            worst = max(worst, np.max(np.abs(st[key] - getattr(ref, key)) / np.maximum(1, np.abs(getattr(ref, key)))))
        for control in ("load", "displacement"):
            po, pr = dh_circular.pull_off_nondimensional(1.0, mu, control=control), model.pull_off(mu=mu, beta0=1.0, control=control)
            worst = max(worst, abs(po["W_star"] - pr.W_star), abs(po["a_star"] - pr.a_star))
    out.append(check_le("circular DH (closed form) vs elliptical DH core at β0 = 1: W*, c*, v, δ* on a* ∈ "
                        f"[{model.DEFAULT_A_STAR[0]:g}, {model.DEFAULT_A_STAR[1]:g}] and the pull-off (both "
                        f"controls), μ = {', '.join(f'{m:g}' for m in MU_TABLE)}, max error", worst, TOL_CORE,
                        "Greenwood & Johnson (1998) in closed form (cubic in c − a), independent of Eq. (31) "
                        "quadrature"))
    rng = np.random.default_rng(1998)
    worst = 0.0
    for _ in range(8):
        aa = rng.uniform(0, 3)
        cc = aa + rng.uniform(0.01, 2)
        v = rng.uniform(0.01, 5)

        def integrand(r):
            slope = 2 / np.pi * (r * np.arccos(aa / r) + aa * np.sqrt(r * r - aa * aa) / r)
            return v * 2 / np.pi * np.sqrt(cc * cc - r * r) * (1 + v) * slope

        q = integrate.quad(integrand, aa, cc, epsabs=0, epsrel=1e-12, limit=200)[0]
        worst = max(worst, abs(dh_circular.work_of_adhesion(aa, cc, v, 1.0, 1.0) / q - 1))
    out.append(check_le("circular DH work of adhesion v(1+v)(2/(3π))(c−a)²(c+2a) vs quadrature of Eq. (31) "
                        "(8 seeded states), max rel. error", worst, TOL_QUAD,
                        "scipy.integrate.quad of σ dh/dr with the Hertz gap outside the contact"))
    return out


def _check_transition():
    from dhfield.core.transition import maugis_parameter

    r, e, dg, s0 = 2e-6, 3e9, 0.07, 4e8
    mu = s0 * np.cbrt(r / (e * e * dg))
    lam = 2 * s0 * np.cbrt(r / (np.pi * dg * (4 * e / 3) ** 2))
    return check_le("μ (Eq. 35) → Maugis λ = 2(9/(16π))^(1/3) μ vs both definitions, rel. error",
                    abs(maugis_parameter(mu) / lam - 1), TOL_EXACT, "Maugis (1992) λ = 2σ0(R/(πΔγK²))^(1/3)")


# --------------------------------------------------------------------------- figures and table


def _fig8(outdir, dpi, n):
    from dhfield.models import jkr, jkr_elliptic as je
    from dhfield.models.dh_elliptic import load_curve, pull_off

    plt = _plt()
    fig, ax = plt.subplots(figsize=figsize(1, 0.8))
    a = np.unique(np.concatenate([np.geomspace(0.05, 0.6, n // 3), np.linspace(0.6, 3.2, n - n // 3)]))
    for b0 in BETA0:
        col = _COLORS[b0]
        cv = load_curve(mu=MU_FIG8, beta0=b0, a_star=a)
        ax.plot(cv.W_star, cv.a_star, "-", color=col, lw=1.6, label=f"{model_label('dh-elliptic')}, β0 = {b0:g}")
        po = pull_off(mu=MU_FIG8, beta0=b0)
        ax.plot(po.W_star, po.a_star, "o", color=col, ms=5)
        st = je.load_curve_nondimensional(a, b0)
        ax.plot(st["W_star"], st["a_star"], "--", color=col, lw=1.2, label=f"{model_label('jkr-elliptic')}, β0 = {b0:g}")
        pj = je.pull_off_nondimensional(b0, 1.0)
        ax.plot(pj["W_star"], pj["a_star"], "s", color=col, mfc="none", ms=5)
    j = jkr.load_curve_nondimensional(a)
    ax.plot(j["W_star"], j["a_star"], ":", color="0.3", lw=1.5, label="JKR circular")
    ax.set_xlabel("load W* = W sinθ / (2πRΔγ)  (Eq. 34)")
    ax.set_ylabel("contact semi-major axis a* (Eq. 32)")
    ax.set_xlim(-0.85, 1.2)
    ax.set_ylim(0, 3.2)
    ax.grid(alpha=0.3)
    ax.set_title(f"Fig. 8: a* vs W* at μ = {MU_FIG8:g}")
    fig.tight_layout()
    legend_below(fig, ncol=2)
    cap = ("Reproduces Fig. 8 of Zini et al. (2018): contact semi-major axis a* against W* (Eq. 34) at μ = 5 "
           "for β0 = 0.8, 0.9, 0.99; solid: elliptical DH (Eqs. 31–36, β = β0), dashed: approximate elliptical "
           "JKR (Johnson & Greenwood 2005, same normalisation with sinθ_skew(β0)), dotted: circular JKR. "
           "Circles and squares mark the load-controlled pull-off.")
    return Figure(save_figure(fig, outdir / "fig8_a_vs_W_mu5.png", dpi), cap)


def _fig9(outdir, dpi, mu, res):
    plt = _plt()
    fig, (ax, bx) = plt.subplots(1, 2, figsize=figsize(2, 0.42))
    for name, (col, ls) in _MODEL_STYLE.items():
        ax.plot(mu, res[name][:, 0], ls, color=col, lw=1.4, label=model_label(name))
    for j, b0 in enumerate(BETA0):
        col = _COLORS[b0]
        ax.plot(mu, res["dh-elliptic"][:, j], "-", color=col, lw=1.6, label=f"DH elliptic (paper), β = β0 = {b0:g}")
        ax.plot(mu, res["dh-elliptic-jkr-beta"][:, j], "-.", color=col, lw=1.3,
                label=f"DH elliptic, β = β_JKR(pull-off), β0 = {b0:g}")
        ax.plot(mu, res["jkr-elliptic"][:, j], ":", color=col, lw=1.6,
                label=f"{model_label('jkr-elliptic')}, β0 = {b0:g}")
        jk = res["jkr-elliptic"][:, j]
        bx.plot(mu, 100 * (res["dh-elliptic"][:, j] / jk - 1), "-", color=col, lw=1.6)
        bx.plot(mu, 100 * (res["dh-elliptic-jkr-beta"][:, j] / jk - 1), "-.", color=col, lw=1.3)
    for axis in (ax, bx):
        axis.set_xscale("log")
        axis.set_xticks([0.3, 0.5, 1, 2, 5, 8])
        axis.xaxis.set_major_formatter(plt.matplotlib.ticker.FormatStrFormatter("%g"))
        axis.xaxis.set_minor_formatter(plt.matplotlib.ticker.NullFormatter())
    ax.set_xlabel("Tabor parameter μ (Eq. 35)")
    ax.set_ylabel("pull-off load W*max (Eq. 34)")
    ax.grid(alpha=0.3, which="both")
    ax.set_title("Fig. 9a: W*max vs μ")
    bx.axhline(0, color="0.5", lw=0.8)
    bx.set_xlabel("Tabor parameter μ (Eq. 35)")
    bx.set_ylabel(rel_diff_label("W*max", "DH", "JKR ell."))
    bx.grid(alpha=0.3, which="both")
    bx.set_title("Fig. 9b: both DH assumptions vs elliptical JKR")
    fig.tight_layout()
    legend_below(fig, ncol=3, axes=[ax])  # panel (b) uses the same colours and line styles as (a)
    cap = ("Reproduces Fig. 9a/9b of Zini et al. (2018). (a) Load-controlled pull-off W*max (Eq. 34) against μ "
           "(Eq. 35) for the elliptical DH model with β = β0 (Eq. 19) and with β_(pull-off) = β_JKR(pull-off), "
           "approximate elliptical JKR (Johnson & Greenwood 2005), and the circular models (DH of Greenwood & "
           "Johnson 1998, JKR, DMT, Maugis–Dugdale at λ = 1.1272 μ). (b) Relative error of both DH "
           "assumptions against elliptical JKR, in %; the comparison is meaningful in the JKR domain (large μ).")
    return Figure(save_figure(fig, outdir / "fig9_pull_off_vs_mu.png", dpi), cap)


def _table(tab):
    names = ("dh-elliptic", "dh-elliptic-jkr-beta", "jkr-elliptic", "dh-circular", "md", "jkr", "dmt")
    head = "| μ | β0 | " + " | ".join(names) + " |"
    lines = [head, "|" + "---|" * (len(names) + 2)]
    for mu in MU_TABLE:
        for b0 in BETA0:
            lines.append(f"| {mu:g} | {b0:g} | " + " | ".join(f"{tab[(mu, b0)][n]:.4f}" for n in names) + " |")
    return "\n".join(lines)


def _statements(tab):
    """The paper's qualitative statements (Sec. 3, Figs. 8-9) and whether they hold here."""
    def err(mu, b0, name):
        return tab[(mu, b0)][name] / tab[(mu, b0)]["jkr-elliptic"] - 1

    rows = []
    e99, e9, e8 = err(5.0, 0.99, "dh-elliptic"), err(5.0, 0.9, "dh-elliptic"), err(5.0, 0.8, "dh-elliptic")
    rows.append(("Fig. 8: “Only the curve of β0 = 0.99 has a close fit to the JKR elliptical model” (μ = 5)",
                 f"rel. error of W*max at β0 = 0.99: {100 * e99:+.2f} %", abs(e99) < 0.01, "abs. error < 1 %"))
    rows.append(("Fig. 8: “The difference in pull-off force … is more apparent with decreasing β0”",
                 f"{100 * e99:+.2f} % (0.99), {100 * e9:+.2f} % (0.9), {100 * e8:+.2f} % (0.8)",
                 abs(e8) > abs(e9) > abs(e99), "abs. error grows as β0 decreases"))
    rows.append(("Fig. 8: “the pull-off forces predicted … at β0 values of 0.8 and 0.9 are considerably low”",
                 f"magnitude of W*max below JKR elliptical by {-100 * e9:.1f} % (0.9) and {-100 * e8:.1f} % (0.8)",
                 e8 < -0.03 and e9 < -0.03, "both lower in magnitude by > 3 %"))
    v9, v8 = err(5.0, 0.9, "dh-elliptic-jkr-beta"), err(5.0, 0.8, "dh-elliptic-jkr-beta")
    rows.append(("Fig. 9b: “With the new assumption of JKR-like behavior, the gap … is slightly improved for "
                 "β0 values of 0.8 and 0.9”",
                 f"μ = 5: {100 * e9:+.2f} → {100 * v9:+.2f} % (0.9), {100 * e8:+.2f} → {100 * v8:+.2f} % (0.8)",
                 abs(v9) < abs(e9) and abs(v8) < abs(e8), "abs. error smaller with β_JKR(pull-off)"))
    ok = all(abs(tab[(mu, 0.99)][n] / tab[(mu, 0.99)]["dh-circular"] - 1) < 0.01
             for mu in MU_TABLE for n in ("dh-elliptic", "dh-elliptic-jkr-beta"))
    worst = max(abs(tab[(mu, 0.99)][n] / tab[(mu, 0.99)]["dh-circular"] - 1)
                for mu in MU_TABLE for n in ("dh-elliptic", "dh-elliptic-jkr-beta"))
    rows.append(("Fig. 9a: “Both results from the developed model produce curves which lie close to the other "
                 "adhesive circular … models at β0 = 0.99”",
                 f"max abs(W*max/W*max,DH circular − 1) at β0 = 0.99 over μ = 0.5…5: {100 * worst:.2f} %", ok,
                 "< 1 % of circular DH"))
    gap = {b: [abs(err(mu, b, "dh-elliptic")) for mu in MU_TABLE] for b in (0.8, 0.9)}
    rows.append(("Fig. 9a: “At β0 values of 0.8 and 0.9, the assumption of Eq. (19) produces results which clearly "
                 "deviate from the JKR elliptical model”",
                 "abs. rel. error at μ = 0.5, 1, 2, 5: " + "; ".join(
                     f"β0 = {b:g}: " + ", ".join(f"{100 * g:.1f} %" for g in gs) for b, gs in gap.items()),
                 gap[0.8][-1] > 0.03 and gap[0.9][-1] > 0.03, "> 3 % at μ = 5 (JKR domain) for both"))
    lines = ["| paper statement | here | criterion | holds |", "|---|---|---|---|"]
    for s, here, ok, crit in rows:
        lines.append(f"| {s} | {here} | {crit} | {'yes' if ok else '**no**'} |")
    return "\n".join(lines)


#: Crossing ellipticities at which the guide quotes the two elliptical JKR limits against each other.
JKR_LIMIT_BETA0 = (0.5, 0.8)


def jkr_limits(beta0=JKR_LIMIT_BETA0):
    """W* of the two elliptical JKR models at each beta0 (both independent of mu).

    Parameters
    ----------
    beta0 : sequence of float
        Hertz ellipticities [-].

    Returns
    -------
    dict
        ``{beta0: (W*_JG, W*_GVG)}``: Johnson & Greenwood (2005), ``jkr-elliptic``, and the
        energy-minimising elliptical JKR of Giudici, Vella & Griffiths (2025), ``jkr-elliptic-energy``
        (load control, Eq. 34).
    """
    from dhfield.analysis import compare

    out = {}
    for b in beta0:
        recs = compare.compare(mu=10.0, beta0=b, models=["jkr-elliptic", "jkr-elliptic-energy"])
        out[b] = (float(recs["jkr-elliptic"]["W_star"]), float(recs["jkr-elliptic-energy"]["W_star"]))
    return out


def verdict_lines(tab, jkr=None):
    """The section's conclusions about the paper, from the W*max table (Markdown lines, numbers computed).

    Parameters
    ----------
    tab : dict
        ``tab[(mu, beta0)][model]`` = load-controlled W*max (Eq. 34), for :data:`MU_TABLE` × :data:`BETA0`,
        with the recommended model (:data:`dhfield.analysis.compare.RECOMMENDED_MODEL`) among the models.
    jkr : dict, optional
        :func:`jkr_limits`: the two elliptical JKR limits compared in the guide.

    Returns
    -------
    verdict, guide : list of str
    """
    from dhfield.analysis.compare import PAPER_MODEL, RECOMMENDED_MODEL

    def rel(mu, b0, name, ref="jkr-elliptic"):
        return tab[(mu, b0)][name] / tab[(mu, b0)][ref] - 1

    def weaker(x, digits):
        return f"{abs(100 * x):.{digits}f} % {'weaker' if x < 0 else 'stronger'}"

    mu = MU_FIG8
    e = {b: rel(mu, b, "dh-elliptic") for b in BETA0}
    ej = {b: rel(mu, b, "dh-elliptic-jkr-beta") for b in BETA0}
    worst99 = max(abs(rel(m, 0.99, n, "dh-circular")) for m in MU_TABLE for n in ("dh-elliptic", "dh-elliptic-jkr-beta"))
    circ = rel(mu, 1.0, "dh-circular", "jkr") if (mu, 1.0) in tab else None
    b_lo, b_mid, b_hi = BETA0
    verdict = [
        f"**The paper's closure under-predicts adhesion away from the circle.** At μ = {mu:g} (JKR side, where "
        "elliptical JKR of Johnson & Greenwood (2005) is the reference) the pull-off force of the paper's model "
        f"(`dh-elliptic`: one β for both ellipses, Δγ imposed on θp = 0 only, Eqs. 17–19, 31) is "
        f"{weaker(e[b_lo], 1)} than elliptical JKR at β0 = {b_lo:g} (W*max = {tab[(mu, b_lo)]['dh-elliptic']:.4f} "
        f"vs {tab[(mu, b_lo)]['jkr-elliptic']:.4f}, Eq. 34), {weaker(e[b_mid], 1)} at β0 = {b_mid:g} and "
        f"{weaker(e[b_hi], 2)} at β0 = {b_hi:g}.",
        f"The paper's second assumption (β at pull-off from JKR, `dh-elliptic-jkr-beta`) changes this only to "
        f"{weaker(ej[b_lo], 1)} (β0 = {b_lo:g}) and {weaker(ej[b_mid], 1)} (β0 = {b_mid:g}) at μ = {mu:g}; near "
        f"the circle (β0 = {b_hi:g}) both variants stay within {100 * worst99:.2f} % of circular DH "
        f"(Greenwood & Johnson 1998) for μ = {min(MU_TABLE):g}–{max(MU_TABLE):g}, as the paper states (Fig. 9a).",
    ]
    guide = []
    if all(RECOMMENDED_MODEL in tab[(m, b_hi)] for m in MU_TABLE):
        agree = max(abs(rel(m, b_hi, PAPER_MODEL, RECOMMENDED_MODEL)) for m in MU_TABLE)
        guide.append(
            f"**Near-circular contacts, β0 ≥ {b_hi:g}:** the recommended `{RECOMMENDED_MODEL}` (the default; "
            "judged against the stored BEM ground truth in the adhesion-map section). The paper's "
            f"`{PAPER_MODEL}`, available by name (`model=\"{PAPER_MODEL}\"`), is within {100 * agree:.1f} % of "
            f"it there for μ = {min(MU_TABLE):g}–{max(MU_TABLE):g}, {abs(100 * e[b_hi]):.2f} % from elliptical "
            f"JKR at μ = {mu:g} and within {100 * worst99:.2f} % of circular DH.")
    if circ is not None and jkr:
        b_jg = min(jkr)

        def jg_vs_gvg(b):
            w_jg, w_gvg = jkr[b]
            return weaker(w_jg / w_gvg - 1, 1)

        guide.append(
            "**Large μ (JKR side):** the JKR limit of an elliptical contact is `jkr-elliptic-energy` (Giudici, "
            "Vella & Griffiths 2025: the energy minimised over both semi-axes, exact as μ → ∞), the limit the "
            f"recommended model reaches; `jkr-elliptic` (Johnson & Greenwood 2005) fixes the contact shape by one "
            f"condition and is {jg_vs_gvg(b_jg)} than it at β0 = {b_jg:g}"
            + "".join(f", {jg_vs_gvg(b)} at β0 = {b:g}" for b in sorted(jkr) if b != b_jg)
            + f". At μ = {mu:g} even circular DH is still {abs(100 * circ):.1f} % from circular JKR, so a DH "
            "closure within ~1 % of the JKR limit there is as close as the DH pressure form allows.")
    return verdict, guide


def _dataset(mu, res, outdir):
    import xarray as xr

    from dhfield.io import provenance_attrs, write_netcdf

    ds = xr.Dataset(
        {name: (("mu", "beta0"), arr, {"long_name": f"load-controlled pull-off W*max, model {name} (Eq. 34)",
                                       "units": "1"})
         for name, arr in res.items()},
        coords={"mu": ("mu", mu, {"long_name": "Tabor parameter (Eq. 35)", "units": "1"}),
                "beta0": ("beta0", np.array(BETA0), {"long_name": "initial ellipticity b/a (Eq. 9)",
                                                     "units": "1"})})
    ds.attrs.update(provenance_attrs("Pull-off of all comparison models (Zini et al. 2018, Fig. 9)",
                                     produced_by="verification.sec_models",
                                     mu_to_lambda="lambda = 2 (9/(16 pi))^(1/3) mu"))
    return write_netcdf(ds, outdir / "fig9_pull_off.nc")


def run(outdir: Path, quick: bool, progress) -> Section:
    """Build the comparison-models section (see the module docstring).

    Parameters
    ----------
    outdir : Path
        Directory for the PNG figures and the netCDF file.
    quick : bool
        Coarser μ grid and curves (a few seconds).
    progress : callable
        ``progress(message)``.

    Returns
    -------
    Section
    """
    from dhfield.analysis import compare

    outdir = Path(outdir)
    outdir.mkdir(parents=True, exist_ok=True)
    cfg = _settings(quick)
    checks = []
    checks += _checks_md()
    progress("Maugis–Dugdale limits")
    jchecks, beta_hi = _checks_jkr_elliptic()
    checks += jchecks
    progress("elliptical JKR limits and Boussinesq check")
    checks += _checks_dh_circular()
    checks.append(_check_transition())
    progress("circular DH vs elliptical core")

    mu = np.unique(np.concatenate([np.geomspace(0.3, 8.0, cfg["n_mu"]), MU_TABLE]))
    # the closures that need a solve per point (two-axis, ray average) are in the periphery section
    grid = compare.compare(mu=mu[:, None], beta0=np.array(BETA0)[None, :], models=FIG9_MODELS, check_closure=False)
    res = {name: np.broadcast_to(rec["W_star"], (mu.size, len(BETA0))).copy() for name, rec in grid.items()}
    progress(f"W*max of {len(res)} models on {mu.size} × {len(BETA0)} (μ, β0)")
    tab = {(m, b): {name: float(res[name][np.flatnonzero(mu == m)[0], j]) for name in res}
           for m in MU_TABLE for j, b in enumerate(BETA0)}
    # the recommended model, for the guide (not drawn in Fig. 9, which reproduces the paper's models)
    rec_grid = compare.pull_off(compare.RECOMMENDED_MODEL, mu=np.array(MU_TABLE)[:, None],
                                beta0=np.array(BETA0)[None, :], warn=False)["W_star"]
    for i, m in enumerate(MU_TABLE):
        for j, b in enumerate(BETA0):
            tab[(m, b)][compare.RECOMMENDED_MODEL] = float(rec_grid[i, j])
    circ = compare.compare(mu=MU_FIG8, beta0=1.0, models=["dh-circular", "jkr"])
    tab[(MU_FIG8, 1.0)] = {name: float(rec["W_star"]) for name, rec in circ.items()}
    figures = [_fig8(outdir, cfg["dpi"], cfg["n_curve"]), _fig9(outdir, cfg["dpi"], mu, res)]
    datasets = [_dataset(mu, res, outdir)]
    progress("figures 8, 9 and the dataset")

    from dhfield.models.jkr_elliptic import pull_off_ellipticity

    bj = pull_off_ellipticity(beta0=np.array(BETA0))
    text = (
        "All models are on the paper's axes: W* = W sinθ_skew/(2πRΔγ) (Eq. 34) with sinθ_skew of β0 for the "
        "elliptical models and 1 for the circular ones, R = √(R′R″), lengths in c_r (Eq. 33). Maugis–Dugdale "
        "is evaluated at λ = 2(9/(16π))^(1/3) μ = 1.1272 μ (same σ0; `dhfield.core.transition`).\n\n"
        "**Elliptical JKR normalisation.** Its W* carries sinθ_skew(β0) like the DH models, so that Figs. 8–9 "
        "compare like with like; at mild ellipticity W* = −0.75·f·sinθ_skew, where f = W/(−1.5πRΔγ) is the "
        "pull-off in circular-JKR units (f = 0.9853, 0.9439, 0.8609 at R′/R″ = 2, 4, 10) and 1 − f, "
        "1 − sinθ_skew are both O((ln R′/R″)²).\n\n"
        "**β_JKR(pull-off)** (load control): " + ", ".join(f"{b:g} → {x:.4f}" for b, x in zip(BETA0, bj)) +
        ". The JKR-β variant uses it for the shapes and Hertz relations (Eqs. 8, 11, 20) of both ellipses and "
        "keeps sinθ_skew(β0) in Eq. (34) (see `dhfield.analysis.compare`).\n\n"
        "**Not reached (physics, not numerics).** (i) β → β0 at W* = 100 to 1e-3 holds for β0 = 0.99 only: "
        "β − β0 = C/√W* with " + ", ".join(f"β0 = {b:g}: β − β0 = {d:.2e} at W* = 100 (C = {c:.3f})"
                                            for b, (d, c) in beta_hi.items()) +
        "; 1e-3 needs W* ≈ (C/1e-3)². (ii) Whole MD load curves within 1e-4 of JKR/DMT: the deviations are "
        "O(λ⁻²) (load, JKR side; 3.1e-4 at λ = 100), O(λ^1.5) (load, DMT side; 1.7e-3 at λ = 0.01) and "
        "O(√λ) for the DMT-side approach (−(8/3)√(λ/π) = −0.150 at λ = 0.01); 1e-4 is met at λ = 1000 and "
        "0.001 (checks below). Pull-off within 0.1 % is met at λ = 0.01 and 100.\n\n"
        "**Paper statements vs this reproduction** (W*max from the table below):\n\n" + _statements(tab))
    verdict, guide = verdict_lines(tab, jkr_limits())
    return Section(title=TITLE, text=text, checks=checks, figures=figures,
                   tables=["W*max (load control, Eq. 34) per model:\n\n" + _table(tab)], datasets=datasets,
                   verdict=verdict, guide=guide)
