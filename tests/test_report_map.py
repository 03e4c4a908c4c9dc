"""The report's adhesion-map section (verification/sec_map.py) runs, opens the report and says where
its reference is validated.

Provenance: the recommended model's worst deviation from the stored BEM is re-derived here from
both ground truths (data/adhesive_ground_truth.nc, W_star_extrapolated, and
data/adhesive_ground_truth_slender.nc, W_star at its finest level; W* of Eq. 34), read here with
xarray directly, and dhfield.analysis.adhesion_map's adapter, independently of the section's own code path.
The validated box is the box of every stored case, read here from the extended ground truth's own
coordinates (beta0 0.1-1, mu 0.1-10: the six mu = 10 cases included, issue 40), and both figures
draw every one of its cases.
"""
from __future__ import annotations

import re

import numpy as np
import pytest

from verification import report, sec_map


@pytest.fixture(scope="module")
def section(tmp_path_factory):
    import matplotlib

    matplotlib.use("Agg")
    out = tmp_path_factory.mktemp("map")
    lines = []
    return sec_map.run(out, True, lines.append), out, lines


def test_map_section_runs_and_passes(section):
    sec, out, lines = section
    assert sec.checks and all(c.passed for c in sec.checks), [c for c in sec.checks if not c.passed]
    assert report._validate_section("map", sec) == []
    # the map first, then the practitioner's figure; PNG with SVG and PDF siblings
    names = [f.path.name for f in sec.figures]
    assert names == ["adhesion_map.png", "practitioner_pull_off.png"]
    for f in sec.figures:
        assert f.path.with_suffix(".svg").is_file() and f.path.with_suffix(".pdf").read_bytes()[:4] == b"%PDF"
    assert lines and lines[-1] == "figures"


def test_map_section_states_the_validated_box_and_the_worst_case(section):
    import xarray as xr

    from dhfield.analysis.adhesion_map import recommended_pull_off
    from dhfield.core.geometry import sin_skew_angle

    sec, _, _ = section
    text = " ".join(sec.verdict)
    # issue 40: the box of the whole stored truth, mu = 10 included (it said 0.3 <= mu <= 5 before)
    with xr.open_dataset(sec_map.ROOT / "data" / "adhesive_ground_truth_extended.nc") as ds:
        finite = np.isfinite(ds["W_star_truth"].transpose("beta0", "mu").values)
        bb, mm = np.meshgrid(ds["beta0"].values, ds["mu"].values, indexing="ij")
    assert (bb[finite].min(), mm[finite].min(), mm[finite].max()) == (0.1, 0.1, 10.0)
    assert "validated against the BEM only inside β0 ≥ 0.1 (θ ≥ 19°), 0.1 ≤ μ ≤ 10** (the box of every stored case)" in text
    assert "0.3 ≤ μ ≤ 5" not in text + " ".join(sec.guide) + " ".join(f.caption for f in sec.figures)
    assert "BEM-validated" not in text  # that label is on the figure; the verdict says it in words
    b, m, w_bem = [], [], []
    for name, read in (("adhesive_ground_truth.nc", lambda ds: ds["W_star_extrapolated"]),
                       ("adhesive_ground_truth_slender.nc", lambda ds: ds["W_star"].isel(level=-1))):
        with xr.open_dataset(sec_map.ROOT / "data" / name) as ds:
            w = read(ds).transpose("beta0", "mu")
            bb, mm = np.meshgrid(ds["beta0"].values, ds["mu"].values, indexing="ij")
            ok = np.isfinite(w.values)
            b.append(bb[ok]), m.append(mm[ok]), w_bem.append(w.values[ok])
    b, m, w_bem = (np.concatenate(x) for x in (b, m, w_bem))
    assert b.size == 42  # 6 x 5 + 3 x 4 stored cases
    dev = recommended_pull_off(beta0=b, mu=m) / w_bem - 1.0  # W*/W*_BEM - 1 = F/F_BEM - 1 (same sin)
    assert f"within {100 * np.max(np.abs(dev)):.2f} % of every one of the {dev.size} stored BEM cases" in text
    from verification.adhesion_map import read_truth, validated_extent

    assert validated_extent(read_truth()) == ((0.1, 1.0), (0.3, 5.0))
    np.testing.assert_allclose(2.0 * w_bem / sin_skew_angle(b), read_truth()["force"], rtol=1e-15)
    assert re.search(r"Numerical JKR limit.*GVG is within \d+\.\d+ %", text)


def test_figures_draw_every_stored_case_and_the_stored_box(section, tmp_path):
    """Issue 40: the map and the practitioner's figure said "validated μ ≤ 5" with six μ = 10 cases stored."""
    import matplotlib

    matplotlib.use("Agg")
    from matplotlib.figure import Figure as MplFigure

    from verification import adhesion_map as vam

    sec, _, _ = section
    n = int(np.isfinite(__import__("xarray").open_dataset(vam.GROUND_TRUTH_EXTENDED)["W_star_truth"].values).sum())
    assert f"every one of the {n} stored BEM cases" in sec.figures[0].caption
    assert "0.1 ≤ μ ≤ 10" in sec.figures[0].caption
    # the figures' own titles: capture the text matplotlib draws
    titles = []
    orig = MplFigure.suptitle

    def keep(self, t, **kw):
        titles.append(t)
        return orig(self, t, **kw)

    MplFigure.suptitle = keep
    try:
        whole = vam.read_truth(vam.GROUND_TRUTH_EXTENDED)
        from dhfield.io.adhesion_map import read_adhesion_map

        stored = read_adhesion_map(sec_map.MAP_DATASET)
        import dataclasses

        box_b, box_m = vam.stored_box(whole)
        stored = dataclasses.replace(stored, validated_beta0=box_b, validated_mu=box_m)
        vam.map_figure(stored, whole, vam.truth_deviation(whole), tmp_path / "m", dpi=40)
        vam.practitioner_figure(sec_map._columns(stored, vam.PRACTITIONER_MU), None, whole, tmp_path / "p", dpi=40)
    finally:
        MplFigure.suptitle = orig
    assert all("0.1 ≤ μ ≤ 10" in t for t in titles) and not any("μ ≤ 5" in t for t in titles), titles
    assert f"({n} BEM cases)" in titles[0]


def test_map_section_states_the_worst_case_of_the_extended_ground_truth(section):
    # re-derived from data/adhesive_ground_truth_extended.nc (W_star_truth, each case's best BEM value,
    # read here with xarray directly) and dhfield.analysis.adhesion_map's adapter
    import xarray as xr

    from dhfield.analysis.adhesion_map import recommended_pull_off

    sec, _, _ = section
    with xr.open_dataset(sec_map.ROOT / "data" / "adhesive_ground_truth_extended.nc") as ds:
        w = ds["W_star_truth"].transpose("beta0", "mu").values
        bb, mm = np.meshgrid(ds["beta0"].values, ds["mu"].values, indexing="ij")
        study = ds["extended_study"].transpose("beta0", "mu").values.astype(bool)
    ok = np.isfinite(w)
    dev = recommended_pull_off(beta0=bb[ok], mu=mm[ok]) / w[ok] - 1.0
    text = " ".join(sec.verdict)
    assert (f"{int((ok & study).sum())} of the {int(study.sum())} points of the extended study answered" in text
            and f"within {100 * np.max(np.abs(dev)):.2f} % of every case" in text and f"{ok.sum()} cases" in text)
    row = [c for c in sec.checks if "extended BEM ground truth" in c.name]
    assert len(row) == 1 and row[0].value == pytest.approx(np.max(np.abs(dev)), rel=1e-12)


def _top_mu_dataset(status2, w2, message2=("", ""), nx1=(1280, 1280)):
    import xarray as xr

    # beta0 (0.5, 1) x mu (1, 10) x level (1, 2); the study is every point; mu = 10 level 1: W* -0.65
    # and -0.75 with stated errors 0.01 and 0.02
    w = np.full((2, 2, 2), -0.5)
    w[:, 1, 0] = (-0.65, -0.75)
    w[:, 1, 1] = w2
    err = np.full((2, 2, 2), 0.01)
    err[1, 1, 0] = 0.02
    status = np.full((2, 2, 2), "ok", dtype=object)
    status[:, 1, 1] = status2
    message = np.full((2, 2, 2), "", dtype=object)
    message[:, 1, 1] = message2
    # cells: level 1 nx1 (square), level 2 2560^2 (twice 1280: the planned lattice)
    nx = np.full((2, 2, 2), 2560.0)
    nx[:, :, 0] = np.asarray(nx1, float)[:, None]
    dims = ("beta0", "mu", "level")
    return xr.Dataset({"W_star": (dims, w), "W_star_error": (dims, err), "status": (dims, status),
                       "nx": (dims, nx), "ny": (dims, nx),
                       "message": (dims, message.astype(str)),
                       "extended_study": (("beta0", "mu"), np.ones((2, 2), dtype=np.int8))},
                      coords={"beta0": [0.5, 1.0], "mu": [1.0, 10.0], "level": [1, 2]})


def test_top_mu_levels_counts_the_cases_converged_on_both_levels():
    none = sec_map.top_mu_levels(_top_mu_dataset(("failed", "not_converged"), (np.nan, -0.7)))
    assert (none["mu"], none["n"], none["n_level2"]) == (10.0, 2, 0) and np.isnan(none["max_step"])
    assert "not yet measured" in sec_map.top_mu_sentence(none)
    # beta0 1 converged on level 2 at -0.751: step 0.001 = 0.001/0.75 of W*, 0.05 of its error 0.02
    one = sec_map.top_mu_levels(_top_mu_dataset(("failed", "ok"), (np.nan, -0.751)))
    assert (one["n"], one["n_level2"], one["beta0_level2"]) == (2, 1, [1.0])
    assert one["max_step"] == pytest.approx(0.001 / 0.75) and one["max_step_over_error"] == pytest.approx(0.05)
    line = sec_map.top_mu_sentence(one)
    assert "1 of 2 cases (β0 = 1) converged on level 2 too (2× level 1's cells per axis)" in line
    assert "at most 0.133 %" in line and one["refinement"] == (2.0, 2.0)
    assert one["beta0_level1_only"] == [0.5]
    assert "; the other (β0 = 0.5) is a single-grid (level 1) value with a calibrated error" in line
    # two cases on level 1 only: the plural names both
    two = dict(one, n=3, beta0_level1_only=[0.3, 0.5])
    assert "; the other 2 (β0 = 0.3, 0.5) are single-grid (level 1) values" in sec_map.top_mu_sentence(two)
    # both: beta0 0.5 steps 0.005 (0.5 of its error 0.01, 0.77 % of W*): the largest of each kind
    both = sec_map.top_mu_levels(_top_mu_dataset(("ok", "ok"), (-0.655, -0.751)))
    assert both["n_level2"] == 2 and both["max_step_over_error"] == pytest.approx(0.5)
    assert both["max_step"] == pytest.approx(0.005 / 0.65) and "the other" not in sec_map.top_mu_sentence(both)
    assert both["beta0_level1_only"] == []
    assert both["beta0_widest"] == [] and "edge held" not in sec_map.top_mu_sentence(both)
    # beta0 0.5's level 1 answered on its retry lattice 1440^2 (beta0 = 0.8 at mu = 10 stored so): 2560/1440
    retry = sec_map.top_mu_levels(_top_mu_dataset(("ok", "ok"), (-0.655, -0.751), nx1=(1440, 1280)))
    assert retry["refinement"] == pytest.approx((2560 / 1440, 2.0))
    assert "(1.78–2× level 1's cells per axis)" in sec_map.top_mu_sentence(retry)


def test_top_mu_sentence_names_the_levels_solved_with_the_edge_held_at_two_cells():
    from dhfield.analysis.bem_start import WIDEST_EDGE_NOTE

    # beta0 0.5's level 2 with the widest edge (its note), beta0 1's with its own; a failed level 2 with the
    # note is not counted
    top = sec_map.top_mu_levels(_top_mu_dataset(("ok", "ok"), (-0.655, -0.751), (WIDEST_EDGE_NOTE, "")))
    # the stored records of 5755b0d said "on every grid": the mark is what is read
    old = "Dugdale edge held at its cap 2 h0 on every grid (options.widest_edge)"
    assert sec_map.top_mu_levels(_top_mu_dataset(("ok", "ok"), (-0.655, -0.751), (old, "")))["beta0_widest"] == [0.5]
    assert top["beta0_level2"] == [0.5, 1.0] and top["beta0_widest"] == [0.5]
    assert "per axis; β0 = 0.5 with the Dugdale edge held at its widest, 2 h0" in sec_map.top_mu_sentence(top)
    lost = sec_map.top_mu_levels(_top_mu_dataset(("failed", "ok"), (np.nan, -0.751), (WIDEST_EDGE_NOTE, "")))
    assert lost["beta0_widest"] == [] and "edge held" not in sec_map.top_mu_sentence(lost)


def test_map_leads_the_report():
    assert report.SECTION_ORDER[0] == "map" and report.VERDICT_ORDER[0] == "map"
    from verification._api import Check, Section

    res = [report.SectionResult(n, Section(n, verdict=[n.upper()], guide=[f"use {n}"]), 0.0, None, False, "",
                                [Check("c", 0.0, 1.0, True)]) for n in ("analytic", "adhesive", "map")]
    verdict, guide = report.collect_verdict(res)
    assert [t for _, t in verdict] == ["MAP", "ADHESIVE", "ANALYTIC"]
    assert guide[0] == ("map", "use map")


def test_domain_of_reads_bands_of_the_map():
    from dhfield.analysis import adhesion_map as am

    r = am.adhesion_map([30.0, 60.0, 90.0], [0.01, 1.0, 100.0], models=("md", "jkr-elliptic-energy", "dmt"))
    md = sec_map.domain_of(r, "md")
    # from 60 deg on the sphere is within 1 % at every mu (GVG at 60 deg: 1.4864 against 1.5, -0.9 %; at 30 deg
    # 1.4333, -4.4 %); every model is DMT at mu = 0.01 to < 1 %
    assert md["angle_min"] == 60.0 and md["mu_max"] == 0.01
    gvg = sec_map.domain_of(r, "jkr-elliptic-energy")
    assert gvg["mu_min"] == 100.0 and gvg["angle_min"] is None
    assert sec_map.domain_of(r, "dmt")["mu_min"] is None
