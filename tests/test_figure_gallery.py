"""The before/after figure gallery (verification/figure_gallery.py): its "after" part runs on this tree.

Tiny inputs (a 2 x 2 sweep, the BEM at N = 32, no report) in a temporary directory; the
full gallery (docs/developer/figure_gallery.rst) is drawn by ``python -m verification.figure_gallery``.
"""
from __future__ import annotations

import json
from pathlib import Path

import pytest

from verification import figure_gallery as fg

ROOT = Path(__file__).resolve().parent.parent


def test_gallery_draws_every_command_figure_of_this_tree(tmp_path, monkeypatch):
    pytest.importorskip("PIL")
    monkeypatch.setenv("MPLBACKEND", "Agg")
    log = []
    notes = fg.draw_tree(ROOT, tmp_path / "work", report=False, log=log, small=True)
    assert notes == {}, notes  # this tree draws them all: plot (with SI axes), fit, solve, cycle
    assert all(entry["returncode"] == 0 for entry in log), log
    manifest = fg.collect(tmp_path / "work", tmp_path / "gallery" / "after", notes, log, 0.0)
    drawn = set(manifest["figures"])
    assert {"plot_pull_off", "plot_error", "plot_ellipticity", "plot_si_pull_off", "plot_si_error", "fit",
            "solve", "cycle"} <= drawn
    assert set(manifest["not_drawn"]) == {name for name in fg.FIGURES if name.startswith("report_")}
    for name in drawn:  # shrunk copies: PNG, at most MAX_WIDTH_PX wide
        from PIL import Image

        with Image.open(tmp_path / "gallery" / "after" / f"{name}.png") as im:
            assert im.format == "PNG" and im.width <= fg.MAX_WIDTH_PX
    # every command's vector siblings: the figures are written as PNG, SVG and PDF
    work = tmp_path / "work"
    for png in (work / "fit.png", work / "solve.png", work / "cycle.png", work / "maps" / "sweep_error.png"):
        assert png.with_suffix(".pdf").read_bytes()[:5] == b"%PDF-"
        assert "<svg" in png.with_suffix(".svg").read_text()[:2000]
    assert json.loads((tmp_path / "gallery" / "after" / "manifest.json").read_text())["figures"]


def test_shrink_png_keeps_small_images_and_narrows_wide_ones(tmp_path):
    Image = pytest.importorskip("PIL.Image")
    for width in (300, 2 * fg.MAX_WIDTH_PX):
        src = tmp_path / f"w{width}.png"
        Image.new("RGB", (width, 100), "white").save(src)
        fg.shrink_png(src, tmp_path / f"out{width}.png")
        with Image.open(tmp_path / f"out{width}.png") as im:
            assert im.width == min(width, fg.MAX_WIDTH_PX) and im.mode == "P"  # palette: a fraction of the bytes
            assert im.height == round(100 * im.width / width)
