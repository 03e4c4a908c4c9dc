"""Krylov iterations of the Newton system's contact rows: the inverse symbol against inner CG (issue 38).

For a saved converged state (``verification.save_state``) this builds, at that state,
(a) the contact-only system ``c K_AA x = b`` and (b) the full Newton Jacobian on the contact and
edge cells (:class:`dhfield.bem.newton._Jacobian`, undamped), and solves each by flexible GMRES
(restart 200; with a fixed preconditioner it is GMRES) right-preconditioned on the contact rows by
``--inner k``: 0 the inverse symbol (today's), k > 0 k iterations of CG on ``K_AA`` preconditioned
by the inverse symbol (``SolverOptions.contact_inner``); ``--floor 1``: the symbol floored at its highest
frequencies' value (``SolverOptions.symbol_floor``).  It prints the iterations to the relative
residuals 1e-2, 1e-4, 1e-6, the operator applications (K; the symbol's FFTs cost about the same)
and the wall time.  Right-hand sides: ``rand`` (standard normal, seed 0) and ``slope`` (the
load-slope system dq/d delta of :func:`dhfield.bem.newton.load_slope`).

Usage::

    python -m verification.save_state 1.0 5 320 3 /tmp/sph5.npz
    python -m verification.bench_contact_precond /tmp/sph5.npz --inner 0 3 10
    python -m verification.bench_contact_precond /tmp/mu10.npz --inner 0 --floor 0 1 --rhs rand
"""
from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from verification.bench_nested import _problem  # noqa: E402

TOLS = (1e-2, 1e-4, 1e-6)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("states", nargs="+", help="npz files of verification.save_state")
    ap.add_argument("--inner", nargs="*", type=int, default=[0, 3, 10])
    ap.add_argument("--rhs", nargs="*", default=["rand", "slope"], choices=("rand", "slope"))
    ap.add_argument("--systems", nargs="*", default=["contact", "jacobian"], choices=("contact", "jacobian"))
    ap.add_argument("--floor", nargs="*", type=int, default=[0], help="symbol_preconditioner(floor=...) 0/1")
    ap.add_argument("--maxiter", type=int, default=3000)
    args = ap.parse_args(argv)
    from dhfield.bem import newton

    print(f"{'state':<22} {'system':<9} {'rhs':<6} {'precond':<10} {'it 1e-2':>8} {'1e-4':>6} {'1e-6':>6} "
          f"{'K calls':>8} {'wall s':>7} {'true res':>9}", flush=True)
    for path in args.states:
        d = np.load(path)
        beta0, mu, n = float(d["beta0"]), float(d["mu"]), int(d["n"])
        P = _problem(beta0, mu, n)
        prob = P.adhesive_problem(1)
        q, delta = d["traction"], float(d["delta"])
        law = newton._Law(prob.law, prob.min_spread)
        h, p = newton._state(prob, law, delta, q)
        c = law.sigma0 / law.h0
        res = float(np.max(np.abs(newton._residual(h, p, c)))) / law.sigma0
        contact = c * h < p
        slope = law.slope(h)
        edge = (~contact) & (slope > 0.0)
        pres = {f: newton.symbol_preconditioner(prob.grid, prob.symmetric, newton._modulus(prob), floor=bool(f))
                for f in args.floor}
        name = f"b{beta0:g} mu{mu:g} {prob.grid.nx}^2"
        print(f"# {name}: residual {res:.1e}, contact {int(contact.sum())}, edge {int(edge.sum())}", flush=True)
        for system in args.systems:
            e = edge if system == "jacobian" else np.zeros_like(edge)
            for rhs_kind in args.rhs:
                for k, f in [(k, f) for f in args.floor for k in args.inner]:
                    pre = pres[f]
                    jac = newton._Jacobian(prob.op, contact, e, slope, pre, gap_scale=c, inner=k)
                    if rhs_kind == "rand":
                        b = np.random.default_rng(0).standard_normal(jac.idx.size)
                    else:
                        b = np.where(contact, c, -slope).ravel()[jac.idx]
                    hist = []
                    t0 = time.perf_counter()
                    x, its, info = newton.fgmres(jac.matvec, jac.right, b, TOLS[-1], args.maxiter, history=hist)
                    wall = time.perf_counter() - t0
                    calls = jac.calls
                    true = float(np.linalg.norm(b - jac.matvec(x)) / np.linalg.norm(b))
                    hist = np.array(hist)
                    at = [str(int(np.argmax(hist <= t)) + 1) if np.any(hist <= t) else ">" + str(its) for t in TOLS]
                    label = ("symbol" if k == 0 else f"cg{k}") + ("+floor" if f else "")
                    print(f"{name:<22} {system:<9} {rhs_kind:<6} {label:<10} {at[0]:>8} {at[1]:>6} {at[2]:>6} "
                          f"{calls:>8} {wall:>7.1f} {true:>9.1e}", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
