"""Peak memory and wall time of a vectorised pull-off map (issue 9, item 7).

Run:  .venv/bin/python -m verification.bench_pulloff_memory [--n 200] [--chunk-mib 64]

Computes ``dhfield.models.dh_elliptic.pull_off`` on an n x n (mu, beta0) grid, mu log-spaced over
[0.01, 100] and beta0 over [0.3, 1], in a fresh subprocess (so the import and
the interpreter are counted and nothing else is), and prints the child's peak
resident set size (VmHWM) and wall time, side by side with a 1 x 1 call in the
same way (the interpreter + import baseline).  Target: <= 1 GiB peak for 200 x 200.
Exits 1 if the target is missed.
"""
from __future__ import annotations

import argparse
import json
import subprocess
import sys

TARGET_BYTES = 2**30

_CHILD = r"""
import json, sys, time
import numpy as np
import dhfield.core.pull_off_search as search
from dhfield.models import dh_elliptic as model
n, chunk = int(sys.argv[1]), int(sys.argv[2])
search.DEFAULT_CHUNK_BYTES = chunk
mu = np.geomspace(0.01, 100.0, n)[:, None]
beta0 = np.linspace(0.3, 1.0, n)[None, :]
t0 = time.perf_counter()
p = model.pull_off(mu=mu, beta0=beta0)
wall = time.perf_counter() - t0
ok = bool(np.all(np.isfinite(p.W_star)))
with open("/proc/self/status") as f:
    hwm = next(int(line.split()[1]) * 1024 for line in f if line.startswith("VmHWM"))
print(json.dumps({"wall": wall, "peak": hwm, "finite": ok}))
"""


def measure(n: int, chunk_bytes: int) -> dict:
    """Run the n x n map in a subprocess; return its wall time [s] and peak RSS [bytes]."""
    out = subprocess.run([sys.executable, "-c", _CHILD, str(n), str(chunk_bytes)], check=True,
                         capture_output=True, text=True)
    return json.loads(out.stdout.strip().splitlines()[-1])


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, default=200, help="grid points per axis (default 200)")
    ap.add_argument("--chunk-mib", type=int, default=64, help="chunk budget of the search [MiB]")
    args = ap.parse_args(argv)
    chunk = args.chunk_mib * 2**20
    base = measure(1, chunk)
    big = measure(args.n, chunk)
    print(f"pull_off map, load control, chunk budget {args.chunk_mib} MiB")
    print(f"{'case':24s} {'peak RSS':>12s} {'wall':>10s} {'per point':>12s}")
    print(f"{'1 x 1 (baseline)':24s} {base['peak'] / 2**20:9.1f}MiB {base['wall']:9.3f}s {'-':>12s}")
    npts = args.n * args.n
    print(f"{f'{args.n} x {args.n}':24s} {big['peak'] / 2**20:9.1f}MiB {big['wall']:9.1f}s "
          f"{big['wall'] / npts * 1e3:9.2f}ms")
    print(f"peak increment over baseline: {(big['peak'] - base['peak']) / 2**20:.1f} MiB; "
          f"all W* finite: {big['finite']}")
    passed = big["peak"] <= TARGET_BYTES
    print(f"target <= {TARGET_BYTES / 2**30:.0f} GiB peak: {'PASS' if passed else 'FAIL'}")
    return 0 if passed else 1


if __name__ == "__main__":
    sys.exit(main())
