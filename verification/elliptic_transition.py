"""The recommended model ``md-elliptic`` (:mod:`dhfield.models.md_elliptic`) against every case
of the stored BEM ground truth, beside the other models, with its cost.

For each stored (beta0, mu) (``data/adhesive_ground_truth.nc``, Dugdale law, load control,
W* Richardson-extrapolated where three converged levels exist, else the finest usable N
as stored; and ``data/adhesive_ground_truth_slender.nc``, beta0 0.1-0.3, its finer grid
level; and, when present, the cases of ``data/adhesive_ground_truth_extended.nc`` that
neither holds: issue 20's extended study run through ``dhfield sweep``, its finest grid
level answering, ``python -m verification.study_extended``) prints W*_BEM, its error
estimate, and the relative deviation of

* ``md-elliptic``: W*_DMT,ell + (W*_GVG - W*_DMT,ell) g(mu_e), g from Maugis-Dugdale on the
  sphere at the effective mu_e = mu sin(theta_skew)^(1/4) (Eq. T0);
* ``mu_e=mu``: the same without Eq. (T0) (g at mu itself), to show what it buys;
* ``candJG``: the same with Johnson & Greenwood (2005) as the JKR limit (to show what the
  exact-energy limit buys);
* ``md``: Maugis-Dugdale on the sphere R = sqrt(R'R''), times sin(theta_skew) (Eq. 34);
* the stored models of the dataset (``W_star_model``): the paper's ``dh-elliptic`` and the
  two-axis closure;

then the max |deviation| of each over every group of cases (the N-ladder set, the slender
set, the new sweep cases, the points of the extended study), the worst case of
``md-elliptic`` with the error estimate of its ground truth, the extended study's points
not run, and the cost per point (a benchmark, not a test).

``python -m verification.elliptic_transition``
"""
from __future__ import annotations

import time
from pathlib import Path

import numpy as np

from dhfield.models import md_elliptic as et
from dhfield.models import jkr_elliptic as jg
from dhfield.models import jkr_elliptic_energy as gvg
from dhfield.models import maugis_dugdale as md
from dhfield.core.geometry import sin_skew_angle

DATASET = Path(__file__).resolve().parent.parent / "data" / "adhesive_ground_truth.nc"
SLENDER = Path(__file__).resolve().parent.parent / "data" / "adhesive_ground_truth_slender.nc"
EXTENDED = Path(__file__).resolve().parent.parent / "data" / "adhesive_ground_truth_extended.nc"


def _candidate_jg(mu, beta0):
    sn = sin_skew_angle(beta0)
    return -sn + (jg.pull_off_nondimensional(beta0, 1.0).W_star + sn) * et.transition_weight(mu)


def main():
    import xarray as xr

    with xr.open_dataset(DATASET) as ds:
        w = ds["W_star_extrapolated"].values
        b0, mu = np.meshgrid(ds["beta0"].values, ds["mu"].values, indexing="ij")
        stored = {m: ds["W_star_model"].sel(model=m).values for m in ("dh-elliptic", "dh-elliptic-two-axis")}
    ok = np.isfinite(w)
    b0, mu, w = b0[ok], mu[ok], w[ok]
    stored = {k: v[ok] for k, v in stored.items()}
    with xr.open_dataset(SLENDER) as ds:   # the finer of the two grid levels of each slender case
        ws = ds["W_star"].isel(level=-1).values
        bs, ms = np.meshgrid(ds["beta0"].values, ds["mu"].values, indexing="ij")
    oks = np.isfinite(ws)
    n_main, n_slender = w.size, int(oks.sum())
    b0, mu, w = np.concatenate([b0, bs[oks]]), np.concatenate([mu, ms[oks]]), np.concatenate([w, ws[oks]])
    err = np.full(w.size, np.nan)
    not_run, study = [], np.zeros(w.size, dtype=bool)
    if EXTENDED.is_file():   # issue 20's extended study: the truth of every point, new cases appended
        with xr.open_dataset(EXTENDED) as ds:
            wt, et_ = ds["W_star_truth"].values, ds["W_star_truth_error"].values
            src, ext = ds["truth_source"].values.astype(str), ds["extended_study"].values.astype(bool)
            be, me = np.meshgrid(ds["beta0"].values, ds["mu"].values, indexing="ij")
            not_run = str(ds.attrs.get("not_run_cases", "none"))
        seen = {(round(float(b), 6), round(float(m), 6)): i for i, (b, m) in enumerate(zip(b0, mu))}
        new = []
        for b, m, v, e, s_, x in zip(be.ravel(), me.ravel(), wt.ravel(), et_.ravel(), src.ravel(), ext.ravel()):
            i = seen.get((round(float(b), 6), round(float(m), 6)))
            if i is not None:
                err[i], study[i] = e, x
            elif np.isfinite(v) and "dhfield sweep" in s_:
                new.append((b, m, v, e, x))
        if new:
            nb, nm, nw, ne, nx_ = (np.array(c) for c in zip(*new))
            b0, mu, w = np.concatenate([b0, nb]), np.concatenate([mu, nm]), np.concatenate([w, nw])
            err, study = np.concatenate([err, ne]), np.concatenate([study, nx_.astype(bool)])
    stored = {k: np.concatenate([v, np.full(w.size - n_main, np.nan)]) for k, v in stored.items()}
    sn = sin_skew_angle(b0)
    cols = {"md-elliptic": et.pull_off_nondimensional(b0, mu).W_star,
            "mu_e=mu": -sn + (gvg.pull_off_nondimensional(b0, 1.0).W_star + sn) * et.transition_weight(mu),
            "candJG": _candidate_jg(mu, b0),
            "md": md.pull_off_nondimensional(1.0, mu).W_star * sn,
            **stored}
    print("Load-control pull-off W* (Eq. 34) against the stored BEM ground truth; deviations in %")
    print("(err%: the ground truth's error estimate, relative; source: L the N-ladder set, S the slender set, "
          "N new through dhfield sweep; * a point of the extended study)")
    print(f"{'beta0':>6} {'mu':>5} {'src':>3} {'W*_BEM':>9} {'err%':>6} " + " ".join(f"{k:>20}" for k in cols))
    n_old = n_main + n_slender
    for i in range(w.size):
        tag = ("L" if i < n_main else "S" if i < n_old else "N") + ("*" if study[i] else " ")
        print(f"{b0[i]:6.3f} {mu[i]:5.2f} {tag:>3} {w[i]:9.5f} {100 * abs(err[i] / w[i]):6.3f} "
              + " ".join(f"{100 * (v[i] / w[i] - 1):+20.3f}" for v in cols.values()))
    groups = [(f"all {w.size}", slice(None)), (f"the {n_main} at beta0 >= 0.5 (N-ladder set)", slice(0, n_main)),
              (f"the {n_slender} slender (beta0 < 0.5)", slice(n_main, n_old))]
    if w.size > n_old:
        groups.append((f"the {w.size - n_old} new (dhfield sweep, verification.study_extended)", slice(n_old, None)))
    if study.any():
        groups.append((f"the {int(study.sum())} answered points of the extended study", study))
    for label, sel in groups:
        print(f"max |deviation| over {label} cases:")
        for k, v in cols.items():
            d = np.abs(v[sel] / w[sel] - 1)
            if not np.any(np.isfinite(d)):
                continue
            j = int(np.nanargmax(d))
            print(f"  {k:22s} {100 * d[j]:6.3f} %  at beta0 = {b0[sel][j]:g}, mu = {mu[sel][j]:g}")
    d = np.abs(cols["md-elliptic"] / w - 1)
    j = int(np.nanargmax(d))
    worst = cols["md-elliptic"][j]
    print(f"worst case of md-elliptic over all {w.size} cases: beta0 = {b0[j]:g}, mu = {mu[j]:g}: "
          f"W* = {worst:.6f} against the BEM's {w[j]:.6f} ({100 * (worst / w[j] - 1):+.3f} %; "
          f"ground-truth error estimate {100 * abs(err[j] / w[j]):.3f} %)")
    if EXTENDED.is_file():
        print(f"extended study, not run (no BEM value): {not_run}")
    rng = np.random.default_rng(0)
    bb, mm = rng.uniform(0.05, 1.0, 1000), 10.0 ** rng.uniform(-2, 4, 1000)
    et.pull_off_nondimensional(bb[:10], mm[:10])  # warm-up
    t = time.perf_counter()
    et.pull_off_nondimensional(bb, mm)
    t1 = time.perf_counter() - t
    bg, mg = np.meshgrid(np.linspace(0.05, 1.0, 200), np.geomspace(0.01, 100.0, 200))
    t = time.perf_counter()
    et.pull_off_nondimensional(bg, mg)
    t2 = time.perf_counter() - t
    print(f"cost: {1e3 * t1 / 1000:.3f} ms per point (1000 distinct random (beta0, mu)); "
          f"200 x 200 map {t2:.2f} s ({1e3 * t2 / 4e4:.4f} ms per point: one GVG per beta0, one MD per distinct mu_e)")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
