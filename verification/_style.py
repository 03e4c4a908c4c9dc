"""One figure style for the verification report: print sizes, fonts, log ticks, labels.

Every report figure is drawn at the size it is printed at, so that no font shrinks
below :data:`MIN_FONT_PT` on paper: a single-panel figure is one journal column
(:data:`SINGLE_COLUMN_IN` wide), a figure with several panels spans the page
(:data:`DOUBLE_COLUMN_IN`).  :func:`figure_style` is the matplotlib rcParams
context the report draws in; :func:`tidy_log_ticks` (called by
:func:`verification._api.save_figure` on every log axis) gives log axes ticks whose
labels never overlap; :data:`MODEL_LABELS` holds the readable name of every model
slug (the library's table of ``dhfield.io.figures``); :func:`rel_diff_label` writes
the one sign convention of a relative difference, ``model/ref − 1``.

matplotlib is imported inside the functions: importing this module costs nothing.
"""
from __future__ import annotations

import contextlib
import math

# The readable name of each model slug: the library's one table (``dhfield plot``, ``fit --plot``,
# ``solve --plot`` and ``cycle --plot`` use it too), so that a model has one name everywhere.
from dhfield.io.figures import MODEL_LABELS, model_label  # noqa: F401 - re-exported for the sections

#: Width of a single-column figure [in] (a two-column journal page's column).
SINGLE_COLUMN_IN = 3.3
#: Width of a full-page (two-column) figure [in].
DOUBLE_COLUMN_IN = 7.0
#: The smallest font on paper [pt]; figures are drawn at print size, so this is the rcParams size.
MIN_FONT_PT = 8.0

#: rcParams of every report figure (fonts in pt at print size).
RC = {
    "font.size": MIN_FONT_PT,
    "axes.titlesize": MIN_FONT_PT + 1,
    "axes.labelsize": MIN_FONT_PT,
    "xtick.labelsize": MIN_FONT_PT,
    "ytick.labelsize": MIN_FONT_PT,
    "legend.fontsize": MIN_FONT_PT,
    "legend.title_fontsize": MIN_FONT_PT,
    "figure.titlesize": MIN_FONT_PT + 1,
    "legend.framealpha": 0.85,
    "legend.handlelength": 1.8,
    "legend.borderaxespad": 0.3,
    "legend.labelspacing": 0.3,
    "legend.columnspacing": 1.0,
    "lines.linewidth": 1.2,
    "lines.markersize": 4.0,
    "axes.linewidth": 0.6,
    "grid.linewidth": 0.4,
    "xtick.major.width": 0.6,
    "ytick.major.width": 0.6,
    "xtick.minor.width": 0.4,
    "ytick.minor.width": 0.4,
    # pdf.fonttype stays 3 (Type 3 subsets): TrueType (42) doubles the PDF's write time (measured 0.74 s
    # against 0.35 s for a two-panel figure), and the report's runtime budget is 10 % over the PNG + SVG one
    "savefig.pad_inches": 0.03,
}

def rel_diff_label(quantity: str = "", model: str = "model", ref: str = "BEM", percent: bool = True,
                   absolute: bool = False) -> str:
    """Axis or colour-bar label of a relative difference, with its sign convention.

    The report's one convention: ``model/ref − 1`` (positive where the model is larger).

    >>> rel_diff_label("W*max")
    'W*max: model/BEM − 1 [%]'
    """
    core = f"{model}/{ref} − 1"
    core = f"|{core}|" if absolute else core
    head = f"{quantity}: " if quantity else ""
    return head + core + (" [%]" if percent else "")


_PREFIXES = {-15: "f", -12: "p", -9: "n", -6: "µ", -3: "m", 0: "", 3: "k", 6: "M", 9: "G", 12: "T"}


def si_format(value: float, unit: str = "", digits: int = 3) -> str:
    """``value`` with ``digits`` significant figures and an SI prefix, e.g. ``7.94e4, 'Pa'`` -> ``'79.4 kPa'``."""
    value = float(value)
    if not math.isfinite(value) or value == 0.0:
        return f"{value:g} {unit}".strip()
    exp3 = int(math.floor(math.log10(abs(value)) / 3.0) * 3)
    exp3 = min(max(exp3, min(_PREFIXES)), max(_PREFIXES))
    scaled = value / 10.0 ** exp3
    text = f"{scaled:.{digits}g}"
    if abs(float(text)) >= 1000.0 and exp3 + 3 in _PREFIXES:  # rounding carried over, e.g. 999.96 -> 1000
        exp3 += 3
        text = f"{value / 10.0 ** exp3:.{digits}g}"
    return f"{text} {_PREFIXES[exp3]}{unit}".strip()


@contextlib.contextmanager
def figure_style():
    """rcParams context of every report figure (fonts of :data:`MIN_FONT_PT` at print size)."""
    import matplotlib

    with matplotlib.rc_context(RC):
        yield


def figsize(columns: int = 1, aspect: float = 0.75):
    """(width, height) [in] of a figure ``columns`` (1 or 2) journal columns wide; height = aspect × width."""
    width = SINGLE_COLUMN_IN if columns == 1 else DOUBLE_COLUMN_IN
    return (width, aspect * width)


def _tick_label(value, plain):
    """A log tick label: a plain decimal (``plain`` and 1e-3 <= value < 1e5) or m×10^n."""
    if value <= 0 or not math.isfinite(value):
        return ""
    exp = math.floor(math.log10(value) + 1e-9)
    if plain and -3 <= exp <= 4:
        return f"{value:.{max(0, -exp)}f}" if exp < 0 else f"{value:.0f}"
    mant = value / 10.0 ** exp
    if abs(mant - 1.0) < 1e-6:
        return rf"$10^{{{exp}}}$"
    return rf"${mant:.0f}\times10^{{{exp}}}$"


def tidy_log_ticks(ax):
    """Ticks of the log axes of ``ax`` whose labels never overlap.

    Decades only (labelled ``10^n``, at most about six of them) when the axis spans
    more than three decades; 1-2-5 (or 1-2-3-5 within 1.5 decades) when it spans
    fewer, so that a short axis still carries labels, written as plain numbers
    where they all lie in [1e-3, 1e5] and as m×10^n otherwise; minor ticks never
    carry labels.  Hand-placed ticks (a FixedLocator) are kept.  Call after the
    limits are final (``save_figure`` does).
    """
    from matplotlib.ticker import FixedLocator, FuncFormatter, LogFormatterSciNotation, LogLocator, NullFormatter

    for axis, scale, lim in ((ax.xaxis, ax.get_xscale(), ax.get_xlim()), (ax.yaxis, ax.get_yscale(), ax.get_ylim())):
        if scale != "log":
            continue
        if isinstance(axis.get_major_locator(), FixedLocator):  # ticks chosen by hand: keep them, unlabel minors
            axis.set_minor_formatter(NullFormatter())
            continue
        lo, hi = sorted(lim)
        if not (lo > 0 and math.isfinite(hi)):
            continue
        decades = math.log10(hi / lo)
        if decades <= 3.0:
            subs = (1.0, 2.0, 3.0, 5.0) if decades <= 1.5 else (1.0, 2.0, 5.0)  # 0.3 labelled on 0.3..5
            plain = 1e-3 <= lo and hi < 1e5
            axis.set_major_locator(LogLocator(base=10.0, subs=subs, numticks=12))
            axis.set_major_formatter(FuncFormatter(lambda v, _pos, plain=plain: _tick_label(v, plain)))
        else:
            axis.set_major_locator(LogLocator(base=10.0, subs=(1.0,), numticks=6))
            axis.set_major_formatter(LogFormatterSciNotation(base=10.0))
        axis.set_minor_locator(LogLocator(base=10.0, subs=tuple(range(2, 10)), numticks=12))
        axis.set_minor_formatter(NullFormatter())


def legend_below(fig, handles=None, labels=None, ncol=2, axes=None):
    """One legend under all panels; the figure grows by its height, so that no panel shrinks.

    ``ncol`` is the most columns: fewer are used where the legend would be wider than the figure.

    ``handles``/``labels`` default to the labelled artists of ``axes`` (all axes),
    without repeats; the axes' own legends are removed.  Works with tight layout
    (the panels are laid out again above the legend) and constrained layout.
    """
    from matplotlib.layout_engine import ConstrainedLayoutEngine

    axes = list(fig.axes if axes is None else axes)
    if handles is None:
        seen = {}
        for ax in axes:
            for h, lab in zip(*ax.get_legend_handles_labels()):
                seen.setdefault(lab, h)
        labels, handles = list(seen), list(seen.values())
    for ax in axes:
        if ax.get_legend() is not None:
            ax.get_legend().remove()
    constrained = isinstance(fig.get_layout_engine(), ConstrainedLayoutEngine)
    renderer = fig.canvas.get_renderer()
    for n in range(max(1, ncol), 0, -1):  # fewer columns until the legend fits the figure's width
        leg = fig.legend(handles, labels, loc="outside lower center" if constrained else "lower center",
                         ncol=n, frameon=False)
        box = leg.get_window_extent(renderer)
        if box.width <= fig.bbox.width or n == 1:
            break
        leg.remove()
    h_in = box.height / fig.dpi + 0.04
    w, h = fig.get_size_inches()
    fig.set_size_inches(w, h + h_in)
    if not constrained:
        fig.tight_layout(rect=(0, h_in / (h + h_in), 1, 1))
    return leg


def shared_limits(arrays, centred: bool = False):
    """(vmin, vmax) covering every finite value of ``arrays``; symmetric about 0 when ``centred``."""
    import numpy as np

    vals = np.concatenate([np.asarray(a, dtype=float).ravel() for a in arrays])
    vals = vals[np.isfinite(vals)]
    if vals.size == 0:
        return (-1.0, 1.0) if centred else (0.0, 1.0)
    if centred:
        m = float(np.max(np.abs(vals))) or 1.0
        return -m, m
    return float(vals.min()), float(vals.max())


#: PNG resolution of the quick report [dpi] (figures are at print size: 3.3 in -> about 500 px).
QUICK_DPI = 150
#: PNG resolution of the full report [dpi].
REPORT_DPI = 200
