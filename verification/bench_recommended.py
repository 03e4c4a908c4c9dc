"""The recommended model ``md-elliptic`` (:mod:`dhfield.models.md_elliptic`): its figures for issue 20.

Prints, in one run (a benchmark and a check, not a test: the machine is shared, so the load
average is printed beside the timings):

* **Ground truth.**  The largest deviation of the load-control pull-off W* from every stored
  BEM case (``data/adhesive_ground_truth_extended.nc``: its best value ``W_star_truth`` per
  (beta0, mu), Richardson-extrapolated where available; the same cases as
  ``python -m verification.elliptic_transition``), and the case where it occurs.
  Target: < 1 % in every case.
* **The JKR limit.**  W* at mu = 1e4 against GVG (``jkr-elliptic-energy``) at crossing angles
  20-90 deg (targets: 1 % at 45-90 deg, 2.5 % at 20-30 deg; exactly MD on the sphere at 90 deg).
* **One model.**  The load curve's minimum of W* against the load-control record (0 by
  construction; measured on a dense grid over 10-90 deg x mu 0.01-100), and the load curve's
  minimum of delta* against the displacement-control record (which is aligned at the
  displacement-control pull-offs instead: the documented difference).
* **Cost.**  Per point, vectorised, over 1000 distinct random (beta0, mu) (beta0 0.05-1, mu
  0.01-1e4): the record core, and ``compare.pull_off`` with its validity message; the paper's
  model with its departure warning (now against md-elliptic; ~200 ms a point against the
  two-axis closure before); one load curve of 200 points.  Target: <= 1 ms per point.
* **Sweep** (unless ``--skip-sweep``).  A 200 x 200 (beta0 x mu) map of md-elliptic through
  ``dhfield sweep --workers 2`` in a subprocess, wall time (target <= 60 s).

``python -m verification.bench_recommended [--map-n 200] [--skip-sweep]``
"""
from __future__ import annotations

import argparse
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

from dhfield.analysis import compare
from dhfield.models import jkr_elliptic_energy, maugis_dugdale
from dhfield.models import md_elliptic as et
from dhfield.core.geometry import ellipticity_from_skew_angle
from dhfield.core.pull_off_search import stable_minimum_index

DATASET = Path(__file__).resolve().parent.parent / "data" / "adhesive_ground_truth_extended.nc"
TARGET_TRUTH = 0.01
TARGET_MS = 1.0
TARGET_SWEEP_S = 60.0
_CLI = [sys.executable, "-c", "import sys; from dhfield.cli import main; sys.exit(main(sys.argv[1:]))"]


def ground_truth():
    import xarray as xr

    with xr.open_dataset(DATASET) as ds:   # every stored case: the N ladder, the slender set, the sweeps
        w = ds["W_star_truth"].values
        b0, mu = np.meshgrid(ds["beta0"].values, ds["mu"].values, indexing="ij")
    ok = np.isfinite(w)
    dev = et.pull_off_nondimensional(b0[ok], mu[ok]).W_star / w[ok] - 1.0
    j = int(np.argmax(np.abs(dev)))
    print(f"ground truth: {ok.sum()} BEM cases, max |W*_md-elliptic/W*_BEM - 1| = {100 * abs(dev[j]):.3f} % "
          f"at beta0 = {b0[ok][j]:g}, mu = {mu[ok][j]:g} (target < {100 * TARGET_TRUTH:g} %: "
          f"{'PASS' if abs(dev[j]) < TARGET_TRUTH else 'FAIL'})")


def jkr_limit():
    deg = np.array([20.0, 30.0, 45.0, 60.0, 75.0, 90.0])
    b0 = ellipticity_from_skew_angle(np.radians(deg))
    got = et.pull_off_nondimensional(b0, 1e4).W_star
    gvg = jkr_elliptic_energy.pull_off_nondimensional(b0, 1.0).W_star
    print("JKR limit, mu = 1e4: W*_md-elliptic/W*_GVG - 1 at "
          + ", ".join(f"{d:g} deg {100 * (g / r - 1):+.1e} %" for d, g, r in zip(deg, got, gvg)))
    sphere = float(maugis_dugdale.pull_off_nondimensional(1.0, 1e4).W_star)
    print(f"  at 90 deg: {float(got[-1]):.15f} against MD on the sphere {sphere:.15f}")


def _curve_min(beta0, mu, key):
    """The pull-off of the load curve by dhfield's one rule (the local minimum of W* or delta* nearest
    the high-load end, :func:`dhfield.core.pull_off_search.stable_minimum_index`) on a dense grid, refined
    by a parabola through the three samples around it."""
    a_p = float(et.pull_off_nondimensional(beta0, mu).a_star)
    a = np.concatenate([np.linspace(1e-4, 1.0, 1500), np.geomspace(1.0, 4.0, 500)[1:]])[::-1] * a_p
    c = et.load_curve_nondimensional(a, beta0, mu)
    v = c[key]
    i = int(stable_minimum_index(v))
    if 0 < i < v.size - 1:
        x = a[i - 1:i + 2]
        p = np.polyfit(x, v[i - 1:i + 2], 2)
        xm = float(np.clip(-p[1] / (2 * p[0]), x.min(), x.max())) if p[0] > 0 else float(a[i])
        cm = et.load_curve_nondimensional(xm, beta0, mu)
        return {k: float(cm[k]) for k in ("W_star", "delta_star", "a_star")}
    return {k: float(c[k][i]) for k in ("W_star", "delta_star", "a_star")}


def one_model():
    deg = np.array([10.0, 20.0, 30.0, 45.0, 60.0, 75.0, 90.0])
    b0 = ellipticity_from_skew_angle(np.radians(deg))
    mus = np.array([0.01, 0.1, 0.3, 1.0, 3.0, 10.0, 100.0])
    worst_load, worst_w, worst_d = 0.0, (0.0, None), (0.0, None)
    for d, b in zip(deg, b0):
        for m in mus:
            lo = et.pull_off_nondimensional(b, m)
            cm = _curve_min(float(b), float(m), "W_star")
            worst_load = max(worst_load, abs(cm["W_star"] / float(lo.W_star) - 1))
            dp = et.pull_off_nondimensional(b, m, control="displacement")
            cd = _curve_min(float(b), float(m), "delta_star")
            ew = abs(cd["W_star"] / float(dp.W_star) - 1)
            ed = abs(cd["delta_star"] - float(dp.delta_star)) / abs(float(dp.delta_star))
            if ew > worst_w[0]:
                worst_w = (ew, (d, m))
            if ed > worst_d[0]:
                worst_d = (ed, (d, m))
    print(f"one model (10-90 deg x mu 0.01-100, {deg.size * mus.size} cases): load curve's min W* against the "
          f"load-control record: max {100 * worst_load:.2e} % (the same point by construction)")
    print(f"  load curve's local min of delta* nearest high load against the displacement-control record: W* differs by up to "
          f"{100 * worst_w[0]:.2f} % ({worst_w[1][0]:g} deg, mu = {worst_w[1][1]:g}), delta* by up to "
          f"{100 * worst_d[0]:.2f} % ({worst_d[1][0]:g} deg, mu = {worst_d[1][1]:g})")


def cost():
    """Per-point cost on fresh random points for each figure (the module caches per-value states)."""
    rng = np.random.default_rng(0)

    def points(n=1000):
        return rng.uniform(0.05, 1.0, n), 10.0 ** rng.uniform(-2, 4, n)

    bb, mm = points(10)
    et.pull_off_nondimensional(bb, mm)  # warm-up (imports, first calls)

    def per_point(f, n):
        t = time.perf_counter()
        f()
        return 1e3 * (time.perf_counter() - t) / n

    bb, mm = points()
    core = per_point(lambda: et.pull_off_nondimensional(bb, mm), bb.size)
    bb, mm = points()
    core_disp = per_point(lambda: et.pull_off_nondimensional(bb, mm, control="displacement"), bb.size)
    bb, mm = points()
    public = per_point(lambda: compare.pull_off("md-elliptic", mu=mm, beta0=bb), bb.size)
    bb, mm = points(200)
    paper = per_point(lambda: compare.pull_off("dh-elliptic", mu=mm, beta0=bb), 200)
    bb, mm = points(200)
    paper_alone = per_point(lambda: compare.pull_off("dh-elliptic", mu=mm, beta0=bb, check_closure=False), 200)
    bb, mm = points(20)
    single = per_point(lambda: [compare.pull_off("md-elliptic", mu=float(m), beta0=float(b)) for b, m in zip(bb, mm)], 20)
    curve = per_point(lambda: compare.load_curve("md-elliptic", mu=2.0, beta0=0.3, n=200), 1)
    print(f"cost per point (1000 fresh random points, vectorised): record core {core:.3f} ms (load), "
          f"{core_disp:.3f} ms (displacement); compare.pull_off {public:.3f} ms "
          f"(target <= {TARGET_MS:g} ms: {'PASS' if public <= TARGET_MS else 'FAIL'}); one scalar call "
          f"{single:.1f} ms (cold: one GVG and one MD pull-off)")
    print(f"  dh-elliptic with its departure warning {paper:.3f} ms per point ({paper_alone:.3f} ms without); "
          f"one 200-point load curve {curve:.1f} ms")


def sweep(n):
    with tempfile.TemporaryDirectory() as tmp:
        argv = _CLI + ["sweep", "--beta0-linspace", "0.047", "1", str(n), "--mu-geomspace", "0.01", "100", str(n),
                       "--models", "md-elliptic", "--workers", "2", "--quiet", "--out", str(Path(tmp) / "map.nc")]
        t = time.perf_counter()
        proc = subprocess.run(argv, capture_output=True, text=True)
        wall = time.perf_counter() - t
    ok = proc.returncode == 0 and wall <= TARGET_SWEEP_S
    print(f"sweep: {n} x {n} md-elliptic map (beta0 0.047-1, mu 0.01-100) with dhfield sweep --workers 2: "
          f"{wall:.1f} s, exit {proc.returncode} (target <= {TARGET_SWEEP_S:g} s: {'PASS' if ok else 'FAIL'})")
    if proc.returncode:
        print(proc.stderr.strip()[-2000:])


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--map-n", type=int, default=200)
    ap.add_argument("--skip-sweep", action="store_true")
    args = ap.parse_args(argv)
    print(f"load average {os.getloadavg()[0]:.2f} on {os.cpu_count()} CPUs")
    ground_truth()
    jkr_limit()
    one_model()
    cost()
    if not args.skip_sweep:
        sweep(args.map_n)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
