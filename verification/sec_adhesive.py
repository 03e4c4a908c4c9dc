"""Report section: the adhesive ground truth and the verdict on the closures (issue 8).

The self-consistent adhesive BEM (:func:`dhfield.bem.adhesive_pull_off`, Dugdale law
sigma0 = mu, h0 = 1/mu, free boundary) gives W*max, beta_ab = b/a and beta_cd = d/c
at the load-control pull-off of the crossed-cylinder contact for beta0 x mu.  The
section READS the stored study (``data/adhesive_ground_truth.nc``, written by
``python -m verification.study_adhesive``: Richardson-extrapolated over the N
ladder where three converged levels exist), RE-RUNS one (quick) or two cheap
cases to show that the stored numbers reproduce, and compares every analytic
model of :mod:`dhfield.analysis.compare` with it:

* the paper's closure (``dh-elliptic``, Eqs. 17-19, 31), its JKR-beta variant,
  the ray-average and the two-axis closures (:mod:`dhfield.models.dh_elliptic_closure`);
* elliptical JKR (Johnson & Greenwood 2005) and Maugis-Dugdale (sphere with
  R = sqrt(R'R''), lambda = 1.1272 mu).

The verdict says which closure is within how many percent of the ground truth,
where in (beta0, mu), and whether the contact and adhesive ellipses share their
ellipticity (beta_ab against beta_cd), all from the stored numbers.

``python -m verification.sec_adhesive [--quick]`` prints the verdict and the table.
"""
from __future__ import annotations

import sys
import time
from pathlib import Path

import numpy as np

from verification._api import Figure, Section, check_le, save_figure
from verification._style import QUICK_DPI, REPORT_DPI, figsize, legend_below, model_label, rel_diff_label

TITLE = "Adhesive ground truth: BEM pull-off of the elliptical contact vs the closures"
ROOT = Path(__file__).resolve().parent.parent
DATASET = ROOT / "data" / "adhesive_ground_truth.nc"
#: Sphere vs MD over N = 256/512/1024 (written by verification/convergence_adhesive.py --out).
SPHERE_CONVERGENCE = ROOT / "data" / "adhesive_sphere_convergence.json"
#: issue 8: Richardson-extrapolated sphere pull-off within 0.5 % of Maugis-Dugdale.
TOL_MD_RICHARDSON = 0.005

#: Closures judged by the verdict, with the words the report uses.
CLOSURES = {
    "dh-elliptic": "the paper's closure (dh-elliptic)",
    "dh-elliptic-jkr-beta": "JKR-β (dh-elliptic-jkr-beta)",
    "dh-elliptic-ray-average": "ray-average (dh-elliptic-ray-average)",
    "dh-elliptic-two-axis": "two-axis (dh-elliptic-two-axis)",
}
OTHERS = {"jkr-elliptic": "elliptical JKR", "md": "Maugis–Dugdale (sphere, R = √(R′R″))"}

#: issue 8: sphere vs Maugis-Dugdale at lambda <= 1 (mu <= 0.887): 1 % (extrapolated or finest N).
TOL_MD_SPHERE = 0.01
#: issue 8: sphere vs MD at lambda <= 3 (mu <= 2.66): 2 %.
TOL_MD_SPHERE_HIGH = 0.02
#: lambda = 1.1272 mu (dhfield.core.transition): mu of lambda = 1 and 3.
MU_LAMBDA1, MU_LAMBDA3 = 1.0 / 1.1272, 3.0 / 1.1272
#: A closure "is within" the ground truth where its W* lies within this relative distance.
WITHIN = (0.01, 0.02, 0.05)
#: beta_ab and beta_cd "agree" when they differ by less than this (absolute, in b/a).
BETA_AGREE = 0.01


def _quick_cases(quick):
    # cheap, well-converged cases of the stored coarsest level (measured 1-4 s at N = 64)
    return ((1.0, 0.5),) if quick else ((1.0, 0.5), (0.8, 1.0))


def _plt():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def _pct(x):
    return f"{100 * x:+.1f} %"


# --------------------------------------------------------------------------- analysis
def truth_table(ds):
    """Per (beta0, mu): the BEM values used as ground truth and each model's deviation.

    Returns a dict of 2-D arrays (beta0, mu): ``W_bem``, ``beta_ab``, ``beta_cd``,
    ``levels`` (3: Richardson; 1-2: finest usable N; 0: none), ``n_used`` (finest
    N used), and ``dev[model]`` = W*_model / W*_BEM - 1.
    """
    from verification.study_adhesive import STATUSES, USABLE

    w = ds["W_star_extrapolated"].values
    levels = ds["W_star_levels"].values.astype(int)
    usable = np.isin(ds["status"].values, [STATUSES.index(s) for s in USABLE])
    ns = ds["n"].values
    n_used = np.where(usable.any(axis=-1), np.max(np.where(usable, ns[None, None, :], 0), axis=-1), 0)
    models = [str(m) for m in ds["model"].values]
    dev = {m: ds["W_star_model"].sel(model=m).values / w - 1.0 for m in models}
    return {"beta0": ds["beta0"].values, "mu": ds["mu"].values, "W_bem": w, "levels": levels,
            "n_used": n_used, "beta_ab": ds["beta_ab_extrapolated"].values,
            "beta_cd": ds["beta_cd_extrapolated"].values, "dev": dev,
            "W_model": {m: ds["W_star_model"].sel(model=m).values for m in models},
            "ell_model": {m: ds["ellipticity_model"].sel(model=m).values for m in models}}


def _where(tab, mask):
    pts = [f"(β0 = {tab['beta0'][i]:g}, μ = {tab['mu'][j]:g})" for i, j in zip(*np.nonzero(mask))]
    return ", ".join(pts) if pts else "nowhere"


def verdict_lines(tab, coverage):
    """The verdict sentences, most important first (every number computed here)."""
    ok = np.isfinite(tab["W_bem"])
    n_ok = int(ok.sum())
    total = ok.size
    lines = []
    if n_ok == 0:
        return [f"**No adhesive ground truth is stored yet** ({coverage}); no closure can be judged."]
    stats = {}
    for m in CLOSURES:
        if m not in tab["dev"]:
            continue
        d = np.abs(tab["dev"][m][ok])
        i = int(np.argmax(d))
        ij = tuple(np.argwhere(ok)[i])
        stats[m] = (float(np.max(d)), float(np.median(d)), ij)
    best = min(stats, key=lambda m: stats[m][0])
    b_i, b_j = stats[best][2]
    lines.append(
        f"**Best double-Hertz closure against the BEM ground truth: {CLOSURES[best]}**, within "
        f"{100 * stats[best][0]:.1f} % of W*max in every one of the {n_ok} (β0, μ) cases solved "
        f"(median {100 * stats[best][1]:.1f} %; worst at β0 = {tab['beta0'][b_i]:g}, μ = {tab['mu'][b_j]:g}).")
    if n_ok < total:
        lines.append(f"**No converged BEM pull-off** (recorded, with the solver's message, in the dataset) at "
                     f"{_where(tab, ~ok)}: the closures are not judged there.")
    for m, (mx, med, (i, j)) in sorted(stats.items(), key=lambda kv: kv[1][0]):
        if m == best:
            continue
        dev = tab["dev"][m][i, j]
        within = [f"{100 * t:g} %: {int(np.sum(np.abs(tab['dev'][m][ok]) <= t))}/{n_ok}" for t in WITHIN]
        lines.append(f"{CLOSURES[m]}: up to {_pct(dev)} from the BEM W*max (at β0 = {tab['beta0'][i]:g}, "
                     f"μ = {tab['mu'][j]:g}; median {100 * med:.1f} %); cases within " + ", ".join(within) + ".")
    # equal beta?
    bab, bcd = tab["beta_ab"], tab["beta_cd"]
    fin = ok & np.isfinite(bab) & np.isfinite(bcd)
    ell = fin & (tab["beta0"][:, None] < 1.0)
    if np.any(ell):
        diff = (bcd - bab)[ell]
        k = int(np.argmax(np.abs(diff)))
        i, j = np.argwhere(ell)[k]
        agree = int(np.sum(np.abs(diff) < BETA_AGREE))
        lines.append(
            f"**The contact and adhesive ellipses do not share β** where the zone is wide: β_cd − β_ab reaches "
            f"{diff[k]:+.3f} (β_ab = {bab[i, j]:.3f}, β_cd = {bcd[i, j]:.3f} at β0 = {tab['beta0'][i]:g}, "
            f"μ = {tab['mu'][j]:g}); they agree within {BETA_AGREE:g} in {agree} of {int(ell.sum())} elliptical "
            f"cases ({_where(tab, ell & (np.abs(bcd - bab) < BETA_AGREE))})." if agree < ell.sum() else
            f"The contact and adhesive ellipses share β within {BETA_AGREE:g} in all {int(ell.sum())} elliptical "
            f"cases (largest β_cd − β_ab = {diff[k]:+.3f} at β0 = {tab['beta0'][i]:g}, μ = {tab['mu'][j]:g}).")
        # the paper's assumption beta = beta0
        dev0 = (bab - tab["beta0"][:, None])[ell]
        k = int(np.argmax(np.abs(dev0)))
        i, j = np.argwhere(ell)[k]
        lines.append(f"The paper's β = β0 (Eq. 19) for the contact ellipse is off by up to {dev0[k]:+.3f} "
                     f"(β_ab = {bab[i, j]:.3f} at β0 = {tab['beta0'][i]:g}, μ = {tab['mu'][j]:g}).")
    if 1.0 in tab["beta0"] and "dh-elliptic" in tab["dev"]:
        i = int(np.nonzero(tab["beta0"] == 1.0)[0][0])
        d = tab["dev"]["dh-elliptic"][i]
        if np.any(np.isfinite(d)):
            k = int(np.nanargmax(np.abs(d)))
            lines.append(f"At β0 = 1 every closure is the circular double-Hertz model (Greenwood & Johnson 1998), "
                         f"whose law differs from Dugdale's: it is {_pct(d[k])} from the BEM at μ = {tab['mu'][k]:g} "
                         f"(largest over μ) — the floor of any DH closure.  Signs: model/BEM − 1 of W*max < 0, so "
                         f"a negative deviation is a weaker pull-off than the BEM.")
    for m, words in OTHERS.items():
        if m in tab["dev"]:
            d = tab["dev"][m]
            k = np.nanargmax(np.where(ok, np.abs(d), -1))
            i, j = np.unravel_index(k, d.shape)
            lines.append(f"{words}: up to {_pct(d[i, j])} (β0 = {tab['beta0'][i]:g}, μ = {tab['mu'][j]:g}).")
    lines.append(f"Coverage: {coverage}.")
    return lines


def guide_lines(tab):
    """'Which model to use when' from the ground truth: the closures ranked by their worst deviation."""
    ok = np.isfinite(tab["W_bem"])
    ranked = []
    for m in CLOSURES:
        if m in tab["dev"] and np.any(ok):
            ranked.append((float(np.max(np.abs(tab["dev"][m][ok]))), m))
    if not ranked:
        return []
    ranked.sort()
    (best_dev, best), rest = ranked[0], ranked[1:]
    b0 = tab["beta0"][np.any(ok, axis=1)]
    mu = tab["mu"][np.any(ok, axis=0)]
    others = "; ".join(f"`{m}` {100 * d:.1f} %" for d, m in rest)
    return [f"**Among the double-Hertz closures, against the self-consistent adhesive BEM (β0 = {b0.min():g}–"
            f"{b0.max():g}, μ = {mu.min():g}–{mu.max():g}, Dugdale law):** `{best}` — within "
            f"{100 * best_dev:.1f} % of the BEM W*max in all {int(ok.sum())} cases solved; the worst deviation "
            f"of the others: {others}."]


def coarse_to_fine_cases(ds):
    """(beta0, mu, n, route) of every stored case solved coarse to fine, in dataset order."""
    if "route" not in ds:
        return []
    routes = ds["route"].values.astype(str)
    return [(float(ds["beta0"][i]), float(ds["mu"][j]), int(ds["n"][k]), str(routes[i, j, k]))
            for i, j, k in zip(*np.nonzero(np.char.startswith(routes, "coarse to fine")))]


def _coverage(ds):
    from verification.study_adhesive import STATUSES

    st = ds["status"].values
    per_n = []
    for k, n in enumerate(ds["n"].values):
        counts = {s: int(np.sum(st[..., k] == i)) for i, s in enumerate(STATUSES)}
        per_n.append(f"N = {int(n)}: " + ", ".join(f"{v} {s.replace('_', ' ')}" for s, v in counts.items() if v))
    lv = ds["W_star_levels"].values
    return (f"{int(np.sum(lv == 3))} of {lv.size} (β0, μ) cases Richardson-extrapolated over three N, "
            f"{int(np.sum((lv > 0) & (lv < 3)))} at their finest converged N (non-monotone or implausible "
            f"order over N, or fewer levels), {int(np.sum(lv == 0))} "
            f"without a usable BEM value; " + "; ".join(per_n))


def table_markdown(tab):
    models = [m for m in list(CLOSURES) + list(OTHERS) if m in tab["dev"]]
    head = ("| β0 | μ | W*max BEM | N (levels) | β_ab | β_cd | "
            + " | ".join(f"{m}" for m in models) + " |")
    sep = "|" + "---|" * (6 + len(models))
    rows = [head, sep]
    for i, b in enumerate(tab["beta0"]):
        for j, m in enumerate(tab["mu"]):
            w = tab["W_bem"][i, j]
            lv = int(tab["levels"][i, j])
            cells = [f"{b:g}", f"{m:g}",
                     f"{w:.4f}" if np.isfinite(w) else "—",
                     f"{int(tab['n_used'][i, j])} ({lv})" if lv else "—",
                     f"{tab['beta_ab'][i, j]:.3f}" if np.isfinite(tab["beta_ab"][i, j]) else "—",
                     f"{tab['beta_cd'][i, j]:.3f}" if np.isfinite(tab["beta_cd"][i, j]) else "—"]
            for mod in models:
                d = tab["dev"][mod][i, j]
                cells.append(f"{tab['W_model'][mod][i, j]:.4f} ({_pct(d)})" if np.isfinite(d) else
                             f"{tab['W_model'][mod][i, j]:.4f}")
            rows.append("| " + " | ".join(cells) + " |")
    return "\n".join(rows)


# --------------------------------------------------------------------------- checks
def _checks_md(tab):
    checks = []
    if 1.0 not in tab["beta0"]:
        return checks
    i = int(np.nonzero(tab["beta0"] == 1.0)[0][0])
    for j, mu in enumerate(tab["mu"]):
        if not np.isfinite(tab["W_bem"][i, j]):
            continue                  # mu > MU_LAMBDA3 (mu = 5, lambda = 5.6): held to the lambda = 3 bound
        tol = TOL_MD_SPHERE if mu <= MU_LAMBDA1 else TOL_MD_SPHERE_HIGH
        lv = int(tab["levels"][i, j])
        how = "Richardson" if lv == 3 else f"N = {int(tab['n_used'][i, j])}"
        checks.append(check_le(
            f"sphere (β0 = 1), μ = {mu:g} (λ = {1.1272 * mu:.2f}): |W*_BEM/W*_MD − 1| ({how})",
            abs(tab["dev"]["md"][i, j]) if "md" in tab["dev"] else np.nan, tol,
            "Maugis (1992) via dhfield.models.maugis_dugdale; targets 1 % at λ ≤ 1, 2 % at λ ≤ 3 (and beyond)"))
    return checks


def _sphere_convergence():
    """Checks and a text line from the stored sphere convergence run (none when absent)."""
    import json

    if not SPHERE_CONVERGENCE.is_file():
        return [], []
    doc = json.loads(SPHERE_CONVERGENCE.read_text())
    checks, parts = [], []
    for case in doc["cases"]:
        err = float(case["richardson_err"])
        checks.append(check_le(
            f"sphere (β0 = 1), λ = {case['lam']:g}: Richardson over N = {'/'.join(map(str, doc['n']))} "
            f"|W*/W*_MD − 1|", abs(err) if np.isfinite(err) else np.inf, TOL_MD_RICHARDSON,
            f"Maugis (1992) via dhfield.models.maugis_dugdale; {SPHERE_CONVERGENCE.relative_to(ROOT)}"))
        per_n = ", ".join(f"N = {r['n']}: {100 * r['err']:+.3f} %" for r in case["rows"])
        parts.append(f"λ = {case['lam']:g}: {per_n}; Richardson {100 * err:+.3f} % (order {case['order']:.2f})")
    line = (f"Sphere against Maugis–Dugdale (`{SPHERE_CONVERGENCE.relative_to(ROOT)}`, command "
            f"`{doc['command']}`, solver commit {doc['git_commit'][:10]}; {doc['route']}): " + "; ".join(parts) + ".")
    return checks, [line]


def _rerun(ds, quick, progress):
    """Re-solve the cheap cases at the coarsest stored N; return checks and a text line."""
    from dhfield.bem import adhesive_pull_off
    from dhfield.analysis.bem_start import AdhesiveOptions
    from dhfield.bem.pull_off import SEARCHES
    from verification.study_adhesive import STATUSES, STUDY_MAX_ITER, USABLE

    checks, lines = [], []
    n0 = int(ds["n"].values[0])
    for b, m in _quick_cases(quick):
        if b not in ds["beta0"].values or m not in ds["mu"].values:
            continue
        sel = dict(beta0=b, mu=m, n=n0)
        if STATUSES[int(ds["status"].sel(**sel))] not in USABLE:
            continue
        stored = float(ds["W_star"].sel(**sel))
        t0 = time.perf_counter()
        # the same load-minimum search as the stored case (march for cases stored before 'search')
        search = str(ds["search"].sel(**sel).values) if "search" in ds else "march"
        res = adhesive_pull_off(mu=m, beta0=b, n=n0, progress=False, search=search if search in SEARCHES else "bracket", options=AdhesiveOptions(max_iter=STUDY_MAX_ITER))
        el = time.perf_counter() - t0
        progress(f"re-run β0 = {b:g}, μ = {m:g}, N = {n0}: {el:.1f} s")
        # the stored study is the former fixed point's (its sub-cell Dugdale edge); the re-run is the
        # Newton solve's (its ramped edge, since 2026-12-02): two discretisations of one law, so the
        # re-run's stated error (the grid's, K |W*| / cells) must cover the stored value
        err = abs(res.W_star - stored)
        checks.append(check_le(f"re-run agrees with the stored W*max within its stated error at β0 = {b:g}, "
                               f"μ = {m:g}, N = {n0}", err, float(res.W_star_error),
                               "data/adhesive_ground_truth.nc (stored study, the former fixed point); the "
                               "re-run by the Newton solve"))
        berr = max(abs(res.ellipticity - float(ds["beta_ab"].sel(**sel))),
                   abs(res.adhesive_ellipticity - float(ds["beta_cd"].sel(**sel))))
        # the semi-axes come from the masks' second moments: on another discretisation of the law
        # they may move by up to a cell, i.e. b/a by up to (b/a) (dx/a + dy/b)
        dx, dy = 2.0 * res.half_width_x / n0, 2.0 * res.half_width_y / n0      # the re-run's n0 x n0 cells
        tol_beta = res.ellipticity * (dx / res.a_star + dy / res.b_star)
        checks.append(check_le(f"re-run agrees with the stored β_ab, β_cd within a cell at β0 = {b:g}, μ = {m:g}, "
                               f"N = {n0}", berr, tol_beta,
                               "data/adhesive_ground_truth.nc (stored study, the former fixed point)"))
        lines.append(f"β0 = {b:g}, μ = {m:g}, N = {n0}: stored W* = {stored:.6f}, re-run {res.W_star:.6f} "
                     f"({el:.1f} s, {res.n_steps} states, {res.iterations / max(res.n_steps, 1):.0f} GMRES "
                     f"iterations per state)")
    return checks, lines


# --------------------------------------------------------------------------- figure
def recommended_deviation(tab):
    """W*/W*_BEM - 1 of the recommended model (:data:`dhfield.analysis.compare.RECOMMENDED_MODEL`) on the
    table's (beta0, mu) grid, evaluated now (the stored file tabulates the other models only)."""
    from dhfield.analysis.compare import RECOMMENDED_MODEL, pull_off

    b, m = np.meshgrid(tab["beta0"], tab["mu"], indexing="ij")
    w = pull_off(RECOMMENDED_MODEL, beta0=b, mu=m, warn=False).W_star
    return np.asarray(w, float) / tab["W_bem"] - 1.0


def _figure(tab, outdir, dpi):
    from dhfield.analysis.compare import RECOMMENDED_MODEL

    plt = _plt()
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=figsize(2, 0.4))
    # the recommended model first (issue 40), then the closures and the comparison models
    markers = {RECOMMENDED_MODEL: "*", "dh-elliptic": "o", "dh-elliptic-jkr-beta": "s",
               "dh-elliptic-ray-average": "^", "dh-elliptic-two-axis": "v", "jkr-elliptic": "x", "md": "+"}
    devs = dict(tab["dev"])
    devs[RECOMMENDED_MODEL] = recommended_deviation(tab)
    colors = plt.cm.viridis(np.linspace(0, 0.9, len(tab["beta0"])))
    for mod, mk in markers.items():
        if mod not in devs:
            continue
        rec = mod == RECOMMENDED_MODEL
        for i, b in enumerate(tab["beta0"]):
            ax1.plot(tab["mu"], 100 * devs[mod][i], marker=mk, color=colors[i], lw=2.0 if rec else 0.8,
                     ms=9 if rec else 6, zorder=4 if rec else 2, label=model_label(mod) if i == 0 else None)
    ax1.axhline(0.0, color="k", lw=0.6)
    ax1.set_xscale("log")
    ax1.set_xlabel("μ (Eq. 35)")
    ax1.set_ylabel(rel_diff_label("W*max", "model", "BEM"))
    ax1.set_title("(a) pull-off vs BEM (colour: β0)")
    for i, b in enumerate(tab["beta0"]):
        ax2.plot(tab["mu"], tab["beta_ab"][i], "-o", color=colors[i], ms=4, label=f"β_ab, β0 = {b:g}")
        ax2.plot(tab["mu"], tab["beta_cd"][i], "--s", color=colors[i], ms=4, mfc="none",
                 label="β_cd" if i == 0 else None)
        ax2.axhline(b, color=colors[i], lw=0.5, ls=":")
    ax2.set_xscale("log")
    ax2.set_xlabel("μ (Eq. 35)")
    ax2.set_ylabel("ellipticity at pull-off")
    ax2.set_title("(b) b/a (solid), d/c (dashed), β0 (dotted)")
    from matplotlib.lines import Line2D

    # one legend: the model by marker (black), β0 by colour
    handles = [Line2D([], [], color="k", marker=mk, lw=2.0 if mod == RECOMMENDED_MODEL else 0.8,
                      label=model_label(mod))
               for mod, mk in markers.items() if mod in devs]
    handles += [Line2D([], [], color=colors[i], lw=3, label=f"β0 = {b:g}") for i, b in enumerate(tab["beta0"])]
    legend_below(fig, handles, [h.get_label() for h in handles], ncol=4)
    cap = ("BEM ground truth (Dugdale, free boundary; Richardson over N where three levels converged) against "
           "the analytic models at the pull-off, on the axes of the paper's Fig. 9 (W* of Eq. 34 vs μ of Eq. 35): "
           f"(a) relative error of each model's W*max, the recommended `{RECOMMENDED_MODEL}` first (stars, thick), "
           "(b) the contact and adhesive ellipticities b/a and d/c "
           "against the paper's assumption β = β0 (Eq. 19).")
    return Figure(save_figure(fig, outdir / "adhesive_ground_truth.png", dpi), cap)


# --------------------------------------------------------------------------- section
def run(outdir: Path, quick: bool, progress) -> Section:
    """Build the adhesive ground-truth section (see the module docstring)."""
    from verification.study_adhesive import read_ground_truth

    outdir = Path(outdir)
    outdir.mkdir(parents=True, exist_ok=True)
    try:
        ds = read_ground_truth(DATASET)
    except ValueError as exc:
        return Section(TITLE, text=f"The stored study could not be read: {exc}",
                       checks=[check_le("adhesive ground-truth dataset readable", 1.0, 0.0,
                                        "python -m verification.study_adhesive")],
                       verdict=[f"**No adhesive ground truth is stored** ({DATASET.name} unreadable): the "
                                "closures are not judged."])
    progress("read the stored study")
    tab = truth_table(ds)
    coverage = _coverage(ds)
    checks = _checks_md(tab)
    rerun_checks, rerun_lines = _rerun(ds, quick, progress)
    checks += rerun_checks
    sphere_checks, sphere_lines = _sphere_convergence()
    checks += sphere_checks
    verdict = verdict_lines(tab, coverage)
    from verification.study_adhesive import STATUSES

    st = ds["status"].values
    bad = [(float(ds["beta0"][i]), float(ds["mu"][j]), int(ds["n"][k]), str(ds["message"].values[i, j, k]))
           for i, j, k in zip(*np.nonzero(np.isin(st, [STATUSES.index("unconverged"), STATUSES.index("failed")])))]
    text = [
        "The ground truth is the self-consistent adhesive BEM (`dhfield.bem.adhesive_pull_off`: Dugdale law "
        "σ0 = μ, h0 = 1/μ; free-boundary DC-FFT; Polonsky–Keer CG inside an Anderson fixed point on the "
        "cohesive zone, sub-cell zone edge), load-control pull-off = minimum of the unloading force.  Semi-axes "
        "from second moments of the contact and adhesive masks.",
        f"Stored study: `{DATASET.relative_to(ROOT)}` (N ladder {ds.attrs.get('param_n_ladder', '?')}, "
        f"solver commit {ds.attrs.get('param_git_commit', '?')[:10]}, "
        f"command `{ds.attrs.get('param_command', '?')}`). {coverage}.",
        "Re-run here: " + ("; ".join(rerun_lines) if rerun_lines else "no usable cheap case stored") + ".",
    ] + sphere_lines
    c2f = coarse_to_fine_cases(ds)
    if c2f:
        text.append("Solved coarse to fine (`dhfield.bem.refine_pull_off`: only the states around the pull-off, "
                    "started from the coarser N; the route is stored per case): "
                    + "; ".join(f"β0 = {b:g}, μ = {m:g}, N = {n} ({r})" for b, m, n, r in c2f) + ".")
    if bad:
        text.append("Cases flagged unconverged or failed (kept in the dataset with their message): "
                    + "; ".join(f"β0 = {b:g}, μ = {m:g}, N = {n}" for b, m, n, _ in bad) + ".")
    figs = []
    if np.any(np.isfinite(tab["W_bem"])):
        figs.append(_figure(tab, outdir, QUICK_DPI if quick else REPORT_DPI))
    return Section(TITLE, text="\n\n".join(text), checks=checks, figures=figs, tables=[table_markdown(tab)],
                   datasets=[DATASET], verdict=verdict, guide=guide_lines(tab))


def main(argv=None) -> int:
    import argparse
    import tempfile

    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--quick", action="store_true")
    args = p.parse_args(argv)
    with tempfile.TemporaryDirectory() as tmp:
        sec = run(Path(tmp), args.quick, lambda m: print(m, file=sys.stderr))
    print("\n".join(f"- {v}" for v in sec.verdict))
    print()
    print(sec.text)
    print()
    for t in sec.tables:
        print(t)
    for c in sec.checks:
        print(f"{'PASS' if c.passed else 'FAIL'}  {c.name}: {c.value:.3g} {c.comparison} {c.tolerance:.3g}")
    return 0 if all(c.passed for c in sec.checks) else 1


if __name__ == "__main__":
    sys.exit(main())
