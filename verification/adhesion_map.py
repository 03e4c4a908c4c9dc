"""The adhesion map for elliptical contacts and the practitioner's pull-off figure (issue 20).

Builds :func:`dhfield.analysis.adhesion_map.adhesion_map` over crossing angle 10-90 deg x mu
0.01-100 (log), writes it to netCDF (:mod:`dhfield.io.adhesion_map`, atomic; default
``data/adhesion_map.nc``) and draws, as PNG, SVG and PDF (default ``out/adhesion_map/``):

1. ``adhesion_map``: one panel per model, crossing angle (x) vs mu (y, log): where its
   load-control pull-off force is within 1 % and within 5 % of the reference; the whole stored
   BEM ground truth overlaid (``data/adhesive_ground_truth_extended.nc``, 57 cases, beta0 0.1-1 x
   mu 0.1-10: every case of ``data/adhesive_ground_truth.nc`` and
   ``data/adhesive_ground_truth_slender.nc``, plus mu = 10 and the extended study), each point
   filled where that model is within 1 % of the BEM; the validated region (the box of the
   stored cases, :func:`dhfield.analysis.model_error.bem_verified`) outlined.
2. ``practitioner_pull_off``: pull-off force -W/(pi R dgamma), R = sqrt(R'R''), against the
   crossing angle at mu = 0.1, 1, 10, 100, every model on the same axes, the BEM where it
   exists (mu = 0.1, 1, 10) and the two-axis double-Hertz closure on a coarse subset (45-90 deg:
   it refuses beta0 < 0.3, and costs 0.2-0.4 s per point, so it is not on the full map).

The reference is the recommended model (:data:`dhfield.analysis.compare.RECOMMENDED_MODEL`),
validated against the BEM only inside the outlined region (beta0 >= 0.1, i.e. crossing angles
>= 19 deg, and mu 0.1-10, read from the stored cases): a deviation outside it is from the
recommended model, not from the truth.  Prints the figure paths and, per
model, the fraction of the map within 1 % and 5 % of the reference and its worst
deviation from the BEM.

``python -m verification.adhesion_map [--n-angle 81 --n-mu 81] [--no-two-axis]``
"""
from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import numpy as np

from dhfield.analysis import adhesion_map as am
from dhfield.core.geometry import sin_skew_angle, skew_angle

ROOT = Path(__file__).resolve().parent.parent
GROUND_TRUTH = ROOT / "data" / "adhesive_ground_truth.nc"
GROUND_TRUTH_SLENDER = ROOT / "data" / "adhesive_ground_truth_slender.nc"
#: Both stored BEM ground truths (beta0 0.5-1 x mu 0.3-5; beta0 0.1-0.3 x mu 0.1-5).
GROUND_TRUTHS = (GROUND_TRUTH, GROUND_TRUTH_SLENDER)
#: Issue 20's extended ground truth (their successor: every case of the two, mu = 10, the extended
#: study's beta0 x mu); its ``W_star_truth`` is each case's best value.
GROUND_TRUTH_EXTENDED = ROOT / "data" / "adhesive_ground_truth_extended.nc"
DEFAULT_NC = ROOT / "data" / "adhesion_map.nc"
DEFAULT_FIG_DIR = ROOT / "out" / "adhesion_map"
FORMATS = ("png", "svg", "pdf")
#: mu of the practitioner's figure's panels.
PRACTITIONER_MU = (0.1, 1.0, 10.0, 100.0)
#: Crossing angles of the two-axis closure's coarse subset [deg] (it refuses below ~44 deg).
TWO_AXIS_ANGLES = (45.0, 60.0, 75.0, 90.0)
TOLERANCES = (0.01, 0.05)
#: Colours: within 1 %, within 5 %, beyond 5 %, no answer.
_BAND_COLOURS = ("#1b7837", "#a6dba0", "#f7f7f7", "#bdbdbd")
_STYLE = {  # model -> (colour, linestyle): distinguishable in greyscale too
    am.REFERENCE_MODEL: ("black", "-"),
    "dh-elliptic": ("#d95f02", "--"),
    "jkr-elliptic": ("#7570b3", "-."),
    "jkr-elliptic-energy": ("#1b9e77", (0, (5, 1.5, 1, 1.5, 1, 1.5))),
    "md": ("#e7298a", ":"),
    "dmt": ("#666666", (0, (1, 3))),
}


def read_truth(paths=GROUND_TRUTHS):
    """Stored BEM cases: beta0, mu, crossing angle [deg] and F = 2 W*/sin(theta) (finite only).

    Parameters
    ----------
    paths : path-like or sequence of path-like
        Ground-truth files, concatenated: the extended one's ``W_star_truth`` (each case's best
        value), the default ground truth's ``W_star_extrapolated`` (Richardson-extrapolated where
        three levels converged), the slender one's ``W_star`` at its finest ``level``.  Default
        the two first stored files (:data:`GROUND_TRUTHS`).

    Returns
    -------
    dict of ndarray
        ``beta0``, ``mu``, ``angle`` [deg], ``force`` = W/(pi R dgamma) (Eq. 34 inverted) and
        ``source`` (the index of the file of each case).
    """
    import xarray as xr

    if isinstance(paths, (str, Path)):
        paths = (paths,)
    parts = []
    for k, path in enumerate(paths):
        with xr.open_dataset(path) as ds:
            if "W_star_truth" in ds:
                w = ds["W_star_truth"].transpose("beta0", "mu").values
            elif "W_star_extrapolated" in ds:
                w = ds["W_star_extrapolated"].transpose("beta0", "mu").values
            elif "W_star" in ds and "level" in ds["W_star"].dims:
                w = ds["W_star"].isel(level=-1).transpose("beta0", "mu").values
            else:
                raise ValueError(f"paths must be BEM ground-truth files (W_star_extrapolated, or W_star on "
                                 f"level); {str(path)!r} has neither")
            b0, mu = np.meshgrid(ds["beta0"].values, ds["mu"].values, indexing="ij")
        ok = np.isfinite(w)
        parts.append((b0[ok], mu[ok], w[ok], np.full(int(ok.sum()), k)))
    b0, mu, w, src = (np.concatenate(x) for x in zip(*parts))
    angle = np.degrees(skew_angle(b0))
    return {"beta0": b0, "mu": mu, "angle": angle, "force": 2.0 * w / sin_skew_angle(b0),  # Eq. (34)
            "source": src}


def validated_extent(truth):
    """The box the stored cases validate: beta0 from the smallest to the largest stored, and the
    mu range stored at EVERY beta0 (the largest per-beta0 minimum to the smallest maximum).

    Returns
    -------
    tuple
        ``(beta0_min, beta0_max), (mu_min, mu_max)`` [-]; for the two stored files
        (0.1, 1) and (0.3, 5): the slender file's mu = 0.1 is not stored at beta0 >= 0.5.
    """
    b = np.unique(truth["beta0"])
    lo = max(float(truth["mu"][truth["beta0"] == x].min()) for x in b)
    hi = min(float(truth["mu"][truth["beta0"] == x].max()) for x in b)
    return (float(b[0]), float(b[-1])), (lo, hi)


def stored_box(truth):
    """The box the stored cases span: the smallest to the largest stored beta0 and mu.

    This is the box of :func:`dhfield.analysis.model_error.bem_verified` when ``truth`` is the whole stored
    ground truth (:data:`GROUND_TRUTH_EXTENDED`).

    Returns
    -------
    tuple
        ``(beta0_min, beta0_max), (mu_min, mu_max)`` [-].
    """
    return ((float(np.min(truth["beta0"])), float(np.max(truth["beta0"]))),
            (float(np.min(truth["mu"])), float(np.max(truth["mu"]))))


def truth_deviation(truth):
    """model -> F_model/F_BEM - 1 at each stored case (the map's models, through the same function,
    on the ground truth's own (angle, mu) grid in one call)."""
    angles, ia = np.unique(truth["angle"], return_inverse=True)
    mus, im = np.unique(truth["mu"], return_inverse=True)
    r = am.adhesion_map(angles, mus)
    return {name: r.force[i][ia, im] / truth["force"] - 1.0 for i, name in enumerate(r.models)}


# --------------------------------------------------------------------------- figures
def _save(fig, stem: Path, dpi: int = 200) -> list:
    from dhfield.io import atomic_path

    paths = []
    for fmt in FORMATS:
        p = stem.with_suffix("." + fmt)
        meta = {"png": {}, "svg": {"Date": None}, "pdf": {"CreationDate": None, "ModDate": None}}[fmt]
        with atomic_path(p) as tmp:
            fig.savefig(tmp, format=fmt, dpi=dpi, metadata=meta)
        paths.append(p)
    return paths


def _log_mu_axis(ax):
    from matplotlib.ticker import LogLocator, NullFormatter

    ax.set_yscale("log")
    ax.yaxis.set_major_locator(LogLocator(base=10, numticks=10))
    ax.yaxis.set_minor_formatter(NullFormatter())
    ax.set_yticks([0.01, 0.1, 1, 10, 100], ["0.01", "0.1", "1", "10", "100"])


def _edges(x, log=False):
    x = np.log10(x) if log else np.asarray(x, float)
    mid = 0.5 * (x[1:] + x[:-1])
    e = np.concatenate([[x[0] - (mid[0] - x[0])], mid, [x[-1] + (x[-1] - mid[-1])]])
    return 10.0 ** e if log else e


#: Contour levels of the reference's -W/(pi R dgamma) (between JKR-elliptic at 10 deg, 1.34, and DMT, 2).
_REF_LEVELS = (1.4, 1.5, 1.6, 1.7, 1.8, 1.9, 1.97)


def _mu_at(r, k, level, angle):
    """mu where the reference's -force crosses ``level`` at ``angle`` (for a contour label); log-interpolated."""
    i = int(np.argmin(np.abs(r.crossing_angle_deg - angle)))
    f = -r.force[k, i]
    order = np.argsort(f)
    return 10.0 ** np.interp(level, f[order], np.log10(r.mu[order]))


def _label_at(r, k, level, angle=14.0):
    """Where to label a reference contour: at ``angle`` if the level is crossed there, else at mu = 20."""
    i = int(np.argmin(np.abs(r.crossing_angle_deg - angle)))
    f = -r.force[k, i]
    if f.min() <= level <= f.max():
        return angle, float(_mu_at(r, k, level, angle))
    row = -r.force[k, :, int(np.argmin(np.abs(r.mu - 20.0)))]
    return float(np.interp(level, np.sort(row), r.crossing_angle_deg[np.argsort(row)])), 20.0


def map_figure(r, truth, dev_truth, stem, dpi=200):
    from matplotlib.colors import ListedColormap
    from matplotlib.figure import Figure
    from matplotlib.lines import Line2D
    from matplotlib.patches import Patch, Rectangle

    n = len(r.models)
    cols = 3
    rows = int(np.ceil(n / cols))
    fig = Figure(figsize=(10.5, 3.3 * rows + 1.5), layout="constrained")
    axes = fig.subplots(rows, cols, sharex=True, sharey=True, squeeze=False).ravel()
    xe, ye = _edges(r.crossing_angle_deg), _edges(r.mu, log=True)
    a_lo = float(np.degrees(skew_angle(r.validated_beta0[0])))
    box = (a_lo, r.validated_mu[0], 90.0 - a_lo, r.validated_mu[1] - r.validated_mu[0])
    f1, f5 = r.fraction_within(TOLERANCES[0]), r.fraction_within(TOLERANCES[1])
    for k, (ax, m) in enumerate(zip(axes, r.models)):
        d = np.abs(r.deviation[k])
        if np.any(np.isnan(d)):  # no answer (refused or non-finite): grey underneath the bands
            ax.pcolormesh(xe, ye, np.where(np.isnan(d), 1.0, np.nan).T, cmap=ListedColormap([_BAND_COLOURS[3]]),
                          vmin=0, vmax=2, rasterized=True)
        if m == r.reference:
            ax.set_facecolor("#deebf7")
            cs = ax.contour(r.crossing_angle_deg, r.mu, -r.force[k].T, levels=_REF_LEVELS, colors="#08519c",
                            linewidths=0.8)
            # labels at 14 deg, left of the ground-truth box (from 19 deg) and its markers
            ax.clabel(cs, fmt="%.2f", fontsize=7, inline_spacing=2,
                      manual=[_label_at(r, k, lev) for lev in cs.levels])
            title = f"Reference: {am.MODEL_LABELS.get(m, m)}\ncontours: pull-off force −W/(πRΔγ)"
        else:
            # bands of |deviation| (contourf: boundaries interpolated between grid points)
            ax.contourf(r.crossing_angle_deg, r.mu, np.nan_to_num(d, nan=np.inf).T,
                        levels=[0.0, TOLERANCES[0], TOLERANCES[1], np.inf], colors=_BAND_COLOURS[:3])
            title = (f"{am.MODEL_LABELS.get(m, m)}\nwithin 1 %: {100 * f1[m]:.0f} % of map, "
                     f"5 %: {100 * f5[m]:.0f} %")
        ax.add_patch(Rectangle(box[:2], box[2], box[3], fill=False, ec="black", lw=1.4, ls="--", zorder=4))
        if m == r.reference:  # the validated box, stated on the map itself
            ax.text(box[0] + 0.5 * box[2], r.validated_mu[1] * 1.25,
                    f"BEM-validated:\nβ0 ≥ {r.validated_beta0[0]:g}, {r.validated_mu[0]:g} ≤ μ ≤ {r.validated_mu[1]:g}",
                    ha="center", va="bottom", fontsize=8, zorder=6,
                    bbox=dict(boxstyle="round,pad=0.2", fc="white", ec="black", lw=0.6, alpha=0.9))
        dv = np.abs(dev_truth[m])
        good = dv <= TOLERANCES[0]
        ax.scatter(truth["angle"][good], truth["mu"][good], s=16, c="black", marker="o", zorder=5, lw=0.6,
                   clip_on=False)
        ax.scatter(truth["angle"][~good], truth["mu"][~good], s=16, facecolors="white", edgecolors="black",
                   marker="o", zorder=5, lw=0.8, clip_on=False)
        ax.set_title(title, fontsize=9)
        ax.set_xlim(xe[0], xe[-1])
        ax.set_ylim(ye[0], ye[-1])
        _log_mu_axis(ax)
        ax.set_xticks([10, 30, 45, 60, 75, 90])
        ax.tick_params(labelsize=8)
        if k % cols == 0:
            ax.set_ylabel("Tabor parameter μ", fontsize=9)
        if k >= n - cols:
            ax.set_xlabel("crossing angle θ (deg)", fontsize=9)
    for ax in axes[n:]:
        ax.set_visible(False)
    handles = [Patch(fc=_BAND_COLOURS[0], ec="grey", label="within 1 % of reference"),
               Patch(fc=_BAND_COLOURS[1], ec="grey", label="within 5 %"),
               Patch(fc=_BAND_COLOURS[2], ec="grey", label="beyond 5 %"),
               Line2D([], [], ls="--", c="black", label="ground-truth extent (reference validated)"),
               Line2D([], [], ls="", marker="o", c="black", ms=5, label="BEM case: model within 1 % of BEM"),
               Line2D([], [], ls="", marker="o", mfc="white", mec="black", ms=5, label="BEM case: model off by > 1 %")]
    if np.any(r.status >= 2):
        handles.insert(3, Patch(fc=_BAND_COLOURS[3], ec="grey", label="no answer (refused)"))
    fig.legend(handles=handles, loc="outside lower center", ncols=3, fontsize=8, frameon=False)
    fig.suptitle("Adhesion map for elliptical contacts (equal cylinders, load control): deviation of the pull-off "
                 "force from the reference\nThe reference is the recommended model, validated against the BEM only "
                 f"inside the dashed box (θ ≥ {a_lo:.0f}°: β0 ≥ {r.validated_beta0[0]:g}; "
                 f"{r.validated_mu[0]:g} ≤ μ ≤ {r.validated_mu[1]:g})\n({truth['force'].size} BEM cases"
                 + (f", {_below_box(r, truth)} of them at μ = {_fmt_mus(truth['mu'][truth['mu'] < r.validated_mu[0]])} "
                    "below it" if _below_box(r, truth) else "") + "); outside it, deviations are from the recommended model, "
                 "not from the truth.\nThe two-axis double-Hertz closure (0.2-0.4 s per point) is not mapped: see the "
                 "practitioner's figure.", fontsize=9)
    return _save(fig, stem, dpi)


def _below_box(r, truth):
    """Number of stored cases below the validated box's mu range."""
    return int(np.sum(truth["mu"] < r.validated_mu[0]))


def _fmt_mus(mus):
    return ", ".join(f"{m:g}" for m in np.unique(mus)) or "none"


def practitioner_figure(curves, two_axis, truth, stem, dpi=200):
    from matplotlib.figure import Figure

    mus = curves.mu
    fig = Figure(figsize=(10.5, 3.9), layout="constrained")
    axes = fig.subplots(1, mus.size, sharey=True)
    handles = []
    bem_label = (f"BEM ground truth (stored at μ = {float(truth['mu'].min()):g}–{float(truth['mu'].max()):g} "
                 "only)")
    for j, (ax, mu) in enumerate(zip(axes, mus)):
        for k, m in enumerate(curves.models):
            colour, ls = _STYLE.get(m, ("C0", "-"))
            (h,) = ax.plot(curves.crossing_angle_deg, -curves.force[k, :, j], c=colour, ls=ls,
                           lw=3.2 if m == curves.reference else 1.6,
                           zorder=2 if m == curves.reference else 3, label=am.MODEL_LABELS.get(m, m))
            if j == 0:
                handles.append(h)
        if two_axis is not None and mu in two_axis.mu:
            jj = int(np.flatnonzero(two_axis.mu == mu)[0])
            i2 = two_axis.index("dh-elliptic-two-axis")
            (h,) = ax.plot(two_axis.crossing_angle_deg, -two_axis.force[i2, :, jj], ls="", marker="s", ms=5,
                           mfc="none", mec="#a6761d", mew=1.2, label=am.MODEL_LABELS["dh-elliptic-two-axis"]
                           + " (μ ≤ 30; refuses θ < 44°)")
            if j == 0:
                handles.append(h)
        sel = np.isclose(truth["mu"], mu)
        if sel.any():
            (h,) = ax.plot(truth["angle"][sel], -truth["force"][sel], ls="", marker="o", ms=5, c="black",
                           mec="white", mew=0.8, zorder=4, label=bem_label)
            if not any(x.get_label() == bem_label for x in handles):
                handles.append(h)
        ax.set_title(f"μ = {mu:g}", fontsize=10)
        ax.set_xlabel("crossing angle θ (deg)", fontsize=9)
        ax.set_xticks([10, 30, 50, 70, 90])
        ax.set_xlim(8, 92)
        ax.grid(alpha=0.3)
        ax.tick_params(labelsize=8)
    axes[0].set_ylabel("pull-off force −W/(πRΔγ)", fontsize=10)
    fig.legend(handles=handles, loc="outside lower center", ncols=3, fontsize=8, frameon=False)
    a_lo = float(np.degrees(skew_angle(curves.validated_beta0[0])))
    fig.suptitle("Pull-off force of equal crossed cylinders against crossing angle, every model (load control; "
                 "R = √(R′R″); 2 = DMT, 1.5 = JKR sphere)\nThe recommended model is validated against the BEM only for "
                 f"θ ≥ {a_lo:.0f}° (β0 ≥ {curves.validated_beta0[0]:g}) and "
                 f"{curves.validated_mu[0]:g} ≤ μ ≤ "
                 f"{curves.validated_mu[1]:g}", fontsize=9)
    return _save(fig, stem, dpi)


# --------------------------------------------------------------------------- main
def _git_commit():
    """The code's commit (with '(uncommitted changes)' when the tree differs), for provenance."""
    import subprocess

    try:
        rev = subprocess.run(["git", "rev-parse", "HEAD"], cwd=ROOT, capture_output=True, text=True, timeout=10)
        dirty = subprocess.run(["git", "status", "--porcelain", "--untracked-files=no", "--", "dhfield",
                                "verification"], cwd=ROOT, capture_output=True, text=True, timeout=10)
    except (OSError, subprocess.SubprocessError):
        return "unavailable"
    if rev.returncode != 0:
        return "unavailable"
    return rev.stdout.strip() + (" (uncommitted changes)" if dirty.stdout.strip() else "")


def main(argv=None) -> int:
    p = argparse.ArgumentParser(prog="python -m verification.adhesion_map", description=__doc__.split("\n")[0])
    p.add_argument("--n-angle", type=int, default=81, help="crossing angles over 10-90 deg (default 81)")
    p.add_argument("--n-mu", type=int, default=81, help="values of mu over 0.01-100, log (default 81)")
    p.add_argument("--out", type=Path, default=DEFAULT_NC, help="netCDF of the map (default data/adhesion_map.nc)")
    p.add_argument("--fig-dir", type=Path, default=DEFAULT_FIG_DIR, help="figure directory")
    p.add_argument("--no-two-axis", action="store_true", help="leave out the two-axis closure's coarse subset")
    args = p.parse_args(argv)
    try:
        angles, mus = am.map_grid(args.n_angle, args.n_mu)
        from dhfield.io import validate_output_path

        validate_output_path(args.out, (".nc",), "--out")
    except ValueError as exc:
        print(f"error: {exc}", file=sys.stderr)
        return 2
    t0 = time.perf_counter()
    truth = read_truth(GROUND_TRUTH_EXTENDED)   # the whole stored truth
    vb, vm = stored_box(truth)
    r = am.adhesion_map(angles, mus, validated_beta0=vb, validated_mu=vm)
    t_map = time.perf_counter() - t0
    from dhfield.io.adhesion_map import write_adhesion_map

    cmd = "python -m verification.adhesion_map " + " ".join(argv if argv is not None else sys.argv[1:])
    nc = write_adhesion_map(r, args.out, command=cmd.strip(),
                            ground_truth=str(GROUND_TRUTH_EXTENDED.relative_to(ROOT)),
                            git_commit=_git_commit())
    dev_truth = truth_deviation(truth)
    curves = am.adhesion_map(np.linspace(10.0, 90.0, 81), PRACTITIONER_MU, validated_beta0=vb, validated_mu=vm)
    two = None
    if not args.no_two_axis:
        t = time.perf_counter()
        two = am.adhesion_map((30.0,) + TWO_AXIS_ANGLES, PRACTITIONER_MU[:3], models=("dh-elliptic-two-axis",))
        t_two = time.perf_counter() - t
    args.fig_dir.mkdir(parents=True, exist_ok=True)
    t_fig = time.perf_counter()
    paths = map_figure(r, truth, dev_truth, args.fig_dir / "adhesion_map")
    paths += practitioner_figure(curves, two, truth, args.fig_dir / "practitioner_pull_off")
    total = time.perf_counter() - t0
    t_fig = time.perf_counter() - t_fig

    print(f"Adhesion map: {angles.size} crossing angles (10-90 deg) x {mus.size} mu (0.01-100, log), "
          f"{len(r.models)} models, load control; map {t_map:.1f} s, figures {t_fig:.1f} s, total {total:.1f} s")
    print(r.reference_note)
    print(f"dataset: {nc} ({nc.stat().st_size / 1024:.0f} KiB)")
    for q in paths:
        print(f"figure: {q}")
    f1, f5, ans = r.fraction_within(0.01), r.fraction_within(0.05), r.fraction_answered()
    head = f"max |dev| vs BEM ({truth['force'].size} cases)"
    print(f"\n{'model':24s} {'label':40s} {'<=1 %':>6s} {'<=5 %':>6s} {'answered':>8s}  {head:>28s}")
    for m in r.models:
        dv = np.abs(dev_truth[m])
        i = int(np.argmax(dv))
        worst = (f"{100 * dv[i]:6.2f} % (beta0 {truth['beta0'][i]:g}, mu {truth['mu'][i]:g})")
        print(f"{m:24s} {am.MODEL_LABELS.get(m, m):40s} {100 * f1[m]:5.1f}% {100 * f5[m]:5.1f}% "
              f"{100 * ans[m]:7.1f}%  {worst:>28s}")
    print("(fractions of the map's area, uniform in angle and log mu; a point without answer counts as outside)")
    for m in r.models:
        if r.notes[m]:
            print(f"  {m}: {r.notes[m][:160]}")
    if two is not None:
        print(f"two-axis closure, coarse subset ({two.crossing_angle_deg.size} angles x {two.mu.size} mu, "
              f"{t_two:.1f} s): {two.notes['dh-elliptic-two-axis'][:160]}")
        i2 = two.index("dh-elliptic-two-axis")
        print("  deviation from the reference [%] (rows: angle " + ", ".join(f"{a:g}" for a in two.crossing_angle_deg)
              + "; cols: mu " + ", ".join(f"{m:g}" for m in two.mu) + ")")
        for a, row in zip(two.crossing_angle_deg, two.deviation[i2]):
            print(f"  {a:4.0f} deg " + " ".join(f"{100 * x:+7.2f}" if np.isfinite(x) else "   (no)" for x in row))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
