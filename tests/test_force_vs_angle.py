"""The pull-off force against the crossing angle of one material (dhfield.analysis.force_vs_angle, its figure and CLI).

Reference values are closed forms: JKR's pull-off 3/2 pi R dgamma and DMT's 2 pi R dgamma of the circle
of R = sqrt(R'R'') = R_c/sin(theta) (Eqs. 3-5), mu of Eq. (35), and the stored BEM W* read from the
netCDF files themselves.
"""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from dhfield.analysis.compare import RECOMMENDED_MODEL
from dhfield.analysis.force_vs_angle import MU_MATCH_TOLERANCE, pull_off_force_vs_angle, stored_bem_cases
from dhfield.io.force_vs_angle_plot import model_styles

DATA = Path(__file__).resolve().parents[1] / "data"
E, NU, RC, DGAMMA = 1.8e6, 0.49, 3e-3, 0.045
E_STAR = E / (2.0 * (1.0 - NU**2))  # Eq. (6), two equal bodies


def _sigma0_for_mu_at_90(mu):
    """sigma0 [Pa] giving Tabor parameter ``mu`` at 90 deg, where R = R_c (Eq. 35 inverted)."""
    return mu * (E_STAR**2 * DGAMMA / RC) ** (1.0 / 3.0)


def test_circular_models_are_the_closed_forms_at_every_angle():
    th = np.array([30.0, 60.0, 90.0])
    t = pull_off_force_vs_angle(E, NU, RC, DGAMMA, 0.3e6, angles_deg=(30, 90), points=3, models=["jkr", "dmt"])
    np.testing.assert_allclose(t.skew_angle_deg, th)
    r = RC / np.sin(np.deg2rad(th))  # R = sqrt(R'R'') of equal crossed cylinders
    np.testing.assert_allclose(t.force["jkr"], -1.5 * math.pi * r * DGAMMA, rtol=1e-9)
    np.testing.assert_allclose(t.force["dmt"], -2.0 * math.pi * r * DGAMMA, rtol=1e-9)
    mu = 0.3e6 / np.cbrt(E_STAR**2 * DGAMMA / r)  # Eq. (35)
    np.testing.assert_allclose(t.mu, mu, rtol=1e-12)
    assert t.beta0[-1] == pytest.approx(1.0)


def test_recommended_model_always_first():
    t = pull_off_force_vs_angle(E, NU, RC, DGAMMA, 0.3e6, angles_deg=(60, 90), points=2, models=["dmt", "jkr"])
    assert t.models == (RECOMMENDED_MODEL, "dmt", "jkr")
    assert t.recommended_model == RECOMMENDED_MODEL
    with pytest.raises(ValueError, match="models must be names"):
        pull_off_force_vs_angle(E, NU, RC, DGAMMA, 0.3e6, models=["no-such-model"])
    with pytest.raises(ValueError, match="angles_deg"):
        pull_off_force_vs_angle(E, NU, RC, DGAMMA, 0.3e6, angles_deg=(0, 90))
    with pytest.raises(ValueError, match="points"):
        pull_off_force_vs_angle(E, NU, RC, DGAMMA, 0.3e6, points=1)


def test_stored_bem_cases_on_the_path_are_converted_to_newtons():
    xr = pytest.importorskip("xarray")
    from dhfield.core.geometry import skew_angle

    # mu = 1 at 90 deg; mu ~ sin(theta)^(-1/3) (Eq. 35, R = R_c/sin theta) stays within 1 % of 1 down to 80 deg,
    # so the stored mu = 1 cases at beta0 = 0.8 (80.45 deg), 0.9, 0.99 and 1 lie on the path, no other
    t = pull_off_force_vs_angle(E, NU, RC, DGAMMA, _sigma0_for_mu_at_90(1.0), angles_deg=(80, 90), points=3,
                                models=["jkr"])
    assert sorted(t.bem.beta0) == [0.8, 0.9, 0.99, 1.0] and np.all(t.bem.mu == 1.0)
    with xr.open_dataset(DATA / "adhesive_ground_truth_extended.nc") as ds:
        for b, f, fe in zip(t.bem.beta0, t.bem.force, t.bem.force_error):
            theta = float(skew_angle(b))
            unit = 2.0 * math.pi * (RC / math.sin(theta)) * DGAMMA / math.sin(theta)  # Eq. (34)
            assert f == pytest.approx(float(ds.W_star_truth.sel(beta0=b, mu=1.0)) * unit, rel=1e-12)
            assert fe == pytest.approx(float(ds.W_star_truth_error.sel(beta0=b, mu=1.0)) * unit, rel=1e-12)
    np.testing.assert_allclose(t.bem.material_mu, 1.0 / np.cbrt(np.sin(skew_angle(t.bem.beta0))), rtol=1e-12)
    # mu 2 % above every stored case there: other contacts, none drawn in newtons
    off = pull_off_force_vs_angle(E, NU, RC, DGAMMA, _sigma0_for_mu_at_90(1.0) * (1 + 2 * MU_MATCH_TOLERANCE),
                                  angles_deg=(80, 90), points=3, models=["jkr"])
    assert len(off.bem) == 0


def test_error_band_where_the_stored_cases_check_the_recommended_model():
    from dhfield.analysis.model_error import model_error

    t = pull_off_force_vs_angle(E, NU, RC, DGAMMA, _sigma0_for_mu_at_90(1.0), angles_deg=(40, 90), points=4,
                                models=["jkr"])
    np.testing.assert_allclose(t.recommended_error, model_error(RECOMMENDED_MODEL, t.beta0, t.mu))
    assert np.all(np.isfinite(t.recommended_error))
    pdms = pull_off_force_vs_angle(E, NU, RC, DGAMMA, 0.3e6, angles_deg=(60, 90), points=2, models=["jkr"])
    assert np.all(pdms.mu > 10) and np.all(np.isnan(pdms.recommended_error))  # outside the stored box


def test_the_slender_file_is_among_the_stored_cases():
    xr = pytest.importorskip("xarray")
    st = stored_bem_cases()
    with xr.open_dataset(DATA / "adhesive_ground_truth_slender.nc") as ds:
        for b in ds.beta0.values:
            for m in ds.mu.values:
                w = float(ds.W_star.sel(beta0=b, mu=m, level=2))
                i = np.flatnonzero((st.beta0 == b) & (st.mu == m))
                assert i.size == 1 and st.W_star[i[0]] == pytest.approx(w, rel=1e-12)


def test_model_styles_distinct_past_ten_models():
    names = [RECOMMENDED_MODEL] + [f"model-{i}" for i in range(30)]
    styles = model_styles(names)
    keys = {(s["color"], str(s["linestyle"]), s["marker"]) for s in styles.values()}
    assert len(keys) == len(names)
    rec = styles[RECOMMENDED_MODEL]
    assert rec["color"] == "black" and rec["linewidth"] > max(s["linewidth"] for n, s in styles.items()
                                                              if n != RECOMMENDED_MODEL)
    assert rec["zorder"] > max(s["zorder"] for n, s in styles.items() if n != RECOMMENDED_MODEL)


def test_figure_draws_the_recommended_model_first_and_the_bem_point(tmp_path):
    pytest.importorskip("matplotlib")
    from dhfield.io.force_vs_angle_plot import force_vs_angle_figure, write_force_vs_angle_plot
    import matplotlib.pyplot as plt

    t = pull_off_force_vs_angle(E, NU, RC, DGAMMA, _sigma0_for_mu_at_90(1.0), angles_deg=(80, 90), points=3,
                                models=["jkr", "dmt"])
    fig = force_vs_angle_figure(t)
    try:
        ax = fig.axes[0]
        labels = [text.get_text() for text in ax.get_legend().get_texts()]
        assert labels[0].startswith("MD elliptical (recommended)")
        assert ax.lines[0].get_linewidth() == max(line.get_linewidth() for line in ax.lines)
        assert any("adhesive BEM" in lab for lab in labels)
        assert any("estimated error" in lab for lab in labels)  # the band: mu 1 is inside the stored box
    finally:
        plt.close(fig)
    paths = write_force_vs_angle_plot(t, tmp_path / "f.png")
    assert all(p.stat().st_size > 0 for p in paths)


def test_cli_force_vs_angle(tmp_path, capsys):
    from dhfield.cli import main

    out = tmp_path / "pdms.png"
    args = ["force-vs-angle", "--youngs-modulus", "1.8e6", "--poisson-ratio", "0.49", "--cylinder-radius", "3e-3",
            "--work-of-adhesion", "0.045", "--adhesive-stress", "0.3e6", "--angles-deg", "60", "90",
            "--points", "3", "--models", "jkr"]
    assert main(args + ["--out", str(out)]) == 0
    text = capsys.readouterr().out
    assert "* MD elliptical (recommended)" in text and "stored BEM cases on this path: 0" in text
    assert out.exists() and out.with_suffix(".svg").exists() and out.with_suffix(".pdf").exists()
    assert main(args[:-4 - 4] + ["--points", "3"]) == 2  # no --adhesive-stress
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "--adhesive-stress" in err[0]
