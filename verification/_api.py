"""The contract between report sections and the report builder.

Each section module ``verification/sec_<name>.py`` exposes::

    def run(outdir: pathlib.Path, quick: bool, progress: Callable[[str], None]) -> Section

It writes its figures (PNG, with SVG and PDF siblings: :func:`save_figure`) and datasets
(netCDF, via dhfield.io.write_netcdf) under ``outdir`` and returns a :class:`Section`.  ``quick=True`` must finish in a few
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
    # Each line is Markdown and every number in it is computed by the section, never typed in.
    verdict: list[str] = field(default_factory=list)
    # "Which model to use when": one Markdown line per recommendation, naming the model
    # (`--model` name) and the range of beta0 and mu, with the evidence in numbers.
    guide: list[str] = field(default_factory=list)


#: The vector sibling of every PNG figure that the report links (issue 10: figures also as SVG or PDF).
VECTOR_FORMAT = "svg"
#: Every vector sibling written beside the PNG (issue 17: PDF beside PNG and SVG).
VECTOR_FORMATS = ("svg", "pdf")
#: Metadata that would date a vector file: left out, so that the files are reproducible.
_NO_DATE = {"svg": {"Date": None}, "pdf": {"CreationDate": None, "ModDate": None}}
#: A legend may touch a curve by this many pixels (anti-aliasing, frame line) without hiding it.
LEGEND_SLACK_PX = 1.5
#: In-axes legend positions tried, in order, when a legend hides data.
_IN_AXES_LOCS = ("upper right", "upper left", "lower left", "lower right", "center right", "center left",
                 "lower center", "upper center", "center")


def _is_drawn(style):
    return style not in (None, "None", "none", "", " ")


def _data_artists(ax):
    """(label, display-space vertices, draws segments) of the data an axes shows.

    Lines and scatter collections in data coordinates; axhline/axvline-style
    reference lines (axes-coordinate transforms) and images are not data curves.
    """
    import numpy as np

    out = []
    for line in ax.get_lines():
        if not line.get_visible() or line.get_transform() is not ax.transData:
            continue
        xy = np.asarray(line.get_xydata(), dtype=float)
        if xy.size == 0:
            continue
        with np.errstate(all="ignore"):
            disp = ax.transData.transform(xy)
        segs = _is_drawn(line.get_linestyle()) and line.get_linewidth() > 0
        out.append((line.get_label(), disp, bool(segs), _is_drawn(line.get_marker())))
    for coll in ax.collections:
        if not coll.get_visible() or not hasattr(coll, "get_offsets"):
            continue
        offs = np.asarray(coll.get_offsets(), dtype=float)
        if offs.size == 0 or coll.get_offset_transform() is not ax.transData:
            continue
        with np.errstate(all="ignore"):
            out.append((coll.get_label(), ax.transData.transform(offs), False, True))
    return out


def _hits(bbox, disp, segments, markers):
    """Whether the display-space polyline/markers ``disp`` enter ``bbox``."""
    import numpy as np
    from matplotlib.path import Path as MplPath

    ok = np.all(np.isfinite(disp), axis=1)
    if markers:
        p = disp[ok]
        if np.any((p[:, 0] > bbox.x0) & (p[:, 0] < bbox.x1) & (p[:, 1] > bbox.y0) & (p[:, 1] < bbox.y1)):
            return True
    if segments:
        # contiguous finite runs (NaN breaks a line, as matplotlib draws it)
        breaks = np.flatnonzero(~ok)
        start = 0
        for stop in list(breaks) + [len(disp)]:
            run = disp[start:stop]
            if len(run) >= 2 and MplPath(run).intersects_bbox(bbox, filled=False):
                return True
            if len(run) == 1 and bbox.contains(*run[0]):
                return True
            start = stop + 1
    return False


def _overlaps(fig, draw=True):
    """(legend, label of the hidden curve) for every curve a legend covers.

    ``draw=False`` reuses the layout of the last draw (legend extents are computed
    without drawing; the axes must not have moved since).
    """
    from matplotlib.transforms import Bbox

    if draw:
        fig.draw_without_rendering()  # layout (tight/constrained) and legend positions, no pixels
    renderer = fig.canvas.get_renderer()
    legends = [ax.get_legend() for ax in fig.axes if ax.get_legend() is not None] + list(fig.legends)
    out = []
    for leg in legends:
        if not leg.get_visible():
            continue
        box = leg.get_window_extent(renderer)
        box = Bbox.from_extents(box.x0 + LEGEND_SLACK_PX, box.y0 + LEGEND_SLACK_PX,
                                box.x1 - LEGEND_SLACK_PX, box.y1 - LEGEND_SLACK_PX)
        for ax in fig.axes:
            inter = Bbox.intersection(box, ax.bbox)
            if inter is None or inter.width <= 0 or inter.height <= 0:
                continue
            out += [(leg, label) for label, disp, segs, marks in _data_artists(ax) if _hits(inter, disp, segs, marks)]
    return out


def hidden_by_legends(fig):
    """Data curves of ``fig`` that a legend covers, as ``"legend hides <label>"`` strings.

    A legend hides a curve when a drawn segment or marker of the curve passes under
    the legend box (shrunk by :data:`LEGEND_SLACK_PX`) inside the visible plot area.
    Reference lines drawn in axes coordinates (``axhline``) and images are ignored.
    Lays the figure out once (no rendering).
    """
    return [f"legend hides {label!r}" for _, label in _overlaps(fig)]


def _clear_of(boxes, leg, renderer):
    """Whether the legend's box stays off every bbox of ``boxes`` (the other axes, with labels)."""
    box = leg.get_window_extent(renderer)
    for other in boxes:
        inter = box.intersection(box, other)
        if inter is not None and inter.width > 0 and inter.height > 0:
            return False
    return True


def fix_legends(fig, draw=True):
    """Move every legend that hides a data curve to a place where it hides none.

    Tries, for each offending axes legend, the in-axes corners and edges, then
    outside the axes to the right of it or below it (clear of the other axes), then
    one figure legend under all axes.  Font size, columns and entries are kept.
    Save with ``bbox_inches="tight"`` so that a legend outside the axes is not cut.

    ``draw=False`` trusts the layout of the last draw (e.g. right after a savefig).

    Returns
    -------
    list of str
        What still hides data after the moves (empty when every legend is clear).
    """
    bad = {id(leg) for leg, _ in _overlaps(fig, draw=draw)}
    if not bad:
        return []
    renderer = fig.canvas.get_renderer()
    for ax in list(fig.axes):
        leg = ax.get_legend()
        if leg is None or id(leg) not in bad:
            continue
        handles, labels = leg.legend_handles, [t.get_text() for t in leg.get_texts()]
        kw = dict(fontsize=leg.prop.get_size_in_points(), ncols=getattr(leg, "_ncols", 1),
                  title=leg.get_title().get_text() or None)

        others = [o.get_tightbbox(renderer) or o.bbox for o in fig.axes if o is not ax and o.get_visible()]

        def clear(new):
            return not any(hit is new for hit, _ in _overlaps(fig, draw=False)) and _clear_of(others, new, renderer)

        candidates = [dict(loc=loc) for loc in _IN_AXES_LOCS]
        candidates += [dict(loc="upper left", bbox_to_anchor=(1.02, 1.0), ncols=1),
                       dict(loc="upper center", bbox_to_anchor=(0.5, -0.16), ncols=max(kw["ncols"], 2))]
        if not any(clear(ax.legend(handles, labels, **dict(kw, **c))) for c in candidates):
            ax.get_legend().remove()
            fig.draw_without_rendering()
            bottom = min(a.get_tightbbox(renderer).y0 for a in fig.axes)
            fig.legend(handles, labels, loc="upper center", bbox_to_anchor=(0.5, bottom / fig.bbox.height),
                       bbox_transform=fig.transFigure, **dict(kw, ncols=min(4, max(1, len(labels)))))
    return hidden_by_legends(fig)


def _legends(fig):
    return [ax.get_legend() for ax in fig.axes if ax.get_legend() is not None] + list(fig.legends)


def _legend_outside_canvas(fig):
    renderer = fig.canvas.get_renderer()
    return any(not (fig.bbox.contains(*box.p0) and fig.bbox.contains(*box.p1))
               for box in (leg.get_window_extent(renderer) for leg in _legends(fig)))


def save_figure(fig, path, dpi) -> Path:
    """Write a matplotlib figure as PNG with SVG and PDF siblings, atomically, and close it.

    Log axes get ticks whose labels never overlap (:func:`verification._style.tidy_log_ticks`).
    Legends that hide a data curve are moved (:func:`fix_legends`, checked on the
    layout of the PNG's own draw, so that a figure whose legends are clear costs no
    extra pass); a legend that then reaches outside the canvas is kept in the
    picture by ``bbox_inches="tight"``.  Every file is written through
    :func:`dhfield.io.atomic_path`; the vector files carry no date, so that they
    are reproducible.

    Returns
    -------
    Path
        The PNG path (the siblings are ``Path(path).with_suffix(".svg")`` and ``".pdf"``).
    """
    import warnings

    import matplotlib.pyplot as plt

    from dhfield.io import atomic_path
    from verification._style import tidy_log_ticks

    path = Path(path)
    try:
        for ax in fig.axes:
            tidy_log_ticks(ax)
        with atomic_path(path) as tmp:
            fig.savefig(tmp, format="png", dpi=dpi)  # draws: the layout below is this one
        kw = {}
        if _legends(fig) and _overlaps(fig, draw=False):
            still = fix_legends(fig, draw=False)
            if still:
                warnings.warn(f"{path.name}: {'; '.join(still)}", stacklevel=2)
            kw = dict(bbox_inches="tight", pad_inches=0.05) if _legend_outside_canvas(fig) else {}
            with atomic_path(path) as tmp:
                fig.savefig(tmp, format="png", dpi=dpi, **kw)
        for fmt in VECTOR_FORMATS:
            with atomic_path(path.with_suffix("." + fmt)) as tmp:
                fig.savefig(tmp, format=fmt, metadata=_NO_DATE[fmt], **kw)
    finally:
        plt.close(fig)
    return path
