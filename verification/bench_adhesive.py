"""Speed of the adhesive BEM against the open peers, side by side in one run (issue 8).

(a) **Path to the load-control pull-off, sphere (beta0 = 1), Dugdale, N = 256.**
    Ours: :func:`dhfield.bem.adhesive_pull_off` (free boundary, DC-FFT, symmetric
    quadrant) with ``search='located'``: the load minimum is located on the
    N/2, N/4, ... grids (the bracket search at N = 64 -- a cold start at the
    analytic DH pull-off approach from the DH cohesive zone, steps until the
    minimum is bracketed -- then three approaches of the lattice
    ``approach_max - j approach_step/2`` around the coarser minimum on every
    finer grid), and only 3-4 states are solved on the N grid.  Every state
    starts from the same approach solved on the grid half as fine
    (:class:`dhfield.bem.pull_off.NestedWarmStart`).  Its wall time includes
    the analytic DH prediction and the coarse solves.  ``search='bracket'``
    (the default of ``adhesive_pull_off``: the bracket search on the N grid
    itself, 4-6 states) is timed beside it.  Printed per run: wall and CPU
    seconds, states on the N grid, CG iterations and outer (zone) iterations
    per state, W*max and its error against Maugis-Dugdale.
    tamaas 2.9: ``PolonskyKeerRey`` with the gap as primal and dual variable plus
    ``MaugisAdhesionFunctional`` (Rey, Anciaux & Molinari 2017) on a *periodic*
    N x N domain of side 8 c_MD (c_MD: Maugis-Dugdale zone radius at pull-off);
    tamaas controls the mean gap, which plays the approach.  Two setups, and the
    ratio is taken against the faster *valid* one (tamaas' best equivalent):

    * ``bracket``: our search with tamaas as the state solver (one state at our
      ``approach_max`` to get onto the contact branch -- tamaas has no initial
      zone, and its cold start at the DH pull-off approach lands on the
      separated branch after 5000 iterations at lambda = 3 -- then the DH
      pull-off approach, steps until the load minimum is interior, parabolic
      vertex states);
    * ``march``: from our ``approach_max`` down by our approach step until two
      steps past the load minimum (the setup of the first session; no
      refinement: its pull-off is the discrete minimum).

    A third run, ``same states``, solves tamaas at ``approach_max`` and then at
    exactly the approaches our path solved, in our order (timing per state
    only: on the periodic domain the
    load minimum sits at another mean gap, so these samples do not bracket it
    and no pull-off is printed).

    Every tamaas run is followed by one more timed run of ours: each ratio pairs
    runs timed side by side (the load of a shared machine drifts over the
    minutes tamaas takes; measured: a single early run of ours against tamaas
    timed 2 min later gave 0.248 wall with a cpu ratio of 0.124).

    The pull-off of every run comes from the same estimator
    (:func:`dhfield.core.pull_off_search.refine_sampled_minimum` over its samples),
    in the paper's units (R = E* = dgamma = 1, sigma0 = mu, h0 = 1/mu), and its
    error is against Maugis-Dugdale.  CG iterations per state: ours from the
    path; tamaas' from its iteration log, recorded in an untimed replica run
    (which is also its warm-up).  ``--march`` adds our old marching path
    (``search='march'``, ~30 states) for reference.
(b) **Non-adhesive elliptical Hertz, N = 512** (beta = 0.7, a = 1, at the Hertz
    approach or load).  Two grids, each solver against the peer on the *same*
    grid:

    * 1.25 a x 1.25 b (ours free boundary, rectangular cells, ~410 cells across
      the contact): ContactMechanics ``FreeFFTElasticHalfSpace`` + hard wall
      (constrained CG, displacement control), same grid;
    * 8 a x 8 b (~64 cells across the contact): tamaas ``PolonskyKeerRey``
      (pressure primal, load control, periodic) and ours (free boundary) on the
      same cells.  (The first session compared tamaas on 8 a x 8 b with ours on
      1.25 a x 1.25 b: 6.4x more cells across the contact for ours, hence ~2.5x
      more CG iterations; that ratio is printed too, for continuity.)

    Printed: wall time, CG iterations, semi-axes and peak pressure against
    Hertz, ratios ours/peer (target <= 0.25).  On 8 a x 8 b our CG runs on the
    cells that can touch (those with a negative rigid gap z - delta: every
    influence coefficient is positive, so no other cell can; the same discrete
    problem, the gap completed on every cell); a second row times the CG on the
    whole quadrant for reference.  On the 8 a x 8 b cells each solver is timed
    ``HERTZ_REPEATS`` times and keeps its fastest run.  ``--skip path`` runs (b)
    only; ``--skip path contactmechanics`` drops ContactMechanics' 2 x ~80 s.

Every timing is one solve (part (b) on 8 a x 8 b: the fastest of
``HERTZ_REPEATS``) after an untimed warm-up (FFT plans, wisdom, caches),
all in this process, one after the other, with one OpenBLAS thread; tamaas gets
the same single thread (``--tamaas-threads 0`` gives it every core).  Wall
seconds are the measure; the process CPU seconds are printed beside them (on a
loaded machine they are the steadier figure).  The peers
are optional (``pip install -e '.[bench]'``); a missing one is skipped with a note.
Runtime: (a) ~2 min on a quiet 2-core machine, nearly all of it tamaas (``--march`` adds ~1 min per lambda).

Usage::

    .venv/bin/python -m verification.bench_adhesive [--quick] [--n-path 256] [--n-hertz 512] [--march]
"""
from __future__ import annotations

import os

# Before numpy loads OpenBLAS: its threads make the CG's dot products of 128 x 128 arrays take tens of
# ms instead of microseconds on a loaded 2-core machine (measured: Hertz N = 256 solve 7.2 s -> 0.9 s).
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import argparse
import contextlib
import math
import re
import sys
import tempfile
import time

import numpy as np

TARGET_PATH = 0.2
TARGET_HERTZ = 0.25
LAMBDAS = (1.0, 3.0)
#: Our load-control search in (a) (dhfield.bem.adhesive_pull_off); 'bracket' is timed beside it.
SEARCH = "located"
#: lambda = 1.1272 mu (dhfield.core.transition; same sigma0 in both models).
LAMBDA_PER_MU = 1.1272
#: Periodic side per MD zone radius for tamaas (issue 8: "a periodic domain 8x the zone").
TAMAAS_SIDE_PER_ZONE = 8.0
HERTZ_BETA = 0.7
#: Peers' tolerances, set to our nominal 1e-6 (dhfield.bem.DEFAULT_TOL); the definitions
#: differ (tamaas: relative complementarity error; ContactMechanics: penetration, here 1e-6 delta).
PEER_TOL = 1e-6
#: Hertz domains: half-widths per semi-axis of our accuracy grid, and tamaas' periodic side per semi-axis.
HERTZ_HALF_WIDTH = 1.25
HERTZ_PERIODIC_SIDE = 8.0
#: Timed runs per solver on the 8a x 8b cells (each side keeps its fastest; ~5 s in all).
HERTZ_REPEATS = 3


def _import(name):
    try:
        return __import__(name)
    except ImportError as exc:
        print(f"  note: {name} is not installed ({exc}); skipping it (pip install -e '.[bench]')")
        return None


def _verdict(ratio, target):
    return "PASS" if ratio <= target else "FAIL"


class _Seconds:
    """Wall and CPU (this process, all threads) seconds of one timed run."""

    def __init__(self, wall, cpu):
        self.wall, self.cpu = wall, cpu

    def __str__(self):
        return f"{self.wall:8.2f} {self.cpu:7.2f}"


def _now():
    return time.perf_counter(), time.process_time()


def _since(t0):
    return _Seconds(time.perf_counter() - t0[0], time.process_time() - t0[1])


@contextlib.contextmanager
def _captured_fds():
    """Capture what C++ code writes to file descriptors 1 and 2 (tamaas' iteration log)."""
    buf = {"text": ""}
    with tempfile.TemporaryFile(mode="w+b") as f:
        sys.stdout.flush()
        sys.stderr.flush()
        saved = os.dup(1), os.dup(2)
        os.dup2(f.fileno(), 1)
        os.dup2(f.fileno(), 2)
        try:
            yield buf
        finally:
            sys.stdout.flush()
            sys.stderr.flush()
            os.dup2(saved[0], 1)
            os.dup2(saved[1], 2)
            os.close(saved[0])
            os.close(saved[1])
            f.seek(0)
            buf["text"] = f.read().decode(errors="replace")


def _tamaas_iterations(text):
    """Iterations per solve from tamaas' log (one table 'Iter Cost_f Error' per solve)."""
    counts, last = [], None
    for line in text.splitlines():
        if line.strip().startswith("Iter"):
            if last is not None:
                counts.append(last + 1)
            last = None
            continue
        m = re.match(r"\s*(\d+)\s+\S+\s+\S+\s*$", line)
        if m:
            last = int(m.group(1))
    if last is not None:
        counts.append(last + 1)
    return counts


# --------------------------------------------------------------------------- (a) adhesive path
class _TamaasAdhesive:
    """tamaas' adhesive sphere on a periodic domain (one model and solver per run)."""

    def __init__(self, tm, mu, n, zone_radius, log=False):
        self.side = side = TAMAAS_SIDE_PER_ZONE * zone_radius
        self.model = tm.ModelFactory.createModel(tm.model_type.basic_2d, [side, side], [n, n])
        self.model.E, self.model.nu = 1.0, 0.0  # E* = E/(1 - nu^2) = 1
        x = (np.arange(n) - n / 2) * side / n
        xx, yy = np.meshgrid(x, x, indexing="ij")
        surface = -(xx**2 + yy**2) / 2.0  # rigid paraboloid, R = 1, apex at 0
        self.solver = tm.PolonskyKeerRey(self.model, surface, PEER_TOL, tm.PolonskyKeerRey.gap,
                                         tm.PolonskyKeerRey.gap)
        adhesion = tm.MaugisAdhesionFunctional(surface)
        adhesion.parameters = {"rho": 1.0 / mu, "surface_energy": 1.0}
        self.solver.addFunctionalTerm(adhesion)
        self.adhesion = adhesion  # keep alive
        self.solver.max_iter = 5000
        if log:
            self.solver.dump_freq = 1
        self.mean_z = float(-surface.mean())

    def load(self, approach):
        self.solver.solve(self.mean_z - approach)
        return float(self.model.traction.mean()) * self.side * self.side


def tamaas_same_states(tm, mu, n, zone_radius, approach_max, approaches, log=False):
    """tamaas at approach_max (its way onto the contact branch), then at our path's approaches in
    our order; returns (loads, seconds)."""
    run = _TamaasAdhesive(tm, mu, n, zone_radius, log=log)
    t0 = _now()
    loads = [run.load(d) for d in [approach_max, *approaches]]
    return np.array(loads), _since(t0)


def tamaas_bracket(tm, mu, n, zone_radius, approach_max, approach_guess, approach_step, log=False,
                   refine_levels=2, refine_factor=4, max_states=16):
    """tamaas with our load-control search: onto the contact branch at approach_max (a cold start
    at the guess lands on the separated branch at lambda = 3, after 5000 iterations), then at the
    DH guess, steps until the load minimum is interior, and parabolic vertex states (the logic of
    ``unloading_path`` with ``approach_guess``).

    Returns (approaches, loads, seconds, valid); not valid when the guess' state is off contact.
    The state at approach_max is solved and timed but not returned among the samples.
    """
    from dhfield.core.pull_off_search import refine_sampled_minimum

    run = _TamaasAdhesive(tm, mu, n, zone_radius, log=log)
    t0 = _now()
    run.load(approach_max)
    xs, ws = [approach_guess], [run.load(approach_guess)]
    valid = ws[0] < 0
    while valid and len(xs) < max_states:
        order = np.argsort(-np.array(xs))
        j = int(np.argmin(np.array(ws)[order]))
        if 0 < j < len(xs) - 1:
            break
        d = xs[order[0]] + approach_step if j == 0 else xs[order[-1]] - approach_step
        xs.append(d)
        ws.append(run.load(d))
        if ws[-1] >= 0:
            break
    xtol = approach_step / refine_factor**refine_levels
    for _ in range(refine_levels + 1 if valid else 0):
        order = np.argsort(-np.array(xs))
        x, w = np.array(xs)[order], np.array(ws)[order]
        sm = refine_sampled_minimum(x, w, first=False)
        if sm.at_boundary or float(np.min(np.abs(x - sm.x))) <= xtol:
            break
        xs.append(sm.x)
        ws.append(run.load(sm.x))
    return np.array(xs), np.array(ws), _since(t0), valid


def tamaas_march(tm, mu, n, zone_radius, approach_max, approach_step, log=False, max_states=120):
    """tamaas from approach_max down by approach_step to two steps past the load minimum."""
    run = _TamaasAdhesive(tm, mu, n, zone_radius, log=log)
    loads, approaches = [], []
    t0 = _now()
    for k in range(max_states):
        approaches.append(approach_max - k * approach_step)
        loads.append(run.load(approaches[-1]))
        i = int(np.argmin(loads))
        if loads[i] < 0 and len(loads) - 1 - i >= 2:
            break
    return np.array(approaches), np.array(loads), _since(t0)


def _w_star(approaches, loads):
    """Load-control pull-off W* (Eq. 34, sin(theta_skew) = 1) from samples, ours' estimator."""
    from dhfield.core.pull_off_search import refine_sampled_minimum

    order = np.argsort(-np.asarray(approaches), kind="stable")
    sm = refine_sampled_minimum(np.asarray(approaches)[order], np.asarray(loads)[order], first=False)
    return sm.y / (2.0 * math.pi)


def bench_path(n, lambdas, tm, march=False):
    from dhfield.analysis import compare
    from dhfield.bem import adhesive_pull_off
    from dhfield.analysis.bem_start import nondimensional_problem

    print(f"(a) path to the load-control pull-off, sphere, Dugdale, N = {n}")
    head = (f"    {'lambda':>6s} {'solver / setup':36s} {'wall s':>8s} {'cpu s':>7s} {'states':>6s} {'CG it/state':>11s} "
            f"{'outer/st':>9s} {'W*max':>9s} {'vs MD':>8s}")
    print(head)
    ratios = []
    for lam in lambdas:
        mu = lam / LAMBDA_PER_MU
        md = compare.pull_off("md", mu=mu, beta0=1.0)
        prob = nondimensional_problem(mu=mu, beta0=1.0, n=n)
        adhesive_pull_off(mu=mu, beta0=1.0, n=n, progress=False, search=SEARCH)   # warm-up: FFT plans, imports
        adhesive_pull_off(mu=mu, beta0=1.0, n=n, progress=False, search="bracket")

        def row(label, seconds, states, its, w, outer=None):
            err = f"{100 * (w / md['W_star'] - 1):+7.3f}%" if np.isfinite(w) else "    n/a"
            its_s = f"{its:11.1f}" if its is not None else f"{'n/a':>11s}"
            out_s = f"{outer:9.1f}" if outer is not None else f"{'n/a':>9s}"
            print(f"    {lam:6.2f} {label:36s} {seconds} {states:6d} {its_s} {out_s} {w:9.5f} {err}")

        def ours(label, search):
            t0 = _now()
            r = adhesive_pull_off(mu=mu, beta0=1.0, n=n, progress=False, search=search)
            t = _since(t0)
            row(label, t, r.n_steps, r.iterations / r.n_steps, r.W_star, float(np.mean(r.path.outer_iterations)))
            if r.path.coarse_states:
                print(f"           (+ {r.path.coarse_states} states, {r.path.coarse_iterations} CG iterations in all, "
                      f"on the N/2, N/4, ... grids; included in the seconds)")
            if not r.converged:
                print(f"           (unconverged states: {len(r.failures)})")
            return r, t

        res, t_ours = ours(f"dhfield {SEARCH} (free boundary)", SEARCH)
        ref, t_ref = ours("dhfield bracket (previous default)", "bracket")
        print(f"           {SEARCH} vs bracket: W* {res.W_star / ref.W_star - 1:+.2e} relative, "
              f"time ratio {t_ours.wall / t_ref.wall:.3f} (cpu {t_ours.cpu / t_ref.cpu:.3f})")
        if march:
            t0 = _now()
            old = adhesive_pull_off(mu=mu, beta0=1.0, n=n, progress=False, search="march")
            row("dhfield march (first session)", _since(t0), old.n_steps,
                old.iterations / old.n_steps, old.W_star, float(np.mean(old.path.outer_iterations)))
            print(f"           {SEARCH} vs march W*: {res.W_star / old.W_star - 1:+.2e} relative")
        if tm is None:
            continue
        zone = float(md["c_star"])
        approaches = res.path.approach
        # untimed replicas with the iteration log (also the warm-up of tamaas' FFT plans)
        tm.set_log_level(tm.LogLevel.info)
        with _captured_fds() as cap:
            tamaas_same_states(tm, mu, n, zone, prob.approach_max, approaches, log=True)
        it_same = _tamaas_iterations(cap["text"])
        with _captured_fds() as cap:
            tamaas_bracket(tm, mu, n, zone, prob.approach_max, prob.pull_off_approach, prob.approach_step,
                           log=True)
        it_bracket = _tamaas_iterations(cap["text"])
        with _captured_fds() as cap:
            tamaas_march(tm, mu, n, zone, prob.approach_max, prob.approach_step, log=True)
        it_march = _tamaas_iterations(cap["text"])
        tm.set_log_level(tm.LogLevel.error)
        def again():
            # ours once more, right after a tamaas run: each ratio pairs runs timed side by side
            t0 = _now()
            adhesive_pull_off(mu=mu, beta0=1.0, n=n, progress=False, search=SEARCH)
            return _since(t0)

        loads_s, t_same = tamaas_same_states(tm, mu, n, zone, prob.approach_max, approaches)
        t_ours_same = again()
        row("tamaas same states (periodic 8 c_MD)", t_same, len(loads_s),
            float(np.mean(it_same)) if it_same else None, float("nan"))
        d_b, loads_b, t_bracket, valid_b = tamaas_bracket(tm, mu, n, zone, prob.approach_max,
                                                          prob.pull_off_approach, prob.approach_step)
        t_ours_bracket = again()
        row("tamaas bracket (periodic 8 c_MD)", t_bracket, len(d_b) + 1,
            float(np.mean(it_bracket)) if it_bracket else None,
            _w_star(d_b, loads_b) if valid_b else float("nan"))
        if not valid_b:
            print(f"           tamaas' cold start at delta = {d_b[0]:+.4f} is not in contact "
                  f"(load {loads_b[0]:+.3g}): bracket setup not valid")
        d_m, loads_m, t_march = tamaas_march(tm, mu, n, zone, prob.approach_max, prob.approach_step)
        t_ours_march = again()
        row("tamaas march (periodic 8 c_MD)", t_march, len(d_m),
            float(np.mean(it_march)) if it_march else None, _w_star(d_m, loads_m))
        print(f"           dhfield {SEARCH} timed again right after each tamaas run (wall / cpu s): "
              f"same states {t_ours_same.wall:.2f} / {t_ours_same.cpu:.2f}, bracket {t_ours_bracket.wall:.2f} / "
              f"{t_ours_bracket.cpu:.2f}, march {t_ours_march.wall:.2f} / {t_ours_march.cpu:.2f}")
        best, ours_next, which = ((t_bracket, t_ours_bracket, "bracket")
                                  if (valid_b and t_bracket.wall <= t_march.wall)
                                  else (t_march, t_ours_march, "march"))
        r = ours_next.wall / best.wall
        ratios.append(r)
        per_state = (t_ours_same.wall / res.n_steps) / (t_same.wall / len(loads_s))
        print(f"    {lam:6.2f} time ratio dhfield/tamaas (tamaas' best: {which}; ours timed right after it) = "
              f"{r:.3f}  (target <= {TARGET_PATH})  {_verdict(r, TARGET_PATH)};  cpu ratio "
              f"{ours_next.cpu / best.cpu:.3f};  per state, same approaches: {per_state:.3f};  "
              f"vs tamaas march {t_ours_march.wall / t_march.wall:.3f}")
    return ratios


# --------------------------------------------------------------------------- (b) Hertz
def hertz_problem(n, half_width=HERTZ_HALF_WIDTH):
    from dhfield.models import hertz
    from dhfield.bem import Grid
    from dhfield.core.geometry import radius_ratio

    rho = float(radius_ratio(HERTZ_BETA))
    r1, r2 = math.sqrt(rho), 1.0 / math.sqrt(rho)  # R = sqrt(R'R'') = 1
    a, b = 1.0, HERTZ_BETA
    delta = float(hertz.approach(a, HERTZ_BETA))
    grid = Grid.centered(n, half_width * a, half_width_y=half_width * b)
    x, y = grid.mesh()
    z = x * x / (2 * r1) + y * y / (2 * r2)  # Eq. (2)
    p0 = float(hertz.max_pressure(a, HERTZ_BETA))
    load = float(hertz.load(a, HERTZ_BETA))
    return dict(grid=grid, z=z, delta=delta, p0=p0, load=load, r1=r1, r2=r2, a=a, b=b)


def _axes_from_pressure(p, x, y, dA):
    from dhfield.bem import Grid, mask_semi_axes

    g = Grid(p.shape[0], p.shape[1], x[1] - x[0], y[1] - y[0])
    return mask_semi_axes(p > 0, g)


def _errors(hp, a, b, p0):
    return (f"{100 * (a / hp['a'] - 1):+7.2f}% {100 * (b / hp['b'] - 1):+7.2f}% "
            f"{100 * (p0 / hp['p0'] - 1):+7.2f}%")


def _best_of(run, repeats):
    """(result, fastest _Seconds) of ``repeats`` timed runs (a 0.05 s solve is at the scheduler's mercy)."""
    best = None
    for _ in range(repeats):
        t0 = _now()
        out = run()
        t = _since(t0)
        if best is None or t.wall < best[1].wall:
            best = (out, t)
    return best


def _ours_hertz(hp, crop=True, repeats=1):
    from dhfield.bem import solve_adhesive, solver

    def run():
        return solve_adhesive(hp["z"], hp["grid"], hp["delta"], None)

    saved = solver.CROP_MAX_FRACTION
    solver.CROP_MAX_FRACTION = saved if crop else 0.0  # 0: the CG always runs on the whole quadrant
    try:
        run()  # warm-up: plans of this grid
        return _best_of(run, repeats)
    finally:
        solver.CROP_MAX_FRACTION = saved


def bench_hertz(n, cm_mod, tm, skip_cm=False):
    print(f"(b) non-adhesive elliptical Hertz, beta = {HERTZ_BETA}, N = {n}")
    print(f"    {'grid':13s} {'solver':38s} {'wall s':>8s} {'cpu s':>7s} {'CG it':>6s} {'a err':>8s} {'b err':>8s} "
          f"{'p0 err':>8s}")
    ratios = {}
    hp = hertz_problem(n)
    g = hp["grid"]
    st, t_ours = _ours_hertz(hp)
    a, b = st.contact_semi_axes()
    fine = f"{HERTZ_HALF_WIDTH:g}a x {HERTZ_HALF_WIDTH:g}b"
    print(f"    {fine:13s} {'dhfield (free, quadrant)':38s} {t_ours} {st.iterations:6d} "
          f"{_errors(hp, a, b, st.peak_pressure)}")
    if cm_mod is not None and not skip_cm:
        from ContactMechanics import make_system
        from SurfaceTopography import Topography

        lx, ly = g.nx * g.dx, g.ny * g.dy
        topo = Topography(-hp["z"], (lx, ly), periodic=False)  # rigid indenter heights, apex at 0

        def run_cm():
            system = make_system(surface=topo, substrate="free", young=1.0, fft="serial")
            system.minimize_proxy(offset=hp["delta"], pentol=PEER_TOL * hp["delta"])
            return system

        run_cm()
        t0 = _now()
        system = run_cm()
        t_cm = _since(t0)
        p = system.substrate.force / (g.dx * g.dy) if hasattr(system.substrate, "force") else None
        if p is not None:
            p = np.asarray(p)[: g.nx, : g.ny]
            ca, cb = _axes_from_pressure(p, g.x, g.y, g.dx * g.dy)
            acc = _errors(hp, ca, cb, p.max())
        else:
            acc = "(fields not exposed)"
        print(f"    {fine:13s} {'ContactMechanics (free, same grid)':38s} {t_cm} {'n/a':>6s} {acc}")
        ratios["ContactMechanics (same grid)"] = (t_ours.wall / t_cm.wall, t_ours.cpu / t_cm.cpu)
    if tm is not None:
        hp8 = hertz_problem(n, HERTZ_PERIODIC_SIDE / 2.0)
        st8, t_ours8 = _ours_hertz(hp8, repeats=HERTZ_REPEATS)
        a8, b8 = st8.contact_semi_axes()
        coarse = f"{HERTZ_PERIODIC_SIDE:g}a x {HERTZ_PERIODIC_SIDE:g}b"
        print(f"    {coarse:13s} {'dhfield (free, quadrant)':38s} {t_ours8} {st8.iterations:6d} "
              f"{_errors(hp8, a8, b8, st8.peak_pressure)}")
        st8f, t_full8 = _ours_hertz(hp8, crop=False, repeats=HERTZ_REPEATS)
        a8f, b8f = st8f.contact_semi_axes()
        print(f"    {coarse:13s} {'dhfield, CG on the whole quadrant':38s} {t_full8} {st8f.iterations:6d} "
              f"{_errors(hp8, a8f, b8f, st8f.peak_pressure)}")
        lx, ly = HERTZ_PERIODIC_SIDE * hp["a"], HERTZ_PERIODIC_SIDE * hp["b"]
        xx, yy = np.meshgrid((np.arange(n) - n / 2) * lx / n, (np.arange(n) - n / 2) * ly / n, indexing="ij")
        surface = -(xx**2 / (2 * hp["r1"]) + yy**2 / (2 * hp["r2"]))

        def run_tm(log=False):  # a fresh model each time: no warm start from the warm-up solve
            model = tm.ModelFactory.createModel(tm.model_type.basic_2d, [lx, ly], [n, n])
            model.E, model.nu = 1.0, 0.0
            solver = tm.PolonskyKeerRey(model, surface, PEER_TOL)
            if log:
                solver.dump_freq = 1
            solver.solve(hp["load"] / (lx * ly))
            return np.array(model.traction, copy=True)

        tm.set_log_level(tm.LogLevel.info)
        with _captured_fds() as cap:
            run_tm(log=True)                   # untimed: iteration count, and the warm-up
        tm.set_log_level(tm.LogLevel.error)
        its = _tamaas_iterations(cap["text"])
        p, t_tm = _best_of(run_tm, HERTZ_REPEATS)
        ta, tb = _axes_from_pressure(p, xx[:, 0], yy[0], 1.0)
        print(f"    {coarse:13s} {'tamaas (periodic, same cells, same load)':38s} {t_tm} "
              f"{(its[0] if its else 0):6d} {_errors(hp, ta, tb, p.max())}")
        ratios["tamaas (same grid)"] = (t_ours8.wall / t_tm.wall, t_ours8.cpu / t_tm.cpu)
        print(f"    (without the crop, the CG on the whole quadrant: ratio {t_full8.wall / t_tm.wall:.3f}; "
              f"loads {st8.load:.8f} cropped, {st8f.load:.8f} whole quadrant, Hertz {hp8['load']:.8f})")
        print(f"    (first session's pairing, ours on {fine} vs tamaas on {coarse}: ratio {t_ours.wall / t_tm.wall:.3f})")
    for name, (r, rc) in ratios.items():
        print(f"    time ratio dhfield/{name} = {r:.3f}  (target <= {TARGET_HERTZ})  {_verdict(r, TARGET_HERTZ)};  "
              f"cpu ratio {rc:.3f}")
    return ratios


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--quick", action="store_true", help="N = 128 path, N = 256 Hertz, lambda = 1 only")
    p.add_argument("--n-path", type=int, default=256)
    p.add_argument("--n-hertz", type=int, default=512)
    p.add_argument("--lambdas", type=float, nargs="+", default=list(LAMBDAS))
    p.add_argument("--march", action="store_true", help="also time our marching path (search='march')")
    p.add_argument("--skip", nargs="*", default=[], choices=["path", "hertz", "contactmechanics"],
                   help="parts to skip ('--skip path' runs only (b); 'contactmechanics' drops its ~2 x 80 s "
                        "Hertz solves from (b))")
    p.add_argument("--tamaas-threads", type=int, default=1,
                   help="tamaas threads (default 1, like ours: one FFTW and one OpenBLAS thread; 0 = tamaas' default, "
                        "all cores)")
    args = p.parse_args(argv)
    if args.quick:
        args.n_path, args.n_hertz, args.lambdas = 128, 256, [1.0]
    tm = _import("tamaas")
    if tm is not None:
        tm.set_log_level(tm.LogLevel.error)
        tm.initialize(args.tamaas_threads)
    print(f"threads: dhfield 1 (FFTW, OpenBLAS); tamaas {args.tamaas_threads or 'all cores'}; "
          f"{os.cpu_count()} cores; wall s is the measure, cpu s (this process) is printed beside it")
    cm_mod = _import("ContactMechanics")
    t_start = time.perf_counter()
    if "path" not in args.skip:
        bench_path(args.n_path, args.lambdas, tm, march=args.march)
    if "hertz" not in args.skip:
        bench_hertz(args.n_hertz, cm_mod, tm, skip_cm="contactmechanics" in args.skip)
    print(f"(benchmark wall time {time.perf_counter() - t_start:.0f} s)")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
