"""The report's first screen (issue 40): one sentence and one table, read from the stored truth.

* The sentence names the registry's recommended model, its worst and median error at the stored
  BEM cases and the box those cases span; the numbers are re-derived here from the stored ground
  truth file itself (``data/adhesive_ground_truth_extended.nc``) and the recommended model run now,
  not from the tabulated values the report reads.
* The table has one row per tabulated model, the recommended model first, with its worst and
  median error and where it is within 1 %.
* :func:`verification.headline.within_box` finds the largest box on small hand-made grids.
* The HTML and Markdown renderings put the first screen first (without running the sections).
"""
from __future__ import annotations

import re
from pathlib import Path

import numpy as np
import pytest

from dhfield.analysis import _truth_table, compare
from verification import headline as hl

ROOT = Path(__file__).resolve().parent.parent


def _truth_from_file():
    """(beta0, mu, W*_truth, error) of every finite stored case, straight from the netCDF file."""
    import xarray as xr

    with xr.open_dataset(ROOT / _truth_table.SOURCE) as ds:
        w = ds["W_star_truth"].transpose("beta0", "mu").values
        err = ds["W_star_truth_error"].transpose("beta0", "mu").values.copy()
        ladder = ds["W_star_ladder"].transpose("beta0", "mu", "n").values
        rule = ds["W_star_truth_error"].attrs.get("long_name", "")
        b, m = np.meshgrid(ds["beta0"].values, ds["mu"].values, indexing="ij")
    # the file's own rule where it stores no error (its long_name): the two finest N of the ladder
    assert "ladder" in rule or "finest" in rule, rule
    for i, j in zip(*np.nonzero(np.isfinite(w) & ~np.isfinite(err))):
        finite = ladder[i, j][np.isfinite(ladder[i, j])]
        err[i, j] = abs(finite[-1] - finite[-2])
    ok = np.isfinite(w)
    return b[ok], m[ok], w[ok], err[ok]


def test_sentence_is_the_recommended_model_against_the_stored_file():
    b, m, w, err = _truth_from_file()
    now = np.array([compare.pull_off(compare.RECOMMENDED_MODEL, beta0=x, mu=y, warn=False).W_star
                    for x, y in zip(b, m)])
    e = (np.abs(now - w) + err) / np.abs(w)
    sentence = hl.headline_sentence()
    assert sentence.startswith(f"**Use `{compare.RECOMMENDED_MODEL}`**")
    assert f"within **{100 * e.max():.2f} %**" in sentence
    assert f"median {100 * np.median(e):.2f} %" in sentence
    assert f"every one of the {b.size} stored cases" in sentence
    assert f"β0 = {b.min():g}–{b.max():g}" in sentence and f"μ = {m.min():g}–{m.max():g}" in sentence
    # the whole stored truth: the mu = 10 cases are inside the stated domain
    assert m.max() == 10.0 and np.sum(m == 10.0) >= 6


def test_table_has_every_model_the_recommended_first():
    table = hl.headline_table().splitlines()
    assert table[0].startswith("| model | worst error | median error | cases within 1 % |")
    rows = table[2:]
    names = [re.match(r"\| `([\w-]+)`", r).group(1) for r in rows]
    assert names[0] == compare.RECOMMENDED_MODEL and "(recommended)" in rows[0]
    assert sorted(names) == sorted(_truth_table.W_STAR_MODEL)
    # the paper's model, recomputed from the tabulated W* and the file's truth: worst and median
    b, m, w, err = _truth_from_file()
    paper = np.asarray(_truth_table.W_STAR_MODEL[compare.PAPER_MODEL], float)
    e = (np.abs(paper - w) + err) / np.abs(w)
    row = rows[names.index(compare.PAPER_MODEL)]
    assert f"| {100 * e.max():.2f} % " in row and f"| {100 * np.median(e):.2f} % |" in row
    assert f"| {int(np.sum(e <= 0.01))} of {e.size} |" in row


def test_within_box_on_hand_made_grids():
    b, m = np.meshgrid([0.1, 0.5, 1.0], [0.1, 1.0, 10.0], indexing="ij")
    b, m = b.ravel(), m.ravel()
    e = np.full(b.size, 0.005)
    assert hl.within_box(b, m, e) == ((0.1, 1.0), (0.1, 10.0), 9)
    e[(b == 0.1) & (m == 10.0)] = 0.02          # one corner out: the larger of the 6-case boxes, wider beta0
    assert hl.within_box(b, m, e) == ((0.1, 1.0), (0.1, 1.0), 6)
    e[(b == 0.5) & (m == 1.0)] = np.nan         # a refused case is not within
    box = hl.within_box(b, m, e)
    assert box[2] == 3
    assert hl.within_box(b, m, np.full(b.size, 0.5)) is None


@pytest.mark.parametrize("fmt", ["html", "md"])
def test_first_screen_comes_first_without_running_sections(fmt):
    from verification import report

    screen = ("**Use `x`**: a sentence.", "| model | worst error |\n|---|---:|\n| `x` | 1 % |")
    if fmt == "html":
        text = report.render_html([], {}, ROOT, 0.0, screen)
        i_first, i_verdict = text.index("id='first-screen'"), text.index("id='verdict'")
        assert i_first < i_verdict
        assert "<strong>Use <code>x</code></strong>" in text and "<td><code>x</code></td>" in text
    else:
        text = report.render_summary([], {}, ROOT, 0.0, screen)
        lines = text.splitlines()
        assert lines[2] == "## Which model to use" and lines[4] == screen[0]
        assert text.index(screen[1]) < text.index("## Verdict")


def test_bem_comparison_figure_includes_the_recommended_model(tmp_path, monkeypatch):
    """Issue 40: the adhesive section's figure of every model against the BEM lacked the recommended one."""
    import matplotlib
    import xarray as xr

    matplotlib.use("Agg")
    from verification import sec_adhesive
    from verification._style import model_label

    labels = []
    real = sec_adhesive.legend_below
    monkeypatch.setattr(sec_adhesive, "legend_below",
                        lambda fig, handles, names, **kw: (labels.extend(names), real(fig, handles, names, **kw))[1])
    with xr.open_dataset(sec_adhesive.DATASET) as ds:
        tab = sec_adhesive.truth_table(ds)
        w_bem = ds["W_star_extrapolated"].transpose("beta0", "mu").values
    fig = sec_adhesive._figure(tab, tmp_path, 40)
    assert labels[0] == model_label(compare.RECOMMENDED_MODEL)
    assert f"`{compare.RECOMMENDED_MODEL}`" in fig.caption
    # its points are the recommended model against the stored BEM: recomputed here point by point
    dev = sec_adhesive.recommended_deviation(tab)
    i, j = 2, 3
    ref = compare.pull_off(compare.RECOMMENDED_MODEL, beta0=float(tab["beta0"][i]), mu=float(tab["mu"][j]),
                           warn=False).W_star / w_bem[i, j] - 1.0
    assert dev[i, j] == pytest.approx(ref, rel=1e-12)
