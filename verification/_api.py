"""The contract between report sections and the report builder.

Each section module ``verification/sec_<name>.py`` exposes::

    def run(outdir: pathlib.Path, quick: bool, progress: Callable[[str], None]) -> Section

It writes its figures (PNG) and datasets (netCDF, via dhfield.io.write_netcdf) under
``outdir`` and returns a :class:`Section`.  ``quick=True`` must finish in a few
seconds (the test suite runs it).  Every check carries a tolerance and a one-line
justification; the report exits non-zero if any check fails.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path


@dataclass
class Check:
    name: str            # what is checked, e.g. "Eq. (31) vs GJ98 closed form at beta0 = 1"
    value: float         # the measured quantity (error, ratio, ...)
    tolerance: float     # the bound it must satisfy
    passed: bool
    reference: str = ""  # where the reference value comes from (closed form, limit, literature)
    comparison: str = "<="  # how value relates to tolerance when it passes


def check_le(name: str, value: float, tolerance: float, reference: str = "") -> Check:
    return Check(name, float(value), float(tolerance), bool(value <= tolerance), reference, "<=")


def check_ge(name: str, value: float, tolerance: float, reference: str = "") -> Check:
    return Check(name, float(value), float(tolerance), bool(value >= tolerance), reference, ">=")


@dataclass
class Figure:
    path: Path
    caption: str         # must cite the equation or paper figure it reproduces


@dataclass
class Section:
    title: str
    text: str = ""                                          # Markdown
    checks: list[Check] = field(default_factory=list)
    figures: list[Figure] = field(default_factory=list)
    tables: list[str] = field(default_factory=list)         # Markdown tables
    datasets: list[Path] = field(default_factory=list)
    # Scientific conclusions in words and numbers, most important first; the report puts every
    # section's verdict at the top of report.html and summary.md, before the checks table.
    verdict: list[str] = field(default_factory=list)


def save_figure(fig, path, dpi) -> Path:
    """Write a matplotlib figure as PNG atomically (dhfield.io.atomic_path) and close it."""
    import matplotlib.pyplot as plt

    from dhfield.io import atomic_path

    with atomic_path(path) as tmp:
        fig.savefig(tmp, format="png", dpi=dpi)
    plt.close(fig)
    return Path(path)
