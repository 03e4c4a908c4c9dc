"""What the figures share (dhfield/io/figures.py): SI conversion of crossed cylinders, SI prefixes,
model names.  The conversion is checked against :func:`dhfield.analysis.dimensional.contact_parameters`, an
independent route through Eqs. 3-6, 34 and 35."""
from __future__ import annotations

import numpy as np
import pytest

from dhfield.analysis import dimensional
from dhfield.analysis.compare import MODEL_NAMES
from dhfield.io.figures import MODEL_LABELS, crossed_cylinders_si, model_label, si_prefix

#: The PDMS crossed cylinders of issue 17.
PDMS = dict(youngs_modulus_1=1.8e6, poisson_ratio_1=0.49, cylinder_radius=3e-3, work_of_adhesion=0.05)
#: Two routes through the same closed forms; beta0 -> theta is a root solve (converged to ~1e-12).
ROUTE_RTOL = 1e-9


@pytest.mark.parametrize("beta0, mu", [(0.5, 0.3), (0.8, 1.0), (1.0, 10.0), (0.3, 3.0)])
def test_si_conversion_matches_the_dimensional_front_end(beta0, mu):
    """The angle, sigma0 and load unit of a (beta0, mu) cell give back beta0, mu and the load unit."""
    q = crossed_cylinders_si(beta0, mu, **PDMS)
    p = dimensional.contact_parameters(PDMS["youngs_modulus_1"], PDMS["poisson_ratio_1"], PDMS["youngs_modulus_1"],
                                       PDMS["poisson_ratio_1"], PDMS["cylinder_radius"],
                                       np.deg2rad(float(q["skew_angle_deg"])), PDMS["work_of_adhesion"],
                                       float(q["max_adhesive_stress"]))
    assert p.beta0 == pytest.approx(beta0, rel=ROUTE_RTOL)
    assert p.mu == pytest.approx(mu, rel=ROUTE_RTOL)
    assert p.load_unit == pytest.approx(float(q["load_unit"]), rel=ROUTE_RTOL)


def test_skew_angle_input_is_the_same_contact():
    q = crossed_cylinders_si(0.6, 2.0, **PDMS)
    r = crossed_cylinders_si(None, 2.0, skew_angle_deg=q["skew_angle_deg"], **PDMS)
    for key in ("max_adhesive_stress", "load_unit"):
        assert float(r[key]) == pytest.approx(float(q[key]), rel=ROUTE_RTOL)


@pytest.mark.parametrize("bad, word", [({"cylinder_radius": -1.0}, "cylinder_radius"),
                                       ({"work_of_adhesion": float("nan")}, "work_of_adhesion"),
                                       ({"poisson_ratio_1": 0.6}, "poisson_ratio")])
def test_bad_material_is_named(bad, word):
    with pytest.raises(ValueError, match=word):
        crossed_cylinders_si(0.8, 1.0, **{**PDMS, **bad})


def test_every_model_has_a_readable_name():
    assert all(name in MODEL_LABELS for name in MODEL_NAMES)
    assert model_label("dh-elliptic-two-axis") == "DH elliptic, two axes"
    assert model_label("unknown-model") == "unknown-model"


@pytest.mark.parametrize("value, unit, scale, label", [(8.3e-4, "N", 1e-6, "µN"), (5e4, "Pa", 1e3, "kPa"),
                                                       (1.0, "N", 1.0, "N"), (0.0, "m", 1.0, "m")])
def test_si_prefix(value, unit, scale, label):
    assert si_prefix(value, unit) == (scale, label)
