"""Error metrics of BEM fields (dhfield.analysis.field_metrics): statistics, region masks, the annulus identity h = (1 + v) h_Hertz."""
from __future__ import annotations

import math

import numpy as np
import pytest

from dhfield import bem
from dhfield.analysis import field_metrics, fields
from dhfield.models import hertz

#: Annulus identity on 256^2 cells (beta0 = 0.9, mu = 1, a* = 1.2): measured 7.9e-4 relative
#: to max (1+v) h_H; O(h^1.5) discretisation of the square-root edges plus spline interpolation.
RTOL_ANNULUS_256 = 1.5e-3
#: Analytic identity h_DH = (1+v) h_H in the annulus (both closed forms): rounding only.
RTOL_ANALYTIC_IDENTITY = 1e-10
#: Error ratio between N = 64 and 128 for an O(h^1.5) error is 2.8; 2^1.2 = 2.3 leaves margin.
MIN_RATIO_ANNULUS = 2.0 ** 1.2
CASE = dict(beta0=0.9, mu=1.0, a_star=1.2)


@pytest.fixture(scope="module")
def dh256():
    return fields.model_case(256, CASE["beta0"], CASE["mu"], CASE["a_star"])


def test_compare_statistics():
    ana = np.array([[1.0, 2.0], [3.0, 4.0]])
    num = ana + np.array([[0.1, -0.2], [0.0, 0.0]])
    masks = {"a": np.array([[True, True], [False, False]]), "empty": np.zeros((2, 2), bool)}
    st = field_metrics.compare(num, ana, masks)
    assert st["all"]["max"] == pytest.approx(0.2)
    assert st["a"]["rms"] == pytest.approx(math.sqrt((0.01 + 0.04) / 2))
    assert st["a"]["rel_max"] == pytest.approx(0.2 / 4.0)
    assert math.isnan(st["empty"]["max"]) and st["empty"]["count"] == 0
    with pytest.raises(ValueError, match="same shape"):
        field_metrics.compare(num, ana[:1])


def test_region_masks_partition_the_plane():
    grid = bem.Grid.centered(40, 2.0)
    x, y = grid.mesh()
    m = field_metrics.region_masks(x, y, 1.0, 0.8, 1.5)
    total = m["contact"].astype(int) + m["annulus"] + m["outside"]
    assert np.all(total == 1)
    assert m["contact"][20, 20] and m["outside"][0, 0]


def test_annulus_identity(dh256):
    res = field_metrics.annulus_identity(dh256)
    assert res["theta_p"][0] == 0.0 and res["theta_p"][-1] == pytest.approx(np.pi / 2)
    assert res["worst"] <= RTOL_ANNULUS_256
    # the analytic DH gap (Eq. 27) is (1+v) times the Hertz gap in the annulus
    prm = dh256.parameters
    x, y = dh256.grid.mesh()
    ann = dh256.masks["annulus"]
    h_h = hertz.gap(x[ann], y[ann], prm["semi_major"], prm["beta"])
    scale = np.max(np.abs(h_h))
    assert np.max(np.abs(dh256.gap_analytic[ann] - (1 + prm["scaling"]) * h_h)) <= RTOL_ANALYTIC_IDENTITY * scale


def test_annulus_identity_converges():
    coarse = field_metrics.annulus_identity(fields.model_case(64, **CASE))["worst"]
    fine = field_metrics.annulus_identity(fields.model_case(128, **CASE))["worst"]
    assert coarse / fine >= MIN_RATIO_ANNULUS
