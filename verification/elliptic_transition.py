"""The recommended model ``md-elliptic`` (:mod:`dhfield.elliptic_transition`) against every case
of the stored BEM ground truth, beside the other models, with its cost.

For each stored (beta0, mu) (``data/adhesive_ground_truth.nc``, Dugdale law, load control,
W* Richardson-extrapolated where three converged levels exist, else the finest usable N
as stored; and ``data/adhesive_ground_truth_slender.nc``, beta0 0.1-0.3, its finer grid
level) prints W*_BEM and the relative deviation of

* ``md-elliptic``: W*_DMT,ell + (W*_GVG - W*_DMT,ell) g(mu_e), g from Maugis-Dugdale on the
  sphere at the effective mu_e = mu sin(theta_skew)^(1/4) (Eq. T0);
* ``mu_e=mu``: the same without Eq. (T0) (g at mu itself), to show what it buys;
* ``candJG``: the same with Johnson & Greenwood (2005) as the JKR limit (to show what the
  exact-energy limit buys);
* ``md``: Maugis-Dugdale on the sphere R = sqrt(R'R''), times sin(theta_skew) (Eq. 34);
* the stored models of the dataset (``W_star_model``): the paper's ``dh-elliptic`` and the
  two-axis closure;

then the max |deviation| of each, and the cost per point (a benchmark, not a test).

``python -m verification.elliptic_transition``
"""
from __future__ import annotations

import time
from pathlib import Path

import numpy as np

from dhfield import elliptic_transition as et
from dhfield import jkr_elliptic as jg
from dhfield import jkr_elliptic_energy as gvg
from dhfield import maugis_dugdale as md
from dhfield.geometry import sin_skew_angle

DATASET = Path(__file__).resolve().parent.parent / "data" / "adhesive_ground_truth.nc"
SLENDER = Path(__file__).resolve().parent.parent / "data" / "adhesive_ground_truth_slender.nc"


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
    n_main = w.size
    b0, mu, w = np.concatenate([b0, bs[oks]]), np.concatenate([mu, ms[oks]]), np.concatenate([w, ws[oks]])
    stored = {k: np.concatenate([v, np.full(oks.sum(), np.nan)]) for k, v in stored.items()}
    sn = sin_skew_angle(b0)
    cols = {"md-elliptic": et.pull_off_nondimensional(b0, mu).W_star,
            "mu_e=mu": -sn + (gvg.pull_off_nondimensional(b0, 1.0).W_star + sn) * et.transition_weight(mu),
            "candJG": _candidate_jg(mu, b0),
            "md": md.pull_off_nondimensional(1.0, mu).W_star * sn,
            **stored}
    print("Load-control pull-off W* (Eq. 34) against the stored BEM ground truth; deviations in %")
    print(f"{'beta0':>6} {'mu':>5} {'W*_BEM':>9} " + " ".join(f"{k:>20}" for k in cols))
    for i in range(w.size):
        print(f"{b0[i]:6.3f} {mu[i]:5.2f} {w[i]:9.5f} "
              + " ".join(f"{100 * (v[i] / w[i] - 1):+20.3f}" for v in cols.values()))
    for label, sel in ((f"all {w.size}", slice(None)), (f"the {n_main} at beta0 >= 0.5", slice(0, n_main)),
                       (f"the {w.size - n_main} slender (beta0 < 0.5)", slice(n_main, None))):
        print(f"max |deviation| over {label} cases:")
        for k, v in cols.items():
            d = np.abs(v[sel] / w[sel] - 1)
            if not np.any(np.isfinite(d)):
                continue
            j = int(np.nanargmax(d))
            print(f"  {k:22s} {100 * d[j]:6.3f} %  at beta0 = {b0[sel][j]:g}, mu = {mu[sel][j]:g}")
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
