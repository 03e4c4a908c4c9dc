"""``dhfield plot SWEEP.nc``: the standard maps of a sweep (PNG + SVG)."""
from __future__ import annotations

from pathlib import Path


def add_parser(sub) -> None:
    p = sub.add_parser("plot", help="standard maps of a sweep: W*max per model, errors, ellipticities")
    p.add_argument("sweep", help="netCDF file written by 'dhfield sweep'")
    p.add_argument("--out", default=None, help="output directory (default: the sweep file's directory)")
    p.add_argument("--reference", default=None,
                   help="reference model of the error maps (default: bem-adhesive, else dh-elliptic)")
    p.set_defaults(func=run)


def run(args) -> int:
    from ..io import read_netcdf
    from ..plotting import standard_maps

    ds = read_netcdf(args.sweep)
    out = Path(args.out) if args.out is not None else (Path(args.sweep).parent or Path("."))
    for path in standard_maps(ds, out, reference=args.reference, stem=Path(args.sweep).stem):
        print(f"wrote {path}")
    return 0
