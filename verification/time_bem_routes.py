"""Wall and CPU time of the BEM pull-off routes of one checkout, best of 2 (compare two checkouts side by side).

    git worktree add /tmp/bem-base e9f3b2e
    for t in /tmp/bem-base $PWD; do DHFIELD_THREADS=1 .venv/bin/python verification/time_bem_routes.py $t; done

argv[1]: the checkout whose dhfield is timed (put first on sys.path).  About 30 s per checkout.
"""
import sys, time
sys.path.insert(0, sys.argv[1])
from dhfield.core import transition
from dhfield.bem import adhesive_pull_off
cases = [("located N=256 lam=3", 3.0, 256, dict(search="located")),
         ("bracket N=128 lam=3", 3.0, 128, dict(search="bracket")),
         ("march N=64 lam=1", 1.0, 64, dict(search="march")),
         ("displacement N=64 lam=2", 2.0, 64, dict(control="displacement"))]
adhesive_pull_off(mu=1.0, beta0=1.0, n=64, progress=False)  # warm-up
for label, lam, n, kw in cases:
    mu = float(transition.tabor_from_maugis(lam))
    best = None
    for _ in range(2):
        t, c = time.perf_counter(), time.process_time()
        r = adhesive_pull_off(mu=mu, beta0=1.0, n=n, progress=False, **kw)
        w, cp = time.perf_counter() - t, time.process_time() - c
        best = (w, cp) if best is None or w < best[0] else best
    print(f"{label:26s} wall {best[0]:7.2f} s  cpu {best[1]:7.2f} s  W*={r.W_star:.10f}", flush=True)
