"""dhfield.analysis.validity: the validated ranges and the warnings of the pull-off records (issue 16 split)."""
import numpy as np
import pytest

from dhfield.analysis import compare, validity


def test_validity_message_inside_and_outside():
    """Ranges from VALIDITY_RANGES (provenance in dhfield.analysis.validity): inside empty, outside says where."""
    assert validity.validity_message("dh-elliptic", 1.0, 0.9) == ""
    out = validity.validity_message("dh-elliptic", [1.0, 10.0], [0.9, 0.9])
    assert out[0] == "" and "mu in [0.5, 5]" in out[1]
    with pytest.raises(ValueError, match="model"):
        validity.validity_message("hertz", 1.0, 1.0)
    assert set(validity.VALIDITY_RANGES) == set(compare.MODEL_NAMES)


def test_join_warnings_skips_empty_and_broadcasts():
    assert validity.join_warnings("", "b") == "b" and validity.join_warnings("a", "b") == "a; b"
    out = validity.join_warnings(np.array(["", "x"], dtype=object), "y")
    assert list(out) == ["y", "x; y"]


def test_departure_warning_threshold():
    """2 % threshold (issue 10): -1 % is silent, -3 % warns and names the better model, now the
    recommended md-elliptic (issue 20; the two-axis closure before)."""
    assert validity.departure_warning(-0.99, 1.0, 0.9, "load", reference_w_star=-1.0) == ""
    w = validity.departure_warning(-0.97, 1.0, 0.9, "load", reference_w_star=-1.0)
    assert "-3.0 %" in w and "prefer the model md-elliptic" in w


def test_departure_warning_computes_its_reference():
    """Without a reference, the recommended model is evaluated: the same departure as computed by hand."""
    from dhfield.models import md_elliptic as elliptic_transition, dh_elliptic as model

    w_paper = float(model.pull_off_nondimensional(0.5, 2.0).W_star)
    ref = float(elliptic_transition.pull_off_nondimensional(0.5, 2.0).W_star)
    w = validity.departure_warning(w_paper, 2.0, 0.5, "load")
    assert f"{100 * (w_paper / ref - 1):+.1f} %" in w


def test_recommended_model_warns_outside_the_bem_verified_box():
    """md-elliptic is silent inside the box of the stored BEM ground truth and says so outside it (issue 40):
    at 10 deg (beta0 = 0.047) and mu = 19.5 no BEM case checked it."""
    lo_b, hi_b = validity.BEM_VERIFIED_BETA0
    lo_m, hi_m = validity.BEM_VERIFIED_MU
    inside = validity.validity_message("md-elliptic", [lo_m, hi_m, 1.0], [lo_b, hi_b, 0.5])
    assert inside.tolist() == ["", "", ""]
    outside = validity.validity_message("md-elliptic", [19.5, 1.0, 1e-3, 1.0], [0.047, 0.047, 0.5, 0.05])
    assert all("outside the BEM-verified box" in m for m in outside)
    assert "beta0 = 0.047, mu = 19.5" in outside[0]
