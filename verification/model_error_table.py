"""Every model's pull-off at every stored BEM ground-truth case: the table behind the error bands.

Reads ``data/adhesive_ground_truth_extended.nc`` (the 57 stored cases: Dugdale law, load
control, beta0 0.1-1, mu 0.1-10, ``W_star_truth`` and ``W_star_truth_error``), evaluates
every model of :data:`dhfield.analysis.compare.MODEL_NAMES` at each case (load control;
:func:`dhfield.analysis.compare.compare`, NaN where a model refuses the case) and writes the
Python module ``dhfield/analysis/_truth_table.py`` atomically: the cases, the truth with its error,
each model's W* and the provenance (source file, its build attributes, this command, the
git commit).  :mod:`dhfield.analysis.model_error` derives each model's error band from it.  About
50 s on one core (the two closures take about 200 ms per case).

``python -m verification.model_error_table``

``--leave-one-out`` writes nothing: it prints, per model, at how many stored cases the error
estimated from the other cases (:func:`dhfield.analysis.model_error.model_error`'s rule) covers the
held-out case's own error, by how much it falls short at worst, and the median ratio.
"""
from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
SOURCE = ROOT / "data" / "adhesive_ground_truth_extended.nc"
TARGET = ROOT / "dhfield" / "_truth_table.py"
COMMAND = "python -m verification.model_error_table"


def stored_cases(path=SOURCE):
    """The stored cases of the extended ground truth.

    Parameters
    ----------
    path : path-like
        The netCDF file.

    Returns
    -------
    beta0, mu, truth, truth_error : ndarray
        One entry per (beta0, mu) with a finite ``W_star_truth``, in the file's order [-].
        Where the file stores no ``W_star_truth_error`` (three N-ladder cases at mu = 5),
        the error is the difference of the two finest N of ``W_star_ladder``, the file's
        own rule for that set (the variable's ``long_name``); NaN if fewer than two.
    attrs : dict
        The file's global attributes ``built`` and ``build_commit``.
    """
    import xarray as xr

    with xr.open_dataset(path) as ds:
        b, m = np.meshgrid(ds["beta0"].values, ds["mu"].values, indexing="ij")
        t = ds["W_star_truth"].values
        e = ds["W_star_truth_error"].values.copy()
        ladder = ds["W_star_ladder"].values
        attrs = {k: str(ds.attrs.get(k, "")) for k in ("built", "build_commit")}
    # the file's rule for the N-ladder set (W_star_truth_error's long_name): where it stores no error,
    # the difference of the two finest N of the ladder
    for i, j in zip(*np.nonzero(np.isfinite(t) & ~np.isfinite(e))):
        finite = ladder[i, j][np.isfinite(ladder[i, j])]
        if finite.size >= 2:
            e[i, j] = abs(finite[-1] - finite[-2])
    ok = np.isfinite(t)
    return b[ok], m[ok], t[ok], e[ok], attrs


def model_values(beta0, mu):
    """W* of every model at each case, load control (NaN where a model refuses it).

    Parameters
    ----------
    beta0, mu : ndarray
        The cases [-].

    Returns
    -------
    dict
        Model name -> ndarray of W* (Eq. 34) [-].
    """
    from dhfield.analysis.compare import MODEL_NAMES, compare

    out = {name: np.full(beta0.shape, np.nan) for name in MODEL_NAMES}
    for i, (b, m) in enumerate(zip(beta0, mu)):
        for name, rec in compare(beta0=float(b), mu=float(m), control="load").items():
            out[name][i] = float(rec.W_star)
    return out


def _tuple(values) -> str:
    return "(" + ", ".join(repr(float(v)) if np.isfinite(v) else "NAN" for v in values) + ",)"


def render(beta0, mu, truth, truth_error, models, attrs, commit) -> str:
    """The text of ``dhfield/analysis/_truth_table.py``."""
    lines = ['"""Every model\'s pull-off at the stored BEM ground-truth cases (generated; do not edit).',
             "",
             f"Written by ``{COMMAND}`` from ``data/adhesive_ground_truth_extended.nc``;",
             "read by :mod:`dhfield.analysis.model_error`.  Load control, the paper's units (Eq. 34).",
             '"""',
             "",
             "NAN = float('nan')",
             f"SOURCE = {'data/adhesive_ground_truth_extended.nc'!r}",
             f"SOURCE_BUILT = {attrs['built']!r}",
             f"SOURCE_BUILD_COMMIT = {attrs['build_commit']!r}",
             f"COMMAND = {COMMAND!r}",
             f"GENERATED_AT_COMMIT = {commit!r}",
             f"BETA0 = {_tuple(beta0)}",
             f"MU = {_tuple(mu)}",
             f"W_STAR_TRUTH = {_tuple(truth)}",
             f"W_STAR_TRUTH_ERROR = {_tuple(truth_error)}",
             "W_STAR_MODEL = {"]
    lines += [f"    {name!r}: {_tuple(v)}," for name, v in models.items()]
    lines += ["}", ""]
    return "\n".join(lines)


def leave_one_out():
    """Print, per model, how often the error estimate from the other stored cases covers a held-out case."""
    from dhfield.analysis import model_error as me
    from dhfield.analysis.compare import MODEL_NAMES

    for name in MODEL_NAMES:
        b, m, e = me.stored_case_error(name)
        covered = n = 0
        short, ratio = 0.0, []
        for i in range(b.size):
            keep = np.arange(b.size) != i
            if not (b[keep].min() <= b[i] <= b[keep].max()) or not np.isfinite(e[i]):
                continue
            est = me._bracket_max(e[keep], b[i], m[i], b[keep], m[keep])
            if not np.isfinite(est):
                continue
            n += 1
            covered += est >= e[i]
            short = max(short, e[i] - est)
            ratio.append(est / e[i])
        print(f"{name:25s} covered {covered}/{n}; estimate short by at most {100 * short:.2f} percentage "
              f"points; median estimate/held-out {np.median(ratio):.2f}")


def main(argv=None) -> int:
    from dhfield.io import atomic_path, git_commit

    if "--leave-one-out" in (sys.argv[1:] if argv is None else argv):
        leave_one_out()
        return 0

    beta0, mu, truth, err, attrs = stored_cases()
    models = model_values(beta0, mu)
    text = render(beta0, mu, truth, err, models, attrs, git_commit())
    with atomic_path(TARGET) as tmp:
        Path(tmp).write_text(text, encoding="utf-8")
    print(f"wrote {TARGET.relative_to(ROOT)}: {beta0.size} cases x {len(models)} models")
    return 0


if __name__ == "__main__":
    sys.exit(main())
