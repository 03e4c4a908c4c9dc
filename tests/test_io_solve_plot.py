"""The figure of ``dhfield solve --plot`` (dhfield.io.solve_plot): it runs, in both unit systems."""
import math

import numpy as np
import pytest

from dhfield.bem import adhesive_pull_off
from dhfield.analysis.dimensional import contact_parameters
from dhfield.io.solve_plot import _prefix, solve_figure, write_solve_plot


@pytest.fixture(scope="module")
def pdms():
    """README's PDMS cylinders at sigma0 = 23.1 kPa (mu = 1.0003) and their BEM pull-off at N = 64."""
    params = contact_parameters(2e6, 0.5, 2e6, 0.5, 5e-3, math.radians(60.0), 0.04, 2.31e4)
    return params, adhesive_pull_off(mu=float(params.mu), beta0=float(params.beta0), n=64, progress=False)


def test_figure_si_axes(pdms):
    import matplotlib.pyplot as plt

    params, res = pdms
    fig = solve_figure(res, params)
    try:
        labels = [ax.get_xlabel() + " " + ax.get_ylabel() for ax in fig.axes]
        assert "[µm]" in labels[0] and "force W [mN]" in labels[2] and "approach δ [µm]" in labels[2]
        assert any("pressure p [kPa]" in ax.get_ylabel() for ax in fig.axes)  # the colour bar
        assert "mN" in fig._suptitle.get_text()
    finally:
        plt.close(fig)


def test_figure_paper_units_and_files(tmp_path, pdms):
    _, res = pdms
    png, svg, pdf = write_solve_plot(res, tmp_path / "nd.png")
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and svg.stat().st_size > 1000
    assert pdf.read_bytes()[:4] == b"%PDF"
    with pytest.raises(ValueError, match="plot must be a .png"):
        write_solve_plot(res, tmp_path / "x.jpg")


@pytest.mark.parametrize("value, scale, label", [
    (1.147e-3, 1e-3, "mN"), (2.2e-4, 1e-6, "µm"), (23100.0, 1e3, "kPa"), (0.5, 1e-3, "mN"), (3.0, 1.0, "N"),
    (0.0, 1.0, "N"), (np.nan, 1.0, "N")])
def test_si_prefix(value, scale, label):
    """A magnitude in [1, 1000) of the prefixed unit (by definition of the SI prefixes)."""
    unit = "m" if label.endswith("m") and label != "mN" else "Pa" if label.endswith("Pa") else "N"
    assert _prefix(value, unit) == (scale, label)
