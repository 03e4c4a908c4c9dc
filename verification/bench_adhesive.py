"""Speed of the adhesive BEM against the open peers, side by side in one run (issue 8).

(a) **Unloading path to pull-off, sphere (beta0 = 1), Dugdale, N = 256.**  Ours:
    :func:`dhfield.bem.adhesive_pull_off` (free boundary, DC-FFT, symmetric
    quadrant, steps refined at the force minimum).  tamaas 2.9: ``PolonskyKeerRey``
    with the gap as primal and dual variable plus ``MaugisAdhesionFunctional``
    (Rey, Anciaux & Molinari 2017) on a *periodic* N x N domain of side 8 c_MD
    (c_MD: Maugis-Dugdale zone radius at pull-off), unloaded with our approach
    step from our starting approach until two steps past the force minimum
    (tamaas controls the mean gap; on a periodic domain it plays the approach).
    Both paths run to the pull-off, in the paper's units (R = E* = dgamma = 1,
    sigma0 = mu, h0 = 1/mu).  Printed: wall time, states, CG iterations per
    state (ours; tamaas does not expose them), the pull-off error against
    Maugis-Dugdale for lambda = 1 and 3, and the time ratio ours/tamaas
    (target <= 0.2).
(b) **Non-adhesive elliptical Hertz, N = 512** (beta = 0.7, a = 1, displacement
    control at the Hertz approach).  Ours: :func:`dhfield.bem.solve_adhesive`
    with ``law=None`` on rectangular cells over 1.25 a x 1.25 b.
    ContactMechanics: ``FreeFFTElasticHalfSpace`` + hard wall (constrained CG) on
    the same grid.  tamaas: ``PolonskyKeerRey`` (pressure primal) on a periodic
    domain 8 a x 8 b at our load.  Printed: wall time, semi-axes and peak
    pressure against Hertz, ratios ours/peer (target <= 0.25).

Every timing is one solve after an untimed warm-up of the same problem (FFT plans,
wisdom, caches), all in this process, one after the other.  The peers are optional
(``pip install -e '.[bench]'``); a missing one is skipped with a printed note.

Usage::

    .venv/bin/python -m verification.bench_adhesive [--quick] [--n-path 256] [--n-hertz 512]
"""
from __future__ import annotations

import os

# Before numpy loads OpenBLAS: its threads make the CG's dot products of 128 x 128 arrays take tens of
# ms instead of microseconds on a loaded 2-core machine (measured: Hertz N = 256 solve 7.2 s -> 0.9 s).
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import argparse
import math
import time

import numpy as np

TARGET_PATH = 0.2
TARGET_HERTZ = 0.25
LAMBDAS = (1.0, 3.0)
#: lambda = 1.1272 mu (dhfield.transition; same sigma0 in both models).
LAMBDA_PER_MU = 1.1272
#: Periodic side per MD zone radius for tamaas (issue 8: "a periodic domain 8x the zone").
TAMAAS_SIDE_PER_ZONE = 8.0
HERTZ_BETA = 0.7
#: Peers' tolerances, set to our nominal 1e-6 (dhfield.bem.adhesive.DEFAULT_TOL); the definitions
#: differ (tamaas: relative complementarity error; ContactMechanics: penetration, here 1e-6 delta).
PEER_TOL = 1e-6


def _import(name):
    try:
        return __import__(name)
    except ImportError as exc:
        print(f"  note: {name} is not installed ({exc}); skipping it (pip install -e '.[bench]')")
        return None


def _timed(fn, warmup=True):
    if warmup:
        fn()
    t0 = time.perf_counter()
    out = fn()
    return out, time.perf_counter() - t0


# --------------------------------------------------------------------------- (a) adhesive path
def ours_path(mu, n):
    from dhfield.bem import adhesive_pull_off

    return adhesive_pull_off(mu, 1.0, n, progress=False)


def tamaas_path(tm, mu, n, approach_max, approach_step, zone_radius, max_states=120):
    """tamaas unloading path on a periodic domain; returns (W*min, states, seconds)."""
    side = TAMAAS_SIDE_PER_ZONE * zone_radius
    model = tm.ModelFactory.createModel(tm.model_type.basic_2d, [side, side], [n, n])
    model.E, model.nu = 1.0, 0.0  # E* = E/(1 - nu^2) = 1
    x = (np.arange(n) - n / 2) * side / n
    xx, yy = np.meshgrid(x, x, indexing="ij")
    surface = -(xx**2 + yy**2) / 2.0  # rigid paraboloid, R = 1, apex at 0
    solver = tm.PolonskyKeerRey(model, surface, PEER_TOL, tm.PolonskyKeerRey.gap, tm.PolonskyKeerRey.gap)
    adhesion = tm.MaugisAdhesionFunctional(surface)
    adhesion.parameters = {"rho": 1.0 / mu, "surface_energy": 1.0}
    solver.addFunctionalTerm(adhesion)
    solver.max_iter = 5000
    mean_z = float(-surface.mean())
    loads = []
    t0 = time.perf_counter()
    for k in range(max_states):
        delta = approach_max - k * approach_step
        solver.solve(mean_z - delta)
        loads.append(float(model.traction.mean()) * side * side)
        i = int(np.argmin(loads))
        if loads[i] < 0 and len(loads) - 1 - i >= 2:
            break
    el = time.perf_counter() - t0
    return min(loads) / (2.0 * math.pi), len(loads), el  # Eq. (34), sin(theta_skew) = 1


def bench_path(n, lambdas, tm):
    from dhfield import compare
    from dhfield.bem.adhesive import nondimensional_problem

    print(f"(a) unloading path to pull-off, sphere, Dugdale, N = {n}")
    print(f"    {'lambda':>6s} {'solver':28s} {'seconds':>9s} {'states':>7s} {'CG it/state':>11s} "
          f"{'W*max':>9s} {'vs MD':>8s}")
    ratios = []
    for lam in lambdas:
        mu = lam / LAMBDA_PER_MU
        md = compare.pull_off("md", mu, 1.0)
        res, t_ours = _timed(lambda: ours_path(mu, n))
        err = res.W_star / md["W_star"] - 1.0
        print(f"    {lam:6.2f} {'dhfield (free boundary)':28s} {t_ours:9.2f} {res.n_steps:7d} "
              f"{res.iterations / max(res.n_steps, 1):11.1f} {res.W_star:9.5f} {100 * err:+7.2f}%"
              f"{'' if res.converged else '  (unconverged states: ' + str(len(res.failures)) + ')'}")
        if tm is None:
            continue
        prob = nondimensional_problem(mu, 1.0, n)
        args = (tm, mu, n, prob.approach_max, prob.approach_step, float(md["c_star"]))
        (w_tm, k_tm, _), t_tm = _timed(lambda: tamaas_path(*args))
        print(f"    {lam:6.2f} {'tamaas (periodic, 8 c_MD)':28s} {t_tm:9.2f} {k_tm:7d} {'n/a':>11s} "
              f"{w_tm:9.5f} {100 * (w_tm / md['W_star'] - 1):+7.2f}%")
        ratios.append(t_ours / t_tm)
        per_state = (t_ours / res.n_steps) / (t_tm / k_tm)
        print(f"    {lam:6.2f} time ratio dhfield/tamaas = {t_ours / t_tm:.3f}  (target <= {TARGET_PATH})  "
              f"{'PASS' if t_ours / t_tm <= TARGET_PATH else 'FAIL'};  per state {per_state:.3f} "
              f"({res.n_steps} vs {k_tm} states: ours loads, unloads to the jump and refines the minimum)")
    return ratios


# --------------------------------------------------------------------------- (b) Hertz
def _hertz_problem(n):
    from dhfield import hertz
    from dhfield.bem import Grid
    from dhfield.geometry import radius_ratio

    rho = float(radius_ratio(HERTZ_BETA))
    r1, r2 = math.sqrt(rho), 1.0 / math.sqrt(rho)  # R = sqrt(R'R'') = 1
    a, b = 1.0, HERTZ_BETA
    delta = float(hertz.approach(a, HERTZ_BETA))
    grid = Grid.centered(n, 1.25 * a, half_width_y=1.25 * b)
    x, y = grid.mesh()
    z = x * x / (2 * r1) + y * y / (2 * r2)  # Eq. (2)
    p0 = float(hertz.max_pressure(a, HERTZ_BETA))
    load = float(hertz.load(a, HERTZ_BETA))
    return dict(grid=grid, z=z, delta=delta, p0=p0, load=load, r1=r1, r2=r2, a=a, b=b)


def _axes_from_pressure(p, x, y, dA):
    from dhfield.bem import Grid, mask_semi_axes

    g = Grid(p.shape[0], p.shape[1], x[1] - x[0], y[1] - y[0])
    return mask_semi_axes(p > 0, g)


def bench_hertz(n, cm_mod, tm):
    from dhfield.bem import solve_adhesive

    hp = _hertz_problem(n)
    g = hp["grid"]
    print(f"(b) non-adhesive elliptical Hertz, beta = {HERTZ_BETA}, N = {n}")
    print(f"    {'solver':36s} {'seconds':>9s} {'a err':>8s} {'b err':>8s} {'p0 err':>8s}")
    st, t_ours = _timed(lambda: solve_adhesive(hp["z"], g, hp["delta"], None))
    a, b = st.contact_semi_axes()
    print(f"    {'dhfield (free, quadrant, 1.25a x 1.25b)':36s} {t_ours:9.3f} {100 * (a / hp['a'] - 1):+7.2f}% "
          f"{100 * (b / hp['b'] - 1):+7.2f}% {100 * (st.peak_pressure / hp['p0'] - 1):+7.2f}%")
    ratios = {}
    if cm_mod is not None:
        from ContactMechanics import make_system
        from SurfaceTopography import Topography

        lx, ly = g.nx * g.dx, g.ny * g.dy
        topo = Topography(-hp["z"], (lx, ly), periodic=False)  # rigid indenter heights, apex at 0

        def run_cm():
            system = make_system(surface=topo, substrate="free", young=1.0, fft="serial")
            system.minimize_proxy(offset=hp["delta"], pentol=PEER_TOL * hp["delta"])
            return system

        system, t_cm = _timed(run_cm)
        p = system.substrate.force / (g.dx * g.dy) if hasattr(system.substrate, "force") else None
        if p is not None:
            p = np.asarray(p)[: g.nx, : g.ny]
            ca, cb = _axes_from_pressure(p, g.x, g.y, g.dx * g.dy)
            acc = (f"{100 * (ca / hp['a'] - 1):+7.2f}% {100 * (cb / hp['b'] - 1):+7.2f}% "
                   f"{100 * (p.max() / hp['p0'] - 1):+7.2f}%")
        else:
            acc = "(fields not exposed)"
        print(f"    {'ContactMechanics (free, same grid)':36s} {t_cm:9.3f} {acc}")
        ratios["ContactMechanics"] = t_ours / t_cm
    if tm is not None:
        lx, ly = 8.0 * hp["a"], 8.0 * hp["b"]
        xx, yy = np.meshgrid((np.arange(n) - n / 2) * lx / n, (np.arange(n) - n / 2) * ly / n, indexing="ij")
        surface = -(xx**2 / (2 * hp["r1"]) + yy**2 / (2 * hp["r2"]))

        def run_tm():  # a fresh model each time: no warm start from the warm-up solve
            model = tm.ModelFactory.createModel(tm.model_type.basic_2d, [lx, ly], [n, n])
            model.E, model.nu = 1.0, 0.0
            solver = tm.PolonskyKeerRey(model, surface, PEER_TOL)
            solver.solve(hp["load"] / (lx * ly))
            return np.array(model.traction, copy=True)

        p, t_tm = _timed(run_tm)
        ta, tb = _axes_from_pressure(p, xx[:, 0], yy[0], 1.0)
        print(f"    {'tamaas (periodic 8a x 8b, same load)':36s} {t_tm:9.3f} {100 * (ta / hp['a'] - 1):+7.2f}% "
              f"{100 * (tb / hp['b'] - 1):+7.2f}% {100 * (p.max() / hp['p0'] - 1):+7.2f}%")
        ratios["tamaas"] = t_ours / t_tm
    for name, r in ratios.items():
        print(f"    time ratio dhfield/{name} = {r:.3f}  (target <= {TARGET_HERTZ})  "
              f"{'PASS' if r <= TARGET_HERTZ else 'FAIL'}")
    return ratios


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--quick", action="store_true", help="N = 128 path, N = 256 Hertz, lambda = 1 only")
    p.add_argument("--n-path", type=int, default=256)
    p.add_argument("--n-hertz", type=int, default=512)
    p.add_argument("--lambdas", type=float, nargs="+", default=list(LAMBDAS))
    p.add_argument("--skip", nargs="*", default=[], choices=["path", "hertz"], help="parts to skip")
    args = p.parse_args(argv)
    if args.quick:
        args.n_path, args.n_hertz, args.lambdas = 128, 256, [1.0]
    tm = _import("tamaas")
    if tm is not None:
        tm.set_log_level(tm.LogLevel.error)
    cm_mod = _import("ContactMechanics")
    if "path" not in args.skip:
        bench_path(args.n_path, args.lambdas, tm)
    if "hertz" not in args.skip:
        bench_hertz(args.n_hertz, cm_mod, tm)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
