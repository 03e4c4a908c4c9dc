"""Benchmark: dhfield's netCDF writer (netCDF4 in slabs, signals deferred) against xarray's to_netcdf.

Both write the same Dataset (``--vars`` float64 variables of ``--n`` x ``--n``) to
the same directory, alternately, ``--repeat`` times; the script prints the best
time of each and their ratio, and checks that the two files read back equal.

    python verification/bench_io.py [--n 2048] [--vars 8] [--repeat 3]
"""
from __future__ import annotations

import argparse
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
if str(ROOT) not in sys.path:
    sys.path.insert(0, str(ROOT))

import numpy as np  # noqa: E402
import xarray as xr  # noqa: E402

from dhfield.io import read_netcdf, write_netcdf  # noqa: E402
from dhfield.io.cf import finalize  # noqa: E402


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, default=2048)
    ap.add_argument("--vars", type=int, default=8)
    ap.add_argument("--repeat", type=int, default=3)
    args = ap.parse_args(argv)
    rng = np.random.default_rng(0)
    n = args.n
    ds = xr.Dataset({f"v{i}": (("x", "y"), rng.random((n, n)), {"units": "1", "long_name": f"v{i}"})
                     for i in range(args.vars)},
                    coords={"x": ("x", np.arange(n) * 1.0, {"units": "m"}), "y": ("y", np.arange(n) * 1.0, {"units": "m"})})
    best = {"dhfield.io.write_netcdf": np.inf, "xarray to_netcdf": np.inf}
    with tempfile.TemporaryDirectory() as tmp:
        a, b = Path(tmp) / "a.nc", Path(tmp) / "b.nc"
        for _ in range(args.repeat):
            t = time.perf_counter()
            write_netcdf(ds, a)
            best["dhfield.io.write_netcdf"] = min(best["dhfield.io.write_netcdf"], time.perf_counter() - t)
            t = time.perf_counter()
            finalize(ds).to_netcdf(b, engine="netcdf4", format="NETCDF4")
            best["xarray to_netcdf"] = min(best["xarray to_netcdf"], time.perf_counter() - t)
        same = read_netcdf(a).equals(read_netcdf(b))
        size = a.stat().st_size / 2**20
    print(f"{args.vars} variables of {n} x {n} float64 ({size:.0f} MiB), best of {args.repeat}:")
    for k, v in best.items():
        print(f"  {k:26s} {v:8.3f} s")
    print(f"  ratio dhfield/xarray      {best['dhfield.io.write_netcdf'] / best['xarray to_netcdf']:8.2f}")
    print(f"  files read back equal: {same}")
    return 0 if same else 1


if __name__ == "__main__":
    sys.exit(main())
