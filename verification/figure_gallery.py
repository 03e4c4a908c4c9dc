"""Draw every figure of ``dhfield plot``, ``fit --plot``, ``solve --plot``, ``cycle --plot`` and the report.

Usage::

    python -m verification.figure_gallery --tree . --label after  [--out docs/_static/gallery]
    python -m verification.figure_gallery --tree /tmp/old --label before

The figures of issue 17's before/after gallery (``docs/developer/figure_gallery.rst``).
Every command runs in a subprocess with ``PYTHONPATH=<tree>`` (so the tree's own
``dhfield`` and ``verification`` draw them, an old commit's as well as this one's) on
small, fast inputs:

* ``dhfield sweep --beta0 0.3 0.45 0.6 0.75 0.9 1 --mu 0.3 1 3 10`` over four models
  (β0 >= 0.3, the two-axis closure's domain), then
  ``dhfield plot`` of it into a directory that does not exist yet (an old tree that
  refuses it gets the directory made for it, and the gallery says so); a tree whose
  ``plot`` takes SI flags also draws the SI maps of PDMS cylinders;
* ``dhfield fit --data`` of a synthetic PDMS load curve (the paper's model, Δγ = 50 mJ/m²,
  σ0 = 50 kPa, 1 % seeded noise) with ``--plot``;
* ``dhfield solve`` with SI flags at N = 64 and ``--plot`` (a tree without it is noted);
* ``dhfield cycle`` of the Maugis–Dugdale sphere with ``--plot`` (likewise);
* ``python -m verification.report --quick`` (its figures).

Each PNG is copied to ``<out>/<label>/<name>.png``, scaled to at most :data:`MAX_WIDTH_PX`
pixels wide and reduced to a 256-colour palette, so that the committed gallery stays
small (about 3 MB for both trees).  ``<out>/<label>/manifest.json`` lists the figures,
the command of each, what a tree could not draw, and the runtime.  The gallery script
itself needs only Pillow (a matplotlib dependency).
"""
from __future__ import annotations

import argparse
import csv
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

__all__ = ["FIGURES", "MAX_WIDTH_PX", "draw_tree", "main", "synthetic_curve_csv"]

#: Widest gallery PNG [px] (about 90 dpi for a 10 in figure; readable beside its pair).
MAX_WIDTH_PX = 900

#: The PDMS crossed cylinders of issue 17 (E = 1.8 MPa, ν = 0.49, R = 3 mm, 60°), SI flags.
PDMS = ["--youngs-modulus", "1.8e6", "--poisson-ratio", "0.49", "--cylinder-radius", "3e-3",
        "--skew-angle-deg", "60"]
#: Work of adhesion and maximum adhesive stress of the examples [J/m², Pa] (μ ≈ 2).
ADHESION = ["--work-of-adhesion", "0.05", "--adhesive-stress", "5e4"]
#: The sweep behind the ``dhfield plot`` maps (the issue's μ = 0.3, 1, 3, 10).
SWEEP = ["--beta0", "0.3", "0.45", "0.6", "0.75", "0.9", "1.0", "--mu", "0.3", "1", "3", "10",
         "--models", "dh-elliptic", "dh-elliptic-two-axis", "jkr-elliptic", "md", "--workers", "1", "--quiet"]
#: A tiny sweep for the test of this script (two models on 2 x 2 points).
SMALL_SWEEP = ["--beta0", "0.5", "1.0", "--mu", "0.3", "1", "--models", "dh-elliptic", "jkr-elliptic",
               "--workers", "1", "--quiet"]

#: Gallery name -> (source, file drawn by the source, relative to its output directory).
FIGURES = {
    "plot_pull_off": ("plot", "maps/sweep_pull_off.png"),
    "plot_error": ("plot", "maps/sweep_error.png"),
    "plot_ellipticity": ("plot", "maps/sweep_ellipticity.png"),
    "plot_si_pull_off": ("plot-si", "maps_si/sweep_pull_off.png"),
    "plot_si_error": ("plot-si", "maps_si/sweep_error.png"),
    "fit": ("fit", "fit.png"),
    "solve": ("solve", "solve.png"),
    "cycle": ("cycle", "cycle.png"),
}
#: The report's figures, by section (``python -m verification.report --quick``).
REPORT_FIGURES = (
    "analytic/fig03_pressure_displacement", "analytic/fig04_contact_axis_vs_load",
    "analytic/fig05_adhesive_axis_vs_load", "analytic/fig06_axes_vs_load_mu0.5",
    "analytic/fig07_axes_vs_load_mu5", "analytic/fig10_ellipse_evolution", "analytic/load_approach",
    "analytic/pull_off_vs_beta0", "analytic/displacement_vs_quadrature",
    "models/fig8_a_vs_W_mu5", "models/fig9_pull_off_vs_mu",
    "fields/fields_maps", "fields/fields_profiles", "fields/fields_convergence", "fields/fields_annulus_identity",
    "periphery/closure_pull_off", "periphery/periphery_rays_pull_off", "periphery/periphery_ratio_load_curves",
    "periphery/periphery_sigma_h_laws", "periphery/periphery_bem_vs_analytic",
    "adhesive/adhesive_ground_truth",
)
for _name in REPORT_FIGURES:
    FIGURES["report_" + _name.split("/")[1]] = ("report", "report/" + _name + ".png")


def synthetic_curve_csv(path: Path, *, seed: int = 17) -> Path:
    """Write a synthetic measured load curve of the PDMS cylinders (force [N], semi_major [m]).

    The paper's model (:func:`dhfield.analysis.dimensional.load_curve_si`) at Δγ = 50 mJ/m² and
    σ0 = 50 kPa, 14 points of the tensile branch and past it, with seeded noise of 1 % of the
    force range.  Drawn with this tree's library, so both trees fit the same numbers.
    """
    import numpy as np

    from dhfield.analysis import dimensional as dim

    params = dim.contact_parameters(youngs_modulus_1=1.8e6, poisson_ratio_1=0.49, youngs_modulus_2=1.8e6,
                                    poisson_ratio_2=0.49, cylinder_radius=3e-3, skew_angle=np.deg2rad(60.0),
                                    work_of_adhesion=0.05, max_adhesive_stress=5e4)
    curve = dim.load_curve_si(params, n=40)
    keep = np.flatnonzero(np.asarray(curve["semi_major"]) > 0)[::3][:14]
    a, force = np.asarray(curve["semi_major"])[keep], np.asarray(curve["force"])[keep]
    rng = np.random.default_rng(seed)
    force = force + 0.01 * np.ptp(force) * rng.standard_normal(force.size)
    with open(path, "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(["force", "semi_major"])
        w.writerows([[f"{f:.6e}", f"{x:.6e}"] for f, x in zip(force, a)])
    return path


def _run(tree: Path, args, cwd: Path, log: list, timeout=600):
    """Run ``python <args>`` with the tree first on the path; log command, status and seconds."""
    env = dict(os.environ, PYTHONPATH=str(tree), MPLBACKEND="Agg")
    t0 = time.perf_counter()
    proc = subprocess.run([sys.executable, *args], cwd=cwd, env=env, capture_output=True, text=True,
                          timeout=timeout)
    entry = {"command": "python " + " ".join(str(a) for a in args), "returncode": proc.returncode,
             "seconds": round(time.perf_counter() - t0, 1),
             "stderr": proc.stderr.strip().splitlines()[-3:]}
    log.append(entry)
    return proc


def _has_option(tree: Path, command: str, option: str, cwd: Path, log: list) -> bool:
    proc = _run(tree, ["-m", "dhfield.cli", command, "--help"], cwd, [])
    return proc.returncode == 0 and option in proc.stdout


def draw_tree(tree, work, *, report: bool = True, log=None, small: bool = False) -> dict:
    """Run every figure command of ``tree`` in ``work``; return {source: note} of what it could not draw.

    Parameters
    ----------
    tree : path
        Root of a dhfield checkout (put first on ``PYTHONPATH``).
    work : path
        Scratch directory: the figures land under it (see :data:`FIGURES`).
    report : bool
        Draw the report's figures too (``verification.report --quick``, about 40 s).
    log : list, optional
        Receives one dict per command run (command, return code, seconds, last stderr lines).
    small : bool
        Tiny inputs (a 2 x 2 sweep of two models, the BEM at N = 32): the test of this script.
    """
    tree, work = Path(tree).resolve(), Path(work).resolve()
    work.mkdir(parents=True, exist_ok=True)
    log = [] if log is None else log
    notes = {}
    mod = ["-m", "dhfield.cli"]

    proc = _run(tree, mod + ["sweep", *(SMALL_SWEEP if small else SWEEP), "--out", "sweep.nc"], work, log)
    if proc.returncode not in (0, 3) and not (proc.returncode == 1 and (work / "sweep.nc").is_file()):
        raise RuntimeError(f"sweep failed: {proc.stderr.strip()[-300:]}")
    if proc.returncode == 1:  # some models failed: stored as failed cases, drawn blank
        notes["sweep"] = "some sweep cases failed (exit status 1); they are drawn blank"
    proc = _run(tree, mod + ["plot", "sweep.nc", "--out", "maps"], work, log)
    if proc.returncode != 0 and not (work / "maps").exists():
        notes["plot"] = f"refused a new --out directory ({proc.stderr.strip()}); drawn after mkdir"
        (work / "maps").mkdir()
        proc = _run(tree, mod + ["plot", "sweep.nc", "--out", "maps"], work, log)
    if proc.returncode != 0:
        raise RuntimeError(f"plot failed: {proc.stderr.strip()[-300:]}")
    if _has_option(tree, "plot", "--youngs-modulus", work, log):
        proc = _run(tree, mod + ["plot", "sweep.nc", "--out", "maps_si", *PDMS[:-2], "--work-of-adhesion", "0.05"],
                    work, log)
        if proc.returncode != 0:
            raise RuntimeError(f"plot (SI) failed: {proc.stderr.strip()[-300:]}")
    else:
        notes["plot-si"] = "no SI option: 'dhfield plot' draws W* against (mu, beta0) only"

    synthetic_curve_csv(work / "measured.csv")
    proc = _run(tree, mod + ["fit", "--data", "measured.csv", *PDMS, *ADHESION, "--plot", "fit.png"], work, log)
    if proc.returncode != 0:
        raise RuntimeError(f"fit failed: {proc.stderr.strip()[-300:]}")

    if _has_option(tree, "solve", "--plot", work, log):
        proc = _run(tree, mod + ["solve", *PDMS, *ADHESION, "--n", "32" if small else "64", "--plot", "solve.png"],
                    work, log)
        if proc.returncode != 0:
            raise RuntimeError(f"solve failed: {proc.stderr.strip()[-300:]}")
    else:
        notes["solve"] = "no 'dhfield solve --plot' (nor SI flags) in this tree"
    if _has_option(tree, "cycle", "--plot", work, log):
        proc = _run(tree, mod + ["cycle", "--beta0", "1", "--mu", "1", "--model", "md", "--plot", "cycle.png"],
                    work, log)
        if proc.returncode != 0:
            raise RuntimeError(f"cycle failed: {proc.stderr.strip()[-300:]}")
    else:
        notes["cycle"] = "no 'dhfield cycle' in this tree"

    if report:
        proc = _run(tree, ["-m", "verification.report", "--quick", "--no-progress", "--out", str(work / "report")],
                    tree, log)
        if proc.returncode != 0:
            raise RuntimeError(f"report failed: {proc.stderr.strip()[-300:]}")
    return notes


def shrink_png(src: Path, dst: Path, max_width: int = MAX_WIDTH_PX) -> None:
    """Copy a PNG at most ``max_width`` px wide, as a 256-colour palette image (a fraction of the bytes)."""
    from PIL import Image

    with Image.open(src) as im:
        im = im.convert("RGB")
        if im.width > max_width:
            im = im.resize((max_width, round(im.height * max_width / im.width)), Image.LANCZOS)
        im = im.quantize(colors=256, method=Image.Quantize.MEDIANCUT, dither=Image.Dither.NONE)
        dst.parent.mkdir(parents=True, exist_ok=True)
        tmp = dst.with_name(dst.name + ".tmp")
        im.save(tmp, format="PNG", optimize=True)
        os.replace(tmp, dst)


def collect(work, out, notes, log, seconds) -> dict:
    """Copy the drawn figures of ``work`` into ``out`` (shrunk) and write ``out/manifest.json``."""
    work, out = Path(work), Path(out)
    if out.exists():
        shutil.rmtree(out)
    out.mkdir(parents=True)
    drawn, missing = [], {}
    for name, (source, rel) in FIGURES.items():
        src = work / rel
        if src.is_file():
            shrink_png(src, out / f"{name}.png")
            drawn.append(name)
        else:
            missing[name] = notes.get(source, "not drawn")
    commands = json.loads(json.dumps(log).replace(str(work.resolve()), "<work>"))  # no scratch paths
    manifest = {"figures": drawn, "not_drawn": missing, "notes": notes, "commands": commands,
                "seconds": round(seconds, 1)}
    (out / "manifest.json").write_text(json.dumps(manifest, indent=1, ensure_ascii=False) + "\n")
    return manifest


def main(argv=None) -> int:
    p = argparse.ArgumentParser(prog="python -m verification.figure_gallery", description=__doc__.split("\n")[0])
    p.add_argument("--tree", default=".", help="dhfield checkout whose figures are drawn (default: .)")
    p.add_argument("--label", required=True, help="gallery column: before or after")
    p.add_argument("--out", default="docs/_static/gallery", help="gallery root (default: docs/_static/gallery)")
    p.add_argument("--no-report", action="store_true", help="skip the report's figures (about 40 s)")
    p.add_argument("--keep", default=None, help="keep the full-size figures in this directory")
    args = p.parse_args(argv)
    t0 = time.perf_counter()
    work = Path(args.keep) if args.keep else Path(tempfile.mkdtemp(prefix="dhfield-gallery-"))
    log = []
    try:
        notes = draw_tree(args.tree, work, report=not args.no_report, log=log)
        manifest = collect(work, Path(args.out) / args.label, notes, log, time.perf_counter() - t0)
    finally:
        if not args.keep:
            shutil.rmtree(work, ignore_errors=True)
    size = sum(f.stat().st_size for f in (Path(args.out) / args.label).glob("*.png"))
    print(f"{args.label}: {len(manifest['figures'])} figures, {size / 1e6:.2f} MB, "
          f"{manifest['seconds']:.0f} s; not drawn: {', '.join(manifest['not_drawn']) or 'none'}")
    for name, why in manifest["notes"].items():
        print(f"  {name}: {why}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
