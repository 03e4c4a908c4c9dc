"""``dhfield solve``: the self-consistent adhesive BEM pull-off of one (beta0, mu) case."""
from __future__ import annotations

import sys

from ._common import add_model_arguments, print_json

#: Exit status when a state of the path did not converge (the result is still printed/written, flagged).
EXIT_UNCONVERGED = 3
#: Exit status when the case cannot be resolved within the memory or time available (or the given
#: --n is far too coarse for it): one line, before solving, with the N it needs and the analytic value.
EXIT_UNRESOLVABLE = 4

_EPILOG = (f"exit status: 0 success (a note on stderr if states beyond the pull-off did not converge); "
           f"2 invalid input (one line on stderr); {EXIT_UNCONVERGED} a state of the path up to the pull-off "
           "did not converge (one line on stderr naming the parameters; the result is still printed and "
           "written, with converged = false); "
           f"{EXIT_UNRESOLVABLE} the case cannot be resolved within the memory or time available, or --n is far "
           "too coarse for it (one line, before solving: the n it needs, its estimated memory and time, and the "
           "analytic W* to use instead)")


def add_parser(sub) -> None:
    p = sub.add_parser("solve", help="self-consistent adhesive BEM (Dugdale) pull-off of the elliptical contact",
                       description="Displacement-controlled loading/unloading path of the adhesive elliptical "
                                   "contact on a free-boundary DC-FFT grid (dhfield.bem.adhesive_pull_off); "
                                   "W* in the normalisation of Eq. (34), semi-axes in c_r (Eq. 32) from the "
                                   "second moments of the contact and adhesive masks.",
                       epilog=_EPILOG)
    add_model_arguments(p)
    p.add_argument("--n", type=int, default=None,
                   help="cells per axis (even, >= 8; default: chosen from the Dugdale zone width and memory)")
    p.add_argument("--law", default="dugdale", choices=("dugdale", "exponential"),
                   help="traction law, sigma0 = mu and dgamma = 1 (default dugdale)")
    p.add_argument("--control", default="load", choices=("load", "displacement"),
                   help="load: minimum of the unloading force; displacement: the jump (default load)")
    p.add_argument("--search", default="located", choices=("located", "bracket", "march"),
                   help="load control: how the force minimum is found -- located on coarser grids first, "
                        "then 3-4 states on this one (default); bracket: from the analytic pull-off on this "
                        "grid; march: unload in uniform steps (slowest)")
    p.add_argument("--threads", type=int, default=None, help="FFTW threads (default $DHFIELD_THREADS or 1)")
    p.add_argument("--out", default=None, help="netCDF file for the pull-off fields and the path")
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.set_defaults(func=run)


def _record(res) -> dict:
    from ..schema import BEM_ADHESIVE_KEYS

    d = res.as_dict()
    out = {"beta0": d["beta0"], "mu": d["mu"], "n": d["n"], "law": d["law"], "control": d["control"]}
    out.update({k: d[k] for k in BEM_ADHESIVE_KEYS})
    out.update(W_star_error=d["W_star_error"], residual=d["residual"], elapsed=d["elapsed"],
               failures=d["failures"], note=d["note"], search=d["search"])
    return out


def run(args) -> int:
    from ..bem import adhesive_pull_off
    from ..io import check_writable

    if args.out is not None:
        check_writable(args.out)
    if args.threads is not None and args.threads < 1:
        raise ValueError(f"threads must be an integer >= 1; got {args.threads}")
    from ..adhesive_start import UnresolvableCaseError, plan_grid

    plan = plan_grid(args.mu, args.beta0, args.n, law=args.law)
    if args.n is not None and plan.too_coarse:   # far too coarse: refused before minutes of unconverged states
        print(f"dhfield: solve refused: {plan.message()}", file=sys.stderr)
        return EXIT_UNRESOLVABLE
    where = (f"beta0={args.beta0:g}, mu={args.mu:g}, n={plan.n}, law={args.law}, control={args.control}")
    try:
        res = adhesive_pull_off(args.mu, args.beta0, args.n, law=args.law, control=args.control,
                                threads=args.threads, progress=None, search=args.search)
    except UnresolvableCaseError as exc:
        print(f"dhfield: solve refused: {exc}", file=sys.stderr)
        return EXIT_UNRESOLVABLE
    except RuntimeError as exc:  # the solver found no converged state to report
        print(f"dhfield: solve did not converge for {where}: {' '.join(str(exc).split())}", file=sys.stderr)
        return EXIT_UNCONVERGED
    if args.out is not None:
        from ..io.solution import write_solution

        write_solution(res, args.out)
    rec = _record(res)
    if args.json:
        print_json(rec)
    else:
        print(f"beta0 = {res.beta0:g}, mu = {res.mu:g}, N = {res.n}, {res.law}, {res.control} control")
        err = f" (fold fit error ~{res.W_star_error:.2g})" if res.W_star_error == res.W_star_error else ""
        print(f"W* = {res.W_star:.6f}{err}  a* = {res.a_star:.5f}  b* = {res.b_star:.5f}  c* = {res.c_star:.5f}  "
              f"d* = {res.d_star:.5f}")
        print(f"beta_ab = {res.beta_ab:.5f}  beta_cd = {res.beta_cd:.5f}  delta* = {res.delta_star:.5f}")
        print(f"converged = {res.converged}  states = {res.n_steps}  CG iterations = {res.iterations}  "
              f"search = {res.search}  ({res.elapsed:.1f} s)")
        if args.out is not None:
            print(f"wrote {args.out}")
    if not res.converged:
        worst = max((f.get("residual", float("nan")) for f in res.failures), default=res.residual)
        why = (f"{len(res.failures)} unconverged state(s), worst residual {worst:.3g}" if res.failures
               else res.note)
        print(f"dhfield: solve did not converge for {where}: {why}", file=sys.stderr)
        return EXIT_UNCONVERGED
    if res.note:
        print(f"dhfield: note: {where}: {res.note}", file=sys.stderr)
    if res.failures:
        print(f"dhfield: note: {len(res.failures)} state(s) beyond the pull-off did not converge for {where} "
              "(the pull-off is not affected; listed under failures)", file=sys.stderr)
    return 0
