"""Report section: the analytic elliptical double-Hertz model along theta_p = 0 (issue 2).

Reproduces the paper's Figs. 4-7 and 10 (Zini et al. 2018, doi:10.1007/s11249-017-0976-8)
with :mod:`dhfield.models.dh_elliptic`, adds the load-approach curves and the pull-off as a
function of beta0, and checks the analytic core against references that do not
share its code path:

* Eq. (31) at beta0 = 1 against the circular closed form of Greenwood & Johnson
  (1998), v (1+v) (2/(3 pi)) (c-a)^2 (c+2a) (units R = E* = dgamma = 1);
* Eqs. (13b)/(15) (library Carlson form and the printed Legendre form) against
  adaptive quadrature (``scipy.integrate.quad``) of the defining integral Eq. (12b)
  at seeded random points outside the ellipse, with the root l found independently
  by ``scipy.optimize.brentq``;
* the pull-off limits: JKR (W* = -3/4) at mu = 20 and DMT (W* = -1) at mu = 0.05;
* along every computed load curve: dgamma = 1 by the direct quadrature of Eq. (31)
  in :mod:`dhfield.models.dh_elliptic_adhesion` (the solve uses an exchanged-order integral),
  sigma0 = mu (Eq. 24 with Eq. 35), Eq. (36) against the dimensional load Eq. (25)
  and the approach against Eq. (26a);
* the pull-off as a stationary point, against the minimum of a dense scan of W*(a*);
* the pull-off as a smooth, monotone function of beta0 in [0.8, 1].
"""
from __future__ import annotations

import time
from pathlib import Path

import numpy as np

from verification._api import Check, Figure, Section, check_le, save_figure
from verification._style import QUICK_DPI, REPORT_DPI, figsize, legend_below

TITLE = "Analytic elliptical double-Hertz model (θp = 0): Figs. 4–7, 10, load curves and pull-off"

#: Relative tolerance of the closed-form and quadrature comparisons (issue 2: "to 1e-10").
TOL_EXACT = 1e-10
#: |dgamma - 1|, |sigma0/mu - 1| and the Eq. (36)/(25), (26a) consistency along load curves:
#: the Newton solve targets 1e-14; 1e-10 leaves room for the different quadrature of Eq. (31).
TOL_CURVE = 1e-10
#: JKR limit at mu = 20 (issue 2): W* within 0.5 % of -3/4.
TOL_JKR = 5e-3
#: DMT limit at mu = 0.05 (issue 2): W* within 2 % of -1.
TOL_DMT = 2e-2
#: Pull-off against the minimum of a dense scan (step 1e-5 in a*): the scan's own error is
#: ~|W''| h^2/2 ~ 1e-10, the root is found to 1e-13 in a*.
TOL_STATIONARY = 1e-8
#: Smoothness of W*max(beta0): max |second difference| / mean |first difference|.  For a
#: smooth curve this is ~ h |W''/W'| (~0.006 at h = 0.0025); a jump or a kink that changes
#: the slope by more than 5 % over one step fails.
TOL_SMOOTH = 0.05

#: Tabor parameters and ellipticities of the paper's figures.
MU_FIG45 = (0.5, 1.0, 5.0)
BETA_FIG45 = 0.99
BETA_FIG67 = (0.8, 0.9, 0.99)
MU_FIG67 = (0.5, 5.0)
MU_CONTINUITY = (0.5, 1.0, 2.0, 5.0)
QUADRATURE_BETAS = (0.3, 0.8, 0.99, 1.0)
SEED = 20180130

_COLORS = {0.5: "tab:blue", 1.0: "tab:orange", 2.0: "tab:purple", 5.0: "tab:green",
           0.8: "tab:red", 0.9: "tab:olive", 0.99: "tab:blue"}


def _settings(quick):
    if quick:
        return dict(n_curve=160, n_quad=1000, n_beta=41, n_eq31=4, dpi=QUICK_DPI)
    return dict(n_curve=600, n_quad=4000, n_beta=81, n_eq31=16, dpi=REPORT_DPI)


# --------------------------------------------------------------------------- helpers


def _curve_grid(n):
    """a* grid of the figures: dense near 0 (pull-off at small contact), up to W* ~ 3."""
    return np.unique(np.concatenate([np.geomspace(2e-3, 0.3, n // 3), np.linspace(0.3, 3.0, n - n // 3)]))




def _label_beta(b):
    return "DH circular" if b == 1.0 else f"β0 = {b:g}"


def _curve_dataset(curve):
    """netCDF Dataset of a load curve: the library's builder when present, else a local one."""
    try:
        from dhfield.io.curves import load_curve_dataset
    except ImportError:
        load_curve_dataset = None
    if load_curve_dataset is not None:
        return load_curve_dataset(curve, produced_by="verification.sec_analytic")
    import xarray as xr

    from dhfield.io import provenance_attrs

    names = {"a_star": "contact semi-major axis a/c_r (Eq. 32)", "b_star": "contact semi-minor axis b/c_r",
             "c_star": "adhesive semi-major axis c/c_r", "d_star": "adhesive semi-minor axis d/c_r",
             "v": "DH scaling factor v (Eq. 22)", "W_star": "normalised load (Eq. 34)",
             "delta_star": "normalised approach delta R/c_r^2"}
    ds = xr.Dataset({k: ("point", np.asarray(getattr(curve, k)), {"long_name": ln, "units": "1"})
                     for k, ln in names.items()})
    ds.attrs.update(provenance_attrs("Elliptical double-Hertz load curve", mu=curve.mu, beta0=curve.beta0,
                                     ellipticity=curve.ellipticity))
    return ds


# --------------------------------------------------------------------------- checks


def _check_circular_closed_form(rng, curves):
    """Eq. (31) at beta = 1 against v(1+v)(2/(3 pi))(c-a)^2(c+2a)."""
    from dhfield.models.dh_elliptic_adhesion import work_of_adhesion

    n = 1000
    a = 10 ** rng.uniform(-2.5, 0.7, n)
    c = a + 10 ** rng.uniform(-3, 0.8, n) * a
    v = 10 ** rng.uniform(-3, 2, n)
    # plus every state of the solved circular load curves
    circ = [cv for cv in curves if cv.ellipticity == 1.0]
    a = np.concatenate([a] + [cv.a_star for cv in circ])
    c = np.concatenate([c] + [cv.c_star for cv in circ])
    v = np.concatenate([v] + [cv.v for cv in circ])
    dg = work_of_adhesion(a, c, 1.0, v, theta=0.0)  # Eq. (31)
    ref = v * (1 + v) * 2 / (3 * np.pi) * (c - a) ** 2 * (c + 2 * a)  # GJ98 circular DH
    err = np.max(np.abs(dg / ref - 1))
    return check_le(f"Eq. (31) at β0 = 1 vs circular closed form, {len(a)} states (1000 seeded random + "
                    "the solved β0 = 1 curves), max rel. error", err, TOL_EXACT,
                    "Greenwood & Johnson (1998) DH: Δγ = v(1+v)(2/(3π))(c−a)²(c+2a), R = E* = Δγ = 1")


def _eq12b_by_quadrature(x, y, a, b, po):
    """omega_out of Eq. (12b) by adaptive quadrature; l from brentq (independent of the library).

    With w = s^2 the integrand 2 [1 - x^2/(a^2+s^2) - y^2/(b^2+s^2)] / sqrt((a^2+s^2)(b^2+s^2))
    is smooth on [sqrt(l), inf); quad on [sqrt(l), sqrt(l) + 4 max(a, sqrt(l))] and the tail.
    """
    from scipy import integrate, optimize

    def root(l):
        return x * x / (a * a + l) + y * y / (b * b + l) - 1.0

    l = optimize.brentq(root, 0.0, x * x + y * y, xtol=1e-300, rtol=1e-15, maxiter=500)

    def f(s):
        s2 = s * s
        return 2.0 * (1.0 - x * x / (a * a + s2) - y * y / (b * b + s2)) / np.sqrt((a * a + s2) * (b * b + s2))

    s0 = np.sqrt(l)
    mid = s0 + 4.0 * max(a, s0)
    i1 = integrate.quad(f, s0, mid, epsabs=0.0, epsrel=1e-13, limit=500)[0]
    i2 = integrate.quad(f, mid, np.inf, epsabs=0.0, epsrel=1e-13, limit=500)[0]
    return (1.0 / np.pi) * (np.pi * po * a * b / 2.0) * (i1 + i2)  # Eq. (12b) with E* = 1


def _check_displacement_quadrature(rng, n, quick):
    """Eqs. (13b)/(15) vs adaptive quadrature of Eq. (12b), per beta."""
    from dhfield.models import hertz
    from dhfield.core.elliptic import ellipsoid_integrals_legendre

    checks, scatter = [], {}
    label = f"{n} seeded random outside points" + (" (quick mode; the default mode uses 4000)" if quick else "")
    for beta in QUADRATURE_BETAS:
        a = 10 ** rng.uniform(-1, 1, n)
        b = beta * a
        th = rng.uniform(0, 2 * np.pi, n)
        gap = 10 ** rng.uniform(-6, 1, n)  # relative distance outside the ellipse boundary
        r_ab = a * b / np.sqrt((b * np.cos(th)) ** 2 + (a * np.sin(th)) ** 2)  # Eq. (A1)
        x, y = r_ab * (1 + gap) * np.cos(th), r_ab * (1 + gap) * np.sin(th)
        po = hertz.max_pressure(a, beta)  # Eq. (8), R = E* = 1
        ref = np.array([_eq12b_by_quadrature(*args) for args in zip(x, y, a, b, po)])
        lib = hertz.surface_displacement(x, y, a, b, po)  # Eqs. (13b), (15) via Carlson forms
        err = np.abs(lib / ref - 1)
        scatter[beta] = (gap, err, None)
        checks.append(check_le(f"Eqs. (13b)/(15) (library, Carlson form) vs quad of Eq. (12b), β = {beta:g}, "
                               f"{label}, max rel. error", err.max(), TOL_EXACT,
                               "scipy.integrate.quad of Eq. (12b), epsrel 1e-13; l by scipy.optimize.brentq"))
        if beta < 1.0:
            l = hertz.ellipse_root(x, y, a, b)
            i1, i2, i3 = ellipsoid_integrals_legendre(l, a, b)  # Eqs. (B1)-(B3) as printed
            pref = 0.5 * np.pi * po * a * b  # Eqs. (B4)-(B6)
            printed = (pref * i1 - pref * i2 * x * x - pref * i3 * y * y) / np.pi  # Eq. (13b)
            err_p = np.abs(printed / ref - 1)
            scatter[beta] = (gap, err, err_p)
            checks.append(check_le(f"Eqs. (13b)/(15) as printed (Legendre F, E) vs quad of Eq. (12b), "
                                   f"β = {beta:g}, {label}, max rel. error", err_p.max(), TOL_EXACT,
                                   "scipy.integrate.quad of Eq. (12b); printed form undefined (0/0) at β = 1"))
    return checks, scatter


def _eq31_by_quadrature(a, c, beta, v):
    """Eq. (31) by nested adaptive quadrature, independent of :mod:`dhfield.models.dh_elliptic_adhesion`.

    Along theta_p = 0 (y = 0) the root of Eq. (12) is l = x^2 - a^2 exactly, and the
    slope of the Hertz gap is dh_H/dx = x/R' + d(omega)/dx with, from Eq. (12b),
    d(omega)/dx = -(Po_ab a b x/E*) I2(l), I2 of Eq. (B2) by ``quad`` of its
    definition.  dh/dx = (1 + v) dh_H/dx in the annulus (Eq. 27) and
    sigma_ac = v Po_cd sqrt(1 - x^2/c^2) (Eq. 23).  With x = a + (c - a) sin^2 t the
    square-root ends become sin t, cos t and the outer ``quad`` runs over t in [0, pi/2].
    The outer quad's nodes are interior, so the endpoint cancellation in dh/dx never enters.
    """
    from scipy import integrate

    from dhfield.models import hertz

    b = beta * a
    r_major, _ = hertz.principal_radii_from_ellipticity(beta)  # R' with R = 1 (Eqs. 3-5)
    po_ab = hertz.max_pressure(a, beta)  # Eq. (8)
    po_cd = hertz.max_pressure(c, beta)  # Eq. (20)

    def i2(l):  # Eq. (B2), w = s^2
        f = (lambda s: 2.0 / ((a * a + s * s) ** 1.5 * np.sqrt(b * b + s * s)))
        s0 = np.sqrt(l)
        mid = s0 + 4.0 * max(a, s0)
        return (integrate.quad(f, s0, mid, epsabs=0.0, epsrel=1e-13, limit=200)[0]
                + integrate.quad(f, mid, np.inf, epsabs=0.0, epsrel=1e-13, limit=200)[0])

    def integrand(t):
        st, ct = np.sin(t), np.cos(t)
        x = a + (c - a) * st * st
        dh = (1.0 + v) * (x / r_major - po_ab * a * b * x * i2((c - a) * st * st * (x + a)))
        sigma = v * po_cd * np.sqrt((c - a) * ct * ct * (c + x)) / c
        return sigma * dh * 2.0 * (c - a) * st * ct

    # Four fixed panels: a single 21-point Gauss-Kronrod panel can accept a wrong answer with a
    # wrong error estimate (seen at beta = 0.3, mu = 0.05: 3e-11 off with an estimate of 3e-13).
    edges = np.linspace(0.0, np.pi / 2, 5)
    return sum(integrate.quad(integrand, lo, hi, epsabs=0.0, epsrel=1e-13, limit=200)[0]
               for lo, hi in zip(edges[:-1], edges[1:]))


def _check_eq31_quadrature(n_per_curve, quick):
    """dgamma = 1 by the independent nested quadrature at states of the solved load curves."""
    from dhfield.models.dh_elliptic import load_curve

    worst, n = 0.0, 0
    cases = [(mu, b) for mu in (0.05, 0.5, 1.0, 5.0, 20.0) for b in (0.3, 0.8, 0.9, 0.99, 1.0)]
    grid = np.geomspace(0.01, 3.0, n_per_curve)
    for mu, beta0 in cases:
        cv = load_curve(mu=mu, beta0=beta0, a_star=grid)
        for a, c, v in zip(cv.a_star, cv.c_star, cv.v):
            worst = max(worst, abs(_eq31_by_quadrature(a, c, cv.ellipticity, v) - 1.0))
            n += 1
    label = f"{n} states: μ ∈ {{0.05, 0.5, 1, 5, 20}} × β0 ∈ {{0.3, 0.8, 0.9, 0.99, 1}}, a* from 0.01 to 3"
    if quick:
        label += " (quick mode: fewer states)"
    return check_le(f"Δγ = 1 on the solved load curves by nested adaptive quadrature of Eq. (31) "
                    f"({label}), max |Δγ − 1|", worst, TOL_CURVE,
                    "scipy.integrate.quad of Eq. (31) with dh/dx from Eq. (12b) differentiated and "
                    "I2 (Eq. B2) by quad; l = x² − a² on θp = 0")


def _check_limits():
    from dhfield.models.dh_elliptic import pull_off

    po = pull_off(mu=np.array([20.0, 0.05]), beta0=1.0)
    jkr = abs(po.W_star[0] / -0.75 - 1)
    dmt = abs(po.W_star[1] / -1.0 - 1)
    return [
        check_le(f"pull-off → JKR at μ = 20, β0 = 1: |W*/(−3/4) − 1| (W* = {po.W_star[0]:.6f})", jkr, TOL_JKR,
                 "JKR (1971) limit W* = −3/4 (μ → ∞), required within 0.5 %"),
        check_le(f"pull-off → DMT at μ = 0.05, β0 = 1: |W*/(−1) − 1| (W* = {po.W_star[1]:.6f})", dmt, TOL_DMT,
                 "DMT (1975) limit W* = −1 (μ → 0), required within 2 %"),
    ], po


def _check_curves(curves):
    """dgamma = 1, sigma0 = mu, Eq. (36) = Eq. (25), delta = Eq. (26a) along every load curve."""
    from dhfield.models import dh_elliptic_fields as double_hertz
    from dhfield.models.dh_elliptic_adhesion import work_of_adhesion
    from dhfield.core.geometry import sin_skew_angle

    e_dg = e_s0 = e_w = e_d = 0.0
    n = 0
    for cv in curves:
        a, c, beta, v = cv.a_star, cv.c_star, cv.ellipticity, cv.v
        dg = work_of_adhesion(a, c, beta, v, theta=0.0)  # Eq. (31), direct graded quadrature
        s0 = double_hertz.max_adhesive_stress(a, c, beta, v)  # Eq. (24)
        w25 = double_hertz.load(a, c, beta, v) * sin_skew_angle(cv.beta0) / (2 * np.pi)  # Eqs. (25), (34)
        d26 = double_hertz.approach(a, c, beta, v)  # Eq. (26a)
        e_dg = max(e_dg, np.max(np.abs(dg - 1)))
        e_s0 = max(e_s0, np.max(np.abs(s0 / cv.mu - 1)))
        e_w = max(e_w, np.max(np.abs(w25 - cv.W_star)) / np.max(np.abs(cv.W_star)))
        e_d = max(e_d, np.max(np.abs(d26 - cv.delta_star)) / np.max(np.abs(cv.delta_star)))
        n += a.size
    what = f"{len(curves)} load curves, {n} states"
    return [
        check_le(f"Δγ = 1 along the load curves: max |Δγ − 1| by direct quadrature of Eq. (31) ({what})", e_dg,
                 TOL_CURVE, "Eq. (31) with Δγ = 1 (Eq. 33 units); dhfield.models.dh_elliptic_adhesion.work_of_adhesion, "
                 "independent of the solve's exchanged-order integral"),
        check_le(f"σ0 = μ along the load curves: max |σ0/μ − 1| from Eq. (24) ({what})", e_s0, TOL_CURVE,
                 "Eqs. (24), (35): σ0 = v Po_cd (1 − a²/c²)^½ = μ in Eq. (33) units"),
        check_le(f"Eq. (36) W* vs dimensional Eq. (25) × sinθ_skew/(2πRΔγ): max abs. error / max |W*| ({what})",
                 e_w, TOL_CURVE, "Eqs. (25), (34), (36); dhfield.models.dh_elliptic_fields.load"),
        check_le(f"δ* vs Eq. (26a) (1+v)δ_ab − vδ_cd: max abs. error / max |δ*| ({what})", e_d, TOL_CURVE,
                 "Eqs. (14a), (26a); dhfield.models.dh_elliptic_fields.approach"),
    ]


def _check_stationary(mu_beta):
    """Load-controlled pull-off vs the minimum of a dense scan of W*(a*) around it."""
    from dhfield.models.dh_elliptic import load_curve, pull_off

    worst, rows = 0.0, []
    for mu, beta0 in mu_beta:
        po = pull_off(mu=mu, beta0=beta0)
        if po.at_zero_contact:
            continue
        a0 = float(po.a_star)
        # 2000 points: the grid does not contain a0 itself, so the scan is independent of the root
        grid = a0 + 0.01 * np.linspace(-1.0, 1.0, 2000)
        grid = grid[grid > 0]
        w = load_curve(mu=mu, beta0=beta0, a_star=grid).W_star
        dev = abs(float(w.min()) - float(po.W_star))
        worst = max(worst, dev)
        rows.append((mu, beta0, dev))
    return check_le(f"load-controlled pull-off vs min of a dense W*(a*) scan (step 1e-5, a* ± 0.01), "
                    f"{len(rows)} cases "
                    f"(μ, β0 of Figs. 4–7), max |W*min,scan − W*max|", worst, TOL_STATIONARY,
                    "brute-force minimum of Eq. (36) along the solved curve"), rows


def _continuity(n_beta):
    """Pull-off vs beta0 in [0.8, 1], both controls, and its monotonicity/smoothness checks."""
    from dhfield.models.dh_elliptic import pull_off

    betas = np.linspace(0.8, 1.0, n_beta)
    mus = np.asarray(MU_CONTINUITY)
    out, checks = {}, []
    for control in ("load", "displacement"):
        po = pull_off(mu=mus[:, None], beta0=betas[None, :], control=control)
        out[control] = po
        w = np.asarray(po.W_star)
        d = np.diff(w, axis=1)
        d2 = np.diff(w, 2, axis=1)
        # monotone: every step has the sign of the overall change
        sign = np.sign(w[:, -1] - w[:, 0])[:, None]
        bad = int(np.sum(d * sign <= 0))
        smooth = float(np.max(np.max(np.abs(d2), axis=1) / np.mean(np.abs(d), axis=1)))
        checks.append(check_le(f"W*max({control} control) monotone in β0 ∈ [0.8, 1] for μ ∈ "
                               f"{{{', '.join(f'{m:g}' for m in mus)}}}: number of non-monotone steps "
                               f"({n_beta} values of β0)", bad, 0,
                               "requirement: pull-off changes monotonically as β0 goes from 0.8 to 1 (Fig. 9a)"))
        checks.append(check_le(f"W*max({control} control) smooth in β0 ∈ [0.8, 1]: max |Δ²W*| / mean |ΔW*| "
                               f"(step {betas[1] - betas[0]:.4g})", smooth, TOL_SMOOTH,
                               "requirement: no jump or kink; a smooth curve gives ≈ h|W''/W'| ≈ 0.006"))
    return betas, mus, out, checks


# --------------------------------------------------------------------------- figures


def _fig_axes_vs_load(curves_by, pulloffs, outdir, dpi, which, fname, caption, jkr=None):
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=figsize(1))
    for (mu, beta0), cv in curves_by.items():
        if beta0 not in (BETA_FIG45, 1.0) or mu not in MU_FIG45:
            continue
        col = _COLORS[mu]
        ls = "-" if beta0 == BETA_FIG45 else "--"
        y = cv.a_star if which == "a" else cv.c_star
        ax.plot(cv.W_star, y, ls, color=col, lw=1.6 if ls == "-" else 1.2,
                label=f"{_label_beta(beta0)}, μ = {mu:g}")
        po = pulloffs[(mu, beta0)]
        ax.plot(po.W_star, po.a_star if which == "a" else po.c_star, "o" if ls == "-" else "s",
                color=col, mfc="none" if ls == "--" else col, ms=5)
    if jkr is not None and which == "a":
        ax.plot(jkr[0], jkr[1], ":", color="k", lw=1.8, label="JKR circular", zorder=5)
    ax.set_xlabel("W* = W sinθ_skew/(2πRΔγ) (Eq. 34)")
    ax.set_ylabel("contact semi-axis a*" if which == "a" else "adhesive semi-axis c*")
    ax.set_xlim(-1.2, 2.6)
    ax.set_ylim(0, 3.1 if which == "a" else 4.6)
    ax.grid(alpha=0.3)
    ax.set_title(("Fig. 4: a* vs W*" if which == "a" else "Fig. 5: c* vs W*") + f", β0 = {BETA_FIG45}")
    legend_below(fig, ncol=2)
    return Figure(save_figure(fig, outdir / fname, dpi), caption)


def _fig_beta_family(curves_by, pulloffs, mu, outdir, dpi, fname, caption):
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=figsize(1))
    for beta0 in BETA_FIG67:
        cv = curves_by[(mu, beta0)]
        col = _COLORS[beta0]
        ax.plot(cv.W_star, cv.a_star, "-", color=col, lw=1.6, label=f"a*, β0 = {beta0:g}")
        ax.plot(cv.W_star, cv.c_star, "--", color=col, lw=1.3, label=f"c*, β0 = {beta0:g}")
        po = pulloffs[(mu, beta0)]
        ax.plot([po.W_star] * 2, [po.a_star, po.c_star], "o", color=col, ms=4)
    ax.set_xlabel("W* (Eq. 34)")
    ax.set_ylabel("semi-major axes a*, c*")
    ax.set_xlim(-1.2, 2.6)
    ax.set_ylim(0, 4.6 if mu < 1 else 2.6)
    ax.grid(alpha=0.3)
    ax.legend(ncol=2 if mu < 1 else 1, loc="lower right")  # the curves turn at W* < 0: the lower right is free
    ax.set_title(f"Fig. {6 if mu < 1 else 7}: a*, c* vs W* at μ = {mu:g}")
    fig.tight_layout()
    return Figure(save_figure(fig, outdir / fname, dpi), caption)


def _fig_load_approach(curves_by, outdir, dpi, fname, caption):
    import matplotlib.pyplot as plt

    from dhfield.models.dh_elliptic import pull_off

    fig, axes = plt.subplots(1, 2, figsize=figsize(2, 0.4))
    ax = axes[0]
    for mu in MU_FIG45:
        for beta0 in (BETA_FIG45, 1.0):
            cv = curves_by[(mu, beta0)]
            ls = "-" if beta0 == BETA_FIG45 else "--"
            ax.plot(cv.delta_star, cv.W_star, ls, color=_COLORS[mu], lw=1.5 if ls == "-" else 1.1,
                    label=f"{_label_beta(beta0)}: μ = {mu:g}")
    ax.set_title(f"β0 = {BETA_FIG45} and DH circular")
    ax = axes[1]
    for mu, ls in zip(MU_FIG67, ("-", "--")):
        for beta0 in BETA_FIG67:
            cv = curves_by[(mu, beta0)]
            ax.plot(cv.delta_star, cv.W_star, ls, color=_COLORS[beta0], lw=1.4, label=f"μ = {mu:g}, β0 = {beta0:g}")
    ax.set_title("β0 = 0.8, 0.9, 0.99 at μ = 0.5 and 5")
    for ax in axes:
        ax.set_xlabel("approach δ* = δR/c_r² (Eq. 26a)")
        ax.set_ylabel("W* (Eq. 36)")
        ax.set_xlim(-3.0, 4.0)
        ax.set_ylim(-1.2, 3.0)
        ax.axhline(0, color="0.6", lw=0.6)
        ax.grid(alpha=0.3)
        ax.legend()
    # displacement-controlled pull-off points (minimum of delta*) on the right panel
    for mu in MU_FIG67:
        p = pull_off(mu=mu, beta0=np.asarray(BETA_FIG67), control="displacement")
        axes[1].plot(p.delta_star, p.W_star, "v", color="k", ms=4)
    fig.tight_layout()
    return Figure(save_figure(fig, outdir / fname, dpi), caption)


def _fig_continuity(betas, mus, po, outdir, dpi, fname, caption):
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, 2, figsize=figsize(2, 0.4))
    for i, mu in enumerate(mus):
        col = _COLORS[float(mu)]
        axes[0].plot(betas, po["load"].W_star[i], "-", color=col, label=f"load control, μ = {mu:g}")
        axes[0].plot(betas, po["displacement"].W_star[i], "--", color=col, label=f"displacement control, μ = {mu:g}")
        axes[1].plot(betas, po["load"].a_star[i], "-", color=col, label=f"a*, μ = {mu:g}")
        axes[1].plot(betas, po["load"].c_star[i], ":", color=col, label=f"c*, μ = {mu:g}")
    axes[0].set_ylabel("pull-off force W*max (Eq. 34)")
    axes[1].set_ylabel("a*, c* at pull-off (load control)")
    for ax in axes:
        ax.set_xlabel("initial ellipticity β0")
        ax.grid(alpha=0.3)
    from matplotlib.lines import Line2D

    handles = [Line2D([], [], color=_COLORS[float(mu)], label=f"μ = {mu:g}") for mu in mus]
    handles += [Line2D([], [], color="k", ls="-", label="load control (W*, a*)"),
                Line2D([], [], color="k", ls="--", label="displacement control (W*)"),
                Line2D([], [], color="k", ls=":", label="c* (load control)")]
    legend_below(fig, handles, [h.get_label() for h in handles], ncol=4)
    return Figure(save_figure(fig, outdir / fname, dpi), caption)


def _fig_quadrature(scatter, outdir, dpi, fname, caption):
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=figsize(1))
    floor = 1e-18
    for beta, (gap, err, err_p) in scatter.items():
        gap, err = gap[:1000], err[:1000]  # every point is checked; 1000 per series are drawn
        err_p = None if err_p is None else err_p[:1000]
        # thousands of markers: rasterized inside the SVG (the axes, labels and legend stay vector)
        ax.loglog(gap, np.maximum(err, floor), ".", ms=2.5, label=f"Carlson, β = {beta:g}", rasterized=True)
        if err_p is not None:
            ax.loglog(gap, np.maximum(err_p, floor), "x", ms=2.5, alpha=0.5, label=f"Legendre, β = {beta:g}",
                      rasterized=True)
    ax.axhline(TOL_EXACT, color="r", lw=1, label="tolerance 1e-10")
    ax.set_xlabel("distance outside the ellipse, r/r_ab − 1")
    ax.set_ylabel("|Eq. (12b)/quadrature − 1|")
    ax.set_ylim(floor / 2, 1e-8)
    ax.grid(alpha=0.3)
    legend_below(fig, ncol=2)
    return Figure(save_figure(fig, outdir / fname, dpi), caption)


def _fig3_state(mu, beta0):
    """(a, c, beta, v) of the load-controlled pull-off state used for Fig. 3."""
    from dhfield.models.dh_elliptic import pull_off

    po = pull_off(mu=mu, beta0=beta0)
    return float(po.a_star), float(po.c_star), float(po.ellipticity), float(po.v)


def _fig_pressure_displacement(outdir, dpi, fname, mu=1.0, beta0=0.99):
    """Fig. 3: pressures (Eqs. 7, 16, 22) and displacements/gap (Eqs. 13, 21, 26, 27) along theta_p = 0."""
    import matplotlib.pyplot as plt

    from dhfield.models import dh_elliptic_fields as double_hertz, hertz

    fig, axes = plt.subplots(1, 2, figsize=figsize(2, 0.4))
    for b0, ls in ((beta0, "-"), (1.0, "--")):
        a, c, beta, v = _fig3_state(mu, b0)
        x = np.linspace(0.0, 1.6 * c, 801)
        y = np.zeros_like(x)
        po_ab = hertz.max_pressure(a, beta)  # Eq. (8)
        po_cd = hertz.max_pressure(c, beta)  # Eq. (20)
        h_ab = hertz.pressure(x, y, a, beta * a, po_ab)  # Eq. (7)
        h_cd = hertz.pressure(x, y, c, beta * c, po_cd)  # Eq. (16)
        p = double_hertz.pressure(x, y, a, c, beta, v)  # Eq. (22)
        first = b0 < 1  # one legend entry per colour; the line style says β0 (proxies below)
        ax = axes[0]
        ax.plot(x, h_ab / po_ab, ls, color="tab:blue", lw=1.1, label="H_ab/Po_ab" if first else None)
        ax.plot(x, v * (h_cd - h_ab) / po_ab, ls, color="tab:orange", lw=1.1,
                label="v(H_cd − H_ab)/Po_ab" if first else None)
        ax.plot(x, p / po_ab, ls, color="k", lw=1.8, label="total P/Po_ab (Eq. 22)" if first else None)
        w = double_hertz.surface_displacement(x, y, a, c, beta, v)  # Eq. (26)
        h = double_hertz.gap(x, y, a, c, beta, v)  # Eq. (27)
        ax = axes[1]
        ax.plot(x, w, ls, color="tab:green", lw=1.4, label="ω (Eq. 26)" if first else None)
        ax.plot(x, h, ls, color="tab:red", lw=1.4, label="gap h (Eq. 27)" if first else None)
        for axx in axes:
            axx.axvline(a, color="0.5", lw=0.6, ls=ls)
            axx.axvline(c, color="0.75", lw=0.6, ls=ls)
    axes[0].set_ylabel("normalised pressure P/Po_ab")
    axes[0].set_title(f"Fig. 3a: pressures at pull-off, μ = {mu:g}")
    axes[1].set_ylabel("ω*, h* (units c_r²/R)")
    axes[1].set_title("Fig. 3b: displacement and gap")
    for ax in axes:
        ax.set_xlabel("x/c_r along θp = 0 (grey: a*, c*)")
        ax.grid(alpha=0.3)
    from matplotlib.lines import Line2D

    handles = [h for ax in axes for h in ax.get_legend_handles_labels()[0]]
    handles += [Line2D([], [], color="0.3", ls="-", label=f"β0 = {beta0:g}"),
                Line2D([], [], color="0.3", ls="--", label="DH circular (β0 = 1)")]
    legend_below(fig, handles, [h.get_label() for h in handles], ncol=4)
    return save_figure(fig, outdir / fname, dpi)


def _check_gap(rng, n):
    """Eq. (27): h = 0 inside the contact ellipse and h >= 0 outside, at the Fig. 3 states."""
    from dhfield.models import dh_elliptic_fields as double_hertz

    worst_in, worst_out = 0.0, np.inf
    for b0 in (0.8, 0.99, 1.0):
        a, c, beta, v = _fig3_state(1.0, b0)
        r = np.sqrt(rng.uniform(0, 1, n))
        t = rng.uniform(0, 2 * np.pi, n)
        h_in = double_hertz.gap(a * r * np.cos(t), beta * a * r * np.sin(t), a, c, beta, v)
        delta = abs(double_hertz.approach(a, c, beta, v))
        worst_in = max(worst_in, np.max(np.abs(h_in)) / delta)
        rr = 1 + 10 ** rng.uniform(-6, 0.5, n)
        h_out = double_hertz.gap(a * rr * np.cos(t), beta * a * rr * np.sin(t), a, c, beta, v)
        worst_out = min(worst_out, np.min(h_out))
    return [
        check_le(f"Eq. (27): gap vanishes inside the contact ellipse, max |h|/|δ| over {3 * n} random points "
                 "(μ = 1 pull-off states, β0 ∈ {0.8, 0.99, 1})", worst_in, 1e-12,
                 "contact condition: the DH pressure Eq. (22) is geometry-consistent (h = 0 for r ≤ r_ab); "
                 "1e-12 = round-off of δ ~ 1"),
        Check(f"Eq. (27): no interpenetration outside the contact ellipse, min h over {3 * n} random points",
              float(worst_out), 0.0, bool(worst_out > 0.0), "h > 0 for r > r_ab (annulus identity h = (1+v) h_H)",
              ">"),
    ]


def _jkr_elliptic_contacts(w_star, beta0):
    """Elliptical-JKR contact semi-axes (Johnson & Greenwood 2005) at the loads ``w_star``.

    Loads below the elliptical-JKR pull-off are replaced by that pull-off, and the
    last state is always the JKR pull-off.  Raises ImportError when
    :mod:`dhfield.models.jkr_elliptic` does not exist.

    Returns
    -------
    a_star, b_star, w_used : ndarray
    """
    from dhfield.models import jkr_elliptic
    from dhfield.core.geometry import sin_skew_angle

    sn = sin_skew_angle(beta0)
    po = jkr_elliptic.pull_off(1.0, 1.0, 1.0, beta0=beta0)  # R = E* = dgamma = 1: lengths are a*
    grid = np.linspace(float(po.semi_major), 8.0, 800)  # stable branch: W* increases with a*
    lc = jkr_elliptic.load_curve(grid, 1.0, 1.0, 1.0, beta0=beta0)
    w_grid = np.asarray(lc.force) * sn / (2 * np.pi)  # Eq. (34)
    w = np.maximum(np.asarray(w_star, float), w_grid[0])
    w[-1] = w_grid[0]
    a = np.interp(w, w_grid, grid)
    b = np.interp(w, w_grid, np.asarray(lc.semi_minor))
    return a, b, w


def _fig_evolution(outdir, dpi, fname, n_states=5):
    """Fig. 10: contact and adhesive ellipses from loading (W* = 1) to load-controlled pull-off."""
    import matplotlib.pyplot as plt

    from dhfield.models.dh_elliptic import load_curve, pull_off

    cases = [(5.0, 0.8), (5.0, 0.9), (0.5, 0.8)]
    fig, axes = plt.subplots(1, len(cases), figsize=figsize(2, 0.34), layout="constrained")
    jkr_note = ""
    cmap = plt.get_cmap("viridis")
    states = []
    for mu, beta0 in cases:
        po = pull_off(mu=mu, beta0=beta0)
        grid = np.linspace(max(float(po.a_star), 1e-3), 6.0, 600)
        cv = load_curve(mu=mu, beta0=beta0, a_star=grid)
        # states evenly spaced in W* from 1 to the pull-off, on the stable branch (W* rises with a* there)
        w_states = np.linspace(1.0, float(po.W_star), n_states)
        a_states = np.interp(w_states, cv.W_star, grid)
        a_states[-1] = max(float(po.a_star), 1e-3)
        states.append(load_curve(mu=mu, beta0=beta0, a_star=a_states))
    # one colour scale for the three panels: the colour is the state's W*, the same quantity in each
    norm = plt.Normalize(min(float(np.min(st.W_star)) for st in states), max(float(np.max(st.W_star))
                                                                            for st in states))
    for ax, (mu, beta0), st in zip(axes, cases, states):
        t = np.linspace(0, 2 * np.pi, 361)
        for k in range(n_states):
            col = cmap(norm(float(st.W_star[k])))
            lab = "pull-off" if k == n_states - 1 else ("initial" if k == 0 else None)
            ax.plot(st.a_star[k] * np.cos(t), st.b_star[k] * np.sin(t), "-", color=col, lw=1.5,
                    label=f"contact ellipse ({lab})" if lab else None)
            ax.plot(st.c_star[k] * np.cos(t), st.d_star[k] * np.sin(t), "--", color=col, lw=1.1,
                    label=f"adhesive ellipse ({lab})" if lab else None)
        jkr_line = ""
        if mu >= 5.0:  # the JKR domain, as in the paper's Fig. 10
            try:
                ja, jb, jw = _jkr_elliptic_contacts(st.W_star, beta0)
                for k in range(n_states):
                    ax.plot(ja[k] * np.cos(t), jb[k] * np.sin(t), ":", color="r", lw=1.1,
                            label="elliptical JKR contact (same W*)" if k == 0 else None)
                jkr_line = f"\nJKR: W* = {jw[-1]:.3f}, b/a = {jb[-1] / ja[-1]:.3f}".replace("-", "−")
            except Exception as exc:  # noqa: BLE001 - optional overlay
                jkr_note = f"{type(exc).__name__}: {exc}"
        ax.set_aspect("equal")
        ax.set_title(f"μ = {mu:g}, β0 = {beta0:g}")
        ax.set_xlabel("x/c_r (θp = 0)" + jkr_line)  # under the panel
        ax.grid(alpha=0.3)
    sm = plt.cm.ScalarMappable(cmap=cmap, norm=norm)
    fig.colorbar(sm, ax=list(axes), shrink=0.9, pad=0.02, label="W* of the state (Eq. 34)")
    axes[0].set_ylabel("y/c_r")
    handles, labels = axes[0].get_legend_handles_labels()
    legend_below(fig, handles, labels, ncol=3)
    return save_figure(fig, outdir / fname, dpi), jkr_note


# --------------------------------------------------------------------------- the section


def run(outdir: Path, quick: bool, progress) -> Section:
    """Build the analytic-model section (see module docstring).

    Parameters
    ----------
    outdir : Path
        Directory for this section's PNG figures and netCDF files.
    quick : bool
        Small grids and fewer quadrature points (a few seconds).
    progress : callable
        ``progress(message)`` for long steps.

    Returns
    -------
    Section
    """
    from dhfield.io import write_netcdf
    from dhfield.models.dh_elliptic import load_curve, pull_off

    outdir = Path(outdir)
    outdir.mkdir(parents=True, exist_ok=True)
    cfg = _settings(quick)
    rng = np.random.default_rng(SEED)
    checks, figures, datasets, tables = [], [], [], []

    # ---- load curves of Figs. 4-7 and their pull-off points
    cases = sorted({(mu, BETA_FIG45) for mu in MU_FIG45} | {(mu, 1.0) for mu in MU_FIG45}
                   | {(mu, b) for mu in MU_FIG67 for b in BETA_FIG67})
    grid = _curve_grid(cfg["n_curve"])
    curves_by, pulloffs, pulloffs_d = {}, {}, {}
    for mu, beta0 in cases:
        curves_by[(mu, beta0)] = load_curve(mu=mu, beta0=beta0, a_star=grid)
        pulloffs[(mu, beta0)] = pull_off(mu=mu, beta0=beta0, control="load")
        pulloffs_d[(mu, beta0)] = pull_off(mu=mu, beta0=beta0, control="displacement")
    progress(f"{len(cases)} load curves of {grid.size} points and their pull-off points")
    for (mu, beta0), cv in curves_by.items():
        p = outdir / f"load_curve_mu{mu:g}_beta0{beta0:g}.nc"
        ds = _curve_dataset(cv)
        po, pd = pulloffs[(mu, beta0)], pulloffs_d[(mu, beta0)]
        ds.attrs.update({"pull_off_W_star_load_control": float(po.W_star),
                         "pull_off_a_star_load_control": float(po.a_star),
                         "pull_off_W_star_displacement_control": float(pd.W_star),
                         "pull_off_a_star_displacement_control": float(pd.a_star)})
        datasets.append(write_netcdf(ds, p))
    progress(f"wrote {len(datasets)} netCDF load curves")

    # ---- checks
    closed_form = _check_circular_closed_form(rng, list(curves_by.values()))
    checks.append(closed_form)
    limit_checks, po_limits = _check_limits()
    checks += limit_checks
    checks += _check_curves(list(curves_by.values()))
    stat_check, _ = _check_stationary(cases)
    checks.append(_check_eq31_quadrature(cfg["n_eq31"], quick))
    checks.append(stat_check)
    progress("closed form, limits and load-curve consistency checked")
    tq = time.perf_counter()
    quad_checks, scatter = _check_displacement_quadrature(rng, cfg["n_quad"], quick)
    checks += quad_checks
    progress(f"Eqs. (13b)/(15) vs quadrature at {cfg['n_quad']} points × {len(QUADRATURE_BETAS)} β "
             f"({time.perf_counter() - tq:.1f} s)")
    betas, mus, po_beta, cont_checks = _continuity(cfg["n_beta"])
    checks += cont_checks
    progress(f"pull-off vs β0 at {betas.size} values × {mus.size} μ × 2 controls")

    # pull-off vs beta0 dataset
    try:
        from dhfield.io.curves import pull_off_dataset
        res = {}
        for control, p in po_beta.items():
            suffix = "" if control == "load" else "_displacement_control"
            for k in ("W_star", "a_star", "c_star", "v", "delta_star"):
                res[k + suffix] = np.asarray(getattr(p, k))
        ds = pull_off_dataset(res, beta0=betas, mu=mus, produced_by="verification.sec_analytic",
                              note="variables without suffix: load control")
    except ImportError:
        import xarray as xr

        from dhfield.io import provenance_attrs
        ds = xr.Dataset({f"W_star_{c}": (("mu", "beta0"), np.asarray(p.W_star),
                                         {"long_name": f"pull-off load W* ({c} control), Eq. (34)", "units": "1"})
                         for c, p in po_beta.items()},
                        coords={"mu": ("mu", mus, {"long_name": "Tabor parameter (Eq. 35)", "units": "1"}),
                                "beta0": ("beta0", betas, {"long_name": "initial ellipticity", "units": "1"})})
        ds.attrs.update(provenance_attrs("Pull-off vs beta0"))
    datasets.append(write_netcdf(ds, outdir / "pull_off_vs_beta0.nc"))

    # ---- figures
    jkr_curve = None
    try:
        from dhfield.models import jkr
        a_j = np.linspace(1e-3, 3.0, 300)
        lc = jkr.load_curve(a_j, 1.0, 1.0, 1.0)  # R = E* = dgamma = 1: W* = W/(2 pi)
        jkr_curve = (np.asarray(lc.force) / (2 * np.pi), a_j)
    except Exception:  # noqa: BLE001 - optional overlay
        jkr_curve = None
    figures.append(_fig_axes_vs_load(
        curves_by, pulloffs, outdir, cfg["dpi"], "a", "fig04_contact_axis_vs_load.png",
        "Reproduces paper Fig. 4: contact semi-major axis a* against W* (Eq. 34) for μ ∈ {0.5, 1, 5} at "
        "β0 = 0.99 (solid) and the circular DH model β0 = 1 (dashed), from the solve of Eqs. (24), (31), (35) "
        "and the load Eq. (36). Markers: load-controlled pull-off." +
        (" Dotted: JKR circular (dhfield.models.jkr), close to μ = 5 as in the paper." if jkr_curve is not None
                                                        else ""), jkr=jkr_curve))
    figures.append(_fig_axes_vs_load(
        curves_by, pulloffs, outdir, cfg["dpi"], "c", "fig05_adhesive_axis_vs_load.png",
        "Reproduces paper Fig. 5: adhesive semi-major axis c* against W* (Eq. 34) for μ ∈ {0.5, 1, 5} at "
        "β0 = 0.99 (solid) and DH circular (dashed); c* from Eqs. (24), (31), (35). Markers: load-controlled "
        "pull-off.", jkr=None))
    figures.append(_fig_beta_family(
        curves_by, pulloffs, 0.5, outdir, cfg["dpi"], "fig06_axes_vs_load_mu0.5.png",
        "Reproduces paper Fig. 6: a* (solid) and c* (dashed) against W* for β0 ∈ {0.8, 0.9, 0.99} at μ = 0.5 "
        "(Eqs. 31, 35, 36). The adhesive zone c* − a* widens as β0 decreases. Dots: load-controlled pull-off."))
    figures.append(_fig_beta_family(
        curves_by, pulloffs, 5.0, outdir, cfg["dpi"], "fig07_axes_vs_load_mu5.png",
        "Reproduces paper Fig. 7: a* (solid) and c* (dashed) against W* for β0 ∈ {0.8, 0.9, 0.99} at μ = 5 "
        "(Eqs. 31, 35, 36): a narrow adhesive zone, c* ≈ a*. Dots: load-controlled pull-off."))
    figures.append(_fig_load_approach(
        curves_by, outdir, cfg["dpi"], "load_approach.png",
        "Load–approach curves W* (Eq. 36) against δ* = [(1+v)δ_ab − vδ_cd] R/c_r² (Eqs. 14a, 26a) for the "
        "cases of Figs. 4–7 (not a figure of the paper). Triangles: displacement-controlled pull-off "
        "(minimum of δ*)."))
    figures.append(_fig_continuity(
        betas, mus, po_beta, outdir, cfg["dpi"], "pull_off_vs_beta0.png",
        "Pull-off force W*max (Eq. 34) and the semi-axes at pull-off against β0 ∈ [0.8, 1] for "
        "μ ∈ {0.5, 1, 2, 5}, load control (solid) and displacement control (dashed); the β0 = 0.8, 0.9, 0.99 "
        "points are the values of paper Fig. 9a. Checked smooth and monotone (table of checks)."))
    figures.insert(0, Figure(_fig_pressure_displacement(outdir, cfg["dpi"], "fig03_pressure_displacement.png"),
        "Reproduces paper Fig. 3: (a) the Hertz pressure of the contact ellipse H_ab (Eq. 7), the scaled "
        "difference v(H_cd − H_ab) (Eqs. 16, 22) and the total pressure (Eq. 22), normalised by Po_ab (Eq. 8); "
        "(b) the total surface displacement (Eq. 26) and the gap (Eq. 27) along θp = 0, at the load-controlled "
        "pull-off state for μ = 1, β0 = 0.99 (solid) and the circular DH model (dashed). The paper gives no "
        "state for its Fig. 3; the pull-off state is our choice."))
    checks += _check_gap(rng, 2000 if quick else 20000)
    fig10, jkr_note = _fig_evolution(outdir, cfg["dpi"], "fig10_ellipse_evolution.png")
    cap10 = ("Reproduces paper Fig. 10: evolution of the contact ellipse (solid, semi-axes a*, b* = β0 a*, "
             "Eqs. 9, 17) and the adhesive ellipse (dashed, c*, d* = β0 c*, Eqs. 17, 19) from W* = 1 to the "
             "load-controlled pull-off, five states evenly spaced in W*; the colour gives W* (Eq. 34) of each "
             "state on one scale for the three panels, from W* = 1 (yellow) to the pull-off (dark).")
    if jkr_note:
        cap10 += (" The elliptical-JKR contact is omitted: dhfield.models.jkr_elliptic is not available "
                  f"({jkr_note}).")
    else:
        cap10 += (" Red dotted (μ = 5 panels, the JKR domain): the elliptical-JKR contact of Johnson & Greenwood "
                  "(2005) (dhfield.models.jkr_elliptic) at the same loads, the innermost at its own pull-off: it grows "
                  "rounder towards pull-off (b/a rises from β0), whereas the DH ellipses keep β0 (Eqs. 17–19).")
    figures.append(Figure(fig10, cap10))
    figures.append(_fig_quadrature(
        scatter, outdir, cfg["dpi"], "displacement_vs_quadrature.png",
        "Relative error of the outside surface displacement, Eqs. (13b)/(15) (library Carlson form and the "
        "printed Legendre form, Eqs. B1–B6), against adaptive quadrature of Eq. (12b), for β ∈ "
        "{0.3, 0.8, 0.99, 1} at seeded random points (up to 1000 per series drawn; all are checked); the red "
        "line is the 1e-10 tolerance. Zero errors are drawn at 1e-18."))
    progress(f"{len(figures)} figures")

    # ---- tables
    rows = ["| μ | β0 | W*max (load) | a* | c* | v | W*max (displ.) | a* (displ.) | at zero contact (displ.) |",
            "|---:|---:|---:|---:|---:|---:|---:|---:|---|"]
    for (mu, beta0) in cases:
        p, d = pulloffs[(mu, beta0)], pulloffs_d[(mu, beta0)]
        rows.append(f"| {mu:g} | {beta0:g} | {float(p.W_star):.6f} | {float(p.a_star):.5f} | {float(p.c_star):.5f} "
                    f"| {float(p.v):.5g} | {float(d.W_star):.6f} | {float(d.a_star):.5f} | "
                    f"{'yes' if bool(d.at_zero_contact) else 'no'} |")
    tables.append("**Pull-off points of the load curves** (nondimensional, Eqs. 32–36; `dhfield.models.dh_elliptic.pull_off`)."
                  "\n\n" + "\n".join(rows))

    n_quad = cfg["n_quad"]
    text = f"""
The analytic model of the paper along the major axis θp = 0: for each contact size a* the adhesive
semi-axis c* and the factor v solve Eq. (24) with σ0 = μ (Eq. 35) and Eq. (31) with Δγ = 1
(`dhfield.models.dh_elliptic.load_curve`); the load follows from Eq. (36) and the approach from Eq. (26a). Both
ellipses share the ellipticity β0 (Eqs. 9, 17, 19). Units: R = E* = Δγ = 1 (Eqs. 32–35).

What this section shows:

- **Fig. 3**: the DH pressure as the difference of two Hertz fields, its displacement and gap along θp = 0,
  with the contact condition (h = 0 inside the contact) and h > 0 outside checked over the surface.
- **Figs. 4–7** of the paper, recomputed: at β0 = 0.99 the curves lie on the circular DH curves (β0 = 1),
  as the paper states; at μ = 0.5 the adhesive zone widens markedly as β0 decreases (Fig. 6), at μ = 5 it
  stays narrow (Fig. 7).
- **Pull-off against β0** from 0.8 to 1 under load and displacement control: smooth and monotone, with the
  circle β0 = 1 on the same curve (no special case at β0 = 1).
- **Fig. 10**: the contact and adhesive ellipses shrink with a fixed shape from loading to pull-off,
  which is the paper's equal-and-fixed-ellipticity assumption (Eqs. 17–19) made visible.
- **Independent references** for the core: the circular closed form of Eq. (31), adaptive quadrature of
  Eq. (12b) at {n_quad} random points per β{' (quick mode: fewer points than the default 4000)' if quick else ''},
  the JKR and DMT limits, and self-consistency of every solved state with the field formulas
  of `dhfield.models.dh_elliptic_fields` (Eqs. 24–26).

Paper notes: the printed Eq. (14a) `L_in = δ = πPo b K(k)` is `πE*δ`; the approach is δ = Po b K(k)/E*.
The printed Legendre forms of Eqs. (15)/(B1)–(B3) are 0/0 at β = 1; the library uses Carlson's symmetric
forms, checked here against both the printed forms and the quadrature.

Section wall time: see the header; all data in netCDF next to the figures
(`load_curve_mu*_beta0*.nc`, `pull_off_vs_beta0.nc`).
"""
    mono = [c for c in cont_checks if "monotone" in c.name]
    verdict = [
        "**The paper's analytic model is reproduced as printed** (Figs. 3–7, 10; errata in the section text): "
        f"Eq. (31) at β0 = 1 equals the Greenwood & Johnson (1998) closed form to {closed_form.value:.0e}; the "
        f"pull-off tends to the JKR limit (W*max = {float(po_limits.W_star[0]):.4f} at μ = 20, −3/4 expected) "
        f"and the DMT limit ({float(po_limits.W_star[1]):.4f} at μ = 0.05, −1 expected); it varies smoothly "
        f"and monotonically with β0 from 0.8 to 1 ({sum(int(c.value) for c in mono)} non-monotone steps)."]
    return Section(title=TITLE, text=text, checks=checks, figures=figures, tables=tables, datasets=datasets,
                   verdict=verdict)
